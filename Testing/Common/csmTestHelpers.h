// SPDX-License-Identifier: BSD-3-Clause
// What the GL tests (passes, image, accuracy, MPI) share: the image of a window, the pixels the
// shadows darken, and the scene of a box over a ground plane lit from above.
#pragma once

#include "vtkActor.h"
#include "vtkCallbackCommand.h"
#include "vtkCascadedShadowMapBakerPass.h"
#include "vtkCommand.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"

#include <array>
#include <vector>

namespace csmTest
{

/// The window's image after window->Render(). With rerender (as vtkWindowToImageFilter does by
/// default) the grab renders the frame once more; without, it reads exactly the frame rendered.
vtkSmartPointer<vtkImageData> Grab(vtkRenderWindow* window, bool rerender = true);

/// A pixel is darkened when its brightness (the sum of its red, green and blue) dropped by more
/// than 15 % and 6 levels.
inline bool IsDarkened(double shadowedBrightness, double plainBrightness)
{
  return shadowedBrightness < 0.85 * plainBrightness - 6.0;
}

/// Pixels darkened from `plain` to `shadowed` (-1 when the images differ in size); only those
/// of the mask (one entry per pixel, rows from the bottom) when one is given, and then
/// `maskPixels` (when given) receives the number of pixels in the mask.
long DarkenedPixels(vtkImageData* shadowed, vtkImageData* plain,
  const std::vector<char>* mask = nullptr, long* maskPixels = nullptr);

/// Channel values (of all pixels) that differ by more than `tolerance` levels.
long DifferingValues(vtkImageData* a, vtkImageData* b, int tolerance = 2);

/// Pixels with a channel that differs by more than `tolerance` levels.
long DifferingPixels(vtkImageData* a, vtkImageData* b, int tolerance);

/// Counts the ErrorEvents of an object (vtkErrorMacro invokes one per message).
struct ErrorCounter
{
  int Count = 0;
  vtkNew<vtkCallbackCommand> Command;
  explicit ErrorCounter(vtkObject* object, unsigned long event = vtkCommand::ErrorEvent)
  {
    this->Command->SetClientData(this);
    this->Command->SetCallback([](vtkObject*, unsigned long, void* self, void*)
      { ++static_cast<ErrorCounter*>(self)->Count; });
    object->AddObserver(event, this->Command);
  }
};

/// An actor of line segments (end points, 6 numbers each) drawn `pixels` wide, as tubes or not.
vtkSmartPointer<vtkActor> SegmentsActor(
  const std::vector<std::array<double, 6>>& segments, float pixels, bool tubes);

/// A flat square at y = 0, |x| and |z| up to halfWidth, of resolution x resolution quads.
vtkSmartPointer<vtkActor> GroundPlane(double halfWidth, int resolution);

/// A box (vtkCubeSource) with the given bounds: xmin, xmax, ymin, ymax, zmin, zmax.
vtkSmartPointer<vtkActor> BoxActor(
  double xmin, double xmax, double ymin, double ymax, double zmin, double zmax);

/// The box-over-plane scene; the defaults are those of the pass tests.
struct BoxOverPlaneSettings
{
  int Size[2] = { 320, 240 };
  double GroundHalfWidth = 10.0;
  int GroundResolution = 1;
  double GroundColor[3] = { 1.0, 1.0, 1.0 };
  double Box[6] = { -1, 1, 2, 4, -1, 1 }; ///< bounds
  double BoxColor[3] = { 0.9, 0.4, 0.2 };
  double Background[3] = { 0.2, 0.3, 0.4 };
  double LightPosition[3] = { 0, 10, 0 }; ///< a directional scene light toward the origin
  double CameraPosition[3] = { 0, 14, 16 };
  double CameraFocalPoint[3] = { 0, 0, 0 }; ///< view up +y
};

/// One cascade's depth texels (rows from the bottom), read back from its light's atlas.
std::vector<float> CascadeDepths(
  vtkRenderWindow* window, const vtkCascadedShadowMapBakerPass::LightMaps& maps, int c);

/// Every cascade's depth texels, the atlas read back once.
std::vector<std::vector<float>> AllCascadeDepths(
  vtkRenderWindow* window, const vtkCascadedShadowMapBakerPass::LightMaps& maps);

/// A box over a ground plane, lit by one directional scene light from above (no automatic
/// lights): the box's shadow falls on the plane. Offscreen, no multisampling.
struct BoxOverPlane
{
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkRenderWindow> Window;
  vtkNew<vtkActor> Ground;
  vtkNew<vtkActor> Box;
  vtkNew<vtkLight> Light;

  explicit BoxOverPlane(const BoxOverPlaneSettings& settings);
  explicit BoxOverPlane(int width = 320, int height = 240);

  /// A frame and its image (the grab renders it again, as vtkWindowToImageFilter does).
  vtkSmartPointer<vtkImageData> Render() { return Grab(this->Window, true); }

  /// One frame, and the image of exactly that frame.
  vtkSmartPointer<vtkImageData> Frame() { return Grab(this->Window, false); }

  /// Makes the box one polydata with a block behind the default camera (0, 14, 16): that prop's
  /// box then holds the camera, so the scene's boxes meet the view far nearer than anything it
  /// shows (the visible depths begin at the box in front).
  void AddBlockBehindTheCamera();
};

} // namespace csmTest
