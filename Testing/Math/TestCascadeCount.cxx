// SPDX-License-Identifier: BSD-3-Clause
// The cascade count from the error model (Lloyd et al. 2006, Eq. 9-10 on the atlas's maps; §5.2's
// hysteresis), each count's splits the better of Barroso & Celes 2007, Eq. 19 and the log splits,
// and the count weighed by caster passes against texels.
#include "csmAtlas.h"
#include "csmCascadeCount.h"
#include "csmMathTestHelpers.h"
#include "csmSetup.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace
{
using csmMathTest::camera;  // eye at the origin looking down -z, up +y
using csmMathTest::lightAt; // gammaDeg: 0 light from behind, 90 overhead, 180 facing
using csmMathTest::settings;
} // namespace

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
      EXPECT_NEAR(e / std::min(eq19, logSplits), 1.0, 1e-12)
        << "f/n " << ratio << " gamma " << gamma;
      if (ratio >= 1200.0 && gamma == 0.0)
      {
        EXPECT_EQ(chosen.cascades.size(), 4u);       // every step cuts the error here
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
  EXPECT_GT(
    csm::predictedError(oneFewer, 600.0, csm::ceilingsForCount(fewer.split.k, 8, 2048)), 1.5);
  std::printf("cascades: overhead f/n 10: %zu (error %.3f); behind f/n 100: %zu (error %.3f, "
              "with one fewer %.3f); behind f/n 1e4: %zu (error %.1f)\n",
    overhead.cascades.size(), csm::predictedError(overhead, 600.0, 2048), enough.cascades.size(),
    csm::predictedError(enough, 600.0, 2048), csm::predictedError(oneFewer, 600.0, 2048),
    behind.cascades.size(), csm::predictedError(behind, 600.0, 2048));
}

TEST(Steps, CascadeCountWhereNoneMeetsTheTarget)
{
  const auto settingsUpTo8 = settings(csm::WarpMode::Generalized, csm::SplitScheme::Adaptive, 8);
  const csm::Camera longView = camera(1.0, 1.0e4, 40.0, 4.0 / 3.0);
  // None meets an unreachable target: more cascades as long as each cuts the worst error to
  // kCountHysteresis of the best fewer reach, each judged at the resolution the atlas gives its
  // count (beyond four cascades, less than 2048). Along a 1:10^4 view that is more than four,
  // and the next count would not cut the error by the margin.
  const csm::ShadowSetup most = csm::computeShadowSetupForError(
    longView, lightAt(longView, 0.0), nullptr, settingsUpTo8, nullptr, 600.0, 2048, 1e-6, 0);
  const int kMost = static_cast<int>(most.cascades.size());
  EXPECT_GT(kMost, 4);
  auto errorAt = [&](int k)
  {
    auto s = settingsUpTo8;
    s.split.k = k;
    return csm::predictedError(csm::computeShadowSetupForError(longView, lightAt(longView, 0.0),
                                 nullptr, s, nullptr, 600.0, 2048, 1e-6, 0),
      600.0, csm::ceilingsForCount(k, 8, 2048));
  };
  const double eMost = csm::predictedError(most, 600.0, csm::ceilingsForCount(kMost, 8, 2048));
  EXPECT_LT(eMost, csm::kCountHysteresis * errorAt(4));
  if (kMost < 8)
  {
    auto next = settingsUpTo8;
    next.split.k = kMost + 1;
    const double eNext =
      csm::predictedError(csm::computeShadowSetupForCount(longView, lightAt(longView, 0.0), nullptr,
                            next, nullptr, kMost + 1, csm::ceilingsForCount(kMost + 1, 8, 2048)),
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
    const double eFewer =
      csm::predictedError(csm::computeShadowSetupForCount(longView, lightAt(longView, 0.0), nullptr,
                            fewer, nullptr, kMost - 1, csm::ceilingsForCount(kMost - 1, 8, 2048)),
        600.0, csm::ceilingsForCount(kMost - 1, 8, 2048));
    const csm::ShadowSetup kept = csm::computeShadowSetupForError(longView, lightAt(longView, 0.0),
      nullptr, settingsUpTo8, nullptr, 600.0, 2048, 1e-6, kMost - 1);
    EXPECT_EQ(kept.cascades.size(),
      static_cast<size_t>(eFewer * csm::kCountHysteresis <= eMost ? kMost - 1 : kMost));
  }
}

TEST(Steps, CascadeCountKeepsAPreviousCountWithinTheMargin)
{
  const auto settingsUpTo8 = settings(csm::WarpMode::Generalized, csm::SplitScheme::Adaptive, 8);
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
  EXPECT_EQ(
    csm::computeShadowSetupForError(mid, light, nullptr, two, nullptr, 1000.0, 2048, target, 0)
      .cascades.size(),
    1u);
  EXPECT_EQ(
    csm::computeShadowSetupForError(mid, light, nullptr, two, nullptr, 1000.0, 2048, target, 2)
      .cascades.size(),
    2u);
  EXPECT_EQ(
    csm::computeShadowSetupForError(mid, light, nullptr, two, nullptr, 1000.0, 2048, e1 / 0.7, 2)
      .cascades.size(),
    1u);
  // Bad input: the same message as a plain plan, no cascades.
  const csm::ShadowSetup bad = csm::computeShadowSetupForError(
    mid, glm::dvec3(std::nan(""), 1.0, 0.0), nullptr, two, nullptr, 1000.0, 2048, 1.0, 0);
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
  auto countFor = [&](const std::vector<csm::CasterLoad>* casters, int previous = 0)
  {
    return static_cast<int>(csm::computeShadowSetupForError(
      view, light, nullptr, upTo4, nullptr, height, 2048, target, previous, casters)
                              .cascades.size());
  };
  auto cheapest = [&](const std::vector<csm::CasterLoad>& casters)
  {
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
