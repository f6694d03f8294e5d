// SPDX-License-Identifier: BSD-3-Clause
// The frame's plan (vtkCascadedShadowMapBakerPass's internal part): every shadowed light planned
// for this frame by the planner, and what the frame does with each of its maps
// (CascadeMap::Action): keep a map of an earlier frame, move it with the view, or draw it.
#ifndef csmLightPlanning_h
#define csmLightPlanning_h

#include "vtkCascadedShadowMapTypes.h" // for LightMaps, FrameStatistics

#include <functional>
#include <string>
#include <vector>

class vtkCamera;
class vtkCascadedShadowMapPlanner;
class vtkLight;
class vtkMultiProcessController;
class vtkOpenGLRenderWindow;
class vtkRenderer;
struct csmCascadeNeed;
struct csmFrameCasters;
struct csmFramePlan;
struct csmRendererMaps;
namespace csm
{
struct PageKey;
struct PageLevels;
}

class csmLightPlanning
{
public:
  /// Says a message once (true: an error, false: a warning).
  using Reporter = std::function<void(bool, const std::string&)>;

  /// The baker's options the plan reads (vtkCascadedShadowMapBakerPass documents each).
  struct BakerOptions
  {
    int Resolution = 0, InteractiveResolution = 0;
    double MapReuseTolerance = 1.0, InteractiveMapBorder = 0.0, MapSlack = 0.0;
    bool MoveKeptMaps = true, VisibleDepthFit = true, VisibleFootprintFit = true;
    bool LightSpacePages = true;
  };

  /// controller: several processes share the maps (null or one process: not).
  csmLightPlanning(vtkCascadedShadowMapPlanner* planner, const BakerOptions& options,
    vtkMultiProcessController* controller, vtkCascadedShadows::FrameStatistics& statistics,
    Reporter report);

  /// Would this frame be planned as the last one was? Nothing of the props changed, the same
  /// view at the same aspect, the user interacts or not as then, the same shadowed lights where
  /// they were, one process: every map of the last frame is then kept as it is (the plan of the
  /// same input is the same) and the planning, which may cost more than the frame's lookup on a
  /// scene of many props, is not done again.
  bool LastPlanStands(vtkRenderer* renderer, vtkOpenGLRenderWindow* window,
    const csmRendererMaps& state, const csmFrameCasters& props, int maximumLights) const;

  /// Plans up to maximumLights shadowed lights of the renderer for this frame into `planned`,
  /// each map with its action, and keeps the state's camera and atlas textures in step; returns
  /// how many lights cast shadows (more than maximumLights: the others are not shadowed).
  /// asLastFrame: LastPlanStands' answer for this frame (every map kept, nothing planned).
  int PlanLights(vtkRenderer* renderer, vtkOpenGLRenderWindow* window, csmRendererMaps& state,
    const csmFrameCasters& props, int maximumLights, bool asLastFrame,
    std::vector<vtkCascadedShadows::LightMaps>& planned);

private:
  bool Distributed() const;
  void FeedVisibleDepths(vtkRenderer* renderer, vtkOpenGLRenderWindow* window,
    csmRendererMaps& state, const csmFrameCasters& props);
  void PlanLight(vtkRenderer* renderer, csmRendererMaps& state, const csmFrameCasters& props,
    const csmFramePlan& frame, vtkLight* light, int index,
    std::vector<vtkCascadedShadows::LightMaps>& planned);
  vtkCascadedShadows::MapKind PlannedMapKind(vtkLight* light) const;
  void PlanCascade(const csmFramePlan& frame, vtkCamera* camera, const csmRendererMaps& state,
    int c, bool smoothPath, vtkCascadedShadows::CascadeMap& map, csmCascadeNeed& need);
  void ServeWithPages(vtkRenderer* renderer, csmRendererMaps& state, const csmFrameCasters& props,
    const csmFramePlan& frame, size_t slot, vtkCascadedShadows::LightMaps& maps);
  bool PageNeeds(const csmRendererMaps& state, const csmFramePlan& frame,
    const double worldToBase[16], int baseSide, int slots, csm::PageLevels& levels,
    std::vector<csm::PageKey>& needed) const;
  void PlanPages(csmRendererMaps& state, const csmFrameCasters& props, const csmFramePlan& frame,
    size_t slot, vtkCascadedShadows::LightMaps& maps);
  bool KeptMapServes(const csmFramePlan& frame, int c, const csmCascadeNeed& need,
    const vtkCascadedShadows::CascadeMap& map, const vtkCascadedShadows::CascadeMap& old,
    vtkCascadedShadows::CascadeMap& moved);
  void DrawWhereAnyProcessDraws(std::vector<vtkCascadedShadows::LightMaps>& planned);

  vtkCascadedShadowMapPlanner* Planner;
  BakerOptions Options;
  vtkMultiProcessController* Controller;
  vtkCascadedShadows::FrameStatistics& Statistics;
  Reporter Report;
};

#endif
