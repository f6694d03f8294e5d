// SPDX-License-Identifier: BSD-3-Clause
// Light-space pages: the levels that bring the scene-fitted map to the error target, the pages
// a view's samples read, each page's clip space, and the pages kept in the pool across frames.
#include "csmPages.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace
{
/// An orthographic base map of a world square `side` wide (x across s, z across t, y depth).
glm::dmat4 baseClip(double side)
{
  return glm::ortho(-side / 2, side / 2, -side / 2, side / 2, -side, side) *
    glm::lookAt(glm::dvec3(0.0), glm::dvec3(0.0, -1.0, 0.0), glm::dvec3(0.0, 0.0, -1.0));
}

const double kPixel = 2.0 * std::tan(glm::radians(30.0)) / 480.0; // 60 degrees, 480 rows

/// Window NDC -> base [0, 1]^2: x and y straight across (the depth does not move a sample).
glm::dmat4 straightAcross()
{
  glm::dmat4 m(0.0);
  m[0][0] = 0.5;
  m[1][1] = 0.5;
  m[3][0] = 0.5;
  m[3][1] = 0.5;
  m[3][3] = 1.0;
  return m;
}

std::vector<csm::PageKey> pagesOfLevel(const std::vector<csm::PageKey>& pages, int level)
{
  std::vector<csm::PageKey> of;
  for (const csm::PageKey& page : pages)
  {
    if (page.level == level)
    {
      of.push_back(page);
    }
  }
  return of;
}
} // namespace

TEST(Pages, LevelsHalveTheTexelEachOctaveOfDepthDownToTheNearestSample)
{
  // 100 world units over 2048 texels: a texel of 0.048828125 meets 0.7 at D_0 = t / (0.7 p).
  csm::PageLevels levels;
  ASSERT_TRUE(csm::pageLevels(baseClip(100.0), csm::MapSize(2048), kPixel, 0.7, 1.0, levels));
  const double baseDepth = (100.0 / 2048.0) / (0.7 * kPixel);
  EXPECT_NEAR(levels.baseDepth, baseDepth, 1e-9 * baseDepth);
  EXPECT_EQ(levels.count, static_cast<int>(std::ceil(std::log2(baseDepth / 1.0))));
  EXPECT_EQ(levels.baseTexels, glm::dvec2(2048.0));
  EXPECT_EQ(levels.texels(3), glm::dvec2(16384.0));
  // Level k serves fineness (k - 1, k]: at D_0 / 2^k the texel of level k meets the target.
  EXPECT_EQ(levels.levelAt(levels.fineness(baseDepth)), 0);
  EXPECT_EQ(levels.levelAt(levels.fineness(baseDepth * 0.99)), 1);
  EXPECT_EQ(levels.levelAt(levels.fineness(baseDepth / 2.0)), 1);
  EXPECT_EQ(levels.levelAt(levels.fineness(baseDepth / 2.01)), 2);
  EXPECT_EQ(levels.levelAt(levels.fineness(1e-9)), levels.count); // the finest serves nearer
  EXPECT_EQ(levels.levelAt(std::numeric_limits<double>::quiet_NaN()), 0);
  // Every level meets the target over the depths it serves: a texel of t_k at depth d reads
  // t_k / (d p), the most at the nearest depth of its octave.
  for (double d = 1.0; d < 2.0 * baseDepth; d *= 1.013)
  {
    const int k = levels.levelAt(levels.fineness(d));
    const double texel = 100.0 / levels.texels(k).x;
    if (k < levels.count)
    {
      EXPECT_LE(texel / (d * kPixel), 0.7 * (1.0 + 1e-9)) << d;
    }
    EXPECT_GE(texel / (d * kPixel), k > 0 ? 0.35 * (1.0 - 1e-9) : 0.0) << d;
  }
  // The view never nearer than D_0: no level.
  ASSERT_TRUE(
    csm::pageLevels(baseClip(100.0), csm::MapSize(2048), kPixel, 0.7, baseDepth * 2.0, levels));
  EXPECT_EQ(levels.count, 0);
}

TEST(Pages, LevelsAreRefusedForBadInputAndWhereTheFinestLevelCannotServe)
{
  csm::PageLevels levels;
  const double baseDepth = (100.0 / 2048.0) / (0.7 * kPixel);
  EXPECT_TRUE(
    csm::pageLevels(baseClip(100.0), csm::MapSize(2048), kPixel, 0.7, baseDepth / 4096.0, levels));
  EXPECT_EQ(levels.count, csm::kMaxPageLevels);
  // The finest level serves one octave more, within twice the target; a sample nearer still (a
  // base thousands of times the view's scale: a prop far out in the scene): no levels, the
  // cascades serve.
  EXPECT_TRUE(
    csm::pageLevels(baseClip(100.0), csm::MapSize(2048), kPixel, 0.7, baseDepth / 8192.0, levels));
  EXPECT_EQ(levels.count, csm::kMaxPageLevels);
  EXPECT_FALSE(
    csm::pageLevels(baseClip(100.0), csm::MapSize(2048), kPixel, 0.7, baseDepth / 8300.0, levels));
  EXPECT_EQ(levels.count, 0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(csm::pageLevels(baseClip(100.0), csm::MapSize(2048), kPixel, 0.7, nan, levels));
  EXPECT_FALSE(csm::pageLevels(baseClip(100.0), csm::MapSize(2048), nan, 0.7, 1.0, levels));
  EXPECT_FALSE(csm::pageLevels(baseClip(100.0), csm::MapSize(0), kPixel, 0.7, 1.0, levels));
  EXPECT_FALSE(csm::pageLevels(baseClip(nan), csm::MapSize(2048), kPixel, 0.7, 1.0, levels));
  const glm::dmat4 perspective = glm::perspective(1.0, 1.0, 0.1, 10.0);
  EXPECT_FALSE(csm::pageLevels(perspective, csm::MapSize(2048), kPixel, 0.7, 1.0, levels));
  EXPECT_EQ(levels.count, 0);
}

TEST(Pages, APageIsItsLevelsTexelsWithABorderAtTheBaseMapsDepth)
{
  csm::PageLevels levels;
  ASSERT_TRUE(csm::pageLevels(baseClip(100.0), csm::MapSize(2048), kPixel, 0.7, 1.0, levels));
  const glm::dmat4 base = baseClip(100.0);
  const csm::PageKey page{ 2, 5, 7 };
  const glm::dmat4 clip = csm::pageClip(base, levels, page);
  // The world point at level 2's texel (5 * 248, 7 * 248) (the page's first own texel corner)
  // lies kPageBorder texels inside the page's clip square; its depth is the base's.
  const glm::dvec2 texels = levels.texels(2);
  const glm::dvec2 u(5.0 * csm::kPageInterior, 7.0 * csm::kPageInterior);
  const glm::dvec2 ndc = 2.0 * u / texels - 1.0;
  const glm::dvec4 world = glm::inverse(base) * glm::dvec4(ndc, 0.25, 1.0);
  const glm::dvec4 inPage = clip * world;
  const double border = -1.0 + 2.0 * csm::kPageBorder / csm::kPageTexels;
  EXPECT_NEAR(inPage.x, border, 1e-9);
  EXPECT_NEAR(inPage.y, border, 1e-9);
  EXPECT_NEAR(inPage.z, 0.25, 1e-12);
  EXPECT_EQ(inPage.w, 1.0);
  // One texel of the level is 2 / 256 of the page's clip span.
  const glm::dvec4 next = clip *
    (glm::inverse(base) * glm::dvec4(2.0 * (u + glm::dvec2(1.0, 0.0)) / texels - 1.0, 0.25, 1.0));
  EXPECT_NEAR(next.x - inPage.x, 2.0 / csm::kPageTexels, 1e-9);
}

TEST(Pages, SamplesMarkThePagesOfTheirLevelAndOfTheBandAndEdges)
{
  // A base of 256 texels: level 2 has 1024 texels a side, 5 pages of 248.
  csm::PageLevels levels;
  levels.baseTexels = glm::dvec2(256.0);
  levels.baseDepth = 100.0;
  levels.count = 3;
  const double vsNear = 1.0, vsFar = 1000.0;
  const int width = 64, height = 48;
  // Every sample at fineness 1.5 (level 2): 5 x 5 pages of level 2, nothing else.
  const double inLevel2 = 100.0 / std::exp2(1.5);
  std::vector<float> depths(width * height,
    static_cast<float>(csm::windowDepthFromViewDepth(inLevel2, vsNear, vsFar, false)));
  depths[5] = 1.0f; // background: no page
  std::vector<csm::PageKey> pages;
  ASSERT_TRUE(csm::markPages(
    levels, straightAcross(), vsNear, vsFar, depths.data(), width, height, {}, 1000, pages));
  EXPECT_EQ(pages.size(), 25u);
  EXPECT_EQ(pagesOfLevel(pages, 2).size(), 25u);
  // In the dithered band before level 3 (fineness 2 - band / 2): level 3's pages too.
  const double inBand = 100.0 / std::exp2(2.0 - csm::kPageBlendBand / 2.0);
  std::fill(depths.begin(), depths.end(),
    static_cast<float>(csm::windowDepthFromViewDepth(inBand, vsNear, vsFar, false)));
  ASSERT_TRUE(csm::markPages(
    levels, straightAcross(), vsNear, vsFar, depths.data(), width, height, {}, 1000, pages));
  EXPECT_EQ(pagesOfLevel(pages, 2).size(), 25u);
  EXPECT_EQ(pagesOfLevel(pages, 3).size(), 81u); // 2048 / 248: 9 a side
  EXPECT_EQ(pagesOfLevel(pages, 1).size(), 0u);
  // More pages than the pool holds: refused.
  EXPECT_FALSE(csm::markPages(
    levels, straightAcross(), vsNear, vsFar, depths.data(), width, height, {}, 100, pages));
  // One sample near the left edge of page 1 of level 2: pages 0 and 1 across, one row.
  std::fill(depths.begin(), depths.end(), 1.0f);
  std::vector<float> one(
    1, static_cast<float>(csm::windowDepthFromViewDepth(inLevel2, vsNear, vsFar, false)));
  glm::dmat4 toTexel = straightAcross();
  // The single pixel's centre (NDC 0, 0) at level 2 texel (248 + 1, 100).
  toTexel[3][0] = (248.0 + 1.0) / 1024.0;
  toTexel[3][1] = 100.0 / 1024.0;
  ASSERT_TRUE(csm::markPages(levels, toTexel, vsNear, vsFar, one.data(), 1, 1, {}, 1000, pages));
  ASSERT_EQ(pages.size(), 2u);
  EXPECT_EQ(pages[0], (csm::PageKey{ 2, 0, 0 }));
  EXPECT_EQ(pages[1], (csm::PageKey{ 2, 1, 0 }));
  // A box standing in for a caster, over the image's left half at level 1's depths (fineness
  // 0.5, outside the band and margins of levels 0 and 2): every page its rectangle touches at
  // level 1 alone.
  csm::BoxStandIn standIn;
  standIn.rect = csm::ScreenRect{ -1.0, -1.0, 0.0, 1.0 };
  standIn.depths.min = standIn.depths.max =
    csm::windowDepthFromViewDepth(100.0 / std::exp2(0.5), vsNear, vsFar, false);
  ASSERT_TRUE(csm::markPages(levels, straightAcross(), vsNear, vsFar, depths.data(), width, height,
    { standIn }, 1000, pages));
  EXPECT_EQ(pagesOfLevel(pages, 1).size(), 2u * 3u); // 512 texels: 3 a side, 2 in the left half
  EXPECT_EQ(pages.size(), 6u);
}

// A view's window NDC goes to the base's map coordinates: a world point seen by the view lands
// where the base's clip space puts it, x and y taken to [0, 1].
TEST(Pages, WindowToBaseUndoesTheViewAndAppliesTheBase)
{
  const glm::dmat4 wsToView = glm::perspective(glm::radians(60.0), 4.0 / 3.0, 0.1, 100.0) *
    glm::lookAt(glm::dvec3(1.0, 2.0, 3.0), glm::dvec3(0.0), glm::dvec3(0.0, 1.0, 0.0));
  const glm::dmat4 wsToBase = baseClip(20.0);
  const glm::dmat4 windowToBase = csm::windowToBase(wsToBase, wsToView);
  for (const glm::dvec3 p : { glm::dvec3(0.0), glm::dvec3(0.5, -0.25, 1.0), glm::dvec3(-1, 0, -2) })
  {
    const glm::dvec4 view = wsToView * glm::dvec4(p, 1.0);
    const glm::dvec4 b = windowToBase * (view / view.w);
    const glm::dvec4 base = wsToBase * glm::dvec4(p, 1.0);
    EXPECT_NEAR(b.x / b.w, 0.5 * base.x / base.w + 0.5, 1e-12);
    EXPECT_NEAR(b.y / b.w, 0.5 * base.y / base.w + 0.5, 1e-12);
  }
}

// A box that stands in for a caster deep along the view marks, at each level, the pages of the
// part of it whose depths that level serves: every page a sample inside it would mark, and at
// the finest level only those of its near part.
TEST(Pages, AStandInMarksAtEachLevelThePagesOfItsPartAtThatLevelsDepths)
{
  csm::PageLevels levels;
  levels.baseTexels = glm::dvec2(256.0); // level 3: 2048 texels, 9 pages of 248 a side
  levels.baseDepth = 100.0;
  levels.count = 3;
  const double vsNear = 1.0, vsFar = 1000.0;
  auto windowAt = [&](double fineness)
  { return csm::windowDepthFromViewDepth(100.0 / std::exp2(fineness), vsNear, vsFar, false); };
  // Base x moves with the window depth (a light across the view): 5 (2 w - 1) - 4.1.
  glm::dmat4 across = straightAcross();
  across[2][0] = 5.0;
  across[3][0] = 0.5 - 4.6;
  csm::BoxStandIn standIn;
  standIn.rect = csm::ScreenRect{ -0.2, -0.2, 0.0, 0.0 };
  standIn.depths.min = windowAt(2.8);
  standIn.depths.max = windowAt(0.2);
  // Samples inside it, each column of its pixels at another depth from its nearest to its
  // farthest.
  const int width = 160, height = 120;
  std::vector<float> depths(width * height, 1.0f);
  for (int y = 0; y < height; ++y)
  {
    for (int x = 0; x < width; ++x)
    {
      const double sx = 2.0 * (x + 0.5) / width - 1.0, sy = 2.0 * (y + 0.5) / height - 1.0;
      if (sx >= -0.2 && sx <= 0.0 && sy >= -0.2 && sy <= 0.0)
      {
        const double t = (sx + 0.2) / 0.2;
        depths[y * width + x] =
          static_cast<float>(standIn.depths.min + t * (standIn.depths.max - standIn.depths.min));
      }
    }
  }
  std::vector<csm::PageKey> bySamples, byBox;
  ASSERT_TRUE(csm::markPages(
    levels, across, vsNear, vsFar, depths.data(), width, height, {}, 1000, bySamples));
  const std::vector<float> none(width * height, 1.0f);
  ASSERT_TRUE(csm::markPages(
    levels, across, vsNear, vsFar, none.data(), width, height, { standIn }, 1000, byBox));
  for (const csm::PageKey& page : bySamples)
  {
    EXPECT_TRUE(std::find(byBox.begin(), byBox.end(), page) != byBox.end())
      << page.level << " " << page.x << " " << page.y;
  }
  for (int k = 1; k <= 3; ++k)
  {
    EXPECT_FALSE(pagesOfLevel(byBox, k).empty()) << k;
  }
  // Level 3 serves its depths down to fineness 2 less the band and margin (window depth 0.9626,
  // base x 0.526 at most: 1079 texels with the margin, page 4); the whole box reaches 0.795 (page
  // 6).
  int farthest = 0;
  for (const csm::PageKey& page : pagesOfLevel(byBox, 3))
  {
    farthest = std::max(farthest, page.x);
  }
  EXPECT_EQ(farthest, 4);
  EXPECT_NEAR(windowAt(2.0 - csm::kPageBlendBand - csm::kPageLevelMargin), 0.9626, 1e-4);
}

// A box that stands in over the whole image at the finest of kMaxPageLevels levels of a 4096²
// base (2^24 texels a side: billions of pages) asks for more pages than the pool holds: refused
// at once, without listing them.
TEST(Pages, AStandInAtTheFinestLevelsIsRefusedWithoutListingItsPages)
{
  csm::PageLevels levels;
  levels.baseTexels = glm::dvec2(4096.0);
  levels.baseDepth = 1e6;
  levels.count = csm::kMaxPageLevels;
  const double vsNear = 1.0, vsFar = 2e6;
  csm::BoxStandIn standIn;
  standIn.rect = csm::ScreenRect{ -1.0, -1.0, 1.0, 1.0 };
  standIn.depths.min = 0.0;
  standIn.depths.max = csm::windowDepthFromViewDepth(vsFar, vsNear, vsFar, false);
  const std::vector<float> none(64 * 48, 1.0f);
  std::vector<csm::PageKey> pages(1);
  EXPECT_FALSE(csm::markPages(
    levels, straightAcross(), vsNear, vsFar, none.data(), 64, 48, { standIn }, 416, pages));
  EXPECT_TRUE(pages.empty());
}

TEST(Pages, TheCacheKeepsResidentPagesAndGivesTheLeastRecentlyNeededSlots)
{
  csm::PageCache cache;
  cache.reset(3);
  std::vector<std::pair<csm::PageKey, int>> drawn;
  const csm::PageKey a{ 1, 0, 0 }, b{ 1, 1, 0 }, c{ 2, 0, 0 }, d{ 2, 1, 0 };
  ASSERT_TRUE(cache.place({ a, b }, drawn));
  EXPECT_EQ(drawn.size(), 2u);
  ASSERT_TRUE(cache.place({ a, b }, drawn));
  EXPECT_EQ(drawn.size(), 0u); // kept
  ASSERT_TRUE(cache.place({ b }, drawn));
  ASSERT_TRUE(cache.place({ b, c }, drawn));
  ASSERT_EQ(drawn.size(), 1u); // the free slot
  EXPECT_EQ(cache.resident(), 3);
  const int slotOfA = cache.slotOf(a);
  ASSERT_TRUE(cache.place({ c, d }, drawn)); // a was needed longest ago: its slot goes
  ASSERT_EQ(drawn.size(), 1u);
  EXPECT_EQ(drawn[0].first, d);
  EXPECT_EQ(drawn[0].second, slotOfA);
  EXPECT_EQ(cache.slotOf(a), -1);
  EXPECT_GE(cache.slotOf(b), 0);
  // More pages than slots: refused, nothing changed.
  EXPECT_FALSE(cache.place({ a, b, c, d }, drawn));
  EXPECT_EQ(cache.slotOf(a), -1);
  EXPECT_EQ(cache.resident(), 3);
}

TEST(Pages, TheTableTagsEachEntryAndTheNeededPagesWinTheirEntries)
{
  csm::PageCache cache;
  cache.reset(4);
  std::vector<std::pair<csm::PageKey, int>> drawn;
  const int side = csm::kPageTableSide;
  const csm::PageKey a{ 1, 3, 2 }, b{ 2, 3 + side, 2 }, c{ 2, 3, 2 }; // b and c share an entry
  ASSERT_TRUE(cache.place({ a, b }, drawn));
  ASSERT_TRUE(cache.place({ a, c }, drawn));
  std::vector<float> entries;
  auto place = [](int slot) { return glm::ivec2(10 + slot, 20); };
  EXPECT_EQ(cache.table(2, { a, c }, place, entries), 0);
  ASSERT_EQ(entries.size(), static_cast<size_t>(side * side * 2 * 4));
  const float* ea = &entries[4 * (2 * side + 3)];
  EXPECT_EQ(ea[0], 10.0f + cache.slotOf(a));
  EXPECT_EQ(ea[1], 20.0f);
  EXPECT_EQ(ea[2], 3.0f);
  EXPECT_EQ(ea[3], 2.0f);
  const float* ec = &entries[4 * ((side + 2) * side + 3)];
  EXPECT_EQ(ec[2], 3.0f); // c, needed now, over b kept from before
  EXPECT_EQ(entries[4 * 0], -1.0f);
  // Both needed: one loses its entry.
  EXPECT_EQ(cache.table(2, { a, b, c }, place, entries), 1);
  // The level the lookup reads: c's where c's page sits, the base elsewhere.
  csm::PageLevels levels;
  levels.baseTexels = glm::dvec2(248.0); // a page a level-0 side
  levels.baseDepth = 100.0;
  levels.count = 2;
  EXPECT_EQ(cache.table(2, { a, c }, place, entries), 0);
  const double atC = (3.5 * 248.0) / (4.0 * 248.0), rowC = (2.5 * 248.0) / (4.0 * 248.0);
  EXPECT_EQ(csm::pageLevelRead(levels, entries, atC, rowC, 1.5), 2);
  EXPECT_EQ(csm::pageLevelRead(levels, entries, atC, rowC, 0.5), 0); // level 1's page there: none
  EXPECT_EQ(csm::pageLevelRead(levels, entries, atC, rowC, -1.0), 0);
  EXPECT_EQ(csm::pageLevelRead(levels, entries, 1.5, rowC, 1.5), 0);
}

TEST(Pages, ThePoolIsTheRestOfTheAtlas)
{
  // A 1024 base in a 4096 x 6144 atlas: 16 x 24 pages less the base's 4 x 4.
  const csm::MapSize atlas(4096, 6144);
  EXPECT_EQ(csm::poolSlots(atlas, 1024), 368);
  EXPECT_EQ(csm::poolSlots(atlas, 1000), 0);
  EXPECT_EQ(csm::poolSlots(atlas, 8192), 0);
  EXPECT_EQ(csm::poolSlots(csm::MapSize(0), 0), 0);
  EXPECT_EQ(csm::poolSlotPlace(atlas, 1024, 0), glm::ivec2(4, 0));
  EXPECT_EQ(csm::poolSlotPlace(atlas, 1024, 11), glm::ivec2(15, 0));
  EXPECT_EQ(csm::poolSlotPlace(atlas, 1024, 12), glm::ivec2(4, 1));
  EXPECT_EQ(csm::poolSlotPlace(atlas, 1024, 48), glm::ivec2(0, 4));
  EXPECT_EQ(csm::poolSlotPlace(atlas, 1024, 367), glm::ivec2(15, 23));
  // Every slot a place of its own, none in the base.
  std::vector<int> seen(16 * 24, 0);
  for (int slot = 0; slot < 368; ++slot)
  {
    const glm::ivec2 place = csm::poolSlotPlace(atlas, 1024, slot);
    EXPECT_FALSE(place.x < 4 && place.y < 4);
    ++seen[static_cast<size_t>(place.y * 16 + place.x)];
  }
  EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), 368);
}

TEST(Pages, PagesDrawnTogetherAreTheBlocksThatHoldThem)
{
  // Blocks of 4 x 4: level 3's pages in three blocks, level 4's row of 5 in two.
  const std::vector<csm::PageKey> pages = { { 3, 4, 7 }, { 3, 5, 7 }, { 3, 6, 7 }, { 3, 4, 8 },
    { 3, 5, 8 }, { 3, 6, 8 }, { 3, 9, 9 }, { 4, 0, 1 }, { 4, 1, 1 }, { 4, 2, 1 }, { 4, 3, 1 },
    { 4, 4, 1 } };
  const std::vector<csm::PageBatch> batches = csm::batchPages(pages, 4);
  ASSERT_EQ(batches.size(), 5u);
  std::vector<int> seen(pages.size(), 0);
  for (const csm::PageBatch& b : batches)
  {
    EXPECT_EQ(b.first % 4, glm::ivec2(0));
    EXPECT_EQ(b.last - b.first, glm::ivec2(3));
    for (const size_t i : b.pages)
    {
      ++seen[i];
      EXPECT_EQ(pages[i].level, b.level);
      EXPECT_TRUE(pages[i].x >= b.from.x && pages[i].x <= b.to.x);
      EXPECT_TRUE(pages[i].y >= b.from.y && pages[i].y <= b.to.y);
    }
    EXPECT_EQ(b.texels(), glm::ivec2(4 * csm::kPageInterior + 2 * csm::kPageBorder));
  }
  EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), static_cast<long>(pages.size()));
  // Level 3's block at (4, 4) holds the pages of row 7 (row 8 is the next block's).
  const csm::PageBatch& b = batches[0];
  EXPECT_EQ(b.level, 3);
  EXPECT_EQ(b.first, glm::ivec2(4, 4));
  EXPECT_EQ(b.from, glm::ivec2(4, 7));
  EXPECT_EQ(b.to, glm::ivec2(6, 7));
  const std::array<int, 4> drawn = { 0, 3 * csm::kPageInterior, 3 * csm::kPageInterior + 8,
    csm::kPageInterior + 8 };
  EXPECT_EQ(b.drawn(), drawn);
  // A batch's clip space is its pages' (page (5, 8) of the 3 x 2 block one page in, one up).
  csm::PageLevels levels;
  ASSERT_TRUE(csm::pageLevels(baseClip(100.0), csm::MapSize(2048), kPixel, 0.7, 1.0, levels));
  const glm::dmat4 base = baseClip(100.0);
  const glm::dmat4 together = csm::pagesClip(base, levels, 3, { 4, 7 }, { 6, 8 });
  const glm::dmat4 alone = csm::pageClip(base, levels, { 3, 5, 8 });
  const glm::dvec4 world = glm::inverse(alone) * glm::dvec4(0.3, -0.2, 0.1, 1.0);
  const glm::dvec4 inBatch = together * world;
  const glm::dvec2 texelInBatch = (glm::dvec2(inBatch) + 1.0) * 0.5 *
    glm::dvec2(3 * csm::kPageInterior + 8, 2 * csm::kPageInterior + 8);
  const glm::dvec2 texelAlone = (glm::dvec2(0.3, -0.2) + 1.0) * 0.5 * double(csm::kPageTexels);
  EXPECT_NEAR(texelInBatch.x, texelAlone.x + csm::kPageInterior, 1e-6);
  EXPECT_NEAR(texelInBatch.y, texelAlone.y + csm::kPageInterior, 1e-6);
  EXPECT_NEAR(inBatch.z, 0.1, 1e-12);
}
