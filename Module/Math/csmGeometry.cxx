// SPDX-License-Identifier: BSD-3-Clause
// Geometry the shadow setups share, and the one check of their input (see csmGeometry.h).
#include "csmGeometry.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace csm
{
namespace
{
constexpr double kMinDistance = 1e-50; // camera near and far distances a double handles
constexpr double kMaxDistance = 1e50;
constexpr double kMinDepthGap = 1e-9; // far must exceed near by this fraction of near
} // namespace

std::string cameraError(const Camera& camera)
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
  if (!(camera.vsFar > camera.vsNear * (1.0 + kMinDepthGap)))
  {
    if (!(camera.vsFar > camera.vsNear))
    {
      return "camera far distance must be greater than near";
    }
    char text[96];
    std::snprintf(text, sizeof(text),
      "camera far distance must exceed near by more than %g of near", kMinDepthGap);
    return text;
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
  return {};
}

std::string lightDirectionError(const glm::dvec3& wsLightDirection)
{
  return finite(wsLightDirection) && glm::length(wsLightDirection) > 0.0
    ? std::string()
    : "light direction must be finite and non-zero";
}

bool acceptSetupInput(ShadowSetup& setup, const Camera& camera, const Bounds* sceneBounds,
  const std::string& lightError, const std::vector<Bounds>* receiverParts)
{
  setup.message = cameraError(camera);
  if (setup.message.empty() && sceneBounds && !sceneBounds->isFinite())
  {
    setup.message = "scene bounds must be finite";
  }
  if (setup.message.empty())
  {
    setup.message = lightError;
  }
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
    return false;
  }
  if (sceneBounds && sceneBounds->isEmpty())
  {
    setup.status = Status::NothingToShadow;
    setup.message = "the scene is empty";
    return false;
  }
  return true;
}

bool finite(const glm::dvec3& v)
{
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

glm::dvec3 perpendicular(const glm::dvec3& n)
{
  const glm::dvec3 helper = std::abs(n.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  return glm::normalize(glm::cross(n, helper));
}

glm::dvec3 perpendicularPart(const glm::dvec3& u, const glm::dvec3& n, const glm::dvec3& fallback)
{
  const glm::dvec3 p = u - glm::dot(u, n) * n;
  const double length = glm::length(p);
  return length > 1e-9 ? p / length : fallback;
}

double angleBetween(const glm::dvec3& a, const glm::dvec3& b)
{
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

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

glm::dvec3 LightBasis::coordinates(const glm::dvec3& p) const
{
  return glm::dvec3(glm::dot(p, this->x), glm::dot(p, this->y), glm::dot(p, this->z));
}

LightBasis lightBasis(const CameraFrame& frame, const glm::dvec3& wsLightDirection)
{
  LightBasis ls;
  ls.y = glm::normalize(wsLightDirection);
  ls.z =
    perpendicularPart(frame.view, ls.y, perpendicularPart(frame.up, ls.y, perpendicular(ls.y)));
  ls.x = glm::cross(ls.y, ls.z);
  return ls;
}

glm::dmat4 frameMatrix(
  const glm::dvec3& x, const glm::dvec3& y, const glm::dvec3& z, const glm::dvec3& wsOrigin)
{
  return fromRows({ x, -glm::dot(x, wsOrigin) }, { y, -glm::dot(y, wsOrigin) },
    { z, -glm::dot(z, wsOrigin) }, { 0, 0, 0, 1 });
}

glm::dvec2 halfSize(const Camera& camera, const CameraFrame& frame, double vsDepth)
{
  if (camera.parallel)
  {
    return { camera.parallelScale * camera.aspect, camera.parallelScale };
  }
  return { vsDepth * frame.tanX, vsDepth * frame.tanY };
}

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

double clipEpsilon(const Camera& camera, const CameraFrame& frame, double vsDepth)
{
  const glm::dvec2 half = halfSize(camera, frame, vsDepth);
  return 1e-12 * (vsDepth + half.x + half.y);
}

double exitTowardLight(
  const glm::dvec3& p, const glm::dvec3& d, const glm::dvec3& lo, const glm::dvec3& hi)
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

glm::dmat4 fromRows(
  const glm::dvec4& r0, const glm::dvec4& r1, const glm::dvec4& r2, const glm::dvec4& r3)
{
  glm::dmat4 m;
  for (int c = 0; c < 4; ++c)
  {
    m[c] = glm::dvec4(r0[c], r1[c], r2[c], r3[c]);
  }
  return m;
}

glm::dvec3 boxCorner(const Bounds& box, int i)
{
  return { (i & 1) ? box.wsMax.x : box.wsMin.x, (i & 2) ? box.wsMax.y : box.wsMin.y,
    (i & 4) ? box.wsMax.z : box.wsMin.z };
}

double inflation(double size, double vsNear)
{
  return 1e-6 * std::max(size, vsNear);
}

std::array<Plane, 6> cameraCentredBoxPlanes(const Bounds& box, const Camera& camera)
{
  const double grow = inflation(glm::length(box.wsMax - box.wsMin), camera.vsNear);
  return boxPlanes(box.wsMin - camera.wsPosition - grow, box.wsMax - camera.wsPosition + grow);
}

} // namespace csm
