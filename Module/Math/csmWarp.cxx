// SPDX-License-Identifier: BSD-3-Clause
#include "csmWarp.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace csm
{
namespace
{
constexpr double kPi = 3.14159265358979323846;
constexpr double kInf = std::numeric_limits<double>::infinity();
}

double gammaLim(const PartitionShape& p)
{
  return std::atan2(p.a + p.b, p.f - p.n); // Barroso & Celes 2007, Eq. 15
}

double rOfGamma(double gamma, double gammaLimit)
{
  if (!(gammaLimit > 0.0))
  {
    return 1.0;
  }
  const double u = std::clamp(gamma / gammaLimit, 0.0, 1.0);
  // Barroso & Celes 2007, Eq. 18: [1 + sin((u - 1) pi/2)]^2 = [1 - cos(u pi/2)]^2 = [2 sin^2(u
  // pi/4)]^2
  const double s = std::sin(u * kPi / 4.0);
  const double base = 2.0 * s * s;
  return base * base;
}

double nPrime1(double gamma, const PartitionShape& p)
{
  // Barroso & Celes 2007, Eq. 13 (first case)
  return (p.n + std::sqrt(p.f * p.n)) * std::sin(gamma) - p.a * std::cos(gamma);
}

double nPrimeGeneralized(double gamma, const PartitionShape& p)
{
  const double limit = gammaLim(p);
  if (gamma >= limit)
  {
    return nPrime1(gamma, p); // Barroso & Celes 2007, Eq. 16, first case
  }
  const double r = rOfGamma(gamma, limit);
  const double value = nPrime1(limit, p) / r; // Barroso & Celes 2007, Eq. 16, second case
  return (r > 0.0 && std::isfinite(value)) ? value : kInf;
}

double nPrime(WarpMode mode, double gamma, const PartitionShape& p)
{
  switch (mode)
  {
    case WarpMode::None:
      return kInf;
    case WarpMode::PSM:
      return p.n;
    case WarpMode::LiSPSM:
    {
      const double s = std::sin(gamma);
      const double value =
        (p.n + std::sqrt(p.f * p.n)) / s; // Wimmer; Barroso & Celes 2007, §2.3 at gamma = pi/2
      return (s > 0.0 && std::isfinite(value)) ? value : kInf;
    }
    case WarpMode::Generalized:
      return nPrimeGeneralized(gamma, p);
  }
  return kInf;
}

const char* toString(WarpMode mode)
{
  switch (mode)
  {
    case WarpMode::None:
      return "none";
    case WarpMode::PSM:
      return "psm";
    case WarpMode::LiSPSM:
      return "lispsm";
    case WarpMode::Generalized:
      return "generalized";
  }
  return "?";
}

bool parseWarpMode(const char* text, WarpMode& mode)
{
  for (WarpMode m : { WarpMode::None, WarpMode::PSM, WarpMode::LiSPSM, WarpMode::Generalized })
  {
    if (text && std::strcmp(text, toString(m)) == 0)
    {
      mode = m;
      return true;
    }
  }
  return false;
}

} // namespace csm
