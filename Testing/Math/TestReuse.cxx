// SPDX-License-Identifier: BSD-3-Clause
// Maps kept across frames: the slack a still frame's map is rendered with, and when a kept map
// still meets the error target at the current view.
#include "csmMathTestHelpers.h"
#include "csmReuse.h"
#include "csmShadowSetup.h"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

TEST(Reuse, SlackSplitsItsFactorBetweenBorderAndTexels)
{
  // 1 + 0.44 = 1.2^2: a border that widens the map by 1.2 and texels 1.44 times the need.
  const csm::SlackedMap s = csm::slackedMap(csm::MapSize(1000, 500), csm::MapSize(2048), 0.44);
  EXPECT_NEAR(1.0 + 2.0 * s.border, 1.2, 1e-12);
  EXPECT_EQ(s.size.width, 1440);
  EXPECT_EQ(s.size.height, 720);
  // The tile leaves room for less: the factor is what fits (2048 / 1600 = 1.28).
  const csm::SlackedMap tight = csm::slackedMap(csm::MapSize(1600, 800), csm::MapSize(2048), 0.44);
  EXPECT_NEAR(1.0 + 2.0 * tight.border, std::sqrt(1.28), 1e-12);
  EXPECT_EQ(tight.size.width, 2048);
  EXPECT_EQ(tight.size.height, 1024);
  // A map that already fills its tile, no slack, or bad input: the tight map.
  for (const csm::SlackedMap& none :
    { csm::slackedMap(csm::MapSize(2048), csm::MapSize(2048), 0.44),
      csm::slackedMap(csm::MapSize(512), csm::MapSize(2048), 0.0),
      csm::slackedMap(csm::MapSize(512), csm::MapSize(2048), std::nan("")),
      csm::slackedMap(csm::MapSize(0, 512), csm::MapSize(2048), 0.44) })
  {
    EXPECT_EQ(none.border, 0.0);
  }
}

TEST(Reuse, AKeptMapServesWhileItsErrorMeetsAFreshMapsAtItsResolution)
{
  // A kept map of 1440 texels where a fresh one needs 1000: its error may be 1.44 times the
  // fresh map's at equal resolution (on the more constrained axis).
  EXPECT_TRUE(csm::keptMapServes(1.0, csm::MapSize(1000), csm::MapSize(1000)));
  EXPECT_FALSE(csm::keptMapServes(1.001, csm::MapSize(1000), csm::MapSize(1000)));
  EXPECT_TRUE(csm::keptMapServes(1.44, csm::MapSize(1440, 720), csm::MapSize(1000, 500)));
  EXPECT_FALSE(csm::keptMapServes(1.45, csm::MapSize(1440, 720), csm::MapSize(1000, 500)));
  EXPECT_FALSE(csm::keptMapServes(1.2, csm::MapSize(1440, 500), csm::MapSize(1000, 500)));
  // Not covering (infinite ratio), NaN and empty maps never serve.
  EXPECT_FALSE(csm::keptMapServes(std::numeric_limits<double>::infinity(), csm::MapSize(2048),
    csm::MapSize(64)));
  EXPECT_FALSE(csm::keptMapServes(std::nan(""), csm::MapSize(2048), csm::MapSize(64)));
  EXPECT_FALSE(csm::keptMapServes(0.5, csm::MapSize(0), csm::MapSize(64)));
}

// A still camera's slacked map serves a camera that turns a little for several frames, and
// then, as the error model says, no longer: the fresh map's need is read at each view.
TEST(Reuse, ASlackedMapServesACameraThatTurnsALittle)
{
  csm::Bounds scene;
  scene.wsMin = { -10, 0, -10 };
  scene.wsMax = { 10, 2, 10 };
  csm::Camera cam = csmMathTest::camera(5.0, 60.0, 30.0, 4.0 / 3.0);
  cam.wsPosition = { 0, 12, 24 };
  cam.wsDirection = -cam.wsPosition;
  const glm::dvec3 light(-0.3, -1.0, -0.4);
  csm::Settings s;
  s.warp = csm::WarpMode::Generalized;
  s.split.scheme = csm::SplitScheme::Adaptive;
  s.split.k = 1;
  const double imageHeight = 480.0, target = 0.7;
  const csm::MapSize most(2048);
  const auto first = csm::computeShadowSetup(cam, light, &scene, s);
  ASSERT_EQ(first.status, csm::Status::Ok);
  const csm::MapSize need = csm::resolutionForError(first.cascades[0], imageHeight, target, 64, most);
  const csm::SlackedMap slacked = csm::slackedMap(need, most, 0.44);
  ASSERT_GT(slacked.border, 0.0);
  const glm::dmat4 kept = csm::withBorder(first.cascades[0].wsToClip, slacked.border);
  int served = 0;
  bool stopped = false;
  for (int frame = 0; frame <= 40; ++frame)
  {
    const double a = glm::radians(0.5 * frame);
    csm::Camera turned = cam;
    turned.wsPosition = { 24.0 * std::sin(a), 12.0, 24.0 * std::cos(a) };
    turned.wsDirection = -turned.wsPosition;
    const auto fresh = csm::computeShadowSetup(turned, light, &scene, s);
    ASSERT_EQ(fresh.status, csm::Status::Ok);
    const csm::MapSize freshNeed =
      csm::resolutionForError(fresh.cascades[0], imageHeight, target, 64, most);
    const auto reuse = csm::compareKeptMap(kept, fresh.cascades[0], turned,
      glm::normalize(light), true, 2.0 * 2.0 / slacked.size.width);
    const bool serves =
      reuse.covers && csm::keptMapServes(reuse.errorRatio, slacked.size, freshNeed);
    if (frame == 0)
    {
      EXPECT_TRUE(serves); // the view it was planned for
    }
    stopped = stopped || !serves;
    served += serves && !stopped ? 1 : 0;
  }
  EXPECT_GE(served, 3);
  EXPECT_TRUE(stopped); // 20 degrees later the map no longer serves
}

TEST(Reuse, ASmallCameraStepIsATurnOfAFewDegreesOrAMoveWellShortOfTheNearestSample)
{
  csm::Camera before = csmMathTest::camera(1.0, 100.0, 60.0);
  csm::Camera turned = before;
  turned.wsDirection = { std::sin(glm::radians(2.0)), 0.0, -std::cos(glm::radians(2.0)) };
  EXPECT_TRUE(csm::smallCameraStep(before, turned, 10.0));
  turned.wsDirection = { std::sin(glm::radians(36.0)), 0.0, -std::cos(glm::radians(36.0)) };
  EXPECT_FALSE(csm::smallCameraStep(before, turned, 10.0)); // a coarse path's step
  csm::Camera moved = before;
  moved.wsPosition = { 0.0, 0.0, -2.0 };
  EXPECT_TRUE(csm::smallCameraStep(before, moved, 10.0));
  EXPECT_FALSE(csm::smallCameraStep(before, moved, 4.0)); // half the way to the nearest sample
  EXPECT_FALSE(csm::smallCameraStep(before, before, 10.0)); // no step at all
  EXPECT_FALSE(csm::smallCameraStep(before, moved, std::nan("")));
  csm::Camera broken = before;
  broken.wsDirection = { 0.0, 0.0, 0.0 };
  EXPECT_FALSE(csm::smallCameraStep(before, broken, 10.0));
}
