// SPDX-License-Identifier: BSD-3-Clause
// Ground truth for shadows by ray casting (Embree), and the error measures of csm-bench:
// misclassified pixels against the truth, and the perspective aliasing m of Lloyd et al.
#pragma once

#include <cmath>
#include <memory>
#include <vector>

class vtkCamera;
class vtkImageData;
class vtkRenderer;

namespace csmTruth
{

/// One pixel's visible surface, from a primary ray through the pixel centre.
struct Surface
{
  bool Hit = false;
  double Position[3] = { 0, 0, 0 }; ///< world
  double Normal[3] = { 0, 0, 0 };   ///< geometric, unit, facing the camera
  double Distance = 0.0;            ///< along the ray
  bool OnTube = false;              ///< a line drawn as a tube, not a triangle
};

/// The triangles of a renderer's visible actors (world space, actor matrices applied) in an
/// Embree scene, and their lines drawn as tubes (vtkProperty RenderLinesAsTubes, LineWidth > 1)
/// as the main view draws them: cones with flat caps (Embree's cone linear curves) whose radius
/// at each vertex is 0.5 * LineWidth * the world size of one pixel of the active camera there
/// (2 d tan(angle / 2) / height at view depth d; 2 parallelScale / height). Those depend on the
/// camera: build again for each view (TubesFollowCamera()). Coordinates are stored relative to
/// the scene's centre, so scenes far from the origin keep their precision in Embree's
/// single-precision vertices.
class RayScene
{
public:
  RayScene();
  ~RayScene();
  RayScene(const RayScene&) = delete;
  RayScene& operator=(const RayScene&) = delete;

  /// Returns the number of triangles and tube segments, 0 when there is nothing to cast
  /// against. Tubes are sized for the renderer's active camera in a viewport of height pixels
  /// (0: the renderer's own size).
  long long Build(vtkRenderer* renderer, int height = 0);

  /// Did the last Build() add tubes (whose size depends on the camera)?
  bool TubesFollowCamera() const;

  /// Visible surface of every pixel (row 0 at the bottom, as VTK images), for the camera seen
  /// in a width x height viewport.
  std::vector<Surface> CastPrimary(vtkCamera* camera, int width, int height) const;

  /// True when something lies between the surface point and a directional light travelling
  /// along lightDirection.
  bool Occluded(const Surface& s, const double lightDirection[3]) const;

  /// The pixels a shadow edge crosses: among `comparable` ones, those where the truth at one of
  /// the pixel's four corners (the primary ray through the corner met on the plane of the surface
  /// seen at the pixel's centre) differs from `occluded`, the truth at its centre. There a lookup
  /// that places the edge anywhere within the pixel is as right as the centre's truth; a light
  /// leak or acne shows in the other pixels. surfaces, comparable, occluded: as CastPrimary,
  /// ComparablePixels and Occluded give them for this camera and size.
  std::vector<char> ShadowEdges(vtkCamera* camera, int width, int height,
    const std::vector<Surface>& surfaces, const std::vector<char>& comparable,
    const std::vector<char>& occluded, const double lightDirection[3]) const;

private:
  struct Internals;
  std::unique_ptr<Internals> Internal;
};

/// Result of comparing a shadow-factor image with the truth.
struct Classification
{
  long Considered = 0;  ///< visible pixels that face the light, away from silhouettes
  long FalseShadow = 0; ///< factor < 0.5 but lit (acne, widened shadows)
  long FalseLight = 0;  ///< factor >= 0.5 but occluded (leaks, peter-panning, lost thin casters)
  /// With the shadow edges given (RayScene::ShadowEdges): the considered pixels no edge crosses,
  /// and how many of those are misclassified (0 and 0 without them).
  long OffEdge = 0;
  long OffEdgeWrong = 0;
  double MismatchPct() const
  {
    return Considered ? 100.0 * (FalseShadow + FalseLight) / Considered : 0.0;
  }
  double FalseShadowPct() const { return Considered ? 100.0 * FalseShadow / Considered : 0.0; }
  double FalseLightPct() const { return Considered ? 100.0 * FalseLight / Considered : 0.0; }
  /// Misclassified pixels that no shadow edge crosses, of all considered (NaN without edges).
  double OffEdgeMismatchPct() const
  {
    return Considered && OffEdge ? 100.0 * OffEdgeWrong / Considered : NAN;
  }
  /// Another image's counts added to these.
  void Add(const Classification& other)
  {
    Considered += other.Considered;
    FalseShadow += other.FalseShadow;
    FalseLight += other.FalseLight;
    OffEdge += other.OffEdge;
    OffEdgeWrong += other.OffEdgeWrong;
  }
};

/// Pixels to compare: hit, facing the light (n . -L > 0.05), and not on a silhouette (no
/// 4-neighbour whose hit is more than 2% farther or nearer).
std::vector<char> ComparablePixels(
  const std::vector<Surface>& surfaces, int width, int height, const double lightDirection[3]);

/// One pixel against the truth: not compared, classified right (lit or shadowed), or wrong.
enum class PixelClass
{
  NotCompared,
  Lit,
  Shadowed,
  FalseShadow, ///< factor < 0.5 but lit
  FalseLight   ///< factor >= 0.5 but occluded
};

/// The class of one pixel (factor: 0 shadowed .. 1 lit, NaN where it cannot be measured).
PixelClass ClassifyPixel(bool comparable, bool occluded, float factor);

/// factor: per pixel, 0 (shadowed) .. 1 (lit), NaN where it cannot be measured. edges
/// (optional, RayScene::ShadowEdges): the pixels a shadow edge crosses, for the OffEdge counts.
Classification Classify(const std::vector<Surface>& surfaces, const std::vector<char>& comparable,
  const std::vector<char>& occluded, const std::vector<float>& factor,
  const std::vector<char>* edges = nullptr);

/// Shadow factor of a technique: the render with shadows over the render without, for a scene
/// lit by one white light with only diffuse reflection (NaN where the plain render is dark).
std::vector<float> FactorFromRenders(vtkImageData* shadowed, vtkImageData* plain);

/// Max, 95th percentile and mean of a list (empty: zeros).
struct Stats
{
  double Max = 0, P95 = 0, Mean = 0;
};
Stats Summarize(std::vector<double> values);

} // namespace csmTruth
