// SPDX-License-Identifier: BSD-3-Clause
#include "csmCameraSpace.h"

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace csm
{
namespace
{
constexpr double kInf = std::numeric_limits<double>::infinity();
/// Below this sine of the angle between the light and the view axis, the light's direction in
/// the image is undefined: the dueling frustum case (or its mirror, light straight from behind).
constexpr double kAlongView = 1e-3;
/// Below this cosine between the light and P's normal, the projection onto P runs away.
constexpr double kParallelToPlane = 1e-6;
/// Share of each ray's w that the depth may use (room for rounding at the ends).
constexpr double kDepthRoom = 0.99;

/// Camera-centred point -> its projection along L onto the plane dot(normal, q) + offset = 0,
/// captured by a camera looking along view with the given right and up axes: rows x, y, (0), w.
glm::dmat4 projectAndCapture(const glm::dvec3& normal, double offset, const glm::dvec3& L,
  const glm::dvec3& right, const glm::dvec3& up, const glm::dvec3& view, double pushBack = 0.0)
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
  glm::dmat4 capture(0.0);
  for (int column = 0; column < 3; ++column)
  {
    capture[column] = glm::dvec4(right[column], up[column], 0.0, view[column]);
  }
  capture[3] = glm::dvec4(0.0, 0.0, 0.0, pushBack); // the capturing camera pushBack behind the eye
  return capture * toPlane;
}

/// The world -> clip matrix: s, t of `projected` fitted to [sMin, sMax] x [tMin, tMax] (after
/// the division by w), the light depth dot(q, L) over [depthMin, depthMax] in kDepthRoom of
/// wMin, for a camera at wsEye.
glm::dmat4 fitClip(const glm::dmat4& projected, const glm::dvec3& L, const glm::dvec2& s,
  const glm::dvec2& t, const glm::dvec2& depth, double wMin, double far, const glm::dvec3& wsEye)
{
  const double sScale = 2.0 / std::max(s.y - s.x, 1e-12);
  const double tScale = 2.0 / std::max(t.y - t.x, 1e-12);
  const double a = 2.0 * kDepthRoom * wMin / std::max(depth.y - depth.x, 1e-12 * far);
  const double b = -0.5 * a * (depth.x + depth.y);
  // Rows: s = sScale (x - sMin w) - w, t likewise, depth = a dot(q, L) + b, w.
  glm::dmat4 clip(0.0);
  for (int column = 0; column < 4; ++column)
  {
    const glm::dvec4 c = projected[column];
    clip[column].x = sScale * (c.x - s.x * c.w) - c.w;
    clip[column].y = tScale * (c.y - t.x * c.w) - c.w;
    clip[column].z = column < 3 ? a * L[column] : b;
    clip[column].w = c.w;
  }
  glm::dmat4 fromWorld(1.0); // q = p - eye
  fromWorld[3] = glm::dvec4(-wsEye, 1.0);
  return clip * fromWorld;
}
}

CameraSpaceMap computeCameraSpaceMap(
  const Camera& camera, const glm::dvec3& wsLightDirection, double vsFocus)
{
  CameraSpaceMap map;
  map.message = cameraError(camera);
  if (map.message.empty())
  {
    map.message = lightDirectionError(wsLightDirection);
  }
  if (map.message.empty() && camera.parallel)
  {
    map.message = "camera space shadow maps need a perspective camera";
  }
  if (!map.message.empty())
  {
    return map;
  }
  const glm::dvec3 L = glm::normalize(wsLightDirection);
  const glm::dvec3 view = glm::normalize(camera.wsDirection);
  // The roll: the light travels down the rolled image (it comes from above).
  const glm::dvec3 inImage = L - glm::dot(L, view) * view;
  if (glm::length(inImage) < kAlongView)
  {
    map.message = "light along the view: the dueling frustum case needs four planes";
    return map;
  }
  const glm::dvec3 up = -glm::normalize(inImage);
  const glm::dvec3 right = glm::cross(view, up);
  map.lightFromFront = glm::dot(L, view) < 0.0;

  // The original frustum's corners (camera-centred), and the rolled camera's field of view
  // that holds them.
  glm::dvec3 oldUp = camera.wsViewUp - glm::dot(camera.wsViewUp, view) * view;
  if (!(glm::length(oldUp) > 1e-9))
  {
    oldUp = up;
  }
  oldUp = glm::normalize(oldUp);
  const glm::dvec3 oldRight = glm::cross(view, oldUp);
  const double tanY = std::tan(glm::radians(0.5 * camera.fovyDeg));
  const double tanX = tanY * camera.aspect;
  double rolledTanY = 0.0;
  std::vector<glm::dvec3> corners;
  for (double d : { camera.vsNear, camera.vsFar })
  {
    for (double sx : { -1.0, 1.0 })
    {
      for (double sy : { -1.0, 1.0 })
      {
        const glm::dvec3 unit = view + oldRight * (sx * tanX) + oldUp * (sy * tanY);
        rolledTanY = std::max(rolledTanY, std::abs(glm::dot(unit, up)));
        corners.push_back(unit * d);
      }
    }
  }
  // P holds the rolled frustum's lower near edge and upper far edge (upper near and lower far
  // for a light from in front), and the rolled right axis.
  const double sign = map.lightFromFront ? -1.0 : 1.0;
  const glm::dvec3 nearEdge = view * camera.vsNear - up * (sign * camera.vsNear * rolledTanY);
  const glm::dvec3 farEdge = view * camera.vsFar + up * (sign * camera.vsFar * rolledTanY);
  const glm::dvec3 normal = glm::normalize(glm::cross(right, farEdge - nearEdge));
  const double offset = -glm::dot(normal, nearEdge); // camera-centred: dot(normal, q) + offset = 0
  const double across = glm::dot(normal, L);
  if (std::abs(across) < kParallelToPlane)
  {
    map.message = "light parallel to the projection plane";
    return map;
  }
  // Fit s, t to the frustum's corners (convex: the corners bound it) and the depth row to
  // their light depths and w, for the capturing camera pushed back by pushBack.
  struct Fit
  {
    glm::dmat4 projected{ 1.0 };
    glm::dvec2 s{ kInf, -kInf }, t{ kInf, -kInf }, depth{ kInf, -kInf };
    double wMin = kInf;
    bool ok = true;
  };
  auto fit = [&](double pushBack) {
    Fit f;
    f.projected = projectAndCapture(normal, offset, L, right, up, view, pushBack);
    for (const glm::dvec3& q : corners)
    {
      const glm::dvec4 h = f.projected * glm::dvec4(q, 1.0);
      if (!(h.w > 1e-9 * camera.vsNear) || !std::isfinite(h.w))
      {
        f.ok = false;
        return f;
      }
      f.s = { std::min(f.s.x, h.x / h.w), std::max(f.s.y, h.x / h.w) };
      f.t = { std::min(f.t.x, h.y / h.w), std::max(f.t.y, h.y / h.w) };
      const double depth = glm::dot(q, L);
      f.depth = { std::min(f.depth.x, depth), std::max(f.depth.y, depth) };
      f.wMin = std::min(f.wMin, h.w);
    }
    return f;
  };
  Fit chosen = fit(0.0);
  if (!chosen.ok)
  {
    map.message = "the light's rays leave the projection plane behind the camera (the dueling "
                  "frustum case needs four planes)";
    return map;
  }
  // The focus range (Kolić & Mihajlović §3.1, Fig. 3): the capturing camera pushed back along
  // the view until P's point at the focus depth (on the view axis's plane) lands on the map's
  // middle row. Pushing back moves the middle away from the eye, monotonically: from about
  // 2 n (captured from the eye, most of the map for the first near distances) toward the middle
  // of P's depth range (captured from afar, t linear in depth).
  const double focus = std::clamp(vsFocus, camera.vsNear, camera.vsFar);
  const glm::dvec3 focusOnPlane = view * focus +
    up * ((-offset - glm::dot(normal, view) * focus) / glm::dot(normal, up));
  auto focusShare = [&](const Fit& f) { // the share of t from P's near edge to the focus
    const glm::dvec4 h = f.projected * glm::dvec4(focusOnPlane, 1.0);
    const double fromBottom = (h.y / h.w - f.t.x) / std::max(f.t.y - f.t.x, 1e-300);
    return map.lightFromFront ? 1.0 - fromBottom : fromBottom; // (then the near edge is on top)
  };
  if (vsFocus > 0.0 && std::abs(glm::dot(normal, up)) > kParallelToPlane &&
    focusShare(chosen) > 0.5)
  {
    double lo = 0.0, hi = camera.vsFar;
    for (int i = 0; i < 40 && focusShare(fit(hi)) > 0.5; ++i)
    {
      hi *= 4.0; // a focus beyond what any push reaches: as far as the loop goes
    }
    for (int i = 0; i < 60; ++i)
    {
      const double mid = 0.5 * (lo + hi);
      (focusShare(fit(mid)) > 0.5 ? lo : hi) = mid;
    }
    const Fit pushed = fit(hi);
    if (pushed.ok)
    {
      chosen = pushed;
      map.pushBack = hi;
    }
  }
  map.wsToClip = fitClip(chosen.projected, L, chosen.s, chosen.t, chosen.depth, chosen.wMin,
    camera.vsFar, camera.wsPosition);
  map.wsPlane = glm::dvec4(normal, offset - glm::dot(normal, camera.wsPosition));
  map.wMin = chosen.wMin;
  map.status = Status::Ok;
  return map;
}

std::vector<CameraSpaceFace> computeCameraSpaceDueling(const Camera& camera,
  const glm::dvec3& wsLightDirection)
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
    face.wsToClip = fitClip(projected, L, { sMin, sMax }, { tMin, tMax }, { depthMin, depthMax },
      wMin, camera.vsFar, camera.wsPosition);
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
