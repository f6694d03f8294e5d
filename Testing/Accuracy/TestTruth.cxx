// SPDX-License-Identifier: BSD-3-Clause
// Ray-cast ground truth (Embree) on a scene whose answer is known: a box over a plane, lit from
// straight above. The truth mask must match the analytic shadow outline, and our pass must
// misclassify fewer than 0.5% of the comparable pixels.
#include "csmTestHelpers.h"
#include "csmTruth.h"

#include "vtkCascadedShadowMapPass.h"
#include "vtkImageData.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace
{
constexpr int W = 400, H = 300;
const double kDown[3] = { 0.0, -1.0, 0.0 };

// The box over the plane of the pass tests, with a finer ground (20 x 20 quads), plain white,
// on black, lit from straight above and seen from aside.
struct Fixture : csmTest::BoxOverPlane
{
  Fixture() : csmTest::BoxOverPlane(Settings()) {}
  static csmTest::BoxOverPlaneSettings Settings()
  {
    csmTest::BoxOverPlaneSettings s;
    s.Size[0] = W;
    s.Size[1] = H;
    s.GroundResolution = 20;
    for (int i = 0; i < 3; ++i)
    {
      s.BoxColor[i] = 1.0;
      s.Background[i] = 0.0;
      s.LightPosition[i] = -kDown[i];
    }
    const double camera[3] = { 3, 9, 12 };
    std::copy(camera, camera + 3, s.CameraPosition);
    return s;
  }
};
} // namespace

TEST(Truth, MatchesTheAnalyticOutline)
{
  Fixture f;
  f.Window->Render();
  csmTruth::RayScene rays;
  EXPECT_EQ(rays.Build(f.Renderer), 2 * 20 * 20 + 12);
  const auto surfaces = rays.CastPrimary(f.Renderer->GetActiveCamera(), W, H);
  const auto comparable = csmTruth::ComparablePixels(surfaces, W, H, kDown);
  long ground = 0, inside = 0, wrong = 0;
  for (size_t k = 0; k < surfaces.size(); ++k)
  {
    const auto& s = surfaces[k];
    if (!comparable[k] || std::abs(s.Position[1]) > 1e-4)
      continue;
    const double x = s.Position[0], z = s.Position[2];
    if (std::abs(std::abs(x) - 1.0) < 0.02 || std::abs(std::abs(z) - 1.0) < 0.02)
      continue; // on the outline itself
    const bool analytic = std::abs(x) < 1.0 && std::abs(z) < 1.0;
    ++ground;
    inside += analytic;
    wrong += analytic != rays.Occluded(s, kDown);
  }
  EXPECT_GT(ground, 50000);
  EXPECT_GT(inside, 1000);
  EXPECT_EQ(wrong, 0);
  // The box's top faces the light and is lit; its sides do not face it and are not compared.
  long top = 0;
  for (size_t k = 0; k < surfaces.size(); ++k)
    if (comparable[k] && std::abs(surfaces[k].Position[1] - 4.0) < 1e-4)
    {
      ++top;
      EXPECT_FALSE(rays.Occluded(surfaces[k], kDown));
    }
  EXPECT_GT(top, 100);
}

TEST(Truth, OurPassMisclassifiesUnderHalfAPercent)
{
  Fixture f;
  auto plain = f.Render();
  vtkCascadedShadowMapPass::UseShadowsOn(f.Renderer);
  auto shadowed = f.Render();
  csmTruth::RayScene rays;
  rays.Build(f.Renderer);
  const auto surfaces = rays.CastPrimary(f.Renderer->GetActiveCamera(), W, H);
  const auto comparable = csmTruth::ComparablePixels(surfaces, W, H, kDown);
  std::vector<char> occluded(surfaces.size(), 0);
  for (size_t k = 0; k < surfaces.size(); ++k)
    occluded[k] = comparable[k] && rays.Occluded(surfaces[k], kDown);
  const auto factor = csmTruth::FactorFromRenders(shadowed, plain);
  const csmTruth::Classification c = csmTruth::Classify(surfaces, comparable, occluded, factor);
  std::printf("considered %ld, false shadow %ld, false light %ld: %.3f%% misclassified\n",
    c.Considered, c.FalseShadow, c.FalseLight, c.MismatchPct());
  EXPECT_GT(c.Considered, 50000);
  EXPECT_LT(c.MismatchPct(), 0.5);
  // And without shadows every occluded pixel is a false light: the measure can fail.
  const auto none = csmTruth::FactorFromRenders(plain, plain);
  const csmTruth::Classification n = csmTruth::Classify(surfaces, comparable, occluded, none);
  EXPECT_GT(n.FalseLight, 1000);
  EXPECT_EQ(n.FalseShadow, 0);
}

TEST(Truth, Summaries)
{
  const csmTruth::Stats s = csmTruth::Summarize({ 1, 2, 3, 4, 5, 6, 7, 8, 9, 10 });
  EXPECT_DOUBLE_EQ(s.Max, 10);
  EXPECT_DOUBLE_EQ(s.Mean, 5.5);
  EXPECT_DOUBLE_EQ(s.P95, 9);
  EXPECT_DOUBLE_EQ(csmTruth::Summarize({}).Max, 0);
}
