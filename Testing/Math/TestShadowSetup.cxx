// SPDX-License-Identifier: BSD-3-Clause
// Light space, body B, per-cascade matrices and the aliasing error of 003.
#include "csmShadowSetup.h"
#include "csmReuse.h"
#include "csmMathTestHelpers.h"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <cstdio>
#include <vector>

namespace
{
constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;

using csmMathTest::camera; // eye at the origin looking down -z, up +y

// gammaDeg: 0 light from behind, 90 overhead, 180 facing.
glm::dvec3 lightAt(const csm::Camera& c, double gammaDeg)
{
  const glm::dvec3 v = glm::normalize(c.wsDirection);
  const glm::dvec3 up = glm::normalize(c.wsViewUp);
  return std::cos(gammaDeg * kDeg) * v - std::sin(gammaDeg * kDeg) * up;
}

csm::Settings settings(csm::WarpMode warp, csm::SplitScheme scheme, int k)
{
  csm::Settings s;
  s.warp = warp;
  s.split.scheme = scheme;
  s.split.k = k;
  return s;
}

bool finite(const glm::dmat4& m)
{
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r]))
        return false;
  return true;
}

glm::dvec3 toNdc(const glm::dmat4& m, const glm::dvec3& p)
{
  const glm::dvec4 h = m * glm::dvec4(p, 1.0);
  return glm::dvec3(h) / h.w;
}

void expectBodyInUnitCube(const csm::ShadowSetup& setup, double tolerance = 1e-9)
{
  for (const csm::Cascade& c : setup.cascades)
  {
    ASSERT_FALSE(c.wsBody.empty());
    for (const glm::dvec3& p : c.wsBody)
    {
      const glm::dvec4 h = c.wsToClip * glm::dvec4(p, 1.0);
      ASSERT_GT(h.w, 0.0);
      const glm::dvec3 q = glm::dvec3(h) / h.w;
      for (int i = 0; i < 3; ++i)
      {
        EXPECT_LE(std::abs(q[i]), 1.0 + tolerance) << "axis " << i;
      }
    }
  }
}

void expectAllFinite(const csm::ShadowSetup& setup)
{
  EXPECT_TRUE(std::isfinite(setup.gammaDeg));
  EXPECT_TRUE(std::isfinite(setup.gammaLimDeg));
  for (double s : setup.splits)
    EXPECT_TRUE(std::isfinite(s));
  for (const csm::Cascade& c : setup.cascades)
  {
    EXPECT_TRUE(finite(c.wsToClip));
    EXPECT_TRUE(std::isfinite(c.Mx) && std::isfinite(c.Mz) && std::isfinite(c.storage));
    EXPECT_TRUE(std::isfinite(c.vsNear) && std::isfinite(c.vsFar));
    EXPECT_FALSE(std::isnan(c.nPrime));
  }
  EXPECT_TRUE(std::isfinite(setup.storageTotal));
  EXPECT_TRUE(std::isfinite(setup.storageOptimal));
}
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

// Lloyd et al. 2006, Eq. 7-10 with n = 1 (the form the paper prints): maxima of m_x, m_z for one LiSPSM map.
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
    EXPECT_NEAR(setup.cascades[0].Mx, f * np / fp, 1e-9);                           // Eq. 9
    EXPECT_NEAR(setup.cascades[0].Mz, n * (f - n) / (2 * tanTheta) * fp / (np * f), 1e-9); // Eq. 10
  }
}

TEST(StorageFactor, NonSquareImageKeepsOverheadStorage)
{
  const double tanTheta = std::tan(20.0 * kDeg);
  const csm::Camera cam = camera(1.0, 1000.0, 40.0, 800.0 / 300.0);
  const csm::ShadowSetup setup = csm::computeShadowSetup(cam, lightAt(cam, 90.0), nullptr,
    settings(csm::WarpMode::LiSPSM, csm::SplitScheme::Log, 3));
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
// where it fades to orthographic (Barroso & Celes 2007, Eq. 16-18), its worst error stays within 10% of it.
TEST(StorageFactor, GeneralizedAgainstUniform)
{
  const csm::Camera cam = camera(1.0, 1000.0, 60.0);
  for (double g = 0.0; g <= 180.0; g += 5.0)
  {
    const auto none = csm::computeShadowSetup(cam, lightAt(cam, g), nullptr,
      settings(csm::WarpMode::None, csm::SplitScheme::Log, 2));
    const auto gen = csm::computeShadowSetup(cam, lightAt(cam, g), nullptr,
      settings(csm::WarpMode::Generalized, csm::SplitScheme::Log, 2));
    const double folded = std::min(g, 180.0 - g);
    if (folded >= 35.0)
    {
      EXPECT_LT(gen.storageTotal, 0.8 * none.storageTotal) << "gamma " << g;
    }
    EXPECT_LE(gen.storageTotal, 1.1 * none.storageTotal) << "gamma " << g;
  }
  const auto overheadNone = csm::computeShadowSetup(cam, lightAt(cam, 90.0), nullptr,
    settings(csm::WarpMode::None, csm::SplitScheme::Log, 2));
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
  for (auto warp : { csm::WarpMode::None, csm::WarpMode::PSM, csm::WarpMode::LiSPSM,
         csm::WarpMode::Generalized })
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

TEST(Body, BoxCulling)
{
  const csm::Camera cam = camera(1.0, 100.0, 60.0);
  const auto setup = csm::computeShadowSetup(cam, lightAt(cam, 90.0), nullptr,
    settings(csm::WarpMode::Generalized, csm::SplitScheme::Log, 2));
  ASSERT_EQ(setup.cascades.size(), 2u);
  const glm::dmat4& nearMap = setup.cascades[0].wsToClip;
  csm::Bounds inside{ { -0.5, -0.5, -5.5 }, { 0.5, 0.5, -4.5 } };
  csm::Bounds far{ { -0.5, -0.5, -90 }, { 0.5, 0.5, -80 } };
  csm::Bounds above{ { -0.5, 50, -5.5 }, { 0.5, 60, -4.5 } }; // toward the light: a caster
  csm::Bounds below{ { -0.5, -60, -5.5 }, { 0.5, -50, -4.5 } };
  EXPECT_FALSE(csm::boxOutsideClipVolume(nearMap, inside, true));
  EXPECT_TRUE(csm::boxOutsideClipVolume(nearMap, far, true));
  EXPECT_FALSE(csm::boxOutsideClipVolume(nearMap, above, true));
  EXPECT_TRUE(csm::boxOutsideClipVolume(nearMap, above, false));
  EXPECT_TRUE(csm::boxOutsideClipVolume(nearMap, below, true));
  EXPECT_TRUE(csm::boxOutsideClipVolume(nearMap, csm::Bounds{}, true));
}

// A caster shadows only what lies beyond it along the light.
TEST(Body, SweptBoxReachesWhatLiesBehindItAlongTheLight)
{
  const csm::Bounds ground{ { -100, -0.5, -100 }, { 100, 0, 100 } };
  const csm::Bounds tower{ { -2, 0, -2 }, { 2, 30, 2 } }; // stands on the ground
  const csm::Bounds buried{ { -2, -0.4, -2 }, { 2, -0.2, 2 } }; // inside the slab
  const csm::Bounds sheet{ { -5, 0, -5 }, { 5, 0, 5 } };       // flat, on the ground's top
  const csm::Bounds beside{ { 150, -0.3, -1 }, { 160, 5, 1 } }; // beside the slab
  const double eps = 1e-6;
  const glm::dvec3 down(0.3, -1.0, 0.2), up(0.3, 1.0, 0.2), sideways(1.0, 0.0, 0.0);
  // Light from above: the ground shadows nothing standing on it, but what lies inside it.
  EXPECT_FALSE(csm::sweptBoxReachesBox(ground, down, tower, eps));
  EXPECT_FALSE(csm::sweptBoxReachesBox(ground, down, sheet, eps));
  EXPECT_TRUE(csm::sweptBoxReachesBox(ground, down, buried, eps));
  EXPECT_TRUE(csm::sweptBoxReachesBox(tower, down, ground, eps));
  // Light from below: the ground shadows the tower, the tower not the ground.
  EXPECT_TRUE(csm::sweptBoxReachesBox(ground, up, tower, eps));
  EXPECT_FALSE(csm::sweptBoxReachesBox(tower, up, ground, eps));
  // Light along +x, level: the slab reaches the box beside it, not one behind the light.
  EXPECT_TRUE(csm::sweptBoxReachesBox(ground, sideways, beside, eps));
  EXPECT_FALSE(csm::sweptBoxReachesBox(ground, -sideways, beside, eps));
  const csm::Bounds lifted{ { 50, 0.1, -2 }, { 60, 30, 2 } };
  EXPECT_FALSE(csm::sweptBoxReachesBox(ground, sideways, lifted, eps)); // its y > the slab's
  EXPECT_TRUE(csm::sweptBoxReachesBox(ground, sideways, tower, eps));   // touching: conservative
  // Far from the origin: the same answers.
  const glm::dvec3 far(3.0e6, 1.0e5, -4.0e6);
  const auto moved = [&](const csm::Bounds& b) { return csm::Bounds{ b.wsMin + far, b.wsMax + far }; };
  EXPECT_FALSE(csm::sweptBoxReachesBox(moved(ground), down, moved(tower), 1e-3));
  EXPECT_TRUE(csm::sweptBoxReachesBox(moved(ground), up, moved(tower), 1e-3));
  // Bad input: the safe answer (draw the caster).
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(csm::sweptBoxReachesBox(ground, glm::dvec3(0.0), tower, eps));
  EXPECT_TRUE(csm::sweptBoxReachesBox(ground, glm::dvec3(nan, -1, 0), tower, eps));
  EXPECT_TRUE(csm::sweptBoxReachesBox(csm::Bounds{}, down, tower, eps));
  EXPECT_TRUE(csm::sweptBoxReachesBox(ground, down, csm::Bounds{ { nan, 0, 0 }, { 1, 1, 1 } }, eps));
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
      for (double g : { 0.0, 1e-12, 1e-6, limitDeg - 1e-9, limitDeg + 1e-9, 90.0, 180.0,
             180.0 - 1e-12 })
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
    const auto setup = csm::computeShadowSetup(cam, lightAt(cam, g), &scene,
      settings(csm::WarpMode::Generalized, csm::SplitScheme::Log, 2));
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
  auto expectInvalid = [&](const csm::Camera& c, glm::dvec3 light, const csm::Settings& st) {
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
  EXPECT_EQ(csm::computeShadowSetup(cam, { 0, -1, 0 }, &infinite, s).status,
    csm::Status::InvalidInput);
  // View-up parallel to the view direction still gives a valid frame.
  bad = cam;
  bad.wsViewUp = bad.wsDirection;
  EXPECT_EQ(csm::computeShadowSetup(bad, { 0, -1, 0 }, nullptr, s).status, csm::Status::Ok);
}

TEST(Spot, FitsTheLitVisibleScene)
{
  csm::Bounds scene{ { -20, 0, -60 }, { 20, 10, 0 } };
  csm::Camera cam = camera(0.5, 1000.0, 45.0, 4.0 / 3.0);
  cam.wsPosition = { 0, 8, 20 };
  const glm::dvec3 lightPos(5, 40, -20);
  for (bool clamp : { true, false })
  {
    const auto setup = csm::computeSpotSetup(cam, lightPos, { 0, -1, 0 }, 30.0, &scene, clamp);
    ASSERT_EQ(setup.status, csm::Status::Ok) << setup.message;
    ASSERT_EQ(setup.cascades.size(), 1u);
    expectBodyInUnitCube(setup, 1e-9);
    EXPECT_TRUE(finite(setup.cascades[0].wsToClip));
    // A point on the floor under the light maps inside the map, behind a caster above it.
    const glm::dvec3 floor = toNdc(setup.cascades[0].wsToClip, { 5, 0, -20 });
    const glm::dvec3 caster = toNdc(setup.cascades[0].wsToClip, { 5, 9, -20 });
    EXPECT_NEAR(floor.x, caster.x, 1e-9);
    EXPECT_NEAR(floor.y, caster.y, 1e-9);
    EXPECT_LT(caster.z, floor.z);
    EXPECT_LE(std::abs(floor.x), 1.0);
    // The map covers only what the cone lights: the window is narrower than the cone.
    const glm::dvec3 edge = toNdc(setup.cascades[0].wsToClip, { 5 + 40 * std::tan(30 * kDeg), 0, -20 });
    EXPECT_GT(std::max(std::abs(edge.x), std::abs(edge.y)), 1.0 - 1e-9);
  }
  // Bad cone, NaN position, a cone that misses the view.
  EXPECT_EQ(csm::computeSpotSetup(cam, lightPos, { 0, -1, 0 }, 95.0, &scene, true).status,
    csm::Status::InvalidInput);
  EXPECT_EQ(csm::computeSpotSetup(cam, { NAN, 0, 0 }, { 0, -1, 0 }, 30.0, &scene, true).status,
    csm::Status::InvalidInput);
  EXPECT_EQ(csm::computeSpotSetup(cam, lightPos, { 0, 1, 0 }, 30.0, &scene, true).status,
    csm::Status::NothingToShadow);
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

// Issue 9 (7): near 1e-10, far 1e10 gave storage 3e-12 .. 3e-22 for the first log cascades (a
// clipping tolerance relative to the far distance swallowed them); near 1e-300, far 1e300 gave
// "ok" with null split depths. Log cascades are self-similar: every one has the same storage.
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
  const auto h = csm::computeShadowSetup(
    huge, lightAt(huge, 90.0), nullptr, settings(csm::WarpMode::Generalized, csm::SplitScheme::Log, 8));
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

TEST(Steps, ResolutionForErrorMeetsTheTargetWithTheFewestTexels)
{
  // A plan's worst cascade error M (per texel and pixel) at the resolution chosen for m <= 1 in a
  // 600-pixel image: the error at every body vertex is at most 1, and one step fewer texels
  // would not reach it.
  const csm::Camera cam = camera(1.0, 200.0, 40.0, 4.0 / 3.0);
  const glm::dvec3 light = lightAt(cam, 60.0);
  const csm::ShadowSetup setup = csm::computeShadowSetup(
    cam, light, nullptr, settings(csm::WarpMode::Generalized, csm::SplitScheme::Adaptive, 2));
  ASSERT_EQ(setup.status, csm::Status::Ok);
  for (const csm::Cascade& c : setup.cascades)
  {
    const double M = std::max(c.Mx, c.Mz);
    const int res = csm::resolutionForError(M, 600.0, 1.0, 64, 8192);
    EXPECT_EQ(res % 64, 0);
    EXPECT_LT(res, 8192) << "this view needs fewer texels than the ceiling";
    double worst = 0.0;
    for (const glm::dvec3& p : c.wsBody)
    {
      const csm::Aliasing a = csm::aliasingAt(c.wsToClip, cam, light, p);
      worst = std::max({ worst, a.mx, a.mz });
    }
    EXPECT_NEAR(worst, M, 1e-9 * M);
    EXPECT_LE(worst * 600.0 / res, 1.0);
    EXPECT_GT(worst * 600.0 / (res - 64), 1.0);
  }
  // The ceiling where the error is undefined or not asked for, the step at the least.
  EXPECT_EQ(csm::resolutionForError(1e9, 600.0, 1.0, 64, 2048), 2048);
  EXPECT_EQ(csm::resolutionForError(std::nan(""), 600.0, 1.0, 64, 2048), 2048);
  EXPECT_EQ(csm::resolutionForError(0.0, 600.0, 1.0, 64, 2048), 2048);
  EXPECT_EQ(csm::resolutionForError(2.0, 600.0, 0.0, 64, 2048), 2048);
  EXPECT_EQ(csm::resolutionForError(2.0, 600.0, std::nan(""), 64, 2048), 2048);
  EXPECT_EQ(csm::resolutionForError(1e-6, 600.0, 1.0, 64, 2048), 64);
  EXPECT_EQ(csm::resolutionForError(2.0, 600.0, 1.0, 64, 2048), 1216); // 1200 rounded up
  EXPECT_EQ(csm::resolutionForError(2.0, 600.0, 2.0, 64, 2048), 640);  // 600 rounded up
}

TEST(Steps, EachCountTakesTheBetterOfEq19AndTheLogSplits)
{
  // With the light along the view over a long range, Eq. 19 (Barroso & Celes 2007) leaves the
  // first partition most of the range and no warp helps; the log splits then predict a far
  // smaller worst error, and the per-frame planner takes them. Elsewhere it takes the better of
  // the two, never worse than Eq. 19 alone.
  auto up4 = settings(csm::WarpMode::Generalized, csm::SplitScheme::Adaptive, 4);
  auto log4 = settings(csm::WarpMode::Generalized, csm::SplitScheme::Log, 4);
  for (double ratio : { 20.0, 1200.0, 1.0e4 })
  {
    const csm::Camera view = camera(5.0, 5.0 * ratio, 50.0, 4.0 / 3.0);
    for (double gamma : { 0.0, 10.0, 30.0, 45.0, 60.0, 90.0, 150.0, 180.0 })
    {
      const glm::dvec3 light = lightAt(view, gamma);
      const csm::ShadowSetup chosen = csm::computeShadowSetupForError(
        view, light, nullptr, up4, nullptr, 600.0, 2048, 1e-9, 0); // unreachable
      ASSERT_EQ(chosen.status, csm::Status::Ok);
      auto eq19Settings = up4, logSettings = log4; // at the count chosen
      eq19Settings.split.k = logSettings.split.k = static_cast<int>(chosen.cascades.size());
      const double eq19 = csm::predictedError(
        csm::computeShadowSetup(view, light, nullptr, eq19Settings, nullptr), 600.0, 2048);
      const double logSplits = csm::predictedError(
        csm::computeShadowSetup(view, light, nullptr, logSettings, nullptr), 600.0, 2048);
      const double e = csm::predictedError(chosen, 600.0, 2048);
      EXPECT_NEAR(e / std::min(eq19, logSplits), 1.0, 1e-12) << "f/n " << ratio << " gamma " << gamma;
      if (ratio >= 1200.0 && gamma == 0.0)
      {
        EXPECT_EQ(chosen.cascades.size(), 4u); // every step cuts the error here
        EXPECT_LT(e, 0.1 * eq19) << "f/n " << ratio; // 7.8 against 200 at f/n 1200 (Mx)
      }
    }
  }
}

TEST(Steps, CascadeCountFromTheErrorModel)
{
  // Lloyd et al. 2006: the storage factor grows with f/n and toward parallel light and view.
  // With an error target of 1.5 texels a pixel, a 600-pixel image and 2048-texel maps: a short
  // view (f/n = 10) with the light overhead needs one cascade; a 1:10^4 view with the light
  // behind the viewer more than two (none of up to 8 reaches the target: the most are taken).
  const auto settingsUpTo8 = settings(csm::WarpMode::Generalized, csm::SplitScheme::Adaptive, 8);
  const csm::Camera shortView = camera(1.0, 10.0, 40.0, 4.0 / 3.0);
  const csm::ShadowSetup overhead = csm::computeShadowSetupForError(
    shortView, lightAt(shortView, 90.0), nullptr, settingsUpTo8, nullptr, 600.0, 2048, 1.5, 0);
  ASSERT_EQ(overhead.status, csm::Status::Ok);
  EXPECT_EQ(overhead.cascades.size(), 1u);
  EXPECT_LE(csm::predictedError(overhead, 600.0, 2048), 1.5);
  const csm::Camera longView = camera(1.0, 1.0e4, 40.0, 4.0 / 3.0);
  const csm::ShadowSetup behind = csm::computeShadowSetupForError(
    longView, lightAt(longView, 0.0), nullptr, settingsUpTo8, nullptr, 600.0, 2048, 1.5, 0);
  ASSERT_EQ(behind.status, csm::Status::Ok);
  EXPECT_GT(behind.cascades.size(), 2u);
  // The count is the smallest that meets the target: one fewer does not (f/n = 100, behind).
  const csm::Camera midView = camera(1.0, 100.0, 40.0, 4.0 / 3.0);
  const csm::ShadowSetup enough = csm::computeShadowSetupForError(
    midView, lightAt(midView, 0.0), nullptr, settingsUpTo8, nullptr, 600.0, 2048, 1.5, 0);
  ASSERT_EQ(enough.status, csm::Status::Ok);
  auto fewer = settingsUpTo8;
  fewer.split.k = static_cast<int>(enough.cascades.size()) - 1;
  const csm::ShadowSetup oneFewer =
    csm::computeShadowSetup(midView, lightAt(midView, 0.0), nullptr, fewer, nullptr);
  EXPECT_GT(enough.cascades.size(), 2u);
  EXPECT_LE(csm::predictedError(enough, 600.0, 2048), 1.5);
  EXPECT_GT(csm::predictedError(oneFewer, 600.0,
              csm::ceilingsForCount(fewer.split.k, 8, 2048)),
    1.5);
  std::printf("cascades: overhead f/n 10: %zu (error %.3f); behind f/n 100: %zu (error %.3f, "
              "with one fewer %.3f); behind f/n 1e4: %zu (error %.1f)\n",
    overhead.cascades.size(), csm::predictedError(overhead, 600.0, 2048), enough.cascades.size(),
    csm::predictedError(enough, 600.0, 2048), csm::predictedError(oneFewer, 600.0, 2048),
    behind.cascades.size(), csm::predictedError(behind, 600.0, 2048));
  // None meets an unreachable target: more cascades as long as each cuts the worst error to
  // kCountHysteresis of the best fewer reach, each judged at the resolution the atlas gives its
  // count (beyond four cascades, less than 2048). Along a 1:10^4 view that is more than four,
  // and the next count would not cut the error by the margin.
  const csm::ShadowSetup most = csm::computeShadowSetupForError(
    longView, lightAt(longView, 0.0), nullptr, settingsUpTo8, nullptr, 600.0, 2048, 1e-6, 0);
  const int kMost = static_cast<int>(most.cascades.size());
  EXPECT_GT(kMost, 4);
  auto errorAt = [&](int k) {
    auto s = settingsUpTo8;
    s.split.k = k;
    return csm::predictedError(
      csm::computeShadowSetupForError(longView, lightAt(longView, 0.0), nullptr, s, nullptr, 600.0,
        2048, 1e-6, 0),
      600.0, csm::ceilingsForCount(k, 8, 2048));
  };
  const double eMost = csm::predictedError(most, 600.0, csm::ceilingsForCount(kMost, 8, 2048));
  EXPECT_LT(eMost, csm::kCountHysteresis * errorAt(4));
  if (kMost < 8)
  {
    auto next = settingsUpTo8;
    next.split.k = kMost + 1;
    const double eNext = csm::predictedError(
      csm::computeShadowSetupForCount(longView, lightAt(longView, 0.0), nullptr, next, nullptr,
        kMost + 1, csm::ceilingsForCount(kMost + 1, 8, 2048)),
      600.0, csm::ceilingsForCount(kMost + 1, 8, 2048));
    EXPECT_GE(eNext, csm::kCountHysteresis * eMost);
  }
  std::printf("unreachable target, f/n 1e4, light behind: %d cascades (error %.2f; four: %.2f)\n",
    kMost, eMost, errorAt(4));
  // A previous count within 1 / kCountHysteresis of that error stays.
  if (kMost > 1)
  {
    auto fewer = settingsUpTo8;
    fewer.split.k = kMost - 1;
    const double eFewer = csm::predictedError(
      csm::computeShadowSetupForCount(longView, lightAt(longView, 0.0), nullptr, fewer, nullptr,
        kMost - 1, csm::ceilingsForCount(kMost - 1, 8, 2048)),
      600.0, csm::ceilingsForCount(kMost - 1, 8, 2048));
    const csm::ShadowSetup kept = csm::computeShadowSetupForError(longView,
      lightAt(longView, 0.0), nullptr, settingsUpTo8, nullptr, 600.0, 2048, 1e-6, kMost - 1);
    EXPECT_EQ(kept.cascades.size(),
      static_cast<size_t>(eFewer * csm::kCountHysteresis <= eMost ? kMost - 1 : kMost));
  }
  // Hysteresis: where one cascade meets the target only within the margin, a previous count of
  // two that meets it stays; without a previous count, one is taken.
  const csm::Camera mid = camera(1.0, 100.0, 40.0, 4.0 / 3.0);
  const glm::dvec3 light = lightAt(mid, 60.0);
  auto one = settingsUpTo8;
  one.split.k = 1;
  auto two = settingsUpTo8;
  two.split.k = 2;
  // (Each on the map its count gets: two tiles in a row, a full map each.)
  ASSERT_EQ(csm::ceilingsForCount(1, 2, 2048).following, csm::MapSize(2048));
  ASSERT_EQ(csm::ceilingsForCount(1, 2, 2048).sceneFitted, csm::MapSize(2048));
  const double e1 = csm::predictedError(csm::computeShadowSetup(mid, light, nullptr, one, nullptr),
    1000.0, csm::ceilingsForCount(1, 2, 2048));
  const double e2 = csm::predictedError(csm::computeShadowSetup(mid, light, nullptr, two, nullptr),
    1000.0, csm::ceilingsForCount(2, 2, 2048));
  ASSERT_LT(e2, e1);
  const double target = e1 / 0.9; // one cascade meets it, not by the hysteresis margin
  EXPECT_EQ(csm::computeShadowSetupForError(mid, light, nullptr, two, nullptr, 1000.0, 2048,
              target, 0).cascades.size(), 1u);
  EXPECT_EQ(csm::computeShadowSetupForError(mid, light, nullptr, two, nullptr, 1000.0, 2048,
              target, 2).cascades.size(), 2u);
  EXPECT_EQ(csm::computeShadowSetupForError(mid, light, nullptr, two, nullptr, 1000.0, 2048,
              e1 / 0.7, 2).cascades.size(), 1u);
  // Bad input: the same message as a plain plan, no cascades.
  const csm::ShadowSetup bad = csm::computeShadowSetupForError(mid,
    glm::dvec3(std::nan(""), 1.0, 0.0), nullptr, two, nullptr, 1000.0, 2048, 1.0, 0);
  EXPECT_EQ(bad.status, csm::Status::InvalidInput);
  EXPECT_TRUE(bad.cascades.empty());
}

// Of the counts that meet the target, the one that costs least: each cascade's caster pass (all
// the casters' cells, kTexelsPerCasterTriangle texels a cell) plus the texels its maps need.
// Without casters, the fewest cascades. Hysteresis keeps a previous count that meets the target
// unless another costs at most 0.8 of it.
TEST(Steps, CascadeCountWeighsCasterPassesAgainstTexels)
{
  const auto upTo4 = settings(csm::WarpMode::Generalized, csm::SplitScheme::Adaptive, 4);
  const csm::Camera view = camera(1.0, 300.0, 40.0, 4.0 / 3.0);
  const glm::dvec3 light = lightAt(view, 50.0);
  const double height = 600.0;
  std::vector<csm::ShadowSetup> plans(5);
  std::vector<double> error(5), texels(5);
  for (int k = 1; k <= 4; ++k)
  {
    const csm::MapSize ceiling = csm::ceilingsForCount(k, 4, 2048).following;
    plans[k] = csm::computeShadowSetupForCount(view, light, nullptr, upTo4, nullptr, k, ceiling);
    ASSERT_EQ(plans[k].status, csm::Status::Ok);
    ASSERT_EQ(plans[k].cascades.size(), static_cast<size_t>(k));
    error[k] = csm::predictedError(plans[k], height, ceiling);
  }
  // A target every count meets.
  const double target = 1.01 * *std::max_element(error.begin() + 1, error.end());
  for (int k = 1; k <= 4; ++k)
  {
    const csm::MapSize ceiling = csm::ceilingsForCount(k, 4, 2048).following;
    texels[k] = csm::texelsForError(plans[k], height, target, ceiling);
    // Each map's texels: max(Mx, Mz) H / target a side, within the ceiling.
    double sum = 0.0;
    for (const csm::Cascade& c : plans[k].cascades)
    {
      const double side = std::min<double>(ceiling.width, std::max(c.Mx, c.Mz) * height / target);
      sum += side * side;
    }
    EXPECT_NEAR(texels[k], sum, 1e-6 * sum) << k;
    EXPECT_LE(texels[k], k * double(ceiling.width) * ceiling.height) << k;
  }
  std::printf("error at the count's ceiling: %.3f %.3f %.3f %.3f; texels for %.3f: %.0f %.0f "
              "%.0f %.0f\n",
    error[1], error[2], error[3], error[4], target, texels[1], texels[2], texels[3], texels[4]);
  ASSERT_GT(texels[1], texels[4]); // more cascades need fewer texels here
  auto countFor = [&](const std::vector<csm::CasterLoad>* casters, int previous = 0) {
    return static_cast<int>(csm::computeShadowSetupForError(view, light, nullptr, upTo4, nullptr,
      height, 2048, target, previous, casters)
                              .cascades.size());
  };
  auto cheapest = [&](const std::vector<csm::CasterLoad>& casters) {
    int best = 1;
    double bestCost = 0.0;
    for (int k = 1; k <= 4; ++k)
    {
      const double cost = csm::passTexels(plans[k], casters) + texels[k];
      if (k == 1 || cost < bestCost)
      {
        best = k;
        bestCost = cost;
      }
    }
    return best;
  };
  EXPECT_EQ(countFor(nullptr), 1); // without casters: the fewest
  // k passes of the casters' cells.
  const csm::Bounds around{ glm::dvec3(-400.0), glm::dvec3(400.0) };
  std::vector<int> seen;
  for (double cells : { 0.0, 1e3, 1e4, 3e4, 1e5, 3e5, 1e10 })
  {
    const std::vector<csm::CasterLoad> casters{ { around, cells } };
    for (int k = 1; k <= 4; ++k)
    {
      EXPECT_DOUBLE_EQ(
        csm::passTexels(plans[k], casters), k * cells * csm::kTexelsPerCasterTriangle)
        << k;
    }
    EXPECT_EQ(countFor(&casters), cheapest(casters)) << cells;
    seen.push_back(countFor(&casters));
  }
  EXPECT_EQ(seen.front(), // no cells: the fewest texels
    static_cast<int>(std::min_element(texels.begin() + 1, texels.end()) - texels.begin()));
  EXPECT_EQ(seen.back(), 1); // passes that cost more than any texels: the fewest passes
  // Every pass counts all the casters (culling saves triangles, not the pass), wherever they
  // are; a scene-fitted cascade is drawn once: nothing.
  const glm::dvec3 far = view.wsPosition + 280.0 * glm::dvec3(0.0, 0.0, -1.0);
  const std::vector<csm::CasterLoad> two{ { csm::Bounds{ far - 5.0, far + 5.0 }, 1e5 },
    { around, 2e5 } };
  EXPECT_DOUBLE_EQ(csm::passTexels(plans[4], two), 4 * 3e5 * csm::kTexelsPerCasterTriangle);
  EXPECT_EQ(countFor(&two), cheapest(two));
  csm::ShadowSetup withFitted = plans[3];
  withFitted.cascades.back().sceneFitted = true;
  EXPECT_DOUBLE_EQ(csm::passTexels(withFitted, two), 2 * 3e5 * csm::kTexelsPerCasterTriangle);
  // Hysteresis: a previous count that costs less than 1 / 0.8 of the cheapest stays; one that
  // costs more gives way.
  const std::vector<csm::CasterLoad> casters{ { around, 6e4 } };
  const int best = cheapest(casters);
  auto costOf = [&](int k) { return csm::passTexels(plans[k], casters) + texels[k]; };
  for (int previous = 1; previous <= 4; ++previous)
  {
    const double ratio = costOf(previous) / costOf(best);
    EXPECT_EQ(countFor(&casters, previous), ratio * csm::kCountHysteresis <= 1.0 ? previous : best)
      << previous << " (cost ratio " << ratio << ")";
  }
  // No texels for a plan without cascades or a target that is not positive.
  EXPECT_TRUE(std::isinf(csm::texelsForError(csm::ShadowSetup(), height, 1.0, 2048)));
  EXPECT_TRUE(std::isinf(csm::texelsForError(plans[1], height, 0.0, 2048)));
}

namespace
{
/// Light clip coordinates of a world point.
glm::dvec3 clipOf(const glm::dmat4& wsToClip, const glm::dvec3& p)
{
  const glm::dvec4 h = wsToClip * glm::dvec4(p, 1.0);
  return glm::dvec3(h) / h.w;
}

/// Inside the four half-spaces of a scene fit's extent across the light?
bool insidePrism(const csm::SceneFit& fit, const glm::dvec3& p, double tolerance)
{
  for (const csm::Plane& plane : fit.wsPrism)
  {
    if (glm::dot(plane.normal, p) + plane.offset < -tolerance)
    {
      return false;
    }
  }
  return true;
}
}

// A point is in shadow only if a caster lies toward the light from it: the scene-fitted map
// spans, across the light, the caster footprints over the receivers they can reach. A box over
// a wide ground: the box's footprint, not the ground's (the ground slab, convex, shadows
// nothing of itself); a ground that may shadow itself: all of it.
TEST(Steps, SceneFitSpansWhatCanBeInShadow)
{
  const csm::Bounds ground{ { -100.0, -0.1, -100.0 }, { 100.0, 0.0, 100.0 } };
  const csm::Bounds box{ { -1.0, 1.0, -1.0 }, { 1.0, 3.0, 1.0 } };
  const csm::Bounds scene{ ground.wsMin, glm::dvec3(100.0, 3.0, 100.0) };
  const std::vector<csm::Bounds> receivers{ ground, box };
  std::vector<csm::CasterLoad> casters{ { ground, 12.0, 0, false }, { box, 12.0, 1, false } };
  for (const glm::dvec3& light : { glm::dvec3(0.0, -1.0, 0.0), glm::dvec3(-0.5, -1.0, 0.2) })
  {
    csm::SceneFit fit;
    ASSERT_TRUE(csm::sceneFit(light, scene, casters, &receivers, fit));
    // The box's corners fill the map across the light (to its minimum margin).
    glm::dvec2 lo(1e300), hi(-1e300);
    for (int i = 0; i < 8; ++i)
    {
      const glm::dvec3 corner((i & 1) ? 1.0 : -1.0, (i & 2) ? 3.0 : 1.0, (i & 4) ? 1.0 : -1.0);
      const glm::dvec3 c = clipOf(fit.wsToClip, corner);
      lo = glm::min(lo, glm::dvec2(c));
      hi = glm::max(hi, glm::dvec2(c));
      EXPECT_TRUE(insidePrism(fit, corner, 1e-9));
      EXPECT_GE(c.z, -1.0 - 1e-9);
      EXPECT_LE(c.z, 1.0 + 1e-9);
    }
    // (The footprint of the box on the ground along an oblique light is the box's own
    // footprint across the light: its clip extent spans [-1, 1].)
    EXPECT_NEAR(lo.x, -1.0, 1e-3);
    EXPECT_NEAR(lo.y, -1.0, 1e-3);
    EXPECT_NEAR(hi.x, 1.0, 1e-3);
    EXPECT_NEAR(hi.y, 1.0, 1e-3);
    // The ground far from the box is outside: nothing can shadow it.
    const glm::dvec3 far(60.0, 0.0, 60.0);
    const glm::dvec3 c = clipOf(fit.wsToClip, far);
    EXPECT_GT(std::max(std::abs(c.x), std::abs(c.y)), 10.0);
    EXPECT_FALSE(insidePrism(fit, far, 1e-9));
    // Its map axes are perpendicular to the light and to each other, fixed by the light alone.
    EXPECT_NEAR(glm::dot(fit.wsMapX, glm::normalize(light)), 0.0, 1e-12);
    EXPECT_NEAR(glm::dot(fit.wsMapZ, glm::normalize(light)), 0.0, 1e-12);
    EXPECT_NEAR(glm::dot(fit.wsMapX, fit.wsMapZ), 0.0, 1e-12);
  }
  // A ground that may shadow itself needs all of its footprint.
  casters[0].shadowsItself = true;
  csm::SceneFit all;
  ASSERT_TRUE(csm::sceneFit(glm::dvec3(0.0, -1.0, 0.0), scene, casters, &receivers, all));
  EXPECT_TRUE(insidePrism(all, glm::dvec3(60.0, 0.0, 60.0), 1e-9));
  EXPECT_NEAR(std::abs(clipOf(all.wsToClip, glm::dvec3(100.0, 0.0, 100.0)).x), 1.0, 1e-3);
  // Without receiver parts the scene box is the one receiver: the casters' footprints.
  csm::SceneFit noParts;
  ASSERT_TRUE(csm::sceneFit(glm::dvec3(0.0, -1.0, 0.0), scene, casters, nullptr, noParts));
  EXPECT_TRUE(insidePrism(noParts, glm::dvec3(60.0, 0.0, 60.0), 1e-9));
  // Nothing that can shadow, a screen-sized caster, a bad light: no fit (and it is unchanged).
  csm::SceneFit none;
  const glm::dmat4 before = none.wsToClip;
  EXPECT_FALSE(csm::sceneFit(glm::dvec3(0.0, -1.0, 0.0), scene, {}, &receivers, none));
  const std::vector<csm::CasterLoad> groundOnly{ { ground, 12.0, 0, false } };
  EXPECT_FALSE(csm::sceneFit(glm::dvec3(0.0, -1.0, 0.0), scene, groundOnly, &receivers, none));
  auto tubes = casters;
  tubes[1].screenSized = true;
  EXPECT_FALSE(csm::sceneFit(glm::dvec3(0.0, -1.0, 0.0), scene, tubes, &receivers, none));
  EXPECT_FALSE(
    csm::sceneFit(glm::dvec3(std::nan(""), -1.0, 0.0), scene, casters, &receivers, none));
  EXPECT_FALSE(csm::sceneFit(glm::dvec3(0.0), scene, casters, &receivers, none));
  EXPECT_EQ(none.wsToClip, before);
}

// Where the scene-fitted map meets the error target, the farthest cascade takes it: its matrix
// is the fit's whatever the view (so a map drawn for one view serves the next), its body is the
// partition's receivers within the fit, and its error is Lloyd's M over that body. A view that
// needs more gets the cascades that follow it.
TEST(Steps, SceneFittedCascadeServesEveryViewThatItMeets)
{
  const csm::Bounds ground{ { -100.0, -0.1, -100.0 }, { 100.0, 0.0, 100.0 } };
  const csm::Bounds box{ { -1.0, 1.0, -1.0 }, { 1.0, 3.0, 1.0 } };
  const csm::Bounds scene{ ground.wsMin, glm::dvec3(100.0, 3.0, 100.0) };
  const std::vector<csm::Bounds> receivers{ ground, box };
  const std::vector<csm::CasterLoad> casters{ { ground, 12.0, 0, false },
    { box, 12.0, 1, false } };
  const glm::dvec3 light(-0.3, -1.0, -0.2);
  csm::SceneFit fit;
  ASSERT_TRUE(csm::sceneFit(light, scene, casters, &receivers, fit));
  auto s = settings(csm::WarpMode::Generalized, csm::SplitScheme::Adaptive, 4);
  s.sceneFitted = true;
  auto orbit = [](double azimuthDeg, double distance) {
    csm::Camera c = camera(0.5, 400.0, 30.0, 4.0 / 3.0);
    const double a = azimuthDeg * 3.14159265358979323846 / 180.0;
    c.wsPosition = glm::dvec3(distance * std::sin(a), 0.5 * distance, distance * std::cos(a));
    c.wsDirection = glm::normalize(glm::dvec3(0.0, 2.0, 0.0) - c.wsPosition);
    c.wsViewUp = glm::dvec3(0.0, 1.0, 0.0);
    return c;
  };
  for (double azimuth : { 0.0, 40.0, 130.0, 250.0 })
  {
    const csm::Camera view = orbit(azimuth, 12.0);
    const csm::ShadowSetup plan = csm::computeShadowSetupForError(
      view, light, &scene, s, &receivers, 480.0, 2048, 1.0, 0, &casters);
    ASSERT_EQ(plan.status, csm::Status::Ok) << azimuth;
    ASSERT_FALSE(plan.cascades.empty());
    const csm::Cascade& last = plan.cascades.back();
    EXPECT_TRUE(last.sceneFitted) << azimuth;
    EXPECT_EQ(last.wsToClip, fit.wsToClip) << azimuth; // exactly: the same map for every view
    EXPECT_LE(csm::predictedError(plan, 480.0,
                csm::resolutionCeilingForCount(static_cast<int>(plan.cascades.size()), 4, 2048)),
      1.0);
    ASSERT_FALSE(last.wsBody.empty());
    double mx = 0.0, mz = 0.0;
    for (const glm::dvec3& p : last.wsBody)
    {
      EXPECT_TRUE(insidePrism(fit, p, 1e-6)) << azimuth;
      const csm::Aliasing m = csm::aliasingAt(fit.wsToClip, view, light, p);
      mx = std::max(mx, m.mx);
      mz = std::max(mz, m.mz);
    }
    EXPECT_DOUBLE_EQ(last.Mx, mx);
    EXPECT_DOUBLE_EQ(last.Mz, mz);
    // Its resolution is its tile's: drawn once, for every view.
    EXPECT_EQ(csm::resolutionForError(last, 480.0, 1.0, 64, csm::MapSize(2896)),
      csm::MapSize(2896));
  }
  // Close to the box with a tight target the fit does not meet it: the cascades follow the view.
  const csm::ShadowSetup close = csm::computeShadowSetupForError(
    orbit(30.0, 3.0), light, &scene, s, &receivers, 480.0, 256, 0.3, 0, &casters);
  ASSERT_EQ(close.status, csm::Status::Ok);
  EXPECT_FALSE(close.cascades.back().sceneFitted);
  // Off, or without casters: never.
  auto off = s;
  off.sceneFitted = false;
  const csm::Camera view = orbit(40.0, 12.0);
  EXPECT_FALSE(csm::computeShadowSetupForError(
    view, light, &scene, off, &receivers, 480.0, 2048, 1.0, 0, &casters)
                 .cascades.back()
                 .sceneFitted);
  EXPECT_FALSE(csm::computeShadowSetupForError(
    view, light, &scene, s, &receivers, 480.0, 2048, 1.0, 0, nullptr)
                 .cascades.back()
                 .sceneFitted);
}

TEST(Steps, CascadesShareOneAtlasOfFourFullMaps)
{
  // Two or three most cascades: a row of full-size tiles; four or more: 2 x 2 of them.
  const csm::AtlasGrid two = csm::atlasLayout(2, 2048);
  EXPECT_EQ(two.columns, 2);
  EXPECT_EQ(two.rows, 1);
  EXPECT_EQ(two.tile, csm::MapSize(2048));
  EXPECT_EQ(csm::atlasLayout(3, 2048).columns, 3);
  EXPECT_EQ(csm::atlasLayout(1, 2048).columns, 1);
  EXPECT_EQ(csm::atlasLayout(1, 2048).rows, 1);
  const csm::AtlasGrid six = csm::atlasLayout(6, 2048);
  EXPECT_EQ(six.columns, 2); // never more than four full maps' texels
  EXPECT_EQ(six.rows, 2);
  EXPECT_EQ(six.tile, csm::MapSize(2048));
  // One cascade gets the whole texture; more share it in the grid whose tiles have the longest
  // short side, none larger than a full map.
  const csm::MapSize expected[9] = { {}, { 4096, 4096 }, { 2048, 2048 }, { 2048, 2048 },
    { 2048, 2048 }, { 2048, 1365 }, { 2048, 1365 }, { 1365, 1365 }, { 1365, 1365 } };
  for (int k = 1; k <= 8; ++k)
  {
    const csm::AtlasGrid f = csm::atlasForCount(k, six);
    EXPECT_EQ(f.tile, expected[k]) << k << " cascades";
    EXPECT_GE(f.columns * f.rows, k);
    // Within the one texture of every count.
    EXPECT_LE(f.columns * f.tile.width, 2 * 2048) << k;
    EXPECT_LE(f.rows * f.tile.height, 2 * 2048) << k;
    if (k > 1)
    {
      EXPECT_EQ(csm::atlasGrid(k, six).tile, f.tile) << k;
    }
    EXPECT_EQ(csm::resolutionCeilingForCount(k, 6, 2048), f.tile);
    // A scene-fitted map gets its tile; one that follows the view at most 2048 a side.
    EXPECT_EQ(csm::ceilingsForCount(k, 6, 2048).sceneFitted, f.tile) << k;
    EXPECT_EQ(csm::ceilingsForCount(k, 6, 2048).following,
      csm::MapSize(std::min(f.tile.width, 2048), std::min(f.tile.height, 2048)))
      << k;
  }
  // Two most cascades in a row: one gets a full map.
  EXPECT_EQ(csm::resolutionCeilingForCount(1, 2, 2048), csm::MapSize(2048));
  EXPECT_EQ(csm::resolutionCeilingForCount(2, 2, 2048), csm::MapSize(2048));
  // A GL size limit: the tiles shrink to fit it.
  const csm::AtlasGrid limited = csm::atlasLayout(6, 4096, 4096);
  EXPECT_EQ(limited.tile, csm::MapSize(2048));
  EXPECT_EQ(csm::atlasForCount(1, limited).tile, csm::MapSize(4096));
  EXPECT_EQ(csm::atlasForCount(6, limited).tile, csm::MapSize(2048, 1365));
  EXPECT_EQ(csm::atlasLayout(3, 2048, 4096).tile, csm::MapSize(1365));
  EXPECT_EQ(csm::atlasForCount(0, six).tile, csm::MapSize(0));
  // 2 x 3 and 3 x 2 tie at 1365 texels on the short side and in area: fewer columns.
  EXPECT_EQ(csm::atlasGrid(6, six).columns, 2);
  EXPECT_EQ(csm::atlasGrid(8, six).columns, 3); // 3 x 3 of 1365 beats 2 x 4 of 2048 x 1024
  // A smaller ceiling (while interacting) shares its own budget; bad counts give nothing.
  EXPECT_EQ(csm::resolutionCeilingForCount(1, 6, 1024), csm::MapSize(2048));
  EXPECT_EQ(csm::resolutionCeilingForCount(4, 6, 1024), csm::MapSize(1024));
  EXPECT_EQ(csm::resolutionCeilingForCount(6, 6, 1024), csm::MapSize(1024, 682));
  EXPECT_EQ(csm::resolutionCeilingForCount(0, 6, 2048), csm::MapSize(0));
  EXPECT_EQ(csm::resolutionCeilingForCount(3, 6, 0), csm::MapSize(0));
  EXPECT_EQ(csm::atlasLayout(0, 2048).tile, csm::MapSize(0));
  EXPECT_EQ(csm::ceilingsForCount(0, 6, 2048).following, csm::MapSize(0));
  // More than the most planned: the atlas grows to hold them (a caller's safety, not a use).
  EXPECT_EQ(csm::resolutionCeilingForCount(3, 1, 2048), csm::MapSize(2048));
}

TEST(Steps, MapsTurnToTheirTilesWhereTheLongSideServesTheLargerError)
{
  // The light along a 4:3 view (gamma 0): no warp helps, and each map spans the frustum's
  // cross-section, a third wider than high, so its error along the image's width is the larger.
  const csm::Camera cam = camera(5.0, 6000.0, 50.0, 4.0 / 3.0);
  const glm::dvec3 light = lightAt(cam, 0.0);
  const csm::ShadowSetup plain =
    csm::computeShadowSetup(cam, light, nullptr, settings(csm::WarpMode::Generalized, csm::SplitScheme::Log, 5));
  ASSERT_EQ(plain.status, csm::Status::Ok);
  ASSERT_EQ(plain.cascades.size(), 5u);
  const csm::MapSize tile(1638, 2048); // a tall tile (five in a row of four full maps)
  csm::ShadowSetup turned = plain;
  csm::orientToTile(turned, tile);
  int turnedCount = 0;
  for (size_t i = 0; i < plain.cascades.size(); ++i)
  {
    const csm::Cascade& before = plain.cascades[i];
    const csm::Cascade& after = turned.cascades[i];
    EXPECT_FALSE(before.mapTurned);
    // Turned exactly where the larger M gets the longer side (height) that way.
    EXPECT_EQ(after.mapTurned, before.Mx > before.Mz) << i;
    turnedCount += after.mapTurned ? 1 : 0;
    const glm::dvec2 m = csm::mapAxisAliasing(after);
    EXPECT_GE(m.y, m.x) << "the larger error along the tile's 2048 texels";
    // The predicted error is that of the turned map, never more than unturned.
    const double unturned = 600.0 * std::max(before.Mx / tile.width, before.Mz / tile.height);
    const double asTurned = 600.0 * std::max(m.x / tile.width, m.y / tile.height);
    EXPECT_NEAR(csm::predictedError(after, 600.0, tile), asTurned, 1e-12 * asTurned);
    EXPECT_NEAR(csm::predictedError(before, 600.0, tile), asTurned, 1e-12 * asTurned);
    EXPECT_LE(asTurned, unturned);
    // A rotation, not a mirror: the same body in the same [-1,1]^3, s' = t, t' = -s, same depth;
    // and Lloyd's m along ls x and z is the same measured on either map.
    for (const glm::dvec3& p : before.wsBody)
    {
      const glm::dvec3 a = toNdc(before.wsToClip, p);
      const glm::dvec3 b = toNdc(after.wsToClip, p);
      const glm::dvec3 expect = after.mapTurned ? glm::dvec3(a.y, -a.x, a.z) : a;
      EXPECT_NEAR(glm::length(b - expect), 0.0, 1e-9);
      const csm::Aliasing ma = csm::aliasingAt(before.wsToClip, cam, light, p);
      const csm::Aliasing mb = csm::aliasingAt(after.wsToClip, cam, light, p);
      EXPECT_NEAR(ma.mx, mb.mx, 1e-9 * ma.mx);
      EXPECT_NEAR(ma.mz, mb.mz, 1e-9 * ma.mz);
    }
    // The texels the larger M needs along both axes, each within its side of the tile.
    const csm::MapSize need = csm::resolutionForError(after, 600.0, 1.0, 64, tile);
    EXPECT_EQ(need.width, csm::resolutionForError(m.y, 600.0, 1.0, 64, tile.width));
    EXPECT_EQ(need.height, csm::resolutionForError(m.y, 600.0, 1.0, 64, tile.height));
  }
  EXPECT_GT(turnedCount, 0);
  // Five tall tiles beat five square tiles of the same row (1638 a side) on this view.
  const double square = csm::predictedError(plain, 600.0, csm::MapSize(1638));
  const double tall = csm::predictedError(turned, 600.0, tile);
  EXPECT_LT(tall, 0.9 * square);
  std::printf("light along a 1:1200 view, 5 cascades: %.2f in 1638 x 2048 tiles, %.2f in 1638^2\n",
    tall, square);
  // A square tile turns nothing.
  csm::ShadowSetup same = plain;
  csm::orientToTile(same, csm::MapSize(2048));
  for (const csm::Cascade& c : same.cascades)
  {
    EXPECT_FALSE(c.mapTurned);
  }
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

TEST(Reuse, ABorderedMapCoversTheBodyOfACameraThatTurnedALittle)
{
  // One cascade over a ground plane: the body ends where the visible scene does, in x, y and in
  // depth; a map with a border of 0.2 keeps covering it while the camera turns 1.5 degrees a
  // frame, with an error ratio near 1; the map without a border does not.
  csm::Bounds scene;
  scene.wsMin = { -10, 0, -10 };
  scene.wsMax = { 10, 2, 10 };
  csm::Camera cam = camera(5.0, 60.0, 30.0, 4.0 / 3.0);
  cam.wsPosition = { 0, 12, 24 };
  cam.wsDirection = -cam.wsPosition;
  const glm::dvec3 light(-0.3, -1.0, -0.4);
  const auto s = settings(csm::WarpMode::Generalized, csm::SplitScheme::Adaptive, 1);
  const auto kept = csm::computeShadowSetup(cam, light, &scene, s);
  ASSERT_EQ(kept.status, csm::Status::Ok);
  ASSERT_EQ(kept.cascades.size(), 1u);
  const glm::dmat4 bordered = csm::withBorder(kept.cascades[0].wsToClip, 0.2);
  // The body's corners land in the central 1/1.4 of the bordered map, depth included.
  for (const glm::dvec3& p : kept.cascades[0].wsBody)
  {
    const glm::dvec4 h = bordered * glm::dvec4(p, 1.0);
    EXPECT_LE(std::abs(h.z / h.w), 1.0 / 1.4 + 1e-9);
  }
  int covered = 0, coveredWithout = 0;
  for (int frame = 1; frame <= 4; ++frame)
  {
    const double a = glm::radians(1.5 * frame);
    csm::Camera turned = cam;
    turned.wsPosition = { 24.0 * std::sin(a), 12.0, 24.0 * std::cos(a) };
    turned.wsDirection = -turned.wsPosition;
    const auto fresh = csm::computeShadowSetup(turned, light, &scene, s);
    ASSERT_EQ(fresh.status, csm::Status::Ok);
    const auto reuse = csm::compareKeptMap(bordered, fresh.cascades[0], turned, glm::normalize(light),
      true, 2.0 * 2.0 / 1024.0);
    covered += reuse.covers;
    if (reuse.covers)
    {
      EXPECT_LT(reuse.errorRatio, 1.6) << "frame " << frame;
      EXPECT_GT(reuse.errorRatio, 0.6) << "frame " << frame;
    }
    coveredWithout +=
      csm::compareKeptMap(kept.cascades[0].wsToClip, fresh.cascades[0], turned,
        glm::normalize(light), true, 2.0 * 2.0 / 1024.0).covers;
  }
  EXPECT_EQ(covered, 4);
  EXPECT_EQ(coveredWithout, 0);
  // The same with the maps turned to a non-square tile (orientToTile): the kept map's rows no
  // longer follow the turned camera's ls x and z exactly, and the error is still read along the
  // row that follows each (the ratio near 1, not the error across the map's other axis).
  const csm::MapSize tile = kept.cascades[0].Mx > kept.cascades[0].Mz ? csm::MapSize(1024, 2048)
                                                                      : csm::MapSize(2048, 1024);
  auto keptTurned = kept;
  csm::orientToTile(keptTurned, tile);
  ASSERT_TRUE(keptTurned.cascades[0].mapTurned);
  const glm::dmat4 borderedTurned = csm::withBorder(keptTurned.cascades[0].wsToClip, 0.2);
  for (int frame = 1; frame <= 4; ++frame)
  {
    const double a = glm::radians(1.5 * frame);
    csm::Camera turned = cam;
    turned.wsPosition = { 24.0 * std::sin(a), 12.0, 24.0 * std::cos(a) };
    turned.wsDirection = -turned.wsPosition;
    auto fresh = csm::computeShadowSetup(turned, light, &scene, s);
    csm::orientToTile(fresh, tile);
    ASSERT_TRUE(fresh.cascades[0].mapTurned);
    const auto reuse = csm::compareKeptMap(borderedTurned, fresh.cascades[0], turned,
      glm::normalize(light), true, 2.0 * 2.0 / 1024.0);
    EXPECT_TRUE(reuse.covers) << "frame " << frame;
    EXPECT_LT(reuse.errorRatio, 1.6) << "frame " << frame;
    EXPECT_GT(reuse.errorRatio, 0.6) << "frame " << frame;
  }
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
