// SPDX-License-Identifier: BSD-3-Clause
// The per-frame shadow math for one light: body, splits, warp, matrices and error of every
// cascade. Run: build/Testing/csmMathBenchmark (see README).
#include "csmSetup.h"

#include <benchmark/benchmark.h>

#include <cmath>

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
}

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
