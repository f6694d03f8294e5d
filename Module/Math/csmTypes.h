// SPDX-License-Identifier: BSD-3-Clause
// The value types the shadow-map math shares: the camera, boxes, the settings of a plan, map
// sizes, a cascade and the plan of one light for one frame (ShadowSetup), the casters the count
// and the scene-fitted map are judged by, and the scene-fitted map itself. The quantities named
// here come from Lloyd et al. 2006 (M_x, M_z: Eq. 9-10, §4.4; storage: Eq. 12, App. C) and
// Barroso & Celes 2007 (n': Eq. 16-18; gamma_lim: Eq. 15). Pure math (C++17, GLM, double
// precision): no VTK, no GL.
//
// Spaces (prefixes on names):
//   ws  world space.
//   cws camera-centred world space: world axes, origin at the eye (keeps numbers small far
//       from the origin).
//   vs  view space; vsDepth is the distance along the view direction.
//   ls  light space (Lloyd et al. 2006, Fig. 3): origin at the eye, y along the light's direction
//   of travel,
//       z the view direction projected onto the plane perpendicular to y, x = y cross z.
//   clip the light's clip space: after division by w, the cascade's body lies in [-1,1]^3;
//       NDC x is the shadow-map s axis (ls x), NDC y the t axis (ls z), NDC z the light depth.
#pragma once

#include "csmConvexBody.h"
#include "csmSplits.h"
#include "csmWarp.h"

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace csm
{

struct Camera
{
  glm::dvec3 wsPosition{ 0.0, 0.0, 0.0 };
  glm::dvec3 wsDirection{ 0.0, 0.0, -1.0 }; ///< view direction (need not be unit length)
  glm::dvec3 wsViewUp{ 0.0, 1.0, 0.0 };     ///< need not be orthogonal to the direction
  double vsNear = 0.1;                      ///< clipping range along the view direction
  double vsFar = 1000.0;
  double fovyDeg = 30.0;      ///< full vertical field of view (perspective)
  double aspect = 1.0;        ///< image width / height
  bool parallel = false;      ///< parallel projection
  double parallelScale = 1.0; ///< half the image height in world units (parallel projection)
};

/// An axis-aligned box; min > max on any axis means "empty".
struct Bounds
{
  glm::dvec3 wsMin{ 1.0, 1.0, 1.0 };
  glm::dvec3 wsMax{ -1.0, -1.0, -1.0 };
  bool isEmpty() const
  {
    return !(this->wsMin.x <= this->wsMax.x && this->wsMin.y <= this->wsMax.y &&
      this->wsMin.z <= this->wsMax.z);
  }
  bool isFinite() const
  {
    return std::isfinite(this->wsMin.x) && std::isfinite(this->wsMin.y) &&
      std::isfinite(this->wsMin.z) && std::isfinite(this->wsMax.x) &&
      std::isfinite(this->wsMax.y) && std::isfinite(this->wsMax.z);
  }
  /// The box of six numbers in the order xmin, xmax, ymin, ymax, zmin, zmax (VTK's bounds);
  /// empty for none.
  static Bounds fromMinMaxPairs(const double* minMaxPairs)
  {
    Bounds box;
    if (minMaxPairs)
    {
      box.wsMin = { minMaxPairs[0], minMaxPairs[2], minMaxPairs[4] };
      box.wsMax = { minMaxPairs[1], minMaxPairs[3], minMaxPairs[5] };
    }
    return box;
  }
};

struct ViewFootprint;

struct Settings
{
  WarpMode warp = WarpMode::Generalized;
  SplitParameters split;  ///< defaults: adaptive, k = 2, alpha = 2 (Barroso & Celes 2007, §4)
  bool depthClamp = true; ///< Lloyd et al. 2006, §6.4: fit the depth range to the receivers only
  /// Orthographic cascades of WarpMode::None get a quantized width and height (focusMatrix), so
  /// that snapToTexels() can fix their texel grid in the world. Off for the analysis (the
  /// papers' storage factors); the render passes turn it on.
  bool stableOrthographic = false;
  /// computeShadowSetupForError may give the farthest cascade the map of sceneFit, which does not
  /// follow the view, where that meets the error target (with caster loads): the passes keep it
  /// while the scene and the light stay. Off for the analysis; the render passes turn it on.
  bool sceneFitted = false;
  /// Where this very view has visible samples, by depth (csmVisibleDepth.h): each cascade's
  /// receivers are then only those its samples' image rectangle shows. Null: the whole view.
  const ViewFootprint* visibleFootprint = nullptr;
};

struct Cascade
{
  double vsNear = 0.0; ///< split depths of this cascade
  double vsFar = 0.0;
  double nPrime = 0.0;            ///< warp parameter; +infinity when orthographic
  double gammaLimDeg = 0.0;       ///< Barroso & Celes 2007, Eq. 15 for this partition
  glm::dmat4 wsToClip{ 1.0 };     ///< world -> light clip space
  std::vector<glm::dvec3> wsBody; ///< vertices of the receiver body (view partition ∩ scene)
  double Mx = 0.0;                ///< Lloyd et al. 2006, Eq. 9-10 as in §4.4: maxima over wsBody
  double Mz = 0.0;
  double storage =
    0.0; ///< Lloyd et al. 2006, Eq. 12: critical texels / image pixels = Mx Mz / aspect
  /// The map is turned a quarter (orientToTile): its s axis follows ls z and its t axis ls x, so
  /// that Mz gets the tile's width and Mx its height.
  bool mapTurned = false;
  /// Its map does not follow the view (sceneFit): it is drawn once while the scene and the light
  /// stay, with all the texels of its tile.
  bool sceneFitted = false;
};

/// Texels of a map or a tile along its s axis (width) and t axis (height).
struct MapSize
{
  int width = 0;
  int height = 0;
  MapSize() = default;
  MapSize(int side) // NOLINT: a square map of side texels
    : width(side)
    , height(side)
  {
  }
  MapSize(int w, int h)
    : width(w)
    , height(h)
  {
  }
  bool operator==(const MapSize& other) const
  {
    return width == other.width && height == other.height;
  }
};

enum class Status
{
  Ok,
  NothingToShadow, ///< empty scene, or the view sees none of it: no cascades
  InvalidInput     ///< message says what; no cascades
};

inline const char* toString(Status status)
{
  switch (status)
  {
    case Status::Ok:
      return "ok";
    case Status::NothingToShadow:
      return "nothing-to-shadow";
    case Status::InvalidInput:
      return "invalid-input";
  }
  return "?";
}

struct ShadowSetup
{
  Status status = Status::InvalidInput;
  std::string message;
  double gammaDeg = 0.0; ///< angle between light and view direction, 0..180 (0: light from behind)
  double gammaLimDeg = 0.0; ///< Barroso & Celes 2007, Eq. 15 for the whole fitted frustum
  double vsNear = 0.0;      ///< depth range the cascades cover (clipping range fitted to the scene)
  double vsFar = 0.0;
  std::vector<double> splits;    ///< split depths, vsNear .. vsFar
  std::vector<Cascade> cascades; ///< the non-empty cascades, near to far
  double storageTotal = 0.0;     ///< sum of the cascades' storage factors
  double storageOptimal =
    0.0; ///< Lloyd et al. 2006, App. C: ln(f/n) / (2 tan theta); NaN for parallel projection
  /// With a SceneFit: the farthest cascade with the scene-fitted map instead (0 or 1 of them).
  std::vector<Cascade> sceneFitted;
};

/// A caster as the cascade count and the scene-fitted map are judged by: its world box, the cells
/// (triangles, lines, vertices) a map pass draws of it, the receiver box (index into the
/// receiver parts; -1: none) of its own prop, whether that prop may shadow itself, and whether
/// it is drawn wider than its data (tubes, spheres, wide lines sized in the main view's pixels:
/// its box does not hold its shadow's extent).
struct CasterLoad
{
  Bounds wsBox;
  double cells = 0.0;
  int receiver = -1;
  bool shadowsItself = true;
  bool screenSized = false;
};

/// An orthographic map fixed in the world of the part of the scene that can be in shadow
/// (sceneFit, csmSceneFit.h): its light clip matrix, its map axes s and t in the world, and the
/// four half-spaces of its s, t extent (world space; normal . p + offset >= 0 inside).
struct SceneFit
{
  glm::dmat4 wsToClip{ 1.0 };
  glm::dvec3 wsMapX{ 1.0, 0.0, 0.0 };
  glm::dvec3 wsMapZ{ 0.0, 0.0, 1.0 };
  std::array<Plane, 4> wsPrism;
};

} // namespace csm
