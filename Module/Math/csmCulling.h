// SPDX-License-Identifier: BSD-3-Clause
// Which casters a map pass must draw: a box against a light clip volume (conservative, in
// homogeneous clip space, with Lloyd et al. 2006, §6.4's depth clamping), and whether a box swept
// along a directional light reaches another box. Pure math (C++17, GLM, double precision): no
// VTK, no GL. Spaces as in csmTypes.h.
#pragma once

#include "csmTypes.h"

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace csm
{

/// True when no point of the box can land inside the light clip volume (conservative test in
/// homogeneous clip space). With depthClamp, points nearer than the near plane count as inside.
bool boxOutsideClipVolume(const glm::dmat4& wsToClip, const Bounds& box, bool depthClamp);

/// Can a caster inside casterBox shadow a point of receiverBox under a directional light
/// travelling along wsLightDirection? True when the caster box, swept along the light by more
/// than minimumDistance, meets the receiver box (closed boxes: a conservative answer). A point
/// is shadowed only by what lies toward the light from it, so false means that no point of the
/// receiver box can be in the caster's shadow (a ground slab under everything else, say).
/// True for empty, non-finite or zero directions (the safe answer: draw the caster).
bool sweptBoxReachesBox(const Bounds& casterBox, const glm::dvec3& wsLightDirection,
  const Bounds& receiverBox, double minimumDistance);

/// Does a perspective camera see only the outside of every closed surface inside a box? True
/// where no point of its near plane's rectangle reaches the box: the eye is farther from the box
/// than the rectangle's farthest corner (vsNear over the cosine of the half diagonal field of
/// view). Of a closed surface in the box, the faces turned away from such an eye are hidden
/// behind those turned toward it. False for a parallel camera (its near plane may cut any box),
/// an empty box and input that is not finite.
bool eyeSeesOnlyOutsideOf(const Camera& camera, const Bounds& box);

} // namespace csm
