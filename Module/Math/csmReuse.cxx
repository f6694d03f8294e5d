// SPDX-License-Identifier: BSD-3-Clause
#include "csmReuse.h"

#include "csmAliasing.h"
#include "csmCascadeCount.h"

#include <glm/geometric.hpp>
#include <glm/vec4.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace csm
{

glm::dmat4 withBorder(const glm::dmat4& wsToClip, double border)
{
  if (!std::isfinite(border) || border <= 0.0)
  {
    return wsToClip;
  }
  // x, y and depth alike: a turning camera moves the body's far end too (one cascade, or the
  // last, ends where the visible scene does), so the kept depth range needs the margin as well.
  glm::dmat4 shrink(1.0);
  shrink[0][0] = shrink[1][1] = shrink[2][2] = 1.0 / (1.0 + 2.0 * border);
  return shrink * wsToClip;
}

SlackedMap slackedMap(const MapSize& need, const MapSize& most, double slack)
{
  SlackedMap slacked;
  slacked.size = need;
  if (need.width <= 0 || need.height <= 0 || !(slack > 0.0) || !std::isfinite(slack))
  {
    return slacked;
  }
  // The factor the tile leaves room for (1 where the tight map already fills it).
  const double factor = std::max(1.0,
    std::min({ 1.0 + slack, double(most.width) / need.width, double(most.height) / need.height }));
  slacked.border = 0.5 * (std::sqrt(factor) - 1.0);
  slacked.size.width = std::min(most.width, static_cast<int>(std::ceil(factor * need.width)));
  slacked.size.height = std::min(most.height, static_cast<int>(std::ceil(factor * need.height)));
  slacked.size.width = std::max(slacked.size.width, need.width);
  slacked.size.height = std::max(slacked.size.height, need.height);
  return slacked;
}

bool smallCameraStep(const Camera& before, const Camera& now, double vsDepth)
{
  const double lengths = glm::length(before.wsDirection) * glm::length(now.wsDirection);
  if (!(lengths > 0.0) || !std::isfinite(lengths) || !(vsDepth > 0.0) || !std::isfinite(vsDepth))
  {
    return false;
  }
  const double cosTurn = glm::dot(before.wsDirection, now.wsDirection) / lengths;
  const double moved = glm::length(now.wsPosition - before.wsPosition);
  const bool turned = cosTurn < 1.0;
  if (!std::isfinite(moved) || (moved == 0.0 && !turned))
  {
    return false;
  }
  constexpr double kPi = 3.14159265358979323846;
  return cosTurn >= std::cos(kSmallStepTurnDeg * kPi / 180.0) && moved <= kSmallStepShare * vsDepth;
}

double keptMapError(double errorRatio, const MapSize& keptSize, const MapSize& need)
{
  if (!std::isfinite(errorRatio) || errorRatio < 0.0 || keptSize.width <= 0 ||
    keptSize.height <= 0 || need.width <= 0 || need.height <= 0)
  {
    return std::numeric_limits<double>::infinity();
  }
  return errorRatio /
    std::min(double(keptSize.width) / need.width, double(keptSize.height) / need.height);
}

bool keptMapServes(
  double errorRatio, const MapSize& keptSize, const MapSize& need, bool targetOutOfReach)
{
  // (Rounding: a map kept for the very view it was planned for has a ratio of 1.)
  constexpr double kRounding = 1e-9;
  const double allowed = targetOutOfReach ? 1.0 / kCountHysteresis : 1.0;
  return keptMapError(errorRatio, keptSize, need) <= allowed * (1.0 + kRounding);
}

MapReuse compareKeptMap(const glm::dmat4& wsKeptToClip, const Cascade& fresh, const Camera& camera,
  const glm::dvec3& wsLightDirection, bool directional, double marginNdc)
{
  constexpr double kInf = std::numeric_limits<double>::infinity();
  MapReuse reuse;
  reuse.errorRatio = kInf;
  if (fresh.wsBody.empty() || !std::isfinite(marginNdc) || marginNdc < 0.0 || marginNdc >= 1.0)
  {
    return reuse;
  }
  // A freshly planned map has the body on its border: allow for rounding there.
  constexpr double kRounding = 1e-9;
  const double limit = 1.0 - marginNdc + kRounding;
  glm::dvec2 ndcMin(kInf), ndcMax(-kInf);
  for (const glm::dvec3& wsPoint : fresh.wsBody)
  {
    const glm::dvec4 h = wsKeptToClip * glm::dvec4(wsPoint, 1.0);
    if (!(h.w > 0.0))
    {
      return reuse;
    }
    const glm::dvec3 ndc = glm::dvec3(h) / h.w;
    if (!(std::abs(ndc.x) <= limit && std::abs(ndc.y) <= limit && ndc.z <= 1.0 + kRounding))
    {
      return reuse;
    }
    ndcMin = glm::min(ndcMin, glm::dvec2(ndc));
    ndcMax = glm::max(ndcMax, glm::dvec2(ndc));
  }
  reuse.covers = true;
  if (directional)
  {
    double kept = 0.0, planned = 0.0;
    for (const glm::dvec3& wsPoint : fresh.wsBody)
    {
      const Aliasing a = aliasingAt(wsKeptToClip, camera, wsLightDirection, wsPoint);
      const Aliasing b = aliasingAt(fresh.wsToClip, camera, wsLightDirection, wsPoint);
      kept = std::max(kept, std::max(a.mx, a.mz));
      planned = std::max(planned, std::max(b.mx, b.mz));
    }
    reuse.errorRatio = planned > 0.0 && std::isfinite(kept) ? kept / planned : kInf;
  }
  else
  {
    // One perspective centre: the ratio of the widths the body spans in the two maps.
    glm::dvec2 freshMin(kInf), freshMax(-kInf);
    for (const glm::dvec3& wsPoint : fresh.wsBody)
    {
      const glm::dvec4 h = fresh.wsToClip * glm::dvec4(wsPoint, 1.0);
      const glm::dvec2 ndc = glm::dvec2(h) / h.w;
      freshMin = glm::min(freshMin, ndc);
      freshMax = glm::max(freshMax, ndc);
    }
    const glm::dvec2 kept = ndcMax - ndcMin, planned = freshMax - freshMin;
    reuse.errorRatio =
      kept.x > 0.0 && kept.y > 0.0 ? std::max(planned.x / kept.x, planned.y / kept.y) : kInf;
    if (!std::isfinite(reuse.errorRatio))
    {
      reuse.errorRatio = kInf;
    }
  }
  return reuse;
}

glm::dmat4 panMatrix(const glm::dmat4& wsToClip, int s, int t, const MapSize& size)
{
  if (size.width <= 0 || size.height <= 0)
  {
    return wsToClip;
  }
  // ndc' = ndc - 2 s / width: in clip coordinates x' = x - (2 s / width) w.
  glm::dmat4 move(1.0);
  move[3][0] = -2.0 * s / size.width;
  move[3][1] = -2.0 * t / size.height;
  return move * wsToClip;
}

MapPan panKeptMap(
  const glm::dmat4& wsKeptToClip, const std::vector<glm::dvec3>& wsBody, const MapSize& size)
{
  MapPan pan;
  if (wsBody.empty() || size.width <= 0 || size.height <= 0)
  {
    return pan;
  }
  constexpr double kInf = std::numeric_limits<double>::infinity();
  glm::dvec2 ndcMin(kInf), ndcMax(-kInf);
  for (const glm::dvec3& wsPoint : wsBody)
  {
    const glm::dvec4 h = wsKeptToClip * glm::dvec4(wsPoint, 1.0);
    if (!(h.w > 0.0) || !std::isfinite(h.x) || !std::isfinite(h.y))
    {
      return pan;
    }
    const glm::dvec2 ndc = glm::dvec2(h) / h.w;
    ndcMin = glm::min(ndcMin, ndc);
    ndcMax = glm::max(ndcMax, ndc);
  }
  // The body's centre in texels from the map's centre.
  const glm::dvec2 centre = 0.5 * (ndcMin + ndcMax);
  const double s = std::round(0.5 * centre.x * size.width);
  const double t = std::round(0.5 * centre.y * size.height);
  if (!(std::abs(s) < size.width && std::abs(t) < size.height) || (s == 0.0 && t == 0.0))
  {
    return pan;
  }
  pan.s = static_cast<int>(s);
  pan.t = static_cast<int>(t);
  pan.wsToClip = panMatrix(wsKeptToClip, pan.s, pan.t, size);
  pan.valid = true;
  return pan;
}

std::vector<TexelRect> panStrips(const MapPan& pan, const MapSize& size)
{
  std::vector<TexelRect> strips;
  const int s = std::abs(pan.s), t = std::abs(pan.t);
  if (!pan.valid || s >= size.width || t >= size.height)
  {
    return strips;
  }
  if (s > 0)
  {
    strips.push_back({ pan.s > 0 ? size.width - s : 0, 0, s, size.height });
  }
  if (t > 0)
  {
    strips.push_back({ pan.s < 0 ? s : 0, pan.t > 0 ? size.height - t : 0, size.width - s, t });
  }
  return strips;
}

glm::dmat4 cropToTexels(const glm::dmat4& wsToClip, const TexelRect& rect, const MapSize& size)
{
  if (size.width <= 0 || size.height <= 0 || rect[2] <= 0 || rect[3] <= 0)
  {
    return wsToClip;
  }
  // The rect's ndc range [lo, hi] to [-1, 1]: ndc' = (ndc - centre) * 2 / (hi - lo).
  glm::dmat4 crop(1.0);
  const double scaleX = double(size.width) / rect[2], scaleY = double(size.height) / rect[3];
  const double centreX = (2.0 * rect[0] + rect[2]) / size.width - 1.0;
  const double centreY = (2.0 * rect[1] + rect[3]) / size.height - 1.0;
  crop[0][0] = scaleX;
  crop[1][1] = scaleY;
  crop[3][0] = -centreX * scaleX;
  crop[3][1] = -centreY * scaleY;
  return crop * wsToClip;
}

TexelRect boxTexels(
  const glm::dmat4& wsToClip, const Bounds& wsBox, const MapSize& size, int marginTexels)
{
  const TexelRect whole = { 0, 0, size.width, size.height };
  if (size.width <= 0 || size.height <= 0 || wsBox.isEmpty())
  {
    return { 0, 0, 0, 0 };
  }
  if (!wsBox.isFinite())
  {
    return whole;
  }
  double lo[2] = { HUGE_VAL, HUGE_VAL }, hi[2] = { -HUGE_VAL, -HUGE_VAL };
  for (int corner = 0; corner < 8; ++corner)
  {
    const glm::dvec4 clip = wsToClip *
      glm::dvec4(corner & 1 ? wsBox.wsMax.x : wsBox.wsMin.x,
        corner & 2 ? wsBox.wsMax.y : wsBox.wsMin.y, corner & 4 ? wsBox.wsMax.z : wsBox.wsMin.z,
        1.0);
    if (!(clip.w > 0.0) || !std::isfinite(clip.x) || !std::isfinite(clip.y))
    {
      return whole;
    }
    // Normalized device x and y to texels from the map's lower left.
    const double s = 0.5 * (clip.x / clip.w + 1.0) * size.width;
    const double t = 0.5 * (clip.y / clip.w + 1.0) * size.height;
    lo[0] = std::min(lo[0], s);
    lo[1] = std::min(lo[1], t);
    hi[0] = std::max(hi[0], s);
    hi[1] = std::max(hi[1], t);
  }
  const int extent[2] = { size.width, size.height };
  TexelRect rect = { 0, 0, 0, 0 };
  for (int axis = 0; axis < 2; ++axis)
  {
    const double first = std::max(0.0, std::floor(lo[axis]) - marginTexels);
    const double last = std::min(double(extent[axis]), std::ceil(hi[axis]) + marginTexels);
    if (!(last > first))
    {
      return { 0, 0, 0, 0 };
    }
    rect[axis] = static_cast<int>(first);
    rect[2 + axis] = static_cast<int>(last - first);
  }
  return rect;
}

namespace
{
double rectArea(const TexelRect& r)
{
  return double(r[2]) * double(r[3]);
}

TexelRect rectAround(const TexelRect& a, const TexelRect& b)
{
  const int x = std::min(a[0], b[0]), y = std::min(a[1], b[1]);
  return { x, y, std::max(a[0] + a[2], b[0] + b[2]) - x, std::max(a[1] + a[3], b[1] + b[3]) - y };
}
} // namespace

std::vector<TexelRect> mergeTexelRects(std::vector<TexelRect> rects)
{
  rects.erase(std::remove_if(rects.begin(), rects.end(),
                [](const TexelRect& r) { return r[2] <= 0 || r[3] <= 0; }),
    rects.end());
  if (rects.size() > kMostMergedRects)
  {
    return rects;
  }
  // Merge any pair that gains, until none does (each merge removes a rectangle).
  bool merged = true;
  while (merged)
  {
    merged = false;
    for (std::size_t i = 0; i < rects.size() && !merged; ++i)
    {
      for (std::size_t j = i + 1; j < rects.size() && !merged; ++j)
      {
        const TexelRect around = rectAround(rects[i], rects[j]);
        if (rectArea(around) <= rectArea(rects[i]) + rectArea(rects[j]))
        {
          rects[i] = around;
          rects.erase(rects.begin() + static_cast<std::ptrdiff_t>(j));
          merged = true;
        }
      }
    }
  }
  return rects;
}

bool rectInside(const TexelRect& inner, const TexelRect& outer)
{
  return inner[0] >= outer[0] && inner[1] >= outer[1] &&
    inner[0] + inner[2] <= outer[0] + outer[2] && inner[1] + inner[3] <= outer[1] + outer[3];
}

TileAssignment assignTiles(const std::vector<TexelRect>& planned,
  const std::vector<TexelRect>& oldTiles, const std::function<bool(int, int)>& serves,
  const std::vector<int>& order, bool acrossTiles)
{
  const int count = static_cast<int>(planned.size());
  const int oldCount = static_cast<int>(oldTiles.size());
  TileAssignment a;
  a.kept.assign(planned.size(), -1);
  a.tile = planned;
  std::vector<bool> tileTaken(planned.size(), false), oldTaken(oldTiles.size(), false);
  // The map of the same index in the same tile.
  for (int c = 0; c < count && c < oldCount; ++c)
  {
    if (oldTiles[c] == planned[c] && serves(c, c))
    {
      a.kept[c] = c;
      tileTaken[c] = oldTaken[c] = true;
    }
  }
  // Any other map whose tile lies in a free tile of the plan.
  for (int c : order)
  {
    if (!acrossTiles || c < 0 || c >= count || a.kept[c] >= 0)
    {
      continue;
    }
    for (int k = 0; k < oldCount && a.kept[c] < 0; ++k)
    {
      for (int t = 0; t < count && !oldTaken[k]; ++t)
      {
        if (!tileTaken[t] && rectInside(oldTiles[k], planned[t]) && serves(c, k))
        {
          a.kept[c] = k;
          a.tile[c] = oldTiles[k];
          tileTaken[t] = oldTaken[k] = true;
          break;
        }
      }
    }
  }
  // The maps drawn afresh: their own tile where it is free, else the first free one.
  for (int c = 0; c < count; ++c)
  {
    if (a.kept[c] >= 0)
    {
      continue;
    }
    int t = tileTaken[c] ? -1 : c;
    for (int u = 0; u < count && t < 0; ++u)
    {
      t = tileTaken[u] ? -1 : u;
    }
    a.tile[c] = planned[t]; // (as many tiles as cascades: one is free)
    tileTaken[t] = true;
  }
  return a;
}

} // namespace csm
