// SPDX-License-Identifier: BSD-3-Clause
#include "csmPages.h"

#include <glm/geometric.hpp>
#include <glm/vec4.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <tuple>

namespace csm
{

double PageLevels::fineness(double vsDepth) const
{
  return std::log2(this->baseDepth / vsDepth);
}

int PageLevels::levelAt(double fineness) const
{
  if (!(fineness > 0.0)) // (NaN: the base)
  {
    return 0;
  }
  return static_cast<int>(std::min(std::ceil(fineness), static_cast<double>(this->count)));
}

glm::dvec2 PageLevels::texels(int level) const
{
  return this->baseTexels * std::ldexp(1.0, level);
}

bool pageLevels(const glm::dmat4& wsToBaseClip, const MapSize& baseTexels, double pixelAtUnitDepth,
  double targetError, double vsNearest, PageLevels& levels)
{
  levels = PageLevels();
  const glm::dmat4& m = wsToBaseClip; // (column-major: row r is m[0][r] .. m[3][r])
  const bool orthographic = m[0][3] == 0.0 && m[1][3] == 0.0 && m[2][3] == 0.0 && m[3][3] == 1.0;
  const double sRow = glm::length(glm::dvec3(m[0][0], m[1][0], m[2][0]));
  const double tRow = glm::length(glm::dvec3(m[0][1], m[1][1], m[2][1]));
  if (!orthographic || !(sRow > 0.0) || !(tRow > 0.0) || baseTexels.width < 1 ||
    baseTexels.height < 1 || !(pixelAtUnitDepth > 0.0) || !(targetError > 0.0) ||
    !(vsNearest > 0.0) || !std::isfinite(vsNearest))
  {
    return false;
  }
  // A clip-space span of 2 is 2 / |row| world units along that axis.
  const double wsTexel =
    std::max(2.0 / (sRow * baseTexels.width), 2.0 / (tRow * baseTexels.height));
  const double baseDepth = wsTexel / (targetError * pixelAtUnitDepth);
  if (!std::isfinite(baseDepth) || !(baseDepth > 0.0))
  {
    return false;
  }
  // The levels' texels square in the world: the base's texel count along its shorter side
  // scaled to the longer texel.
  levels.baseTexels = glm::dvec2(2.0 / (sRow * wsTexel), 2.0 / (tRow * wsTexel));
  levels.baseDepth = baseDepth;
  const double finest = levels.fineness(vsNearest);
  if (!(finest <= kMaxPageLevels + 1))
  {
    return false; // samples nearer than the finest level serves within twice the target
  }
  levels.count =
    finest > 0.0 ? static_cast<int>(std::ceil(std::min(finest, 1.0 * kMaxPageLevels))) : 0;
  return true;
}

std::uint64_t PageKey::packed() const
{
  return (static_cast<std::uint64_t>(this->level & 0xff) << 56) |
    (static_cast<std::uint64_t>(this->x & 0xfffffff) << 28) |
    static_cast<std::uint64_t>(this->y & 0xfffffff);
}

PageKey PageKey::unpack(std::uint64_t packed)
{
  PageKey key;
  key.level = static_cast<int>(packed >> 56);
  key.x = static_cast<int>((packed >> 28) & 0xfffffff);
  key.y = static_cast<int>(packed & 0xfffffff);
  return key;
}

namespace
{
/// Collects the pages samples need, each run of the same pages once (a row of pixels crosses
/// few pages: the recent keys spare the sort most repeats). A sample's level by its window
/// depth against each level's edges, window depths themselves (the view depth grows with it).
class PageMarks
{
public:
  PageMarks(const PageLevels& levels, double vsNear, double vsFar, std::size_t mostPages)
    : Count(std::min(levels.count, kMaxPageLevels))
    , Most(mostPages)
  {
    auto windowAt = [&](double fineness) {
      return windowDepthFromViewDepth(
        levels.baseDepth * std::exp2(-fineness), vsNear, vsFar, false);
    };
    for (int k = 0; k <= this->Count; ++k)
    {
      this->Edge[k] = windowAt(k);
      this->Finer[k] = windowAt(k - kPageBlendBand - kPageLevelMargin);
      this->Coarser[k] = windowAt(k - 1 + kPageLevelMargin);
      this->Texels[k] = levels.texels(k);
      this->Last[k] = glm::ceil(this->Texels[k] / double(kPageInterior)) - 1.0;
    }
  }

  /// The pages around base coordinates (bx, by) at the levels a sample at window depth w needs.
  void sample(double bx, double by, double w)
  {
    if (!(bx >= 0.0 && bx <= 1.0 && by >= 0.0 && by <= 1.0))
    {
      return; // outside the base (the lookup finds no map there)
    }
    const int k = this->levelAt(w);
    const bool finer = k < this->Count && w < this->Finer[k];
    const bool coarser = k > 1 && w > this->Coarser[k];
    if (!finer && !coarser && k == this->Alone.level && k >= 1)
    {
      // Inside the last lone page, away from its margins: nothing new (neighbouring pixels
      // mostly land there).
      const glm::dvec2 u = glm::dvec2(bx, by) * this->Texels[k];
      if (u.x >= this->Alone.lower.x && u.x <= this->Alone.upper.x && u.y >= this->Alone.lower.y &&
        u.y <= this->Alone.upper.y)
      {
        return;
      }
    }
    this->Alone.level = -1;
    this->at(k, bx, by);
    if (finer)
    {
      this->at(k + 1, bx, by); // the dithered band, or the edge
    }
    if (coarser)
    {
      this->at(k - 1, bx, by);
    }
    if (!finer && !coarser && k >= 1)
    {
      // A sample that marks one page alone: the part of that page that marks nothing else.
      const glm::dvec2 page =
        glm::floor(glm::dvec2(bx, by) * this->Texels[k] / double(kPageInterior));
      const glm::dvec2 lower = page * double(kPageInterior) + kPageTexelMargin;
      const glm::dvec2 upper = (page + 1.0) * double(kPageInterior) - kPageTexelMargin;
      const glm::dvec2 u = glm::dvec2(bx, by) * this->Texels[k];
      if (u.x >= lower.x && u.x <= upper.x && u.y >= lower.y && u.y <= upper.y)
      {
        this->Alone = { k, lower, upper };
      }
    }
  }

  /// Every page of levels k0 .. k1 that base rectangle [b0, b1] touches (a box that stood in
  /// for a caster's samples); none, and Overflowed, where one level's part is more than the
  /// most pages wanted (a fine level's rectangle can hold billions).
  void rect(int k0, int k1, const glm::dvec2& b0, const glm::dvec2& b1)
  {
    for (int k = std::max(k0, 1); k <= std::min(k1, this->Count); ++k)
    {
      const glm::dvec2 first =
        glm::floor((b0 * this->Texels[k] - kPageTexelMargin) / double(kPageInterior));
      const glm::dvec2 end =
        glm::floor((b1 * this->Texels[k] + kPageTexelMargin) / double(kPageInterior));
      const glm::ivec2 p0(glm::clamp(first, glm::dvec2(0.0), this->Last[k]));
      const glm::ivec2 p1(glm::clamp(end, glm::dvec2(0.0), this->Last[k]));
      if (double(p1.x - p0.x + 1) * double(p1.y - p0.y + 1) > double(this->Most))
      {
        this->Overflowed = true;
        return;
      }
      for (int y = p0.y; y <= p1.y; ++y)
      {
        for (int x = p0.x; x <= p1.x; ++x)
        {
          this->push(PageKey{ k, x, y }.packed());
        }
      }
    }
  }

  /// The window depths whose samples mark pages of level k (1 .. Count): its own, those of
  /// the coarser level in its band or margin before k, those of the finer one within the margin.
  void band(int k, double& w0, double& w1) const
  {
    w0 = k < this->Count ? this->Coarser[k + 1] : 0.0;
    w1 = this->Finer[k - 1];
  }

  /// The level of a sample at window depth w.
  int levelAt(double w) const
  {
    int k = 0;
    while (k < this->Count && w < this->Edge[k])
    {
      ++k;
    }
    return k;
  }

  std::vector<std::uint64_t> Keys;
  bool Overflowed = false;

private:
  /// The pages of one axis within kPageTexelMargin of texel coordinate u: first and last.
  static void pagesAlong(double u, double last, int& first, int& end)
  {
    const double page = std::floor(u / kPageInterior);
    const double within = u - page * kPageInterior;
    first = static_cast<int>(std::max(0.0, page - (within < kPageTexelMargin ? 1.0 : 0.0)));
    end = static_cast<int>(
      std::min(last, page + (within > kPageInterior - kPageTexelMargin ? 1.0 : 0.0)));
  }

  void at(int k, double bx, double by)
  {
    if (k < 1)
    {
      return; // the base
    }
    int x0, x1, y0, y1;
    pagesAlong(bx * this->Texels[k].x, this->Last[k].x, x0, x1);
    pagesAlong(by * this->Texels[k].y, this->Last[k].y, y0, y1);
    for (int y = y0; y <= y1; ++y)
    {
      for (int x = x0; x <= x1; ++x)
      {
        this->push(PageKey{ k, x, y }.packed());
      }
    }
  }

  void push(std::uint64_t key)
  {
    if (key == this->Recent[this->Latest] ||
      std::find(this->Recent.begin(), this->Recent.end(), key) != this->Recent.end())
    {
      return;
    }
    this->Latest = (this->Latest + 1) % this->Recent.size();
    this->Recent[this->Latest] = key;
    this->Keys.push_back(key);
  }

  int Count;
  std::size_t Most; ///< the most pages wanted
  std::array<double, kMaxPageLevels + 1> Edge{}, Finer{}, Coarser{};
  std::array<glm::dvec2, kMaxPageLevels + 1> Texels{}, Last{};
  std::array<std::uint64_t, 8> Recent{};
  std::size_t Latest = 0;
  /// The page the last sample marked alone, and where in it a sample marks nothing else.
  struct
  {
    int level = -1;
    glm::dvec2 lower{ 0.0 }, upper{ 0.0 };
  } Alone;
};
} // namespace

glm::dmat4 windowToBase(const glm::dmat4& wsToBaseClip, const glm::dmat4& wsToViewClip)
{
  glm::dmat4 toUnit(0.5); // (clip x, y -> [0, 1])
  toUnit[2][2] = 1.0;
  toUnit[3] = glm::dvec4(0.5, 0.5, 0.0, 1.0);
  return toUnit * wsToBaseClip * glm::inverse(wsToViewClip);
}

bool markPages(const PageLevels& levels, const glm::dmat4& windowToBase, double vsNear,
  double vsFar, const float* windowDepths, int width, int height,
  const std::vector<BoxStandIn>& standIns, std::size_t mostPages, std::vector<PageKey>& pages)
{
  pages.clear();
  if (levels.count < 1 || !windowDepths || width < 1 || height < 1 || !(vsNear > 0.0) ||
    !(vsFar > vsNear))
  {
    return true; // (no level finer than the base: no page)
  }
  PageMarks marks(levels, vsNear, vsFar, mostPages);
  const glm::dvec4 alongX = windowToBase[0];
  const glm::dvec4 alongZ = windowToBase[2];
  for (int y = 0; y < height; ++y)
  {
    const double ndcY = 2.0 * (y + 0.5) / height - 1.0;
    const glm::dvec4 row = windowToBase * glm::dvec4(-1.0 + 1.0 / width, ndcY, 0.0, 1.0);
    const glm::dvec4 step = alongX * (2.0 / width);
    const float* depths = windowDepths + static_cast<std::size_t>(y) * width;
    for (int x = 0; x < width; ++x)
    {
      const float w = depths[x];
      if (!(w < 1.0f) || !(w >= 0.0f))
      {
        continue; // background, or not a depth
      }
      const glm::dvec4 b = row + double(x) * step + (2.0 * w - 1.0) * alongZ;
      if (b.w > 0.0)
      {
        marks.sample(b.x / b.w, b.y / b.w, w);
      }
    }
  }
  for (const BoxStandIn& standIn : standIns)
  {
    if (marks.Overflowed)
    {
      return false;
    }
    const ScreenRect& r = standIn.rect;
    if (r.isEmpty() || standIn.depths.isEmpty())
    {
      continue;
    }
    for (int k = 1; k <= std::min(levels.count, kMaxPageLevels); ++k)
    {
      // The part of its rectangle between the depths that mark level k: the box of its
      // corners in base coordinates holds the part (a convex solid the projective map keeps
      // convex in front of the eye).
      double w0 = 0.0, w1 = 0.0;
      marks.band(k, w0, w1);
      w0 = std::max(w0, standIn.depths.min);
      w1 = std::min(w1, standIn.depths.max);
      if (!(w0 <= w1))
      {
        continue;
      }
      glm::dvec2 b0(1e300), b1(-1e300);
      for (const double w : { w0, w1 })
      {
        for (const double sx : { r.x0, r.x1 })
        {
          for (const double sy : { r.y0, r.y1 })
          {
            const glm::dvec4 b = windowToBase * glm::dvec4(sx, sy, 2.0 * w - 1.0, 1.0);
            if (b.w > 0.0)
            {
              b0 = glm::min(b0, glm::dvec2(b) / b.w);
              b1 = glm::max(b1, glm::dvec2(b) / b.w);
            }
          }
        }
      }
      if (b0.x <= b1.x && b0.y <= b1.y)
      {
        marks.rect(k, k, glm::clamp(b0, 0.0, 1.0), glm::clamp(b1, 0.0, 1.0));
      }
    }
  }
  if (marks.Overflowed)
  {
    return false;
  }
  std::sort(marks.Keys.begin(), marks.Keys.end());
  marks.Keys.erase(std::unique(marks.Keys.begin(), marks.Keys.end()), marks.Keys.end());
  if (marks.Keys.size() > mostPages)
  {
    return false;
  }
  pages.reserve(marks.Keys.size());
  for (const std::uint64_t key : marks.Keys)
  {
    pages.push_back(PageKey::unpack(key));
  }
  return true;
}

int pageLevelRead(
  const PageLevels& levels, const std::vector<float>& table, double bx, double by, double f)
{
  const int k = levels.levelAt(f);
  const int side = kPageTableSide;
  if (k < 1 || !(bx >= 0.0 && bx <= 1.0 && by >= 0.0 && by <= 1.0))
  {
    return 0;
  }
  const glm::dvec2 u = glm::dvec2(bx, by) * levels.texels(k);
  const glm::ivec2 page(glm::floor(u / double(kPageInterior)));
  const std::size_t entry =
    (static_cast<std::size_t>(k - 1) * side + static_cast<std::size_t>(page.y & (side - 1))) *
      side +
    static_cast<std::size_t>(page.x & (side - 1));
  if (4 * entry + 3 >= table.size())
  {
    return 0;
  }
  const float* e = &table[4 * entry];
  return e[0] >= 0.0f && e[2] == static_cast<float>(page.x) && e[3] == static_cast<float>(page.y)
    ? k
    : 0;
}

bool pageReachesBox(const glm::dmat4& wsToBaseClip, const PageLevels& levels, const PageKey& page,
  const Bounds& wsBox)
{
  if (wsBox.isEmpty())
  {
    return false;
  }
  // The box's rectangle in base coordinates against the page's texels with their border.
  glm::dvec2 b0(1e300), b1(-1e300);
  for (int corner = 0; corner < 8; ++corner)
  {
    const glm::dvec3 p((corner & 1) ? wsBox.wsMax.x : wsBox.wsMin.x,
      (corner & 2) ? wsBox.wsMax.y : wsBox.wsMin.y, (corner & 4) ? wsBox.wsMax.z : wsBox.wsMin.z);
    const glm::dvec4 c = wsToBaseClip * glm::dvec4(p, 1.0);
    const glm::dvec2 b = 0.5 * glm::dvec2(c) / c.w + 0.5;
    b0 = glm::min(b0, b);
    b1 = glm::max(b1, b);
  }
  const glm::dvec2 texels = levels.texels(page.level);
  const glm::dvec2 from =
    (glm::dvec2(page.x, page.y) * double(kPageInterior) - double(kPageBorder) - 1.0) / texels;
  const glm::dvec2 to =
    (glm::dvec2(page.x + 1, page.y + 1) * double(kPageInterior) + double(kPageBorder) + 1.0) /
    texels;
  return b0.x <= to.x && b1.x >= from.x && b0.y <= to.y && b1.y >= from.y;
}

glm::dmat4 pagesClip(const glm::dmat4& wsToBaseClip, const PageLevels& levels, int level,
  const glm::ivec2& first, const glm::ivec2& last)
{
  // Base clip x = 2 u / texels - 1 for texel coordinate u of the level; the pages' texels with
  // their border are u in [first kPageInterior - kPageBorder, (last + 1) kPageInterior +
  // kPageBorder).
  const glm::dvec2 texels = levels.texels(level);
  const glm::dvec2 from = glm::dvec2(first) * double(kPageInterior) - double(kPageBorder);
  const glm::dvec2 to = glm::dvec2(last + 1) * double(kPageInterior) + double(kPageBorder);
  const glm::dvec2 centre = (from + to) / texels - 1.0;
  const glm::dvec2 half = (to - from) / texels;
  glm::dmat4 crop(1.0);
  crop[0][0] = 1.0 / half.x;
  crop[1][1] = 1.0 / half.y;
  crop[3][0] = -centre.x / half.x;
  crop[3][1] = -centre.y / half.y;
  return crop * wsToBaseClip;
}

glm::dmat4 pageClip(const glm::dmat4& wsToBaseClip, const PageLevels& levels, const PageKey& page)
{
  const glm::ivec2 at(page.x, page.y);
  return pagesClip(wsToBaseClip, levels, page.level, at, at);
}

glm::ivec2 PageBatch::texels() const
{
  return (this->last - this->first + 1) * kPageInterior + 2 * kPageBorder;
}

std::array<int, 4> PageBatch::drawn() const
{
  const glm::ivec2 from = (this->from - this->first) * kPageInterior;
  const glm::ivec2 size = (this->to - this->from + 1) * kPageInterior + 2 * kPageBorder;
  return { from.x, from.y, size.x, size.y };
}

std::vector<PageBatch> batchPages(const std::vector<PageKey>& pages, int side)
{
  // The blocks of side x side pages of a level from its lower left, each with the pages of it
  // given.
  side = std::max(side, 1);
  std::map<std::tuple<int, int, int>, PageBatch> blocks;
  for (std::size_t i = 0; i < pages.size(); ++i)
  {
    const PageKey& p = pages[i];
    const glm::ivec2 at(p.x, p.y);
    const glm::ivec2 block = at / side;
    PageBatch& b = blocks[std::make_tuple(p.level, block.y, block.x)];
    if (b.pages.empty())
    {
      b.level = p.level;
      b.first = block * side;
      b.last = b.first + side - 1;
      b.from = b.to = at;
    }
    b.from = glm::min(b.from, at);
    b.to = glm::max(b.to, at);
    b.pages.push_back(i);
  }
  std::vector<PageBatch> batches;
  for (auto& block : blocks)
  {
    batches.push_back(std::move(block.second));
  }
  return batches;
}

void PageCache::reset(int slots)
{
  this->Slots.assign(static_cast<std::size_t>(std::max(slots, 0)), Slot());
  this->Index.clear();
  this->Frame = 0;
}

bool PageCache::place(
  const std::vector<PageKey>& needed, std::vector<std::pair<PageKey, int>>& drawn)
{
  drawn.clear();
  if (needed.size() > this->Slots.size())
  {
    return false;
  }
  ++this->Frame;
  std::vector<PageKey> missing;
  for (const PageKey& page : needed)
  {
    const auto found = this->Index.find(page.packed());
    if (found != this->Index.end())
    {
      this->Slots[static_cast<std::size_t>(found->second)].lastNeeded = this->Frame;
    }
    else
    {
      missing.push_back(page);
    }
  }
  // Free slots first, then those needed least recently (none of this frame's: there are as many
  // of the others as pages missing).
  std::vector<int> free;
  for (int i = 0; i < this->slots(); ++i)
  {
    const Slot& slot = this->Slots[static_cast<std::size_t>(i)];
    if (!slot.used || slot.lastNeeded != this->Frame)
    {
      free.push_back(i);
    }
  }
  std::stable_sort(free.begin(), free.end(),
    [this](int a, int b)
    {
      const Slot& sa = this->Slots[static_cast<std::size_t>(a)];
      const Slot& sb = this->Slots[static_cast<std::size_t>(b)];
      return sa.used != sb.used ? !sa.used : sa.lastNeeded < sb.lastNeeded;
    });
  for (std::size_t i = 0; i < missing.size(); ++i)
  {
    const int index = free[i];
    Slot& slot = this->Slots[static_cast<std::size_t>(index)];
    if (slot.used)
    {
      this->Index.erase(slot.key);
    }
    slot.key = missing[i].packed();
    slot.lastNeeded = this->Frame;
    slot.used = true;
    this->Index[slot.key] = index;
    drawn.emplace_back(missing[i], index);
  }
  return true;
}

void PageCache::forget(const std::function<bool(const PageKey&)>& stale)
{
  for (auto it = this->Index.begin(); it != this->Index.end();)
  {
    if (stale(PageKey::unpack(it->first)))
    {
      this->Slots[static_cast<std::size_t>(it->second)] = Slot();
      it = this->Index.erase(it);
    }
    else
    {
      ++it;
    }
  }
}

int PageCache::slotOf(const PageKey& page) const
{
  const auto found = this->Index.find(page.packed());
  return found == this->Index.end() ? -1 : found->second;
}

int PageCache::table(int levels, const std::vector<PageKey>& needed,
  const std::function<glm::ivec2(int)>& slotPlace, std::vector<float>& entries) const
{
  const int side = kPageTableSide;
  levels = std::max(0, std::min(levels, kMaxPageLevels));
  entries.assign(static_cast<std::size_t>(side) * side * levels * 4, -1.0f);
  std::vector<bool> takenNow(static_cast<std::size_t>(side) * side * levels, false);
  auto write = [&](const PageKey& page, int slot) -> std::size_t
  {
    const std::size_t entry = (static_cast<std::size_t>(page.level - 1) * side +
                                static_cast<std::size_t>(page.y & (side - 1))) *
        side +
      static_cast<std::size_t>(page.x & (side - 1));
    const glm::ivec2 place = slotPlace(slot);
    float* e = &entries[4 * entry];
    e[0] = static_cast<float>(place.x);
    e[1] = static_cast<float>(place.y);
    e[2] = static_cast<float>(page.x);
    e[3] = static_cast<float>(page.y);
    return entry;
  };
  for (const auto& resident : this->Index)
  {
    const PageKey page = PageKey::unpack(resident.first);
    if (page.level >= 1 && page.level <= levels)
    {
      write(page, resident.second);
    }
  }
  int lost = 0;
  for (const PageKey& page : needed)
  {
    const int slot = this->slotOf(page);
    if (slot < 0 || page.level < 1 || page.level > levels)
    {
      continue;
    }
    const std::size_t entry = write(page, slot);
    lost += takenNow[entry] ? 1 : 0;
    takenNow[entry] = true;
  }
  return lost;
}

int poolSlots(const MapSize& atlas, int baseSide)
{
  if (atlas.width < kPageTexels || atlas.height < kPageTexels || baseSide < kPageTexels ||
    atlas.width % kPageTexels != 0 || atlas.height % kPageTexels != 0 ||
    baseSide % kPageTexels != 0 || baseSide > atlas.width || baseSide > atlas.height)
  {
    return 0;
  }
  const int b = baseSide / kPageTexels;
  return (atlas.width / kPageTexels) * (atlas.height / kPageTexels) - b * b;
}

glm::ivec2 poolSlotPlace(const MapSize& atlas, int baseSide, int slot)
{
  // The rows beside the base first (columns b .. n - 1), then the rows above it.
  const int n = std::max(1, atlas.width / kPageTexels), b = std::max(0, baseSide / kPageTexels);
  const int beside = b * (n - b);
  if (slot < beside)
  {
    return glm::ivec2(b + slot % std::max(n - b, 1), slot / std::max(n - b, 1));
  }
  return glm::ivec2((slot - beside) % n, b + (slot - beside) / n);
}

} // namespace csm
