// SPDX-License-Identifier: BSD-3-Clause
// Linked with glvnd's libGLX, libOpenGL and libGL ahead of libcsm_headless and libOSMesa (the
// wrong order): making a render window must stop with the message that says how to link, exit
// status 2, not a crash inside GLEW or VTK. Checked by expect-refusal.sh.
#include "vtkActor.h"
#include "vtkConeSource.h"
#include "vtkNew.h"
#include "vtkPolyDataMapper.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"

#include <cstdio>

int main()
{
  vtkNew<vtkConeSource> cone;
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(cone->GetOutputPort());
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->AddRenderer(renderer);
  window->Render();
  std::printf("rendered with a %s\n", window->GetClassName());
  return 0;
}
