// SPDX-License-Identifier: BSD-3-Clause
#include "csmPages.h"

#include <glm/geometric.hpp>
#include <glm/vec4.hpp>

#include <algorithm>
#include <array>
#include <cmath>

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
  levels.baseTexels = glm::dvec2(baseTexels.width, baseTexels.height);
  levels.baseDepth = baseDepth;
  const double finest = levels.fineness(vsNearest);
  if (finest > kMaxPageLevels)
  {
    return false;
  }
  levels.count = finest > 0.0 ? static_cast<int>(std::ceil(finest)) : 0;
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
/// few pages: the recent keys spare the sort most repeats).
class PageMarks
{
public:
  explicit PageMarks(const PageLevels& levels)
    : Levels(levels)
  {
  }

  /// The pages around base coordinates (bx, by) at the levels a sample of fineness f needs.
  void sample(double bx, double by, double f)
  {
    const int k = this->Levels.levelAt(f);
    this->at(k, bx, by);
    if (k < this->Levels.count && f > k - kPageBlendBand - kPageLevelMargin)
    {
      this->at(k + 1, bx, by); // the dithered band, or the edge
    }
    if (k > 1 && f < k - 1 + kPageLevelMargin)
    {
      this->at(k - 1, bx, by);
    }
  }

  /// Every page of levels k0 .. k1 that base rectangle [b0, b1] touches, up to mostPerLevel
  /// pages a level (more: that level is left to the coarser ones).
  void rect(int k0, int k1, const glm::dvec2& b0, const glm::dvec2& b1, int mostPerLevel)
  {
    for (int k = std::max(k0, 1); k <= std::min(k1, this->Levels.count); ++k)
    {
      const glm::dvec2 texels = this->Levels.texels(k);
      const glm::ivec2 p0 = this->pageOf(b0 * texels - kPageTexelMargin, texels);
      const glm::ivec2 p1 = this->pageOf(b1 * texels + kPageTexelMargin, texels);
      if (static_cast<double>(p1.x - p0.x + 1) * (p1.y - p0.y + 1) > mostPerLevel)
      {
        continue;
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

  std::vector<std::uint64_t> Keys;

private:
  glm::ivec2 pageOf(const glm::dvec2& texel, const glm::dvec2& texels) const
  {
    const glm::dvec2 last = glm::ceil(texels / double(kPageInterior)) - 1.0;
    const glm::dvec2 page =
      glm::clamp(glm::floor(texel / double(kPageInterior)), glm::dvec2(0.0), last);
    return glm::ivec2(page);
  }

  void at(int k, double bx, double by)
  {
    if (k < 1 || !(bx >= 0.0 && bx <= 1.0 && by >= 0.0 && by <= 1.0))
    {
      return; // the base, or outside it (the lookup finds no map there)
    }
    const glm::dvec2 texels = this->Levels.texels(k);
    const glm::dvec2 u(bx * texels.x, by * texels.y);
    const glm::ivec2 p0 = this->pageOf(u - kPageTexelMargin, texels);
    const glm::ivec2 p1 = this->pageOf(u + kPageTexelMargin, texels);
    for (int y = p0.y; y <= p1.y; ++y)
    {
      for (int x = p0.x; x <= p1.x; ++x)
      {
        this->push(PageKey{ k, x, y }.packed());
      }
    }
  }

  void push(std::uint64_t key)
  {
    if (std::find(this->Recent.begin(), this->Recent.end(), key) != this->Recent.end())
    {
      return;
    }
    this->Recent[this->Next] = key;
    this->Next = (this->Next + 1) % this->Recent.size();
    this->Keys.push_back(key);
  }

  const PageLevels& Levels;
  std::array<std::uint64_t, 8> Recent{};
  std::size_t Next = 0;
};
} // namespace

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
  PageMarks marks(levels);
  // (Key 0 is no page: level 0 is the base.)
  for (int y = 0; y < height; ++y)
  {
    const double ndcY = 2.0 * (y + 0.5) / height - 1.0;
    const glm::dvec4 row = windowToBase * glm::dvec4(0.0, ndcY, 0.0, 1.0);
    const glm::dvec4 alongX = windowToBase[0];
    const glm::dvec4 alongZ = windowToBase[2];
    for (int x = 0; x < width; ++x)
    {
      const float w = windowDepths[static_cast<std::size_t>(y) * width + x];
      if (!(w < 1.0f) || !(w >= 0.0f))
      {
        continue; // background, or not a depth
      }
      const double ndcX = 2.0 * (x + 0.5) / width - 1.0;
      const glm::dvec4 b = row + ndcX * alongX + (2.0 * w - 1.0) * alongZ;
      if (!(b.w > 0.0))
      {
        continue;
      }
      const double d = viewDepthFromWindowDepth(w, vsNear, vsFar, false);
      marks.sample(b.x / b.w, b.y / b.w, levels.fineness(d));
    }
  }
  for (const BoxStandIn& standIn : standIns)
  {
    const ScreenRect& r = standIn.rect;
    if (r.isEmpty() || standIn.depths.isEmpty())
    {
      continue;
    }
    glm::dvec2 b0(1e300), b1(-1e300);
    for (const double w : { standIn.depths.min, standIn.depths.max })
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
    const double nearest =
      levels.fineness(viewDepthFromWindowDepth(standIn.depths.min, vsNear, vsFar, false));
    const double farthest =
      levels.fineness(viewDepthFromWindowDepth(standIn.depths.max, vsNear, vsFar, false));
    if (b0.x <= b1.x && b0.y <= b1.y)
    {
      marks.rect(levels.levelAt(farthest - kPageLevelMargin),
        levels.levelAt(nearest + kPageBlendBand + kPageLevelMargin), glm::clamp(b0, 0.0, 1.0),
        glm::clamp(b1, 0.0, 1.0), kPageTableSide * kPageTableSide / 16);
    }
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

glm::dmat4 pageClip(const glm::dmat4& wsToBaseClip, const PageLevels& levels, const PageKey& page)
{
  // Base clip x = 2 u / texels - 1 for texel coordinate u of the level; the page's texels with
  // its border are u in [x kPageInterior - kPageBorder, + kPageTexels).
  const glm::dvec2 texels = levels.texels(page.level);
  const glm::dvec2 first(
    page.x * double(kPageInterior) - kPageBorder, page.y * double(kPageInterior) - kPageBorder);
  const glm::dvec2 centre = (2.0 * first + double(kPageTexels)) / texels - 1.0;
  const glm::dvec2 half = double(kPageTexels) / texels;
  glm::dmat4 crop(1.0);
  crop[0][0] = 1.0 / half.x;
  crop[1][1] = 1.0 / half.y;
  crop[3][0] = -centre.x / half.x;
  crop[3][1] = -centre.y / half.y;
  return crop * wsToBaseClip;
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

int poolSlots(int baseSide)
{
  if (baseSide < kPageTexels || baseSide % kPageTexels != 0)
  {
    return 0;
  }
  const int n = baseSide / kPageTexels;
  return 3 * n * n;
}

glm::ivec2 poolSlotPlace(int baseSide, int slot)
{
  const int n = std::max(1, baseSide / kPageTexels);
  const int square = slot / (n * n), i = slot % (n * n);
  static const glm::ivec2 corners[3] = { { 1, 0 }, { 0, 1 }, { 1, 1 } };
  return corners[std::min(std::max(square, 0), 2)] * n + glm::ivec2(i % n, i / n);
}

} // namespace csm
