// SPDX-License-Identifier: BSD-3-Clause
// The depth range the view really has samples in (sample distribution, as Lauritzen's SDSM and
// the Vázquez slides' "adjust the depth range to visible objects"): read from a frame's depth
// buffer, carried to the next frame's camera with a bound on how far the camera moved, and
// checked against the range the cascades of that frame covered. Pure math, no VTK, no GL.
#pragma once

#include "csmTypes.h"

#include <cstddef>

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

} // namespace csm
