// SPDX-License-Identifier: BSD-3-Clause
// A family of machined parts whose shadows meet their receivers along concave creases and
// contact edges: L, U and inverted-T profiles with fillets and chamfers, a hollow box section
// lying on a plate, a plate with a hole, a boss and a stacked plate, stacked steps from thick to
// thin, an L standing on a plate with a block in its inner corner. Every prop is one or more
// closed, consistently wound surfaces (drawn into the maps from behind); parts touch, none
// interpenetrate. Metres, y up, parts of 10-25 cm.
#pragma once

#include "csmScenes.h"

#include <string>
#include <vector>

namespace csmPartFamily
{

/// The members, each a scene of plain white actors (diffuse only) with no camera set.
std::vector<csmScenes::Scene> Members();

/// One view of a member: a camera (close or far) and a directional light.
struct View
{
  int Member = 0;
  bool Close = true;
  double Elevation = 20.0; ///< degrees above the horizon
  double Azimuth = 0.0;    ///< degrees; 0: the light travels along +x, 90: along -z
};

/// The views of every member: each camera under each light of the sweep. The short sweep
/// (eight lights from 5 to 80 degrees above the horizon, azimuths all round) for the tests; the
/// full one (elevations 5, 10, 20, 30, 45, 60, 80 times azimuths every 30 degrees) for a study.
std::vector<View> Views(int members, bool full);

/// The light's direction of travel for a view.
void LightDirection(const View& view, double direction[3]);

/// Puts the view's camera on the renderer (the member's actors already added): close, from
/// 1.1 times the member's diagonal looking into its inner corners; far, from 3 times it, higher.
void PlaceCamera(const View& view, const csmScenes::Scene& member, vtkRenderer* renderer);

} // namespace csmPartFamily
