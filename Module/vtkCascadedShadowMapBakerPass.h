// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkCascadedShadowMapBakerPass
 * @brief   Renders the depth of the shadow casters into cascaded shadow maps.
 *
 * For every light VTK would shadow (scene or camera lights, switched on; directional lights and
 * spot lights with cone angle < 90 degrees), this pass plans the cascades with
 * vtkCascadedShadowMapPlanner (z-partitioned, warped with the generalized LiSPSM parameter of
 * Barroso & Celes; a spot light gets one perspective map) and renders the depth of the props
 * whose bounds reach each cascade's light volume into one tile of a depth-texture atlas per
 * light, cleared to far depth and sampled with hardware depth compare. When more lights cast
 * shadows than the GL context has texture units for (leaving 8 for the mappers' own textures),
 * the first ones get maps and the others are lit without shadows (one warning). Lines drawn as
 * tubes or wide and points drawn as spheres or big are drawn into the maps as wide as the main
 * view draws them (their width is in the view's pixels; Module/glsl/csmCaster.glsl).
 *
 * The cascades are planned anew every frame (microseconds), but a map is re-rendered only when
 * it must be: every map when a light, a prop, the window size or an option changed; when only
 * the camera moved, a cascade keeps the map it has (with its own world -> map matrix, still a
 * valid shadow map) while that map covers the cascade's part of the visible scene and its
 * aliasing error there (Lloyd et al. 2006) is bounded: equal to a fresh map's in a still frame,
 * within MapReuseTolerance while the user interacts (see SetInteractiveMapBorder(); the maps
 * then have InteractiveResolution texels a side). Maps are kept per renderer (and so per GL
 * context): one pass chain may serve several renderers. Used with vtkCascadedShadowMapPass,
 * which reads the maps:
 * @code
 * camera pass -> sequence{ shadowPass->GetShadowMapBakerPass(), shadowPass }
 * @endcode
 * or in one call with vtkCascadedShadowMapPass::UseShadowsOn(renderer).
 */
#ifndef vtkCascadedShadowMapBakerPass_h
#define vtkCascadedShadowMapBakerPass_h

#include "vtkCascadedShadowMapPlanner.h" // for MAXIMUM_NUMBER_OF_CASCADES
#include "vtkCascadedShadowsSetMacro.h"  // for vtkSetFiniteClampMacro
#include "vtkOpenGLRenderPass.h"
#include "vtkRenderingCascadedShadowsModule.h" // for export macro
#include "vtkSmartPointer.h"                   // for members
#include "vtkWeakPointer.h"                    // for members

#include <algorithm> // for std::equal
#include <array>     // for members
#include <atomic>    // for members
#include <future>    // for members
#include <map>       // for members
#include <memory>    // for members
#include <set>       // for members
#include <string>    // for members
#include <vector>    // for members

class vtkActor;
class vtkCamera;
class vtkCascadedShadowBlockMapper;
class csmCasterCollection;
struct csmFrameCasters;
class vtkCascadedShadowCasterPass;
class vtkLight;
class vtkMatrix4x4;
class vtkMultiProcessController;
class vtkOpenGLFramebufferObject;
class vtkOpenGLRenderWindow;
class vtkOpenGLRenderer;
class vtkOpenGLState;
class vtkPolyData;
class vtkPolyDataMapper;
class vtkProp;
class vtkRenderWindow;
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

  ///@{
  /// Resolution: width and height in texels of each cascade's map at most, four of them
  /// (csm::kAtlasFullMaps) in 2 x 2 tiles of a light's atlas; more cascades share its texels in
  /// smaller tiles, and one scene-fitted cascade alone gets them all, 2 Resolution a side
  /// (csm::atlasForCount, csm::ceilingsForCount). 64..8192. Default 2048.
  vtkSetClampMacro(Resolution, int, 64, 8192);
  vtkGetMacro(Resolution, int);
  ///@}

  ///@{
  /// While the user interacts (see SetInteractiveMapBorder()), the maps are rendered at
  /// min(InteractiveResolution, Resolution) texels a side, a quarter of the texels to fill at
  /// the default; the first still frame re-renders them at Resolution. 64..8192. Default 1024.
  vtkSetClampMacro(InteractiveResolution, int, 64, 8192);
  vtkGetMacro(InteractiveResolution, int);
  ///@}

  /**
   * How the cascades are planned is the planner's (GetPlanner(), which documents each option):
   * the number of cascades (default 8: the most AdaptiveCascades may use), the warp mode
   * (default generalized LiSPSM), the split scheme (default adaptive), lambda, alpha, depth
   * clamping, the scene-fitted cascade, ErrorTarget (default 0.7) and AdaptiveCascades. Each
   * cascade's map gets the fewest texels (a multiple of RESOLUTION_STEP) at which its predicted
   * worst aliasing error m in this renderer's viewport is at most ErrorTarget, with Resolution
   * (InteractiveResolution while the user drags) the largest map that follows the view.
   */
  /// Resolutions chosen from ErrorTarget are multiples of this.
  static constexpr int RESOLUTION_STEP = 64;

  ///@{
  /**
   * Maps across frames while the user interacts. VTK's interactor raises the window's desired
   * update rate while the user drags (vtkRenderWindow::GetDesiredUpdateRate() >= 1 here); then
   * each cascade's map is rendered with a border of InteractiveMapBorder of its width on each
   * side around its part of the scene (the texel size grows by 1 + 2 border), and a map is kept
   * while the camera moves as long as it covers the cascade's part of the visible scene and its
   * aliasing error there is at most MapReuseTolerance times that of a freshly planned map with
   * the same border (Lloyd et al. 2006, Eq. 2-4, at the vertices of the cascade's receiver body). A
   * still frame keeps only maps that are exactly what it would plan: it always has full quality.
   * Defaults 0.2 (0..0.5) and 1.25 (1..100; 1: re-render every map the camera moves). Maps
   * are only kept with DepthClamp on (without it, a kept map's near plane may cut the casters
   * of the new view).
   */
  vtkSetFiniteClampMacro(InteractiveMapBorder, double, 0.0, 0.5);
  vtkGetMacro(InteractiveMapBorder, double);
  vtkSetFiniteClampMacro(MapReuseTolerance, double, 1.0, 100.0);
  vtkGetMacro(MapReuseTolerance, double);
  ///@}

  ///@{
  /**
   * Maps across still frames (a camera path rendered frame by frame, a script's animation): a
   * map that follows the view is rendered with slack, at most 1 + MapSlack times the texels a
   * side that its error target needs, half of the factor as a border around its part of the
   * scene and half as finer texels (csm::slackedMap). The next frames keep it while it covers
   * their part of the visible scene and its aliasing error there (Lloyd et al. 2006, Eq. 2-4,
   * read by the error model at the current view) is at most what a fresh map of the needed
   * texels would have (csm::keptMapServes): every frame meets ErrorTarget, and a small camera
   * step re-renders only the maps it must. 0: maps exactly as planned, kept only for the view
   * they were planned for. 0..3. Default 0.44 (a border of 0.1 and 1.2 times the texels a
   * side).
   */
  vtkSetFiniteClampMacro(MapSlack, double, 0.0, 3.0);
  vtkGetMacro(MapSlack, double);
  ///@}

  ///@{
  /**
   * Closed casters drawn from behind. A prop whose polydata bounds solids (every edge, its
   * vertices welded by position, traversed as often in each direction: csm::classifySurface,
   * checked once per change of the data) is drawn into the maps with only its faces turned away
   * from the light. Any ray that enters a solid leaves it, so this exit layer shadows exactly
   * what the whole surface does (Wang & Molnar's second-depth shadow maps) with about half the
   * fragments, and the lit side no longer shadows itself. Props that are open (a sheet, a tube
   * without caps), drawn as wireframe or points, with lines or vertices, with clipping planes,
   * or with the user's own face culling are drawn with both sides, as before. Default on.
   */
  vtkSetMacro(CullClosedCasters, bool);
  vtkGetMacro(CullClosedCasters, bool);
  vtkBooleanMacro(CullClosedCasters, bool);
  ///@}

  ///@{
  /**
   * Casters with nothing to shadow left out of the maps. A prop that cannot shadow itself (its
   * polydata is planar, or closed and convex: csm::SurfaceClosure::canShadowItself, checked once
   * per change of the data) and whose box, swept along a directional light, reaches no other
   * prop's box (csm::sweptBoxReachesBox) casts no shadow on anything: it is not drawn into that
   * light's maps. The ground slab or floor under a model is such a prop, and it covers every
   * map. Spot lights, and several processes sharing the maps, draw every caster. Default on.
   */
  vtkSetMacro(CullCastersWithoutReceivers, bool);
  vtkGetMacro(CullCastersWithoutReceivers, bool);
  vtkBooleanMacro(CullCastersWithoutReceivers, bool);
  ///@}

  ///@{
  /**
   * Casters drawn from compact blocks. A map needs a caster's depth only, so a prop that is a
   * plain vtkActor with a plain vtkPolyDataMapper drawing polygons or strips as a surface (no
   * clipping planes) is drawn into the maps from a copy of its triangles with positions alone
   * (points split for normals welded again), split into spatial blocks of at least
   * MINIMUM_BLOCK_TRIANGLES triangles (at most MAXIMUM_BLOCKS a prop): each cascade draws only the
   * blocks whose boxes reach its light volume, so one actor spanning the scene no longer goes
   * whole into every cascade (csm::splitIntoBlocks; built once per change of the data, per
   * window; the copy costs about the positions and triangle indices once more in memory). The
   * blocks share the prop's property and matrix. Other props are drawn as they are. Default on.
   */
  vtkSetMacro(CompactCasters, bool);
  vtkGetMacro(CompactCasters, bool);
  vtkBooleanMacro(CompactCasters, bool);
  static constexpr int MINIMUM_BLOCK_TRIANGLES = 16384;
  static constexpr int MAXIMUM_BLOCKS = 64;
  /// Meshes of more triangles are prepared (blocks, closed-surface classification) by a worker
  /// thread while the frames draw them as they are; meshes of more than MOST_CLASSIFIED_TRIANGLES
  /// are not classified (drawn into the maps with both sides).
  static constexpr int SYNCHRONOUS_PREPARATION_TRIANGLES = 262144;
  static constexpr int MOST_CLASSIFIED_TRIANGLES = 4194304;
  ///@}

  ///@{
  /**
   * Cascades fitted to the depths the view really has samples at. Before it plans a frame
   * whose view or scene changed, the baker draws the depth of the casters the view can see
   * (depth only, the frame's own depth buffer, cleared again after) and reads its nearest and
   * farthest sample; the directional cascades then cover only that depth range
   * (vtkCascadedShadowMapPlanner::SetVisibleDepths). The scene's boxes often reach far nearer
   * and farther than anything the view shows (a camera among tall structures: a near plane at
   * 0.25 with the nearest sample at 15), and the split scheme spends its resolution on that
   * range. The range is measured in the frame it serves, so a frame's maps depend only on its
   * view and scene: a single render (a screenshot) gets what a second render would. It costs
   * one depth-only pass of the visible casters in each frame whose view moved (Results.md,
   * "Visible depths"). Off with several processes (each sees only its own samples), and with
   * a multisampled framebuffer (its depth cannot be read directly). Default on.
   */
  vtkSetMacro(VisibleDepthFit, bool);
  vtkGetMacro(VisibleDepthFit, bool);
  vtkBooleanMacro(VisibleDepthFit, bool);
  ///@}

  /// The planner that holds the options above and computes the cascades.
  vtkCascadedShadowMapPlanner* GetPlanner();
  /// Another planner for this pass (one may serve several bakers); null is refused.
  void SetPlanner(vtkCascadedShadowMapPlanner* planner);

  /// Includes the planner's options.
  vtkMTimeType GetMTime() override;

  ///@{
  /// Slope-scaled depth offset applied while rendering the maps (glPolygonOffset factor and
  /// units), finite; not to closed casters drawn from behind (CullClosedCasters), whose exit
  /// layer stays at its own depth (an offset there lets light through along concave creases:
  /// Documentation/Results.md, "Closed casters"). Defaults 1.1 and 2. A value that is not
  /// finite gets one error and the offset stays.
  void SetPolygonOffset(double factor, double units);
  vtkGetVector2Macro(PolygonOffset, double);
  ///@}

  ///@{
  /**
   * Distributed data: with a controller of more than one process, every process renders its
   * own casters into the maps, the maps are combined across processes (minimum depth), and all
   * processes use the same cascades, planned from the global bounds of the scene. Every process
   * must then render every frame with the same camera and lights (as ParaView and parallel VTK
   * programs do). Default: none (one process).
   */
  virtual void SetController(vtkMultiProcessController* controller);
  vtkGetObjectMacro(Controller, vtkMultiProcessController);
  ///@}

  /// Does VTK shadow this light? Scene and camera lights that are on: directional, or spot with
  /// cone angle < 90 degrees (the same rule as vtkShadowMapBakerPass), and whose
  /// ShadowAttenuation is above 0 (an invisible shadow gets no maps).
  static bool LightCastsShadows(vtkLight* light);

  /// The kinds of light that get maps.
  enum class LightKind
  {
    Directional, ///< cascades along the view (z-partitions), or a scene-fitted map
    Spot         ///< one perspective map fitted to the lit part of the visible scene
  };
  /// The kinds of map a cascade has.
  enum class MapKind
  {
    FollowsView, ///< planned for the view: re-rendered when the view moves out of what it serves
    SceneFitted, ///< fixed in the world: kept while the scene and the light stay
#if CSM_COMPARISON_TECHNIQUES
    FacePartition, ///< a face partition, selected by its planes (comparison technique)
    CameraSpace    ///< a camera space map (comparison technique)
#endif
  };

  /// One cascade's map, as the shadow pass reads it.
  struct CascadeMap
  {
    MapKind Kind = MapKind::FollowsView;
    double WorldToMap[16] = {}; ///< world -> light clip, row-major
    double SplitFar = 0.0;      ///< view depth where the cascade ends
    /// Its tile in the light's atlas, texels: x, y (from the lower left), width, height.
    int Tile[4] = {};
    /// Texels of its map along its s and t axes (from ErrorTarget), in the lower left of its
    /// tile.
    int Resolution[2] = {};
    /// Turned a quarter to its tile (vtkCascadedShadowMapPlanner::GetCascadeMapTurned).
    bool Turned = false;
    /// The main view its screen-sized casters (tubes, spheres, wide lines, big points) were
    /// sized for: world -> view (row-major) and the pixel size (the baker's casterView()).
    double CasterView[18] = {};
#if CSM_COMPARISON_TECHNIQUES
    /// Face partitions: the 4 world half-spaces of the piece
    /// (vtkCascadedShadowMapPlanner::GetCascadePlanes).
    double Planes[16] = {};
    /// Camera space maps: the smallest w of the map (its constant bias scales by it over the
    /// point's w); 0 otherwise.
    double DepthW = 0.0;
#endif
    bool IsSceneFitted() const
    {
      return this->Kind == MapKind::SceneFitted;
    }
  };

  /// The maps of one shadowed light, as the shadow pass reads them.
  struct LightMaps
  {
    vtkLight* Light = nullptr;
    int LightIndex = -1; ///< index among the renderer's switched-on lights
    LightKind Kind = LightKind::Directional;
    /// Where the maps were rendered from: the light's transformed position and focal point, and
    /// a spot light's cone angle (0 for a directional light).
    double Position[3] = { 0, 0, 0 };
    double FocalPoint[3] = { 0, 0, 0 };
    double ConeAngle = 0.0;
    double SplitNear = 0.0; ///< view depth where the first cascade begins
    /// The cascades (none: nothing to shadow for this light this frame).
    std::vector<CascadeMap> Cascades;
    int AtlasSize[2] = { 0, 0 }; ///< texels of the atlas texture
    vtkSmartPointer<vtkTextureObject> Atlas;

    int GetNumberOfCascades() const { return static_cast<int>(this->Cascades.size()); }
#if CSM_COMPARISON_TECHNIQUES
    /// The maps are face partitions, selected by their planes.
    bool SelectedByPlanes() const
    {
      return !this->Cascades.empty() && this->Cascades[0].Kind == MapKind::FacePartition;
    }
#endif
    /// Were these maps rendered for the same light geometry as other's?
    bool SameGeometry(const LightMaps& other) const
    {
      return this->Kind == other.Kind && this->ConeAngle == other.ConeAngle &&
        std::equal(this->Position, this->Position + 3, other.Position) &&
        std::equal(this->FocalPoint, this->FocalPoint + 3, other.FocalPoint);
    }
  };

  /// The shadowed lights of a renderer (as of its last Render(); null: the renderer of the last
  /// Render()), in its light order; none where it has no shadows.
  const std::vector<LightMaps>& GetLightMaps(vtkRenderer* renderer = nullptr) const;

  /// Is the user interacting with the window? VTK's convention: vtkRenderWindowInteractor raises
  /// the window's desired update rate (to 15 by default) while the user drags, and lowers it
  /// (to 0.0001) for the still frame; here interacting means a rate of at least 1 frame a second.
  static bool IsInteracting(vtkRenderWindow* window);

  /// The line width and point size VTK draws a prop with, in the main view's pixels (1 for
  /// props without a vtkProperty, and where the property's value is not finite or below 1).
  static void GetScreenSizes(vtkProp* prop, float sizes[2]);

  /// Does this prop's own lit side stay out of the maps? True for a closed surface drawn with
  /// only its faces turned away from the light (CullClosedCasters): its lit faces cannot shadow
  /// themselves, so the lookup may bias them less
  /// (vtkCascadedShadowMapPass::ClosedSurfaceBiasFactor).
  bool DrawsFromBehind(vtkProp* prop)
  {
    return this->ClosureOf(prop) != 0;
  }

  /// What the last Render() did, for tests and benchmarks (machine-independent counts; the
  /// seconds only with MeasureTimes).
  struct FrameStatistics
  {
    int CascadesRendered = 0;    ///< maps rendered
    int CascadesKept = 0;        ///< maps kept from an earlier frame
    int PropsDrawn = 0;          ///< props (or a prop's block actor) drawn into the rendered maps
    double TexelsRendered = 0.0; ///< texels of the rendered maps
    double CellsDrawn = 0.0;     ///< caster cells (triangles, lines, ...) drawn into them
    int ClosedCasters = 0;       ///< casters drawn with their exit layer only (CullClosedCasters)
    int CompactCasters = 0;      ///< casters drawn from compact blocks (CompactCasters)
    int BlocksDrawn = 0;         ///< blocks drawn into the rendered maps
    int CastersWithoutReceivers = 0;    ///< casters (or blocks) left out: they shadow nothing there
    bool VisibleDepthsUsed = false;     ///< cascades fitted to the visible depths (VisibleDepthFit)
    bool VisibleDepthsMeasured = false; ///< by a depth-only pass in this frame (VisibleDepthFit)
    double PlanSeconds = 0.0;           ///< planning, all lights (MeasureTimes)
    double MapSeconds = 0.0;     ///< rendering the maps, the GPU's work included (MeasureTimes)
    double ClearSeconds = 0.0;   ///< clearing the first light's tiles (MeasureTimes)
    double CombineSeconds = 0.0; ///< combining the maps across processes
    /// Each of the first light's re-rendered maps (MeasureTimes; 0 for a kept one).
    double CascadeSeconds[vtkCascadedShadowMapPlanner::MAXIMUM_NUMBER_OF_CASCADES] = {};
    /// CascadeSeconds[cascade], 0 for an index out of range.
    double GetCascadeSeconds(int cascade) const
    {
      return cascade >= 0 && cascade < vtkCascadedShadowMapPlanner::MAXIMUM_NUMBER_OF_CASCADES
        ? this->CascadeSeconds[cascade]
        : 0.0;
    }
  };
  const FrameStatistics& GetLastFrameStatistics() const
  {
    return this->Statistics;
  }

  ///@{
  /**
   * For benchmarks: with MeasureTimes on, Render() measures the seconds of its steps
   * (GetLastFrameStatistics()), the GPU work included: glFinish around each, which slows
   * rendering down, so it is off by default.
   */
  vtkSetMacro(MeasureTimes, bool);
  vtkGetMacro(MeasureTimes, bool);
  vtkBooleanMacro(MeasureTimes, bool);
  ///@}

protected:
  vtkCascadedShadowMapBakerPass();
  ~vtkCascadedShadowMapBakerPass() override;

  /// The maps of one renderer and the GL objects (of its window's context) that hold them.
  struct RendererMaps
  {
    vtkWeakPointer<vtkRenderer> Renderer;
    vtkOpenGLRenderWindow* Window = nullptr; // the context of the atlases and framebuffer
    std::vector<LightMaps> Maps;
    std::vector<vtkSmartPointer<vtkTextureObject>> AtlasPool; // one per light slot, reused
    vtkSmartPointer<vtkOpenGLFramebufferObject> FrameBuffer;
    vtkMTimeType LastInputTime = 0;
    int LastSize[2] = { 0, 0 };
    /// The visible depths last measured (VisibleDepthFit): the camera that measured them
    /// (null: none), its aspect and window depths; whether this frame measured them, and
    /// whether the last plan used them.
    vtkSmartPointer<vtkCamera> VisibleCamera;
    double VisibleAspect = 1.0;
    double VisibleWindow[2] = { 1.0, 0.0 };
    bool VisibleDepthsMeasured = false;
    bool VisibleDepthsUsed = false;
    /// The camera of the last plan (MapSlack: did this frame's camera take a small step?).
    vtkSmartPointer<vtkCamera> LastCamera;
  };

  /// The steps of Render(): collect the props, share them across processes, plan the lights
  /// (and choose the cascades to re-render: 1 in render per light slot and cascade), render the
  /// chosen cascades into the atlases.
  void CollectProps(vtkRenderer* renderer, RendererMaps& state, csmFrameCasters& props);
  /// The window depths of the casters this view sees, unless measured for this view and scene.
  void MeasureVisibleDepths(vtkOpenGLRenderer* renderer, const vtkRenderState* s,
    RendererMaps& state, const csmFrameCasters& props);
  void PlanLights(vtkRenderer* renderer, vtkOpenGLRenderWindow* window, RendererMaps& state,
    const csmFrameCasters& props, std::vector<LightMaps>& planned, std::vector<int>& render);
  void RenderAtlases(vtkOpenGLRenderer* renderer, vtkOpenGLRenderWindow* window,
    RendererMaps& state, const csmFrameCasters& props, std::vector<LightMaps>& planned,
    std::vector<int>& render);
  /// What every light of a frame is planned with.
  struct FramePlan
  {
    bool Interacting = false;
    bool Changed = true;      ///< every map must be rendered
    bool ScreenSized = false; ///< some caster is drawn as wide as the main view draws it
    double Border = 0.0;      ///< of the maps while interacting (InteractiveMapBorder)
    double Tolerance = 1.0;   ///< of a kept map's error while interacting
    int Ceiling = 0;          ///< texels a side of the largest map that follows the view
    int MostCascades = 0;     ///< this frame's (0: NumberOfCascades)
    int ImageHeight = 0;
    double Aspect = 1.0;
    double ViewKey[18] = {}; ///< the main view (the baker's casterView())
  };
  /// The receivers' boxes and the casters' loads, for the planner.
  void FeedPlanner(const csmFrameCasters& props);
  /// Plans one light, appends its maps to planned and, per cascade, 1 (render) or 0 (keep).
  void PlanLight(vtkRenderer* renderer, RendererMaps& state, const csmFrameCasters& props,
    const FramePlan& frame, vtkLight* light, int index, std::vector<LightMaps>& planned,
    std::vector<int>& render);
  /// The kind of the maps that the last plan made for this light, the scene-fitted one aside.
  MapKind PlannedMapKind(vtkLight* light) const;
  /// Cascade c's map as planned (or the one kept, whose map it returns true for).
  bool PlanCascade(const FramePlan& frame, vtkCamera* camera, const RendererMaps& state, int c,
    bool smoothPath, const LightMaps* kept, CascadeMap& map);
  /// Renders the cascades of one light marked in renderCascade into its atlas.
  void RenderAtlas(vtkOpenGLRenderer* renderer, vtkOpenGLRenderWindow* window, RendererMaps& state,
    const csmFrameCasters& props, LightMaps& maps, int* renderCascade, bool timed);

  RendererMaps& MapsOf(vtkRenderer* renderer, vtkOpenGLRenderWindow* window);
  bool InputsChanged(vtkRenderer* renderer, RendererMaps& state);
  bool Distributed() const;
  void CombineAcrossProcesses(vtkTextureObject* atlas);
  /// Allocates the light's atlas as planned; returns false when it cannot be allocated. Sets
  /// reallocated when the texture is new (nothing in it may be kept).
  bool PrepareAtlas(vtkOpenGLRenderWindow* window, LightMaps& maps, bool& reallocated);
  /// Gives the tiles of the cascades to render (renderCascade[c]) far depth.
  void ClearTiles(vtkOpenGLState* ostate, const LightMaps& maps, const int* renderCascade);
  void RenderCascade(vtkOpenGLRenderer* renderer, vtkOpenGLFramebufferObject* frameBuffer,
    LightMaps& maps, int cascade, const csmFrameCasters& props, bool depthClamp);
  /// +1 / -1: the prop's data is closed, its counter-clockwise faces turned outward / inward in
  /// world space; 0: draw both sides (CullClosedCasters).
  int ClosureOf(vtkProp* prop);
  /// vtkErrorMacro / vtkWarningMacro, once per distinct message.
  void ReportOnce(bool error, const std::string& message);
  /// The light camera for a cascade: the light's rotation as view, the rest as projection.
  void SetUpLightCamera(const LightMaps& maps, int cascade);
  /// Lights that can get maps in this context: a texture unit each, leaving units and uniforms
  /// for the mapper's own.
  int MaximumShadowedLights(vtkOpenGLRenderWindow* window);

  int Resolution = 2048;
  int InteractiveResolution = 1024;
  double PolygonOffset[2] = { 1.1, 2.0 }; ///< glPolygonOffset factor and units
  double MapReuseTolerance = 1.25;
  double InteractiveMapBorder = 0.2;
  double MapSlack = 0.44;
  bool MeasureTimes = false;
  bool CullClosedCasters = true;
  bool CompactCasters = true;
  bool CullCastersWithoutReceivers = true;
  bool VisibleDepthFit = true;

  std::vector<RendererMaps> Renderers;
  vtkWeakPointer<vtkRenderer> LastRenderer;
  vtkSmartPointer<vtkCascadedShadowMapPlanner> Planner;
  vtkSmartPointer<vtkCamera> LightCamera;
  vtkSmartPointer<vtkMatrix4x4> Projection;
  /// The pass in the casters' keys while the maps render (their shader hooks); not the baker
  /// itself, which owns mappers (vtkCascadedShadowCasterPass says why).
  vtkSmartPointer<vtkCascadedShadowCasterPass> CasterPass;
  vtkMultiProcessController* Controller = nullptr;
  FrameStatistics Statistics;
  long long FrameNumber = 0; ///< Render() calls
  bool ViewMoved = false;    ///< this frame's camera differs from the last one's
  /// The casters and receivers of the frames, and their caches.
  std::unique_ptr<csmCasterCollection> Casters;
  int WarnedShadowingLights = 0;  // lights over the limit last warned about: warn once
  std::set<std::string> Reported; // messages said already (ReportOnce)

private:
  vtkCascadedShadowMapBakerPass(const vtkCascadedShadowMapBakerPass&) = delete;
  void operator=(const vtkCascadedShadowMapBakerPass&) = delete;
};

#endif
