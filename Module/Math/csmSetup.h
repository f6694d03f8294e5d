// SPDX-License-Identifier: BSD-3-Clause
// The cascades of a directional light for one frame (computeShadowSetup): light space (Lloyd et
// al. 2006, Fig. 3), the body B of each z-partition (view partition ∩ receivers, extruded to the
// casters: Barroso & Celes 2007, §2.3), the split depths (csmSplits.h), the warp (n' of Barroso
// & Celes 2007, Eq. 16-18, Fig. 4 and 6), the focus (Lloyd et al. 2006, §6.4), the light
// view-projection matrix of each cascade and its perspective aliasing error (Lloyd et al. 2006,
// Eq. 9-12, §4.4, App. C); and the steps it composes: warpMatrix, focusMatrix, the depth floor
// of orthographic maps and the texel snap of stable orthographic maps. Pure math (C++17, GLM,
// double precision): no VTK, no GL. Spaces as in csmTypes.h.
#pragma once

#include "csmTypes.h"

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <vector>

namespace csm
{

/// Everything a shadow pass needs for one directional light in one frame. wsLightDirection is the
/// direction the light travels. sceneBounds may be null (no clipping, no caster extrusion: the
/// bodies are the view-frustum partitions, as in the papers' analysis). receiverParts (optional,
/// with sceneBounds) are the boxes of the individual props: the receivers are then the
/// partitions clipped by each box, which fits the depth range and the maps tighter than the one
/// box around everything (a large flat ground and a tall structure, say).
///
/// With a SceneFit (and sceneBounds), sceneFitted holds the farthest cascade once more with that
/// map: its body the partition's receivers within the fit's s, t extent (the rest cannot be in
/// shadow), its Mx, Mz Lloyd et al. 2006, §4.4's maxima over that body along this view's ls x
/// and z (aliasingAt: the map's rows best aligned with them, so a map turned about the light
/// by 45 degrees reads sqrt 2 times its texel); empty where that body is.
///
/// Input errors (InvalidInput, with a message): those of acceptSetupInput (csmGeometry.h), a
/// light direction that is not finite or zero, a cascade count outside [1, kMaxSplits], lambda
/// outside [0, 1], alpha not above 1.
ShadowSetup computeShadowSetup(const Camera& camera, const glm::dvec3& wsLightDirection,
  const Bounds* sceneBounds, const Settings& settings,
  const std::vector<Bounds>* receiverParts = nullptr, const SceneFit* fit = nullptr);

/// The warp of a cascade in light space (rows: map s, map t, depth, w): orthographic for an
/// infinite n', else a perspective along ls z whose centre lies n' before the body's nearest
/// ls z (Barroso & Celes 2007, Fig. 4 and 6).
glm::dmat4 warpMatrix(double nPrime, double lsZMin);

/// The focus: the scale and offset that take the warped light-space points' bounds to
/// [-1, 1]^3, with 1 % of room in depth for the bias (Lloyd et al. 2006, §6.4).
/// With quantizeExtent (orthographic cascades of WarpMode::None), the map's width and height
/// are rounded up to the next quarter power of two with 4 % of room, so that a camera moving a
/// little keeps the same texel size (see snapToTexels()).
glm::dmat4 focusMatrix(const std::vector<glm::dvec3>& lsPoints, const glm::dmat4& lsToWarped,
  bool quantizeExtent = false);

/// Share of an orthographic map's scale that its depth range (along the light) keeps at least:
/// the larger of its body's extent across the light and the distance of its farthest point from
/// the eye. Depth clamping fits the range to the receivers (Lloyd et al. 2006, §6.4), and a
/// flat receiver perpendicular to the light (a ground under an overhead light, alone in a far
/// cascade) has one depth: fitted to it, the map's depth scale would magnify the float rounding
/// of the lookup's and the rasterizer's positions (a few 1e-7 of the distance from the eye)
/// beyond the constant depth bias, which is a share of the range (0.002 by default), and the
/// ground would shadow itself in stripes. At 1/50 the default bias is 4e-5 of that distance,
/// about a hundred times the rounding and still a small part of a texel (the passes' box over a
/// ground, llvmpipe: clean at 1/2000, striped at 1/50000).
constexpr double kOrthographicDepthShare = 1.0 / 50.0;

/// The least depth range of an orthographic map whose body spans lsAcross across the light and
/// whose farthest point lies eyeDistance from the eye (0 where no eye applies):
/// kOrthographicDepthShare of the larger; 0 for values that are not finite.
double orthographicDepthFloor(double lsAcross, double eyeDistance);

/// Gives the points of an orthographic map (light space: x, z across the light, y along it)
/// the depth range orthographicDepthFloor asks for at least: two more points about the middle
/// of the depth range where it is thinner. eyeAtOrigin: the points are camera-centred, and
/// their distance from the origin counts as the distance from the eye.
void keepOrthographicDepthRange(std::vector<glm::dvec3>& lsPoints, bool eyeAtOrigin);

/// An orthographic (affine) world -> clip matrix moved by less than half a texel of a map of
/// the given resolution so that its texel grid is fixed in the world: the texel edges of two
/// frames of a translating camera coincide, and shadow edges do not crawl (the cascaded-maps
/// stabilisation of Vázquez's and King's slides). Unchanged when the matrix is projective or the
/// resolution is not positive.
glm::dmat4 snapToTexels(const glm::dmat4& wsToClip, const MapSize& resolution);

} // namespace csm
