// SPDX-License-Identifier: BSD-3-Clause
// The casters: which props are drawn into which maps (culling by cascade, casters that shadow
// nothing, compact blocks of big props), closed casters drawn from behind, and casters VTK
// draws in the view's pixels or through other mappers (tubes, spheres, splats, glyphs,
// composite data).
#include "vtkActor.h"
#include "vtkAppendPolyData.h"
#include "vtkCamera.h"
#include "vtkCascadedShadowMapBakerPass.h"
#include "vtkCascadedShadowMapPass.h"
#include "vtkCascadedShadowMapPlanner.h"
#include "vtkCompositePolyDataMapper2.h"
#include "vtkCubeSource.h"
#include "vtkGlyph3DMapper.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkPNGWriter.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPointGaussianMapper.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"
#include "vtkStripper.h"
#include "vtkTextureObject.h"
#include "vtkTriangleFilter.h"
#include "vtkUnsignedCharArray.h"
#include "vtk_glew.h"

#include "csmProps.h" // csmScreenSizes
#include "csmTestHelpers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

namespace
{
using csmTest::BoxOverPlane;
using csmTest::BoxOverPlaneSettings;
using csmTest::DarkenedPixels;
using csmTest::DifferingValues;
} // namespace

TEST(Passes, CastersOutsideACascadeAreNotDrawnIntoIt)
{
  BoxOverPlane scene;
  // A second box far along the view: it cannot reach the near cascade's light volume.
  scene.Renderer->AddActor(csmTest::BoxActor(-1, 1, 0, 2, -60, -58));
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(-10, 0, -70);
  plane->SetPoint1(10, 0, -70);
  plane->SetPoint2(-10, 0, 10);
  vtkPolyDataMapper::SafeDownCast(scene.Ground->GetMapper())
    ->SetInputConnection(plane->GetOutputPort());
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
  baker->LightSpacePagesOff(); // (the cascades' own behaviour)
  baker->GetPlanner()->SetNumberOfCascades(3);
  baker->GetPlanner()->AdaptiveCascadesOff();
  baker->CullCastersWithoutReceiversOff(); // the ground is counted below
  scene.Frame();
  ASSERT_EQ(baker->GetLastFrameStatistics().CascadesRendered, 3);
  // 3 casters x 3 cascades would be 9 draws; culling must save some.
  EXPECT_LT(baker->GetLastFrameStatistics().PropsDrawn, 9);
  EXPECT_GE(baker->GetLastFrameStatistics().PropsDrawn, 3);
}

// A ground plane under everything shadows nothing: it is left out of the maps, the shadows stay.
TEST(Passes, CastersThatShadowNothingAreLeftOutOfTheMaps)
{
  BoxOverPlane scene;
  auto plain = scene.Render();
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  pass->GetShadowMapBakerPass()->LightSpacePagesOff(); // (the cascades' own behaviour)
  vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
  baker->SetResolution(1024);
  baker->GetPlanner()->SetNumberOfCascades(2);
  baker->GetPlanner()->AdaptiveCascadesOff();
  auto without = scene.Frame();
  ASSERT_GT(baker->GetLastFrameStatistics().CascadesRendered, 0);
  // The plane (planar: it cannot shadow itself; the box floats above it) is left out of every
  // cascade, the box is drawn.
  EXPECT_GE(
    baker->GetLastFrameStatistics().CastersWithoutReceivers, 1); // where the box reaches a cascade
  EXPECT_EQ(
    baker->GetLastFrameStatistics().PropsDrawn, baker->GetLastFrameStatistics().CascadesRendered);
  EXPECT_GT(DarkenedPixels(without, plain), 800);
  // The same image as with the plane drawn into the maps.
  baker->CullCastersWithoutReceiversOff();
  auto with = scene.Frame();
  EXPECT_EQ(baker->GetLastFrameStatistics().CastersWithoutReceivers, 0);
  EXPECT_EQ(baker->GetLastFrameStatistics().PropsDrawn,
    2 * baker->GetLastFrameStatistics().CascadesRendered);
  EXPECT_LE(csmTest::DifferingPixels(without, with, 8), 20);
  baker->CullCastersWithoutReceiversOn();
  // The box reaching through the plane: the plane shadows its lower part, so it is drawn.
  vtkNew<vtkCubeSource> deep;
  deep->SetBounds(-1, 1, -2, 4, -1, 1);
  vtkPolyDataMapper::SafeDownCast(scene.Box->GetMapper())
    ->SetInputConnection(deep->GetOutputPort());
  scene.Frame();
  EXPECT_EQ(baker->GetLastFrameStatistics().CastersWithoutReceivers, 0);
  // Light from below the plane: the plane shadows the box and is drawn; the box (convex, over
  // nothing else along this light) is left out.
  vtkNew<vtkCubeSource> above;
  above->SetBounds(-1, 1, 2, 4, -1, 1);
  vtkPolyDataMapper::SafeDownCast(scene.Box->GetMapper())
    ->SetInputConnection(above->GetOutputPort());
  scene.Frame();
  EXPECT_EQ(baker->GetLastFrameStatistics().CastersWithoutReceivers,
    baker->GetLastFrameStatistics().CascadesRendered);
  scene.Light->SetPosition(0, -10, 0);
  scene.Frame();
  EXPECT_GT(baker->GetLastFrameStatistics().CascadesRendered, 0);
  EXPECT_GE(
    baker->GetLastFrameStatistics().CastersWithoutReceivers, 1); // where the box reaches a cascade
  EXPECT_EQ(
    baker->GetLastFrameStatistics().PropsDrawn, baker->GetLastFrameStatistics().CascadesRendered);
  // A spot light: every caster is drawn.
  scene.Light->SetPosition(0, 10, 0);
  scene.Light->SetPositional(true);
  scene.Light->SetConeAngle(60.0);
  scene.Frame();
  EXPECT_GT(baker->GetLastFrameStatistics().CascadesRendered, 0);
  EXPECT_EQ(baker->GetLastFrameStatistics().CastersWithoutReceivers, 0);
}

// A caster drawn as it is counts what it draws: a box of six quads twelve triangles, and the
// same box as triangle strips twelve (the cascade count weighs casters by their triangles).
TEST(Passes, CastersDrawnAsTheyAreCountTheirTriangles)
{
  BoxOverPlane scene;
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
  baker->CompactCastersOff();
  baker->LightSpacePagesOff();
  scene.Frame();
  const auto& stats = baker->GetLastFrameStatistics();
  ASSERT_GT(stats.CascadesRendered, 0);
  EXPECT_EQ(stats.PropsDrawn, stats.CascadesRendered); // (the plane shadows nothing)
  EXPECT_EQ(stats.CellsDrawn, 12.0 * stats.CascadesRendered);
  vtkNew<vtkCubeSource> cube;
  cube->SetBounds(-1, 1, 2, 4, -1, 1);
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputConnection(cube->GetOutputPort());
  vtkNew<vtkStripper> strips;
  strips->SetInputConnection(triangles->GetOutputPort());
  strips->Update();
  ASSERT_GT(strips->GetOutput()->GetNumberOfStrips(), 0);
  ASSERT_LT(strips->GetOutput()->GetNumberOfStrips(), 12);
  vtkPolyDataMapper::SafeDownCast(scene.Box->GetMapper())
    ->SetInputConnection(strips->GetOutputPort());
  scene.Frame();
  ASSERT_GT(stats.CascadesRendered, 0);
  EXPECT_EQ(stats.CellsDrawn, 12.0 * stats.CascadesRendered);
}

TEST(Passes, ClosedSurfacesDrawnFromBehindTakeAShareOfTheBias)
{
  // A bias so large that it hides the box's shadow on the ground (the ground's reference depth
  // moves past the box, 2 units above it): with the ground an open plane the bias applies in
  // full whatever ClosedSurfaceBiasFactor says; with the ground a closed slab, drawn into the
  // maps from behind, only its share does, and the shadow is back. (Maps that follow the view:
  // a scene-fitted map takes a share of the bias by its texel.)
  BoxOverPlane scene;
  auto plain = scene.Render();
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
  baker->GetPlanner()->SceneFittedCascadesOff();
  EXPECT_EQ(pass->GetClosedSurfaceBiasFactor(), 0.01);
  pass->SetSlopeBias(0.0);
  pass->SetConstantBias(0.9);
  EXPECT_LT(DarkenedPixels(scene.Render(), plain), 50);
  EXPECT_FALSE(baker->DrawsFromBehind(scene.Ground)); // a plane: open
  EXPECT_TRUE(baker->DrawsFromBehind(scene.Box));
  vtkNew<vtkCubeSource> slab;
  slab->SetBounds(-10, 10, -0.5, 0, -10, 10);
  vtkPolyDataMapper::SafeDownCast(scene.Ground->GetMapper())
    ->SetInputConnection(slab->GetOutputPort());
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
  for (int c = 0; c < maps.GetNumberOfCascades() && !result.Found; ++c)
  {
    double ndc[3];
    project(maps.Cascades[c].WorldToMap, at, ndc);
    if (std::abs(ndc[0]) > 0.9 || std::abs(ndc[1]) > 0.9)
      continue;
    const int width = static_cast<int>(maps.Atlas->GetWidth());
    const int height = static_cast<int>(maps.Atlas->GetHeight());
    std::vector<float> depth(static_cast<size_t>(width) * height);
    window->MakeCurrent();
    maps.Atlas->Bind();
    glGetTexImage(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT, GL_FLOAT, depth.data());
    // (The map fills the lower left of its tile.)
    const auto& map = maps.Cascades[c];
    const int x = static_cast<int>(map.Tile[0] + (0.5 * ndc[0] + 0.5) * map.Resolution[0]);
    const int y = static_cast<int>(map.Tile[1] + (0.5 * ndc[1] + 0.5) * map.Resolution[1]);
    result.Held = depth[static_cast<size_t>(y) * width + x];
    for (int i = 0; i < 2; ++i)
    {
      project(maps.Cascades[c].WorldToMap, points[i], ndc);
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
    EXPECT_EQ(baker->GetLastFrameStatistics().ClosedCasters, 0);
    const MapDepths before = DepthsInMap(scene.Window, baker->GetLightMaps()[0], centre, faces);

    baker->CullClosedCastersOn();
    const long exitLayer = DarkenedPixels(scene.Render(), plain);
    EXPECT_EQ(
      baker->GetLastFrameStatistics().ClosedCasters, 1); // the box; not the plane, not the sheet
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

  pass->GetShadowMapBakerPass()->LightSpacePagesOff(); // (the cascades' own behaviour)
  vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
  baker->GetPlanner()->SetNumberOfCascades(3);
  baker->GetPlanner()->AdaptiveCascadesOff();
  baker->CullCastersWithoutReceiversOff(); // the ground's blocks are counted below
  baker->CompactCastersOff();
  auto whole = scene.Frame();
  EXPECT_EQ(baker->GetLastFrameStatistics().CompactCasters, 0);
  EXPECT_EQ(baker->GetLastFrameStatistics().BlocksDrawn, 0);
  const long wholeDark = DarkenedPixels(whole, plain);

  baker->CompactCastersOn();
  auto blocks = scene.Frame();
  ASSERT_EQ(baker->GetLastFrameStatistics().CascadesRendered, 3);
  EXPECT_EQ(baker->GetLastFrameStatistics().CompactCasters, 3); // the box, the ground, the row
  // Blocks: the box 1, the ground 80,000 / 16,384 -> 8 (median halving), the row 4; drawn into 3
  // cascades that would be 39. Each cascade draws only the blocks that reach it.
  // (One actor a prop draws the blocks a cascade chose.)
  EXPECT_LE(baker->GetLastFrameStatistics().PropsDrawn, 9);
  EXPECT_GE(baker->GetLastFrameStatistics().BlocksDrawn, 13);
  EXPECT_LT(baker->GetLastFrameStatistics().BlocksDrawn, 39);
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
  EXPECT_EQ(baker->GetLastFrameStatistics().CompactCasters, 2);
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
} // namespace

// Screen-sized casters (tubes drawn in the main view's pixels) have no fixed extent and cost
// their fragments: while one is in the scene there is no scene-fitted map.
TEST(Passes, ScreenSizedCastersGetNoSceneFittedMap)
{
  BoxOverPlane scene;
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
  auto lastFitted = [&]()
  {
    return baker->GetPlanner()->GetCascadeSceneFitted(
      baker->GetLightMaps().at(0).GetNumberOfCascades() - 1);
  };
  scene.Frame();
  EXPECT_TRUE(lastFitted()); // the box alone
  vtkSmartPointer<vtkActor> tubes = TubeRow(2.0, -4.0, 4.0, 4.0f);
  scene.Renderer->AddActor(tubes);
  scene.Frame();
  EXPECT_FALSE(lastFitted());
  scene.Renderer->RemoveActor(tubes);
  scene.Frame();
  // (The tubes' boxes are what changed: the maps of the view serve while it stays; the next
  // plan, the camera moved, takes the scene-fitted map again.)
  scene.Renderer->GetActiveCamera()->Azimuth(2.0);
  scene.Renderer->ResetCameraClippingRange();
  scene.Frame();
  EXPECT_TRUE(lastFitted());
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
      ->GetPlanner()
      ->SceneFittedCascadesOff();
    auto shadowed = scene.Render();
    float sizes[2] = { 0, 0 };
    csmScreenSizes(tubes, sizes);
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

  const std::pair<const char*, vtkMapper*> mappers[] = { { "splats", splats }, { "glyphs", glyphs },
    { "composite", composite } };
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

// VTK fades a point-Gaussian splat's triangle by a Gaussian opacity (its default, no splat code):
// the map holds the disc where the splat is at least half opaque (radius sqrt(2 ln 2) standard
// deviations), not the triangle that holds it (its circle of TriangleScale, 3, of them). Counted
// in an unwarped map: the texels nearer the light than the ground.
TEST(Passes, ADefaultSplatCastsTheShadowOfItsHalfOpaqueDisc)
{
  vtkNew<vtkPoints> points;
  points->InsertNextPoint(0.0, 3.0, 0.0);
  vtkNew<vtkPolyData> centre;
  centre->SetPoints(points);
  // The splat code of each case: VTK's default, its disc of half opacity cut out, its whole
  // triangle (nothing cut out).
  const std::pair<const char*, const char*> codes[] = { { "default", nullptr },
    { "disc",
      "//VTK::Color::Impl\n"
      "if (dot(offsetVCVSOutput.xy, offsetVCVSOutput.xy) > 2.0 * log(2.0)) { discard; }\n" },
    { "triangle", "//VTK::Color::Impl\n" } };
  std::array<long, 3> texels{};
  for (size_t i = 0; i < texels.size(); ++i)
  {
    vtkNew<vtkPointGaussianMapper> splat;
    splat->SetInputData(centre);
    splat->SetScaleFactor(1.0);
    splat->EmissiveOff();
    if (codes[i].second)
    {
      splat->SetSplatShaderCode(codes[i].second);
    }
    BoxOverPlane scene;
    scene.Box->SetMapper(splat);
    vtkCascadedShadowMapBakerPass* baker =
      vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer)->GetShadowMapBakerPass();
    baker->LightSpacePagesOff();
    baker->CullCastersWithoutReceiversOff(); // (the ground's depth in the map: the reference)
    baker->GetPlanner()->SetNumberOfCascades(1);
    baker->GetPlanner()->AdaptiveCascadesOff();
    baker->GetPlanner()->SetWarpMode(vtkCascadedShadowMapPlanner::WARP_NONE); // (depth linear)
    baker->GetPlanner()->DepthClampOff();
    scene.Frame();
    const std::vector<float> depths =
      csmTest::CascadeDepths(scene.Window, baker->GetLightMaps(scene.Renderer).at(0), 0);
    ASSERT_FALSE(depths.empty());
    const float ground = *std::max_element(depths.begin(), depths.end(),
      [](float a, float b) { return (a < 1.0f ? a : -1.0f) < (b < 1.0f ? b : -1.0f); });
    const float nearest = *std::min_element(depths.begin(), depths.end());
    const float between = 0.5f * (nearest + ground);
    texels[i] = std::count_if(depths.begin(), depths.end(), [&](float d) { return d < between; });
    std::printf("%s: %ld texels of the splat\n", codes[i].first, texels[i]);
  }
  EXPECT_GT(texels[1], 100);
  EXPECT_NEAR(double(texels[0]), double(texels[1]), 0.05 * double(texels[1]));
  // (The triangle: (3 / 1.18)^2 the disc's area times a triangle's over its circle's, 1.65.)
  EXPECT_GT(texels[2], 8 * texels[1]);
}
