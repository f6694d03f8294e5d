// SPDX-License-Identifier: BSD-3-Clause
// The number of cascades of a directional light from the error model: each count's plan judged
// by its predicted worst error (Lloyd et al. 2006, Eq. 9-10 as in §4.4) on the maps the atlas
// gives it, and weighed by what it costs to render (caster passes and texels); each count's
// splits the better of Barroso & Celes 2007, Eq. 19 and the log splits (Lloyd et al. 2006,
// Eq. 15-16); hysteresis against popping between counts (Lloyd et al. 2006, §5.2). Pure math
// (C++17, GLM, double precision): no VTK, no GL. Spaces as in csmTypes.h.
#pragma once

#include "csmAtlas.h"
#include "csmTypes.h"

#include <glm/vec3.hpp>

#include <vector>

namespace csm
{

/// The number of cascades from the error model. Each count k in [1, settings.split.k] is judged
/// by its plan's predicted worst error, max over its cascades of max(M_x, M_z) (Lloyd et al.
/// 2006, Eq. 9-10) times imageHeight over the largest maps that count can have
/// (planAtlas(k, settings.split.k, atlas).ceilings); of the counts whose
/// error is at most targetError, the one that costs least to render: its caster passes
/// (passTexels) plus the texels its maps need to meet the target (texelsForError); with
/// settings.sceneFitted, each count also with its farthest cascade scene-fitted (sceneFit),
/// which costs nothing (drawn once while the scene and the light stay), where that meets the
/// target. Without casters (null, the default) that is the
/// smallest count that meets the target. Where none meets it, settings.split.k (see below).
/// Changing the partitioning from frame to frame can pop (Lloyd et al. 2006, §5.2): a previous
/// count kPrevious (0: none) that still meets the target stays unless another costs at most
/// kCountHysteresis of its cost (without casters: unless a smaller count meets
/// kCountHysteresis times the target). Returns the plan for the chosen
/// count (its cascades.size() may be smaller where partitions are empty); the same input errors
/// as computeShadowSetup. With the adaptive split scheme each count's plan takes Barroso & Celes
/// 2007, Eq. 19's splits unless the log splits (Lloyd et al. 2006, Eq. 15-16) predict a smaller
/// worst error for this view: with the light along the view no warp helps, and over a long
/// depth range Eq. 19 (which only moves splits beyond the log splits) leaves the first
/// partition most of the range (f/n 1200, k 4, gamma 0: storage 22,512 against 139).
///
/// One light's maps share an atlas of the texels of min(settings.split.k, kAtlasFullMaps) maps
/// of atlas.resolution a side (atlasLayout): one scene-fitted cascade gets them all, more get
/// tiles that need not be square, maps that follow the view at most atlas.ceiling (planAtlas),
/// each map turned to its tile (predictedError). The plan returned is not turned: the caller
/// turns it for its tile (orientToTile). Where no count meets the target, more cascades are
/// taken only while each step cuts the predicted worst error to kCountHysteresis of the best
/// fewer cascades reach; a previous count within 1 / kCountHysteresis of that error stays.
ShadowSetup computeShadowSetupForError(const Camera& camera, const glm::dvec3& wsLightDirection,
  const Bounds* sceneBounds, const Settings& settings, const std::vector<Bounds>* receiverParts,
  double imageHeight, const AtlasLimits& atlas, double targetError, int kPrevious,
  const std::vector<CasterLoad>* casters = nullptr);

/// What one caster triangle costs to draw into a shadow map, in texels filled: a map pass of T
/// triangles costs as much as T times this many texels (passTexels). Measured on llvmpipe
/// (Mesa's software rasterizer, 2 threads): about 130 ns a triangle of a thin-bar lattice
/// against 5-8 ns a texel of a depth map (Documentation/Tried.md, "Where the map time goes"
/// and "Cascade count"); a GPU's triangle setup against its depth fill is of the same
/// order. A property of the renderer, not of a scene.
constexpr double kTexelsPerCasterTriangle = 16.0;

/// The cost of drawing the casters into a plan's maps, in texels filled: for each cascade that
/// follows the view (a scene-fitted one is drawn once: nothing), all the casters' cells times
/// kTexelsPerCasterTriangle. (The passes cull casters per cascade, but crediting that made the
/// count choose more, cheaper-looking cascades that cost more: on the towers 4.7 cascades a
/// frame instead of 3.7 and 2.5 maps drawn a frame instead of 1.7; a pass costs its draws too.)
double passTexels(const ShadowSetup& setup, const std::vector<CasterLoad>& casters);

/// The texels the maps of a plan need for a worst error of targetError in an image imageHeight
/// pixels high: each cascade's map (square, max(M_x, M_z) texels per pixel along both axes, as
/// resolutionForError sizes it, without its rounding) within its ceiling (CascadeCeilings::of);
/// +infinity for a plan without cascades or a target that is not positive.
double texelsForError(const ShadowSetup& setup, double imageHeight, double targetError,
  const CascadeCeilings& ceilings);

/// The plan computeShadowSetupForError judges for exactly k cascades (settings.split.k is
/// ignored): with the adaptive split scheme, Barroso & Celes 2007, Eq. 19's splits or the log
/// splits, whichever predicts the smaller worst error on maps of the given sizes (turned to
/// them; square by default); else computeShadowSetup's.
ShadowSetup computeShadowSetupForCount(const Camera& camera, const glm::dvec3& wsLightDirection,
  const Bounds* sceneBounds, const Settings& settings, const std::vector<Bounds>* receiverParts,
  int k, const CascadeCeilings& maps = MapSize(1), const SceneFit* fit = nullptr);

/// Share of the error target a smaller cascade count must meet to replace a previous count, and
/// share of the error a larger count must reach to be taken where none meets the target.
constexpr double kCountHysteresis = 0.8;

} // namespace csm
