// SPDX-License-Identifier: BSD-3-Clause
#include "csmProps.h"

#include "vtkActor.h"
#include "vtkLight.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"

#include <cmath>

namespace
{
// Frames per second from which the window's desired update rate means "interacting" (the
// interactor's default is 15, its still rate 0.0001).
constexpr double kInteractiveUpdateRate = 1.0;
}

void csmScreenSizes(vtkProp* prop, float sizes[2])
{
  vtkActor* actor = vtkActor::SafeDownCast(prop);
  vtkProperty* property = actor ? actor->GetProperty() : nullptr;
  sizes[0] = property ? property->GetLineWidth() : 1.0f;
  sizes[1] = property ? property->GetPointSize() : 1.0f;
  for (int i = 0; i < 2; ++i)
  {
    // vtkProperty's clamped setters let NaN through: such a prop is drawn one pixel wide here.
    sizes[i] = std::isfinite(sizes[i]) && sizes[i] >= 1.0f ? sizes[i] : 1.0f;
  }
}

bool csmLightCastsShadows(vtkLight* light)
{
  return light && light->GetSwitch() && !light->LightTypeIsHeadlight() &&
    (!light->GetPositional() || light->GetConeAngle() < 90.0) &&
    light->GetShadowAttenuation() > 0.0f; // a shadow of attenuation 0 is invisible: no maps
}

bool csmIsInteracting(vtkRenderWindow* window)
{
  return window && window->GetDesiredUpdateRate() >= kInteractiveUpdateRate;
}
