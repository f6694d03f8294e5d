// SPDX-License-Identifier: BSD-3-Clause
// What the math tests share: the test camera.
#pragma once

#include "csmShadowSetup.h"

namespace csmMathTest
{
/// Eye at the origin looking down -z, up +y.
inline csm::Camera camera(double n, double f, double fovyDeg, double aspect = 1.0)
{
  csm::Camera c;
  c.vsNear = n;
  c.vsFar = f;
  c.fovyDeg = fovyDeg;
  c.aspect = aspect;
  return c;
}
} // namespace csmMathTest
