// SPDX-License-Identifier: BSD-3-Clause
// Light-space pages: the scene-fitted map of a directional light refined where the view needs
// finer texels, in levels of half the texel of the level before, fixed in light space (the
// generalized LiSPSM parameter's n' -> infinity end, as the scene-fitted map), of which only the
// pages that the view's visible samples read are drawn and kept (Fernando et al. 2001's adaptive
// shadow maps; the pages of virtual shadow maps). A page's texels depend only on the light, the
// casters and where it lies, so it serves every view that reads it: a camera that moves draws
// only the pages that come into view. Pure math (C++17, GLM, double precision): no VTK, no GL.
// Spaces as in csmTypes.h; "base" coordinates are the scene-fitted (base) map's [0, 1]^2.
#pragma once

#include "csmTypes.h"
#include "csmVisibleDepth.h"

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>

#include <array>
#include <cstdint>
#include <functional>
#include <unordered_map>
#include <vector>

namespace csm
{

/// A page's side in texels as drawn into the pool: its kPageInterior texels and kPageBorder of
/// its neighbours' on each side, so that a lookup's kernel (at most a 7 x 7 PCF, its bilinear
/// taps and the receiver plane) never reads outside the page it chose.
constexpr int kPageTexels = 256;
constexpr int kPageBorder = 4;
constexpr int kPageInterior = kPageTexels - 2 * kPageBorder;

/// Entries a side of one level's window in the page table: page (x, y) of level k sits at entry
/// (x mod kPageTableSide, y mod kPageTableSide) of level k's window, tagged with x and y.
constexpr int kPageTableSide = 32;

/// The most levels finer than the base map (float map coordinates keep a quarter of a texel
/// at 2^12 times the base's texels a side). The finest serves one octave of view depth more,
/// within twice the target (as a map at its ceiling); a view that needs finer texels than that
/// is served by the cascades.
constexpr int kMaxPageLevels = 12;

/// Share of the error target the levels are sized for where the pool holds their pages (else
/// the target itself): a level's error halves across its octave, while a map sized to meet the
/// target where its error is worst meets it with room over most of its view, so that at the
/// target itself pages misclassify more pixels than the cascades (Results.md, "Light-space
/// pages"); at this share, as many.
constexpr double kPageErrorShare = 0.70710678118654752;

/// Share of a level's octave of view depth (its nearest part) whose samples take the next finer
/// level in a dithered share growing from 0 to 1 toward it (the seam between two levels becomes
/// a dithered band, both sides meeting the target); the samples there need both levels' pages.
constexpr double kPageBlendBand = 0.05;

/// Samples whose fineness lies this close to a level's edge need the pages of both levels
/// (depth-buffer quantization, float rounding in the lookup), and texels this close to a page's
/// edge the neighbouring page's too.
constexpr double kPageLevelMargin = 0.01;
constexpr double kPageTexelMargin = 2.0;

/// The levels of one light for one view: level 0 is the base map (baseTexels a side, complete),
/// level k in 1..count has 2^k times its texels a side and serves the view depths whose
/// fineness log2(baseDepth / d) lies in (k - 1, k]; the base serves fineness <= 0, the finest
/// level everything nearer.
struct PageLevels
{
  /// Level 0's texels along s and t: square in the world, as large as the base's larger texel
  /// (the base map's own texels along its shorter side are finer than that).
  glm::dvec2 baseTexels{ 0.0, 0.0 };
  double baseDepth = 0.0; ///< D_0: the view depth from which the base map meets the target
  int count = 0;          ///< levels finer than the base
  /// log2(baseDepth / vsDepth): the level a sample at that depth needs, as a real number.
  double fineness(double vsDepth) const;
  /// The level a sample of that fineness reads (without the dithered band): 0 .. count.
  int levelAt(double fineness) const;
  /// Texels a side of level k's (virtual) map.
  glm::dvec2 texels(int level) const;
};

/// The levels that bring a base map (world -> its clip space, orthographic; baseTexels texels
/// a side) to targetError down to view depth vsNearest, for a perspective image whose pixel at
/// view depth 1 is pixelAtUnitDepth wide (2 tan(fovy / 2) / image height). A texel of world size
/// t at view depth d reads an error m = t / (d pixelAtUnitDepth) (Lloyd et al. 2006, Eq. 1, the
/// texel face-on to the view, the largest over the ways it can turn; the receiver's own angle to
/// the light aside, as in the cascades' error), so the base meets the target from D_0 =
/// t_max / (targetError pixelAtUnitDepth) on, level k from D_0 / 2^k; the finest, at most
/// kMaxPageLevels, serves what is nearer down to D_0 / 2^(kMaxPageLevels + 1). False where the
/// input is not finite or positive, the base is not orthographic, or vsNearest is nearer still
/// (a base far wider than the view: the cascades serve).
bool pageLevels(const glm::dmat4& wsToBaseClip, const MapSize& baseTexels, double pixelAtUnitDepth,
  double targetError, double vsNearest, PageLevels& levels);

/// One page: its level (1 .. kMaxPageLevels) and place (x, y from the level's lower left, in
/// pages of kPageInterior texels).
struct PageKey
{
  int level = 0;
  int x = 0;
  int y = 0;
  std::uint64_t packed() const;
  static PageKey unpack(std::uint64_t packed);
  bool operator==(const PageKey& o) const { return level == o.level && x == o.x && y == o.y; }
};

/// Window NDC (x, y, z in [-1, 1]) of a view -> base coordinates [0, 1]^2 in x and y (markPages'
/// windowToBase): the view's world -> clip matrix undone, the base's applied, its clip x and y
/// taken to [0, 1]; z and w as the base's clip has them.
glm::dmat4 windowToBase(const glm::dmat4& wsToBaseClip, const glm::dmat4& wsToViewClip);

/// The pages the visible samples of one view read: each sample of a depth buffer (width x
/// height window depths, rows from the bottom; 1 the cleared background) at its pixel's centre,
/// carried to base coordinates by windowToBase (window NDC x, y, z in [-1, 1] -> base [0, 1]^2
/// in x, y: the lookup's own map coordinates), its level by its view depth (the camera's
/// clipping range, perspective), and its page and the neighbours within kPageTexelMargin
/// texels; within kPageLevelMargin of a level's edge or in the dithered band, both levels'
/// pages. Then the boxes that stood in for casters the buffer lacks: at each level, every page
/// that the part of a box's rectangle between the window depths that level's samples mark it
/// from (its own, its band and margins) touches, so every page a sample in that part would
/// mark. Sorted, each once; false where more than mostPages are needed.
bool markPages(const PageLevels& levels, const glm::dmat4& windowToBase, double vsNear,
  double vsFar, const float* windowDepths, int width, int height,
  const std::vector<BoxStandIn>& standIns, std::size_t mostPages, std::vector<PageKey>& pages);

/// The level the lookup reads at base coordinates (bx, by) for a sample of fineness f (the
/// dithered band aside): its level (PageLevels::levelAt) where the page table `table`
/// (PageCache::table's entries for levels.count windows) holds its page there, else 0 (the
/// base). The lookup's own choice (csmShadowFS.glsl's csmPagedShadow), for measuring it.
int pageLevelRead(
  const PageLevels& levels, const std::vector<float>& table, double bx, double by, double f);

/// Does a world box reach page's texels (with its border) across the light? What a caster in
/// the box casts lies in its column along the light: a page the box reaches nowhere holds
/// nothing of it. wsToBaseClip: the base map's world -> clip space (orthographic).
bool pageReachesBox(const glm::dmat4& wsToBaseClip, const PageLevels& levels, const PageKey& page,
  const Bounds& wsBox);

/// World -> clip space of one page as drawn into its kPageTexels square of the pool: the base
/// map's clip space (the same depth) cropped to the page's texels of its level and the
/// kPageBorder texels around them.
glm::dmat4 pageClip(const glm::dmat4& wsToBaseClip, const PageLevels& levels, const PageKey& page);

/// The same for the pages first .. last (columns, rows) of a level drawn in one pass: their
/// texels and the kPageBorder texels around them all.
glm::dmat4 pagesClip(const glm::dmat4& wsToBaseClip, const PageLevels& levels, int level,
  const glm::ivec2& first, const glm::ivec2& last);

/// Pages of one level drawn in one pass, each then copied to its slot: a caster pass costs its
/// triangles whatever it covers, so the pages a view brings in together are drawn together. A
/// batch is a block of pages first .. last (columns, rows) at a fixed place in its level, drawn
/// with its own clip space (pagesClip) over the rectangle of its pages from .. to (the texels
/// drawn): a page's texels are the same whichever pages come with it. pages: indices into the
/// pages batched.
struct PageBatch
{
  int level = 0;
  glm::ivec2 first{ 0 }, last{ 0 };
  glm::ivec2 from{ 0 }, to{ 0 };
  std::vector<std::size_t> pages;
  /// Texels a side of the block's clip space: its pages' own and a border around them.
  glm::ivec2 texels() const;
  /// The texels drawn, from the block's lower left: x, y, width, height.
  std::array<int, 4> drawn() const;
};

/// The pages in blocks of side x side pages of their level (from its lower left), each page in
/// the one block that holds it.
std::vector<PageBatch> batchPages(const std::vector<PageKey>& pages, int side);

/// The pages kept in a pool of slots across frames. A page keeps its slot while it is needed
/// or no other page needs the slot (least recently needed first).
class PageCache
{
public:
  /// Empty, with this many slots.
  void reset(int slots);
  int slots() const { return static_cast<int>(this->Slots.size()); }
  int resident() const { return static_cast<int>(this->Index.size()); }
  /// This frame's pages: those resident stay, the others take free slots or those of the pages
  /// needed least recently; `drawn` gets each page that took a slot and its slot. False (the
  /// cache unchanged) where there are more pages than slots.
  bool place(const std::vector<PageKey>& needed, std::vector<std::pair<PageKey, int>>& drawn);
  /// The slot of a resident page; -1 where it is not.
  int slotOf(const PageKey& page) const;
  /// Gives up the slots of the resident pages `stale` says are (drawn again where needed).
  void forget(const std::function<bool(const PageKey&)>& stale);
  /// The page table of `levels` level windows (kPageTableSide entries a side, level k's window
  /// the (k - 1)-th from the bottom), four values an entry: the slot's place in the pool grid
  /// (slotPlace: column, row, in pages), the page's x and y; -1 where no page sits. The pages of
  /// the last place() written last (a page needed now wins its entry over one kept from
  /// before). Returns how many of those lost their entry to another page needed now.
  int table(int levels, const std::vector<PageKey>& needed,
    const std::function<glm::ivec2(int)>& slotPlace, std::vector<float>& entries) const;

private:
  struct Slot
  {
    std::uint64_t key = 0;
    std::uint64_t lastNeeded = 0;
    bool used = false;
  };
  std::vector<Slot> Slots;
  std::unordered_map<std::uint64_t, int> Index;
  std::uint64_t Frame = 0;
};

/// The pool beside a base map of baseSide texels a side in the lower left of an atlas: every
/// other kPageTexels square of the atlas, row by row from the lower left; slot i's place in
/// pages (column, row). Slots: 0 where the sides are not positive multiples of kPageTexels or
/// the base does not fit.
int poolSlots(const MapSize& atlas, int baseSide);
glm::ivec2 poolSlotPlace(const MapSize& atlas, int baseSide, int slot);

} // namespace csm
