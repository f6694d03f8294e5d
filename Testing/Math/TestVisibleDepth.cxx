// SPDX-License-Identifier: BSD-3-Clause
// The visible depth range: from a depth buffer, carried to the next frame's camera, checked.
#include "csmMathTestHelpers.h"
#include "csmVisibleDepth.h"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace
{
using csmMathTest::camera; // eye at the origin looking down -z, up +y

/// The window depths a camera writes for world points (no clipping: the points are inside).
std::vector<float> depthsOf(const csm::Camera& cam, const std::vector<glm::dvec3>& points)
{
  std::vector<float> depths;
  const glm::dvec3 dir = glm::normalize(cam.wsDirection);
  for (const auto& p : points)
  {
    depths.push_back(static_cast<float>(csm::windowDepthFromViewDepth(
      glm::dot(p - cam.wsPosition, dir), cam.vsNear, cam.vsFar, cam.parallel)));
  }
  return depths;
}
}

TEST(VisibleDepth, WindowAndViewDepthsAreInverse)
{
  for (bool parallel : { false, true })
  {
    for (double d : { 0.25, 1.0, 17.0, 3000.0, 5999.0 })
    {
      const double w = csm::windowDepthFromViewDepth(d, 0.25, 6000.0, parallel);
      EXPECT_GE(w, 0.0);
      EXPECT_LE(w, 1.0);
      EXPECT_NEAR(csm::viewDepthFromWindowDepth(w, 0.25, 6000.0, parallel), d, 1e-9 * d);
    }
    EXPECT_NEAR(csm::windowDepthFromViewDepth(0.25, 0.25, 6000.0, parallel), 0.0, 1e-12);
    EXPECT_NEAR(csm::windowDepthFromViewDepth(6000.0, 0.25, 6000.0, parallel), 1.0, 1e-12);
  }
}

TEST(VisibleDepth, TheNearestSampleOfABoxAtKnownDepth)
{
  // A depth buffer of a box face at view depth 40 in front of a background (1.0), camera
  // 0.5 .. 1000: the measured near is the face's depth within 1 %, and the
  // carried range of a still camera holds it.
  const csm::Camera cam = camera(0.5, 1000.0, 30.0, 4.0 / 3.0);
  std::vector<float> buffer(640 * 480, 1.0f);
  const float face = static_cast<float>(csm::windowDepthFromViewDepth(40.0, 0.5, 1000.0, false));
  const float back = static_cast<float>(csm::windowDepthFromViewDepth(55.0, 0.5, 1000.0, false));
  for (int y = 200; y < 300; ++y)
  {
    for (int x = 250; x < 400; ++x)
    {
      buffer[y * 640 + x] = x < 300 ? face : back;
    }
  }
  buffer[7] = std::numeric_limits<float>::quiet_NaN(); // ignored
  const csm::WindowDepthRange window = csm::windowDepthRange(buffer.data(), buffer.size());
  ASSERT_FALSE(window.isEmpty());
  const csm::DepthRange range = csm::viewDepthRange(window, cam);
  EXPECT_NEAR(range.vsNear, 40.0, 0.4);
  EXPECT_NEAR(range.vsFar, 55.0, 0.55);
  const csm::DepthRange carried = csm::carryDepthRange(cam, range, cam);
  EXPECT_NEAR(carried.vsNear, 40.0, 0.4);
  EXPECT_LT(carried.vsNear, range.vsNear);
  EXPECT_GT(carried.vsFar, range.vsFar);
  EXPECT_TRUE(csm::depthRangeHolds(carried, window, cam));
  // Nothing drawn: no range, and nothing to miss.
  std::vector<float> empty(100, 1.0f);
  EXPECT_TRUE(csm::windowDepthRange(empty.data(), empty.size()).isEmpty());
  EXPECT_TRUE(csm::windowDepthRange(nullptr, 5).isEmpty());
  EXPECT_TRUE(
    csm::depthRangeHolds(csm::DepthRange(), csm::windowDepthRange(empty.data(), 100), cam));
}

TEST(VisibleDepth, CarriedRangeHoldsThePointsSeenBeforeAfterTheCameraMoved)
{
  // Points visible to a camera (inside its frustum between depths 20 and 300) stay inside the
  // range carried to a camera that moved 2 units and turned 3 degrees; the range is tighter
  // than the clipping range; a turn beyond kVisibleDepthMaximumTurnDeg gives no range.
  for (bool parallel : { false, true })
  {
    csm::Camera before = camera(0.1, 5000.0, 40.0, 1.5);
    before.parallel = parallel;
    before.parallelScale = 50.0;
    std::mt19937 random(7);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    std::uniform_real_distribution<double> depth(20.0, 300.0);
    std::vector<glm::dvec3> points;
    const double tanY = std::tan(glm::radians(20.0));
    for (int i = 0; i < 2000; ++i)
    {
      const double d = i == 0 ? 20.0 : (i == 1 ? 300.0 : depth(random));
      const double halfY = parallel ? 50.0 : d * tanY;
      points.push_back({ unit(random) * 1.5 * halfY, unit(random) * halfY, -d });
    }
    const std::vector<float> seen = depthsOf(before, points);
    const csm::DepthRange measured =
      csm::viewDepthRange(csm::windowDepthRange(seen.data(), seen.size()), before);
    EXPECT_NEAR(measured.vsNear, 20.0, 0.01);
    EXPECT_NEAR(measured.vsFar, 300.0, parallel ? 0.01 : 1.0);
    csm::Camera after = before;
    after.wsPosition = { 1.2, -0.8, -1.4 };
    const double a = glm::radians(3.0);
    after.wsDirection = { std::sin(a), 0.0, -std::cos(a) };
    const csm::DepthRange carried = csm::carryDepthRange(before, measured, after);
    ASSERT_FALSE(carried.isEmpty());
    EXPECT_GT(carried.vsNear, 5.0) << "parallel " << parallel;
    EXPECT_LT(carried.vsFar, 400.0) << "parallel " << parallel;
    const std::vector<float> now = depthsOf(after, points);
    EXPECT_TRUE(csm::depthRangeHolds(carried, csm::windowDepthRange(now.data(), now.size()), after))
      << "parallel " << parallel;
    // A point that was not visible before, nearer than the carried range, is a miss.
    std::vector<float> withNew = now;
    withNew.push_back(static_cast<float>(
      csm::windowDepthFromViewDepth(0.5 * carried.vsNear, 0.1, 5000.0, parallel)));
    EXPECT_FALSE(
      csm::depthRangeHolds(carried, csm::windowDepthRange(withNew.data(), withNew.size()), after));

    csm::Camera jumped = before;
    const double b = glm::radians(csm::kVisibleDepthMaximumTurnDeg + 1.0);
    jumped.wsDirection = { std::sin(b), 0.0, -std::cos(b) };
    EXPECT_TRUE(csm::carryDepthRange(before, measured, jumped).isEmpty());
  }
}

TEST(VisibleDepth, BadInputGivesNoRange)
{
  const csm::Camera cam = camera(0.5, 1000.0, 30.0);
  csm::DepthRange measured;
  measured.vsNear = 10.0;
  measured.vsFar = 20.0;
  csm::Camera bad = cam;
  bad.wsDirection = { std::nan(""), 0.0, -1.0 };
  EXPECT_TRUE(csm::carryDepthRange(bad, measured, cam).isEmpty());
  EXPECT_TRUE(csm::carryDepthRange(cam, measured, bad).isEmpty());
  EXPECT_TRUE(csm::carryDepthRange(cam, csm::DepthRange(), cam).isEmpty());
  measured.vsFar = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(csm::carryDepthRange(cam, measured, cam).isEmpty());
  csm::WindowDepthRange window;
  window.min = 0.2;
  window.max = 0.3;
  EXPECT_TRUE(csm::viewDepthRange(window, bad).isEmpty());
  EXPECT_FALSE(csm::depthRangeHolds(csm::DepthRange(), window, cam));
}
