// SPDX-License-Identifier: BSD-3-Clause
// The planner's state (private to the module): what vtkCascadedShadowMapPlanner.cxx and, with
// CSM_COMPARISON_TECHNIQUES, vtkCascadedShadowMapPlannerComparison.cxx share.
#ifndef vtkCascadedShadowMapPlannerInternals_h
#define vtkCascadedShadowMapPlannerInternals_h

#include "vtkCascadedShadowsConfigure.h" // for CSM_COMPARISON_TECHNIQUES
#include "vtkType.h"                     // for vtkMTimeType

#include "csmAtlas.h"
#include "csmTypes.h"
#include "csmVisibleDepth.h"

#include <glm/vec3.hpp>

#include <map>
#include <string>
#include <vector>

#if CSM_COMPARISON_TECHNIQUES
#include <glm/vec4.hpp>

namespace csm
{
struct CameraSpaceMap;
}
#endif

struct vtkCascadedShadowMapPlannerInternals
{
  csm::ShadowSetup Setup;
  /// The atlas of the last plan, and the largest map that follows the view it was planned for.
  csm::AtlasPlan Atlas;
  int MapCeiling = 0;
  std::vector<csm::Bounds> Receivers;
  std::vector<csm::CasterLoad> Casters; // what a map pass draws (AddCasterLoad)
  /// The error last reported per light (nullptr: plans from a direction) and the light's MTime
  /// then, so that a bad light is reported once until it changes.
  struct Reported
  {
    vtkMTimeType Time = 0;
    std::string Message;
  };
  std::map<const void*, Reported> ReportedErrors;
  /// The number of cascades last planned per light (AdaptiveCascades' hysteresis).
  std::map<const void*, int> LastCount;
  // What the last plan was made for (compares kept maps with it).
  csm::Camera Camera;
  glm::dvec3 wsLightDirection{ 0.0, -1.0, 0.0 };
  bool Directional = true;
  // SetVisibleDepths(): the camera that measured them and their view depths; used by the last plan.
  csm::Camera VisibleCamera;
  csm::DepthRange Visible;
  bool VisibleUsed = false;
  // SetVisibleFootprint(): where that camera's samples lie on its image, by depth.
  csm::WindowFootprint Footprint;
  bool FootprintUsed = false;
  // SetCastersChanging(): the casters change every frame.
  bool CastersChanging = false;

#if CSM_COMPARISON_TECHNIQUES
  // The comparison techniques (vtkCascadedShadowMapPlannerComparison.cxx).

  /// Face partitions of the last plan: each piece's world half-spaces (empty for cascades).
  std::vector<std::vector<glm::dvec4>> Planes;

  /// CameraSpace: the smallest w of each of the last plan's maps (empty: not camera space maps).
  std::vector<double> DepthW;
  /// CameraSpace: why the last plan's map is not focused at CameraSpaceFocus (empty: it is, or
  /// the focus is automatic), and the focus last warned about (warned once per focus).
  std::string FocusClamped;
  double WarnedFocus = 0.0;

  /// Forgets the last plan's planes, w and focus note.
  void ClearComparison();

  /// A directional light's plan (Setup, and Planes, DepthW) with FacePartitions k > 0 or
  /// CameraSpace, for a perspective camera; false where neither applies (Setup untouched: the
  /// cascades then). focus: CameraSpaceFocus.
  bool PlanComparison(int k, bool cameraSpace, double focus, const csm::Camera& camera,
    const glm::dvec3& direction, const csm::Bounds* scene, const csm::Settings& settings,
    const std::vector<csm::Bounds>* parts);

  /// A spot light's standard map (Setup) replaced by its camera space map where cameraSpace
  /// (CameraSpace with DepthClamp) and one applies.
  void PlanComparisonSpot(
    bool cameraSpace, double focus, const csm::Camera& camera, const glm::dvec3& wsPosition);

  /// The message for a camera space map whose focus was clamped (csm::CameraSpaceMap).
  void NoteFocus(const csm::CameraSpaceMap& map, double focus, const csm::Camera& fitted);

  /// Setup (and DepthW, and Planes for the dueling case) for CameraSpace: the camera space
  /// maps of the fitted frustum; false (Setup untouched) where neither case applies.
  /// focus: CameraSpaceFocus (0: the fitted range's geometric mean).
  bool PlanCameraSpace(const csm::Camera& camera, const glm::dvec3& direction,
    const csm::Bounds* scene, const csm::Settings& settings, const std::vector<csm::Bounds>* parts,
    double focus);

  /// Setup and Planes for FacePartitions k: the face partitions of the fitted frustum.
  void PlanFaces(const csm::Camera& camera, const glm::dvec3& direction, const csm::Bounds* scene,
    const csm::Settings& settings, const std::vector<csm::Bounds>* parts, int k);
#endif
};

#endif
