// SPDX-License-Identifier: BSD-3-Clause
// Ray-cast ground truth (Embree) on a scene whose answer is known: a box over a plane, lit from
// straight above. The truth mask must match the analytic shadow outline, and our pass must
// misclassify fewer than 0.5% of the comparable pixels.
#include "csmTestHelpers.h"
#include "csmTruth.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCascadedShadowMapPass.h"
#include "vtkCubeSource.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPolyDataMapper.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace
{
constexpr int W = 400, H = 300;
const double kDown[3] = { 0.0, -1.0, 0.0 };

// The box over the plane of the pass tests, with a finer ground (20 x 20 quads), plain white,
// on black, lit from straight above and seen from aside.
struct Fixture : csmTest::BoxOverPlane
{
  Fixture()
    : csmTest::BoxOverPlane(Settings())
  {
  }
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

namespace
{
/// The fixture rendered without and with our pass, and the truth at each pixel.
struct Measured
{
  Measured()
  {
    this->Plain = this->Scene.Render();
    vtkCascadedShadowMapPass::UseShadowsOn(this->Scene.Renderer);
    this->Shadowed = this->Scene.Render();
    this->Rays.Build(this->Scene.Renderer);
    this->Surfaces = this->Rays.CastPrimary(this->Scene.Renderer->GetActiveCamera(), W, H);
    this->Comparable = csmTruth::ComparablePixels(this->Surfaces, W, H, kDown);
    this->Occluded.assign(this->Surfaces.size(), 0);
    for (size_t k = 0; k < this->Surfaces.size(); ++k)
      this->Occluded[k] = this->Comparable[k] && this->Rays.Occluded(this->Surfaces[k], kDown);
  }
  Fixture Scene;
  vtkSmartPointer<vtkImageData> Plain, Shadowed;
  csmTruth::RayScene Rays;
  std::vector<csmTruth::Surface> Surfaces;
  std::vector<char> Comparable, Occluded;
};
} // namespace

TEST(Truth, OurPassMisclassifiesUnderHalfAPercent)
{
  Measured m;
  const auto& surfaces = m.Surfaces;
  const auto& comparable = m.Comparable;
  const auto& occluded = m.Occluded;
  const auto factor = csmTruth::FactorFromRenders(m.Shadowed, m.Plain);
  const csmTruth::Classification c = csmTruth::Classify(surfaces, comparable, occluded, factor);
  std::printf("considered %ld, false shadow %ld, false light %ld: %.3f%% misclassified\n",
    c.Considered, c.FalseShadow, c.FalseLight, c.MismatchPct());
  EXPECT_GT(c.Considered, 50000);
  EXPECT_LT(c.MismatchPct(), 0.5);
  // And without shadows every occluded pixel is a false light: the measure can fail.
  const auto none = csmTruth::FactorFromRenders(m.Plain, m.Plain);
  const csmTruth::Classification n = csmTruth::Classify(surfaces, comparable, occluded, none);
  EXPECT_GT(n.FalseLight, 1000);
  EXPECT_EQ(n.FalseShadow, 0);
}

// The pixels a shadow edge crosses are those of the outline: on the ground, every comparable pixel
// that is an edge lies within a pixel's width of the box's shadow outline, and every pixel whose
// footprint the outline crosses is one; the pass misclassifies no pixel beyond them.
TEST(Truth, ShadowEdgesAreThePixelsTheOutlineCrosses)
{
  Measured m;
  const auto& surfaces = m.Surfaces;
  const auto& comparable = m.Comparable;
  const auto& occluded = m.Occluded;
  const auto edges = m.Rays.ShadowEdges(
    m.Scene.Renderer->GetActiveCamera(), W, H, surfaces, comparable, occluded, kDown);
  ASSERT_EQ(edges.size(), surfaces.size());
  // A ground pixel's world size there: the distance to its right neighbour's hit.
  long onOutline = 0, crossed = 0, far = 0, farEdges = 0;
  for (int j = 0; j < H; ++j)
  {
    for (int i = 0; i + 1 < W; ++i)
    {
      const size_t k = static_cast<size_t>(j) * W + i;
      const auto& s = surfaces[k];
      const auto& right = surfaces[k + 1];
      if (!comparable[k] || !right.Hit || std::abs(s.Position[1]) > 1e-4 ||
        std::abs(right.Position[1]) > 1e-4)
        continue;
      const double pixel =
        std::hypot(right.Position[0] - s.Position[0], right.Position[2] - s.Position[2]);
      // Distance from the outline of the square |x|, |z| <= 1.
      const double ax = std::abs(s.Position[0]), az = std::abs(s.Position[2]);
      const double outside = std::hypot(std::max(ax - 1.0, 0.0), std::max(az - 1.0, 0.0));
      const double distance = outside > 0.0 ? outside : std::min(1.0 - ax, 1.0 - az);
      if (distance < 0.25 * pixel)
      {
        ++onOutline;
        crossed += edges[k] != 0;
      }
      else if (distance > 1.5 * pixel)
      {
        ++far;
        farEdges += edges[k] != 0;
      }
    }
  }
  EXPECT_GT(onOutline, 50);
  EXPECT_EQ(crossed, onOutline);
  EXPECT_GT(far, 50000);
  EXPECT_EQ(farEdges, 0);
  const auto factor = csmTruth::FactorFromRenders(m.Shadowed, m.Plain);
  const csmTruth::Classification c =
    csmTruth::Classify(surfaces, comparable, occluded, factor, &edges);
  std::printf("%ld of %ld considered pixels off the edges, %ld misclassified (%ld in all)\n",
    c.OffEdge, c.Considered, c.OffEdgeWrong, c.FalseShadow + c.FalseLight);
  EXPECT_GT(c.OffEdge, c.Considered - 2 * onOutline - 1000);
  EXPECT_EQ(c.OffEdgeWrong, 0);
  // Without shadows every occluded pixel off the edges is wrong: the measure can fail.
  const auto none = csmTruth::FactorFromRenders(m.Plain, m.Plain);
  EXPECT_GT(csmTruth::Classify(surfaces, comparable, occluded, none, &edges).OffEdgeWrong, 1000);
}

// A bar over a large ground (6 km a side) under a light 5 degrees above the horizon: the bar's
// shadow lies 23 units downstream and is 2.5 units long; the truth must find its edges within
// 0.05 units. The ray's lift off the ground moves the shadow by lift / tan(5 deg), so a lift
// sized to the scene (1e-5 of 6 km = 0.06, a shift of 0.7) fails here.
TEST(Truth, GrazingShadowsStayInPlace)
{
  const double degrees = 5.0, t = std::tan(degrees * M_PI / 180.0);
  const double light[3] = { 0.0, -std::sin(degrees * M_PI / 180.0),
    std::cos(degrees * M_PI / 180.0) };
  vtkNew<vtkRenderer> renderer;
  auto add = [&](double x0, double x1, double y0, double y1, double z0, double z1)
  {
    vtkNew<vtkCubeSource> cube;
    cube->SetBounds(x0, x1, y0, y1, z0, z1);
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputConnection(cube->GetOutputPort());
    mapper->Update();
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    renderer->AddActor(actor);
  };
  add(-3000, 3000, -1, 0, -3000, 3000); // ground, its top at y = 0
  add(-1, 1, 2.0, 2.2, -0.1, 0.1);      // bar
  renderer->GetActiveCamera()->SetPosition(0, 3, 40);
  renderer->GetActiveCamera()->SetFocalPoint(0, 0, 20);
  csmTruth::RayScene rays;
  ASSERT_EQ(rays.Build(renderer, 300), 24);
  const double first = -0.1 + 2.0 / t, last = 0.1 + 2.2 / t; // the shadow's extent along z
  int checked = 0, wrong = 0;
  for (double z = first - 3.0; z <= last + 3.0; z += 0.01)
  {
    if (std::abs(z - first) < 0.05 || std::abs(z - last) < 0.05)
      continue;
    csmTruth::Surface s;
    s.Hit = true;
    s.Position[2] = z;
    s.Normal[1] = 1.0;
    s.Distance = std::hypot(3.0, 40.0 - z);
    ++checked;
    wrong += rays.Occluded(s, light) != (z > first && z < last);
  }
  EXPECT_GT(checked, 800);
  EXPECT_EQ(wrong, 0);
}

TEST(Truth, Summaries)
{
  const csmTruth::Stats s = csmTruth::Summarize({ 1, 2, 3, 4, 5, 6, 7, 8, 9, 10 });
  EXPECT_DOUBLE_EQ(s.Max, 10);
  EXPECT_DOUBLE_EQ(s.Mean, 5.5);
  EXPECT_DOUBLE_EQ(s.P95, 9);
  EXPECT_DOUBLE_EQ(csmTruth::Summarize({}).Max, 0);
}
