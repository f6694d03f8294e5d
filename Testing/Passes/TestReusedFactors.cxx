// SPDX-License-Identifier: BSD-3-Clause
// A frame drawn as the last one reads each pixel's shadow factors from that frame
// (vtkCascadedShadowMapPass::ReuseShadowFactors): no lookup, no view depth, and the image the
// lookup draws; whatever moves a shadow or a surface makes the lookup again.
#include "vtkActor.h"
#include "vtkAssembly.h"
#include "vtkCamera.h"
#include "vtkCascadedShadowMapBakerPass.h"
#include "vtkCascadedShadowMapPass.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"

#include "csmTestHelpers.h"

#include <gtest/gtest.h>

#include <array>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace
{
using csmTest::BoxOverPlane;
using csmTest::DifferingValues;

/// The same frame with every lookup made (ReuseShadowFactors off for one frame).
vtkSmartPointer<vtkImageData> LookedUp(BoxOverPlane& scene, vtkCascadedShadowMapPass* pass)
{
  pass->ReuseShadowFactorsOff();
  auto image = scene.Frame();
  EXPECT_FALSE(pass->GetLastFrameReusedShadowFactors());
  pass->ReuseShadowFactorsOn();
  return image;
}

/// A frame that stores the factors and one that reads them (true: it did), the second's image.
vtkSmartPointer<vtkImageData> StoredThenRead(
  BoxOverPlane& scene, vtkCascadedShadowMapPass* pass, bool& read)
{
  scene.Frame();
  auto image = scene.Frame();
  read = pass->GetLastFrameReusedShadowFactors();
  return image;
}

/// Does a frame that reads the factors give the lookup's image to the level?
void ExpectTheLookupsImage(BoxOverPlane& scene, vtkCascadedShadowMapPass* pass, bool reads = true)
{
  bool read = false;
  auto image = StoredThenRead(scene, pass, read);
  EXPECT_EQ(read, reads);
  EXPECT_EQ(DifferingValues(LookedUp(scene, pass), image, 0), 0);
}

/// A box over the ground with three more boxes beside it.
void AddBoxes(BoxOverPlane& scene)
{
  for (int i = 0; i < 3; ++i)
  {
    const double x = -5.0 + 4.0 * i;
    scene.Renderer->AddActor(csmTest::BoxActor(x - 0.5, x + 0.5, 0.0, 2.0 + i, 3.0, 4.0));
  }
}

/// The boxes with shadows, after a frame that stored the factors and one that read them.
vtkCascadedShadowMapPass* BoxesThatRead(BoxOverPlane& scene)
{
  AddBoxes(scene);
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  bool read = false;
  StoredThenRead(scene, pass, read);
  return pass;
}
} // namespace

// Still frames after the first read the factors: no view depth drawn, no map, and the image of
// the lookup to the level (with the shadows in it: darker than the frame without shadows).
TEST(ReusedFactors, AStillFrameReadsTheLastFramesFactors)
{
  BoxOverPlane scene;
  AddBoxes(scene);
  auto plain = scene.Frame();
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
  auto first = scene.Frame();
  EXPECT_FALSE(pass->GetLastFrameReusedShadowFactors());
  EXPECT_GT(csmTest::DarkenedPixels(first, plain), 500);
  for (int still = 0; still < 3; ++still)
  {
    auto again = scene.Frame();
    EXPECT_TRUE(pass->GetLastFrameReusedShadowFactors()) << still;
    EXPECT_TRUE(baker->GetLastFrameStatistics().AsLastFrame) << still;
    EXPECT_FALSE(baker->GetLastFrameStatistics().ViewDepthDrawn) << still;
    EXPECT_EQ(baker->GetLastFrameStatistics().TexelsRendered, 0.0) << still;
    EXPECT_EQ(DifferingValues(again, first, 0), 0) << still;
  }
  EXPECT_EQ(DifferingValues(LookedUp(scene, pass), first, 0), 0);
}

// A caster inside an assembly (drawn with its parts' matrices poked in, which modifies the parts
// at every frame) keeps its maps and its factors on still frames, as a plain actor does; the
// assembly moved, or its part, draws the map again.
TEST(ReusedFactors, AnAssemblysStillFramesKeepTheMapsAndTheFactors)
{
  BoxOverPlane scene;
  scene.Renderer->RemoveActor(scene.Box);
  vtkNew<vtkAssembly> assembly;
  assembly->AddPart(scene.Box);
  scene.Renderer->AddActor(assembly);
  auto plain = scene.Frame();
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
  auto first = scene.Frame();
  EXPECT_GT(csmTest::DarkenedPixels(first, plain), 800);
  scene.Frame();
  for (int still = 0; still < 3; ++still)
  {
    auto again = scene.Frame();
    EXPECT_TRUE(pass->GetLastFrameReusedShadowFactors()) << still;
    EXPECT_EQ(baker->GetLastFrameStatistics().TexelsRendered, 0.0) << still;
    EXPECT_EQ(DifferingValues(again, first, 0), 0) << still;
  }
  for (vtkProp3D* moved : { static_cast<vtkProp3D*>(assembly), static_cast<vtkProp3D*>(scene.Box) })
  {
    moved->AddPosition(0.5, 0.0, 0.0);
    auto changed = scene.Frame();
    EXPECT_FALSE(pass->GetLastFrameReusedShadowFactors());
    EXPECT_GT(baker->GetLastFrameStatistics().TexelsRendered, 0.0);
    EXPECT_EQ(DifferingValues(LookedUp(scene, pass), changed, 0), 0);
  }
}

// Colours and materials keep the factors; a moved camera, light or box, edited points, another
// darkness, bias or window size, a light's shadow attenuation, a box made translucent make the
// lookup again. Each frame is the image of the lookup to the level.
TEST(ReusedFactors, OnlyChangesOfColourOrMaterialKeepTheFactors)
{
  BoxOverPlane scene;
  vtkCascadedShadowMapPass* pass = BoxesThatRead(scene);
  ASSERT_TRUE(pass->GetLastFrameReusedShadowFactors());
  struct Change
  {
    std::string Name;
    bool Keeps;
    std::function<void()> Apply;
  };
  const std::vector<Change> changes = {
    { "colour", true, [&]() { scene.Box->GetProperty()->SetColor(0.2, 0.8, 0.3); } },
    { "specular", true, [&]() { scene.Ground->GetProperty()->SetSpecular(0.5); } },
    { "camera", false,
      [&]()
      {
        scene.Renderer->GetActiveCamera()->Azimuth(3.0);
        scene.Renderer->ResetCameraClippingRange();
      } },
    { "light", false, [&]() { scene.Light->SetPosition(1.0, 10.0, 0.5); } },
    { "box moved", false, [&]() { scene.Box->SetPosition(0.4, 0.0, 0.0); } },
    { "darkness", false, [&]() { pass->SetShadowDarkness(0.6); } },
    { "bias", false, [&]() { pass->SetConstantBias(0.004); } },
    { "attenuation", false, [&]() { scene.Light->SetShadowAttenuation(0.5f); } },
    { "window size", false, [&]() { scene.Window->SetSize(300, 220); } },
    { "translucent", false, [&]() { scene.Box->GetProperty()->SetOpacity(0.5); } },
  };
  for (const Change& change : changes)
  {
    change.Apply();
    auto changed = scene.Frame();
    EXPECT_EQ(pass->GetLastFrameReusedShadowFactors(), change.Keeps) << change.Name;
    EXPECT_EQ(DifferingValues(LookedUp(scene, pass), changed, 0), 0) << change.Name;
    scene.Frame();
    auto still = scene.Frame(); // (after the lookup's frame: stored, then read)
    EXPECT_TRUE(pass->GetLastFrameReusedShadowFactors()) << change.Name;
    EXPECT_EQ(DifferingValues(still, changed, 0), 0) << change.Name;
  }
}

// A translucent box in front of the shadowed ground makes its own lookup: the frame that reads
// the factors of the opaque surfaces behind it is the lookup's image.
TEST(ReusedFactors, TranslucentPropsMakeTheirOwnLookup)
{
  BoxOverPlane scene;
  vtkSmartPointer<vtkActor> glass = csmTest::BoxActor(-3.0, 3.0, 0.5, 1.5, 2.0, 6.0);
  glass->GetProperty()->SetOpacity(0.4);
  scene.Renderer->AddActor(glass);
  ExpectTheLookupsImage(scene, vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer));
}

// Tubes and wide lines (VTK's impostors and screen-sized lines) beside surfaces that read their
// factors: the impostors make their own lookup, and the frame is the lookup's image.
TEST(ReusedFactors, ImpostorsBesideSurfacesThatRead)
{
  BoxOverPlane scene;
  const std::vector<std::array<double, 6>> bars = { { -4, 3, -4, 4, 3, -4 }, { -4, 3, 4, 4, 3, 4 },
    { -4, 2, -4, -4, 2, 4 } };
  scene.Renderer->AddActor(csmTest::SegmentsActor(bars, 6.0f, true));
  scene.Renderer->AddActor(csmTest::SegmentsActor({ { 4, 2.5, -4, 4, 2.5, 4 } }, 3.0f, false));
  ExpectTheLookupsImage(scene, vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer));
}

// A camera path: the first moved frame stores its factors, which the next frame (moved again)
// cannot read; the frames after it make the lookup alone until the view stands (a frame drawn as
// the last one stores, the next reads). Each frame is the lookup's image.
TEST(ReusedFactors, APathStoresOnceUntilTheViewStands)
{
  BoxOverPlane scene;
  vtkCascadedShadowMapPass* pass = BoxesThatRead(scene);
  ASSERT_TRUE(pass->GetLastFrameReusedShadowFactors());
  for (int step = 0; step < 4; ++step)
  {
    scene.Renderer->GetActiveCamera()->Azimuth(2.0);
    scene.Renderer->ResetCameraClippingRange();
    auto moved = scene.Frame();
    EXPECT_FALSE(pass->GetLastFrameReusedShadowFactors()) << step;
    EXPECT_EQ(pass->GetLastFrameStoredShadowFactors(), step == 0) << step;
    EXPECT_EQ(DifferingValues(LookedUp(scene, pass), moved, 0), 0) << step;
  }
  auto stands = scene.Frame();
  EXPECT_TRUE(pass->GetLastFrameStoredShadowFactors());
  auto still = scene.Frame();
  EXPECT_TRUE(pass->GetLastFrameReusedShadowFactors());
  EXPECT_EQ(DifferingValues(still, stands, 0), 0);
}

// Two renderers side by side sharing one pass chain: each keeps its own factors, and each frame
// is the lookup's image.
TEST(ReusedFactors, TwoRenderersSharingAPass)
{
  BoxOverPlane scene;
  AddBoxes(scene);
  vtkNew<vtkRenderer> right;
  right->SetViewport(0.5, 0.0, 1.0, 1.0);
  scene.Renderer->SetViewport(0.0, 0.0, 0.5, 1.0);
  right->AutomaticLightCreationOff();
  right->AddLight(scene.Light);
  right->AddActor(scene.Box);
  right->AddActor(scene.Ground);
  right->SetActiveCamera(scene.Renderer->GetActiveCamera());
  scene.Window->AddRenderer(right);
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  right->SetPass(scene.Renderer->GetPass());
  scene.Frame();
  for (int frame = 0; frame < 3; ++frame)
  {
    auto image = scene.Frame();
    EXPECT_TRUE(pass->GetLastFrameReusedShadowFactors()) << frame; // (the right one's frame)
    EXPECT_EQ(DifferingValues(LookedUp(scene, pass), image, 0), 0) << frame;
    scene.Frame();
    scene.Renderer->GetActiveCamera()->Azimuth(5.0); // (the camera both renderers share)
    scene.Renderer->ResetCameraClippingRange();
    right->ResetCameraClippingRange();
    auto moved = scene.Frame();
    EXPECT_EQ(DifferingValues(LookedUp(scene, pass), moved, 0), 0) << frame;
    scene.Frame();
  }
}

// Renderers in two windows sharing one pass chain: the graphics resources of one window released
// (its window closed) leave the other window's factors alone; its frames stay the lookup's
// image (released with the first window's, they left it black).
TEST(ReusedFactors, ReleasingOneWindowKeepsTheOthersFactors)
{
  BoxOverPlane first;
  BoxOverPlane second;
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(first.Renderer);
  second.Renderer->SetPass(first.Renderer->GetPass());
  first.Frame();
  second.Frame();
  auto before = second.Frame();
  EXPECT_TRUE(pass->GetLastFrameReusedShadowFactors());
  for (const bool wholeWindow : { false, true })
  {
    if (wholeWindow)
    {
      first.Window->ReleaseGraphicsResources(first.Window);
    }
    else
    {
      pass->ReleaseGraphicsResources(first.Window);
    }
    second.Frame();
    auto after = second.Frame();
    EXPECT_TRUE(pass->GetLastFrameReusedShadowFactors()) << wholeWindow;
    EXPECT_EQ(DifferingValues(before, after, 0), 0) << wholeWindow;
    EXPECT_EQ(DifferingValues(LookedUp(second, pass), after, 0), 0) << wholeWindow;
  }
}

// A multisampled framebuffer shades a pixel once for the samples of several surfaces: each
// sample keeps the factors of the surface it shows, and the frame that reads them is the
// lookup's image to the level, edges of the boxes over their shadows included.
TEST(ReusedFactors, AMultisampledWindowKeepsEachSamplesSurface)
{
  BoxOverPlane scene;
  AddBoxes(scene);
  scene.Window->SetMultiSamples(4);
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  scene.Frame();
  EXPECT_TRUE(pass->GetLastFrameStoredShadowFactors());
  auto read = scene.Frame();
  EXPECT_TRUE(pass->GetLastFrameReusedShadowFactors());
  EXPECT_FALSE(pass->GetShadowMapBakerPass()->GetLastFrameStatistics().ViewDepthDrawn);
  EXPECT_EQ(DifferingValues(LookedUp(scene, pass), read, 0), 0);
}

// Up to four shadowed lights keep their factors (three in a multisampled framebuffer, where a
// channel holds the depth that tells a pixel's surfaces apart); more make the lookup.
TEST(ReusedFactors, FourLightsOrThreeWithSamples)
{
  for (const int samples : { 0, 4 })
  {
    BoxOverPlane scene;
    scene.Window->SetMultiSamples(samples);
    vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
    for (int lights = 2; lights <= 5; ++lights)
    {
      vtkNew<vtkLight> light;
      light->SetLightTypeToSceneLight();
      light->SetPositional(false);
      light->SetPosition(2.0 * lights - 6.0, 10.0, 1.0);
      light->SetFocalPoint(0.0, 0.0, 0.0);
      light->SetIntensity(0.3);
      scene.Renderer->AddLight(light);
      SCOPED_TRACE(std::to_string(samples) + " samples, " + std::to_string(lights) + " lights");
      ExpectTheLookupsImage(scene, pass, lights <= (samples > 1 ? 3 : 4));
    }
  }
}
