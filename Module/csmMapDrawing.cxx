// SPDX-License-Identifier: BSD-3-Clause
#include "csmMapDrawing.h"

#include "csmCasterCollection.h"
#include "csmClosedSurface.h" // csm::closedFaceTowardViewer
#include "csmPages.h"
#include "csmProps.h"
#include "csmVTKMath.h"
#include "csmVisibleDepth.h"

#include "vtkCamera.h"
#include "vtkCascadedShadowBlockMapper.h"
#include "vtkCascadedShadowCasterPass.h"
#include "vtkCascadedShadowMapPlanner.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkOpenGLError.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLRenderer.h"
#include "vtkOpenGLState.h"
#include "vtkRenderState.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include <glm/gtc/type_ptr.hpp>
#include <glm/mat4x4.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

namespace
{
// Rows of a moved map copied at a time (csmMapDrawing::MoveMap's buffer: the atlas's width).
constexpr int kMoveBandRows = 256;

// Steps of the depth buffer the view's depth pass writes its depths behind the surfaces by,
// beyond their change across the pixel (vtkCascadedShadowCasterPass::SetViewDepthNudge).
constexpr int kViewDepthNudgeSteps = 4;

/// kViewDepthNudgeSteps steps of the depth buffer being drawn, in window depth: 2^-n a step of
/// an n-bit buffer, and of a float one's 24-bit mantissa at depths from 1/2 to 1 (finer nearer);
/// at most 24 bits, a float's own resolution near 1, and 16 where the GL does not say.
float viewDepthNudge(vtkOpenGLState* state)
{
  vtkOpenGLClearErrorMacro();
  unsigned int drawBinding = 0, drawBuffer = 0;
  state->GetCurrentDrawFramebufferState(drawBinding, drawBuffer);
  const GLenum attachment = drawBinding == 0 ? GL_DEPTH : GL_DEPTH_ATTACHMENT;
  GLint bits = 0, type = GL_NONE;
  glGetFramebufferAttachmentParameteriv(
    GL_DRAW_FRAMEBUFFER, attachment, GL_FRAMEBUFFER_ATTACHMENT_DEPTH_SIZE, &bits);
  glGetFramebufferAttachmentParameteriv(
    GL_DRAW_FRAMEBUFFER, attachment, GL_FRAMEBUFFER_ATTACHMENT_COMPONENT_TYPE, &type);
  if (glGetError() != GL_NO_ERROR || bits < 1)
  {
    bits = 16;
  }
  return std::ldexp(float(kViewDepthNudgeSteps), -std::min(type == GL_FLOAT ? 24 : bits, 24));
}

/// Does the caster shadow anything in this light's maps (CullCastersWithoutReceivers)?
/// Directional lights only; with several processes the receivers are everyone's boxes.
bool casterHasReceivers(const csmFrameCasters& props, const csmFrameCasters::Caster& caster,
  const csmMapDrawing::LightMaps& maps, bool distributed)
{
  if (maps.Kind != vtkCascadedShadows::LightKind::Directional || distributed)
  {
    return true;
  }
  const double travel[3] = { maps.FocalPoint[0] - maps.Position[0],
    maps.FocalPoint[1] - maps.Position[1], maps.FocalPoint[2] - maps.Position[2] };
  return props.CasterHasReceivers(caster, travel);
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
  const csmMapDrawing::LightMaps& maps, int c, int x, int y, int w, int h)
{
  const double* key = maps.Cascades[c].CasterView; // DrawCascade set it for this view
  vtkNew<vtkMatrix4x4> worldToView, viewToWorld, worldToMap, mapToWorld;
  worldToView->DeepCopy(key);
  vtkMatrix4x4::Invert(worldToView, viewToWorld);
  worldToMap->DeepCopy(maps.Cascades[c].WorldToMap);
  vtkMatrix4x4::Invert(worldToMap, mapToWorld);
  double mapToView[16], viewToMap[16];
  vtkMatrix4x4::Multiply4x4(key, mapToWorld->GetData(), mapToView);
  vtkMatrix4x4::Multiply4x4(maps.Cascades[c].WorldToMap, viewToWorld->GetData(), viewToMap);
  vtkCascadedShadowCasterPass::CasterUniforms u;
  toColumnMajor(mapToView, u.MapToView);
  toColumnMajor(viewToMap, u.ViewToMap);
  const double* position = maps.Position;
  const double* focal = maps.FocalPoint;
  double light[4];
  if (maps.Kind == vtkCascadedShadows::LightKind::Directional)
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

/// The nearest and farthest sample of the renderer's viewport in the framebuffer being drawn
/// (window depths), and where they lie (with the boxes that stood in for casters left out);
/// false when they cannot be read (a multisampled framebuffer, a GL error).
bool readWindowDepths(vtkRenderer* renderer, const std::vector<csm::BoxStandIn>& standIns,
  double range[2], csm::WindowFootprint& footprint, csm::DepthSamples* samples)
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
  footprint = csm::windowFootprint(depths.data(), width, height, standIns);
  range[0] = footprint.range.min;
  range[1] = footprint.range.max;
  if (samples)
  {
    samples->windowDepths = std::move(depths);
    samples->width = width;
    samples->height = height;
    samples->standIns = standIns;
  }
  return true;
}

} // namespace

csmMapDrawing::csmMapDrawing()
  : LightCamera(vtkSmartPointer<vtkCamera>::New())
  , Projection(vtkSmartPointer<vtkMatrix4x4>::New())
  , CasterPass(vtkSmartPointer<vtkCascadedShadowCasterPass>::New())
{
  // Identity view: the cascade matrix (world -> light clip) is the whole projection.
  this->LightCamera->SetPosition(0.0, 0.0, 0.0);
  this->LightCamera->SetFocalPoint(0.0, 0.0, -1.0);
  this->LightCamera->SetViewUp(0.0, 1.0, 0.0);
  this->LightCamera->SetParallelProjection(1);
  this->LightCamera->SetExplicitProjectionTransformMatrix(this->Projection);
  this->LightCamera->UseExplicitProjectionTransformMatrixOn();
}

csmMapDrawing::~csmMapDrawing() = default;

void csmMapDrawing::MainView(vtkRenderer* renderer, vtkCamera* camera, double key[18])
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

csmDepthDrawingGuard::csmDepthDrawingGuard(vtkOpenGLState* ostate)
  : State(ostate)
  , Viewport(ostate)
  , Scissor(ostate)
  , ScissorTest(ostate, GL_SCISSOR_TEST)
  , DepthMask(ostate)
  , ColorMask(ostate)
  , DepthFunc(ostate)
  , DepthTest(ostate, GL_DEPTH_TEST)
  , DepthClamp(ostate, GL_DEPTH_CLAMP)
  , OffsetFill(ostate, GL_POLYGON_OFFSET_FILL)
  , OffsetLine(ostate, GL_POLYGON_OFFSET_LINE)
  , OffsetPoint(ostate, GL_POLYGON_OFFSET_POINT)
  , Culling(ostate, GL_CULL_FACE)
  , CullFace(GL_BACK)
{
  glGetIntegerv(GL_CULL_FACE_MODE, &this->CullFace);
  ostate->PushFramebufferBindings();
}

csmDepthDrawingGuard::~csmDepthDrawingGuard()
{
  this->State->PopFramebufferBindings();
  this->State->vtkglCullFace(static_cast<unsigned int>(this->CullFace));
}

void csmMapDrawing::ClearTiles(vtkOpenGLState* ostate, const LightMaps& maps)
{
  // Far depth where nothing casts, all before the first draw: a clear between two cascades'
  // draws would wait for the one drawn before it (a software rasterizer maps the texture).
  // (A map that moves with the view keeps most of its texels: MoveMap clears its strips.)
  // Where the texture's rectangles can be cleared directly, only the maps drawn: their texels
  // are fewer than the atlas's (the maps of a light that turns with the camera are drawn every
  // frame, each in a part of its tile), and a software rasterizer writes every texel it clears.
  const bool clearsRectangles = GLEW_VERSION_4_4 || GLEW_ARB_clear_texture;
  bool all = true;
  for (int c = 0; c < maps.GetNumberOfCascades(); ++c)
  {
    all = all && maps.Cascades[c].Action == vtkCascadedShadows::MapAction::Draw;
  }
  if (all && !clearsRectangles)
  {
    // Nothing kept: one clear of the whole atlas.
    ostate->vtkglDisable(GL_SCISSOR_TEST);
    ostate->vtkglClear(GL_DEPTH_BUFFER_BIT);
    return;
  }
  // Only the drawn maps' rectangles.
  for (int c = 0; c < maps.GetNumberOfCascades(); ++c)
  {
    if (maps.Cascades[c].Action == vtkCascadedShadows::MapAction::Draw)
    {
      csmMapDrawing::ClearMap(ostate, maps, c, nullptr);
    }
  }
}

void csmMapDrawing::ClearMap(vtkOpenGLState* ostate, const LightMaps& maps, int c, const int* rect)
{
  // (The map fills the lower left of its tile.)
  const vtkCascadedShadows::CascadeMap& map = maps.Cascades[c];
  const int area[4] = { map.Tile[0] + (rect ? rect[0] : 0), map.Tile[1] + (rect ? rect[1] : 0),
    rect ? rect[2] : map.Resolution[0], rect ? rect[3] : map.Resolution[1] };
  if (area[2] <= 0 || area[3] <= 0)
  {
    return;
  }
  // Clearing the texture's rectangles directly (GL 4.4, ARB_clear_texture) is several times
  // cheaper on software Mesa than a scissored framebuffer clear, which it draws as a quad.
  if (GLEW_VERSION_4_4 || GLEW_ARB_clear_texture)
  {
    const GLfloat farDepth = 1.0f;
    glClearTexSubImage(maps.Atlas->GetHandle(), 0, area[0], area[1], 0, area[2], area[3], 1,
      GL_DEPTH_COMPONENT, GL_FLOAT, &farDepth);
  }
  else
  {
    ostate->vtkglEnable(GL_SCISSOR_TEST);
    ostate->vtkglScissor(area[0], area[1], area[2], area[3]);
    ostate->vtkglClear(GL_DEPTH_BUFFER_BIT);
  }
}

void csmMapDrawing::CopyTexels(vtkTextureObject* from, int fromX, int fromY, vtkTextureObject* to,
  int toX, int toY, int width, int height)
{
  glCopyImageSubData(from->GetHandle(), GL_TEXTURE_2D, 0, fromX, fromY, 0, to->GetHandle(),
    GL_TEXTURE_2D, 0, toX, toY, 0, width, height, 1);
}

std::vector<csm::TexelRect> csmMapDrawing::MovedStrips(const vtkCascadedShadows::CascadeMap& map)
{
  csm::MapPan pan;
  pan.s = map.Moved[0];
  pan.t = map.Moved[1];
  pan.valid = map.IsMoved();
  return csm::panStrips(pan, csm::MapSize(map.Resolution[0], map.Resolution[1]));
}

bool csmMapDrawing::MoveMap(
  vtkOpenGLRenderWindow* window, vtkTextureObject* buffer, const LightMaps& maps, int c)
{
  const vtkCascadedShadows::CascadeMap& map = maps.Cascades[c];
  const int s = map.Moved[0], t = map.Moved[1];
  const int width = map.Resolution[0] - std::abs(s), height = map.Resolution[1] - std::abs(t);
  if (width <= 0 || height <= 0 || !(GLEW_VERSION_4_3 || GLEW_ARB_copy_image) ||
    !maps.Atlas->GetHandle())
  {
    return false;
  }
  // A band of rows of the atlas's width (the same depth format: images copy between them).
  if (!buffer->GetHandle() || buffer->GetContext() != window ||
    static_cast<int>(buffer->GetWidth()) < width || buffer->GetHeight() < kMoveBandRows)
  {
    buffer->ReleaseGraphicsResources(window);
    buffer->SetContext(window);
    if (!buffer->AllocateDepth(std::max(static_cast<unsigned int>(width), maps.Atlas->GetWidth()),
          static_cast<unsigned int>(kMoveBandRows), vtkTextureObject::Float32))
    {
      return false;
    }
  }
  vtkOpenGLClearErrorMacro();
  // Kept texel (x + s, y + t) goes to (x, y). Rows move down when t > 0: bands from the bottom,
  // each written only over rows read before it; up when t < 0: from the top.
  const int fromX = map.Tile[0] + std::max(s, 0), toX = map.Tile[0] + std::max(-s, 0);
  const int fromY = map.Tile[1] + std::max(t, 0), toY = map.Tile[1] + std::max(-t, 0);
  const int bands = (height + kMoveBandRows - 1) / kMoveBandRows;
  for (int b = 0; b < bands; ++b)
  {
    const int band = t >= 0 ? b : bands - 1 - b;
    const int row = band * kMoveBandRows;
    const int rows = std::min(kMoveBandRows, height - row);
    csmMapDrawing::CopyTexels(maps.Atlas, fromX, fromY + row, buffer, 0, 0, width, rows);
    csmMapDrawing::CopyTexels(buffer, 0, 0, maps.Atlas, toX, toY + row, width, rows);
  }
  if (glGetError() != GL_NO_ERROR)
  {
    return false;
  }
  for (const csm::TexelRect& strip : csmMapDrawing::MovedStrips(map))
  {
    csmMapDrawing::ClearMap(window->GetState(), maps, c, strip.data());
  }
  return true;
}

int csmMapDrawing::DrawCascade(vtkOpenGLRenderer* renderer, vtkOpenGLFramebufferObject* frameBuffer,
  LightMaps& maps, int c, const csmFrameCasters& props, bool depthClamp, bool distributed,
  FrameStatistics& statistics, const int* strip)
{
  vtkOpenGLState* ostate =
    static_cast<vtkOpenGLRenderWindow*>(renderer->GetRenderWindow())->GetState();
  // The map fills the lower left of its tile.
  const vtkCascadedShadows::CascadeMap& map = maps.Cascades[c];
  const int x = map.Tile[0], y = map.Tile[1], w = map.Resolution[0], h = map.Resolution[1];
  const csm::TexelRect area =
    strip ? csm::TexelRect{ strip[0], strip[1], strip[2], strip[3] } : csm::TexelRect{ 0, 0, w, h };
  ostate->vtkglViewport(x, y, w, h);
  ostate->vtkglScissor(x + area[0], y + area[1], area[2], area[3]); // given far depth before
  csmMapDrawing::MainView(renderer, renderer->GetActiveCamera(), maps.Cascades[c].CasterView);
  // The casters are culled with the light volume of the area drawn.
  double cullToClip[16];
  {
    const glm::dmat4 m =
      csm::cropToTexels(glm::transpose(glm::make_mat4(map.WorldToMap)), area, csm::MapSize(w, h));
    const glm::dmat4 rows = glm::transpose(m);
    std::copy(glm::value_ptr(rows), glm::value_ptr(rows) + 16, cullToClip);
  }

  // Only the casters whose bounds reach this cascade's light volume; for the closed ones, the
  // face to cull: the one turned toward the light (csm::closedFaceTowardViewer).
  std::map<vtkProp*, unsigned int> cullFaces;
  const double mapDeterminant = vtkMatrix4x4::Determinant(maps.Cascades[c].WorldToMap);
  std::vector<vtkProp*> drawn;
  for (const csmFrameCasters::Caster& caster : props.Casters)
  {
    if (!csmCascadeReachesBox(cullToClip, caster.Bounds.data(), depthClamp))
    {
      continue;
    }
    if (caster.Compact >= 0)
    {
      // Only its blocks that reach the cascade and may shadow something in it.
      const csmFrameCasters::Compact& compact = props.Compacts[static_cast<size_t>(caster.Compact)];
      std::vector<size_t> blocks;
      csmFrameCasters::Caster block = caster;
      for (size_t k = 0; k < compact.Bounds.size(); ++k)
      {
        block.Bounds = compact.Bounds[k];
        if (!csmCascadeReachesBox(cullToClip, block.Bounds.data(), depthClamp))
        {
          continue;
        }
        if (!casterHasReceivers(props, block, maps, distributed))
        {
          ++statistics.CastersWithoutReceivers;
          continue;
        }
        blocks.push_back(k);
        statistics.CellsDrawn += compact.Cells[k];
      }
      if (blocks.empty())
      {
        continue;
      }
      compact.Mapper->SetDrawnBlocks(blocks);
      statistics.BlocksDrawn += static_cast<int>(blocks.size());
    }
    else if (!casterHasReceivers(props, caster, maps, distributed))
    {
      ++statistics.CastersWithoutReceivers;
      continue;
    }
    else
    {
      statistics.CellsDrawn += caster.Cells;
    }
    drawn.push_back(caster.Prop);
    const int outward = csm::closedFaceTowardViewer(caster.Closure, mapDeterminant);
    if (outward != 0)
    {
      cullFaces[caster.Prop] = outward > 0 ? GL_FRONT : GL_BACK; // the face toward the light
    }
  }
  statistics.CascadesRendered += strip ? 0 : 1; // (a moved map counts as kept)
  statistics.TexelsRendered += double(area[2]) * double(area[3]);
  statistics.PropsDrawn += static_cast<int>(drawn.size());
  if (drawn.empty())
  {
    return 0;
  }
  vtkSmartPointer<vtkCamera> realCamera = renderer->GetActiveCamera();
  this->SetUpLightCamera(maps, c);
  this->CasterPass->SetViewDepthNudge(0.0f);
  this->CasterPass->BeginCascade(
    ostate, casterUniformsFor(maps, c, x, y, w, h), std::move(cullFaces));
  renderer->SetActiveCamera(this->LightCamera);
  const int rendered = this->CasterPass->DrawCasters(renderer, frameBuffer, drawn);
  this->CasterPass->EndCascade();
  renderer->SetActiveCamera(realCamera);
  return rendered;
}

void csmMapDrawing::SetUpLightCamera(const LightMaps& maps, int c)
{
  // The camera's view is the light's rotation (so that what VTK's shaders offset in view space,
  // such as vtkPointGaussianMapper's splats, faces the light); its projection the rest of the
  // cascade's world -> light clip matrix.
  double travel[3] = { maps.FocalPoint[0] - maps.Position[0], maps.FocalPoint[1] - maps.Position[1],
    maps.FocalPoint[2] - maps.Position[2] };
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
    maps.Cascades[c].WorldToMap, viewToWorld->GetData(), this->Projection->GetData());
  this->Projection->Modified();
  this->LightCamera->Modified();
}

namespace
{
/// What the view's depth pass draws: the casters (or their blocks) the view can see, each
/// closed one seen from outside with its faces turned away culled, and the boxes that stand in
/// for casters small on the image.
struct ViewCasters
{
  std::map<vtkProp*, unsigned int> CullFaces;
  std::vector<vtkProp*> Drawn;
  std::vector<csm::BoxStandIn> StandIns;
  bool ScreenSizedDrawn = false;
};

/// The casters the view's depth is drawn with; screenSized: also those drawn wider than their
/// data (wide lines, big points, tubes, spheres), whose width in the depth cannot match the
/// mapper's own rasterization to the pixel.
ViewCasters viewCasters(vtkCamera* camera, double aspect, const csmFrameCasters& props, int width,
  int height, bool screenSized)
{
  vtkMatrix4x4* worldToClip = camera->GetCompositeProjectionTransformMatrix(aspect, -1, 1);
  // A closed caster seen from outside only (the near plane reaches no point of its box) shows
  // only the faces turned toward the eye: the faces turned away are culled (the depth is the
  // same, and a software rasterizer pays for every face it draws).
  const double viewDeterminant = worldToClip->Determinant();
  ViewCasters chosen;
  // A caster (or block) small on the image for its triangles stands in by its box, which the
  // footprint holds instead of its samples (csm::boxStandIn): drawing it would cost more than
  // the lookups its depth spares. Screen-sized casters are drawn: their boxes do not hold them.
  const glm::dmat4 wsToClip = glm::transpose(glm::make_mat4(worldToClip->GetData()));
  auto standsIn = [&](const std::array<double, 6>& bounds, double cells, bool screenSized)
  {
    csm::BoxStandIn standIn;
    if (screenSized ||
      !csm::boxStandIn(
        wsToClip, csm::Bounds::fromMinMaxPairs(bounds.data()), cells, width, height, standIn))
    {
      return false;
    }
    chosen.StandIns.push_back(standIn);
    return true;
  };
  for (const csmFrameCasters::Caster& caster : props.Casters)
  {
    if (!csmCascadeReachesBox(worldToClip->GetData(), caster.Bounds.data(), false))
    {
      continue;
    }
    float screenSizes[2];
    csmScreenSizes(caster.Prop, screenSizes);
    const bool wide = screenSizes[0] > 1.0f || screenSizes[1] > 1.0f;
    if ((wide && !screenSized) ||
      (caster.Compact < 0 && standsIn(caster.Bounds, caster.Cells, wide)))
    {
      continue;
    }
    chosen.ScreenSizedDrawn = chosen.ScreenSizedDrawn || wide;
    const int towardEye = csm::closedFaceTowardViewer(caster.Closure, viewDeterminant);
    if (towardEye != 0 && csmViewSeesOnlyOutsideOf(camera, aspect, caster.Bounds.data()))
    {
      chosen.CullFaces[caster.Prop] = towardEye > 0 ? GL_BACK : GL_FRONT;
    }
    if (caster.Compact >= 0)
    {
      const csmFrameCasters::Compact& compact = props.Compacts[static_cast<size_t>(caster.Compact)];
      // A group stands in whole or draws its blocks in view.
      std::vector<size_t> blocks;
      for (const csmFrameCasters::Compact::Group& group : compact.Groups)
      {
        if (!csmCascadeReachesBox(worldToClip->GetData(), group.Bounds.data(), false) ||
          standsIn(group.Bounds, group.Cells, wide))
        {
          continue;
        }
        for (size_t k = group.First; k < group.First + group.Count; ++k)
        {
          if (csmCascadeReachesBox(worldToClip->GetData(), compact.Bounds[k].data(), false))
          {
            blocks.push_back(k);
          }
        }
      }
      if (blocks.empty())
      {
        continue;
      }
      compact.Mapper->SetDrawnBlocks(blocks);
    }
    chosen.Drawn.push_back(caster.Prop);
  }
  return chosen;
}
} // namespace

bool csmMapDrawing::DrawViewDepth(vtkOpenGLRenderer* renderer, const vtkRenderState* s,
  const csmFrameCasters& props, double depths[2], csm::WindowFootprint& footprint,
  int& standInCount, csm::DepthSamples* samples)
{
  standInCount = 0;
  vtkCamera* camera = renderer->GetActiveCamera();
  const double aspect = renderer->GetTiledAspectRatio();
  vtkOpenGLRenderWindow* window = static_cast<vtkOpenGLRenderWindow*>(renderer->GetRenderWindow());
  // The casters the view can see, their depth only, into the frame's own depth buffer (the
  // camera pass set its viewport and scissor and cleared it).
  int width = 0, height = 0, x = 0, y = 0;
  renderer->GetTiledSizeAndOrigin(&width, &height, &x, &y);
  // (Screen-sized casters only where the depths are read: their depth is cleared after.)
  ViewCasters casters = viewCasters(camera, aspect, props, width, height, depths != nullptr);
  vtkOpenGLState* ostate = window->GetState();
  csmDepthDrawingGuard guard(ostate);
  ostate->vtkglColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  ostate->vtkglDepthMask(GL_TRUE);
  ostate->vtkglEnable(GL_DEPTH_TEST);
  // The depth stays for the frame's own geometry pass, which then shades only the fragments
  // it keeps (the lookup is its costliest part): each fragment's written a few steps farther
  // than its surface's farthest sample in the pixel, so that the same surface drawn by other
  // shaders passes VTK's depth test (GL_LESS), and of surfaces at one depth the first drawn
  // shows, as without shadows. (No polygon offset: llvmpipe moves no depth by its units.)
  glPolygonOffset(0.0f, 0.0f);
  // Screen-sized casters as wide as this view draws them: the "map" is the view itself.
  double key[18];
  csmMapDrawing::MainView(renderer, camera, key);
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
  this->CasterPass->SetViewDepthNudge(viewDepthNudge(ostate));
  this->CasterPass->BeginCascade(ostate, u, std::move(casters.CullFaces));
  this->CasterPass->DrawCasters(renderer, s->GetFrameBuffer(), casters.Drawn);
  this->CasterPass->EndCascade();
  standInCount = static_cast<int>(casters.StandIns.size());
  const bool read =
    depths && readWindowDepths(renderer, casters.StandIns, depths, footprint, samples);
  if (casters.ScreenSizedDrawn)
  {
    // Their depth, a pixel wider or narrower than the mapper draws them, would let the
    // background through at their edges: the frame's pass draws without the view's depth.
    ostate->vtkglClearDepth(1.0);
    ostate->vtkglClear(GL_DEPTH_BUFFER_BIT);
  }
  return read;
}
