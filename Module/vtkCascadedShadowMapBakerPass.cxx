// SPDX-License-Identifier: BSD-3-Clause
#include "vtkCascadedShadowMapBakerPass.h"

#include "csmAtlas.h" // csm::kAtlasFullMaps
#include "csmBakerState.h"
#include "csmCasterCollection.h"
#include "csmMapDrawing.h"
#include "csmReportOnce.h"
#include "csmReuse.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCascadedShadowMapPlanner.h"
#include "vtkCommunicator.h"
#include "vtkInformation.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMatrix4x4.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLError.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLRenderer.h"
#include "vtkOpenGLState.h"
#include "vtkPropCollection.h"
#include "vtkProperty.h"
#include "vtkRenderState.h"
#include "vtkTextureObject.h"
#include "vtkTextureUnitManager.h"
#include "vtk_glew.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <utility>

vtkStandardNewMacro(vtkCascadedShadowMapBakerPass);
vtkCxxSetObjectMacro(vtkCascadedShadowMapBakerPass, Controller, vtkMultiProcessController);

namespace
{
constexpr int kMaxCascades = vtkCascadedShadowMapPlanner::MAXIMUM_NUMBER_OF_CASCADES;
// Frames per second from which the window's desired update rate means "interacting" (the
// interactor's default is 15, its still rate 0.0001).
constexpr double kInteractiveUpdateRate = 1.0;
// Border a kept map must have around the new body, in texels: none, as a freshly planned map,
// fitted to the body, has none either (the lookup clamps its taps to the map).
constexpr double kReuseMarginTexels = 0.0;
// Texture units of the fragment shader left to the mapper's own textures (colour, normal,
// ORM, emissive and anisotropy maps, and PBR's irradiance, prefiltered and BRDF maps).
constexpr int kMapperTextureUnits = 8;
// Fragment uniform components one shadowed light costs: per cascade a mat4, a vec4 and two
// floats (padded to vec4s), and the per-light values; face partitions add 4 planes a cascade.
constexpr int kUniformComponentsPerLight = kMaxCascades * (16 + 4 + 4 + 4) + 16;
constexpr int kFacePlaneComponentsPerLight = kMaxCascades * 16;
constexpr int kMapperUniformComponents = 1024;

}

vtkCascadedShadowMapBakerPass::vtkCascadedShadowMapBakerPass()
  : Planner(vtkSmartPointer<vtkCascadedShadowMapPlanner>::New())
  , Casters(std::make_unique<csmCasterCollection>())
  , Drawing(std::make_unique<csmMapDrawing>())
{
}

vtkCascadedShadowMapBakerPass::~vtkCascadedShadowMapBakerPass()
{
  this->SetController(nullptr);
}

bool vtkCascadedShadowMapBakerPass::Distributed() const
{
  return this->Controller && this->Controller->GetNumberOfProcesses() > 1;
}

void vtkCascadedShadowMapBakerPass::CombineAcrossProcesses(vtkTextureObject* atlas)
{
  // Every process drew its own casters; the nearest depth of all is the map of the whole scene.
  const auto start = std::chrono::steady_clock::now();
  const vtkIdType size = static_cast<vtkIdType>(atlas->GetWidth()) * atlas->GetHeight();
  std::vector<float> local(size), global(size);
  atlas->Activate();
  glGetTexImage(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT, GL_FLOAT, local.data());
  this->Controller->AllReduce(local.data(), global.data(), size, vtkCommunicator::MIN_OP);
  glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, static_cast<GLsizei>(atlas->GetWidth()),
    static_cast<GLsizei>(atlas->GetHeight()), GL_DEPTH_COMPONENT, GL_FLOAT, global.data());
  atlas->Deactivate();
  this->Statistics.CombineSeconds +=
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

bool vtkCascadedShadowMapBakerPass::LightCastsShadows(vtkLight* light)
{
  return light && light->GetSwitch() && !light->LightTypeIsHeadlight() &&
    (!light->GetPositional() || light->GetConeAngle() < 90.0) &&
    light->GetShadowAttenuation() > 0.0f; // a shadow of attenuation 0 is invisible: no maps
}

csmRendererMaps& vtkCascadedShadowMapBakerPass::MapsOf(
  vtkRenderer* renderer, vtkOpenGLRenderWindow* window)
{
  // Forget renderers that are gone (their textures free themselves with their context).
  this->Renderers.erase(std::remove_if(this->Renderers.begin(), this->Renderers.end(),
                          [](const std::unique_ptr<csmRendererMaps>& r) { return !r->Renderer; }),
    this->Renderers.end());
  for (auto& entry : this->Renderers)
  {
    csmRendererMaps& state = *entry;
    if (state.Renderer == renderer)
    {
      if (state.Window != window)
      {
        state = csmRendererMaps(); // moved to another context: start afresh
        state.Renderer = renderer;
        state.Window = window;
      }
      return state;
    }
  }
  auto state = std::make_unique<csmRendererMaps>();
  state->Renderer = renderer;
  state->Window = window;
  this->Renderers.push_back(std::move(state));
  return *this->Renderers.back();
}

const std::vector<vtkCascadedShadowMapBakerPass::LightMaps>&
vtkCascadedShadowMapBakerPass::GetLightMaps(vtkRenderer* renderer) const
{
  static const std::vector<LightMaps> none;
  renderer = renderer ? renderer : this->LastRenderer.GetPointer();
  for (const auto& state : this->Renderers)
  {
    if (renderer && state->Renderer == renderer)
    {
      return state->Maps;
    }
  }
  return none;
}

bool vtkCascadedShadowMapBakerPass::InputsChanged(vtkRenderer* renderer, csmRendererMaps& state)
{
  // Everything but the camera and the lights' geometry: a camera move is judged cascade by
  // cascade, a light's direction or position with its maps (Render()). Headlights and camera
  // lights follow the camera, so their MTime changes with every camera move.
  vtkMTimeType input = std::max(this->GetMTime(), renderer->GetLights()->GetMTime());
  vtkPropCollection* props = renderer->GetViewProps();
  input = std::max(input, props->GetMTime());
  vtkCollectionSimpleIterator pit;
  props->InitTraversal(pit);
  while (vtkProp* prop = props->GetNextProp(pit))
  {
    if (!prop->GetPropertyKeys())
    {
      // The passes tag props through their keys; creating them modifies the prop, so do it
      // here, once, rather than have the first tagging trigger a second bake.
      vtkNew<vtkInformation> keys;
      prop->SetPropertyKeys(keys);
    }
    input = std::max(input, prop->GetRedrawMTime());
  }
  int* size = renderer->GetSize();
  const bool changed =
    input > state.LastInputTime || size[0] != state.LastSize[0] || size[1] != state.LastSize[1];
  state.LastInputTime = input;
  state.LastSize[0] = size[0];
  state.LastSize[1] = size[1];
  return changed;
}

int vtkCascadedShadowMapBakerPass::MaximumShadowedLights(vtkOpenGLRenderWindow* window)
{
  GLint units = 16, components = 1024;
  glGetIntegerv(GL_MAX_TEXTURE_IMAGE_UNITS, &units);
  glGetIntegerv(GL_MAX_FRAGMENT_UNIFORM_COMPONENTS, &components);
  if (vtkTextureUnitManager* manager = window->GetTextureUnitManager())
  {
    int free = 0;
    for (int unit = 0; unit < manager->GetNumberOfTextureUnits(); ++unit)
    {
      free += manager->IsAllocated(unit) ? 0 : 1;
    }
    units = std::min<GLint>(units, free);
  }
  const int byUnits = static_cast<int>(units) - kMapperTextureUnits;
  int perLight = kUniformComponentsPerLight;
#if CSM_COMPARISON_TECHNIQUES
  perLight += (this->Planner->GetFacePartitions() > 0 ? kFacePlaneComponentsPerLight : 0) +
    (this->Planner->GetCameraSpace() ? kMaxCascades * 4 : 0);
#endif
  const int byUniforms = (static_cast<int>(components) - kMapperUniformComponents) / perLight;
  return std::max(0, std::min(byUnits, byUniforms));
}

void vtkCascadedShadowMapBakerPass::ReportOnce(bool error, const std::string& message)
{
  csmReportOnce(this, this->Reported, error, message);
}

bool vtkCascadedShadowMapBakerPass::PrepareAtlas(
  vtkOpenGLRenderWindow* window, LightMaps& maps, bool& reallocated)
{
  reallocated = false;
  // The texture the planner laid out (the same for every count of cascades: a new texture would
  // cost its allocation and every map's render).
  vtkTextureObject* atlas = maps.Atlas;
  const unsigned int width = static_cast<unsigned int>(maps.AtlasSize[0]);
  const unsigned int height = static_cast<unsigned int>(maps.AtlasSize[1]);
  if (width == 0 || height == 0)
  {
    return false;
  }
  if (atlas->GetContext() == window && atlas->GetWidth() == width && atlas->GetHeight() == height &&
    atlas->GetHandle())
  {
    return true;
  }
  atlas->ReleaseGraphicsResources(window);
  atlas->SetContext(window);
  atlas->SetWrapS(vtkTextureObject::ClampToEdge);
  atlas->SetWrapT(vtkTextureObject::ClampToEdge);
  atlas->SetMinificationFilter(vtkTextureObject::Linear); // 2x2 hardware PCF per tap
  atlas->SetMagnificationFilter(vtkTextureObject::Linear);
  atlas->SetDepthTextureCompare(true);
  atlas->SetDepthTextureCompareFunction(vtkTextureObject::Lequal);
  if (!atlas->AllocateDepth(width, height, vtkTextureObject::Float32))
  {
    std::ostringstream message;
    message << "Cannot allocate a " << width << " x " << height << " shadow map atlas";
    this->ReportOnce(true, message.str());
    return false;
  }
  // A new GL texture: its compare mode and filters must be sent again, but the setters above
  // did not change the object when the values were the same as before.
  atlas->Modified();
  reallocated = true;
  return true;
}

void vtkCascadedShadowMapBakerPass::Render(const vtkRenderState* s)
{
  vtkOpenGLClearErrorMacro();
  this->NumberOfRenderedProps = 0;
  vtkOpenGLRenderer* renderer = vtkOpenGLRenderer::SafeDownCast(s->GetRenderer());
  if (!renderer || renderer->GetSelector())
  {
    return; // hardware selection renders no shadows; keep the last maps
  }
  vtkOpenGLRenderWindow* window = vtkOpenGLRenderWindow::SafeDownCast(renderer->GetRenderWindow());
  vtkCamera* camera = renderer->GetActiveCamera();
  if (!window || !camera)
  {
    return;
  }
  // Camera lights and headlights follow this frame's camera before they are planned for (the
  // renderer would move them only when the lights pass after this one runs).
  this->UpdateLightGeometry(renderer);
  // The atlas the planner lays out: tiles of Resolution, within this context's texture limit
  // (set before the inputs are compared: a change re-renders every map).
  GLint maximumTextureSize = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maximumTextureSize);
  this->Planner->SetAtlasResolution(this->Resolution);
  this->Planner->SetMaximumTextureSize(static_cast<int>(maximumTextureSize));
  using Clock = std::chrono::steady_clock;
  const auto planStart = Clock::now();
  this->LastRenderer = renderer;
  csmRendererMaps& state = this->MapsOf(renderer, window);
  this->Statistics = FrameStatistics();
  ++this->FrameNumber;

  this->ViewMoved = state.LastCamera && !sameViewpoint(state.LastCamera, camera);
  // 1. The props: casters, receivers, scene bounds (across processes when distributed).
  csmFrameCasters props;
  this->CollectProps(renderer, state, props);
  if (this->Distributed())
  {
    props.GatherAcrossProcesses(this->Controller);
  }
  // The nearest and farthest visible depth of this very view (VisibleDepthFit).
  this->MeasureVisibleDepths(renderer, s, state, props);
  // 2. Plan every shadowed light, and choose the cascades to re-render.
  std::vector<LightMaps> planned;
  std::vector<int> render; // per light slot and cascade: 1 render, 0 keep
  this->PlanLights(renderer, window, state, props, planned, render);
  if (this->MeasureTimes)
  {
    this->Statistics.PlanSeconds = std::chrono::duration<double>(Clock::now() - planStart).count();
  }
  if (planned.empty())
  {
    state.Maps.clear();
    return;
  }
  // 3. Render those cascades into the lights' atlases.
  const auto mapStart = Clock::now();
  if (this->MeasureTimes)
  {
    glFinish();
  }
  this->RenderAtlases(renderer, window, state, props, planned, render);
  if (this->MeasureTimes)
  {
    glFinish();
    this->Statistics.MapSeconds = std::chrono::duration<double>(Clock::now() - mapStart).count();
  }
  state.Maps = planned;
  vtkOpenGLCheckErrorMacro("failed after rendering the cascaded shadow maps");
}

void vtkCascadedShadowMapBakerPass::MeasureVisibleDepths(vtkOpenGLRenderer* renderer,
  const vtkRenderState* s, csmRendererMaps& state, const csmFrameCasters& props)
{
  vtkCamera* camera = renderer->GetActiveCamera();
  const double aspect = renderer->GetTiledAspectRatio();
  // (Only directional lights' cascades are fitted to the view's depths.)
  bool directional = false;
  vtkCollectionSimpleIterator lit;
  renderer->GetLights()->InitTraversal(lit);
  while (vtkLight* light = renderer->GetLights()->GetNextLight(lit))
  {
    directional = directional ||
      (vtkCascadedShadowMapBakerPass::LightCastsShadows(light) && !light->GetPositional());
  }
  if (!this->VisibleDepthFit || this->Distributed() || props.Casters.empty() || !directional)
  {
    state.VisibleCamera = nullptr; // each process sees only its own; nothing to see
    return;
  }
  if (!props.Changed && state.VisibleCamera && state.VisibleAspect == aspect &&
    sameView(state.VisibleCamera, camera, aspect))
  {
    return; // measured for this very view of this scene
  }
  state.VisibleCamera = nullptr;
  GLint sampleBuffers = 0;
  glGetIntegerv(GL_SAMPLE_BUFFERS, &sampleBuffers);
  if (sampleBuffers > 0)
  {
    return; // a multisampled depth buffer cannot be read directly: fitted to the boxes
  }
  double samples[2] = { 1.0, 0.0 };
  csm::WindowFootprint footprint;
  const bool read = this->Drawing->DrawViewDepth(
    renderer, s, props, samples, footprint, this->Statistics.DepthPassStandIns);
  this->Statistics.VisibleDepthsMeasured = true;
  if (read && samples[0] <= samples[1])
  {
    state.VisibleCamera = vtkSmartPointer<vtkCamera>::New();
    state.VisibleCamera->DeepCopy(camera);
    state.VisibleAspect = aspect;
    state.VisibleWindow[0] = samples[0];
    state.VisibleWindow[1] = samples[1];
    state.VisibleFootprint = std::move(footprint);
  }
}

void vtkCascadedShadowMapBakerPass::CollectProps(
  vtkRenderer* renderer, csmRendererMaps& state, csmFrameCasters& props)
{
  // Bounds first: computing them brings the props' pipelines up to date, which must not count
  // as a change next frame.
  renderer->ComputeVisiblePropBounds(props.SceneBounds);
  props.Changed = this->InputsChanged(renderer, state) || state.Maps.empty();
  csmCasterCollection::Options options;
  options.CullClosedCasters = this->CullClosedCasters;
  options.CompactCasters = this->CompactCasters;
  options.CullCastersWithoutReceivers = this->CullCastersWithoutReceivers;
  const csmCasterCollection::Counts counts =
    this->Casters->Collect(renderer, options, this->FrameNumber, this->ViewMoved, props);
  this->Statistics.ClosedCasters = counts.ClosedCasters;
  this->Statistics.CompactCasters = counts.CompactCasters;
}

int vtkCascadedShadowMapBakerPass::ClosureOf(vtkProp* prop)
{
  return this->Casters->ClosureOf(prop, this->CullClosedCasters);
}

void vtkCascadedShadowMapBakerPass::PlanLights(vtkRenderer* renderer, vtkOpenGLRenderWindow* window,
  csmRendererMaps& state, const csmFrameCasters& props, std::vector<LightMaps>& planned,
  std::vector<int>& render)
{
  props.FeedPlanner(this->Planner);
  // Plan every shadowed light for this frame, and decide per cascade whether the map kept from
  // an earlier frame still serves (only the camera moved, it covers, its error is bounded).
  // While the user interacts (VTK's convention: the interactor raises the window's desired
  // update rate), maps get a border and may be kept within MapReuseTolerance; a still frame
  // keeps a map while its error at this view meets what a fresh map would (MapSlack).
  csmFramePlan frame;
  frame.Interacting = vtkCascadedShadowMapBakerPass::IsInteracting(window);
  frame.Border = frame.Interacting ? this->InteractiveMapBorder : 0.0;
  // (The tolerance is against a fresh map with the same border, whose error is 1 + 2 border
  // times a tight one's.)
  frame.Tolerance = this->MapReuseTolerance * (1.0 + 2.0 * frame.Border);
  // Tubes, spheres, wide lines and big points are drawn into the maps as wide as the main view
  // draws them: a still frame keeps such a map only for the view it was sized for.
  frame.ScreenSized = props.ScreenSized;
  // Kept maps move with the view where the GL copies between images (GL 4.3) and one process
  // draws the maps (each would move its own).
  frame.MoveMaps =
    this->MoveKeptMaps && (GLEW_VERSION_4_3 || GLEW_ARB_copy_image) && !this->Distributed();
  // Resolution from need (ErrorTarget), up to the ceiling of this kind of frame; more cascades
  // than fill the atlas with full maps only in a still frame (each is a caster pass; they
  // refine the error where four full maps cannot reach ErrorTarget).
  frame.Ceiling =
    frame.Interacting ? std::min(this->InteractiveResolution, this->Resolution) : this->Resolution;
  frame.MostCascades = frame.Interacting ? csm::kAtlasFullMaps : 0;
  frame.ImageHeight = renderer->GetSize()[1];
  frame.Aspect = renderer->GetTiledAspectRatio();
  frame.Changed = props.Changed;
  csmMapDrawing::MainView(renderer, renderer->GetActiveCamera(), frame.ViewKey);
  // The visible depths of this view (VisibleDepthFit; MeasureVisibleDepths).
  if (this->VisibleDepthFit && !this->Distributed() && state.VisibleCamera)
  {
    this->Planner->SetVisibleDepths(
      state.VisibleCamera, state.VisibleAspect, state.VisibleWindow[0], state.VisibleWindow[1]);
    // Where on the image (VisibleFootprintFit): the depth pass draws the casters, so not where
    // a receiver without opaque geometry may lie outside it; and its pixels are the camera's
    // whole image only for an on-axis camera drawn in one tile (not a magnified screenshot's
    // tiles, not an off-axis or shifted projection).
    vtkCamera* camera = renderer->GetActiveCamera();
    const double* tile = window->GetTileViewport();
    const double* centre = camera->GetWindowCenter();
    const bool wholeImage = window->GetTileScale()[0] == 1 && window->GetTileScale()[1] == 1 &&
      tile[0] == 0.0 && tile[1] == 0.0 && tile[2] == 1.0 && tile[3] == 1.0 && centre[0] == 0.0 &&
      centre[1] == 0.0 && !camera->GetUseOffAxisProjection() &&
      !camera->GetUseExplicitProjectionTransformMatrix();
    this->Planner->SetVisibleFootprint(
      this->VisibleFootprintFit && !props.TranslucentReceivers && wholeImage
        ? &state.VisibleFootprint
        : nullptr);
  }
  else
  {
    this->Planner->ClearVisibleDepths();
  }
  const int maximumLights = this->MaximumShadowedLights(window);
  int shadowingLights = 0;
  int lightIndex = 0;
  vtkCollectionSimpleIterator lit;
  renderer->GetLights()->InitTraversal(lit);
  while (vtkLight* light = renderer->GetLights()->GetNextLight(lit))
  {
    if (!light->GetSwitch())
    {
      continue; // the mapper numbers switched-on lights only
    }
    const int index = lightIndex++;
    if (!vtkCascadedShadowMapBakerPass::LightCastsShadows(light) ||
      ++shadowingLights > maximumLights)
    {
      continue;
    }
    this->PlanLight(renderer, state, props, frame, light, index, planned, render);
  }
  if (!state.LastCamera)
  {
    state.LastCamera = vtkSmartPointer<vtkCamera>::New();
  }
  state.LastCamera->DeepCopy(renderer->GetActiveCamera());
  if (this->Distributed() && !render.empty())
  {
    // One process's "render" is every process's: the maps are combined across them.
    std::vector<int> any(render.size(), 0);
    this->Controller->AllReduce(
      render.data(), any.data(), static_cast<vtkIdType>(render.size()), vtkCommunicator::MAX_OP);
    render = any;
  }
  if (shadowingLights > maximumLights && shadowingLights != this->WarnedShadowingLights)
  {
    vtkWarningMacro(<< shadowingLights << " lights cast shadows but this GL context has texture "
                    << "units for " << maximumLights << "; the others are lit without shadows");
  }
  this->WarnedShadowingLights = shadowingLights > maximumLights ? shadowingLights : 0;
  // Textures only for the lights that cast shadows now.
  for (size_t i = planned.size(); i < state.AtlasPool.size(); ++i)
  {
    state.AtlasPool[i]->ReleaseGraphicsResources(window);
  }
  state.AtlasPool.resize(planned.size());
}

void vtkCascadedShadowMapBakerPass::PlanLight(vtkRenderer* renderer, csmRendererMaps& state,
  const csmFrameCasters& props, const csmFramePlan& frame, vtkLight* light, int index,
  std::vector<LightMaps>& planned, std::vector<int>& render)
{
  vtkCamera* camera = renderer->GetActiveCamera();
  const size_t slot = planned.size();
  LightMaps maps;
  maps.Light = light;
  maps.LightIndex = index;
  maps.Kind = light->GetPositional() ? LightKind::Spot : LightKind::Directional;
  light->GetTransformedPosition(maps.Position);
  light->GetTransformedFocalPoint(maps.FocalPoint);
  maps.ConeAngle = light->GetPositional() ? light->GetConeAngle() : 0.0;
  const int count = std::min(kMaxCascades,
    this->Planner->Plan(camera, frame.Aspect, light, props.SceneBounds, frame.ImageHeight,
      frame.Ceiling, frame.MostCascades));
  this->Statistics.VisibleDepthsUsed =
    this->Statistics.VisibleDepthsUsed || this->Planner->GetVisibleDepthsUsed();
  this->Statistics.VisibleFootprintUsed =
    this->Statistics.VisibleFootprintUsed || this->Planner->GetVisibleFootprintUsed();
  if (this->Planner->GetAtlasShrunk())
  {
    this->ReportOnce(false,
      "Shadow map tiles of " + std::to_string(this->Resolution) +
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
    bool moved = false;
    if (assigned.kept[c] >= 0)
    {
      const CascadeMap& old = serving.at({ c, assigned.kept[c] });
      std::copy(old.WorldToMap, old.WorldToMap + 16, map.WorldToMap);
      std::copy(old.CasterView, old.CasterView + 18, map.CasterView);
      std::copy(old.Resolution, old.Resolution + 2, map.Resolution);
      std::copy(old.Moved, old.Moved + 2, map.Moved);
      moved = map.IsMoved();
    }
    // (A moved map is drawn too: its strips.)
    render.push_back(assigned.kept[c] < 0 || moved ? 1 : 0);
  }
  render.resize(kMaxCascades * (slot + 1), 0);
  if (count > 0)
  {
    maps.SplitNear = this->Planner->GetCascadeNear(0);
  }
  if (state.AtlasPool.size() <= slot)
  {
    state.AtlasPool.push_back(vtkSmartPointer<vtkTextureObject>::New());
  }
  maps.Atlas = state.AtlasPool[slot];
  planned.push_back(std::move(maps));
}

vtkCascadedShadowMapBakerPass::MapKind vtkCascadedShadowMapBakerPass::PlannedMapKind(
  vtkLight* light) const
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

void vtkCascadedShadowMapBakerPass::PlanCascade(const csmFramePlan& frame, vtkCamera* camera,
  const csmRendererMaps& state, int c, bool smoothPath, CascadeMap& map, csmCascadeNeed& need)
{
  // The map this cascade needs (ErrorTarget) in its tile of the planned atlas.
  this->Planner->GetCascadeTile(c, map.Tile);
  int ceiling[2];
  this->Planner->GetCascadeResolutionCeiling(c, ceiling);
  this->Planner->GetCascadeResolution(
    c, frame.ImageHeight, RESOLUTION_STEP, ceiling, map.Resolution);
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
    vtkCascadedShadowMapPlanner::IsSmallCameraStep(
      state.LastCamera, camera, frame.Aspect, this->Planner->GetCascadeFar(c)))
  {
    const csm::SlackedMap slacked =
      csm::slackedMap(csm::MapSize(need.Texels[0], need.Texels[1]), most, this->MapSlack);
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

bool vtkCascadedShadowMapBakerPass::KeptMapServes(const csmFramePlan& frame, int c,
  const csmCascadeNeed& need, const CascadeMap& map, const CascadeMap& old, CascadeMap& moved)
{
  // A kept map serves if it has the texels this view needs (or all its tile holds, where the
  // GL's texture size limit made the tiles smaller than Resolution): while the user interacts,
  // within MapReuseTolerance of a fresh map with the same border; in a still frame, where its
  // error at this view meets ErrorTarget (what a fresh map of the fewest texels that meet it
  // meets; fresh maps get whole RESOLUTION_STEPs more), or comes within the cascade count's
  // hysteresis of a fresh map where no map meets ErrorTarget (csm::keptMapServes). (Turned the
  // same way: the error ratio compares the maps at equal resolution.)
  // (Of the same kind; its tile is assignTiles' to choose.)
  if ((!frame.Interacting && frame.ScreenSized &&
        !std::equal(frame.ViewKey, frame.ViewKey + 18, old.CasterView)) ||
    old.Turned != map.Turned || old.Kind != map.Kind)
  {
    return false;
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

void vtkCascadedShadowMapBakerPass::RenderAtlases(vtkOpenGLRenderer* renderer,
  vtkOpenGLRenderWindow* window, csmRendererMaps& state, const csmFrameCasters& props,
  std::vector<LightMaps>& planned, std::vector<int>& render)
{
  vtkOpenGLState* ostate = window->GetState();
  vtkOpenGLState::ScopedglViewport savedViewport(ostate);
  vtkOpenGLState::ScopedglScissor savedScissor(ostate);
  vtkOpenGLState::ScopedglEnableDisable savedScissorTest(ostate, GL_SCISSOR_TEST);
  vtkOpenGLState::ScopedglDepthMask savedDepthMask(ostate);
  vtkOpenGLState::ScopedglColorMask savedColorMask(ostate);
  vtkOpenGLState::ScopedglDepthFunc savedDepthFunc(ostate);
  vtkOpenGLState::ScopedglEnableDisable savedDepthTest(ostate, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglEnableDisable savedDepthClamp(ostate, GL_DEPTH_CLAMP);
  vtkOpenGLState::ScopedglEnableDisable savedOffset(ostate, GL_POLYGON_OFFSET_FILL);
  vtkOpenGLState::ScopedglEnableDisable savedCulling(ostate, GL_CULL_FACE);
  GLint savedCullFace = GL_BACK;
  glGetIntegerv(GL_CULL_FACE_MODE, &savedCullFace);
  ostate->PushFramebufferBindings();

  const bool automaticLights = renderer->GetAutomaticLightCreation() != 0;
  renderer->SetAutomaticLightCreation(false);
  if (!state.FrameBuffer)
  {
    state.FrameBuffer = vtkSmartPointer<vtkOpenGLFramebufferObject>::New();
  }
  state.FrameBuffer->SetContext(window);
  for (size_t slot = 0; slot < planned.size(); ++slot)
  {
    this->RenderAtlas(renderer, window, state, props, planned[slot],
      render.data() + kMaxCascades * slot, slot == 0);
  }
  ostate->PopFramebufferBindings();
  ostate->vtkglCullFace(static_cast<unsigned int>(savedCullFace));
  renderer->SetAutomaticLightCreation(automaticLights);
}

void vtkCascadedShadowMapBakerPass::RenderAtlas(vtkOpenGLRenderer* renderer,
  vtkOpenGLRenderWindow* window, csmRendererMaps& state, const csmFrameCasters& props,
  LightMaps& maps, int* renderCascade, bool timed)
{
  // The atlas the planner laid out, the same for every count of cascades (a new texture would
  // cost its allocation and every map's render); each cascade's map fills the lower left of
  // its tile with the resolution PlanLights chose.
  bool reallocated = false;
  if (!this->PrepareAtlas(window, maps, reallocated))
  {
    maps.Cascades.clear();
    return;
  }
  bool any = false;
  for (int c = 0; c < maps.GetNumberOfCascades(); ++c)
  {
    if (reallocated) // (nothing kept to move: drawn whole)
    {
      maps.Cascades[c].Moved[0] = maps.Cascades[c].Moved[1] = 0;
    }
    renderCascade[c] = renderCascade[c] || reallocated;
    any = any || renderCascade[c];
  }
  this->Statistics.CascadesKept += maps.GetNumberOfCascades();
  if (!any)
  {
    return;
  }
  state.FrameBuffer->Bind();
  state.FrameBuffer->AddDepthAttachment(maps.Atlas);
  state.FrameBuffer->DeactivateDrawBuffers();
  state.FrameBuffer->DeactivateReadBuffer();
  if (state.FrameBuffer->CheckFrameBufferStatus(GL_FRAMEBUFFER) == 0)
  {
    this->ReportOnce(true, "The shadow map framebuffer is incomplete; no shadows");
    maps.Cascades.clear();
    return;
  }
  vtkOpenGLState* ostate = window->GetState();
  const bool depthClamp = this->Planner->GetDepthClamp();
  ostate->vtkglColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  ostate->vtkglDepthMask(GL_TRUE);
  ostate->vtkglClearDepth(1.0);
  ostate->vtkglEnable(GL_DEPTH_TEST);
  ostate->vtkglDepthFunc(GL_LEQUAL);
  if (depthClamp)
  {
    ostate->vtkglEnable(GL_DEPTH_CLAMP);
  }
  else
  {
    ostate->vtkglDisable(GL_DEPTH_CLAMP);
  }
  ostate->vtkglEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(
    static_cast<GLfloat>(this->PolygonOffset[0]), static_cast<GLfloat>(this->PolygonOffset[1]));
  using Clock = std::chrono::steady_clock;
  auto since = Clock::now();
  // (MeasureTimes: each step's time up to its glFinish.)
  const bool measure = this->MeasureTimes && timed;
  auto lap = [&](double& seconds)
  {
    glFinish();
    const auto now = Clock::now();
    seconds = std::chrono::duration<double>(now - since).count();
    since = now;
  };
  csmMapDrawing::ClearTiles(ostate, maps, renderCascade);
  // The maps that move with the view: their kept texels shifted, the strips that came in
  // cleared (drawn whole where the move fails).
  for (int c = 0; c < maps.GetNumberOfCascades(); ++c)
  {
    CascadeMap& map = maps.Cascades[c];
    if (renderCascade[c] && map.IsMoved())
    {
      if (!state.MoveBuffer)
      {
        state.MoveBuffer = vtkSmartPointer<vtkTextureObject>::New();
      }
      if (!csmMapDrawing::MoveMap(window, state.MoveBuffer, maps, c))
      {
        map.Moved[0] = map.Moved[1] = 0;
        csmMapDrawing::ClearMap(ostate, maps, c, nullptr);
      }
    }
  }
  if (measure)
  {
    lap(this->Statistics.ClearSeconds);
  }
  ostate->vtkglEnable(GL_SCISSOR_TEST);
  glEnable(GL_PROGRAM_POINT_SIZE); // points sized as the main view draws them
  for (int c = 0; c < maps.GetNumberOfCascades(); ++c)
  {
    const CascadeMap& map = maps.Cascades[c];
    if (renderCascade[c] && map.IsMoved())
    {
      ++this->Statistics.CascadesMoved; // (kept in part: its strips drawn)
      for (const csm::TexelRect& strip : csmMapDrawing::MovedStrips(map))
      {
        this->NumberOfRenderedProps += this->Drawing->DrawCascade(renderer, state.FrameBuffer, maps,
          c, props, depthClamp, this->Distributed(), this->Statistics, strip.data());
      }
      glFlush();
      if (measure)
      {
        lap(this->Statistics.CascadeSeconds[c]);
      }
    }
    else if (renderCascade[c])
    {
      --this->Statistics.CascadesKept;
      this->NumberOfRenderedProps += this->Drawing->DrawCascade(renderer, state.FrameBuffer, maps,
        c, props, depthClamp, this->Distributed(), this->Statistics);
      // Hand the map to the GL while the next one is set up: a software rasterizer fills
      // this one on its threads while this thread transforms and bins the next one's casters.
      glFlush();
      if (measure)
      {
        lap(this->Statistics.CascadeSeconds[c]);
      }
    }
  }
  glDisable(GL_PROGRAM_POINT_SIZE);
  state.FrameBuffer->RemoveDepthAttachment();
  if (this->Distributed())
  {
    this->CombineAcrossProcesses(maps.Atlas);
  }
}

bool vtkCascadedShadowMapBakerPass::IsInteracting(vtkRenderWindow* window)
{
  return window && window->GetDesiredUpdateRate() >= kInteractiveUpdateRate;
}

void vtkCascadedShadowMapBakerPass::GetScreenSizes(vtkProp* prop, float sizes[2])
{
  vtkActor* actor = vtkActor::SafeDownCast(prop);
  vtkProperty* property = actor ? actor->GetProperty() : nullptr;
  sizes[0] = property ? property->GetLineWidth() : 1.0f;
  sizes[1] = property ? property->GetPointSize() : 1.0f;
  for (int i = 0; i < 2; ++i)
  {
    // vtkProperty's clamped setters let NaN through: such a prop is drawn one pixel wide here.
    sizes[i] = std::isfinite(sizes[i]) && sizes[i] >= 1.0f ? sizes[i] : 1.0f;
  }
}

void vtkCascadedShadowMapBakerPass::ReleaseGraphicsResources(vtkWindow* w)
{
  // The maps of the renderers drawn in this window (all of them for no window).
  for (auto& entry : this->Renderers)
  {
    csmRendererMaps& state = *entry;
    if (w && state.Window != w)
    {
      continue;
    }
    for (auto& atlas : state.AtlasPool)
    {
      atlas->ReleaseGraphicsResources(w ? w : state.Window);
    }
    if (state.FrameBuffer)
    {
      state.FrameBuffer->ReleaseGraphicsResources(w ? w : state.Window);
    }
    if (state.MoveBuffer)
    {
      state.MoveBuffer->ReleaseGraphicsResources(w ? w : state.Window);
    }
    state.Renderer = nullptr; // forgotten at the next Render()
  }
  this->Renderers.erase(std::remove_if(this->Renderers.begin(), this->Renderers.end(),
                          [](const std::unique_ptr<csmRendererMaps>& r) { return !r->Renderer; }),
    this->Renderers.end());
  // The compact blocks drawn in this window (all of them for no window).
  this->Casters->ReleaseGraphicsResources(w);
}

void vtkCascadedShadowMapBakerPass::SetPolygonOffset(double factor, double units)
{
  if (!std::isfinite(factor) || !std::isfinite(units))
  {
    vtkErrorMacro(<< "SetPolygonOffset(" << factor << ", " << units
                  << "): not finite numbers; keeping " << this->PolygonOffset[0] << ", "
                  << this->PolygonOffset[1]);
    return;
  }
  const double most = VTK_FLOAT_MAX; // (glPolygonOffset takes floats)
  factor = std::max(-most, std::min(most, factor));
  units = std::max(-most, std::min(most, units));
  if (factor != this->PolygonOffset[0] || units != this->PolygonOffset[1])
  {
    this->PolygonOffset[0] = factor;
    this->PolygonOffset[1] = units;
    this->Modified();
  }
}

void vtkCascadedShadowMapBakerPass::SetPlanner(vtkCascadedShadowMapPlanner* planner)
{
  if (!planner)
  {
    vtkErrorMacro(<< "SetPlanner(nullptr): a baker needs a planner; keeping the one it has");
    return;
  }
  if (planner != this->Planner)
  {
    this->Planner = planner;
    this->Modified();
  }
}

vtkCascadedShadowMapPlanner* vtkCascadedShadowMapBakerPass::GetPlanner()
{
  return this->Planner;
}

vtkMTimeType vtkCascadedShadowMapBakerPass::GetMTime()
{
  return std::max(this->Superclass::GetMTime(), this->Planner->GetMTime());
}

void vtkCascadedShadowMapBakerPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Resolution: " << this->Resolution << "\n";
  os << indent << "InteractiveResolution: " << this->InteractiveResolution << "\n";
  os << indent << "Planner:\n";
  this->Planner->PrintSelf(os, indent.GetNextIndent());
  os << indent << "PolygonOffset: " << this->PolygonOffset[0] << ", " << this->PolygonOffset[1]
     << "\n";
  os << indent << "MapReuseTolerance: " << this->MapReuseTolerance << "\n";
  os << indent << "InteractiveMapBorder: " << this->InteractiveMapBorder << "\n";
  os << indent << "MapSlack: " << this->MapSlack << "\n";
  os << indent << "MoveKeptMaps: " << (this->MoveKeptMaps ? "on" : "off") << "\n";
  os << indent << "MeasureTimes: " << (this->MeasureTimes ? "on" : "off") << "\n";
  os << indent << "CullClosedCasters: " << (this->CullClosedCasters ? "on" : "off") << "\n";
  os << indent << "VisibleDepthFit: " << (this->VisibleDepthFit ? "on" : "off") << "\n";
  os << indent << "VisibleFootprintFit: " << (this->VisibleFootprintFit ? "on" : "off") << "\n";
  os << indent
     << "CullCastersWithoutReceivers: " << (this->CullCastersWithoutReceivers ? "on" : "off")
     << "\n";
  os << indent << "CompactCasters: " << (this->CompactCasters ? "on" : "off") << "\n";
  os << indent << "Renderers: " << this->Renderers.size() << "\n";
  os << indent << "ShadowedLights: " << this->GetLightMaps().size() << "\n";
  os << indent << "Controller: " << this->Controller << "\n";
}
