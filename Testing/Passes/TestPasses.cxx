// SPDX-License-Identifier: BSD-3-Clause
// Behaviour of the passes in a real GL context (Mesa llvmpipe through OSMesa, no X server; Xvfb
// in a build without OSMesa): what VTK's shadow pass gets wrong or does not do, each checked with
// numbers.
#include "vtkActor.h"
#include "vtkAppendPolyData.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCascadedShadowMapBakerPass.h"
#include "vtkCascadedShadowMapPass.h"
#include "vtkCascadedShadowMapPlanner.h"
#include "vtkCellArray.h"
#include "vtkCompositePolyDataMapper2.h"
#include "vtkCubeSource.h"
#include "vtkGlyph3DMapper.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkHardwareSelector.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkNew.h"
#include "vtkPNGWriter.h"
#include "vtkPlaneSource.h"
#include "vtkPointGaussianMapper.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSelection.h"
#include "vtkSelectionNode.h"
#include "vtkSphereSource.h"
#include "vtkTextureObject.h"
#include "vtkUnsignedCharArray.h"
#include "vtk_glew.h"

#include "csmTestHelpers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace
{
using csmTest::BoxOverPlane;
using csmTest::BoxOverPlaneSettings;
using csmTest::DarkenedPixels;
using csmTest::DifferingValues;

using csmTest::ErrorCounter;
} // namespace

TEST(Passes, ShadowAppearsUnderTheBox)
{
  BoxOverPlane scene;
  auto plain = scene.Render();
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  ASSERT_NE(pass, nullptr);
  auto shadowed = scene.Render();
  // The box's shadow: a 2x2 square about 21 pixels a unit away, partly hidden by the box.
  EXPECT_GT(DarkenedPixels(shadowed, plain), 800);
  EXPECT_EQ(pass->GetShadowMapBakerPass()->GetLightMaps().size(), 1u);
  // A small scene: one cascade meets the error target (AdaptiveCascades, the default).
  EXPECT_EQ(pass->GetShadowMapBakerPass()->GetLightMaps()[0].NumberOfCascades, 1);
  // Switching back off gives the plain image again.
  vtkCascadedShadowMapPass::UseShadowsOff(scene.Renderer);
  EXPECT_EQ(DifferingValues(scene.Render(), plain), 0);
}

TEST(Passes, MapsAreRebakedOnlyWhenSomethingChanged)
{
  BoxOverPlane scene;
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
  // (The cascades that follow the view: a scene-fitted map would serve every view here.)
  baker->SceneFittedCascadesOff();
  // (Window renders only: grabbing an image renders with a copy of the camera. Two warm-up
  // frames: anything the first frame creates, such as an actor's default property, is a change.)
  scene.Window->Render();
  scene.Window->Render();
  const int first = baker->GetBakeCount();
  scene.Window->Render();
  scene.Window->Render();
  EXPECT_EQ(baker->GetBakeCount(), first); // nothing changed
  scene.Renderer->GetActiveCamera()->Azimuth(10);
  scene.Window->Render();
  EXPECT_EQ(baker->GetBakeCount(), first + 1); // the camera moved
  scene.Light->SetPosition(1, 10, 0);
  scene.Window->Render();
  EXPECT_EQ(baker->GetBakeCount(), first + 2); // the light moved
  scene.Box->SetPosition(0.5, 0, 0);
  scene.Window->Render();
  EXPECT_EQ(baker->GetBakeCount(), first + 3); // a prop moved
  scene.Window->SetSize(300, 200);
  scene.Window->Render();
  EXPECT_EQ(baker->GetBakeCount(), first + 4); // the window changed shape
  pass->SetPCFSize(5);
  scene.Window->Render();
  EXPECT_EQ(baker->GetBakeCount(), first + 4); // a lookup option needs no new maps
}

// For benchmarks (csm-bench --breakdown): with MeasureTimes the planning, the maps, the clear
// and each re-rendered cascade's map are timed, and the parts fit in the whole; kept maps take
// no time; off, nothing is measured.
TEST(Passes, MeasuredTimesAreRecorded)
{
  BoxOverPlane scene;
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
  baker->MeasureTimesOn();
  scene.Window->Render();
  const int n = baker->GetLightMaps().at(0).NumberOfCascades;
  ASSERT_GE(n, 1);
  EXPECT_EQ(baker->GetLastCascadeRenders(), n);
  EXPECT_GT(baker->GetLastPlanSeconds(), 0.0);
  double parts = baker->GetLastClearSeconds();
  for (int c = 0; c < n; ++c)
  {
    EXPECT_GT(baker->GetLastCascadeSeconds(c), 0.0) << c;
    parts += baker->GetLastCascadeSeconds(c);
  }
  EXPECT_EQ(baker->GetLastCascadeSeconds(n), 0.0);
  EXPECT_EQ(baker->GetLastCascadeSeconds(-1), 0.0);
  EXPECT_EQ(baker->GetLastCascadeSeconds(1000), 0.0);
  // Structure only: every part was timed (how long each took is the benchmark's business).
  EXPECT_GT(parts, 0.0);
  EXPECT_GT(baker->GetLastMapSeconds(), 0.0);
  scene.Window->Render(); // nothing changed: every map kept
  EXPECT_EQ(baker->GetLastCascadeRenders(), 0);
  for (int c = 0; c < n; ++c)
  {
    EXPECT_EQ(baker->GetLastCascadeSeconds(c), 0.0) << c;
  }
  baker->MeasureTimesOff();
  scene.Box->SetPosition(0.25, 0, 0); // a prop moved: every map again, not timed
  scene.Window->Render();
  EXPECT_EQ(baker->GetLastCascadeRenders(), baker->GetLightMaps().at(0).NumberOfCascades);
  EXPECT_EQ(baker->GetLastMapSeconds(), 0.0);
  EXPECT_EQ(baker->GetLastCascadeSeconds(0), 0.0);
}

// The atlas holds the texels of four maps of Resolution² in 2 x 2 tiles, one texture for every
// count of cascades (a new one would cost its allocation and every map's render); one
// scene-fitted cascade (drawn once) gets all its texels, while maps that follow the view stay at
// most Resolution a side (a larger one would cost more every time the view moves).
TEST(Passes, OneAtlasServesEveryCountAndOneFittedMapGetsItAll)
{
  BoxOverPlane scene;
  auto plain = scene.Render();
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
  baker->SetResolution(256);
  baker->SetNumberOfCascades(4);
  bool sawFitted = false;
  vtkTextureObject* texture = nullptr;
  for (bool fitted : { true, false })
  {
    // (A target no count meets gets no scene-fitted map: the count of least error is taken.
    // Without one, a target more than any count can give: every map at its ceiling.)
    baker->SetErrorTarget(fitted ? 1.0 : 0.05);
    baker->SetSceneFittedCascades(fitted);
    const long shadowed = DarkenedPixels(scene.Render(), plain);
    ASSERT_EQ(baker->GetLightMaps().size(), 1u);
    const auto& maps = baker->GetLightMaps()[0];
    const int n = maps.NumberOfCascades;
    ASSERT_GE(n, 1);
    ASSERT_LT(n, 4); // the box over the plane is a short view: fewer than four
    EXPECT_EQ(maps.Atlas->GetWidth(), 512u);
    EXPECT_EQ(maps.Atlas->GetHeight(), 512u);
    EXPECT_TRUE(texture == nullptr || texture == maps.Atlas.Get());
    texture = maps.Atlas;
    const int tile = n == 1 ? 512 : 256;
    EXPECT_EQ(maps.Resolution[0], tile) << n << " cascades";
    EXPECT_EQ(maps.Resolution[1], tile);
    bool anyFitted = false;
    for (int c = 0; c < n; ++c)
    {
      anyFitted = anyFitted || maps.SceneFitted[c];
      for (int axis = 0; axis < 2; ++axis)
      {
        if (maps.SceneFitted[c])
        {
          EXPECT_EQ(maps.CascadeResolution[c][axis], tile) << c << " of " << n;
        }
        else if (fitted)
        {
          EXPECT_LE(maps.CascadeResolution[c][axis], 256) << c << " of " << n; // from need
        }
        else
        {
          EXPECT_EQ(maps.CascadeResolution[c][axis], 256) << c << " of " << n;
        }
      }
    }
    EXPECT_FALSE(!fitted && anyFitted);
    sawFitted = sawFitted || (anyFitted && n == 1);
    EXPECT_GT(shadowed, 500);
  }
  EXPECT_TRUE(sawFitted); // the box's footprint on the ground: one scene-fitted map
  // Four fixed cascades: the four tiles of Resolution in the same texture, the same shadow
  // within the penumbra's change.
  const long shadowed = DarkenedPixels(scene.Render(), plain);
  baker->AdaptiveCascadesOff();
  const long four = DarkenedPixels(scene.Render(), plain);
  EXPECT_EQ(baker->GetLightMaps()[0].NumberOfCascades, 4);
  EXPECT_EQ(baker->GetLightMaps()[0].Resolution[0], 256);
  EXPECT_EQ(baker->GetLightMaps()[0].Atlas.Get(), texture);
  EXPECT_EQ(baker->GetLightMaps()[0].Atlas->GetWidth(), 512u);
  EXPECT_EQ(baker->GetLightMaps()[0].Atlas->GetHeight(), 512u);
  EXPECT_NEAR(four, shadowed, 0.1 * shadowed);
}

// The farthest cascade's scene-fitted map (the box's footprint: the ground shadows nothing of
// itself) serves every view of an orbit: drawn in the first frame, kept while the camera turns,
// shading as a fresh pass's; a moved prop draws it again.
TEST(Passes, SceneFittedMapServesEveryViewOfAnOrbit)
{
  BoxOverPlane scene;
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
  EXPECT_TRUE(baker->GetSceneFittedCascades()); // the default
  scene.Frame();
  const int first = baker->GetLastCascadeRenders();
  EXPECT_GE(first, 1);
  int kept = 0;
  for (int frame = 0; frame < 6; ++frame)
  {
    scene.Renderer->GetActiveCamera()->Azimuth(35.0);
    auto image = scene.Frame();
    const auto& maps = baker->GetLightMaps().at(0);
    ASSERT_GE(maps.NumberOfCascades, 1);
    const int last = maps.NumberOfCascades - 1;
    EXPECT_TRUE(baker->GetPlanner()->GetCascadeSceneFitted(last)) << "frame " << frame;
    kept += baker->GetLastCascadesKept();
    EXPECT_EQ(baker->GetLastCascadeRenders(), last) << "frame " << frame; // only the others
    // As a pass that plans this view afresh.
    BoxOverPlane other;
    other.Renderer->GetActiveCamera()->DeepCopy(scene.Renderer->GetActiveCamera());
    auto plain = other.Frame();
    vtkCascadedShadowMapPass::UseShadowsOn(other.Renderer);
    auto expected = other.Frame();
    EXPECT_LE(csmTest::DifferingPixels(image, expected, 26), image->GetNumberOfPoints() / 200)
      << "frame " << frame;
    EXPECT_GT(DarkenedPixels(image, plain), 500) << "frame " << frame;
  }
  EXPECT_GE(kept, 6);
  // A prop moved: drawn again.
  scene.Box->SetPosition(0.5, 0, 0);
  scene.Frame();
  EXPECT_GE(baker->GetLastCascadeRenders(), 1);
  // Off: the farthest cascade follows the view, and a turn draws it again.
  baker->SceneFittedCascadesOff();
  scene.Frame();
  scene.Renderer->GetActiveCamera()->Azimuth(35.0);
  scene.Frame();
  EXPECT_FALSE(baker->GetPlanner()->GetCascadeSceneFitted(
    baker->GetLightMaps().at(0).NumberOfCascades - 1));
  EXPECT_GE(baker->GetLastCascadeRenders(), 1);
}

TEST(Passes, ResolutionAndCascadesCanChangeBetweenFrames)
{
  BoxOverPlane scene;
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
  auto plain = scene.Render();
  baker->AdaptiveCascadesOff(); // the counts set here, not the fewest that meet the target
  baker->SetResolution(512);
  baker->SetNumberOfCascades(1);
  auto one = scene.Render();
  ASSERT_EQ(baker->GetLightMaps().size(), 1u);
  EXPECT_EQ(baker->GetLightMaps()[0].Atlas->GetWidth(), 512u);
  EXPECT_EQ(baker->GetLightMaps()[0].NumberOfCascades, 1);
  baker->SetResolution(1024);
  baker->SetNumberOfCascades(6);
  auto six = scene.Render();
  // Four full tiles at most, 2 x 2: six cascades share that area, 2 x 3 tiles of 1024 x 682.
  const auto& maps = baker->GetLightMaps()[0];
  EXPECT_EQ(maps.Atlas->GetWidth(), 2048u);
  EXPECT_EQ(maps.Atlas->GetHeight(), 2048u);
  ASSERT_EQ(maps.NumberOfCascades, 6);
  for (int c = 0; c < 6; ++c)
  {
    EXPECT_LE(maps.CascadeResolution[c][0], 1024) << c;
    EXPECT_LE(maps.CascadeResolution[c][1], 682) << c;
    EXPECT_NEAR(maps.Tile[c][0], (c % 2) * 0.5, 1e-12) << c;
    EXPECT_NEAR(maps.Tile[c][1], (c / 2) * 682.0 / 2048.0, 1e-12) << c;
  }
  pass->SetPCFSize(1);
  auto hard = scene.Render();
  // A reallocated atlas must behave exactly like a first one (its compare mode and filters are
  // sent again to the new texture): compare with a fresh pass made with the final settings.
  baker->SetResolution(512);
  baker->SetNumberOfCascades(1);
  pass->SetPCFSize(5);
  auto reallocated = scene.Render();
  {
    BoxOverPlane fresh;
    vtkCascadedShadowMapPass* first = vtkCascadedShadowMapPass::UseShadowsOn(fresh.Renderer);
    first->GetShadowMapBakerPass()->AdaptiveCascadesOff();
    first->GetShadowMapBakerPass()->SetResolution(512);
    first->GetShadowMapBakerPass()->SetNumberOfCascades(1);
    first->SetPCFSize(5);
    EXPECT_EQ(DifferingValues(reallocated, fresh.Render()), 0);
  }
  scene.Renderer->SetPass(nullptr);
  plain = scene.Render();
  EXPECT_GT(DarkenedPixels(one, plain), 800);
  EXPECT_GT(DarkenedPixels(six, plain), 800);
  EXPECT_GT(DarkenedPixels(hard, plain), 800);
}

TEST(Passes, NonSquareWindowKeepsTheShadowInPlace)
{
  // VTK's pass bakes with the window aspect and looks up with 1: its shadows move in a wide
  // window. Ours must darken the same ground region whatever the window's shape, so the
  // shadowed share of the ground inside a centred square must agree between the two windows.
  BoxOverPlane square(300, 300), wide(900, 300);
  vtkCascadedShadowMapPass::UseShadowsOn(square.Renderer);
  vtkCascadedShadowMapPass::UseShadowsOn(wide.Renderer);
  wide.Renderer->GetActiveCamera()->SetViewAngle(30); // same vertical field
  auto sq = square.Render();
  auto wd = wide.Render();
  square.Renderer->SetPass(nullptr);
  wide.Renderer->SetPass(nullptr);
  auto sqPlain = square.Render();
  auto wdPlain = wide.Render();
  // Crop the wide image's centre 300x300.
  vtkNew<vtkImageData> crop, cropPlain;
  for (auto* pair : { &crop, &cropPlain })
  {
    (*pair)->SetDimensions(300, 300, 1);
    (*pair)->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  }
  for (int y = 0; y < 300; ++y)
    for (int x = 0; x < 300; ++x)
      for (int c = 0; c < 3; ++c)
      {
        crop->SetScalarComponentFromDouble(x, y, 0, c, wd->GetScalarComponentAsDouble(x + 300, y, 0, c));
        cropPlain->SetScalarComponentFromDouble(
          x, y, 0, c, wdPlain->GetScalarComponentAsDouble(x + 300, y, 0, c));
      }
  const long a = DarkenedPixels(sq, sqPlain);
  const long b = DarkenedPixels(crop, cropPlain);
  EXPECT_GT(a, 1000);
  EXPECT_NEAR(double(b), double(a), 0.05 * a);
}

TEST(Passes, TranslucentActorsAreStillDrawn)
{
  BoxOverPlane scene;
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(4, 2, 4);
  sphere->SetRadius(1.5);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(sphere->GetOutputPort());
  vtkNew<vtkActor> glass;
  glass->SetMapper(mapper);
  glass->GetProperty()->SetColor(0.1, 1.0, 0.1);
  glass->GetProperty()->SetOpacity(0.5);
  scene.Renderer->AddActor(glass);
  auto withGlass = [&]() { return scene.Render(); };
  vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  auto shadowed = withGlass();
  glass->SetVisibility(false);
  auto without = scene.Render();
  glass->SetVisibility(true);
  // The translucent sphere changes thousands of pixels (green tint), shadows on or not.
  EXPECT_GT(DifferingValues(shadowed, without), 1000);
}

TEST(Passes, HardwareSelectionStillWorks)
{
  BoxOverPlane scene;
  auto plain = scene.Render();
  vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  auto before = scene.Render();
  vtkNew<vtkHardwareSelector> selector;
  selector->SetRenderer(scene.Renderer);
  selector->SetArea(0, 0, 319, 239);
  selector->SetFieldAssociation(vtkDataObject::FIELD_ASSOCIATION_CELLS);
  vtkSmartPointer<vtkSelection> selection;
  selection.TakeReference(selector->Select());
  ASSERT_NE(selection, nullptr);
  // Both the ground and the box are picked.
  EXPECT_EQ(selection->GetNumberOfNodes(), 2u);
  // And the shadows come back on the next frame: the box's shadow (as in ShadowAppearsUnderTheBox),
  // and the very image of before the selection.
  auto after = scene.Render();
  EXPECT_GT(DarkenedPixels(after, plain), 800);
  EXPECT_EQ(DifferingValues(after, before), 0);
}

TEST(Passes, EmptyRendererAndNoShadowingLight)
{
  BoxOverPlane scene;
  // Only a headlight: VTK never shadows it. The image must equal the one without the pass.
  scene.Renderer->RemoveAllLights();
  vtkNew<vtkLight> head;
  head->SetLightTypeToHeadlight();
  scene.Renderer->AddLight(head);
  auto plain = scene.Render();
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  EXPECT_EQ(DifferingValues(scene.Render(), plain), 0);
  EXPECT_FALSE(pass->GetShadowMapBakerPass()->GetHasShadows());
  // No props at all.
  scene.Renderer->RemoveAllViewProps();
  scene.Renderer->AddLight(scene.Light);
  auto empty = scene.Render();
  auto* scalars = vtkUnsignedCharArray::SafeDownCast(empty->GetPointData()->GetScalars());
  // Every pixel is the background (0.2, 0.3, 0.4).
  long background = 0;
  for (vtkIdType i = 0; i < scalars->GetNumberOfTuples(); ++i)
    background += std::abs(scalars->GetValue(3 * i) - 51) <= 1 &&
      std::abs(scalars->GetValue(3 * i + 2) - 102) <= 1;
  EXPECT_EQ(background, scalars->GetNumberOfTuples());
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
    cascades += maps.NumberOfCascades;
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

TEST(Passes, CastersOutsideACascadeAreNotDrawnIntoIt)
{
  BoxOverPlane scene;
  // A second box far along the view: it cannot reach the near cascade's light volume.
  vtkNew<vtkCubeSource> cube;
  cube->SetBounds(-1, 1, 0, 2, -60, -58);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(cube->GetOutputPort());
  vtkNew<vtkActor> far;
  far->SetMapper(mapper);
  scene.Renderer->AddActor(far);
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(-10, 0, -70);
  plane->SetPoint1(10, 0, -70);
  plane->SetPoint2(-10, 0, 10);
  vtkPolyDataMapper::SafeDownCast(scene.Ground->GetMapper())->SetInputConnection(plane->GetOutputPort());
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
  baker->SetNumberOfCascades(3);
  baker->AdaptiveCascadesOff();
  baker->CullCastersWithoutReceiversOff(); // the ground is counted below
  scene.Render();
  ASSERT_EQ(baker->GetLastCascadeRenders(), 3);
  // 3 casters x 3 cascades would be 9 draws; culling must save some.
  EXPECT_LT(baker->GetLastPropsDrawn(), 9);
  EXPECT_GE(baker->GetLastPropsDrawn(), 3);
}

// A ground plane under everything shadows nothing: it is left out of the maps, the shadows stay.
TEST(Passes, CastersThatShadowNothingAreLeftOutOfTheMaps)
{
  BoxOverPlane scene;
  auto plain = scene.Render();
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
  baker->SetResolution(1024);
  baker->SetNumberOfCascades(2);
  baker->AdaptiveCascadesOff();
  auto without = scene.Render();
  ASSERT_GT(baker->GetLastCascadeRenders(), 0);
  // The plane (planar: it cannot shadow itself; the box floats above it) is left out of every
  // cascade, the box is drawn.
  EXPECT_GE(baker->GetLastCastersWithoutReceivers(), 1); // where the box reaches a cascade
  EXPECT_EQ(baker->GetLastPropsDrawn(), baker->GetLastCascadeRenders());
  EXPECT_GT(DarkenedPixels(without, plain), 800);
  // The same image as with the plane drawn into the maps.
  baker->CullCastersWithoutReceiversOff();
  auto with = scene.Render();
  EXPECT_EQ(baker->GetLastCastersWithoutReceivers(), 0);
  EXPECT_EQ(baker->GetLastPropsDrawn(), 2 * baker->GetLastCascadeRenders());
  EXPECT_LE(csmTest::DifferingPixels(without, with, 8), 20);
  baker->CullCastersWithoutReceiversOn();
  // The box reaching through the plane: the plane shadows its lower part, so it is drawn.
  vtkNew<vtkCubeSource> deep;
  deep->SetBounds(-1, 1, -2, 4, -1, 1);
  vtkPolyDataMapper::SafeDownCast(scene.Box->GetMapper())->SetInputConnection(deep->GetOutputPort());
  scene.Render();
  EXPECT_EQ(baker->GetLastCastersWithoutReceivers(), 0);
  // Light from below the plane: the plane shadows the box and is drawn; the box (convex, over
  // nothing else along this light) is left out.
  vtkNew<vtkCubeSource> above;
  above->SetBounds(-1, 1, 2, 4, -1, 1);
  vtkPolyDataMapper::SafeDownCast(scene.Box->GetMapper())->SetInputConnection(above->GetOutputPort());
  scene.Render();
  EXPECT_EQ(baker->GetLastCastersWithoutReceivers(), baker->GetLastCascadeRenders());
  scene.Light->SetPosition(0, -10, 0);
  scene.Render();
  EXPECT_GT(baker->GetLastCascadeRenders(), 0);
  EXPECT_GE(baker->GetLastCastersWithoutReceivers(), 1); // where the box reaches a cascade
  EXPECT_EQ(baker->GetLastPropsDrawn(), baker->GetLastCascadeRenders());
  // A spot light: every caster is drawn.
  scene.Light->SetPosition(0, 10, 0);
  scene.Light->SetPositional(true);
  scene.Light->SetConeAngle(60.0);
  scene.Render();
  EXPECT_GT(baker->GetLastCascadeRenders(), 0);
  EXPECT_EQ(baker->GetLastCastersWithoutReceivers(), 0);
}

TEST(Passes, ClosedSurfacesDrawnFromBehindTakeAShareOfTheBias)
{
  // A bias so large that it hides the box's shadow on the ground (the ground's reference depth
  // moves past the box, 2 units above it): with the ground an open plane the bias applies in
  // full whatever ClosedSurfaceBiasFactor says; with the ground a closed slab, drawn into the
  // maps from behind, only its share does, and the shadow is back.
  BoxOverPlane scene;
  auto plain = scene.Render();
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
  EXPECT_EQ(pass->GetClosedSurfaceBiasFactor(), 0.25);
  pass->SetSlopeBias(0.0);
  pass->SetConstantBias(0.9);
  EXPECT_LT(DarkenedPixels(scene.Render(), plain), 50);
  EXPECT_FALSE(baker->DrawsFromBehind(scene.Ground)); // a plane: open
  EXPECT_TRUE(baker->DrawsFromBehind(scene.Box));
  vtkNew<vtkCubeSource> slab;
  slab->SetBounds(-10, 10, -0.5, 0, -10, 10);
  vtkPolyDataMapper::SafeDownCast(scene.Ground->GetMapper())->SetInputConnection(slab->GetOutputPort());
  vtkSmartPointer<vtkRenderPass> chain = scene.Renderer->GetPass();
  scene.Renderer->SetPass(nullptr);
  plain = scene.Render();
  scene.Renderer->SetPass(chain);
  EXPECT_TRUE(baker->DrawsFromBehind(scene.Ground));
  pass->SetClosedSurfaceBiasFactor(1.0);
  EXPECT_LT(DarkenedPixels(scene.Render(), plain), 50);
  pass->SetClosedSurfaceBiasFactor(0.1);
  EXPECT_GT(DarkenedPixels(scene.Render(), plain), 800);
  // Without CullClosedCasters the slab's lit side is in the maps: the full bias again.
  baker->CullClosedCastersOff();
  EXPECT_FALSE(baker->DrawsFromBehind(scene.Ground));
  EXPECT_LT(DarkenedPixels(scene.Render(), plain), 50);
}

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
    EXPECT_GT(maps.NumberOfCascades, 0);
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

// Issue 9 (5): NaN through the clamped setters turned the whole view black (darkness, biases)
// or silently broke the blend band and the polygon offset.
TEST(Passes, NonFiniteOptionsAreRefused)
{
  BoxOverPlane scene;
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
  auto before = scene.Render();
  ErrorCounter passErrors(pass), bakerErrors(baker);
  pass->SetShadowDarkness(NAN);
  pass->SetConstantBias(NAN);
  pass->SetSlopeBias(NAN);
  pass->SetBlendBand(NAN);
  pass->SetShadowDarkness(-INFINITY);
  baker->SetPolygonOffsetFactor(NAN);
  baker->SetPolygonOffsetUnits(INFINITY);
  EXPECT_EQ(passErrors.Count, 5);
  EXPECT_EQ(bakerErrors.Count, 2);
  EXPECT_DOUBLE_EQ(pass->GetShadowDarkness(), 1.0);
  EXPECT_DOUBLE_EQ(pass->GetConstantBias(), 0.002);
  EXPECT_DOUBLE_EQ(pass->GetSlopeBias(), 1.5);
  EXPECT_DOUBLE_EQ(pass->GetBlendBand(), 0.05);
  EXPECT_DOUBLE_EQ(baker->GetPolygonOffsetFactor(), 1.1);
  EXPECT_DOUBLE_EQ(baker->GetPolygonOffsetUnits(), 2.0);
  EXPECT_EQ(DifferingValues(scene.Render(), before), 0);
}

// Issue 9 (12): one degenerate light beside a good one was reported on every frame.
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
  // (The cascades that follow the view: a scene-fitted map would serve every view here.)
  pass->GetShadowMapBakerPass()->SceneFittedCascadesOff();
  pass->GetShadowMapBakerPass()->SetMapSlack(0.0); // (no map kept across the steps)
  ErrorCounter errors(pass->GetShadowMapBakerPass()->GetPlanner());
  for (int frame = 0; frame < 20; ++frame)
  {
    scene.Renderer->GetActiveCamera()->Azimuth(2); // a new bake every frame
    scene.Window->Render();
  }
  EXPECT_EQ(pass->GetShadowMapBakerPass()->GetBakeCount(), 20);
  EXPECT_EQ(errors.Count, 1);
  ASSERT_EQ(pass->GetShadowMapBakerPass()->GetLightMaps().size(), 2u);
  EXPECT_GT(pass->GetShadowMapBakerPass()->GetLightMaps()[0].NumberOfCascades, 0);
}

// Issue 9 (6): more shadowed lights than the fragment shader has texture units (33 on llvmpipe's
// 32) failed to link the shader and every object disappeared. The first lights keep their
// shadows, the rest are lit without, and one warning says so.
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
  countWarnings->SetCallback([](vtkObject*, unsigned long, void* n, void*) { ++*static_cast<int*>(n); });
  baker->AddObserver(vtkCommand::WarningEvent, countWarnings);
  auto shadowed = scene.Render();
  scene.Renderer->GetActiveCamera()->Azimuth(5);
  scene.Render();
  scene.Renderer->GetActiveCamera()->Azimuth(-5);
  shadowed = scene.Render();
  const size_t shadowedLights = baker->GetLightMaps().size();
  EXPECT_GE(shadowedLights, 8u); // 16 units (the least GL 3.2 allows) - 8 for the mapper
  EXPECT_LT(shadowedLights, 33u);
  EXPECT_EQ(warnings, 1);
  // Objects are drawn (box and ground differ from the background) ...
  auto* scalars = vtkUnsignedCharArray::SafeDownCast(shadowed->GetPointData()->GetScalars());
  long drawn = 0;
  for (vtkIdType i = 0; i < scalars->GetNumberOfTuples(); ++i)
    drawn += std::abs(scalars->GetValue(3 * i) - 51) > 3;
  EXPECT_GT(drawn, 30000);
  // ... and the first light's shadow is there.
  EXPECT_GT(DarkenedPixels(shadowed, plain), 800);
}

// Maps kept across frames while the user drags (issue: speed). A pass that keeps maps and one
// that re-renders them every frame must shade a short interactive orbit alike.
TEST(Passes, KeptMapsShadeLikeFreshOnesAlongAnInteractivePath)
{
  BoxOverPlane keep, fresh;
  vtkCascadedShadowMapPass* a = vtkCascadedShadowMapPass::UseShadowsOn(keep.Renderer);
  vtkCascadedShadowMapPass* b = vtkCascadedShadowMapPass::UseShadowsOn(fresh.Renderer);
  b->GetShadowMapBakerPass()->SetInteractiveMapBorder(0.0);
  b->GetShadowMapBakerPass()->SetMapReuseTolerance(1.0); // re-render whenever the camera moves
  // (The cascades that follow the view: a scene-fitted map would serve every view here.)
  a->GetShadowMapBakerPass()->SceneFittedCascadesOff();
  b->GetShadowMapBakerPass()->SceneFittedCascadesOff();
  keep.Frame();
  fresh.Frame();
  keep.Window->SetDesiredUpdateRate(15.0); // as vtkRenderWindowInteractor while dragging
  fresh.Window->SetDesiredUpdateRate(15.0);
  int kept = 0, rendered = 0, cascades = 0;
  for (int frame = 0; frame < 8; ++frame)
  {
    keep.Renderer->GetActiveCamera()->Azimuth(1.5);
    fresh.Renderer->GetActiveCamera()->Azimuth(1.5);
    auto ia = keep.Frame();
    auto ib = fresh.Frame();
    kept += a->GetShadowMapBakerPass()->GetLastCascadesKept();
    rendered += b->GetShadowMapBakerPass()->GetLastCascadeRenders();
    cascades += b->GetShadowMapBakerPass()->GetLightMaps(fresh.Renderer).at(0).NumberOfCascades;
    // <= 0.5 % of the pixels differ by more than 0.1 of the range (26 levels).
    const long differing = csmTest::DifferingPixels(ia, ib, 26);
    EXPECT_GE(differing, 0);
    EXPECT_LE(differing, ia->GetNumberOfPoints() / 200) << "frame " << frame;
  }
  EXPECT_GT(kept, 0);         // the point of it: maps were kept
  EXPECT_EQ(rendered, cascades); // the reference re-rendered every cascade every frame
  // While dragging, the maps have at most InteractiveResolution texels a side.
  vtkCascadedShadowMapBakerPass* baker = a->GetShadowMapBakerPass();
  const auto& dragged = baker->GetLightMaps(keep.Renderer).at(0);
  for (int c = 0; c < dragged.NumberOfCascades; ++c)
  {
    EXPECT_LE(dragged.CascadeResolution[c][0], baker->GetInteractiveResolution());
    EXPECT_LE(dragged.CascadeResolution[c][1], baker->GetInteractiveResolution());
  }
  // The still frame after dragging returns to tight maps (full quality): identical images.
  keep.Window->SetDesiredUpdateRate(0.0001);
  fresh.Window->SetDesiredUpdateRate(0.0001);
  EXPECT_EQ(DifferingValues(keep.Frame(), fresh.Frame()), 0);
  const auto& still = baker->GetLightMaps(keep.Renderer).at(0);
  const auto& reference = b->GetShadowMapBakerPass()->GetLightMaps(fresh.Renderer).at(0);
  for (int c = 0; c < still.NumberOfCascades; ++c)
  {
    EXPECT_EQ(still.CascadeResolution[c][0], reference.CascadeResolution[c][0]);
    EXPECT_EQ(still.CascadeResolution[c][1], reference.CascadeResolution[c][1]);
  }
  EXPECT_EQ(baker->GetLastCascadeRenders(), still.NumberOfCascades);
}

namespace
{
/// The box on a ground 4000 wide, seen low along it from (0, 3, 12) (the clipping range to set:
/// 0.5 to 4000), the light from the given point toward the origin.
BoxOverPlaneSettings longGroundSeenLow(double lightX, double lightY, double lightZ)
{
  BoxOverPlaneSettings settings;
  settings.GroundHalfWidth = 2000.0;
  settings.CameraPosition[0] = 0;
  settings.CameraPosition[1] = 3;
  settings.CameraPosition[2] = 12;
  settings.LightPosition[0] = lightX;
  settings.LightPosition[1] = lightY;
  settings.LightPosition[2] = lightZ;
  return settings;
}

/// One cascade's depth texels, read back from its light's atlas (the window's context current).
std::vector<float> cascadeDepths(
  vtkRenderWindow* window, const vtkCascadedShadowMapBakerPass::LightMaps& maps, int c)
{
  window->MakeCurrent();
  vtkTextureObject* atlas = maps.Atlas;
  const int width = static_cast<int>(atlas->GetWidth());
  const int height = static_cast<int>(atlas->GetHeight());
  std::vector<float> all(static_cast<size_t>(width) * height);
  atlas->Bind();
  glGetTexImage(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT, GL_FLOAT, all.data());
  atlas->Deactivate();
  const int x = static_cast<int>(std::lround(maps.Tile[c][0] * width));
  const int y = static_cast<int>(std::lround(maps.Tile[c][1] * height));
  const int w = static_cast<int>(std::lround(maps.Tile[c][2] * width));
  const int h = static_cast<int>(std::lround(maps.Tile[c][3] * height));
  std::vector<float> tile;
  for (int row = y; row < y + h; ++row)
  {
    tile.insert(tile.end(), all.begin() + static_cast<size_t>(row) * width + x,
      all.begin() + static_cast<size_t>(row) * width + x + w);
  }
  return tile;
}
} // namespace

// A cascade re-rendered while others are kept begins from far depth: its tile holds exactly what
// a pass that re-renders every map draws into it (nothing left of the casters of its last matrix).
TEST(Passes, AMapReRenderedBesideKeptOnesHoldsOnlyItsOwnCasters)
{
  // Several cascades, the near ones changing first.
  const BoxOverPlaneSettings settings = longGroundSeenLow(4.0, 10.0, 3.0);
  BoxOverPlane keep(settings), fresh(settings);
  keep.Renderer->GetActiveCamera()->SetClippingRange(0.5, 4000.0);
  fresh.Renderer->GetActiveCamera()->SetClippingRange(0.5, 4000.0);
  // Boxes down the ground, in the farther cascades too (each window its own mappers).
  vtkNew<vtkCubeSource> far;
  far->SetBounds(-4, 4, 0, 16, -4, 4);
  vtkNew<vtkPolyDataMapper> farMappers[2];
  vtkNew<vtkActor> farBoxes[2][3];
  for (int window = 0; window < 2; ++window)
  {
    farMappers[window]->SetInputConnection(far->GetOutputPort());
    for (int k = 0; k < 3; ++k)
    {
      farBoxes[window][k]->SetMapper(farMappers[window]);
      farBoxes[window][k]->SetScale(0.5 * (k + 1));
      farBoxes[window][k]->SetPosition(6.0 * k - 6.0, 0.0, -30.0 - 90.0 * k * k);
      (window == 0 ? keep : fresh).Renderer->AddActor(farBoxes[window][k]);
    }
  }
  vtkCascadedShadowMapPass* a = vtkCascadedShadowMapPass::UseShadowsOn(keep.Renderer);
  vtkCascadedShadowMapPass* b = vtkCascadedShadowMapPass::UseShadowsOn(fresh.Renderer);
  a->GetShadowMapBakerPass()->SetErrorTarget(0.5);
  b->GetShadowMapBakerPass()->SetErrorTarget(0.5);
  b->GetShadowMapBakerPass()->SetMapReuseTolerance(1.0); // re-render whenever the camera moves
  keep.Window->SetDesiredUpdateRate(15.0);
  fresh.Window->SetDesiredUpdateRate(15.0);
  keep.Frame();
  fresh.Frame();
  int compared = 0;
  for (int frame = 0; frame < 24 && compared == 0; ++frame)
  {
    keep.Renderer->GetActiveCamera()->Azimuth(1.5);
    fresh.Renderer->GetActiveCamera()->Azimuth(1.5);
    keep.Frame();
    fresh.Frame();
    vtkCascadedShadowMapBakerPass* baker = a->GetShadowMapBakerPass();
    if (baker->GetLastCascadesKept() == 0 || baker->GetLastCascadeRenders() == 0)
    {
      continue; // not a frame with both
    }
    const auto& mk = baker->GetLightMaps(keep.Renderer).at(0);
    const auto& mf = b->GetShadowMapBakerPass()->GetLightMaps(fresh.Renderer).at(0);
    ASSERT_EQ(mk.NumberOfCascades, mf.NumberOfCascades);
    for (int c = 0; c < mk.NumberOfCascades; ++c)
    {
      // The re-rendered cascades: planned for this camera, as the reference's.
      if (!std::equal(mk.WorldToMap[c], mk.WorldToMap[c] + 16, mf.WorldToMap[c]) ||
        !std::equal(mk.Tile[c], mk.Tile[c] + 4, mf.Tile[c]))
      {
        continue;
      }
      const std::vector<float> kept = cascadeDepths(keep.Window, mk, c);
      const std::vector<float> reference = cascadeDepths(fresh.Window, mf, c);
      ASSERT_EQ(kept.size(), reference.size());
      long differing = 0, covered = 0;
      for (size_t k = 0; k < kept.size(); ++k)
      {
        differing += kept[k] != reference[k];
        covered += reference[k] < 1.0f;
      }
      EXPECT_GT(covered, 0) << "cascade " << c << " holds casters";
      EXPECT_EQ(differing, 0) << "frame " << frame << ", cascade " << c;
      ++compared;
    }
  }
  EXPECT_GT(compared, 0) << "no frame re-rendered a map beside a kept one";
}

// More than four cascades (tall tiles, maps turned to them) where the still frame's error
// needs them, at most four while the user drags (VTK's interactive convention), and the shadow
// there either way: a long ground seen low along it, the light from behind the viewer.
TEST(Passes, MoreThanFourCascadesOnlyInStillFrames)
{
  // The light travels along the view, a little down.
  BoxOverPlane scene(longGroundSeenLow(0.0, 3.5, 12.0));
  scene.Renderer->GetActiveCamera()->SetClippingRange(0.5, 4000.0);
  auto plain = scene.Render();
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
  baker->SetErrorTarget(0.05); // out of reach: as many as pay
  // (Of the cascades that follow the view: one scene-fitted map of the box's footprint would
  // meet even this.)
  baker->SceneFittedCascadesOff();
  pass->MapCoordinatesFromVerticesOn(); // (off by default)
  const long still = DarkenedPixels(scene.Render(), plain);
  const auto& maps = baker->GetLightMaps().at(0);
  EXPECT_GT(maps.NumberOfCascades, 4);
  int turned = 0;
  for (int c = 0; c < maps.NumberOfCascades; ++c)
  {
    EXPECT_NE(maps.Resolution[0], maps.Resolution[1]) << "tall tiles";
    turned += maps.MapTurned[c];
  }
  std::printf("still: %d cascades (%d turned), tiles %d x %d\n", maps.NumberOfCascades, turned,
    maps.Resolution[0], maps.Resolution[1]);
  EXPECT_EQ(pass->GetLastMapCoordinateVaryings(),
    vtkCascadedShadowMapPlanner::MAXIMUM_NUMBER_OF_CASCADES);
  const vtkMTimeType shaders = pass->GetShaderStageMTime();
  scene.Window->SetDesiredUpdateRate(15.0); // as vtkRenderWindowInteractor while dragging
  const long dragged = DarkenedPixels(scene.Render(), plain);
  EXPECT_LE(baker->GetLightMaps().at(0).NumberOfCascades, 4);
  // The count changes with the view: the shaders keep the eight cascades' coordinates they
  // were built with (a new variant would rebuild every shader).
  EXPECT_EQ(pass->GetLastMapCoordinateVaryings(),
    vtkCascadedShadowMapPlanner::MAXIMUM_NUMBER_OF_CASCADES);
  EXPECT_EQ(pass->GetShaderStageMTime(), shaders);
  EXPECT_GT(still, 200);
  EXPECT_NEAR(dragged, still, 0.1 * still);
}

TEST(Passes, PropLightOrOptionChangesReRenderEveryMap)
{
  BoxOverPlane scene;
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
  scene.Window->SetDesiredUpdateRate(15.0);
  scene.Frame(); // (warm-up: what the first frame creates may count as a change)
  scene.Frame();
  scene.Frame();
  // Every cascade this frame has (as many as AdaptiveCascades chose).
  auto cascades = [baker]() { return baker->GetLightMaps().at(0).NumberOfCascades; };
  EXPECT_EQ(baker->GetLastCascadeRenders(), 0);
  EXPECT_GE(cascades(), 1);
  EXPECT_EQ(baker->GetLastCascadesKept(), cascades());
  scene.Box->SetPosition(0.3, 0, 0);
  scene.Frame();
  EXPECT_EQ(baker->GetLastCascadeRenders(), cascades());
  scene.Light->SetPosition(1, 10, 0);
  scene.Frame();
  EXPECT_EQ(baker->GetLastCascadeRenders(), cascades());
  baker->SetPolygonOffsetUnits(3.0);
  scene.Frame();
  EXPECT_EQ(baker->GetLastCascadeRenders(), cascades());
  scene.Frame();
  EXPECT_EQ(baker->GetLastCascadeRenders(), 0);
}

TEST(Passes, LeavingAKeptMapReRendersItInThatFrame)
{
  BoxOverPlane scene, reference;
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  // (The cascades that follow the view: a scene-fitted map would serve every view here.)
  pass->GetShadowMapBakerPass()->SceneFittedCascadesOff();
  vtkCascadedShadowMapPass::UseShadowsOn(reference.Renderer)
    ->GetShadowMapBakerPass()
    ->SceneFittedCascadesOff();
  scene.Window->SetDesiredUpdateRate(15.0);
  reference.Window->SetDesiredUpdateRate(15.0);
  scene.Frame();
  // A jump no kept map covers: re-rendered at once, the same image as a fresh pass's.
  scene.Renderer->GetActiveCamera()->Azimuth(70);
  scene.Renderer->GetActiveCamera()->Elevation(-20);
  scene.Renderer->GetActiveCamera()->OrthogonalizeViewUp();
  reference.Renderer->GetActiveCamera()->DeepCopy(scene.Renderer->GetActiveCamera());
  auto moved = scene.Frame();
  EXPECT_GE(pass->GetShadowMapBakerPass()->GetLastCascadeRenders(), 1);
  EXPECT_EQ(DifferingValues(moved, reference.Frame()), 0);
}

// Wrong images of the hostile user's report (issue: wrong images), items 1, 3 and 4.
TEST(Passes, BlendBandDoesNotLightAStripeThroughTheShadow)
{
  BoxOverPlane scene;
  vtkCamera* camera = scene.Renderer->GetActiveCamera();
  camera->SetPosition(10, 6, 12);
  scene.Renderer->ResetCameraClippingRange();
  scene.Light->SetPosition(-0.3, 1, -0.2); // travelling (0.3, -1, 0.2)
  auto plain = scene.Render();
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  pass->SetBlendBand(0.0);
  const long hard = DarkenedPixels(scene.Render(), plain);
  pass->SetBlendBand(0.05);
  const long blended = DarkenedPixels(scene.Render(), plain);
  EXPECT_GT(hard, 500);
  EXPECT_GE(blended, hard - 10); // before the fix: 30-210 shadow pixels lit by the band
}

TEST(Passes, SwitchingBackToAnEarlierCameraReRendersItsMaps)
{
  BoxOverPlane scene;
  auto plain = scene.Render();
  vtkNew<vtkCamera> other;
  other->SetPosition(0, 4, -30);
  other->SetFocalPoint(0, 0, -40);
  vtkSmartPointer<vtkCamera> first = scene.Renderer->GetActiveCamera();
  vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  const long before = DarkenedPixels(scene.Render(), plain);
  scene.Renderer->SetActiveCamera(other);
  scene.Render();
  scene.Renderer->SetActiveCamera(first);
  const long after = DarkenedPixels(scene.Render(), plain);
  EXPECT_GT(before, 800);
  EXPECT_EQ(after, before);
}

TEST(Passes, OnePassChainServesTwoViewports)
{
  // Side by side: each viewport must get its own maps (before: the left showed the right's).
  BoxOverPlane solo(320, 240);
  vtkCascadedShadowMapPass::UseShadowsOn(solo.Renderer);
  auto alone = solo.Render();

  BoxOverPlane pair(640, 240);
  pair.Renderer->SetViewport(0, 0, 0.5, 1);
  vtkNew<vtkRenderer> right;
  right->SetViewport(0.5, 0, 1, 1);
  right->SetBackground(0.2, 0.3, 0.4);
  right->AutomaticLightCreationOff();
  right->AddLight(pair.Light);
  right->AddActor(pair.Box);
  right->AddActor(pair.Ground);
  right->GetActiveCamera()->SetPosition(12, 10, -6);
  right->GetActiveCamera()->SetFocalPoint(0, 0, 0);
  right->ResetCameraClippingRange();
  pair.Window->AddRenderer(right);
  vtkCascadedShadowMapPass* shared = vtkCascadedShadowMapPass::UseShadowsOn(pair.Renderer);
  right->SetPass(pair.Renderer->GetPass());
  auto both = pair.Render();
  pair.Render();
  both = pair.Render();
  // The left half equals the same view rendered alone.
  long differing = 0;
  for (int y = 0; y < 240; ++y)
    for (int x = 0; x < 320; ++x)
      for (int c = 0; c < 3; ++c)
        differing += std::abs(both->GetScalarComponentAsDouble(x, y, 0, c) -
                       alone->GetScalarComponentAsDouble(x, y, 0, c)) > 2;
  EXPECT_LE(differing, 20);
  EXPECT_EQ(shared->GetShadowMapBakerPass()->GetLightMaps(right).size(), 1u);
  EXPECT_EQ(shared->GetShadowMapBakerPass()->GetLightMaps(pair.Renderer).size(), 1u);
}

namespace
{
/// Lines along z drawn as tubes (LineWidth pixels) at height y, from z0 to z1.
vtkSmartPointer<vtkActor> TubeRow(double y, double z0, double z1, float pixels)
{
  std::vector<std::array<double, 6>> segments;
  for (int i = 0; i < 5; ++i)
  {
    const double x = -4.0 + 2.0 * i;
    segments.push_back({ x, y, z0, x, y, z1 });
  }
  vtkSmartPointer<vtkActor> actor = csmTest::SegmentsActor(segments, pixels, true);
  actor->GetProperty()->SetColor(0.9, 0.9, 0.9);
  return actor;
}

// Screen-sized casters (tubes drawn in the main view's pixels) have no fixed extent and cost
// their fragments: while one is in the scene there is no scene-fitted map.
TEST(Passes, ScreenSizedCastersGetNoSceneFittedMap)
{
  BoxOverPlane scene;
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
  auto lastFitted = [&]() {
    return baker->GetPlanner()->GetCascadeSceneFitted(
      baker->GetLightMaps().at(0).NumberOfCascades - 1);
  };
  scene.Frame();
  EXPECT_TRUE(lastFitted()); // the box alone
  vtkSmartPointer<vtkActor> tubes = TubeRow(2.0, -4.0, 4.0, 4.0f);
  scene.Renderer->AddActor(tubes);
  scene.Frame();
  EXPECT_FALSE(lastFitted());
  scene.Renderer->RemoveActor(tubes);
  scene.Frame();
  EXPECT_TRUE(lastFitted());
}

/// Pixels that differ from the background colour (0.2, 0.3, 0.4).
std::vector<char> Covered(vtkImageData* image)
{
  auto* p = vtkUnsignedCharArray::SafeDownCast(image->GetPointData()->GetScalars());
  const int nc = p->GetNumberOfComponents();
  std::vector<char> mask(p->GetNumberOfTuples());
  const int background[3] = { 51, 76, 102 };
  for (vtkIdType i = 0; i < p->GetNumberOfTuples(); ++i)
  {
    int off = 0;
    for (int c = 0; c < 3; ++c)
      off += std::abs(int(p->GetValue(nc * i + c)) - background[c]);
    mask[i] = off > 6;
  }
  return mask;
}

}

// Tubes receive shadows on the surface VTK draws: under a deck their lit side is dark; in the
// open they do not shadow themselves (the maps hold their centre line, their lit side is in
// front of it).
TEST(Passes, TubesUnderADeckAreDarkAndTubesInTheOpenAreNot)
{
  BoxOverPlane scene(640, 480);
  scene.Box->SetVisibility(false);
  vtkNew<vtkCubeSource> deckSource;
  deckSource->SetBounds(-6, 6, 4.5, 5, -6, 0);
  vtkNew<vtkPolyDataMapper> deckMapper;
  deckMapper->SetInputConnection(deckSource->GetOutputPort());
  vtkNew<vtkActor> deck;
  deck->SetMapper(deckMapper);
  vtkSmartPointer<vtkActor> covered = TubeRow(2.0, -5.0, -0.5, 10.0f);
  vtkSmartPointer<vtkActor> open = TubeRow(2.0, 0.5, 5.0, 10.0f);
  scene.Renderer->AddActor(deck);
  scene.Renderer->AddActor(covered);
  scene.Renderer->AddActor(open);
  scene.Renderer->AddLight(scene.Light);
  scene.Light->SetPosition(0.5, 10, 0.3); // from above, a little oblique
  vtkNew<vtkLight> fill;
  fill->SetLightTypeToHeadlight();
  fill->SetIntensity(0.2);
  scene.Renderer->AddLight(fill);

  // The screen pixels of each row of tubes, each drawn alone.
  scene.Ground->SetVisibility(false);
  deck->SetVisibility(false);
  open->SetVisibility(false);
  const std::vector<char> coveredMask = Covered(scene.Render());
  covered->SetVisibility(false);
  open->SetVisibility(true);
  const std::vector<char> openMask = Covered(scene.Render());
  scene.Ground->SetVisibility(true);
  deck->SetVisibility(true);
  covered->SetVisibility(true);

  auto plain = scene.Render();
  vtkCascadedShadowMapPass* tubePass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  if (const char* debug = std::getenv("CSM_TEST_DEBUG_VIEW"))
    tubePass->SetDebugMode(std::atoi(debug));
  auto shadowed = scene.Render();
  long coveredPixels = 0, openPixels = 0;
  const long coveredDark = DarkenedPixels(shadowed, plain, &coveredMask, &coveredPixels);
  const long openDark = DarkenedPixels(shadowed, plain, &openMask, &openPixels);
  if (const char* dir = std::getenv("CSM_TEST_IMAGES")) // to look at
  {
    vtkNew<vtkImageData> marked;
    marked->DeepCopy(shadowed);
    auto* m = vtkUnsignedCharArray::SafeDownCast(marked->GetPointData()->GetScalars());
    auto* pa = vtkUnsignedCharArray::SafeDownCast(shadowed->GetPointData()->GetScalars());
    auto* pb = vtkUnsignedCharArray::SafeDownCast(plain->GetPointData()->GetScalars());
    const int nc = m->GetNumberOfComponents();
    for (vtkIdType i = 0; i < m->GetNumberOfTuples(); ++i)
    {
      double la = 0, lb = 0;
      for (int c = 0; c < 3; ++c)
      {
        la += pa->GetValue(nc * i + c);
        lb += pb->GetValue(nc * i + c);
      }
      if (openMask[i] && csmTest::IsDarkened(la, lb))
      {
        m->SetValue(nc * i, 255);
        m->SetValue(nc * i + 1, 0);
        m->SetValue(nc * i + 2, 0);
      }
    }
    vtkNew<vtkPNGWriter> writer;
    writer->SetInputData(marked);
    writer->SetFileName((std::string(dir) + "/tubes-deck.png").c_str());
    writer->Write();
  }
  std::printf("tube pixels under the deck: %ld, darkened %ld; in the open: %ld, darkened %ld\n",
    coveredPixels, coveredDark, openPixels, openDark);
  ASSERT_GT(coveredPixels, 4000);
  ASSERT_GT(openPixels, 4000);
  EXPECT_GE(coveredDark, coveredPixels * 7 / 10);
  EXPECT_LE(openDark, openPixels / 100);
}

// Other mappers VTK draws with still cast shadows through the maps: opaque point-Gaussian
// splats (which VTK offsets in view space: the light camera's view faces the light), glyphs,
// and composite data.
TEST(Passes, SplatsGlyphsAndCompositeDataCastShadows)
{
  vtkNew<vtkPoints> points;
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k)
      points->InsertNextPoint(-4.5 + 3.0 * i, 3.0, -3.0 + 3.0 * k);
  vtkNew<vtkPolyData> centres;
  centres->SetPoints(points);

  vtkNew<vtkPointGaussianMapper> splats;
  splats->SetInputData(centres);
  splats->SetScaleFactor(0.8);
  splats->EmissiveOff();
  splats->SetSplatShaderCode("//VTK::Color::Impl\n"
                             "float dist = dot(offsetVCVSOutput.xy, offsetVCVSOutput.xy);\n"
                             "if (dist > 1.0) { discard; }\n");
  vtkNew<vtkSphereSource> ball;
  ball->SetRadius(0.8);
  vtkNew<vtkGlyph3DMapper> glyphs;
  glyphs->SetInputData(centres);
  glyphs->SetSourceConnection(ball->GetOutputPort());
  glyphs->ScalingOff();
  vtkNew<vtkMultiBlockDataSet> blocks;
  blocks->SetNumberOfBlocks(2);
  blocks->SetBlock(0, ball->GetOutput());
  ball->Update();
  vtkNew<vtkSphereSource> second;
  second->SetCenter(2.5, 0, 0);
  second->SetRadius(1.0);
  second->Update();
  blocks->SetBlock(0, ball->GetOutput());
  blocks->SetBlock(1, second->GetOutput());
  vtkNew<vtkCompositePolyDataMapper2> composite;
  composite->SetInputDataObject(blocks);

  const std::pair<const char*, vtkMapper*> mappers[] = { { "splats", splats },
    { "glyphs", glyphs }, { "composite", composite } };
  for (const auto& named : mappers)
  {
    BoxOverPlane scene;
    scene.Box->SetMapper(named.second);
    scene.Box->SetPosition(0, named.second == composite ? 3.0 : 0.0, 0);
    auto plain = scene.Render();
    vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
    auto shadowed = scene.Render();
    const long darkened = DarkenedPixels(shadowed, plain);
    std::printf("%s: %ld pixels darkened\n", named.first, darkened);
    EXPECT_GT(darkened, 500) << named.first;
  }
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

// A tube or sphere whose width is not a number (vtkProperty's clamped setter lets NaN through)
// is drawn into the maps one pixel wide: no garbage shadow, no crash.
TEST(Passes, NaNLineWidthAndPointSizeGiveNoGarbage)
{
  // The darkened pixels of the same lines at width 1 and at width NaN.
  long darkened[2] = { 0, 0 };
  for (int nan = 0; nan < 2; ++nan)
  {
    BoxOverPlane scene;
    scene.Box->SetVisibility(false);
    const float width = nan ? std::nanf("") : 1.0f;
    vtkSmartPointer<vtkActor> tubes = TubeRow(2.0, -4.0, 4.0, width);
    tubes->GetProperty()->SetPointSize(width);
    tubes->GetProperty()->RenderPointsAsSpheresOn();
    scene.Renderer->AddActor(tubes);
    auto plain = scene.Render();
    // (At the view-fitted maps: a hairline's shadow is a texel wide, and a scene-fitted map's
    // texels are finer.)
    vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer)
      ->GetShadowMapBakerPass()
      ->SceneFittedCascadesOff();
    auto shadowed = scene.Render();
    float sizes[2] = { 0, 0 };
    vtkCascadedShadowMapBakerPass::GetScreenSizes(tubes, sizes);
    EXPECT_EQ(sizes[0], 1.0f);
    EXPECT_EQ(sizes[1], 1.0f);
    darkened[nan] = DarkenedPixels(shadowed, plain);
  }
  std::printf("darkened pixels: width 1 %ld, width NaN %ld\n", darkened[0], darkened[1]);
  // Hairline shadows in both, and about as many.
  EXPECT_GT(darkened[0], 100);
  EXPECT_GE(darkened[1], darkened[0] / 2);
  EXPECT_LE(darkened[1], darkened[0] * 3 / 2);
}

// Resolution from need (issue: speed): a view that full maps oversample gets the maps its
// predicted error needs, and the shadow stays; ErrorTarget 0 renders every map at Resolution.
TEST(Passes, MapsHaveTheResolutionTheirErrorNeeds)
{
  BoxOverPlane scene; // 320 x 240: 2048-texel maps oversample it several times
  auto plain = scene.Render();
  // Pixels in shadow: less than half as bright as without shadows (the penumbra of a texel-space
  // filter widens on screen with the texels, the shadow's extent does not).
  auto halfDark = [&plain](vtkImageData* shadowed) {
    auto* a = vtkUnsignedCharArray::SafeDownCast(shadowed->GetPointData()->GetScalars());
    auto* b = vtkUnsignedCharArray::SafeDownCast(plain->GetPointData()->GetScalars());
    long n = 0;
    for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
    {
      const int sa = a->GetValue(3 * i) + a->GetValue(3 * i + 1) + a->GetValue(3 * i + 2);
      const int sb = b->GetValue(3 * i) + b->GetValue(3 * i + 1) + b->GetValue(3 * i + 2);
      n += sb > 30 && 2 * sa < sb;
    }
    return n;
  };
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
  baker->SceneFittedCascadesOff(); // (a scene-fitted map has all the texels of its tile)
  baker->SetErrorTarget(0.0);
  const long full = halfDark(scene.Render());
  for (int c = 0; c < baker->GetLightMaps().at(0).NumberOfCascades; ++c)
  {
    // (Its tile: NumberOfCascades of them share four full maps' texels.)
    const auto& full = baker->GetLightMaps().at(0);
    EXPECT_EQ(full.CascadeResolution[c][0], full.Resolution[0]);
    EXPECT_EQ(full.CascadeResolution[c][1], full.Resolution[1]);
  }
  baker->SetErrorTarget(1.0);
  const long needed = halfDark(scene.Render());
  const auto& maps = baker->GetLightMaps().at(0);
  vtkCascadedShadowMapPlanner* planner = baker->GetPlanner();
  long texels = 0;
  const int ceiling[2] = { baker->GetResolution(), baker->GetResolution() };
  for (int c = 0; c < maps.NumberOfCascades; ++c)
  {
    const int* r = maps.CascadeResolution[c];
    // The planner's choice for this 240-pixel-high view, and fewer texels than the ceiling.
    int planned[2] = { 0, 0 };
    planner->GetCascadeResolution(
      c, 240, vtkCascadedShadowMapBakerPass::RESOLUTION_STEP, ceiling, planned);
    for (int axis = 0; axis < 2; ++axis)
    {
      EXPECT_EQ(r[axis], planned[axis]);
      EXPECT_LT(r[axis], baker->GetResolution());
      EXPECT_EQ(r[axis] % vtkCascadedShadowMapBakerPass::RESOLUTION_STEP, 0);
    }
    // Predicted worst error at this resolution (the larger M along the longer side): at most
    // the target.
    EXPECT_LE(planner->GetCascadeMaximumAliasing(c) * 240 / std::max(r[0], r[1]), 1.0);
    texels += static_cast<long>(r[0]) * r[1];
  }
  std::printf("shadowed pixels: full maps %ld, maps from need %ld (%.1f %% of the texels)\n",
    full, needed, 100.0 * texels / (2.0 * baker->GetResolution() * baker->GetResolution()));
  EXPECT_GT(full, 800);
  EXPECT_NEAR(static_cast<double>(needed), static_cast<double>(full), 0.03 * full);
  // A larger window needs more texels (up to the ceiling).
  scene.Window->SetSize(960, 720);
  scene.Render();
  for (int c = 0; c < maps.NumberOfCascades; ++c)
  {
    int planned[2] = { 0, 0 };
    planner->GetCascadeResolution(
      c, 720, vtkCascadedShadowMapBakerPass::RESOLUTION_STEP, ceiling, planned);
    EXPECT_EQ(baker->GetLightMaps().at(0).CascadeResolution[c][0], planned[0]);
    EXPECT_EQ(baker->GetLightMaps().at(0).CascadeResolution[c][1], planned[1]);
  }
}

// Temporal stability (issue: accuracy): a still camera shows the same shadow every frame, the
// dithered blend band included (its pattern is fixed on the screen).
TEST(Passes, AStillCameraDoesNotFlicker)
{
  BoxOverPlane scene;
  auto plain = scene.Render();
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  pass->SetBlendBand(0.5); // a wide band: half of each cascade is dithered
  auto first = scene.Frame();
  EXPECT_GT(DarkenedPixels(first, plain), 800);
  for (int frame = 0; frame < 3; ++frame)
  {
    EXPECT_EQ(DifferingValues(scene.Frame(), first, 0), 0) << "frame " << frame;
  }
}

namespace
{
/// The depth a light's map holds at the atlas texel where a world point falls, and the map depth
/// of two world points (all in [0, 1]), from the cascade whose map contains the point.
struct MapDepths
{
  bool Found = false;
  float Held = 0.0f;
  double Of[2] = { 0.0, 0.0 };
};

MapDepths DepthsInMap(vtkRenderWindow* window, const vtkCascadedShadowMapBakerPass::LightMaps& maps,
  const double at[3], const double points[2][3])
{
  MapDepths result;
  const auto project = [](const double* m, const double p[3], double ndc[3])
  {
    double clip[4];
    for (int r = 0; r < 4; ++r)
      clip[r] = m[4 * r] * p[0] + m[4 * r + 1] * p[1] + m[4 * r + 2] * p[2] + m[4 * r + 3];
    for (int k = 0; k < 3; ++k)
      ndc[k] = clip[k] / clip[3];
  };
  for (int c = 0; c < maps.NumberOfCascades && !result.Found; ++c)
  {
    double ndc[3];
    project(maps.WorldToMap[c], at, ndc);
    if (std::abs(ndc[0]) > 0.9 || std::abs(ndc[1]) > 0.9)
      continue;
    const int width = static_cast<int>(maps.Atlas->GetWidth());
    const int height = static_cast<int>(maps.Atlas->GetHeight());
    std::vector<float> depth(static_cast<size_t>(width) * height);
    window->MakeCurrent();
    maps.Atlas->Bind();
    glGetTexImage(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT, GL_FLOAT, depth.data());
    const int x = static_cast<int>((maps.Tile[c][0] + (0.5 * ndc[0] + 0.5) * maps.Tile[c][2]) * width);
    const int y = static_cast<int>((maps.Tile[c][1] + (0.5 * ndc[1] + 0.5) * maps.Tile[c][3]) * height);
    result.Held = depth[static_cast<size_t>(y) * width + x];
    for (int i = 0; i < 2; ++i)
    {
      project(maps.WorldToMap[c], points[i], ndc);
      result.Of[i] = 0.5 * ndc[2] + 0.5;
    }
    result.Found = true;
  }
  return result;
}
} // namespace

TEST(Passes, ClosedCastersCastTheSameShadowsFromTheirExitLayer)
{
  // The box (closed) hangs over the ground (an open plane); beside it an open sheet faces the
  // light. Closed casters are drawn with the faces turned away from the light only: the same
  // shadows, the map holding the box's bottom (its exit layer) instead of its top. A mirrored
  // box (negative determinant) and a box wound inside out keep the same layer.
  for (int variant = 0; variant < 3; ++variant)
  {
    SCOPED_TRACE(variant == 0 ? "box" : variant == 1 ? "mirrored box" : "inside-out box");
    BoxOverPlane scene;
    vtkNew<vtkPlaneSource> sheet;
    sheet->SetOrigin(3.0, 3.0, -1.0);
    sheet->SetPoint1(3.0, 3.0, 1.0); // (Point1 - Origin) x (Point2 - Origin) = +y: toward the light
    sheet->SetPoint2(5.0, 3.0, -1.0);
    vtkNew<vtkPolyDataMapper> sheetMapper;
    sheetMapper->SetInputConnection(sheet->GetOutputPort());
    vtkNew<vtkActor> sheetActor;
    sheetActor->SetMapper(sheetMapper);
    scene.Renderer->AddActor(sheetActor);
    if (variant == 1)
    {
      scene.Box->SetScale(-1.0, 1.0, 1.0); // the box is centred on x = 0: same place
    }
    if (variant == 2)
    {
      vtkNew<vtkCubeSource> cube;
      cube->SetBounds(-1, 1, 2, 4, -1, 1);
      cube->Update();
      vtkNew<vtkPolyData> inverted;
      inverted->DeepCopy(cube->GetOutput());
      inverted->ReverseCell(0);
      for (vtkIdType i = 1; i < inverted->GetNumberOfCells(); ++i)
        inverted->ReverseCell(i);
      vtkNew<vtkPolyDataMapper> mapper;
      mapper->SetInputData(inverted);
      scene.Box->SetMapper(mapper);
    }
    auto plain = scene.Render();
    vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
    vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
    const double centre[3] = { 0.0, 3.0, 0.0 };
    const double faces[2][3] = { { 0.0, 2.0, 0.0 }, { 0.0, 4.0, 0.0 } }; // bottom, top

    baker->CullClosedCastersOff();
    const long bothSides = DarkenedPixels(scene.Render(), plain);
    EXPECT_EQ(baker->GetLastClosedCasters(), 0);
    const MapDepths before = DepthsInMap(scene.Window, baker->GetLightMaps()[0], centre, faces);

    baker->CullClosedCastersOn();
    const long exitLayer = DarkenedPixels(scene.Render(), plain);
    EXPECT_EQ(baker->GetLastClosedCasters(), 1); // the box; not the plane, not the sheet
    const MapDepths after = DepthsInMap(scene.Window, baker->GetLightMaps()[0], centre, faces);

    EXPECT_GT(bothSides, 1200); // the box's and the sheet's shadows
    EXPECT_LE(std::abs(exitLayer - bothSides), bothSides / 100);
    ASSERT_TRUE(before.Found && after.Found);
    // Both sides: the top (nearest the light); exit layer: the bottom. Within the polygon offset.
    const double gap = std::abs(before.Of[0] - before.Of[1]);
    EXPECT_GT(gap, 1e-4);
    EXPECT_LT(std::abs(before.Held - before.Of[1]), 0.1 * gap);
    EXPECT_LT(std::abs(after.Held - after.Of[0]), 0.1 * gap);
  }
}

TEST(Passes, BigCastersAreDrawnFromCompactBlocksWithTheSameShadows)
{
  // A row of spheres along the view as one polydata (one actor spanning every cascade), over a
  // finely tessellated ground: both are drawn into the maps from compact blocks, each cascade
  // drawing only the blocks that reach it, and the shadows are those of the props themselves.
  BoxOverPlaneSettings settings;
  settings.GroundHalfWidth = 40.0;
  settings.GroundResolution = 200; // 80,000 triangles
  BoxOverPlane scene(settings);
  vtkNew<vtkAppendPolyData> row;
  for (int i = 0; i < 32; ++i)
  {
    vtkNew<vtkSphereSource> sphere;
    sphere->SetCenter(3.0, 1.5, 6.0 - 2.0 * i);
    sphere->SetRadius(0.6);
    sphere->SetThetaResolution(32);
    sphere->SetPhiResolution(32);
    row->AddInputConnection(sphere->GetOutputPort());
  }
  row->Update();
  const vtkIdType rowTriangles = row->GetOutput()->GetNumberOfPolys();
  ASSERT_GT(rowTriangles, 3 * vtkCascadedShadowMapBakerPass::MINIMUM_BLOCK_TRIANGLES);
  vtkNew<vtkPolyDataMapper> rowMapper;
  rowMapper->SetInputConnection(row->GetOutputPort());
  vtkNew<vtkActor> rowActor;
  rowActor->SetMapper(rowMapper);
  scene.Renderer->AddActor(rowActor);
  auto plain = scene.Render();

  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
  baker->SetNumberOfCascades(3);
  baker->AdaptiveCascadesOff();
  baker->CullCastersWithoutReceiversOff(); // the ground's blocks are counted below
  baker->CompactCastersOff();
  auto whole = scene.Render();
  EXPECT_EQ(baker->GetLastCompactCasters(), 0);
  EXPECT_EQ(baker->GetLastBlocksDrawn(), 0);
  const long wholeDark = DarkenedPixels(whole, plain);

  baker->CompactCastersOn();
  auto blocks = scene.Render();
  ASSERT_EQ(baker->GetLastCascadeRenders(), 3);
  EXPECT_EQ(baker->GetLastCompactCasters(), 3); // the box, the ground, the row
  // Blocks: the box 1, the ground 80,000 / 16,384 -> 8 (median halving), the row 4; drawn into 3
  // cascades that would be 39. Each cascade draws only the blocks that reach it.
  EXPECT_EQ(baker->GetLastPropsDrawn(), baker->GetLastBlocksDrawn());
  EXPECT_GE(baker->GetLastBlocksDrawn(), 13);
  EXPECT_LT(baker->GetLastBlocksDrawn(), 39);
  const long blockDark = DarkenedPixels(blocks, plain);
  EXPECT_GT(wholeDark, 2000);
  EXPECT_LE(std::abs(blockDark - wholeDark), wholeDark / 200);
  EXPECT_LE(DifferingValues(blocks, whole, 8), 320 * 240 * 3 / 200);

  // The data changes: the blocks are built again (the row's shadow moves with it).
  vtkNew<vtkPolyData> moved;
  moved->DeepCopy(row->GetOutput());
  for (vtkIdType i = 0; i < moved->GetNumberOfPoints(); ++i)
  {
    double p[3];
    moved->GetPoint(i, p);
    moved->GetPoints()->SetPoint(i, p[0] - 6.0, p[1], p[2]);
  }
  rowMapper->SetInputData(moved);
  auto movedImage = scene.Render();
  baker->CompactCastersOff();
  auto movedWhole = scene.Render();
  EXPECT_GT(DifferingValues(movedImage, blocks, 8), 1000);
  EXPECT_LE(DifferingValues(movedImage, movedWhole, 8), 320 * 240 * 3 / 200);

  // What the blocks cannot draw as the prop does is drawn as it is: a wireframe prop.
  baker->CompactCastersOn();
  scene.Box->GetProperty()->SetRepresentationToWireframe();
  scene.Render();
  EXPECT_EQ(baker->GetLastCompactCasters(), 2);
}

TEST(Passes, MapCoordinatesFromTheVerticesGiveTheSameShadows)
{
  // The lookup's map coordinates interpolated from the vertices equal the fragment's matrix
  // products up to float rounding: the same shadow, a few edge pixels apart at most.
  BoxOverPlane scene;
  auto plain = scene.Render();
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
  EXPECT_FALSE(pass->GetMapCoordinatesFromVertices()); // the default
  baker->AdaptiveCascadesOff(); // the counts set here
  for (int cascades : { 2, 3, vtkCascadedShadowMapPlanner::MAXIMUM_NUMBER_OF_CASCADES })
  {
    baker->SetNumberOfCascades(cascades);
    pass->MapCoordinatesFromVerticesOff();
    auto products = scene.Render();
    EXPECT_EQ(pass->GetLastMapCoordinateVaryings(), 0);
    pass->MapCoordinatesFromVerticesOn();
    auto interpolated = scene.Render();
    EXPECT_EQ(pass->GetLastMapCoordinateVaryings(), cascades) << cascades << " cascades";
    const long dark = DarkenedPixels(products, plain);
    EXPECT_GT(dark, 1000) << cascades << " cascades"; // the box's shadow: ~1250 pixels
    EXPECT_LE(std::abs(DarkenedPixels(interpolated, plain) - dark), dark / 200);
    EXPECT_LE(DifferingValues(interpolated, products, 8), 320 * 240 * 3 / 1000)
      << cascades << " cascades";
  }
  // Up to eight cascades allowed, at most four used: four coordinates interpolated (the eight
  // are compiled in only while a light uses more than four).
  baker->AdaptiveCascadesOn();
  scene.Render();
  ASSERT_LE(baker->GetLightMaps().at(0).NumberOfCascades, 4);
  EXPECT_EQ(pass->GetLastMapCoordinateVaryings(), 4);

  // More varyings than the limit (two lights of 8 cascades): the fragment multiplies.
  BoxOverPlane two;
  vtkNew<vtkLight> second;
  second->SetLightTypeToSceneLight();
  second->SetPositional(false);
  second->SetPosition(-6, 10, 2);
  second->SetFocalPoint(0, 0, 0);
  two.Renderer->AddLight(second);
  auto twoPlain = two.Render();
  vtkCascadedShadowMapPass* twoPass = vtkCascadedShadowMapPass::UseShadowsOn(two.Renderer);
  twoPass->MapCoordinatesFromVerticesOn();
  twoPass->GetShadowMapBakerPass()->SetNumberOfCascades(
    vtkCascadedShadowMapPlanner::MAXIMUM_NUMBER_OF_CASCADES);
  two.Render();
  EXPECT_EQ(twoPass->GetLastMapCoordinateVaryings(), 4); // two lights of at most four used
  twoPass->GetShadowMapBakerPass()->AdaptiveCascadesOff(); // eight each
  auto both = two.Render();
  ASSERT_EQ(twoPass->GetShadowMapBakerPass()->GetLightMaps().size(), 2u);
  EXPECT_EQ(twoPass->GetLastMapCoordinateVaryings(), 0);
  EXPECT_GT(DarkenedPixels(both, twoPlain), 300); // two half-dark shadows: ~420 pixels
}

namespace
{
/// An actor of a box with the given bounds, in grey.
vtkSmartPointer<vtkActor> BoxActor(double xmin, double xmax, double ymin, double ymax,
  double zmin, double zmax)
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

// Issue 15, item 1: the cascades begin at the nearest visible sample, not where the scene's
// boxes meet the view (here one prop's box holds the camera: a block behind it and the box in
// front of it are one polydata).
TEST(Passes, VisibleDepthFitStartsTheCascadesAtTheNearestSample)
{
  BoxOverPlane scene;
  vtkNew<vtkCubeSource> behind, front;
  behind->SetBounds(-1, 1, 13, 15, 18, 20); // behind the camera at (0, 14, 16)
  front->SetBounds(-1, 1, 2, 4, -1, 1);
  vtkNew<vtkAppendPolyData> both;
  both->AddInputConnection(behind->GetOutputPort());
  both->AddInputConnection(front->GetOutputPort());
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(both->GetOutputPort());
  scene.Box->SetMapper(mapper);
  scene.Renderer->ResetCameraClippingRange();
  auto plain = scene.Render();
  vtkCamera* camera = scene.Renderer->GetActiveCamera();
  const double cameraNear = camera->GetClippingRange()[0];

  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
  baker->SceneFittedCascadesOff(); // (the cascades that follow the view)
  baker->VisibleDepthFitOff();
  auto boxes = scene.Frame();
  const double boxesNear = baker->GetLightMaps()[0].SplitNear;
  EXPECT_FALSE(baker->GetLastVisibleDepthsUsed());
  EXPECT_LT(boxesNear, 1.01 * cameraNear); // the box around the two blocks holds the eye

  baker->VisibleDepthFitOn();
  const int measures = baker->GetVisibleDepthMeasures();
  auto fitted = scene.Frame(); // measured in the frame it serves
  EXPECT_TRUE(baker->GetLastVisibleDepthsUsed());
  EXPECT_EQ(baker->GetVisibleDepthMeasures(), measures + 1);
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
  EXPECT_EQ(baker->GetVisibleDepthMeasures(), measures + 1);
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
  ASSERT_TRUE(baker->GetLastVisibleDepthsUsed());
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
  const std::vector<char> nearer = NearerThan(scene.Window, scene.Renderer->GetActiveCamera(), fittedNear);
  EXPECT_TRUE(baker->GetLastVisibleDepthsUsed());
  EXPECT_LT(baker->GetLightMaps()[0].SplitNear, 0.8 * fittedNear);
  auto fresh = reference.Frame();
  EXPECT_EQ(DifferingValues(image, fresh), 0);
  // The cube's shadow on the shelf, nearer than the last frame's nearest sample.
  long shelfPixels = 0;
  EXPECT_GT(DarkenedPixels(image, plain, &nearer, &shelfPixels), 150);
  EXPECT_GT(shelfPixels, 2000);
}

// Issue 12: face partitioning as a comparison technique. The light 10 degrees from behind the
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
  EXPECT_FALSE(baker->GetLightMaps()[0].Faces);
  baker->SetFacePartitions(1);
  const long faces = DarkenedPixels(scene.Render(), plain);
  ASSERT_EQ(baker->GetLightMaps().size(), 1u);
  EXPECT_TRUE(baker->GetLightMaps()[0].Faces);
  EXPECT_EQ(baker->GetLightMaps()[0].NumberOfCascades, 4);
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
  baker->SetFacePartitions(0);
  pass->SetDebugMode(vtkCascadedShadowMapPass::DEBUG_OFF);
  EXPECT_EQ(DarkenedPixels(scene.Render(), plain), cascaded);
  EXPECT_FALSE(baker->GetLightMaps()[0].Faces);
}

// Face partitions need a directional light and a perspective camera: a spot light and a
// parallel view keep the cascades (and their shadows).
TEST(Passes, FacePartitionsFallBackToCascadesWhereTheyDoNotApply)
{
  BoxOverPlane scene;
  auto plain = scene.Render();
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
  baker->SetFacePartitions(2);
  EXPECT_EQ(baker->GetFacePartitions(), 2);
  baker->SetFacePartitions(99); // clamped
  EXPECT_EQ(baker->GetFacePartitions(), vtkCascadedShadowMapPlanner::MAXIMUM_FACE_Z_PARTITIONS);
  vtkCamera* camera = scene.Renderer->GetActiveCamera();
  camera->ParallelProjectionOn();
  camera->SetParallelScale(8.0);
  scene.Render();
  ASSERT_EQ(baker->GetLightMaps().size(), 1u);
  EXPECT_FALSE(baker->GetLightMaps()[0].Faces);
  EXPECT_GT(baker->GetLightMaps()[0].NumberOfCascades, 0);
  camera->ParallelProjectionOff();
  scene.Render();
  EXPECT_TRUE(baker->GetLightMaps()[0].Faces); // back in perspective: face partitions
  scene.Light->SetPositional(true);
  scene.Light->SetPosition(0, 10, 0);
  scene.Light->SetConeAngle(40);
  const long spot = DarkenedPixels(scene.Render(), plain);
  ASSERT_EQ(baker->GetLightMaps().size(), 1u);
  EXPECT_FALSE(baker->GetLightMaps()[0].Faces);
  EXPECT_GT(spot, 300);
}

// Issue 12: camera space shadow maps (Kolić & Mihajlović). The general case: one map whose
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
  EXPECT_EQ(baker->GetLightMaps()[0].DepthW[0], 0.0);
  baker->CameraSpaceOn();
  const long cssm = DarkenedPixels(scene.Render(), plain);
  ASSERT_EQ(baker->GetLightMaps().size(), 1u);
  EXPECT_EQ(baker->GetLightMaps()[0].NumberOfCascades, 1);
  EXPECT_GT(baker->GetLightMaps()[0].DepthW[0], 0.0);
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
  baker->CameraSpaceOff();
  const long behindCascaded = DarkenedPixels(scene.Render(), plain);
  baker->CameraSpaceOn();
  const long behind = DarkenedPixels(scene.Render(), plain);
  const auto& maps = baker->GetLightMaps()[0];
  EXPECT_EQ(maps.NumberOfCascades, 4);
  EXPECT_TRUE(maps.Faces);
  for (int c = 0; c < 4; ++c)
    EXPECT_GT(maps.DepthW[c], 0.0);
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
  std::vector<double> standardMatrix(
    baker->GetLightMaps()[0].WorldToMap[0], baker->GetLightMaps()[0].WorldToMap[0] + 16);
  baker->CameraSpaceOn();
  auto cssmImage = scene.Render();
  const long cssm = DarkenedPixels(cssmImage, plain);
  ASSERT_EQ(baker->GetLightMaps().size(), 1u);
  const auto& maps = baker->GetLightMaps()[0];
  EXPECT_EQ(maps.NumberOfCascades, 1);
  // Another map: its shadow edges fall on other pixels.
  EXPECT_GT(DifferingValues(standardImage, cssmImage, 8), 0);
  EXPECT_FALSE(std::equal(standardMatrix.begin(), standardMatrix.end(), maps.WorldToMap[0]));
  EXPECT_GT(standard, 500);
  EXPECT_NEAR(cssm, standard, 0.05 * standard);
  std::printf("spot light: standard map %ld darkened pixels, camera space map %ld; %ld values "
              "differ\n", standard, cssm, static_cast<long>(DifferingValues(standardImage, cssmImage, 8)));
  // The light in the view (in front of the camera, facing the ground): the standard map.
  scene.Light->SetPosition(0, 4, 4);
  baker->CameraSpaceOff();
  scene.Render();
  standardMatrix.assign(
    baker->GetLightMaps()[0].WorldToMap[0], baker->GetLightMaps()[0].WorldToMap[0] + 16);
  baker->CameraSpaceOn();
  scene.Render();
  EXPECT_TRUE(std::equal(
    standardMatrix.begin(), standardMatrix.end(), baker->GetLightMaps()[0].WorldToMap[0]));
}
