// SPDX-License-Identifier: BSD-3-Clause
/**
 * The maps a frame makes, as the baker draws them and the shadow pass reads them, and what the
 * frame did (vtkCascadedShadowMapBakerPass names them LightMaps, CascadeMap, LightKind, MapKind
 * and FrameStatistics). The bottom of the module: it includes none of the module's classes, and
 * the baker, the shadow pass and the module's helpers include it.
 */
#ifndef vtkCascadedShadowMapTypes_h
#define vtkCascadedShadowMapTypes_h

#include "vtkCascadedShadowsConfigure.h" // for CSM_COMPARISON_TECHNIQUES
#include "vtkSmartPointer.h"             // for LightMaps::Atlas

#include <array>  // for CascadeMap::Patches
#include <vector> // for LightMaps::Cascades

class vtkLight;
class vtkTextureObject;

namespace vtkCascadedShadows
{
/// The most cascades a light gets (the shaders hold them in uniform arrays).
constexpr int MaximumCascades = 8;

/// Texture units the lookup takes a shadowed light: its atlas, read by bilinear compares and
/// through a second unit texel by texel (vtkCascadedShadowMapPass); a paged light's page table
/// takes one more where one is left.
constexpr int TextureUnitsPerLight = 2;

/// Map sizes from the error target are multiples of it (texels).
constexpr int ResolutionStep = 64;

/// Compact casters (vtkCascadedShadowMapBakerPass::CompactCasters): at least
/// MinimumBlockTriangles a block, at most MaximumBlocks a prop; the visible-depth pass and the
/// cascade count weigh groups of BlocksPerGroup consecutive blocks (a k-d subtree each where the
/// median splits are balanced), the maps cull the blocks; meshes of more than
/// SynchronousPreparationTriangles are prepared by a worker thread; beyond
/// MostClassifiedTriangles none is classified as closed.
constexpr int MinimumBlockTriangles = 2048;
constexpr int MaximumBlocks = 512;
constexpr int BlocksPerGroup = 8;
constexpr int SynchronousPreparationTriangles = 262144;
constexpr int MostClassifiedTriangles = 4194304;

enum class LightKind
{
  Directional, ///< cascades along the view (z-partitions), or a scene-fitted map
  Spot         ///< one perspective map fitted to the lit part of the visible scene
};

enum class MapKind
{
  FollowsView, ///< planned for the view: rendered again when it does not serve the view
  SceneFitted, ///< fixed in the world: kept while the scene and the light stay
#if CSM_COMPARISON_TECHNIQUES
  FacePartition, ///< a face partition, selected by its planes (comparison technique)
  CameraSpace    ///< a camera space map (comparison technique)
#endif
};

/// What a frame does with a cascade's map.
enum class MapAction
{
  Keep,  ///< the map of an earlier frame serves as it is
  Move,  ///< the map of an earlier frame, moved with the view: its texels shifted, strips drawn
  Patch, ///< the map of an earlier frame, the texels its changed casters cover drawn again
  Draw   ///< drawn whole
};

/// One cascade's map, as the shadow pass reads it.
struct CascadeMap
{
  MapKind Kind = MapKind::FollowsView;
  MapAction Action = MapAction::Draw; ///< what this frame does with it
  double WorldToMap[16] = {};         ///< world -> light clip, row-major
  double SplitFar = 0.0;              ///< view depth where the cascade ends
  int Tile[4] = {};                   ///< its tile in the atlas, texels: x, y, width, height
  int Resolution[2] = {};             ///< texels of its map, in the lower left of its tile
  bool Turned = false;                ///< turned a quarter to its tile (csm::orientToTile)
  double CasterView[18] = {};         ///< the view its screen-sized casters were sized for
  /// Texels its window moved along s and t in this frame's render, the rest of the earlier map
  /// kept (a map that follows the view, moved with it: csm::panKeptMap); 0, 0: drawn whole or
  /// kept as it was.
  int Moved[2] = {};
  /// The texels (x, y, width, height from the map's lower left) a map kept as it was draws again
  /// where casters changed (MapAction::Patch).
  std::vector<std::array<int, 4>> Patches;
#if CSM_COMPARISON_TECHNIQUES
  double Planes[16] = {}; ///< a face partition's 4 world half-spaces
  double DepthW = 0.0;    ///< a camera space map's smallest w (0: none)
#endif
  bool IsSceneFitted() const
  {
    return this->Kind == MapKind::SceneFitted;
  }
  bool IsMoved() const
  {
    return this->Moved[0] != 0 || this->Moved[1] != 0;
  }
};

/// A directional light's scene-fitted map (its one cascade, the base) refined by light-space
/// pages (csmPages.h): levels of half the texel of the level before, fixed in light space, of
/// which only the pages the view's visible samples read are drawn into the rest of the atlas
/// and kept while the light and the casters stay.
struct LightPages
{
  bool Active = false;                 ///< the light's maps are a base and its pages
  int Levels = 0;                      ///< levels finer than the base
  double BaseDepth = 0.0;              ///< view depth from which the base meets the error target
  double BaseTexels[2] = { 0.0, 0.0 }; ///< level 0's texels along s and t (csm::PageLevels)
  std::vector<float> Table;            ///< the page table, csm::PageCache::table's entries
  /// The pages this frame draws: level, column and row (csm::PageKey), the lower left of the
  /// slot (texels of the atlas).
  std::vector<std::array<int, 5>> Drawn;
  vtkSmartPointer<vtkTextureObject> TableTexture;
};

/// The maps of one shadowed light, as the shadow pass reads them.
struct LightMaps
{
  vtkLight* Light = nullptr;
  int LightIndex = -1; ///< index among the renderer's switched-on lights
  LightKind Kind = LightKind::Directional;
  double Position[3] = { 0, 0, 0 };   ///< transformed, as the maps were rendered for
  double FocalPoint[3] = { 0, 0, 0 }; ///< transformed, likewise
  double ConeAngle = 0.0;             ///< a spot light's (0 for a directional light)
  double SplitNear = 0.0;             ///< view depth where the first cascade begins
  std::vector<CascadeMap> Cascades;   ///< none: nothing to shadow this frame
  int AtlasSize[2] = { 0, 0 };        ///< texels of the atlas texture
  vtkSmartPointer<vtkTextureObject> Atlas;
  LightPages Pages; ///< Active: Cascades is the base, refined by these pages

  int GetNumberOfCascades() const { return static_cast<int>(this->Cascades.size()); }
#if CSM_COMPARISON_TECHNIQUES
  bool SelectedByPlanes() const
  {
    return !this->Cascades.empty() && this->Cascades[0].Kind == MapKind::FacePartition;
  }
#endif
};

/// What the last frame did, for tests and benchmarks (seconds only with MeasureTimes).
struct FrameStatistics
{
  int CascadesRendered = 0, CascadesKept = 0;
  int CascadesMoved = 0;   ///< kept maps moved with the view (counted as kept; their strips drawn)
  int CascadesPatched = 0; ///< kept maps whose changed casters' texels were drawn (counted as kept)
  int PropsDrawn = 0;      ///< props (or block actors) drawn into maps
  double TexelsRendered = 0.0, CellsDrawn = 0.0; ///< of the rendered maps
  int ClosedCasters = 0;                         ///< drawn with their exit layer only
  int CompactCasters = 0, BlocksDrawn = 0;       ///< casters from compact blocks, blocks drawn
  int PreparedBlocks = 0; ///< meshes prepared in compact blocks anew (not their points moved)
  int CastersWithoutReceivers = 0; ///< casters (or blocks) left out of a map
  bool VisibleDepthsUsed = false, VisibleDepthsMeasured = false; ///< measured in this frame
  bool VisibleFootprintUsed = false; ///< a light's cascades were fitted to the footprint
  bool ViewDepthDrawn = false;       ///< the view's depth was drawn (measured or not)
  /// Planned as the last frame: the same view, lights and props (colours, scalars and
  /// materials aside), every map kept as it was (csmLightPlanning::LastPlanStands).
  bool AsLastFrame = false;
  /// Planned as a frame of casters that change every frame: maps fitted to the view, no
  /// scene-fitted map (the second frame in a row with changed casters, a first one whose changes
  /// would draw a kept scene-fitted map whole, or the next change after a frame planned so; as
  /// SceneFittedCascades off).
  bool CastersChanging = false;
  /// Light-space pages (LightSpacePages): drawn this frame, read by this view, resident.
  int PagesDrawn = 0, PagesNeeded = 0, PagesResident = 0;
  /// Casters (or blocks) the visible-depth pass left out, small on the image for their
  /// triangles: their boxes stand in for their samples (csm::boxStandIn).
  int DepthPassStandIns = 0;
  double PlanSeconds = 0.0, MapSeconds = 0.0, ClearSeconds = 0.0, CombineSeconds = 0.0;
  double CascadeSeconds[MaximumCascades] = {};
  /// Per cascade, in a frame that is not interactive: the least error of a map kept from the
  /// last frame (as it was or moved) over the fresh map's that meets ErrorTarget
  /// (csm::keptMapError; at most 1 serves, or 1 / csm::kCountHysteresis where no map meets the
  /// target); 0 where no kept map was judged, +infinity where none covers the cascade.
  double KeptError[MaximumCascades] = {};
  double GetCascadeSeconds(int c) const
  {
    return c >= 0 && c < MaximumCascades ? this->CascadeSeconds[c] : 0.0;
  }
};
} // namespace vtkCascadedShadows

#endif
