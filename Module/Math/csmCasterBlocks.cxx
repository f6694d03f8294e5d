// SPDX-License-Identifier: BSD-3-Clause
#include "csmCasterBlocks.h"

#include "csmClosedSurface.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace csm
{

namespace
{
template <typename Vector>
struct Splitter
{
  const std::vector<Vector>& Centroids;
  std::size_t MaxTriangles;
  std::vector<std::pair<std::size_t, std::size_t>> Leaves; // ranges of the order
  const std::atomic<bool>* Stop = nullptr;                 // set: end early, no leaves

  // Median splits of order[begin, end) until every range fits (explicit stack: no recursion depth
  // to worry about on a degenerate distribution).
  void Split(std::vector<std::uint32_t>& order)
  {
    std::vector<std::pair<std::size_t, std::size_t>> todo{ { 0, order.size() } };
    while (!todo.empty())
    {
      if (this->Stop && this->Stop->load(std::memory_order_relaxed))
      {
        this->Leaves.clear();
        return;
      }
      const auto [begin, end] = todo.back();
      todo.pop_back();
      if (end - begin <= this->MaxTriangles)
      {
        this->Leaves.emplace_back(begin, end);
        continue;
      }
      Vector lo(std::numeric_limits<typename Vector::value_type>::max());
      Vector hi(-std::numeric_limits<typename Vector::value_type>::max());
      for (std::size_t i = begin; i < end; ++i)
      {
        lo = glm::min(lo, this->Centroids[order[i]]);
        hi = glm::max(hi, this->Centroids[order[i]]);
      }
      const Vector extent = hi - lo;
      const int axis =
        extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
      const std::size_t middle = begin + (end - begin) / 2;
      std::nth_element(order.begin() + static_cast<std::ptrdiff_t>(begin),
        order.begin() + static_cast<std::ptrdiff_t>(middle),
        order.begin() + static_cast<std::ptrdiff_t>(end),
        [this, axis](std::uint32_t a, std::uint32_t b)
        { return this->Centroids[a][axis] < this->Centroids[b][axis]; });
      // Left first out of the stack: blocks come out in the tree's order.
      todo.emplace_back(middle, end);
      todo.emplace_back(begin, middle);
    }
  }
};
} // namespace

std::vector<CasterBlock> splitIntoBlocks(const std::vector<glm::dvec3>& positions,
  const std::vector<std::array<std::int64_t, 3>>& triangles, std::size_t maxTriangles)
{
  std::vector<std::uint32_t> ids;
  if (positions.empty() || !weldPositions(positions, ids) ||
    triangles.size() > std::numeric_limits<std::uint32_t>::max())
  {
    return {};
  }
  // One input index per welded id (the first), the kept triangles in welded ids, their centroids.
  const std::uint32_t distinct = ids.empty() ? 0u : *std::max_element(ids.begin(), ids.end()) + 1u;
  std::vector<std::size_t> representative(distinct, positions.size());
  for (std::size_t i = positions.size(); i-- > 0;)
  {
    representative[ids[i]] = i;
  }
  std::vector<std::array<std::uint32_t, 3>> kept;
  std::vector<glm::dvec3> centroids;
  kept.reserve(triangles.size());
  centroids.reserve(triangles.size());
  for (const auto& t : triangles)
  {
    std::array<std::uint32_t, 3> v{};
    for (int k = 0; k < 3; ++k)
    {
      if (t[k] < 0 || static_cast<std::uint64_t>(t[k]) >= positions.size())
      {
        return {};
      }
      v[k] = ids[static_cast<std::size_t>(t[k])];
    }
    if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0])
    {
      continue;
    }
    kept.push_back(v);
    centroids.push_back(
      (positions[static_cast<std::size_t>(t[0])] + positions[static_cast<std::size_t>(t[1])] +
        positions[static_cast<std::size_t>(t[2])]) /
      3.0);
  }
  if (kept.empty())
  {
    return {};
  }
  std::vector<std::uint32_t> order(kept.size());
  std::iota(order.begin(), order.end(), 0u);
  Splitter<glm::dvec3> splitter{ centroids, std::max<std::size_t>(maxTriangles, 1), {} };
  splitter.Split(order);

  std::vector<CasterBlock> blocks;
  blocks.reserve(splitter.Leaves.size());
  std::vector<std::uint32_t> local(distinct, std::numeric_limits<std::uint32_t>::max());
  for (const auto& [begin, end] : splitter.Leaves)
  {
    // The input's order within a block: neighbouring triangles share corners, which a vertex
    // cache reuses (the median splits shuffle them).
    std::sort(order.begin() + static_cast<std::ptrdiff_t>(begin),
      order.begin() + static_cast<std::ptrdiff_t>(end));
    CasterBlock block;
    block.triangles.reserve(end - begin);
    for (std::size_t i = begin; i < end; ++i)
    {
      std::array<std::uint32_t, 3> corner{};
      for (int k = 0; k < 3; ++k)
      {
        const std::uint32_t id = kept[order[i]][k];
        if (local[id] == std::numeric_limits<std::uint32_t>::max())
        {
          local[id] = static_cast<std::uint32_t>(block.points.size());
          block.points.push_back(representative[id]);
        }
        corner[k] = local[id];
      }
      block.triangles.push_back(corner);
    }
    block.lower = block.upper = positions[block.points.front()];
    for (const std::size_t p : block.points)
    {
      block.lower = glm::min(block.lower, positions[p]);
      block.upper = glm::max(block.upper, positions[p]);
      local[ids[p]] = std::numeric_limits<std::uint32_t>::max(); // ready for the next block
    }
    blocks.push_back(std::move(block));
  }
  return blocks;
}

BlockOrder orderIntoBlocks(
  const std::vector<glm::vec3>& centroids, std::size_t maxTriangles, const std::atomic<bool>* stop)
{
  BlockOrder result;
  if (centroids.empty() || centroids.size() > std::numeric_limits<std::uint32_t>::max())
  {
    return result;
  }
  for (const glm::vec3& c : centroids)
  {
    if (!std::isfinite(c.x) || !std::isfinite(c.y) || !std::isfinite(c.z))
    {
      return result;
    }
  }
  result.order.resize(centroids.size());
  std::iota(result.order.begin(), result.order.end(), 0u);
  Splitter<glm::vec3> splitter{ centroids, std::max<std::size_t>(maxTriangles, 1), {}, stop };
  splitter.Split(result.order);
  if (splitter.Leaves.empty())
  {
    return BlockOrder(); // stopped
  }
  result.blocks.reserve(splitter.Leaves.size());
  for (const auto& [begin, end] : splitter.Leaves)
  {
    // The input's order within a block: neighbouring triangles share corners, which a vertex
    // cache reuses (the median splits shuffle them).
    std::sort(result.order.begin() + static_cast<std::ptrdiff_t>(begin),
      result.order.begin() + static_cast<std::ptrdiff_t>(end));
    result.blocks.emplace_back(begin, end - begin);
  }
  return result;
}

} // namespace csm
