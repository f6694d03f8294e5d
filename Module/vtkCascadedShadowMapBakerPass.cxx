#include "vtkCascadedShadowMapBakerPass.h"

#include "csmShadowSetup.h" // the shadow math: culling test

#include "vtkCamera.h"
#include "vtkCascadedShadowMapPlanner.h"
#include "vtkInformation.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkCommunicator.h"
#include "vtkMatrix4x4.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLError.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLRenderer.h"
#include "vtkOpenGLState.h"
#include "vtkProp.h"
#include "vtkPropCollection.h"
#include "vtkRenderState.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtkTextureUnitManager.h"
#include "vtk_glew.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>

vtkStandardNewMacro(vtkCascadedShadowMapBakerPass);
vtkCxxSetObjectMacro(vtkCascadedShadowMapBakerPass, Controller, vtkMultiProcessController);

namespace
{
constexpr int kMaxCascades = 8;
constexpr size_t kMaxReceiverBoxes = 64;
// Texture units of the fragment shader left to the mapper's own textures (colour, normal,
// ORM, emissive and anisotropy maps, and PBR's irradiance, prefiltered and BRDF maps).
constexpr int kMapperTextureUnits = 8;
// Fragment uniform components one shadowed light costs: 8 cascades of a mat4, a vec4 and a
// float (padded to a vec4), and the per-light values.
constexpr int kUniformComponentsPerLight = 8 * (16 + 4 + 4) + 16;
constexpr int kMapperUniformComponents = 1024;

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

/// Does any part of the box reach the light volume of a cascade (row-major world -> clip)?
bool reachesLightVolume(const double m[16], const double b[6], bool depthClamp)
{
  glm::dmat4 matrix;
  for (int row = 0; row < 4; ++row)
  {
    for (int column = 0; column < 4; ++column)
    {
      matrix[column][row] = m[4 * row + column];
    }
  }
  const csm::Bounds box{ { b[0], b[2], b[4] }, { b[1], b[3], b[5] } };
  return !csm::boxOutsideClipVolume(matrix, box, depthClamp);
}
}

vtkCascadedShadowMapBakerPass::vtkCascadedShadowMapBakerPass()
{
  this->Planner = vtkSmartPointer<vtkCascadedShadowMapPlanner>::New();
  this->FrameBuffer = vtkSmartPointer<vtkOpenGLFramebufferObject>::New();
  this->LightCamera = vtkSmartPointer<vtkCamera>::New();
  this->Projection = vtkSmartPointer<vtkMatrix4x4>::New();
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
  this->LastCombineSeconds +=
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

bool vtkCascadedShadowMapBakerPass::LightCastsShadows(vtkLight* light)
{
  return light && light->GetSwitch() && !light->LightTypeIsHeadlight() &&
    (!light->GetPositional() || light->GetConeAngle() < 90.0) &&
    light->GetShadowAttenuation() > 0.0f; // a shadow of attenuation 0 is invisible: no maps
}

bool vtkCascadedShadowMapBakerPass::NeedsBake(vtkRenderer* renderer)
{
  vtkMTimeType input = std::max(this->GetMTime(), renderer->GetActiveCamera()->GetMTime());
  vtkLightCollection* lights = renderer->GetLights();
  input = std::max(input, lights->GetMTime());
  vtkCollectionSimpleIterator lit;
  lights->InitTraversal(lit);
  while (vtkLight* light = lights->GetNextLight(lit))
  {
    input = std::max(input, light->GetMTime());
  }
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
  const bool changed = input > this->LastInputTime || size[0] != this->LastSize[0] ||
    size[1] != this->LastSize[1];
  this->LastInputTime = input;
  this->LastSize[0] = size[0];
  this->LastSize[1] = size[1];
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
  const int byUniforms =
    (static_cast<int>(components) - kMapperUniformComponents) / kUniformComponentsPerLight;
  return std::max(0, std::min(byUnits, byUniforms));
}

bool vtkCascadedShadowMapBakerPass::PrepareAtlas(
  vtkOpenGLRenderWindow* window, LightMaps& maps, int tiles)
{
  const int columns = std::min(tiles, 4);
  const int rows = (tiles + columns - 1) / columns;
  GLint maxSize = 4096;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
  int resolution = this->Resolution;
  if (resolution * columns > maxSize)
  {
    resolution = maxSize / columns;
    vtkWarningMacro(<< "Shadow map resolution " << this->Resolution << " x " << columns
                    << " cascades exceeds the GL limit " << maxSize << "; using " << resolution);
  }
  vtkTextureObject* atlas = maps.Atlas;
  const unsigned int width = static_cast<unsigned int>(columns * resolution);
  const unsigned int height = static_cast<unsigned int>(rows * resolution);
  if (atlas->GetContext() != window || atlas->GetWidth() != width || atlas->GetHeight() != height)
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
      vtkErrorMacro(<< "Cannot allocate a " << width << " x " << height << " shadow map atlas");
      return false;
    }
    // A new GL texture: its compare mode and filters must be sent again, but the setters above
    // did not change the object when the values were the same as before.
    atlas->Modified();
  }
  maps.Resolution = resolution;
  for (int i = 0; i < tiles; ++i)
  {
    maps.Tile[i][0] = double(i % columns) / columns;
    maps.Tile[i][1] = double(i / columns) / rows;
    maps.Tile[i][2] = 1.0 / columns;
    maps.Tile[i][3] = 1.0 / rows;
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
  if (!window || !camera)
  {
    return;
  }
  // Bounds first: computing them brings the props' pipelines up to date, which must not count
  // as a change next frame.
  double sceneBounds[6];
  renderer->ComputeVisiblePropBounds(sceneBounds);
  int needed = this->NeedsBake(renderer) || this->Maps.empty() ? 1 : 0;
  if (this->Distributed())
  {
    // All processes plan from the global bounds and bake together, or none does.
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
    int anyNeeded = 0;
    this->Controller->AllReduce(&needed, &anyNeeded, 1, vtkCommunicator::MAX_OP);
    needed = anyNeeded;
  }
  if (!needed)
  {
    return;
  }
  this->LastCombineSeconds = 0.0;
  ++this->BakeCount;
  this->LastCascadeRenders = 0;
  this->LastPropsDrawn = 0;

  // Plan every shadowed light first: nothing may move while the light camera is active.
  const bool depthClamp = this->Planner->GetDepthClamp();
  const int numberOfCascades = this->Planner->GetNumberOfCascades();
  const double aspect = renderer->GetTiledAspectRatio();

  // Casters: visible opaque props. Receivers: every visible prop; their boxes fit the cascades
  // (up to kMaxReceiverBoxes; beyond, the box around all of them).
  std::vector<vtkProp*> casters;
  std::vector<std::array<double, 6>> casterBounds;
  this->Planner->ClearReceiverBounds();
  std::vector<std::array<double, 6>> receivers;
  vtkPropCollection* props = renderer->GetViewProps();
  vtkCollectionSimpleIterator pit;
  props->InitTraversal(pit);
  while (vtkProp* prop = props->GetNextProp(pit))
  {
    std::array<double, 6> b;
    if (propBounds(prop, b.data()))
    {
      receivers.push_back(b);
      if (prop->HasOpaqueGeometry())
      {
        casters.push_back(prop);
        casterBounds.push_back(b);
      }
    }
  }
  if (this->Distributed())
  {
    // The same receiver boxes on every process: gather them all (padded with empty boxes).
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
  if (receivers.size() <= kMaxReceiverBoxes)
  {
    for (const auto& b : receivers)
    {
      this->Planner->AddReceiverBounds(b.data());
    }
  }

  this->Maps.clear();
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
    LightMaps maps;
    maps.Light = light;
    maps.LightIndex = index;
    const int planned = this->Planner->Plan(camera, aspect, light, sceneBounds);
    maps.NumberOfCascades = std::min(planned, kMaxCascades);
    if (maps.NumberOfCascades > 0)
    {
      vtkNew<vtkMatrix4x4> m;
      for (int c = 0; c < maps.NumberOfCascades; ++c)
      {
        this->Planner->GetCascadeMatrix(c, m);
        std::copy(m->GetData(), m->GetData() + 16, maps.WorldToMap[c]);
        maps.SplitFar[c] = this->Planner->GetCascadeFar(c);
      }
      maps.SplitNear = this->Planner->GetCascadeNear(0);
    }
    const size_t slot = this->Maps.size();
    if (this->AtlasPool.size() <= slot)
    {
      this->AtlasPool.push_back(vtkSmartPointer<vtkTextureObject>::New());
    }
    maps.Atlas = this->AtlasPool[slot];
    this->Maps.push_back(maps);
  }
  if (shadowingLights > maximumLights && shadowingLights != this->WarnedShadowingLights)
  {
    vtkWarningMacro(<< shadowingLights << " lights cast shadows but this GL context has texture "
                    << "units for " << maximumLights << "; the others are lit without shadows");
  }
  this->WarnedShadowingLights = shadowingLights > maximumLights ? shadowingLights : 0;
  // Textures only for the lights that cast shadows now.
  for (size_t i = this->Maps.size(); i < this->AtlasPool.size(); ++i)
  {
    this->AtlasPool[i]->ReleaseGraphicsResources(window);
  }
  this->AtlasPool.resize(this->Maps.size());
  if (this->Maps.empty())
  {
    return;
  }

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
  ostate->PushFramebufferBindings();

  vtkSmartPointer<vtkCamera> realCamera = camera;
  const bool automaticLights = renderer->GetAutomaticLightCreation() != 0;
  renderer->SetAutomaticLightCreation(false);
  this->FrameBuffer->SetContext(window);

  for (LightMaps& maps : this->Maps)
  {
    if (!this->PrepareAtlas(window, maps, numberOfCascades))
    {
      maps.NumberOfCascades = 0;
      continue;
    }
    this->FrameBuffer->Bind();
    this->FrameBuffer->AddDepthAttachment(maps.Atlas);
    this->FrameBuffer->DeactivateDrawBuffers();
    this->FrameBuffer->DeactivateReadBuffer();
    if (this->FrameBuffer->CheckFrameBufferStatus(GL_FRAMEBUFFER) == 0)
    {
      vtkErrorMacro(<< "The shadow map framebuffer is incomplete; no shadows");
      maps.NumberOfCascades = 0;
      continue;
    }
    const int width = static_cast<int>(maps.Atlas->GetWidth());
    const int height = static_cast<int>(maps.Atlas->GetHeight());
    // Clear the whole atlas to far depth: unused tiles and skipped cascades read as lit.
    ostate->vtkglDisable(GL_SCISSOR_TEST);
    ostate->vtkglViewport(0, 0, width, height);
    ostate->vtkglColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    ostate->vtkglDepthMask(GL_TRUE);
    ostate->vtkglClearDepth(1.0);
    ostate->vtkglClear(GL_DEPTH_BUFFER_BIT);
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
    ostate->vtkglEnable(GL_SCISSOR_TEST);

    for (int c = 0; c < maps.NumberOfCascades; ++c)
    {
      const int x = static_cast<int>(std::lround(maps.Tile[c][0] * width));
      const int y = static_cast<int>(std::lround(maps.Tile[c][1] * height));
      const int w = static_cast<int>(std::lround(maps.Tile[c][2] * width));
      const int h = static_cast<int>(std::lround(maps.Tile[c][3] * height));
      ostate->vtkglViewport(x, y, w, h);
      ostate->vtkglScissor(x, y, w, h);

      // Only the casters whose bounds reach this cascade's light volume.
      std::vector<vtkProp*> drawn;
      for (size_t i = 0; i < casters.size(); ++i)
      {
        if (reachesLightVolume(maps.WorldToMap[c], casterBounds[i].data(), depthClamp))
        {
          drawn.push_back(casters[i]);
        }
      }
      ++this->LastCascadeRenders;
      this->LastPropsDrawn += static_cast<int>(drawn.size());
      if (drawn.empty())
      {
        continue;
      }
      this->Projection->DeepCopy(maps.WorldToMap[c]);
      this->LightCamera->Modified();
      renderer->SetActiveCamera(this->LightCamera);
      vtkRenderState casterState(renderer);
      casterState.SetPropArrayAndCount(drawn.data(), static_cast<int>(drawn.size()));
      casterState.SetFrameBuffer(this->FrameBuffer);
      this->PreRender(&casterState);
      for (vtkProp* prop : drawn)
      {
        this->NumberOfRenderedProps += prop->RenderOpaqueGeometry(renderer);
      }
      this->PostRender(&casterState);
      renderer->SetActiveCamera(realCamera);
    }
    this->FrameBuffer->RemoveDepthAttachment();
    if (this->Distributed())
    {
      this->CombineAcrossProcesses(maps.Atlas);
    }
  }
  ostate->PopFramebufferBindings();
  renderer->SetAutomaticLightCreation(automaticLights);
  vtkOpenGLCheckErrorMacro("failed after rendering the cascaded shadow maps");
}

bool vtkCascadedShadowMapBakerPass::PreReplaceShaderValues(std::string&, std::string&,
  std::string& fragmentShader, vtkAbstractMapper*, vtkProp*)
{
  // Depth only: no lighting in the maps' fragment shader (the mapper finds no tag to expand).
  // This also keeps the depth program apart from the main pass's in the shader cache.
  vtkShaderProgram::Substitute(fragmentShader, "//VTK::Light::Impl",
    "gl_FragData[0] = vec4(1.0); // cascaded shadow map: depth pass\n", false);
  return true;
}

void vtkCascadedShadowMapBakerPass::ReleaseGraphicsResources(vtkWindow* w)
{
  for (auto& atlas : this->AtlasPool)
  {
    atlas->ReleaseGraphicsResources(w);
  }
  this->AtlasPool.clear();
  this->Maps.clear();
  if (this->FrameBuffer)
  {
    this->FrameBuffer->ReleaseGraphicsResources(w);
  }
  this->LastInputTime = 0;
}

vtkCascadedShadowMapPlanner* vtkCascadedShadowMapBakerPass::GetPlanner()
{
  return this->Planner;
}

// The planning options live in the planner; the baker forwards them.
void vtkCascadedShadowMapBakerPass::SetNumberOfCascades(int k)
{
  this->Planner->SetNumberOfCascades(k);
}
int vtkCascadedShadowMapBakerPass::GetNumberOfCascades()
{
  return this->Planner->GetNumberOfCascades();
}
void vtkCascadedShadowMapBakerPass::SetWarpMode(int mode)
{
  this->Planner->SetWarpMode(mode);
}
int vtkCascadedShadowMapBakerPass::GetWarpMode()
{
  return this->Planner->GetWarpMode();
}
void vtkCascadedShadowMapBakerPass::SetSplitScheme(int scheme)
{
  this->Planner->SetSplitScheme(scheme);
}
int vtkCascadedShadowMapBakerPass::GetSplitScheme()
{
  return this->Planner->GetSplitScheme();
}
void vtkCascadedShadowMapBakerPass::SetLambda(double lambda)
{
  this->Planner->SetLambda(lambda);
}
double vtkCascadedShadowMapBakerPass::GetLambda()
{
  return this->Planner->GetLambda();
}
void vtkCascadedShadowMapBakerPass::SetAlpha(double alpha)
{
  this->Planner->SetAlpha(alpha);
}
double vtkCascadedShadowMapBakerPass::GetAlpha()
{
  return this->Planner->GetAlpha();
}
void vtkCascadedShadowMapBakerPass::SetDepthClamp(bool clamp)
{
  this->Planner->SetDepthClamp(clamp);
}
bool vtkCascadedShadowMapBakerPass::GetDepthClamp()
{
  return this->Planner->GetDepthClamp();
}

vtkMTimeType vtkCascadedShadowMapBakerPass::GetMTime()
{
  return std::max(this->Superclass::GetMTime(), this->Planner->GetMTime());
}

void vtkCascadedShadowMapBakerPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Resolution: " << this->Resolution << "\n";
  os << indent << "Planner:\n";
  this->Planner->PrintSelf(os, indent.GetNextIndent());
  os << indent << "PolygonOffsetFactor: " << this->PolygonOffsetFactor << "\n";
  os << indent << "PolygonOffsetUnits: " << this->PolygonOffsetUnits << "\n";
  os << indent << "ShadowedLights: " << this->Maps.size() << "\n";
  os << indent << "Controller: " << this->Controller << "\n";
}
