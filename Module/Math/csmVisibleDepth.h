// SPDX-License-Identifier: BSD-3-Clause
// The depth range the view really has samples in (sample distribution, as Lauritzen's SDSM and
// the Vázquez slides' "adjust the depth range to visible objects"): read from a frame's depth
// buffer, carried to the next frame's camera with a bound on how far the camera moved, and
// checked against the range the cascades of that frame covered. Pure math, no VTK, no GL.
#pragma once

#include "csmConvexBody.h"
#include "csmTypes.h"

#include <glm/mat4x4.hpp>

#include <cstddef>
#include <vector>

namespace csm
{

/// View depths (distance along the view direction); empty when vsNear > vsFar.
struct DepthRange
{
  double vsNear = 1.0;
  double vsFar = -1.0;
  bool isEmpty() const;
};

/// Window depths of a depth buffer (GL's default depth range [0, 1]); empty when min > max.
struct WindowDepthRange
{
  double min = 1.0;
  double max = 0.0;
  bool isEmpty() const;
};

/// Relative margin around a carried range (depth-buffer quantization, float rounding).
constexpr double kVisibleDepthMargin = 0.005;

/// The carried range is given up (the camera jumped) when the view direction turned by more
/// than this many degrees since the frame that measured it.
constexpr double kVisibleDepthMaximumTurnDeg = 15.0;

/// Window depths that differ by at most this much count as equal (a few steps of a 24-bit
/// depth buffer).
constexpr double kWindowDepthTolerance = 16.0 / 16777216.0;

/// The nearest and farthest window depth of a depth buffer's values, those below 1 (1 is the
/// cleared background); empty when every value is 1 or none is finite.
WindowDepthRange windowDepthRange(const float* windowDepths, std::size_t count);

/// The view depth of a window depth (GL's default depth range) for a camera's clipping range:
/// the inverse of the perspective (or, with parallel, the orthographic) projection's depth.
double viewDepthFromWindowDepth(double windowDepth, double vsNear, double vsFar, bool parallel);

/// Its inverse: the window depth a view depth is written with.
double windowDepthFromViewDepth(double vsDepth, double vsNear, double vsFar, bool parallel);

/// The view depths of a window depth range seen by camera (its clipping range and projection).
DepthRange viewDepthRange(const WindowDepthRange& window, const Camera& camera);

/// The view depths, for camera, of every point that was visible at depths measured.vsNear ..
/// measured.vsFar to measuredBy (an earlier frame's camera): each such point lies within
/// |p - eye| <= r(d) of that eye (r: d over the cosine of the half diagonal field of view, or
/// d plus the half diagonal of a parallel view), so its new depth is within r(d) |dir' - dir| +
/// |eye' - eye| of d; widened by kVisibleDepthMargin. Empty when either camera is invalid,
/// measured is empty, or the view direction turned by more than kVisibleDepthMaximumTurnDeg
/// (the camera jumped: fit to the scene's boxes instead). Points that were not visible before
/// may land outside: depthRangeHolds() tells, once the frame is drawn.
DepthRange carryDepthRange(
  const Camera& measuredBy, const DepthRange& measured, const Camera& camera);

/// Did every visible sample of a frame (window depths measured, as camera wrote them) fall in
/// the view depths covered (the cascades' range), up to kWindowDepthTolerance? True for an empty
/// measurement (nothing visible).
bool depthRangeHolds(
  const DepthRange& covered, const WindowDepthRange& measured, const Camera& camera);

/// A rectangle of the image in normalized device coordinates ([-1, 1] across the viewport);
/// empty when x0 > x1 or y0 > y1.
struct ScreenRect
{
  double x0 = 1.0, y0 = 1.0, x1 = -1.0, y1 = -1.0;
  bool isEmpty() const;
  /// Grown to hold another rectangle (an empty one changes nothing).
  void add(const ScreenRect& other);
};

/// Window-depth bins of a depth buffer's samples between the nearest and the farthest.
constexpr int kFootprintBins = 64;

/// Where on the image a frame's visible samples lie, by depth (the tight partition bounds of
/// Lauritzen et al. 2011's sample distribution shadow maps): the window depths from the nearest
/// to the farthest sample in kFootprintBins equal bins (about equal in 1 / view depth for a
/// perspective view: fine near the eye), each with the rectangle of its samples' pixels.
struct WindowFootprint
{
  WindowDepthRange range;
  std::vector<ScreenRect> bins;
  bool isEmpty() const;
  /// The rectangle of the samples at window depths w0 .. w1 (of every bin that range touches);
  /// empty where there are none.
  ScreenRect rectBetween(double w0, double w1) const;
};

/// A caster the visible-depth pass leaves out, represented by its box: the image rectangle and
/// the window depths the box spans, which a footprint holds as if they were samples.
struct BoxStandIn
{
  ScreenRect rect;
  WindowDepthRange depths;
};

/// Pixels of the image a caster's box must cover per cell (triangle) for the visible-depth pass
/// to draw the caster rather than stand its box in for it: each pixel whose hidden fragments
/// the pass's depth spares the lookup (about 50 ns of llvmpipe, Results.md, "Walking through a
/// structure") against each triangle the pass draws (about 130 ns, csm::kTexelsPerCasterTriangle).
/// A property of the renderer, not of a scene.
constexpr double kDepthPassPixelsPerCell = 2.5;

/// The stand-in of a world box of `cells` triangles for an image of width x height pixels seen
/// through wsToClip (world -> clip), where the box covers fewer than kDepthPassPixelsPerCell
/// pixels a cell; false where it covers more, reaches behind the eye's plane (its rectangle is
/// unbounded), or an input is not finite or positive.
bool boxStandIn(const glm::dmat4& wsToClip, const Bounds& wsBox, double cells, int width,
  int height, BoxStandIn& standIn);

/// The footprint of a depth buffer of width x height values (rows from the bottom), those
/// below 1 (1 is the cleared background), and of the boxes that stood in for casters the buffer
/// lacks (their window depths widen the range, their rectangles every bin they span); empty
/// when there is none of either or the size is not positive.
WindowFootprint windowFootprint(
  const float* windowDepths, int width, int height, const std::vector<BoxStandIn>& standIns = {});

/// A depth buffer as the visible-depth pass read it (width x height window depths, rows from
/// the bottom) and the boxes that stood in for the casters it left out.
struct DepthSamples
{
  std::vector<float> windowDepths;
  int width = 0;
  int height = 0;
  std::vector<BoxStandIn> standIns;
  bool isEmpty() const { return this->width < 1 || this->height < 1; }
};

/// A footprint and the camera that drew it.
struct ViewFootprint
{
  WindowFootprint window;
  Camera measuredBy;
};

/// Do two cameras see the same image, up to a relative 1e-6 (position against the nearer near
/// distance, direction, up, angle or scale, aspect; the clipping range may differ otherwise)?
/// A footprint serves only its own view.
bool sameImage(const Camera& a, const Camera& b);

/// The rectangle of the samples camera drew at view depths vsD0 .. vsD1 (its footprint);
/// empty where there are none, or for an invalid camera.
ScreenRect footprintRect(
  const WindowFootprint& footprint, const Camera& camera, double vsD0, double vsD1);

/// The camera-centred half-spaces whose intersection is the part of camera's view volume that
/// projects into rect (planes through the eye, or for a parallel view parallel to its axis);
/// none for an empty rectangle or an invalid camera.
std::vector<Plane> screenRectPlanes(const Camera& camera, const ScreenRect& rect);

} // namespace csm
