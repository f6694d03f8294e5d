// SPDX-License-Identifier: BSD-3-Clause
// Box culling against a light clip volume and swept-box reach (see csmCulling.h).
#include "csmCulling.h"

#include "csmGeometry.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <iterator>

namespace csm
{

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

bool eyeSeesOnlyOutsideOf(const Camera& camera, const Bounds& box)
{
  constexpr double kPi = 3.14159265358979323846;
  const double tanHalfY = std::tan(0.5 * camera.fovyDeg * kPi / 180.0);
  const double tanHalfDiagonal = tanHalfY * std::sqrt(1.0 + camera.aspect * camera.aspect);
  const double reach = camera.vsNear * std::sqrt(1.0 + tanHalfDiagonal * tanHalfDiagonal);
  if (camera.parallel || box.isEmpty() || !box.isFinite() || !std::isfinite(reach) ||
    !(camera.vsNear > 0.0) || !(camera.fovyDeg > 0.0 && camera.fovyDeg < 180.0) ||
    !std::isfinite(camera.wsPosition.x) || !std::isfinite(camera.wsPosition.y) ||
    !std::isfinite(camera.wsPosition.z))
  {
    return false;
  }
  const glm::dvec3 nearest = glm::clamp(camera.wsPosition, box.wsMin, box.wsMax);
  return glm::length(camera.wsPosition - nearest) > reach;
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

} // namespace csm
