// SPDX-License-Identifier: BSD-3-Clause
// Drawing the casters' depth (vtkCascadedShadowMapBakerPass's internal part): into a cascade's
// tile of its light's atlas, with only the casters and blocks that reach the cascade and can
// shadow something in it, and into the main view's own depth buffer, whose nearest and farthest
// samples are the visible depths.
#ifndef csmMapDrawing_h
#define csmMapDrawing_h

#include "vtkCascadedShadowMapBakerPass.h"
#include "vtkSmartPointer.h"

class vtkCamera;
class vtkCascadedShadowCasterPass;
class vtkMatrix4x4;
class vtkOpenGLFramebufferObject;
class vtkOpenGLRenderer;
class vtkOpenGLState;
class vtkRenderState;
class vtkRenderer;
struct csmFrameCasters;

class csmMapDrawing
{
public:
  using LightMaps = vtkCascadedShadowMapBakerPass::LightMaps;
  using FrameStatistics = vtkCascadedShadowMapBakerPass::FrameStatistics;

  csmMapDrawing();
  ~csmMapDrawing();
  csmMapDrawing(const csmMapDrawing&) = delete;
  csmMapDrawing& operator=(const csmMapDrawing&) = delete;

  /// The main view that screen-sized casters are sized for (VTK draws tubes and spheres with a
  /// width in the renderer's pixels): world -> view (row-major) in [0, 16), and the world size
  /// of one pixel at view depth d, [16] + [17] d, from the camera's projection.
  static void MainView(vtkRenderer* renderer, vtkCamera* camera, double key[18]);

  /// Gives the maps of the cascades to render (renderCascade[c]) far depth, all before the
  /// first draw (the framebuffer holds the light's atlas).
  static void ClearTiles(vtkOpenGLState* ostate, const LightMaps& maps, const int* renderCascade);

  /// Draws the depth of the casters that reach cascade c (and may shadow something in it) into
  /// its map; sets its CasterView to this view. distributed: several processes share the maps
  /// (every caster may shadow another process's receivers). Returns the props drawn.
  int DrawCascade(vtkOpenGLRenderer* renderer, vtkOpenGLFramebufferObject* frameBuffer,
    LightMaps& maps, int c, const csmFrameCasters& props, bool depthClamp, bool distributed,
    FrameStatistics& statistics);

  /// Draws the depth of the casters the view can see into the frame's own depth buffer (kept
  /// for the frame's geometry pass, a little behind the surfaces) and reads its nearest and
  /// farthest sample (window depths); false where they cannot be read (a multisampled
  /// framebuffer, a GL error).
  bool DrawViewDepth(vtkOpenGLRenderer* renderer, const vtkRenderState* s,
    const csmFrameCasters& props, double depths[2]);

private:
  /// The light camera for a cascade: the light's rotation as view, the rest as projection.
  void SetUpLightCamera(const LightMaps& maps, int c);

  vtkSmartPointer<vtkCamera> LightCamera;
  vtkSmartPointer<vtkMatrix4x4> Projection;
  /// The pass in the casters' keys while they are drawn (their shader hooks); not the baker
  /// itself, which owns mappers (vtkCascadedShadowCasterPass says why).
  vtkSmartPointer<vtkCascadedShadowCasterPass> CasterPass;
};

#endif
