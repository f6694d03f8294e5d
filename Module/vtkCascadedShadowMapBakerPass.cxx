// SPDX-License-Identifier: BSD-3-Clause
#include "vtkCascadedShadowMapBakerPass.h"

#include "csmAtlas.h" // csm::kAtlasFullMaps
#include "csmBakerState.h"
#include "csmCasterCollection.h"
#include "csmLightPlanning.h"
#include "csmMapDrawing.h"
#include "csmPageDrawing.h"
#include "csmProps.h"
#include "csmReportOnce.h"
#include "csmReuse.h"
#include "csmVTKMath.h"

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
#include <unordered_map>
#include <utility>

vtkStandardNewMacro(vtkCascadedShadowMapBakerPass);
vtkCxxSetObjectMacro(vtkCascadedShadowMapBakerPass, Controller, vtkMultiProcessController);

namespace
{
constexpr int kMaxCascades = vtkCascadedShadowMapPlanner::MAXIMUM_NUMBER_OF_CASCADES;
// Texture units of the fragment shader left to the mapper's own textures (colour, normal,
// ORM, emissive and anisotropy maps, and PBR's irradiance, prefiltered and BRDF maps).
constexpr int kMapperTextureUnits = 8;
// Fragment uniform components one shadowed light costs: per cascade a mat4, a vec4 and two
// floats (padded to vec4s), and the per-light values (its light-space pages' among them, each
// padded to a vec4); face partitions add 4 planes a cascade.
constexpr int kUniformComponentsPerLight = kMaxCascades * (16 + 4 + 4 + 4) + 32;
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
  return csmLightCastsShadows(light);
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

vtkRenderer* vtkCascadedShadowMapBakerPass::GetLastRenderer() const
{
  return this->LastRenderer.GetPointer();
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

namespace
{
/// Is a camera's explicit projection the one it would compute itself (as a compositor that
/// hands every process the whole view sets it), to within rounding?
bool ExplicitProjectionIsTheCamerasOwn(vtkCamera* camera, double aspect)
{
  vtkMatrix4x4* given = camera->GetExplicitProjectionTransformMatrix();
  if (!given)
  {
    return false;
  }
  vtkNew<vtkCamera> own;
  own->DeepCopy(camera);
  own->SetUseExplicitProjectionTransformMatrix(false);
  vtkMatrix4x4* computed = own->GetProjectionTransformMatrix(aspect, -1.0, 1.0);
  for (int i = 0; i < 16; ++i)
  {
    const double a = given->GetData()[i], b = computed->GetData()[i];
    if (!(std::abs(a - b) <= 1e-6 * std::max({ 1.0, std::abs(a), std::abs(b) })))
    {
      return false;
    }
  }
  return true;
}

/// The boxes, before and after, of the props whose casting changed, and of the props that came
/// or went, each prop matched by itself (not by its place in the list).
void DirtyBoxes(const std::vector<vtkProp*>& lastProps,
  const std::vector<std::vector<double>>& lastCasting,
  const std::vector<std::array<double, 6>>& lastBounds, const std::vector<vtkProp*>& props,
  const std::vector<std::vector<double>>& casting, const std::vector<std::array<double, 6>>& boxes,
  std::vector<std::array<double, 6>>& dirty)
{
  const auto add = [&dirty](const std::array<double, 6>& box)
  {
    if (box[0] <= box[1])
    {
      dirty.push_back(box);
    }
  };
  std::unordered_map<vtkProp*, size_t> last;
  for (size_t j = 0; j < lastProps.size(); ++j)
  {
    last.emplace(lastProps[j], j);
  }
  std::vector<char> kept(lastProps.size(), 0);
  for (size_t i = 0; i < props.size(); ++i)
  {
    const auto found = last.find(props[i]);
    if (found == last.end())
    {
      add(boxes[i]); // came
      continue;
    }
    const size_t j = found->second;
    kept[j] = 1;
    // (A box that moved with nothing else seen to change: the data was edited in place.)
    if (casting[i] != lastCasting[j] || boxes[i] != lastBounds[j])
    {
      add(lastBounds[j]);
      add(boxes[i]);
    }
  }
  for (size_t j = 0; j < lastProps.size(); ++j)
  {
    if (!kept[j])
    {
      add(lastBounds[j]); // went
    }
  }
}
} // namespace

bool vtkCascadedShadowMapBakerPass::InputsChanged(
  vtkRenderer* renderer, csmRendererMaps& state, std::vector<std::array<double, 6>>& dirty)
{
  // Everything but the camera and the lights' geometry: a camera move is judged cascade by
  // cascade, a light's direction or position with its maps (Render()). Headlights and camera
  // lights follow the camera, so their MTime changes with every camera move. Of the props, only
  // what they cast (csmCastingState): a new colour, scalars or material changes no map, and
  // where only some props' casting changed, or props came or went, their boxes before and
  // after are the dirty part. (The options: the baker's and its planner's.)
  const vtkMTimeType input =
    std::max({ this->GetMTime(), this->Planner->GetMTime(), renderer->GetLights()->GetMTime() });
  vtkPropCollection* props = renderer->GetViewProps();
  std::vector<std::vector<double>> casting;
  std::vector<vtkProp*> list;
  std::vector<std::array<double, 6>> boxes;
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
    casting.push_back(csmCastingState(prop));
    list.push_back(prop);
    std::array<double, 6> box = { 1, -1, 1, -1, 1, -1 };
    const double* b = prop->GetVisibility() && prop->GetUseBounds() ? prop->GetBounds() : nullptr;
    if (b && b[0] <= b[1] && b[2] <= b[3] && b[4] <= b[5])
    {
      std::copy(b, b + 6, box.begin());
    }
    boxes.push_back(box);
  }
  int* size = renderer->GetSize();
  const bool changed =
    input > state.LastInputTime || size[0] != state.LastSize[0] || size[1] != state.LastSize[1];
  dirty.clear();
  if (!changed)
  {
    DirtyBoxes(state.LastProps, state.LastCasting, state.LastBounds, list, casting, boxes, dirty);
  }
  state.LastInputTime = input;
  state.LastCasting = std::move(casting);
  state.LastProps = std::move(list);
  state.LastBounds = std::move(boxes);
  state.LastSize[0] = size[0];
  state.LastSize[1] = size[1];
  if (changed)
  {
    dirty.clear();
  }
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
  const int byUnits =
    (static_cast<int>(units) - kMapperTextureUnits) / vtkCascadedShadows::TextureUnitsPerLight;
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
  vtkOpenGLRenderWindow* window, csmRendererMaps& state, LightMaps& maps, bool& reallocated)
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
  // Kept maps in a texture of another size (a light's scene-fitted map becoming the base of its
  // pages): a texture of the new size takes the part both sizes share, then replaces the old one
  // in the light's slot (one allocation and one copy: the allocation is most of the time a
  // growing atlas costs a frame).
  const unsigned int sharedWidth = std::min(width, atlas->GetWidth());
  const unsigned int sharedHeight = std::min(height, atlas->GetHeight());
  const bool kept = std::any_of(maps.Cascades.begin(), maps.Cascades.end(),
    [](const CascadeMap& map) { return map.Action != MapAction::Draw; });
  const bool carried = kept && atlas->GetContext() == window && atlas->GetHandle() &&
    sharedWidth > 0 && sharedHeight > 0 && (GLEW_VERSION_4_3 || GLEW_ARB_copy_image);
  vtkSmartPointer<vtkTextureObject> grown =
    carried ? vtkSmartPointer<vtkTextureObject>::New() : vtkSmartPointer<vtkTextureObject>(atlas);
  if (!carried)
  {
    atlas->ReleaseGraphicsResources(window);
  }
  grown->SetContext(window);
  grown->SetWrapS(vtkTextureObject::ClampToEdge);
  grown->SetWrapT(vtkTextureObject::ClampToEdge);
  grown->SetMinificationFilter(vtkTextureObject::Linear); // 2x2 hardware PCF per tap
  grown->SetMagnificationFilter(vtkTextureObject::Linear);
  grown->SetDepthTextureCompare(true);
  grown->SetDepthTextureCompareFunction(vtkTextureObject::Lequal);
  if (!grown->AllocateDepth(width, height, vtkTextureObject::Float32))
  {
    std::ostringstream message;
    message << "Cannot allocate a " << width << " x " << height << " shadow map atlas";
    this->ReportOnce(true, message.str());
    if (carried)
    {
      atlas->ReleaseGraphicsResources(window);
    }
    return false;
  }
  // A new GL texture: its compare mode and filters must be sent again, but the setters above
  // did not change the object when the values were the same as before.
  grown->Modified();
  reallocated = true;
  if (carried)
  {
    csmMapDrawing::CopyTexels(
      atlas, 0, 0, grown, 0, 0, static_cast<int>(sharedWidth), static_cast<int>(sharedHeight));
    atlas->ReleaseGraphicsResources(window);
    std::replace(state.AtlasPool.begin(), state.AtlasPool.end(),
      vtkSmartPointer<vtkTextureObject>(atlas), grown);
    maps.Atlas = grown;
    // (A map outside the shared part is drawn whole.)
    for (CascadeMap& map : maps.Cascades)
    {
      if (static_cast<unsigned int>(map.Tile[0] + map.Tile[2]) > sharedWidth ||
        static_cast<unsigned int>(map.Tile[1] + map.Tile[3]) > sharedHeight)
      {
        map.Action = MapAction::Draw;
        map.Patches.clear();
        map.Moved[0] = map.Moved[1] = 0;
      }
    }
    reallocated = false;
  }
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
  int size[2] = { 0, 0 }, origin[2] = { 0, 0 };
  renderer->GetTiledSizeAndOrigin(size, size + 1, origin, origin + 1);
  if (!window || !camera || size[0] < 1 || size[1] < 1)
  {
    return; // (a viewport of no pixels shows nothing to shadow)
  }
  if (camera->GetUseOffAxisProjection() ||
    (camera->GetUseExplicitProjectionTransformMatrix() &&
      !ExplicitProjectionIsTheCamerasOwn(camera, renderer->GetTiledAspectRatio())))
  {
    this->ReportOnce(false,
      "An off-axis or explicit camera projection: the shadow maps are fitted to the camera's "
      "position, direction and view angle, not to its projection (shadows may be missing)");
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
  // A frame planned as the last one keeps every map unplanned.
  csmLightPlanning planning = this->Planning();
  const int maximumLights = this->MaximumShadowedLights(window);
  const bool asLastFrame = planning.LastPlanStands(renderer, window, state, props, maximumLights);
  // The nearest and farthest visible depth of this very view (VisibleDepthFit).
  this->MeasureVisibleDepths(renderer, s, state, props, asLastFrame);
  // 2. Plan every shadowed light, and choose the cascades to re-render.
  std::vector<LightMaps> planned;
  this->PlanLights(planning, renderer, window, state, props, maximumLights, asLastFrame, planned);
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
  this->RenderAtlases(renderer, window, state, props, planned);
  if (this->MeasureTimes)
  {
    glFinish();
    this->Statistics.MapSeconds = std::chrono::duration<double>(Clock::now() - mapStart).count();
  }
  state.Maps = planned;
  vtkOpenGLCheckErrorMacro("failed after rendering the cascaded shadow maps");
}

void vtkCascadedShadowMapBakerPass::SetFactorsHeldFor(vtkRenderer* renderer)
{
  this->FactorsHeldFor = renderer;
}

void vtkCascadedShadowMapBakerPass::MeasureVisibleDepths(vtkOpenGLRenderer* renderer,
  const vtkRenderState* s, csmRendererMaps& state, const csmFrameCasters& props, bool asLastFrame)
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
    state.VisibleSamples = csm::DepthSamples();
    return;
  }
  if (asLastFrame && this->FactorsHeldFor == renderer)
  {
    return; // the frame reads the factors its last frame held at its pixels: no lookup to spare
  }
  const bool measured = !props.GeometryChanged && state.VisibleCamera &&
    state.VisibleAspect == aspect && sameView(state.VisibleCamera, camera, aspect);
  GLint sampleBuffers = 0;
  glGetIntegerv(GL_SAMPLE_BUFFERS, &sampleBuffers);
  this->Statistics.ViewDepthDrawn = true;
  if (measured || sampleBuffers > 0)
  {
    // Measured for this very view of this scene, or not readable (a multisampled depth buffer:
    // the cascades are fitted to the boxes): the view's depth is drawn all the same, for the
    // frame's own geometry pass, which then makes the lookup only for the fragments it keeps
    // (Documentation/Results.md, "A still frame").
    if (!measured)
    {
      state.VisibleCamera = nullptr;
      state.VisibleSamples = csm::DepthSamples();
    }
    this->Drawing->DrawViewDepth(
      renderer, s, props, nullptr, state.VisibleFootprint, this->Statistics.DepthPassStandIns);
    return;
  }
  state.VisibleCamera = nullptr;
  double samples[2] = { 1.0, 0.0 };
  csm::WindowFootprint footprint;
  csm::DepthSamples buffer;
  // (The depth buffer and the boxes that stood in kept for light-space pages, marked from them
  // where a light's plan wants them, this very frame.)
  const bool read = this->Drawing->DrawViewDepth(renderer, s, props, samples, footprint,
    this->Statistics.DepthPassStandIns, this->LightSpacePages ? &buffer : nullptr);
  state.VisibleSamples = std::move(buffer);
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
  props.Changed = this->InputsChanged(renderer, state, props.Dirty) || state.Maps.empty();
  if (props.Changed || this->Distributed()) // (each process sees its own casters change)
  {
    props.Changed = props.Changed || !props.Dirty.empty();
    props.Dirty.clear();
  }
  props.GeometryChanged = props.Changed || !props.Dirty.empty();
  csmCasterCollection::Options options;
  options.CullClosedCasters = this->CullClosedCasters;
  options.CompactCasters = this->CompactCasters;
  options.CullCastersWithoutReceivers = this->CullCastersWithoutReceivers;
  const csmCasterCollection::Counts counts =
    this->Casters->Collect(renderer, options, this->FrameNumber, this->ViewMoved, props);
  this->Statistics.ClosedCasters = counts.ClosedCasters;
  this->Statistics.CompactCasters = counts.CompactCasters;
  this->Statistics.PreparedBlocks = counts.PreparedBlocks;
}

csmLightPlanning vtkCascadedShadowMapBakerPass::Planning()
{
  csmLightPlanning::BakerOptions options;
  options.Resolution = this->Resolution;
  options.InteractiveResolution = this->InteractiveResolution;
  options.MapReuseTolerance = this->MapReuseTolerance;
  options.InteractiveMapBorder = this->InteractiveMapBorder;
  options.MapSlack = this->MapSlack;
  options.MoveKeptMaps = this->MoveKeptMaps;
  options.LightSpacePages = this->LightSpacePages;
  options.VisibleDepthFit = this->VisibleDepthFit;
  options.VisibleFootprintFit = this->VisibleFootprintFit;
  return csmLightPlanning(this->Planner, options, this->Distributed() ? this->Controller : nullptr,
    this->Statistics,
    [this](bool error, const std::string& message) { this->ReportOnce(error, message); });
}

void vtkCascadedShadowMapBakerPass::PlanLights(csmLightPlanning& planning, vtkRenderer* renderer,
  vtkOpenGLRenderWindow* window, csmRendererMaps& state, const csmFrameCasters& props,
  int maximumLights, bool asLastFrame, std::vector<LightMaps>& planned)
{
  const int shadowingLights =
    planning.PlanLights(renderer, window, state, props, maximumLights, asLastFrame, planned);
  if (shadowingLights > maximumLights && shadowingLights != this->WarnedShadowingLights)
  {
    vtkWarningMacro(<< shadowingLights << " lights cast shadows but this GL context has texture "
                    << "units for " << maximumLights << "; the others are lit without shadows");
  }
  this->WarnedShadowingLights = shadowingLights > maximumLights ? shadowingLights : 0;
}

int vtkCascadedShadowMapBakerPass::ClosureOf(vtkProp* prop)
{
  return this->Casters->ClosureOf(prop, this->CullClosedCasters);
}

void vtkCascadedShadowMapBakerPass::RenderAtlases(vtkOpenGLRenderer* renderer,
  vtkOpenGLRenderWindow* window, csmRendererMaps& state, const csmFrameCasters& props,
  std::vector<LightMaps>& planned)
{
  csmDepthDrawingGuard guard(window->GetState());
  const bool automaticLights = renderer->GetAutomaticLightCreation() != 0;
  renderer->SetAutomaticLightCreation(false);
  if (!state.FrameBuffer)
  {
    state.FrameBuffer = vtkSmartPointer<vtkOpenGLFramebufferObject>::New();
  }
  state.FrameBuffer->SetContext(window);
  for (size_t slot = 0; slot < planned.size(); ++slot)
  {
    this->RenderAtlas(renderer, window, state, props, planned[slot], slot == 0);
    if (!this->Statistics.AsLastFrame) // (else the table of the last frame, as it was)
    {
      csmPageDrawing::UploadPageTable(window, state, slot, planned[slot]);
    }
  }
  renderer->SetAutomaticLightCreation(automaticLights);
}

bool vtkCascadedShadowMapBakerPass::BindAtlas(
  vtkOpenGLRenderWindow* window, csmRendererMaps& state, LightMaps& maps)
{
  // The atlas the planner laid out, the same for every count of cascades (a new texture would
  // cost its allocation and every map's render); each cascade's map fills the lower left of
  // its tile with the resolution PlanLights chose. False: nothing to draw.
  bool reallocated = false;
  if (!this->PrepareAtlas(window, state, maps, reallocated))
  {
    maps.Cascades.clear();
    return false;
  }
  bool any = false;
  for (CascadeMap& map : maps.Cascades)
  {
    if (reallocated) // (nothing kept: drawn whole)
    {
      map.Moved[0] = map.Moved[1] = 0;
      map.Patches.clear();
      map.Action = MapAction::Draw;
    }
    any = any || map.Action != MapAction::Keep;
  }
  any = any || !maps.Pages.Drawn.empty();
  this->Statistics.CascadesKept += maps.GetNumberOfCascades();
  if (!any)
  {
    return false;
  }
  state.FrameBuffer->Bind();
  state.FrameBuffer->AddDepthAttachment(maps.Atlas);
  state.FrameBuffer->DeactivateDrawBuffers();
  state.FrameBuffer->DeactivateReadBuffer();
  if (state.FrameBuffer->CheckFrameBufferStatus(GL_FRAMEBUFFER) == 0)
  {
    this->ReportOnce(true, "The shadow map framebuffer is incomplete; no shadows");
    maps.Cascades.clear();
    return false;
  }
  vtkOpenGLState* ostate = window->GetState();
  ostate->vtkglColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  ostate->vtkglDepthMask(GL_TRUE);
  ostate->vtkglClearDepth(1.0);
  ostate->vtkglEnable(GL_DEPTH_TEST);
  ostate->vtkglDepthFunc(GL_LEQUAL);
  if (this->Planner->GetDepthClamp())
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
  return true;
}

void vtkCascadedShadowMapBakerPass::ClearAndMoveMaps(
  vtkOpenGLRenderWindow* window, csmRendererMaps& state, LightMaps& maps)
{
  vtkOpenGLState* ostate = window->GetState();
  csmMapDrawing::ClearTiles(ostate, maps);
  // The maps that move with the view: their kept texels shifted, the strips that came in
  // cleared (drawn whole where the move fails). Then the texels changed casters cover.
  for (int c = 0; c < maps.GetNumberOfCascades(); ++c)
  {
    CascadeMap& map = maps.Cascades[c];
    if (map.Action == MapAction::Move)
    {
      if (!state.MoveBuffer)
      {
        state.MoveBuffer = vtkSmartPointer<vtkTextureObject>::New();
      }
      if (!csmMapDrawing::MoveMap(window, state.MoveBuffer, maps, c))
      {
        map.Moved[0] = map.Moved[1] = 0;
        map.Action = MapAction::Draw;
        csmMapDrawing::ClearMap(ostate, maps, c, nullptr);
      }
    }
    else if (map.Action == MapAction::Patch)
    {
      for (const std::array<int, 4>& patch : map.Patches)
      {
        csmMapDrawing::ClearMap(ostate, maps, c, patch.data());
      }
    }
  }
}

void vtkCascadedShadowMapBakerPass::RenderAtlas(vtkOpenGLRenderer* renderer,
  vtkOpenGLRenderWindow* window, csmRendererMaps& state, const csmFrameCasters& props,
  LightMaps& maps, bool timed)
{
  if (!this->BindAtlas(window, state, maps))
  {
    return;
  }
  using Clock = std::chrono::steady_clock;
  auto since = Clock::now();
  // (MeasureTimes: each step's time up to its glFinish.)
  const bool measure = this->MeasureTimes && timed;
  auto lap = [&](double& seconds)
  {
    if (measure)
    {
      glFinish();
      const auto now = Clock::now();
      seconds = std::chrono::duration<double>(now - since).count();
      since = now;
    }
  };
  this->ClearAndMoveMaps(window, state, maps);
  lap(this->Statistics.ClearSeconds);
  window->GetState()->vtkglEnable(GL_SCISSOR_TEST);
  glEnable(GL_PROGRAM_POINT_SIZE); // points sized as the main view draws them
  const bool depthClamp = this->Planner->GetDepthClamp();
  for (int c = 0; c < maps.GetNumberOfCascades(); ++c)
  {
    const CascadeMap& map = maps.Cascades[c];
    if (map.Action == MapAction::Move || map.Action == MapAction::Patch)
    {
      // Kept in part: a moved map's strips, or the texels of changed casters.
      const bool moved = map.Action == MapAction::Move;
      ++(moved ? this->Statistics.CascadesMoved : this->Statistics.CascadesPatched);
      const std::vector<csm::TexelRect> rects =
        moved ? csmMapDrawing::MovedStrips(map) : map.Patches;
      for (const csm::TexelRect& rect : rects)
      {
        this->NumberOfRenderedProps += this->Drawing->DrawCascade(renderer, state.FrameBuffer, maps,
          c, props, depthClamp, this->Distributed(), this->Statistics, rect.data());
      }
    }
    else if (map.Action == MapAction::Draw)
    {
      --this->Statistics.CascadesKept;
      this->NumberOfRenderedProps += this->Drawing->DrawCascade(renderer, state.FrameBuffer, maps,
        c, props, depthClamp, this->Distributed(), this->Statistics);
    }
    if (map.Action != MapAction::Keep)
    {
      // Hand the map to the GL while the next one is set up: a software rasterizer fills this
      // one on its threads while this thread transforms and bins the next one's casters.
      glFlush();
      lap(this->Statistics.CascadeSeconds[c]);
    }
  }
  this->NumberOfRenderedProps += csmPageDrawing::DrawPages(*this->Drawing, renderer, window, state,
    props, maps, this->Resolution / 2, this->Planner->GetDepthClamp(), this->Statistics);
  glDisable(GL_PROGRAM_POINT_SIZE);
  state.FrameBuffer->RemoveDepthAttachment();
  if (this->Distributed())
  {
    this->CombineAcrossProcesses(maps.Atlas);
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
    for (auto& table : state.PageTablePool)
    {
      if (table)
      {
        table->ReleaseGraphicsResources(w ? w : state.Window);
      }
    }
    if (state.PageScratch)
    {
      state.PageScratch->ReleaseGraphicsResources(w ? w : state.Window);
      state.PageFrameBuffer->ReleaseGraphicsResources(w ? w : state.Window);
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
  os << indent << "LightSpacePages: " << (this->LightSpacePages ? "on" : "off") << "\n";
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
