// SPDX-License-Identifier: BSD-3-Clause
// The generalized LiSPSM parameter (Barroso & Celes 2007, Eq. 13-18).
#include "csmWarp.h"

#include <gtest/gtest.h>

#include <cmath>

namespace
{
constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;

// Barroso & Celes 2007, Fig. 7: n = 1, f = 100, phi_y = pi/6; a, b half-heights of near and far
// faces.
csm::PartitionShape figure7()
{
  const double t = std::tan(kPi / 6.0);
  return { 1.0, 100.0, 1.0 * t, 100.0 * t };
}
}

TEST(GeneralizedWarp, GammaLimIsEq15)
{
  const csm::PartitionShape p = figure7();
  EXPECT_NEAR(csm::gammaLim(p), std::atan((p.a + p.b) / (p.f - p.n)), 1e-15);
  // For f >> n it approaches the half field of view (Barroso & Celes 2007, §3.1: keep it above
  // phi).
  EXPECT_GT(csm::gammaLim(p), kPi / 6.0);
  EXPECT_LT(csm::gammaLim(p), kPi / 6.0 + 2.0 * kDeg);
}

TEST(GeneralizedWarp, RIsOneAtLimitAndZeroAtZero)
{
  const double limit = 0.6;
  EXPECT_DOUBLE_EQ(csm::rOfGamma(limit, limit), 1.0);
  EXPECT_DOUBLE_EQ(csm::rOfGamma(0.0, limit), 0.0);
  // Eq. 18 as printed, at a few interior angles.
  for (double u : { 0.1, 0.3, 0.5, 0.9 })
  {
    const double printed = std::pow(1.0 + std::sin((u - 1.0) * kPi / 2.0), 2.0);
    EXPECT_NEAR(csm::rOfGamma(u * limit, limit), printed, 1e-14);
  }
  // Monotonic descent toward 0.
  double previous = 1.0;
  for (double u = 0.95; u > 0.0; u -= 0.05)
  {
    const double r = csm::rOfGamma(u * limit, limit);
    EXPECT_LT(r, previous);
    previous = r;
  }
}

TEST(GeneralizedWarp, EqualsNPrime1AboveLimit)
{
  const csm::PartitionShape p = figure7();
  const double limit = csm::gammaLim(p);
  for (double g = limit; g <= kPi / 2.0; g += 0.05)
  {
    const double expected = (p.n + std::sqrt(p.f * p.n)) * std::sin(g) - p.a * std::cos(g);
    EXPECT_DOUBLE_EQ(csm::nPrimeGeneralized(g, p), expected);
  }
}

TEST(GeneralizedWarp, LiSPSMValueAtNinetyDegrees)
{
  const csm::PartitionShape p = figure7();
  EXPECT_NEAR(csm::nPrimeGeneralized(kPi / 2.0, p), 1.0 + std::sqrt(100.0), 1e-12);
  EXPECT_NEAR(csm::nPrime(csm::WarpMode::LiSPSM, kPi / 2.0, p), 1.0 + std::sqrt(100.0), 1e-12);
  EXPECT_DOUBLE_EQ(csm::nPrime(csm::WarpMode::PSM, 0.3, p), 1.0);
  EXPECT_TRUE(std::isinf(csm::nPrime(csm::WarpMode::None, 0.3, p)));
}

TEST(GeneralizedWarp, ContinuousAtLimit)
{
  const csm::PartitionShape p = figure7();
  const double limit = csm::gammaLim(p);
  const double above = csm::nPrimeGeneralized(limit + 1e-9, p);
  const double below = csm::nPrimeGeneralized(limit - 1e-9, p);
  EXPECT_NEAR(above, below, 1e-6 * above);
  EXPECT_NEAR(csm::nPrimeGeneralized(limit, p), csm::nPrime1(limit, p), 1e-12);
}

TEST(GeneralizedWarp, GrowsWithoutBoundTowardParallel)
{
  const csm::PartitionShape p = figure7();
  const double limit = csm::gammaLim(p);
  double previous = csm::nPrimeGeneralized(limit, p);
  for (double g : { 0.5 * limit, 0.1 * limit, 1e-2 * limit, 1e-4 * limit, 1e-8 * limit })
  {
    const double value = csm::nPrimeGeneralized(g, p);
    EXPECT_GT(value, previous) << "gamma " << g;
    previous = value;
  }
  EXPECT_GT(previous, 1e30);
  EXPECT_TRUE(std::isinf(csm::nPrimeGeneralized(0.0, p)));
  EXPECT_GT(csm::nPrimeGeneralized(1e-12, p), 0.0);
}

TEST(GeneralizedWarp, ParsesAndPrintsModes)
{
  csm::WarpMode mode = csm::WarpMode::None;
  for (const char* name : { "none", "psm", "lispsm", "generalized" })
  {
    ASSERT_TRUE(csm::parseWarpMode(name, mode));
    EXPECT_STREQ(csm::toString(mode), name);
  }
  EXPECT_FALSE(csm::parseWarpMode("LiSPSM ", mode));
  EXPECT_FALSE(csm::parseWarpMode(nullptr, mode));
}
