// SPDX-License-Identifier: BSD-3-Clause
// The visible depth range: from a depth buffer, carried to the next frame's camera, checked.
#include "csmGeometry.h"
#include "csmMathTestHelpers.h"
#include "csmSetup.h"
#include "csmVisibleDepth.h"

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
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

TEST(VisibleDepth, AFootprintHoldsEachDepthsSamplesInTheirPixelsRectangle)
{
  // 64 x 48 pixels: a near block in the lower left (view depth 10), a far one in the upper
  // right (view depth 400), background elsewhere; camera 1 .. 1000.
  const csm::Camera cam = camera(1.0, 1000.0, 40.0, 4.0 / 3.0);
  const int width = 64, height = 48;
  std::vector<float> buffer(width * height, 1.0f);
  const float nearW = static_cast<float>(csm::windowDepthFromViewDepth(10.0, 1.0, 1000.0, false));
  const float farW = static_cast<float>(csm::windowDepthFromViewDepth(400.0, 1.0, 1000.0, false));
  for (int y = 0; y < 12; ++y)
    for (int x = 0; x < 16; ++x)
      buffer[y * width + x] = nearW; // columns 0-15, rows 0-11
  for (int y = 36; y < 48; ++y)
    for (int x = 48; x < 64; ++x)
      buffer[y * width + x] = farW; // columns 48-63, rows 36-47
  const csm::WindowFootprint footprint = csm::windowFootprint(buffer.data(), width, height);
  ASSERT_FALSE(footprint.isEmpty());
  EXPECT_EQ(static_cast<int>(footprint.bins.size()), csm::kFootprintBins);
  EXPECT_FLOAT_EQ(static_cast<float>(footprint.range.min), nearW);
  EXPECT_FLOAT_EQ(static_cast<float>(footprint.range.max), farW);

  // Around the near block's depth: its pixels' rectangle, in NDC (pixel edges, not centres).
  const csm::ScreenRect nearRect = csm::footprintRect(footprint, cam, 9.0, 11.0);
  ASSERT_FALSE(nearRect.isEmpty());
  EXPECT_DOUBLE_EQ(nearRect.x0, -1.0);
  EXPECT_DOUBLE_EQ(nearRect.y0, -1.0);
  EXPECT_DOUBLE_EQ(nearRect.x1, 2.0 * 16 / width - 1.0);
  EXPECT_DOUBLE_EQ(nearRect.y1, 2.0 * 12 / height - 1.0);
  const csm::ScreenRect farRect = csm::footprintRect(footprint, cam, 300.0, 500.0);
  ASSERT_FALSE(farRect.isEmpty());
  EXPECT_DOUBLE_EQ(farRect.x0, 2.0 * 48 / width - 1.0);
  EXPECT_DOUBLE_EQ(farRect.y0, 2.0 * 36 / height - 1.0);
  EXPECT_DOUBLE_EQ(farRect.x1, 1.0);
  EXPECT_DOUBLE_EQ(farRect.y1, 1.0);
  // Between them nothing; over both depths both blocks.
  EXPECT_TRUE(csm::footprintRect(footprint, cam, 20.0, 100.0).isEmpty());
  const csm::ScreenRect both = csm::footprintRect(footprint, cam, 5.0, 900.0);
  EXPECT_DOUBLE_EQ(both.x0, -1.0);
  EXPECT_DOUBLE_EQ(both.y1, 1.0);
  // Beyond the samples, or a bad query: nothing.
  EXPECT_TRUE(csm::footprintRect(footprint, cam, 600.0, 900.0).isEmpty());
  EXPECT_TRUE(csm::footprintRect(footprint, cam, 11.0, 9.0).isEmpty());
  EXPECT_TRUE(csm::footprintRect(footprint, csm::Camera{ {}, { 0, 0, 0 } }, 9.0, 11.0).isEmpty());
  // Only background, no buffer or no pixels: an empty footprint.
  std::vector<float> background(width * height, 1.0f);
  EXPECT_TRUE(csm::windowFootprint(background.data(), width, height).isEmpty());
  EXPECT_TRUE(csm::windowFootprint(nullptr, width, height).isEmpty());
  EXPECT_TRUE(csm::windowFootprint(buffer.data(), 0, height).isEmpty());
}

// The footprint, taken a run of one bin's samples at a time, holds in each bin exactly the
// pixels whose samples fall in it: a buffer of smooth ramps (long runs that cross bins), noise,
// background and NaN, against each sample binned alone; and a buffer of one depth (every
// sample in the first bin).
TEST(VisibleDepth, AFootprintBinsEverySampleAsItsOwnDepthSays)
{
  const int width = 97, height = 61;
  std::vector<float> buffer(width * height);
  std::mt19937 random(11);
  for (int y = 0; y < height; ++y)
  {
    for (int x = 0; x < width; ++x)
    {
      float& w = buffer[y * width + x];
      const int kind = static_cast<int>(random() % 10);
      w = kind == 0 ? 1.0f
        : kind == 1 ? std::numeric_limits<float>::quiet_NaN()
        : kind == 2 ? 0.3f + 0.6f * static_cast<float>(random() % 1000) / 999.0f
                    : 0.35f + 0.5f * static_cast<float>(x + 3 * y) / (width + 3 * height);
    }
  }
  const csm::WindowFootprint footprint = csm::windowFootprint(buffer.data(), width, height);
  ASSERT_FALSE(footprint.isEmpty());
  const double lo = footprint.range.min, hi = footprint.range.max;
  const double scale = csm::kFootprintBins / (hi - lo);
  std::vector<csm::ScreenRect> expected(csm::kFootprintBins);
  for (int y = 0; y < height; ++y)
  {
    for (int x = 0; x < width; ++x)
    {
      const float w = buffer[y * width + x];
      if (!(w < 1.0f) || !(w >= 0.0f))
      {
        continue;
      }
      const double t = (w - lo) * scale;
      const int b = !(t > 0.0)         ? 0
        : t >= csm::kFootprintBins - 1 ? csm::kFootprintBins - 1
                                       : static_cast<int>(t);
      csm::ScreenRect pixel;
      pixel.x0 = 2.0 * x / width - 1.0;
      pixel.y0 = 2.0 * y / height - 1.0;
      pixel.x1 = 2.0 * (x + 1) / width - 1.0;
      pixel.y1 = 2.0 * (y + 1) / height - 1.0;
      expected[b].add(pixel);
    }
  }
  int filled = 0;
  for (int b = 0; b < csm::kFootprintBins; ++b)
  {
    const csm::ScreenRect& got = footprint.bins[b];
    ASSERT_EQ(got.isEmpty(), expected[b].isEmpty()) << b;
    if (!got.isEmpty())
    {
      ++filled;
      EXPECT_DOUBLE_EQ(got.x0, expected[b].x0) << b;
      EXPECT_DOUBLE_EQ(got.y0, expected[b].y0) << b;
      EXPECT_DOUBLE_EQ(got.x1, expected[b].x1) << b;
      EXPECT_DOUBLE_EQ(got.y1, expected[b].y1) << b;
    }
  }
  EXPECT_GT(filled, csm::kFootprintBins / 2);
  std::vector<float> flat(width * height, 0.5f);
  flat[7] = 1.0f;
  const csm::WindowFootprint one = csm::windowFootprint(flat.data(), width, height);
  ASSERT_FALSE(one.isEmpty());
  EXPECT_DOUBLE_EQ(one.bins[0].x0, -1.0);
  EXPECT_DOUBLE_EQ(one.bins[0].y1, 1.0);
  for (int b = 1; b < csm::kFootprintBins; ++b)
  {
    EXPECT_TRUE(one.bins[b].isEmpty()) << b;
  }
}

TEST(VisibleDepth, ABoxStandsInForACasterOnlyWhereItIsSmallOnTheImageForItsTriangles)
{
  // A 640 x 480 view from the origin down -z, 1 .. 1000, 40 degrees high.
  const glm::dmat4 wsToClip = glm::perspective(glm::radians(40.0), 640.0 / 480.0, 1.0, 1000.0) *
    glm::lookAt(glm::dvec3(0.0), glm::dvec3(0.0, 0.0, -1.0), glm::dvec3(0.0, 1.0, 0.0));
  // A unit box 100 away covers about 44 pixels (480 / (2 * 99.5 * tan 20) a unit at its front).
  const csm::Bounds far{ { -0.5, -0.5, -100.5 }, { 0.5, 0.5, -99.5 } };
  csm::BoxStandIn standIn;
  ASSERT_TRUE(csm::boxStandIn(wsToClip, far, 1000.0, 640, 480, standIn));
  const double pixels =
    0.25 * (standIn.rect.x1 - standIn.rect.x0) * 640 * (standIn.rect.y1 - standIn.rect.y0) * 480;
  EXPECT_GT(pixels, 40.0);
  EXPECT_LT(pixels, 48.0);
  EXPECT_NEAR(standIn.rect.x0, -standIn.rect.x1, 1e-12); // centred on the view axis
  EXPECT_NEAR(standIn.depths.min, csm::windowDepthFromViewDepth(99.5, 1.0, 1000.0, false), 1e-9);
  EXPECT_NEAR(standIn.depths.max, csm::windowDepthFromViewDepth(100.5, 1.0, 1000.0, false), 1e-9);
  // Drawn where its pixels pay for its triangles: fewer than pixels / kDepthPassPixelsPerCell.
  EXPECT_FALSE(csm::boxStandIn(
    wsToClip, far, 0.99 * pixels / csm::kDepthPassPixelsPerCell, 640, 480, standIn));
  EXPECT_TRUE(csm::boxStandIn(
    wsToClip, far, 1.01 * pixels / csm::kDepthPassPixelsPerCell, 640, 480, standIn));
  // A box around the eye has no bounded rectangle; one beside the view nothing to stand in for.
  const csm::Bounds around{ { -1.0, -1.0, -1.0 }, { 1.0, 1.0, 1.0 } };
  EXPECT_FALSE(csm::boxStandIn(wsToClip, around, 1e9, 640, 480, standIn));
  const csm::Bounds beside{ { 500.0, -0.5, -100.5 }, { 501.0, 0.5, -99.5 } };
  EXPECT_FALSE(csm::boxStandIn(wsToClip, beside, 1e9, 640, 480, standIn));
  // Bad input: drawn.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(csm::boxStandIn(wsToClip, far, 0.0, 640, 480, standIn));
  EXPECT_FALSE(csm::boxStandIn(wsToClip, far, nan, 640, 480, standIn));
  EXPECT_FALSE(csm::boxStandIn(wsToClip, far, 1000.0, 0, 480, standIn));
  EXPECT_FALSE(csm::boxStandIn(
    wsToClip, csm::Bounds{ { nan, 0, 0 }, { 1, 1, 1 } }, 1000.0, 640, 480, standIn));
  EXPECT_FALSE(csm::boxStandIn(wsToClip, csm::Bounds(), 1000.0, 640, 480, standIn)); // empty
}

TEST(VisibleDepth, AFootprintHoldsTheBoxesThatStoodInForCastersTheDepthPassLeftOut)
{
  // 64 x 48 pixels: a near block in the lower left (view depth 10); a caster left out of the
  // depth pass stands in by its box's rectangle at view depths 200 .. 250.
  const csm::Camera cam = camera(1.0, 1000.0, 40.0, 4.0 / 3.0);
  const int width = 64, height = 48;
  std::vector<float> buffer(width * height, 1.0f);
  const float nearW = static_cast<float>(csm::windowDepthFromViewDepth(10.0, 1.0, 1000.0, false));
  for (int y = 0; y < 12; ++y)
    for (int x = 0; x < 16; ++x)
      buffer[y * width + x] = nearW;
  csm::BoxStandIn standIn;
  standIn.rect = csm::ScreenRect{ 0.5, 0.25, 0.75, 0.5 };
  standIn.depths.min = csm::windowDepthFromViewDepth(200.0, 1.0, 1000.0, false);
  standIn.depths.max = csm::windowDepthFromViewDepth(250.0, 1.0, 1000.0, false);
  const csm::WindowFootprint footprint =
    csm::windowFootprint(buffer.data(), width, height, { standIn });
  ASSERT_FALSE(footprint.isEmpty());
  EXPECT_FLOAT_EQ(static_cast<float>(footprint.range.min), nearW);
  EXPECT_DOUBLE_EQ(footprint.range.max, standIn.depths.max);
  // Its depths: its rectangle, as if sampled; the block's depths: the block's pixels.
  const csm::ScreenRect atBox = csm::footprintRect(footprint, cam, 190.0, 260.0);
  EXPECT_DOUBLE_EQ(atBox.x0, 0.5);
  EXPECT_DOUBLE_EQ(atBox.y0, 0.25);
  EXPECT_DOUBLE_EQ(atBox.x1, 0.75);
  EXPECT_DOUBLE_EQ(atBox.y1, 0.5);
  const csm::ScreenRect atBlock = csm::footprintRect(footprint, cam, 9.0, 11.0);
  EXPECT_DOUBLE_EQ(atBlock.x0, -1.0);
  EXPECT_DOUBLE_EQ(atBlock.x1, 2.0 * 16 / width - 1.0);
  EXPECT_TRUE(csm::footprintRect(footprint, cam, 20.0, 150.0).isEmpty());
  // A stand-in nearer than every sample: the nearest depth is its box's.
  csm::BoxStandIn nearer = standIn;
  nearer.depths.min = csm::windowDepthFromViewDepth(5.0, 1.0, 1000.0, false);
  EXPECT_DOUBLE_EQ(
    csm::windowFootprint(buffer.data(), width, height, { nearer }).range.min, nearer.depths.min);
  // Stand-ins only (nothing drawn): a footprint of their boxes; an empty one changes nothing.
  std::vector<float> background(width * height, 1.0f);
  const csm::WindowFootprint boxes =
    csm::windowFootprint(background.data(), width, height, { standIn, csm::BoxStandIn() });
  ASSERT_FALSE(boxes.isEmpty());
  EXPECT_DOUBLE_EQ(csm::footprintRect(boxes, cam, 200.0, 250.0).x0, 0.5);
  EXPECT_TRUE(
    csm::windowFootprint(background.data(), width, height, { csm::BoxStandIn() }).isEmpty());
}

TEST(VisibleDepth, AScreenRectanglesPlanesHoldWhatProjectsIntoIt)
{
  for (bool parallel : { false, true })
  {
    csm::Camera cam = camera(0.5, 100.0, 50.0, 1.5);
    cam.wsPosition = { 3.0, -2.0, 7.0 };
    cam.wsDirection = { 1.0, 0.2, -1.0 };
    cam.wsViewUp = { 0.0, 1.0, 0.3 };
    cam.parallel = parallel;
    cam.parallelScale = 4.0;
    const csm::CameraFrame frame = csm::cameraFrame(cam);
    const csm::ScreenRect rect{ -0.5, 0.1, 0.25, 0.8 };
    const std::vector<csm::Plane> planes = csm::screenRectPlanes(cam, rect);
    ASSERT_EQ(planes.size(), 4u);
    std::mt19937 random(7);
    std::uniform_real_distribution<double> ndc(-1.0, 1.0), depth(0.5, 100.0);
    int inside = 0;
    for (int i = 0; i < 2000; ++i)
    {
      const double x = ndc(random), y = ndc(random), d = depth(random);
      const glm::dvec2 half = csm::halfSize(cam, frame, d);
      const glm::dvec3 p = frame.view * d + frame.right * (x * half.x) + frame.up * (y * half.y);
      bool inAll = true;
      for (const csm::Plane& plane : planes)
        inAll = inAll && glm::dot(plane.normal, p) + plane.offset >= -1e-9 * d;
      const bool inRect = x >= rect.x0 && x <= rect.x1 && y >= rect.y0 && y <= rect.y1;
      EXPECT_EQ(inAll, inRect) << "parallel " << parallel << " x " << x << " y " << y;
      inside += inRect ? 1 : 0;
    }
    EXPECT_GT(inside, 100);
    EXPECT_TRUE(csm::screenRectPlanes(cam, csm::ScreenRect()).empty());
  }
}

TEST(VisibleDepth, AFootprintServesOnlyTheImageThatMeasuredIt)
{
  const csm::Camera a = camera(1.0, 1000.0, 40.0, 4.0 / 3.0);
  csm::Camera b = a;
  b.vsNear = 7.0; // another clipping range: the same image
  EXPECT_TRUE(csm::sameImage(a, b));
  b.wsPosition.x += 1e-3;
  EXPECT_FALSE(csm::sameImage(a, b));
  b = a;
  b.wsDirection = { 0.01, 0.0, -1.0 };
  EXPECT_FALSE(csm::sameImage(a, b));
  b = a;
  b.wsViewUp = { 0.1, 1.0, 0.0 }; // rolled
  EXPECT_FALSE(csm::sameImage(a, b));
  b = a;
  b.fovyDeg = 41.0;
  EXPECT_FALSE(csm::sameImage(a, b));
  b = a;
  b.aspect = 1.0;
  EXPECT_FALSE(csm::sameImage(a, b));
  b = a;
  b.parallel = true;
  EXPECT_FALSE(csm::sameImage(a, b));
}

TEST(VisibleDepth, CascadesFittedToAFootprintHoldOnlyThePartOfTheViewItShows)
{
  // Samples only in the lower half of the image, at every depth from 2 to 800 (a ground seen
  // below the horizon, sky above): each cascade's body stays below the horizon and needs fewer
  // texels than the whole view's slab.
  csm::Camera cam = camera(1.0, 1000.0, 50.0, 4.0 / 3.0);
  const int width = 160, height = 120;
  std::vector<float> buffer(width * height, 1.0f);
  for (int y = 0; y < height / 2; ++y)
  {
    for (int x = 0; x < width; ++x)
    {
      const double t = double(x) / (width - 1);
      buffer[y * width + x] = static_cast<float>(
        csm::windowDepthFromViewDepth(2.0 * std::pow(400.0, t), 1.0, 1000.0, false));
    }
  }
  csm::ViewFootprint footprint;
  footprint.window = csm::windowFootprint(buffer.data(), width, height);
  footprint.measuredBy = cam;
  csm::Camera fitted = cam;
  fitted.vsNear = 2.0; // the nearest sample, as the planner carries it
  fitted.vsFar = 800.0;
  csm::Settings whole = csmMathTest::settings(csm::WarpMode::Generalized, csm::SplitScheme::Log, 3);
  csm::Settings tight = whole;
  tight.visibleFootprint = &footprint;
  const glm::dvec3 light = csmMathTest::lightAt(cam, 60.0);
  const csm::ShadowSetup a = csm::computeShadowSetup(fitted, light, nullptr, whole);
  const csm::ShadowSetup b = csm::computeShadowSetup(fitted, light, nullptr, tight);
  ASSERT_EQ(a.status, csm::Status::Ok);
  ASSERT_EQ(b.status, csm::Status::Ok);
  ASSERT_EQ(a.cascades.size(), b.cascades.size());
  csmMathTest::expectBodyInUnitCube(b);
  const csm::CameraFrame frame = csm::cameraFrame(cam);
  double wholeStorage = 0.0, tightStorage = 0.0;
  for (size_t i = 0; i < b.cascades.size(); ++i)
  {
    bool above = false;
    for (const glm::dvec3& p : a.cascades[i].wsBody)
      above = above || glm::dot(p - cam.wsPosition, frame.up) > 1e-6;
    EXPECT_TRUE(above); // the whole view's slab reaches above the horizon
    for (const glm::dvec3& p : b.cascades[i].wsBody)
      EXPECT_LE(glm::dot(p - cam.wsPosition, frame.up), 1e-9 * glm::length(p - cam.wsPosition));
    EXPECT_LT(b.cascades[i].storage, a.cascades[i].storage);
    wholeStorage += a.cascades[i].storage;
    tightStorage += b.cascades[i].storage;
  }
  EXPECT_LT(tightStorage, 0.75 * wholeStorage);
}
