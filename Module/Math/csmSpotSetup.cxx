// SPDX-License-Identifier: BSD-3-Clause
// One perspective map of a spot light fitted to the lit part of the visible scene (see
// csmSpotSetup.h).
#include "csmSpotSetup.h"

#include "csmConvexBody.h"
#include "csmGeometry.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

namespace csm
{
namespace
{
/// What computeSpotSetup checks of the light beyond acceptSetupInput; empty when it can be used.
std::string spotLightError(
  const glm::dvec3& wsLightPosition, const glm::dvec3& wsLightAxis, double coneAngleDeg)
{
  if (!finite(wsLightPosition) || !finite(wsLightAxis) || !(glm::length(wsLightAxis) > 0.0))
  {
    return "spot light position and direction must be finite and non-zero";
  }
  if (!(coneAngleDeg > 0.0 && coneAngleDeg < 90.0))
  {
    return "spot light cone angle must be in (0, 90) degrees";
  }
  return {};
}

/// The light's frame: x along u, y along v, z (w) the distance along the axis; the apex
/// camera-centred; the tangent of the cone's half-angle.
struct SpotFrame
{
  glm::dvec3 u, v, w;
  glm::dvec3 cwsApex;
  double tanCone = 0.0;

  SpotFrame(const Camera& camera, const glm::dvec3& wsLightPosition, const glm::dvec3& wsLightAxis,
    double coneAngleDeg)
  {
    this->w = glm::normalize(wsLightAxis);
    this->u = perpendicular(this->w);
    this->v = glm::cross(this->w, this->u);
    this->cwsApex = wsLightPosition - camera.wsPosition;
    this->tanCone = std::tan(coneAngleDeg * kDegree);
  }
};

/// What the view needs: the visible scene inside the cone's bounding pyramid.
ConvexBody litVisibleBody(const Camera& camera, const CameraFrame& frame, const Bounds* sceneBounds,
  const SpotFrame& spot, double epsilon)
{
  ConvexBody body =
    ConvexBody::hexahedron(partitionCorners(camera, frame, camera.vsNear, camera.vsFar));
  if (sceneBounds)
  {
    for (const Plane& plane : cameraCentredBoxPlanes(*sceneBounds, camera))
    {
      body.clip(plane, epsilon);
    }
  }
  const double t = spot.tanCone;
  const glm::dvec3 sideNormals[4] = { t * spot.w - spot.u, t * spot.w + spot.u, t * spot.w - spot.v,
    t * spot.w + spot.v };
  for (const glm::dvec3& normal : sideNormals)
  {
    body.clip({ normal, -glm::dot(normal, spot.cwsApex) }, epsilon);
  }
  return body;
}

/// The map's near and far distances along the axis: the far one beyond the body's farthest
/// point; the near one at the body (depthClamp) or at the nearest corner of the scene box
/// (the casters), and at least 1e-3 of the far one. The margins are a share of that range, not
/// of the distance, so that a light far from a small scene spreads the scene over the map's
/// depths and a constant bias (a share of those depths) stays a small share of the scene's
/// depth; but at least 1e-4 of the distance: a perspective map's depth, computed in single
/// precision, is good to about 2e-7 of the distance over the range, and 1e-4 keeps that under
/// a default ConstantBias.
void spotDepthRange(const Camera& camera, const glm::dvec3& wsLightPosition, const SpotFrame& spot,
  const Bounds* sceneBounds, bool depthClamp, double zMin, double zMax, double& zNear, double& zFar)
{
  zFar = std::max(zMax, 1e-9 * (camera.vsFar + glm::length(spot.cwsApex)));
  double nearest = 0.0; // (none: 1e-3 of the far one)
  if (depthClamp)
  {
    nearest = zMin;
  }
  else if (sceneBounds)
  {
    nearest = kInf; // the nearest corner of the scene box along the axis
    for (int i = 0; i < 8; ++i)
    {
      nearest = std::min(nearest, glm::dot(boxCorner(*sceneBounds, i) - wsLightPosition, spot.w));
    }
  }
  const double margin = std::max(0.01 * (zFar - std::max(nearest, 0.0)), 1e-4 * zFar);
  zFar += margin;
  zNear = std::max(1e-3 * zFar, nearest - margin);
}

/// The window of the vertices at unit distance along the axis (x / z, y / z), within the cone
/// and at least a sliver wide on each axis.
void spotWindow(const std::vector<glm::dvec3>& vertices, const SpotFrame& spot, double zNear,
  glm::dvec2& lo, glm::dvec2& hi)
{
  lo = glm::dvec2(kInf);
  hi = glm::dvec2(-kInf);
  for (const glm::dvec3& p : vertices)
  {
    const glm::dvec3 q = p - spot.cwsApex;
    const double z = std::max(glm::dot(q, spot.w), zNear);
    const glm::dvec2 xy(glm::dot(q, spot.u) / z, glm::dot(q, spot.v) / z);
    lo = glm::min(lo, xy);
    hi = glm::max(hi, xy);
  }
  lo = glm::max(lo, glm::dvec2(-spot.tanCone));
  hi = glm::min(hi, glm::dvec2(spot.tanCone));
  for (int axis = 0; axis < 2; ++axis)
  {
    const double minWidth = 1e-6 * spot.tanCone;
    if (!(hi[axis] - lo[axis] > minWidth))
    {
      const double middle = 0.5 * (lo[axis] + hi[axis]);
      lo[axis] = middle - minWidth;
      hi[axis] = middle + minWidth;
    }
  }
}

/// Off-centre perspective (glFrustum at unit distance) looking along the axis.
glm::dmat4 spotProjection(const glm::dvec2& lo, const glm::dvec2& hi, double zNear, double zFar)
{
  const double a = (zFar + zNear) / (zFar - zNear);
  const double b = -2.0 * zFar * zNear / (zFar - zNear);
  return fromRows({ 2.0 / (hi.x - lo.x), 0, -(hi.x + lo.x) / (hi.x - lo.x), 0 },
    { 0, 2.0 / (hi.y - lo.y), -(hi.y + lo.y) / (hi.y - lo.y), 0 }, { 0, 0, a, b }, { 0, 0, 1, 0 });
}
} // namespace

ShadowSetup computeSpotSetup(const Camera& camera, const glm::dvec3& wsLightPosition,
  const glm::dvec3& wsLightAxis, double coneAngleDeg, const Bounds* sceneBounds, bool depthClamp)
{
  ShadowSetup setup;
  if (!acceptSetupInput(
        setup, camera, sceneBounds, spotLightError(wsLightPosition, wsLightAxis, coneAngleDeg)))
  {
    return setup;
  }
  const CameraFrame frame = cameraFrame(camera);
  const double epsilon = clipEpsilon(camera, frame, camera.vsFar);
  const SpotFrame spot(camera, wsLightPosition, wsLightAxis, coneAngleDeg);
  const ConvexBody body = litVisibleBody(camera, frame, sceneBounds, spot, epsilon);
  if (body.empty())
  {
    setup.status = Status::NothingToShadow;
    setup.message = "the spot light reaches none of the visible scene";
    return setup;
  }

  // The body's extent along the axis and the view direction.
  double zMin = kInf, zMax = -kInf, vsMin = kInf, vsMax = -kInf;
  const std::vector<glm::dvec3> vertices = body.vertices(epsilon);
  Cascade cascade;
  for (const glm::dvec3& p : vertices)
  {
    const double z = glm::dot(p - spot.cwsApex, spot.w);
    zMin = std::min(zMin, z);
    zMax = std::max(zMax, z);
    const double depth = glm::dot(p, frame.view);
    vsMin = std::min(vsMin, depth);
    vsMax = std::max(vsMax, depth);
    cascade.wsBody.push_back(p + camera.wsPosition);
  }
  double zNear = 0.0, zFar = 0.0;
  spotDepthRange(camera, wsLightPosition, spot, sceneBounds, depthClamp, zMin, zMax, zNear, zFar);
  glm::dvec2 lo, hi;
  spotWindow(vertices, spot, zNear, lo, hi);
  cascade.wsToClip =
    spotProjection(lo, hi, zNear, zFar) * frameMatrix(spot.u, spot.v, spot.w, wsLightPosition);
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
  setup.gammaDeg = angleBetween(frame.view, spot.w) / kDegree;
  setup.storageOptimal = 0.0;
  setup.cascades.push_back(std::move(cascade));
  setup.status = Status::Ok;
  return setup;
}

double perspectiveBiasFactor(const glm::dmat4& wsToClip)
{
  // Rows z and w (glm is column-major): clip z = a w + b on a perspective map, its z row a times
  // its w row plus b in the last column.
  const glm::dvec4 zRow(wsToClip[0][2], wsToClip[1][2], wsToClip[2][2], wsToClip[3][2]);
  const glm::dvec4 wRow(wsToClip[0][3], wsToClip[1][3], wsToClip[2][3], wsToClip[3][3]);
  const glm::dvec3 axis(wRow);
  const double length2 = glm::dot(axis, axis);
  if (!(length2 > 0.0) || !std::isfinite(length2))
  {
    return 0.0; // orthographic (w = 1)
  }
  const double a = glm::dot(glm::dvec3(zRow), axis) / length2;
  const double b = zRow.w - a * wRow.w;
  const double k = b * b / (a * a - 1.0); // f n, from a = (f + n) / (f - n), b = -2 f n / (f - n)
  return std::isfinite(k) && k > 0.0 ? k : 0.0;
}

} // namespace csm
