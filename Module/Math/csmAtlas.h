// SPDX-License-Identifier: BSD-3-Clause
// The atlas one light's cascades share and each cascade's error on its tile: the atlas layout,
// the tiles a cascade count gets in it, the largest maps of each kind of cascade, the predicted
// worst error of a cascade on a map of a given size (Lloyd et al. 2006, Eq. 9-10 as in §4.4,
// per map axis) and the quarter turn that gives its larger error the longer side of a tile.
// Pure math (C++17, GLM, double precision): no VTK, no GL. Spaces as in csmTypes.h.
#pragma once

#include "csmTypes.h"

#include <glm/vec2.hpp>

#include <array>

namespace csm
{

/// One light's cascades share one depth texture (an atlas) with the texels of at most this many
/// maps of the largest resolution, allocated once for the most cascades planned: the count
/// changes with the view, and a new texture would cost its allocation (on a software
/// rasterizer, more than drawing the maps into it) and every map's render. The texels (and the
/// memory) do not grow with the number of cascades; one cascade alone, where it is scene-fitted
/// (drawn once), gets them all in one map.
constexpr int kAtlasFullMaps = 4;

/// An atlas, or a grid of equal tiles in one: texels of the tiles along s and t, and their
/// columns and rows.
struct AtlasGrid
{
  int columns = 1;
  int rows = 1;
  MapSize tile;
};

/// The largest maps count cascades can have: a scene-fitted cascade (drawn once while the scene
/// and the light stay) its whole tile of the atlas, resolutionCeilingForCount; a cascade that
/// follows the view (drawn again as the view moves) at most resolution texels a side of that
/// tile, so that the whole atlas a single cascade gets does not make its map cost more at every
/// re-render (Documentation/Tried.md, "Atlas layout"). One size for both converts to this.
struct CascadeCeilings
{
  MapSize sceneFitted;
  MapSize following;
  CascadeCeilings(const MapSize& both = MapSize()) // NOLINT: a size for both kinds
    : sceneFitted(both)
    , following(both)
  {
  }
  CascadeCeilings(int side) // NOLINT: a square map of side texels for both
    : CascadeCeilings(MapSize(side))
  {
  }
  const MapSize& of(bool isSceneFitted) const { return isSceneFitted ? sceneFitted : following; }
  const MapSize& of(const Cascade& cascade) const { return of(cascade.sceneFitted); }
};

/// The atlas for at most mostCascades maps of resolution texels a side: min(mostCascades,
/// kAtlasFullMaps) square tiles of that resolution, four in 2 x 2 (a square texture: one map
/// can have all its texels), two or three in a row. Where maximumSide (a GL texture's size
/// limit; 0: none) is less than the texture's side, the tiles shrink to fit it. A 1 x 1 grid of
/// 0 texels for counts or resolutions below 1.
AtlasGrid atlasLayout(int mostCascades, int resolution, int maximumSide = 0);

/// The grid of count equal tiles in an atlas of atlas.columns x atlas.rows tiles of atlas.tile
/// texels, no side longer than atlas.tile's: of the grids with columns x rows >= count, the one
/// whose tiles have the longest short side, then the largest area (ties: fewer columns). Tiles
/// need not be square: 5 or 6 cascades in 2 x 2 tiles of 2048 get 2048 x 1365 each, and a
/// cascade turned to its tile (orientToTile) keeps 2048 texels where its error is largest.
AtlasGrid atlasGrid(int count, const AtlasGrid& atlas);

/// The tiles count cascades get in the atlas of atlasLayout (atlas), within its texture: one
/// cascade the largest square it holds (4096² in 2 x 2 tiles of 2048), more the grid of
/// atlasGrid(count, atlas). A 1 x 1 grid of 0 texels for counts or atlases without texels.
AtlasGrid atlasForCount(int count, const AtlasGrid& atlas);

/// The largest map count cascades can have in the atlas of atlasLayout(mostCascades,
/// resolution): its tile in atlasForCount (at 2048 with four or more most cascades: 1 cascade
/// 4096², 2-4 cascades 2048², 5-6 cascades 2048 x 1365, 7-8 cascades 1365²). 0 x 0 for
/// counts or resolutions below 1.
MapSize resolutionCeilingForCount(int count, int mostCascades, int resolution);

/// ceilingsForCount(count, mostCascades, resolution): see CascadeCeilings (0 x 0 where
/// resolutionCeilingForCount is).
CascadeCeilings ceilingsForCount(int count, int mostCascades, int resolution);

/// What a light's atlas is planned from: tiles of resolution texels a side (the texture holds
/// min(most cascades, kAtlasFullMaps) of them), maps that follow the view at most ceiling
/// texels a side (at most resolution; fewer while the user interacts), and the GL's texture
/// size limit (0: none). One number converts to tiles and ceiling of that side, without limit.
struct AtlasLimits
{
  int resolution = 0;
  int ceiling = 0;
  int maximumSide = 0;
  AtlasLimits(int side = 0) // NOLINT: tiles and ceiling of one side
    : resolution(side)
    , ceiling(side)
  {
  }
  AtlasLimits(int tileResolution, int mapCeiling, int textureLimit)
    : resolution(tileResolution)
    , ceiling(mapCeiling)
    , maximumSide(textureLimit)
  {
  }
};

/// One light's atlas as planned for count cascades: the texture (the atlasLayout of the most
/// cascades), the tiles of this count in it (atlasForCount), the largest map of each kind of
/// cascade (ceilingsForCount within the tiles) and whether the GL's limit shrank the tiles.
struct AtlasPlan
{
  MapSize texture;
  AtlasGrid tiles;
  CascadeCeilings ceilings;
  bool shrunk = false;
  /// Cascade i's tile in the texture, texels: x, y (from the lower left), width, height.
  std::array<int, 4> tile(int i) const;
};

/// The atlas of count cascades of at most mostCascades (the texture stays the one mostCascades
/// needs: the count changes with the view); for no cascade, that texture and no tiles. Empty
/// (0 texels) for limits below 1.
AtlasPlan planAtlas(int count, int mostCascades, const AtlasLimits& limits);

/// Lloyd's M along the cascade's map axes s and t: (Mx, Mz), or (Mz, Mx) where its map is turned.
glm::dvec2 mapAxisAliasing(const Cascade& cascade);

/// A cascade's predicted worst error on a map of the given size, turned as orientToTile would
/// turn it: min over both orientations of max(M_s / width, M_t / height) times imageHeight.
/// +infinity for a map without texels.
double predictedError(const Cascade& cascade, double imageHeight, const MapSize& map);

/// The predicted worst error of a plan (see computeShadowSetupForError): the largest of its
/// cascades' on the largest maps they can have (CascadeCeilings::of); +infinity without
/// cascades.
double predictedError(const ShadowSetup& setup, double imageHeight, const CascadeCeilings& maps);

/// Turn each cascade's map a quarter (rows s, t of wsToClip to t, -s: a rotation, so the
/// triangles keep their winding) where that gives its larger error the longer side of a
/// non-square tile, and set its mapTurned. A square tile changes nothing.
void orientToTile(ShadowSetup& setup, const MapSize& tile);

} // namespace csm
