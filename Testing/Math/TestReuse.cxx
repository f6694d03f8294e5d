// SPDX-License-Identifier: BSD-3-Clause
// Maps kept across frames: the slack a still frame's map is rendered with, and when a kept map
// still meets the error target at the current view.
#include "csmAliasing.h"
#include "csmAtlas.h"
#include "csmCascadeCount.h"
#include "csmMathTestHelpers.h"
#include "csmReuse.h"
#include "csmSetup.h"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
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
  EXPECT_FALSE(csm::keptMapServes(
    std::numeric_limits<double>::infinity(), csm::MapSize(2048), csm::MapSize(64)));
  EXPECT_FALSE(csm::keptMapServes(std::nan(""), csm::MapSize(2048), csm::MapSize(64)));
  EXPECT_FALSE(csm::keptMapServes(0.5, csm::MapSize(0), csm::MapSize(64)));
}

TEST(Reuse, AKeptMapsErrorIsItsRatioOverTheTexelsItHasBeyondTheNeed)
{
  // 1.2 times the fresh map's error at equal resolution, 1440 x 500 texels where 1000 x 500 are
  // needed: the t axis gains nothing, so 1.2; at 1440 x 720, 1.2 / 1.44.
  EXPECT_DOUBLE_EQ(csm::keptMapError(1.2, csm::MapSize(1440, 500), csm::MapSize(1000, 500)), 1.2);
  EXPECT_DOUBLE_EQ(
    csm::keptMapError(1.2, csm::MapSize(1440, 720), csm::MapSize(1000, 500)), 1.2 / 1.44);
  // A map smaller than the need is worse by the texels it lacks.
  EXPECT_DOUBLE_EQ(csm::keptMapError(1.0, csm::MapSize(512), csm::MapSize(1024)), 2.0);
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(csm::keptMapError(inf, csm::MapSize(2048), csm::MapSize(64)), inf);
  EXPECT_EQ(csm::keptMapError(std::nan(""), csm::MapSize(2048), csm::MapSize(64)), inf);
  EXPECT_EQ(csm::keptMapError(-1.0, csm::MapSize(2048), csm::MapSize(64)), inf);
  EXPECT_EQ(csm::keptMapError(1.0, csm::MapSize(2048), csm::MapSize(0, 64)), inf);
}

// Where even the largest map misses the error target, a kept map may be up to 1 / kCountHysteresis
// worse than a fresh one (the count's own hysteresis there); its room for a map smaller than
// that largest one shrinks as before.
TEST(Reuse, WhereNoMapMeetsTheTargetAKeptMapServesWithinTheCountsHysteresis)
{
  csm::Cascade cascade;
  cascade.Mx = 2.0;
  cascade.Mz = 3.0; // 3 x 600 / 0.7 = 2571 texels a side meet the target 0.7 at 600 pixels
  EXPECT_TRUE(csm::errorTargetOutOfReach(cascade, 600.0, 0.7, csm::MapSize(2048)));
  EXPECT_TRUE(csm::errorTargetOutOfReach(cascade, 600.0, 0.7, csm::MapSize(4096, 2048)));
  EXPECT_FALSE(csm::errorTargetOutOfReach(cascade, 600.0, 0.7, csm::MapSize(2572)));
  EXPECT_FALSE(csm::errorTargetOutOfReach(cascade, 600.0, 0.0, csm::MapSize(2048))); // no target
  EXPECT_FALSE(csm::errorTargetOutOfReach(cascade, std::nan(""), 0.7, csm::MapSize(2048)));
  EXPECT_FALSE(csm::errorTargetOutOfReach(cascade, 600.0, 0.7, csm::MapSize(0)));
  csm::Cascade fitted = cascade;
  fitted.sceneFitted = true; // drawn once at its tile: no target to miss
  EXPECT_FALSE(csm::errorTargetOutOfReach(fitted, 600.0, 0.7, csm::MapSize(2048)));
  csm::Cascade spot; // no M
  EXPECT_FALSE(csm::errorTargetOutOfReach(spot, 600.0, 0.7, csm::MapSize(2048)));

  const double most = 1.0 / csm::kCountHysteresis; // 1.25
  const csm::MapSize full(2048);
  EXPECT_FALSE(csm::keptMapServes(1.01, full, full));
  EXPECT_TRUE(csm::keptMapServes(1.01, full, full, true));
  EXPECT_TRUE(csm::keptMapServes(most, full, full, true));
  EXPECT_FALSE(csm::keptMapServes(most * 1.001, full, full, true));
  // A kept map of 1600 texels where the largest map is 2048: 1.25 x 1600 / 2048 = 0.977.
  EXPECT_TRUE(csm::keptMapServes(0.97, csm::MapSize(1600), full, true));
  EXPECT_FALSE(csm::keptMapServes(0.98, csm::MapSize(1600), full, true));
  EXPECT_FALSE(csm::keptMapServes(std::nan(""), full, full, true));
  EXPECT_FALSE(csm::keptMapServes(std::numeric_limits<double>::infinity(), full, full, true));
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
  const csm::MapSize need =
    csm::resolutionForError(first.cascades[0], imageHeight, target, 64, most);
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
    const auto reuse = csm::compareKeptMap(
      kept, fresh.cascades[0], turned, glm::normalize(light), true, 2.0 * 2.0 / slacked.size.width);
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

TEST(Reuse, ASmallCameraStepIsATurnOfAFewDegreesAndAMoveWellShortOfTheDepth)
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
  EXPECT_FALSE(csm::smallCameraStep(before, moved, 4.0));   // half the way to the depth
  EXPECT_FALSE(csm::smallCameraStep(before, before, 10.0)); // no step at all
  EXPECT_FALSE(csm::smallCameraStep(before, moved, std::nan("")));
  csm::Camera broken = before;
  broken.wsDirection = { 0.0, 0.0, 0.0 };
  EXPECT_FALSE(csm::smallCameraStep(before, broken, 10.0));
}

TEST(Reuse, ABorderedMapCoversTheBodyOfACameraThatTurnedALittle)
{
  // One cascade over a ground plane: the body ends where the visible scene does, in x, y and in
  // depth; a map with a border of 0.2 keeps covering it while the camera turns 1.5 degrees a
  // frame, with an error ratio near 1; the map without a border does not.
  csm::Bounds scene;
  scene.wsMin = { -10, 0, -10 };
  scene.wsMax = { 10, 2, 10 };
  csm::Camera cam = csmMathTest::camera(5.0, 60.0, 30.0, 4.0 / 3.0);
  cam.wsPosition = { 0, 12, 24 };
  cam.wsDirection = -cam.wsPosition;
  const glm::dvec3 light(-0.3, -1.0, -0.4);
  const auto s = csmMathTest::settings(csm::WarpMode::Generalized, csm::SplitScheme::Adaptive, 1);
  const auto kept = csm::computeShadowSetup(cam, light, &scene, s);
  ASSERT_EQ(kept.status, csm::Status::Ok);
  ASSERT_EQ(kept.cascades.size(), 1u);
  const glm::dmat4 bordered = csm::withBorder(kept.cascades[0].wsToClip, 0.2);
  // The body's corners land in the central 1/1.4 of the bordered map, depth included.
  for (const glm::dvec3& p : kept.cascades[0].wsBody)
  {
    const glm::dvec4 h = bordered * glm::dvec4(p, 1.0);
    EXPECT_LE(std::abs(h.z / h.w), 1.0 / 1.4 + 1e-9);
  }
  int covered = 0, coveredWithout = 0;
  for (int frame = 1; frame <= 4; ++frame)
  {
    const double a = glm::radians(1.5 * frame);
    csm::Camera turned = cam;
    turned.wsPosition = { 24.0 * std::sin(a), 12.0, 24.0 * std::cos(a) };
    turned.wsDirection = -turned.wsPosition;
    const auto fresh = csm::computeShadowSetup(turned, light, &scene, s);
    ASSERT_EQ(fresh.status, csm::Status::Ok);
    const auto reuse = csm::compareKeptMap(
      bordered, fresh.cascades[0], turned, glm::normalize(light), true, 2.0 * 2.0 / 1024.0);
    covered += reuse.covers;
    if (reuse.covers)
    {
      EXPECT_LT(reuse.errorRatio, 1.6) << "frame " << frame;
      EXPECT_GT(reuse.errorRatio, 0.6) << "frame " << frame;
    }
    coveredWithout += csm::compareKeptMap(kept.cascades[0].wsToClip, fresh.cascades[0], turned,
      glm::normalize(light), true, 2.0 * 2.0 / 1024.0)
                        .covers;
  }
  EXPECT_EQ(covered, 4);
  EXPECT_EQ(coveredWithout, 0);
  // The same with the maps turned to a non-square tile (orientToTile): the kept map's rows no
  // longer follow the turned camera's ls x and z exactly, and the error is still read along the
  // row that follows each (the ratio near 1, not the error across the map's other axis).
  const csm::MapSize tile =
    kept.cascades[0].Mx > kept.cascades[0].Mz ? csm::MapSize(1024, 2048) : csm::MapSize(2048, 1024);
  auto keptTurned = kept;
  csm::orientToTile(keptTurned, tile);
  ASSERT_TRUE(keptTurned.cascades[0].mapTurned);
  const glm::dmat4 borderedTurned = csm::withBorder(keptTurned.cascades[0].wsToClip, 0.2);
  for (int frame = 1; frame <= 4; ++frame)
  {
    const double a = glm::radians(1.5 * frame);
    csm::Camera turned = cam;
    turned.wsPosition = { 24.0 * std::sin(a), 12.0, 24.0 * std::cos(a) };
    turned.wsDirection = -turned.wsPosition;
    auto fresh = csm::computeShadowSetup(turned, light, &scene, s);
    csm::orientToTile(fresh, tile);
    ASSERT_TRUE(fresh.cascades[0].mapTurned);
    const auto reuse = csm::compareKeptMap(
      borderedTurned, fresh.cascades[0], turned, glm::normalize(light), true, 2.0 * 2.0 / 1024.0);
    EXPECT_TRUE(reuse.covers) << "frame " << frame;
    EXPECT_LT(reuse.errorRatio, 1.6) << "frame " << frame;
    EXPECT_GT(reuse.errorRatio, 0.6) << "frame " << frame;
  }
}

// The kept maps across a change of the count of cascades: a map that still serves stays in the
// tile it is in, the cascades drawn afresh take the other tiles, and no two maps overlap.
TEST(Reuse, KeptMapsStayInTheirTilesAcrossACountChange)
{
  using Rect = csm::TexelRect;
  const std::vector<Rect> three = { Rect{ 0, 0, 2048, 2048 }, Rect{ 2048, 0, 2048, 2048 },
    Rect{ 0, 2048, 2048, 2048 } };
  const std::vector<Rect> four = { three[0], three[1], three[2], Rect{ 2048, 2048, 2048, 2048 } };
  auto apart = [](const Rect& a, const Rect& b)
  {
    return a[0] + a[2] <= b[0] || b[0] + b[2] <= a[0] || a[1] + a[3] <= b[1] || b[1] + b[3] <= a[1];
  };
  // The same count: each cascade keeps its own map where it serves.
  int asked = 0;
  csm::TileAssignment same = csm::assignTiles(
    three, three, [&](int c, int k) { return ++asked, c == k && c != 1; }, { 2, 0, 1 }, true);
  EXPECT_EQ(same.kept, (std::vector<int>{ 0, -1, 2 }));
  EXPECT_EQ(same.tile, three);
  // Three to four cascades: the scene-fitted map (old 2, now cascade 3) stays where it is;
  // cascade 2, drawn afresh, takes the tile left.
  csm::TileAssignment grown = csm::assignTiles(
    four, three, [](int c, int k) { return c == 3 && k == 2; }, { 3, 0, 1, 2 }, true);
  EXPECT_EQ(grown.kept, (std::vector<int>{ -1, -1, -1, 2 }));
  EXPECT_EQ(grown.tile[3], three[2]);
  EXPECT_EQ(grown.tile[2], four[3]);
  for (int a = 0; a < 4; ++a)
  {
    for (int b = 0; b < a; ++b)
    {
      EXPECT_TRUE(apart(grown.tile[a], grown.tile[b])) << a << " " << b;
    }
  }
  // Without acrossTiles (several processes) only a map of the same index in the same tile.
  csm::TileAssignment local = csm::assignTiles(
    four, three, [](int c, int k) { return c == 3 && k == 2; }, { 3, 0, 1, 2 }, false);
  EXPECT_EQ(local.kept, (std::vector<int>{ -1, -1, -1, -1 }));
  EXPECT_EQ(local.tile, four);
  // Three cascades to one (its tile the whole atlas): the scene-fitted map in its own tile.
  const std::vector<Rect> one = { Rect{ 0, 0, 4096, 4096 } };
  csm::TileAssignment shrunk = csm::assignTiles(
    one, three, [](int, int k) { return k == 2; }, { 0 }, true);
  EXPECT_EQ(shrunk.kept, (std::vector<int>{ 2 }));
  EXPECT_EQ(shrunk.tile[0], three[2]);
  // One to three: the one map fits in no tile of three; serves is not asked for it.
  asked = 0;
  csm::TileAssignment split = csm::assignTiles(
    three, one, [&](int, int) { return ++asked, true; }, { 2, 0, 1 }, true);
  EXPECT_EQ(split.kept, (std::vector<int>{ -1, -1, -1 }));
  EXPECT_EQ(split.tile, three);
  EXPECT_EQ(asked, 0);
  EXPECT_TRUE(csm::rectInside(three[2], one[0]));
  EXPECT_FALSE(csm::rectInside(one[0], three[2]));
}

namespace
{
/// Texel coordinates (from the map's lower left) of a world point in a map of `size`.
glm::dvec2 texelOf(const glm::dmat4& wsToClip, const glm::dvec3& wsPoint, const csm::MapSize& size)
{
  const glm::dvec4 h = wsToClip * glm::dvec4(wsPoint, 1.0);
  return { 0.5 * (h.x / h.w + 1.0) * size.width, 0.5 * (h.y / h.w + 1.0) * size.height };
}
}

// A moved map holds the kept map's texels shifted by whole texels, warped or not: a world point
// at texel (i, j) of the kept map lies at (i - s, j - t) of the moved one, at the same depth.
TEST(Reuse, AMovedMapIsTheKeptMapShiftedByWholeTexels)
{
  csm::Bounds scene;
  scene.wsMin = { -10, 0, -10 };
  scene.wsMax = { 10, 2, 10 };
  csm::Camera cam = csmMathTest::camera(2.0, 60.0, 40.0, 4.0 / 3.0);
  cam.wsPosition = { 0, 6, 24 };
  cam.wsDirection = { 0, -0.3, -1 };
  const auto s = csmMathTest::settings(csm::WarpMode::Generalized, csm::SplitScheme::Adaptive, 1);
  const auto setup = csm::computeShadowSetup(cam, glm::dvec3(-0.3, -1.0, -0.4), &scene, s);
  ASSERT_EQ(setup.status, csm::Status::Ok);
  const glm::dmat4 kept = setup.cascades[0].wsToClip;
  ASSERT_NE(kept[3][3], 1.0); // warped: a perspective map
  const csm::MapSize size(1536, 1024);
  const glm::dmat4 moved = csm::panMatrix(kept, 37, -12, size);
  for (const glm::dvec3& p : setup.cascades[0].wsBody)
  {
    const glm::dvec2 before = texelOf(kept, p, size), after = texelOf(moved, p, size);
    EXPECT_NEAR(after.x, before.x - 37.0, 1e-6);
    EXPECT_NEAR(after.y, before.y + 12.0, 1e-6);
    const glm::dvec4 a = kept * glm::dvec4(p, 1.0), b = moved * glm::dvec4(p, 1.0);
    EXPECT_NEAR(a.z / a.w, b.z / b.w, 1e-12);
  }
  // A crop to a strip of the moved map sends the strip's corners to the corners of clip space.
  const csm::TexelRect strip = { 1499, 0, 37, 1024 };
  const glm::dmat4 cropped = csm::cropToTexels(moved, strip, size);
  const glm::dvec3 p = setup.cascades[0].wsBody[0];
  const glm::dvec2 inMap = texelOf(moved, p, size);
  const glm::dvec2 inStrip = texelOf(cropped, p, csm::MapSize(strip[2], strip[3]));
  EXPECT_NEAR(inStrip.x, inMap.x - strip[0], 1e-6);
  EXPECT_NEAR(inStrip.y, inMap.y - strip[1], 1e-6);
}

// The move that centres a fresh body in a kept map, and the strips it draws: together with the
// kept part they cover the map once.
TEST(Reuse, AMoveCentresTheBodyAndDrawsOnlyTheStripsThatCameIn)
{
  const glm::dmat4 ortho = glm::dmat4(1.0); // world x, y = clip x, y
  const csm::MapSize size(1000, 800);
  // A body whose centre lies at ndc (0.1, -0.05): 50 texels right, 20 down.
  const std::vector<glm::dvec3> body = { { -0.2, -0.3, 0.0 }, { 0.4, 0.2, 0.5 } };
  const csm::MapPan pan = csm::panKeptMap(ortho, body, size);
  ASSERT_TRUE(pan.valid);
  EXPECT_EQ(pan.s, 50);
  EXPECT_EQ(pan.t, -20);
  for (const glm::dvec3& p : body)
  {
    const glm::dvec4 h = pan.wsToClip * glm::dvec4(p, 1.0);
    EXPECT_NEAR(h.x, p.x - 0.1, 1e-12);
    EXPECT_NEAR(h.y, p.y + 0.05, 1e-12);
  }
  const std::vector<csm::TexelRect> strips = csm::panStrips(pan, size);
  ASSERT_EQ(strips.size(), 2u);
  EXPECT_EQ(strips[0], (csm::TexelRect{ 950, 0, 50, 800 })); // the columns that came in
  EXPECT_EQ(strips[1], (csm::TexelRect{ 0, 0, 950, 20 }));   // the rows, beside them
  // Each texel once: drawn in a strip or kept (shifted from inside the kept map).
  std::vector<int> hits(size_t(size.width) * size.height, 0);
  for (const csm::TexelRect& r : strips)
  {
    for (int y = r[1]; y < r[1] + r[3]; ++y)
      for (int x = r[0]; x < r[0] + r[2]; ++x)
        ++hits[size_t(y) * size.width + x];
  }
  for (int y = 0; y < size.height; ++y)
  {
    for (int x = 0; x < size.width; ++x)
    {
      const int keptX = x + pan.s, keptY = y + pan.t;
      hits[size_t(y) * size.width + x] +=
        keptX >= 0 && keptX < size.width && keptY >= 0 && keptY < size.height;
    }
  }
  EXPECT_EQ(std::count(hits.begin(), hits.end(), 1), long(hits.size()));
  // No move: centred already, behind a perspective map's centre, farther than the map, empty.
  EXPECT_FALSE(csm::panKeptMap(ortho, { { -0.5, -0.5, 0 }, { 0.5, 0.5, 0 } }, size).valid);
  glm::dmat4 perspective(1.0);
  perspective[2][3] = -1.0; // w = -z
  perspective[3][3] = 0.0;
  EXPECT_FALSE(csm::panKeptMap(perspective, { { 0.1, 0.1, 1.0 } }, size).valid);
  EXPECT_FALSE(csm::panKeptMap(ortho, { { 2.5, 0.0, 0.0 } }, size).valid);
  EXPECT_FALSE(csm::panKeptMap(ortho, {}, size).valid);
  EXPECT_FALSE(csm::panKeptMap(ortho, body, csm::MapSize(0)).valid);
  EXPECT_TRUE(csm::panStrips(csm::MapPan(), size).empty());
}

// A camera that moves sideways (a strafe past a structure): a slacked map that stays where it
// was stops covering the body within a few frames; moved with the view by whole texels it
// serves on (its error at each view read by the error model, as any kept map's), and only the
// strips that came in are drawn.
namespace
{
struct SidewaysWalk
{
  int StillServed = 0, MovingServed = 0, Moves = 0;
  double StripShare = 0.0; ///< texels drawn in strips over a whole map's, a move
};

SidewaysWalk WalkSideways(csm::WarpMode warp, int frames)
{
  SidewaysWalk result;
  csm::Bounds scene;
  scene.wsMin = { -40, 0, -40 };
  scene.wsMax = { 40, 3, 40 };
  csm::Camera cam = csmMathTest::camera(2.0, 60.0, 12.0, 4.0 / 3.0);
  cam.wsPosition = { 0, 4, 18 };
  cam.wsDirection = { 0, -0.35, -1 };
  const glm::dvec3 light(0.0, -1.0, -0.4); // (across the move: the depths stay)
  const auto s = csmMathTest::settings(warp, csm::SplitScheme::Adaptive, 1);
  const double imageHeight = 480.0, target = 2.0;
  const csm::MapSize most(8192); // (room for the slack: the need is below the ceiling)
  const auto first = csm::computeShadowSetup(cam, light, &scene, s);
  EXPECT_EQ(first.status, csm::Status::Ok);
  const csm::MapSize need =
    csm::resolutionForError(first.cascades[0], imageHeight, target, 64, most);
  const csm::SlackedMap slacked = csm::slackedMap(need, most, 0.44);
  EXPECT_LT(need.width, most.width);
  const glm::dmat4 still = csm::withBorder(first.cascades[0].wsToClip, slacked.border);
  glm::dmat4 moving = still;
  int& stillServed = result.StillServed;
  int& movingServed = result.MovingServed;
  double stripTexels = 0.0;
  for (int frame = 1; frame <= frames; ++frame)
  {
    csm::Camera now = cam;
    now.wsPosition.x += 0.25 * frame;
    const auto fresh = csm::computeShadowSetup(now, light, &scene, s);
    EXPECT_EQ(fresh.status, csm::Status::Ok);
    const csm::MapSize freshNeed =
      csm::resolutionForError(fresh.cascades[0], imageHeight, target, 64, most);
    const double margin = 2.0 * 2.0 / slacked.size.width;
    auto serves = [&](const glm::dmat4& m)
    {
      const auto reuse =
        csm::compareKeptMap(m, fresh.cascades[0], now, glm::normalize(light), true, margin);
      return reuse.covers && csm::keptMapServes(reuse.errorRatio, slacked.size, freshNeed);
    };
    stillServed += serves(still) && stillServed == frame - 1;
    if (movingServed != frame - 1)
    {
      continue;
    }
    if (serves(moving))
    {
      ++movingServed;
      continue;
    }
    const csm::MapPan pan = csm::panKeptMap(moving, fresh.cascades[0].wsBody, slacked.size);
    if (pan.valid && serves(pan.wsToClip))
    {
      moving = pan.wsToClip;
      ++movingServed;
      ++result.Moves;
      for (const csm::TexelRect& r : csm::panStrips(pan, slacked.size))
      {
        stripTexels += double(r[2]) * r[3];
      }
    }
  }
  result.StripShare = result.Moves > 0
    ? stripTexels / (result.Moves * double(slacked.size.width) * slacked.size.height)
    : 0.0;
  return result;
}
} // namespace

TEST(Reuse, AMovedOrthographicMapServesACameraMovingSideways)
{
  // Orthographic: the move is exact, the map serves every frame.
  const SidewaysWalk walk = WalkSideways(csm::WarpMode::None, 30);
  EXPECT_GE(walk.StillServed, 1);
  EXPECT_LT(walk.StillServed, 10);
  EXPECT_EQ(walk.MovingServed, 30);
  EXPECT_GT(walk.Moves, 2);
  EXPECT_LT(walk.StripShare, 0.3); // a small part of drawing the map at every move
  EXPECT_GT(walk.StripShare, 0.0);
}

TEST(Reuse, AMovedWarpedMapServesACameraMovingSidewaysLongerThanAKeptOne)
{
  // Warped: a move shears the body in the map (its x scale falls with the distance from the
  // warp's centre), and the error model ends the moves a few frames later.
  const SidewaysWalk walk = WalkSideways(csm::WarpMode::Generalized, 30);
  EXPECT_GE(walk.StillServed, 1);
  EXPECT_GT(walk.MovingServed, walk.StillServed);
  EXPECT_GT(walk.Moves, 0);
}

// The texels a changed caster's box may set in a kept map: its image, grown by the margin and
// clipped to the map; nothing where it misses the map, the whole map where part of it lies
// behind the light's eye.
TEST(Reuse, ABoxSetsTheTexelsOfItsImage)
{
  // An orthographic map of x, y in [-10, 10] over 200 x 100 texels: 10 and 5 texels a unit.
  glm::dmat4 wsToClip(1.0);
  wsToClip[0][0] = 0.1;
  wsToClip[1][1] = 0.1;
  wsToClip[2][2] = 0.1;
  const csm::MapSize size(200, 100);
  csm::Bounds box;
  box.wsMin = { -1.0, 2.0, -3.0 };
  box.wsMax = { 1.5, 4.0, 3.0 };
  // x -1 .. 1.5 -> texels 90 .. 115; y 2 .. 4 -> texels 60 .. 70; one texel more each side.
  const csm::TexelRect rect = csm::boxTexels(wsToClip, box, size, 1);
  EXPECT_EQ(rect, (csm::TexelRect{ 89, 59, 27, 12 }));
  EXPECT_EQ(csm::boxTexels(wsToClip, box, size, 0), (csm::TexelRect{ 90, 60, 25, 10 }));
  // At the map's edge: clipped.
  box.wsMin.x = 8.0;
  box.wsMax.x = 30.0;
  EXPECT_EQ(csm::boxTexels(wsToClip, box, size, 1), (csm::TexelRect{ 179, 59, 21, 12 }));
  // Beside the map: nothing.
  box.wsMin.x = 12.0;
  EXPECT_EQ(csm::boxTexels(wsToClip, box, size, 1)[2], 0);
  // Empty box: nothing; a box behind a perspective map's eye (w <= 0): the whole map.
  EXPECT_EQ(csm::boxTexels(wsToClip, csm::Bounds(), size, 1)[2], 0);
  glm::dmat4 perspective(1.0);
  perspective[2][3] = -1.0; // w = -z
  perspective[3][3] = 0.0;
  box.wsMin = { -1.0, -1.0, -2.0 };
  box.wsMax = { 1.0, 1.0, 1.0 };
  EXPECT_EQ(csm::boxTexels(perspective, box, size, 1), (csm::TexelRect{ 0, 0, 200, 100 }));
  box.wsMin = { -0.5, -0.5, -2.0 };
  box.wsMax = { 0.5, 0.5, -1.0 }; // in front: x / w and y / w in [-0.5, 0.5], the middle half
  const csm::TexelRect front = csm::boxTexels(perspective, box, size, 0);
  EXPECT_EQ(front, (csm::TexelRect{ 50, 25, 100, 50 }));
}

// The rectangles a kept map draws again: a caster's boxes before and after a small move overlap
// and become one rectangle (its casters drawn once); rectangles far apart stay apart (the one
// around them would draw many texels neither needs); merging goes on while a pair gains.
TEST(Reuse, OverlappingPatchesAreDrawnAsOne)
{
  using csm::TexelRect;
  // Before and after a move of 2 texels: 10 x 10 each, 12 x 10 around them (120 <= 200).
  EXPECT_EQ(csm::mergeTexelRects({ { 10, 10, 10, 10 }, { 12, 10, 10, 10 } }),
    (std::vector<TexelRect>{ { 10, 10, 12, 10 } }));
  // Apart: 10 x 10 at 0 and at 50 would be 60 x 10 (600 > 200).
  const std::vector<TexelRect> apart = { { 0, 0, 10, 10 }, { 50, 0, 10, 10 } };
  EXPECT_EQ(csm::mergeTexelRects(apart), apart);
  // Touching side by side: the rectangle around is their union.
  EXPECT_EQ(csm::mergeTexelRects({ { 0, 0, 10, 10 }, { 10, 0, 5, 10 } }),
    (std::vector<TexelRect>{ { 0, 0, 15, 10 } }));
  // One inside another: the outer one.
  EXPECT_EQ(csm::mergeTexelRects({ { 2, 2, 3, 3 }, { 0, 0, 10, 10 } }),
    (std::vector<TexelRect>{ { 0, 0, 10, 10 } }));
  // A chain: a and b apart (the rectangle around them 30 x 10 = 300 > 200), c over both's gap
  // joins a (20 x 10 <= 100 + 100), then the pair joins b (30 x 10 <= 200 + 100).
  EXPECT_EQ(csm::mergeTexelRects({ { 0, 0, 10, 10 }, { 20, 0, 10, 10 }, { 10, 0, 10, 10 } }),
    (std::vector<TexelRect>{ { 0, 0, 30, 10 } }));
  // Empty rectangles dropped.
  EXPECT_EQ(csm::mergeTexelRects({ { 5, 5, 0, 4 }, { 1, 1, 2, 2 }, { 3, 3, 4, -1 } }),
    (std::vector<TexelRect>{ { 1, 1, 2, 2 } }));
  EXPECT_TRUE(csm::mergeTexelRects({}).empty());
  // Past kMostMergedRects: as they are (but the empty ones).
  std::vector<TexelRect> many(csm::kMostMergedRects + 1, TexelRect{ 0, 0, 4, 4 });
  EXPECT_EQ(csm::mergeTexelRects(many), many);
}
