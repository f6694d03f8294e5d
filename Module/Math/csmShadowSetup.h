// SPDX-License-Identifier: BSD-3-Clause
// Per-frame shadow setup for one directional light: light space, body B, split depths, warp,
// the light view-projection matrix of each cascade, and its perspective aliasing error.
// Pure math (C++17, GLM, double precision): no VTK, no GL.
//
// Spaces (prefixes on names):
//   ws  world space.
//   cws camera-centred world space: world axes, origin at the eye (keeps numbers small far
//       from the origin).
//   vs  view space; vsDepth is the distance along the view direction.
//   ls  light space (Lloyd et al. 2006, Fig. 3): origin at the eye, y along the light's direction of travel,
//       z the view direction projected onto the plane perpendicular to y, x = y cross z.
//   clip the light's clip space: after division by w, the cascade's body lies in [-1,1]^3;
//       NDC x is the shadow-map s axis (ls x), NDC y the t axis (ls z), NDC z the light depth.
#pragma once

#include "csmConvexBody.h"
#include "csmSplits.h"
#include "csmWarp.h"

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <array>
#include <string>
#include <vector>

namespace csm
{

struct Camera
{
  glm::dvec3 wsPosition{ 0.0, 0.0, 0.0 };
  glm::dvec3 wsDirection{ 0.0, 0.0, -1.0 }; ///< view direction (need not be unit length)
  glm::dvec3 wsViewUp{ 0.0, 1.0, 0.0 };     ///< need not be orthogonal to the direction
  double vsNear = 0.1;                      ///< clipping range along the view direction
  double vsFar = 1000.0;
  double fovyDeg = 30.0;  ///< full vertical field of view (perspective)
  double aspect = 1.0;    ///< image width / height
  bool parallel = false;  ///< parallel projection
  double parallelScale = 1.0; ///< half the image height in world units (parallel projection)
};

/// An axis-aligned box; min > max on any axis means "empty".
struct Bounds
{
  glm::dvec3 wsMin{ 1.0, 1.0, 1.0 };
  glm::dvec3 wsMax{ -1.0, -1.0, -1.0 };
  bool isEmpty() const;
  bool isFinite() const;
};

struct Settings
{
  WarpMode warp = WarpMode::Generalized;
  SplitParameters split;       ///< defaults: adaptive, k = 2, alpha = 2 (Barroso & Celes 2007, §4)
  bool depthClamp = true;      ///< Lloyd et al. 2006, §6.4: fit the depth range to the receivers only
  /// Orthographic cascades of WarpMode::None get a quantized width and height (focusMatrix), so
  /// that snapToTexels() can fix their texel grid in the world. Off for the analysis (the
  /// papers' storage factors); the render passes turn it on.
  bool stableOrthographic = false;
  /// computeShadowSetupForError may give the farthest cascade the map of sceneFit, which does not
  /// follow the view, where that meets the error target (with caster loads): the passes keep it
  /// while the scene and the light stay. Off for the analysis; the render passes turn it on.
  bool sceneFitted = false;
};

/// Perspective aliasing at one point (Lloyd et al. 2006, Eq. 1-4 with all resolutions set to 1).
struct Aliasing
{
  double mx = 0.0; ///< w_lx / w_i
  double mz = 0.0; ///< w_lz / w_i
};

struct Cascade
{
  double vsNear = 0.0;           ///< split depths of this cascade
  double vsFar = 0.0;
  double nPrime = 0.0;           ///< warp parameter; +infinity when orthographic
  double gammaLimDeg = 0.0;      ///< Barroso & Celes 2007, Eq. 15 for this partition
  glm::dmat4 wsToClip{ 1.0 };    ///< world -> light clip space
  std::vector<glm::dvec3> wsBody;///< vertices of the receiver body (view partition ∩ scene)
  double Mx = 0.0;               ///< Lloyd et al. 2006, Eq. 9-10 as in §4.4: maxima over wsBody
  double Mz = 0.0;
  double storage = 0.0;          ///< Lloyd et al. 2006, Eq. 12: critical texels / image pixels = Mx Mz / aspect
  /// The map is turned a quarter (orientToTile): its s axis follows ls z and its t axis ls x, so
  /// that Mz gets the tile's width and Mx its height.
  bool mapTurned = false;
  /// Its map does not follow the view (sceneFit): it is drawn once while the scene and the light
  /// stay, with all the texels of its tile.
  bool sceneFitted = false;
};

/// Texels of a map or a tile along its s axis (width) and t axis (height).
struct MapSize
{
  int width = 0;
  int height = 0;
  MapSize() = default;
  MapSize(int side) // NOLINT: a square map of side texels
    : width(side)
    , height(side)
  {
  }
  MapSize(int w, int h)
    : width(w)
    , height(h)
  {
  }
  bool operator==(const MapSize& other) const
  {
    return width == other.width && height == other.height;
  }
};

enum class Status
{
  Ok,
  NothingToShadow, ///< empty scene, or the view sees none of it: no cascades
  InvalidInput     ///< message says what; no cascades
};

struct ShadowSetup
{
  Status status = Status::InvalidInput;
  std::string message;
  double gammaDeg = 0.0;     ///< angle between light and view direction, 0..180 (0: light from behind)
  double gammaLimDeg = 0.0;  ///< Barroso & Celes 2007, Eq. 15 for the whole fitted frustum
  double vsNear = 0.0;       ///< depth range the cascades cover (clipping range fitted to the scene)
  double vsFar = 0.0;
  std::vector<double> splits;    ///< split depths, vsNear .. vsFar
  std::vector<Cascade> cascades; ///< the non-empty cascades, near to far
  double storageTotal = 0.0;     ///< sum of the cascades' storage factors
  double storageOptimal = 0.0;   ///< Lloyd et al. 2006, App. C: ln(f/n) / (2 tan theta); NaN for parallel projection
  /// With a SceneFit: the farthest cascade with the scene-fitted map instead (0 or 1 of them).
  std::vector<Cascade> sceneFitted;
};

/// The largest maps count cascades can have: a scene-fitted cascade (drawn once while the scene
/// and the light stay) its whole tile of the atlas, resolutionCeilingForCount; a cascade that
/// follows the view (drawn again as the view moves) at most resolution texels a side of that
/// tile, so that the whole atlas a single cascade gets does not make its map cost more at every
/// re-render (Documentation/Results.md, fifteenth session). One size for both converts to this.
struct CascadeCeilings
{
  MapSize sceneFitted;
  MapSize following;
  CascadeCeilings(const MapSize& both = MapSize()) // NOLINT: a size for both kinds
    : sceneFitted(both)
    , following(both)
  {
  }
  CascadeCeilings(int side) // NOLINT: a square map of side texels for both
    : CascadeCeilings(MapSize(side))
  {
  }
  const MapSize& of(bool isSceneFitted) const { return isSceneFitted ? sceneFitted : following; }
  const MapSize& of(const Cascade& cascade) const { return of(cascade.sceneFitted); }
};

/// A caster as the cascade count and the scene-fitted map are judged by: its world box, the cells
/// (triangles, lines, vertices) a map pass draws of it, the receiver box (index into the
/// receiver parts; -1: none) of its own prop, whether that prop may shadow itself, and whether
/// it is drawn wider than its data (tubes, spheres, wide lines sized in the main view's pixels:
/// its box does not hold its shadow's extent).
struct CasterLoad
{
  Bounds wsBox;
  double cells = 0.0;
  int receiver = -1;
  bool shadowsItself = true;
  bool screenSized = false;
};

/// An orthographic map fixed in the world of the part of the scene that can be in shadow
/// (sceneFit): its light clip matrix, its map axes s and t in the world, and the four
/// half-spaces of its s, t extent (world space; normal . p + offset >= 0 inside).
struct SceneFit
{
  glm::dmat4 wsToClip{ 1.0 };
  glm::dvec3 wsMapX{ 1.0, 0.0, 0.0 };
  glm::dvec3 wsMapZ{ 0.0, 0.0, 1.0 };
  std::array<Plane, 4> wsPrism;
};

/// The map of the part of the scene a directional light can shadow, fixed in the world: a point
/// is in shadow only if a caster lies toward the light from it, so across the light only the
/// footprints of caster boxes over the boxes of receivers they can reach (sweptBoxReachesBox;
/// a prop that cannot shadow itself not over its own box) need texels; a wide ground under a
/// structure adds only the structure's footprint. Axes: the light's direction of travel as
/// depth (the scene box's extent along it), s and t perpendicular to it from the direction alone
/// (not from the view). Without receiver parts the scene box is the one receiver. Its matrix
/// depends only on the light and the boxes, so a map drawn for one view serves every view they
/// stay for. False (fit unchanged) where no caster can shadow anything, a caster is screen-sized
/// (its shadow's extent changes with the view) or the input is not finite.
bool sceneFit(const glm::dvec3& wsLightDirection, const Bounds& sceneBounds,
  const std::vector<CasterLoad>& casters, const std::vector<Bounds>* receiverParts,
  SceneFit& fit);

/// Everything a shadow pass needs for one directional light in one frame. wsLightDirection is the
/// direction the light travels. sceneBounds may be null (no clipping, no caster extrusion: the
/// bodies are the view-frustum partitions, as in the papers' analysis). receiverParts (optional,
/// with sceneBounds) are the boxes of the individual props: the receivers are then the
/// partitions clipped by each box, which fits the depth range and the maps tighter than the one
/// box around everything (a large flat ground and a tall structure, say).
///
/// With a SceneFit (and sceneBounds), sceneFitted holds the farthest cascade once more with that
/// map: its body the partition's receivers within the fit's s, t extent (the rest cannot be in
/// shadow), its Mx, Mz Lloyd et al. 2006, §4.4's maxima over that body along this view's ls x
/// and z (aliasingAt: the map's rows best aligned with them, so a map turned about the light
/// by 45 degrees reads sqrt 2 times its texel); empty where that body is.
ShadowSetup computeShadowSetup(const Camera& camera, const glm::dvec3& wsLightDirection,
  const Bounds* sceneBounds, const Settings& settings,
  const std::vector<Bounds>* receiverParts = nullptr, const SceneFit* fit = nullptr);


/// The number of cascades from the error model. Each count k in [1, settings.split.k] is judged
/// by its plan's predicted worst error, max over its cascades of max(M_x, M_z) (Lloyd et al.
/// 2006, Eq. 9-10) times imageHeight over the largest maps that count can have
/// (resolutionCeilingForCount(k, settings.split.k, maximumResolution)); of the counts whose
/// error is at most targetError, the one that costs least to render: its caster passes
/// (passTexels) plus the texels its maps need to meet the target (texelsForError); with
/// settings.sceneFitted, each count also with its farthest cascade scene-fitted (sceneFit),
/// which costs nothing (drawn once while the scene and the light stay), where that meets the
/// target. Without casters (null, the default) that is the
/// smallest count that meets the target. Where none meets it, settings.split.k (see below).
/// Changing the partitioning from frame to frame can pop (Lloyd et al. 2006, §5.2): a previous
/// count kPrevious (0: none) that still meets the target stays unless another costs at most
/// kCountHysteresis of its cost (without casters: unless a smaller count meets
/// kCountHysteresis times the target). Returns the plan for the chosen
/// count (its cascades.size() may be smaller where partitions are empty); the same input errors
/// as computeShadowSetup. With the adaptive split scheme each count's plan takes Barroso & Celes
/// 2007, Eq. 19's splits unless the log splits (Lloyd et al. 2006, Eq. 15-16) predict a smaller
/// worst error for this view: with the light along the view no warp helps, and over a long
/// depth range Eq. 19 (which only moves splits beyond the log splits) leaves the first
/// partition most of the range (f/n 1200, k 4, gamma 0: storage 22,512 against 139).
///
/// One light's maps share an atlas of the texels of min(settings.split.k, kAtlasFullMaps) maps
/// of maximumResolution a side (atlasLayout): one scene-fitted cascade gets them all, more get
/// tiles of at most maximumResolution that need not be square (atlasForCount, ceilingsForCount),
/// each map turned to its tile (predictedError). The plan returned is not turned: the caller
/// turns it for its tile (orientToTile). Where no count meets the target, more cascades are
/// taken only while each step cuts the predicted worst error to kCountHysteresis of the best
/// fewer cascades reach; a previous count within 1 / kCountHysteresis of that error stays.
ShadowSetup computeShadowSetupForError(const Camera& camera, const glm::dvec3& wsLightDirection,
  const Bounds* sceneBounds, const Settings& settings, const std::vector<Bounds>* receiverParts,
  double imageHeight, int maximumResolution, double targetError, int kPrevious,
  const std::vector<CasterLoad>* casters = nullptr);

/// What one caster triangle costs to draw into a shadow map, in texels filled: a map pass of T
/// triangles costs as much as T times this many texels (passTexels). Measured on llvmpipe
/// (Mesa's software rasterizer, 2 threads): about 130 ns a triangle of a thin-bar lattice
/// against 5-8 ns a texel of a depth map (Documentation/Results.md, thirteenth and fourteenth
/// sessions); a GPU's triangle setup against its depth fill is of the same order. A property of
/// the renderer, not of a scene.
constexpr double kTexelsPerCasterTriangle = 16.0;

/// The cost of drawing the casters into a plan's maps, in texels filled: for each cascade that
/// follows the view (a scene-fitted one is drawn once: nothing), all the casters' cells times
/// kTexelsPerCasterTriangle. (The passes cull casters per cascade, but crediting that made the
/// count choose more, cheaper-looking cascades that cost more: on the towers 4.7 cascades a
/// frame instead of 3.7 and 2.5 maps drawn a frame instead of 1.7; a pass costs its draws too.)
double passTexels(const ShadowSetup& setup, const std::vector<CasterLoad>& casters);

/// The texels the maps of a plan need for a worst error of targetError in an image imageHeight
/// pixels high: each cascade's map (square, max(M_x, M_z) texels per pixel along both axes, as
/// resolutionForError sizes it, without its rounding) within its ceiling (CascadeCeilings::of);
/// +infinity for a plan without cascades or a target that is not positive.
double texelsForError(const ShadowSetup& setup, double imageHeight, double targetError,
  const CascadeCeilings& ceilings);

/// The plan computeShadowSetupForError judges for exactly k cascades (settings.split.k is
/// ignored): with the adaptive split scheme, Barroso & Celes 2007, Eq. 19's splits or the log
/// splits, whichever predicts the smaller worst error on maps of the given sizes (turned to
/// them; square by default); else computeShadowSetup's.
ShadowSetup computeShadowSetupForCount(const Camera& camera, const glm::dvec3& wsLightDirection,
  const Bounds* sceneBounds, const Settings& settings, const std::vector<Bounds>* receiverParts,
  int k, const CascadeCeilings& maps = MapSize(1), const SceneFit* fit = nullptr);

/// Share of the error target a smaller cascade count must meet to replace a previous count, and
/// share of the error a larger count must reach to be taken where none meets the target.
constexpr double kCountHysteresis = 0.8;

/// One light's cascades share one depth texture (an atlas) with the texels of at most this many
/// maps of the largest resolution, allocated once for the most cascades planned: the count
/// changes with the view, and a new texture would cost its allocation (on a software
/// rasterizer, more than drawing the maps into it) and every map's render. The texels (and the
/// memory) do not grow with the number of cascades; one cascade alone, where it is scene-fitted
/// (drawn once), gets them all in one map.
constexpr int kAtlasFullMaps = 4;

/// An atlas, or a grid of equal tiles in one: texels of the tiles along s and t, and their
/// columns and rows.
struct AtlasGrid
{
  int columns = 1;
  int rows = 1;
  MapSize tile;
};

/// The atlas for at most mostCascades maps of resolution texels a side: min(mostCascades,
/// kAtlasFullMaps) square tiles of that resolution, four in 2 x 2 (a square texture: one map
/// can have all its texels), two or three in a row. Where maximumSide (a GL texture's size
/// limit; 0: none) is less than the texture's side, the tiles shrink to fit it. A 1 x 1 grid of
/// 0 texels for counts or resolutions below 1.
AtlasGrid atlasLayout(int mostCascades, int resolution, int maximumSide = 0);

/// The grid of count equal tiles in an atlas of atlas.columns x atlas.rows tiles of atlas.tile
/// texels, no side longer than atlas.tile's: of the grids with columns x rows >= count, the one
/// whose tiles have the longest short side, then the largest area (ties: fewer columns). Tiles
/// need not be square: 5 or 6 cascades in 2 x 2 tiles of 2048 get 2048 x 1365 each, and a
/// cascade turned to its tile (orientToTile) keeps 2048 texels where its error is largest.
AtlasGrid atlasGrid(int count, const AtlasGrid& atlas);

/// The tiles count cascades get in the atlas of atlasLayout (atlas), within its texture: one
/// cascade the largest square it holds (4096² in 2 x 2 tiles of 2048), more the grid of
/// atlasGrid(count, atlas). A 1 x 1 grid of 0 texels for counts or atlases without texels.
AtlasGrid atlasForCount(int count, const AtlasGrid& atlas);

/// The largest map count cascades can have in the atlas of atlasLayout(mostCascades,
/// resolution): its tile in atlasForCount (at 2048 with four or more most cascades: 1 cascade
/// 4096², 2-4 cascades 2048², 5-6 cascades 2048 x 1365, 7-8 cascades 1365²). 0 x 0 for
/// counts or resolutions below 1.
MapSize resolutionCeilingForCount(int count, int mostCascades, int resolution);

/// ceilingsForCount(count, mostCascades, resolution): see CascadeCeilings (0 x 0 where
/// resolutionCeilingForCount is).
CascadeCeilings ceilingsForCount(int count, int mostCascades, int resolution);

/// A cascade's predicted worst error on a map of the given size, turned as orientToTile would
/// turn it: min over both orientations of max(M_s / width, M_t / height) times imageHeight.
/// +infinity for a map without texels.
double predictedError(const Cascade& cascade, double imageHeight, const MapSize& map);

/// The predicted worst error of a plan (see computeShadowSetupForError): the largest of its
/// cascades' on the largest maps they can have (CascadeCeilings::of); +infinity without
/// cascades.
double predictedError(const ShadowSetup& setup, double imageHeight, const CascadeCeilings& maps);

/// Turn each cascade's map a quarter (rows s, t of wsToClip to t, -s: a rotation, so the
/// triangles keep their winding) where that gives its larger error the longer side of a
/// non-square tile, and set its mapTurned. A square tile changes nothing.
void orientToTile(ShadowSetup& setup, const MapSize& tile);

/// Lloyd's M along the cascade's map axes s and t: (Mx, Mz), or (Mz, Mx) where its map is turned.
glm::dvec2 mapAxisAliasing(const Cascade& cascade);

/// One perspective map for a spot light at wsLightPosition shining along wsLightAxis with the
/// given cone half-angle (< 90 degrees), fitted to what the view needs: the part of the visible
/// scene (view frustum clipped by the scene bounds, may be null) inside the cone's bounding
/// pyramid. One cascade covering the fitted depth range; its Mx, Mz and storage are 0 (Lloyd's
/// metric is defined for directional lights).
ShadowSetup computeSpotSetup(const Camera& camera, const glm::dvec3& wsLightPosition,
  const glm::dvec3& wsLightAxis, double coneAngleDeg, const Bounds* sceneBounds, bool depthClamp);

/// Lloyd et al. 2006, Eq. 2-4 at a world point for a light clip matrix: beam widths of one shadow-map texel
/// (map resolution 1) along ls x and ls z over the width of one image pixel (image height 1).
/// Each is measured along the map row that follows it: s for ls x and t for ls z, the other
/// way round for a map turned by orientToTile (whose t row is the one along ls x); for a map
/// whose axes are not ls x and z (kept from an earlier camera, or VTK's), the better aligned.
Aliasing aliasingAt(const glm::dmat4& wsToClip, const Camera& camera,
  const glm::dvec3& wsLightDirection, const glm::dvec3& wsPoint);

/// The same for a map whose s and t axes follow the unit vectors wsMapX and wsMapZ, both
/// perpendicular to the light (a face partition's map, whose z axis is not the projected view
/// direction: Lloyd et al. 2006, §5.1).
Aliasing aliasingAt(const glm::dmat4& wsToClip, const Camera& camera, const glm::dvec3& wsMapX,
  const glm::dvec3& wsMapZ, const glm::dvec3& wsPoint);

/// Why computeShadowSetup would refuse this camera; empty when it is valid.
std::string cameraError(const Camera& camera);

/// Why a directional light's direction cannot be used (not finite, or zero); empty when it can.
std::string lightDirectionError(const glm::dvec3& wsLightDirection);

/// The map resolution (texels a side) at which a cascade whose worst perspective aliasing is
/// maxAliasing (max(M_x, M_z) of Lloyd et al. 2006, Eq. 9-10, for a map of 1 texel and an image
/// 1 pixel high) reaches the error targetError (m, a texel's width over a pixel's, Eq. 1) in an
/// image imageHeight pixels high: maxAliasing * imageHeight / targetError, rounded up to a
/// multiple of step and kept in [step, ceiling]. The ceiling when any input is not a finite
/// positive number (spot lights have no M; a target of 0 means "always the ceiling").
int resolutionForError(double maxAliasing, double imageHeight, double targetError, int step,
  int ceiling);

/// The same for a cascade's map on a tile of at most ceiling texels along s and t: the texels
/// its larger M needs (max(Mx, Mz)) along both axes, each in [step, its side of the ceiling].
/// (Sized per axis, the map would be sharper along one axis than the other and the filter's
/// footprint elongated: the box and plane scene of the tests then darkens 4 % more pixels.)
MapSize resolutionForError(const Cascade& cascade, double imageHeight, double targetError,
  int step, const MapSize& ceiling);

/// The warp of a cascade in light space (rows: map s, map t, depth, w): orthographic for an
/// infinite n', else a perspective along ls z whose centre lies n' before the body's nearest
/// ls z (Barroso & Celes 2007, Fig. 4 and 6).
glm::dmat4 warpMatrix(double nPrime, double lsZMin);

/// The focus: the scale and offset that take the warped light-space points' bounds to
/// [-1, 1]^3, with 1 % of room in depth for the bias (Lloyd et al. 2006, §6.4).
/// With quantizeExtent (orthographic cascades of WarpMode::None), the map's width and height
/// are rounded up to the next quarter power of two with 4 % of room, so that a camera moving a
/// little keeps the same texel size (see snapToTexels()).
glm::dmat4 focusMatrix(const std::vector<glm::dvec3>& lsPoints, const glm::dmat4& lsToWarped,
  bool quantizeExtent = false);

/// Share of an orthographic map's scale that its depth range (along the light) keeps at least:
/// the larger of its body's extent across the light and the distance of its farthest point from
/// the eye. Depth clamping fits the range to the receivers (Lloyd et al. 2006, §6.4), and a
/// flat receiver perpendicular to the light (a ground under an overhead light, alone in a far
/// cascade) has one depth: fitted to it, the map's depth scale would magnify the float rounding
/// of the lookup's and the rasterizer's positions (a few 1e-7 of the distance from the eye)
/// beyond the constant depth bias, which is a share of the range (0.002 by default), and the
/// ground would shadow itself in stripes. At 1/50 the default bias is 4e-5 of that distance,
/// about a hundred times the rounding and still a small part of a texel (the passes' box over a
/// ground, llvmpipe: clean at 1/2000, striped at 1/50000).
constexpr double kOrthographicDepthShare = 1.0 / 50.0;

/// The least depth range of an orthographic map whose body spans lsAcross across the light and
/// whose farthest point lies eyeDistance from the eye (0 where no eye applies):
/// kOrthographicDepthShare of the larger; 0 for values that are not finite.
double orthographicDepthFloor(double lsAcross, double eyeDistance);

/// An orthographic (affine) world -> clip matrix moved by less than half a texel of a map of
/// the given resolution so that its texel grid is fixed in the world: the texel edges of two
/// frames of a translating camera coincide, and shadow edges do not crawl (the cascaded-maps
/// stabilisation of Vázquez's and King's slides). Unchanged when the matrix is projective or the
/// resolution is not positive.
glm::dmat4 snapToTexels(const glm::dmat4& wsToClip, const MapSize& resolution);

/// True when no point of the box can land inside the light clip volume (conservative test in
/// homogeneous clip space). With depthClamp, points nearer than the near plane count as inside.
bool boxOutsideClipVolume(const glm::dmat4& wsToClip, const Bounds& box, bool depthClamp);

/// Can a caster inside casterBox shadow a point of receiverBox under a directional light
/// travelling along wsLightDirection? True when the caster box, swept along the light by more
/// than minimumDistance, meets the receiver box (closed boxes: a conservative answer). A point
/// is shadowed only by what lies toward the light from it, so false means that no point of the
/// receiver box can be in the caster's shadow (a ground slab under everything else, say).
/// True for empty, non-finite or zero directions (the safe answer: draw the caster).
bool sweptBoxReachesBox(const Bounds& casterBox, const glm::dvec3& wsLightDirection,
  const Bounds& receiverBox, double minimumDistance);

const char* toString(Status status);

} // namespace csm
