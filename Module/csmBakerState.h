// SPDX-License-Identifier: BSD-3-Clause
// vtkCascadedShadowMapBakerPass's state across frames per renderer, and what a frame's lights
// are planned with (internal).
#ifndef csmBakerState_h
#define csmBakerState_h

#include "vtkCascadedShadowMapTypes.h" // for LightMaps

#include "csmPages.h"
#include "csmVisibleDepth.h"

#include "vtkCamera.h"
#include "vtkMatrix4x4.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkSmartPointer.h"
#include "vtkTextureObject.h"
#include "vtkWeakPointer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

class vtkOpenGLRenderWindow;
class vtkProp;
class vtkRenderer;

/// The maps of one renderer and the GL objects (of its window's context) that hold them.
struct csmRendererMaps
{
  vtkWeakPointer<vtkRenderer> Renderer;
  vtkOpenGLRenderWindow* Window = nullptr; ///< the context of the atlases and framebuffer
  std::vector<vtkCascadedShadows::LightMaps> Maps;
  std::vector<vtkSmartPointer<vtkTextureObject>> AtlasPool; ///< one per light slot, reused
  vtkSmartPointer<vtkOpenGLFramebufferObject> FrameBuffer;
  /// Rows of a map in transit while it moves with the view (csmMapDrawing::MoveMap).
  vtkSmartPointer<vtkTextureObject> MoveBuffer;
  vtkMTimeType LastInputTime = 0;
  std::vector<std::vector<double>> LastCasting;  ///< each view prop's csmCastingState, in order
  std::vector<vtkProp*> LastProps;               ///< the view props, in order
  std::vector<std::array<double, 6>> LastBounds; ///< their world boxes (empty: none shown)
  int LastSize[2] = { 0, 0 };
  /// The visible depths last measured (VisibleDepthFit): the camera that measured them (null:
  /// none), its aspect and window depths.
  vtkSmartPointer<vtkCamera> VisibleCamera;
  double VisibleAspect = 1.0;
  double VisibleWindow[2] = { 1.0, 0.0 };
  /// ... and where its samples lie on its image, by depth, and the depth buffer itself.
  csm::WindowFootprint VisibleFootprint;
  csm::DepthSamples VisibleSamples;
  /// Per light slot: the pages kept in the pool of its atlas (LightSpacePages) and the texture
  /// of their table.
  std::vector<csm::PageCache> PageCaches;
  std::vector<vtkSmartPointer<vtkTextureObject>> PageTablePool;
  /// Where the pages a view brings in together are drawn in one pass before each is copied to
  /// its slot (csm::batchPages), and its framebuffer.
  vtkSmartPointer<vtkTextureObject> PageScratch;
  vtkSmartPointer<vtkOpenGLFramebufferObject> PageFrameBuffer;
  /// The camera of the last plan (MapSlack: did this frame's camera take a small step?).
  vtkSmartPointer<vtkCamera> LastCamera;
  /// What else the last plan was made for: the aspect, whether the user interacted, how many
  /// lights cast shadows, and what the planning found (csmLightPlanning::LastPlanStands).
  double LastAspect = 0.0;
  bool LastInteracting = false;
  int LastShadowingLights = 0;
  /// Frames in a row in which some casters changed (csmFrameCasters::Dirty).
  int CastersChangedFrames = 0;
  /// The last planned frame was planned as one of casters that change every frame (frames drawn
  /// as the last one since keep its maps): the next change continues it.
  bool PlannedAsChanging = false;
  vtkCascadedShadows::FrameStatistics LastPlanStatistics;
};

/// Were the maps rendered for the same light geometry?
inline bool sameLightGeometry(
  const vtkCascadedShadows::LightMaps& a, const vtkCascadedShadows::LightMaps& b)
{
  return a.Kind == b.Kind && a.ConeAngle == b.ConeAngle &&
    std::equal(a.Position, a.Position + 3, b.Position) &&
    std::equal(a.FocalPoint, a.FocalPoint + 3, b.FocalPoint);
}

/// Values equal up to this share of the larger (a grabbed image renders with a camera whose view
/// angle went through the tiling's trigonometry: 30 degrees become 30.0000008).
constexpr double kSameViewTolerance = 1e-6;
inline bool nearlyEqual(const double* a, const double* b, int n)
{
  for (int i = 0; i < n; ++i)
  {
    const double scale = std::max({ 1.0, std::abs(a[i]), std::abs(b[i]) });
    if (!(std::abs(a[i] - b[i]) <= kSameViewTolerance * scale))
    {
      return false;
    }
  }
  return true;
}

/// Does a camera look from where and where another did (its clipping range aside)?
inline bool sameViewpoint(vtkCamera* a, vtkCamera* b)
{
  const double angles[2] = { a->GetViewAngle(), a->GetParallelScale() };
  const double others[2] = { b->GetViewAngle(), b->GetParallelScale() };
  return nearlyEqual(a->GetPosition(), b->GetPosition(), 3) &&
    nearlyEqual(a->GetFocalPoint(), b->GetFocalPoint(), 3) &&
    nearlyEqual(a->GetViewUp(), b->GetViewUp(), 3) && nearlyEqual(angles, others, 2) &&
    a->GetParallelProjection() == b->GetParallelProjection();
}

/// Does a camera see as another did (view and projection at this aspect)?
inline bool sameView(vtkCamera* a, vtkCamera* b, double aspect)
{
  if (!nearlyEqual(a->GetModelViewTransformMatrix()->GetData(),
        b->GetModelViewTransformMatrix()->GetData(), 16))
  {
    return false;
  }
  double projectionA[16];
  std::copy(a->GetProjectionTransformMatrix(aspect, -1, 1)->GetData(),
    a->GetProjectionTransformMatrix(aspect, -1, 1)->GetData() + 16, projectionA);
  return nearlyEqual(projectionA, b->GetProjectionTransformMatrix(aspect, -1, 1)->GetData(), 16);
}

/// What every light of a frame is planned with.
struct csmFramePlan
{
  bool Interacting = false;
  bool Changed = true;         ///< every map must be rendered
  bool CastersChanged = false; ///< some casters changed (csmFrameCasters::Dirty)
  bool ScreenSized = false;    ///< some caster is drawn as wide as the main view draws it
  bool MoveMaps = false;       ///< kept maps may move with the view (one process, GL copies images)
  double Border = 0.0;         ///< of the maps while interacting (InteractiveMapBorder)
  double Tolerance = 1.0;      ///< of a kept map's error while interacting
  int Ceiling = 0;             ///< texels a side of the largest map that follows the view
  int MostCascades = 0;        ///< this frame's (0: NumberOfCascades)
  int ImageHeight = 0;
  double Aspect = 1.0;
  double ViewKey[18] = {}; ///< the main view (csmMapDrawing::MainView)
};

/// What a cascade's fresh map needs this frame: the texels that meet ErrorTarget, within the
/// largest map it may have (Texels: in steps of RESOLUTION_STEP, what a fresh map gets;
/// TargetTexels: the fewest, what a kept map is judged against), and whether even that map
/// misses the target.
struct csmCascadeNeed
{
  int Texels[2] = { 0, 0 };
  int TargetTexels[2] = { 0, 0 };
  bool TargetOutOfReach = false;
};

#endif
