// SPDX-License-Identifier: BSD-3-Clause
// Face partitioning (FP) of the view frustum for one directional light, Lloyd et al. 2006, §5.1:
// the frustum is split by the planes through the edges of its side faces and the light, each
// side-face partition gets its own warped shadow map, and the partitions may be z-partitioned
// along their face (FP+ZP+W, Lloyd et al. 2006, §5.2 "Combining with face partitioning").
// Pure math (C++17, GLM, double precision): no VTK, no GL. Spaces as in csmTypes.h.
//
// The construction, for a perspective camera:
//  - The light direction is folded so that it travels away from the viewer (dot with the view
//    direction >= 0): a light from the front and one from behind at the same angle give the same
//    partitions, and Lloyd et al. 2006, §5.1's choice "front faces when v . y < 0, back faces when
//    v . y > 0" (its y points toward the light) becomes "the side faces the folded light enters".
//  - The near face is left out and stretched over (Lloyd et al. 2006, §5.2): the side faces are
//    extended to the eye, so a face's partition is the frustum clipped by the two planes through
//    the eye that hold the face's side edges e_0, e_1 and the light direction. Seen from the light,
//    these wedges around the eye tile the frustum, near face included; the far face never faces
//    the folded light. Faces seen edge-on (no area from the light) get no partition.
//  - z-partitioning splits a face partition by the planes through the face's edge at the split
//    depth s_i (log splits, Lloyd et al. 2006, Eq. 15-16) and the light: seen from the light, the
//    face's trapezoid is cut into self-similar trapezoids (Lloyd et al. 2006, Fig. 8b).
//  - Each piece is warped as csm::computeShadowSetup warps a cascade, in its own light space:
//    y the light's direction of travel, z the bisector of the projected side edges, e'_0/|e'_0| +
//    e'_1/|e'_1| (Lloyd et al. 2006, §5.1), x = y cross z. Seen from the light the piece is an
//    overhead-like trapezoid opening along z, so n' is the warp mode's value at gamma = 90 deg for
//    the trapezoid of the face (n, f: the nearest and farthest light-space z of the face's corners
//    in the piece, measured from the eye). The warp's centre lies n' before the face's near edge
//    (ls z = n), or n' before the body where that would be inside it (the stretched near face).
#pragma once

#include "csmTypes.h"

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <string>
#include <vector>

namespace csm
{

/// A side face of the view frustum (looking down the view direction, up is the view-up vector).
enum class FrustumFace
{
  Bottom,
  Right,
  Top,
  Left
};

struct FacePartitionSettings
{
  /// The warp of each piece; at gamma = 90 deg LiSPSM and Generalized give the same n'
  /// (n + sqrt(f n)), PSM n' = n, None an orthographic map per piece (Lloyd et al. 2006, §4.1).
  WarpMode warp = WarpMode::LiSPSM;
  /// z-partitions per face (log splits, Lloyd et al. 2006, Eq. 15-16): 1 for FP+W, more for
  /// FP+ZP+W.
  int k = 1;
};

/// One face partition (or one z-partition of it) with its own shadow map.
struct FacePartition
{
  FrustumFace face = FrustumFace::Bottom;
  int zIndex = 0;           ///< 0 .. k-1, from the eye outward along the face
  glm::dvec3 wsMapX{ 0.0 }; ///< the map's s axis (unit, perpendicular to the light)
  glm::dvec3 wsMapZ{ 0.0 }; ///< the map's t axis: the bisector of the projected side edges
  /// vsNear, vsFar: the face's split depths s_i, s_i+1 (the body reaches nearer, down to the near
  /// plane, where the near face is stretched over); wsBody: the piece's vertices; wsToClip, nPrime,
  /// gammaLimDeg (Barroso & Celes 2007, Eq. 15 for the face's trapezoid), Mx, Mz and storage
  /// (Lloyd et al. 2006, Eq. 9-12, measured along wsMapX and wsMapZ) as for a cascade.
  Cascade map;
  /// The half-spaces that cut this piece out of the frustum (world space: a point p is inside
  /// when dot(xyz, p) + w >= 0, xyz a unit normal): the two planes through the eye holding the
  /// face's side edges and the light, and the split planes through the face's edge at s_i and
  /// s_i+1 and the light (where they cut: none for k = 1). Inside the frustum the pieces tile
  /// it, so a point belongs to the piece whose smallest plane distance is largest
  /// (partitionAt()): how the lookup selects the map (Lloyd et al. 2006, §6.3).
  std::vector<glm::dvec4> wsPlanes;
};

struct FacePartitioning
{
  Status status = Status::InvalidInput;
  std::string message;   ///< why, when the status is not Ok
  double gammaDeg = 0.0; ///< angle between light and view direction, 0..180 (0: light from behind)
  std::vector<double> splits;            ///< split depths along the faces, s_0 = near .. s_k = far
  std::vector<FacePartition> partitions; ///< face by face (Bottom, Right, Top, Left), near to far
  double storageTotal = 0.0;             ///< sum of the partitions' storage factors
  double storageOptimal = 0.0;           ///< Lloyd et al. 2006, App. C: ln(f/n) / (2 tan theta)
};

/// The face partitions of the camera's view frustum [vsNear, vsFar] for a directional light
/// travelling along wsLightDirection (no scene clipping: the bodies are the frustum's partitions,
/// as in the paper's analysis). InvalidInput, with a message and no partitions, for an invalid or
/// parallel-projection camera, a zero or non-finite light direction, or k outside [1, 64].
FacePartitioning computeFacePartitions(
  const Camera& camera, const glm::dvec3& wsLightDirection, const FacePartitionSettings& settings);

/// The partition a world point belongs to: the one whose smallest signed distance to its
/// wsPlanes is largest (inside one, up to rounding, for points of the frustum). -1 when there
/// are no partitions.
int partitionAt(const FacePartitioning& partitioning, const glm::dvec3& wsPoint);

const char* toString(FrustumFace face);

} // namespace csm
