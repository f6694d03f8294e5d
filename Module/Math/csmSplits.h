// SPDX-License-Identifier: BSD-3-Clause
// Split depths of a z-partitioned (cascaded) view frustum. Pure math: no VTK, no GL.
#pragma once

#include <vector>

namespace csm
{

enum class SplitScheme
{
  Single,  ///< one partition [n, f], whatever k says
  Uniform, ///< n + (f - n) i / k
  Log,     ///< self-similar partitions, Barroso & Celes 2007, Eq. 5 / Lloyd et al. 2006, Eq. 15-16
  Practical, ///< lambda log + (1 - lambda) uniform (Vázquez, parallel-split shadow maps)
  Adaptive   ///< Barroso & Celes, Barroso & Celes 2007, Eq. 19
};

/// The most partitions the math plans (the render passes use fewer: see
/// vtkCascadedShadowMapPlanner::MAXIMUM_NUMBER_OF_CASCADES).
constexpr int kMaxSplits = 64;

struct SplitParameters
{
  SplitScheme scheme = SplitScheme::Adaptive;
  int k = 2;           ///< number of partitions, >= 1
  double lambda = 0.5; ///< weight of the log splits in the practical scheme, [0, 1]
  double alpha =
    2.0; ///< adaptive scheme: f_i / n_i of every partition but the first at gamma = 0, > 1
};

/// Split depths s_0 = n < s_1 < ... < s_k = f along the view direction (k + 1 values; 2 for
/// Single). gamma is the smallest angle between light and view direction, in [0, pi/2]; only the
/// adaptive scheme uses it. Requires 0 < n < f, finite; lambda in [0,1]; alpha > 1; k >= 1.
std::vector<double> splitDepths(const SplitParameters& params, double n, double f, double gamma);

/// The partition a view depth falls in: the first i with depth <= splitFar[i], or -1 outside
/// [splitNear, splitFar[count - 1]] (the shader's selection by depth, Lloyd et al. 2006, §6.3).
int partitionAtDepth(double depth, double splitNear, const double* splitFar, int count);

const char* toString(SplitScheme scheme);
bool parseSplitScheme(const char* text, SplitScheme& scheme);

} // namespace csm
