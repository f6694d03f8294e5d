// SPDX-License-Identifier: BSD-3-Clause
#include "csmClosedSurface.h"

#include "csmDigest.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>

namespace csm
{

bool weldPositions(const std::vector<glm::dvec3>& positions, std::vector<std::uint32_t>& ids)
{
  constexpr std::uint32_t kEmpty = std::numeric_limits<std::uint32_t>::max();
  const size_t n = positions.size();
  if (n >= kEmpty)
  {
    return false;
  }
  size_t capacity = 1;
  while (capacity < 2 * n)
  {
    capacity <<= 1;
  }
  std::vector<std::uint32_t> slots(capacity, kEmpty); // the first point of each position
  ids.assign(n, 0u);
  std::uint32_t next = 0;
  for (size_t i = 0; i < n; ++i)
  {
    const glm::dvec3 q = positions[i] + glm::dvec3(0.0); // -0 becomes +0
    if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z))
    {
      return false;
    }
    std::uint64_t bits[3];
    std::memcpy(bits, &q[0], sizeof(double));
    std::memcpy(bits + 1, &q[1], sizeof(double));
    std::memcpy(bits + 2, &q[2], sizeof(double));
    std::uint64_t h = bits[0] * 0x9e3779b97f4a7c15ull;
    h = (h ^ (h >> 29) ^ bits[1]) * 0xbf58476d1ce4e5b9ull;
    h = (h ^ (h >> 31) ^ bits[2]) * 0x94d049bb133111ebull;
    size_t slot = static_cast<size_t>(h ^ (h >> 32)) & (capacity - 1);
    while (slots[slot] != kEmpty && positions[slots[slot]] + glm::dvec3(0.0) != q)
    {
      slot = (slot + 1) & (capacity - 1);
    }
    if (slots[slot] == kEmpty)
    {
      slots[slot] = static_cast<std::uint32_t>(i);
      ids[i] = next++;
    }
    else
    {
      ids[i] = ids[slots[slot]];
    }
  }
  return true;
}

namespace
{
/// Sorts keys in place, least significant 16 bits first (what std::sort gives, in linear time).
void radixSort(std::vector<std::uint64_t>& keys)
{
  std::vector<std::uint64_t> spare(keys.size());
  std::vector<size_t> count(size_t(1) << 16);
  for (int shift = 0; shift < 64; shift += 16)
  {
    std::fill(count.begin(), count.end(), size_t(0));
    for (const std::uint64_t key : keys)
    {
      ++count[(key >> shift) & 0xffff];
    }
    if (count[keys.empty() ? 0 : (keys.front() >> shift) & 0xffff] == keys.size())
    {
      continue; // every key has this digit
    }
    size_t sum = 0;
    for (size_t& c : count)
    {
      const size_t here = c;
      c = sum;
      sum += here;
    }
    for (const std::uint64_t key : keys)
    {
      spare[count[(key >> shift) & 0xffff]++] = key;
    }
    keys.swap(spare);
  }
}

/// Size of the mesh: the diagonal of the box around the positions its triangles use.
double meshSize(const std::vector<glm::dvec3>& positions,
  const std::vector<std::array<std::int64_t, 3>>& triangles)
{
  glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-lo);
  for (const auto& t : triangles)
  {
    for (const std::int64_t i : t)
    {
      lo = glm::min(lo, positions[static_cast<size_t>(i)]);
      hi = glm::max(hi, positions[static_cast<size_t>(i)]);
    }
  }
  return glm::length(hi - lo);
}

/// The unit normal of the triangle with the largest area (counter-clockwise), and one of its
/// corners; false when every triangle is degenerate.
bool largestTriangle(const std::vector<glm::dvec3>& positions,
  const std::vector<std::array<std::int64_t, 3>>& triangles, glm::dvec3& normal, glm::dvec3& corner)
{
  double largest = 0.0;
  for (const auto& t : triangles)
  {
    const glm::dvec3& a = positions[static_cast<size_t>(t[0])];
    const glm::dvec3 n = glm::cross(
      positions[static_cast<size_t>(t[1])] - a, positions[static_cast<size_t>(t[2])] - a);
    const double area = glm::length(n);
    if (area > largest)
    {
      largest = area;
      normal = n / area;
      corner = a;
    }
  }
  return largest > 0.0;
}

/// Sets result.planar (tolerance: kShapeTolerance of the mesh's size).
void classifyShape(const std::vector<glm::dvec3>& positions,
  const std::vector<std::array<std::int64_t, 3>>& triangles, double tolerance,
  SurfaceClosure& result)
{
  glm::dvec3 normal, corner;
  if (!largestTriangle(positions, triangles, normal, corner))
  {
    return;
  }
  result.planar = std::all_of(triangles.begin(), triangles.end(),
    [&](const auto& t)
    {
      return std::all_of(t.begin(), t.end(),
        [&](std::int64_t i) {
          return std::abs(glm::dot(positions[static_cast<size_t>(i)] - corner, normal)) <=
            tolerance;
        });
    });
}

/// Does every (welded) vertex lie on the inner side of every triangle's plane? outward: +1 when
/// counter-clockwise triangles face outward, -1 when inward (tolerance as classifyShape's).
bool isConvex(const std::vector<glm::dvec3>& positions,
  const std::vector<std::array<std::int64_t, 3>>& triangles, const std::vector<std::uint32_t>& ids,
  double outward, double tolerance)
{
  // One position per welded vertex.
  std::vector<glm::dvec3> vertices;
  std::vector<char> seen(positions.size(), 0);
  for (const auto& t : triangles)
  {
    for (const std::int64_t i : t)
    {
      const std::uint32_t id = ids[static_cast<size_t>(i)];
      if (!seen[id])
      {
        seen[id] = 1;
        vertices.push_back(positions[static_cast<size_t>(i)]);
      }
    }
  }
  if (double(vertices.size()) * double(triangles.size()) > kMaximumConvexityWork)
  {
    return false;
  }
  for (const auto& t : triangles)
  {
    const glm::dvec3& a = positions[static_cast<size_t>(t[0])];
    const glm::dvec3 n = glm::cross(
      positions[static_cast<size_t>(t[1])] - a, positions[static_cast<size_t>(t[2])] - a);
    const double area = glm::length(n);
    if (!(area > 0.0))
    {
      continue; // degenerate: no plane
    }
    const glm::dvec3 out = outward * n / area;
    for (const glm::dvec3& v : vertices)
    {
      if (glm::dot(v - a, out) > tolerance)
      {
        return false;
      }
    }
  }
  return true;
}

/// The welded edges of a mesh: a -> b with a < b in forward, those with a > b (stored as b -> a)
/// in backward (the boundary is empty exactly when the two are equal as multisets), and its
/// enclosed signed volume over the triangles counted (those of three distinct welded corners).
struct WeldedEdges
{
  std::vector<std::uint64_t> forward, backward;
  std::vector<std::uint64_t> faces; ///< per triangle, its welded corners as a set (hashed)
  double volume = 0.0, area = 0.0;
  size_t counted = 0;
  /// Per welded vertex: the volume and area of the triangles whose first corner it is, and
  /// (listing the edges) its parent in the union of the vertices the triangles join.
  std::vector<double> vertexVolume, vertexArea;
  std::vector<std::uint32_t> parent;
};

std::uint32_t rootOf(std::vector<std::uint32_t>& parent, std::uint32_t v)
{
  while (parent[v] != v)
  {
    parent[v] = parent[parent[v]]; // (path halving)
    v = parent[v];
  }
  return v;
}

void join(std::vector<std::uint32_t>& parent, std::uint32_t a, std::uint32_t b)
{
  a = rootOf(parent, a);
  b = rootOf(parent, b);
  parent[std::max(a, b)] = std::min(a, b);
}

/// Does every connected part of a closed mesh bound a solid: its volume over half its area above
/// the tolerance (a sheet drawn as both its sides, triangulated either way, encloses none beside
/// a solid), wound as the whole mesh is or inside a part that is (a cavity; a part wound inside
/// out elsewhere would be drawn from its lit side)? component: per welded vertex, the least
/// vertex of its part.
bool everyPartBoundsASolid(const std::vector<glm::dvec3>& positions,
  const std::vector<std::uint32_t>& ids, const WeldedEdges& edges,
  const std::vector<std::uint32_t>& component, double tolerance)
{
  std::vector<double> volume(component.size(), 0.0), area(component.size(), 0.0);
  for (size_t v = 0; v < component.size(); ++v)
  {
    volume[component[v]] += edges.vertexVolume[v];
    area[component[v]] += edges.vertexArea[v];
  }
  std::vector<size_t> parts, turned; // (each part by its root), those wound against the whole
  for (size_t c = 0; c < component.size(); ++c)
  {
    if (!(area[c] > 0.0))
    {
      continue;
    }
    if (!(std::abs(volume[c]) > 0.5 * area[c] * tolerance))
    {
      return false;
    }
    parts.push_back(c);
    if ((volume[c] > 0.0) != (edges.volume > 0.0))
    {
      turned.push_back(c);
    }
  }
  if (turned.empty())
  {
    return true;
  }
  if (static_cast<double>(turned.size()) * static_cast<double>(parts.size()) > kMaximumNestingWork)
  {
    return false; // (too many to place: the safe answer)
  }
  std::vector<glm::dvec3> lower(component.size(), glm::dvec3(HUGE_VAL)),
    upper(component.size(), glm::dvec3(-HUGE_VAL));
  for (size_t i = 0; i < positions.size(); ++i)
  {
    const std::uint32_t c = component[ids[i]];
    lower[c] = glm::min(lower[c], positions[i]);
    upper[c] = glm::max(upper[c], positions[i]);
  }
  for (const size_t c : turned)
  {
    const bool inside = std::any_of(parts.begin(), parts.end(),
      [&](size_t d)
      {
        return (volume[d] > 0.0) == (edges.volume > 0.0) &&
          glm::all(glm::lessThan(lower[d], lower[c])) &&
          glm::all(glm::lessThan(upper[c], upper[d]));
      });
    if (!inside)
    {
      return false;
    }
  }
  return true;
}

/// Walks the triangles: checks their indices, counts the non-degenerate ones and sums their
/// volume, and with listEdges lists their welded edges; false for an index out of range or when
/// stopped.
template <typename Stopped>
bool walkTriangles(const std::vector<glm::dvec3>& positions,
  const std::vector<std::array<std::int64_t, 3>>& triangles, const std::vector<std::uint32_t>& ids,
  bool listEdges, const Stopped& stopped, WeldedEdges& edges)
{
  const size_t vertices = ids.empty() ? 0 : *std::max_element(ids.begin(), ids.end()) + size_t(1);
  edges.vertexVolume.assign(vertices, 0.0);
  edges.vertexArea.assign(vertices, 0.0);
  if (listEdges)
  {
    edges.forward.reserve(3 * triangles.size() / 2 + 1);
    edges.backward.reserve(3 * triangles.size() / 2 + 1);
    edges.parent.resize(vertices);
    for (size_t v = 0; v < vertices; ++v)
    {
      edges.parent[v] = static_cast<std::uint32_t>(v);
    }
  }
  // (Volumes relative to a point of the mesh: no cancellation far from the world's origin.)
  const glm::dvec3 origin = positions[0];
  for (const auto& t : triangles)
  {
    if ((edges.counted & 0xffff) == 0 && stopped())
    {
      return false;
    }
    std::uint32_t v[3];
    for (int k = 0; k < 3; ++k)
    {
      if (t[k] < 0 || static_cast<std::uint64_t>(t[k]) >= positions.size())
      {
        return false;
      }
      v[k] = ids[static_cast<size_t>(t[k])];
    }
    if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0])
    {
      continue; // degenerate: no area, no boundary
    }
    ++edges.counted;
    for (int k = 0; listEdges && k < 3; ++k)
    {
      const std::uint32_t a = v[k], b = v[(k + 1) % 3];
      (a < b ? edges.forward : edges.backward)
        .push_back((std::uint64_t(std::min(a, b)) << 32) | std::uint64_t(std::max(a, b)));
    }
    if (listEdges)
    {
      join(edges.parent, v[0], v[1]);
      join(edges.parent, v[1], v[2]);
    }
    const glm::dvec3 a = positions[static_cast<size_t>(t[0])] - origin;
    const glm::dvec3 b = positions[static_cast<size_t>(t[1])] - origin;
    const glm::dvec3 c = positions[static_cast<size_t>(t[2])] - origin;
    const double volume = glm::dot(a, glm::cross(b, c)) / 6.0;
    const double area = 0.5 * glm::length(glm::cross(b - a, c - a));
    edges.volume += volume;
    edges.area += area;
    edges.vertexVolume[v[0]] += volume;
    edges.vertexArea[v[0]] += area;
    if (listEdges)
    {
      std::sort(v, v + 3);
      edges.faces.push_back((std::uint64_t(v[0]) * 0x9E3779B97F4A7C15ull) ^
        ((std::uint64_t(v[1]) * 0xC2B2AE3D27D4EB4Full) >> 1) ^
        ((std::uint64_t(v[2]) * 0x165667B19E3779F9ull) >> 2));
    }
  }
  return true;
}
} // namespace

int closedFaceTowardViewer(int closure, double worldToClipDeterminant)
{
  return std::isfinite(worldToClipDeterminant) ? closure * (worldToClipDeterminant < 0.0 ? 1 : -1)
                                               : 0;
}

SurfaceClosure classifySurface(const std::vector<glm::dvec3>& positions,
  const std::vector<std::array<std::int64_t, 3>>& triangles, const std::atomic<bool>* stop,
  SurfaceTopology* topology)
{
  SurfaceClosure result;
  auto stopped = [stop]() { return stop && stop->load(std::memory_order_relaxed); };
  std::vector<std::uint32_t> ids;
  const bool known = topology && topology->known;
  if (topology)
  {
    topology->known = false; // (until this classification is finished)
  }
  if (positions.empty() || positions.size() > 0xffffffffu || !weldPositions(positions, ids) ||
    stopped())
  {
    return result;
  }
  std::uint64_t digest = 0; // (of the triangles' indices: which triangles, in order)
  if (topology)
  {
    digestBytes(triangles.data(), triangles.size() * sizeof(triangles[0]), digest);
  }
  const bool sameEdges = known && topology->triangleDigest == digest && topology->ids == ids;
  WeldedEdges edges;
  if (!walkTriangles(positions, triangles, ids, !sameEdges, stopped, edges) || stopped())
  {
    return SurfaceClosure();
  }
  if (edges.counted == 0)
  {
    return result;
  }
  const double tolerance = kShapeTolerance * meshSize(positions, triangles);
  classifyShape(positions, triangles, tolerance, result);
  if (stopped())
  {
    return SurfaceClosure();
  }
  bool closed = sameEdges && topology->closed;
  if (!sameEdges && edges.forward.size() == edges.backward.size())
  {
    radixSort(edges.forward);
    radixSort(edges.backward);
    if (stopped())
    {
      return SurfaceClosure();
    }
    closed = edges.forward == edges.backward;
    if (closed)
    {
      // Two triangles on the same three corners (a sheet drawn as both its sides inside an
      // otherwise closed mesh: a wall, a fin): no solid there (a digest's coincidence, as rare,
      // only draws the mesh with both sides).
      radixSort(edges.faces);
      closed = std::adjacent_find(edges.faces.begin(), edges.faces.end()) == edges.faces.end();
    }
  }
  // Balanced edges around no thickness (two coincident sheets facing apart: a wall drawn as both
  // its sides, alone or as a part of the mesh) bound no solid: the mean thickness, volume over
  // half the area, within the shape tolerance, of the whole and of each connected part.
  std::vector<std::uint32_t> component;
  if (sameEdges)
  {
    component = std::move(topology->components);
  }
  else if (closed)
  {
    component.resize(edges.parent.size());
    for (size_t v = 0; v < component.size(); ++v)
    {
      component[v] = rootOf(edges.parent, static_cast<std::uint32_t>(v));
    }
  }
  result.closed = closed && std::abs(edges.volume) > 0.5 * edges.area * tolerance &&
    component.size() == edges.vertexVolume.size() &&
    everyPartBoundsASolid(positions, ids, edges, component, tolerance);
  result.volume = result.closed ? edges.volume : 0.0;
  if (result.closed && result.volume != 0.0 && !result.planar)
  {
    result.convex =
      isConvex(positions, triangles, ids, result.volume > 0.0 ? 1.0 : -1.0, tolerance);
  }
  if (topology)
  {
    topology->ids = std::move(ids);
    topology->triangleDigest = digest;
    topology->closed = closed;
    topology->components = std::move(component);
    topology->known = true;
  }
  return result;
}

} // namespace csm
