// SPDX-License-Identifier: BSD-3-Clause
// The comparison techniques and paths: face partitions (Lloyd et al. 2006, §5.1), camera space
// shadow maps (Kolić & Mihajlović), and map coordinates computed per vertex, each against the
// cascades' shadows.
#include "vtkCamera.h"
#include "vtkCascadedShadowMapBakerPass.h"
#include "vtkCascadedShadowMapPass.h"
#include "vtkCascadedShadowMapPlanner.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"

#include "csmTestHelpers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace
{
using csmTest::BoxOverPlane;
using csmTest::BoxOverPlaneSettings;
using csmTest::DarkenedPixels;
using csmTest::DifferingValues;
} // namespace

// Face partitioning as a comparison technique. The light 10 degrees from behind the
// viewer enters all four side faces: four maps, each selected by its planes; the box's shadow
// is the one the cascades give (the same darkened pixels within 3 %), and the debug view shows
// each partition's colour.
TEST(Passes, FacePartitionsShadeLikeCascades)
{
  BoxOverPlaneSettings settings;
  settings.CameraPosition[0] = 0;
  settings.CameraPosition[1] = 9;
  settings.CameraPosition[2] = 14;
  // The light travels along the view turned 10 degrees down (from behind the viewer; VTK's
  // field of view is 30 degrees, so it enters all four side faces).
  const double view[3] = { 0, -9, -14 };
  const double length = std::sqrt(9.0 * 9.0 + 14.0 * 14.0);
  const double a = 10.0 * 3.14159265358979323846 / 180.0;
  const double down[3] = { 0, -14 / length, 9 / length }; // perpendicular to the view, downward
  for (int i = 0; i < 3; ++i)
    settings.LightPosition[i] = -(std::cos(a) * view[i] / length + std::sin(a) * down[i]);
  BoxOverPlane scene(settings);
  auto plain = scene.Render();
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
  const long cascaded = DarkenedPixels(scene.Render(), plain);
  EXPECT_FALSE(baker->GetLightMaps()[0].SelectedByPlanes());
  baker->GetPlanner()->SetFacePartitions(1);
  const long faces = DarkenedPixels(scene.Render(), plain);
  ASSERT_EQ(baker->GetLightMaps().size(), 1u);
  EXPECT_TRUE(baker->GetLightMaps()[0].SelectedByPlanes());
  EXPECT_EQ(baker->GetLightMaps()[0].GetNumberOfCascades(), 4);
  EXPECT_GT(cascaded, 500);
  EXPECT_NEAR(faces, cascaded, 0.03 * cascaded);
  // The debug view's colours: one per partition (cascade colours of csmShadowFS.glsl).
  pass->SetDebugMode(vtkCascadedShadowMapPass::DEBUG_CASCADES);
  auto debug = scene.Render();
  int seen[4] = { 0, 0, 0, 0 };
  const double colours[4][3] = { { 1.0, 0.25, 0.25 }, { 0.25, 1.0, 0.25 }, { 0.3, 0.45, 1.0 },
    { 1.0, 1.0, 0.25 } };
  const int* size = scene.Window->GetSize();
  for (int y = 0; y < size[1]; ++y)
    for (int x = 0; x < size[0]; ++x)
    {
      double rgb[3];
      for (int c = 0; c < 3; ++c)
        rgb[c] = debug->GetScalarComponentAsDouble(x, y, 0, c) / 255.0;
      for (int k = 0; k < 4; ++k)
      {
        // Lit pixels show the colour times 1 (times 0.35 .. 1 with shading): compare hues.
        const double m = std::max({ rgb[0], rgb[1], rgb[2] });
        const double cm = std::max({ colours[k][0], colours[k][1], colours[k][2] });
        bool match = m > 0.2;
        for (int c = 0; c < 3; ++c)
          match = match && std::abs(rgb[c] / m - colours[k][c] / cm) < 0.08;
        seen[k] += match;
      }
    }
  for (int k = 0; k < 4; ++k)
    EXPECT_GT(seen[k], 200) << "partition " << k;
  // Back to cascades: no face partitions.
  baker->GetPlanner()->SetFacePartitions(0);
  pass->SetDebugMode(vtkCascadedShadowMapPass::DEBUG_OFF);
  EXPECT_EQ(DarkenedPixels(scene.Render(), plain), cascaded);
  EXPECT_FALSE(baker->GetLightMaps()[0].SelectedByPlanes());
}

// Face partitions need a directional light and a perspective camera: a spot light and a
// parallel view keep the cascades (and their shadows).
TEST(Passes, FacePartitionsFallBackToCascadesWhereTheyDoNotApply)
{
  BoxOverPlane scene;
  auto plain = scene.Render();
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
  baker->GetPlanner()->SetFacePartitions(2);
  EXPECT_EQ(baker->GetPlanner()->GetFacePartitions(), 2);
  baker->GetPlanner()->SetFacePartitions(99); // clamped
  EXPECT_EQ(baker->GetPlanner()->GetFacePartitions(),
    vtkCascadedShadowMapPlanner::MAXIMUM_FACE_Z_PARTITIONS);
  vtkCamera* camera = scene.Renderer->GetActiveCamera();
  camera->ParallelProjectionOn();
  camera->SetParallelScale(8.0);
  scene.Render();
  ASSERT_EQ(baker->GetLightMaps().size(), 1u);
  EXPECT_FALSE(baker->GetLightMaps()[0].SelectedByPlanes());
  EXPECT_GT(baker->GetLightMaps()[0].GetNumberOfCascades(), 0);
  camera->ParallelProjectionOff();
  scene.Render();
  EXPECT_TRUE(baker->GetLightMaps()[0].SelectedByPlanes()); // back in perspective: face partitions
  scene.Light->SetPositional(true);
  scene.Light->SetPosition(0, 10, 0);
  scene.Light->SetConeAngle(40);
  const long spot = DarkenedPixels(scene.Render(), plain);
  ASSERT_EQ(baker->GetLightMaps().size(), 1u);
  EXPECT_FALSE(baker->GetLightMaps()[0].SelectedByPlanes());
  EXPECT_GT(spot, 300);
}

// Camera space shadow maps (Kolić & Mihajlović). The general case: one map whose
// depth bias follows each ray's w, the box's shadow as the cascades give it (within 3 %); the
// light inside the view's cone: the dueling frustum case's four maps, the same shadow.
TEST(Passes, CameraSpaceMapShadesLikeCascades)
{
  BoxOverPlaneSettings settings;
  settings.LightPosition[0] = -0.4; // from above, a little from the side and the front
  settings.LightPosition[1] = 1.0;
  settings.LightPosition[2] = -0.5;
  BoxOverPlane scene(settings);
  auto plain = scene.Render();
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  // Hard shadows: the techniques' maps differ in size (one camera space map gets the atlas's
  // texels of four), and a filter in texels would widen their penumbrae apart.
  pass->SetPCFSize(1);
  vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
  const long cascaded = DarkenedPixels(scene.Render(), plain);
  EXPECT_EQ(baker->GetLightMaps()[0].Cascades[0].DepthW, 0.0);
  baker->GetPlanner()->CameraSpaceOn();
  const long cssm = DarkenedPixels(scene.Render(), plain);
  ASSERT_EQ(baker->GetLightMaps().size(), 1u);
  EXPECT_EQ(baker->GetLightMaps()[0].GetNumberOfCascades(), 1);
  EXPECT_GT(baker->GetLightMaps()[0].Cascades[0].DepthW, 0.0);
  EXPECT_GT(cascaded, 500);
  EXPECT_NEAR(cssm, cascaded, 0.03 * cascaded);
  // The light from straight behind the viewer (inside the view's cone): the dueling frustum
  // case, four maps selected by their planes, the same shadow.
  vtkCamera* camera = scene.Renderer->GetActiveCamera();
  double position[3], focal[3];
  camera->GetPosition(position);
  camera->GetFocalPoint(focal);
  scene.Light->SetPosition(position);
  scene.Light->SetFocalPoint(focal);
  baker->GetPlanner()->CameraSpaceOff();
  const long behindCascaded = DarkenedPixels(scene.Render(), plain);
  baker->GetPlanner()->CameraSpaceOn();
  const long behind = DarkenedPixels(scene.Render(), plain);
  const auto& maps = baker->GetLightMaps()[0];
  EXPECT_EQ(maps.GetNumberOfCascades(), 4);
  EXPECT_TRUE(maps.SelectedByPlanes());
  for (int c = 0; c < 4; ++c)
    EXPECT_GT(maps.Cascades[c].DepthW, 0.0);
  EXPECT_GT(behindCascaded, 100);
  EXPECT_NEAR(behind, behindCascaded, 0.05 * behindCascaded + 10);
}

// A spot light's camera space map (Kolić & Mihajlović §6.2: the casters projected from the
// light onto the plane in the view): the box's shadow as the standard spot map gives it (within
// 5 %), from another matrix; with the light in the view, the standard map.
TEST(Passes, CameraSpaceSpotLightShadesLikeItsStandardMap)
{
  BoxOverPlane scene;
  scene.Light->SetPositional(true);
  scene.Light->SetPosition(-3, 18, 12); // above and a little behind the camera (0, 14, 16)
  scene.Light->SetFocalPoint(0, 0, 0);
  scene.Light->SetConeAngle(40);
  auto plain = scene.Render();
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
  auto standardImage = scene.Render();
  const long standard = DarkenedPixels(standardImage, plain);
  ASSERT_EQ(baker->GetLightMaps().size(), 1u);
  std::vector<double> standardMatrix(baker->GetLightMaps()[0].Cascades[0].WorldToMap,
    baker->GetLightMaps()[0].Cascades[0].WorldToMap + 16);
  baker->GetPlanner()->CameraSpaceOn();
  auto cssmImage = scene.Render();
  const long cssm = DarkenedPixels(cssmImage, plain);
  ASSERT_EQ(baker->GetLightMaps().size(), 1u);
  const auto& maps = baker->GetLightMaps()[0];
  EXPECT_EQ(maps.GetNumberOfCascades(), 1);
  // Another map: its shadow edges fall on other pixels.
  EXPECT_GT(DifferingValues(standardImage, cssmImage, 8), 0);
  EXPECT_FALSE(
    std::equal(standardMatrix.begin(), standardMatrix.end(), maps.Cascades[0].WorldToMap));
  EXPECT_GT(standard, 500);
  EXPECT_NEAR(cssm, standard, 0.05 * standard);
  std::printf("spot light: standard map %ld darkened pixels, camera space map %ld; %ld values "
              "differ\n",
    standard, cssm, static_cast<long>(DifferingValues(standardImage, cssmImage, 8)));
  // The light in the view (in front of the camera, facing the ground): the standard map.
  scene.Light->SetPosition(0, 4, 4);
  baker->GetPlanner()->CameraSpaceOff();
  scene.Render();
  standardMatrix.assign(baker->GetLightMaps()[0].Cascades[0].WorldToMap,
    baker->GetLightMaps()[0].Cascades[0].WorldToMap + 16);
  baker->GetPlanner()->CameraSpaceOn();
  scene.Render();
  EXPECT_TRUE(std::equal(
    standardMatrix.begin(), standardMatrix.end(), baker->GetLightMaps()[0].Cascades[0].WorldToMap));
}
