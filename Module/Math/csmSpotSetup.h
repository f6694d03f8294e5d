// SPDX-License-Identifier: BSD-3-Clause
// One perspective shadow map of a spot light for one frame, fitted to what the view needs: the
// visible scene (view frustum ∩ scene box, as the body B of Barroso & Celes 2007, §2.3) inside
// the cone's bounding pyramid. Lloyd et al. 2006's aliasing metric is defined for directional
// lights; a spot light's cascade carries none. Pure math (C++17, GLM, double precision): no VTK,
// no GL. Spaces as in csmTypes.h.
#pragma once

#include "csmTypes.h"

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace csm
{

/// One perspective map for a spot light at wsLightPosition shining along wsLightAxis with the
/// given cone half-angle (< 90 degrees), fitted to what the view needs: the part of the visible
/// scene (view frustum clipped by the scene bounds, may be null) inside the cone's bounding
/// pyramid. One cascade covering the fitted depth range; its Mx, Mz and storage are 0 (Lloyd's
/// metric is defined for directional lights). Input errors: those of acceptSetupInput
/// (csmGeometry.h), a light position or axis that is not finite or a zero axis, a cone angle
/// outside (0, 90) degrees.
ShadowSetup computeSpotSetup(const Camera& camera, const glm::dvec3& wsLightPosition,
  const glm::dvec3& wsLightAxis, double coneAngleDeg, const Bounds* sceneBounds, bool depthClamp);

/// The constant bias's scale on a map of world -> clip matrix wsToClip at a point whose clip w
/// is w: K / w^2 (the lookup divides K by its w). A perspective map (a spot light's, near n and
/// far f along its axis) stores window depths f / (f - n) (1 - n / z), whose change per unit of
/// z is f n / ((f - n) z^2): a constant bias meant as a share of the map's depth range, as on an
/// orthographic map, is that share of f - n in z, so K = f n (w = z). Without it a light close
/// to a caster (n small against f) squeezes its far receivers' depths under the bias, which then
/// lights them. 0 where the matrix is not a perspective one along an axis (an orthographic
/// map: w = 1, its bias a share as it is).
double perspectiveBiasFactor(const glm::dmat4& wsToClip);

} // namespace csm
