// SPDX-License-Identifier: BSD-3-Clause
#include "csmProps.h"

#include "vtkActor.h"
#include "vtkAssembly.h"
#include "vtkAssemblyNode.h"
#include "vtkAssemblyPath.h"
#include "vtkCellArray.h"
#include "vtkCompositePolyDataMapper2.h"
#include "vtkLight.h"
#include "vtkMatrix4x4.h"
#include "vtkPlane.h"
#include "vtkPlaneCollection.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkPropAssembly.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"

#include <cmath>
#include <cstdint>

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

namespace
{
/// What an actor casts (csmCastingState), placed by matrix; for another prop, its redraw time.
std::vector<double> castingStateAt(vtkProp* prop, vtkMatrix4x4* matrix)
{
  vtkActor* actor = vtkActor::SafeDownCast(prop);
  vtkPolyDataMapper* mapper = actor ? vtkPolyDataMapper::SafeDownCast(actor->GetMapper()) : nullptr;
  vtkPolyData* data = mapper ? mapper->GetInput() : nullptr;
  if (!data || !matrix || vtkCompositePolyDataMapper2::SafeDownCast(mapper))
  {
    return { static_cast<double>(prop->GetRedrawMTime()) };
  }
  auto time = [](vtkObject* object)
  { return object ? static_cast<double>(object->GetMTime()) : -1.0; };
  // (Its matrix: position, orientation, scale, origin, user matrix and transform.)
  std::vector<double> state(matrix->GetData(), matrix->GetData() + 16);
  state.insert(state.end(),
    { static_cast<double>(actor->GetVisibility()),
      static_cast<double>(reinterpret_cast<std::uintptr_t>(mapper)),
      static_cast<double>(reinterpret_cast<std::uintptr_t>(data)), time(data->GetPoints()),
      time(data->GetVerts()), time(data->GetLines()), time(data->GetPolys()),
      time(data->GetStrips()),
      // (The polydata's own time, without its point and cell data's: an application that edits
      // a cell in place, which changes no count and no array's time, says so by modifying it;
      // new scalars or fields change none of these.)
      static_cast<double>(data->vtkObject::GetMTime()),
      // (Counts too: an application may empty or refill an array in place, which need not
      // touch its MTime.)
      static_cast<double>(data->GetNumberOfPoints()), static_cast<double>(data->GetNumberOfVerts()),
      static_cast<double>(data->GetNumberOfLines()), static_cast<double>(data->GetNumberOfPolys()),
      static_cast<double>(data->GetNumberOfStrips()), prop->HasOpaqueGeometry() ? 1.0 : 0.0,
      static_cast<double>(mapper->GetNumberOfClippingPlanes()) });
  if (vtkPlaneCollection* planes = mapper->GetClippingPlanes())
  {
    state.push_back(time(planes));
    vtkCollectionSimpleIterator it;
    planes->InitTraversal(it);
    while (vtkPlane* plane = planes->GetNextPlane(it))
    {
      state.push_back(time(plane));
    }
  }
  if (vtkProperty* property = actor->GetProperty())
  {
    state.insert(state.end(),
      { static_cast<double>(property->GetRepresentation()), property->GetOpacity(),
        property->GetLineWidth(), property->GetPointSize(),
        property->GetBackfaceCulling() ? 1.0 : 0.0, property->GetFrontfaceCulling() ? 1.0 : 0.0,
        property->GetRenderLinesAsTubes() ? 1.0 : 0.0,
        property->GetRenderPointsAsSpheres() ? 1.0 : 0.0 });
  }
  return state;
}
} // namespace

std::vector<double> csmCastingState(vtkProp* prop)
{
  if (!prop)
  {
    return {};
  }
  std::vector<double> state;
  if (vtkAssembly::SafeDownCast(prop) || vtkPropAssembly::SafeDownCast(prop))
  {
    // Each part as its path places it: drawing an assembly pokes each part's matrix in and out,
    // which modifies the part (and so the assembly) at every frame.
    state.push_back(static_cast<double>(prop->GetVisibility()));
    prop->InitPathTraversal();
    while (vtkAssemblyPath* path = prop->GetNextPath())
    {
      vtkAssemblyNode* leaf = path->GetLastNode();
      vtkProp* part = leaf ? leaf->GetViewProp() : nullptr;
      if (!part)
      {
        continue;
      }
      const std::vector<double> placed = castingStateAt(part, leaf->GetMatrix());
      state.push_back(static_cast<double>(placed.size()));
      state.insert(state.end(), placed.begin(), placed.end());
    }
  }
  else
  {
    vtkActor* actor = vtkActor::SafeDownCast(prop);
    state = castingStateAt(prop, actor ? actor->GetMatrix() : nullptr);
  }
  for (double& value : state)
  {
    value = std::isfinite(value) ? value : -2.0; // (NaN would differ from itself every frame)
  }
  return state;
}

bool csmLightCastsShadows(vtkLight* light)
{
  return light && light->GetSwitch() && !light->LightTypeIsHeadlight() &&
    // (A point light, cone 90 or more, casts none; a NaN cone is a spot light's error.)
    (!light->GetPositional() || !(light->GetConeAngle() >= 90.0)) &&
    light->GetShadowAttenuation() > 0.0f; // a shadow of attenuation 0 is invisible: no maps
}

bool csmIsInteracting(vtkRenderWindow* window)
{
  return window && window->GetDesiredUpdateRate() >= kInteractiveUpdateRate;
}

std::string csmPropDigest(vtkRenderer* renderer, const std::function<bool(vtkProp*)>& so)
{
  size_t digest = 0, count = 0;
  vtkPropCollection* props = renderer->GetViewProps();
  vtkCollectionSimpleIterator it;
  props->InitTraversal(it);
  while (vtkProp* prop = props->GetNextProp(it))
  {
    if (so(prop))
    {
      digest ^=
        std::hash<const void*>()(prop) + 0x9e3779b97f4a7c15ULL + (digest << 6) + (digest >> 2);
      ++count;
    }
  }
  return std::to_string(count) + ":" + std::to_string(digest);
}
