// SPDX-License-Identifier: BSD-3-Clause
#include "csmShadowSetup.h"

#include "csmConvexBody.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace csm
{
namespace
{
constexpr double kPi = 3.14159265358979323846;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kDegree = kPi / 180.0;
/// Beyond n' = kOrthoRatio * (light-space depth of the body) the warp differs from orthographic
/// by < 0.2% in storage but costs precision (t = A - B/z' cancels): use the orthographic map.
constexpr double kOrthoRatio = 1.0e3;
constexpr double kMinDistance = 1e-50; // camera near and far distances a double handles
constexpr double kMaxDistance = 1e50;

bool finite(const glm::dvec3& v)
{
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

/// Any unit vector perpendicular to the unit vector n.
glm::dvec3 perpendicular(const glm::dvec3& n)
{
  const glm::dvec3 helper = std::abs(n.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  return glm::normalize(glm::cross(n, helper));
}

/// The part of u perpendicular to the unit vector n, normalized; fallback where u is (nearly)
/// parallel to n.
glm::dvec3 perpendicularPart(const glm::dvec3& u, const glm::dvec3& n, const glm::dvec3& fallback)
{
  const glm::dvec3 p = u - glm::dot(u, n) * n;
  const double length = glm::length(p);
  return length > 1e-9 ? p / length : fallback;
}

struct CameraFrame
{
  glm::dvec3 view, up, right; // orthonormal
  double tanX = 0.0, tanY = 0.0;
};

CameraFrame cameraFrame(const Camera& camera)
{
  CameraFrame frame;
  frame.view = glm::normalize(camera.wsDirection);
  frame.up = perpendicularPart(camera.wsViewUp, frame.view, perpendicular(frame.view));
  frame.right = glm::cross(frame.view, frame.up);
  frame.tanY = std::tan(0.5 * camera.fovyDeg * kDegree);
  frame.tanX = frame.tanY * camera.aspect;
  return frame;
}

struct LightBasis
{
  glm::dvec3 x, y, z; // Lloyd et al. 2006, Fig. 3; y is the light's direction of travel
};

LightBasis lightBasis(const CameraFrame& frame, const glm::dvec3& wsLightDirection)
{
  LightBasis ls;
  ls.y = glm::normalize(wsLightDirection);
  // z: the view direction projected onto the plane perpendicular to the light; when light and
  // view are parallel, the view-up vector takes its place (it is perpendicular to both).
  ls.z = perpendicularPart(
    frame.view, ls.y, perpendicularPart(frame.up, ls.y, perpendicular(ls.y)));
  ls.x = glm::cross(ls.y, ls.z);
  return ls;
}

/// Half-widths of the view volume at a depth (perspective or parallel).
glm::dvec2 halfSize(const Camera& camera, const CameraFrame& frame, double vsDepth)
{
  if (camera.parallel)
  {
    return { camera.parallelScale * camera.aspect, camera.parallelScale };
  }
  return { vsDepth * frame.tanX, vsDepth * frame.tanY };
}

/// The view-volume partition [d0, d1], in camera-centred world space.
std::array<glm::dvec3, 8> partitionCorners(
  const Camera& camera, const CameraFrame& frame, double d0, double d1)
{
  std::array<glm::dvec3, 8> corners;
  const double signX[4] = { -1, 1, 1, -1 };
  const double signY[4] = { -1, -1, 1, 1 };
  for (int face = 0; face < 2; ++face)
  {
    const double depth = face == 0 ? d0 : d1;
    const glm::dvec2 half = halfSize(camera, frame, depth);
    for (int i = 0; i < 4; ++i)
    {
      corners[4 * face + i] =
        frame.view * depth + frame.right * (signX[i] * half.x) + frame.up * (signY[i] * half.y);
    }
  }
  return corners;
}

/// Parameter t >= 0 where the ray p - t d (toward the light) leaves the box [lo, hi].
double exitTowardLight(const glm::dvec3& p, const glm::dvec3& d, const glm::dvec3& lo,
  const glm::dvec3& hi)
{
  double t = kInf;
  for (int i = 0; i < 3; ++i)
  {
    if (d[i] < 0.0)
    {
      t = std::min(t, (hi[i] - p[i]) / -d[i]);
    }
    else if (d[i] > 0.0)
    {
      t = std::min(t, (p[i] - lo[i]) / d[i]);
    }
  }
  return std::isfinite(t) ? std::max(t, 0.0) : 0.0;
}

glm::dmat4 fromRows(const glm::dvec4& r0, const glm::dvec4& r1, const glm::dvec4& r2,
  const glm::dvec4& r3)
{
  glm::dmat4 m;
  for (int c = 0; c < 4; ++c)
  {
    m[c] = glm::dvec4(r0[c], r1[c], r2[c], r3[c]);
  }
  return m;
}

/// Corner i (0..7, bit 0: x, bit 1: y, bit 2: z at the maximum) of a box.
glm::dvec3 boxCorner(const Bounds& box, int i)
{
  return { (i & 1) ? box.wsMax.x : box.wsMin.x, (i & 2) ? box.wsMax.y : box.wsMin.y,
    (i & 4) ? box.wsMax.z : box.wsMin.z };
}

/// How much a box or a body of the given size is grown so that a flat or point scene keeps a
/// volume: relative to its size, and at least to the camera's near distance.
double inflation(double size, double vsNear)
{
  return 1e-6 * std::max(size, vsNear);
}

/// The clip planes of a box, camera-centred and inflated.
std::array<Plane, 6> cameraCentredBoxPlanes(const Bounds& box, const Camera& camera)
{
  const double grow = inflation(glm::length(box.wsMax - box.wsMin), camera.vsNear);
  return boxPlanes(box.wsMin - camera.wsPosition - grow, box.wsMax - camera.wsPosition + grow);
}

/// Clipping tolerance for the view volume up to a depth: relative to its size there, not to the
/// whole view (a near partition may be 1e-20 of the far distance).
double clipEpsilon(const Camera& camera, const CameraFrame& frame, double vsDepth)
{
  const glm::dvec2 half = halfSize(camera, frame, vsDepth);
  return 1e-12 * (vsDepth + half.x + half.y);
}

std::string validateCamera(const Camera& camera, const Bounds* bounds)
{
  if (!finite(camera.wsPosition) || !finite(camera.wsDirection) || !finite(camera.wsViewUp))
  {
    return "camera position, direction and view-up must be finite";
  }
  if (!(glm::length(camera.wsDirection) > 0.0))
  {
    return "camera direction has zero length";
  }
  if (!std::isfinite(camera.vsNear) || !std::isfinite(camera.vsFar) || !(camera.vsNear > 0.0))
  {
    return "camera near distance must be finite and > 0";
  }
  if (!(camera.vsFar > camera.vsNear * (1.0 + 1e-9)))
  {
    return "camera far distance must be greater than near";
  }
  // Beyond these the squared distances of the body's points over- or underflow a double.
  if (camera.vsNear < kMinDistance || camera.vsFar > kMaxDistance)
  {
    return "camera near and far distances must be within [1e-50, 1e50]";
  }
  if (!(camera.aspect > 0.0) || !std::isfinite(camera.aspect))
  {
    return "aspect ratio must be finite and > 0";
  }
  if (!camera.parallel && !(camera.fovyDeg > 0.0 && camera.fovyDeg < 180.0))
  {
    return "field of view must be in (0, 180) degrees";
  }
  if (camera.parallel && !(camera.parallelScale > 0.0 && std::isfinite(camera.parallelScale)))
  {
    return "parallel scale must be finite and > 0";
  }
  if (bounds && !bounds->isFinite())
  {
    return "scene bounds must be finite";
  }
  return {};
}

std::string validate(const Camera& camera, const glm::dvec3& light, const Bounds* bounds,
  const Settings& settings)
{
  const std::string cameraError = validateCamera(camera, bounds);
  if (!cameraError.empty())
  {
    return cameraError;
  }
  const std::string lightError = lightDirectionError(light);
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

} // namespace

bool Bounds::isEmpty() const
{
  return !(this->wsMin.x <= this->wsMax.x && this->wsMin.y <= this->wsMax.y &&
    this->wsMin.z <= this->wsMax.z);
}

bool Bounds::isFinite() const
{
  return finite(this->wsMin) && finite(this->wsMax);
}

namespace
{
/// The receivers of a view partition: the partition clipped by each receiver box (or the one
/// scene box, or nothing without bounds), as the vertices of those convex bodies.
class ReceiverClipper
{
public:
  ReceiverClipper(const Camera& camera, const CameraFrame& frame, const Bounds* sceneBounds,
    const std::vector<Bounds>* receiverParts)
    : Cam(camera)
    , Frame(frame)
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

  /// extra: more half-spaces (camera-centred) every part is clipped by.
  std::vector<glm::dvec3> body(
    double d0, double d1, const std::vector<Plane>* extra = nullptr) const
  {
    ConvexBody partition =
      ConvexBody::hexahedron(partitionCorners(this->Cam, this->Frame, d0, d1));
    const double epsilon = clipEpsilon(this->Cam, this->Frame, std::min(d1, this->Cam.vsFar));
    for (const Plane& plane : extra ? *extra : std::vector<Plane>())
    {
      partition.clip(plane, epsilon);
    }
    if (!this->Clip)
    {
      return partition.vertices(epsilon);
    }
    std::vector<glm::dvec3> vertices;
    for (const auto& planes : this->Boxes)
    {
      ConvexBody part = partition;
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
  bool Clip = false;
  std::vector<std::array<Plane, 6>> Boxes;
};

/// The view depth range [n, f] of the visible receivers, within the camera's; false when the
/// view sees none of them.
bool fitDepthRange(const ReceiverClipper& receivers, const Camera& camera,
  const CameraFrame& frame, double& n, double& f)
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
  auto toLight = [&](const glm::dvec3& p) {
    return glm::dvec3(glm::dot(p, ls.x), glm::dot(p, ls.y), glm::dot(p, ls.z));
  };
  std::vector<glm::dvec3> lsPoints;
  lsPoints.reserve(2 * cwsBody.size() + 6);
  glm::dvec3 lsMin(kInf), lsMax(-kInf);
  for (const glm::dvec3& p : cwsBody)
  {
    lsPoints.push_back(toLight(p));
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
      lsPoints.push_back(toLight(p - ls.y * exitTowardLight(p, ls.y, cwsBoxMin, cwsBoxMax)));
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

/// The points of an orthographic map (light space, camera-centred: x, z across the light, y
/// along it) with the depth range orthographicDepthFloor gives at least: two points about the
/// middle of the depth range where it is thinner.
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
  const double floor = orthographicDepthFloor(
    std::max(hi.x - lo.x, hi.z - lo.z), eyeAtOrigin ? eyeDistance : 0.0);
  if (lsPoints.empty() || !(hi.y - lo.y < floor))
  {
    return;
  }
  const glm::dvec3 centre = 0.5 * (lo + hi);
  lsPoints.push_back(centre - glm::dvec3(0.0, 0.5 * floor, 0.0));
  lsPoints.push_back(centre + glm::dvec3(0.0, 0.5 * floor, 0.0));
}

/// Lloyd et al. 2006, §4.4: maxima of the beam-width ratios over the body's vertices, and
/// Eq. 12's storage factor.
void cascadeError(Cascade& cascade, const Camera& camera, const glm::dvec3& wsLightDirection)
{
  for (const glm::dvec3& p : cascade.wsBody)
  {
    const Aliasing m = aliasingAt(cascade.wsToClip, camera, wsLightDirection, p);
    cascade.Mx = std::max(cascade.Mx, m.mx);
    cascade.Mz = std::max(cascade.Mz, m.mz);
  }
  cascade.storage = cascade.Mx * cascade.Mz / camera.aspect;
}
} // namespace

double orthographicDepthFloor(double lsAcross, double eyeDistance)
{
  const double scale = std::max(lsAcross, eyeDistance);
  return std::isfinite(scale) && scale > 0.0 ? kOrthographicDepthShare * scale : 0.0;
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

glm::dmat4 focusMatrix(const std::vector<glm::dvec3>& lsPoints, const glm::dmat4& lsToWarped,
  bool quantizeExtent)
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
  setup.message = validate(camera, wsLightDirection, sceneBounds, settings);
  if (setup.message.empty() && receiverParts)
  {
    for (const Bounds& part : *receiverParts)
    {
      if (!part.isFinite())
      {
        setup.message = "receiver bounds must be finite";
      }
    }
  }
  if (!setup.message.empty())
  {
    setup.status = Status::InvalidInput;
    return setup;
  }
  if (sceneBounds && sceneBounds->isEmpty())
  {
    setup.status = Status::NothingToShadow;
    setup.message = "the scene is empty";
    return setup;
  }

  const CameraFrame frame = cameraFrame(camera);
  const LightBasis ls = lightBasis(frame, wsLightDirection);
  const double gamma = std::atan2(glm::length(glm::cross(frame.view, ls.y)),
    glm::dot(frame.view, ls.y));
  const double gammaFolded = std::min(gamma, kPi - gamma); // light from behind ~ from the front
  setup.gammaDeg = gamma / kDegree;

  // 1. Receivers, and the depth range of what is visible of them.
  const ReceiverClipper receivers(camera, frame, sceneBounds, receiverParts);
  double n = camera.vsNear;
  double f = camera.vsFar;
  if (sceneBounds && !fitDepthRange(receivers, camera, frame, n, f))
  {
    setup.status = Status::NothingToShadow;
    setup.message = "the view sees none of the scene";
    return setup;
  }
  setup.vsNear = n;
  setup.vsFar = f;

  // 2. Splits.
  setup.splits = splitDepths(settings.split, n, f, gammaFolded);

  // Half-height of the view volume per unit depth in the plane of light and view (a, b of
  // Barroso & Celes 2007, §3.1): the support of the image rectangle in the direction of the
  // light's image-plane part.
  const glm::dvec3 lightAcross = perpendicularPart(ls.y, frame.view, frame.up);
  const double heightPerDepth = std::abs(glm::dot(lightAcross, frame.right)) * frame.tanX +
    std::abs(glm::dot(lightAcross, frame.up)) * frame.tanY;
  auto shape = [&](double d0, double d1) {
    return PartitionShape{ d0, d1, d0 * heightPerDepth, d1 * heightPerDepth };
  };
  setup.gammaLimDeg = gammaLim(shape(n, f)) / kDegree;
  const glm::dmat4 wsToLs = fromRows({ ls.x, -glm::dot(ls.x, camera.wsPosition) },
    { ls.y, -glm::dot(ls.y, camera.wsPosition) }, { ls.z, -glm::dot(ls.z, camera.wsPosition) },
    { 0, 0, 0, 1 });

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
    Cascade cascade;
    cascade.vsNear = d0;
    cascade.vsFar = d1;
    cascade.gammaLimDeg = gammaLim(shape(d0, d1)) / kDegree;
    for (const glm::dvec3& p : cwsBody)
    {
      cascade.wsBody.push_back(p + camera.wsPosition);
    }
    std::vector<glm::dvec3> lsPoints =
      lightSpacePoints(cwsBody, ls, camera, sceneBounds, settings.depthClamp);
    double lsZMin = kInf, lsZMax = -kInf;
    for (const glm::dvec3& p : lsPoints)
    {
      lsZMin = std::min(lsZMin, p.z);
      lsZMax = std::max(lsZMax, p.z);
    }
    // The warp: a perspective along ls z with its centre n' before the body (Barroso & Celes
    // 2007, Fig. 4 and 6); orthographic where n' is so large that it only costs precision.
    double warp = camera.parallel ? kInf : nPrime(settings.warp, gammaFolded, shape(d0, d1));
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
      settings.stableOrthographic && settings.warp == WarpMode::None && std::isinf(warp);
    cascade.wsToClip = focusMatrix(lsPoints, lsToWarped, stable) * lsToWarped * wsToLs;
    cascadeError(cascade, camera, ls.y);
    setup.storageTotal += cascade.storage;
    setup.cascades.push_back(std::move(cascade));
  }

  if (fit && sceneBounds && !setup.cascades.empty())
  {
    // The farthest cascade once more with the scene-fitted map: its receivers within the map's
    // extent across the light (the rest cannot be in shadow).
    const Cascade& last = setup.cascades.back();
    std::vector<Plane> cwsPrism;
    for (const Plane& plane : fit->wsPrism)
    {
      cwsPrism.push_back(
        { plane.normal, plane.offset + glm::dot(plane.normal, camera.wsPosition) });
    }
    const std::vector<glm::dvec3> cwsBody = receivers.body(last.vsNear, last.vsFar, &cwsPrism);
    if (!cwsBody.empty())
    {
      Cascade fitted;
      fitted.vsNear = last.vsNear;
      fitted.vsFar = last.vsFar;
      fitted.gammaLimDeg = last.gammaLimDeg;
      fitted.nPrime = kInf;
      fitted.sceneFitted = true;
      fitted.wsToClip = fit->wsToClip;
      for (const glm::dvec3& p : cwsBody)
      {
        // Along this view's ls x and z (the rows of the fit's map best aligned with them), as
        // Lloyd's M of every cascade.
        fitted.wsBody.push_back(p + camera.wsPosition);
        const Aliasing m = aliasingAt(fitted.wsToClip, camera, ls.y, fitted.wsBody.back());
        fitted.Mx = std::max(fitted.Mx, m.mx);
        fitted.Mz = std::max(fitted.Mz, m.mz);
      }
      fitted.storage = fitted.Mx * fitted.Mz / camera.aspect;
      setup.sceneFitted.push_back(std::move(fitted));
    }
  }
  setup.storageOptimal = camera.parallel
    ? std::numeric_limits<double>::quiet_NaN()
    : (std::log(f) - std::log(n)) / (2.0 * frame.tanY); // Lloyd et al. 2006, App. C
  if (setup.cascades.empty())
  {
    setup.status = Status::NothingToShadow;
    setup.message = "no partition of the view holds any of the scene";
    return setup;
  }
  setup.status = Status::Ok;
  return setup;
}

bool sceneFit(const glm::dvec3& wsLightDirection, const Bounds& sceneBounds,
  const std::vector<CasterLoad>& casters, const std::vector<Bounds>* receiverParts,
  SceneFit& fit)
{
  if (!finite(wsLightDirection) || !(glm::length(wsLightDirection) > 0.0) ||
    !sceneBounds.isFinite() || sceneBounds.isEmpty())
  {
    return false;
  }
  // Axes fixed in the world: the light's direction of travel and a perpendicular of it alone.
  LightBasis ls;
  ls.y = glm::normalize(wsLightDirection);
  ls.x = perpendicular(ls.y);
  ls.z = glm::cross(ls.x, ls.y);
  const glm::dvec3 wsOrigin = 0.5 * (sceneBounds.wsMin + sceneBounds.wsMax);
  // A box's extent in light space (x, y, z), about the origin.
  auto lsExtent = [&](const Bounds& box, glm::dvec3& lo, glm::dvec3& hi) {
    lo = glm::dvec3(kInf);
    hi = glm::dvec3(-kInf);
    for (int i = 0; i < 8; ++i)
    {
      const glm::dvec3 p = boxCorner(box, i) - wsOrigin;
      const glm::dvec3 q(glm::dot(p, ls.x), glm::dot(p, ls.y), glm::dot(p, ls.z));
      lo = glm::min(lo, q);
      hi = glm::max(hi, q);
    }
  };
  const std::vector<Bounds> sceneOnly{ sceneBounds };
  const std::vector<Bounds>& receivers =
    receiverParts && !receiverParts->empty() ? *receiverParts : sceneOnly;
  std::vector<glm::dvec3> receiverLo(receivers.size()), receiverHi(receivers.size());
  for (size_t r = 0; r < receivers.size(); ++r)
  {
    lsExtent(receivers[r], receiverLo[r], receiverHi[r]);
  }
  // Across the light: the union of caster footprints over the receivers each can reach.
  glm::dvec2 lo(kInf), hi(-kInf);
  for (const CasterLoad& caster : casters)
  {
    if (caster.screenSized)
    {
      return false;
    }
    if (!caster.wsBox.isFinite() || caster.wsBox.isEmpty())
    {
      continue;
    }
    glm::dvec3 cLo, cHi;
    lsExtent(caster.wsBox, cLo, cHi);
    for (size_t r = 0; r < receivers.size(); ++r)
    {
      const bool own = &receivers == receiverParts && static_cast<int>(r) == caster.receiver;
      if ((own && !caster.shadowsItself) || receivers[r].isEmpty() ||
        !sweptBoxReachesBox(caster.wsBox, ls.y, receivers[r], 0.0))
      {
        continue;
      }
      // (x and z: across the light.)
      const glm::dvec2 a =
        glm::max(glm::dvec2(cLo.x, cLo.z), glm::dvec2(receiverLo[r].x, receiverLo[r].z));
      const glm::dvec2 b =
        glm::min(glm::dvec2(cHi.x, cHi.z), glm::dvec2(receiverHi[r].x, receiverHi[r].z));
      if (a.x <= b.x && a.y <= b.y)
      {
        lo = glm::min(lo, a);
        hi = glm::max(hi, b);
      }
    }
  }
  if (!(lo.x <= hi.x && lo.y <= hi.y))
  {
    return false; // nothing can be in shadow
  }
  // Along the light: the scene's extent; a flat extent gets a minimum size, as a cascade's.
  glm::dvec3 sceneLo, sceneHi;
  lsExtent(sceneBounds, sceneLo, sceneHi);
  glm::dvec3 lsLo(lo.x, sceneLo.y, lo.y), lsHi(hi.x, sceneHi.y, hi.y);
  const double minSize = inflation(glm::length(sceneBounds.wsMax - sceneBounds.wsMin), 0.0);
  for (int axis = 0; axis < 3; ++axis)
  {
    const double grow = 0.5 * std::max(minSize - (lsHi[axis] - lsLo[axis]), 0.0) + minSize;
    lsLo[axis] -= grow;
    lsHi[axis] += grow;
  }
  std::vector<glm::dvec3> lsPoints{ lsLo, lsHi };
  keepOrthographicDepthRange(lsPoints, false); // (no eye: about the scene's middle)
  const glm::dmat4 wsToLs = fromRows({ ls.x, -glm::dot(ls.x, wsOrigin) },
    { ls.y, -glm::dot(ls.y, wsOrigin) }, { ls.z, -glm::dot(ls.z, wsOrigin) }, { 0, 0, 0, 1 });
  const glm::dmat4 lsToMap = warpMatrix(kInf, 0.0);
  fit.wsToClip = focusMatrix(lsPoints, lsToMap, false) * lsToMap * wsToLs;
  fit.wsMapX = ls.x;
  fit.wsMapZ = ls.z;
  // x >= lsLo.x: ls.x . (p - origin) - lsLo.x >= 0, and so on.
  fit.wsPrism = { { { ls.x, -glm::dot(ls.x, wsOrigin) - lsLo.x },
    { -ls.x, glm::dot(ls.x, wsOrigin) + lsHi.x }, { ls.z, -glm::dot(ls.z, wsOrigin) - lsLo.z },
    { -ls.z, glm::dot(ls.z, wsOrigin) + lsHi.z } } };
  return true;
}

ShadowSetup computeSpotSetup(const Camera& camera, const glm::dvec3& wsLightPosition,
  const glm::dvec3& wsLightAxis, double coneAngleDeg, const Bounds* sceneBounds, bool depthClamp)
{
  ShadowSetup setup;
  setup.message = validateCamera(camera, sceneBounds);
  if (setup.message.empty() &&
    (!finite(wsLightPosition) || !finite(wsLightAxis) || !(glm::length(wsLightAxis) > 0.0)))
  {
    setup.message = "spot light position and direction must be finite and non-zero";
  }
  if (setup.message.empty() && !(coneAngleDeg > 0.0 && coneAngleDeg < 90.0))
  {
    setup.message = "spot light cone angle must be in (0, 90) degrees";
  }
  if (!setup.message.empty())
  {
    setup.status = Status::InvalidInput;
    return setup;
  }
  if (sceneBounds && sceneBounds->isEmpty())
  {
    setup.status = Status::NothingToShadow;
    setup.message = "the scene is empty";
    return setup;
  }
  const CameraFrame frame = cameraFrame(camera);
  const double epsilon = clipEpsilon(camera, frame, camera.vsFar);

  // What the view needs: the visible scene inside the cone's bounding pyramid.
  ConvexBody body =
    ConvexBody::hexahedron(partitionCorners(camera, frame, camera.vsNear, camera.vsFar));
  if (sceneBounds)
  {
    for (const Plane& plane : cameraCentredBoxPlanes(*sceneBounds, camera))
    {
      body.clip(plane, epsilon);
    }
  }
  const glm::dvec3 w = glm::normalize(wsLightAxis);
  const glm::dvec3 u = perpendicular(w);
  const glm::dvec3 v = glm::cross(w, u);
  const glm::dvec3 cwsApex = wsLightPosition - camera.wsPosition;
  const double tanCone = std::tan(coneAngleDeg * kDegree);
  const glm::dvec3 sideNormals[4] = { tanCone * w - u, tanCone * w + u, tanCone * w - v,
    tanCone * w + v };
  for (const glm::dvec3& normal : sideNormals)
  {
    body.clip({ normal, -glm::dot(normal, cwsApex) }, epsilon);
  }
  if (body.empty())
  {
    setup.status = Status::NothingToShadow;
    setup.message = "the spot light reaches none of the visible scene";
    return setup;
  }

  // Light frame: x along u, y along v, z the distance along the axis.
  double zMin = kInf, zMax = -kInf, vsMin = kInf, vsMax = -kInf;
  glm::dvec2 lo(kInf), hi(-kInf);
  const std::vector<glm::dvec3> vertices = body.vertices(epsilon);
  Cascade cascade;
  for (const glm::dvec3& p : vertices)
  {
    const glm::dvec3 q = p - cwsApex;
    const double z = glm::dot(q, w);
    zMin = std::min(zMin, z);
    zMax = std::max(zMax, z);
    const double depth = glm::dot(p, frame.view);
    vsMin = std::min(vsMin, depth);
    vsMax = std::max(vsMax, depth);
    cascade.wsBody.push_back(p + camera.wsPosition);
  }
  const double zFar = std::max(zMax, 1e-9 * (camera.vsFar + glm::length(cwsApex))) * 1.01;
  double zNear = 1e-3 * zFar;
  if (depthClamp)
  {
    zNear = std::max(zNear, 0.99 * zMin);
  }
  else if (sceneBounds)
  {
    double boxMin = kInf; // nearest corner of the scene box along the axis
    for (int i = 0; i < 8; ++i)
    {
      boxMin = std::min(boxMin, glm::dot(boxCorner(*sceneBounds, i) - wsLightPosition, w));
    }
    zNear = std::max(zNear, 0.99 * boxMin);
  }
  for (const glm::dvec3& p : vertices)
  {
    const glm::dvec3 q = p - cwsApex;
    const double z = std::max(glm::dot(q, w), zNear);
    const glm::dvec2 xy(glm::dot(q, u) / z, glm::dot(q, v) / z);
    lo = glm::min(lo, xy);
    hi = glm::max(hi, xy);
  }
  lo = glm::max(lo, glm::dvec2(-tanCone));
  hi = glm::min(hi, glm::dvec2(tanCone));
  for (int axis = 0; axis < 2; ++axis)
  {
    const double minWidth = 1e-6 * tanCone;
    if (!(hi[axis] - lo[axis] > minWidth))
    {
      const double middle = 0.5 * (lo[axis] + hi[axis]);
      lo[axis] = middle - minWidth;
      hi[axis] = middle + minWidth;
    }
  }
  // Off-centre perspective (glFrustum at unit distance) looking along the axis.
  const double a = (zFar + zNear) / (zFar - zNear);
  const double b = -2.0 * zFar * zNear / (zFar - zNear);
  const glm::dmat4 projection = fromRows({ 2.0 / (hi.x - lo.x), 0, -(hi.x + lo.x) / (hi.x - lo.x), 0 },
    { 0, 2.0 / (hi.y - lo.y), -(hi.y + lo.y) / (hi.y - lo.y), 0 }, { 0, 0, a, b }, { 0, 0, 1, 0 });
  const glm::dmat4 view = fromRows({ u, -glm::dot(u, wsLightPosition) },
    { v, -glm::dot(v, wsLightPosition) }, { w, -glm::dot(w, wsLightPosition) }, { 0, 0, 0, 1 });
  cascade.wsToClip = projection * view;
  cascade.vsNear = std::clamp(vsMin, camera.vsNear, camera.vsFar);
  cascade.vsFar = std::clamp(vsMax, camera.vsNear, camera.vsFar);
  if (!(cascade.vsFar > cascade.vsNear))
  {
    cascade.vsFar = std::min(camera.vsFar, cascade.vsNear * (1.0 + 1e-6));
  }
  cascade.nPrime = kInf;
  setup.vsNear = cascade.vsNear;
  setup.vsFar = cascade.vsFar;
  setup.splits = { cascade.vsNear, cascade.vsFar };
  setup.gammaDeg = std::atan2(glm::length(glm::cross(frame.view, w)), glm::dot(frame.view, w)) / kDegree;
  setup.storageOptimal = 0.0;
  setup.cascades.push_back(std::move(cascade));
  setup.status = Status::Ok;
  return setup;
}

glm::dvec2 mapAxisAliasing(const Cascade& cascade)
{
  return cascade.mapTurned ? glm::dvec2(cascade.Mz, cascade.Mx) : glm::dvec2(cascade.Mx, cascade.Mz);
}

namespace
{
/// max(M_s / width, M_t / height) for the map as it is turned now, or turned once more.
double errorAsTurned(const Cascade& cascade, const MapSize& map, bool turnOnceMore = false)
{
  const glm::dvec2 m = mapAxisAliasing(cascade);
  return turnOnceMore ? std::max(m.y / map.width, m.x / map.height)
                      : std::max(m.x / map.width, m.y / map.height);
}
}

double predictedError(const Cascade& cascade, double imageHeight, const MapSize& map)
{
  if (map.width <= 0 || map.height <= 0)
  {
    return std::numeric_limits<double>::infinity();
  }
  return imageHeight * std::min(errorAsTurned(cascade, map), errorAsTurned(cascade, map, true));
}

double predictedError(const ShadowSetup& setup, double imageHeight, const CascadeCeilings& maps)
{
  if (setup.cascades.empty())
  {
    return std::numeric_limits<double>::infinity();
  }
  double worst = 0.0;
  for (const Cascade& c : setup.cascades)
  {
    worst = std::max(worst, predictedError(c, imageHeight, maps.of(c)));
  }
  return worst;
}

void orientToTile(ShadowSetup& setup, const MapSize& tile)
{
  if (tile.width <= 0 || tile.height <= 0 || tile.width == tile.height)
  {
    return;
  }
  for (Cascade& c : setup.cascades)
  {
    if (c.sceneFitted || !(errorAsTurned(c, tile, true) < errorAsTurned(c, tile)))
    {
      continue; // (a scene-fitted map keeps its axes: its matrix must not change with the view)
    }
    // New s = old t, new t = -old s (glm is column-major: m[column][row]).
    for (int column = 0; column < 4; ++column)
    {
      const double s = c.wsToClip[column][0];
      c.wsToClip[column][0] = c.wsToClip[column][1];
      c.wsToClip[column][1] = -s;
    }
    c.mapTurned = !c.mapTurned;
  }
}

ShadowSetup computeShadowSetupForCount(const Camera& camera, const glm::dvec3& wsLightDirection,
  const Bounds* sceneBounds, const Settings& settings, const std::vector<Bounds>* receiverParts,
  int k, const CascadeCeilings& maps, const SceneFit* fit)
{
  Settings s = settings;
  s.split.k = k;
  ShadowSetup plan =
    computeShadowSetup(camera, wsLightDirection, sceneBounds, s, receiverParts, fit);
  if (plan.status != Status::Ok || k < 2 || s.split.scheme != SplitScheme::Adaptive)
  {
    return plan;
  }
  s.split.scheme = SplitScheme::Log;
  ShadowSetup logPlan =
    computeShadowSetup(camera, wsLightDirection, sceneBounds, s, receiverParts, fit);
  // The common factor imageHeight does not change the order.
  return logPlan.status == Status::Ok &&
      predictedError(logPlan, 1.0, maps) < predictedError(plan, 1.0, maps)
    ? logPlan
    : plan;
}

double texelsForError(const ShadowSetup& setup, double imageHeight, double targetError,
  const CascadeCeilings& ceilings)
{
  if (setup.cascades.empty() || !(targetError > 0.0))
  {
    return std::numeric_limits<double>::infinity();
  }
  double texels = 0.0;
  for (const Cascade& c : setup.cascades)
  {
    // resolutionForError's sides, without the rounding to its step (a scene-fitted map: its
    // tile).
    const MapSize& ceiling = ceilings.of(c);
    const double side =
      c.sceneFitted ? kInf : std::max(c.Mx, c.Mz) * imageHeight / targetError;
    const double s = std::isfinite(side) ? side : ceiling.width;
    const double t = std::isfinite(side) ? side : ceiling.height;
    // (std::min below keeps a scene-fitted map at its tile.)
    texels += std::min<double>(std::max(s, 1.0), ceiling.width) *
      std::min<double>(std::max(t, 1.0), ceiling.height);
  }
  return texels;
}

double passTexels(const ShadowSetup& setup, const std::vector<CasterLoad>& casters)
{
  double cells = 0.0;
  for (const CasterLoad& caster : casters)
  {
    cells += std::max(caster.cells, 0.0);
  }
  double passes = 0.0;
  for (const Cascade& c : setup.cascades)
  {
    passes += c.sceneFitted ? 0.0 : 1.0;
  }
  return passes * cells * kTexelsPerCasterTriangle;
}

ShadowSetup computeShadowSetupForError(const Camera& camera, const glm::dvec3& wsLightDirection,
  const Bounds* sceneBounds, const Settings& settings, const std::vector<Bounds>* receiverParts,
  double imageHeight, int maximumResolution, double targetError, int kPrevious,
  const std::vector<CasterLoad>* casters)
{
  const int kMax = std::max(1, settings.split.k);
  auto ceilingOf = [&](int k) { return ceilingsForCount(k, kMax, maximumResolution); };
  auto errorOf = [&](const ShadowSetup& plan, int k) {
    return predictedError(plan, imageHeight, ceilingOf(k));
  };
  // With casters the counts that meet the target are weighed by what they cost to render;
  // without, the smallest is taken (the cost is then the count). A scene-fitted map costs
  // nothing: it is drawn once while the scene and the light stay.
  const bool weighed = casters != nullptr;
  auto costOf = [&](const ShadowSetup& plan, int k) {
    if (!weighed)
    {
      return static_cast<double>(k);
    }
    ShadowSetup followingView = plan;
    followingView.cascades.clear();
    for (const Cascade& c : plan.cascades)
    {
      if (!c.sceneFitted)
      {
        followingView.cascades.push_back(c);
      }
    }
    return followingView.cascades.empty()
      ? 0.0
      : passTexels(followingView, *casters) +
        texelsForError(followingView, imageHeight, targetError, ceilingOf(k));
  };
  // A count's plan, or (settings.sceneFitted, square tiles) the same with its farthest cascade
  // on the scene-fitted map (sceneFit), whichever meets the target at less cost; false:
  // neither does.
  auto meeting = [&](const ShadowSetup& plan, int k, ShadowSetup& taken, double& cost) {
    bool found = false;
    if (errorOf(plan, k) <= targetError)
    {
      taken = plan;
      cost = costOf(plan, k);
      found = true;
    }
    const MapSize tile = ceilingOf(k).sceneFitted;
    if (!plan.sceneFitted.empty() && !plan.cascades.empty() && tile.width == tile.height)
    {
      ShadowSetup fitted = plan;
      fitted.cascades.back() = plan.sceneFitted.front();
      if (errorOf(fitted, k) <= targetError)
      {
        const double fittedCost = costOf(fitted, k);
        if (!found || fittedCost <= cost)
        {
          taken = std::move(fitted);
          cost = fittedCost;
          found = true;
        }
      }
    }
    return found;
  };
  // The scene-fitted map, the same for every count.
  SceneFit fit;
  const bool fitted = settings.sceneFitted && casters && sceneBounds &&
    sceneFit(wsLightDirection, *sceneBounds, *casters, receiverParts, fit);
  auto planFor = [&](int k) {
    return computeShadowSetupForCount(camera, wsLightDirection, sceneBounds, settings,
      receiverParts, k, ceilingOf(k), fitted ? &fit : nullptr);
  };
  std::vector<ShadowSetup> plans;
  std::vector<double> errors;
  int chosen = 0; // 1-based; 0: none meets the target
  ShadowSetup chosenPlan;
  double chosenCost = 0.0;
  int best = 0;   // where none does: the count taken
  for (int k = 1; k <= kMax; ++k)
  {
    if (chosen > 0 && !weighed)
    {
      break;
    }
    plans.push_back(planFor(k));
    if (plans.back().status != Status::Ok)
    {
      return plans.back(); // the same for every count
    }
    errors.push_back(errorOf(plans.back(), k));
    if (best == 0 || errors.back() < kCountHysteresis * errors[best - 1])
    {
      best = k;
    }
    ShadowSetup taken;
    double cost = 0.0;
    if (meeting(plans.back(), k, taken, cost) && (chosen == 0 || cost < chosenCost))
    {
      chosen = k;
      chosenPlan = std::move(taken);
      chosenCost = cost;
    }
  }
  if (chosen == 0)
  {
    // None meets the target. A previous count close to the best error stays (no popping
    // between two counts that do about as well).
    if (kPrevious >= 1 && kPrevious <= kMax && kPrevious != best &&
      errors[kPrevious - 1] * kCountHysteresis <= errors[best - 1])
    {
      return plans[kPrevious - 1];
    }
    return plans[best - 1];
  }
  if (kPrevious >= 1 && kPrevious <= kMax && kPrevious != chosen)
  {
    // Another count does better, but not by a margin: keep the previous one if it still meets
    // the target.
    const bool byMargin =
      !weighed && errorOf(chosenPlan, chosen) <= kCountHysteresis * targetError;
    if (weighed || (kPrevious > chosen && !byMargin))
    {
      const ShadowSetup previous = kPrevious <= static_cast<int>(plans.size())
        ? plans[kPrevious - 1]
        : planFor(kPrevious);
      ShadowSetup taken;
      double cost = 0.0;
      if (previous.status == Status::Ok && meeting(previous, kPrevious, taken, cost) &&
        (!weighed || kCountHysteresis * cost <= chosenCost))
      {
        return taken;
      }
    }
  }
  return chosenPlan;
}

AtlasGrid atlasLayout(int mostCascades, int resolution, int maximumSide)
{
  AtlasGrid atlas;
  if (mostCascades < 1 || resolution < 1)
  {
    return atlas;
  }
  const int maps = std::min(mostCascades, kAtlasFullMaps);
  const int side = static_cast<int>(std::lround(std::sqrt(double(maps))));
  atlas.columns = side * side == maps ? side : maps;
  atlas.rows = side * side == maps ? side : 1;
  int tile = resolution;
  if (maximumSide > 0)
  {
    tile = std::max(1, std::min(tile, maximumSide / std::max(atlas.columns, atlas.rows)));
  }
  atlas.tile = MapSize(tile);
  return atlas;
}

AtlasGrid atlasGrid(int count, const AtlasGrid& atlas)
{
  AtlasGrid grid;
  if (count < 1 || atlas.tile.width < 1 || atlas.tile.height < 1)
  {
    return grid;
  }
  const long long width = static_cast<long long>(atlas.columns) * atlas.tile.width;
  const long long height = static_cast<long long>(atlas.rows) * atlas.tile.height;
  auto better = [](const MapSize& a, const MapSize& b) {
    const int shortA = std::min(a.width, a.height), shortB = std::min(b.width, b.height);
    return shortA != shortB ? shortA > shortB
                            : static_cast<long long>(a.width) * a.height >
        static_cast<long long>(b.width) * b.height;
  };
  for (int columns = 1; columns <= count; ++columns)
  {
    const int rows = (count + columns - 1) / columns;
    const MapSize tile(static_cast<int>(std::min<long long>(width / columns, atlas.tile.width)),
      static_cast<int>(std::min<long long>(height / rows, atlas.tile.height)));
    if (better(tile, grid.tile))
    {
      grid.columns = columns;
      grid.rows = rows;
      grid.tile = tile;
    }
  }
  return grid;
}

AtlasGrid atlasForCount(int count, const AtlasGrid& atlas)
{
  if (count < 1 || atlas.tile.width < 1 || atlas.tile.height < 1)
  {
    return AtlasGrid();
  }
  if (count > 1)
  {
    return atlasGrid(count, atlas);
  }
  AtlasGrid one;
  one.tile = MapSize(std::min(atlas.columns * atlas.tile.width, atlas.rows * atlas.tile.height));
  return one;
}

MapSize resolutionCeilingForCount(int count, int mostCascades, int resolution)
{
  return atlasForCount(count, atlasLayout(std::max(mostCascades, count), resolution)).tile;
}

CascadeCeilings ceilingsForCount(int count, int mostCascades, int resolution)
{
  CascadeCeilings ceilings(resolutionCeilingForCount(count, mostCascades, resolution));
  ceilings.following.width = std::min(ceilings.following.width, std::max(resolution, 0));
  ceilings.following.height = std::min(ceilings.following.height, std::max(resolution, 0));
  return ceilings;
}

int resolutionForError(double maxAliasing, double imageHeight, double targetError, int step,
  int ceiling)
{
  ceiling = std::max(ceiling, 1);
  step = std::max(1, std::min(step, ceiling));
  const double texels = maxAliasing * imageHeight / targetError;
  if (!(maxAliasing > 0.0) || !(imageHeight > 0.0) || !(targetError > 0.0) ||
    !std::isfinite(texels) || texels >= ceiling)
  {
    return ceiling;
  }
  const int steps = static_cast<int>(std::ceil(texels / step));
  return std::min(ceiling, std::max(step, steps * step));
}

MapSize resolutionForError(const Cascade& cascade, double imageHeight, double targetError,
  int step, const MapSize& ceiling)
{
  // Both axes get the texels of the larger M (a map sharper along its other axis than the target
  // asks costs little and keeps the filter's footprint round); each within its side of the tile.
  if (cascade.sceneFitted)
  {
    return MapSize(std::max(ceiling.width, 1), std::max(ceiling.height, 1)); // drawn once
  }
  const double m = std::max(cascade.Mx, cascade.Mz);
  return MapSize(resolutionForError(m, imageHeight, targetError, step, ceiling.width),
    resolutionForError(m, imageHeight, targetError, step, ceiling.height));
}

Aliasing aliasingAt(const glm::dmat4& wsToClip, const Camera& camera,
  const glm::dvec3& wsLightDirection, const glm::dvec3& wsPoint)
{
  const LightBasis ls = lightBasis(cameraFrame(camera), wsLightDirection);
  return aliasingAt(wsToClip, camera, ls.x, ls.z, wsPoint);
}

Aliasing aliasingAt(const glm::dmat4& wsToClip, const Camera& camera, const glm::dvec3& wsMapX,
  const glm::dvec3& wsMapZ, const glm::dvec3& wsPoint)
{
  const CameraFrame frame = cameraFrame(camera);
  // Lloyd et al. 2006, Eq. 2 with res_i = 1: width of the image beam at the point.
  const double depth = std::max(glm::dot(wsPoint - camera.wsPosition, frame.view), camera.vsNear);
  const double wi = camera.parallel ? 2.0 * camera.parallelScale : 2.0 * frame.tanY * depth;

  const glm::dvec4 h = wsToClip * glm::dvec4(wsPoint, 1.0);
  const glm::dmat4 t = glm::transpose(wsToClip); // t[r] is row r
  auto gradient = [&](int row) { // d(ndc_row)/d(ws point)
    return (glm::dvec3(t[row]) * h.w - glm::dvec3(t[3]) * h[row]) / (h.w * h.w);
  };
  // Lloyd et al. 2006, Eq. 3-4 with res = 1: s, t in [0, 1] are half the NDC. The map axis
  // along ls x is the row that follows it: s, or t for a map turned a quarter (orientToTile),
  // also when the map was planned for an earlier camera (whose ls x differs a little) or its
  // axes are not ls x and z at all (VTK's map: the better aligned row).
  const bool turned = std::abs(glm::dot(glm::dvec3(t[1]), wsMapX)) >
    std::abs(glm::dot(glm::dvec3(t[0]), wsMapX));
  const double dsdx = 0.5 * std::abs(glm::dot(gradient(turned ? 1 : 0), wsMapX));
  const double dtdz = 0.5 * std::abs(glm::dot(gradient(turned ? 0 : 1), wsMapZ));
  Aliasing m;
  m.mx = (dsdx > 0.0 ? 1.0 / dsdx : kInf) / wi;
  m.mz = (dtdz > 0.0 ? 1.0 / dtdz : kInf) / wi;
  return m;
}

std::string cameraError(const Camera& camera)
{
  return validateCamera(camera, nullptr);
}

std::string lightDirectionError(const glm::dvec3& wsLightDirection)
{
  return finite(wsLightDirection) && glm::length(wsLightDirection) > 0.0
    ? std::string()
    : "light direction must be finite and non-zero";
}

bool boxOutsideClipVolume(const glm::dmat4& wsToClip, const Bounds& box, bool depthClamp)
{
  if (box.isEmpty())
  {
    return true;
  }
  // Count, for each clip plane, the corners outside it; all eight outside one plane: culled.
  int outside[7] = { 0, 0, 0, 0, 0, 0, 0 };
  for (int i = 0; i < 8; ++i)
  {
    const glm::dvec4 h = wsToClip * glm::dvec4(boxCorner(box, i), 1.0);
    outside[0] += h.x < -h.w;
    outside[1] += h.x > h.w;
    outside[2] += h.y < -h.w;
    outside[3] += h.y > h.w;
    outside[4] += h.z > h.w;
    outside[5] += !depthClamp && h.z < -h.w;
    outside[6] += h.w <= 0.0;
  }
  return std::any_of(std::begin(outside), std::end(outside), [](int c) { return c == 8; });
}

bool sweptBoxReachesBox(const Bounds& casterBox, const glm::dvec3& wsLightDirection,
  const Bounds& receiverBox, double minimumDistance)
{
  const double length = glm::length(wsLightDirection);
  if (casterBox.isEmpty() || receiverBox.isEmpty() || !casterBox.isFinite() ||
    !receiverBox.isFinite() || !std::isfinite(length) || !(length > 0.0) ||
    !std::isfinite(minimumDistance))
  {
    return true;
  }
  // The caster box moved by t d (unit d, t >= minimumDistance) meets the receiver box when
  // on every axis lo_c + t d <= hi_r and hi_c + t d >= lo_r: an interval of t per axis.
  const glm::dvec3 d = wsLightDirection / length;
  double tLo = std::max(minimumDistance, 0.0), tHi = kInf;
  for (int i = 0; i < 3; ++i)
  {
    const double toHi = receiverBox.wsMax[i] - casterBox.wsMin[i]; // t d_i <= toHi
    const double toLo = receiverBox.wsMin[i] - casterBox.wsMax[i]; // t d_i >= toLo
    if (d[i] == 0.0)
    {
      if (toHi < 0.0 || toLo > 0.0)
      {
        return false;
      }
      continue;
    }
    const double a = (d[i] > 0.0 ? toLo : toHi) / d[i];
    const double b = (d[i] > 0.0 ? toHi : toLo) / d[i];
    tLo = std::max(tLo, a);
    tHi = std::min(tHi, b);
  }
  return tLo <= tHi;
}

const char* toString(Status status)
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

} // namespace csm
