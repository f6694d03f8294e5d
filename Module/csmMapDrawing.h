// SPDX-License-Identifier: BSD-3-Clause
// Drawing the casters' depth (vtkCascadedShadowMapBakerPass's internal part): into a cascade's
// tile of its light's atlas, with only the casters and blocks that reach the cascade and can
// shadow something in it, and into the main view's own depth buffer, whose nearest and farthest
// samples are the visible depths.
#ifndef csmMapDrawing_h
#define csmMapDrawing_h

#include "csmReuse.h"                  // for csm::TexelRect
#include "csmVisibleDepth.h"           // for csm::WindowFootprint
#include "vtkCascadedShadowMapTypes.h" // for LightMaps, FrameStatistics
#include "vtkOpenGLState.h"            // for the guard's scoped state
#include "vtkSmartPointer.h"

#include <vector>

class vtkCamera;
class vtkCascadedShadowCasterPass;
class vtkMatrix4x4;
class vtkOpenGLFramebufferObject;
class vtkOpenGLRenderWindow;
class vtkOpenGLRenderer;
class vtkRenderState;
class vtkRenderer;
class vtkTextureObject;
struct csmFrameCasters;

/// The GL state that drawing depth changes (viewport, scissor, masks, depth test, function and
/// clamp, polygon offset, face culling, framebuffer bindings), restored when the guard goes: the
/// maps' passes and the view's depth pass share it.
class csmDepthDrawingGuard
{
public:
  explicit csmDepthDrawingGuard(vtkOpenGLState* ostate);
  ~csmDepthDrawingGuard();
  csmDepthDrawingGuard(const csmDepthDrawingGuard&) = delete;
  csmDepthDrawingGuard& operator=(const csmDepthDrawingGuard&) = delete;

private:
  vtkOpenGLState* State;
  vtkOpenGLState::ScopedglViewport Viewport;
  vtkOpenGLState::ScopedglScissor Scissor;
  vtkOpenGLState::ScopedglEnableDisable ScissorTest;
  vtkOpenGLState::ScopedglDepthMask DepthMask;
  vtkOpenGLState::ScopedglColorMask ColorMask;
  vtkOpenGLState::ScopedglDepthFunc DepthFunc;
  vtkOpenGLState::ScopedglEnableDisable DepthTest;
  vtkOpenGLState::ScopedglEnableDisable DepthClamp;
  vtkOpenGLState::ScopedglEnableDisable OffsetFill;
  vtkOpenGLState::ScopedglEnableDisable OffsetLine;
  vtkOpenGLState::ScopedglEnableDisable OffsetPoint;
  vtkOpenGLState::ScopedglEnableDisable Culling;
  int CullFace;
};

class csmMapDrawing
{
public:
  using LightMaps = vtkCascadedShadows::LightMaps;
  using FrameStatistics = vtkCascadedShadows::FrameStatistics;

  csmMapDrawing();
  ~csmMapDrawing();
  csmMapDrawing(const csmMapDrawing&) = delete;
  csmMapDrawing& operator=(const csmMapDrawing&) = delete;

  /// The main view that screen-sized casters are sized for (VTK draws tubes and spheres with a
  /// width in the renderer's pixels): world -> view (row-major) in [0, 16), and the world size
  /// of one pixel at view depth d, [16] + [17] d, from the camera's projection.
  static void MainView(vtkRenderer* renderer, vtkCamera* camera, double key[18]);

  /// Gives the maps drawn whole this frame (MapAction::Draw) far depth, all before the first
  /// draw (the framebuffer holds the light's atlas).
  static void ClearTiles(vtkOpenGLState* ostate, const LightMaps& maps);

  /// Gives cascade c's map far depth: all of it, or a rect of it (x, y, width, height in texels
  /// from the map's lower left).
  static void ClearMap(vtkOpenGLState* ostate, const LightMaps& maps, int c, const int* rect);

  /// Copies width x height texels of one depth texture from (fromX, fromY) to another at
  /// (toX, toY) (GL 4.3 image copies; the caller checks that the GL has them).
  static void CopyTexels(vtkTextureObject* from, int fromX, int fromY, vtkTextureObject* to,
    int toX, int toY, int width, int height);

  /// Moves cascade c's map with the view (its Moved texels, csm::panKeptMap): shifts the texels
  /// it keeps by -Moved through `buffer` (a band of rows at a time, in the order that reads
  /// each row before it is written over) and gives the strips that came in far depth. False
  /// where the GL cannot (the map must then be drawn whole).
  static bool MoveMap(
    vtkOpenGLRenderWindow* window, vtkTextureObject* buffer, const LightMaps& maps, int c);

  /// The strips a moved map draws (csm::panStrips), in texels of the map.
  static std::vector<csm::TexelRect> MovedStrips(const vtkCascadedShadows::CascadeMap& map);

  /// Draws the depth of the casters that reach cascade c (and may shadow something in it) into
  /// its map; sets its CasterView to this view. distributed: several processes share the maps
  /// (every caster may shadow another process's receivers). strip: only that rect of the map
  /// (texels from its lower left; a moved map's, MovedStrips), its casters culled to it; null:
  /// the whole map. Returns the props drawn.
  int DrawCascade(vtkOpenGLRenderer* renderer, vtkOpenGLFramebufferObject* frameBuffer,
    LightMaps& maps, int c, const csmFrameCasters& props, bool depthClamp, bool distributed,
    FrameStatistics& statistics, const int* strip = nullptr);

  /// Draws the depth of the casters the view can see into the frame's own depth buffer (kept
  /// for the frame's geometry pass, a little behind the surfaces) and reads its nearest and
  /// farthest sample (window depths) and where the samples lie on the image by depth
  /// (csm::windowFootprint); false where they cannot be read (a multisampled framebuffer, a GL
  /// error). standInCount: the casters (or blocks) left out, small on the image for their
  /// triangles, whose boxes stand in for their samples (csm::boxStandIn). depths null: the
  /// depth only, nothing read (a view whose depths are known, or a multisampled framebuffer).
  /// samples: where read, the depth buffer and the stand-ins kept there (what light-space pages
  /// are marked from).
  bool DrawViewDepth(vtkOpenGLRenderer* renderer, const vtkRenderState* s,
    const csmFrameCasters& props, double depths[2], csm::WindowFootprint& footprint,
    int& standInCount, csm::DepthSamples* samples = nullptr);

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
