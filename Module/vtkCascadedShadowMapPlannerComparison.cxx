// SPDX-License-Identifier: BSD-3-Clause
// The planner's comparison techniques (CSM_COMPARISON_TECHNIQUES): face partitioning (Lloyd et
// al. 2006, §5.1) and camera space shadow maps (Kolić & Mihajlović), planned from the math of
// Math/Comparison. The cascades' planning is vtkCascadedShadowMapPlanner.cxx.
#include "vtkCascadedShadowMapPlanner.h"
#include "vtkCascadedShadowMapPlannerInternals.h"

#include "csmCameraSpace.h"
#include "csmFacePartition.h"
#include "csmSetup.h"

#include "vtkObjectFactory.h"

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

static_assert(CSM_COMPARISON_TECHNIQUES, "built with CSM_COMPARISON_TECHNIQUES only");

void vtkCascadedShadowMapPlannerInternals::ClearComparison()
{
  this->Planes.clear();
  this->DepthW.clear();
  this->FocusClamped.clear();
}

bool vtkCascadedShadowMapPlannerInternals::PlanComparison(int k, bool cameraSpace, double focus,
  const csm::Camera& camera, const glm::dvec3& direction, const csm::Bounds* scene,
  const csm::Settings& settings, const std::vector<csm::Bounds>* parts)
{
  this->ClearComparison();
  if (camera.parallel)
  {
    return false;
  }
  if (k > 0)
  {
    this->PlanFaces(camera, direction, scene, settings, parts, k);
    return true;
  }
  return cameraSpace && this->PlanCameraSpace(camera, direction, scene, settings, parts, focus);
}

void vtkCascadedShadowMapPlannerInternals::PlanComparisonSpot(
  bool cameraSpace, double focus, const csm::Camera& cam, const glm::dvec3& wsPosition)
{
  csm::ShadowSetup& setup = this->Setup;
  if (cameraSpace && !cam.parallel && setup.status == csm::Status::Ok && setup.cascades.size() == 1)
  {
    // Camera space (Kolić & Mihajlović §6.2) over the depth range the standard map was fitted
    // to; where the paper takes a standard map (the light in or near the view), that map.
    csm::Camera fitted = cam;
    fitted.vsNear = setup.cascades[0].vsNear;
    fitted.vsFar = setup.cascades[0].vsFar;
    const csm::CameraSpaceMap map = csm::computeCameraSpaceSpot(
      fitted, wsPosition, focus > 0.0 ? focus : std::sqrt(fitted.vsNear * fitted.vsFar));
    if (map.status == csm::Status::Ok)
    {
      setup.cascades[0].wsToClip = map.wsToClip;
      this->NoteFocus(map, focus, fitted);
    }
  }
}

void vtkCascadedShadowMapPlannerInternals::NoteFocus(
  const csm::CameraSpaceMap& map, double focus, const csm::Camera& fitted)
{
  if (map.status != csm::Status::Ok || !map.focusClamped || !(focus > 0.0))
  {
    return;
  }
  std::ostringstream message;
  message << "CameraSpaceFocus " << focus
          << " lies beyond the farthest view depth a camera space map can focus on in this view ("
          << map.vsFocus << "; the depth range fitted to the scene is " << fitted.vsNear << " to "
          << fitted.vsFar << "): the map is focused there";
  this->FocusClamped = message.str();
}

void vtkCascadedShadowMapPlanner::WarnFocusClamped()
{
  // Once per focus: the view depth it can reach changes with every camera move.
  if (!this->Internal->FocusClamped.empty() &&
    this->CameraSpaceFocus != this->Internal->WarnedFocus)
  {
    this->Internal->WarnedFocus = this->CameraSpaceFocus;
    vtkWarningMacro(<< this->Internal->FocusClamped);
  }
}

namespace
{
/// The single-cascade plan of the frustum clipped by the scene (the same input checks and depth
/// fit as the cascades'), and the camera narrowed to its fitted depth range: what the comparison
/// techniques partition.
csm::ShadowSetup fitDepthRange(const csm::Camera& camera, const glm::dvec3& direction,
  const csm::Bounds* scene, const csm::Settings& settings, const std::vector<csm::Bounds>* parts,
  csm::Camera& fitted)
{
  csm::Settings one = settings;
  one.split.scheme = csm::SplitScheme::Single;
  one.split.k = 1;
  csm::ShadowSetup setup = csm::computeShadowSetup(camera, direction, scene, one, parts);
  fitted = camera;
  fitted.vsNear = setup.vsNear;
  fitted.vsFar = setup.vsFar;
  return setup;
}
}

void vtkCascadedShadowMapPlannerInternals::PlanFaces(const csm::Camera& camera,
  const glm::dvec3& direction, const csm::Bounds* scene, const csm::Settings& settings,
  const std::vector<csm::Bounds>* parts, int k)
{
  // The face partitions of the part of the frustum the scene fills.
  csm::Camera fitted;
  csm::ShadowSetup& setup = this->Setup;
  setup = fitDepthRange(camera, direction, scene, settings, parts, fitted);
  if (setup.status != csm::Status::Ok)
  {
    return;
  }
  csm::FacePartitionSettings faces;
  faces.warp = settings.warp;
  faces.k = k;
  const csm::FacePartitioning fp = csm::computeFacePartitions(fitted, direction, faces);
  if (fp.status != csm::Status::Ok)
  {
    setup.status = fp.status;
    setup.message = fp.message;
    setup.cascades.clear();
    return;
  }
  setup.splits = fp.splits;
  setup.cascades.clear();
  for (const csm::FacePartition& piece : fp.partitions)
  {
    setup.cascades.push_back(piece.map);
    setup.cascades.back().vsNear = fitted.vsNear; // selected by their planes, not by depth
    setup.cascades.back().vsFar = fitted.vsFar;
    this->Planes.push_back(piece.wsPlanes);
  }
  setup.storageTotal = fp.storageTotal;
  setup.storageOptimal = fp.storageOptimal;
}

bool vtkCascadedShadowMapPlannerInternals::PlanCameraSpace(const csm::Camera& camera,
  const glm::dvec3& direction, const csm::Bounds* scene, const csm::Settings& settings,
  const std::vector<csm::Bounds>* parts, double focus)
{
  csm::Camera fitted;
  csm::ShadowSetup setup = fitDepthRange(camera, direction, scene, settings, parts, fitted);
  if (setup.status != csm::Status::Ok || setup.cascades.empty())
  {
    this->Setup = setup;
    return true; // nothing to shadow, or bad input: the same answer as the cascades'
  }
  // The general case (one plane), else the dueling frustum case (four planes through t).
  std::vector<csm::CameraSpaceFace> maps;
  const csm::CameraSpaceMap general = csm::computeCameraSpaceMap(
    fitted, direction, focus > 0.0 ? focus : std::sqrt(fitted.vsNear * fitted.vsFar));
  if (general.status == csm::Status::Ok)
  {
    maps.push_back({ general.wsToClip, {}, general.wMin });
    this->NoteFocus(general, focus, fitted);
  }
  else
  {
    maps = csm::computeCameraSpaceDueling(fitted, direction);
  }
  if (maps.empty())
  {
    return false; // neither applies (t at infinity): the cascades
  }
  csm::Cascade cascade = setup.cascades[0];
  cascade.nPrime = 0.0;
  cascade.Mx = 0.0; // Lloyd's M is defined for light-space maps: the maps get the ceiling
  cascade.Mz = 0.0;
  cascade.storage = 0.0;
  setup.cascades.clear();
  for (const csm::CameraSpaceFace& face : maps)
  {
    cascade.wsToClip = face.wsToClip;
    setup.cascades.push_back(cascade);
    this->DepthW.push_back(face.wMin);
    if (maps.size() > 1)
    {
      this->Planes.push_back(face.wsPlanes);
    }
  }
  setup.storageTotal = 0.0;
  this->Setup = setup;
  return true;
}

double vtkCascadedShadowMapPlanner::GetCascadeDepthW(int i) const
{
  const auto& w = this->Internal->DepthW;
  return i >= 0 && i < static_cast<int>(w.size()) ? w[i] : 0.0;
}

bool vtkCascadedShadowMapPlanner::GetCascadesSelectedByPlanes() const
{
  return !this->Internal->Planes.empty();
}

void vtkCascadedShadowMapPlanner::GetCascadePlanes(int i, double planes[16]) const
{
  for (int k = 0; k < 4; ++k)
  {
    const bool some = i >= 0 && i < static_cast<int>(this->Internal->Planes.size()) &&
      k < static_cast<int>(this->Internal->Planes[i].size());
    const glm::dvec4 plane = some ? this->Internal->Planes[i][k] : glm::dvec4(0.0, 0.0, 0.0, 1.0);
    for (int c = 0; c < 4; ++c)
    {
      planes[4 * k + c] = plane[c];
    }
  }
}
