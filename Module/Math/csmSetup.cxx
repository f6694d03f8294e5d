// SPDX-License-Identifier: BSD-3-Clause
// The cascades of a directional light for one frame: body, splits, warp (Barroso & Celes 2007,
// Eq. 16-18), focus (Lloyd et al. 2006, §6.4) and error (Lloyd et al. 2006, Eq. 9-12); see
// csmSetup.h.
#include "csmSetup.h"

#include "csmAliasing.h"
#include "csmConvexBody.h"
#include "csmGeometry.h"
#include "csmVisibleDepth.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace csm
{
namespace
{
/// Beyond n' = kOrthoRatio * (light-space depth of the body) the warp differs from orthographic
/// by < 0.2% in storage but costs precision (t = A - B/z' cancels): use the orthographic map.
constexpr double kOrthoRatio = 1.0e3;

/// What computeShadowSetup checks of a directional light and the settings beyond
/// acceptSetupInput; empty when they can be used.
std::string directionalLightError(const glm::dvec3& wsLightDirection, const Settings& settings)
{
  const std::string lightError = lightDirectionError(wsLightDirection);
  if (!lightError.empty())
  {
    return lightError;
  }
  const SplitParameters& split = settings.split;
  if (split.k < 1 || split.k > kMaxSplits)
  {
    return "number of cascades must be in [1, 64]";
  }
  if (!(split.lambda >= 0.0 && split.lambda <= 1.0))
  {
    return "lambda must be in [0, 1]";
  }
  if (!(split.alpha > 1.0) || !std::isfinite(split.alpha))
  {
    return "alpha must be finite and > 1";
  }
  return {};
}

/// The receivers of a view partition: the partition clipped by each receiver box (or the one
/// scene box, or nothing without bounds), as the vertices of those convex bodies.
class ReceiverClipper
{
public:
  ReceiverClipper(const Camera& camera, const CameraFrame& frame, const Bounds* sceneBounds,
    const std::vector<Bounds>* receiverParts, const ViewFootprint* footprint = nullptr)
    : Cam(camera)
    , Frame(frame)
    , Footprint(footprint && !footprint->window.isEmpty() ? footprint : nullptr)
  {
    if (!sceneBounds)
    {
      return;
    }
    this->Clip = true;
    if (receiverParts && !receiverParts->empty())
    {
      for (const Bounds& part : *receiverParts)
      {
        if (!part.isEmpty())
        {
          this->Boxes.push_back(cameraCentredBoxPlanes(part, camera));
        }
      }
    }
    else
    {
      this->Boxes.push_back(cameraCentredBoxPlanes(*sceneBounds, camera));
    }
  }

  /// extra: more half-spaces (camera-centred) every part is clipped by. With a footprint, the
  /// partition is only the image rectangle of its visible samples (all of it where it has none).
  std::vector<glm::dvec3> body(
    double d0, double d1, const std::vector<Plane>* extra = nullptr) const
  {
    ConvexBody partition = ConvexBody::hexahedron(partitionCorners(this->Cam, this->Frame, d0, d1));
    const double epsilon = clipEpsilon(this->Cam, this->Frame, std::min(d1, this->Cam.vsFar));
    for (const Plane& plane : extra ? *extra : std::vector<Plane>())
    {
      partition.clip(plane, epsilon);
    }
    if (this->Footprint)
    {
      const ScreenRect rect =
        footprintRect(this->Footprint->window, this->Footprint->measuredBy, d0, d1);
      for (const Plane& plane : screenRectPlanes(this->Cam, rect))
      {
        partition.clip(plane, epsilon);
      }
    }
    if (!this->Clip)
    {
      return partition.vertices(epsilon);
    }
    std::vector<glm::dvec3> vertices;
    ConvexBody part; // (assigned each box: its faces' buffers are reused)
    for (const auto& planes : this->Boxes)
    {
      part = partition;
      for (const Plane& plane : planes)
      {
        part.clip(plane, epsilon);
      }
      const std::vector<glm::dvec3> partVertices = part.vertices(epsilon);
      vertices.insert(vertices.end(), partVertices.begin(), partVertices.end());
    }
    return vertices;
  }

private:
  const Camera& Cam;
  const CameraFrame& Frame;
  const ViewFootprint* Footprint = nullptr;
  bool Clip = false;
  std::vector<std::array<Plane, 6>> Boxes;
};

/// The view depth range [n, f] of the visible receivers, within the camera's; false when the
/// view sees none of them.
bool fitDepthRange(const ReceiverClipper& receivers, const Camera& camera, const CameraFrame& frame,
  double& n, double& f)
{
  const std::vector<glm::dvec3> visible = receivers.body(camera.vsNear, camera.vsFar);
  if (visible.empty())
  {
    return false;
  }
  double lo = kInf, hi = -kInf;
  for (const glm::dvec3& p : visible)
  {
    const double depth = glm::dot(p, frame.view);
    lo = std::min(lo, depth);
    hi = std::max(hi, depth);
  }
  n = std::clamp(lo, camera.vsNear, camera.vsFar);
  f = std::clamp(hi, camera.vsNear, camera.vsFar);
  if (!(f > n * (1.0 + 1e-6)))
  {
    const double middle = 0.5 * (n + f);
    n = std::max(camera.vsNear, middle * (1.0 - 1e-6));
    f = std::min(camera.vsFar, middle * (1.0 + 1e-6));
  }
  return true;
}

/// A cascade's points in light space: its receiver body and, without depth clamping, the
/// casters between it and the light (the body extruded toward the light to the scene box); a
/// flat or point body gets a minimum thickness on each axis.
std::vector<glm::dvec3> lightSpacePoints(const std::vector<glm::dvec3>& cwsBody,
  const LightBasis& ls, const Camera& camera, const Bounds* sceneBounds, bool depthClamp)
{
  std::vector<glm::dvec3> lsPoints;
  lsPoints.reserve(2 * cwsBody.size() + 6);
  glm::dvec3 lsMin(kInf), lsMax(-kInf);
  for (const glm::dvec3& p : cwsBody)
  {
    lsPoints.push_back(ls.coordinates(p));
    lsMin = glm::min(lsMin, lsPoints.back());
    lsMax = glm::max(lsMax, lsPoints.back());
  }
  if (sceneBounds && !depthClamp)
  {
    const double grow =
      inflation(glm::length(sceneBounds->wsMax - sceneBounds->wsMin), camera.vsNear);
    const glm::dvec3 cwsBoxMin = sceneBounds->wsMin - camera.wsPosition - grow;
    const glm::dvec3 cwsBoxMax = sceneBounds->wsMax - camera.wsPosition + grow;
    for (const glm::dvec3& p : cwsBody)
    {
      lsPoints.push_back(ls.coordinates(p - ls.y * exitTowardLight(p, ls.y, cwsBoxMin, cwsBoxMax)));
    }
  }
  const glm::dvec3 lsSize = lsMax - lsMin;
  const double minSize = inflation(std::max({ lsSize.x, lsSize.y, lsSize.z }), camera.vsNear);
  const glm::dvec3 lsCentre = 0.5 * (lsMin + lsMax);
  for (int axis = 0; axis < 3; ++axis)
  {
    if (lsSize[axis] < minSize)
    {
      glm::dvec3 offset(0.0);
      offset[axis] = minSize;
      lsPoints.push_back(lsCentre - offset);
      lsPoints.push_back(lsCentre + offset);
    }
  }
  return lsPoints;
}

/// What the cascades of one frame share: the camera's frame, light space, the folded angle
/// between light and view, and the shape of the view volume in the plane of light and view.
struct DirectionalFrame
{
  const Camera& camera;
  const Settings& settings;
  const Bounds* sceneBounds;
  CameraFrame frame;
  LightBasis ls;
  double gamma = 0.0;          ///< between view and light, 0..pi
  double gammaFolded = 0.0;    ///< light from behind ~ from the front: 0..pi/2
  double heightPerDepth = 0.0; ///< a, b of Barroso & Celes 2007, §3.1 per unit depth
  glm::dmat4 wsToLs{ 1.0 };

  DirectionalFrame(
    const Camera& cam, const glm::dvec3& wsLightDirection, const Settings& s, const Bounds* bounds)
    : camera(cam)
    , settings(s)
    , sceneBounds(bounds)
    , frame(cameraFrame(cam))
    , ls(lightBasis(frame, wsLightDirection))
  {
    this->gamma = angleBetween(this->frame.view, this->ls.y);
    this->gammaFolded = std::min(this->gamma, kPi - this->gamma);
    // Half-height of the view volume per unit depth in the plane of light and view (a, b of
    // Barroso & Celes 2007, §3.1): the support of the image rectangle in the direction of the
    // light's image-plane part.
    const glm::dvec3 lightAcross = perpendicularPart(this->ls.y, frame.view, frame.up);
    this->heightPerDepth = std::abs(glm::dot(lightAcross, frame.right)) * frame.tanX +
      std::abs(glm::dot(lightAcross, frame.up)) * frame.tanY;
    this->wsToLs = frameMatrix(this->ls.x, this->ls.y, this->ls.z, cam.wsPosition);
  }

  /// The view partition [d0, d1] as the warp sees it (Barroso & Celes 2007, §3.1).
  PartitionShape shape(double d0, double d1) const
  {
    return PartitionShape{ d0, d1, d0 * this->heightPerDepth, d1 * this->heightPerDepth };
  }
};

/// The cascade of the view partition [d0, d1] whose receivers are cwsBody (not empty): its
/// light-space points, warp, focus and error.
Cascade partitionCascade(
  const DirectionalFrame& in, double d0, double d1, const std::vector<glm::dvec3>& cwsBody)
{
  const Camera& camera = in.camera;
  Cascade cascade;
  cascade.vsNear = d0;
  cascade.vsFar = d1;
  cascade.gammaLimDeg = gammaLim(in.shape(d0, d1)) / kDegree;
  for (const glm::dvec3& p : cwsBody)
  {
    cascade.wsBody.push_back(p + camera.wsPosition);
  }
  std::vector<glm::dvec3> lsPoints =
    lightSpacePoints(cwsBody, in.ls, camera, in.sceneBounds, in.settings.depthClamp);
  double lsZMin = kInf, lsZMax = -kInf;
  for (const glm::dvec3& p : lsPoints)
  {
    lsZMin = std::min(lsZMin, p.z);
    lsZMax = std::max(lsZMax, p.z);
  }
  // The warp: a perspective along ls z with its centre n' before the body (Barroso & Celes
  // 2007, Fig. 4 and 6); orthographic where n' is so large that it only costs precision.
  double warp = camera.parallel ? kInf : nPrime(in.settings.warp, in.gammaFolded, in.shape(d0, d1));
  const double lsDepth = std::max(lsZMax - lsZMin, inflation(0.0, camera.vsNear));
  if (!(warp <= kOrthoRatio * lsDepth))
  {
    warp = kInf;
  }
  warp = std::max(warp, 1e-9 * lsDepth);
  if (std::isinf(warp))
  {
    keepOrthographicDepthRange(lsPoints, true); // (a warped map's depth varies across it)
  }
  cascade.nPrime = warp;
  const glm::dmat4 lsToWarped = warpMatrix(warp, lsZMin);
  // Orthographic maps of WarpMode::None keep their texel size while the camera moves a little
  // (and snapToTexels() fixes their texel grid in the world).
  const bool stable =
    in.settings.stableOrthographic && in.settings.warp == WarpMode::None && std::isinf(warp);
  cascade.wsToClip = focusMatrix(lsPoints, lsToWarped, stable) * lsToWarped * in.wsToLs;
  cascadeError(cascade, camera, in.ls.y);
  return cascade;
}

/// The farthest cascade once more with the scene-fitted map: its receivers within the map's
/// extent across the light (the rest cannot be in shadow); false where there are none.
bool sceneFittedCascade(const DirectionalFrame& in, const ReceiverClipper& receivers,
  const Cascade& last, const SceneFit& fit, Cascade& fitted)
{
  const Camera& camera = in.camera;
  std::vector<Plane> cwsPrism;
  for (const Plane& plane : fit.wsPrism)
  {
    cwsPrism.push_back({ plane.normal, plane.offset + glm::dot(plane.normal, camera.wsPosition) });
  }
  const std::vector<glm::dvec3> cwsBody = receivers.body(last.vsNear, last.vsFar, &cwsPrism);
  if (cwsBody.empty())
  {
    return false;
  }
  fitted.vsNear = last.vsNear;
  fitted.vsFar = last.vsFar;
  fitted.gammaLimDeg = last.gammaLimDeg;
  fitted.nPrime = kInf;
  fitted.sceneFitted = true;
  fitted.wsToClip = fit.wsToClip;
  for (const glm::dvec3& p : cwsBody)
  {
    fitted.wsBody.push_back(p + camera.wsPosition);
  }
  // Along this view's ls x and z (the rows of the fit's map best aligned with them), as
  // Lloyd's M of every cascade.
  cascadeError(fitted, camera, in.ls.y);
  return true;
}
} // namespace

double orthographicDepthFloor(double lsAcross, double eyeDistance)
{
  const double scale = std::max(lsAcross, eyeDistance);
  return std::isfinite(scale) && scale > 0.0 ? kOrthographicDepthShare * scale : 0.0;
}

void keepOrthographicDepthRange(std::vector<glm::dvec3>& lsPoints, bool eyeAtOrigin)
{
  glm::dvec3 lo(kInf), hi(-kInf);
  double eyeDistance = 0.0;
  for (const glm::dvec3& p : lsPoints)
  {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
    eyeDistance = std::max(eyeDistance, glm::length(p));
  }
  const double floor =
    orthographicDepthFloor(std::max(hi.x - lo.x, hi.z - lo.z), eyeAtOrigin ? eyeDistance : 0.0);
  if (lsPoints.empty() || !(hi.y - lo.y < floor))
  {
    return;
  }
  const glm::dvec3 centre = 0.5 * (lo + hi);
  lsPoints.push_back(centre - glm::dvec3(0.0, 0.5 * floor, 0.0));
  lsPoints.push_back(centre + glm::dvec3(0.0, 0.5 * floor, 0.0));
}

glm::dmat4 warpMatrix(double nPrime, double lsZMin)
{
  if (std::isinf(nPrime))
  {
    return fromRows({ 1, 0, 0, 0 }, { 0, 0, 1, 0 }, { 0, 1, 0, 0 }, { 0, 0, 0, 1 });
  }
  const double zCentre = lsZMin - nPrime;
  return fromRows({ 1, 0, 0, 0 }, { 0, 0, 0, -1 }, { 0, 1, 0, 0 }, { 0, 0, 1, -zCentre });
}

glm::dmat4 focusMatrix(
  const std::vector<glm::dvec3>& lsPoints, const glm::dmat4& lsToWarped, bool quantizeExtent)
{
  glm::dvec3 lo(kInf), hi(-kInf);
  for (const glm::dvec3& p : lsPoints)
  {
    const glm::dvec4 h = lsToWarped * glm::dvec4(p, 1.0);
    const glm::dvec3 q = glm::dvec3(h) / h.w;
    lo = glm::min(lo, q);
    hi = glm::max(hi, q);
  }
  const double depthMargin = 0.01 * (hi.z - lo.z); // Lloyd et al. 2006, §6.4: room for the bias
  lo.z -= depthMargin;
  hi.z += depthMargin;
  if (quantizeExtent)
  {
    for (int a = 0; a < 2; ++a)
    {
      const double size = hi[a] - lo[a];
      if (size > 0.0 && std::isfinite(size))
      {
        const double quantized = std::exp2(std::ceil(4.0 * std::log2(1.04 * size)) / 4.0);
        const double centre = 0.5 * (lo[a] + hi[a]);
        lo[a] = centre - 0.5 * quantized;
        hi[a] = centre + 0.5 * quantized;
      }
    }
  }
  const glm::dvec3 scale = 2.0 / (hi - lo);
  return fromRows({ scale.x, 0, 0, -scale.x * 0.5 * (lo.x + hi.x) },
    { 0, scale.y, 0, -scale.y * 0.5 * (lo.y + hi.y) },
    { 0, 0, scale.z, -scale.z * 0.5 * (lo.z + hi.z) }, { 0, 0, 0, 1 });
}

glm::dmat4 snapToTexels(const glm::dmat4& wsToClip, const MapSize& resolution)
{
  // Affine: the last row is (0, 0, 0, 1).
  if (resolution.width <= 0 || resolution.height <= 0 || wsToClip[0][3] != 0.0 ||
    wsToClip[1][3] != 0.0 || wsToClip[2][3] != 0.0 || wsToClip[3][3] != 1.0)
  {
    return wsToClip;
  }
  glm::dmat4 snapped = wsToClip;
  for (int row = 0; row < 2; ++row)
  {
    // clip = s u + b with u the world coordinate along the row's unit axis; the texel edges are
    // at u = (k 2 / R - 1 - b) / s: fixed in the world when b / (2 / R) is a whole number (R
    // even) or a half (R odd).
    const int texels = row == 0 ? resolution.width : resolution.height;
    const double texel = 2.0 / texels;
    const double shift = texels % 2 == 0 ? 0.0 : 0.5;
    const double b = wsToClip[3][row];
    const double snappedB = (std::round(b / texel - shift) + shift) * texel;
    if (std::isfinite(snappedB))
    {
      snapped[3][row] = snappedB;
    }
  }
  return snapped;
}

ShadowSetup computeShadowSetup(const Camera& camera, const glm::dvec3& wsLightDirection,
  const Bounds* sceneBounds, const Settings& settings, const std::vector<Bounds>* receiverParts,
  const SceneFit* fit)
{
  ShadowSetup setup;
  if (!acceptSetupInput(setup, camera, sceneBounds,
        directionalLightError(wsLightDirection, settings), receiverParts))
  {
    return setup;
  }
  const DirectionalFrame in(camera, wsLightDirection, settings, sceneBounds);
  setup.gammaDeg = in.gamma / kDegree;

  // 1. Receivers, and the depth range of what is visible of them.
  const ReceiverClipper receivers(
    camera, in.frame, sceneBounds, receiverParts, settings.visibleFootprint);
  double n = camera.vsNear;
  double f = camera.vsFar;
  if (sceneBounds && !fitDepthRange(receivers, camera, in.frame, n, f))
  {
    setup.status = Status::NothingToShadow;
    setup.message = "the view sees none of the scene";
    return setup;
  }
  setup.vsNear = n;
  setup.vsFar = f;

  // 2. Splits.
  setup.splits = splitDepths(settings.split, n, f, in.gammaFolded);
  setup.gammaLimDeg = gammaLim(in.shape(n, f)) / kDegree;

  // 3. Per partition: body, light-space points, warp, focus, error.
  for (size_t i = 0; i + 1 < setup.splits.size(); ++i)
  {
    const double d0 = setup.splits[i];
    const double d1 = setup.splits[i + 1];
    const std::vector<glm::dvec3> cwsBody = receivers.body(d0, d1);
    if (cwsBody.empty())
    {
      continue; // nothing of the scene in this partition
    }
    setup.cascades.push_back(partitionCascade(in, d0, d1, cwsBody));
    setup.storageTotal += setup.cascades.back().storage;
  }

  // 4. The farthest cascade on the scene-fitted map.
  Cascade fitted;
  if (fit && sceneBounds && !setup.cascades.empty() &&
    sceneFittedCascade(in, receivers, setup.cascades.back(), *fit, fitted))
  {
    setup.sceneFitted.push_back(std::move(fitted));
  }
  setup.storageOptimal = camera.parallel
    ? std::numeric_limits<double>::quiet_NaN()
    : (std::log(f) - std::log(n)) / (2.0 * in.frame.tanY); // Lloyd et al. 2006, App. C
  if (setup.cascades.empty())
  {
    setup.status = Status::NothingToShadow;
    setup.message = "no partition of the view holds any of the scene";
    return setup;
  }
  setup.status = Status::Ok;
  return setup;
}

} // namespace csm
