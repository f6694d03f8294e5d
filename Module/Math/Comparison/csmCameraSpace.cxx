// SPDX-License-Identifier: BSD-3-Clause
#include "csmCameraSpace.h"

#include "csmGeometry.h"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <glm/vec2.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace csm
{
namespace
{
/// Below this sine of the angle between the light and the view axis, the light's direction in
/// the image is undefined: the dueling frustum case (or its mirror, light straight from behind).
constexpr double kAlongView = 1e-3;
/// Below this cosine between the light and P's normal, the projection onto P runs away.
constexpr double kParallelToPlane = 1e-6;
/// Share of each ray's w that the depth may use (room for rounding at the ends).
constexpr double kDepthRoom = 0.99;

/// Camera-centred homogeneous point -> its projection onto the plane dot(normal, q) + offset = 0
/// along the direction L (affine: w = 1).
glm::dmat4 projectAlong(const glm::dvec3& normal, double offset, const glm::dvec3& L)
{
  const double across = glm::dot(normal, L);
  glm::dmat4 toPlane(1.0);
  for (int column = 0; column < 3; ++column)
  {
    for (int row = 0; row < 3; ++row)
    {
      toPlane[column][row] -= L[row] * normal[column] / across;
    }
  }
  toPlane[3] = glm::dvec4(-L * (offset / across), 1.0);
  return toPlane;
}

/// The same from the point l (camera-centred): the central projection, homogeneous. For q the
/// plane point is l + (q - l) t with t = -(dot(normal, l) + offset) / dot(normal, q - l); times
/// W = dot(normal, q - l) that is X = l dot(normal, q) - (dot(normal, l) + offset) q + offset l.
/// Along a ray from l, X and W grow with the distance from l (they are 0 at l).
glm::dmat4 projectFrom(const glm::dvec3& normal, double offset, const glm::dvec3& l)
{
  const double nl = glm::dot(normal, l);
  glm::dmat4 toPlane(0.0);
  for (int column = 0; column < 3; ++column)
  {
    for (int row = 0; row < 3; ++row)
    {
      toPlane[column][row] = l[row] * normal[column] - (row == column ? nl + offset : 0.0);
    }
    toPlane[column][3] = normal[column];
  }
  toPlane[3] = glm::dvec4(offset * l, -nl);
  return toPlane;
}

/// A plane point (homogeneous) captured by a camera at the eye pushed back by pushBack along the
/// view, looking along view with the given right and up axes: rows x, y, (0), w.
glm::dmat4 capture(
  const glm::dvec3& right, const glm::dvec3& up, const glm::dvec3& view, double pushBack)
{
  glm::dmat4 c(0.0);
  for (int column = 0; column < 3; ++column)
  {
    c[column] = glm::dvec4(right[column], up[column], 0.0, view[column]);
  }
  c[3] = glm::dvec4(0.0, 0.0, 0.0, pushBack);
  return c;
}

/// Camera-centred point -> its projection along L onto the plane, captured from the eye.
glm::dmat4 projectAndCapture(const glm::dvec3& normal, double offset, const glm::dvec3& L,
  const glm::dvec3& right, const glm::dvec3& up, const glm::dvec3& view)
{
  return capture(right, up, view, 0.0) * projectAlong(normal, offset, L);
}

/// The depth row of a directional light's map: the light depth dot(q, L) over [depth.x,
/// depth.y] in kDepthRoom of wMin (w is constant along a ray: depth / w keeps the light's order).
glm::dvec4 lightDepthRow(const glm::dvec3& L, const glm::dvec2& depth, double wMin, double far)
{
  const double a = 2.0 * kDepthRoom * wMin / std::max(depth.y - depth.x, 1e-12 * far);
  return glm::dvec4(a * L, -0.5 * a * (depth.x + depth.y));
}

/// The world -> clip matrix: s, t of `projected` fitted to [sMin, sMax] x [tMin, tMax] (after
/// the division by w), the depth row given (camera-centred), for a camera at wsEye.
glm::dmat4 fitClip(const glm::dmat4& projected, const glm::dvec4& depthRow, const glm::dvec2& s,
  const glm::dvec2& t, const glm::dvec3& wsEye)
{
  const double sScale = 2.0 / std::max(s.y - s.x, 1e-12);
  const double tScale = 2.0 / std::max(t.y - t.x, 1e-12);
  // Rows: s = sScale (x - sMin w) - w, t likewise, depth, w.
  glm::dmat4 clip(0.0);
  for (int column = 0; column < 4; ++column)
  {
    const glm::dvec4 c = projected[column];
    clip[column].x = sScale * (c.x - s.x * c.w) - c.w;
    clip[column].y = tScale * (c.y - t.x * c.w) - c.w;
    clip[column].z = depthRow[column];
    clip[column].w = c.w;
  }
  glm::dmat4 fromWorld(1.0); // q = p - eye
  fromWorld[3] = glm::dvec4(-wsEye, 1.0);
  return clip * fromWorld;
}

/// The general case's frame for light travelling along L (for a spot light: from the light
/// toward the view): the camera rolled so that the light comes from above, the original
/// frustum's corners (camera-centred), and the plane P through the rolled frustum's lower near
/// and upper far edges (upper near and lower far for a light from in front).
struct GeneralFrame
{
  std::string message; ///< empty when the frame exists
  glm::dvec3 view{ 0.0 }, up{ 0.0 }, right{ 0.0 };
  glm::dvec3 normal{ 0.0 }; ///< P: dot(normal, q) + offset = 0, camera-centred
  double offset = 0.0;
  bool lightFromFront = false;
  std::vector<glm::dvec3> corners;
};

GeneralFrame generalFrame(const Camera& camera, const glm::dvec3& L)
{
  GeneralFrame g;
  g.view = glm::normalize(camera.wsDirection);
  // The roll: the light travels down the rolled image (it comes from above).
  const glm::dvec3 inImage = L - glm::dot(L, g.view) * g.view;
  if (glm::length(inImage) < kAlongView)
  {
    g.message = "light along the view: the dueling frustum case needs four planes";
    return g;
  }
  g.up = -glm::normalize(inImage);
  g.right = glm::cross(g.view, g.up);
  g.lightFromFront = glm::dot(L, g.view) < 0.0;
  // The original frustum's corners, and the rolled camera's field of view that holds them.
  glm::dvec3 oldUp = camera.wsViewUp - glm::dot(camera.wsViewUp, g.view) * g.view;
  if (!(glm::length(oldUp) > 1e-9))
  {
    oldUp = g.up;
  }
  oldUp = glm::normalize(oldUp);
  const glm::dvec3 oldRight = glm::cross(g.view, oldUp);
  const double tanY = std::tan(glm::radians(0.5 * camera.fovyDeg));
  const double tanX = tanY * camera.aspect;
  double rolledTanY = 0.0;
  for (double d : { camera.vsNear, camera.vsFar })
  {
    for (double sx : { -1.0, 1.0 })
    {
      for (double sy : { -1.0, 1.0 })
      {
        const glm::dvec3 unit = g.view + oldRight * (sx * tanX) + oldUp * (sy * tanY);
        rolledTanY = std::max(rolledTanY, std::abs(glm::dot(unit, g.up)));
        g.corners.push_back(unit * d);
      }
    }
  }
  const double sign = g.lightFromFront ? -1.0 : 1.0;
  const glm::dvec3 nearEdge = g.view * camera.vsNear - g.up * (sign * camera.vsNear * rolledTanY);
  const glm::dvec3 farEdge = g.view * camera.vsFar + g.up * (sign * camera.vsFar * rolledTanY);
  g.normal = glm::normalize(glm::cross(g.right, farEdge - nearEdge));
  g.offset = -glm::dot(g.normal, nearEdge);
  return g;
}

/// s, t, w (and a directional light's depth) ranges of the frustum's corners in a projection
/// (convex: the corners bound the frustum's image).
struct CornerFit
{
  glm::dmat4 projected{ 1.0 };
  glm::dvec2 s{ kInf, -kInf }, t{ kInf, -kInf }, w{ kInf, -kInf }, depth{ kInf, -kInf };
  bool ok = true; ///< every corner in front of the capturing camera
};

CornerFit fitCorners(
  const glm::dmat4& projected, const GeneralFrame& g, const glm::dvec3& L, double wFloor)
{
  CornerFit f;
  f.projected = projected;
  for (const glm::dvec3& q : g.corners)
  {
    const glm::dvec4 h = projected * glm::dvec4(q, 1.0);
    if (!(h.w > wFloor) || !std::isfinite(h.w))
    {
      f.ok = false;
      return f;
    }
    f.s = { std::min(f.s.x, h.x / h.w), std::max(f.s.y, h.x / h.w) };
    f.t = { std::min(f.t.x, h.y / h.w), std::max(f.t.y, h.y / h.w) };
    f.w = { std::min(f.w.x, h.w), std::max(f.w.y, h.w) };
    const double depth = glm::dot(q, L);
    f.depth = { std::min(f.depth.x, depth), std::max(f.depth.y, depth) };
  }
  return f;
}

/// The view depth whose points of P (one t per depth: P holds the right axis) land on the
/// middle row of the map f fitted for a camera pushed back by pushBack: for q = view d + up u(d)
/// on P, u(d) = u0 + u1 d, the capture gives t = u(d) / (d + pushBack), so the middle row's
/// t_m = (t_min + t_max) / 2 holds d = (t_m pushBack - u0) / (u1 - t_m). 0 where it does not
/// exist (P parallel to the up axis, or to the middle row's ray).
double focusOfFit(const GeneralFrame& g, const CornerFit& f, double pushBack)
{
  const double across = glm::dot(g.normal, g.up);
  if (!(std::abs(across) > kParallelToPlane))
  {
    return 0.0;
  }
  const double u0 = -g.offset / across;
  const double u1 = -glm::dot(g.normal, g.view) / across;
  const double middle = 0.5 * (f.t.x + f.t.y);
  const double depth = (middle * pushBack - u0) / (u1 - middle);
  return std::isfinite(depth) && depth > 0.0 ? depth : 0.0;
}

/// The focus range (Kolić & Mihajlović §3.1, Fig. 3): the push back of the capturing camera at
/// which P's points at view depth vsFocus (one t per depth: P holds the right axis) land on the
/// map's middle row, by bisection; fit(pushBack) fits the corners. Pushing back moves the middle
/// away from the eye, monotonically: from about 2 n (captured from the eye, most of the map for
/// the first near distances) toward the middle of P's depth range (captured from afar, t linear
/// in depth). 0 where vsFocus is not positive or the eye's middle is already beyond it;
/// kMostPushBack vsFar, and clamped set, where the focus lies beyond what that push reaches.
double focusPushBack(const Camera& camera, const GeneralFrame& g, double vsFocus,
  const std::function<CornerFit(double)>& fit, bool& clamped)
{
  clamped = false;
  if (!(vsFocus > 0.0) || !(std::abs(glm::dot(g.normal, g.up)) > kParallelToPlane))
  {
    return 0.0;
  }
  const double focus = std::clamp(vsFocus, camera.vsNear, camera.vsFar);
  const glm::dvec3 focusOnPlane = g.view * focus +
    g.up * ((-g.offset - glm::dot(g.normal, g.view) * focus) / glm::dot(g.normal, g.up));
  // The share of t from P's near edge to the focus (the near edge is on top for a light from in
  // front). The plane's own points project onto themselves, from a point or along L.
  auto share = [&](const CornerFit& f)
  {
    const glm::dvec4 h = f.projected * glm::dvec4(focusOnPlane, 1.0);
    const double fromBottom = (h.y / h.w - f.t.x) / std::max(f.t.y - f.t.x, 1e-300);
    return g.lightFromFront ? 1.0 - fromBottom : fromBottom;
  };
  const CornerFit eye = fit(0.0);
  if (!eye.ok || !(share(eye) > 0.5))
  {
    return 0.0;
  }
  double lo = 0.0, hi = kMostPushBack * camera.vsFar;
  const CornerFit farthest = fit(hi);
  if (!farthest.ok)
  {
    return 0.0;
  }
  if (share(farthest) > 0.5)
  {
    clamped = true; // beyond what the farthest push reaches: focused as far as it goes
    return hi;
  }
  for (int i = 0; i < 60; ++i)
  {
    const double mid = 0.5 * (lo + hi);
    (share(fit(mid)) > 0.5 ? lo : hi) = mid;
  }
  return fit(hi).ok ? hi : 0.0;
}

std::string generalCaseError(const Camera& camera)
{
  std::string message = cameraError(camera);
  if (message.empty() && camera.parallel)
  {
    message = "camera space shadow maps need a perspective camera";
  }
  return message;
}
}

CameraSpaceMap computeCameraSpaceMap(
  const Camera& camera, const glm::dvec3& wsLightDirection, double vsFocus)
{
  CameraSpaceMap map;
  map.message = generalCaseError(camera);
  if (map.message.empty())
  {
    map.message = lightDirectionError(wsLightDirection);
  }
  if (!map.message.empty())
  {
    return map;
  }
  const glm::dvec3 L = glm::normalize(wsLightDirection);
  const GeneralFrame g = generalFrame(camera, L);
  map.message = g.message;
  map.lightFromFront = g.lightFromFront;
  if (!map.message.empty())
  {
    return map;
  }
  if (std::abs(glm::dot(g.normal, L)) < kParallelToPlane)
  {
    map.message = "light parallel to the projection plane";
    return map;
  }
  // The projection onto P along the light, captured by the camera pushed back by pushBack.
  const glm::dmat4 toPlane = projectAlong(g.normal, g.offset, L);
  auto fit = [&](double pushBack)
  {
    return fitCorners(
      capture(g.right, g.up, g.view, pushBack) * toPlane, g, L, 1e-9 * camera.vsNear);
  };
  map.pushBack = focusPushBack(camera, g, vsFocus, fit, map.focusClamped);
  const CornerFit f = fit(map.pushBack);
  map.vsFocus = f.ok ? focusOfFit(g, f, map.pushBack) : 0.0;
  if (!f.ok)
  {
    map.message = "the light's rays leave the projection plane behind the camera (the dueling "
                  "frustum case needs four planes)";
    return map;
  }
  map.wsToClip = fitClip(
    f.projected, lightDepthRow(L, f.depth, f.w.x, camera.vsFar), f.s, f.t, camera.wsPosition);
  map.wsPlane = glm::dvec4(g.normal, g.offset - glm::dot(g.normal, camera.wsPosition));
  map.wMin = f.w.x;
  map.status = Status::Ok;
  return map;
}

CameraSpaceMap computeCameraSpaceSpot(
  const Camera& camera, const glm::dvec3& wsLightPosition, double vsFocus)
{
  CameraSpaceMap map;
  map.message = generalCaseError(camera);
  if (map.message.empty() &&
    !(std::isfinite(wsLightPosition.x) && std::isfinite(wsLightPosition.y) &&
      std::isfinite(wsLightPosition.z)))
  {
    map.message = "the light's position must be finite";
  }
  if (!map.message.empty())
  {
    return map;
  }
  const glm::dvec3 l = wsLightPosition - camera.wsPosition; // camera-centred
  const glm::dvec3 view = glm::normalize(camera.wsDirection);
  // The rays from the light toward the middle of the view set the roll and the plane.
  const glm::dvec3 middle = view * (0.5 * (camera.vsNear + camera.vsFar));
  if (!(glm::length(middle - l) > 1e-9 * camera.vsFar))
  {
    map.message = "the light is in the view: a standard map";
    return map;
  }
  const GeneralFrame g = generalFrame(camera, glm::normalize(middle - l));
  map.lightFromFront = g.lightFromFront;
  if (!g.message.empty())
  {
    map.message = "the light lies along the view: a standard map";
    return map;
  }
  // Every point of the view on the side of the light's plane parallel to P that its rays
  // reach P from: W = dot(normal, q - l) of one sign (then orient it positive).
  double sideMin = kInf, sideMax = -kInf;
  for (const glm::dvec3& q : g.corners)
  {
    const double side = glm::dot(g.normal, q - l);
    sideMin = std::min(sideMin, side);
    sideMax = std::max(sideMax, side);
  }
  const double scale = 1e-9 * camera.vsFar;
  if (!(sideMin > scale) && !(sideMax < -scale))
  {
    map.message = "the light's plane parallel to P cuts the view (the light is in or near the "
                  "view): a standard map";
    return map;
  }
  const glm::dmat4 toPlane = projectFrom(g.normal, g.offset, l) * (sideMin > 0.0 ? 1.0 : -1.0);
  const glm::dvec3 none(0.0);
  auto fit = [&](double pushBack)
  { return fitCorners(capture(g.right, g.up, g.view, pushBack) * toPlane, g, none, 0.0); };
  map.pushBack = focusPushBack(camera, g, vsFocus, fit, map.focusClamped);
  const CornerFit f = fit(map.pushBack);
  map.vsFocus = f.ok ? focusOfFit(g, f, map.pushBack) : 0.0;
  if (!f.ok || !(f.w.y > f.w.x))
  {
    map.message = "the light's rays meet the projection plane behind the camera: a standard map";
    return map;
  }
  // Depth: a + b / w over [wMin, wMax] in [-kDepthRoom, kDepthRoom]; along a ray from the light
  // w grows with the distance from it, so depth / w keeps the light's order (a perspective
  // map's depth). Casters between the light and the view lie below -kDepthRoom: depth clamping.
  const double b = -2.0 * kDepthRoom / (1.0 / f.w.x - 1.0 / f.w.y);
  const double a = kDepthRoom - b / f.w.y;
  glm::dvec4 depthRow(0.0);
  for (int column = 0; column < 4; ++column)
  {
    depthRow[column] = a * f.projected[column].w + (column == 3 ? b : 0.0);
  }
  map.wsToClip = fitClip(f.projected, depthRow, f.s, f.t, camera.wsPosition);
  map.wsPlane = glm::dvec4(g.normal, g.offset - glm::dot(g.normal, camera.wsPosition));
  map.wMin = f.w.x;
  map.status = Status::Ok;
  return map;
}

std::vector<CameraSpaceFace> computeCameraSpaceDueling(
  const Camera& camera, const glm::dvec3& wsLightDirection)
{
  std::vector<CameraSpaceFace> faces;
  if (!cameraError(camera).empty() || !lightDirectionError(wsLightDirection).empty() ||
    camera.parallel)
  {
    return faces;
  }
  const glm::dvec3 L = glm::normalize(wsLightDirection);
  const glm::dvec3 view = glm::normalize(camera.wsDirection);
  const double along = glm::dot(L, view);
  if (std::abs(along) < kAlongView)
  {
    return faces;
  }
  glm::dvec3 up = camera.wsViewUp - glm::dot(camera.wsViewUp, view) * view;
  if (!(glm::length(up) > 1e-9))
  {
    up = std::abs(view.x) < 0.6 ? glm::cross(view, glm::dvec3(1, 0, 0))
                                : glm::cross(view, glm::dvec3(0, 1, 0));
  }
  up = glm::normalize(up);
  const glm::dvec3 right = glm::cross(view, up);
  const double tanY = std::tan(glm::radians(0.5 * camera.fovyDeg));
  const double tanX = tanY * camera.aspect;
  // Camera-centred: t on the near plane on the line through the eye along the light; the far
  // corners counter-clockwise.
  const glm::dvec3 t = L * (camera.vsNear / along);
  std::array<glm::dvec3, 4> far;
  const double sx[4] = { -1, 1, 1, -1 };
  const double sy[4] = { -1, -1, 1, 1 };
  for (int i = 0; i < 4; ++i)
  {
    far[i] = (view + right * (sx[i] * tanX) + up * (sy[i] * tanY)) * camera.vsFar;
  }
  std::vector<glm::dvec3> corners(far.begin(), far.end());
  for (int i = 0; i < 4; ++i)
  {
    corners.push_back(far[i] * (camera.vsNear / camera.vsFar));
  }
  double depthMin = kInf, depthMax = -kInf;
  for (const glm::dvec3& q : corners)
  {
    depthMin = std::min(depthMin, glm::dot(q, L));
    depthMax = std::max(depthMax, glm::dot(q, L));
  }
  for (int k = 0; k < 4; ++k)
  {
    const glm::dvec3& a = far[k];
    const glm::dvec3& b = far[(k + 1) & 3];
    const glm::dvec3 normal = glm::normalize(glm::cross(a - t, b - t));
    const double offset = -glm::dot(normal, t);
    const double across = glm::dot(normal, L);
    if (std::abs(across) < kParallelToPlane)
    {
      return {};
    }
    const glm::dmat4 projected = projectAndCapture(normal, offset, L, right, up, view);
    // The face's triangle is where its points land: fit s, t to it (its w is n at t, f at the
    // far edge).
    double sMin = kInf, sMax = -kInf, tMin = kInf, tMax = -kInf, wMin = kInf;
    for (const glm::dvec3& q : { t, a, b })
    {
      const glm::dvec4 h(glm::dot(q, right), glm::dot(q, up), 0.0, glm::dot(q, view));
      sMin = std::min(sMin, h.x / h.w);
      sMax = std::max(sMax, h.x / h.w);
      tMin = std::min(tMin, h.y / h.w);
      tMax = std::max(tMax, h.y / h.w);
      wMin = std::min(wMin, h.w);
    }
    CameraSpaceFace face;
    face.wsToClip = fitClip(projected, lightDepthRow(L, { depthMin, depthMax }, wMin, camera.vsFar),
      { sMin, sMax }, { tMin, tMax }, camera.wsPosition);
    face.wMin = wMin;
    // The planes through t, a far corner and the light, each facing the face's other corner.
    for (const auto& edge : { std::make_pair(a, b), std::make_pair(b, a) })
    {
      glm::dvec3 n = glm::normalize(glm::cross(edge.first - t, L));
      if (glm::dot(n, edge.second - t) < 0.0)
      {
        n = -n;
      }
      face.wsPlanes.emplace_back(n, -glm::dot(n, t) - glm::dot(n, camera.wsPosition));
    }
    faces.push_back(face);
  }
  return faces;
}

} // namespace csm
