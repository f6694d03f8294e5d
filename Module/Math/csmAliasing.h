// SPDX-License-Identifier: BSD-3-Clause
// Perspective aliasing of a shadow map and the resolution a target error needs: Lloyd et al.
// 2006, Eq. 1-4 at a point (the beam widths of a texel over a pixel), its maxima over a
// cascade's body (Eq. 9-10 as in §4.4) and the storage factor (Eq. 12). Pure math (C++17, GLM,
// double precision): no VTK, no GL. Spaces as in csmTypes.h.
#pragma once

#include "csmTypes.h"

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace csm
{

/// Perspective aliasing at one point (Lloyd et al. 2006, Eq. 1-4 with all resolutions set to 1).
struct Aliasing
{
  double mx = 0.0; ///< w_lx / w_i
  double mz = 0.0; ///< w_lz / w_i
};

/// Lloyd et al. 2006, Eq. 2-4 at a world point for a light clip matrix: beam widths of one
/// shadow-map texel (map resolution 1) along ls x and ls z over the width of one image pixel (image
/// height 1). Each is measured along the map row that follows it: s for ls x and t for ls z, the
/// other way round for a map turned by orientToTile (whose t row is the one along ls x); for a map
/// whose axes are not ls x and z (kept from an earlier camera, or VTK's), the better aligned.
Aliasing aliasingAt(const glm::dmat4& wsToClip, const Camera& camera,
  const glm::dvec3& wsLightDirection, const glm::dvec3& wsPoint);

/// The same for a map whose s and t axes follow the unit vectors wsMapX and wsMapZ, both
/// perpendicular to the light (a face partition's map, whose z axis is not the projected view
/// direction: Lloyd et al. 2006, §5.1).
Aliasing aliasingAt(const glm::dmat4& wsToClip, const Camera& camera, const glm::dvec3& wsMapX,
  const glm::dvec3& wsMapZ, const glm::dvec3& wsPoint);

/// Lloyd et al. 2006, §4.4: a cascade's Mx and Mz, the maxima of aliasingAt over the vertices
/// of its wsBody (at least their values on entry), and Eq. 12's storage factor Mx Mz / aspect.
void cascadeError(Cascade& cascade, const Camera& camera, const glm::dvec3& wsLightDirection);

/// The map resolution (texels a side) at which a cascade whose worst perspective aliasing is
/// maxAliasing (max(M_x, M_z) of Lloyd et al. 2006, Eq. 9-10, for a map of 1 texel and an image
/// 1 pixel high) reaches the error targetError (m, a texel's width over a pixel's, Eq. 1) in an
/// image imageHeight pixels high: maxAliasing * imageHeight / targetError, rounded up to a
/// multiple of step and kept in [step, ceiling]. The ceiling when any input is not a finite
/// positive number (spot lights have no M; a target of 0 means "always the ceiling").
int resolutionForError(
  double maxAliasing, double imageHeight, double targetError, int step, int ceiling);

/// The same for a cascade's map on a tile of at most ceiling texels along s and t: the texels
/// its larger M needs (max(Mx, Mz)) along both axes, each in [step, its side of the ceiling].
/// (Sized per axis, the map would be sharper along one axis than the other and the filter's
/// footprint elongated: the box and plane scene of the tests then darkens 4 % more pixels.)
/// A scene-fitted cascade (drawn once) gets the whole ceiling.
MapSize resolutionForError(
  const Cascade& cascade, double imageHeight, double targetError, int step, const MapSize& ceiling);

/// Does even the largest map a cascade may have (ceiling texels along s and t) miss the error
/// target in an image imageHeight pixels high (max(Mx, Mz) imageHeight / texels > targetError
/// along an axis)? Then no map of this frame meets it, a fresh one neither. False for a
/// scene-fitted cascade (drawn once at its tile), a target of 0 ("always the ceiling") and
/// inputs that are not finite positive numbers (spot lights have no M).
bool errorTargetOutOfReach(
  const Cascade& cascade, double imageHeight, double targetError, const MapSize& ceiling);

} // namespace csm
