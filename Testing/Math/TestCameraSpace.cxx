// SPDX-License-Identifier: BSD-3-Clause
// Camera space shadow maps (Kolić & Mihajlović), general case, as one world -> clip matrix.
#include "csmCameraSpace.h"
#include "csmMathTestHelpers.h"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace
{
using csmMathTest::camera; // eye at the origin looking down -z, up +y

// gammaDeg: 0 light from behind, 90 overhead, 180 facing; sideways tilts it toward +x.
glm::dvec3 lightAt(double gammaDeg, double sideways = 0.0)
{
  const double g = glm::radians(gammaDeg);
  return glm::normalize(glm::dvec3(sideways, -std::sin(g), -std::cos(g)));
}

struct RayCheck
{
  int outside = 0;   ///< frustum points outside their map ([-1, 1]^3 after the division, w > 0)
  int moving = 0;    ///< casters on the same light ray that land on another texel
  int unordered = 0; ///< casters nearer the light that do not have the smaller depth
};

/// 2000 points of the camera's frustum (depth log-uniform), each with the matrix mapFor(p) gives
/// it, and a caster 0.1 .. 10 units toward the light on its ray: the light travels along L, or
/// with a light position, from there (the caster then at most 0.9 of the way to the light).
template <typename MapFor>
RayCheck checkRays(const csm::Camera& cam, const glm::dvec3& L, double slack, MapFor mapFor,
  const glm::dvec3* lightPosition = nullptr)
{
  RayCheck check;
  std::mt19937 random(3);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), share(0.0, 1.0);
  const double tanY = std::tan(glm::radians(0.5 * cam.fovyDeg));
  for (int i = 0; i < 2000; ++i)
  {
    const double d = cam.vsNear * std::pow(cam.vsFar / cam.vsNear, share(random));
    const glm::dvec3 p = cam.wsPosition +
      glm::dvec3(unit(random) * tanY * cam.aspect * d, unit(random) * tanY * d, -d);
    const glm::dmat4& m = mapFor(p);
    const glm::dvec4 h = m * glm::dvec4(p, 1.0);
    check.outside += !(h.w > 0.0) || std::abs(h.x / h.w) > 1.0 + slack ||
      std::abs(h.y / h.w) > 1.0 + slack || std::abs(h.z / h.w) > 1.0 + 1e-9;
    const double toLight = lightPosition ? glm::length(p - *lightPosition) : 1e300;
    const glm::dvec3 along = lightPosition ? (p - *lightPosition) / toLight : L;
    const glm::dvec3 caster = p - along * std::min(0.1 + 10.0 * share(random), 0.9 * toLight);
    const glm::dvec4 c = m * glm::dvec4(caster, 1.0);
    const double scale = 1e-9 * (1.0 + std::abs(h.x / h.w) + std::abs(h.y / h.w));
    check.moving +=
      std::abs(c.x / c.w - h.x / h.w) > scale || std::abs(c.y / c.w - h.y / h.w) > scale;
    check.unordered += !(c.z / c.w < h.z / h.w);
  }
  return check;
}
}

// Every point of the view frustum lands in the map ([-1, 1]^3 after the division, in front of
// the projection centre); the points of one light ray share a texel, and the one nearer the
// light has the smaller depth (the map orders the casters of a ray as the light does).
TEST(CameraSpace, TheFrustumLandsInTheMapAndRaysKeepTheirOrder)
{
  csm::Camera moved = camera(0.5, 300.0, 50.0, 1.5);
  moved.wsPosition = { 40.0, -7.0, 1200.0 };
  for (const csm::Camera& cam : { camera(1.0, 100.0, 60.0), moved })
  {
    for (double gamma : { 50.0, 60.0, 75.0, 90.0, 105.0, 120.0, 130.0 })
    {
      for (double sideways : { 0.0, 0.5 })
      {
        const glm::dvec3 L = lightAt(gamma, sideways);
        const csm::CameraSpaceMap map = csm::computeCameraSpaceMap(cam, L);
        ASSERT_EQ(map.status, csm::Status::Ok) << "gamma " << gamma << ": " << map.message;
        EXPECT_EQ(map.lightFromFront, gamma > 90.0);
        const RayCheck check = checkRays(
          cam, L, 1e-9, [&](const glm::dvec3&) -> const glm::dmat4& { return map.wsToClip; });
        EXPECT_EQ(check.outside, 0) << "gamma " << gamma << " sideways " << sideways;
        EXPECT_EQ(check.moving, 0) << "gamma " << gamma << " sideways " << sideways;
        EXPECT_EQ(check.unordered, 0) << "gamma " << gamma << " sideways " << sideways;
      }
    }
  }
}

// The focus range (Kolić & Mihajlović §3.1, Fig. 3): the capturing camera pushed back so that
// P's points at the focus depth land on the map's middle row, where the capture from the eye
// gives the middle to about 2 n; the map stays a valid shadow map (every frustum point inside,
// rays keep their texel and order); a focus nearer than 2 n keeps the eye.
TEST(CameraSpace, TheFocusRangeTakesHalfTheMap)
{
  csm::Camera moved = camera(0.5, 300.0, 50.0, 1.5);
  moved.wsPosition = { 40.0, -7.0, 1200.0 };
  for (const csm::Camera& cam : { camera(1.0, 1000.0, 60.0), moved })
  {
    const glm::dvec3 view = glm::normalize(cam.wsDirection);
    for (double gamma : { 60.0, 90.0, 125.0 })
    {
      for (double sideways : { 0.0, 0.5 })
      {
        const glm::dvec3 L = lightAt(gamma, sideways);
        // NDC t of P's points at view depth d (P holds the rolled right axis: one t per depth).
        auto tAt = [&](const csm::CameraSpaceMap& map, double d)
        {
          const glm::dvec3 n(map.wsPlane);
          const glm::dvec3 across = glm::normalize(n - glm::dot(n, view) * view);
          const glm::dvec3 onAxis = cam.wsPosition + view * d;
          const glm::dvec3 q =
            onAxis - across * ((glm::dot(n, onAxis) + map.wsPlane.w) / glm::dot(n, across));
          const glm::dvec4 h = map.wsToClip * glm::dvec4(q, 1.0);
          return h.y / h.w;
        };
        const double focus = std::sqrt(cam.vsNear * cam.vsFar);
        const csm::CameraSpaceMap eye = csm::computeCameraSpaceMap(cam, L);
        const csm::CameraSpaceMap focused = csm::computeCameraSpaceMap(cam, L, focus);
        ASSERT_EQ(focused.status, csm::Status::Ok) << focused.message;
        EXPECT_EQ(eye.pushBack, 0.0);
        EXPECT_GT(focused.pushBack, 0.0);
        const double nearSide = tAt(focused, cam.vsNear) < 0.0 ? -1.0 : 1.0;
        EXPECT_NEAR(tAt(focused, focus), 0.0, 1e-6) << "gamma " << gamma;
        // From the eye, the focus depth is far past the middle (toward P's far edge).
        EXPECT_LT(nearSide * tAt(eye, focus), -0.8) << "gamma " << gamma;
        EXPECT_NEAR(nearSide * tAt(eye, 2.0 * cam.vsNear), 0.0, 0.05);
        const RayCheck check = checkRays(
          cam, L, 1e-9, [&](const glm::dvec3&) -> const glm::dmat4& { return focused.wsToClip; });
        EXPECT_EQ(check.outside, 0) << "gamma " << gamma << " sideways " << sideways;
        EXPECT_EQ(check.moving, 0) << "gamma " << gamma << " sideways " << sideways;
        EXPECT_EQ(check.unordered, 0) << "gamma " << gamma << " sideways " << sideways;
        // A farther focus pushes farther; one nearer than the eye's middle keeps the eye.
        EXPECT_GT(csm::computeCameraSpaceMap(cam, L, 4.0 * focus).pushBack, focused.pushBack);
        EXPECT_EQ(csm::computeCameraSpaceMap(cam, L, 1.5 * cam.vsNear).pushBack, 0.0);
      }
    }
  }
}

// A spot light's general case (Kolić & Mihajlović §6.2): the casters projected onto P from the
// light. Every frustum point lands in the map, its ray's casters on its texel with a smaller
// depth; the focus range as for a directional light; a light in the view, or whose plane
// parallel to P cuts it, and bad input are refused (the paper takes a standard map there).
TEST(CameraSpace, ASpotLightsRaysKeepTheirTexelAndOrder)
{
  csm::Camera moved = camera(0.5, 300.0, 50.0, 1.5);
  moved.wsPosition = { 40.0, -7.0, 1200.0 };
  for (const csm::Camera& cam : { camera(1.0, 100.0, 60.0), moved })
  {
    const glm::dvec3 view = glm::normalize(cam.wsDirection);
    // Above and behind, above the eye, high above and a little behind, to the side and behind.
    const glm::dvec3 offsets[] = { { 0.0, 40.0, 30.0 }, { 5.0, 60.0, 0.0 }, { -10.0, 150.0, 20.0 },
      { 120.0, 20.0, 10.0 } };
    for (const glm::dvec3& offset : offsets)
    {
      const glm::dvec3 light = cam.wsPosition + offset;
      for (double focus : { 0.0, std::sqrt(cam.vsNear * cam.vsFar) })
      {
        const csm::CameraSpaceMap map = csm::computeCameraSpaceSpot(cam, light, focus);
        ASSERT_EQ(map.status, csm::Status::Ok)
          << offset.x << "," << offset.y << "," << offset.z << ": " << map.message;
        EXPECT_EQ(map.pushBack > 0.0, focus > 0.0);
        EXPECT_GT(map.wMin, 0.0);
        const RayCheck check = checkRays(
          cam, view, 1e-9, [&](const glm::dvec3&) -> const glm::dmat4& { return map.wsToClip; },
          &light);
        EXPECT_EQ(check.outside, 0) << offset.y << " focus " << focus;
        EXPECT_EQ(check.moving, 0) << offset.y << " focus " << focus;
        EXPECT_EQ(check.unordered, 0) << offset.y << " focus " << focus;
      }
    }
    // Refused: in the view, on the view axis behind the eye, a position that is not finite.
    EXPECT_EQ(csm::computeCameraSpaceSpot(cam, cam.wsPosition + view * 20.0).status,
      csm::Status::InvalidInput);
    EXPECT_EQ(csm::computeCameraSpaceSpot(cam, cam.wsPosition - view * 20.0).status,
      csm::Status::InvalidInput);
    const csm::CameraSpaceMap bad = csm::computeCameraSpaceSpot(cam, { std::nan(""), 0.0, 0.0 });
    EXPECT_EQ(bad.status, csm::Status::InvalidInput);
    EXPECT_FALSE(bad.message.empty());
  }
}

// The light along the view or inside the view's cone (the dueling frustum case and its mirror)
// and bad input give one message and no matrix.
TEST(CameraSpace, DuelingFrustaAndBadInputAreRefused)
{
  const csm::Camera cam = camera(1.0, 100.0, 60.0);
  // (20 and 160 degrees: inside the 39-degree half diagonal of this view, from behind and in
  // front: the rays of some visible points meet P behind the camera.)
  for (double gamma : { 0.0, 20.0, 160.0, 180.0 })
  {
    const csm::CameraSpaceMap map = csm::computeCameraSpaceMap(cam, lightAt(gamma));
    EXPECT_EQ(map.status, csm::Status::InvalidInput);
    EXPECT_NE(map.message.find("dueling"), std::string::npos) << map.message;
  }
  EXPECT_EQ(
    csm::computeCameraSpaceMap(cam, { std::nan(""), -1.0, 0.0 }).status, csm::Status::InvalidInput);
  EXPECT_EQ(csm::computeCameraSpaceMap(cam, { 0.0, 0.0, 0.0 }).status, csm::Status::InvalidInput);
  csm::Camera parallel = cam;
  parallel.parallel = true;
  EXPECT_EQ(csm::computeCameraSpaceMap(parallel, lightAt(60.0)).status, csm::Status::InvalidInput);
}

// The dueling frustum case: four maps through the point t; every frustum point takes the map
// whose planes hold it, lands inside it, and keeps its ray's texel and order.
TEST(CameraSpace, DuelingFacesCoverTheFrustumAndRaysKeepTheirOrder)
{
  csm::Camera moved = camera(0.5, 300.0, 50.0, 1.5);
  moved.wsPosition = { 40.0, -7.0, 1200.0 };
  for (const csm::Camera& cam : { camera(1.0, 100.0, 60.0), moved })
  {
    for (double gamma : { 0.0, 10.0, 170.0, 180.0 })
    {
      for (double sideways : { 0.0, 0.2 })
      {
        const glm::dvec3 L = lightAt(gamma, sideways);
        const std::vector<csm::CameraSpaceFace> faces = csm::computeCameraSpaceDueling(cam, L);
        ASSERT_EQ(faces.size(), 4u) << "gamma " << gamma;
        const RayCheck check = checkRays(cam, L, 1e-6,
          [&](const glm::dvec3& p) -> const glm::dmat4&
          {
            size_t chosen = 0;
            double best = -1e300;
            for (size_t k = 0; k < faces.size(); ++k)
            {
              double distance = 1e300;
              for (const glm::dvec4& plane : faces[k].wsPlanes)
                distance = std::min(distance, glm::dot(glm::dvec3(plane), p) + plane.w);
              if (distance > best)
              {
                best = distance;
                chosen = k;
              }
            }
            return faces[chosen].wsToClip;
          });
        EXPECT_EQ(check.outside, 0) << "gamma " << gamma << " sideways " << sideways;
        EXPECT_EQ(check.moving, 0) << "gamma " << gamma << " sideways " << sideways;
        EXPECT_EQ(check.unordered, 0) << "gamma " << gamma << " sideways " << sideways;
      }
    }
  }
  // A light perpendicular to the view has no t.
  EXPECT_TRUE(csm::computeCameraSpaceDueling(camera(1.0, 100.0, 60.0), lightAt(90.0)).empty());
}

// A focus beyond what any push reaches (past about the middle of the depth range, beyond the
// far plane, or absurdly far) is clamped to the farthest focus the map can have: the push of
// csm::kMostPushBack far depths, focusClamped set, vsFocus on the map's middle row and inside
// the view; every matrix entry stays within float's range and the map a valid shadow map. A
// focus it reaches is not clamped and is the one on the middle row.
TEST(CameraSpace, AFocusBeyondReachIsClampedToTheFarthestFocus)
{
  csm::Camera moved = camera(0.5, 300.0, 50.0, 1.5);
  moved.wsPosition = { 40.0, -7.0, 1200.0 };
  auto floatSafe = [](const glm::dmat4& m)
  {
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r)
        if (!(std::abs(m[c][r]) < 1e30))
          return false;
    return true;
  };
  for (const csm::Camera& cam : { camera(1.0, 1000.0, 60.0), moved })
  {
    const glm::dvec3 view = glm::normalize(cam.wsDirection);
    for (double gamma : { 60.0, 90.0, 125.0 })
    {
      for (double sideways : { 0.0, 0.5 })
      {
        const glm::dvec3 L = lightAt(gamma, sideways);
        auto tAt = [&](const csm::CameraSpaceMap& map, double d)
        {
          const glm::dvec3 n(map.wsPlane);
          const glm::dvec3 across = glm::normalize(n - glm::dot(n, view) * view);
          const glm::dvec3 onAxis = cam.wsPosition + view * d;
          const glm::dvec3 q =
            onAxis - across * ((glm::dot(n, onAxis) + map.wsPlane.w) / glm::dot(n, across));
          const glm::dvec4 h = map.wsToClip * glm::dvec4(q, 1.0);
          return h.y / h.w;
        };
        const double reachable = std::sqrt(cam.vsNear * cam.vsFar);
        const csm::CameraSpaceMap within = csm::computeCameraSpaceMap(cam, L, reachable);
        ASSERT_EQ(within.status, csm::Status::Ok) << within.message;
        EXPECT_FALSE(within.focusClamped);
        EXPECT_NEAR(within.vsFocus, reachable, 1e-6 * reachable) << "gamma " << gamma;
        for (double focus : { 0.9 * cam.vsFar, cam.vsFar, 1e6, 1e300 })
        {
          const csm::CameraSpaceMap map = csm::computeCameraSpaceMap(cam, L, focus);
          ASSERT_EQ(map.status, csm::Status::Ok) << map.message;
          EXPECT_TRUE(map.focusClamped) << "gamma " << gamma << " focus " << focus;
          EXPECT_DOUBLE_EQ(map.pushBack, csm::kMostPushBack * cam.vsFar);
          EXPECT_GT(map.vsFocus, reachable) << "gamma " << gamma;
          EXPECT_LT(map.vsFocus, 0.9 * cam.vsFar) << "gamma " << gamma;
          EXPECT_NEAR(tAt(map, map.vsFocus), 0.0, 1e-6) << "gamma " << gamma;
          EXPECT_TRUE(floatSafe(map.wsToClip)) << "gamma " << gamma << " focus " << focus;
          const RayCheck check = checkRays(
            cam, L, 1e-9, [&](const glm::dvec3&) -> const glm::dmat4& { return map.wsToClip; });
          EXPECT_EQ(check.outside, 0) << "gamma " << gamma << " focus " << focus;
          EXPECT_EQ(check.moving, 0) << "gamma " << gamma << " focus " << focus;
          EXPECT_EQ(check.unordered, 0) << "gamma " << gamma << " focus " << focus;
        }
      }
    }
    // A spot light (above and behind the eye) the same way.
    const glm::dvec3 light = cam.wsPosition + glm::dvec3(0.0, 40.0, 30.0);
    const csm::CameraSpaceMap spot = csm::computeCameraSpaceSpot(cam, light, 1e6);
    ASSERT_EQ(spot.status, csm::Status::Ok) << spot.message;
    EXPECT_TRUE(spot.focusClamped);
    EXPECT_GT(spot.vsFocus, cam.vsNear);
    EXPECT_LT(spot.vsFocus, cam.vsFar);
    EXPECT_TRUE(floatSafe(spot.wsToClip));
    EXPECT_FALSE(
      csm::computeCameraSpaceSpot(cam, light, std::sqrt(cam.vsNear * cam.vsFar)).focusClamped);
  }
}
