// SPDX-License-Identifier: BSD-3-Clause
// Lloyd et al. 2006, Eq. 2-4 at the body's vertices against the cascade's M (Eq. 9-10, §4.4), and
// the resolution a target error needs.
#include "csmAliasing.h"
#include "csmMathTestHelpers.h"
#include "csmSetup.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace
{
using csmMathTest::camera;  // eye at the origin looking down -z, up +y
using csmMathTest::lightAt; // gammaDeg: 0 light from behind, 90 overhead, 180 facing
using csmMathTest::settings;
} // namespace

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
