// SPDX-License-Identifier: BSD-3-Clause
// The scene-fitted map of a directional light (see csmSceneFit.h).
#include "csmSceneFit.h"

#include "csmConvexBody.h"
#include "csmCulling.h"
#include "csmGeometry.h"
#include "csmSetup.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>

namespace csm
{
namespace
{
/// Light space fixed in the world: the light's direction of travel (y), a perpendicular of it
/// alone (x) and z = x cross y, about the scene box's centre.
struct WorldLightSpace
{
  LightBasis ls;
  glm::dvec3 wsOrigin;

  WorldLightSpace(const glm::dvec3& wsLightDirection, const Bounds& sceneBounds)
  {
    this->ls.y = glm::normalize(wsLightDirection);
    this->ls.x = perpendicular(this->ls.y);
    this->ls.z = glm::cross(this->ls.x, this->ls.y);
    this->wsOrigin = 0.5 * (sceneBounds.wsMin + sceneBounds.wsMax);
  }

  /// A box's extent in light space (x, y, z), about the origin.
  void extent(const Bounds& box, glm::dvec3& lo, glm::dvec3& hi) const
  {
    lo = glm::dvec3(kInf);
    hi = glm::dvec3(-kInf);
    for (int i = 0; i < 8; ++i)
    {
      const glm::dvec3 q = this->ls.coordinates(boxCorner(box, i) - this->wsOrigin);
      lo = glm::min(lo, q);
      hi = glm::max(hi, q);
    }
  }
};

/// Across the light (ls x and z): the union of the caster footprints over the receivers each
/// can reach (lo > hi where there are none). partsGiven: the receivers are the casters' own
/// props' boxes (CasterLoad::receiver indexes them). False where a caster is screen-sized.
bool footprintAcross(const WorldLightSpace& space, const std::vector<CasterLoad>& casters,
  const std::vector<Bounds>& receivers, bool partsGiven, glm::dvec2& lo, glm::dvec2& hi)
{
  std::vector<glm::dvec3> receiverLo(receivers.size()), receiverHi(receivers.size());
  for (size_t r = 0; r < receivers.size(); ++r)
  {
    space.extent(receivers[r], receiverLo[r], receiverHi[r]);
  }
  lo = glm::dvec2(kInf);
  hi = glm::dvec2(-kInf);
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
    space.extent(caster.wsBox, cLo, cHi);
    for (size_t r = 0; r < receivers.size(); ++r)
    {
      const bool own = partsGiven && static_cast<int>(r) == caster.receiver;
      if ((own && !caster.shadowsItself) || receivers[r].isEmpty() ||
        !sweptBoxReachesBox(caster.wsBox, space.ls.y, receivers[r], 0.0))
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
  return true;
}

/// Along the light (ls y): the extent of the boxes' parts inside the prism lo..hi across it, each
/// box clipped to the prism (a wide ground under a structure adds only its patch under the
/// structure); lo > hi where no box reaches inside.
void extentAlongInside(const WorldLightSpace& space, const std::vector<Bounds>& boxes,
  const glm::dvec2& lo, const glm::dvec2& hi, double& yLo, double& yHi)
{
  yLo = kInf;
  yHi = -kInf;
  const std::array<Plane, 4> lsPrism{ { { glm::dvec3(1.0, 0.0, 0.0), -lo.x },
    { glm::dvec3(-1.0, 0.0, 0.0), hi.x }, { glm::dvec3(0.0, 0.0, 1.0), -lo.y },
    { glm::dvec3(0.0, 0.0, -1.0), hi.y } } };
  for (const Bounds& box : boxes)
  {
    if (!box.isFinite() || box.isEmpty())
    {
      continue;
    }
    glm::dvec3 bLo, bHi;
    space.extent(box, bLo, bHi);
    if (bLo.x > hi.x || bHi.x < lo.x || bLo.z > hi.y || bHi.z < lo.y)
    {
      continue; // wholly outside across the light
    }
    if (bLo.x >= lo.x && bHi.x <= hi.x && bLo.z >= lo.y && bHi.z <= hi.y)
    {
      yLo = std::min(yLo, bLo.y); // wholly inside
      yHi = std::max(yHi, bHi.y);
      continue;
    }
    // The box in light space (its corners in hexahedron order), clipped to the prism.
    static const int kOrder[8] = { 0, 1, 3, 2, 4, 5, 7, 6 };
    std::array<glm::dvec3, 8> corners;
    for (int i = 0; i < 8; ++i)
    {
      corners[i] = space.ls.coordinates(boxCorner(box, kOrder[i]) - space.wsOrigin);
    }
    ConvexBody body = ConvexBody::hexahedron(corners);
    const double epsilon = 1e-9 * std::max(glm::length(bHi - bLo), glm::length(hi - lo));
    for (const Plane& plane : lsPrism)
    {
      body.clip(plane, epsilon);
    }
    for (const glm::dvec3& p : body.vertices(epsilon))
    {
      yLo = std::min(yLo, p.y);
      yHi = std::max(yHi, p.y);
    }
  }
}
} // namespace

bool sceneFit(const glm::dvec3& wsLightDirection, const Bounds& sceneBounds,
  const std::vector<CasterLoad>& casters, const std::vector<Bounds>* receiverParts, SceneFit& fit)
{
  if (!lightDirectionError(wsLightDirection).empty() || !sceneBounds.isFinite() ||
    sceneBounds.isEmpty())
  {
    return false;
  }
  // Axes fixed in the world: the light's direction of travel and a perpendicular of it alone.
  const WorldLightSpace space(wsLightDirection, sceneBounds);
  const LightBasis& ls = space.ls;
  const glm::dvec3& wsOrigin = space.wsOrigin;
  const bool partsGiven = receiverParts && !receiverParts->empty();
  const std::vector<Bounds> sceneOnly{ sceneBounds };
  glm::dvec2 lo, hi;
  if (!footprintAcross(space, casters, partsGiven ? *receiverParts : sceneOnly, partsGiven, lo, hi))
  {
    return false;
  }
  if (!(lo.x <= hi.x && lo.y <= hi.y))
  {
    return false; // nothing can be in shadow
  }
  // Along the light: what lies inside that extent across it (the receivers' and the casters'
  // boxes clipped to it), not the whole scene's depth, of which the constant bias is a share
  // (a prop far off, or a ground far wider than the structure on it, would spread the map's
  // depths over distances no shadow spans). A flat extent gets a minimum size, as a cascade's.
  std::vector<Bounds> inside = partsGiven ? *receiverParts : sceneOnly;
  for (const CasterLoad& caster : casters)
  {
    inside.push_back(caster.wsBox);
  }
  double yLo = 0.0, yHi = 0.0;
  extentAlongInside(space, inside, lo, hi, yLo, yHi);
  glm::dvec3 sceneLo, sceneHi;
  space.extent(sceneBounds, sceneLo, sceneHi);
  glm::dvec3 lsLo(lo.x, yLo <= yHi ? yLo : sceneLo.y, lo.y),
    lsHi(hi.x, yLo <= yHi ? yHi : sceneHi.y, hi.y);
  const double minSize = inflation(glm::length(sceneBounds.wsMax - sceneBounds.wsMin), 0.0);
  for (int axis = 0; axis < 3; ++axis)
  {
    const double grow = 0.5 * std::max(minSize - (lsHi[axis] - lsLo[axis]), 0.0) + minSize;
    lsLo[axis] -= grow;
    lsHi[axis] += grow;
  }
  std::vector<glm::dvec3> lsPoints{ lsLo, lsHi };
  keepOrthographicDepthRange(lsPoints, false); // (no eye: about the scene's middle)
  const glm::dmat4 wsToLs = frameMatrix(ls.x, ls.y, ls.z, wsOrigin);
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

double sceneFittedBiasShare(double texels)
{
  return texels > kSceneFittedBiasTexels ? kSceneFittedBiasTexels / texels : 1.0;
}

} // namespace csm
