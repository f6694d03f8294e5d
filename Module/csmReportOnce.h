// SPDX-License-Identifier: BSD-3-Clause
// Internal to the module: a message said once per object (a frame is rendered on every camera
// move), as vtkErrorMacro / vtkWarningMacro of that object (its observers see the event).
#pragma once

#include "vtkObject.h"
#include "vtkSetGet.h"

#include <set>
#include <string>

inline void csmReportOnce(
  vtkObject* self, std::set<std::string>& said, bool error, const std::string& message)
{
  if (!said.insert(message).second)
  {
    return;
  }
  if (error)
  {
    vtkErrorWithObjectMacro(self, << message);
  }
  else
  {
    vtkWarningWithObjectMacro(self, << message);
  }
}
