// SPDX-License-Identifier: BSD-3-Clause
// Casters a map pass draws: boxes against a cascade's light clip volume (with Lloyd et al. 2006,
// §6.4's depth clamping) and boxes swept along the light against receiver boxes.
#include "csmCulling.h"
#include "csmMathTestHelpers.h"
#include "csmSetup.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace
{
using csmMathTest::camera;  // eye at the origin looking down -z, up +y
using csmMathTest::lightAt; // gammaDeg: 0 light from behind, 90 overhead, 180 facing
using csmMathTest::settings;
} // namespace

TEST(Body, BoxCulling)
{
  const csm::Camera cam = camera(1.0, 100.0, 60.0);
  const auto setup = csm::computeShadowSetup(cam, lightAt(cam, 90.0), nullptr,
    settings(csm::WarpMode::Generalized, csm::SplitScheme::Log, 2));
  ASSERT_EQ(setup.cascades.size(), 2u);
  const glm::dmat4& nearMap = setup.cascades[0].wsToClip;
  csm::Bounds inside{ { -0.5, -0.5, -5.5 }, { 0.5, 0.5, -4.5 } };
  csm::Bounds far{ { -0.5, -0.5, -90 }, { 0.5, 0.5, -80 } };
  csm::Bounds above{ { -0.5, 50, -5.5 }, { 0.5, 60, -4.5 } }; // toward the light: a caster
  csm::Bounds below{ { -0.5, -60, -5.5 }, { 0.5, -50, -4.5 } };
  EXPECT_FALSE(csm::boxOutsideClipVolume(nearMap, inside, true));
  EXPECT_TRUE(csm::boxOutsideClipVolume(nearMap, far, true));
  EXPECT_FALSE(csm::boxOutsideClipVolume(nearMap, above, true));
  EXPECT_TRUE(csm::boxOutsideClipVolume(nearMap, above, false));
  EXPECT_TRUE(csm::boxOutsideClipVolume(nearMap, below, true));
  EXPECT_TRUE(csm::boxOutsideClipVolume(nearMap, csm::Bounds{}, true));
}

// A caster shadows only what lies beyond it along the light.
TEST(Body, SweptBoxReachesWhatLiesBehindItAlongTheLight)
{
  const csm::Bounds ground{ { -100, -0.5, -100 }, { 100, 0, 100 } };
  const csm::Bounds tower{ { -2, 0, -2 }, { 2, 30, 2 } };       // stands on the ground
  const csm::Bounds buried{ { -2, -0.4, -2 }, { 2, -0.2, 2 } }; // inside the slab
  const csm::Bounds sheet{ { -5, 0, -5 }, { 5, 0, 5 } };        // flat, on the ground's top
  const csm::Bounds beside{ { 150, -0.3, -1 }, { 160, 5, 1 } }; // beside the slab
  const double eps = 1e-6;
  const glm::dvec3 down(0.3, -1.0, 0.2), up(0.3, 1.0, 0.2), sideways(1.0, 0.0, 0.0);
  // Light from above: the ground shadows nothing standing on it, but what lies inside it.
  EXPECT_FALSE(csm::sweptBoxReachesBox(ground, down, tower, eps));
  EXPECT_FALSE(csm::sweptBoxReachesBox(ground, down, sheet, eps));
  EXPECT_TRUE(csm::sweptBoxReachesBox(ground, down, buried, eps));
  EXPECT_TRUE(csm::sweptBoxReachesBox(tower, down, ground, eps));
  // Light from below: the ground shadows the tower, the tower not the ground.
  EXPECT_TRUE(csm::sweptBoxReachesBox(ground, up, tower, eps));
  EXPECT_FALSE(csm::sweptBoxReachesBox(tower, up, ground, eps));
  // Light along +x, level: the slab reaches the box beside it, not one behind the light.
  EXPECT_TRUE(csm::sweptBoxReachesBox(ground, sideways, beside, eps));
  EXPECT_FALSE(csm::sweptBoxReachesBox(ground, -sideways, beside, eps));
  const csm::Bounds lifted{ { 50, 0.1, -2 }, { 60, 30, 2 } };
  EXPECT_FALSE(csm::sweptBoxReachesBox(ground, sideways, lifted, eps)); // its y > the slab's
  EXPECT_TRUE(csm::sweptBoxReachesBox(ground, sideways, tower, eps));   // touching: conservative
  // Far from the origin: the same answers.
  const glm::dvec3 far(3.0e6, 1.0e5, -4.0e6);
  const auto moved = [&](const csm::Bounds& b) {
    return csm::Bounds{ b.wsMin + far, b.wsMax + far };
  };
  EXPECT_FALSE(csm::sweptBoxReachesBox(moved(ground), down, moved(tower), 1e-3));
  EXPECT_TRUE(csm::sweptBoxReachesBox(moved(ground), up, moved(tower), 1e-3));
  // Bad input: the safe answer (draw the caster).
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(csm::sweptBoxReachesBox(ground, glm::dvec3(0.0), tower, eps));
  EXPECT_TRUE(csm::sweptBoxReachesBox(ground, glm::dvec3(nan, -1, 0), tower, eps));
  EXPECT_TRUE(csm::sweptBoxReachesBox(csm::Bounds{}, down, tower, eps));
  EXPECT_TRUE(
    csm::sweptBoxReachesBox(ground, down, csm::Bounds{ { nan, 0, 0 }, { 1, 1, 1 } }, eps));
}

// A perspective eye sees only the outside of a closed surface in a box when its near plane's
// rectangle reaches no point of the box: outside the box by more than near / cos(half diagonal).
TEST(Body, AnEyeSeesOnlyTheOutsideOfABoxItsNearPlaneDoesNotReach)
{
  csm::Camera camera;
  camera.wsPosition = { 0.0, 0.0, 10.0 };
  camera.wsDirection = { 0.0, 0.0, -1.0 };
  camera.vsNear = 1.0;
  camera.fovyDeg = 90.0;
  camera.aspect = 1.0;
  // tan(45°) sqrt(2): the corners of the near plane lie sqrt(3) from the eye.
  const double reach = std::sqrt(3.0);
  csm::Bounds box;
  box.wsMin = { -1.0, -1.0, -1.0 };
  box.wsMax = { 1.0, 1.0, 1.0 };
  EXPECT_TRUE(csm::eyeSeesOnlyOutsideOf(camera, box));
  camera.wsPosition = { 0.0, 0.0, 1.0 + 1.01 * reach };
  EXPECT_TRUE(csm::eyeSeesOnlyOutsideOf(camera, box));
  camera.wsPosition = { 0.0, 0.0, 1.0 + 0.99 * reach }; // the near plane's corners reach it
  EXPECT_FALSE(csm::eyeSeesOnlyOutsideOf(camera, box));
  camera.wsPosition = { 0.0, 0.0, 0.0 }; // inside
  EXPECT_FALSE(csm::eyeSeesOnlyOutsideOf(camera, box));
  // Beside the box, looking away from it: its near plane still decides (the direction does not).
  camera.wsPosition = { 1.0 + 0.99 * reach, 0.0, 0.0 };
  EXPECT_FALSE(csm::eyeSeesOnlyOutsideOf(camera, box));
  camera.wsPosition = { 0.0, 0.0, 10.0 };
  csm::Camera parallel = camera;
  parallel.parallel = true;
  EXPECT_FALSE(csm::eyeSeesOnlyOutsideOf(parallel, box));
  csm::Camera nan = camera;
  nan.wsPosition.x = std::nan("");
  EXPECT_FALSE(csm::eyeSeesOnlyOutsideOf(nan, box));
  csm::Camera wide = camera;
  wide.fovyDeg = 180.0;
  EXPECT_FALSE(csm::eyeSeesOnlyOutsideOf(wide, box));
  EXPECT_FALSE(csm::eyeSeesOnlyOutsideOf(camera, csm::Bounds())); // empty
}
