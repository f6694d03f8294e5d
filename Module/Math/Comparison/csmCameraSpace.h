// SPDX-License-Identifier: BSD-3-Clause
// Camera space shadow maps (CSSM, Kolić & Mihajlović), the general case for a directional
// light, as one world -> clip matrix. Pure math (C++17, GLM, double): no VTK, no GL. Rendered
// by the passes with the planner's CameraSpace option, as a comparison technique; the map's
// depth spans a different range on every light ray (see below), and the lookup scales its
// constant bias by wMin / w.
//
// Kolić & Mihajlović, §3.1: roll the camera about its view axis so that the light comes from
// above, widen its field of view to hold the original frustum, put a plane P through the two
// lower corners of the near plane and the two upper corners of the far plane (the two upper
// near and lower far corners when the light comes from in front), project the casters onto P
// along the light, and capture P with the rolled camera. Projection along a fixed direction onto
// a plane is affine, so the map's s, t and w are one projective map of the world point: every
// point of a light ray lands on the same texel with the same w. The depth row is the light
// depth (dot(p, L), affine), scaled so that depth / w stays in [-1, 1] over the view: along each
// ray w is constant, so depth / w orders the casters of a ray as the light does, but its scale
// is 1 / w of that ray.
#pragma once

#include "csmTypes.h"

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <string>
#include <vector>

namespace csm
{

struct CameraSpaceMap
{
  Status status = Status::InvalidInput;
  std::string message;         ///< why, when the status is not Ok
  bool lightFromFront = false; ///< the plane runs from the upper near to the lower far edge
  glm::dmat4 wsToClip{ 1.0 };  ///< world -> clip; the view frustum [vsNear, vsFar] in [-1, 1]^3
  glm::dvec4 wsPlane{ 0.0 };   ///< the projection plane P (xyz unit normal, w offset), world
  /// The smallest w over the frustum: on a ray of w the map's depth (after the division) spans
  /// wMin / w of what it spans on the nearest ray, so a constant depth bias must scale by it.
  double wMin = 0.0;
  /// How far behind the eye, along the view, the capturing camera stands (the focus range; 0:
  /// at the eye).
  double pushBack = 0.0;
  /// The view depth whose points of P the map's middle row holds (the focus it has).
  double vsFocus = 0.0;
  /// The focus asked for lies beyond the farthest one the map can have (see
  /// computeCameraSpaceMap): the map is focused at vsFocus, that farthest one, instead.
  bool focusClamped = false;
};

/// The farthest the capturing camera is pushed back for the focus range, in view depths of the
/// far plane. Pushed back that far the capture is orthographic to within 1 % (its w varies by
/// 1 % over the view), so it reaches within about 1 % of the depth range the farthest focus
/// any push reaches; farther pushes only grow the map's s and t rows (with the square of the
/// push), which beyond float's range leave the lookup infinities and no shadow.
constexpr double kMostPushBack = 100.0;

/// The general-case CSSM map of the camera's view frustum [vsNear, vsFar] for a directional
/// light travelling along wsLightDirection. InvalidInput, with a message, for an invalid or
/// parallel camera, a zero or non-finite light, a light (nearly) along the view or inside the
/// view's cone (the dueling frustum case, Kolić & Mihajlović Fig. 2, which needs four planes:
/// computeCameraSpaceDueling()), or a light (nearly) parallel to the plane P.
///
/// The focus range (Kolić & Mihajlović §3.1, Fig. 3): with vsFocus > 0 the capturing camera is
/// pushed back along the view (and the map fitted anew) so that the part of P in front of the
/// view depth vsFocus takes half of the map's t axis, where the capture from the eye gives
/// half of it to about the first 2 vsNear. A focus nearer than that keeps the eye. Captured
/// from afar, the middle row holds P's points at a depth short of vsFar (about the middle of the
/// range, where t is linear in depth): a focus beyond what kMostPushBack vsFar of push reaches
/// (or beyond vsFar) is clamped to that farthest focus (focusClamped, vsFocus). 0: captured
/// from the eye.
CameraSpaceMap computeCameraSpaceMap(
  const Camera& camera, const glm::dvec3& wsLightDirection, double vsFocus = 0.0);

/// The general case for a spot light at wsLightPosition (Kolić & Mihajlović §6.2): the same
/// plane P (the roll and the plane set by the rays from the light toward the middle of the
/// view), the casters projected onto it from the light (a central projection: one projective
/// map, every point of a ray from the light on one texel), captured by the camera, the focus
/// range as above. Depth is a perspective map's: a + b / w over the view's w range (w grows
/// with the distance from the light along each ray), so casters between the light and the view
/// need depth clamping. InvalidInput, with a message, where the paper takes a standard map:
/// the light in or near the view (the light's plane parallel to P cuts the view), along the
/// view, or its rays meeting P behind the camera; and for an invalid or parallel camera or a
/// position that is not finite.
CameraSpaceMap computeCameraSpaceSpot(
  const Camera& camera, const glm::dvec3& wsLightPosition, double vsFocus = 0.0);

/// One map of the dueling frustum case: its matrix, the half-spaces that select it (world,
/// as FacePartition::wsPlanes) and its smallest w.
struct CameraSpaceFace
{
  glm::dmat4 wsToClip{ 1.0 };
  std::vector<glm::dvec4> wsPlanes;
  double wMin = 0.0;
};

/// The dueling frustum case (Kolić & Mihajlović §3.1, Fig. 2): the point t where the line
/// through the eye along the light meets the near plane, four planes through t and the far
/// plane's edges, the casters projected along the light onto each and captured by the camera:
/// four maps, a point taking the one whose triangle (t and a far edge) its light ray crosses,
/// i.e. whose two planes through t, a far corner and the light hold it. Empty for an invalid
/// or parallel camera, a bad light, or a light (nearly) perpendicular to the view (t at
/// infinity).
std::vector<CameraSpaceFace> computeCameraSpaceDueling(
  const Camera& camera, const glm::dvec3& wsLightDirection);

} // namespace csm
