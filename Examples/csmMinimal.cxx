// SPDX-License-Identifier: BSD-3-Clause
// The complete minimal program of Documentation/Passes.md: a box casting a cascaded shadow.
#include "vtkActor.h"
#include "vtkCascadedShadowMapPass.h"
#include "vtkCubeSource.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkPlaneSource.h"
#include "vtkPolyDataMapper.h"
#include "vtkRenderWindow.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkRenderer.h"

#include <cstdio>
#include <cstdlib>

int main()
{
  vtkNew<vtkPlaneSource> ground;
  ground->SetOrigin(-10, 0, -10);
  ground->SetPoint1(10, 0, -10);
  ground->SetPoint2(-10, 0, 10);
  vtkNew<vtkCubeSource> box;
  box->SetBounds(-1, 1, 2, 4, -1, 1);
  vtkNew<vtkRenderer> renderer;
  for (vtkAlgorithm* source :
    { static_cast<vtkAlgorithm*>(ground), static_cast<vtkAlgorithm*>(box) })
  {
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputConnection(source->GetOutputPort());
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    renderer->AddActor(actor);
  }
  vtkNew<vtkLight> sun; // a scene light: VTK shadows scene and camera lights, not headlights
  sun->SetLightTypeToSceneLight();
  sun->SetPositional(false);
  sun->SetPosition(3, 10, 2);
  sun->SetFocalPoint(0, 0, 0);
  renderer->AddLight(sun);

  // One call, like vtkRenderer::UseShadowsOn(); returns the pass for its options.
  vtkCascadedShadowMapPass* shadows = vtkCascadedShadowMapPass::UseShadowsOn(renderer);
  shadows->SetPCFSize(5);
  shadows->GetShadowMapBakerPass()->GetPlanner()->SetNumberOfCascades(3);

  vtkNew<vtkRenderWindow> window;
  // VTK's X window crashes when it cannot open the X display: say so instead.
  if (window->IsA("vtkXOpenGLRenderWindow"))
  {
    vtkObject::GlobalWarningDisplayOff(); // (VTK's own warning would follow)
    const bool opened = window->GetGenericDisplayId() != nullptr;
    vtkObject::GlobalWarningDisplayOn();
    if (!opened)
    {
      const char* display = std::getenv("DISPLAY");
      std::fprintf(stderr, "csm-minimal: no X display (%s%s%s): run it under xvfb-run -a\n",
        display ? "cannot open DISPLAY='" : "DISPLAY is not set", display ? display : "",
        display ? "'" : "");
      return EXIT_FAILURE;
    }
  }
  window->AddRenderer(renderer);
  vtkNew<vtkRenderWindowInteractor> interactor;
  interactor->SetRenderWindow(window);
  renderer->ResetCamera();
  window->Render();
  interactor->Start();
  return 0;
}
