// SPDX-License-Identifier: BSD-3-Clause
// The scene-fitted map of a directional light: what can be in shadow across the light, and the
// farthest cascade on it where it meets the error target (Lloyd et al. 2006's M over its body).
#include "csmAliasing.h"
#include "csmAtlas.h"
#include "csmCascadeCount.h"
#include "csmGeometry.h"
#include "csmMathTestHelpers.h"
#include "csmSceneFit.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace
{
using csmMathTest::camera; // eye at the origin looking down -z, up +y
using csmMathTest::settings;

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
} // namespace

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

// Along the light the map spans what lies inside its extent across the light (each receiver
// part clipped to it), not the scene's depth: over a ground 20,000 wide, or with a speck of a
// prop 1e6 away, the box and the ground under it keep a large share of the map's depths, of which
// the constant bias is a share.
TEST(Steps, SceneFitDepthSpansWhatLiesUnderItsShadows)
{
  const csm::Bounds box{ { -1.0, 1.0, -1.0 }, { 1.0, 3.0, 1.0 } };
  const glm::dvec3 light(-0.5, -1.0, 0.2);
  const glm::dvec3 under = glm::dvec3(0.0, 3.0, 0.0) + 3.0 * light; // the ground under its top
  for (const bool speck : { false, true })
  {
    const double half = speck ? 10.0 : 1e4;
    const csm::Bounds ground{ { -half, -0.1, -half }, { half, 0.0, half } };
    const csm::Bounds far{ { 1e6, 0.0, 1e6 }, { 1e6 + 1.0, 1.0, 1e6 + 1.0 } };
    std::vector<csm::Bounds> receivers{ ground, box };
    std::vector<csm::CasterLoad> casters{ { ground, 12.0, 0, false }, { box, 12.0, 1, false } };
    csm::Bounds scene{ ground.wsMin, glm::dvec3(half, 3.0, half) };
    if (speck)
    {
      receivers.push_back(far);
      casters.push_back({ far, 12.0, 2, false });
      scene.wsMax = far.wsMax;
    }
    {
      csm::SceneFit fit;
      ASSERT_TRUE(csm::sceneFit(light, scene, casters, &receivers, fit));
      const double top = clipOf(fit.wsToClip, glm::dvec3(0.0, 3.0, 0.0)).z;
      const double ground = clipOf(fit.wsToClip, under).z;
      EXPECT_GT(ground - top, 0.2) << speck; // of the clip depths' 2
      // Everything inside the map across the light is inside its depths.
      for (int i = 0; i < 8; ++i)
      {
        const glm::dvec3 c = clipOf(fit.wsToClip, csm::boxCorner(box, i));
        EXPECT_GE(c.z, -1.0 - 1e-9);
        EXPECT_LE(c.z, 1.0 + 1e-9);
      }
      for (const double x : { -1.0, 0.0, 1.0 })
      {
        const glm::dvec3 g = under + glm::dvec3(x, 0.0, 0.5 * x);
        if (insidePrism(fit, g, 0.0))
        {
          EXPECT_LE(clipOf(fit.wsToClip, g).z, 1.0 + 1e-9);
          EXPECT_GE(clipOf(fit.wsToClip, g - glm::dvec3(0.0, 0.1, 0.0)).z, -1.0 - 1e-9);
        }
      }
    }
  }
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
  const std::vector<csm::CasterLoad> casters{ { ground, 12.0, 0, false }, { box, 12.0, 1, false } };
  const glm::dvec3 light(-0.3, -1.0, -0.2);
  csm::SceneFit fit;
  ASSERT_TRUE(csm::sceneFit(light, scene, casters, &receivers, fit));
  auto s = settings(csm::WarpMode::Generalized, csm::SplitScheme::Adaptive, 4);
  s.sceneFitted = true;
  auto orbit = [](double azimuthDeg, double distance)
  {
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
    EXPECT_EQ(
      csm::resolutionForError(last, 480.0, 1.0, 64, csm::MapSize(2896)), csm::MapSize(2896));
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

// The constant bias on a scene-fitted map follows its texel: the whole of it at
// kSceneFittedBiasTexels a side and coarser, a quarter at four times as many texels.
TEST(Steps, SceneFittedBiasShareFollowsTheTexel)
{
  EXPECT_DOUBLE_EQ(csm::sceneFittedBiasShare(csm::kSceneFittedBiasTexels), 1.0);
  EXPECT_DOUBLE_EQ(csm::sceneFittedBiasShare(512.0), 1.0);
  EXPECT_DOUBLE_EQ(csm::sceneFittedBiasShare(4.0 * csm::kSceneFittedBiasTexels), 0.25);
  EXPECT_DOUBLE_EQ(csm::sceneFittedBiasShare(0.0), 1.0);
  EXPECT_DOUBLE_EQ(csm::sceneFittedBiasShare(std::nan("")), 1.0);
}
