// SPDX-License-Identifier: BSD-3-Clause
// Shadows across MPI ranks: each rank holds part of the scene (rank 0 the casters, rank 1 the
// ground that receives their shadows, further ranks more casters), renders it with the
// cascaded passes sharing a controller, and rank 0 composites the images by depth. The result
// must match the single-process image of the whole scene, and the ground on rank 1 must be
// shadowed by the caster on rank 0. Prints the per-frame cost of combining the maps.
//   mpiexec -n N csmMPITest <output dir>
#include "csmTestHelpers.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCascadedShadowMapBakerPass.h"
#include "vtkCascadedShadowMapPass.h"
#include "vtkCubeSource.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMPIController.h"
#include "vtkNew.h"
#include "vtkPNGWriter.h"
#include "vtkPointData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"
#include "vtkTesting.h"
#include "vtkTrivialProducer.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace
{
constexpr int W = 400, H = 300;

// The scene: the box over the plane of the pass tests (a taller box, a wider ground), and a
// sphere and a second box as further casters. Part p of it: 0 the tall box (caster), 1 the
// ground (receiver), 2 the sphere, 3 the second box.
csmTest::BoxOverPlaneSettings Settings()
{
  csmTest::BoxOverPlaneSettings s;
  s.Size[0] = W;
  s.Size[1] = H;
  s.GroundHalfWidth = 12.0;
  const double ground[3] = { 0.8, 0.8, 0.85 }, caster[3] = { 0.9, 0.5, 0.3 };
  const double box[6] = { -1, 1, 0, 5, -1, 1 };
  const double background[3] = { 0.3, 0.4, 0.5 }, light[3] = { 4, 10, 3 };
  const double camera[3] = { 4, 14, 20 }, focal[3] = { 0, 1, 0 };
  std::copy(ground, ground + 3, s.GroundColor);
  std::copy(caster, caster + 3, s.BoxColor);
  std::copy(box, box + 6, s.Box);
  std::copy(background, background + 3, s.Background);
  std::copy(light, light + 3, s.LightPosition);
  std::copy(camera, camera + 3, s.CameraPosition);
  std::copy(focal, focal + 3, s.CameraFocalPoint);
  return s;
}

vtkSmartPointer<vtkActor> ExtraPart(int p)
{
  vtkSmartPointer<vtkAlgorithm> source;
  if (p == 2)
  {
    auto sphere = vtkSmartPointer<vtkSphereSource>::New();
    sphere->SetCenter(4, 2, -3);
    sphere->SetRadius(1.5);
    sphere->SetThetaResolution(32);
    sphere->SetPhiResolution(32);
    source = sphere;
  }
  else
  {
    auto cube = vtkSmartPointer<vtkCubeSource>::New();
    cube->SetBounds(-6, -4, 0, 3, 2, 4);
    source = cube;
  }
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(source->GetOutputPort());
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(Settings().BoxColor);
  return actor;
}

/// The parts `keep` says, of the whole scene; the clipping range the same on every rank.
struct View : csmTest::BoxOverPlane
{
  template <typename Keep>
  explicit View(Keep keep)
    : csmTest::BoxOverPlane(Settings())
  {
    if (!keep(0))
      this->Renderer->RemoveActor(this->Box);
    if (!keep(1))
      this->Renderer->RemoveActor(this->Ground);
    for (int p = 2; p < 4; ++p)
      if (keep(p))
        this->Renderer->AddActor(ExtraPart(p));
    this->Renderer->GetActiveCamera()->SetClippingRange(5, 60);
  }
};

// Colour (RGB) and depth of the window.
void Read(vtkRenderWindow* window, std::vector<unsigned char>& rgb, std::vector<float>& z)
{
  rgb.resize(3 * W * H);
  z.resize(W * H);
  unsigned char* pixels = window->GetPixelData(0, 0, W - 1, H - 1, 0, 0);
  std::copy(pixels, pixels + 3 * W * H, rgb.begin());
  delete[] pixels;
  window->GetZbufferData(0, 0, W - 1, H - 1, z.data());
}

vtkSmartPointer<vtkImageData> ToImage(const std::vector<unsigned char>& rgb)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(W, H, 1);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  std::copy(rgb.begin(), rgb.end(), static_cast<unsigned char*>(image->GetScalarPointer()));
  return image;
}

// Rank 0 gathers every rank's colour and depth and keeps the nearest surface of each pixel.
std::vector<unsigned char> Composite(vtkMPIController* controller, vtkRenderWindow* window)
{
  std::vector<unsigned char> rgb;
  std::vector<float> z;
  Read(window, rgb, z);
  const int n = controller->GetNumberOfProcesses();
  std::vector<unsigned char> allRgb(controller->GetLocalProcessId() == 0 ? rgb.size() * n : 0);
  std::vector<float> allZ(controller->GetLocalProcessId() == 0 ? z.size() * n : 0);
  controller->Gather(rgb.data(), allRgb.data(), static_cast<vtkIdType>(rgb.size()), 0);
  controller->Gather(z.data(), allZ.data(), static_cast<vtkIdType>(z.size()), 0);
  if (controller->GetLocalProcessId() != 0)
    return {};
  for (int r = 1; r < n; ++r)
    for (int i = 0; i < W * H; ++i)
      if (allZ[r * W * H + i] < z[i])
      {
        z[i] = allZ[r * W * H + i];
        std::copy_n(&allRgb[3 * (r * W * H + i)], 3, &rgb[3 * i]);
      }
  return rgb;
}

} // namespace

int main(int argc, char* argv[])
{
  vtkNew<vtkMPIController> controller;
  controller->Initialize(&argc, &argv);
  vtkMultiProcessController::SetGlobalController(controller);
  const int rank = controller->GetLocalProcessId();
  const int ranks = controller->GetNumberOfProcesses();
  const std::string out = argc > 1 ? argv[1] : ".";
  int status = 0;
  {
    View view([&](int p) { return p % ranks == rank; });
    vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(view.Renderer);
    pass->GetShadowMapBakerPass()->SetController(controller);
    pass->GetShadowMapBakerPass()->SetResolution(1024);

    // Frames orbiting the scene: the cost of combining the maps across ranks.
    std::vector<double> combine, frame;
    for (int f = 0; f < 6; ++f)
    {
      view.Renderer->GetActiveCamera()->Azimuth(f == 0 ? 0.0 : 3.0);
      controller->Barrier();
      const auto start = std::chrono::steady_clock::now();
      view.Window->Render();
      view.Window->WaitForCompletion();
      frame.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
          .count());
      combine.push_back(
        1000.0 * pass->GetShadowMapBakerPass()->GetLastFrameStatistics().CombineSeconds);
    }
    view.Renderer->GetActiveCamera()->Azimuth(-15.0);
    view.Window->Render();
    const std::vector<unsigned char> shadowed = Composite(controller, view.Window);
    view.Renderer->SetPass(nullptr);
    view.Window->Render();
    const std::vector<unsigned char> plain = Composite(controller, view.Window);

    if (rank == 0)
    {
      std::sort(combine.begin() + 1, combine.end());
      std::sort(frame.begin() + 1, frame.end());
      std::printf(
        "ranks: %d  median_frame_ms: %.1f  median_combine_ms: %.1f\n", ranks, frame[3], combine[3]);
      // The whole scene in one process: the reference.
      View single([](int) { return true; });
      vtkCascadedShadowMapBakerPass* singleBaker =
        vtkCascadedShadowMapPass::UseShadowsOn(single.Renderer)->GetShadowMapBakerPass();
      singleBaker->SetResolution(1024);
      // With several processes no prop knows every other prop's box, so none is left out of
      // the maps as shadowing nothing (the ground under the boxes is drawn; see
      // CullCastersWithoutReceivers): the same here, so that the images compare the maps'
      // combination alone.
      singleBaker->CullCastersWithoutReceiversOff();
      single.Window->Render();
      std::vector<unsigned char> reference;
      std::vector<float> z;
      Read(single.Window, reference, z);
      const std::string name = "mpi-" + std::to_string(ranks);
      vtkNew<vtkPNGWriter> writer;
      writer->SetFileName((out + "/" + name + "-reference.png").c_str());
      writer->SetInputData(ToImage(reference));
      writer->Write();
      writer->SetFileName((out + "/" + name + "-composite.png").c_str());
      writer->SetInputData(ToImage(shadowed));
      writer->Write();
      // Regression comparison of the composite against the single-process image.
      vtkNew<vtkTesting> testing;
      testing->AddArgument("-B");
      testing->AddArgument(out.c_str());
      testing->AddArgument("-V");
      testing->AddArgument((name + "-reference.png").c_str());
      testing->AddArgument("-T");
      testing->AddArgument(out.c_str());
      vtkNew<vtkTrivialProducer> producer;
      producer->SetOutput(ToImage(shadowed));
      const int compared = testing->RegressionTest(producer, 0.15);
      const long darkened = csmTest::DarkenedPixels(ToImage(shadowed), ToImage(plain));
      const long darkenedReference = csmTest::DarkenedPixels(ToImage(reference), ToImage(plain));
      std::printf("composite vs single process: %s; shadowed pixels: %ld (single process: %ld)\n",
        compared == vtkTesting::PASSED ? "match" : "DIFFER", darkened, darkenedReference);
      if (compared != vtkTesting::PASSED || darkened < 2000 ||
        std::abs(darkened - darkenedReference) > 0.02 * darkenedReference)
      {
        std::printf("mpi shadow test FAILED\n");
        status = 1;
      }
    }
  }
  controller->Broadcast(&status, 1, 0);
  controller->Finalize();
  return status;
}
