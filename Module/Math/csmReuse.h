// SPDX-License-Identifier: BSD-3-Clause
// Whether a shadow map rendered for an earlier frame can stand in for a freshly planned cascade
// (maps reused across frames: re-render only what the view needs). Pure math, no VTK, no GL.
#pragma once

#include "csmTypes.h"

#include <array>
#include <cstddef>
#include <functional>
#include <vector>

namespace csm
{

struct MapReuse
{
  /// Every vertex of the fresh cascade's receiver body projects inside the kept map (in front of
  /// its projection centre, inside its xy square shrunk by the margin, in front of its far plane).
  bool covers = false;
  /// The kept map's aliasing error over the fresh map's on that body, at equal resolution:
  /// for a directional light the ratio of the maxima of max(m_x, m_z) over the body's vertices
  /// (Lloyd et al. 2006, Eq. 2-4); for a spot light (one perspective map, same centre) the
  /// largest ratio of the widths the body spans in the fresh map over those in the kept map.
  /// +infinity when the kept map does not cover the body.
  double errorRatio = 0.0;
};

/// The same map with a border: the body, which wsToClip fits to [-1,1]^3, is fitted to the
/// central 1/(1 + 2 border) of the map in x, y and depth, so that a camera that moves a little
/// stays covered.
glm::dmat4 withBorder(const glm::dmat4& wsToClip, double border);

/// A map rendered with slack, so that a camera that moves a little can keep it: a border around
/// its body and more texels, together at most 1 + slack times the texels a side of the tight
/// map that meets the error target (need), and at most `most` (the atlas tile). Half the factor
/// (in ratio) goes to the border, half to the texel size: a fresh slacked map meets the target
/// with room for its error to grow by the same factor again before keptMapServes() fails.
struct SlackedMap
{
  double border = 0.0; ///< withBorder()'s share of the body's width on each side
  MapSize size;        ///< texels along s and t
};
SlackedMap slackedMap(const MapSize& need, const MapSize& most, double slack);

/// Did the camera take a small step since the last frame (a smooth path, whose next frames a
/// slacked map may serve)? Turned by at most kSmallStepTurnDeg and moved by at most
/// kSmallStepShare of vsDepth (the far end of the cascade that would keep its map); a camera
/// that did not move took no step, and an invalid one none either.
constexpr double kSmallStepTurnDeg = 5.0;
constexpr double kSmallStepShare = 0.25;
bool smallCameraStep(const Camera& before, const Camera& now, double vsDepth);

/// The error of a kept map of keptSize texels over that of the tight fresh map of `need` texels
/// that meets the error target: errorRatio (its error over the fresh map's at equal resolution,
/// compareKeptMap; +infinity where it does not cover) times need / keptSize along the axis that
/// gains least (aliasing falls with the texel size, Lloyd et al. 2006, Eq. 1). +infinity for
/// sizes that are not positive or a ratio that is negative or not finite.
double keptMapError(double errorRatio, const MapSize& keptSize, const MapSize& need);

/// Does a kept map of keptSize texels serve where a tight fresh map needs `need` texels to meet
/// the error target? Its keptMapError must be at most 1 (no worse than the fresh map's). Where no
/// map of this frame meets the target (targetOutOfReach: errorTargetOutOfReach at the largest map
/// the cascade may have, so that need is that map), every map is as good as maps can be and a fresh
/// one misses the target too: there a kept map serves while its error is at most 1 /
/// kCountHysteresis of the fresh one's, the hysteresis the cascade count keeps in the same case
/// (Lloyd et al. 2006, §5.2), so that a walk does not redraw every map for a few percent of error
/// that no map can bring to the target.
bool keptMapServes(
  double errorRatio, const MapSize& keptSize, const MapSize& need, bool targetOutOfReach = false);

/// Compare a kept world -> light clip matrix with the freshly planned cascade of the same light
/// for the current camera. marginNdc: the band along the map's border that the lookup's filter
/// reaches (PCF radius plus one texel, in NDC units: 2 (r + 1) / resolution).
MapReuse compareKeptMap(const glm::dmat4& wsKeptToClip, const Cascade& fresh, const Camera& camera,
  const glm::dvec3& wsLightDirection, bool directional, double marginNdc);

/// A rectangle of texels in an atlas: x, y (from the lower left), width, height.
using TexelRect = std::array<int, 4>;

/// A kept map moved across its own texel grid with the view: its window moved by whole texels
/// (s, t), so that what it holds stays valid shifted by (-s, -t) texels and only the strips that
/// came into it are drawn afresh (the clipmap's update of a moved window, Tanner et al. 1998).
/// It serves where compareKeptMap and keptMapServes accept its matrix, as any kept map.
struct MapPan
{
  int s = 0, t = 0;         ///< texels the window moved along the map's s and t
  glm::dmat4 wsToClip{ 1 }; ///< the kept map's matrix, moved
  bool valid = false;       ///< a move that keeps part of the map (not 0, 0; less than the map)
};

/// The kept matrix moved by (s, t) texels of a map of `size`: a point at texel (i, j) of the
/// kept map lies at texel (i - s, j - t) of the moved one (a translation in clip x and y, times
/// w: exact for a warped map as for an orthographic one).
glm::dmat4 panMatrix(const glm::dmat4& wsToClip, int s, int t, const MapSize& size);

/// The move of a kept map (wsKeptToClip, `size` texels) that centres the fresh body (world
/// points) in it, in whole texels. Not valid where a body point lies behind the map's
/// projection centre, the body is centred already, or nothing of the map would stay.
MapPan panKeptMap(
  const glm::dmat4& wsKeptToClip, const std::vector<glm::dvec3>& wsBody, const MapSize& size);

/// The strips a moved map draws afresh, in texels of the map (from its lower left): the columns
/// its s move brought in, over the whole height, then the rows its t move brought in, over the
/// rest of the width. Empty for a move that is not valid.
std::vector<TexelRect> panStrips(const MapPan& pan, const MapSize& size);

/// The matrix that draws only the texels of `rect` of a map of `size` (viewport: the rect):
/// wsToClip with the rect's share of clip x and y stretched to [-1, 1].
glm::dmat4 cropToTexels(const glm::dmat4& wsToClip, const TexelRect& rect, const MapSize& size);

/// The texels of a map of `size` (world -> light clip wsToClip) whose content a caster inside a
/// world box may set: the box's image grown by marginTexels, clipped to the map (what a change
/// of that caster makes a kept map draw again). Width 0 where the box misses the map; the whole
/// map where part of the box lies at or behind the light's eye (w <= 0: no bounded image).
TexelRect boxTexels(
  const glm::dmat4& wsToClip, const Bounds& wsBox, const MapSize& size, int marginTexels);

/// The rectangles of texels a kept map draws again, merged where the rectangle around two covers
/// no more texels than the two do apart (their overlap drawn twice): the casters that reach them
/// are then drawn once, not once a rectangle (a caster's boxes before and after a small move or
/// a deformation overlap). Empty rectangles are dropped; past kMostMergedRects, the rectangles are
/// returned as they are (the pairwise search grows with their square).
std::vector<TexelRect> mergeTexelRects(std::vector<TexelRect> rects);
constexpr std::size_t kMostMergedRects = 64;

/// Does inner lie inside outer (edges may touch)?
bool rectInside(const TexelRect& inner, const TexelRect& outer);

/// Where this frame's cascades take their maps: kept[c], the earlier frame's map cascade c keeps
/// (-1: drawn afresh), and tile[c], its map's tile (a kept map's own, inside one of the plan's).
struct TileAssignment
{
  std::vector<int> kept;
  std::vector<TexelRect> tile;
};

/// Assigns the plan's tiles (planned[c], one a cascade, apart) to this frame's cascades with
/// the maps kept from the earlier frame (in oldTiles[k]) where serves(c, k) says one stands in
/// for cascade c. First each cascade with the earlier map of its own index in its own tile (the
/// count did not change); then, with acrossTiles, in the given order, any map not taken yet whose
/// tile lies inside a tile no cascade takes (the count changed: a scene-fitted map, say, is in
/// another tile now). The cascades drawn afresh take their own tile where it is free, else the
/// first free one. serves is asked only for maps whose tile could take them.
TileAssignment assignTiles(const std::vector<TexelRect>& planned,
  const std::vector<TexelRect>& oldTiles, const std::function<bool(int, int)>& serves,
  const std::vector<int>& order, bool acrossTiles);

} // namespace csm
