// SPDX-License-Identifier: BSD-3-Clause
// Whether a triangle mesh bounds solids, so that a shadow map may hold only its faces turned away
// from the light. Pure math, no VTK, no GL.
//
// A ray that enters a closed surface leaves it again. If every edge of a mesh (its vertices welded
// by position) is traversed as often in one direction as in the other (the oriented boundary of the
// mesh is empty), then along any ray the faces the ray crosses toward the light and away from it
// alternate in number, and a ray that crosses a face turned toward the light also crosses one
// turned away. A map of only the faces turned away from the light (the exit layer; Wang & Molnar's
// second-depth shadow maps) therefore shadows exactly the points the whole mesh shadows, with half
// the fragments, and the lit side's own depth no longer competes with it (no acne on lit faces).
// Open meshes (a sheet, a tube without caps, a mesh with one flipped triangle) fail the test and
// are drawn with both sides.
#pragma once

#include <glm/glm.hpp>

#include <array>
#include <atomic>
#include <cstdint>
#include <vector>

namespace csm
{

struct SurfaceClosure
{
  /// Every edge is traversed as often in each direction (at least one non-degenerate triangle),
  /// around a thickness: the enclosed volume over half the area above kShapeTolerance of the
  /// mesh's size, of the whole mesh and of each of its connected parts; each part wound as the
  /// whole or inside the box of a part that is (a cavity); and no two triangles on the same
  /// three (welded) corners (a flat sheet drawn as both its sides, alone or beside a solid, however
  /// its faces are triangulated, is not closed).
  bool closed = false;
  /// The enclosed signed volume (positive when the triangles wind counter-clockwise seen from
  /// outside, as VTK's outward normals do); meaningful when closed.
  double volume = 0.0;
  /// Every vertex lies in one plane (within kShapeTolerance of the mesh's size).
  bool planar = false;
  /// Closed, and every vertex lies on the inner side of every triangle's plane (within
  /// kShapeTolerance of the mesh's size): the surface bounds one convex solid. Only decided for
  /// meshes of at most kMaximumConvexityWork vertex-triangle pairs (larger ones: false).
  bool convex = false;
  /// Can the surface shadow a point of itself that faces the light? Not a plane (a ray meets it
  /// once), and not a convex solid (a ray that enters it toward the light leaves through a face
  /// turned away from the light, which its diffuse light leaves dark anyway).
  bool canShadowItself() const { return !planar && !(closed && convex); }
};

/// Of a closed surface (closure: +1 where its triangles wind counter-clockwise seen from outside
/// as its matrix places them, -1 where clockwise, 0 not closed) drawn through a world -> clip
/// matrix of the given determinant: +1 where its outward faces toward the viewer wind
/// counter-clockwise in the window (the front faces), -1 where clockwise, 0 where it is not
/// closed or the determinant is not finite. The usual projections (glFrustum's, glOrtho's, VTK's)
/// have a negative determinant and keep the winding; a positive one mirrors it.
int closedFaceTowardViewer(int closure, double worldToClipDeterminant);

/// Tolerance of planar and convex, relative to the diagonal of the mesh's bounding box (the
/// positions are often floats).
constexpr double kShapeTolerance = 1e-6;
/// Most vertex-triangle pairs the convexity test examines.
constexpr double kMaximumConvexityWork = 1.0e6;
/// Most pairs of a part wound against the whole and a part that may hold it (a cavity) the
/// closure test examines; beyond, the mesh is open.
constexpr double kMaximumNestingWork = 1.0e7;

/// One id per distinct position (numbered in the order the positions first appear; bitwise-equal
/// positions, +0 and -0 alike, share one), found by hashing: a mesh whose points move every frame
/// is welded every frame. Returns false, leaving ids unspecified, when a position is not finite
/// or there are 2^32 - 1 positions or more.
bool weldPositions(const std::vector<glm::dvec3>& positions, std::vector<std::uint32_t>& ids);

/// What classifySurface found of a mesh's connectivity, kept for its next classification. A mesh
/// whose points move while its triangles and the coincidences of its positions stay (a deforming
/// structure: the same weld, the same triangles) has the same welded edges, so whether they
/// balance (closed) is not sorted out again; only the volume, planar and convex, which depend on
/// the positions, are computed anew.
struct SurfaceTopology
{
  std::vector<std::uint32_t> ids;   ///< the weld (weldPositions) of the last classification
  std::uint64_t triangleDigest = 0; ///< a digest of its triangles' indices
  bool closed = false;              ///< its welded edges balance (at least one triangle counted)
  /// where closed: per welded vertex, the least vertex of its connected part
  std::vector<std::uint32_t> components;
  bool known = false; ///< the fields above describe a finished classification
};

/// Classify a triangle mesh (closed, volume, planar, convex). Vertices at bitwise-equal positions
/// (+0 and -0 alike) are one vertex, so meshes whose points were split for normals or texture seams
/// still close. Triangles with two equal (welded) corners are ignored; an index out of range or a
/// non-finite position makes the mesh open (the safe answer: both sides are drawn).
/// stop: once set (by another thread), the work ends early with an open answer.
/// topology (optional): the last classification's connectivity, used where the weld and the
/// triangles are the same (the answer is the same as without it) and updated to this one's.
SurfaceClosure classifySurface(const std::vector<glm::dvec3>& positions,
  const std::vector<std::array<std::int64_t, 3>>& triangles,
  const std::atomic<bool>* stop = nullptr, SurfaceTopology* topology = nullptr);

} // namespace csm
