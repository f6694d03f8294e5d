// SPDX-License-Identifier: BSD-3-Clause
// Big casters: their compact blocks are prepared by a worker thread while the frames draw them
// as they are, with the same shadows; an edit prepares again only the prop that changed; the
// application may edit a mesh in place while a worker prepares it.
#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCascadedShadowMapBakerPass.h"
#include "vtkCascadedShadowMapPass.h"
#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"

#include "csmTestHelpers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace
{
using csmTest::BoxOverPlane;
using csmTest::DarkenedPixels;
using csmTest::DifferingValues;

/// A finely tessellated ball (more triangles than the baker prepares at once) over the ground.
vtkSmartPointer<vtkPolyData> BigBall(double x, int resolution = 520, double z = 3.0)
{
  vtkNew<vtkSphereSource> ball;
  ball->SetCenter(x, 2.0, z);
  ball->SetRadius(1.0);
  ball->SetThetaResolution(resolution);
  ball->SetPhiResolution(resolution);
  ball->Update();
  vtkSmartPointer<vtkPolyData> data = ball->GetOutput();
  return data;
}

/// Frames of a camera that moves a little (a big mesh is prepared once the view moves) until
/// the baker draws `expected` props from compact blocks (at most 120 s: a sanitizer's build
/// prepares slowly); then the view is the one it was.
bool FramesUntilCompact(BoxOverPlane& scene, vtkCascadedShadowMapBakerPass* baker, int expected)
{
  vtkNew<vtkCamera> start;
  start->DeepCopy(scene.Renderer->GetActiveCamera());
  bool prepared = false;
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  for (int frame = 0; std::chrono::steady_clock::now() < until && !prepared; ++frame)
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
  // New scalars on it (a time step's field): its blocks stay, a moved view draws them at once.
  {
    vtkNew<vtkFloatArray> field;
    field->SetNumberOfTuples(mapper->GetInput()->GetNumberOfPoints());
    field->Fill(0.5f);
    mapper->GetInput()->GetPointData()->SetScalars(field);
    scene.Frame();
    vtkCamera* camera = scene.Renderer->GetActiveCamera();
    camera->Azimuth(0.5);
    scene.Frame();
    EXPECT_EQ(baker->GetLastFrameStatistics().CompactCasters, 3);
    camera->Azimuth(-0.5);
    mapper->GetInput()->GetPointData()->SetScalars(nullptr);
  }
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

namespace
{
/// The ways VTK lets an application edit a mesh in place between two renders.
const std::vector<std::pair<std::string, std::function<void(vtkPolyData*)>>>& InPlaceEdits()
{
  static const std::vector<std::pair<std::string, std::function<void(vtkPolyData*)>>> edits = {
    { "PolysInitialize", [](vtkPolyData* data) { data->GetPolys()->Initialize(); } },
    { "PointsResizeThenMoved",
      [](vtkPolyData* data)
      {
        vtkPoints* points = data->GetPoints();
        const vtkIdType n = points->GetNumberOfPoints();
        points->Resize(3 * n);
        for (vtkIdType i = 0; i < n; ++i)
        {
          double p[3];
          points->GetPoint(i, p);
          points->SetPoint(i, p[0] + 4.0, p[1], p[2]);
        }
      } },
    { "PointsSetData",
      [](vtkPolyData* data)
      {
        vtkNew<vtkFloatArray> moved;
        moved->DeepCopy(data->GetPoints()->GetData());
        for (vtkIdType i = 0; i < moved->GetNumberOfTuples(); ++i)
        {
          moved->SetComponent(i, 0, moved->GetComponent(i, 0) + 4.0);
        }
        data->GetPoints()->SetData(moved);
      } },
    { "SetNumberOfPoints",
      [](vtkPolyData* data)
      {
        // Fewer points, then the polygons that use them only.
        vtkPoints* points = data->GetPoints();
        const vtkIdType n = points->GetNumberOfPoints() / 2;
        points->SetNumberOfPoints(n);
        vtkNew<vtkCellArray> kept;
        vtkIdType count;
        const vtkIdType* ids;
        auto cells = vtk::TakeSmartPointer(data->GetPolys()->NewIterator());
        for (cells->GoToFirstCell(); !cells->IsDoneWithTraversal(); cells->GoToNextCell())
        {
          cells->GetCurrentCell(count, ids);
          if (std::all_of(ids, ids + count, [n](vtkIdType id) { return id < n; }))
          {
            kept->InsertNextCell(count, ids);
          }
        }
        data->GetPolys()->DeepCopy(kept);
      } },
    { "InsertNextCell",
      [](vtkPolyData* data)
      {
        const vtkIdType triangle[3] = { 0, 1, 2 };
        for (int i = 0; i < 1000; ++i)
        {
          data->GetPolys()->InsertNextCell(3, triangle);
        }
      } },
    { "DeepCopyInto", [](vtkPolyData* data) { data->DeepCopy(BigBall(1.0, 200)); } },
    { "SetPoints",
      [](vtkPolyData* data)
      {
        vtkNew<vtkPoints> moved;
        moved->DeepCopy(data->GetPoints());
        for (vtkIdType i = 0; i < moved->GetNumberOfPoints(); ++i)
        {
          double p[3];
          moved->GetPoint(i, p);
          moved->SetPoint(i, p[0], p[1] + 1.0, p[2]);
        }
        data->SetPoints(moved);
      } },
  };
  return edits;
}

int EnvironmentOr(const char* name, int fallback)
{
  const char* value = std::getenv(name);
  return value && std::atoi(value) > 0 ? std::atoi(value) : fallback;
}

class InPlaceEdit : public ::testing::TestWithParam<size_t>
{
};
} // namespace

// A big mesh is edited in place (as VTK lets an application do between renders) right after a
// camera move started its preparation on a worker thread: the worker reads its own copy, the
// frame after the edit shows the edited mesh as a fresh chain does, and nothing waits for the
// preparation that the edit made useless. CSM_INPLACE_REPEATS (3) and CSM_INPLACE_RESOLUTION
// (520: 540k triangles; 1400: 3.9 M) make the run longer.
TEST_P(InPlaceEdit, WhileAWorkerPreparesTheMesh)
{
  const auto& [name, edit] = InPlaceEdits()[GetParam()];
  const int repeats = EnvironmentOr("CSM_INPLACE_REPEATS", 3);
  const int resolution = EnvironmentOr("CSM_INPLACE_RESOLUTION", 520);
  for (int run = 0; run < repeats; ++run)
  {
    BoxOverPlane scene;
    // Every other run the ball is behind the camera: it draws nothing, and the frame that
    // starts its preparation ends long before the worker has read the mesh.
    const bool behind = run % 2 == 1;
    vtkSmartPointer<vtkPolyData> data = BigBall(-3.0, resolution, behind ? 30.0 : 3.0);
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputData(data);
    vtkNew<vtkActor> ball;
    ball->SetMapper(mapper);
    scene.Renderer->AddActor(ball);
    vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
    scene.Frame();
    scene.Renderer->GetActiveCamera()->Azimuth(1.0); // the worker starts in this frame
    scene.Frame();
    // The edit at another moment of the worker's preparation each run.
    std::this_thread::sleep_for(std::chrono::milliseconds((run / 2 * 30) % 150));
    edit(data);
    data->Modified();
    const auto start = std::chrono::steady_clock::now();
    auto edited = scene.Frame();
    const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    BoxOverPlane fresh;
    vtkNew<vtkPolyData> same;
    same->DeepCopy(data);
    vtkNew<vtkPolyDataMapper> freshMapper;
    freshMapper->SetInputData(same);
    vtkNew<vtkActor> freshBall;
    freshBall->SetMapper(freshMapper);
    fresh.Renderer->AddActor(freshBall);
    fresh.Renderer->GetActiveCamera()->DeepCopy(scene.Renderer->GetActiveCamera());
    fresh.Renderer->GetActiveCamera()->Modified();
    vtkCascadedShadowMapPass::UseShadowsOn(fresh.Renderer);
    EXPECT_EQ(DifferingValues(fresh.Frame(), edited), 0) << name << ", run " << run;
    // The frames go on while a worker stops; say how long the edited frame took.
    std::printf("%s run %d: the frame after the edit %.3f s\n", name.c_str(), run, seconds);
  }
}

INSTANTIATE_TEST_SUITE_P(LargeCasters, InPlaceEdit,
  ::testing::Range<size_t>(0, InPlaceEdits().size()),
  [](const ::testing::TestParamInfo<size_t>& info) { return InPlaceEdits()[info.param].first; });
