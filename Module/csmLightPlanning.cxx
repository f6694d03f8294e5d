// SPDX-License-Identifier: BSD-3-Clause
#include "csmLightPlanning.h"

#include "csmAtlas.h" // csm::assignTiles, csm::kAtlasFullMaps
#include "csmBakerState.h"
#include "csmCasterCollection.h"
#include "csmMapDrawing.h"
#include "csmProps.h"
#include "csmReuse.h"
#include "csmVTKMath.h"

#include "vtkCamera.h"
#include "vtkCascadedShadowMapPlanner.h"
#include "vtkCommunicator.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMatrix4x4.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

using namespace vtkCascadedShadows; // LightMaps, CascadeMap, MapKind, MapAction, LightKind

namespace
{
constexpr int kMaxCascades = vtkCascadedShadowMapPlanner::MAXIMUM_NUMBER_OF_CASCADES;
// Border a kept map must have around the new body, in texels: none, as a freshly planned map,
// fitted to the body, has none either (the lookup clamps its taps to the map).
constexpr double kReuseMarginTexels = 0.0;

/// The base of a light refined by light-space pages, for maps of resolution texels a side: its
/// scene-fitted map as it serves alone (the planner's whole atlas of 2 x 2 tiles), so that a
/// view that comes close keeps that map as the base, and one that moves away keeps the pages.
int pageBaseSide(int resolution)
{
  return 2 * resolution;
}

/// Pages the pool of a paged light holds for a view of kPoolPixels, and in proportion for a
/// larger one, up to kMostPoolScale times as many: the pages a view reads depend on its pixels
/// and depths, not on Resolution (the towers' orbit at 640x480 needs up to 311 at once, and a
/// pool of 320 made it draw pages it had given up; at 1280x720 a pool of 416 held 375-416 of
/// them and drew pages again, Results.md, "Light-space pages"). The most, 1,664 pages, is
/// 436 MB of pool; a view whose pages do not fit takes the cascades.
constexpr int kPoolPages = 416;
constexpr double kPoolPixels = 640.0 * 480.0;
constexpr double kMostPoolScale = 4.0;

/// The atlas of such a light for a view of viewPixels, in whole pages: its base in the lower
/// left, the pool beside and above it. 3 x 3.5 Resolution where that holds the pool, with no
/// more rows above the base than the pool needs (at 4096, 12288 x 8192 texels: 402 MB where
/// 3 x 3.5 would be 704 MB); a square of base and pool where 3 x 3.5 is too small (a large view).
csm::MapSize pageAtlas(int resolution, double viewPixels)
{
  const auto pages = [](int texels) { return (texels + csm::kPageTexels - 1) / csm::kPageTexels; };
  const int base = pages(pageBaseSide(resolution));
  const double scale =
    std::isfinite(viewPixels) ? std::clamp(viewPixels / kPoolPixels, 1.0, kMostPoolScale) : 1.0;
  const int pool = static_cast<int>(std::ceil(scale * kPoolPages));
  const int all = base * base + pool;
  int columns = pages(3 * resolution);
  if (columns * pages(7 * resolution / 2) < all)
  {
    columns = std::max(columns, static_cast<int>(std::ceil(std::sqrt(double(all)))));
  }
  const int rows = std::max(base, (all + columns - 1) / columns);
  return csm::MapSize(columns * csm::kPageTexels, rows * csm::kPageTexels);
}

/// The pixels of the frame's view.
double viewPixels(const csmFramePlan& frame)
{
  return double(frame.ImageHeight) * double(frame.ImageHeight) * frame.Aspect;
}

/// Frames in a row with changed casters after which they count as changing every frame
/// (vtkCascadedShadowMapPlanner::SetCastersChanging): the second such frame, when a map kept
/// for the next one would be drawn again.
constexpr int kChangingFrames = 2;

/// Texels around a changed caster's image a kept map draws again (rasterization rounds a
/// triangle's edge to the texel centres it covers, never beyond the next texel).
constexpr int kPatchMarginTexels = 1;

/// Do the changed casters' boxes (each box's rectangle, with kPatchMarginTexels; rectangles that
/// gain merged, csm::mergeTexelRects) cover as many texels as a kept map has, so that it is drawn
/// whole? The rectangles are appended to patches where given.
bool ChangesDrawWhole(
  const csmFrameCasters& props, const CascadeMap& map, std::vector<csm::TexelRect>* patches)
{
  const csm::MapSize size(map.Resolution[0], map.Resolution[1]);
  const glm::dmat4 wsToClip = csmFromRowMajor(map.WorldToMap);
  std::vector<csm::TexelRect> rects;
  for (const std::array<double, 6>& box : props.Dirty)
  {
    rects.push_back(
      csm::boxTexels(wsToClip, csm::Bounds::fromMinMaxPairs(box.data()), size, kPatchMarginTexels));
  }
  double texels = 0.0;
  for (const csm::TexelRect& rect : csm::mergeTexelRects(std::move(rects)))
  {
    if (patches)
    {
      patches->push_back(rect);
    }
    texels += double(rect[2]) * double(rect[3]);
  }
  return texels >= double(size.width) * double(size.height);
}

/// Would the changed casters draw a kept scene-fitted map whole? Then this first frame of
/// changed casters is planned as one of casters that change every frame (maps fitted to the
/// view): a time series stepped one step at a time draws those, not the scene-fitted map, a step.
bool SceneFittedMapDrawnWhole(const csmFrameCasters& props, const std::vector<LightMaps>& kept)
{
  for (const LightMaps& maps : kept)
  {
    for (const CascadeMap& map : maps.Cascades)
    {
      if (map.IsSceneFitted() && ChangesDrawWhole(props, map, nullptr))
      {
        return true;
      }
    }
  }
  return false;
}

/// A map kept as it was where casters changed (props.Dirty; KeptMapServes keeps no other then):
/// the texels their boxes cover, drawn again (MapAction::Patch); drawn whole where they cover as
/// many texels as the map.
void PatchChangedCasters(const csmFrameCasters& props, CascadeMap& map)
{
  map.Patches.clear();
  if (ChangesDrawWhole(props, map, &map.Patches))
  {
    map.Patches.clear();
    map.Action = MapAction::Draw;
  }
  else if (!map.Patches.empty())
  {
    map.Action = MapAction::Patch;
  }
}

/// Calls shadowed(light, index) for each light of the renderer that gets maps this frame, in
/// order, with its index among the switched-on lights (the mappers number those only); returns
/// how many lights cast shadows (more than maximumLights: the others are not shadowed).
template <typename F>
int forEachShadowedLight(vtkRenderer* renderer, int maximumLights, F&& shadowed)
{
  int shadowingLights = 0;
  int lightIndex = 0;
  vtkCollectionSimpleIterator lit;
  renderer->GetLights()->InitTraversal(lit);
  while (vtkLight* light = renderer->GetLights()->GetNextLight(lit))
  {
    if (!light->GetSwitch())
    {
      continue;
    }
    const int index = lightIndex++;
    if (csmLightCastsShadows(light) && ++shadowingLights <= maximumLights)
    {
      shadowed(light, index);
    }
  }
  return shadowingLights;
}

/// A point light (positional, a cone of 90 degrees or more) casts no shadows: said once.
void reportPointLights(vtkRenderer* renderer, const csmLightPlanning::Reporter& report)
{
  vtkCollectionSimpleIterator lit;
  renderer->GetLights()->InitTraversal(lit);
  while (vtkLight* light = renderer->GetLights()->GetNextLight(lit))
  {
    if (report && light->GetSwitch() && light->GetPositional() && light->GetConeAngle() >= 90.0)
    {
      report(false,
        "A point light (positional, a cone angle of 90 degrees or more) casts no shadows; "
        "directional lights and spot lights of cones under 90 degrees do");
      return;
    }
  }
}

/// The entries of v in the order of `order` (an index past v: a default entry).
template <typename T>
void permuted(std::vector<T>& v, const std::vector<size_t>& order)
{
  std::vector<T> result(order.size());
  for (size_t s = 0; s < order.size(); ++s)
  {
    if (order[s] < v.size())
    {
      result[s] = std::move(v[order[s]]);
    }
  }
  v = std::move(result);
}

/// Each light shadowed this frame takes the slot it had the frame before (its maps, atlas, page
/// table and page cache), wherever it now is in the list of shadowed lights, so that a light
/// switched off or on does not make the others draw their maps again in another's atlas; a
/// light new to the list takes the slot (and the textures) of one that left it.
void alignSlots(vtkRenderer* renderer, int maximumLights, csmRendererMaps& state)
{
  std::vector<vtkLight*> lights;
  forEachShadowedLight(
    renderer, maximumLights, [&lights](vtkLight* light, int) { lights.push_back(light); });
  constexpr size_t none = std::numeric_limits<size_t>::max();
  const size_t last = state.Maps.size();
  std::vector<char> taken(last, 0);
  std::vector<size_t> order;
  for (vtkLight* light : lights)
  {
    size_t found = none;
    for (size_t j = 0; j < last && found == none; ++j)
    {
      found = !taken[j] && state.Maps[j].Light == light ? j : none;
    }
    if (found != none)
    {
      taken[found] = 1;
    }
    order.push_back(found);
  }
  size_t free = 0;
  for (size_t& o : order)
  {
    for (; o == none && free < last; ++free)
    {
      if (!taken[free])
      {
        taken[free] = 1;
        o = free;
      }
    }
  }
  for (size_t j = 0; j < last; ++j)
  {
    if (!taken[j])
    {
      order.push_back(j); // (released after the plan)
    }
  }
  bool identity = order.size() == last;
  for (size_t s = 0; identity && s < order.size(); ++s)
  {
    identity = order[s] == s;
  }
  if (identity)
  {
    return;
  }
  permuted(state.Maps, order);
  permuted(state.AtlasPool, order);
  permuted(state.PageTablePool, order);
  permuted(state.PageCaches, order);
  for (vtkSmartPointer<vtkTextureObject>& atlas : state.AtlasPool)
  {
    atlas = atlas ? atlas : vtkSmartPointer<vtkTextureObject>::New();
  }
}

/// A light's maps before they are planned: the light as they are rendered for.
LightMaps lightMapsOf(vtkLight* light, int index)
{
  LightMaps maps;
  maps.Light = light;
  maps.LightIndex = index;
  maps.Kind = light->GetPositional() ? LightKind::Spot : LightKind::Directional;
  light->GetTransformedPosition(maps.Position);
  light->GetTransformedFocalPoint(maps.FocalPoint);
  maps.ConeAngle = light->GetPositional() ? light->GetConeAngle() : 0.0;
  return maps;
}
}

csmLightPlanning::csmLightPlanning(vtkCascadedShadowMapPlanner* planner,
  const BakerOptions& options, vtkMultiProcessController* controller, FrameStatistics& statistics,
  Reporter report)
  : Planner(planner)
  , Options(options)
  , Controller(controller)
  , Statistics(statistics)
  , Report(std::move(report))
{
}

bool csmLightPlanning::Distributed() const
{
  return this->Controller && this->Controller->GetNumberOfProcesses() > 1;
}

bool csmLightPlanning::LastPlanStands(vtkRenderer* renderer, vtkOpenGLRenderWindow* window,
  const csmRendererMaps& state, const csmFrameCasters& props, int maximumLights) const
{
  const double aspect = renderer->GetTiledAspectRatio();
  if (props.Changed || !props.Dirty.empty() || this->Distributed() || !state.LastCamera ||
    state.Maps.empty() || state.LastAspect != aspect ||
    state.LastInteracting != csmIsInteracting(window) ||
    !sameView(state.LastCamera, renderer->GetActiveCamera(), aspect))
  {
    return false;
  }
  size_t slot = 0;
  bool same = true;
  const int shadowingLights = forEachShadowedLight(renderer, maximumLights,
    [&](vtkLight* light, int index)
    {
      same = same && slot < state.Maps.size() && state.Maps[slot].Light == light &&
        state.Maps[slot].LightIndex == index &&
        sameLightGeometry(state.Maps[slot], lightMapsOf(light, index));
      ++slot;
    });
  return same && slot == state.Maps.size() && shadowingLights == state.LastShadowingLights;
}

int csmLightPlanning::PlanLights(vtkRenderer* renderer, vtkOpenGLRenderWindow* window,
  csmRendererMaps& state, const csmFrameCasters& props, int maximumLights, bool asLastFrame,
  std::vector<LightMaps>& planned)
{
  if (asLastFrame)
  {
    planned = state.Maps;
    for (LightMaps& maps : planned)
    {
      for (CascadeMap& map : maps.Cascades)
      {
        map.Action = MapAction::Keep;
        map.Patches.clear();
        map.Moved[0] = map.Moved[1] = 0;
      }
      maps.Pages.Drawn.clear();
    }
    this->Statistics.AsLastFrame = true;
    this->Statistics.VisibleDepthsUsed = state.LastPlanStatistics.VisibleDepthsUsed;
    this->Statistics.VisibleFootprintUsed = state.LastPlanStatistics.VisibleFootprintUsed;
    std::copy(std::begin(state.LastPlanStatistics.KeptError),
      std::end(state.LastPlanStatistics.KeptError), std::begin(this->Statistics.KeptError));
    state.CastersChangedFrames = 0;
    return state.LastShadowingLights;
  }
  props.FeedPlanner(this->Planner);
  state.CastersChangedFrames = props.Dirty.empty() ? 0 : state.CastersChangedFrames + 1;
  this->Statistics.CastersChanging = state.CastersChangedFrames >= kChangingFrames ||
    (state.CastersChangedFrames == 1 &&
      (state.PlannedAsChanging || SceneFittedMapDrawnWhole(props, state.Maps)));
  state.PlannedAsChanging = this->Statistics.CastersChanging;
  this->Planner->SetCastersChanging(this->Statistics.CastersChanging);
  // Plan every shadowed light for this frame, and decide per cascade whether the map kept from
  // an earlier frame still serves (only the camera moved, it covers, its error is bounded).
  // While the user interacts (VTK's convention: the interactor raises the window's desired
  // update rate), maps get a border and may be kept within MapReuseTolerance; a still frame
  // keeps a map while its error at this view meets what a fresh map would (MapSlack).
  csmFramePlan frame;
  frame.Interacting = csmIsInteracting(window);
  frame.Border = frame.Interacting ? this->Options.InteractiveMapBorder : 0.0;
  // (The tolerance is against a fresh map with the same border, whose error is 1 + 2 border
  // times a tight one's.)
  frame.Tolerance = this->Options.MapReuseTolerance * (1.0 + 2.0 * frame.Border);
  // Tubes, spheres, wide lines and big points are drawn into the maps as wide as the main view
  // draws them: a still frame keeps such a map only for the view it was sized for.
  frame.ScreenSized = props.ScreenSized;
  // Kept maps move with the view where the GL copies between images (GL 4.3) and one process
  // draws the maps (each would move its own).
  frame.MoveMaps =
    this->Options.MoveKeptMaps && (GLEW_VERSION_4_3 || GLEW_ARB_copy_image) && !this->Distributed();
  // Resolution from need (ErrorTarget), up to the ceiling of this kind of frame; more cascades
  // than fill the atlas with full maps only in a still frame (each is a caster pass; they
  // refine the error where four full maps cannot reach ErrorTarget).
  frame.Ceiling = frame.Interacting
    ? std::min(this->Options.InteractiveResolution, this->Options.Resolution)
    : this->Options.Resolution;
  frame.MostCascades = frame.Interacting ? csm::kAtlasFullMaps : 0;
  frame.ImageHeight = static_cast<int>(
    std::lround(renderer->GetSize()[1] * csmWindowCentreScale(renderer->GetActiveCamera())));
  frame.Aspect = renderer->GetTiledAspectRatio();
  frame.Changed = props.Changed;
  frame.CastersChanged = !props.Dirty.empty();
  csmMapDrawing::MainView(renderer, renderer->GetActiveCamera(), frame.ViewKey);
  this->FeedVisibleDepths(renderer, window, state, props);
  alignSlots(renderer, maximumLights, state);
  const int shadowingLights = forEachShadowedLight(renderer, maximumLights,
    [&](vtkLight* light, int index)
    { this->PlanLight(renderer, state, props, frame, light, index, planned); });
  reportPointLights(renderer, this->Report);
  if (!state.LastCamera)
  {
    state.LastCamera = vtkSmartPointer<vtkCamera>::New();
  }
  state.LastCamera->DeepCopy(renderer->GetActiveCamera());
  state.LastAspect = frame.Aspect;
  state.LastInteracting = frame.Interacting;
  state.LastShadowingLights = shadowingLights;
  state.LastPlanStatistics = this->Statistics;
  if (this->Distributed())
  {
    this->DrawWhereAnyProcessDraws(planned);
  }
  // Textures only for the lights that cast shadows now.
  for (size_t i = planned.size(); i < state.AtlasPool.size(); ++i)
  {
    state.AtlasPool[i]->ReleaseGraphicsResources(window);
  }
  state.AtlasPool.resize(planned.size());
  for (size_t i = planned.size(); i < state.PageTablePool.size(); ++i)
  {
    if (state.PageTablePool[i]) // (a slot that had no pages)
    {
      state.PageTablePool[i]->ReleaseGraphicsResources(window);
    }
  }
  state.PageTablePool.resize(std::min(state.PageTablePool.size(), planned.size()));
  state.PageCaches.resize(std::min(state.PageCaches.size(), planned.size()));
  return shadowingLights;
}

void csmLightPlanning::PlanLight(vtkRenderer* renderer, csmRendererMaps& state,
  const csmFrameCasters& props, const csmFramePlan& frame, vtkLight* light, int index,
  std::vector<LightMaps>& planned)
{
  vtkCamera* camera = renderer->GetActiveCamera();
  const size_t slot = planned.size();
  LightMaps maps = lightMapsOf(light, index);
  const int count = std::min(kMaxCascades,
    this->Planner->Plan(camera, frame.Aspect, light, props.SceneBounds, frame.ImageHeight,
      frame.Ceiling, frame.MostCascades));
  this->Statistics.VisibleDepthsUsed =
    this->Statistics.VisibleDepthsUsed || this->Planner->GetVisibleDepthsUsed();
  this->Statistics.VisibleFootprintUsed =
    this->Statistics.VisibleFootprintUsed || this->Planner->GetVisibleFootprintUsed();
  if (this->Planner->GetAtlasShrunk())
  {
    this->Report(false,
      "Shadow map tiles of " + std::to_string(this->Options.Resolution) +
        " texels exceed the GL's texture size limit; the tiles are smaller");
  }
  this->Planner->GetAtlasSize(maps.AtlasSize);
  maps.Cascades.resize(static_cast<size_t>(std::max(count, 0)));
  const MapKind followKind = this->PlannedMapKind(light);
  // The maps kept from the last frame (only the camera moved: the light, the scene, the options
  // and the atlas are the same). (Face partitions and camera space maps are re-rendered every
  // frame: their error is not measured along the cascades' map axes.)
  const LightMaps* kept = !frame.Changed && this->Planner->GetDepthClamp() &&
      followKind == MapKind::FollowsView && slot < state.Maps.size() &&
      state.Maps[slot].Light == light && sameLightGeometry(state.Maps[slot], maps) &&
      std::equal(state.Maps[slot].AtlasSize, state.Maps[slot].AtlasSize + 2, maps.AtlasSize)
    ? &state.Maps[slot]
    : nullptr;
  // Slack pays only where the next frames can keep the map: a still frame of a camera on a
  // smooth path, the light and scene unchanged (a camera light moves with the camera).
  const bool smoothPath = !frame.Interacting && kept && count > 0;
  std::vector<csm::TexelRect> tiles(static_cast<size_t>(std::max(count, 0)));
  std::vector<csmCascadeNeed> needs(tiles.size());
  std::vector<int> order; // the scene-fitted cascades first: they cost most to draw again
  for (int c = 0; c < count; ++c)
  {
    CascadeMap& map = maps.Cascades[c];
    map.Kind = this->Planner->GetCascadeSceneFitted(c) ? MapKind::SceneFitted : followKind;
    this->PlanCascade(frame, camera, state, c, smoothPath, map, needs[c]);
    std::copy(map.Tile, map.Tile + 4, tiles[c].begin());
    order.insert(map.IsSceneFitted() ? order.begin() : order.end(), c);
  }
  // The kept maps where they serve, also across a change of the count (then in the tile they
  // are in), except with several processes (each would choose its own tiles).
  std::vector<csm::TexelRect> keptTiles;
  for (int k = 0; kept && k < kept->GetNumberOfCascades(); ++k)
  {
    const int* tile = kept->Cascades[k].Tile;
    keptTiles.push_back({ tile[0], tile[1], tile[2], tile[3] });
  }
  // (What serves for cascade c: kept map k as it was, or moved with the view.)
  std::map<std::pair<int, int>, CascadeMap> serving;
  const csm::TileAssignment assigned = csm::assignTiles(
    tiles, keptTiles,
    [&](int c, int k)
    {
      CascadeMap candidate;
      if (!this->KeptMapServes(frame, c, needs[c], maps.Cascades[c], kept->Cascades[k], candidate))
      {
        return false;
      }
      serving[{ c, k }] = candidate;
      return true;
    },
    order, !this->Distributed());
  for (int c = 0; c < count; ++c)
  {
    CascadeMap& map = maps.Cascades[c];
    std::copy(assigned.tile[c].begin(), assigned.tile[c].end(), map.Tile);
    map.Action = MapAction::Draw;
    if (assigned.kept[c] >= 0)
    {
      const CascadeMap& old = serving.at({ c, assigned.kept[c] });
      std::copy(old.WorldToMap, old.WorldToMap + 16, map.WorldToMap);
      std::copy(old.CasterView, old.CasterView + 18, map.CasterView);
      std::copy(old.Resolution, old.Resolution + 2, map.Resolution);
      std::copy(old.Moved, old.Moved + 2, map.Moved);
      map.Action = map.IsMoved() ? MapAction::Move : MapAction::Keep;
      if (map.Action == MapAction::Keep)
      {
        PatchChangedCasters(props, map);
      }
    }
  }
  if (count > 0)
  {
    maps.SplitNear = this->Planner->GetCascadeNear(0);
  }
  this->ServeWithPages(renderer, state, props, frame, slot, maps);
  if (state.AtlasPool.size() <= slot)
  {
    state.AtlasPool.push_back(vtkSmartPointer<vtkTextureObject>::New());
  }
  maps.Atlas = state.AtlasPool[slot];
  planned.push_back(std::move(maps));
}

void csmLightPlanning::ServeWithPages(vtkRenderer* renderer, csmRendererMaps& state,
  const csmFrameCasters& props, const csmFramePlan& frame, size_t slot, LightMaps& maps)
{
  // Pages where the cascades would follow the view of a scene light (its one scene-fitted map
  // already serves the whole view with all of the atlas; the pages refine that map, so not
  // where scene-fitted maps are off), the casters stay and are not sized on the screen, every
  // receiver is in the view's depth buffer, the view is a perspective one about its axis (the
  // samples are read back through it) and the atlas holds a base and its pool; marked from this
  // view's samples (the depth pass keeps them where
  // LightSpacePages is on).
  vtkCamera* camera = renderer->GetActiveCamera();
  const int side = this->Options.Resolution;
  const bool followsView = std::any_of(maps.Cascades.begin(), maps.Cascades.end(),
    [](const CascadeMap& map) { return map.Kind == MapKind::FollowsView; });
  const bool sceneFittedAlone = maps.Cascades.size() == 1 && maps.Cascades[0].IsSceneFitted();
  const bool otherKinds = std::any_of(maps.Cascades.begin(), maps.Cascades.end(),
    [](const CascadeMap& map)
    { return map.Kind != MapKind::FollowsView && map.Kind != MapKind::SceneFitted; });
  const int textureLimit = this->Planner->GetMaximumTextureSize();
  const csm::MapSize atlas = pageAtlas(side, viewPixels(frame));
  // (Casters that changed: only where the last frame's maps were this light's pages, which the
  // changes patch, and not every frame. A light paged in the last frame stays paged where its
  // scene-fitted map alone would serve: that map is the base, and the pages are kept.)
  const bool lastPaged = slot < state.Maps.size() && state.Maps[slot].Pages.Active &&
    state.Maps[slot].Light == maps.Light;
  const bool serve = this->Options.LightSpacePages && !this->Distributed() &&
    this->Planner->GetSceneFittedCascades() && (followsView || (sceneFittedAlone && lastPaged)) &&
    !otherKinds && maps.Kind == LightKind::Directional && maps.Light->LightTypeIsSceneLight() &&
    (!frame.CastersChanged || (lastPaged && !this->Statistics.CastersChanging)) &&
    !frame.ScreenSized && !props.TranslucentReceivers && !camera->GetParallelProjection() &&
    csmCameraOnAxis(camera) && this->Planner->GetDepthClamp() &&
    csm::poolSlots(atlas, pageBaseSide(side)) > 0 &&
    (textureLimit <= 0 || std::max(atlas.width, atlas.height) <= textureLimit);
  if (serve && state.VisibleCamera && !state.VisibleSamples.isEmpty() &&
    sameView(state.VisibleCamera, camera, frame.Aspect))
  {
    this->PlanPages(state, props, frame, slot, maps);
  }
}

bool csmLightPlanning::PageNeeds(const csmRendererMaps& state, const csmFramePlan& frame,
  const double worldToBase[16], int baseSide, int slots, csm::PageLevels& levels,
  std::vector<csm::PageKey>& needed) const
{
  // The levels from this view's pixel and nearest sample; the pages its samples read.
  vtkCamera* camera = state.VisibleCamera; // this very view
  const double* clip = camera->GetClippingRange();
  const glm::dmat4 viewToClip =
    csmFromRowMajor(camera->GetProjectionTransformMatrix(frame.Aspect, -1, 1)->GetData());
  const glm::dmat4 worldToView = csmFromRowMajor(camera->GetModelViewTransformMatrix()->GetData());
  const double pixel = 2.0 / (std::max(frame.ImageHeight, 1) * viewToClip[1][1]);
  const double nearest =
    csm::viewDepthFromWindowDepth(state.VisibleWindow[0], clip[0], clip[1], false);
  const glm::dmat4 wsToBase = csmFromRowMajor(worldToBase);
  const glm::dmat4 windowToBase = csm::windowToBase(wsToBase, viewToClip * worldToView);
  const csm::DepthSamples& samples = state.VisibleSamples;
  // At csm::kPageErrorShare of the target where the pool holds those pages, else at the target
  // (the same pages: a level's texels do not depend on the depths it serves).
  for (const double share : { csm::kPageErrorShare, 1.0 })
  {
    if (csm::pageLevels(wsToBase, csm::MapSize(baseSide), pixel,
          share * this->Planner->GetErrorTarget(), nearest, levels) &&
      csm::markPages(levels, windowToBase, clip[0], clip[1], samples.windowDepths.data(),
        samples.width, samples.height, samples.standIns, static_cast<size_t>(slots), needed))
    {
      return true;
    }
  }
  return false;
}

void csmLightPlanning::PlanPages(csmRendererMaps& state, const csmFrameCasters& props,
  const csmFramePlan& frame, size_t slot, LightMaps& maps)
{
  // The base: the scene-fitted map as it serves alone, in the lower left of the atlas, fixed
  // while the scene and the light stay; the pages refine it where the view needs finer texels.
  // Where the pages this view needs do not fit, or need more levels than there are, the
  // cascades serve.
  const csm::MapSize atlas = pageAtlas(this->Options.Resolution, viewPixels(frame));
  const int side = pageBaseSide(this->Options.Resolution);
  const double direction[3] = { maps.FocalPoint[0] - maps.Position[0],
    maps.FocalPoint[1] - maps.Position[1], maps.FocalPoint[2] - maps.Position[2] };
  double worldToBase[16];
  csm::PageLevels levels;
  std::vector<csm::PageKey> needed;
  const int slots = csm::poolSlots(atlas, side);
  if (!this->Planner->GetSceneFittedMatrix(direction, props.SceneBounds, worldToBase) ||
    !this->PageNeeds(state, frame, worldToBase, side, slots, levels, needed))
  {
    return;
  }
  // The base is kept where the last frame's maps of this light were this very map in this
  // texture: its base, or its scene-fitted map alone (the atlas grows around it, keeping its
  // texels); the pool keeps its pages where they were its base's.
  const LightMaps* last = slot < state.Maps.size() ? &state.Maps[slot] : nullptr;
  const bool sameMap = !frame.Changed && last && last->Light == maps.Light &&
    sameLightGeometry(*last, maps) && last->Cascades.size() == 1 &&
    last->Cascades[0].IsSceneFitted() && last->Cascades[0].Tile[0] == 0 &&
    last->Cascades[0].Tile[1] == 0 && last->Cascades[0].Resolution[0] == side &&
    last->Cascades[0].Resolution[1] == side &&
    std::equal(worldToBase, worldToBase + 16, last->Cascades[0].WorldToMap) &&
    slot < state.AtlasPool.size() && state.AtlasPool[slot]->GetHandle() &&
    state.AtlasPool[slot]->GetContext() == state.Window;
  const bool keep = sameMap && last->Pages.Active && last->AtlasSize[0] == atlas.width &&
    last->AtlasSize[1] == atlas.height;
  CascadeMap base;
  base.Kind = MapKind::SceneFitted;
  base.Action = sameMap ? MapAction::Keep : MapAction::Draw;
  std::copy(worldToBase, worldToBase + 16, base.WorldToMap);
  base.Tile[2] = base.Tile[3] = base.Resolution[0] = base.Resolution[1] = side;
  base.SplitFar = maps.Cascades.back().SplitFar;
  if (sameMap && frame.CastersChanged)
  {
    // The base's texels the changed casters' boxes cover drawn again (or all of it).
    PatchChangedCasters(props, base);
  }
  maps.Cascades.assign(1, base);
  if (needed.empty() && !(last && last->Pages.Active))
  {
    // No page needed yet: the base serves alone, in an atlas of its own size, as the
    // scene-fitted map alone does (the atlas grows around it when a page is needed: that
    // allocation costs a frame).
    maps.AtlasSize[0] = maps.AtlasSize[1] = side;
    return;
  }
  if (state.PageCaches.size() <= slot)
  {
    state.PageCaches.resize(slot + 1);
  }
  csm::PageCache& cache = state.PageCaches[slot];
  if (!keep)
  {
    cache.reset(slots);
  }
  if (sameMap && frame.CastersChanged)
  {
    // The pages the changed casters' boxes reach across the light given up (drawn again where
    // this view needs them).
    const glm::dmat4 wsToBase = csmFromRowMajor(worldToBase);
    cache.forget(
      [&](const csm::PageKey& page)
      {
        return base.Action == MapAction::Draw ||
          std::any_of(props.Dirty.begin(), props.Dirty.end(),
            [&](const std::array<double, 6>& box) {
              return csm::pageReachesBox(
                wsToBase, levels, page, csm::Bounds::fromMinMaxPairs(box.data()));
            });
      });
  }
  std::vector<std::pair<csm::PageKey, int>> fresh;
  cache.place(needed, fresh);
  maps.AtlasSize[0] = atlas.width;
  maps.AtlasSize[1] = atlas.height;
  LightPages& pages = maps.Pages;
  pages.Active = true;
  pages.Levels = levels.count;
  pages.BaseDepth = levels.baseDepth;
  pages.BaseTexels[0] = levels.baseTexels.x;
  pages.BaseTexels[1] = levels.baseTexels.y;
  const auto place = [atlas, side](int s) { return csm::poolSlotPlace(atlas, side, s); };
  cache.table(std::max(levels.count, 1), needed, place, pages.Table);
  for (const auto& page : fresh)
  {
    const glm::ivec2 at = place(page.second) * csm::kPageTexels;
    pages.Drawn.push_back({ page.first.level, page.first.x, page.first.y, at.x, at.y });
  }
  this->Statistics.PagesDrawn += static_cast<int>(fresh.size());
  this->Statistics.PagesNeeded += static_cast<int>(needed.size());
  this->Statistics.PagesResident += cache.resident();
}

MapKind csmLightPlanning::PlannedMapKind(vtkLight* light) const
{
#if CSM_COMPARISON_TECHNIQUES
  if (!light->GetPositional() && this->Planner->GetCascadesSelectedByPlanes())
  {
    return MapKind::FacePartition;
  }
  return this->Planner->GetCameraSpace() ? MapKind::CameraSpace : MapKind::FollowsView;
#else
  (void)light;
  return MapKind::FollowsView;
#endif
}

void csmLightPlanning::PlanCascade(const csmFramePlan& frame, vtkCamera* camera,
  const csmRendererMaps& state, int c, bool smoothPath, CascadeMap& map, csmCascadeNeed& need)
{
  // The map this cascade needs (ErrorTarget) in its tile of the planned atlas.
  this->Planner->GetCascadeTile(c, map.Tile);
  int ceiling[2];
  this->Planner->GetCascadeResolutionCeiling(c, ceiling);
  this->Planner->GetCascadeResolution(
    c, frame.ImageHeight, ResolutionStep, ceiling, map.Resolution);
  need.Texels[0] = map.Resolution[0];
  need.Texels[1] = map.Resolution[1];
  this->Planner->GetCascadeResolution(c, frame.ImageHeight, 1, ceiling, need.TargetTexels);
  need.TargetOutOfReach =
    this->Planner->GetCascadeErrorTargetOutOfReach(c, frame.ImageHeight, ceiling);
  const csm::MapSize most(ceiling[0], ceiling[1]);
  // A still frame's map that follows the view gets slack (a border and more texels), so that
  // the next frames of a camera that moves a little keep it while it meets what a fresh map
  // would (csm::slackedMap, csm::keptMapServes). Not for screen-sized casters, whose maps serve
  // only the view they were sized for. (Judged per cascade: a step that moves a near cascade's
  // small body out of any border may leave a far one's well inside.)
  double border = frame.Border;
  if (smoothPath && !frame.ScreenSized && map.Kind == MapKind::FollowsView &&
    csmIsSmallCameraStep(state.LastCamera, camera, frame.Aspect, this->Planner->GetCascadeFar(c)))
  {
    const csm::SlackedMap slacked =
      csm::slackedMap(csm::MapSize(need.Texels[0], need.Texels[1]), most, this->Options.MapSlack);
    border = slacked.border;
    map.Resolution[0] = slacked.size.width;
    map.Resolution[1] = slacked.size.height;
  }
  for (int axis = 0; axis < 2; ++axis)
  {
    map.Resolution[axis] = std::max(1, std::min(map.Resolution[axis], map.Tile[2 + axis]));
  }
  map.Turned = this->Planner->GetCascadeMapTurned(c);
  vtkNew<vtkMatrix4x4> m;
  this->Planner->GetCascadeMatrix(c, m, border, map.Resolution);
  std::copy(m->GetData(), m->GetData() + 16, map.WorldToMap);
  map.SplitFar = this->Planner->GetCascadeFar(c);
#if CSM_COMPARISON_TECHNIQUES
  this->Planner->GetCascadePlanes(c, map.Planes);
  map.DepthW = this->Planner->GetCascadeDepthW(c);
#endif
}

bool csmLightPlanning::KeptMapServes(const csmFramePlan& frame, int c, const csmCascadeNeed& need,
  const CascadeMap& map, const CascadeMap& old, CascadeMap& moved)
{
  // A kept map serves if it has the texels this view needs (or all its tile holds, where the
  // GL's texture size limit made the tiles smaller than Resolution): while the user interacts,
  // within MapReuseTolerance of a fresh map with the same border; in a still frame, where its
  // error at this view meets ErrorTarget (what a fresh map of the fewest texels that meet it
  // meets; fresh maps get whole steps of ResolutionStep more), or comes within the cascade
  // count's hysteresis of a fresh map where no map meets ErrorTarget (csm::keptMapServes).
  // (Turned the same way: the error ratio compares the maps at equal resolution.) (Of the same
  // kind; its tile is assignTiles' to choose.) Where casters changed, only a map planned as it
  // was serves, its changed texels drawn again: the frame is then the one a fresh map gives.
  if ((!frame.Interacting && frame.ScreenSized &&
        !std::equal(frame.ViewKey, frame.ViewKey + 18, old.CasterView)) ||
    old.Turned != map.Turned || old.Kind != map.Kind)
  {
    return false;
  }
  if (frame.CastersChanged)
  {
    moved = old;
    return !old.IsMoved() && std::equal(old.WorldToMap, old.WorldToMap + 16, map.WorldToMap) &&
      std::equal(old.Resolution, old.Resolution + 2, map.Resolution);
  }
  auto serves = [&](const double* worldToMap)
  {
    const double ratio = this->Planner->CompareKeptMap(
      c, worldToMap, kReuseMarginTexels, std::min(old.Resolution[0], old.Resolution[1]));
    if (frame.Interacting)
    {
      return old.Resolution[0] >= std::min(map.Resolution[0], map.Tile[2]) &&
        old.Resolution[1] >= std::min(map.Resolution[1], map.Tile[3]) && ratio <= frame.Tolerance;
    }
    const csm::MapSize keptSize(old.Resolution[0], old.Resolution[1]);
    const csm::MapSize tight(
      std::min(need.TargetTexels[0], map.Tile[2]), std::min(need.TargetTexels[1], map.Tile[3]));
    if (c >= 0 && c < kMaxCascades)
    {
      double& least = this->Statistics.KeptError[c];
      const double error = csm::keptMapError(ratio, keptSize, tight);
      least = least == 0.0 ? error : std::min(least, error);
    }
    return csm::keptMapServes(ratio, keptSize, tight, need.TargetOutOfReach);
  };
  moved = old;
  moved.Moved[0] = moved.Moved[1] = 0;
  if (serves(old.WorldToMap))
  {
    return true;
  }
  // Where it no longer serves as it is, the map moved with the view by whole texels (its
  // content shifted, the strips that came in drawn): judged at this view like any kept map.
  // (Not a map of screen-sized casters, sized for one view only.)
  return frame.MoveMaps && !frame.ScreenSized && old.Kind == MapKind::FollowsView &&
    this->Planner->PanKeptMap(c, old.WorldToMap, old.Resolution, moved.WorldToMap, moved.Moved) &&
    serves(moved.WorldToMap);
}

void csmLightPlanning::FeedVisibleDepths(vtkRenderer* renderer, vtkOpenGLRenderWindow* window,
  csmRendererMaps& state, const csmFrameCasters& props)
{
  // The visible depths of this view (VisibleDepthFit; MeasureVisibleDepths).
  if (this->Options.VisibleDepthFit && !this->Distributed() && state.VisibleCamera)
  {
    this->Planner->SetVisibleDepths(
      state.VisibleCamera, state.VisibleAspect, state.VisibleWindow[0], state.VisibleWindow[1]);
    // Where on the image (VisibleFootprintFit): the depth pass draws the casters, so not where
    // a receiver without opaque geometry may lie outside it; and its pixels are the camera's
    // whole image only for an on-axis camera drawn in one tile (not a magnified screenshot's
    // tiles, not an off-axis or shifted projection).
    vtkCamera* camera = renderer->GetActiveCamera();
    const double* tile = window->GetTileViewport();
    const bool wholeImage = window->GetTileScale()[0] == 1 && window->GetTileScale()[1] == 1 &&
      tile[0] == 0.0 && tile[1] == 0.0 && tile[2] == 1.0 && tile[3] == 1.0 &&
      csmCameraOnAxis(camera);
    this->Planner->SetVisibleFootprint(
      this->Options.VisibleFootprintFit && !props.TranslucentReceivers && wholeImage
        ? &state.VisibleFootprint
        : nullptr);
  }
  else
  {
    this->Planner->ClearVisibleDepths();
  }
}

void csmLightPlanning::DrawWhereAnyProcessDraws(std::vector<LightMaps>& planned)
{
  // One process's draw is every process's: the maps are combined across them. (Kept maps do
  // not move with several processes.)
  std::vector<int> draw(kMaxCascades * planned.size(), 0), any(draw.size(), 0);
  for (size_t slot = 0; slot < planned.size(); ++slot)
  {
    for (int c = 0; c < planned[slot].GetNumberOfCascades(); ++c)
    {
      draw[kMaxCascades * slot + c] = planned[slot].Cascades[c].Action != MapAction::Keep ? 1 : 0;
    }
  }
  this->Controller->AllReduce(
    draw.data(), any.data(), static_cast<vtkIdType>(draw.size()), vtkCommunicator::MAX_OP);
  for (size_t slot = 0; slot < planned.size(); ++slot)
  {
    for (int c = 0; c < planned[slot].GetNumberOfCascades(); ++c)
    {
      if (any[kMaxCascades * slot + c] != 0)
      {
        planned[slot].Cascades[c].Action = MapAction::Draw;
      }
    }
  }
}
