// SPDX-License-Identifier: BSD-3-Clause
// The maps: one atlas for every count of cascades, the scene-fitted map, the resolution each
// map's predicted error needs, and maps kept across frames (while the user drags and in still
// frames) that shade as fresh ones.
#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCascadedShadowMapBakerPass.h"
#include "vtkCascadedShadowMapPass.h"
#include "vtkCascadedShadowMapPlanner.h"
#include "vtkCubeSource.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyDataMapper.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkTextureObject.h"
#include "vtkUnsignedCharArray.h"
#include "vtk_glew.h"

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
  baker->GetPlanner()->SetNumberOfCascades(4);
  bool sawFitted = false;
  vtkTextureObject* texture = nullptr;
  for (bool fitted : { true, false })
  {
    // (A target no count meets gets no scene-fitted map: the count of least error is taken.
    // Without one, a target more than any count can give: every map at its ceiling.)
    baker->GetPlanner()->SetErrorTarget(fitted ? 1.0 : 0.05);
    baker->GetPlanner()->SetSceneFittedCascades(fitted);
    const long shadowed = DarkenedPixels(scene.Render(), plain);
    ASSERT_EQ(baker->GetLightMaps().size(), 1u);
    const auto& maps = baker->GetLightMaps()[0];
    const int n = maps.GetNumberOfCascades();
    ASSERT_GE(n, 1);
    ASSERT_LT(n, 4); // the box over the plane is a short view: fewer than four
    EXPECT_EQ(maps.Atlas->GetWidth(), 512u);
    EXPECT_EQ(maps.Atlas->GetHeight(), 512u);
    EXPECT_TRUE(texture == nullptr || texture == maps.Atlas.Get());
    texture = maps.Atlas;
    const int tile = n == 1 ? 512 : 256;
    EXPECT_EQ(maps.Cascades[0].Tile[2], tile) << n << " cascades";
    EXPECT_EQ(maps.Cascades[0].Tile[3], tile);
    bool anyFitted = false;
    for (int c = 0; c < n; ++c)
    {
      anyFitted = anyFitted || maps.Cascades[c].IsSceneFitted();
      for (int axis = 0; axis < 2; ++axis)
      {
        if (maps.Cascades[c].IsSceneFitted())
        {
          EXPECT_EQ(maps.Cascades[c].Resolution[axis], tile) << c << " of " << n;
        }
        else if (fitted)
        {
          EXPECT_LE(maps.Cascades[c].Resolution[axis], 256) << c << " of " << n; // from need
        }
        else
        {
          EXPECT_EQ(maps.Cascades[c].Resolution[axis], 256) << c << " of " << n;
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
  baker->GetPlanner()->AdaptiveCascadesOff();
  const long four = DarkenedPixels(scene.Render(), plain);
  EXPECT_EQ(baker->GetLightMaps()[0].GetNumberOfCascades(), 4);
  EXPECT_EQ(baker->GetLightMaps()[0].Cascades[0].Tile[2], 256);
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
  EXPECT_TRUE(baker->GetPlanner()->GetSceneFittedCascades()); // the default
  scene.Frame();
  const int first = baker->GetLastFrameStatistics().CascadesRendered;
  EXPECT_GE(first, 1);
  int kept = 0;
  for (int frame = 0; frame < 6; ++frame)
  {
    scene.Renderer->GetActiveCamera()->Azimuth(35.0);
    auto image = scene.Frame();
    const auto& maps = baker->GetLightMaps().at(0);
    ASSERT_GE(maps.GetNumberOfCascades(), 1);
    const int last = maps.GetNumberOfCascades() - 1;
    EXPECT_TRUE(baker->GetPlanner()->GetCascadeSceneFitted(last)) << "frame " << frame;
    kept += baker->GetLastFrameStatistics().CascadesKept;
    EXPECT_EQ(baker->GetLastFrameStatistics().CascadesRendered, last)
      << "frame " << frame; // only the others
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
  EXPECT_GE(baker->GetLastFrameStatistics().CascadesRendered, 1);
  // Off: the farthest cascade follows the view, and a turn draws it again.
  baker->LightSpacePagesOff(); // (the cascades' own behaviour)
  baker->GetPlanner()->SceneFittedCascadesOff();
  scene.Frame();
  scene.Renderer->GetActiveCamera()->Azimuth(35.0);
  scene.Frame();
  EXPECT_FALSE(baker->GetPlanner()->GetCascadeSceneFitted(
    baker->GetLightMaps().at(0).GetNumberOfCascades() - 1));
  EXPECT_GE(baker->GetLastFrameStatistics().CascadesRendered, 1);
}

// While the light has one map, the lookup compiled without the cascade choice
// (SingleMapLookup) shades every pixel as the lookup with the choice does, along an orbit and
// with more maps; the shadow is there.
TEST(Passes, TheSingleMapLookupShadesAsTheChoiceDoes)
{
  BoxOverPlane scene;
  auto plain = scene.Frame();
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  pass->GetShadowMapBakerPass()->LightSpacePagesOff(); // (the cascades' own behaviour)
  pass->ReuseShadowFactorsOff();                       // (every frame makes the lookup)
  EXPECT_TRUE(pass->GetSingleMapLookup());             // the default
  vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
  for (int cascades : { 1, 3 })
  {
    if (cascades > 1)
    {
      baker->GetPlanner()->SetNumberOfCascades(cascades);
      baker->GetPlanner()->AdaptiveCascadesOff();
    }
    for (int frame = 0; frame < 4; ++frame)
    {
      scene.Renderer->GetActiveCamera()->Azimuth(frame == 0 ? 0.0 : 20.0);
      pass->SingleMapLookupOn();
      auto single = scene.Frame();
      EXPECT_EQ(baker->GetLightMaps().at(0).GetNumberOfCascades(), cascades) << frame;
      pass->SingleMapLookupOff();
      auto chosen = scene.Frame();
      EXPECT_EQ(baker->GetLastFrameStatistics().CascadesRendered, 0) << frame; // the same maps
      EXPECT_EQ(DifferingValues(single, chosen, 0), 0) << cascades << " maps, frame " << frame;
      if (cascades == 1 && frame == 0)
      {
        EXPECT_GT(DarkenedPixels(single, plain), 500);
      }
    }
  }
}

// Resolution from need: a view that full maps oversample gets the maps its
// predicted error needs, and the shadow stays; ErrorTarget 0 renders every map at Resolution.
TEST(Passes, MapsHaveTheResolutionTheirErrorNeeds)
{
  BoxOverPlane scene; // 320 x 240: 2048-texel maps oversample it several times
  auto plain = scene.Render();
  // Pixels in shadow: less than half as bright as without shadows (the penumbra of a texel-space
  // filter widens on screen with the texels, the shadow's extent does not).
  auto halfDark = [&plain](vtkImageData* shadowed)
  {
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
  pass->GetShadowMapBakerPass()->LightSpacePagesOff(); // (the cascades' own behaviour)
  vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
  baker->GetPlanner()
    ->SceneFittedCascadesOff(); // (a scene-fitted map has all the texels of its tile)
  baker->GetPlanner()->SetErrorTarget(0.0);
  const long full = halfDark(scene.Render());
  for (int c = 0; c < baker->GetLightMaps().at(0).GetNumberOfCascades(); ++c)
  {
    // (Its tile: NumberOfCascades of them share four full maps' texels.)
    const auto& full = baker->GetLightMaps().at(0);
    EXPECT_EQ(full.Cascades[c].Resolution[0], full.Cascades[0].Tile[2]);
    EXPECT_EQ(full.Cascades[c].Resolution[1], full.Cascades[0].Tile[3]);
  }
  baker->GetPlanner()->SetErrorTarget(1.0);
  const long needed = halfDark(scene.Render());
  const auto& maps = baker->GetLightMaps().at(0);
  vtkCascadedShadowMapPlanner* planner = baker->GetPlanner();
  long texels = 0;
  const int ceiling[2] = { baker->GetResolution(), baker->GetResolution() };
  for (int c = 0; c < maps.GetNumberOfCascades(); ++c)
  {
    const int* r = maps.Cascades[c].Resolution;
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
  std::printf("shadowed pixels: full maps %ld, maps from need %ld (%.1f %% of the texels)\n", full,
    needed, 100.0 * texels / (2.0 * baker->GetResolution() * baker->GetResolution()));
  EXPECT_GT(full, 800);
  // The same shadow up to its edge: at ErrorTarget 1 a texel spans up to a pixel, and each edge
  // of this shadow (about 150 pixels around, 13 % of its area) may move by up to one.
  EXPECT_NEAR(static_cast<double>(needed), static_cast<double>(full), 0.08 * full);
  // A larger window needs more texels (up to the ceiling).
  scene.Window->SetSize(960, 720);
  scene.Render();
  for (int c = 0; c < maps.GetNumberOfCascades(); ++c)
  {
    int planned[2] = { 0, 0 };
    planner->GetCascadeResolution(
      c, 720, vtkCascadedShadowMapBakerPass::RESOLUTION_STEP, ceiling, planned);
    EXPECT_EQ(baker->GetLightMaps().at(0).Cascades[c].Resolution[0], planned[0]);
    EXPECT_EQ(baker->GetLightMaps().at(0).Cascades[c].Resolution[1], planned[1]);
  }
}

// Maps kept across frames while the user drags. A pass that keeps maps and one
// that re-renders them every frame must shade a short interactive orbit alike.
TEST(Passes, KeptMapsShadeLikeFreshOnesAlongAnInteractivePath)
{
  BoxOverPlane keep, fresh;
  vtkCascadedShadowMapPass* a = vtkCascadedShadowMapPass::UseShadowsOn(keep.Renderer);
  a->GetShadowMapBakerPass()->LightSpacePagesOff(); // (the cascades' own behaviour)
  vtkCascadedShadowMapPass* b = vtkCascadedShadowMapPass::UseShadowsOn(fresh.Renderer);
  b->GetShadowMapBakerPass()->LightSpacePagesOff();
  b->GetShadowMapBakerPass()->SetInteractiveMapBorder(0.0);
  b->GetShadowMapBakerPass()->SetMapReuseTolerance(1.0); // re-render whenever the camera moves
  // (The cascades that follow the view: a scene-fitted map would serve every view here.)
  a->GetShadowMapBakerPass()->GetPlanner()->SceneFittedCascadesOff();
  b->GetShadowMapBakerPass()->GetPlanner()->SceneFittedCascadesOff();
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
    kept += a->GetShadowMapBakerPass()->GetLastFrameStatistics().CascadesKept;
    rendered += b->GetShadowMapBakerPass()->GetLastFrameStatistics().CascadesRendered;
    cascades +=
      b->GetShadowMapBakerPass()->GetLightMaps(fresh.Renderer).at(0).GetNumberOfCascades();
    // <= 0.5 % of the pixels differ by more than 0.1 of the range (26 levels).
    const long differing = csmTest::DifferingPixels(ia, ib, 26);
    EXPECT_GE(differing, 0);
    EXPECT_LE(differing, ia->GetNumberOfPoints() / 200) << "frame " << frame;
  }
  EXPECT_GT(kept, 0);            // the point of it: maps were kept
  EXPECT_EQ(rendered, cascades); // the reference re-rendered every cascade every frame
  // While dragging, the maps have at most InteractiveResolution texels a side.
  vtkCascadedShadowMapBakerPass* baker = a->GetShadowMapBakerPass();
  const auto& dragged = baker->GetLightMaps(keep.Renderer).at(0);
  for (int c = 0; c < dragged.GetNumberOfCascades(); ++c)
  {
    EXPECT_LE(dragged.Cascades[c].Resolution[0], baker->GetInteractiveResolution());
    EXPECT_LE(dragged.Cascades[c].Resolution[1], baker->GetInteractiveResolution());
  }
  // The still frame after dragging returns to tight maps (full quality): identical images.
  keep.Window->SetDesiredUpdateRate(0.0001);
  fresh.Window->SetDesiredUpdateRate(0.0001);
  EXPECT_EQ(DifferingValues(keep.Frame(), fresh.Frame()), 0);
  const auto& still = baker->GetLightMaps(keep.Renderer).at(0);
  const auto& reference = b->GetShadowMapBakerPass()->GetLightMaps(fresh.Renderer).at(0);
  for (int c = 0; c < still.GetNumberOfCascades(); ++c)
  {
    EXPECT_EQ(still.Cascades[c].Resolution[0], reference.Cascades[c].Resolution[0]);
    EXPECT_EQ(still.Cascades[c].Resolution[1], reference.Cascades[c].Resolution[1]);
  }
  EXPECT_EQ(baker->GetLastFrameStatistics().CascadesRendered, still.GetNumberOfCascades());
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
  a->GetShadowMapBakerPass()->LightSpacePagesOff(); // (the cascades' own behaviour)
  vtkCascadedShadowMapPass* b = vtkCascadedShadowMapPass::UseShadowsOn(fresh.Renderer);
  b->GetShadowMapBakerPass()->LightSpacePagesOff();
  a->GetShadowMapBakerPass()->GetPlanner()->SetErrorTarget(0.5);
  b->GetShadowMapBakerPass()->GetPlanner()->SetErrorTarget(0.5);
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
    if (baker->GetLastFrameStatistics().CascadesKept == 0 ||
      baker->GetLastFrameStatistics().CascadesRendered == 0)
    {
      continue; // not a frame with both
    }
    const auto& mk = baker->GetLightMaps(keep.Renderer).at(0);
    const auto& mf = b->GetShadowMapBakerPass()->GetLightMaps(fresh.Renderer).at(0);
    ASSERT_EQ(mk.GetNumberOfCascades(), mf.GetNumberOfCascades());
    for (int c = 0; c < mk.GetNumberOfCascades(); ++c)
    {
      // The re-rendered cascades: planned for this camera, as the reference's.
      if (!std::equal(
            mk.Cascades[c].WorldToMap, mk.Cascades[c].WorldToMap + 16, mf.Cascades[c].WorldToMap) ||
        !std::equal(mk.Cascades[c].Tile, mk.Cascades[c].Tile + 4, mf.Cascades[c].Tile) ||
        !std::equal(
          mk.Cascades[c].Resolution, mk.Cascades[c].Resolution + 2, mf.Cascades[c].Resolution))
      {
        continue;
      }
      const std::vector<float> kept = csmTest::CascadeDepths(keep.Window, mk, c);
      const std::vector<float> reference = csmTest::CascadeDepths(fresh.Window, mf, c);
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
  // (A frame that reads the last frame's factors has shaders of its own: passes.ReusedFactors.)
  pass->ReuseShadowFactorsOff();
  vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
  baker->LightSpacePagesOff();               // (the cascades' own behaviour)
  baker->GetPlanner()->SetErrorTarget(0.05); // out of reach: as many as pay
  // (Of the cascades that follow the view: one scene-fitted map of the box's footprint would
  // meet even this.)
  baker->GetPlanner()->SceneFittedCascadesOff();
  const long still = DarkenedPixels(scene.Render(), plain);
  const auto& maps = baker->GetLightMaps().at(0);
  EXPECT_GT(maps.GetNumberOfCascades(), 4);
  int turned = 0;
  for (int c = 0; c < maps.GetNumberOfCascades(); ++c)
  {
    EXPECT_NE(maps.Cascades[0].Tile[2], maps.Cascades[0].Tile[3]) << "tall tiles";
    turned += maps.Cascades[c].Turned;
  }
  std::printf("still: %d cascades (%d turned), tiles %d x %d\n", maps.GetNumberOfCascades(), turned,
    maps.Cascades[0].Tile[2], maps.Cascades[0].Tile[3]);
  const vtkMTimeType shaders = pass->GetShaderStageMTime();
  scene.Window->SetDesiredUpdateRate(15.0); // as vtkRenderWindowInteractor while dragging
  const long dragged = DarkenedPixels(scene.Render(), plain);
  EXPECT_LE(baker->GetLightMaps().at(0).GetNumberOfCascades(), 4);
  // The count changes with the view: the shaders stay (a rebuild of every shader would cost a
  // frame).
  EXPECT_EQ(pass->GetShaderStageMTime(), shaders);
  EXPECT_GT(still, 200);
  EXPECT_NEAR(dragged, still, 0.1 * still);
}

TEST(Passes, LeavingAKeptMapReRendersItInThatFrame)
{
  BoxOverPlane scene, reference;
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  pass->GetShadowMapBakerPass()->LightSpacePagesOff(); // (the cascades' own behaviour)
  // (The cascades that follow the view: a scene-fitted map would serve every view here.)
  pass->GetShadowMapBakerPass()->GetPlanner()->SceneFittedCascadesOff();
  vtkCascadedShadowMapBakerPass* fresh =
    vtkCascadedShadowMapPass::UseShadowsOn(reference.Renderer)->GetShadowMapBakerPass();
  fresh->LightSpacePagesOff();
  fresh->GetPlanner()->SceneFittedCascadesOff();
  scene.Window->SetDesiredUpdateRate(15.0);
  reference.Window->SetDesiredUpdateRate(15.0);
  scene.Frame();
  // A jump no kept map covers: re-rendered at once, the same image as a fresh pass's.
  scene.Renderer->GetActiveCamera()->Azimuth(70);
  scene.Renderer->GetActiveCamera()->Elevation(-20);
  scene.Renderer->GetActiveCamera()->OrthogonalizeViewUp();
  reference.Renderer->GetActiveCamera()->DeepCopy(scene.Renderer->GetActiveCamera());
  reference.Renderer->GetActiveCamera()->Modified(); // (a copy does not modify it)
  auto moved = scene.Frame();
  EXPECT_GE(pass->GetShadowMapBakerPass()->GetLastFrameStatistics().CascadesRendered, 1);
  EXPECT_EQ(DifferingValues(moved, reference.Frame()), 0);
}
