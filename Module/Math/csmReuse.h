// SPDX-License-Identifier: BSD-3-Clause
// Whether a shadow map rendered for an earlier frame can stand in for a freshly planned cascade
// (maps reused across frames: re-render only what the view needs). Pure math, no VTK, no GL.
#pragma once

#include "csmShadowSetup.h"

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

/// Compare a kept world -> light clip matrix with the freshly planned cascade of the same light
/// for the current camera. marginNdc: the band along the map's border that the lookup's filter
/// reaches (PCF radius plus one texel, in NDC units: 2 (r + 1) / resolution).
MapReuse compareKeptMap(const glm::dmat4& wsKeptToClip, const Cascade& fresh,
  const Camera& camera, const glm::dvec3& wsLightDirection, bool directional, double marginNdc);

} // namespace csm
