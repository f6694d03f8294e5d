// SPDX-License-Identifier: BSD-3-Clause
// Perspective aliasing (Lloyd et al. 2006, Eq. 1-4, 9-12) and the resolution a target error
// needs (see csmAliasing.h).
#include "csmAliasing.h"

#include "csmGeometry.h"

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>

namespace csm
{

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
  auto gradient = [&](int row) {                 // d(ndc_row)/d(ws point)
    return (glm::dvec3(t[row]) * h.w - glm::dvec3(t[3]) * h[row]) / (h.w * h.w);
  };
  // Lloyd et al. 2006, Eq. 3-4 with res = 1: s, t in [0, 1] are half the NDC. The map axis
  // along ls x is the row that follows it: s, or t for a map turned a quarter (orientToTile),
  // also when the map was planned for an earlier camera (whose ls x differs a little) or its
  // axes are not ls x and z at all (VTK's map: the better aligned row).
  const bool turned =
    std::abs(glm::dot(glm::dvec3(t[1]), wsMapX)) > std::abs(glm::dot(glm::dvec3(t[0]), wsMapX));
  const double dsdx = 0.5 * std::abs(glm::dot(gradient(turned ? 1 : 0), wsMapX));
  const double dtdz = 0.5 * std::abs(glm::dot(gradient(turned ? 0 : 1), wsMapZ));
  Aliasing m;
  m.mx = (dsdx > 0.0 ? 1.0 / dsdx : kInf) / wi;
  m.mz = (dtdz > 0.0 ? 1.0 / dtdz : kInf) / wi;
  return m;
}

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

int resolutionForError(
  double maxAliasing, double imageHeight, double targetError, int step, int ceiling)
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

MapSize resolutionForError(
  const Cascade& cascade, double imageHeight, double targetError, int step, const MapSize& ceiling)
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

bool errorTargetOutOfReach(
  const Cascade& cascade, double imageHeight, double targetError, const MapSize& ceiling)
{
  const double m = std::max(cascade.Mx, cascade.Mz);
  const int texels = std::min(ceiling.width, ceiling.height);
  if (cascade.sceneFitted || !(m > 0.0) || !std::isfinite(m) || !(imageHeight > 0.0) ||
    !std::isfinite(imageHeight) || !(targetError > 0.0) || !std::isfinite(targetError) ||
    texels <= 0)
  {
    return false;
  }
  return m * imageHeight / texels > targetError;
}

} // namespace csm
