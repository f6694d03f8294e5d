// SPDX-License-Identifier: BSD-3-Clause
// The scene-fitted map of a directional light: one orthographic map fixed in the world, of the
// part of the scene that can be in shadow, which serves every view while the scene and the
// light stay (the farthest cascade takes it where it meets the error target: csmCascadeCount.h).
// Its depth range keeps the floor of orthographic maps (csmSetup.h) and its focus is Lloyd et
// al. 2006, §6.4's. Pure math (C++17, GLM, double precision): no VTK, no GL. Spaces as in
// csmTypes.h.
#pragma once

#include "csmTypes.h"

#include <glm/vec3.hpp>

#include <vector>

namespace csm
{

/// The map of the part of the scene a directional light can shadow, fixed in the world: a point
/// is in shadow only if a caster lies toward the light from it, so across the light only the
/// footprints of caster boxes over the boxes of receivers they can reach (sweptBoxReachesBox;
/// a prop that cannot shadow itself not over its own box) need texels; a wide ground under a
/// structure adds only the structure's footprint. Axes: the light's direction of travel as
/// depth (the extent along it of the receiver parts and casters clipped to the map's extent
/// across the light; without parts, of the scene box so clipped), s and t perpendicular to it
/// from the direction alone (not from the view). Without receiver parts the scene box is the
/// one receiver. Its matrix
/// depends only on the light and the boxes, so a map drawn for one view serves every view they
/// stay for. False (fit unchanged) where no caster can shadow anything, a caster is screen-sized
/// (its shadow's extent changes with the view) or the input is not finite.
bool sceneFit(const glm::dvec3& wsLightDirection, const Bounds& sceneBounds,
  const std::vector<CasterLoad>& casters, const std::vector<Bounds>* receiverParts, SceneFit& fit);

/// Texels a side of a scene-fitted map whose lookup takes the whole constant depth bias.
constexpr double kSceneFittedBiasTexels = 1024.0;

/// Share of the constant depth bias the lookup takes on a scene-fitted map of `texels` texels a
/// side (on the finer of its sides). The constant bias is a share of a map's depth range; a
/// scene-fitted map's is the whole scene along the light, so the bias follows its texel:
/// kSceneFittedBiasTexels / texels, at most 1 (light-space pages of level k take 2^-k of their
/// base's). At the full share the 4096² scene-fitted map let light through contacts and along
/// shadows' edges on grazing receivers (Results.md, "Light-space pages"). 1 where texels is
/// not a positive number.
double sceneFittedBiasShare(double texels);

} // namespace csm
