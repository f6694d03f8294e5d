// SPDX-License-Identifier: BSD-3-Clause
// Split schemes (Barroso & Celes 2007, Eq. 5, 19; Lloyd et al. 2006, Eq. 15-16; Vázquez practical).
#include "csmSplits.h"

#include <gtest/gtest.h>

#include <cmath>

namespace
{
constexpr double kHalfPi = 1.57079632679489661923;

csm::SplitParameters params(csm::SplitScheme scheme, int k, double alpha = 2.0, double lambda = 0.5)
{
  csm::SplitParameters p;
  p.scheme = scheme;
  p.k = k;
  p.alpha = alpha;
  p.lambda = lambda;
  return p;
}
}

TEST(Splits, UniformLogPractical)
{
  const auto u = csm::splitDepths(params(csm::SplitScheme::Uniform, 4), 1.0, 101.0, 0.0);
  ASSERT_EQ(u.size(), 5u);
  EXPECT_DOUBLE_EQ(u[1], 26.0);
  EXPECT_DOUBLE_EQ(u[2], 51.0);
  const auto l = csm::splitDepths(params(csm::SplitScheme::Log, 4), 1.0, 1e4, 0.0);
  EXPECT_NEAR(l[1], 10.0, 1e-12);
  EXPECT_NEAR(l[2], 100.0, 1e-12);
  EXPECT_NEAR(l[3], 1000.0, 1e-9);
  EXPECT_EQ(l[4], 1e4);
  const auto p =
    csm::splitDepths(params(csm::SplitScheme::Practical, 2, 2.0, 0.25), 1.0, 101.0, 0.0);
  EXPECT_NEAR(p[1], 0.25 * std::sqrt(101.0) + 0.75 * 51.0, 1e-12);
  const auto s = csm::splitDepths(params(csm::SplitScheme::Single, 4), 2.0, 3.0, 0.0);
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[0], 2.0);
  EXPECT_EQ(s[1], 3.0);
}

TEST(Splits, AdaptiveEqualsLogOverhead)
{
  for (int k = 1; k <= 6; ++k)
  {
    for (double ratio : { 10.0, 1e3, 1e5 })
    {
      const auto a =
        csm::splitDepths(params(csm::SplitScheme::Adaptive, k), 0.5, 0.5 * ratio, kHalfPi);
      const auto l = csm::splitDepths(params(csm::SplitScheme::Log, k), 0.5, 0.5 * ratio, kHalfPi);
      ASSERT_EQ(a.size(), l.size());
      for (size_t i = 0; i < a.size(); ++i)
      {
        EXPECT_NEAR(a[i], l[i], 1e-12 * l[i]) << "k " << k << " ratio " << ratio << " i " << i;
      }
    }
  }
}

TEST(Splits, AdaptiveRatioIsAlphaWhenParallel)
{
  for (int k = 2; k <= 5; ++k)
  {
    for (double alpha : { 1.5, 2.0, 4.0 })
    {
      const auto s = csm::splitDepths(params(csm::SplitScheme::Adaptive, k, alpha), 1.0, 1e4, 0.0);
      for (int i = 2; i <= k; ++i) // every partition but the first
      {
        EXPECT_NEAR(s[i] / s[i - 1], alpha, 1e-12) << "k " << k << " i " << i;
      }
      EXPECT_GT(s[1] / s[0], alpha);
    }
  }
}

TEST(Splits, AlwaysStrictlyIncreasingAndCovering)
{
  for (auto scheme : { csm::SplitScheme::Uniform, csm::SplitScheme::Log,
         csm::SplitScheme::Practical, csm::SplitScheme::Adaptive })
  {
    for (int k = 1; k <= 8; ++k)
    {
      for (double ratio : { 1.0 + 1e-6, 1.5, 10.0, 1e4, 1e7 })
      {
        for (double gamma = 0.0; gamma <= kHalfPi; gamma += kHalfPi / 16.0)
        {
          for (double alpha : { 1.01, 2.0, 8.0 })
          {
            const double n = 0.01;
            const auto s = csm::splitDepths(params(scheme, k, alpha), n, n * ratio, gamma);
            ASSERT_EQ(s.size(), size_t(k + 1));
            EXPECT_EQ(s.front(), n);
            EXPECT_EQ(s.back(), n * ratio);
            for (int i = 1; i <= k; ++i)
            {
              ASSERT_TRUE(std::isfinite(s[i]));
              EXPECT_LT(s[i - 1], s[i]) << csm::toString(scheme) << " k " << k << " ratio " << ratio
                                        << " gamma " << gamma << " alpha " << alpha;
            }
          }
        }
      }
    }
  }
}

TEST(Splits, ParsesAndPrintsSchemes)
{
  csm::SplitScheme scheme = csm::SplitScheme::Single;
  for (const char* name : { "single", "uniform", "log", "practical", "adaptive" })
  {
    ASSERT_TRUE(csm::parseSplitScheme(name, scheme));
    EXPECT_STREQ(csm::toString(scheme), name);
  }
  EXPECT_FALSE(csm::parseSplitScheme("logarithmic", scheme));
}

// f/n beyond a double (1e600) still gives finite, increasing log splits.
TEST(Splits, LogSplitsInLogSpace)
{
  const auto l = csm::splitDepths(params(csm::SplitScheme::Log, 4), 1e-300, 1e300, 0.0);
  ASSERT_EQ(l.size(), 5u);
  EXPECT_NEAR(std::log10(l[1]), -150.0, 1e-9);
  EXPECT_NEAR(std::log10(l[2]), 0.0, 1e-9);
  EXPECT_NEAR(std::log10(l[3]), 150.0, 1e-9);
  const auto a = csm::splitDepths(params(csm::SplitScheme::Adaptive, 3), 1e-300, 1e300, kHalfPi);
  for (size_t i = 1; i < a.size(); ++i)
    EXPECT_TRUE(std::isfinite(a[i]) && a[i] > a[i - 1]);
}

TEST(Splits, PartitionAtDepthSelectsAsTheShaderDoes)
{
  const double far[3] = { 2.0, 5.0, 10.0 };
  EXPECT_EQ(csm::partitionAtDepth(0.5, 1.0, far, 3), -1); // before the first
  EXPECT_EQ(csm::partitionAtDepth(1.0, 1.0, far, 3), 0);
  EXPECT_EQ(csm::partitionAtDepth(2.0, 1.0, far, 3), 0); // a split belongs to the nearer
  EXPECT_EQ(csm::partitionAtDepth(2.0001, 1.0, far, 3), 1);
  EXPECT_EQ(csm::partitionAtDepth(10.0, 1.0, far, 3), 2);
  EXPECT_EQ(csm::partitionAtDepth(10.5, 1.0, far, 3), -1); // beyond the last
  EXPECT_EQ(csm::partitionAtDepth(std::nan(""), 1.0, far, 3), -1);
  EXPECT_EQ(csm::partitionAtDepth(3.0, 1.0, far, 0), -1);
}
