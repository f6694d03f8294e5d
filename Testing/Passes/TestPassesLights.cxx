// SPDX-License-Identifier: BSD-3-Clause
// The lights: several shadowed lights, PBR, every lighting model VTK's mapper writes, more
// lights than texture units, and lights with no direction.
#include "vtkActor.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCascadedShadowMapBakerPass.h"
#include "vtkCascadedShadowMapPass.h"
#include "vtkCubeSource.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkStringOutputWindow.h"
#include "vtkUnsignedCharArray.h"

#include "csmTestHelpers.h"

#include <gtest/gtest.h>

#include <vector>

#include <cmath>

namespace
{
using csmTest::BoxOverPlane;
using csmTest::DarkenedPixels;
using csmTest::ErrorCounter;
} // namespace

TEST(Passes, FourDirectionalLightsAndPBR)
{
  BoxOverPlane scene;
  scene.Box->GetProperty()->SetInterpolationToPBR();
  scene.Ground->GetProperty()->SetInterpolationToPBR();
  scene.Ground->GetProperty()->SetRoughness(0.6);
  scene.Light->SetIntensity(0.4);
  const double positions[3][3] = { { 6, 10, 0 }, { -6, 10, 0 }, { 0, 10, 6 } };
  for (const auto& p : positions)
  {
    vtkNew<vtkLight> light;
    light->SetLightTypeToSceneLight();
    light->SetPositional(false);
    light->SetPosition(p[0], p[1], p[2]);
    light->SetFocalPoint(0, 0, 0);
    light->SetIntensity(0.4);
    scene.Renderer->AddLight(light);
  }
  auto plain = scene.Render();
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  auto shadowed = scene.Render();
  ASSERT_EQ(pass->GetShadowMapBakerPass()->GetLightMaps().size(), 4u);
  for (const auto& maps : pass->GetShadowMapBakerPass()->GetLightMaps())
    EXPECT_GT(maps.GetNumberOfCascades(), 0);
  // Four shadows of the box, each taking a quarter of the light: many pixels darker.
  EXPECT_GT(DarkenedPixels(shadowed, plain), 600);
  // A light whose shadow attenuation is 0 gets no maps.
  scene.Light->SetShadowAttenuation(0.0f);
  scene.Render();
  EXPECT_EQ(pass->GetShadowMapBakerPass()->GetLightMaps().size(), 3u);
  scene.Light->SetShadowAttenuation(1.0f);
  // Switching three lights off frees their maps.
  int off = 0;
  vtkCollectionSimpleIterator it;
  scene.Renderer->GetLights()->InitTraversal(it);
  while (vtkLight* light = scene.Renderer->GetLights()->GetNextLight(it))
    if (light != scene.Light.Get() && off++ < 3)
      light->SwitchOff();
  scene.Render();
  EXPECT_EQ(pass->GetShadowMapBakerPass()->GetLightMaps().size(), 1u);
}

// Every lighting model VTK's mapper writes gets the shadow factor of the shadowed light (the
// pass warns when it cannot find a light's shading lines; here it must not, and the shadow must
// be there).
TEST(Passes, EveryInterpolationGetsTheShadowFactor)
{
  const int models[] = { VTK_FLAT, VTK_GOURAUD, VTK_PHONG, VTK_PBR };
  for (int model : models)
  {
    for (bool edges : { false, true })
    {
      BoxOverPlane scene;
      scene.Ground->GetProperty()->SetInterpolation(model);
      scene.Ground->GetProperty()->SetEdgeVisibility(edges);
      auto plain = scene.Render();
      vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
      vtkNew<vtkCallbackCommand> onWarning;
      int warnings = 0;
      onWarning->SetClientData(&warnings);
      onWarning->SetCallback(
        [](vtkObject*, unsigned long, void* count, void*) { ++*static_cast<int*>(count); });
      pass->AddObserver(vtkCommand::WarningEvent, onWarning);
      auto shadowed = scene.Render();
      EXPECT_EQ(warnings, 0) << "interpolation " << model << (edges ? " with edges" : "");
      EXPECT_GT(DarkenedPixels(shadowed, plain), 800) // 1155-1158 measured
        << "interpolation " << model << (edges ? " with edges" : "");
    }
  }
}

// More shadowed lights than the fragment shader has texture units (33 on llvmpipe's 32) would
// fail to link the shader and every object would disappear. The first lights keep their
// shadows, the rest are lit without, and one warning says so; the lights kept find texture units
// for both of their atlas's reads (no texture left without a unit, nothing from VTK).
TEST(Passes, MoreLightsThanTextureUnits)
{
  BoxOverPlane scene;
  for (int i = 0; i < 32; ++i)
  {
    vtkNew<vtkLight> light;
    light->SetLightTypeToSceneLight();
    light->SetPositional(false);
    light->SetPosition(0.1 * (i % 8) - 0.4, 10, 0.1 * (i / 8) - 0.2);
    light->SetFocalPoint(0, 0, 0);
    light->SetIntensity(0.01);
    scene.Renderer->AddLight(light);
  }
  auto plain = scene.Render();
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
  baker->SetResolution(256);
  vtkNew<vtkCallbackCommand> countWarnings;
  int warnings = 0;
  countWarnings->SetClientData(&warnings);
  countWarnings->SetCallback(
    [](vtkObject*, unsigned long, void* n, void*) { ++*static_cast<int*>(n); });
  baker->AddObserver(vtkCommand::WarningEvent, countWarnings);
  // (VTK's own messages, such as a texture that finds no unit, go to the output window.)
  vtkNew<vtkStringOutputWindow> output;
  vtkSmartPointer<vtkOutputWindow> previous = vtkOutputWindow::GetInstance();
  vtkOutputWindow::SetInstance(output);
  auto shadowed = scene.Render();
  scene.Renderer->GetActiveCamera()->Azimuth(5);
  scene.Render();
  scene.Renderer->GetActiveCamera()->Azimuth(-5);
  shadowed = scene.Render();
  vtkOutputWindow::SetInstance(previous);
  const size_t shadowedLights = baker->GetLightMaps().size();
  // 16 units (the least GL 3.2 allows) - 8 for the mapper, 2 a light
  EXPECT_GE(shadowedLights, 4u);
  EXPECT_LT(shadowedLights, 33u);
  EXPECT_EQ(warnings, 1);
  // Every shadowed light's textures found their units.
  EXPECT_EQ(output->GetOutput(), "");
  // Objects are drawn (box and ground differ from the background) ...
  auto* scalars = vtkUnsignedCharArray::SafeDownCast(shadowed->GetPointData()->GetScalars());
  long drawn = 0;
  for (vtkIdType i = 0; i < scalars->GetNumberOfTuples(); ++i)
    drawn += std::abs(scalars->GetValue(3 * i) - 51) > 3;
  EXPECT_GT(drawn, 30000);
  // ... and the first light's shadow is there.
  EXPECT_GT(DarkenedPixels(shadowed, plain), 800);
}

TEST(Passes, NaNLightDirectionGivesNoShadowsAndNoGarbage)
{
  BoxOverPlane scene;
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
  ErrorCounter passErrors(pass), bakerErrors(baker), plannerErrors(baker->GetPlanner());
  scene.Light->SetPosition(NAN, 10, 0);
  // Two frames: the bad light is reported once, not on every frame, and gets no cascades.
  scene.Frame();
  auto image = scene.Frame();
  EXPECT_EQ(passErrors.Count + bakerErrors.Count + plannerErrors.Count, 1);
  EXPECT_EQ(plannerErrors.Count, 1);
  int cascades = 0;
  for (const auto& maps : baker->GetLightMaps())
    cascades += maps.GetNumberOfCascades();
  EXPECT_EQ(cascades, 0);
  scene.Light->SetPosition(0, 10, 0);
  // A light whose direction is NaN lights nothing the shader can trust; the frame must still be
  // drawn: the box and the ground differ from the background.
  auto* scalars = vtkUnsignedCharArray::SafeDownCast(image->GetPointData()->GetScalars());
  long drawn = 0;
  for (vtkIdType i = 0; i < scalars->GetNumberOfTuples(); ++i)
    drawn += std::abs(scalars->GetValue(3 * i) - 51) > 3;
  EXPECT_GT(drawn, 10000);
}

// A point light (positional, a cone of 90 degrees or more) casts no shadow, and says so once
// (a warning of the baker's, not one a frame); a directional light beside it keeps its shadow.
TEST(Passes, APointLightSaysOnceThatItCastsNoShadow)
{
  BoxOverPlane scene;
  scene.Light->SetIntensity(0.5);
  vtkNew<vtkLight> point;
  point->SetLightTypeToSceneLight();
  point->SetPositional(true);
  point->SetConeAngle(120.0);
  point->SetPosition(0, 6, 0);
  point->SetFocalPoint(0, 0, 0);
  point->SetIntensity(0.5);
  scene.Renderer->AddLight(point);
  auto plain = scene.Render();
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  ErrorCounter warnings(pass->GetShadowMapBakerPass(), vtkCommand::WarningEvent);
  for (int frame = 0; frame < 3; ++frame)
  {
    scene.Renderer->GetActiveCamera()->Azimuth(5);
    scene.Render();
  }
  EXPECT_EQ(warnings.Count, 1);
  EXPECT_EQ(pass->GetShadowMapBakerPass()->GetLightMaps(scene.Renderer).size(), 1u);
  scene.Renderer->GetActiveCamera()->Azimuth(-15);
  EXPECT_GT(DarkenedPixels(scene.Render(), plain), 300);
}

// A spot light far above the box casts the shadow a directional light from the same direction
// casts: its map's depths are fitted to the scene, not to its distance, so the constant bias
// stays a small share of the scene's depth (with margins of 1 % of the distance it ate the whole
// shadow from 5e4 on).
TEST(Passes, AFarSpotLightCastsItsShadow)
{
  BoxOverPlane scene;
  auto plain = scene.Render();
  vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  scene.Light->SetPosition(0.3, 10, 0.2);
  const long directional = DarkenedPixels(scene.Render(), plain);
  EXPECT_GT(directional, 800);
  scene.Light->SetPositional(true);
  scene.Light->SetConeAngle(30);
  for (const double height : { 1e4, 5e4, 1e6 })
  {
    scene.Light->SetPosition(0.3, height, 0.2);
    const long spot = DarkenedPixels(scene.Render(), plain);
    EXPECT_GT(spot, directional * 9 / 10) << height;
    EXPECT_LT(spot, directional * 11 / 10) << height;
  }
}

// A spot light just above the box (its near plane a thousandth of its far one) shadows the
// ground under the box: the constant bias follows the map depth's change with distance, so it
// stays a share of the map's depth range there too (a bias of the window depth ate the box's
// shadow on the far ground).
TEST(Passes, ASpotLightCloseAboveACasterShadowsTheGroundUnderIt)
{
  BoxOverPlane scene;
  scene.Light->SetPositional(true);
  scene.Light->SetConeAngle(60);
  scene.Light->SetFocalPoint(0, 0, 0);
  scene.Light->SetPosition(0, 4.001, 0); // the box's top is at 4
  // The ground the light reaches, where the box does not hide it from the camera: the pixels
  // the spot lights without the box (brighter than with the light off) that are not the box's.
  auto plain = scene.Render();
  scene.Box->VisibilityOff();
  auto ground = scene.Render();
  scene.Light->SetIntensity(0.0);
  auto unlit = scene.Render();
  scene.Light->SetIntensity(1.0);
  scene.Box->VisibilityOn();
  auto* withBox = vtkUnsignedCharArray::SafeDownCast(plain->GetPointData()->GetScalars());
  auto* lit = vtkUnsignedCharArray::SafeDownCast(ground->GetPointData()->GetScalars());
  auto* dark = vtkUnsignedCharArray::SafeDownCast(unlit->GetPointData()->GetScalars());
  ASSERT_NE(withBox, nullptr);
  ASSERT_NE(lit, nullptr);
  ASSERT_NE(dark, nullptr);
  const int nc = lit->GetNumberOfComponents();
  std::vector<char> reached(static_cast<size_t>(lit->GetNumberOfTuples()), 0);
  for (vtkIdType i = 0; i < lit->GetNumberOfTuples(); ++i)
  {
    bool box = false;
    int gain = 0;
    for (int c = 0; c < 3; ++c)
    {
      box = box || withBox->GetValue(nc * i + c) != lit->GetValue(nc * i + c);
      gain += lit->GetValue(nc * i + c) - dark->GetValue(nc * i + c);
    }
    reached[static_cast<size_t>(i)] = !box && gain > 30 ? 1 : 0;
  }
  vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  auto shadowed = scene.Render();
  // The light sees nothing past the box's top face: all of that ground is in its shadow.
  long reachedPixels = 0;
  const long darkened = csmTest::DarkenedPixels(shadowed, plain, &reached, &reachedPixels);
  EXPECT_GT(reachedPixels, 5000);
  EXPECT_GE(darkened, reachedPixels * 99 / 100) << reachedPixels;
}

// One degenerate light beside a good one is reported once, not on every frame.
TEST(Passes, DegenerateLightIsReportedOnce)
{
  BoxOverPlane scene;
  vtkNew<vtkLight> bad;
  bad->SetLightTypeToSceneLight();
  bad->SetPositional(false);
  bad->SetPosition(1, 1, 1);
  bad->SetFocalPoint(1, 1, 1); // no direction
  scene.Renderer->AddLight(bad);
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  pass->GetShadowMapBakerPass()->LightSpacePagesOff(); // (the cascades' own behaviour)
  // (The cascades that follow the view: a scene-fitted map would serve every view here.)
  pass->GetShadowMapBakerPass()->GetPlanner()->SceneFittedCascadesOff();
  pass->GetShadowMapBakerPass()->SetMapSlack(0.0); // (no map kept across the steps)
  ErrorCounter errors(pass->GetShadowMapBakerPass()->GetPlanner());
  int bakes = 0;
  for (int frame = 0; frame < 20; ++frame)
  {
    scene.Renderer->GetActiveCamera()->Azimuth(2); // a new bake every frame
    scene.Window->Render();
    bakes += pass->GetShadowMapBakerPass()->GetLastFrameStatistics().CascadesRendered > 0 ? 1 : 0;
  }
  EXPECT_EQ(bakes, 20);
  EXPECT_EQ(errors.Count, 1);
  ASSERT_EQ(pass->GetShadowMapBakerPass()->GetLightMaps().size(), 2u);
  EXPECT_GT(pass->GetShadowMapBakerPass()->GetLightMaps()[0].GetNumberOfCascades(), 0);
}

// A box over a ground far wider than itself, or with a speck of a prop far off, casts the shadow
// it casts over a ground of its own size: the scene-fitted map's depths span what lies under the
// shadows it holds, not the whole scene along the light, of which the constant bias is a share
// (over the scene's whole depth, the bias ate the shadow of a box over a ground 5,000 times its
// size).
TEST(Passes, ABoxOverAFarWiderGroundCastsItsShadow)
{
  const auto darkened = [](double groundHalfWidth, double speck)
  {
    csmTest::BoxOverPlaneSettings settings;
    settings.GroundHalfWidth = groundHalfWidth;
    settings.LightPosition[0] = 3.0; // oblique: a wide ground spans a deep range along the light
    settings.LightPosition[2] = 2.0;
    BoxOverPlane scene(settings);
    vtkNew<vtkActor> far;
    if (speck > 0.0)
    {
      vtkNew<vtkCubeSource> cube;
      cube->SetBounds(speck, speck + 1, 0, 1, speck, speck + 1);
      vtkNew<vtkPolyDataMapper> mapper;
      mapper->SetInputConnection(cube->GetOutputPort());
      far->SetMapper(mapper);
      scene.Renderer->AddActor(far);
    }
    scene.Renderer->ResetCameraClippingRange();
    auto plain = scene.Render();
    vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
    return DarkenedPixels(scene.Render(), plain);
  };
  const long own = darkened(10.0, 0.0);
  EXPECT_GT(own, 800);
  for (const double width : { 2e3, 1e4 })
  {
    const long wide = darkened(width, 0.0);
    EXPECT_GT(wide, own * 9 / 10) << width;
    EXPECT_LT(wide, own * 11 / 10) << width;
  }
  // (A cube 1e7 away: the box, whose shadow on the ground begins 2 below it, was left out of the
  // maps as a caster with nothing to shadow: its shadow had to be a millionth of the scene long.
  // 1e8 and more: the light-space pages' finest level served the box's shadow with texels
  // thousands of times too coarse.)
  for (const double speck : { 1e6, 1e7, 1e8, 1e10 })
  {
    const long withSpeck = darkened(10.0, speck);
    EXPECT_GT(withSpeck, own * 9 / 10) << speck;
    EXPECT_LT(withSpeck, own * 11 / 10) << speck;
  }
}

// Two shadowed lights, the first switched off and on again: the second keeps its maps in its own
// atlas both times (only the first's are drawn when it comes back), and the frame is the one
// before the switching.
TEST(Passes, ALightSwitchedOffAndOnLeavesTheOthersMaps)
{
  BoxOverPlane scene;
  scene.Light->SetPosition(3.0, 10.0, 2.0);
  vtkNew<vtkLight> second;
  second->SetLightTypeToSceneLight();
  second->SetPositional(false);
  second->SetPosition(-3.0, 10.0, 1.0);
  second->SetFocalPoint(0.0, 0.0, 0.0);
  scene.Renderer->AddLight(second);
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
  pass->ReuseShadowFactorsOff();
  scene.Frame();
  auto before = scene.Frame();
  ASSERT_EQ(baker->GetLightMaps().size(), 2u);
  const int secondMaps = baker->GetLightMaps()[1].GetNumberOfCascades();
  scene.Light->SwitchOff();
  scene.Frame();
  EXPECT_EQ(baker->GetLastFrameStatistics().CascadesRendered, 0);
  EXPECT_EQ(baker->GetLastFrameStatistics().CascadesKept, secondMaps);
  scene.Light->SwitchOn();
  auto after = scene.Frame();
  EXPECT_EQ(baker->GetLastFrameStatistics().CascadesKept, secondMaps);
  EXPECT_EQ(baker->GetLastFrameStatistics().CascadesRendered,
    baker->GetLightMaps()[0].GetNumberOfCascades());
  EXPECT_EQ(csmTest::DifferingValues(after, before, 0), 0);
}
