// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkCascadedShadowMapBakerPass
 * @brief   Renders the depth of the shadow casters into cascaded shadow maps.
 *
 * For every light VTK would shadow (LightCastsShadows()), GetPlanner() plans the cascades
 * (z-partitions warped with the generalized LiSPSM parameter of Barroso & Celes 2007; one
 * perspective map for a spot light) and their atlas, one depth texture per light; this pass
 * renders into each cascade's tile the casters that reach it and can shadow something in it.
 * When only the camera moved, a map is kept while its error at the new view (Lloyd et al.
 * 2006) is what a fresh map would have (MapSlack; MapReuseTolerance while the user drags).
 * Maps are kept per renderer. With vtkCascadedShadowMapPass, which reads the maps:
 * @code
 * camera pass -> sequence{ shadowPass->GetShadowMapBakerPass(), shadowPass }
 * @endcode
 * or vtkCascadedShadowMapPass::UseShadowsOn(renderer); Passes.md gives the measured reasons.
 */
#ifndef vtkCascadedShadowMapBakerPass_h
#define vtkCascadedShadowMapBakerPass_h

#include "vtkCascadedShadowMapPlanner.h" // for GetPlanner()
#include "vtkCascadedShadowMapTypes.h"   // for LightMaps, FrameStatistics
#include "vtkCascadedShadowsSetMacro.h" // for vtkSetFiniteClampMacro, vtkCascadedShadowsStatisticMacro
#include "vtkOpenGLRenderPass.h"
#include "vtkRenderingCascadedShadowsModule.h" // for export macro
#include "vtkSmartPointer.h"                   // for members
#include "vtkWeakPointer.h"                    // for members

#include <array>  // for InputsChanged
#include <memory> // for members
#include <set>    // for members
#include <string> // for members
#include <vector> // for members

class csmCasterCollection;
class csmMapDrawing;
class csmLightPlanning;
struct csmFrameCasters;
struct csmRendererMaps;
class vtkCamera;
class vtkLight;
class vtkMultiProcessController;
class vtkOpenGLRenderWindow;
class vtkOpenGLRenderer;
class vtkProp;
class vtkRenderer;
class vtkTextureObject;
class vtkWindow;

class VTKRENDERINGCASCADEDSHADOWS_EXPORT vtkCascadedShadowMapBakerPass : public vtkOpenGLRenderPass
{
public:
  static vtkCascadedShadowMapBakerPass* New();
  vtkTypeMacro(vtkCascadedShadowMapBakerPass, vtkOpenGLRenderPass);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  void Render(const vtkRenderState* s) override;
  void ReleaseGraphicsResources(vtkWindow* w) override;

  /// The planner: the number of cascades, warp, splits, ErrorTarget and the atlas layout.
  vtkCascadedShadowMapPlanner* GetPlanner();
  /// Another planner for this pass; null is refused.
  void SetPlanner(vtkCascadedShadowMapPlanner* planner);

  /// Texels a side of the largest map that follows the view; a light's atlas holds four such
  /// tiles (more cascades share them, a scene-fitted map alone gets all). 64..8192, 2048.
  vtkSetClampMacro(Resolution, int, 64, 8192);
  vtkGetMacro(Resolution, int);
  /// The same while the user drags (at most Resolution). 64..8192, 1024.
  vtkSetClampMacro(InteractiveResolution, int, 64, 8192);
  vtkGetMacro(InteractiveResolution, int);
  static constexpr int RESOLUTION_STEP =
    vtkCascadedShadows::ResolutionStep; ///< map sizes from ErrorTarget are multiples of it

  /// While the user drags (the window's desired update rate at least 1, VTK's interactor
  /// convention), maps get a border of InteractiveMapBorder of their width each side (0..0.5,
  /// 0.2) and are kept while their error is at most MapReuseTolerance times a fresh bordered
  /// map's (Lloyd et al. 2006, Eq. 2-4; 1..100, 1.25).
  vtkSetFiniteClampMacro(InteractiveMapBorder, double, 0.0, 0.5);
  vtkGetMacro(InteractiveMapBorder, double);
  vtkSetFiniteClampMacro(MapReuseTolerance, double, 1.0, 100.0);
  vtkGetMacro(MapReuseTolerance, double);

  /// Across still frames (a camera path rendered frame by frame) a map that follows the view is
  /// rendered with up to 1 + MapSlack times the texels a side it needs, half as a border and half
  /// as finer texels (csm::slackedMap), and kept, in its tile also when the count changes, while
  /// its error at the view meets a fresh map's (csm::keptMapServes). 0: kept only for the view
  /// it was planned for. 0..3, 0.44.
  vtkSetFiniteClampMacro(MapSlack, double, 0.0, 3.0);
  vtkGetMacro(MapSlack, double);

  /// A kept map that no longer serves where it is moves with the view by whole texels where
  /// the moved map serves (the same test, at this view): its texels are shifted and only the
  /// strips that came in are drawn (csm::panKeptMap). Not with several processes, nor for
  /// screen-sized casters; needs GL 4.3's image copies. On.
  vtkSetMacro(MoveKeptMaps, bool);
  vtkGetMacro(MoveKeptMaps, bool);
  vtkBooleanMacro(MoveKeptMaps, bool);

  /// A scene light whose cascades would follow the view gets its scene-fitted map (the base,
  /// 2 x Resolution a side, the very map that serves a far view alone) refined by light-space
  /// pages instead (csmPages.h): levels of half the texel of the level before, each meeting
  /// ErrorTarget an octave of view depth nearer, of which only the pages (256 texels a side)
  /// that this view's visible samples read are drawn into the rest of the atlas (3 x 3.5
  /// Resolution, no more rows than the pool the view's pixels need), and kept while the light
  /// stays: a camera that moves draws only the pages that come into view (and keeps them when it
  /// moves away again), a caster that changes only the pages its boxes reach. Where it cannot serve
  /// (several processes, a parallel view, casters that change every frame or are sized on the
  /// screen, translucent receivers, no visible depths of this view, more pages than the pool holds)
  /// the cascades serve. On.
  vtkSetMacro(LightSpacePages, bool);
  vtkGetMacro(LightSpacePages, bool);
  vtkBooleanMacro(LightSpacePages, bool);

  /// Closed casters (csm::classifySurface) drawn with only their faces turned away from the
  /// light, at their own depth: the exit layer shadows what the solid does (Wang & Molnar 1994)
  /// with half the fragments. Open, clipped, wireframe or user-culled props keep both sides. On.
  vtkSetMacro(CullClosedCasters, bool);
  vtkGetMacro(CullClosedCasters, bool);
  vtkBooleanMacro(CullClosedCasters, bool);

  /// A prop that cannot shadow itself (planar, or closed and convex) and whose box, swept along
  /// a directional light, reaches no other prop's box is left out of that light's maps (the
  /// floor under a model). Spot lights and several processes draw every caster. On.
  vtkSetMacro(CullCastersWithoutReceivers, bool);
  vtkGetMacro(CullCastersWithoutReceivers, bool);
  vtkBooleanMacro(CullCastersWithoutReceivers, bool);

  /// Plain surface actors drawn into the maps as spatial blocks of their own points (index
  /// ranges, no copy of the positions; at least MINIMUM_BLOCK_TRIANGLES a block, at most
  /// MAXIMUM_BLOCKS a prop): a cascade draws only the blocks that reach it. Meshes of more than
  /// SYNCHRONOUS_PREPARATION_TRIANGLES are prepared by a worker thread once the view moves and
  /// drawn as they are until then; beyond MOST_CLASSIFIED_TRIANGLES none is classified. On.
  vtkSetMacro(CompactCasters, bool);
  vtkGetMacro(CompactCasters, bool);
  vtkBooleanMacro(CompactCasters, bool);
  static constexpr int MINIMUM_BLOCK_TRIANGLES = vtkCascadedShadows::MinimumBlockTriangles;
  static constexpr int MAXIMUM_BLOCKS = vtkCascadedShadows::MaximumBlocks;
  static constexpr int SYNCHRONOUS_PREPARATION_TRIANGLES =
    vtkCascadedShadows::SynchronousPreparationTriangles;
  static constexpr int MOST_CLASSIFIED_TRIANGLES = vtkCascadedShadows::MostClassifiedTriangles;

  /// A directional light's cascades begin at the nearest sample the view has, measured in the
  /// frame it serves by a depth-only pass of the visible casters, whose depth the frame's own
  /// geometry pass keeps. Off with several processes and multisampled framebuffers. On.
  vtkSetMacro(VisibleDepthFit, bool);
  vtkGetMacro(VisibleDepthFit, bool);
  vtkBooleanMacro(VisibleDepthFit, bool);

  /// With VisibleDepthFit, each cascade's receivers are only the part of the view where that
  /// pass found samples at its depths (the image rectangle of each depth's samples; Lauritzen
  /// et al. 2011's tight partition bounds), so a map spends no texels on empty sky. Not where a
  /// receiver has no opaque geometry (that pass draws the casters only). On.
  vtkSetMacro(VisibleFootprintFit, bool);
  vtkGetMacro(VisibleFootprintFit, bool);
  vtkBooleanMacro(VisibleFootprintFit, bool);

  /// glPolygonOffset factor and units while rendering the maps, finite (not on closed casters'
  /// exit layer: Tried.md, "Closed casters"): what keeps the other surfaces off their own depth,
  /// scaled by their slope (the lookup adds no slope-scaled bias there). 1.1, 2.
  void SetPolygonOffset(double factor, double units);
  vtkGetVector2Macro(PolygonOffset, double);

  /// Distributed data: with a controller of several processes, each renders its own casters,
  /// the maps are combined (minimum depth), and all plan from the global bounds; every process
  /// must render every frame with the same camera and lights. Default: none.
  virtual void SetController(vtkMultiProcessController* controller);
  vtkGetObjectMacro(Controller, vtkMultiProcessController);

  /// Benchmarks: Render() times its steps with glFinish (GetLastFrameStatistics()). Off.
  vtkSetMacro(MeasureTimes, bool);
  vtkGetMacro(MeasureTimes, bool);
  vtkBooleanMacro(MeasureTimes, bool);

  /// Does VTK shadow this light? Scene and camera lights that are on, directional or spot with
  /// cone angle < 90 degrees (vtkShadowMapBakerPass's rule), with ShadowAttenuation above 0.
  static bool LightCastsShadows(vtkLight* light);

  /// The maps of a frame and what it did (vtkCascadedShadowMapTypes.h).
  using LightKind = vtkCascadedShadows::LightKind;
  using MapKind = vtkCascadedShadows::MapKind;
  using MapAction = vtkCascadedShadows::MapAction;
  using CascadeMap = vtkCascadedShadows::CascadeMap;
  using LightMaps = vtkCascadedShadows::LightMaps;
  using FrameStatistics = vtkCascadedShadows::FrameStatistics;

  /// The shadowed lights of a renderer as of its last Render() (null: the last renderer).
  const std::vector<LightMaps>& GetLightMaps(vtkRenderer* renderer = nullptr) const;
  /// The renderer the last Render() planned for (null before any): in a pass sequence the baker
  /// renders each renderer just before the shadow pass does.
  vtkRenderer* GetLastRenderer() const;

  /// The renderer whose last frame's shadow factors vtkCascadedShadowMapPass holds at its
  /// pixels (null: none; the pass sets it after each frame): a frame of it planned as that one
  /// reads them and makes no lookup, so the view's depth is not drawn for the lookups' sake.
  void SetFactorsHeldFor(vtkRenderer* renderer);

  /// Is the prop's lit side out of the maps (a closed surface drawn from behind)?
  bool DrawsFromBehind(vtkProp* prop) { return this->ClosureOf(prop) != 0; }

  /// What the last Render() did, for tests and benchmarks (seconds only with MeasureTimes).
  const FrameStatistics& GetLastFrameStatistics() const { return this->Statistics; }
  ///@{
  /// The same one by one (the struct is C++ only): maps drawn (moved ones counted as kept),
  /// kept and moved; texels and cells drawn into maps; casters; the visible-depth pass; seconds.
  vtkCascadedShadowsStatisticMacro(CascadesRendered, int);
  vtkCascadedShadowsStatisticMacro(CascadesKept, int);
  vtkCascadedShadowsStatisticMacro(CascadesMoved, int);
  vtkCascadedShadowsStatisticMacro(CascadesPatched, int);
  vtkCascadedShadowsStatisticMacro(PropsDrawn, int);
  vtkCascadedShadowsStatisticMacro(TexelsRendered, double);
  vtkCascadedShadowsStatisticMacro(CellsDrawn, double);
  vtkCascadedShadowsStatisticMacro(ClosedCasters, int);
  vtkCascadedShadowsStatisticMacro(CompactCasters, int);
  vtkCascadedShadowsStatisticMacro(BlocksDrawn, int);
  vtkCascadedShadowsStatisticMacro(CastersWithoutReceivers, int);
  vtkCascadedShadowsStatisticMacro(VisibleDepthsUsed, bool);
  vtkCascadedShadowsStatisticMacro(VisibleDepthsMeasured, bool);
  vtkCascadedShadowsStatisticMacro(VisibleFootprintUsed, bool);
  vtkCascadedShadowsStatisticMacro(ViewDepthDrawn, bool);
  vtkCascadedShadowsStatisticMacro(AsLastFrame, bool);
  vtkCascadedShadowsStatisticMacro(DepthPassStandIns, int);
  vtkCascadedShadowsStatisticMacro(PlanSeconds, double);
  vtkCascadedShadowsStatisticMacro(MapSeconds, double);
  vtkCascadedShadowsStatisticMacro(ClearSeconds, double);
  vtkCascadedShadowsStatisticMacro(CombineSeconds, double);
  double GetLastFrameCascadeSeconds(int c) const { return this->Statistics.GetCascadeSeconds(c); }
  double GetLastFrameKeptError(int c) const
  {
    return c >= 0 && c < vtkCascadedShadows::MaximumCascades ? this->Statistics.KeptError[c] : 0.0;
  }
  ///@}

protected:
  vtkCascadedShadowMapBakerPass();
  ~vtkCascadedShadowMapBakerPass() override;

  // The steps of Render() (csmBakerState.h: the per-renderer state, the frame's plan).
  void CollectProps(vtkRenderer* renderer, csmRendererMaps& state, csmFrameCasters& props);
  /// asLastFrame: the frame is planned as the last one (csmLightPlanning::LastPlanStands).
  void MeasureVisibleDepths(vtkOpenGLRenderer* renderer, const vtkRenderState* s,
    csmRendererMaps& state, const csmFrameCasters& props, bool asLastFrame);
  /// The frame's planning with the baker's options.
  csmLightPlanning Planning();
  void PlanLights(csmLightPlanning& planning, vtkRenderer* renderer, vtkOpenGLRenderWindow* window,
    csmRendererMaps& state, const csmFrameCasters& props, int maximumLights, bool asLastFrame,
    std::vector<LightMaps>& planned);
  void RenderAtlases(vtkOpenGLRenderer* renderer, vtkOpenGLRenderWindow* window,
    csmRendererMaps& state, const csmFrameCasters& props, std::vector<LightMaps>& planned);
  bool BindAtlas(vtkOpenGLRenderWindow* window, csmRendererMaps& state, LightMaps& maps);
  void ClearAndMoveMaps(vtkOpenGLRenderWindow* window, csmRendererMaps& state, LightMaps& maps);
  void RenderAtlas(vtkOpenGLRenderer* renderer, vtkOpenGLRenderWindow* window,
    csmRendererMaps& state, const csmFrameCasters& props, LightMaps& maps, bool timed);

  csmRendererMaps& MapsOf(vtkRenderer* renderer, vtkOpenGLRenderWindow* window);
  bool InputsChanged(
    vtkRenderer* renderer, csmRendererMaps& state, std::vector<std::array<double, 6>>& dirty);
  bool Distributed() const;
  void CombineAcrossProcesses(vtkTextureObject* atlas);
  bool PrepareAtlas(
    vtkOpenGLRenderWindow* window, csmRendererMaps& state, LightMaps& maps, bool& reallocated);
  int ClosureOf(vtkProp* prop);
  void ReportOnce(bool error, const std::string& message);
  int MaximumShadowedLights(vtkOpenGLRenderWindow* window);

  int Resolution = 2048;
  int InteractiveResolution = 1024;
  double PolygonOffset[2] = { 1.1, 2.0 };
  double MapReuseTolerance = 1.25, InteractiveMapBorder = 0.2, MapSlack = 0.44;
  bool MeasureTimes = false, CullClosedCasters = true, CompactCasters = true;
  bool CullCastersWithoutReceivers = true, VisibleDepthFit = true, MoveKeptMaps = true;
  bool VisibleFootprintFit = true, LightSpacePages = true;

  std::vector<std::unique_ptr<csmRendererMaps>> Renderers;
  vtkWeakPointer<vtkRenderer> LastRenderer;
  vtkWeakPointer<vtkRenderer> FactorsHeldFor;
  vtkSmartPointer<vtkCascadedShadowMapPlanner> Planner;
  vtkMultiProcessController* Controller = nullptr;
  FrameStatistics Statistics;
  long long FrameNumber = 0; ///< Render() calls
  bool ViewMoved = false;    ///< this frame's camera differs from the last one's
  std::unique_ptr<csmCasterCollection> Casters;
  std::unique_ptr<csmMapDrawing> Drawing;
  int WarnedShadowingLights = 0;  ///< lights over the limit last warned about
  std::set<std::string> Reported; ///< messages said already (ReportOnce)

private:
  vtkCascadedShadowMapBakerPass(const vtkCascadedShadowMapBakerPass&) = delete;
  void operator=(const vtkCascadedShadowMapBakerPass&) = delete;
};

#endif
