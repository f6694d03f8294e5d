// SPDX-License-Identifier: BSD-3-Clause
#include "csmVisibleDepth.h"

#include "csmGeometry.h"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>

namespace csm
{

bool DepthRange::isEmpty() const
{
  return !(this->vsNear <= this->vsFar);
}

bool WindowDepthRange::isEmpty() const
{
  return !(this->min <= this->max);
}

WindowDepthRange windowDepthRange(const float* windowDepths, std::size_t count)
{
  WindowDepthRange range;
  if (!windowDepths)
  {
    return range;
  }
  float lo = 1.0f;
  float hi = 0.0f;
  for (std::size_t i = 0; i < count; ++i)
  {
    const float d = windowDepths[i];
    if (d < 1.0f && d >= 0.0f) // also false for NaN
    {
      lo = std::min(lo, d);
      hi = std::max(hi, d);
    }
  }
  if (lo <= hi)
  {
    range.min = lo;
    range.max = hi;
  }
  return range;
}

double viewDepthFromWindowDepth(double windowDepth, double vsNear, double vsFar, bool parallel)
{
  const double w = std::clamp(windowDepth, 0.0, 1.0);
  if (parallel)
  {
    return vsNear + w * (vsFar - vsNear);
  }
  // NDC z = (f + n) / (f - n) - 2 f n / ((f - n) d), window = (NDC z + 1) / 2.
  const double ndc = 2.0 * w - 1.0;
  return 2.0 * vsFar * vsNear / ((vsFar + vsNear) - ndc * (vsFar - vsNear));
}

double windowDepthFromViewDepth(double vsDepth, double vsNear, double vsFar, bool parallel)
{
  if (parallel)
  {
    return (vsDepth - vsNear) / (vsFar - vsNear);
  }
  const double ndc =
    (vsFar + vsNear) / (vsFar - vsNear) - 2.0 * vsFar * vsNear / ((vsFar - vsNear) * vsDepth);
  return 0.5 * (ndc + 1.0);
}

DepthRange viewDepthRange(const WindowDepthRange& window, const Camera& camera)
{
  DepthRange range;
  if (window.isEmpty() || !cameraError(camera).empty())
  {
    return range;
  }
  range.vsNear = viewDepthFromWindowDepth(window.min, camera.vsNear, camera.vsFar, camera.parallel);
  range.vsFar = viewDepthFromWindowDepth(window.max, camera.vsNear, camera.vsFar, camera.parallel);
  return range;
}

namespace
{
/// How far from the eye a point seen at view depth d can be: d over the cosine of the half
/// diagonal field of view, or (parallel) d plus the half diagonal of the view.
double reach(const Camera& camera, double d)
{
  if (camera.parallel)
  {
    return d + camera.parallelScale * std::sqrt(1.0 + camera.aspect * camera.aspect);
  }
  const double tanHalfY = std::tan(glm::radians(0.5 * camera.fovyDeg));
  const double tanHalfX = tanHalfY * camera.aspect;
  return d * std::sqrt(1.0 + tanHalfX * tanHalfX + tanHalfY * tanHalfY);
}
}

DepthRange carryDepthRange(
  const Camera& measuredBy, const DepthRange& measured, const Camera& camera)
{
  DepthRange carried;
  if (measured.isEmpty() || !std::isfinite(measured.vsNear) || !std::isfinite(measured.vsFar) ||
    !cameraError(measuredBy).empty() || !cameraError(camera).empty() ||
    camera.parallel != measuredBy.parallel)
  {
    return carried;
  }
  const glm::dvec3 before = glm::normalize(measuredBy.wsDirection);
  const glm::dvec3 now = glm::normalize(camera.wsDirection);
  const double turn = glm::length(now - before); // 2 sin(angle / 2)
  const double maximumTurn = 2.0 * std::sin(glm::radians(0.5 * kVisibleDepthMaximumTurnDeg));
  if (!(turn <= maximumTurn))
  {
    return carried;
  }
  const double moved = glm::length(camera.wsPosition - measuredBy.wsPosition);
  const double nearest = measured.vsNear - reach(measuredBy, measured.vsNear) * turn - moved;
  const double farthest = measured.vsFar + reach(measuredBy, measured.vsFar) * turn + moved;
  carried.vsNear = nearest * (1.0 - kVisibleDepthMargin);
  carried.vsFar = farthest * (1.0 + kVisibleDepthMargin);
  if (!std::isfinite(carried.vsNear) || !std::isfinite(carried.vsFar))
  {
    return DepthRange();
  }
  return carried;
}

bool depthRangeHolds(
  const DepthRange& covered, const WindowDepthRange& measured, const Camera& camera)
{
  if (measured.isEmpty())
  {
    return true;
  }
  if (covered.isEmpty() || !cameraError(camera).empty())
  {
    return false;
  }
  const double lo =
    windowDepthFromViewDepth(covered.vsNear, camera.vsNear, camera.vsFar, camera.parallel);
  const double hi =
    windowDepthFromViewDepth(covered.vsFar, camera.vsNear, camera.vsFar, camera.parallel);
  return measured.min >= lo - kWindowDepthTolerance && measured.max <= hi + kWindowDepthTolerance;
}

} // namespace csm
