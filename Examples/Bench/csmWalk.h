// SPDX-License-Identifier: BSD-3-Clause
// csm-bench --walk: smooth camera paths close to the geometry, every frame a normal render.
#pragma once

#include "csmTruth.h"        // for FrameTruth
#include "vtkImageData.h"    // for GrabFrame
#include "vtkSmartPointer.h" // for GrabFrame

#include <string>
#include <vector>

class vtkCamera;
class vtkLight;
class vtkRenderWindow;
class vtkRenderer;
namespace csmScenes
{
struct Scene;
}

namespace csmWalk
{
/// Runs the walk benchmark with csm-bench's arguments (--walk and its options); the engine
/// model's path comes from the build. Returns the exit status.
int Run(int argc, char** argv, const std::string& engineModel);
/// The walk's usage: its options with their defaults.
std::string Usage();
/// The image of the frame the window just rendered (not rendered again), as both modes of
/// csm-bench measure it against the truth.
vtkSmartPointer<vtkImageData> GrabFrame(vtkRenderWindow* window);

/// The truth at a view: each pixel's surface, whether it is compared, and whether something
/// lies between it and a directional light travelling along `travel`.
struct FrameTruth
{
  std::vector<csmTruth::Surface> Surfaces;
  std::vector<char> Comparable, Occluded;
  std::vector<char> Edges; ///< the pixels a shadow edge crosses (RayScene::ShadowEdges)
};
FrameTruth CastTruth(
  const csmTruth::RayScene& rays, vtkCamera* camera, int width, int height, const double travel[3]);

/// The frame the window just rendered against the truth, given the plain (unshadowed) frame of
/// the same view; factors: each pixel's shadow factor, where wanted.
csmTruth::Classification ClassifyFrame(vtkRenderWindow* window, vtkImageData* plain,
  const FrameTruth& truth, std::vector<float>* factors = nullptr);

/// The direction the benchmarks' scene light travels (world), where a mode sets none of its own.
constexpr double kSceneLightTravel[3] = { -0.45, -1.0, -0.35 };

/// A directional scene light travelling along `travel`.
void SetSceneLight(vtkLight* light, const double travel[3]);

/// The renderer showing the scene in an offscreen window of width x height pixels without
/// multisampling, from the scene's default view, lit by `light` alone.
void ShowScene(vtkRenderer* renderer, vtkRenderWindow* window, vtkLight* light,
  const csmScenes::Scene& scene, const int size[2]);

/// The median of a list of times (NaN for none).
double Median(std::vector<double> values);
}
