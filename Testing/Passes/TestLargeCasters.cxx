// SPDX-License-Identifier: BSD-3-Clause
// Big casters: their compact blocks are prepared by a worker thread while the frames draw them
// as they are, with the same shadows; an edit prepares again only the prop that changed.
#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCascadedShadowMapBakerPass.h"
#include "vtkCascadedShadowMapPass.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"

#include "csmTestHelpers.h"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

namespace
{
using csmTest::BoxOverPlane;
using csmTest::DarkenedPixels;
using csmTest::DifferingValues;

/// A finely tessellated ball (more triangles than the baker prepares at once) over the ground.
vtkSmartPointer<vtkPolyData> BigBall(double x)
{
  vtkNew<vtkSphereSource> ball;
  ball->SetCenter(x, 2.0, 3.0);
  ball->SetRadius(1.0);
  ball->SetThetaResolution(520);
  ball->SetPhiResolution(520);
  ball->Update();
  vtkSmartPointer<vtkPolyData> data = ball->GetOutput();
  return data;
}

/// Frames of a camera that moves a little (a big mesh is prepared once the view moves) until
/// the baker draws `expected` props from compact blocks (at most ~30 s); then the view is the
/// one it was.
bool FramesUntilCompact(BoxOverPlane& scene, vtkCascadedShadowMapBakerPass* baker, int expected)
{
  vtkNew<vtkCamera> start;
  start->DeepCopy(scene.Renderer->GetActiveCamera());
  bool prepared = false;
  for (int frame = 0; frame < 300 && !prepared; ++frame)
  {
    scene.Renderer->GetActiveCamera()->Azimuth(frame % 2 == 0 ? 0.5 : -0.5);
    scene.Window->Render();
    prepared = baker->GetLastFrameStatistics().CompactCasters == expected;
    if (!prepared)
    {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
  }
  // (A copy does not modify the camera, and VTK would draw the next frame from the last one's
  // matrices.)
  scene.Renderer->GetActiveCamera()->DeepCopy(start);
  scene.Renderer->GetActiveCamera()->Modified();
  return prepared;
}
} // namespace

// A still view does not wait for a big prop's blocks, nor prepare them: it draws the prop as it
// is, with the shadow the prepared blocks give once the view moves.
TEST(LargeCasters, APropNotYetPreparedCastsTheSameShadow)
{
  BoxOverPlane scene;
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(BigBall(-3.0));
  vtkNew<vtkActor> ball;
  ball->SetMapper(mapper);
  scene.Renderer->AddActor(ball);
  ASSERT_GT(mapper->GetInput()->GetNumberOfPolys(),
    vtkCascadedShadowMapBakerPass::SYNCHRONOUS_PREPARATION_TRIANGLES / 2);
  auto plain = scene.Frame();
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
  auto first = scene.Frame();
  // The box and the ground at once; the ball as it is, in this frame and the next of the same
  // view.
  EXPECT_EQ(baker->GetLastFrameStatistics().CompactCasters, 2);
  EXPECT_EQ(DifferingValues(scene.Frame(), first), 0);
  EXPECT_EQ(baker->GetLastFrameStatistics().CompactCasters, 2);
  ASSERT_TRUE(FramesUntilCompact(scene, baker, 3));
  auto prepared = scene.Frame();
  EXPECT_EQ(baker->GetLastFrameStatistics().CompactCasters, 3);
  const long shadow = DarkenedPixels(first, plain);
  EXPECT_GT(shadow, 1500); // the box's and the ball's
  EXPECT_NEAR(static_cast<double>(DarkenedPixels(prepared, plain)), static_cast<double>(shadow),
    0.005 * shadow);
  EXPECT_LE(DifferingValues(prepared, first, 8), 40);
  // A camera copied back onto the active one is not modified (vtkCamera::DeepCopy), and VTK
  // draws that frame from the last frame's matrices: the lookup reads view space as the mappers
  // do, so the frame has the shadows of the view drawn (a mix of the two views shadows the
  // ball's lit side: 3,708 darkened pixels).
  {
    vtkCamera* camera = scene.Renderer->GetActiveCamera();
    vtkNew<vtkCamera> start;
    start->DeepCopy(camera);
    camera->Azimuth(0.5);
    scene.Window->Render();
    camera->DeepCopy(start);
    auto copied = scene.Frame();
    EXPECT_NEAR(static_cast<double>(DarkenedPixels(copied, plain)), static_cast<double>(shadow),
      0.1 * shadow);
    camera->Modified();
  }

  // Its points move: only it is prepared again (drawn as it is meanwhile, with the shadow of
  // where it is now); the box and the ground keep their blocks.
  vtkNew<vtkPolyData> moved;
  moved->DeepCopy(mapper->GetInput());
  for (vtkIdType i = 0; i < moved->GetNumberOfPoints(); ++i)
  {
    double p[3];
    moved->GetPoint(i, p);
    moved->GetPoints()->SetPoint(i, p[0] + 5.0, p[1], p[2]);
  }
  mapper->SetInputData(moved);
  auto whileMoving = scene.Frame();
  EXPECT_EQ(baker->GetLastFrameStatistics().CompactCasters, 2);
  ASSERT_TRUE(FramesUntilCompact(scene, baker, 3));
  auto movedPrepared = scene.Frame();
  EXPECT_GT(DifferingValues(whileMoving, prepared, 8), 1000); // the shadow moved at once
  EXPECT_LE(DifferingValues(movedPrepared, whileMoving, 8), 40);
}
