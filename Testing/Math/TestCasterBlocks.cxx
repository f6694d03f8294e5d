// SPDX-License-Identifier: BSD-3-Clause
// Caster blocks: a big mesh as compact spatial blocks for the shadow maps.
#include "csmCasterBlocks.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <map>
#include <set>

namespace
{
using Triangles = std::vector<std::array<std::int64_t, 3>>;

/// A row of n unit quads (two triangles each) along x, one unit apart, every quad with its own
/// four points, each point stored twice (as a mesh split for normals stores corners).
void quadRow(int n, std::vector<glm::dvec3>& p, Triangles& t)
{
  for (int i = 0; i < n; ++i)
  {
    const double x = 2.0 * i;
    const glm::dvec3 c[4] = { { x, 0, 0 }, { x + 1, 0, 0 }, { x + 1, 1, 0 }, { x, 1, 0 } };
    const std::int64_t base = static_cast<std::int64_t>(p.size());
    for (const auto& q : c)
    {
      p.push_back(q);
    }
    for (const auto& q : c)
    {
      p.push_back(q); // the duplicate
    }
    t.push_back({ base + 0, base + 1, base + 2 });
    t.push_back({ base + 4, base + 6, base + 7 }); // the second triangle uses the duplicates
  }
}

/// A triangle as its three corner positions, for comparing meshes by geometry.
using Corners = std::array<double, 9>;
Corners corners(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c)
{
  return { a.x, a.y, a.z, b.x, b.y, b.z, c.x, c.y, c.z };
}
}

TEST(CasterBlocks, EveryTriangleLandsInExactlyOneBlockWithItsCornersWelded)
{
  std::vector<glm::dvec3> p;
  Triangles t;
  quadRow(100, p, t);
  const auto blocks = csm::splitIntoBlocks(p, t, 16);
  // 200 triangles, at most 16 a block, halved at medians: 200 -> 100 -> 50 -> 25 -> 13/12: 16.
  ASSERT_EQ(blocks.size(), 16u);
  std::multiset<Corners> input, output;
  for (const auto& tri : t)
  {
    input.insert(corners(p[tri[0]], p[tri[1]], p[tri[2]]));
  }
  size_t points = 0;
  for (const auto& b : blocks)
  {
    EXPECT_LE(b.triangles.size(), 16u);
    EXPECT_GE(b.triangles.size(), 12u);
    points += b.points.size();
    // Welded: no position twice in a block.
    std::set<std::array<double, 3>> distinct;
    for (size_t q : b.points)
    {
      distinct.insert({ p[q].x, p[q].y, p[q].z });
    }
    EXPECT_EQ(distinct.size(), b.points.size());
    for (const auto& tri : b.triangles)
    {
      output.insert(corners(p[b.points[tri[0]]], p[b.points[tri[1]]], p[b.points[tri[2]]]));
    }
  }
  EXPECT_EQ(input, output); // same triangles, same winding
  // 4 corners a quad, not the input's 8; a quad cut by a block boundary (at most one per
  // boundary, 15 boundaries) counts its two shared corners twice.
  EXPECT_GE(points, 400u);
  EXPECT_LE(points, 430u);
}

TEST(CasterBlocks, BlocksOfSeparatedPartsDoNotOverlap)
{
  std::vector<glm::dvec3> p;
  Triangles t;
  quadRow(64, p, t);
  const auto blocks = csm::splitIntoBlocks(p, t, 8); // 4 quads a block
  ASSERT_EQ(blocks.size(), 16u);
  std::vector<std::pair<double, double>> spans;
  for (const auto& b : blocks)
  {
    EXPECT_DOUBLE_EQ(b.upper.x - b.lower.x, 7.0); // four quads side by side: 0..7
    EXPECT_DOUBLE_EQ(b.lower.y, 0.0);
    EXPECT_DOUBLE_EQ(b.upper.y, 1.0);
    spans.emplace_back(b.lower.x, b.upper.x);
  }
  std::sort(spans.begin(), spans.end());
  for (size_t i = 1; i < spans.size(); ++i)
  {
    EXPECT_LT(spans[i - 1].second, spans[i].first);
  }
}

TEST(CasterBlocks, SmallMeshIsOneBlockAndDegenerateTrianglesAreDropped)
{
  std::vector<glm::dvec3> p = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 1, 0, 0 } };
  Triangles t = { { 0, 1, 2 }, { 0, 1, 3 }, { 2, 2, 0 } }; // the last two have no area
  const auto blocks = csm::splitIntoBlocks(p, t, 1000);
  ASSERT_EQ(blocks.size(), 1u);
  EXPECT_EQ(blocks[0].triangles.size(), 1u);
  EXPECT_EQ(blocks[0].points.size(), 3u);
  EXPECT_EQ(blocks[0].lower, glm::dvec3(0.0));
  EXPECT_EQ(blocks[0].upper, glm::dvec3(1.0, 1.0, 0.0));
}

TEST(CasterBlocks, CoincidentCentroidsStillSplit)
{
  // 50 identical triangles: the median split must still terminate and bound the block size.
  std::vector<glm::dvec3> p = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 } };
  Triangles t(50, { 0, 1, 2 });
  const auto blocks = csm::splitIntoBlocks(p, t, 7);
  size_t total = 0;
  for (const auto& b : blocks)
  {
    EXPECT_LE(b.triangles.size(), 7u);
    total += b.triangles.size();
  }
  EXPECT_EQ(total, 50u);
}

TEST(CasterBlocks, BadInputGivesNoBlocks)
{
  std::vector<glm::dvec3> p = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 } };
  EXPECT_TRUE(csm::splitIntoBlocks(p, { { 0, 1, 3 } }, 10).empty()); // index out of range
  EXPECT_TRUE(csm::splitIntoBlocks(p, { { -1, 1, 2 } }, 10).empty());
  EXPECT_TRUE(csm::splitIntoBlocks({}, {}, 10).empty());
  EXPECT_TRUE(csm::splitIntoBlocks(p, {}, 10).empty());
  EXPECT_EQ(csm::splitIntoBlocks(p, { { 0, 1, 2 } }, 0).size(), 1u); // 0 means 1
  p[1].y = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(csm::splitIntoBlocks(p, { { 0, 1, 2 } }, 10).empty());
}

TEST(CasterBlocks, TrianglesKeepTheInputOrderWithinABlock)
{
  std::vector<glm::dvec3> p;
  Triangles t;
  quadRow(40, p, t); // 80 triangles, left to right
  // Reverse them: the median splits must not reorder a block's triangles.
  std::reverse(t.begin(), t.end());
  for (const size_t most : { size_t(1000), size_t(10) })
  {
    const auto blocks = csm::splitIntoBlocks(p, t, most);
    for (const auto& b : blocks)
    {
      for (size_t i = 1; i < b.triangles.size(); ++i)
      {
        // Input order is right to left: each triangle's first corner is no further right.
        EXPECT_LE(p[b.points[b.triangles[i][0]]].x, p[b.points[b.triangles[i - 1][0]]].x);
      }
      // Corners numbered in first use: the first triangle uses 0, 1, 2.
      EXPECT_EQ(b.triangles[0], (std::array<std::uint32_t, 3>{ 0, 1, 2 }));
    }
  }
}

// Stopped (another thread set the flag): no blocks; not stopped, the same blocks as without.
TEST(CasterBlocks, StoppedOrderingGivesNoBlocks)
{
  std::vector<glm::vec3> centroids;
  for (int i = 0; i < 1000; ++i)
  {
    centroids.emplace_back(static_cast<float>(i % 37), static_cast<float>(i / 37), 0.0f);
  }
  std::atomic<bool> stop(false);
  const csm::BlockOrder free = csm::orderIntoBlocks(centroids, 100);
  const csm::BlockOrder going = csm::orderIntoBlocks(centroids, 100, &stop);
  EXPECT_GT(free.blocks.size(), 1u);
  EXPECT_EQ(going.blocks, free.blocks);
  EXPECT_EQ(going.order, free.order);
  stop = true;
  const csm::BlockOrder stopped = csm::orderIntoBlocks(centroids, 100, &stop);
  EXPECT_TRUE(stopped.blocks.empty());
}
