// SPDX-License-Identifier: BSD-3-Clause
// computeSpotSetup: one perspective map of a spot light fitted to the lit part of the visible
// scene; bad input refused.
#include "csmMathTestHelpers.h"
#include "csmSpotSetup.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace
{
using csmMathTest::camera; // eye at the origin looking down -z, up +y
using csmMathTest::expectBodyInUnitCube;
using csmMathTest::finite;
using csmMathTest::kDeg;
using csmMathTest::toNdc;
} // namespace

TEST(Spot, FitsTheLitVisibleScene)
{
  csm::Bounds scene{ { -20, 0, -60 }, { 20, 10, 0 } };
  csm::Camera cam = camera(0.5, 1000.0, 45.0, 4.0 / 3.0);
  cam.wsPosition = { 0, 8, 20 };
  const glm::dvec3 lightPos(5, 40, -20);
  for (bool clamp : { true, false })
  {
    const auto setup = csm::computeSpotSetup(cam, lightPos, { 0, -1, 0 }, 30.0, &scene, clamp);
    ASSERT_EQ(setup.status, csm::Status::Ok) << setup.message;
    ASSERT_EQ(setup.cascades.size(), 1u);
    expectBodyInUnitCube(setup, 1e-9);
    EXPECT_TRUE(finite(setup.cascades[0].wsToClip));
    // A point on the floor under the light maps inside the map, behind a caster above it.
    const glm::dvec3 floor = toNdc(setup.cascades[0].wsToClip, { 5, 0, -20 });
    const glm::dvec3 caster = toNdc(setup.cascades[0].wsToClip, { 5, 9, -20 });
    EXPECT_NEAR(floor.x, caster.x, 1e-9);
    EXPECT_NEAR(floor.y, caster.y, 1e-9);
    EXPECT_LT(caster.z, floor.z);
    EXPECT_LE(std::abs(floor.x), 1.0);
    // The map covers only what the cone lights: the window is narrower than the cone.
    const glm::dvec3 edge =
      toNdc(setup.cascades[0].wsToClip, { 5 + 40 * std::tan(30 * kDeg), 0, -20 });
    EXPECT_GT(std::max(std::abs(edge.x), std::abs(edge.y)), 1.0 - 1e-9);
  }
  // Bad cone, NaN position, a cone that misses the view.
  EXPECT_EQ(csm::computeSpotSetup(cam, lightPos, { 0, -1, 0 }, 95.0, &scene, true).status,
    csm::Status::InvalidInput);
  EXPECT_EQ(csm::computeSpotSetup(cam, { NAN, 0, 0 }, { 0, -1, 0 }, 30.0, &scene, true).status,
    csm::Status::InvalidInput);
  EXPECT_EQ(csm::computeSpotSetup(cam, lightPos, { 0, 1, 0 }, 30.0, &scene, true).status,
    csm::Status::NothingToShadow);
}
