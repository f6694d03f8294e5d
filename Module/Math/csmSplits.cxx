// SPDX-License-Identifier: BSD-3-Clause
#include "csmSplits.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace csm
{
namespace
{
constexpr double kHalfPi = 1.57079632679489661923;

double logSplit(double n, double f, int i, int k)
{
  // Barroso & Celes 2007, Eq. 5, Lloyd et al. 2006, Eq. 15-16: n (f/n)^(i/k), in log space so that
  // f/n may exceed a double.
  return std::exp(std::log(n) + (std::log(f) - std::log(n)) * double(i) / double(k));
}
}

std::vector<double> splitDepths(const SplitParameters& params, double n, double f, double gamma)
{
  const int k = params.scheme == SplitScheme::Single ? 1 : std::max(1, params.k);
  std::vector<double> s(k + 1);
  s[0] = n;
  s[k] = f;
  switch (params.scheme)
  {
    case SplitScheme::Single:
      break;
    case SplitScheme::Uniform:
      for (int i = 1; i < k; ++i)
      {
        s[i] = n + (f - n) * double(i) / double(k);
      }
      break;
    case SplitScheme::Log:
      for (int i = 1; i < k; ++i)
      {
        s[i] = logSplit(n, f, i, k);
      }
      break;
    case SplitScheme::Practical:
    {
      const double lambda = std::clamp(params.lambda, 0.0, 1.0);
      for (int i = 1; i < k; ++i) // Vázquez: C_i = lambda C_log + (1 - lambda) C_uniform
      {
        s[i] =
          lambda * logSplit(n, f, i, k) + (1.0 - lambda) * (n + (f - n) * double(i) / double(k));
      }
      break;
    }
    case SplitScheme::Adaptive:
    {
      const double lambda = std::clamp(
        gamma / kHalfPi, 0.0, 1.0); // Barroso & Celes 2007, Eq. 19: lambda = gamma/(pi/2)
      // Barroso & Celes 2007, Eq. 19, from the last partition backwards: n_i = f_{i-1} =
      //   lambda n (f_i/n)^((i-1)/i) + (1 - lambda) f_i / alpha.
      // Where alpha^(i-1) would not fit in [n, f_i], the self-similar split of [n, f_i] is the
      // floor, so that splits stay strictly increasing (Eq. 19 itself equals it at lambda = 1).
      for (int i = k; i >= 2; --i)
      {
        const double fi = s[i];
        const double logI = logSplit(n, fi, i - 1, i);
        const double eq19 = lambda * logI + (1.0 - lambda) * fi / params.alpha;
        s[i - 1] = std::max(eq19, logI);
      }
      break;
    }
  }
  return s;
}

const char* toString(SplitScheme scheme)
{
  switch (scheme)
  {
    case SplitScheme::Single:
      return "single";
    case SplitScheme::Uniform:
      return "uniform";
    case SplitScheme::Log:
      return "log";
    case SplitScheme::Practical:
      return "practical";
    case SplitScheme::Adaptive:
      return "adaptive";
  }
  return "?";
}

bool parseSplitScheme(const char* text, SplitScheme& scheme)
{
  for (SplitScheme m : { SplitScheme::Single, SplitScheme::Uniform, SplitScheme::Log,
         SplitScheme::Practical, SplitScheme::Adaptive })
  {
    if (text && std::strcmp(text, toString(m)) == 0)
    {
      scheme = m;
      return true;
    }
  }
  return false;
}

int partitionAtDepth(double depth, double splitNear, const double* splitFar, int count)
{
  if (!splitFar || count <= 0 || !(depth >= splitNear) || !(depth <= splitFar[count - 1]))
  {
    return -1;
  }
  int i = 0;
  while (i < count - 1 && depth > splitFar[i])
  {
    ++i;
  }
  return i;
}

} // namespace csm
