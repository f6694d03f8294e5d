// SPDX-License-Identifier: BSD-3-Clause
// Cascades fitted to the visible depths (VisibleDepthFit): they begin at the nearest sample of
// the view, not where the scene's boxes meet it, and something nearer coming into view is
// shadowed in the frame that first shows it.
#include "vtkActor.h"
#include "vtkAppendPolyData.h"
#include "vtkCamera.h"
#include "vtkCascadedShadowMapBakerPass.h"
#include "vtkCascadedShadowMapPass.h"
#include "vtkCubeSource.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"
#include "vtkWindowToImageFilter.h"

#include "csmTestHelpers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace
{
using csmTest::BoxOverPlane;
using csmTest::BoxOverPlaneSettings;
using csmTest::DarkenedPixels;
using csmTest::DifferingValues;
} // namespace

namespace
{
/// An actor of a box with the given bounds, in grey.
vtkSmartPointer<vtkActor> BoxActor(
  double xmin, double xmax, double ymin, double ymax, double zmin, double zmax)
{
  vtkNew<vtkCubeSource> cube;
  cube->SetBounds(xmin, xmax, ymin, ymax, zmin, zmax);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(cube->GetOutputPort());
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(0.8, 0.8, 0.8);
  return actor;
}

/// The view depths of the window's depth buffer (last frame), rows from the bottom.
std::vector<double> ViewDepths(vtkRenderWindow* window, vtkCamera* camera)
{
  const int* size = window->GetSize();
  std::vector<float> z(static_cast<size_t>(size[0]) * size[1]);
  window->GetZbufferData(0, 0, size[0] - 1, size[1] - 1, z.data());
  double range[2];
  camera->GetClippingRange(range);
  std::vector<double> depths;
  for (float v : z)
  {
    const double ndc = 2.0 * v - 1.0;
    depths.push_back(v < 1.0f
        ? 2.0 * range[0] * range[1] / ((range[1] + range[0]) - ndc * (range[1] - range[0]))
        : HUGE_VAL);
  }
  return depths;
}

double NearestSampleDepth(vtkRenderWindow* window, vtkCamera* camera)
{
  const std::vector<double> depths = ViewDepths(window, camera);
  return *std::min_element(depths.begin(), depths.end());
}

/// The pixels whose sample is nearer than a view depth.
std::vector<char> NearerThan(vtkRenderWindow* window, vtkCamera* camera, double depth)
{
  std::vector<char> mask;
  for (double d : ViewDepths(window, camera))
    mask.push_back(d < depth);
  return mask;
}
} // namespace

// The cascades begin at the nearest visible sample, not where the scene's
// boxes meet the view (here one prop's box holds the camera: a block behind it and the box in
// front of it are one polydata).
TEST(Passes, VisibleDepthFitStartsTheCascadesAtTheNearestSample)
{
  BoxOverPlane scene;
  scene.AddBlockBehindTheCamera();
  auto plain = scene.Render();
  vtkCamera* camera = scene.Renderer->GetActiveCamera();
  const double cameraNear = camera->GetClippingRange()[0];

  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);

  pass->GetShadowMapBakerPass()->LightSpacePagesOff(); // (the cascades' own behaviour)
  vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
  baker->GetPlanner()->SceneFittedCascadesOff(); // (the cascades that follow the view)
  baker->VisibleDepthFitOff();
  auto boxes = scene.Frame();
  const double boxesNear = baker->GetLightMaps()[0].SplitNear;
  EXPECT_FALSE(baker->GetLastFrameStatistics().VisibleDepthsUsed);
  EXPECT_LT(boxesNear, 1.01 * cameraNear); // the box around the two blocks holds the eye

  baker->VisibleDepthFitOn();
  auto fitted = scene.Frame(); // measured in the frame it serves
  EXPECT_TRUE(baker->GetLastFrameStatistics().VisibleDepthsUsed);
  EXPECT_TRUE(baker->GetLastFrameStatistics().VisibleDepthsMeasured);
  const double nearest = NearestSampleDepth(scene.Window, camera);
  EXPECT_GT(nearest, 10.0 * cameraNear);
  EXPECT_NEAR(baker->GetLightMaps()[0].SplitNear, nearest, 0.01 * nearest);
  EXPECT_LE(baker->GetLightMaps()[0].SplitNear, nearest);
  // The same shadows (the fitted cascades are finer; a few edge pixels may differ).
  const long shadowBoxes = DarkenedPixels(boxes, plain);
  const long shadowFitted = DarkenedPixels(fitted, plain);
  EXPECT_GT(shadowBoxes, 800);
  EXPECT_NEAR(shadowFitted, shadowBoxes, 0.02 * shadowBoxes);
  // The same view again: the depths measured for it serve, with no second depth pass.
  EXPECT_EQ(DifferingValues(scene.Frame(), fitted), 0);
  EXPECT_FALSE(baker->GetLastFrameStatistics().VisibleDepthsMeasured);
}

// The depth pass leaves out the faces of a closed caster turned away from the eye only where the
// eye sees it from outside: from inside a closed room, the walls it sees are those faces, and
// the cascades begin at the nearest of them.
TEST(Passes, FromInsideAClosedRoomTheCascadesBeginAtItsNearestWall)
{
  BoxOverPlane scene;
  scene.Renderer->RemoveActor(scene.Ground);
  scene.Renderer->RemoveActor(scene.Box);
  // A closed box around the eye; a block outside it, seen from outside: its back faces culled.
  const vtkSmartPointer<vtkActor> roomActor = csmTest::BoxActor(-5.0, 5.0, 0.0, 6.0, -5.0, 5.0);
  scene.Renderer->AddActor(roomActor);
  scene.Renderer->AddActor(csmTest::BoxActor(-1.0, 1.0, 1.0, 3.0, -12.0, -10.0));
  vtkCamera* camera = scene.Renderer->GetActiveCamera();
  camera->SetPosition(0.0, 3.0, 3.0);
  camera->SetFocalPoint(0.0, 3.0, -5.0); // the far wall, 8 away, fills the view
  camera->SetViewUp(0.0, 1.0, 0.0);
  camera->SetViewAngle(30.0);
  scene.Renderer->ResetCameraClippingRange();
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
  baker->GetPlanner()->SceneFittedCascadesOff();
  EXPECT_TRUE(baker->DrawsFromBehind(roomActor)); // (the room is a closed caster)
  scene.Frame();
  EXPECT_TRUE(baker->GetLastFrameStatistics().VisibleDepthsUsed);
  const double nearest = NearestSampleDepth(scene.Window, camera);
  EXPECT_NEAR(nearest, 8.0, 0.05);
  EXPECT_NEAR(baker->GetLightMaps().at(0).SplitNear, nearest, 0.01 * nearest);
  EXPECT_LE(baker->GetLightMaps().at(0).SplitNear, nearest);
}

// Something nearer put in front of a still camera (a shelf with a cube on it) is measured in the
// frame that first shows it: the same image as a fresh pass's, the cube's shadow on the shelf
// included.
TEST(Passes, SomethingNearerComingIntoViewIsShadowedInThatFrame)
{
  BoxOverPlane scene, reference;
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
  scene.Frame();
  scene.Frame();
  ASSERT_TRUE(baker->GetLastFrameStatistics().VisibleDepthsUsed);
  const double fittedNear = baker->GetLightMaps()[0].SplitNear;
  auto shelf = BoxActor(-2, 2, 7.8, 8, 4, 8);
  auto cube = BoxActor(-0.5, 0.5, 9, 10, 5.5, 6.5);
  auto shelfPlain = BoxActor(-2, 2, 7.8, 8, 4, 8);
  auto cubePlain = BoxActor(-0.5, 0.5, 9, 10, 5.5, 6.5);
  for (BoxOverPlane* s : { &scene, &reference })
  {
    s->Renderer->AddActor(s == &scene ? shelf : shelfPlain);
    s->Renderer->AddActor(s == &scene ? cube : cubePlain);
    s->Renderer->ResetCameraClippingRange();
  }
  auto plain = reference.Render();
  vtkCascadedShadowMapPass::UseShadowsOn(reference.Renderer);
  auto image = scene.Frame();
  const std::vector<char> nearer =
    NearerThan(scene.Window, scene.Renderer->GetActiveCamera(), fittedNear);
  EXPECT_TRUE(baker->GetLastFrameStatistics().VisibleDepthsUsed);
  EXPECT_LT(baker->GetLightMaps()[0].SplitNear, 0.8 * fittedNear);
  auto fresh = reference.Frame();
  EXPECT_EQ(DifferingValues(image, fresh), 0);
  // The cube's shadow on the shelf, nearer than the last frame's nearest sample.
  long shelfPixels = 0;
  EXPECT_GT(DarkenedPixels(image, plain, &nearer, &shelfPixels), 150);
  EXPECT_GT(shelfPixels, 2000);
}

// Grabbing an image renders the frame again with a camera whose view angle went through the
// tiling's trigonometry (a few 1e-8 off): that frame is the same view, so it measures no depths
// again, draws no map and starts no preparation of a big mesh (the view did not move).
TEST(Passes, AGrabbedImageIsTheSameView)
{
  BoxOverPlane scene;
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
  scene.Renderer->GetActiveCamera()->SetViewAngle(30.0);
  scene.Window->Render();
  EXPECT_TRUE(baker->GetLastFrameStatistics().VisibleDepthsMeasured);
  EXPECT_GT(baker->GetLastFrameStatistics().CascadesRendered, 0);
  // What the grab does to the camera, by hand: the same angle up to its rounding.
  scene.Renderer->GetActiveCamera()->SetViewAngle(30.000000834826057);
  scene.Window->Render();
  EXPECT_FALSE(baker->GetLastFrameStatistics().VisibleDepthsMeasured);
  EXPECT_EQ(baker->GetLastFrameStatistics().CascadesRendered, 0);
  // And a grab itself.
  scene.Render();
  EXPECT_FALSE(baker->GetLastFrameStatistics().VisibleDepthsMeasured);
  EXPECT_EQ(baker->GetLastFrameStatistics().CascadesRendered, 0);
  // A real step is a step.
  scene.Renderer->GetActiveCamera()->Azimuth(1.0);
  scene.Window->Render();
  EXPECT_TRUE(baker->GetLastFrameStatistics().VisibleDepthsMeasured);
}

// Where the view shows empty background around what it sees, each cascade's map covers only
// the part of the image where the depth pass found samples at its depths (VisibleFootprintFit):
// fewer texels for the same shadow. Not with a receiver the depth pass does not draw (a
// translucent one).
TEST(Passes, CascadesFittedToTheVisibleFootprintDrawFewerTexelsForTheSameShadow)
{
  BoxOverPlane scene(400, 300);
  scene.Renderer->RemoveActor(scene.Ground);
  scene.Renderer->RemoveActor(scene.Box);
  // One prop: a plate with a block on it near the lower left of the view and a tower far off
  // at the upper right. Its box holds most of the view volume, so the boxes do not tell where
  // the image is empty; the depths do.
  vtkNew<vtkAppendPolyData> parts;
  for (const std::array<double, 6>& b : { std::array<double, 6>{ -7, -1, 0, 0.2, -2, 3 },
         std::array<double, 6>{ -4.5, -3.5, 0.2, 1.7, -0.5, 0.5 },
         std::array<double, 6>{ 8, 10, 4, 12, -30, -28 } })
  {
    vtkNew<vtkCubeSource> cube;
    cube->SetBounds(b.data());
    cube->Update();
    parts->AddInputData(cube->GetOutput());
  }
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(parts->GetOutputPort());
  vtkNew<vtkActor> prop;
  prop->SetMapper(mapper);
  scene.Renderer->AddActor(prop);
  scene.Light->SetPosition(6.0, 10.0, 2.0); // (toward the origin: the block's shadow beside it)
  vtkCamera* camera = scene.Renderer->GetActiveCamera();
  camera->SetPosition(0.0, 6.0, 18.0);
  camera->SetFocalPoint(0.0, 2.0, -5.0);
  scene.Renderer->ResetCameraClippingRange();
  auto plain = scene.Render();
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  pass->GetShadowMapBakerPass()->LightSpacePagesOff(); // (the cascades' own behaviour)
  vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
  baker->GetPlanner()->SceneFittedCascadesOff(); // (the cascades that follow the view)
  baker->GetPlanner()->AdaptiveCascadesOff();
  baker->GetPlanner()->SetNumberOfCascades(2); // (the plate in the first, the tower in the last)
  baker->VisibleFootprintFitOff();
  auto whole = scene.Frame();
  const auto wholeStats = baker->GetLastFrameStatistics();
  EXPECT_TRUE(wholeStats.VisibleDepthsUsed);
  EXPECT_FALSE(wholeStats.VisibleFootprintUsed);

  baker->VisibleFootprintFitOn();
  baker->Modified(); // (an option changed: every map drawn again)
  auto fitted = scene.Frame();
  const auto fittedStats = baker->GetLastFrameStatistics();
  EXPECT_TRUE(fittedStats.VisibleFootprintUsed);
  std::printf("texels: whole view %.0f, footprint %.0f\n", wholeStats.TexelsRendered,
    fittedStats.TexelsRendered);
  EXPECT_GT(fittedStats.CascadesRendered, 0);
  EXPECT_LT(fittedStats.TexelsRendered, 0.6 * wholeStats.TexelsRendered); // 1.10 -> 0.52 M
  const long shadowWhole = DarkenedPixels(whole, plain);
  const long shadowFitted = DarkenedPixels(fitted, plain);
  std::printf("darkened pixels: whole view %ld, footprint %ld\n", shadowWhole, shadowFitted);
  EXPECT_GT(shadowWhole, 200); // the block's shadow on the plate
  EXPECT_NEAR(shadowFitted, shadowWhole, 0.03 * shadowWhole);

  // A shifted projection (as a magnified screenshot's tiles have): the depth pass's pixels are
  // not the camera's whole image, and the footprint is not used.
  camera->SetWindowCenter(0.2, 0.0);
  scene.Frame();
  EXPECT_TRUE(baker->GetLastFrameStatistics().VisibleDepthsUsed);
  EXPECT_FALSE(baker->GetLastFrameStatistics().VisibleFootprintUsed);
  camera->SetWindowCenter(0.0, 0.0);
  scene.Frame();
  EXPECT_TRUE(baker->GetLastFrameStatistics().VisibleFootprintUsed);

  // A translucent receiver: the footprint is not used.
  vtkSmartPointer<vtkActor> glass = csmTest::BoxActor(4.0, 6.0, 0.0, 2.0, -1.0, 1.0);
  glass->GetProperty()->SetOpacity(0.5);
  scene.Renderer->AddActor(glass);
  scene.Frame();
  EXPECT_TRUE(baker->GetLastFrameStatistics().VisibleDepthsUsed);
  EXPECT_FALSE(baker->GetLastFrameStatistics().VisibleFootprintUsed);
}

// A caster small on the image for its triangles (a finely tessellated ball far off) is left out
// of the visible-depth pass, its box standing in for its samples in the footprint: it still
// casts its shadow, the same as with the cascades fitted to the scene's boxes.
TEST(Passes, ACasterSmallOnTheImageForItsTrianglesStandsInByItsBoxForTheSameShadow)
{
  BoxOverPlaneSettings settings;
  settings.Size[0] = 400;
  settings.Size[1] = 300;
  settings.GroundHalfWidth = 30.0;
  settings.CameraFocalPoint[2] = -8.0;
  BoxOverPlane scene(settings);
  vtkNew<vtkSphereSource> ball;
  ball->SetCenter(5.0, 1.5, -16.0);
  ball->SetRadius(1.5);
  ball->SetThetaResolution(100);
  ball->SetPhiResolution(100); // 19,600 triangles over some 2,000 pixels
  vtkNew<vtkPolyDataMapper> ballMapper;
  ballMapper->SetInputConnection(ball->GetOutputPort());
  vtkNew<vtkActor> ballActor;
  ballActor->SetMapper(ballMapper);
  scene.Renderer->AddActor(ballActor);
  scene.Renderer->ResetCameraClippingRange();
  auto plain = scene.Render();
  ballActor->VisibilityOff();
  auto plainWithout = scene.Render();
  ballActor->VisibilityOn();
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
  auto boxes = [&]()
  {
    baker->VisibleDepthFitOff();
    baker->Modified();
    auto image = scene.Frame();
    EXPECT_EQ(baker->GetLastFrameStatistics().DepthPassStandIns, 0);
    return image;
  }();
  baker->VisibleDepthFitOn();
  baker->Modified();
  auto fitted = scene.Frame();
  const auto stats = baker->GetLastFrameStatistics();
  EXPECT_TRUE(stats.VisibleDepthsUsed);
  EXPECT_GE(stats.DepthPassStandIns, 1); // the ball (its blocks); the ground and the box drawn
  const long shadowBoxes = DarkenedPixels(boxes, plain);
  const long shadowFitted = DarkenedPixels(fitted, plain);
  std::printf("darkened pixels: boxes' fit %ld, visible depths with the ball standing in %ld\n",
    shadowBoxes, shadowFitted);
  EXPECT_GT(shadowBoxes, 400); // the box's shadow and the ball's
  EXPECT_NEAR(shadowFitted, shadowBoxes, 0.03 * shadowBoxes);
  // Without the ball the shadow is smaller: the ball's own shadow is among those pixels.
  ballActor->VisibilityOff();
  const long shadowWithout = DarkenedPixels(scene.Frame(), plainWithout);
  std::printf("darkened pixels without the ball: %ld\n", shadowWithout);
  EXPECT_LT(shadowWithout, shadowFitted - 20);
}

// A view square to the ground (straight down, as ParaView's -Y button, with and without
// multisampling): the view's depth drawn before the frame (a polygon offset farther, which on a
// face square to the view is its constant term alone) must not hide the ground from the frame's
// own pass (under VTK's GL_LESS every ground fragment failed: the background showed, or black).
TEST(Passes, AViewSquareToTheGroundStillDrawsIt)
{
  for (const int samples : { 0, 4 })
  {
    BoxOverPlaneSettings settings;
    settings.CameraPosition[0] = 0.0;
    settings.CameraPosition[1] = 30.0;
    settings.CameraPosition[2] = 0.0;
    settings.LightPosition[0] = 3.0;
    settings.LightPosition[2] = 2.0;
    BoxOverPlane scene(settings);
    scene.Window->SetMultiSamples(samples);
    scene.Renderer->GetActiveCamera()->SetViewUp(0.0, 0.0, -1.0);
    scene.Renderer->ResetCameraClippingRange();
    auto plain = scene.Frame();
    vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
    vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
    pass->ReuseShadowFactorsOff();
    auto shadowed = scene.Frame();
    ASSERT_TRUE(baker->GetLastFrameStatistics().ViewDepthDrawn) << samples;
    EXPECT_GT(DarkenedPixels(shadowed, plain), 500) << samples; // the box's shadow
    // The background shows where it shows without shadows, and the frame is the boxes' fit's.
    const auto background = [](vtkImageData* image)
    {
      long count = 0;
      for (int y = 0; y < 240; ++y)
        for (int x = 0; x < 320; ++x)
          count += image->GetScalarComponentAsDouble(x, y, 0, 0) == 51.0 &&
              image->GetScalarComponentAsDouble(x, y, 0, 2) == 102.0
            ? 1
            : 0;
      return count;
    };
    EXPECT_EQ(background(shadowed), background(plain)) << samples;
    baker->VisibleDepthFitOff();
    auto boxesFit = scene.Frame();
    EXPECT_LE(DifferingValues(shadowed, boxesFit), 200) << samples;
  }
}

// Two actors showing one plate at one depth: the first drawn shows, as without shadows, in a
// frame that draws the view's depth first and in a still frame that reads its factors, with and
// without multisampling (under GL_LEQUAL against the view's depth the second one showed).
TEST(Passes, OfTwoSurfacesAtOneDepthTheFirstDrawnShows)
{
  for (const int samples : { 0, 4 })
  {
    BoxOverPlane scene;
    scene.Window->SetMultiSamples(samples);
    vtkNew<vtkCubeSource> plate;
    plate->SetBounds(-3, 3, 1, 1, -3, 3); // (a square at y = 1, its faces coincident)
    for (const double green : { 0.0, 1.0 })
    {
      vtkNew<vtkPolyDataMapper> mapper;
      mapper->SetInputConnection(plate->GetOutputPort());
      vtkNew<vtkActor> actor;
      actor->SetMapper(mapper);
      actor->GetProperty()->SetColor(1.0 - green, green, 0.0);
      actor->GetProperty()->SetAmbient(0.5);
      scene.Renderer->AddActor(actor);
    }
    const auto count = [](vtkImageData* image, int channel)
    {
      long n = 0;
      for (int y = 0; y < 240; ++y)
        for (int x = 0; x < 320; ++x)
          n += image->GetScalarComponentAsDouble(x, y, 0, channel) > 100.0 &&
              image->GetScalarComponentAsDouble(x, y, 0, 1 - channel) < 30.0
            ? 1
            : 0;
      return n;
    };
    auto plain = scene.Frame();
    ASSERT_GT(count(plain, 0), 2000) << samples; // red
    ASSERT_EQ(count(plain, 1), 0) << samples;    // no green
    vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
    scene.Renderer->GetActiveCamera()->Azimuth(3.0);
    auto moved = scene.Frame();
    ASSERT_TRUE(vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer)
                  ->GetShadowMapBakerPass()
                  ->GetLastFrameStatistics()
                  .ViewDepthDrawn)
      << samples;
    auto still = scene.Frame();
    EXPECT_GT(count(moved, 0), 2000) << samples;
    EXPECT_EQ(count(moved, 1), 0) << samples;
    EXPECT_EQ(count(still, 1), 0) << samples;
    EXPECT_EQ(DifferingValues(moved, still), 0) << samples;
  }
}

// A magnified screenshot (vtkWindowToImageFilter's scale: tiles, each drawn with the camera's
// window centre shifted and its view angle narrowed) has the shadows of the same view rendered
// at that size: the maps hold the tile's shifted frustum (planned about the axis, the frustum
// that holds it, its pixels as large as the tile's), not a narrow one about the axis.
TEST(Passes, AMagnifiedScreenshotKeepsItsShadows)
{
  const auto darkened = [](int scale)
  {
    BoxOverPlaneSettings settings;
    settings.Size[0] = 960 / scale;
    settings.Size[1] = 720 / scale;
    settings.LightPosition[0] = 3.0;
    settings.LightPosition[2] = 2.0;
    const double box[6] = { -8.0, -6.0, 1.0, 3.0, 4.0, 6.0 }; // off the image's centre
    std::copy(box, box + 6, settings.Box);
    BoxOverPlane scene(settings);
    const auto grab = [&scene, scale]()
    {
      vtkNew<vtkWindowToImageFilter> filter;
      filter->SetInput(scene.Window);
      filter->SetScale(scale);
      filter->ReadFrontBufferOff();
      filter->Update();
      return vtkSmartPointer<vtkImageData>(filter->GetOutput());
    };
    auto plain = grab();
    vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
    scene.Frame();
    return DarkenedPixels(grab(), plain);
  };
  const long direct = darkened(1);
  EXPECT_GT(direct, 300);
  const long magnified = darkened(3);
  EXPECT_GT(magnified, direct * 9 / 10);
  EXPECT_LT(magnified, direct * 11 / 10);
}
