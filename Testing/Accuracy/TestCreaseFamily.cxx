// SPDX-License-Identifier: BSD-3-Clause
// Creases and contact edges in shadow on a family of parts (csmPartFamily: L, U and T profiles,
// fillets and chamfers, a hollow section, a hole, a boss, stacked and resting plates, walls
// from 4 to 30 mm), each seen close and far under lights from 5 to 80 degrees above the horizon
// and all round, against the ray-cast truth (Embree): per view the misclassified pixels and the
// longest run of false light (the longest side of the bounding box of an 8-connected group of
// false-light pixels: a line of light along a crease), and the same with gaps of one pixel
// bridged (a dotted line).
//
// CreaseFamily.Sweep: 8 members x 2 cameras x 8 lights. The full sweep (7 elevations x 12
// azimuths, 1344 views), with a table of every view:
//   Testing/csmAccuracyTests --gtest_also_run_disabled_tests \
//     --gtest_filter=CreaseFamily.DISABLED_FullSweep
// CSM_FAMILY_TABLE=<file> writes the table of either sweep as CSV; CSM_FAMILY_IMAGES=<directory>
// writes each view with shadows as a PNG, its false light red and its false shadow blue;
// CSM_FAMILY_VIEWS=<member-camera-elevation-azimuth,...> (l-on-base-close-5-270) measures only
// those views.
#include "csmPartFamily.h"
#include "csmTestHelpers.h"
#include "csmTruth.h"

#include "vtkActor.h"
#include "vtkCascadedShadowMapPass.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkPNGWriter.h"
#include "vtkRenderPass.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace
{
constexpr int W = 640, H = 480;

/// What one view measures.
struct Measure
{
  csmPartFamily::View View;
  csmTruth::Classification Pixels;
  int LongestFalseLight = 0; ///< pixels
  int LongestDotted = 0;     ///< pixels, one-pixel gaps bridged
  long FalseLightWithoutShadows = 0;
};

/// A frame and its image (the grab renders it again).
vtkSmartPointer<vtkImageData> Grab(vtkRenderWindow* window)
{
  return csmTest::Grab(window, true);
}

/// The longest side of the bounding boxes of the groups of marked pixels connected within `reach`
/// pixels (1: 8-connected; 2: across gaps of one pixel).
int LongestRun(const std::vector<char>& marked, int reach)
{
  std::vector<char> seen(marked.size(), 0);
  std::vector<int> stack;
  int longest = 0;
  for (int start = 0; start < W * H; ++start)
  {
    if (!marked[start] || seen[start])
      continue;
    int x0 = W, x1 = -1, y0 = H, y1 = -1;
    stack.push_back(start);
    seen[start] = 1;
    while (!stack.empty())
    {
      const int k = stack.back();
      stack.pop_back();
      const int x = k % W, y = k / W;
      x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
      for (int dy = -reach; dy <= reach; ++dy)
        for (int dx = -reach; dx <= reach; ++dx)
        {
          const int nx = x + dx, ny = y + dy, n = ny * W + nx;
          if (nx >= 0 && nx < W && ny >= 0 && ny < H && marked[n] && !seen[n])
          {
            seen[n] = 1;
            stack.push_back(n);
          }
        }
    }
    longest = std::max(longest, std::max(x1 - x0, y1 - y0) + 1);
  }
  return longest;
}

/// The render with shadows, its false light red and its false shadow blue.
void WriteMarked(const std::string& directory, const std::string& name,
  const csmPartFamily::View& view, vtkImageData* image,
  const std::vector<csmTruth::Surface>& surfaces, const std::vector<char>& comparable,
  const std::vector<char>& occluded, const std::vector<float>& factor)
{
  auto* rgb = static_cast<unsigned char*>(image->GetScalarPointer());
  const int components = image->GetNumberOfScalarComponents();
  for (size_t k = 0; k < surfaces.size(); ++k)
  {
    const auto c = csmTruth::ClassifyPixel(comparable[k], occluded[k], factor[k]);
    unsigned char* p = rgb + k * components;
    if (c == csmTruth::PixelClass::FalseLight || c == csmTruth::PixelClass::FalseShadow)
    {
      const bool light = c == csmTruth::PixelClass::FalseLight;
      p[0] = light ? 255 : 0;
      p[1] = 0;
      p[2] = light ? 0 : 255;
    }
  }
  char file[512];
  std::snprintf(file, sizeof(file), "%s/%s-%s-el%02.0f-az%03.0f.png", directory.c_str(),
    name.c_str(), view.Close ? "close" : "far", view.Elevation, view.Azimuth);
  vtkNew<vtkPNGWriter> writer;
  writer->SetInputData(image);
  writer->SetFileName(file);
  writer->Write();
}

/// Renders every view of the family with and without shadows and compares with the truth.
std::vector<Measure> MeasureFamily(bool full)
{
  const std::vector<csmScenes::Scene> members = csmPartFamily::Members();
  const auto views = csmPartFamily::Views(static_cast<int>(members.size()), full);
  std::vector<Measure> measures;
  for (int m = 0; m < static_cast<int>(members.size()); ++m)
  {
    vtkNew<vtkRenderer> renderer;
    vtkNew<vtkRenderWindow> window;
    window->SetSize(W, H);
    window->SetMultiSamples(0);
    window->SetOffScreenRendering(1);
    window->AddRenderer(renderer);
    renderer->SetBackground(0, 0, 0);
    renderer->AutomaticLightCreationOff();
    vtkNew<vtkLight> light;
    light->SetLightTypeToSceneLight();
    light->SetPositional(false);
    renderer->AddLight(light);
    for (const auto& actor : members[m].Actors)
      renderer->AddActor(actor);
    vtkCascadedShadowMapPass::UseShadowsOn(renderer);
    vtkSmartPointer<vtkRenderPass> shadows = renderer->GetPass();
    csmTruth::RayScene rays;
    rays.Build(renderer);
    for (const auto& view : views)
    {
      if (view.Member != m)
        continue;
      if (const char* only = std::getenv("CSM_FAMILY_VIEWS"))
      {
        char key[256];
        std::snprintf(key, sizeof(key), "%s-%s-%g-%g", members[m].Name.c_str(),
          view.Close ? "close" : "far", view.Elevation, view.Azimuth);
        if (std::string(only).find(key) == std::string::npos)
          continue;
      }
      double direction[3];
      csmPartFamily::LightDirection(view, direction);
      light->SetPosition(-direction[0], -direction[1], -direction[2]);
      light->SetFocalPoint(0, 0, 0);
      csmPartFamily::PlaceCamera(view, members[m], renderer);
      renderer->SetPass(nullptr);
      auto plain = Grab(window);
      renderer->SetPass(shadows);
      auto shadowed = Grab(window);
      const auto surfaces = rays.CastPrimary(renderer->GetActiveCamera(), W, H);
      const auto comparable = csmTruth::ComparablePixels(surfaces, W, H, direction);
      std::vector<char> occluded(surfaces.size(), 0);
      for (size_t k = 0; k < surfaces.size(); ++k)
        occluded[k] = comparable[k] && rays.Occluded(surfaces[k], direction);
      const auto factor = csmTruth::FactorFromRenders(shadowed, plain);
      const auto edges = rays.ShadowEdges(
        renderer->GetActiveCamera(), W, H, surfaces, comparable, occluded, direction);
      Measure measure;
      measure.View = view;
      measure.Pixels = csmTruth::Classify(surfaces, comparable, occluded, factor, &edges);
      measure.FalseLightWithoutShadows = csmTruth::Classify(
        surfaces, comparable, occluded, csmTruth::FactorFromRenders(plain, plain))
                                           .FalseLight;
      std::vector<char> falseLight(surfaces.size(), 0);
      for (size_t k = 0; k < surfaces.size(); ++k)
        falseLight[k] = csmTruth::ClassifyPixel(comparable[k], occluded[k], factor[k]) ==
          csmTruth::PixelClass::FalseLight;
      measure.LongestFalseLight = LongestRun(falseLight, 1);
      measure.LongestDotted = LongestRun(falseLight, 2);
      if (const char* directory = std::getenv("CSM_FAMILY_IMAGES"))
        WriteMarked(
          directory, members[m].Name, view, shadowed, surfaces, comparable, occluded, factor);
      measures.push_back(measure);
    }
  }
  return measures;
}

/// Prints (and with CSM_FAMILY_TABLE writes as CSV) every view, and checks the bounds.
void Report(const std::vector<Measure>& measures, const std::vector<csmScenes::Scene>& members)
{
  const char* path = std::getenv("CSM_FAMILY_TABLE");
  FILE* csv = path ? std::fopen(path, "w") : nullptr;
  if (csv)
    std::fprintf(csv,
      "member,camera,elevation,azimuth,considered,false_shadow,false_light,"
      "misclassified_pct,longest_false_light,longest_dotted,off_edge_misclassified_pct\n");
  double sum = 0.0, worst = 0.0, offEdgeSum = 0.0, offEdgeWorst = 0.0;
  int longest = 0, dotted = 0;
  for (const auto& m : measures)
  {
    const auto& p = m.Pixels;
    sum += p.MismatchPct();
    worst = std::max(worst, p.MismatchPct());
    longest = std::max(longest, m.LongestFalseLight);
    dotted = std::max(dotted, m.LongestDotted);
    offEdgeSum += p.OffEdgeMismatchPct();
    offEdgeWorst = std::max(offEdgeWorst, p.OffEdgeMismatchPct());
    std::printf("%-15s %-5s el %4.0f az %4.0f: considered %6ld, false shadow %4ld, false light "
                "%4ld, %.3f%%, longest false light %d px (dotted %d px)\n",
      members[m.View.Member].Name.c_str(), m.View.Close ? "close" : "far", m.View.Elevation,
      m.View.Azimuth, p.Considered, p.FalseShadow, p.FalseLight, p.MismatchPct(),
      m.LongestFalseLight, m.LongestDotted);
    if (csv)
      std::fprintf(csv, "%s,%s,%g,%g,%ld,%ld,%ld,%.4f,%d,%d,%.4f\n",
        members[m.View.Member].Name.c_str(), m.View.Close ? "close" : "far", m.View.Elevation,
        m.View.Azimuth, p.Considered, p.FalseShadow, p.FalseLight, p.MismatchPct(),
        m.LongestFalseLight, m.LongestDotted, p.OffEdgeMismatchPct());
  }
  if (csv)
    std::fclose(csv);
  const double mean = measures.empty() ? 0.0 : sum / measures.size();
  std::printf("%zu views: mean %.4f%%, worst %.4f%%, longest false light %d px (dotted %d px); "
              "off shadow edges mean %.4f%%, worst %.4f%%\n",
    measures.size(), mean, worst, longest, dotted,
    measures.empty() ? 0.0 : offEdgeSum / measures.size(), offEdgeWorst);
}
} // namespace

// Every view misclassifies at most 0.05 % of its light-facing pixels, 0.02 % on average, with
// no line of false light longer than 10 pixels and at most 0.02 % false shadow (before the
// lookup compared faces turned toward the light with each texel's own receiver-plane depth:
// mean 0.030 %, worst 0.233 %, lines up to 21 pixels, 27 views over 0.05 %).
TEST(CreaseFamily, Sweep)
{
  const auto members = csmPartFamily::Members();
  const auto measures = MeasureFamily(false);
  Report(measures, members);
  ASSERT_EQ(members.size(), 8u);
  ASSERT_EQ(measures.size(), 128u);
  double sum = 0.0;
  long withoutShadows = 0;
  for (const auto& m : measures)
  {
    const auto& p = m.Pixels;
    const std::string view = members[m.View.Member].Name + (m.View.Close ? " close" : " far") +
      ", light " + std::to_string(m.View.Elevation) + " / " + std::to_string(m.View.Azimuth);
    EXPECT_GT(p.Considered, 10000) << view;
    EXPECT_LE(p.MismatchPct(), 0.05) << view;
    EXPECT_LE(p.FalseShadowPct(), 0.02) << view;
    EXPECT_LE(m.LongestFalseLight, 10) << view;
    sum += p.MismatchPct();
    withoutShadows += m.FalseLightWithoutShadows;
  }
  EXPECT_LE(sum / measures.size(), 0.02);
  // Without shadows the measure fails: the shadowed pixels are all false light.
  EXPECT_GT(withoutShadows, 100 * static_cast<long>(measures.size()));
}

TEST(CreaseFamily, DISABLED_FullSweep)
{
  const auto measures = MeasureFamily(true);
  Report(measures, csmPartFamily::Members());
}
