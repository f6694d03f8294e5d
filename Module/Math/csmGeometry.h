// SPDX-License-Identifier: BSD-3-Clause
// Geometry the shadow setups share, and the one check of their input: the camera's orthonormal
// frame, the light-space basis of Lloyd et al. 2006, Fig. 3, view-volume partitions (the
// frustum pieces that Barroso & Celes 2007, §2.3 clip into the body B), boxes and their clip
// planes, row-wise matrices. Pure math (C++17, GLM, double precision): no VTK, no GL. Spaces as
// in csmTypes.h.
#pragma once

#include "csmConvexBody.h"
#include "csmTypes.h"

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <array>
#include <limits>
#include <string>
#include <vector>

namespace csm
{

constexpr double kPi = 3.14159265358979323846;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kDegree = kPi / 180.0;

/// Why a shadow setup would refuse this camera; empty when it is valid.
std::string cameraError(const Camera& camera);

/// Why a directional light's direction cannot be used (not finite, or zero); empty when it can.
std::string lightDirectionError(const glm::dvec3& wsLightDirection);

/// The input check every shadow setup of one frame starts with (directional and spot lights):
/// the first of the camera's error (cameraError), non-finite scene bounds, lightError (what the
/// caller found wrong with its light and settings; empty: nothing) and non-finite receiver parts
/// makes the setup InvalidInput with that message; an empty scene box makes it NothingToShadow.
/// True when the setup can go on (its status is then untouched).
bool acceptSetupInput(ShadowSetup& setup, const Camera& camera, const Bounds* sceneBounds,
  const std::string& lightError, const std::vector<Bounds>* receiverParts = nullptr);

/// All three coordinates finite.
bool finite(const glm::dvec3& v);

/// Any unit vector perpendicular to the unit vector n.
glm::dvec3 perpendicular(const glm::dvec3& n);

/// The part of u perpendicular to the unit vector n, normalized; fallback where u is (nearly)
/// parallel to n.
glm::dvec3 perpendicularPart(const glm::dvec3& u, const glm::dvec3& n, const glm::dvec3& fallback);

/// The angle between two non-zero vectors, in radians (0..pi).
double angleBetween(const glm::dvec3& a, const glm::dvec3& b);

/// The camera's orthonormal frame and the tangents of its half fields of view.
struct CameraFrame
{
  glm::dvec3 view, up, right; // orthonormal
  double tanX = 0.0, tanY = 0.0;
};

CameraFrame cameraFrame(const Camera& camera);

/// Lloyd et al. 2006, Fig. 3; y is the light's direction of travel.
struct LightBasis
{
  glm::dvec3 x, y, z;
  /// A (camera-centred) point's coordinates along x, y, z.
  glm::dvec3 coordinates(const glm::dvec3& p) const;
};

/// The light space of a view: z the view direction projected onto the plane perpendicular to
/// the light; when light and view are parallel, the view-up vector takes its place.
LightBasis lightBasis(const CameraFrame& frame, const glm::dvec3& wsLightDirection);

/// The world -> frame matrix of the orthonormal axes x, y, z (its rows) at wsOrigin.
glm::dmat4 frameMatrix(
  const glm::dvec3& x, const glm::dvec3& y, const glm::dvec3& z, const glm::dvec3& wsOrigin);

/// Half-widths of the view volume at a depth (perspective or parallel).
glm::dvec2 halfSize(const Camera& camera, const CameraFrame& frame, double vsDepth);

/// The view-volume partition [d0, d1], in camera-centred world space: the 4 corners of its near
/// face, then the 4 of its far face, in the same winding.
std::array<glm::dvec3, 8> partitionCorners(
  const Camera& camera, const CameraFrame& frame, double d0, double d1);

/// Clipping tolerance for the view volume up to a depth: relative to its size there, not to the
/// whole view (a near partition may be 1e-20 of the far distance).
double clipEpsilon(const Camera& camera, const CameraFrame& frame, double vsDepth);

/// Parameter t >= 0 where the ray p - t d (toward the light) leaves the box [lo, hi].
double exitTowardLight(
  const glm::dvec3& p, const glm::dvec3& d, const glm::dvec3& lo, const glm::dvec3& hi);

/// A matrix from its four rows.
glm::dmat4 fromRows(
  const glm::dvec4& r0, const glm::dvec4& r1, const glm::dvec4& r2, const glm::dvec4& r3);

/// Corner i (0..7, bit 0: x, bit 1: y, bit 2: z at the maximum) of a box.
glm::dvec3 boxCorner(const Bounds& box, int i);

/// How much a box or a body of the given size is grown so that a flat or point scene keeps a
/// volume: relative to its size, and at least to the camera's near distance.
double inflation(double size, double vsNear);

/// The clip planes of a box, camera-centred and inflated.
std::array<Plane, 6> cameraCentredBoxPlanes(const Bounds& box, const Camera& camera);

} // namespace csm
