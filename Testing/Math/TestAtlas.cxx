// SPDX-License-Identifier: BSD-3-Clause
// The atlas one light's cascades share, the tiles each count gets, and maps turned to their
// tiles so that the larger of Lloyd et al. 2006's M_x, M_z gets the longer side.
#include "csmAliasing.h"
#include "csmAtlas.h"
#include "csmMathTestHelpers.h"
#include "csmSetup.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

namespace
{
using csmMathTest::camera;  // eye at the origin looking down -z, up +y
using csmMathTest::lightAt; // gammaDeg: 0 light from behind, 90 overhead, 180 facing
using csmMathTest::settings;
using csmMathTest::toNdc;
} // namespace

TEST(Steps, CascadesShareOneAtlasOfFourFullMaps)
{
  // Two or three most cascades: a row of full-size tiles; four or more: 2 x 2 of them.
  const csm::AtlasGrid two = csm::atlasLayout(2, 2048);
  EXPECT_EQ(two.columns, 2);
  EXPECT_EQ(two.rows, 1);
  EXPECT_EQ(two.tile, csm::MapSize(2048));
  EXPECT_EQ(csm::atlasLayout(3, 2048).columns, 3);
  EXPECT_EQ(csm::atlasLayout(1, 2048).columns, 1);
  EXPECT_EQ(csm::atlasLayout(1, 2048).rows, 1);
  const csm::AtlasGrid six = csm::atlasLayout(6, 2048);
  EXPECT_EQ(six.columns, 2); // never more than four full maps' texels
  EXPECT_EQ(six.rows, 2);
  EXPECT_EQ(six.tile, csm::MapSize(2048));
  // One cascade gets the whole texture; more share it in the grid whose tiles have the longest
  // short side, none larger than a full map.
  const csm::MapSize expected[9] = { {}, { 4096, 4096 }, { 2048, 2048 }, { 2048, 2048 },
    { 2048, 2048 }, { 2048, 1365 }, { 2048, 1365 }, { 1365, 1365 }, { 1365, 1365 } };
  for (int k = 1; k <= 8; ++k)
  {
    const csm::AtlasGrid f = csm::atlasForCount(k, six);
    EXPECT_EQ(f.tile, expected[k]) << k << " cascades";
    EXPECT_GE(f.columns * f.rows, k);
    // Within the one texture of every count.
    EXPECT_LE(f.columns * f.tile.width, 2 * 2048) << k;
    EXPECT_LE(f.rows * f.tile.height, 2 * 2048) << k;
    if (k > 1)
    {
      EXPECT_EQ(csm::atlasGrid(k, six).tile, f.tile) << k;
    }
    EXPECT_EQ(csm::resolutionCeilingForCount(k, 6, 2048), f.tile);
    // A scene-fitted map gets its tile; one that follows the view at most 2048 a side.
    EXPECT_EQ(csm::ceilingsForCount(k, 6, 2048).sceneFitted, f.tile) << k;
    EXPECT_EQ(csm::ceilingsForCount(k, 6, 2048).following,
      csm::MapSize(std::min(f.tile.width, 2048), std::min(f.tile.height, 2048)))
      << k;
  }
  // Two most cascades in a row: one gets a full map.
  EXPECT_EQ(csm::resolutionCeilingForCount(1, 2, 2048), csm::MapSize(2048));
  EXPECT_EQ(csm::resolutionCeilingForCount(2, 2, 2048), csm::MapSize(2048));
  // A GL size limit: the tiles shrink to fit it.
  const csm::AtlasGrid limited = csm::atlasLayout(6, 4096, 4096);
  EXPECT_EQ(limited.tile, csm::MapSize(2048));
  EXPECT_EQ(csm::atlasForCount(1, limited).tile, csm::MapSize(4096));
  EXPECT_EQ(csm::atlasForCount(6, limited).tile, csm::MapSize(2048, 1365));
  EXPECT_EQ(csm::atlasLayout(3, 2048, 4096).tile, csm::MapSize(1365));
  EXPECT_EQ(csm::atlasForCount(0, six).tile, csm::MapSize(0));
  // 2 x 3 and 3 x 2 tie at 1365 texels on the short side and in area: fewer columns.
  EXPECT_EQ(csm::atlasGrid(6, six).columns, 2);
  EXPECT_EQ(csm::atlasGrid(8, six).columns, 3); // 3 x 3 of 1365 beats 2 x 4 of 2048 x 1024
  // A smaller ceiling (while interacting) shares its own budget; bad counts give nothing.
  EXPECT_EQ(csm::resolutionCeilingForCount(1, 6, 1024), csm::MapSize(2048));
  EXPECT_EQ(csm::resolutionCeilingForCount(4, 6, 1024), csm::MapSize(1024));
  EXPECT_EQ(csm::resolutionCeilingForCount(6, 6, 1024), csm::MapSize(1024, 682));
  EXPECT_EQ(csm::resolutionCeilingForCount(0, 6, 2048), csm::MapSize(0));
  EXPECT_EQ(csm::resolutionCeilingForCount(3, 6, 0), csm::MapSize(0));
  EXPECT_EQ(csm::atlasLayout(0, 2048).tile, csm::MapSize(0));
  EXPECT_EQ(csm::ceilingsForCount(0, 6, 2048).following, csm::MapSize(0));
  // More than the most planned: the atlas grows to hold them (a caller's safety, not a use).
  EXPECT_EQ(csm::resolutionCeilingForCount(3, 1, 2048), csm::MapSize(2048));
}

TEST(Steps, MapsTurnToTheirTilesWhereTheLongSideServesTheLargerError)
{
  // The light along a 4:3 view (gamma 0): no warp helps, and each map spans the frustum's
  // cross-section, a third wider than high, so its error along the image's width is the larger.
  const csm::Camera cam = camera(5.0, 6000.0, 50.0, 4.0 / 3.0);
  const glm::dvec3 light = lightAt(cam, 0.0);
  const csm::ShadowSetup plain = csm::computeShadowSetup(
    cam, light, nullptr, settings(csm::WarpMode::Generalized, csm::SplitScheme::Log, 5));
  ASSERT_EQ(plain.status, csm::Status::Ok);
  ASSERT_EQ(plain.cascades.size(), 5u);
  const csm::MapSize tile(1638, 2048); // a tall tile (five in a row of four full maps)
  csm::ShadowSetup turned = plain;
  csm::orientToTile(turned, tile);
  int turnedCount = 0;
  for (size_t i = 0; i < plain.cascades.size(); ++i)
  {
    const csm::Cascade& before = plain.cascades[i];
    const csm::Cascade& after = turned.cascades[i];
    EXPECT_FALSE(before.mapTurned);
    // Turned exactly where the larger M gets the longer side (height) that way.
    EXPECT_EQ(after.mapTurned, before.Mx > before.Mz) << i;
    turnedCount += after.mapTurned ? 1 : 0;
    const glm::dvec2 m = csm::mapAxisAliasing(after);
    EXPECT_GE(m.y, m.x) << "the larger error along the tile's 2048 texels";
    // The predicted error is that of the turned map, never more than unturned.
    const double unturned = 600.0 * std::max(before.Mx / tile.width, before.Mz / tile.height);
    const double asTurned = 600.0 * std::max(m.x / tile.width, m.y / tile.height);
    EXPECT_NEAR(csm::predictedError(after, 600.0, tile), asTurned, 1e-12 * asTurned);
    EXPECT_NEAR(csm::predictedError(before, 600.0, tile), asTurned, 1e-12 * asTurned);
    EXPECT_LE(asTurned, unturned);
    // A rotation, not a mirror: the same body in the same [-1,1]^3, s' = t, t' = -s, same depth;
    // and Lloyd's m along ls x and z is the same measured on either map.
    for (const glm::dvec3& p : before.wsBody)
    {
      const glm::dvec3 a = toNdc(before.wsToClip, p);
      const glm::dvec3 b = toNdc(after.wsToClip, p);
      const glm::dvec3 expect = after.mapTurned ? glm::dvec3(a.y, -a.x, a.z) : a;
      EXPECT_NEAR(glm::length(b - expect), 0.0, 1e-9);
      const csm::Aliasing ma = csm::aliasingAt(before.wsToClip, cam, light, p);
      const csm::Aliasing mb = csm::aliasingAt(after.wsToClip, cam, light, p);
      EXPECT_NEAR(ma.mx, mb.mx, 1e-9 * ma.mx);
      EXPECT_NEAR(ma.mz, mb.mz, 1e-9 * ma.mz);
    }
    // The texels the larger M needs along both axes, each within its side of the tile.
    const csm::MapSize need = csm::resolutionForError(after, 600.0, 1.0, 64, tile);
    EXPECT_EQ(need.width, csm::resolutionForError(m.y, 600.0, 1.0, 64, tile.width));
    EXPECT_EQ(need.height, csm::resolutionForError(m.y, 600.0, 1.0, 64, tile.height));
  }
  EXPECT_GT(turnedCount, 0);
  // Five tall tiles beat five square tiles of the same row (1638 a side) on this view.
  const double square = csm::predictedError(plain, 600.0, csm::MapSize(1638));
  const double tall = csm::predictedError(turned, 600.0, tile);
  EXPECT_LT(tall, 0.9 * square);
  std::printf("light along a 1:1200 view, 5 cascades: %.2f in 1638 x 2048 tiles, %.2f in 1638^2\n",
    tall, square);
  // A square tile turns nothing.
  csm::ShadowSetup same = plain;
  csm::orientToTile(same, csm::MapSize(2048));
  for (const csm::Cascade& c : same.cascades)
  {
    EXPECT_FALSE(c.mapTurned);
  }
}

// One plan a light: the texture of the most cascades, this count's tiles in it (placed without
// overlap, inside the texture), the largest map of each kind within its tile, and the GL's
// texture limit shrinking the tiles (the count is judged with the same plan).
TEST(Steps, OneAtlasPlanGivesTheTextureTilesAndCeilings)
{
  for (int count = 0; count <= 8; ++count)
  {
    const csm::AtlasPlan plan = csm::planAtlas(count, 8, csm::AtlasLimits(2048, 2048, 0));
    EXPECT_EQ(plan.texture, csm::MapSize(4096)) << count; // the same texture for every count
    EXPECT_FALSE(plan.shrunk);
    for (int i = 0; i < count; ++i)
    {
      const std::array<int, 4> a = plan.tile(i);
      EXPECT_GE(a[0], 0);
      EXPECT_GE(a[1], 0);
      EXPECT_LE(a[0] + a[2], plan.texture.width) << count << " " << i;
      EXPECT_LE(a[1] + a[3], plan.texture.height) << count << " " << i;
      for (int j = 0; j < i; ++j)
      {
        const std::array<int, 4> b = plan.tile(j);
        const bool apart =
          a[0] + a[2] <= b[0] || b[0] + b[2] <= a[0] || a[1] + a[3] <= b[1] || b[1] + b[3] <= a[1];
        EXPECT_TRUE(apart) << count << ": tiles " << j << " and " << i;
      }
      // The largest maps fit the tile; one that follows the view is at most the ceiling.
      EXPECT_LE(plan.ceilings.sceneFitted.width, a[2]);
      EXPECT_LE(plan.ceilings.sceneFitted.height, a[3]);
      EXPECT_LE(plan.ceilings.following.width, 2048);
    }
  }
  // One cascade: the whole texture; a scene-fitted map may have it all, one that follows the
  // view Resolution a side.
  const csm::AtlasPlan one = csm::planAtlas(1, 8, csm::AtlasLimits(2048, 2048, 0));
  EXPECT_EQ(one.tile(0), (std::array<int, 4>{ 0, 0, 4096, 4096 }));
  EXPECT_EQ(one.ceilings.sceneFitted, csm::MapSize(4096));
  EXPECT_EQ(one.ceilings.following, csm::MapSize(2048));
  // While the user drags: the same texture, maps that follow the view at most the ceiling.
  const csm::AtlasPlan dragging = csm::planAtlas(3, 8, csm::AtlasLimits(2048, 1024, 0));
  EXPECT_EQ(dragging.texture, csm::MapSize(4096));
  EXPECT_EQ(dragging.tiles.tile, csm::MapSize(2048));
  EXPECT_EQ(dragging.ceilings.following, csm::MapSize(1024));
  // A GL limit of 2048 texels: tiles of 1024, and the ceilings within them.
  const csm::AtlasPlan limited = csm::planAtlas(4, 8, csm::AtlasLimits(2048, 2048, 2048));
  EXPECT_TRUE(limited.shrunk);
  EXPECT_EQ(limited.texture, csm::MapSize(2048));
  EXPECT_EQ(limited.tiles.tile, csm::MapSize(1024));
  EXPECT_EQ(limited.ceilings.following, csm::MapSize(1024));
  EXPECT_EQ(limited.ceilings.sceneFitted, csm::MapSize(1024));
  // Limits below one texel: nothing.
  EXPECT_EQ(csm::planAtlas(2, 8, csm::AtlasLimits(0)).texture, csm::MapSize(0));
}
