// SPDX-License-Identifier: BSD-3-Clause
// The number of cascades from the error model (Lloyd et al. 2006, Eq. 9-10, §5.2; Barroso &
// Celes 2007, Eq. 19); see csmCascadeCount.h.
#include "csmCascadeCount.h"

#include "csmGeometry.h"
#include "csmSceneFit.h"
#include "csmSetup.h"

#include <algorithm>
#include <cmath>

namespace csm
{
namespace
{
/// computeShadowSetupForError's choice among the counts 1 .. settings.split.k.
class CountChooser
{
public:
  CountChooser(const Camera& camera, const glm::dvec3& wsLightDirection, const Bounds* sceneBounds,
    const Settings& settings, const std::vector<Bounds>* receiverParts, double imageHeight,
    const AtlasLimits& atlas, double targetError, const std::vector<CasterLoad>* casters)
    : Cam(camera)
    , Light(wsLightDirection)
    , SceneBounds(sceneBounds)
    , Set(settings)
    , ReceiverParts(receiverParts)
    , ImageHeight(imageHeight)
    , Atlas(atlas)
    , TargetError(targetError)
    , Casters(casters)
    , KMax(std::max(1, settings.split.k))
    // With casters the counts that meet the target are weighed by what they cost to render;
    // without, the smallest is taken (the cost is then the count).
    , Weighed(casters != nullptr)
  {
    // The scene-fitted map, the same for every count.
    this->Fitted = settings.sceneFitted && casters && sceneBounds &&
      sceneFit(wsLightDirection, *sceneBounds, *casters, receiverParts, this->Fit);
  }

  ShadowSetup choose(int kPrevious)
  {
    ShadowSetup invalid;
    if (!this->scanCounts(invalid))
    {
      return invalid;
    }
    return this->Chosen == 0 ? this->bestWhereNoneMeets(kPrevious)
                             : this->chosenOrPrevious(kPrevious);
  }

private:
  CascadeCeilings ceilingOf(int k) const { return planAtlas(k, this->KMax, this->Atlas).ceilings; }

  double errorOf(const ShadowSetup& plan, int k) const
  {
    return predictedError(plan, this->ImageHeight, this->ceilingOf(k));
  }

  /// A scene-fitted map costs nothing: it is drawn once while the scene and the light stay.
  double costOf(const ShadowSetup& plan, int k) const
  {
    if (!this->Weighed)
    {
      return static_cast<double>(k);
    }
    ShadowSetup followingView = plan;
    followingView.cascades.clear();
    for (const Cascade& c : plan.cascades)
    {
      if (!c.sceneFitted)
      {
        followingView.cascades.push_back(c);
      }
    }
    return followingView.cascades.empty() ? 0.0
                                          : passTexels(followingView, *this->Casters) +
        texelsForError(followingView, this->ImageHeight, this->TargetError, this->ceilingOf(k));
  }

  /// A count's plan, or (settings.sceneFitted, square tiles) the same with its farthest cascade
  /// on the scene-fitted map (sceneFit), whichever meets the target at less cost; false:
  /// neither does.
  bool meeting(const ShadowSetup& plan, int k, ShadowSetup& taken, double& cost) const
  {
    bool found = false;
    if (this->errorOf(plan, k) <= this->TargetError)
    {
      taken = plan;
      cost = this->costOf(plan, k);
      found = true;
    }
    const MapSize tile = this->ceilingOf(k).sceneFitted;
    if (!plan.sceneFitted.empty() && !plan.cascades.empty() && tile.width == tile.height)
    {
      ShadowSetup fitted = plan;
      fitted.cascades.back() = plan.sceneFitted.front();
      if (this->errorOf(fitted, k) <= this->TargetError)
      {
        const double fittedCost = this->costOf(fitted, k);
        if (!found || fittedCost <= cost)
        {
          taken = std::move(fitted);
          cost = fittedCost;
          found = true;
        }
      }
    }
    return found;
  }

  ShadowSetup planFor(int k) const
  {
    return computeShadowSetupForCount(this->Cam, this->Light, this->SceneBounds, this->Set,
      this->ReceiverParts, k, this->ceilingOf(k), this->Fitted ? &this->Fit : nullptr);
  }

  /// Plans the counts from 1 up (without casters, up to the first that meets the target): the
  /// cheapest that meets it (Chosen) and, for where none does, the count taken (Best). False
  /// with the refused plan where the input is invalid (the same for every count).
  bool scanCounts(ShadowSetup& invalid)
  {
    for (int k = 1; k <= this->KMax; ++k)
    {
      if (this->Chosen > 0 && !this->Weighed)
      {
        break;
      }
      this->Plans.push_back(this->planFor(k));
      if (this->Plans.back().status != Status::Ok)
      {
        invalid = this->Plans.back();
        return false;
      }
      this->Errors.push_back(this->errorOf(this->Plans.back(), k));
      if (this->Best == 0 || this->Errors.back() < kCountHysteresis * this->Errors[this->Best - 1])
      {
        this->Best = k;
      }
      ShadowSetup taken;
      double cost = 0.0;
      if (this->meeting(this->Plans.back(), k, taken, cost) &&
        (this->Chosen == 0 || cost < this->ChosenCost))
      {
        this->Chosen = k;
        this->ChosenPlan = std::move(taken);
        this->ChosenCost = cost;
      }
    }
    return true;
  }

  /// None meets the target. A previous count close to the best error stays (no popping
  /// between two counts that do about as well).
  ShadowSetup bestWhereNoneMeets(int kPrevious) const
  {
    if (kPrevious >= 1 && kPrevious <= this->KMax && kPrevious != this->Best &&
      this->Errors[kPrevious - 1] * kCountHysteresis <= this->Errors[this->Best - 1])
    {
      return this->Plans[kPrevious - 1];
    }
    return this->Plans[this->Best - 1];
  }

  /// Another count than the previous one does better, but not by a margin: keep the previous
  /// one if it still meets the target.
  ShadowSetup chosenOrPrevious(int kPrevious) const
  {
    if (kPrevious < 1 || kPrevious > this->KMax || kPrevious == this->Chosen)
    {
      return this->ChosenPlan;
    }
    const bool byMargin = !this->Weighed &&
      this->errorOf(this->ChosenPlan, this->Chosen) <= kCountHysteresis * this->TargetError;
    if (this->Weighed || (kPrevious > this->Chosen && !byMargin))
    {
      const ShadowSetup previous = kPrevious <= static_cast<int>(this->Plans.size())
        ? this->Plans[kPrevious - 1]
        : this->planFor(kPrevious);
      ShadowSetup taken;
      double cost = 0.0;
      if (previous.status == Status::Ok && this->meeting(previous, kPrevious, taken, cost) &&
        (!this->Weighed || kCountHysteresis * cost <= this->ChosenCost))
      {
        return taken;
      }
    }
    return this->ChosenPlan;
  }

  const Camera& Cam;
  const glm::dvec3& Light;
  const Bounds* SceneBounds;
  const Settings& Set;
  const std::vector<Bounds>* ReceiverParts;
  const double ImageHeight;
  const AtlasLimits Atlas;
  const double TargetError;
  const std::vector<CasterLoad>* Casters;
  const int KMax;
  const bool Weighed;
  SceneFit Fit;
  bool Fitted = false;

  std::vector<ShadowSetup> Plans;
  std::vector<double> Errors;
  int Chosen = 0; ///< 1-based; 0: none meets the target
  ShadowSetup ChosenPlan;
  double ChosenCost = 0.0;
  int Best = 0; ///< where none does: the count taken
};
} // namespace

ShadowSetup computeShadowSetupForCount(const Camera& camera, const glm::dvec3& wsLightDirection,
  const Bounds* sceneBounds, const Settings& settings, const std::vector<Bounds>* receiverParts,
  int k, const CascadeCeilings& maps, const SceneFit* fit)
{
  Settings s = settings;
  s.split.k = k;
  ShadowSetup plan =
    computeShadowSetup(camera, wsLightDirection, sceneBounds, s, receiverParts, fit);
  if (plan.status != Status::Ok || k < 2 || s.split.scheme != SplitScheme::Adaptive)
  {
    return plan;
  }
  s.split.scheme = SplitScheme::Log;
  ShadowSetup logPlan =
    computeShadowSetup(camera, wsLightDirection, sceneBounds, s, receiverParts, fit);
  // The common factor imageHeight does not change the order.
  return logPlan.status == Status::Ok &&
      predictedError(logPlan, 1.0, maps) < predictedError(plan, 1.0, maps)
    ? logPlan
    : plan;
}

double texelsForError(
  const ShadowSetup& setup, double imageHeight, double targetError, const CascadeCeilings& ceilings)
{
  if (setup.cascades.empty() || !(targetError > 0.0))
  {
    return kInf;
  }
  double texels = 0.0;
  for (const Cascade& c : setup.cascades)
  {
    // resolutionForError's sides, without the rounding to its step (a scene-fitted map: its
    // tile).
    const MapSize& ceiling = ceilings.of(c);
    const double side = c.sceneFitted ? kInf : std::max(c.Mx, c.Mz) * imageHeight / targetError;
    const double s = std::isfinite(side) ? side : ceiling.width;
    const double t = std::isfinite(side) ? side : ceiling.height;
    // (std::min below keeps a scene-fitted map at its tile.)
    texels += std::min<double>(std::max(s, 1.0), ceiling.width) *
      std::min<double>(std::max(t, 1.0), ceiling.height);
  }
  return texels;
}

double passTexels(const ShadowSetup& setup, const std::vector<CasterLoad>& casters)
{
  double cells = 0.0;
  for (const CasterLoad& caster : casters)
  {
    cells += std::max(caster.cells, 0.0);
  }
  double passes = 0.0;
  for (const Cascade& c : setup.cascades)
  {
    passes += c.sceneFitted ? 0.0 : 1.0;
  }
  return passes * cells * kTexelsPerCasterTriangle;
}

ShadowSetup computeShadowSetupForError(const Camera& camera, const glm::dvec3& wsLightDirection,
  const Bounds* sceneBounds, const Settings& settings, const std::vector<Bounds>* receiverParts,
  double imageHeight, const AtlasLimits& atlas, double targetError, int kPrevious,
  const std::vector<CasterLoad>* casters)
{
  CountChooser chooser(camera, wsLightDirection, sceneBounds, settings, receiverParts, imageHeight,
    atlas, targetError, casters);
  return chooser.choose(kPrevious);
}

} // namespace csm
