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

// A spot light far above a small scene: the map's depth range is fitted to the scene, not to the
// light's distance, so the scene spans much of the map's depths (a constant bias, a share of
// them, stays a small share of the scene's depth: margins of 1 % of the distance put the 4 units
// of this scene in 0.4 % of the depths at 5e4, under the default bias of 0.2 %) and the caster
// stays in front of its receiver.
TEST(Spot, AFarSpotSpreadsTheSceneOverTheMapsDepths)
{
  csm::Bounds scene{ { -10, 0, -10 }, { 10, 4, 10 } };
  csm::Camera cam = camera(0.5, 100.0, 45.0, 4.0 / 3.0);
  cam.wsPosition = { 0, 5, 30 }; // (looking down -z: the ground and the top at x = z = 0 in view)
  for (const double distance : { 50.0, 5e4, 2e5 })
  {
    for (bool clamp : { true, false })
    {
      const auto setup =
        csm::computeSpotSetup(cam, { 0.3, distance, 0.2 }, { 0, -1, 0 }, 30.0, &scene, clamp);
      ASSERT_EQ(setup.status, csm::Status::Ok) << setup.message;
      const glm::dmat4& toClip = setup.cascades[0].wsToClip;
      const glm::dvec3 ground = toNdc(toClip, { 0, 0, 0 });
      const glm::dvec3 top = toNdc(toClip, { 0, 4, 0 });
      EXPECT_LT(top.z, ground.z) << distance;
      EXPECT_GE(top.z, -1.0) << distance;
      EXPECT_LE(ground.z, 1.0) << distance;
      // The scene's 4 units of height over at least 5 % of the depths (window depth [0, 1]), 25
      // times the default constant bias.
      EXPECT_GT(0.5 * (ground.z - top.z), 0.05) << distance << (clamp ? " clamped" : "");
    }
  }
}

// The bias factor of a spot map is its near times its far distance along the axis: its window
// depth is A - C / z at distance z (A = f / (f - n), C = f n / (f - n)), whose change per unit of
// z, C / z^2, the lookup's bias follows; f n = C^2 / (A (A - 1)), read here from the matrix's
// depths down the axis. An orthographic matrix has none.
TEST(Spot, ThePerspectiveBiasFactorIsNearTimesFar)
{
  csm::Bounds scene{ { -10, 0, -10 }, { 10, 4, 10 } };
  csm::Camera cam = camera(0.5, 100.0, 45.0, 4.0 / 3.0);
  cam.wsPosition = { 0, 5, 30 };
  const glm::dvec3 light(0.3, 40.0, 0.2);
  const auto setup = csm::computeSpotSetup(cam, light, { 0, -1, 0 }, 30.0, &scene, true);
  ASSERT_EQ(setup.status, csm::Status::Ok);
  const glm::dmat4& toClip = setup.cascades[0].wsToClip;
  auto window = [&](double z) { return 0.5 * toNdc(toClip, light - glm::dvec3(0, z, 0)).z + 0.5; };
  const double z1 = 37.0, z2 = 39.0;
  const double c = (window(z2) - window(z1)) / (1.0 / z1 - 1.0 / z2);
  const double a = window(z1) + c / z1;
  EXPECT_NEAR(
    csm::perspectiveBiasFactor(toClip), c * c / (a * (a - 1.0)), 1e-6 * c * c / (a * (a - 1.0)));
  EXPECT_GT(csm::perspectiveBiasFactor(toClip), 0.0);
  EXPECT_EQ(csm::perspectiveBiasFactor(glm::dmat4(1.0)), 0.0);
}
