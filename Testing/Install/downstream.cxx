// SPDX-License-Identifier: BSD-3-Clause
// A box over a ground plane, rendered offscreen without and with the installed module's
// shadows; prints the pixels the shadow darkened and fails below a floor. With an argument,
// writes the shadowed picture there (PNG).
#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCascadedShadowMapPass.h"
#include "vtkCubeSource.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkPNGWriter.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPolyDataMapper.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkUnsignedCharArray.h"
#include "vtkWindowToImageFilter.h"

#include <cstdio>

namespace
{
vtkSmartPointer<vtkImageData> Grab(vtkRenderWindow* window)
{
  window->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->ReadFrontBufferOff();
  grab->Update();
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->DeepCopy(grab->GetOutput());
  return image;
}
}

int main(int argc, char* argv[])
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
  renderer->AutomaticLightCreationOff();
  vtkNew<vtkLight> sun;
  sun->SetLightTypeToSceneLight();
  sun->SetPositional(false);
  sun->SetPosition(3, 10, 2);
  sun->SetFocalPoint(0, 0, 0);
  renderer->AddLight(sun);
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(0);
  window->SetSize(320, 240);
  window->AddRenderer(renderer);
  renderer->GetActiveCamera()->SetPosition(0, 14, 16); // looking down at the ground
  renderer->GetActiveCamera()->SetFocalPoint(0, 0, 0);
  renderer->ResetCameraClippingRange();

  vtkSmartPointer<vtkImageData> plain = Grab(window);
  vtkCascadedShadowMapPass::UseShadowsOn(renderer);
  vtkSmartPointer<vtkImageData> shadowed = Grab(window);

  auto* a = vtkUnsignedCharArray::SafeDownCast(shadowed->GetPointData()->GetScalars());
  auto* b = vtkUnsignedCharArray::SafeDownCast(plain->GetPointData()->GetScalars());
  long darkened = 0;
  for (vtkIdType i = 0; a && b && i < a->GetNumberOfTuples(); ++i)
  {
    double la = 0, lb = 0;
    for (int c = 0; c < 3; ++c)
    {
      la += a->GetComponent(i, c);
      lb += b->GetComponent(i, c);
    }
    darkened += la < 0.85 * lb - 6.0;
  }
  std::printf("shadowed_pixels: %ld\n", darkened);
  if (argc > 1)
  {
    vtkNew<vtkPNGWriter> writer;
    writer->SetFileName(argv[1]);
    writer->SetInputData(shadowed);
    writer->Write();
  }
  return darkened >= 1000 ? 0 : 1;
}
