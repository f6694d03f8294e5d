// SPDX-License-Identifier: BSD-3-Clause
#include "csmVisibleDepth.h"

#include "csmGeometry.h"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace csm
{

bool DepthRange::isEmpty() const
{
  return !(this->vsNear <= this->vsFar);
}

bool WindowDepthRange::isEmpty() const
{
  return !(this->min <= this->max);
}

WindowDepthRange windowDepthRange(const float* windowDepths, std::size_t count)
{
  WindowDepthRange range;
  if (!windowDepths)
  {
    return range;
  }
  float lo = 1.0f;
  float hi = 0.0f;
  for (std::size_t i = 0; i < count; ++i)
  {
    // (Without a branch, so that the loop vectorizes: the background, 1, and NaN leave both.)
    const float d = windowDepths[i];
    const bool sample = d < 1.0f && d >= 0.0f; // also false for NaN
    lo = std::min(lo, sample ? d : 1.0f);
    hi = std::max(hi, sample ? d : 0.0f);
  }
  if (lo <= hi)
  {
    range.min = lo;
    range.max = hi;
  }
  return range;
}

double viewDepthFromWindowDepth(double windowDepth, double vsNear, double vsFar, bool parallel)
{
  const double w = std::clamp(windowDepth, 0.0, 1.0);
  if (parallel)
  {
    return vsNear + w * (vsFar - vsNear);
  }
  // NDC z = (f + n) / (f - n) - 2 f n / ((f - n) d), window = (NDC z + 1) / 2.
  const double ndc = 2.0 * w - 1.0;
  return 2.0 * vsFar * vsNear / ((vsFar + vsNear) - ndc * (vsFar - vsNear));
}

double windowDepthFromViewDepth(double vsDepth, double vsNear, double vsFar, bool parallel)
{
  if (parallel)
  {
    return (vsDepth - vsNear) / (vsFar - vsNear);
  }
  const double ndc =
    (vsFar + vsNear) / (vsFar - vsNear) - 2.0 * vsFar * vsNear / ((vsFar - vsNear) * vsDepth);
  return 0.5 * (ndc + 1.0);
}

DepthRange viewDepthRange(const WindowDepthRange& window, const Camera& camera)
{
  DepthRange range;
  if (window.isEmpty() || !cameraError(camera).empty())
  {
    return range;
  }
  range.vsNear = viewDepthFromWindowDepth(window.min, camera.vsNear, camera.vsFar, camera.parallel);
  range.vsFar = viewDepthFromWindowDepth(window.max, camera.vsNear, camera.vsFar, camera.parallel);
  return range;
}

namespace
{
/// How far from the eye a point seen at view depth d can be: d over the cosine of the half
/// diagonal field of view, or (parallel) d plus the half diagonal of the view.
double reach(const Camera& camera, double d)
{
  if (camera.parallel)
  {
    return d + camera.parallelScale * std::sqrt(1.0 + camera.aspect * camera.aspect);
  }
  const double tanHalfY = std::tan(glm::radians(0.5 * camera.fovyDeg));
  const double tanHalfX = tanHalfY * camera.aspect;
  return d * std::sqrt(1.0 + tanHalfX * tanHalfX + tanHalfY * tanHalfY);
}
}

DepthRange carryDepthRange(
  const Camera& measuredBy, const DepthRange& measured, const Camera& camera)
{
  DepthRange carried;
  if (measured.isEmpty() || !std::isfinite(measured.vsNear) || !std::isfinite(measured.vsFar) ||
    !cameraError(measuredBy).empty() || !cameraError(camera).empty() ||
    camera.parallel != measuredBy.parallel)
  {
    return carried;
  }
  const glm::dvec3 before = glm::normalize(measuredBy.wsDirection);
  const glm::dvec3 now = glm::normalize(camera.wsDirection);
  const double turn = glm::length(now - before); // 2 sin(angle / 2)
  const double maximumTurn = 2.0 * std::sin(glm::radians(0.5 * kVisibleDepthMaximumTurnDeg));
  if (!(turn <= maximumTurn))
  {
    return carried;
  }
  const double moved = glm::length(camera.wsPosition - measuredBy.wsPosition);
  const double nearest = measured.vsNear - reach(measuredBy, measured.vsNear) * turn - moved;
  const double farthest = measured.vsFar + reach(measuredBy, measured.vsFar) * turn + moved;
  carried.vsNear = nearest * (1.0 - kVisibleDepthMargin);
  carried.vsFar = farthest * (1.0 + kVisibleDepthMargin);
  if (!std::isfinite(carried.vsNear) || !std::isfinite(carried.vsFar))
  {
    return DepthRange();
  }
  return carried;
}

bool depthRangeHolds(
  const DepthRange& covered, const WindowDepthRange& measured, const Camera& camera)
{
  if (measured.isEmpty())
  {
    return true;
  }
  if (covered.isEmpty() || !cameraError(camera).empty())
  {
    return false;
  }
  const double lo =
    windowDepthFromViewDepth(covered.vsNear, camera.vsNear, camera.vsFar, camera.parallel);
  const double hi =
    windowDepthFromViewDepth(covered.vsFar, camera.vsNear, camera.vsFar, camera.parallel);
  return measured.min >= lo - kWindowDepthTolerance && measured.max <= hi + kWindowDepthTolerance;
}

bool ScreenRect::isEmpty() const
{
  return !(this->x0 <= this->x1 && this->y0 <= this->y1);
}

void ScreenRect::add(const ScreenRect& other)
{
  if (other.isEmpty())
  {
    return;
  }
  if (this->isEmpty())
  {
    *this = other;
    return;
  }
  this->x0 = std::min(this->x0, other.x0);
  this->y0 = std::min(this->y0, other.y0);
  this->x1 = std::max(this->x1, other.x1);
  this->y1 = std::max(this->y1, other.y1);
}

bool WindowFootprint::isEmpty() const
{
  return this->range.isEmpty() || this->bins.empty();
}

namespace
{
/// The bins of a footprint's range: a window depth's bin is (w - min) times `scale`, truncated
/// and clamped to the bins (one formula for the samples and the queries).
struct FootprintBins
{
  double min = 0.0;
  double scale = 0.0; ///< bins per window depth (0: a range of one depth, all in bin 0)
  int count = 0;
  explicit FootprintBins(const WindowFootprint& footprint)
    : min(footprint.range.min)
    , count(static_cast<int>(footprint.bins.size()))
  {
    const double span = footprint.range.max - footprint.range.min;
    this->scale = span > 0.0 ? this->count / span : 0.0;
  }
  int of(double w) const
  {
    const double t = (w - this->min) * this->scale;
    if (!(t > 0.0)) // also NaN
    {
      return 0;
    }
    return t >= this->count - 1 ? this->count - 1 : static_cast<int>(t);
  }
  /// The smallest float window depth in bin b or a later one (b in 1 .. count - 1), so that a
  /// float w is in bin b exactly where lowest(b) <= w < lowest(b + 1).
  float lowest(int b) const
  {
    if (!(this->scale > 0.0))
    {
      return 2.0f; // (one depth: every sample in bin 0)
    }
    float w = static_cast<float>(this->min + b / this->scale);
    while (this->of(w) >= b && w > 0.0f)
    {
      w = std::nextafter(w, 0.0f);
    }
    while (this->of(w) < b)
    {
      w = std::nextafter(w, 2.0f);
    }
    return w;
  }
};
}

ScreenRect WindowFootprint::rectBetween(double w0, double w1) const
{
  ScreenRect rect;
  if (this->isEmpty() || !(w0 <= w1) || w1 < this->range.min || w0 > this->range.max)
  {
    return rect;
  }
  const FootprintBins binning(*this);
  const int first = binning.of(w0);
  const int last = binning.of(w1);
  for (int b = first; b <= last; ++b)
  {
    rect.add(this->bins[static_cast<size_t>(b)]);
  }
  return rect;
}

bool boxStandIn(const glm::dmat4& wsToClip, const Bounds& wsBox, double cells, int width,
  int height, BoxStandIn& standIn)
{
  if (width < 1 || height < 1 || !(cells > 0.0) || !std::isfinite(cells) || wsBox.isEmpty() ||
    !wsBox.isFinite())
  {
    return false;
  }
  BoxStandIn box;
  constexpr double inf = std::numeric_limits<double>::infinity();
  double x0 = inf, y0 = inf, x1 = -inf, y1 = -inf;
  double w0 = inf, w1 = -inf;
  for (int corner = 0; corner < 8; ++corner)
  {
    const glm::dvec4 wsCorner((corner & 1) ? wsBox.wsMax.x : wsBox.wsMin.x,
      (corner & 2) ? wsBox.wsMax.y : wsBox.wsMin.y, (corner & 4) ? wsBox.wsMax.z : wsBox.wsMin.z,
      1.0);
    const glm::dvec4 clip = wsToClip * wsCorner;
    if (!(clip.w > 0.0) || !std::isfinite(clip.x) || !std::isfinite(clip.y) ||
      !std::isfinite(clip.z) || !std::isfinite(clip.w))
    {
      return false; // behind the eye's plane: no bounded rectangle
    }
    const glm::dvec3 ndc = glm::dvec3(clip) / clip.w;
    x0 = std::min(x0, ndc.x);
    y0 = std::min(y0, ndc.y);
    x1 = std::max(x1, ndc.x);
    y1 = std::max(y1, ndc.y);
    const double w = 0.5 * ndc.z + 0.5; // GL's default depth range
    w0 = std::min(w0, w);
    w1 = std::max(w1, w);
  }
  box.rect.x0 = std::max(x0, -1.0);
  box.rect.y0 = std::max(y0, -1.0);
  box.rect.x1 = std::min(x1, 1.0);
  box.rect.y1 = std::min(y1, 1.0);
  box.depths.min = std::max(w0, 0.0);
  box.depths.max = std::min(w1, 1.0);
  if (!(box.rect.x0 < box.rect.x1) || !(box.rect.y0 < box.rect.y1) || box.depths.isEmpty())
  {
    return false; // outside the view (or edge-on): nothing to stand in for
  }
  const double pixels =
    0.25 * (box.rect.x1 - box.rect.x0) * width * (box.rect.y1 - box.rect.y0) * height;
  if (!(pixels < kDepthPassPixelsPerCell * cells))
  {
    return false;
  }
  standIn = box;
  return true;
}

WindowFootprint windowFootprint(
  const float* windowDepths, int width, int height, const std::vector<BoxStandIn>& standIns)
{
  WindowFootprint footprint;
  if (!windowDepths || width < 1 || height < 1)
  {
    return footprint;
  }
  const size_t count = static_cast<size_t>(width) * static_cast<size_t>(height);
  footprint.range = windowDepthRange(windowDepths, count);
  for (const BoxStandIn& box : standIns)
  {
    if (!box.rect.isEmpty() && !box.depths.isEmpty())
    {
      footprint.range.min = std::min(footprint.range.min, box.depths.min);
      footprint.range.max = std::max(footprint.range.max, box.depths.max);
    }
  }
  if (footprint.range.isEmpty())
  {
    return footprint;
  }
  footprint.bins.assign(kFootprintBins, ScreenRect());
  const FootprintBins binning(footprint);
  // Per bin, the pixel columns and rows its samples cover; then their pixels' full extent. A
  // row is taken in runs of samples of one bin (a surface's neighbouring pixels mostly share
  // theirs): a run's bin is checked against that bin's float bounds, its cover updated once.
  std::vector<std::array<int, 4>> cover(kFootprintBins, { width, height, -1, -1 });
  std::array<float, kFootprintBins + 1> lowest;
  lowest[0] = -1.0f;
  for (int b = 1; b < kFootprintBins; ++b)
  {
    lowest[b] = binning.lowest(b);
  }
  lowest[kFootprintBins] = 2.0f;
  for (int row = 0; row < height; ++row)
  {
    const float* line = windowDepths + static_cast<size_t>(row) * static_cast<size_t>(width);
    int column = 0;
    while (column < width)
    {
      const float w = line[column];
      if (!(w < 1.0f) || !(w >= 0.0f)) // the background, and NaN
      {
        ++column;
        continue;
      }
      const int b = binning.of(w);
      const float below = lowest[b], above = lowest[b + 1];
      const int first = column;
      for (++column; column < width; ++column)
      {
        const float next = line[column];
        if (!(next >= below && next < above && next < 1.0f))
        {
          break;
        }
      }
      std::array<int, 4>& c = cover[static_cast<size_t>(b)];
      c[0] = std::min(c[0], first);
      c[1] = std::min(c[1], row);
      c[2] = std::max(c[2], column - 1);
      c[3] = row;
    }
  }
  for (int b = 0; b < kFootprintBins; ++b)
  {
    const std::array<int, 4>& c = cover[static_cast<size_t>(b)];
    if (c[2] < c[0])
    {
      continue;
    }
    ScreenRect& rect = footprint.bins[static_cast<size_t>(b)];
    rect.x0 = 2.0 * c[0] / width - 1.0;
    rect.y0 = 2.0 * c[1] / height - 1.0;
    rect.x1 = 2.0 * (c[2] + 1) / width - 1.0;
    rect.y1 = 2.0 * (c[3] + 1) / height - 1.0;
  }
  // The stand-ins, in every bin their depths span.
  for (const BoxStandIn& box : standIns)
  {
    if (box.rect.isEmpty() || box.depths.isEmpty())
    {
      continue;
    }
    for (int b = binning.of(box.depths.min); b <= binning.of(box.depths.max); ++b)
    {
      footprint.bins[static_cast<size_t>(b)].add(box.rect);
    }
  }
  return footprint;
}

bool sameImage(const Camera& a, const Camera& b)
{
  constexpr double tolerance = 1e-6;
  if (!cameraError(a).empty() || !cameraError(b).empty() || a.parallel != b.parallel)
  {
    return false;
  }
  auto close = [&](double x, double y, double scale) {
    return std::abs(x - y) <= tolerance * std::max({ std::abs(x), std::abs(y), scale });
  };
  auto sameDirection = [&](const glm::dvec3& u, const glm::dvec3& v)
  { return glm::length(glm::normalize(u) - glm::normalize(v)) <= tolerance; };
  // Positions compared at the nearest distance either view draws (a step shifts the image of
  // a point at depth d by step / d).
  const double scale = std::max(std::min(a.vsNear, b.vsNear), 1e-300);
  const glm::dvec3 moved = a.wsPosition - b.wsPosition;
  return glm::length(moved) <= tolerance * scale && sameDirection(a.wsDirection, b.wsDirection) &&
    sameDirection(glm::cross(a.wsDirection, a.wsViewUp), glm::cross(b.wsDirection, b.wsViewUp)) &&
    close(a.aspect, b.aspect, 0.0) &&
    (a.parallel ? close(a.parallelScale, b.parallelScale, 0.0) : close(a.fovyDeg, b.fovyDeg, 0.0));
}

ScreenRect footprintRect(
  const WindowFootprint& footprint, const Camera& camera, double vsD0, double vsD1)
{
  if (footprint.isEmpty() || !cameraError(camera).empty() || !(vsD0 <= vsD1))
  {
    return ScreenRect();
  }
  const double w0 = windowDepthFromViewDepth(vsD0, camera.vsNear, camera.vsFar, camera.parallel);
  const double w1 = windowDepthFromViewDepth(vsD1, camera.vsNear, camera.vsFar, camera.parallel);
  if (!std::isfinite(w0) || !std::isfinite(w1))
  {
    return ScreenRect();
  }
  return footprint.rectBetween(std::min(w0, w1), std::max(w0, w1));
}

std::vector<Plane> screenRectPlanes(const Camera& camera, const ScreenRect& rect)
{
  std::vector<Plane> planes;
  if (rect.isEmpty() || !cameraError(camera).empty())
  {
    return planes;
  }
  const CameraFrame frame = cameraFrame(camera);
  // A point p = a view + b right + c up (camera-centred) is at image x = b / (a tanX) in a
  // perspective view, b / half width in a parallel one; x >= x0 is then
  // dot(p, right - x0 tanX view) >= 0, or dot(p, right) - x0 halfWidth >= 0 (and so on).
  const glm::dvec2 half = halfSize(camera, frame, 1.0);
  const double tanAxis[2] = { frame.tanX, frame.tanY };
  const glm::dvec3 axis[2] = { frame.right, frame.up };
  const double low[2] = { rect.x0, rect.y0 };
  const double high[2] = { rect.x1, rect.y1 };
  for (int i = 0; i < 2; ++i)
  {
    for (int side = 0; side < 2; ++side)
    {
      const double sign = side == 0 ? 1.0 : -1.0;
      const double edge = side == 0 ? low[i] : high[i];
      Plane plane;
      if (camera.parallel)
      {
        plane.normal = sign * axis[i];
        plane.offset = -sign * edge * (i == 0 ? half.x : half.y);
      }
      else
      {
        plane.normal = sign * (axis[i] - edge * tanAxis[i] * frame.view);
        plane.offset = 0.0;
      }
      const double length = glm::length(plane.normal);
      plane.normal /= length;
      plane.offset /= length;
      planes.push_back(plane);
    }
  }
  return planes;
}

} // namespace csm
