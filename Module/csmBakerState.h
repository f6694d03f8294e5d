// SPDX-License-Identifier: BSD-3-Clause
// vtkCascadedShadowMapBakerPass's state across frames per renderer, and what a frame's lights
// are planned with (internal).
#ifndef csmBakerState_h
#define csmBakerState_h

#include "vtkCascadedShadowMapBakerPass.h"

#include "vtkCamera.h"
#include "vtkMatrix4x4.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkSmartPointer.h"
#include "vtkTextureObject.h"
#include "vtkWeakPointer.h"

#include <algorithm>
#include <vector>

/// The maps of one renderer and the GL objects (of its window's context) that hold them.
struct csmRendererMaps
{
  vtkWeakPointer<vtkRenderer> Renderer;
  vtkOpenGLRenderWindow* Window = nullptr; ///< the context of the atlases and framebuffer
  std::vector<vtkCascadedShadowMapBakerPass::LightMaps> Maps;
  std::vector<vtkSmartPointer<vtkTextureObject>> AtlasPool; ///< one per light slot, reused
  vtkSmartPointer<vtkOpenGLFramebufferObject> FrameBuffer;
  vtkMTimeType LastInputTime = 0;
  int LastSize[2] = { 0, 0 };
  /// The visible depths last measured (VisibleDepthFit): the camera that measured them (null:
  /// none), its aspect and window depths; whether this frame measured them, and whether the
  /// last plan used them.
  vtkSmartPointer<vtkCamera> VisibleCamera;
  double VisibleAspect = 1.0;
  double VisibleWindow[2] = { 1.0, 0.0 };
  bool VisibleDepthsMeasured = false;
  bool VisibleDepthsUsed = false;
  /// The camera of the last plan (MapSlack: did this frame's camera take a small step?).
  vtkSmartPointer<vtkCamera> LastCamera;
};

/// Were the maps rendered for the same light geometry?
inline bool sameLightGeometry(const vtkCascadedShadowMapBakerPass::LightMaps& a,
  const vtkCascadedShadowMapBakerPass::LightMaps& b)
{
  return a.Kind == b.Kind && a.ConeAngle == b.ConeAngle &&
    std::equal(a.Position, a.Position + 3, b.Position) &&
    std::equal(a.FocalPoint, a.FocalPoint + 3, b.FocalPoint);
}

/// Does a camera look from where and where another did (its clipping range aside)?
inline bool sameViewpoint(vtkCamera* a, vtkCamera* b)
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
inline bool sameView(vtkCamera* a, vtkCamera* b, double aspect)
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

/// What every light of a frame is planned with.
struct csmFramePlan
{
  bool Interacting = false;
  bool Changed = true;      ///< every map must be rendered
  bool ScreenSized = false; ///< some caster is drawn as wide as the main view draws it
  double Border = 0.0;      ///< of the maps while interacting (InteractiveMapBorder)
  double Tolerance = 1.0;   ///< of a kept map's error while interacting
  int Ceiling = 0;          ///< texels a side of the largest map that follows the view
  int MostCascades = 0;     ///< this frame's (0: NumberOfCascades)
  int ImageHeight = 0;
  double Aspect = 1.0;
  double ViewKey[18] = {}; ///< the main view (csmMapDrawing::MainView)
};

#endif
