// SPDX-License-Identifier: BSD-3-Clause
// The warp parameter n' of a light-space perspective shadow map, and its pieces.
// Pure math: no VTK, no GL. Angles in radians, lengths in view-space units.
#pragma once

namespace csm
{

enum class WarpMode
{
  None,   ///< orthographic light frustum: the standard shadow map (n' = infinity)
  PSM,    ///< n' = n (Lloyd et al. 2006, §4.1)
  LiSPSM, ///< Wimmer's n' = (n + sqrt(f n)) / sin(gamma) (Barroso & Celes 2007, §2.3 at gamma = 90
          ///< deg)
  Generalized ///< Barroso & Celes, Barroso & Celes 2007, Eq. 16-18
};

/// The view-frustum partition a warp is fitted to, as Barroso & Celes 2007, §3.1 names it.
struct PartitionShape
{
  double n = 1.0; ///< near distance of the partition along the view direction
  double f = 2.0; ///< far distance
  double a = 0.0; ///< half the height of the near face, in the plane of light and view
  double b = 0.0; ///< half the height of the far face, in the same direction
};

/// Barroso & Celes 2007, Eq. 15: the limit angle below which n' stops following Eq. 13.
double gammaLim(const PartitionShape& p);

/// Barroso & Celes 2007, Eq. 18 (written as 2 sin^2(u pi/4), the same value without cancellation
/// near 0): r(gammaLim) = 1, r(0) = 0. gamma is clamped to [0, gammaLim].
double rOfGamma(double gamma, double gammaLimit);

/// Barroso & Celes 2007, Eq. 13, first case: n'_1(gamma) = (n + sqrt(f n)) sin(gamma) - a
/// cos(gamma).
double nPrime1(double gamma, const PartitionShape& p);

/// Barroso & Celes 2007, Eq. 16: the generalized LiSPSM parameter. gamma is the smallest angle
/// between light and view direction, in [0, pi/2]. Returns +infinity (orthographic) at gamma = 0.
double nPrimeGeneralized(double gamma, const PartitionShape& p);

/// n' for any warp mode; +infinity means orthographic. gamma in [0, pi/2].
double nPrime(WarpMode mode, double gamma, const PartitionShape& p);

const char* toString(WarpMode mode);
bool parseWarpMode(const char* text, WarpMode& mode);

} // namespace csm
