// SPDX-License-Identifier: BSD-3-Clause
// The OSMesa render window (Support/Headless): the programs render with no X server at all.
// CTest runs these with DISPLAY unset.
#include "csmHeadless.h"
#include "vtkOSMesaHeadlessRenderWindow.h"

#include "vtkActor.h"
#include "vtkConeSource.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyDataMapper.h"
#include "vtkRenderWindow.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"
#include "vtkWindowToImageFilter.h"

#include <GL/osmesa.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <string>

namespace
{
struct Cone
{
  vtkNew<vtkRenderer> Renderer;
  vtkSmartPointer<vtkRenderWindow> Window = vtkSmartPointer<vtkRenderWindow>::New();

  Cone(int width, int height)
  {
    vtkNew<vtkConeSource> cone;
    cone->SetResolution(32);
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputConnection(cone->GetOutputPort());
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    this->Renderer->AddActor(actor);
    this->Renderer->SetBackground(0.0, 0.0, 1.0);
    this->Window->SetSize(width, height);
    this->Window->SetMultiSamples(0);
    this->Window->SetOffScreenRendering(1);
    this->Window->AddRenderer(this->Renderer);
  }

  /// Renders; the image's size and how many of its pixels are not the (blue) background.
  long Draw(int size[2])
  {
    this->Window->Render();
    vtkNew<vtkWindowToImageFilter> grab;
    grab->SetInput(this->Window);
    grab->ReadFrontBufferOff();
    grab->Update();
    int* dims = grab->GetOutput()->GetDimensions();
    size[0] = dims[0];
    size[1] = dims[1];
    auto* rgb = vtkUnsignedCharArray::SafeDownCast(grab->GetOutput()->GetPointData()->GetScalars());
    long drawn = 0;
    const int nc = rgb->GetNumberOfComponents();
    for (vtkIdType i = 0; i < rgb->GetNumberOfTuples(); ++i)
      drawn += !(rgb->GetValue(nc * i) < 5 && rgb->GetValue(nc * i + 1) < 5 &&
        rgb->GetValue(nc * i + 2) > 250);
    return drawn;
  }
};
}

TEST(Headless, RendersWithNoXServer)
{
  ASSERT_EQ(std::getenv("DISPLAY"), nullptr) << "run with DISPLAY unset: the point is no X server";
  ASSERT_TRUE(csmHeadless::Available());
  ASSERT_TRUE(csmHeadless::UsingOSMesa());
  EXPECT_EQ(vtkOSMesaHeadlessRenderWindow::CheckLinkOrder(), "");

  Cone scene(200, 150);
  auto* window = vtkOSMesaHeadlessRenderWindow::SafeDownCast(scene.Window);
  ASSERT_NE(window, nullptr) << "vtkRenderWindow::New() made a " << scene.Window->GetClassName();
  EXPECT_STREQ(window->GetContextAPI(), "OSMesa");

  int size[2];
  const long drawn = scene.Draw(size);
  EXPECT_EQ(size[0], 200);
  EXPECT_EQ(size[1], 150);
  EXPECT_GT(drawn, 2000) << "the cone covers a good part of the view";
  EXPECT_LT(drawn, 200 * 150);

  // The context current is the window's OSMesa context, and it is Mesa's software rasterizer
  // with a core profile of at least 3.2.
  EXPECT_TRUE(window->IsCurrent());
  EXPECT_EQ(static_cast<void*>(OSMesaGetCurrentContext()), window->GetGenericContext());
  const std::string report = window->ReportCapabilities();
  std::printf("%s\n", report.substr(0, report.find("OpenGL extensions")).c_str());
  EXPECT_NE(report.find("Context API: OSMesa"), std::string::npos);
  EXPECT_NE(report.find("llvmpipe"), std::string::npos);
  int major = 0, minor = 0;
  const auto version = report.find("OpenGL version string:");
  ASSERT_NE(version, std::string::npos);
  ASSERT_EQ(
    std::sscanf(report.c_str() + version, "OpenGL version string: %d.%d", &major, &minor), 2);
  EXPECT_GE(major * 10 + minor, 32);
  EXPECT_NE(report.find("Core Profile"), std::string::npos);
}

TEST(Headless, TwoWindowsAndAResize)
{
  Cone a(160, 120), b(100, 100);
  int size[2];
  EXPECT_GT(a.Draw(size), 1000);
  EXPECT_GT(b.Draw(size), 1000);
  EXPECT_EQ(size[0], 100);
  a.Window->SetSize(320, 200);
  EXPECT_GT(a.Draw(size), 4000);
  EXPECT_EQ(size[0], 320);
  EXPECT_EQ(size[1], 200);
  EXPECT_GT(b.Draw(size), 1000);
  EXPECT_EQ(size[0], 100);
}

TEST(Headless, AWindowWithAnInteractorRenders)
{
  // As vtkContextView (csm-bench's plot) does: VTK's X interactor would open the display here.
  Cone scene(120, 90);
  vtkNew<vtkRenderWindowInteractor> interactor;
  EXPECT_STREQ(interactor->GetClassName(), "vtkGenericRenderWindowInteractor");
  interactor->SetRenderWindow(scene.Window);
  int size[2];
  EXPECT_GT(scene.Draw(size), 500);
  EXPECT_TRUE(interactor->GetInitialized());
}

TEST(Headless, OverridesCanBeTurnedOff)
{
  EXPECT_FALSE(csmHeadless::UseOSMesa(false));
  EXPECT_FALSE(csmHeadless::UsingOSMesa());
  // VTK's own X window and interactor (not rendered: there is no X server here).
  vtkSmartPointer<vtkRenderWindow> x = vtkSmartPointer<vtkRenderWindow>::New();
  EXPECT_STREQ(x->GetClassName(), "vtkXOpenGLRenderWindow");
  vtkSmartPointer<vtkRenderWindowInteractor> xi = vtkSmartPointer<vtkRenderWindowInteractor>::New();
  EXPECT_STREQ(xi->GetClassName(), "vtkXRenderWindowInteractor");
  EXPECT_TRUE(csmHeadless::UseOSMesa(true));
  vtkSmartPointer<vtkRenderWindow> o = vtkSmartPointer<vtkRenderWindow>::New();
  EXPECT_STREQ(o->GetClassName(), "vtkOSMesaHeadlessRenderWindow");
  vtkSmartPointer<vtkRenderWindowInteractor> oi = vtkSmartPointer<vtkRenderWindowInteractor>::New();
  EXPECT_STREQ(oi->GetClassName(), "vtkGenericRenderWindowInteractor");
}
