// SPDX-License-Identifier: BSD-3-Clause
// A big caster mesh as compact spatial blocks, so that each cascade's map draws only the blocks
// whose boxes reach its light volume, and draws them from positions alone. Pure math, no VTK, no
// GL.
//
// A shadow map needs a caster's depth only: its normals, colours and texture coordinates are
// dead weight in the map's vertex stage, and the points a mesh splits for its normals (a box has
// 24 points for 8 corners) are the same corner drawn several times. The blocks weld them
// (csm::weldPositions) and keep only the triangles. One mesh spanning the whole scene (a platform's
// steel as one actor) reaches every cascade as a whole; split by a k-d tree over its triangles'
// centroids, each block reaches only the cascades around it.
#pragma once

#include <glm/glm.hpp>

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace csm
{

struct CasterBlock
{
  /// The block's corners: for each, the index of one input position (welded positions appear once).
  std::vector<std::size_t> points;
  /// The block's triangles, as indices into points, wound as the input's.
  std::vector<std::array<std::uint32_t, 3>> triangles;
  /// The box of the block's corners.
  glm::dvec3 lower{ 0.0 }, upper{ 0.0 };
};

/// Split a triangle mesh into blocks of at most maxTriangles triangles (at least 1), halving the
/// triangles at the median centroid along the longest side of their centroids' box until each part
/// fits; within a block the triangles keep the input's order, and corners are numbered in the
/// order the triangles first use them. Every triangle with three distinct (welded) corners lands in
/// exactly one block; degenerate ones are dropped (they cover no texel). Empty result when there is
/// no such triangle, a position is not finite, or an index is out of range: the caller then draws
/// the mesh as it is.
std::vector<CasterBlock> splitIntoBlocks(const std::vector<glm::dvec3>& positions,
  const std::vector<std::array<std::int64_t, 3>>& triangles, std::size_t maxTriangles);

/// The triangles of a big caster grouped into compact spatial blocks without copying the mesh:
/// `order` lists triangle indices block after block (each block in the input's order), and
/// blocks[b] is the b-th block's first position in `order` and its count. The same median
/// splits as splitIntoBlocks, over the triangles' centroids (one per triangle; a centroid that
/// is not finite puts its triangle in no block: the caller then draws the mesh as it is).
struct BlockOrder
{
  std::vector<std::uint32_t> order;
  std::vector<std::pair<std::size_t, std::size_t>> blocks;
};
/// stop: once set (by another thread), the work ends early with no blocks.
BlockOrder orderIntoBlocks(const std::vector<glm::vec3>& centroids, std::size_t maxTriangles,
  const std::atomic<bool>* stop = nullptr);

} // namespace csm
