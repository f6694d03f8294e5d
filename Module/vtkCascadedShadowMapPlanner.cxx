// SPDX-License-Identifier: BSD-3-Clause
#include "vtkCascadedShadowMapPlanner.h"
#include "vtkCascadedShadowMapPlannerInternals.h"

#include "csmAliasing.h"
#include "csmAtlas.h"
#include "csmCascadeCount.h"
#include "csmCulling.h"
#include "csmReuse.h"
#include "csmSceneFit.h"
#include "csmSetup.h"
#include "csmSpotSetup.h"
#include "csmVTKMath.h"
#include "csmVisibleDepth.h"

#include "vtkCamera.h"
#include "vtkLight.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

// The planner's option values are the math's enums, in the same order.
static_assert(vtkCascadedShadowMapPlanner::WARP_NONE == int(csm::WarpMode::None) &&
    vtkCascadedShadowMapPlanner::WARP_PSM == int(csm::WarpMode::PSM) &&
    vtkCascadedShadowMapPlanner::WARP_LISPSM == int(csm::WarpMode::LiSPSM) &&
    vtkCascadedShadowMapPlanner::WARP_GENERALIZED == int(csm::WarpMode::Generalized),
  "WarpModes must match csm::WarpMode");
static_assert(vtkCascadedShadowMapPlanner::SPLIT_SINGLE == int(csm::SplitScheme::Single) &&
    vtkCascadedShadowMapPlanner::SPLIT_UNIFORM == int(csm::SplitScheme::Uniform) &&
    vtkCascadedShadowMapPlanner::SPLIT_LOG == int(csm::SplitScheme::Log) &&
    vtkCascadedShadowMapPlanner::SPLIT_PRACTICAL == int(csm::SplitScheme::Practical) &&
    vtkCascadedShadowMapPlanner::SPLIT_ADAPTIVE == int(csm::SplitScheme::Adaptive),
  "SplitSchemes must match csm::SplitScheme");
static_assert(vtkCascadedShadowMapPlanner::MAXIMUM_NUMBER_OF_CASCADES <= csm::kMaxSplits,
  "the passes cannot use more cascades than the math plans");

vtkStandardNewMacro(vtkCascadedShadowMapPlanner);

vtkCascadedShadowMapPlanner::vtkCascadedShadowMapPlanner()
  : Internal(new vtkCascadedShadowMapPlannerInternals)
{
}

vtkCascadedShadowMapPlanner::~vtkCascadedShadowMapPlanner() = default;

namespace
{
/// The atlas limits of a plan for maps of at most maximumResolution texels a side (tiles of
/// atlasResolution, 0: of maximumResolution).
csm::AtlasLimits atlasLimits(int atlasResolution, int maximumResolution, int maximumTextureSize)
{
  return csm::AtlasLimits(atlasResolution > 0 ? atlasResolution : maximumResolution,
    maximumResolution, maximumTextureSize);
}
}

void vtkCascadedShadowMapPlanner::PlanAtlas()
{
  // Once a plan: the caller allocates and draws into it, and each map is turned to its tile.
  this->Internal->Atlas =
    csm::planAtlas(static_cast<int>(this->Internal->Setup.cascades.size()), this->NumberOfCascades,
      atlasLimits(this->AtlasResolution, this->Internal->MapCeiling, this->MaximumTextureSize));
}

int vtkCascadedShadowMapPlanner::Plan(vtkCamera* camera, double aspect,
  const double lightDirection[3], const double bounds[6], int imageHeight, int maximumResolution)
{
  this->Internal->MapCeiling = maximumResolution;
  this->PlanDirection(
    camera, aspect, lightDirection, bounds, nullptr, imageHeight, maximumResolution);
  return this->Report(nullptr, 0);
}

void vtkCascadedShadowMapPlanner::PlanDirection(vtkCamera* camera, double aspect,
  const double lightDirection[3], const double bounds[6], const void* light, int imageHeight,
  int maximumResolution, int mostCascades)
{
  csm::Camera cam;
  if (!csmToCamera(camera, aspect, cam) || !lightDirection)
  {
    this->Internal->Setup = csm::ShadowSetup();
    this->Internal->Setup.message = "no camera or no light direction";
    this->Internal->VisibleUsed = false;
    this->Internal->FootprintUsed = false;
    this->PlanAtlas();
    return;
  }
  csm::Settings settings;
  settings.warp = static_cast<csm::WarpMode>(this->WarpMode);
  settings.split.scheme = static_cast<csm::SplitScheme>(this->SplitScheme);
  settings.split.k =
    mostCascades > 0 ? std::min(mostCascades, this->NumberOfCascades) : this->NumberOfCascades;
  settings.split.lambda = this->Lambda;
  settings.split.alpha = this->Alpha;
  settings.depthClamp = this->DepthClamp;
  // A map fixed in the world pays only while the light stays: not for a light that follows
  // the camera (a camera light or headlight moves with every view).
  const vtkLight* vtkLightOf = static_cast<const vtkLight*>(light);
  // (Nor while the casters change every frame: no map is kept.)
  settings.sceneFitted = this->SceneFittedCascades && !this->Internal->CastersChanging &&
    (!vtkLightOf || const_cast<vtkLight*>(vtkLightOf)->LightTypeIsSceneLight());
  settings.stableOrthographic = true; // with GetCascadeMatrix(..., resolution)'s snap
  const csm::Bounds scene = csm::Bounds::fromMinMaxPairs(bounds);
  const glm::dvec3 direction(lightDirection[0], lightDirection[1], lightDirection[2]);
  // The visible samples of an earlier frame, carried to this camera: the cascades begin where
  // the view can have samples. (Only the near end: it sets the depth ratio that the splits and
  // the warp pay for; the farthest samples are often thin far objects that cover a pixel in
  // one frame and none in the next, and the scene's boxes bound them as well.)
  const csm::DepthRange visible =
    csm::carryDepthRange(this->Internal->VisibleCamera, this->Internal->Visible, cam);
  this->Internal->VisibleUsed =
    !visible.isEmpty() && visible.vsNear > cam.vsNear && visible.vsNear < cam.vsFar;
  if (this->Internal->VisibleUsed)
  {
    cam.vsNear = visible.vsNear;
  }
  // Where the samples of this very view lie on its image, by depth: each cascade's receivers are
  // only what the image rectangle of its samples shows (SetVisibleFootprint).
  csm::ViewFootprint footprint;
  this->Internal->FootprintUsed = this->Internal->VisibleUsed &&
    !this->Internal->Footprint.isEmpty() && csm::sameImage(this->Internal->VisibleCamera, cam);
  if (this->Internal->FootprintUsed)
  {
    footprint.window = this->Internal->Footprint;
    footprint.measuredBy = this->Internal->VisibleCamera;
    settings.visibleFootprint = &footprint;
  }
  const void* lightKey = light;
  const std::vector<csm::Bounds>* parts =
    this->Internal->Receivers.empty() ? nullptr : &this->Internal->Receivers;
  this->Internal->Camera = cam;
  this->Internal->wsLightDirection = direction;
  this->Internal->Directional = true;
  const csm::Bounds* sceneOrNull = bounds ? &scene : nullptr;
#if CSM_COMPARISON_TECHNIQUES
  // The comparison techniques (perspective views only), else the cascades.
  const bool planned = this->Internal->PlanComparison(this->FacePartitions, this->CameraSpace,
    this->CameraSpaceFocus, cam, direction, sceneOrNull, settings, parts);
#else
  const bool planned = false;
#endif
  if (!planned && this->AdaptiveCascades && this->ErrorTarget > 0.0 && imageHeight > 0 &&
    maximumResolution > 0)
  {
    auto last = this->Internal->LastCount.find(lightKey);
    this->Internal->Setup =
      csm::computeShadowSetupForError(cam, direction, sceneOrNull, settings, parts, imageHeight,
        atlasLimits(this->AtlasResolution, maximumResolution, this->MaximumTextureSize),
        this->ErrorTarget, last == this->Internal->LastCount.end() ? 0 : last->second,
        this->Internal->Casters.empty() ? nullptr : &this->Internal->Casters);
  }
  else if (!planned)
  {
    this->Internal->Setup = csm::computeShadowSetup(cam, direction, sceneOrNull, settings, parts);
  }
  this->PlanAtlas();
  if (maximumResolution > 0)
  {
    // Each map turned to the tile it gets in the atlas (more than csm::kAtlasFullMaps cascades
    // share it in non-square tiles).
    csm::orientToTile(this->Internal->Setup, this->Internal->Atlas.tiles.tile);
  }
  if (this->Internal->LastCount.size() > 64)
  {
    this->Internal->LastCount.clear(); // lights come and go: keep the memory bounded
  }
  this->Internal->LastCount[lightKey] = static_cast<int>(this->Internal->Setup.cascades.size());
#if CSM_COMPARISON_TECHNIQUES
  this->WarnFocusClamped();
#endif
}

int vtkCascadedShadowMapPlanner::Plan(vtkCamera* camera, double aspect, vtkLight* light,
  const double bounds[6], int imageHeight, int maximumResolution, int mostCascades)
{
  this->Internal->MapCeiling = maximumResolution;
  if (!light)
  {
    return this->Plan(camera, aspect, static_cast<const double*>(nullptr), bounds);
  }
  double position[3], focal[3];
  light->GetTransformedPosition(position);
  light->GetTransformedFocalPoint(focal);
  const double direction[3] = { focal[0] - position[0], focal[1] - position[1],
    focal[2] - position[2] };
  if (!light->GetPositional())
  {
    this->PlanDirection(
      camera, aspect, direction, bounds, light, imageHeight, maximumResolution, mostCascades);
    return this->Report(light, light->GetMTime());
  }
  // A spot light: one perspective map fitted to the lit part of the visible scene.
  this->Internal->VisibleUsed = false;
  this->Internal->FootprintUsed = false;
#if CSM_COMPARISON_TECHNIQUES
  this->Internal->ClearComparison();
#endif
  csm::Camera cam;
  csmToCamera(camera, aspect, cam);
  const csm::Bounds scene = csm::Bounds::fromMinMaxPairs(bounds);
  if (!camera)
  {
    this->Internal->Setup = csm::ShadowSetup();
    this->Internal->Setup.message = "no camera";
  }
  else
  {
    this->Internal->Camera = cam;
    this->Internal->wsLightDirection = glm::dvec3(direction[0], direction[1], direction[2]);
    this->Internal->Directional = false;
    this->Internal->Setup =
      csm::computeSpotSetup(cam, glm::dvec3(position[0], position[1], position[2]),
        glm::dvec3(direction[0], direction[1], direction[2]), light->GetConeAngle(),
        bounds ? &scene : nullptr, this->DepthClamp);
#if CSM_COMPARISON_TECHNIQUES
    this->Internal->PlanComparisonSpot(this->CameraSpace && this->DepthClamp,
      this->CameraSpaceFocus, cam, glm::dvec3(position[0], position[1], position[2]));
#endif
  }
  this->PlanAtlas();
#if CSM_COMPARISON_TECHNIQUES
  this->WarnFocusClamped();
#endif
  return this->Report(light, light->GetMTime());
}

void vtkCascadedShadowMapPlanner::SetVisibleDepths(
  vtkCamera* measuredBy, double aspect, double windowMin, double windowMax)
{
  csm::Camera cam;
  csm::WindowDepthRange window;
  window.min = windowMin;
  window.max = windowMax;
  this->Internal->Visible =
    csmToCamera(measuredBy, aspect, cam) ? csm::viewDepthRange(window, cam) : csm::DepthRange();
  this->Internal->VisibleCamera = cam;
}

void vtkCascadedShadowMapPlanner::ClearVisibleDepths()
{
  this->Internal->Visible = csm::DepthRange();
  this->Internal->Footprint = csm::WindowFootprint();
}

void vtkCascadedShadowMapPlanner::SetVisibleFootprint(const csm::WindowFootprint* footprint)
{
  this->Internal->Footprint = footprint ? *footprint : csm::WindowFootprint();
}

bool vtkCascadedShadowMapPlanner::GetVisibleFootprintUsed() const
{
  return this->Internal->FootprintUsed;
}

bool vtkCascadedShadowMapPlanner::GetVisibleDepthsUsed() const
{
  return this->Internal->VisibleUsed;
}

void vtkCascadedShadowMapPlanner::ClearReceiverBounds()
{
  this->Internal->Receivers.clear();
}

void vtkCascadedShadowMapPlanner::AddReceiverBounds(const double bounds[6])
{
  if (bounds)
  {
    this->Internal->Receivers.push_back(csm::Bounds::fromMinMaxPairs(bounds));
  }
}

void vtkCascadedShadowMapPlanner::ClearCasterLoads()
{
  this->Internal->Casters.clear();
}

void vtkCascadedShadowMapPlanner::SetCastersChanging(bool changing)
{
  this->Internal->CastersChanging = changing;
}

bool vtkCascadedShadowMapPlanner::GetCastersChanging() const
{
  return this->Internal->CastersChanging;
}

void vtkCascadedShadowMapPlanner::AddCasterLoad(
  const double bounds[6], double cells, int receiver, bool shadowsItself, bool screenSized)
{
  // (A box that is not finite or a count that is not positive weighs nothing.)
  if (bounds && std::isfinite(cells) && cells > 0.0 &&
    std::all_of(bounds, bounds + 6, [](double v) { return std::isfinite(v); }) &&
    bounds[0] <= bounds[1] && bounds[2] <= bounds[3] && bounds[4] <= bounds[5])
  {
    this->Internal->Casters.push_back(
      { csm::Bounds::fromMinMaxPairs(bounds), cells, receiver, shadowsItself, screenSized });
  }
}

int vtkCascadedShadowMapPlanner::Report(const void* light, vtkMTimeType lightTime)
{
  const csm::ShadowSetup& setup = this->Internal->Setup;
  auto& reported = this->Internal->ReportedErrors;
  if (setup.status == csm::Status::InvalidInput)
  {
    auto last = reported.find(light);
    if (last == reported.end() || last->second.Time != lightTime ||
      last->second.Message != setup.message)
    {
      vtkErrorMacro(<< "No shadows: " << setup.message);
      reported[light] = { lightTime, setup.message };
    }
  }
  else
  {
    reported.erase(light);
  }
  return this->GetNumberOfPlannedCascades();
}

int vtkCascadedShadowMapPlanner::GetNumberOfPlannedCascades() const
{
  return static_cast<int>(this->Internal->Setup.cascades.size());
}

void vtkCascadedShadowMapPlanner::GetCascadeMatrix(int i, vtkMatrix4x4* matrix) const
{
  this->GetCascadeMatrix(i, matrix, 0.0);
}

void vtkCascadedShadowMapPlanner::GetCascadeMatrix(int i, vtkMatrix4x4* matrix, double border) const
{
  const int none[2] = { 0, 0 };
  this->GetCascadeMatrix(i, matrix, border, none);
}

void vtkCascadedShadowMapPlanner::GetCascadeMatrix(
  int i, vtkMatrix4x4* matrix, double border, const int resolution[2]) const
{
  if (!matrix)
  {
    return;
  }
  if (i < 0 || i >= this->GetNumberOfPlannedCascades())
  {
    matrix->Identity();
    return;
  }
  // (A scene-fitted map holds the whole scene: no border, so that its matrix stays; and no
  // snap, which would move its edge inside the scene by up to half a texel, so that no view
  // would find its body covered: it is fixed in the world, its texels do not crawl.)
  const csm::Cascade& cascade = this->Internal->Setup.cascades[i];
  glm::dmat4 m = csm::withBorder(cascade.wsToClip, cascade.sceneFitted ? 0.0 : border);
  if (this->WarpMode == WARP_NONE && resolution && !cascade.sceneFitted)
  {
    m = csm::snapToTexels(m, csm::MapSize(resolution[0], resolution[1]));
  }
  csmToRowMajor(m, matrix->GetData());
  matrix->Modified();
}

double vtkCascadedShadowMapPlanner::GetCascadeNear(int i) const
{
  const auto& c = this->Internal->Setup.cascades;
  return i >= 0 && i < static_cast<int>(c.size()) ? c[i].vsNear : 0.0;
}

double vtkCascadedShadowMapPlanner::GetCascadeFar(int i) const
{
  const auto& c = this->Internal->Setup.cascades;
  return i >= 0 && i < static_cast<int>(c.size()) ? c[i].vsFar : 0.0;
}

double vtkCascadedShadowMapPlanner::GetCascadeMaximumAliasing(int i) const
{
  const auto& c = this->Internal->Setup.cascades;
  return i >= 0 && i < static_cast<int>(c.size()) ? std::max(c[i].Mx, c[i].Mz) : 0.0;
}

void vtkCascadedShadowMapPlanner::GetCascadeResolution(
  int i, int imageHeight, int step, const int ceiling[2], int resolution[2]) const
{
  const auto& c = this->Internal->Setup.cascades;
  const csm::MapSize most(ceiling[0], ceiling[1]);
  const csm::MapSize size = i >= 0 && i < static_cast<int>(c.size())
    ? csm::resolutionForError(c[i], imageHeight, this->ErrorTarget, step, most)
    : most;
  resolution[0] = size.width;
  resolution[1] = size.height;
}

void vtkCascadedShadowMapPlanner::GetCascadeResolution(
  int i, int imageHeight, int step, int resolution[2]) const
{
  int ceiling[2];
  this->GetCascadeResolutionCeiling(i, ceiling);
  this->GetCascadeResolution(i, imageHeight, step, ceiling, resolution);
}

bool vtkCascadedShadowMapPlanner::GetCascadeErrorTargetOutOfReach(
  int i, int imageHeight, const int ceiling[2]) const
{
  const auto& c = this->Internal->Setup.cascades;
  return i >= 0 && i < static_cast<int>(c.size()) &&
    csm::errorTargetOutOfReach(
      c[i], imageHeight, this->ErrorTarget, csm::MapSize(ceiling[0], ceiling[1]));
}

void vtkCascadedShadowMapPlanner::GetCascadeResolutionCeiling(int i, int ceiling[2]) const
{
  const auto& c = this->Internal->Setup.cascades;
  const csm::MapSize& most =
    this->Internal->Atlas.ceilings.of(i >= 0 && i < static_cast<int>(c.size()) && c[i].sceneFitted);
  ceiling[0] = most.width;
  ceiling[1] = most.height;
}

void vtkCascadedShadowMapPlanner::GetAtlasSize(int size[2]) const
{
  size[0] = this->Internal->Atlas.texture.width;
  size[1] = this->Internal->Atlas.texture.height;
}

bool vtkCascadedShadowMapPlanner::GetAtlasShrunk() const
{
  return this->Internal->Atlas.shrunk;
}

void vtkCascadedShadowMapPlanner::GetCascadeTile(int i, int tile[4]) const
{
  const std::array<int, 4> t = i >= 0 && i < this->GetNumberOfPlannedCascades()
    ? this->Internal->Atlas.tile(i)
    : std::array<int, 4>{ 0, 0, 0, 0 };
  std::copy(t.begin(), t.end(), tile);
}

bool vtkCascadedShadowMapPlanner::GetSceneFittedMatrix(
  const double lightDirection[3], const double bounds[6], double worldToClip[16]) const
{
  if (!lightDirection || !bounds || this->Internal->Casters.empty())
  {
    return false;
  }
  csm::SceneFit fit;
  const glm::dvec3 direction(lightDirection[0], lightDirection[1], lightDirection[2]);
  if (!csm::sceneFit(direction, csm::Bounds::fromMinMaxPairs(bounds), this->Internal->Casters,
        this->Internal->Receivers.empty() ? nullptr : &this->Internal->Receivers, fit))
  {
    return false;
  }
  csmToRowMajor(fit.wsToClip, worldToClip);
  return true;
}

bool vtkCascadedShadowMapPlanner::GetCascadeSceneFitted(int i) const
{
  const auto& c = this->Internal->Setup.cascades;
  return i >= 0 && i < static_cast<int>(c.size()) && c[i].sceneFitted;
}

bool vtkCascadedShadowMapPlanner::GetCascadeMapTurned(int i) const
{
  const auto& c = this->Internal->Setup.cascades;
  return i >= 0 && i < static_cast<int>(c.size()) && c[i].mapTurned;
}

double vtkCascadedShadowMapPlanner::GetStorageTotal() const
{
  return this->Internal->Setup.storageTotal;
}

double vtkCascadedShadowMapPlanner::GetStorageOptimal() const
{
  return this->Internal->Setup.storageOptimal;
}

double vtkCascadedShadowMapPlanner::GetGammaDegrees() const
{
  return this->Internal->Setup.gammaDeg;
}

void vtkCascadedShadowMapPlanner::ComputeAliasing(vtkCamera* camera, double aspect,
  const double lightDirection[3], const double worldToClip[16], const double point[3], double m[2])
{
  m[0] = m[1] = 0.0;
  csm::Camera cam;
  if (!csmToCamera(camera, aspect, cam) || !lightDirection || !worldToClip || !point)
  {
    return;
  }
  const glm::dmat4 matrix = csmFromRowMajor(worldToClip);
  const csm::Aliasing a = csm::aliasingAt(matrix, cam,
    glm::dvec3(lightDirection[0], lightDirection[1], lightDirection[2]),
    glm::dvec3(point[0], point[1], point[2]));
  m[0] = a.mx;
  m[1] = a.mz;
}

double vtkCascadedShadowMapPlanner::CompareKeptMap(
  int i, const double keptWorldToClip[16], double marginTexels, int resolution) const
{
  const auto& cascades = this->Internal->Setup.cascades;
  if (!keptWorldToClip || i < 0 || i >= static_cast<int>(cascades.size()) || resolution <= 0)
  {
    return std::numeric_limits<double>::infinity();
  }
  const glm::dmat4 kept = csmFromRowMajor(keptWorldToClip);
  const csm::MapReuse reuse = csm::compareKeptMap(kept, cascades[i], this->Internal->Camera,
    this->Internal->wsLightDirection, this->Internal->Directional, 2.0 * marginTexels / resolution);
  return reuse.covers ? reuse.errorRatio : std::numeric_limits<double>::infinity();
}

bool vtkCascadedShadowMapPlanner::PanKeptMap(int i, const double keptWorldToClip[16],
  const int resolution[2], double movedWorldToClip[16], int texels[2]) const
{
  const auto& cascades = this->Internal->Setup.cascades;
  if (!keptWorldToClip || !resolution || !movedWorldToClip || !texels || i < 0 ||
    i >= static_cast<int>(cascades.size()))
  {
    return false;
  }
  const csm::MapPan pan = csm::panKeptMap(csmFromRowMajor(keptWorldToClip), cascades[i].wsBody,
    csm::MapSize(resolution[0], resolution[1]));
  if (!pan.valid)
  {
    return false;
  }
  csmToRowMajor(pan.wsToClip, movedWorldToClip);
  texels[0] = pan.s;
  texels[1] = pan.t;
  return true;
}

int vtkCascadedShadowMapPlanner::GetCascadeAtDepth(
  double viewDepth, double splitNear, const double splitFar[], int count)
{
  return csm::partitionAtDepth(viewDepth, splitNear, splitFar, count);
}

const char* vtkCascadedShadowMapPlanner::GetLastMessage() const
{
  return this->Internal->Setup.message.c_str();
}

void vtkCascadedShadowMapPlanner::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NumberOfCascades: " << this->NumberOfCascades << "\n";
  os << indent << "WarpMode: " << csm::toString(static_cast<csm::WarpMode>(this->WarpMode)) << "\n";
  os << indent << "SplitScheme: " << csm::toString(static_cast<csm::SplitScheme>(this->SplitScheme))
     << "\n";
  os << indent << "Lambda: " << this->Lambda << "\n";
  os << indent << "Alpha: " << this->Alpha << "\n";
  os << indent << "AtlasResolution: " << this->AtlasResolution << "\n";
  os << indent << "MaximumTextureSize: " << this->MaximumTextureSize << "\n";
  os << indent << "DepthClamp: " << (this->DepthClamp ? "on" : "off") << "\n";
  os << indent << "SceneFittedCascades: " << (this->SceneFittedCascades ? "on" : "off") << "\n";
  os << indent << "ErrorTarget: " << this->ErrorTarget << "\n";
  os << indent << "AdaptiveCascades: " << (this->AdaptiveCascades ? "on" : "off") << "\n";
#if CSM_COMPARISON_TECHNIQUES
  os << indent << "FacePartitions: " << this->FacePartitions << "\n";
  os << indent << "CameraSpace: " << (this->CameraSpace ? "on" : "off") << "\n";
  os << indent << "CameraSpaceFocus: " << this->CameraSpaceFocus << "\n";
#endif
  os << indent << "PlannedCascades: " << this->GetNumberOfPlannedCascades() << "\n";
  os << indent << "VisibleDepthsUsed: " << (this->Internal->VisibleUsed ? "yes" : "no") << "\n";
  os << indent << "VisibleFootprintUsed: " << (this->Internal->FootprintUsed ? "yes" : "no")
     << "\n";
}
