// SPDX-License-Identifier: BSD-3-Clause
#include "vtkCascadedShadowMapBakerPass.h"

#include "csmReportOnce.h"

#include "csmAtlas.h" // the atlas layout
#include "csmCasterBlocks.h"
#include "csmClosedSurface.h"
#include "csmReuse.h"
#include "csmVisibleDepth.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCascadedShadowBlockMapper.h"
#include "vtkCascadedShadowCasterPass.h"
#include "vtkCascadedShadowMapPlanner.h"
#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkCommunicator.h"
#include "vtkInformation.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLError.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLRenderer.h"
#include "vtkOpenGLState.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProp.h"
#include "vtkPropCollection.h"
#include "vtkProperty.h"
#include "vtkRenderState.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtkTextureUnitManager.h"
#include "vtk_glew.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <future>
#include <limits>
#include <memory>
#include <sstream>

vtkStandardNewMacro(vtkCascadedShadowMapBakerPass);
vtkCxxSetObjectMacro(vtkCascadedShadowMapBakerPass, Controller, vtkMultiProcessController);

namespace
{
/// A cascade's rectangle in its light's atlas, in texels: x, y, width, height.
std::array<int, 4> tileTexels(const vtkCascadedShadowMapBakerPass::LightMaps& maps, int c)
{
  const double width = static_cast<double>(maps.Atlas->GetWidth());
  const double height = static_cast<double>(maps.Atlas->GetHeight());
  return { static_cast<int>(std::lround(maps.Tile[c][0] * width)),
    static_cast<int>(std::lround(maps.Tile[c][1] * height)),
    static_cast<int>(std::lround(maps.Tile[c][2] * width)),
    static_cast<int>(std::lround(maps.Tile[c][3] * height)) };
}
constexpr int kMaxCascades = vtkCascadedShadowMapPlanner::MAXIMUM_NUMBER_OF_CASCADES;
constexpr size_t kMaxReceiverBoxes = 64;
/// Most casters the cascade count is weighed with one by one (each is tested against every
/// cascade of every count planned).
constexpr size_t kMaxCasterLoads = 256;
/// Most receiver boxes a caster without self-shadow is tested against
/// (CullCastersWithoutReceivers); beyond, every caster is drawn.
constexpr size_t kMaxReceiverTests = 4096;
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
// The depth pre-pass's offset behind the surfaces (glPolygonOffset factor and units): enough
// for the same triangle drawn by another shader to pass GL_LEQUAL.
constexpr float kPrePassOffsetFactor = 1.0f;
constexpr float kPrePassOffsetUnits = 4.0f;

/// Bounds of a prop that draws 3D geometry, or false (2D actors, invisible, no bounds).
bool propBounds(vtkProp* prop, double bounds[6])
{
  if (!prop || !prop->GetVisibility() || !prop->GetUseBounds())
  {
    return false;
  }
  const double* b = prop->GetBounds();
  if (!b || !(b[0] <= b[1] && b[2] <= b[3] && b[4] <= b[5]))
  {
    return false;
  }
  std::copy(b, b + 6, bounds);
  return true;
}

/// The main view that screen-sized casters are sized for (VTK draws tubes and spheres with a
/// width in the renderer's pixels): world -> view (row-major) in [0, 16), and the world size
/// of one pixel at view depth d, [16] + [17] d, from the camera's projection.
void casterView(vtkRenderer* renderer, vtkCamera* camera, double key[18])
{
  int width = 0, height = 0, x = 0, y = 0;
  renderer->GetTiledSizeAndOrigin(&width, &height, &x, &y);
  vtkMatrix4x4* worldToView = camera->GetModelViewTransformMatrix();
  std::copy(worldToView->GetData(), worldToView->GetData() + 16, key);
  vtkMatrix4x4* projection =
    camera->GetProjectionTransformMatrix(double(std::max(width, 1)) / std::max(height, 1), -1, 1);
  const double p11 = projection->GetElement(1, 1);
  const double pixel = height > 0 && std::isfinite(p11) && p11 != 0.0 ? 2.0 / (height * p11) : 0.0;
  key[16] = pixel * projection->GetElement(3, 3);  // parallel: constant
  key[17] = -pixel * projection->GetElement(3, 2); // perspective: grows with depth
}

/// Does any caster draw lines wider or points bigger than one pixel (its map then depends on
/// the main view)?
template <typename Caster>
bool hasScreenSizedCasters(const std::vector<Caster>& casters)
{
  vtkNew<vtkPropCollection> actors;
  for (const Caster& caster : casters)
  {
    caster.Prop->GetActors(actors);
  }
  vtkCollectionSimpleIterator it;
  actors->InitTraversal(it);
  while (vtkProp* prop = actors->GetNextProp(it))
  {
    float sizes[2];
    vtkCascadedShadowMapBakerPass::GetScreenSizes(prop, sizes);
    if (sizes[0] > 1.0f || sizes[1] > 1.0f)
    {
      return true;
    }
  }
  return false;
}

/// Cells of an actor's input data (0 for other props or without data).
double casterCells(vtkProp* prop)
{
  vtkActor* actor = vtkActor::SafeDownCast(prop);
  vtkMapper* mapper = actor ? actor->GetMapper() : nullptr;
  vtkDataObject* data =
    mapper && mapper->GetNumberOfInputPorts() > 0 && mapper->GetNumberOfInputConnections(0) > 0
    ? mapper->GetInputDataObject(0, 0)
    : nullptr;
  return data ? static_cast<double>(data->GetNumberOfElements(vtkDataObject::CELL)) : 0.0;
}

/// Does a camera look from where and where another did (its clipping range aside)?
bool sameViewpoint(vtkCamera* a, vtkCamera* b)
{
  const double* pa = a->GetPosition();
  const double* pb = b->GetPosition();
  const double* fa = a->GetFocalPoint();
  const double* fb = b->GetFocalPoint();
  const double* ua = a->GetViewUp();
  const double* ub = b->GetViewUp();
  return std::equal(pa, pa + 3, pb) && std::equal(fa, fa + 3, fb) && std::equal(ua, ua + 3, ub) &&
    a->GetViewAngle() == b->GetViewAngle() && a->GetParallelScale() == b->GetParallelScale() &&
    a->GetParallelProjection() == b->GetParallelProjection();
}

/// Does a camera see exactly as another did (view and projection at this aspect)?
bool sameView(vtkCamera* a, vtkCamera* b, double aspect)
{
  vtkMatrix4x4* viewA = a->GetModelViewTransformMatrix();
  vtkMatrix4x4* viewB = b->GetModelViewTransformMatrix();
  if (!std::equal(viewA->GetData(), viewA->GetData() + 16, viewB->GetData()))
  {
    return false;
  }
  double projectionA[16];
  std::copy(a->GetProjectionTransformMatrix(aspect, -1, 1)->GetData(),
    a->GetProjectionTransformMatrix(aspect, -1, 1)->GetData() + 16, projectionA);
  vtkMatrix4x4* projectionB = b->GetProjectionTransformMatrix(aspect, -1, 1);
  return std::equal(projectionA, projectionA + 16, projectionB->GetData());
}

/// Row-major double -> column-major float (GLSL's mat4).
void toColumnMajor(const double m[16], float out[16])
{
  for (int row = 0; row < 4; ++row)
  {
    for (int column = 0; column < 4; ++column)
    {
      out[4 * column + row] = static_cast<float>(m[4 * row + column]);
    }
  }
}

/// The caster uniforms for a cascade, from its CasterView and its tile.
vtkCascadedShadowCasterPass::CasterUniforms casterUniformsFor(
  const vtkCascadedShadowMapBakerPass::LightMaps& maps, int c, int x, int y, int w, int h)
{
  const double* key = maps.CasterView[c]; // RenderCascade set it for this view
  vtkNew<vtkMatrix4x4> worldToView, viewToWorld, worldToMap, mapToWorld;
  worldToView->DeepCopy(key);
  vtkMatrix4x4::Invert(worldToView, viewToWorld);
  worldToMap->DeepCopy(maps.WorldToMap[c]);
  vtkMatrix4x4::Invert(worldToMap, mapToWorld);
  double mapToView[16], viewToMap[16];
  vtkMatrix4x4::Multiply4x4(key, mapToWorld->GetData(), mapToView);
  vtkMatrix4x4::Multiply4x4(maps.WorldToMap[c], viewToWorld->GetData(), viewToMap);
  vtkCascadedShadowCasterPass::CasterUniforms u;
  toColumnMajor(mapToView, u.MapToView);
  toColumnMajor(viewToMap, u.ViewToMap);
  const double* position = maps.LightGeometry;
  const double* focal = maps.LightGeometry + 3;
  double light[4];
  if (maps.LightGeometry[6] < 0.0)
  {
    const double toward[4] = { position[0] - focal[0], position[1] - focal[1],
      position[2] - focal[2], 0.0 };
    worldToView->MultiplyPoint(toward, light);
  }
  else
  {
    const double at[4] = { position[0], position[1], position[2], 1.0 };
    worldToView->MultiplyPoint(at, light);
  }
  for (int i = 0; i < 4; ++i)
  {
    u.LightView[i] = static_cast<float>(light[i]);
  }
  u.PixelWorld[0] = static_cast<float>(key[16]);
  u.PixelWorld[1] = static_cast<float>(key[17]);
  u.Viewport[0] = static_cast<float>(x);
  u.Viewport[1] = static_cast<float>(y);
  u.Viewport[2] = static_cast<float>(w);
  u.Viewport[3] = static_cast<float>(h);
  return u;
}

}

vtkCascadedShadowMapBakerPass::vtkCascadedShadowMapBakerPass()
{
  this->Planner = vtkSmartPointer<vtkCascadedShadowMapPlanner>::New();
  this->LightCamera = vtkSmartPointer<vtkCamera>::New();
  this->Projection = vtkSmartPointer<vtkMatrix4x4>::New();
  this->CasterPass = vtkSmartPointer<vtkCascadedShadowCasterPass>::New();
  this->StopWorkers = std::make_shared<std::atomic<bool>>(false);
  // Identity view: the cascade matrix (world -> light clip) is the whole projection.
  this->LightCamera->SetPosition(0.0, 0.0, 0.0);
  this->LightCamera->SetFocalPoint(0.0, 0.0, -1.0);
  this->LightCamera->SetViewUp(0.0, 1.0, 0.0);
  this->LightCamera->SetParallelProjection(1);
  this->LightCamera->SetExplicitProjectionTransformMatrix(this->Projection);
  this->LightCamera->UseExplicitProjectionTransformMatrixOn();
}

vtkCascadedShadowMapBakerPass::~vtkCascadedShadowMapBakerPass()
{
  // Preparations under way stop at their next check (their futures wait for them below).
  this->StopWorkers->store(true);
  this->Closures.clear();
  this->Blocks.clear();
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

vtkCascadedShadowMapBakerPass::RendererMaps& vtkCascadedShadowMapBakerPass::MapsOf(
  vtkRenderer* renderer, vtkOpenGLRenderWindow* window)
{
  // Forget renderers that are gone (their textures free themselves with their context).
  this->Renderers.erase(std::remove_if(this->Renderers.begin(), this->Renderers.end(),
                          [](const RendererMaps& r) { return !r.Renderer; }),
    this->Renderers.end());
  for (RendererMaps& state : this->Renderers)
  {
    if (state.Renderer == renderer)
    {
      if (state.Window != window)
      {
        state = RendererMaps(); // moved to another context: start afresh
        state.Renderer = renderer;
        state.Window = window;
      }
      return state;
    }
  }
  RendererMaps state;
  state.Renderer = renderer;
  state.Window = window;
  this->Renderers.push_back(std::move(state));
  return this->Renderers.back();
}

const std::vector<vtkCascadedShadowMapBakerPass::LightMaps>&
vtkCascadedShadowMapBakerPass::GetLightMaps(vtkRenderer* renderer) const
{
  static const std::vector<LightMaps> none;
  for (const RendererMaps& state : this->Renderers)
  {
    if (renderer && state.Renderer == renderer)
    {
      return state.Maps;
    }
  }
  return none;
}

const std::vector<vtkCascadedShadowMapBakerPass::LightMaps>&
vtkCascadedShadowMapBakerPass::GetLightMaps() const
{
  return this->GetLightMaps(this->LastRenderer);
}

bool vtkCascadedShadowMapBakerPass::InputsChanged(vtkRenderer* renderer, RendererMaps& state)
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
  vtkOpenGLRenderWindow* window, LightMaps& maps, int tiles, int wanted, bool& reallocated)
{
  reallocated = false;
  // The texels of up to csm::kAtlasFullMaps full maps in one texture for every count of
  // cascades (a new texture would cost its allocation and every map's render); this frame's
  // count in its tiles.
  GLint maxSize = 4096;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
  const csm::AtlasGrid budget = csm::atlasLayout(tiles, wanted, maxSize);
  const int count = std::max(maps.NumberOfCascades, 1);
  const csm::AtlasGrid grid = csm::atlasForCount(count, budget);
  if (budget.tile.width < wanted)
  {
    std::ostringstream message;
    message << "Shadow map tiles of " << wanted << " texels exceed the GL limit " << maxSize
            << " in an atlas of " << budget.columns << " x " << budget.rows << "; using "
            << budget.tile.width;
    this->ReportOnce(false, message.str());
  }
  vtkTextureObject* atlas = maps.Atlas;
  const unsigned int width = static_cast<unsigned int>(budget.columns * budget.tile.width);
  const unsigned int height = static_cast<unsigned int>(budget.rows * budget.tile.height);
  if (atlas->GetContext() != window || atlas->GetWidth() != width || atlas->GetHeight() != height ||
    !atlas->GetHandle())
  {
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
  }
  maps.Resolution[0] = grid.tile.width;
  maps.Resolution[1] = grid.tile.height;
  for (int i = 0; i < maps.NumberOfCascades; ++i)
  {
    maps.Tile[i][0] = double((i % grid.columns) * grid.tile.width) / width;
    maps.Tile[i][1] = double((i / grid.columns) * grid.tile.height) / height;
    maps.Tile[i][2] = double(grid.tile.width) / width;
    maps.Tile[i][3] = double(grid.tile.height) / height;
  }
  return true;
}

void vtkCascadedShadowMapBakerPass::ClearTiles(
  vtkOpenGLState* ostate, const LightMaps& maps, const int* renderCascade)
{
  // Far depth where nothing casts, all before the first draw: a clear between two cascades'
  // draws would wait for the one drawn before it (a software rasterizer maps the texture).
  bool all = true;
  for (int c = 0; c < maps.NumberOfCascades; ++c)
  {
    all = all && renderCascade[c];
  }
  if (all)
  {
    // Nothing kept: one clear of the whole atlas, the fast clear of every driver.
    ostate->vtkglDisable(GL_SCISSOR_TEST);
    ostate->vtkglClear(GL_DEPTH_BUFFER_BIT);
    return;
  }
  // Some maps kept: only the others' tiles. Clearing the texture's rectangles directly (GL 4.4,
  // ARB_clear_texture) is several times cheaper on software Mesa than a scissored framebuffer
  // clear, which it draws as a quad.
  const bool clearTexture = GLEW_VERSION_4_4 || GLEW_ARB_clear_texture;
  ostate->vtkglEnable(GL_SCISSOR_TEST);
  for (int c = 0; c < maps.NumberOfCascades; ++c)
  {
    if (!renderCascade[c])
    {
      continue;
    }
    const std::array<int, 4> tile = tileTexels(maps, c);
    if (clearTexture)
    {
      const GLfloat farDepth = 1.0f;
      glClearTexSubImage(maps.Atlas->GetHandle(), 0, tile[0], tile[1], 0, tile[2], tile[3], 1,
        GL_DEPTH_COMPONENT, GL_FLOAT, &farDepth);
    }
    else
    {
      ostate->vtkglScissor(tile[0], tile[1], tile[2], tile[3]);
      ostate->vtkglClear(GL_DEPTH_BUFFER_BIT);
    }
  }
}

void vtkCascadedShadowMapBakerPass::RenderCascade(vtkOpenGLRenderer* renderer,
  vtkOpenGLFramebufferObject* frameBuffer, LightMaps& maps, int c, const FrameProps& props,
  bool depthClamp)
{
  vtkOpenGLState* ostate =
    static_cast<vtkOpenGLRenderWindow*>(renderer->GetRenderWindow())->GetState();
  const std::array<int, 4> tile = tileTexels(maps, c);
  const int x = tile[0], y = tile[1], w = tile[2], h = tile[3];
  ostate->vtkglViewport(x, y, w, h);
  ostate->vtkglScissor(x, y, w, h); // ClearTiles gave it far depth
  casterView(renderer, renderer->GetActiveCamera(), maps.CasterView[c]);

  // Only the casters whose bounds reach this cascade's light volume; for the closed ones, the
  // face to cull (the one turned toward the light). VTK's projections turn a counter-clockwise
  // face toward the eye into a front face when their determinant is negative (as glFrustum's and
  // glOrtho's are); a positive one swaps the sides.
  std::map<vtkProp*, unsigned int> cullFaces;
  const double mapDeterminant = vtkMatrix4x4::Determinant(maps.WorldToMap[c]);
  std::vector<vtkProp*> drawn;
  for (const FrameProps::Caster& caster : props.Casters)
  {
    if (!vtkCascadedShadowMapPlanner::CascadeReachesBox(
          maps.WorldToMap[c], caster.Bounds.data(), depthClamp))
    {
      continue;
    }
    if (caster.Compact >= 0)
    {
      // Only its blocks that reach the cascade and may shadow something in it.
      const FrameProps::Compact& compact = props.Compacts[static_cast<size_t>(caster.Compact)];
      std::vector<size_t> blocks;
      FrameProps::Caster block = caster;
      for (size_t k = 0; k < compact.Bounds.size(); ++k)
      {
        block.Bounds = compact.Bounds[k];
        if (!vtkCascadedShadowMapPlanner::CascadeReachesBox(
              maps.WorldToMap[c], block.Bounds.data(), depthClamp))
        {
          continue;
        }
        if (!this->CasterHasReceivers(props, block, maps))
        {
          ++this->Statistics.CastersWithoutReceivers;
          continue;
        }
        blocks.push_back(k);
        this->Statistics.CellsDrawn += compact.Cells[k];
      }
      if (blocks.empty())
      {
        continue;
      }
      compact.Mapper->SetDrawnBlocks(blocks);
      this->Statistics.BlocksDrawn += static_cast<int>(blocks.size());
    }
    else if (!this->CasterHasReceivers(props, caster, maps))
    {
      ++this->Statistics.CastersWithoutReceivers;
      continue;
    }
    else
    {
      this->Statistics.CellsDrawn += casterCells(caster.Prop);
    }
    drawn.push_back(caster.Prop);
    const int outward =
      std::isfinite(mapDeterminant) ? caster.Closure * (mapDeterminant < 0.0 ? 1 : -1) : 0;
    if (outward != 0)
    {
      cullFaces[caster.Prop] = outward > 0 ? GL_FRONT : GL_BACK;
    }
  }
  ++this->Statistics.CascadesRendered;
  this->Statistics.TexelsRendered += double(w) * double(h);
  this->Statistics.PropsDrawn += static_cast<int>(drawn.size());
  if (drawn.empty())
  {
    return;
  }
  vtkSmartPointer<vtkCamera> realCamera = renderer->GetActiveCamera();
  this->SetUpLightCamera(maps, c);
  this->CasterPass->BeginCascade(
    ostate, casterUniformsFor(maps, c, x, y, w, h), std::move(cullFaces));
  renderer->SetActiveCamera(this->LightCamera);
  this->NumberOfRenderedProps += this->CasterPass->DrawCasters(renderer, frameBuffer, drawn);
  this->CasterPass->EndCascade();
  renderer->SetActiveCamera(realCamera);
}

void vtkCascadedShadowMapBakerPass::SetUpLightCamera(const LightMaps& maps, int c)
{
  // The camera's view is the light's rotation (so that what VTK's shaders offset in view space,
  // such as vtkPointGaussianMapper's splats, faces the light); its projection the rest of the
  // cascade's world -> light clip matrix.
  double travel[3] = { maps.LightGeometry[3] - maps.LightGeometry[0],
    maps.LightGeometry[4] - maps.LightGeometry[1], maps.LightGeometry[5] - maps.LightGeometry[2] };
  const double length = vtkMath::Norm(travel);
  this->LightCamera->SetPosition(0.0, 0.0, 0.0);
  if (length > 0.0 && std::isfinite(length))
  {
    vtkMath::MultiplyScalar(travel, 1.0 / length);
    this->LightCamera->SetFocalPoint(travel);
    this->LightCamera->SetViewUp(
      std::abs(travel[1]) < 0.9 ? 0.0 : 1.0, std::abs(travel[1]) < 0.9 ? 1.0 : 0.0, 0.0);
  }
  else
  {
    this->LightCamera->SetFocalPoint(0.0, 0.0, -1.0);
    this->LightCamera->SetViewUp(0.0, 1.0, 0.0);
  }
  vtkNew<vtkMatrix4x4> viewToWorld;
  vtkMatrix4x4::Invert(this->LightCamera->GetModelViewTransformMatrix(), viewToWorld);
  vtkMatrix4x4::Multiply4x4(
    maps.WorldToMap[c], viewToWorld->GetData(), this->Projection->GetData());
  this->Projection->Modified();
  this->LightCamera->Modified();
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
  using Clock = std::chrono::steady_clock;
  const auto planStart = Clock::now();
  this->LastRenderer = renderer;
  RendererMaps& state = this->MapsOf(renderer, window);
  this->Statistics = FrameStatistics();
  ++this->FrameNumber;

  this->ViewMoved = state.LastCamera && !sameViewpoint(state.LastCamera, camera);
  // 1. The props: casters, receivers, scene bounds (across processes when distributed).
  FrameProps props;
  this->CollectProps(renderer, state, props);
  if (this->Distributed())
  {
    this->GatherAcrossProcesses(props);
  }
  // The nearest and farthest visible depth of this very view (VisibleDepthFit).
  this->MeasureVisibleDepths(renderer, s, state, props);
  // 2. Plan every shadowed light, and choose the cascades to re-render.
  std::vector<LightMaps> planned;
  std::vector<int> render; // per light slot and cascade: 1 render, 0 keep
  this->PlanLights(renderer, window, state, props, planned, render);
  this->Statistics.VisibleDepthsUsed = state.VisibleDepthsUsed;
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
  if (this->Statistics.CascadesRendered > 0)
  {
    ++this->BakeCount;
  }
  state.Maps = planned;
  vtkOpenGLCheckErrorMacro("failed after rendering the cascaded shadow maps");
}

namespace
{
/// The nearest and farthest sample of the renderer's viewport in the framebuffer being drawn
/// (window depths); false when they cannot be read (a multisampled framebuffer, a GL error).
bool readWindowDepths(vtkRenderer* renderer, double range[2])
{
  vtkOpenGLRenderWindow* window =
    vtkOpenGLRenderWindow::SafeDownCast(renderer ? renderer->GetRenderWindow() : nullptr);
  if (!window)
  {
    return false;
  }
  int width = 0, height = 0, x = 0, y = 0;
  renderer->GetTiledSizeAndOrigin(&width, &height, &x, &y);
  if (width < 1 || height < 1)
  {
    return false;
  }
  vtkOpenGLState* state = window->GetState();
  GLint sampleBuffers = 0;
  glGetIntegerv(GL_SAMPLE_BUFFERS, &sampleBuffers);
  if (sampleBuffers > 0)
  {
    return false; // a multisampled framebuffer's depth cannot be read directly
  }
  vtkOpenGLClearErrorMacro();
  // Read from the framebuffer being drawn (the window's, or the one a pass around us set).
  unsigned int drawBinding = 0, drawBuffer = 0;
  state->GetCurrentDrawFramebufferState(drawBinding, drawBuffer);
  state->PushReadFramebufferBinding();
  state->vtkglBindFramebuffer(GL_READ_FRAMEBUFFER, drawBinding);
  std::vector<float> depths(static_cast<size_t>(width) * static_cast<size_t>(height));
  state->vtkglPixelStorei(GL_PACK_ALIGNMENT, 4);
  glReadPixels(x, y, width, height, GL_DEPTH_COMPONENT, GL_FLOAT, depths.data());
  const bool ok = glGetError() == GL_NO_ERROR;
  state->PopReadFramebufferBinding();
  if (!ok)
  {
    return false;
  }
  const csm::WindowDepthRange samples = csm::windowDepthRange(depths.data(), depths.size());
  range[0] = samples.min;
  range[1] = samples.max;
  return true;
}

}

void vtkCascadedShadowMapBakerPass::MeasureVisibleDepths(vtkOpenGLRenderer* renderer,
  const vtkRenderState* s, RendererMaps& state, const FrameProps& props)
{
  vtkCamera* camera = renderer->GetActiveCamera();
  const double aspect = renderer->GetTiledAspectRatio();
  state.VisibleDepthsMeasured = false;
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
  vtkOpenGLRenderWindow* window = static_cast<vtkOpenGLRenderWindow*>(renderer->GetRenderWindow());
  GLint sampleBuffers = 0;
  glGetIntegerv(GL_SAMPLE_BUFFERS, &sampleBuffers);
  if (sampleBuffers > 0)
  {
    return; // a multisampled depth buffer cannot be read directly: fitted to the boxes
  }
  // The casters the view can see, their depth only, into the frame's own depth buffer (the
  // camera pass set its viewport and scissor and cleared it), which is cleared again after.
  int width = 0, height = 0, x = 0, y = 0;
  renderer->GetTiledSizeAndOrigin(&width, &height, &x, &y);
  vtkMatrix4x4* worldToClip = camera->GetCompositeProjectionTransformMatrix(aspect, -1, 1);
  std::vector<vtkProp*> drawn;
  for (const FrameProps::Caster& caster : props.Casters)
  {
    if (!vtkCascadedShadowMapPlanner::CascadeReachesBox(
          worldToClip->GetData(), caster.Bounds.data(), false))
    {
      continue;
    }
    if (caster.Compact >= 0)
    {
      const FrameProps::Compact& compact = props.Compacts[static_cast<size_t>(caster.Compact)];
      std::vector<size_t> blocks;
      for (size_t k = 0; k < compact.Bounds.size(); ++k)
      {
        if (vtkCascadedShadowMapPlanner::CascadeReachesBox(
              worldToClip->GetData(), compact.Bounds[k].data(), false))
        {
          blocks.push_back(k);
        }
      }
      compact.Mapper->SetDrawnBlocks(blocks);
    }
    drawn.push_back(caster.Prop);
  }
  vtkOpenGLState* ostate = window->GetState();
  vtkOpenGLState::ScopedglDepthMask savedDepthMask(ostate);
  vtkOpenGLState::ScopedglColorMask savedColorMask(ostate);
  vtkOpenGLState::ScopedglEnableDisable savedDepthTest(ostate, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglEnableDisable savedOffsetFill(ostate, GL_POLYGON_OFFSET_FILL);
  vtkOpenGLState::ScopedglEnableDisable savedOffsetLine(ostate, GL_POLYGON_OFFSET_LINE);
  vtkOpenGLState::ScopedglEnableDisable savedOffsetPoint(ostate, GL_POLYGON_OFFSET_POINT);
  ostate->vtkglColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  ostate->vtkglDepthMask(GL_TRUE);
  ostate->vtkglEnable(GL_DEPTH_TEST);
  // The depth stays for the frame's own geometry pass, which then shades only the fragments
  // it keeps (the lookup is its costliest part): a little farther than the surfaces, so that
  // the same surface drawn by other shaders passes the depth test (GL_LEQUAL).
  ostate->vtkglEnable(GL_POLYGON_OFFSET_FILL);
  ostate->vtkglEnable(GL_POLYGON_OFFSET_LINE);
  ostate->vtkglEnable(GL_POLYGON_OFFSET_POINT);
  glPolygonOffset(kPrePassOffsetFactor, kPrePassOffsetUnits);
  // Screen-sized casters as wide as this view draws them: the "map" is the view itself.
  double key[18];
  casterView(renderer, camera, key);
  vtkNew<vtkMatrix4x4> viewToClip, clipToView;
  viewToClip->DeepCopy(camera->GetProjectionTransformMatrix(aspect, -1, 1));
  vtkMatrix4x4::Invert(viewToClip, clipToView);
  vtkCascadedShadowCasterPass::CasterUniforms u;
  toColumnMajor(clipToView->GetData(), u.MapToView);
  toColumnMajor(viewToClip->GetData(), u.ViewToMap);
  const bool parallel = camera->GetParallelProjection() != 0;
  u.LightView[2] = parallel ? 1.0f : 0.0f; // toward the eye
  u.LightView[3] = parallel ? 0.0f : 1.0f;
  u.PixelWorld[0] = static_cast<float>(key[16]);
  u.PixelWorld[1] = static_cast<float>(key[17]);
  u.Viewport[0] = static_cast<float>(x);
  u.Viewport[1] = static_cast<float>(y);
  u.Viewport[2] = static_cast<float>(width);
  u.Viewport[3] = static_cast<float>(height);
  this->CasterPass->BeginCascade(ostate, u, {});
  this->CasterPass->DrawCasters(renderer, s->GetFrameBuffer(), drawn);
  this->CasterPass->EndCascade();
  double samples[2] = { 1.0, 0.0 };
  const bool read = readWindowDepths(renderer, samples);
  if (!this->KeepPrePassDepth)
  {
    ostate->vtkglClear(GL_DEPTH_BUFFER_BIT);
  }
  ++this->VisibleDepthMeasures;
  if (read && samples[0] <= samples[1])
  {
    state.VisibleCamera = vtkSmartPointer<vtkCamera>::New();
    state.VisibleCamera->DeepCopy(camera);
    state.VisibleAspect = aspect;
    state.VisibleWindow[0] = samples[0];
    state.VisibleWindow[1] = samples[1];
    state.VisibleDepthsMeasured = true;
  }
}

void vtkCascadedShadowMapBakerPass::CollectProps(
  vtkRenderer* renderer, RendererMaps& state, FrameProps& props)
{
  // Bounds first: computing them brings the props' pipelines up to date, which must not count
  // as a change next frame.
  renderer->ComputeVisiblePropBounds(props.SceneBounds);
  props.Changed = this->InputsChanged(renderer, state) || state.Maps.empty();
  // Forget the closed-surface answers for data that is gone, and the blocks of data or props
  // that are gone (releasing their buffers in this window's context, which is current).
  for (auto it = this->Closures.begin(); it != this->Closures.end();)
  {
    it = it->second.Data ? std::next(it) : this->Closures.erase(it);
  }
  vtkWindow* window = renderer->GetRenderWindow();
  for (auto it = this->Blocks.begin(); it != this->Blocks.end();)
  {
    const bool gone = !it->second.Window || !it->second.Data;
    if (gone && it->second.Window == window && it->second.Mapper)
    {
      it->second.Mapper->ReleaseGraphicsResources(window);
    }
    it = gone ? this->Blocks.erase(it) : std::next(it);
  }
  for (auto it = this->Proxies.begin(); it != this->Proxies.end();)
  {
    it = it->second.Window && it->second.Prop ? std::next(it) : this->Proxies.erase(it);
  }
  // Casters: visible opaque props. Receivers: every visible prop; their boxes fit the cascades.
  vtkPropCollection* collection = renderer->GetViewProps();
  vtkCollectionSimpleIterator pit;
  collection->InitTraversal(pit);
  while (vtkProp* prop = collection->GetNextProp(pit))
  {
    std::array<double, 6> b;
    if (propBounds(prop, b.data()))
    {
      props.Receivers.push_back(b);
      if (prop->HasOpaqueGeometry())
      {
        const int closure = this->ClosureOf(prop);
        this->Statistics.ClosedCasters += closure != 0 ? 1 : 0;
        const size_t first = props.Casters.size();
        if (this->CompactCasters &&
          this->AddCompactCaster(
            prop, closure, static_cast<vtkOpenGLRenderWindow*>(renderer->GetRenderWindow()), props))
        {
          ++this->Statistics.CompactCasters;
        }
        else
        {
          FrameProps::Caster caster;
          caster.Prop = prop;
          caster.Bounds = b;
          caster.Closure = closure;
          props.Casters.push_back(caster);
        }
        const bool itself = this->ShadowsItself(prop);
        for (size_t i = first; i < props.Casters.size(); ++i)
        {
          FrameProps::Caster& caster = props.Casters[i];
          caster.ShadowsItself = itself;
          caster.Receiver = static_cast<int>(props.Receivers.size()) - 1;
          float sizes[2];
          vtkCascadedShadowMapBakerPass::GetScreenSizes(caster.Prop, sizes);
          const bool screenSized = sizes[0] > 1.0f || sizes[1] > 1.0f;
          if (caster.Compact < 0)
          {
            props.CasterLoads.push_back(
              { caster.Bounds, casterCells(caster.Prop), caster.Receiver, itself, screenSized });
            continue;
          }
          const FrameProps::Compact& compact = props.Compacts[static_cast<size_t>(caster.Compact)];
          for (size_t k = 0; k < compact.Bounds.size(); ++k)
          {
            props.CasterLoads.push_back(
              { compact.Bounds[k], compact.Cells[k], caster.Receiver, itself, screenSized });
          }
        }
      }
    }
  }
}

namespace
{
/// The positions and the triangles of a polydata's polygons (fans) and strips (false: no points).
/// Calls f(a, b, c) for every triangle of a polydata's polygons (fans) and strips, wound as
/// drawn; safe beside the main thread's own reading (each traversal has its own iterator).
/// Stops early (returning false) once `stop` is set.
template <typename F>
bool forEachTriangle(vtkPolyData* data, F&& f, const std::atomic<bool>* stop = nullptr)
{
  vtkIdType n;
  const vtkIdType* ids;
  vtkIdType visited = 0;
  auto stopped = [&visited, stop]()
  { return stop && (++visited & 0xfff) == 0 && stop->load(std::memory_order_relaxed); };
  auto polys = vtk::TakeSmartPointer(data->GetPolys()->NewIterator());
  for (polys->GoToFirstCell(); !polys->IsDoneWithTraversal(); polys->GoToNextCell())
  {
    if (stopped())
    {
      return false;
    }
    polys->GetCurrentCell(n, ids);
    for (vtkIdType k = 2; k < n; ++k)
    {
      f(ids[0], ids[k - 1], ids[k]);
    }
  }
  auto strips = vtk::TakeSmartPointer(data->GetStrips()->NewIterator());
  for (strips->GoToFirstCell(); !strips->IsDoneWithTraversal(); strips->GoToNextCell())
  {
    if (stopped())
    {
      return false;
    }
    strips->GetCurrentCell(n, ids);
    for (vtkIdType k = 2; k < n; ++k)
    {
      // Every other triangle of a strip is wound the other way round.
      if (k % 2 == 0)
      {
        f(ids[k - 2], ids[k - 1], ids[k]);
      }
      else
      {
        f(ids[k - 1], ids[k - 2], ids[k]);
      }
    }
  }
  return true;
}

/// Triangles of a polydata (polygons as fans, strips) without traversing them.
double triangleCount(vtkPolyData* data)
{
  const double polys = static_cast<double>(data->GetPolys()->GetNumberOfConnectivityIds()) -
    2.0 * static_cast<double>(data->GetPolys()->GetNumberOfCells());
  const double strips = static_cast<double>(data->GetStrips()->GetNumberOfConnectivityIds()) -
    2.0 * static_cast<double>(data->GetStrips()->GetNumberOfCells());
  return std::max(0.0, polys) + std::max(0.0, strips);
}

/// A big caster's triangles in compact blocks (csm::orderIntoBlocks), for
/// vtkCascadedShadowBlockMapper: the corners block after block, each block's triangles and its
/// box in the data's coordinates. Empty where the mesh has no usable triangle.
} // namespace

struct csmPreparedBlocks
{
  std::vector<std::uint32_t> Corners;
  std::vector<std::pair<std::size_t, std::size_t>> Blocks;
  std::vector<std::array<double, 6>> Bounds;
};

struct csmPreparedClosure
{
  csm::SurfaceClosure Closure;
};

namespace
{
std::shared_ptr<csmPreparedBlocks> prepareBlocks(
  vtkSmartPointer<vtkPolyData> data, std::size_t perBlock, const std::atomic<bool>* stop)
{
  auto result = std::make_shared<csmPreparedBlocks>();
  vtkPoints* points = data->GetPoints();
  const vtkIdType pointCount = points ? points->GetNumberOfPoints() : 0;
  if (pointCount == 0 ||
    pointCount > static_cast<vtkIdType>(std::numeric_limits<std::uint32_t>::max()))
  {
    return result;
  }
  std::vector<std::uint32_t> corners;
  std::vector<glm::vec3> centroids;
  corners.reserve(3 * static_cast<size_t>(triangleCount(data)));
  centroids.reserve(static_cast<size_t>(triangleCount(data)));
  bool valid = true;
  valid = forEachTriangle(
            data,
            [&](vtkIdType a, vtkIdType b, vtkIdType c)
            {
              if (a < 0 || b < 0 || c < 0 || a >= pointCount || b >= pointCount || c >= pointCount)
              {
                valid = false;
                return;
              }
              if (a == b || b == c || c == a)
              {
                return; // covers no texel
              }
              double pa[3], pb[3], pc[3];
              points->GetPoint(a, pa);
              points->GetPoint(b, pb);
              points->GetPoint(c, pc);
              corners.insert(corners.end(),
                { static_cast<std::uint32_t>(a), static_cast<std::uint32_t>(b),
                  static_cast<std::uint32_t>(c) });
              centroids.emplace_back(static_cast<float>((pa[0] + pb[0] + pc[0]) / 3.0),
                static_cast<float>((pa[1] + pb[1] + pc[1]) / 3.0),
                static_cast<float>((pa[2] + pb[2] + pc[2]) / 3.0));
            },
            stop) &&
    valid;
  if (!valid || centroids.empty())
  {
    return result;
  }
  csm::BlockOrder order = csm::orderIntoBlocks(centroids, perBlock);
  std::vector<glm::vec3>().swap(centroids);
  if (order.blocks.empty() || (stop && stop->load()))
  {
    return result;
  }
  result->Corners.resize(corners.size());
  for (size_t i = 0; i < order.order.size(); ++i)
  {
    std::copy_n(corners.begin() + 3 * static_cast<std::ptrdiff_t>(order.order[i]), 3,
      result->Corners.begin() + 3 * static_cast<std::ptrdiff_t>(i));
  }
  std::vector<std::uint32_t>().swap(corners);
  std::vector<std::uint32_t>().swap(order.order);
  result->Blocks = std::move(order.blocks);
  for (const auto& [first, count] : result->Blocks)
  {
    std::array<double, 6> box = { VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX, VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX,
      VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX };
    for (size_t i = 3 * first; i < 3 * (first + count); ++i)
    {
      double p[3];
      points->GetPoint(result->Corners[i], p);
      for (int k = 0; k < 3; ++k)
      {
        box[2 * k] = std::min(box[2 * k], p[k]);
        box[2 * k + 1] = std::max(box[2 * k + 1], p[k]);
      }
    }
    result->Bounds.push_back(box);
  }
  return result;
}

bool trianglesOf(vtkPolyData* data, std::vector<glm::dvec3>& positions,
  std::vector<std::array<std::int64_t, 3>>& triangles, const std::atomic<bool>* stop = nullptr)
{
  // (Cell iterators and GetPoint into a buffer: safe beside the main thread's own reading.)
  vtkPoints* points = data->GetPoints();
  if (!points || points->GetNumberOfPoints() == 0)
  {
    return false;
  }
  positions.resize(static_cast<size_t>(points->GetNumberOfPoints()));
  for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i)
  {
    double p[3];
    points->GetPoint(i, p);
    positions[static_cast<size_t>(i)] = glm::dvec3(p[0], p[1], p[2]);
  }
  triangles.clear();
  return forEachTriangle(
    data,
    [&triangles](vtkIdType a, vtkIdType b, vtkIdType c) {
      triangles.push_back({ a, b, c });
    },
    stop);
}

/// csm::classifySurface of a polydata.
csm::SurfaceClosure classifyPolyData(vtkPolyData* data, const std::atomic<bool>* stop = nullptr)
{
  std::vector<glm::dvec3> positions;
  std::vector<std::array<std::int64_t, 3>> triangles;
  return trianglesOf(data, positions, triangles, stop) ? csm::classifySurface(positions, triangles)
                                                       : csm::SurfaceClosure();
}

/// The polydata of a prop that may be drawn from compact blocks: a plain actor and mapper,
/// polygons or strips drawn as a surface, nothing else (see CompactCasters).
vtkPolyData* compactableData(vtkProp* prop)
{
  vtkActor* actor = vtkActor::SafeDownCast(prop);
  vtkProperty* property = actor ? actor->GetProperty() : nullptr;
  vtkPolyDataMapper* mapper = actor ? vtkPolyDataMapper::SafeDownCast(actor->GetMapper()) : nullptr;
  vtkPolyData* data = mapper ? mapper->GetInput() : nullptr;
  // Subclasses (followers, LOD actors, impostor and splat mappers) draw what their class knows.
  if (!data || !property || std::strcmp(actor->GetClassName(), "vtkOpenGLActor") != 0 ||
    std::strcmp(mapper->GetClassName(), "vtkOpenGLPolyDataMapper") != 0 ||
    property->GetRepresentation() != VTK_SURFACE || mapper->GetNumberOfClippingPlanes() > 0 ||
    data->GetNumberOfVerts() > 0 || data->GetNumberOfLines() > 0 ||
    data->GetNumberOfPolys() + data->GetNumberOfStrips() == 0)
  {
    return nullptr;
  }
  return data;
}

}

const vtkCascadedShadowMapBakerPass::Closure& vtkCascadedShadowMapBakerPass::ClassifiedShape(
  vtkPolyData* data)
{
  Closure& closure = this->Closures[data];
  if (closure.Data == data && closure.Time == data->GetMTime())
  {
    return closure;
  }
  closure.Data = data;
  // Until it is classified, a shape counts as open (drawn with both sides, its full bias) and
  // as one that may shadow itself: correct, only without the savings of a closed one.
  closure.Orientation = 0;
  closure.Planar = false;
  closure.ShadowsItself = true;
  const double triangles = triangleCount(data);
  if (triangles > MOST_CLASSIFIED_TRIANGLES)
  {
    closure.Time = data->GetMTime(); // not classified: what it costs outweighs what it saves
    return closure;
  }
  csm::SurfaceClosure c;
  if (triangles <= SYNCHRONOUS_PREPARATION_TRIANGLES)
  {
    c = classifyPolyData(data);
  }
  else
  {
    // A big mesh is classified by a worker thread; frames go on meanwhile.
    if (!closure.Pending.valid() || closure.PendingTime != data->GetMTime())
    {
      // (From the second frame that draws it on, as its blocks.)
      if (closure.SeenTime != data->GetMTime() || closure.SeenFrame >= this->FrameNumber ||
        !this->ViewMoved)
      {
        if (closure.SeenTime != data->GetMTime())
        {
          closure.SeenTime = data->GetMTime();
          closure.SeenFrame = this->FrameNumber;
        }
        return closure;
      }
      auto copy = vtkSmartPointer<vtkPolyData>::New();
      copy->ShallowCopy(data);
      closure.PendingTime = data->GetMTime();
      std::shared_ptr<std::atomic<bool>> stop = this->StopWorkers;
      closure.Pending = std::async(std::launch::async,
        [copy, stop]()
        {
          auto prepared = std::make_shared<csmPreparedClosure>();
          prepared->Closure = classifyPolyData(copy, stop.get());
          return prepared;
        });
      return closure;
    }
    if (closure.Pending.wait_for(std::chrono::seconds(0)) != std::future_status::ready)
    {
      return closure;
    }
    c = closure.Pending.get()->Closure;
  }
  closure.Time = data->GetMTime();
  closure.Orientation = c.closed && c.volume != 0.0 ? (c.volume > 0.0 ? 1 : -1) : 0;
  closure.Planar = c.planar;
  closure.ShadowsItself = c.canShadowItself();
  return closure;
}

bool vtkCascadedShadowMapBakerPass::ShadowsItself(vtkProp* prop)
{
  // Only surfaces drawn as they are, by the plain mapper (impostor and splat mappers draw
  // spheres and discs around the points, which stand out of a plane): lines and points may be
  // drawn as tubes and spheres, and the user's clipping planes open a solid (its inside then
  // shows).
  vtkActor* actor = vtkActor::SafeDownCast(prop);
  vtkPolyDataMapper* mapper = actor ? vtkPolyDataMapper::SafeDownCast(actor->GetMapper()) : nullptr;
  vtkPolyData* data = mapper ? mapper->GetInput() : nullptr;
  vtkProperty* property = actor ? actor->GetProperty() : nullptr;
  if (!this->CullCastersWithoutReceivers || !data || !property ||
    std::strcmp(mapper->GetClassName(), "vtkOpenGLPolyDataMapper") != 0 ||
    property->GetRepresentation() != VTK_SURFACE || data->GetNumberOfVerts() > 0 ||
    data->GetNumberOfLines() > 0)
  {
    return true;
  }
  const Closure& closure = this->ClassifiedShape(data);
  return mapper->GetNumberOfClippingPlanes() > 0 ? !closure.Planar : closure.ShadowsItself;
}

bool vtkCascadedShadowMapBakerPass::CasterHasReceivers(
  const FrameProps& props, const FrameProps::Caster& caster, const LightMaps& maps) const
{
  // Directional lights only; with several processes the receivers are everyone's boxes.
  if (caster.ShadowsItself || caster.Receiver < 0 || maps.LightGeometry[6] >= 0.0 ||
    this->Distributed() || props.Receivers.size() > kMaxReceiverTests)
  {
    return true;
  }
  const double travel[3] = { maps.LightGeometry[3] - maps.LightGeometry[0],
    maps.LightGeometry[4] - maps.LightGeometry[1], maps.LightGeometry[5] - maps.LightGeometry[2] };
  // A shadow shorter than a millionth of the scene is no shadow (the lookup's bias hides it).
  const double* s = props.SceneBounds;
  const double minimum = 1e-6 *
    std::sqrt((s[1] - s[0]) * (s[1] - s[0]) + (s[3] - s[2]) * (s[3] - s[2]) +
      (s[5] - s[4]) * (s[5] - s[4]));
  for (size_t r = 0; r < props.Receivers.size(); ++r)
  {
    if (static_cast<int>(r) != caster.Receiver &&
      vtkCascadedShadowMapPlanner::CasterBoxReachesBox(
        travel, caster.Bounds.data(), props.Receivers[r].data(), minimum))
    {
      return true;
    }
  }
  return false;
}

int vtkCascadedShadowMapBakerPass::ClosureOf(vtkProp* prop)
{
  vtkActor* actor = vtkActor::SafeDownCast(prop);
  vtkPolyDataMapper* mapper = actor ? vtkPolyDataMapper::SafeDownCast(actor->GetMapper()) : nullptr;
  vtkPolyData* data = mapper ? mapper->GetInput() : nullptr;
  vtkProperty* property = actor ? actor->GetProperty() : nullptr;
  if (!this->CullClosedCasters || !data || !property ||
    property->GetRepresentation() != VTK_SURFACE || property->GetBackfaceCulling() ||
    property->GetFrontfaceCulling() || mapper->GetNumberOfClippingPlanes() > 0 ||
    data->GetNumberOfVerts() > 0 || data->GetNumberOfLines() > 0)
  {
    return 0;
  }
  const Closure& closure = this->ClassifiedShape(data);
  const double determinant = actor->GetMatrix()->Determinant();
  if (closure.Orientation == 0 || !std::isfinite(determinant) || determinant == 0.0)
  {
    return 0;
  }
  return determinant > 0.0 ? closure.Orientation : -closure.Orientation;
}

bool vtkCascadedShadowMapBakerPass::AddCompactCaster(
  vtkProp* prop, int closure, vtkOpenGLRenderWindow* window, FrameProps& props)
{
  vtkPolyData* data = compactableData(prop);
  if (!data || !window)
  {
    return false;
  }
  // The data's blocks in this window, prepared again when the data changed: a small mesh at
  // once, a big one by a worker thread while the frames draw the prop as it is (correct, only
  // without culling inside it) until the blocks are ready.
  CasterBlocks& blocks = this->Blocks[{ window, data }];
  const vtkMTimeType dataTime = data->GetMTime();
  const bool current = blocks.Data == data && blocks.Window == window && blocks.Time == dataTime &&
    blocks.Mapper && blocks.Mapper->HasTriangles();
  if (!current)
  {
    if (!blocks.Pending.valid() || blocks.PendingTime != dataTime || blocks.Data != data ||
      blocks.Window != window)
    {
      const size_t triangles = static_cast<size_t>(triangleCount(data));
      const bool now = triangles <= SYNCHRONOUS_PREPARATION_TRIANGLES;
      // A big mesh is prepared once a later frame's view moved (the maps that follow a moving
      // view are drawn again and again; a still view keeps its maps): a single image (a
      // screenshot, a batch frame, even rendered twice) never waits for, nor holds the memory
      // of, its preparation.
      const bool seen = blocks.SeenTime == dataTime && blocks.Data == data &&
        blocks.Window == window && blocks.SeenFrame < this->FrameNumber && this->ViewMoved;
      if (!seen)
      {
        blocks.SeenFrame = this->FrameNumber;
      }
      blocks.Window = window;
      blocks.Data = data;
      blocks.SeenTime = dataTime;
      if (!now && !seen)
      {
        return false;
      }
      auto copy = vtkSmartPointer<vtkPolyData>::New();
      copy->ShallowCopy(data); // the prop's own points and cells, held while prepared
      const size_t perBlock = std::max<size_t>(
        MINIMUM_BLOCK_TRIANGLES, (triangles + MAXIMUM_BLOCKS - 1) / MAXIMUM_BLOCKS);
      blocks.PendingTime = dataTime;
      blocks.Pending = std::async(now ? std::launch::deferred : std::launch::async,
        [copy, perBlock, stop = this->StopWorkers]()
        { return prepareBlocks(copy, perBlock, stop.get()); });
      if (!now)
      {
        return false; // (picked up in a later frame, whenever it is ready)
      }
    }
    if (blocks.Pending.wait_for(std::chrono::seconds(0)) == std::future_status::timeout)
    {
      return false;
    }
    std::shared_ptr<csmPreparedBlocks> prepared = blocks.Pending.get();
    if (blocks.Mapper)
    {
      blocks.Mapper->ReleaseGraphicsResources(window);
    }
    blocks.Mapper = nullptr;
    blocks.Bounds.clear();
    blocks.Cells.clear();
    blocks.Time = dataTime;
    blocks.Build = ++this->BlockBuilds;
    if (prepared->Blocks.empty())
    {
      return false; // nothing usable (no area, a bad index or position): drawn as it is
    }
    // The prop's own points (the vertex buffer its mapper uploads serves both, through the
    // window's buffer cache), the blocks' triangles.
    auto input = vtkSmartPointer<vtkPolyData>::New();
    input->SetPoints(data->GetPoints());
    blocks.Mapper = vtkSmartPointer<vtkCascadedShadowBlockMapper>::New();
    blocks.Mapper->SetInputData(input);
    blocks.Mapper->ScalarVisibilityOff();
    for (const auto& block : prepared->Blocks)
    {
      blocks.Cells.push_back(static_cast<double>(block.second));
    }
    blocks.Bounds = std::move(prepared->Bounds);
    blocks.Mapper->SetBlocks(std::move(prepared->Corners), std::move(prepared->Blocks));
  }
  if (!blocks.Mapper)
  {
    return false;
  }
  // The prop's actor for its blocks: its property, a copy of its matrix.
  vtkActor* actor = vtkActor::SafeDownCast(prop);
  CasterProxy& proxy = this->Proxies[{ window, prop }];
  if (proxy.Prop != prop || proxy.Window != window || proxy.Data != data ||
    proxy.Build != blocks.Build)
  {
    proxy.Prop = prop;
    proxy.Window = window;
    proxy.Data = data;
    proxy.Build = blocks.Build;
    proxy.Matrix = vtkSmartPointer<vtkMatrix4x4>::New();
    proxy.Actor = vtkSmartPointer<vtkActor>::New();
    proxy.Actor->SetMapper(blocks.Mapper);
    proxy.Actor->SetUserMatrix(proxy.Matrix);
  }
  vtkMatrix4x4* matrix = actor->GetMatrix();
  if (!std::equal(matrix->GetData(), matrix->GetData() + 16, proxy.Matrix->GetData()))
  {
    proxy.Matrix->DeepCopy(matrix);
  }
  proxy.Actor->SetProperty(actor->GetProperty());
  FrameProps::Compact compact;
  compact.Mapper = blocks.Mapper;
  compact.Cells = blocks.Cells;
  for (const std::array<double, 6>& local : blocks.Bounds)
  {
    // The block's box in world space: the box of its corners' images.
    std::array<double, 6> world = { VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX, VTK_DOUBLE_MAX,
      -VTK_DOUBLE_MAX, VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX };
    for (int corner = 0; corner < 8; ++corner)
    {
      const double p[4] = { local[corner & 1], local[2 + ((corner >> 1) & 1)],
        local[4 + ((corner >> 2) & 1)], 1.0 };
      double q[4];
      matrix->MultiplyPoint(p, q);
      for (int k = 0; k < 3; ++k)
      {
        const double v = q[k] / q[3];
        world[2 * k] = std::min(world[2 * k], v);
        world[2 * k + 1] = std::max(world[2 * k + 1], v);
      }
    }
    if (!std::all_of(world.begin(), world.end(), [](double v) { return std::isfinite(v); }))
    {
      return false; // a matrix that sends a corner to infinity: the prop is drawn as it is
    }
    compact.Bounds.push_back(world);
  }
  std::array<double, 6> whole = compact.Bounds.front();
  for (const auto& box : compact.Bounds)
  {
    for (int k = 0; k < 3; ++k)
    {
      whole[2 * k] = std::min(whole[2 * k], box[2 * k]);
      whole[2 * k + 1] = std::max(whole[2 * k + 1], box[2 * k + 1]);
    }
  }
  FrameProps::Caster caster;
  caster.Prop = proxy.Actor;
  caster.Bounds = whole;
  caster.Closure = closure;
  caster.Compact = static_cast<int>(props.Compacts.size());
  props.Compacts.push_back(std::move(compact));
  props.Casters.push_back(caster);
  return true;
}

void vtkCascadedShadowMapBakerPass::GatherAcrossProcesses(FrameProps& props)
{
  // All processes plan from the global bounds and the same receiver boxes, and re-render when
  // any of them saw a change.
  double* sceneBounds = props.SceneBounds;
  double lo[3] = { sceneBounds[0], sceneBounds[2], sceneBounds[4] };
  double hi[3] = { sceneBounds[1], sceneBounds[3], sceneBounds[5] };
  double globalLo[3], globalHi[3];
  this->Controller->AllReduce(lo, globalLo, 3, vtkCommunicator::MIN_OP);
  this->Controller->AllReduce(hi, globalHi, 3, vtkCommunicator::MAX_OP);
  for (int i = 0; i < 3; ++i)
  {
    sceneBounds[2 * i] = globalLo[i];
    sceneBounds[2 * i + 1] = globalHi[i];
  }
  int changed = props.Changed ? 1 : 0, anyChanged = 0;
  this->Controller->AllReduce(&changed, &anyChanged, 1, vtkCommunicator::MAX_OP);
  props.Changed = anyChanged != 0;
  // The caster loads of every process (padded with loads of no cells).
  {
    // Box, cells, shadows itself, screen-sized (their receiver indices are each process's
    // own: dropped).
    constexpr size_t n = 9;
    std::vector<FrameProps::CasterLoad>& loads = props.CasterLoads;
    int mineCount = static_cast<int>(loads.size()), mostLoads = 0;
    this->Controller->AllReduce(&mineCount, &mostLoads, 1, vtkCommunicator::MAX_OP);
    std::vector<double> mineLoads(n * static_cast<size_t>(mostLoads), 0.0), allLoads;
    for (int i = 0; i < mineCount; ++i)
    {
      double* out = mineLoads.data() + n * i;
      std::copy(loads[i].Bounds.begin(), loads[i].Bounds.end(), out);
      out[6] = loads[i].Cells;
      out[7] = loads[i].ShadowsItself ? 1.0 : 0.0;
      out[8] = loads[i].ScreenSized ? 1.0 : 0.0;
    }
    allLoads.resize(mineLoads.size() * this->Controller->GetNumberOfProcesses());
    this->Controller->AllGather(
      mineLoads.data(), allLoads.data(), static_cast<vtkIdType>(mineLoads.size()));
    loads.clear();
    for (size_t i = 0; i + n <= allLoads.size(); i += n)
    {
      if (allLoads[i + 6] > 0.0) // (padding has no cells)
      {
        FrameProps::CasterLoad load;
        std::copy(allLoads.begin() + i, allLoads.begin() + i + 6, load.Bounds.begin());
        load.Cells = allLoads[i + 6];
        load.ShadowsItself = allLoads[i + 7] != 0.0;
        load.ScreenSized = allLoads[i + 8] != 0.0;
        loads.push_back(load);
      }
    }
  }
  // The receiver boxes of every process (padded with empty boxes).
  std::vector<std::array<double, 6>>& receivers = props.Receivers;
  int count = static_cast<int>(receivers.size()), most = 0;
  this->Controller->AllReduce(&count, &most, 1, vtkCommunicator::MAX_OP);
  std::vector<double> mine(6 * static_cast<size_t>(most), 0.0), all;
  for (int i = 0; i < most; ++i)
  {
    for (int k = 0; k < 6; ++k)
    {
      mine[6 * i + k] = i < count ? receivers[i][k] : (k % 2 == 0 ? 1.0 : -1.0);
    }
  }
  all.resize(mine.size() * this->Controller->GetNumberOfProcesses());
  this->Controller->AllGather(mine.data(), all.data(), static_cast<vtkIdType>(mine.size()));
  receivers.clear();
  for (size_t i = 0; i + 5 < all.size(); i += 6)
  {
    if (all[i] <= all[i + 1])
    {
      receivers.push_back({ all[i], all[i + 1], all[i + 2], all[i + 3], all[i + 4], all[i + 5] });
    }
  }
}

void vtkCascadedShadowMapBakerPass::PlanLights(vtkRenderer* renderer, vtkOpenGLRenderWindow* window,
  RendererMaps& state, const FrameProps& props, std::vector<LightMaps>& planned,
  std::vector<int>& render)
{
  vtkCamera* camera = renderer->GetActiveCamera();
  const bool depthClamp = this->Planner->GetDepthClamp();
  const double aspect = renderer->GetTiledAspectRatio();
  const double* sceneBounds = props.SceneBounds;
  // The receivers' boxes fit the cascades (up to kMaxReceiverBoxes; beyond, the box around all
  // of them).
  this->Planner->ClearReceiverBounds();
  if (props.Receivers.size() <= kMaxReceiverBoxes)
  {
    for (const auto& b : props.Receivers)
    {
      this->Planner->AddReceiverBounds(b.data());
    }
  }
  // What each cascade's pass would draw weighs the cascade count (up to kMaxCasterLoads
  // casters; beyond, one load of all their cells in the scene's box, which every cascade draws).
  // Screen-sized casters (tubes, spheres, wide lines) cost their fragments, not their cells,
  // and have no fixed extent: with any of them the count is the fewest that meets the target
  // and there is no scene-fitted map (measured on the tube-drawn platform, `csm-bench --quick
  // --scenes platform-beams`: weighed by cells, paths 1.35-1.44x VTK's; unweighed 1.03x).
  this->Planner->ClearCasterLoads();
  const bool screenSizedCasters = std::any_of(props.CasterLoads.begin(), props.CasterLoads.end(),
    [](const FrameProps::CasterLoad& l) { return l.ScreenSized; });
  if (!screenSizedCasters && props.CasterLoads.size() <= kMaxCasterLoads)
  {
    for (const auto& load : props.CasterLoads)
    {
      this->Planner->AddCasterLoad(load.Bounds.data(), load.Cells,
        props.Receivers.size() <= kMaxReceiverBoxes ? load.Receiver : -1, load.ShadowsItself,
        load.ScreenSized);
    }
  }
  else if (!screenSizedCasters)
  {
    double cells = 0.0;
    for (const auto& load : props.CasterLoads)
    {
      cells += load.Cells;
    }
    this->Planner->AddCasterLoad(sceneBounds, cells);
  }
  // Plan every shadowed light for this frame, and decide per cascade whether the map kept from
  // an earlier frame still serves (only the camera moved, it covers, its error is bounded).
  // While the user interacts (VTK's convention: the interactor raises the window's desired
  // update rate), maps get a border and may be kept within MapReuseTolerance; a still frame
  // keeps only a map that is exactly the one it would plan, so it always has full quality.
  const bool interacting = vtkCascadedShadowMapBakerPass::IsInteracting(window);
  const double border = interacting ? this->InteractiveMapBorder : 0.0;
  // (The tolerance is against a fresh map with the same border, whose error is 1 + 2 border
  // times a tight one's.)
  const double tolerance = this->MapReuseTolerance * (1.0 + 2.0 * border);
  // Tubes, spheres, wide lines and big points are drawn into the maps as wide as the main view
  // draws them: a still frame keeps such a map only for the view it was sized for.
  const bool screenSized = hasScreenSizedCasters(props.Casters);
  // Resolution from need (ErrorTarget), up to the ceiling of this kind of frame.
  const int ceiling =
    interacting ? std::min(this->InteractiveResolution, this->Resolution) : this->Resolution;
  // And the cascades: more than fill the atlas with full maps only in a still frame (each is a
  // caster pass; they refine the error where four full maps cannot reach ErrorTarget).
  const int mostCascades = interacting ? csm::kAtlasFullMaps : 0;
  const int imageHeight = renderer->GetSize()[1];
  // The visible depths of this view (VisibleDepthFit; MeasureVisibleDepths).
  if (this->VisibleDepthFit && !this->Distributed() && state.VisibleCamera)
  {
    this->Planner->SetVisibleDepths(
      state.VisibleCamera, state.VisibleAspect, state.VisibleWindow[0], state.VisibleWindow[1]);
  }
  else
  {
    this->Planner->ClearVisibleDepths();
  }
  state.VisibleDepthsUsed = false;
  double viewKey[18];
  casterView(renderer, camera, viewKey);
  const int maximumLights = this->MaximumShadowedLights(window);
  int shadowingLights = 0;
  int lightIndex = 0;
  vtkLightCollection* lights = renderer->GetLights();
  vtkCollectionSimpleIterator lit;
  lights->InitTraversal(lit);
  while (vtkLight* light = lights->GetNextLight(lit))
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
    const size_t slot = planned.size();
    LightMaps maps;
    maps.Light = light;
    maps.LightIndex = index;
    const int count =
      this->Planner->Plan(camera, aspect, light, sceneBounds, imageHeight, ceiling, mostCascades);
    state.VisibleDepthsUsed = state.VisibleDepthsUsed || this->Planner->GetVisibleDepthsUsed();
    maps.NumberOfCascades = std::min(count, kMaxCascades);
#if CSM_COMPARISON_TECHNIQUES
    maps.Faces =
      count > 0 && !light->GetPositional() && this->Planner->GetCascadesSelectedByPlanes();
#endif
    light->GetTransformedPosition(maps.LightGeometry);
    light->GetTransformedFocalPoint(maps.LightGeometry + 3);
    maps.LightGeometry[6] = light->GetPositional() ? light->GetConeAngle() : -1.0;
#if CSM_COMPARISON_TECHNIQUES
    // (Face partitions and camera space maps are re-rendered every frame: compareKeptMap
    // measures the error along the cascades' map axes, which their maps do not have.)
    const bool ownMapAxes =
      this->Planner->GetFacePartitions() > 0 || this->Planner->GetCameraSpace();
#else
    const bool ownMapAxes = false;
#endif
    const LightMaps* kept = !props.Changed && depthClamp && !ownMapAxes &&
        slot < state.Maps.size() && state.Maps[slot].Light == light &&
        std::equal(maps.LightGeometry, maps.LightGeometry + 7, state.Maps[slot].LightGeometry) &&
        state.Maps[slot].NumberOfCascades == maps.NumberOfCascades
      ? &state.Maps[slot]
      : nullptr;
    // Slack pays only where the next frames can keep the map: a still frame of a camera on a
    // smooth path, the light and scene unchanged (a camera light moves with the camera).
    // (Judged per cascade: a step that moves a near cascade's small body out of any border may
    // leave a far one's well inside.)
    const bool smoothPath = !interacting && kept && maps.NumberOfCascades > 0;
    vtkNew<vtkMatrix4x4> m;
    // The largest maps this count of cascades has in the atlas (csm::ceilingsForCount: the
    // planner judged the count at the same).
    const csm::CascadeCeilings countCeilings =
      csm::ceilingsForCount(maps.NumberOfCascades, this->Planner->GetNumberOfCascades(), ceiling);
    for (int c = 0; c < maps.NumberOfCascades; ++c)
    {
      int* resolution = maps.CascadeResolution[c];
      maps.SceneFitted[c] = this->Planner->GetCascadeSceneFitted(c);
      const csm::MapSize& most = countCeilings.of(maps.SceneFitted[c]);
      const int countCeiling[2] = { most.width, most.height };
      this->Planner->GetCascadeResolution(
        c, imageHeight, RESOLUTION_STEP, countCeiling, resolution);
      const csm::MapSize need(resolution[0], resolution[1]);
      // A still frame's map that follows the view gets slack (a border and more texels), so
      // that the next frames of a camera that moves a little keep it while it meets what a
      // fresh map would (csm::slackedMap, csm::keptMapServes). Not for screen-sized casters,
      // whose maps serve only the view they were sized for.
      double cascadeBorder = border;
      if (smoothPath && !screenSized && !maps.SceneFitted[c] &&
        vtkCascadedShadowMapPlanner::IsSmallCameraStep(
          state.LastCamera, camera, aspect, this->Planner->GetCascadeFar(c)))
      {
        const csm::SlackedMap slacked = csm::slackedMap(need, most, this->MapSlack);
        cascadeBorder = slacked.border;
        resolution[0] = slacked.size.width;
        resolution[1] = slacked.size.height;
      }
      maps.MapTurned[c] = this->Planner->GetCascadeMapTurned(c);
      this->Planner->GetCascadeMatrix(c, m, cascadeBorder, resolution);
      std::copy(m->GetData(), m->GetData() + 16, maps.WorldToMap[c]);
      maps.SplitFar[c] = this->Planner->GetCascadeFar(c);
#if CSM_COMPARISON_TECHNIQUES
      this->Planner->GetCascadePlanes(c, maps.Planes[c]);
      maps.DepthW[c] = this->Planner->GetCascadeDepthW(c);
#endif
      // A kept map serves if it has the texels this view needs (or all its tile holds, where the
      // GL's texture size limit made the tiles smaller than Resolution): while the user
      // interacts, within MapReuseTolerance of a fresh map with the same border; in a still
      // frame, where its error at this view meets what a fresh tight map meets.
      // (Turned the same way: the error ratio compares the maps at equal resolution.)
      const int* keptResolution = kept ? kept->CascadeResolution[c] : nullptr;
      bool keep = kept &&
        (interacting || !screenSized || std::equal(viewKey, viewKey + 18, kept->CasterView[c])) &&
        kept->MapTurned[c] == maps.MapTurned[c];
      if (keep)
      {
        const double ratio = this->Planner->CompareKeptMap(c, kept->WorldToMap[c],
          kReuseMarginTexels, std::min(keptResolution[0], keptResolution[1]));
        // (Where the GL's texture size limit made the tile smaller than the need.)
        const csm::MapSize fits(
          std::min(need.width, kept->Resolution[0]), std::min(need.height, kept->Resolution[1]));
        keep = interacting
          ? keptResolution[0] >= std::min(resolution[0], kept->Resolution[0]) &&
            keptResolution[1] >= std::min(resolution[1], kept->Resolution[1]) && ratio <= tolerance
          : csm::keptMapServes(ratio, csm::MapSize(keptResolution[0], keptResolution[1]), fits);
      }
      if (keep)
      {
        std::copy(kept->WorldToMap[c], kept->WorldToMap[c] + 16, maps.WorldToMap[c]);
        std::copy(kept->CasterView[c], kept->CasterView[c] + 18, maps.CasterView[c]);
        std::copy(keptResolution, keptResolution + 2, resolution);
      }
      render.push_back(keep ? 0 : 1);
    }
    render.resize(kMaxCascades * (slot + 1), 0);
    if (maps.NumberOfCascades > 0)
    {
      maps.SplitNear = this->Planner->GetCascadeNear(0);
    }
    if (state.AtlasPool.size() <= slot)
    {
      state.AtlasPool.push_back(vtkSmartPointer<vtkTextureObject>::New());
    }
    maps.Atlas = state.AtlasPool[slot];
    planned.push_back(maps);
  }
  if (!state.LastCamera)
  {
    state.LastCamera = vtkSmartPointer<vtkCamera>::New();
  }
  state.LastCamera->DeepCopy(camera);
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

void vtkCascadedShadowMapBakerPass::RenderAtlases(vtkOpenGLRenderer* renderer,
  vtkOpenGLRenderWindow* window, RendererMaps& state, const FrameProps& props,
  std::vector<LightMaps>& planned, std::vector<int>& render)
{
  const bool depthClamp = this->Planner->GetDepthClamp();
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
    LightMaps& maps = planned[slot];
    bool reallocated = false;
    // One atlas for as many cascades as NumberOfCascades (the most AdaptiveCascades uses: the
    // count changes with the view, and a new atlas would cost its allocation and every map's
    // render): up to csm::kAtlasFullMaps tiles of Resolution texels, more cascades in smaller
    // tiles of the same area; each cascade's map fills the lower left of its tile with the
    // resolution PlanLights chose.
    if (!this->PrepareAtlas(window, maps,
          std::max(this->Planner->GetNumberOfCascades(), maps.NumberOfCascades), this->Resolution,
          reallocated))
    {
      maps.NumberOfCascades = 0;
      continue;
    }
    for (int c = 0; c < maps.NumberOfCascades; ++c)
    {
      int* resolution = maps.CascadeResolution[c];
      resolution[0] = std::max(1, std::min(resolution[0], maps.Resolution[0]));
      resolution[1] = std::max(1, std::min(resolution[1], maps.Resolution[1]));
      maps.Tile[c][2] = double(resolution[0]) / maps.Atlas->GetWidth();
      maps.Tile[c][3] = double(resolution[1]) / maps.Atlas->GetHeight();
    }
    int* renderCascade = render.data() + kMaxCascades * slot;
    bool any = false;
    for (int c = 0; c < maps.NumberOfCascades; ++c)
    {
      renderCascade[c] = renderCascade[c] || reallocated;
      any = any || renderCascade[c];
    }
    this->Statistics.CascadesKept += maps.NumberOfCascades;
    if (!any)
    {
      continue;
    }
    state.FrameBuffer->Bind();
    state.FrameBuffer->AddDepthAttachment(maps.Atlas);
    state.FrameBuffer->DeactivateDrawBuffers();
    state.FrameBuffer->DeactivateReadBuffer();
    if (state.FrameBuffer->CheckFrameBufferStatus(GL_FRAMEBUFFER) == 0)
    {
      this->ReportOnce(true, "The shadow map framebuffer is incomplete; no shadows");
      maps.NumberOfCascades = 0;
      continue;
    }
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
    glPolygonOffset(static_cast<GLfloat>(this->PolygonOffsetFactor),
      static_cast<GLfloat>(this->PolygonOffsetUnits));
    using Clock = std::chrono::steady_clock;
    auto since = Clock::now();
    // (MeasureTimes: each step's time up to its glFinish.)
    auto lap = [&](double& seconds)
    {
      glFinish();
      const auto now = Clock::now();
      seconds = std::chrono::duration<double>(now - since).count();
      since = now;
    };
    this->ClearTiles(ostate, maps, renderCascade);
    if (this->MeasureTimes && slot == 0)
    {
      lap(this->Statistics.ClearSeconds);
    }
    ostate->vtkglEnable(GL_SCISSOR_TEST);
    glEnable(GL_PROGRAM_POINT_SIZE); // points sized as the main view draws them
    for (int c = 0; c < maps.NumberOfCascades; ++c)
    {
      if (renderCascade[c])
      {
        --this->Statistics.CascadesKept;
        this->RenderCascade(renderer, state.FrameBuffer, maps, c, props, depthClamp);
        // Hand the map to the GL while the next one is set up: a software rasterizer fills
        // this one on its threads while this thread transforms and bins the next one's casters.
        glFlush();
        if (this->MeasureTimes && slot == 0)
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
  ostate->PopFramebufferBindings();
  ostate->vtkglCullFace(static_cast<unsigned int>(savedCullFace));
  renderer->SetAutomaticLightCreation(automaticLights);
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
  for (RendererMaps& state : this->Renderers)
  {
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
    state.Renderer = nullptr; // forgotten at the next Render()
  }
  this->Renderers.erase(std::remove_if(this->Renderers.begin(), this->Renderers.end(),
                          [](const RendererMaps& r) { return !r.Renderer; }),
    this->Renderers.end());
  // The compact blocks drawn in this window (all of them for no window).
  for (auto it = this->Blocks.begin(); it != this->Blocks.end();)
  {
    if (w && it->second.Window != w)
    {
      ++it;
      continue;
    }
    vtkWindow* context = w ? w : it->second.Window.GetPointer();
    if (it->second.Mapper && context)
    {
      it->second.Mapper->ReleaseGraphicsResources(context);
    }
    it = this->Blocks.erase(it);
  }
  for (auto it = this->Proxies.begin(); it != this->Proxies.end();)
  {
    it = !w || it->second.Window == w ? this->Proxies.erase(it) : std::next(it);
  }
}

vtkCascadedShadowMapPlanner* vtkCascadedShadowMapBakerPass::GetPlanner()
{
  return this->Planner;
}

// The planning options live in the planner; the baker forwards them.
#define csmForwardToPlanner(name, type)                                                            \
  void vtkCascadedShadowMapBakerPass::Set##name(type value)                                        \
  {                                                                                                \
    this->Planner->Set##name(value);                                                               \
  }                                                                                                \
  type vtkCascadedShadowMapBakerPass::Get##name()                                                  \
  {                                                                                                \
    return this->Planner->Get##name();                                                             \
  }
csmForwardToPlanner(NumberOfCascades, int)
csmForwardToPlanner(WarpMode, int)
csmForwardToPlanner(SplitScheme, int)
csmForwardToPlanner(Lambda, double)
csmForwardToPlanner(Alpha, double)
csmForwardToPlanner(DepthClamp, bool)
csmForwardToPlanner(SceneFittedCascades, bool)
csmForwardToPlanner(ErrorTarget, double)
csmForwardToPlanner(AdaptiveCascades, bool)
#if CSM_COMPARISON_TECHNIQUES
csmForwardToPlanner(FacePartitions, int)
csmForwardToPlanner(CameraSpace, bool)
csmForwardToPlanner(CameraSpaceFocus, double)
#endif
#undef csmForwardToPlanner

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
  os << indent << "PolygonOffsetFactor: " << this->PolygonOffsetFactor << "\n";
  os << indent << "PolygonOffsetUnits: " << this->PolygonOffsetUnits << "\n";
  os << indent << "MapReuseTolerance: " << this->MapReuseTolerance << "\n";
  os << indent << "InteractiveMapBorder: " << this->InteractiveMapBorder << "\n";
  os << indent << "MapSlack: " << this->MapSlack << "\n";
  os << indent << "MeasureTimes: " << (this->MeasureTimes ? "on" : "off") << "\n";
  os << indent << "CullClosedCasters: " << (this->CullClosedCasters ? "on" : "off") << "\n";
  os << indent << "VisibleDepthFit: " << (this->VisibleDepthFit ? "on" : "off") << "\n";
  os << indent
     << "CullCastersWithoutReceivers: " << (this->CullCastersWithoutReceivers ? "on" : "off")
     << "\n";
  os << indent << "CompactCasters: " << (this->CompactCasters ? "on" : "off") << "\n";
  os << indent << "Renderers: " << this->Renderers.size() << "\n";
  os << indent << "ShadowedLights: " << this->GetLightMaps().size() << "\n";
  os << indent << "Controller: " << this->Controller << "\n";
}
