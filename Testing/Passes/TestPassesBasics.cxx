// SPDX-License-Identifier: BSD-3-Clause
// The passes in a real GL context (Mesa llvmpipe through OSMesa, no X server; Xvfb in a build
// without OSMesa), the basics: the shadow appears, the maps are re-rendered when something
// changed and only then, the renderer keeps working as without the passes (translucency,
// picking, several viewports, windows of any shape), and bad input gives no garbage.
#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCascadedShadowMapBakerPass.h"
#include "vtkCascadedShadowMapPass.h"
#include "vtkCommand.h"
#include "vtkHardwareSelector.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSelection.h"
#include "vtkSphereSource.h"
#include "vtkTextureObject.h"
#include "vtkUnsignedCharArray.h"

#include "csmTestHelpers.h"

#include <gtest/gtest.h>

#include <cmath>

namespace
{
using csmTest::BoxOverPlane;
using csmTest::DarkenedPixels;
using csmTest::DifferingPixels;
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
  EXPECT_EQ(pass->GetShadowMapBakerPass()->GetLightMaps()[0].GetNumberOfCascades(), 1);
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
  baker->GetPlanner()->SceneFittedCascadesOff();
  baker->LightSpacePagesOff(); // (the cascades' own behaviour)
  // (Window renders only: grabbing an image renders with a copy of the camera. Two warm-up
  // frames: anything the first frame creates, such as an actor's default property, is a change.)
  scene.Window->Render();
  scene.Window->Render();
  auto rendered = [&]()
  {
    scene.Window->Render();
    return baker->GetLastFrameStatistics().CascadesRendered;
  };
  EXPECT_EQ(rendered(), 0);
  EXPECT_EQ(rendered(), 0); // nothing changed
  scene.Renderer->GetActiveCamera()->Azimuth(10);
  EXPECT_GT(rendered(), 0); // the camera moved
  scene.Light->SetPosition(1, 10, 0);
  EXPECT_GT(rendered(), 0); // the light moved
  scene.Box->SetPosition(0.5, 0, 0);
  scene.Window->Render(); // a prop moved: its maps drawn again, whole or where it was and is
  EXPECT_GT(baker->GetLastFrameStatistics().TexelsRendered, 0.0);
  scene.Window->SetSize(300, 200);
  EXPECT_GT(rendered(), 0); // the window changed shape
  pass->SetPCFSize(5);
  EXPECT_EQ(rendered(), 0); // a lookup option needs no new maps
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
  const int n = baker->GetLightMaps().at(0).GetNumberOfCascades();
  ASSERT_GE(n, 1);
  EXPECT_EQ(baker->GetLastFrameStatistics().CascadesRendered, n);
  EXPECT_GT(baker->GetLastFrameStatistics().PlanSeconds, 0.0);
  double parts = baker->GetLastFrameStatistics().ClearSeconds;
  for (int c = 0; c < n; ++c)
  {
    EXPECT_GT(baker->GetLastFrameStatistics().GetCascadeSeconds(c), 0.0) << c;
    parts += baker->GetLastFrameStatistics().GetCascadeSeconds(c);
  }
  EXPECT_EQ(baker->GetLastFrameStatistics().GetCascadeSeconds(n), 0.0);
  EXPECT_EQ(baker->GetLastFrameStatistics().GetCascadeSeconds(-1), 0.0);
  EXPECT_EQ(baker->GetLastFrameStatistics().GetCascadeSeconds(1000), 0.0);
  // Structure only: every part was timed (how long each took is the benchmark's business).
  EXPECT_GT(parts, 0.0);
  EXPECT_GT(baker->GetLastFrameStatistics().MapSeconds, 0.0);
  scene.Window->Render(); // nothing changed: every map kept
  EXPECT_EQ(baker->GetLastFrameStatistics().CascadesRendered, 0);
  for (int c = 0; c < n; ++c)
  {
    EXPECT_EQ(baker->GetLastFrameStatistics().GetCascadeSeconds(c), 0.0) << c;
  }
  baker->MeasureTimesOff();
  scene.Box->SetPosition(0.25, 0, 0); // a prop moved: every map again, not timed
  scene.Window->Render();
  EXPECT_EQ(baker->GetLastFrameStatistics().CascadesRendered,
    baker->GetLightMaps().at(0).GetNumberOfCascades());
  EXPECT_EQ(baker->GetLastFrameStatistics().MapSeconds, 0.0);
  EXPECT_EQ(baker->GetLastFrameStatistics().GetCascadeSeconds(0), 0.0);
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
  auto cascades = [baker]() { return baker->GetLightMaps().at(0).GetNumberOfCascades(); };
  EXPECT_EQ(baker->GetLastFrameStatistics().CascadesRendered, 0);
  EXPECT_GE(cascades(), 1);
  EXPECT_EQ(baker->GetLastFrameStatistics().CascadesKept, cascades());
  scene.Box->SetPosition(0.3, 0, 0);
  scene.Frame();
  EXPECT_EQ(baker->GetLastFrameStatistics().CascadesRendered, cascades());
  scene.Light->SetPosition(1, 10, 0);
  scene.Frame();
  EXPECT_EQ(baker->GetLastFrameStatistics().CascadesRendered, cascades());
  baker->SetPolygonOffset(1.1, 3.0);
  scene.Frame();
  EXPECT_EQ(baker->GetLastFrameStatistics().CascadesRendered, cascades());
  scene.Frame();
  EXPECT_EQ(baker->GetLastFrameStatistics().CascadesRendered, 0);
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

TEST(Passes, ResolutionAndCascadesCanChangeBetweenFrames)
{
  BoxOverPlane scene;
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  pass->GetShadowMapBakerPass()->LightSpacePagesOff(); // (the cascades' own behaviour)
  vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
  auto plain = scene.Render();
  baker->GetPlanner()
    ->AdaptiveCascadesOff(); // the counts set here, not the fewest that meet the target
  baker->SetResolution(512);
  baker->GetPlanner()->SetNumberOfCascades(1);
  auto one = scene.Render();
  ASSERT_EQ(baker->GetLightMaps().size(), 1u);
  EXPECT_EQ(baker->GetLightMaps()[0].Atlas->GetWidth(), 512u);
  EXPECT_EQ(baker->GetLightMaps()[0].GetNumberOfCascades(), 1);
  baker->SetResolution(1024);
  baker->GetPlanner()->SetNumberOfCascades(6);
  auto six = scene.Render();
  // Four full tiles at most, 2 x 2: six cascades share that area, 2 x 3 tiles of 1024 x 682.
  const auto& maps = baker->GetLightMaps()[0];
  EXPECT_EQ(maps.Atlas->GetWidth(), 2048u);
  EXPECT_EQ(maps.Atlas->GetHeight(), 2048u);
  ASSERT_EQ(maps.GetNumberOfCascades(), 6);
  for (int c = 0; c < 6; ++c)
  {
    EXPECT_LE(maps.Cascades[c].Resolution[0], 1024) << c;
    EXPECT_LE(maps.Cascades[c].Resolution[1], 682) << c;
    EXPECT_EQ(maps.Cascades[c].Tile[0], (c % 2) * 1024) << c;
    EXPECT_EQ(maps.Cascades[c].Tile[1], (c / 2) * 682) << c;
    EXPECT_EQ(maps.Cascades[c].Tile[2], 1024) << c;
    EXPECT_EQ(maps.Cascades[c].Tile[3], 682) << c;
  }
  pass->SetPCFSize(1);
  auto hard = scene.Render();
  // A reallocated atlas must behave exactly like a first one (its compare mode and filters are
  // sent again to the new texture): compare with a fresh pass made with the final settings.
  baker->SetResolution(512);
  baker->GetPlanner()->SetNumberOfCascades(1);
  pass->SetPCFSize(5);
  auto reallocated = scene.Render();
  {
    BoxOverPlane fresh;
    vtkCascadedShadowMapPass* first = vtkCascadedShadowMapPass::UseShadowsOn(fresh.Renderer);
    first->GetShadowMapBakerPass()->LightSpacePagesOff();
    first->GetShadowMapBakerPass()->GetPlanner()->AdaptiveCascadesOff();
    first->GetShadowMapBakerPass()->SetResolution(512);
    first->GetShadowMapBakerPass()->GetPlanner()->SetNumberOfCascades(1);
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
        crop->SetScalarComponentFromDouble(
          x, y, 0, c, wd->GetScalarComponentAsDouble(x + 300, y, 0, c));
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

// A translucent closed surface is not in the maps, so it is not a surface drawn into them from
// behind (whose lit side takes almost no bias) and its far faces, seen through its near ones, are
// lit inside. With nothing else casting, the frame is the one without shadows.
TEST(Passes, ATranslucentClosedSurfaceIsLitInside)
{
  BoxOverPlane scene;
  scene.Box->SetVisibility(false);
  scene.Light->SetPosition(2, 10, 5);
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(0, 3, 0);
  sphere->SetRadius(3);
  sphere->SetThetaResolution(48);
  sphere->SetPhiResolution(24);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(sphere->GetOutputPort());
  vtkNew<vtkActor> glass;
  glass->SetMapper(mapper);
  glass->GetProperty()->SetColor(1.0, 0.3, 0.3);
  glass->GetProperty()->SetOpacity(0.4);
  scene.Renderer->AddActor(glass);
  auto plain = scene.Render();
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  auto shadowed = scene.Render();
  EXPECT_FALSE(pass->GetShadowMapBakerPass()->DrawsFromBehind(glass));
  EXPECT_EQ(DifferingValues(shadowed, plain), 0);
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

// A renderer whose viewport has no pixels beside one that has: nothing to shadow there, no
// message (the planner said the view angle was wrong), and the other renderer's shadow stays.
TEST(Passes, AViewportOfNoPixelsIsLeftAlone)
{
  BoxOverPlane pair(640, 240);
  pair.Renderer->SetViewport(0, 0, 0.5, 1);
  vtkNew<vtkRenderer> empty;
  empty->SetViewport(0.5, 0.5, 0.5, 0.5);
  empty->AutomaticLightCreationOff();
  empty->AddLight(pair.Light);
  empty->AddActor(pair.Box);
  empty->AddActor(pair.Ground);
  pair.Window->AddRenderer(empty);
  auto plain = pair.Render();
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(pair.Renderer);
  empty->SetPass(pair.Renderer->GetPass());
  vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
  ErrorCounter passErrors(pass), bakerErrors(baker), plannerErrors(baker->GetPlanner());
  ErrorCounter passWarnings(pass, vtkCommand::WarningEvent),
    bakerWarnings(baker, vtkCommand::WarningEvent);
  pair.Frame();
  auto shadowed = pair.Render();
  EXPECT_EQ(passErrors.Count + bakerErrors.Count + plannerErrors.Count, 0);
  EXPECT_EQ(passWarnings.Count + bakerWarnings.Count, 0);
  EXPECT_GT(DarkenedPixels(shadowed, plain), 800);
  EXPECT_TRUE(baker->GetLightMaps(empty).empty());
}

// A shadow pass without a baker draws the scene without shadows and says so, once.
TEST(Passes, NoBakerSaysSoOnce)
{
  BoxOverPlane scene;
  auto plain = scene.Render();
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  pass->SetShadowMapBakerPass(nullptr);
  ErrorCounter warnings(pass, vtkCommand::WarningEvent), errors(pass);
  scene.Frame();
  auto image = scene.Frame();
  EXPECT_EQ(warnings.Count, 1);
  EXPECT_EQ(errors.Count, 0);
  EXPECT_EQ(DifferingValues(image, plain, 2), 0);
}

// A baker set on the shadow pass but not in the renderer's pass sequence renders nothing: the
// pass says so once and draws the frame as without shadows.
TEST(Passes, ABakerOutsideTheSequenceSaysSoOnce)
{
  BoxOverPlane scene;
  auto plain = scene.Render();
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  scene.Frame();
  ErrorCounter warnings(pass, vtkCommand::WarningEvent), errors(pass);
  scene.Renderer->GetActiveCamera()->Azimuth(5.0);
  scene.Frame(); // (its own baker: no message)
  EXPECT_EQ(warnings.Count, 0);
  vtkNew<vtkCascadedShadowMapBakerPass> outside;
  pass->SetShadowMapBakerPass(outside);
  scene.Renderer->GetActiveCamera()->Azimuth(-5.0);
  scene.Frame();
  auto image = scene.Frame();
  EXPECT_EQ(warnings.Count, 1);
  EXPECT_EQ(errors.Count, 0);
  EXPECT_EQ(DifferingValues(image, plain, 2), 0);
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
  EXPECT_TRUE(pass->GetShadowMapBakerPass()->GetLightMaps().empty());
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

// NaN through the clamped setters would turn the whole view black (darkness, biases) or
// silently break the blend band and the polygon offset: a value that is not finite is refused.
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
  baker->SetPolygonOffset(NAN, 2.0);
  baker->SetPolygonOffset(1.1, INFINITY);
  baker->SetPlanner(nullptr);
  EXPECT_EQ(passErrors.Count, 5);
  EXPECT_EQ(bakerErrors.Count, 3);
  EXPECT_NE(baker->GetPlanner(), nullptr);
  EXPECT_DOUBLE_EQ(pass->GetShadowDarkness(), 1.0);
  EXPECT_DOUBLE_EQ(pass->GetConstantBias(), 0.002);
  EXPECT_DOUBLE_EQ(pass->GetSlopeBias(), 1.5);
  EXPECT_DOUBLE_EQ(pass->GetBlendBand(), 0.05);
  EXPECT_DOUBLE_EQ(baker->GetPolygonOffset()[0], 1.1);
  EXPECT_DOUBLE_EQ(baker->GetPolygonOffset()[1], 2.0);
  EXPECT_EQ(DifferingValues(scene.Render(), before), 0);
}

// The dithered blend band at a cascade border leaves the shadow across the border dark.
// A camera whose projection the maps do not follow (off-axis, or an explicit matrix) is said
// once, as a warning, and the frames go on; back on axis, the shadow is there again.
TEST(Passes, AnOffAxisCameraIsReportedOnce)
{
  BoxOverPlane scene;
  auto plain = scene.Render();
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  ErrorCounter warnings(pass->GetShadowMapBakerPass(), vtkCommand::WarningEvent);
  ErrorCounter errors(pass->GetShadowMapBakerPass());
  vtkCamera* camera = scene.Renderer->GetActiveCamera();
  camera->SetUseOffAxisProjection(1);
  for (int frame = 0; frame < 3; ++frame)
  {
    scene.Frame();
  }
  EXPECT_EQ(warnings.Count, 1);
  EXPECT_EQ(errors.Count, 0);
  camera->SetUseOffAxisProjection(0);
  EXPECT_GT(DarkenedPixels(scene.Render(), plain), 800);
  EXPECT_EQ(warnings.Count, 1);
}

// An explicit projection that is the camera's own (as a compositor hands every process the
// whole view) is no reason for a warning; the shadows are the camera's.
TEST(Passes, AnExplicitProjectionThatIsTheCamerasOwnSaysNothing)
{
  BoxOverPlane scene;
  auto plain = scene.Render();
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  ErrorCounter warnings(pass->GetShadowMapBakerPass(), vtkCommand::WarningEvent);
  vtkCamera* camera = scene.Renderer->GetActiveCamera();
  vtkNew<vtkMatrix4x4> own;
  own->DeepCopy(camera->GetProjectionTransformMatrix(scene.Renderer->GetTiledAspectRatio(), -1, 1));
  camera->SetExplicitProjectionTransformMatrix(own);
  camera->SetUseExplicitProjectionTransformMatrix(true);
  EXPECT_GT(DarkenedPixels(scene.Render(), plain), 800);
  EXPECT_EQ(warnings.Count, 0);
  own->SetElement(0, 2, 0.3); // shifted: now it is not the camera's
  scene.Render();
  EXPECT_EQ(warnings.Count, 1);
}

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
  EXPECT_GE(blended, hard - 10); // a band that lights the shadow loses 30-210 of its pixels
}

// Temporal stability: a still camera shows the same shadow every frame, the
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

// One actor shown in two windows (VTK builds its mapper's buffers in the window that draws it
// and releases them in the one that made them, its context made current for a while): each
// window draws it as a window of its own would, with shadows or without, frame after frame.
// The headless window left the other's context current after that release, and the next draw
// crashed inside the rasterizer.
TEST(Passes, AnActorShownInTwoWindowsIsDrawnInBoth)
{
  BoxOverPlane own;
  vtkCascadedShadowMapPass::UseShadowsOn(own.Renderer);
  const auto expected = own.Render();
  vtkCascadedShadowMapPass::UseShadowsOff(own.Renderer);
  const auto expectedPlain = own.Render();
  for (const bool bothShadowed : { false, true })
  {
    BoxOverPlane first, second;
    second.Renderer->RemoveActor(second.Box);
    second.Renderer->AddActor(first.Box);
    if (bothShadowed)
    {
      vtkCascadedShadowMapPass::UseShadowsOn(first.Renderer);
    }
    first.Render();
    vtkCascadedShadowMapPass::UseShadowsOn(second.Renderer);
    for (int frame = 0; frame < 3; ++frame)
    {
      EXPECT_EQ(DifferingPixels(second.Render(), expected, 0), 0) << bothShadowed << frame;
      EXPECT_EQ(DifferingPixels(first.Render(), bothShadowed ? expected : expectedPlain, 0), 0)
        << bothShadowed << frame;
    }
  }
}

// UseShadowsOn on a renderer that has them returns the pass it has, its options kept; after
// UseShadowsOff, a new one.
TEST(Passes, UseShadowsOnTwiceKeepsThePassAndItsOptions)
{
  BoxOverPlane scene;
  vtkCascadedShadowMapPass* first = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  ASSERT_NE(first, nullptr);
  first->SetPCFSize(5);
  scene.Render();
  EXPECT_EQ(vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer), first);
  EXPECT_EQ(first->GetPCFSize(), 5);
  vtkCascadedShadowMapPass::UseShadowsOff(scene.Renderer);
  vtkCascadedShadowMapPass* again = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  ASSERT_NE(again, nullptr);
  EXPECT_EQ(again->GetPCFSize(), 3);
  EXPECT_EQ(vtkCascadedShadowMapPass::UseShadowsOn(nullptr), nullptr);
}
