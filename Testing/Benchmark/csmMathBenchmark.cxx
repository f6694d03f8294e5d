// SPDX-License-Identifier: BSD-3-Clause
// The per-frame shadow math for one light: body, splits, warp, matrices and error of every
// cascade. Run: build/Testing/csmMathBenchmark (see README).
#include "csmPages.h"
#include "csmSetup.h"
#include "csmVisibleDepth.h"

#include <benchmark/benchmark.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <vector>

namespace
{
// A CAD-like frame: a platform-sized scene box, a camera on the deck looking across it.
void frame(benchmark::State& state, csm::WarpMode warp, csm::SplitScheme scheme, bool bounds)
{
  csm::Camera camera;
  camera.wsPosition = { 12.0, 25.0, 60.0 };
  camera.wsDirection = { -0.2, -0.25, -1.0 };
  camera.vsNear = 0.05;
  camera.vsFar = 5000.0;
  camera.fovyDeg = 45.0;
  camera.aspect = 4.0 / 3.0;
  const csm::Bounds scene{ { -80.0, -30.0, -400.0 }, { 80.0, 60.0, 80.0 } };
  csm::Settings settings;
  settings.warp = warp;
  settings.split.scheme = scheme;
  settings.split.k = static_cast<int>(state.range(0));
  int step = 0;
  for (auto _ : state)
  {
    // Move the light a little every frame so no two frames are the same.
    const double a = 0.001 * (step++ % 1000);
    const glm::dvec3 light(0.3 + a, -1.0, -0.4 + a);
    csm::ShadowSetup setup =
      csm::computeShadowSetup(camera, light, bounds ? &scene : nullptr, settings);
    benchmark::DoNotOptimize(setup);
  }
}

void GeneralizedAdaptiveWithScene(benchmark::State& state)
{
  frame(state, csm::WarpMode::Generalized, csm::SplitScheme::Adaptive, true);
}
void GeneralizedAdaptiveFrustumOnly(benchmark::State& state)
{
  frame(state, csm::WarpMode::Generalized, csm::SplitScheme::Adaptive, false);
}
void UniformSingleWithScene(benchmark::State& state)
{
  frame(state, csm::WarpMode::None, csm::SplitScheme::Single, true);
}

// A 640x480 view of a ground: the camera 2 above it looking 10 ahead and down; its window depths
// (1: the sky).
struct GroundView
{
  static constexpr int width = 640, height = 480;
  static constexpr double vsNear = 0.1, vsFar = 1000.0;
  glm::dmat4 worldToView, viewToClip;
  std::vector<float> depths;
  GroundView()
  {
    const glm::dvec3 eye(0.0, 2.0, 0.0);
    this->worldToView = glm::lookAt(eye, glm::dvec3(0.0, 0.0, -10.0), glm::dvec3(0, 1, 0));
    this->viewToClip = glm::perspective(glm::radians(60.0), double(width) / height, vsNear, vsFar);
    const glm::dmat4 clipToWorld = glm::inverse(this->viewToClip * this->worldToView);
    this->depths.assign(static_cast<std::size_t>(width) * height, 1.0f);
    for (int y = 0; y < height; ++y)
    {
      for (int x = 0; x < width; ++x)
      {
        const glm::dvec4 far = clipToWorld *
          glm::dvec4(2.0 * (x + 0.5) / width - 1.0, 2.0 * (y + 0.5) / height - 1.0, 1.0, 1.0);
        const glm::dvec3 ray = glm::dvec3(far) / far.w - eye;
        if (ray.y < 0.0)
        {
          const glm::dvec3 hit = eye + ray * (-eye.y / ray.y);
          const double depth = -(this->worldToView * glm::dvec4(hit, 1.0)).z;
          this->depths[static_cast<std::size_t>(y) * width + x] =
            static_cast<float>(csm::windowDepthFromViewDepth(depth, vsNear, vsFar, false));
        }
      }
    }
  }
};

// The pages that view marks (csm::markPages, every visible-depth pass of a paged light), the
// light from above.
void MarkPages(benchmark::State& state)
{
  const GroundView view;
  const glm::dmat4 wsToBase = glm::ortho(-100.0, 100.0, -100.0, 100.0, -100.0, 100.0) *
    glm::lookAt(glm::dvec3(0.0), glm::dvec3(0.1, -1.0, 0.2), glm::dvec3(0, 0, -1));
  const glm::dmat4 windowToBase = csm::windowToBase(wsToBase, view.viewToClip * view.worldToView);
  csm::PageLevels levels;
  levels.baseTexels = glm::dvec2(1024.0);
  levels.baseDepth = 100.0;
  levels.count = 6;
  std::vector<csm::PageKey> pages;
  for (auto _ : state)
  {
    csm::markPages(levels, windowToBase, view.vsNear, view.vsFar, view.depths.data(), view.width,
      view.height, {}, 100000, pages);
    benchmark::DoNotOptimize(pages);
  }
  state.counters["pages"] = static_cast<double>(pages.size());
}

// That view's footprint (csm::windowFootprint, every visible-depth pass).
void WindowFootprint(benchmark::State& state)
{
  const GroundView view;
  for (auto _ : state)
  {
    csm::WindowFootprint footprint =
      csm::windowFootprint(view.depths.data(), view.width, view.height);
    benchmark::DoNotOptimize(footprint);
  }
}
}

BENCHMARK(MarkPages)->Unit(benchmark::kMillisecond)->Repetitions(5)->ReportAggregatesOnly(true);
BENCHMARK(WindowFootprint)
  ->Unit(benchmark::kMillisecond)
  ->Repetitions(5)
  ->ReportAggregatesOnly(true);
BENCHMARK(GeneralizedAdaptiveWithScene)
  ->Arg(1)
  ->Arg(2)
  ->Arg(4)
  ->Arg(8)
  ->Unit(benchmark::kMicrosecond)
  ->Repetitions(5)
  ->ReportAggregatesOnly(true);
BENCHMARK(GeneralizedAdaptiveFrustumOnly)
  ->Arg(4)
  ->Unit(benchmark::kMicrosecond)
  ->Repetitions(5)
  ->ReportAggregatesOnly(true);
BENCHMARK(UniformSingleWithScene)
  ->Arg(1)
  ->Unit(benchmark::kMicrosecond)
  ->Repetitions(5)
  ->ReportAggregatesOnly(true);

BENCHMARK_MAIN();
