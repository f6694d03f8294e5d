// SPDX-License-Identifier: BSD-3-Clause
// computeShadowSetup for a directional light: the storage factors of Lloyd et al. 2006, Eq. 12,
// 17-18 and its maxima (Eq. 9-10); the generalized warp (Barroso & Celes 2007, Eq. 16-18)
// against the orthographic map; the body B in its map; hard and bad input; the warp and focus
// steps; the texel grid and the depth floor of orthographic maps.
#include "csmAliasing.h"
#include "csmMathTestHelpers.h"
#include "csmSetup.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

namespace
{
using csmMathTest::camera; // eye at the origin looking down -z, up +y
using csmMathTest::expectAllFinite;
using csmMathTest::expectBodyInUnitCube;
using csmMathTest::finite;
using csmMathTest::kDeg;
using csmMathTest::lightAt; // gammaDeg: 0 light from behind, 90 overhead, 180 facing
using csmMathTest::settings;
using csmMathTest::toNdc;
} // namespace

// Lloyd et al. 2006, Eq. 12, 17, 18 for an overhead light and self-similar (log) partitions.
TEST(StorageFactor, OverheadMatchesClosedForms)
{
  const double tanTheta = std::tan(30.0 * kDeg);
  for (auto warp : { csm::WarpMode::None, csm::WarpMode::LiSPSM, csm::WarpMode::Generalized })
  {
    for (int k = 1; k <= 4; ++k)
    {
      for (double ratio : { 10.0, 100.0, 1e3, 1e4 })
      {
        const csm::Camera cam = camera(1.0, ratio, 60.0);
        const csm::ShadowSetup setup = csm::computeShadowSetup(
          cam, lightAt(cam, 90.0), nullptr, settings(warp, csm::SplitScheme::Log, k));
        ASSERT_EQ(setup.status, csm::Status::Ok) << setup.message;
        ASSERT_EQ(setup.cascades.size(), size_t(k));
        const double r = std::pow(ratio, 1.0 / k);
        const double expected = warp == csm::WarpMode::None
          ? k * r * (r - 1.0) / (2.0 * tanTheta) // Lloyd et al. 2006, Eq. 17
          : k * (r - 1.0) / (2.0 * tanTheta);    // Lloyd et al. 2006, Eq. 18
        EXPECT_NEAR(setup.storageTotal, expected, 1e-6 * expected)
          << csm::toString(warp) << " k " << k << " f/n " << ratio;
        EXPECT_NEAR(setup.storageOptimal, std::log(ratio) / (2.0 * tanTheta), 1e-12);
        EXPECT_GE(setup.storageTotal, setup.storageOptimal * (1.0 - 1e-12));
      }
    }
  }
}

// Lloyd et al. 2006, Eq. 7-10 with n = 1 (the form the paper prints): maxima of m_x, m_z for one
// LiSPSM map.
TEST(StorageFactor, OverheadMaximaMatchEq9And10)
{
  const double n = 1.0, f = 100.0, tanTheta = std::tan(30.0 * kDeg);
  const csm::Camera cam = camera(n, f, 60.0);
  for (auto warp : { csm::WarpMode::PSM, csm::WarpMode::LiSPSM })
  {
    const csm::ShadowSetup setup = csm::computeShadowSetup(
      cam, lightAt(cam, 90.0), nullptr, settings(warp, csm::SplitScheme::Single, 1));
    ASSERT_EQ(setup.cascades.size(), 1u);
    const double np = setup.cascades[0].nPrime;
    EXPECT_NEAR(np, warp == csm::WarpMode::PSM ? n : n + std::sqrt(f * n), 1e-12);
    const double fp = np + f - n;
    EXPECT_NEAR(setup.cascades[0].Mx, f * np / fp, 1e-9);                                  // Eq. 9
    EXPECT_NEAR(setup.cascades[0].Mz, n * (f - n) / (2 * tanTheta) * fp / (np * f), 1e-9); // Eq. 10
  }
}

TEST(StorageFactor, NonSquareImageKeepsOverheadStorage)
{
  const double tanTheta = std::tan(20.0 * kDeg);
  const csm::Camera cam = camera(1.0, 1000.0, 40.0, 800.0 / 300.0);
  const csm::ShadowSetup setup = csm::computeShadowSetup(
    cam, lightAt(cam, 90.0), nullptr, settings(csm::WarpMode::LiSPSM, csm::SplitScheme::Log, 3));
  const double r = 10.0;
  EXPECT_NEAR(setup.storageTotal, 3 * (r - 1) / (2 * tanTheta), 1e-6 * setup.storageTotal);
}

TEST(StorageFactor, LightBehindAndInFrontAgree)
{
  const csm::Camera cam = camera(1.0, 500.0, 50.0);
  for (double g : { 0.0, 10.0, 40.0, 70.0 })
  {
    const auto s = settings(csm::WarpMode::Generalized, csm::SplitScheme::Adaptive, 3);
    const auto behind = csm::computeShadowSetup(cam, lightAt(cam, g), nullptr, s);
    const auto front = csm::computeShadowSetup(cam, lightAt(cam, 180.0 - g), nullptr, s);
    EXPECT_NEAR(behind.gammaDeg, g, 1e-9);
    EXPECT_NEAR(front.gammaDeg, 180.0 - g, 1e-9);
    EXPECT_NEAR(behind.storageTotal, front.storageTotal, 1e-9 * behind.storageTotal) << g;
  }
}

// Beyond gamma_lim the generalized warp beats the orthographic map by a wide margin; below it,
// where it fades to orthographic (Barroso & Celes 2007, Eq. 16-18), its worst error stays within
// 10% of it.
TEST(StorageFactor, GeneralizedAgainstUniform)
{
  const csm::Camera cam = camera(1.0, 1000.0, 60.0);
  for (double g = 0.0; g <= 180.0; g += 5.0)
  {
    const auto none = csm::computeShadowSetup(
      cam, lightAt(cam, g), nullptr, settings(csm::WarpMode::None, csm::SplitScheme::Log, 2));
    const auto gen = csm::computeShadowSetup(cam, lightAt(cam, g), nullptr,
      settings(csm::WarpMode::Generalized, csm::SplitScheme::Log, 2));
    const double folded = std::min(g, 180.0 - g);
    if (folded >= 35.0)
    {
      EXPECT_LT(gen.storageTotal, 0.8 * none.storageTotal) << "gamma " << g;
    }
    EXPECT_LE(gen.storageTotal, 1.1 * none.storageTotal) << "gamma " << g;
  }
  const auto overheadNone = csm::computeShadowSetup(
    cam, lightAt(cam, 90.0), nullptr, settings(csm::WarpMode::None, csm::SplitScheme::Log, 2));
  const auto overheadGen = csm::computeShadowSetup(cam, lightAt(cam, 90.0), nullptr,
    settings(csm::WarpMode::Generalized, csm::SplitScheme::Log, 2));
  // Lloyd et al. 2006, Eq. 17 over Eq. 18: the warp saves the factor (f/n)^(1/k).
  EXPECT_NEAR(overheadNone.storageTotal / overheadGen.storageTotal, std::sqrt(1000.0), 1e-6);
}

TEST(Body, EveryVertexMapsIntoUnitCube)
{
  csm::Bounds scene;
  scene.wsMin = { -50, -2, -400 };
  scene.wsMax = { 60, 30, 5 };
  for (auto warp :
    { csm::WarpMode::None, csm::WarpMode::PSM, csm::WarpMode::LiSPSM, csm::WarpMode::Generalized })
  {
    for (auto scheme : { csm::SplitScheme::Single, csm::SplitScheme::Log,
           csm::SplitScheme::Practical, csm::SplitScheme::Adaptive })
    {
      for (double g = 0.0; g <= 180.0; g += 15.0)
      {
        for (bool clamp : { true, false })
        {
          csm::Camera cam = camera(0.5, 2000.0, 45.0, 1.5);
          cam.wsPosition = { 3, 8, 20 };
          auto s = settings(warp, scheme, 4);
          s.depthClamp = clamp;
          // Tilt the light sideways too, so the light is in general position.
          const glm::dvec3 light = lightAt(cam, g) + glm::dvec3(0.3, 0.0, 0.0);
          const auto without = csm::computeShadowSetup(cam, light, nullptr, s);
          ASSERT_EQ(without.status, csm::Status::Ok);
          expectBodyInUnitCube(without);
          const auto with = csm::computeShadowSetup(cam, light, &scene, s);
          ASSERT_EQ(with.status, csm::Status::Ok) << with.message;
          expectBodyInUnitCube(with);
          expectAllFinite(with);
        }
      }
    }
  }
}

TEST(Body, CastersTowardTheLightAreInsideOrClamped)
{
  // A tall box; the camera looks at its lower part; the light comes from above.
  csm::Bounds scene;
  scene.wsMin = { -10, 0, -60 };
  scene.wsMax = { 10, 100, -10 };
  csm::Camera cam = camera(1.0, 100.0, 30.0);
  cam.wsPosition = { 0, 1, 0 };
  cam.wsDirection = { 0, -0.05, -1 };
  const glm::dvec3 light(0.2, -1.0, -0.1);
  const glm::dvec3 caster(-9.0, 40.0, -30.0); // high above the visible part; lands at (-1, 0, -34)
  auto s = settings(csm::WarpMode::Generalized, csm::SplitScheme::Adaptive, 2);
  s.depthClamp = false;
  const auto full = csm::computeShadowSetup(cam, light, &scene, s);
  ASSERT_EQ(full.status, csm::Status::Ok);
  s.depthClamp = true;
  const auto clamped = csm::computeShadowSetup(cam, light, &scene, s);
  ASSERT_EQ(clamped.status, csm::Status::Ok);
  // The caster's shadow falls where its light ray meets the body: find a cascade that holds it.
  bool tested = false;
  for (size_t i = 0; i < full.cascades.size(); ++i)
  {
    const glm::dvec3 a = toNdc(full.cascades[i].wsToClip, caster);
    const glm::dvec3 b = toNdc(clamped.cascades[i].wsToClip, caster);
    if (std::abs(a.x) <= 1 && std::abs(a.y) <= 1)
    {
      tested = true;
      EXPECT_GE(a.z, -1.0); // inside the depth range without clamping
      EXPECT_LT(b.z, -1.0); // in front of the near plane: the GPU clamps it to the near depth
    }
  }
  EXPECT_TRUE(tested);
}

TEST(Body, DepthRangeFitsTheVisibleScene)
{
  csm::Bounds scene;
  scene.wsMin = { -1, -1, -80 };
  scene.wsMax = { 1, 1, -20 };
  const csm::Camera cam = camera(0.1, 10000.0, 60.0);
  const auto setup = csm::computeShadowSetup(cam, lightAt(cam, 90.0), &scene,
    settings(csm::WarpMode::Generalized, csm::SplitScheme::Log, 3));
  ASSERT_EQ(setup.status, csm::Status::Ok);
  EXPECT_NEAR(setup.vsNear, 20.0, 1e-3);
  EXPECT_NEAR(setup.vsFar, 80.0, 1e-3);
  EXPECT_NEAR(setup.splits[1], 20.0 * std::pow(4.0, 1.0 / 3.0), 1e-3);
}

// Hard cases: no NaN or Inf anywhere, and an empty body reported as such.
TEST(Stability, AnglesRangesAndFields)
{
  for (double ratio : { 1.0 + 1e-6, 10.0, 1e4, 1e7 })
  {
    for (double fovy : { 1.0, 60.0, 170.0 })
    {
      // gamma_lim of the whole frustum (the first cascade's is near it)
      const double t = std::tan(0.5 * fovy * kDeg);
      const csm::PartitionShape whole{ 0.01, 0.01 * ratio, 0.01 * t, 0.01 * ratio * t };
      const double limitDeg = csm::gammaLim(whole) / kDeg;
      for (double g :
        { 0.0, 1e-12, 1e-6, limitDeg - 1e-9, limitDeg + 1e-9, 90.0, 180.0, 180.0 - 1e-12 })
      {
        for (auto warp : { csm::WarpMode::None, csm::WarpMode::PSM, csm::WarpMode::LiSPSM,
               csm::WarpMode::Generalized })
        {
          csm::Camera cam = camera(0.01, 0.01 * ratio, fovy);
          const auto setup = csm::computeShadowSetup(
            cam, lightAt(cam, g), nullptr, settings(warp, csm::SplitScheme::Adaptive, 4));
          ASSERT_EQ(setup.status, csm::Status::Ok) << setup.message;
          expectAllFinite(setup);
          expectBodyInUnitCube(setup, 1e-6);
        }
      }
    }
  }
}

TEST(Stability, DegenerateScenes)
{
  const auto s = settings(csm::WarpMode::Generalized, csm::SplitScheme::Adaptive, 3);
  const csm::Camera cam = camera(0.1, 1000.0, 45.0);
  for (double g : { 0.0, 1e-6, 45.0, 90.0, 180.0 })
  {
    const glm::dvec3 light = lightAt(cam, g);
    // A point.
    csm::Bounds point{ { 0, 0, -10 }, { 0, 0, -10 } };
    auto setup = csm::computeShadowSetup(cam, light, &point, s);
    EXPECT_NE(setup.status, csm::Status::InvalidInput);
    expectAllFinite(setup);
    expectBodyInUnitCube(setup, 1e-6);
    // A flat ground plane, and a wall facing the camera.
    csm::Bounds ground{ { -100, -1, -500 }, { 100, -1, 0 } };
    setup = csm::computeShadowSetup(cam, light, &ground, s);
    EXPECT_EQ(setup.status, csm::Status::Ok) << setup.message;
    expectAllFinite(setup);
    expectBodyInUnitCube(setup, 1e-6);
    csm::Bounds wall{ { -100, -100, -50 }, { 100, 100, -50 } };
    setup = csm::computeShadowSetup(cam, light, &wall, s);
    EXPECT_EQ(setup.status, csm::Status::Ok) << setup.message;
    expectAllFinite(setup);
    expectBodyInUnitCube(setup, 1e-6);
    // Empty bounds (VTK's uninitialized bounds).
    csm::Bounds empty;
    setup = csm::computeShadowSetup(cam, light, &empty, s);
    EXPECT_EQ(setup.status, csm::Status::NothingToShadow);
    EXPECT_TRUE(setup.cascades.empty());
    // The camera looks away from the scene.
    csm::Bounds behind{ { -10, -10, 10 }, { 10, 10, 30 } };
    setup = csm::computeShadowSetup(cam, light, &behind, s);
    EXPECT_EQ(setup.status, csm::Status::NothingToShadow);
    EXPECT_TRUE(setup.cascades.empty());
    EXPECT_FALSE(setup.message.empty());
    // The camera inside the scene box.
    csm::Bounds around{ { -200, -200, -200 }, { 200, 200, 200 } };
    setup = csm::computeShadowSetup(cam, light, &around, s);
    EXPECT_EQ(setup.status, csm::Status::Ok);
    EXPECT_NEAR(setup.vsNear, 0.1, 1e-9);
    expectAllFinite(setup);
    expectBodyInUnitCube(setup, 1e-6);
  }
}

TEST(Stability, FarFromTheOrigin)
{
  const glm::dvec3 offset(1e7, -1e7, 1e7);
  csm::Bounds scene{ offset + glm::dvec3(-50, 0, -200), offset + glm::dvec3(50, 40, 0) };
  csm::Camera cam = camera(0.5, 5000.0, 45.0);
  cam.wsPosition = offset + glm::dvec3(0, 10, 30);
  csm::Camera local = cam;
  local.wsPosition -= offset;
  csm::Bounds localScene{ scene.wsMin - offset, scene.wsMax - offset };
  for (double g : { 0.0, 2.0, 60.0, 90.0, 178.0 })
  {
    const auto s = settings(csm::WarpMode::Generalized, csm::SplitScheme::Adaptive, 3);
    const auto far = csm::computeShadowSetup(cam, lightAt(cam, g), &scene, s);
    const auto near = csm::computeShadowSetup(local, lightAt(local, g), &localScene, s);
    ASSERT_EQ(far.status, csm::Status::Ok);
    expectAllFinite(far);
    expectBodyInUnitCube(far, 1e-6);
    ASSERT_EQ(far.cascades.size(), near.cascades.size());
    EXPECT_NEAR(far.storageTotal, near.storageTotal, 1e-6 * near.storageTotal);
    // The same point maps to the same shadow-map coordinates.
    for (size_t i = 0; i < far.cascades.size(); ++i)
    {
      const glm::dvec3 a = toNdc(far.cascades[i].wsToClip, offset + glm::dvec3(3, 1, -20));
      const glm::dvec3 b = toNdc(near.cascades[i].wsToClip, glm::dvec3(3, 1, -20));
      EXPECT_NEAR(glm::length(a - b), 0.0, 1e-7);
    }
  }
}

TEST(Stability, ParallelProjection)
{
  csm::Camera cam = camera(1.0, 200.0, 30.0);
  cam.parallel = true;
  cam.parallelScale = 20.0;
  csm::Bounds scene{ { -30, -5, -150 }, { 30, 20, -10 } };
  for (double g : { 0.0, 45.0, 90.0, 180.0 })
  {
    const auto setup = csm::computeShadowSetup(
      cam, lightAt(cam, g), &scene, settings(csm::WarpMode::Generalized, csm::SplitScheme::Log, 2));
    ASSERT_EQ(setup.status, csm::Status::Ok);
    for (const auto& c : setup.cascades)
    {
      EXPECT_TRUE(std::isinf(c.nPrime)); // warping cannot help a parallel projection
      EXPECT_TRUE(finite(c.wsToClip));
    }
    expectBodyInUnitCube(setup);
    EXPECT_TRUE(std::isnan(setup.storageOptimal));
  }
}

TEST(Stability, BadInputIsReported)
{
  const auto s = settings(csm::WarpMode::Generalized, csm::SplitScheme::Adaptive, 2);
  const double nan = std::nan("");
  csm::Camera cam = camera(1.0, 100.0, 60.0);
  auto expectInvalid = [&](const csm::Camera& c, glm::dvec3 light, const csm::Settings& st)
  {
    const auto setup = csm::computeShadowSetup(c, light, nullptr, st);
    EXPECT_EQ(setup.status, csm::Status::InvalidInput);
    EXPECT_FALSE(setup.message.empty());
    EXPECT_TRUE(setup.cascades.empty());
  };
  expectInvalid(cam, { nan, -1, 0 }, s);
  expectInvalid(cam, { 0, 0, 0 }, s);
  csm::Camera bad = cam;
  bad.vsNear = 0.0;
  expectInvalid(bad, { 0, -1, 0 }, s);
  bad = cam;
  bad.vsFar = 0.5;
  expectInvalid(bad, { 0, -1, 0 }, s);
  bad = cam;
  bad.fovyDeg = 180.0;
  expectInvalid(bad, { 0, -1, 0 }, s);
  bad = cam;
  bad.wsPosition.x = nan;
  expectInvalid(bad, { 0, -1, 0 }, s);
  auto st = s;
  st.split.k = 0;
  expectInvalid(cam, { 0, -1, 0 }, st);
  st = s;
  st.split.alpha = 1.0;
  expectInvalid(cam, { 0, -1, 0 }, st);
  st = s;
  st.split.lambda = nan;
  expectInvalid(cam, { 0, -1, 0 }, st);
  csm::Bounds infinite{ { 0, 0, 0 }, { INFINITY, 1, 1 } };
  EXPECT_EQ(
    csm::computeShadowSetup(cam, { 0, -1, 0 }, &infinite, s).status, csm::Status::InvalidInput);
  // View-up parallel to the view direction still gives a valid frame.
  bad = cam;
  bad.wsViewUp = bad.wsDirection;
  EXPECT_EQ(csm::computeShadowSetup(bad, { 0, -1, 0 }, nullptr, s).status, csm::Status::Ok);
}

TEST(Body, PartsFitTighterThanTheirUnion)
{
  // A wide thin ground and a small tower: their union box fills the air in front of the camera.
  const csm::Bounds ground{ { -150, -0.5, -150 }, { 150, 0, 150 } };
  const csm::Bounds tower{ { -10, 0, -10 }, { 10, 80, 10 } };
  const csm::Bounds all{ { -150, -0.5, -150 }, { 150, 80, 150 } };
  const std::vector<csm::Bounds> parts = { ground, tower };
  csm::Camera cam = camera(0.3, 400.0, 30.0);
  cam.wsPosition = { 75, 60, 95 };
  cam.wsDirection = glm::dvec3(0, 30, 0) - cam.wsPosition;
  const auto s = settings(csm::WarpMode::Generalized, csm::SplitScheme::Log, 2);
  const glm::dvec3 light(-0.45, -1.0, -0.35);
  const auto loose = csm::computeShadowSetup(cam, light, &all, s);
  const auto tight = csm::computeShadowSetup(cam, light, &all, s, &parts);
  ASSERT_EQ(loose.status, csm::Status::Ok);
  ASSERT_EQ(tight.status, csm::Status::Ok);
  EXPECT_NEAR(loose.vsNear, 0.3, 1e-9); // the camera is inside the union box
  EXPECT_GT(tight.vsNear, 50.0);        // the first receiver is far in front
  EXPECT_LT(tight.storageTotal, loose.storageTotal);
  expectBodyInUnitCube(tight);
  // Every corner of the tower that the view sees stays inside the maps.
  for (const auto& c : tight.cascades)
    EXPECT_TRUE(std::isfinite(c.storage));
}

// Near 1e-10, far 1e10: a clipping tolerance relative to the far distance would swallow the
// first log cascades (storage 3e-12 .. 3e-22); near 1e-300, far 1e300 is beyond what a double
// holds and is refused, not planned with null split depths. Log cascades are self-similar:
// every one has the same storage.
TEST(Stability, ExtremeDepthRanges)
{
  const csm::Camera c = camera(1e-10, 1e10, 60.0);
  const auto s = csm::computeShadowSetup(
    c, lightAt(c, 90.0), nullptr, settings(csm::WarpMode::Generalized, csm::SplitScheme::Log, 8));
  ASSERT_EQ(s.status, csm::Status::Ok);
  ASSERT_EQ(s.cascades.size(), 8u);
  const double expected = s.cascades[4].storage; // the cascade [1, 316]
  EXPECT_NEAR(expected, 273.0, 1.0);
  for (const csm::Cascade& cascade : s.cascades)
  {
    EXPECT_NEAR(cascade.storage / expected, 1.0, 1e-6) << "cascade from " << cascade.vsNear;
    EXPECT_TRUE(std::isfinite(cascade.nPrime));
  }
  // The widest range a double handles: everything finite, for every scheme.
  for (auto scheme : { csm::SplitScheme::Single, csm::SplitScheme::Log, csm::SplitScheme::Adaptive,
         csm::SplitScheme::Practical })
  {
    const csm::Camera wide = camera(1e-50, 1e50, 60.0);
    const auto w = csm::computeShadowSetup(
      wide, lightAt(wide, 30.0), nullptr, settings(csm::WarpMode::Generalized, scheme, 8));
    ASSERT_EQ(w.status, csm::Status::Ok);
    for (double split : w.splits)
      EXPECT_TRUE(std::isfinite(split) && split > 0.0);
    EXPECT_TRUE(std::isfinite(w.storageTotal));
    EXPECT_TRUE(std::isfinite(w.storageOptimal));
  }
  // Beyond it: refused with a message, no cascades.
  const csm::Camera huge = camera(1e-300, 1e300, 60.0);
  const auto h = csm::computeShadowSetup(huge, lightAt(huge, 90.0), nullptr,
    settings(csm::WarpMode::Generalized, csm::SplitScheme::Log, 8));
  EXPECT_EQ(h.status, csm::Status::InvalidInput);
  EXPECT_TRUE(h.cascades.empty());
  EXPECT_NE(h.message.find("1e50"), std::string::npos) << h.message;
}

// The warp and the focus alone (the steps computeShadowSetup composes).
TEST(Steps, WarpMatrixIsOrthographicOrACentredPerspective)
{
  // Orthographic: s = ls x, t = ls z, depth = ls y (the light's direction of travel).
  const glm::dmat4 ortho = csm::warpMatrix(std::numeric_limits<double>::infinity(), 5.0);
  const glm::dvec4 p = ortho * glm::dvec4(1.0, 2.0, 3.0, 1.0);
  EXPECT_DOUBLE_EQ(p.x, 1.0);
  EXPECT_DOUBLE_EQ(p.y, 3.0);
  EXPECT_DOUBLE_EQ(p.z, 2.0);
  EXPECT_DOUBLE_EQ(p.w, 1.0);
  // Perspective centred n' = 4 before lsZMin = 5 (at ls z = 1): w is the distance from it, and
  // t / w = -1 / w runs from -1/4 at the body's near side toward 0.
  const glm::dmat4 warp = csm::warpMatrix(4.0, 5.0);
  const glm::dvec4 nearSide = warp * glm::dvec4(0.0, 0.0, 5.0, 1.0);
  const glm::dvec4 farSide = warp * glm::dvec4(2.0, 7.0, 9.0, 1.0);
  EXPECT_DOUBLE_EQ(nearSide.w, 4.0);
  EXPECT_DOUBLE_EQ(nearSide.y / nearSide.w, -0.25);
  EXPECT_DOUBLE_EQ(farSide.w, 8.0);
  EXPECT_DOUBLE_EQ(farSide.x / farSide.w, 0.25);
  EXPECT_DOUBLE_EQ(farSide.z / farSide.w, 7.0 / 8.0);
}

TEST(Steps, FocusMatrixTakesTheBoundsToTheUnitCube)
{
  const std::vector<glm::dvec3> points = { { -3.0, 1.0, 2.0 }, { 5.0, 4.0, 10.0 },
    { 1.0, 2.0, 6.0 } };
  const glm::dmat4 ortho = csm::warpMatrix(std::numeric_limits<double>::infinity(), 2.0);
  const glm::dmat4 clip = csm::focusMatrix(points, ortho) * ortho;
  glm::dvec3 lo(1e300), hi(-1e300);
  for (const glm::dvec3& p : points)
  {
    const glm::dvec4 h = clip * glm::dvec4(p, 1.0);
    lo = glm::min(lo, glm::dvec3(h) / h.w);
    hi = glm::max(hi, glm::dvec3(h) / h.w);
  }
  EXPECT_NEAR(lo.x, -1.0, 1e-12);
  EXPECT_NEAR(hi.x, 1.0, 1e-12);
  EXPECT_NEAR(lo.y, -1.0, 1e-12);
  EXPECT_NEAR(hi.y, 1.0, 1e-12);
  // Depth keeps 1 % of the range as room for the bias on each side: 2 / 1.02 of [-1, 1].
  EXPECT_NEAR(lo.z, -1.0 / 1.02, 1e-12);
  EXPECT_NEAR(hi.z, 1.0 / 1.02, 1e-12);
}

TEST(Steps, OrthographicMapsKeepTheirTexelGridWhileTheCameraTranslates)
{
  // A camera sliding sideways and forward over a fixed scene, orthographic cascades (no warp):
  // the maps keep their texel size (quantized width) and, snapped, their texel edges stay where
  // they were in the world, so shadow edges do not crawl. Without the snap they do.
  csm::Bounds scene;
  scene.wsMin = { -50.0, -1.0, -150.0 };
  scene.wsMax = { 50.0, 10.0, 10.0 };
  const glm::dvec3 light = glm::normalize(glm::dvec3(-0.4, -1.0, -0.3));
  auto ortho = settings(csm::WarpMode::None, csm::SplitScheme::Practical, 2);
  ortho.stableOrthographic = true;
  struct Frame
  {
    glm::dmat4 raw, snapped;
    int resolution;
  };
  std::vector<std::vector<Frame>> frames(2);
  for (int step = 0; step < 40; ++step)
  {
    csm::Camera cam = camera(1.0, 200.0, 40.0, 4.0 / 3.0);
    cam.wsPosition = { 0.37 * step, 5.0, -0.21 * step };
    cam.wsDirection = { 0.0, -0.2, -1.0 };
    const csm::ShadowSetup setup = csm::computeShadowSetup(cam, light, &scene, ortho, nullptr);
    ASSERT_EQ(setup.status, csm::Status::Ok);
    ASSERT_EQ(setup.cascades.size(), 2u);
    for (size_t c = 0; c < 2; ++c)
    {
      const csm::Cascade& cascade = setup.cascades[c];
      ASSERT_TRUE(std::isinf(cascade.nPrime));
      const int r = csm::resolutionForError(std::max(cascade.Mx, cascade.Mz), 600.0, 1.0, 64, 2048);
      const glm::dmat4 snapped = csm::snapToTexels(cascade.wsToClip, csm::MapSize(r));
      for (const glm::dvec3& p : cascade.wsBody) // still covers its body
      {
        const glm::dvec3 q = toNdc(snapped, p);
        EXPECT_LE(std::abs(q.x), 1.0 + 1e-9);
        EXPECT_LE(std::abs(q.y), 1.0 + 1e-9);
      }
      frames[c].push_back({ cascade.wsToClip, snapped, r });
    }
  }
  int sameSize = 0, compared = 0, rawAligned = 0;
  for (const auto& cascadeFrames : frames)
  {
    for (size_t i = 1; i < cascadeFrames.size(); ++i)
    {
      const Frame& a = cascadeFrames[i - 1];
      const Frame& b = cascadeFrames[i];
      ++compared;
      const bool same = a.resolution == b.resolution &&
        std::abs(a.snapped[0][0] - b.snapped[0][0]) < 1e-12 &&
        std::abs(a.snapped[1][1] - b.snapped[1][1]) < 1e-12 &&
        std::abs(a.snapped[2][0] - b.snapped[2][0]) < 1e-12;
      if (!same)
        continue;
      ++sameSize;
      // Same texel size: the offsets differ by whole texels (2 / R in clip units).
      const double texel = 2.0 / a.resolution;
      for (int row = 0; row < 2; ++row)
      {
        const double shift = (b.snapped[3][row] - a.snapped[3][row]) / texel;
        EXPECT_NEAR(shift, std::round(shift), 1e-6) << "frame " << i << " row " << row;
        const double rawShift = (b.raw[3][row] - a.raw[3][row]) / texel;
        rawAligned += std::abs(rawShift - std::round(rawShift)) < 1e-6;
      }
    }
  }
  std::printf("orthographic cascades: %d of %d consecutive frames keep their texel size; raw "
              "offsets on whole texels in %d of %d rows\n",
    sameSize, compared, rawAligned, 2 * sameSize);
  EXPECT_GE(sameSize, compared * 3 / 4);
  EXPECT_LT(rawAligned, sameSize); // without the snap, the grid slides
}

TEST(ShadowSetup, OrthographicMapsOfAFlatGroundKeepADepthRangeAboveTheRounding)
{
  // The passes' box over a ground, light straight down, unwarped cascades: the far cascades hold
  // only the ground (one light depth). Each map's depth range (2 over its depth row's length)
  // is at least kOrthographicDepthShare of the farthest body point's distance from the eye,
  // so that the default constant bias (0.002 of the range, in [0, 1]) is a hundred times the
  // float rounding of a position at that distance (6e-8 of it); the body stays in the map.
  csm::Camera cam = camera(4.0, 40.0, 30.0, 4.0 / 3.0);
  cam.wsPosition = { 0.0, 14.0, 16.0 };
  cam.wsDirection = -cam.wsPosition;
  csm::Bounds scene, ground, box;
  ground.wsMin = { -10.0, 0.0, -10.0 };
  ground.wsMax = { 10.0, 0.0, 10.0 };
  box.wsMin = { -1.0, 2.0, -1.0 };
  box.wsMax = { 1.0, 4.0, 1.0 };
  scene.wsMin = ground.wsMin;
  scene.wsMax = { 10.0, 4.0, 10.0 };
  const std::vector<csm::Bounds> parts{ ground, box };
  for (int k : { 2, 4, 8 })
  {
    auto s = settings(csm::WarpMode::None, csm::SplitScheme::Log, k);
    s.stableOrthographic = true;
    const csm::ShadowSetup setup =
      csm::computeShadowSetup(cam, glm::dvec3(0.0, -1.0, 0.0), &scene, s, &parts);
    ASSERT_EQ(setup.status, csm::Status::Ok);
    ASSERT_GE(setup.cascades.size(), 2u);
    expectBodyInUnitCube(setup);
    for (const csm::Cascade& c : setup.cascades)
    {
      ASSERT_TRUE(std::isinf(c.nPrime));
      double eyeDistance = 0.0;
      for (const glm::dvec3& p : c.wsBody)
        eyeDistance = std::max(eyeDistance, glm::length(p - cam.wsPosition));
      const glm::dvec3 depthRow(c.wsToClip[0][2], c.wsToClip[1][2], c.wsToClip[2][2]);
      const double range = 2.0 / glm::length(depthRow);
      EXPECT_GE(range, csm::kOrthographicDepthShare * eyeDistance) << k;
      EXPECT_GT(0.002 * range, 100.0 * 6e-8 * eyeDistance) << k;
    }
  }
  // The floor: the larger scale, none for values that are not finite.
  EXPECT_DOUBLE_EQ(csm::orthographicDepthFloor(10.0, 50.0), csm::kOrthographicDepthShare * 50.0);
  EXPECT_DOUBLE_EQ(csm::orthographicDepthFloor(10.0, 0.0), csm::kOrthographicDepthShare * 10.0);
  EXPECT_EQ(csm::orthographicDepthFloor(std::nan(""), 1.0), 0.0);
  // A map whose depth range is wider keeps it: the box over the ground seen straight from above
  // in one cascade spans the box's height, more than the floor.
  const csm::ShadowSetup one = csm::computeShadowSetup(cam, glm::dvec3(0.0, -1.0, 0.0), &scene,
    settings(csm::WarpMode::None, csm::SplitScheme::Single, 1), nullptr);
  ASSERT_EQ(one.cascades.size(), 1u);
  const glm::dvec3 depthRow(
    one.cascades[0].wsToClip[0][2], one.cascades[0].wsToClip[1][2], one.cascades[0].wsToClip[2][2]);
  EXPECT_NEAR(2.0 / glm::length(depthRow), 4.0 * 1.02, 1e-3); // 1 % of room each side
}
