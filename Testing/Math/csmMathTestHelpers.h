// SPDX-License-Identifier: BSD-3-Clause
// What the math tests share: the test camera, a light at a given angle to the view, settings,
// and checks that a plan's numbers are finite and its bodies land in their maps.
#pragma once

#include "csmTypes.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cmath>

namespace csmMathTest
{
constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;

/// Eye at the origin looking down -z, up +y.
inline csm::Camera camera(double n, double f, double fovyDeg, double aspect = 1.0)
{
  csm::Camera c;
  c.vsNear = n;
  c.vsFar = f;
  c.fovyDeg = fovyDeg;
  c.aspect = aspect;
  return c;
}

/// gammaDeg: 0 light from behind, 90 overhead, 180 facing.
inline glm::dvec3 lightAt(const csm::Camera& c, double gammaDeg)
{
  const glm::dvec3 v = glm::normalize(c.wsDirection);
  const glm::dvec3 up = glm::normalize(c.wsViewUp);
  return std::cos(gammaDeg * kDeg) * v - std::sin(gammaDeg * kDeg) * up;
}

inline csm::Settings settings(csm::WarpMode warp, csm::SplitScheme scheme, int k)
{
  csm::Settings s;
  s.warp = warp;
  s.split.scheme = scheme;
  s.split.k = k;
  return s;
}

inline bool finite(const glm::dmat4& m)
{
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r]))
        return false;
  return true;
}

inline glm::dvec3 toNdc(const glm::dmat4& m, const glm::dvec3& p)
{
  const glm::dvec4 h = m * glm::dvec4(p, 1.0);
  return glm::dvec3(h) / h.w;
}

inline void expectBodyInUnitCube(const csm::ShadowSetup& setup, double tolerance = 1e-9)
{
  for (const csm::Cascade& c : setup.cascades)
  {
    ASSERT_FALSE(c.wsBody.empty());
    for (const glm::dvec3& p : c.wsBody)
    {
      const glm::dvec4 h = c.wsToClip * glm::dvec4(p, 1.0);
      ASSERT_GT(h.w, 0.0);
      const glm::dvec3 q = glm::dvec3(h) / h.w;
      for (int i = 0; i < 3; ++i)
      {
        EXPECT_LE(std::abs(q[i]), 1.0 + tolerance) << "axis " << i;
      }
    }
  }
}

inline void expectAllFinite(const csm::ShadowSetup& setup)
{
  EXPECT_TRUE(std::isfinite(setup.gammaDeg));
  EXPECT_TRUE(std::isfinite(setup.gammaLimDeg));
  for (double s : setup.splits)
    EXPECT_TRUE(std::isfinite(s));
  for (const csm::Cascade& c : setup.cascades)
  {
    EXPECT_TRUE(finite(c.wsToClip));
    EXPECT_TRUE(std::isfinite(c.Mx) && std::isfinite(c.Mz) && std::isfinite(c.storage));
    EXPECT_TRUE(std::isfinite(c.vsNear) && std::isfinite(c.vsFar));
    EXPECT_FALSE(std::isnan(c.nPrime));
  }
  EXPECT_TRUE(std::isfinite(setup.storageTotal));
  EXPECT_TRUE(std::isfinite(setup.storageOptimal));
}
} // namespace csmMathTest
