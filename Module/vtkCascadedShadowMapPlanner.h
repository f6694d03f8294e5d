// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkCascadedShadowMapPlanner
 * @brief   Plans the cascades of a directional light's shadow maps for a VTK camera.
 *
 * The bridge between VTK objects and the shadow math (Module/Math, no VTK there): it reads a
 * vtkCamera, a light direction and the bounds of the visible scene, and computes for each
 * cascade the world -> light clip matrix of a z-partitioned shadow map warped with the selected
 * perspective parameter (default: the generalized LiSPSM parameter of Barroso & Celes, with
 * 2 adaptive partitions and alpha = 2, as in their §4), its split depths and its aliasing error
 * (Lloyd et al. 2006). The render passes use it once per light and frame.
 *
 * Bad input (NaN light direction, degenerate camera) gives one error message and no cascades;
 * a bad vtkLight is reported once, again only when the light or the message changes.
 */
#ifndef vtkCascadedShadowMapPlanner_h
#define vtkCascadedShadowMapPlanner_h

#include "vtkCascadedShadowMapTypes.h"   // for vtkCascadedShadows::MaximumCascades
#include "vtkCascadedShadowsConfigure.h" // for CSM_COMPARISON_TECHNIQUES
#include "vtkCascadedShadowsSetMacro.h"  // for vtkSetFiniteClampMacro
#include "vtkObject.h"
#include "vtkRenderingCascadedShadowsModule.h" // for export macro

#include <memory> // for std::unique_ptr

class vtkCamera;
class vtkLight;
class vtkMatrix4x4;
struct vtkCascadedShadowMapPlannerInternals; // the planner's state (private to the module)
namespace csm
{
struct WindowFootprint;
}

class VTKRENDERINGCASCADEDSHADOWS_EXPORT vtkCascadedShadowMapPlanner : public vtkObject
{
public:
  static vtkCascadedShadowMapPlanner* New();
  vtkTypeMacro(vtkCascadedShadowMapPlanner, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum WarpModes
  {
    WARP_NONE = 0,   ///< orthographic (standard shadow map)
    WARP_PSM,        ///< n' = n
    WARP_LISPSM,     ///< n' = (n + sqrt(f n)) / sin(gamma)
    WARP_GENERALIZED ///< Barroso & Celes Eq. 16-18
  };
  enum SplitSchemes
  {
    SPLIT_SINGLE = 0,
    SPLIT_UNIFORM,
    SPLIT_LOG,
    SPLIT_PRACTICAL,
    SPLIT_ADAPTIVE
  };

  /// The most cascades a light gets (the shaders hold them in uniform arrays).
  static constexpr int MAXIMUM_NUMBER_OF_CASCADES = vtkCascadedShadows::MaximumCascades;

  ///@{
  /// Number of z-partitions (cascades), 1..MAXIMUM_NUMBER_OF_CASCADES; with AdaptiveCascades
  /// (the default) the most a frame may use. Default 8 (MAXIMUM_NUMBER_OF_CASCADES: the error
  /// model chooses; beyond csm::kAtlasFullMaps they share four full maps' texels in non-square
  /// tiles, so more cascades never cost more texels).
  vtkSetClampMacro(NumberOfCascades, int, 1, MAXIMUM_NUMBER_OF_CASCADES);
  vtkGetMacro(NumberOfCascades, int);
  ///@}

  ///@{
  /// Warp parameter. Default WARP_GENERALIZED.
  vtkSetClampMacro(WarpMode, int, WARP_NONE, WARP_GENERALIZED);
  vtkGetMacro(WarpMode, int);
  ///@}

  ///@{
  /// Split scheme. Default SPLIT_ADAPTIVE.
  vtkSetClampMacro(SplitScheme, int, SPLIT_SINGLE, SPLIT_ADAPTIVE);
  vtkGetMacro(SplitScheme, int);
  ///@}

  ///@{
  /// Weight of the log splits in the practical scheme, [0, 1]. Default 0.5.
  vtkSetFiniteClampMacro(Lambda, double, 0.0, 1.0);
  vtkGetMacro(Lambda, double);
  ///@}

  ///@{
  /// Adaptive scheme: f_i/n_i of the far partitions when light and view are parallel (> 1).
  /// Default 2 (Barroso & Celes recommend <= 2 with PCF).
  vtkSetFiniteClampMacro(Alpha, double, 1.000001, 1.0e6);
  vtkGetMacro(Alpha, double);
  ///@}

  ///@{
  /**
   * The aliasing error (Lloyd et al. 2006, Eq. 1: m, the width of a texel over that of a
   * pixel) the maps are sized for: each cascade's map gets the fewest texels at which its
   * predicted worst error is at most ErrorTarget (GetCascadeResolution()), and with
   * AdaptiveCascades the number of cascades is one that reaches it. 0: neither (every
   * map at the ceiling, NumberOfCascades cascades). 0..1e6. Default 0.7 (a texel at most 0.7 of
   * a pixel where the error is largest: against 1, the engine's worst error 0.87 -> 0.69 for at
   * most 5 % more frame time; Documentation/Tried.md, "Error target").
   */
  vtkSetFiniteClampMacro(ErrorTarget, double, 0.0, 1.0e6);
  vtkGetMacro(ErrorTarget, double);
  ///@}

  ///@{
  /**
   * Choose the number of cascades per frame from the error model: of the numbers up to
   * NumberOfCascades whose predicted worst error at the largest maps that count can have
   * (csm::ceilingsForCount: one scene-fitted cascade gets the whole atlas, others a tile) meets
   * ErrorTarget, the smallest, or with caster loads (AddCasterLoad()) the one that costs least
   * to render (passes and texels); when none does, more cascades only
   * while each cuts the predicted error to csm::kCountHysteresis; changed with hysteresis from the
   * last frame's (csm::computeShadowSetupForError; with the adaptive split scheme each count takes
   * Eq. 19's splits or the log splits, whichever predicts the smaller worst error). Needs the
   * image height and the largest map
   * resolution (see Plan()). Default on: against two fixed cascades, the towers' worst error
   * 1.27 instead of 31 (Documentation/Tried.md, "Cascade count").
   */
  vtkSetMacro(AdaptiveCascades, bool);
  vtkGetMacro(AdaptiveCascades, bool);
  vtkBooleanMacro(AdaptiveCascades, bool);
  ///@}

#if CSM_COMPARISON_TECHNIQUES
  // The comparison techniques of csm-bench (built with -DCSM_COMPARISON_TECHNIQUES=ON).

  /// The most z-partitions a face partition may have (4 faces of them fill the cascade slots).
  static constexpr int MAXIMUM_FACE_Z_PARTITIONS = MAXIMUM_NUMBER_OF_CASCADES / 4;

  ///@{
  /**
   * Face partitioning (Lloyd et al. 2006, §5.1), a comparison technique. 0 (default): cascades
   * along the view depth (SplitScheme). k = 1 or 2: a directional light's maps are the
   * partitions of the view frustum (its depth range fitted to the scene as for the cascades) by
   * the planes through its side-face edges and the light, one per side face the light enters
   * (up to 4), each z-partitioned into k log-split pieces along its face (FP+W for 1, FP+ZP+W
   * for 2), each with its own map warped with WarpMode's parameter at gamma = 90 degrees
   * (csm::computeFacePartitions); the lookup selects the piece by its planes
   * (GetCascadePlanes()). NumberOfCascades, SplitScheme and AdaptiveCascades do not apply;
   * parallel projections and spot lights get the cascades.
   */
  vtkSetClampMacro(FacePartitions, int, 0, MAXIMUM_FACE_Z_PARTITIONS);
  vtkGetMacro(FacePartitions, int);
  ///@}

  ///@{
  /**
   * Camera space shadow maps (Kolić & Mihajlović), the general case, a comparison technique:
   * with it on, a directional light gets one map (csm::computeCameraSpaceMap: the casters
   * projected along the light onto a plane inside the view frustum, captured by the camera
   * rolled so that the light comes from above) over the depth range fitted to the scene; where
   * the light lies inside the view's cone, the dueling frustum case: four maps, the casters
   * projected onto the planes through t (where the line through the eye along the light meets
   * the near plane) and the far plane's edges (csm::computeCameraSpaceDueling), selected by
   * their planes. A spot light gets one map of its casters projected from the light onto the
   * same plane (csm::computeCameraSpaceSpot, over the depth range its standard map is fitted to;
   * with DepthClamp), or its standard map where the paper takes one (the light in or near the
   * view). Parallel views and a light perpendicular to the view with no general case get the
   * cascades. FacePartitions takes precedence. Default off.
   */
  vtkSetMacro(CameraSpace, bool);
  vtkGetMacro(CameraSpace, bool);
  vtkBooleanMacro(CameraSpace, bool);
  ///@}

  ///@{
  /**
   * CameraSpace, general case: the focus range (Kolić & Mihajlović §3.1, Fig. 3), a view depth
   * in world units: the camera capturing the map is pushed back along the view until the part
   * of the view in front of this depth takes half of the map's length. 0 (default): the
   * geometric mean of the depth range fitted to the scene, sqrt(n f), which gives the near and
   * far decades equal shares as the log distribution does (Lloyd et al. 2006, §4.2); the paper
   * leaves it to the application (10-20 m for a first-person game, 500 m and more for flight).
   * A focus below about twice the fitted near depth keeps the capture at the eye (half the map
   * for the first near distances): on the directional bench scenes that misclassified slightly
   * fewer pixels, but a spot light's map captured from the eye streaks (Documentation/Results.md,
   * "Face partitions and camera space maps"). Even a
   * capture from afar holds on the middle row a depth short of the fitted far depth (about the
   * middle of the range): a focus beyond the farthest one the map can have in a view (or
   * beyond the fitted range) is clamped to it (csm::kMostPushBack), with one warning per focus.
   */
  vtkSetFiniteClampMacro(CameraSpaceFocus, double, 0.0, 1.0e300);
  vtkGetMacro(CameraSpaceFocus, double);
  ///@}

  /// For a camera space map (CameraSpace): its smallest w over the view (the constant depth
  /// bias scales by it over the point's w); 0 for cascades and face partitions.
  double GetCascadeDepthW(int i) const;

  /// Are the last plan's maps selected per point by their planes (face partitions, camera
  /// space maps of the dueling frustum case), not by view depth? Their GetCascadeNear() and
  /// GetCascadeFar() are the whole fitted range then.
  bool GetCascadesSelectedByPlanes() const;

  /// The half-spaces that hold piece i of a face partitioning (world space, 4 planes of 4
  /// numbers: a point p is inside when a p_x + b p_y + c p_z + d >= 0; (0, 0, 0, 1) where a
  /// piece has fewer); all (0, 0, 0, 1) for cascades.
  void GetCascadePlanes(int i, double planes[16]) const;
#endif

  ///@{
  /// Fit the light depth range to the receivers only and let the GPU clamp casters in front of
  /// it (Lloyd et al. §6.4). Default on.
  vtkSetMacro(DepthClamp, bool);
  vtkGetMacro(DepthClamp, bool);
  vtkBooleanMacro(DepthClamp, bool);
  ///@}

  ///@{
  /**
   * With AdaptiveCascades and caster loads (AddCasterLoad()), the farthest cascade may get an
   * orthographic map fixed in the world of the part of the scene that can be in shadow
   * (csm::sceneFit) where that meets ErrorTarget: its matrix depends only on the light and
   * the boxes, so the baker keeps its map while they stay (an orbit around a model draws it
   * once), at all the texels of its tile. A view that needs more (close to the scene, a long
   * depth range) gets the cascade fitted to it, and so does a light that follows the camera (a
   * camera light or headlight: its map would be drawn again every frame). Default on.
   */
  vtkSetMacro(SceneFittedCascades, bool);
  vtkGetMacro(SceneFittedCascades, bool);
  vtkBooleanMacro(SceneFittedCascades, bool);
  ///@}

  /// Is cascade i of the last plan a scene-fitted one (SceneFittedCascades)?
  bool GetCascadeSceneFitted(int i) const;

  /// The scene-fitted map of a directional light travelling along lightDirection over the scene
  /// bounds, from the casters and receivers set (csm::sceneFit), whatever the last plan took:
  /// world -> its clip space, row-major. False where there is none (no caster can shadow
  /// anything, a screen-sized caster, input not finite).
  bool GetSceneFittedMatrix(
    const double lightDirection[3], const double bounds[6], double worldToClip[16]) const;

  /**
   * Plan the cascades for a camera seen in a viewport of the given aspect (width/height), a
   * directional light travelling along lightDirection (world), and the world bounds of the
   * scene (xmin, xmax, ymin, ymax, zmin, zmax; null: use the view frustum alone). Returns the
   * number of cascades, 0 when there is nothing to shadow or the input is invalid (see
   * GetLastMessage()).
   */
  int Plan(vtkCamera* camera, double aspect, const double lightDirection[3], const double bounds[6],
    int imageHeight = 0, int maximumResolution = 0);

  /// imageHeight (pixels) and maximumResolution (texels a side of the largest map) are what
  /// AdaptiveCascades weighs the error with; without them it plans NumberOfCascades.
  /// The same for a vtkLight: a directional light travels from its transformed position to its
  /// transformed focal point; a positional (spot) light gets one perspective map fitted to the
  /// part of the visible scene inside its cone (cone angle < 90 degrees). mostCascades > 0
  /// plans at most that many cascades this frame (the baker's interactive frames: at most
  /// csm::kAtlasFullMaps), below NumberOfCascades; the atlas stays the one NumberOfCascades gives.
  int Plan(vtkCamera* camera, double aspect, vtkLight* light, const double bounds[6],
    int imageHeight = 0, int maximumResolution = 0, int mostCascades = 0);

  ///@{
  /**
   * Bounds of the individual receivers (props) inside the scene bounds. When given, the cascades
   * are fitted to the view clipped by each box rather than by the one box around all of them,
   * which is much tighter for a wide flat ground under a tall structure. Kept until cleared.
   */
  void ClearReceiverBounds();
  void AddReceiverBounds(const double bounds[6]);
  ///@}

  ///@{
  /**
   * The casters a map pass draws: each one's world box, its cells (triangles, lines,
   * vertices), the index of its prop's box among the receiver bounds (-1: none), whether
   * that prop may shadow itself, and whether it is drawn wider than its data (screen-sized
   * tubes, spheres, wide lines: no scene-fitted map then). When given, AdaptiveCascades takes,
   * of the counts that meet ErrorTarget, the one that costs least to render, each cascade's
   * pass drawing the casters (csm::passTexels, csm::kTexelsPerCasterTriangle) and its maps'
   * texels together; without them, the fewest cascades that meet it. They also bound the
   * scene-fitted map (SceneFittedCascades, csm::sceneFit). Kept until cleared; like the
   * receivers, not a property (setting them does not modify the planner).
   */
  void ClearCasterLoads();
  void AddCasterLoad(const double bounds[6], double cells, int receiver = -1,
    bool shadowsItself = true, bool screenSized = false);
  ///@}

  ///@{
  /**
   * Do the casters change every frame (a time series, a deforming structure)? Then no map is
   * kept from one frame to the next, and a scene-fitted map (SceneFittedCascades), which costs
   * nothing only while it is kept, would draw all the texels of its tile each frame: Plan()
   * fits the cascades to the view instead, each map sized to what ErrorTarget needs. Like the
   * caster loads, an input of the frame, not a property (setting it does not modify the
   * planner). Default false.
   */
  void SetCastersChanging(bool changing);
  bool GetCastersChanging() const;
  ///@}

  ///@{
  /**
   * The depths the view really has samples at (Lauritzen's sample distribution; the Vazquez
   * slides' "adjust the depth range to visible objects"): an earlier frame drawn by measuredBy
   * in a viewport of the given aspect had visible samples at window depths windowMin ..
   * windowMax (its depth buffer's, GL's default depth range; min > max: nothing visible). A
   * directional light's Plan() carries that range to the current camera (widened by how far
   * the camera moved and turned since: csm::carryDepthRange) and fits the cascades to that part
   * of the view only; not when the camera turned more than csm::kVisibleDepthMaximumTurnDeg.
   * Kept until cleared.
   */
  void SetVisibleDepths(vtkCamera* measuredBy, double aspect, double windowMin, double windowMax);
  void ClearVisibleDepths();
  /// Did the last Plan() fit to the visible depths (SetVisibleDepths())?
  bool GetVisibleDepthsUsed() const;
#if !defined(__VTK_WRAP__)
  /**
   * Where the samples of that same frame lie on its image, by depth (csm::windowFootprint of its
   * depth buffer; null: nowhere known). A directional light's Plan() for the very view that
   * measured them (csm::sameImage) then gives each cascade only the receivers that the image
   * rectangle of its samples shows (Lauritzen et al. 2011's tight partition bounds): the whole
   * view where its depths have none. Cleared with ClearVisibleDepths().
   */
  void SetVisibleFootprint(const csm::WindowFootprint* footprint);
#endif
  /// Did the last Plan() fit the cascades to the footprint (SetVisibleFootprint())?
  bool GetVisibleFootprintUsed() const;
  ///@}

  /// Number of cascades of the last plan.
  int GetNumberOfPlannedCascades() const;

  /// World -> light clip matrix of cascade i (after the division by w, its body is in [-1,1]^3).
  void GetCascadeMatrix(int i, vtkMatrix4x4* worldToLightClip) const;

  /// The same with a border of the given share of the map's width on each side around the body
  /// (0: none), so that a camera that moves a little stays covered (see csm::withBorder).
  void GetCascadeMatrix(int i, vtkMatrix4x4* worldToLightClip, double border) const;

  /// The same for a map of the given resolution (texels along its s and t axes): with WARP_NONE
  /// (orthographic cascades, whose width is quantized) its texel grid is fixed in the world
  /// (csm::snapToTexels), so that the shadow edges of a translating camera do not crawl. Other
  /// warp modes: as above.
  void GetCascadeMatrix(
    int i, vtkMatrix4x4* worldToLightClip, double border, const int resolution[2]) const;

  /// Split depths of cascade i along the view direction.
  double GetCascadeNear(int i) const;
  double GetCascadeFar(int i) const;

  /// Predicted worst perspective aliasing of cascade i (Lloyd et al. 2006, Eq. 9-10: the maxima
  /// M_x, M_z over its receiver body) for a map of 1 texel and an image 1 pixel high: multiply by
  /// image height / map resolution for texels per pixel. 0 for spot lights and bad indices.
  double GetCascadeMaximumAliasing(int i) const;

  /// The map resolution (texels along its s and t axes) cascade i needs for an aliasing error m
  /// of at most ErrorTarget in an image imageHeight pixels high: multiples of step, at most
  /// ceiling; the ceiling where the error is not defined (spot lights) or ErrorTarget is 0
  /// (csm::resolutionForError, along each map axis).
  void GetCascadeResolution(
    int i, int imageHeight, int step, const int ceiling[2], int resolution[2]) const;
  /// The same within the largest map cascade i has in the last plan's atlas
  /// (GetCascadeResolutionCeiling()).
  void GetCascadeResolution(int i, int imageHeight, int step, int resolution[2]) const;
  /// Does even a map of ceiling texels miss ErrorTarget for cascade i in an image imageHeight
  /// pixels high (csm::errorTargetOutOfReach)? False where ErrorTarget is 0, for spot lights,
  /// scene-fitted cascades and bad indices.
  bool GetCascadeErrorTargetOutOfReach(int i, int imageHeight, const int ceiling[2]) const;

  ///@{
  /**
   * The atlas one light's maps share, planned once with the cascades (csm::planAtlas): a depth
   * texture of the texels of min(NumberOfCascades, csm::kAtlasFullMaps) tiles of
   * AtlasResolution a side (0, the default: Plan()'s maximumResolution), within
   * MaximumTextureSize texels a side (the GL's limit; 0, the default: none), the same for every
   * count of cascades; each planned cascade's tile in it (texels: x, y from the lower left,
   * width, height) and the largest map it may have there (a scene-fitted cascade its whole
   * tile, one that follows the view at most maximumResolution a side). GetAtlasShrunk(): the
   * texture limit made the tiles smaller than AtlasResolution. For a planner used alone: the
   * baker sets both before every frame it plans (from its Resolution and the context's limit).
   */
  vtkSetClampMacro(AtlasResolution, int, 0, 65536);
  vtkGetMacro(AtlasResolution, int);
  vtkSetClampMacro(MaximumTextureSize, int, 0, 1048576);
  vtkGetMacro(MaximumTextureSize, int);
  void GetAtlasSize(int size[2]) const;
  bool GetAtlasShrunk() const;
  void GetCascadeTile(int i, int tile[4]) const;
  void GetCascadeResolutionCeiling(int i, int ceiling[2]) const;
  ///@}

  /// Is cascade i's map turned a quarter to fit a non-square tile (csm::orientToTile: its s axis
  /// follows light space z)? Plan() turns the maps for their tiles in the atlas (GetCascadeTile()).
  bool GetCascadeMapTurned(int i) const;

  /// Storage factor of the plan (Lloyd Eq. 12 summed over the cascades) and its optimum.
  double GetStorageTotal() const;
  double GetStorageOptimal() const;

  /// Angle between light and view direction of the last plan, degrees (0: light from behind).
  double GetGammaDegrees() const;

  /**
   * Perspective aliasing at a world point (Lloyd et al. Eq. 1-4 with the map and image
   * resolutions set to 1) for a world -> light clip matrix (row-major) of a directional light
   * travelling along lightDirection, seen by the camera in a viewport of the given aspect:
   * m[0] = m_x, m[1] = m_z. Multiply by image height / map resolution for texels per pixel.
   */
  static void ComputeAliasing(vtkCamera* camera, double aspect, const double lightDirection[3],
    const double worldToClip[16], const double point[3], double m[2]);

  /**
   * Can a map rendered earlier with keptWorldToClip (row-major world -> light clip) stand in for
   * cascade i of the last plan? Returns the kept map's aliasing error over the planned map's on
   * the cascade's receiver body at equal resolution (1: as good; csm::compareKeptMap), or
   * +infinity when the kept map does not cover that body with a border of marginTexels texels
   * of a map of the given resolution.
   */
  double CompareKeptMap(
    int i, const double keptWorldToClip[16], double marginTexels, int resolution) const;

  /**
   * The move of a map rendered earlier with keptWorldToClip (row-major), of resolution[2]
   * texels, that centres cascade i's receiver body in it, in whole texels (csm::panKeptMap):
   * texels[2] and the moved matrix (row-major), which CompareKeptMap judges as any kept map.
   * False where no move keeps part of the map (or none is needed).
   */
  bool PanKeptMap(int i, const double keptWorldToClip[16], const int resolution[2],
    double movedWorldToClip[16], int texels[2]) const;

  /// The cascade a view depth falls in, as the shadow lookup selects it (before it falls back to
  /// the next map covering a point a kept map misses), or -1 outside [splitNear,
  /// splitFar[count-1]].
  static int GetCascadeAtDepth(
    double viewDepth, double splitNear, const double splitFar[], int count);

  /// Why the last plan has no cascades (empty when it has some).
  const char* GetLastMessage() const;

protected:
  vtkCascadedShadowMapPlanner();
  ~vtkCascadedShadowMapPlanner() override;

  int NumberOfCascades = MAXIMUM_NUMBER_OF_CASCADES;
  int WarpMode = WARP_GENERALIZED;
  int SplitScheme = SPLIT_ADAPTIVE;
  double Lambda = 0.5;
  double Alpha = 2.0;
  bool DepthClamp = true;
  bool SceneFittedCascades = true;
  double ErrorTarget = 0.7;
  bool AdaptiveCascades = true;
#if CSM_COMPARISON_TECHNIQUES
  int FacePartitions = 0;
  bool CameraSpace = false;
  double CameraSpaceFocus = 0.0;
#endif
  int AtlasResolution = 0;
  int MaximumTextureSize = 0;

private:
  vtkCascadedShadowMapPlanner(const vtkCascadedShadowMapPlanner&) = delete;
  void operator=(const vtkCascadedShadowMapPlanner&) = delete;

  /// The atlas of the plan just made (Internal->Atlas).
  void PlanAtlas();
  void PlanDirection(vtkCamera* camera, double aspect, const double lightDirection[3],
    const double bounds[6], const void* light, int imageHeight, int maximumResolution,
    int mostCascades = 0);
  /// Reports an invalid plan once per light (null: a direction) until the light or message changes.
  int Report(const void* light, vtkMTimeType lightTime);
#if CSM_COMPARISON_TECHNIQUES
  /// Warns, once per CameraSpaceFocus, that the last plan's camera space map could not be
  /// focused there (csm::CameraSpaceMap::focusClamped).
  void WarnFocusClamped();
#endif

  std::unique_ptr<vtkCascadedShadowMapPlannerInternals> Internal;
};

#endif
