// SPDX-License-Identifier: BSD-3-Clause
// csmHeadless without the OSMesa window (built with CSM_OSMESA=OFF): VTK's own X window.
#include "csmHeadless.h"

namespace csmHeadless
{
bool Available()
{
  return false;
}

bool UseOSMesa(bool)
{
  return false;
}

bool UsingOSMesa()
{
  return false;
}
}
