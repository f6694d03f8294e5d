// SPDX-License-Identifier: BSD-3-Clause
// What a frame draws and how long a pass chain lives: a frame's shadows depend only on its view,
// lights and scene (a frame equals its repeat and a fresh chain's frame, camera lights
// included), and a dropped chain frees itself and its maps.
#include "vtkActor.h"
#include "vtkAppendPolyData.h"
#include "vtkCamera.h"
#include "vtkCascadedShadowMapBakerPass.h"
#include "vtkCascadedShadowMapPass.h"
#include "vtkCascadedShadowMapPlanner.h"
#include "vtkCubeSource.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkWeakPointer.h"

#include "csmCascadeCount.h" // kCountHysteresis
#include "csmReuse.h"        // keptMapError
#include "csmTestHelpers.h"

#include <gtest/gtest.h>

#include <malloc.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

namespace
{
using csmTest::BoxOverPlane;
using csmTest::BoxOverPlaneSettings;
using csmTest::DarkenedPixels;
using csmTest::DifferingValues;

/// The box scene lit by a camera light (as ParaView's light kit key light is): above and to the
/// left of the camera, so the shadow falls in view.
void UseCameraLight(BoxOverPlane& scene)
{
  scene.Light->SetLightTypeToCameraLight();
  scene.Light->SetPositional(false);
  scene.Light->SetPosition(-0.4, 1.0, 0.3); // camera coordinates: up, left, in front
  scene.Light->SetFocalPoint(0.0, 0.0, 0.0);
}

/// One step of a dolly: eye and focal point moved along the view by 1 % of their distance.
void DollyStep(vtkCamera* camera)
{
  double eye[3], focal[3];
  camera->GetPosition(eye);
  camera->GetFocalPoint(focal);
  for (int k = 0; k < 3; ++k)
  {
    const double step = 0.01 * (focal[k] - eye[k]);
    eye[k] += step;
    focal[k] += step;
  }
  camera->SetPosition(eye);
  camera->SetFocalPoint(focal);
}

/// Was a map kept from the last frame (as it was, or moved with the view)? `last` holds the
/// last frame's world -> map matrices; the map's own is appended to `now`.
bool KeptFromLastFrame(const vtkCascadedShadowMapBakerPass::CascadeMap& map,
  const std::vector<std::vector<double>>& last, std::vector<std::vector<double>>& now)
{
  now.emplace_back(map.WorldToMap, map.WorldToMap + 16);
  return map.IsMoved() || std::find(last.begin(), last.end(), now.back()) != last.end();
}

void CopyCamera(BoxOverPlane& from, BoxOverPlane& to)
{
  // (A copy does not modify the camera: VTK would draw the next frame from its last matrices.)
  to.Renderer->GetActiveCamera()->DeepCopy(from.Renderer->GetActiveCamera());
  to.Renderer->GetActiveCamera()->Modified();
}

/// The resident set size of this process, in MB (0 where /proc cannot be read), after the
/// allocator returned what it can of the freed memory to the system.
double ResidentMB()
{
  malloc_trim(0);
  std::ifstream status("/proc/self/status");
  std::string word;
  while (status >> word)
  {
    if (word == "VmRSS:")
    {
      double kB = 0.0;
      status >> kB;
      return kB / 1024.0;
    }
  }
  return 0.0;
}
} // namespace

// A camera light moves with the camera: each frame's maps are those of that frame's light, so a
// frame equals its repeat and a fresh chain's frame of the same view, after every camera move.
TEST(Frames, CameraLightIsShadowedFromThisFramesDirection)
{
  BoxOverPlane scene;
  UseCameraLight(scene);
  auto plain = scene.Frame();
  vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  auto first = scene.Frame();
  EXPECT_GT(DarkenedPixels(first, plain), 500);
  EXPECT_EQ(DifferingValues(scene.Frame(), first), 0);
  for (int step = 0; step < 3; ++step)
  {
    scene.Renderer->GetActiveCamera()->Azimuth(25);
    auto moved = scene.Frame();
    auto repeat = scene.Frame();
    EXPECT_EQ(DifferingValues(moved, repeat), 0) << step;
    BoxOverPlane fresh;
    UseCameraLight(fresh);
    CopyCamera(scene, fresh);
    vtkCascadedShadowMapPass::UseShadowsOn(fresh.Renderer);
    EXPECT_EQ(DifferingValues(fresh.Frame(), moved), 0) << step;
  }
}

// A single render (a screenshot, a batch frame, an image test) gets the maps a second render of
// the same view gets: the visible depths are measured in the frame they serve. The part's box
// holds the camera (a block behind it and the box in front are one polydata), so the visible
// depths begin far beyond where the boxes meet the view.
TEST(Frames, TheFirstRenderIsTheFittedOne)
{
  BoxOverPlane scene;
  scene.AddBlockBehindTheCamera();
  auto plain = scene.Frame();
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
  baker->GetPlanner()->SceneFittedCascadesOff(); // (the cascades that follow the view)
  auto first = scene.Frame();
  EXPECT_TRUE(baker->GetLastFrameStatistics().VisibleDepthsUsed);
  EXPECT_GT(DarkenedPixels(first, plain), 800);
  const double firstNear = baker->GetLightMaps().at(0).SplitNear;
  auto second = scene.Frame();
  EXPECT_EQ(DifferingValues(first, second), 0);
  EXPECT_EQ(baker->GetLightMaps().at(0).SplitNear, firstNear);
  // Without the visible depths, the cascades begin where the boxes meet the view: nearer.
  baker->VisibleDepthFitOff();
  scene.Frame();
  EXPECT_LT(baker->GetLightMaps().at(0).SplitNear, 0.5 * firstNear);
}

// A chain that has rendered frees itself, its maps and its caster blocks once it is dropped (the
// mappers it drew keep only the passes of their last frame): no reference cycle.
TEST(Frames, ADroppedChainIsFreed)
{
  BoxOverPlane scene;
  vtkWeakPointer<vtkCascadedShadowMapPass> pass =
    vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  vtkWeakPointer<vtkCascadedShadowMapBakerPass> baker = pass->GetShadowMapBakerPass();
  scene.Frame();
  ASSERT_FALSE(baker->GetLightMaps().empty());
  EXPECT_GT(
    baker->GetLastFrameStatistics().CompactCasters, 0); // the baker's own mappers were drawn
  vtkCascadedShadowMapPass::UseShadowsOff(scene.Renderer);
  scene.Frame(); // the props' mappers forget the chain's passes
  EXPECT_EQ(pass.GetPointer(), nullptr);
  EXPECT_EQ(baker.GetPointer(), nullptr);
}

// Switching shadows on and off many times keeps the memory flat: every chain but the one the
// props drew last is gone, with its 64 MB atlas. (A chain kept alive would add its atlas every
// cycle, 6.4 GB over 100 cycles. Resident memory is read after malloc_trim, the lowest of ten
// readings. With llvmpipe the process takes one step of an atlas's size around the hundredth
// cycle, with no chain alive, and then stays flat over 300 cycles: Results.md, "Memory".)
TEST(Frames, SwitchingShadowsOnAndOffKeepsMemoryFlat)
{
  BoxOverPlane scene;
  std::vector<vtkWeakPointer<vtkCascadedShadowMapBakerPass>> bakers;
  std::vector<double> resident;
  for (int i = 0; i < 110; ++i)
  {
    vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
    bakers.push_back(pass->GetShadowMapBakerPass());
    scene.Frame();
    vtkCascadedShadowMapPass::UseShadowsOff(scene.Renderer);
    resident.push_back(ResidentMB());
  }
  int alive = 0;
  for (const auto& baker : bakers)
  {
    alive += baker ? 1 : 0;
  }
  EXPECT_LE(alive, 1); // the last chain lives until the props draw without it
  // Cycles 10-19 (the driver's own caches settled) against the last ten.
  const double early = *std::min_element(resident.begin() + 10, resident.begin() + 20);
  const double late = *std::min_element(resident.end() - 10, resident.end());
  ASSERT_GT(early, 0.0);
  EXPECT_LT(late - early, 20.0 + 64.0);
}

namespace
{
/// The largest aliasing error (texels per pixel, Lloyd et al. 2006) of the light's cascade c over
/// ground points (y = 0) the view sees in that cascade's depth slice and the map holds.
double LargestGroundError(vtkRenderer* renderer,
  const vtkCascadedShadowMapBakerPass::LightMaps& maps, int c, const double lightDirection[3],
  int* samples, double halfWidth = 10.0)
{
  vtkCamera* camera = renderer->GetActiveCamera();
  const double aspect = renderer->GetTiledAspectRatio();
  const int imageHeight = renderer->GetSize()[1];
  vtkMatrix4x4* worldToClip = camera->GetCompositeProjectionTransformMatrix(aspect, -1, 1);
  double eye[3], direction[3];
  camera->GetPosition(eye);
  camera->GetDirectionOfProjection(direction);
  double largest = 0.0;
  *samples = 0;
  for (double x = -halfWidth; x <= halfWidth; x += 0.25)
  {
    for (double z = -halfWidth; z <= halfWidth; z += 0.25)
    {
      const double p[4] = { x, 0.0, z, 1.0 };
      double clip[4], map[4];
      worldToClip->MultiplyPoint(p, clip);
      if (!(clip[3] > 0.0) || std::abs(clip[0]) > clip[3] || std::abs(clip[1]) > clip[3])
      {
        continue; // not in view
      }
      const double depth =
        (x - eye[0]) * direction[0] + (0.0 - eye[1]) * direction[1] + (z - eye[2]) * direction[2];
      const double from = c == 0 ? maps.SplitNear : maps.Cascades[c - 1].SplitFar;
      if (depth < from || depth > maps.Cascades[c].SplitFar)
      {
        continue;
      }
      vtkMatrix4x4::MultiplyPoint(maps.Cascades[c].WorldToMap, p, map);
      if (!(map[3] > 0.0) || std::abs(map[0]) > map[3] || std::abs(map[1]) > map[3])
      {
        continue;
      }
      double m[2];
      vtkCascadedShadowMapPlanner::ComputeAliasing(
        camera, aspect, lightDirection, maps.Cascades[c].WorldToMap, p, m);
      const bool turned = maps.Cascades[c].Turned;
      const double error = std::max(m[0] / maps.Cascades[c].Resolution[turned ? 1 : 0],
                             m[1] / maps.Cascades[c].Resolution[turned ? 0 : 1]) *
        imageHeight;
      largest = std::max(largest, error);
      ++*samples;
    }
  }
  return largest;
}
} // namespace

// A camera on a smooth path over a static scene re-renders only the maps it must: the others are
// kept, and each kept map still meets the error target at the new view, as the error model reads
// it at the ground the view sees.
TEST(Frames, ASmallCameraStepKeepsMapsThatStillMeetTheErrorTarget)
{
  BoxOverPlane scene;
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
  baker->GetPlanner()->SceneFittedCascadesOff(); // (the maps that follow the view)
  const double target = baker->GetPlanner()->GetErrorTarget();
  const double lightDirection[3] = { 0.0, -1.0, 0.0 };
  scene.Frame();
  scene.Frame();
  int rendered = 0, kept = 0, checked = 0;
  double texels = 0.0, allTexels = 0.0;
  std::vector<std::vector<double>> last;
  for (int frame = 0; frame < 16; ++frame)
  {
    scene.Renderer->GetActiveCamera()->Azimuth(0.5);
    scene.Frame();
    const auto& maps = baker->GetLightMaps().at(0);
    rendered += baker->GetLastFrameStatistics().CascadesRendered;
    kept += baker->GetLastFrameStatistics().CascadesKept;
    texels += baker->GetLastFrameStatistics().TexelsRendered;
    std::vector<std::vector<double>> now;
    for (int c = 0; c < maps.GetNumberOfCascades(); ++c)
    {
      allTexels += double(maps.Cascades[c].Resolution[0]) * maps.Cascades[c].Resolution[1];
      now.emplace_back(maps.Cascades[c].WorldToMap, maps.Cascades[c].WorldToMap + 16);
      const bool keptMap = c < static_cast<int>(last.size()) && last[c] == now.back();
      int samples = 0;
      const double error = LargestGroundError(scene.Renderer, maps, c, lightDirection, &samples);
      if (keptMap && samples > 0)
      {
        EXPECT_LE(error, target * 1.001) << "frame " << frame << " cascade " << c;
        ++checked;
      }
    }
    last = now;
  }
  EXPECT_GT(kept, rendered); // most maps are kept
  EXPECT_GT(checked, 4);
  EXPECT_LT(texels, 0.5 * allTexels); // far fewer texels than re-rendering every map
}

// Where no map meets the error target (maps of at most 128 texels here), a fresh map misses it
// too: a small camera step keeps a map while its error at the new view is within the cascade
// count's hysteresis of a fresh map's (csm::keptMapServes), where it would otherwise draw every
// map again for a few percent of error that no map can win back.
TEST(Frames, WhereNoMapMeetsTheTargetAKeptMapStaysWithinTheCountsHysteresis)
{
  BoxOverPlane scene;
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
  vtkCascadedShadowMapPlanner* planner = baker->GetPlanner();
  planner->SceneFittedCascadesOff(); // (the maps that follow the view)
  baker->SetResolution(128);
  scene.Frame();
  scene.Frame();
  const int imageHeight = scene.Renderer->GetSize()[1];
  int kept = 0, rendered = 0, keptWorse = 0, outOfReach = 0, cascades = 0;
  double worstRatio = 0.0;
  std::vector<std::vector<double>> last;
  for (int frame = 0; frame < 16; ++frame)
  {
    DollyStep(scene.Renderer->GetActiveCamera());
    scene.Frame();
    const auto& maps = baker->GetLightMaps().at(0);
    kept += baker->GetLastFrameStatistics().CascadesKept;
    rendered += baker->GetLastFrameStatistics().CascadesRendered;
    std::vector<std::vector<double>> now;
    for (int c = 0; c < maps.GetNumberOfCascades(); ++c)
    {
      const auto& map = maps.Cascades[c];
      int ceiling[2];
      planner->GetCascadeResolutionCeiling(c, ceiling);
      const bool unreachable = planner->GetCascadeErrorTargetOutOfReach(c, imageHeight, ceiling);
      outOfReach += unreachable ? 1 : 0;
      ++cascades;
      if (!KeptFromLastFrame(map, last, now))
      {
        continue; // drawn afresh for this view
      }
      // A kept map (as it was, or moved with the view): its error over a fresh map's at this
      // view, at equal resolution.
      const double ratio = planner->CompareKeptMap(
        c, map.WorldToMap, 0.0, std::min(map.Resolution[0], map.Resolution[1]));
      EXPECT_LE(ratio, (1.0 + 1e-9) / csm::kCountHysteresis) << "frame " << frame << " map " << c;
      EXPECT_TRUE(ratio <= 1.0 + 1e-9 || unreachable) << "frame " << frame << " map " << c;
      worstRatio = std::max(worstRatio, ratio);
      keptWorse += ratio > 1.0 + 1e-9 ? 1 : 0;
      // The statistics say the same: the least error of a kept map judged for this cascade, at
      // its own resolution, within what serves.
      const double keptError = baker->GetLastFrameStatistics().KeptError[c];
      EXPECT_GT(keptError, 0.0) << "frame " << frame << " map " << c;
      EXPECT_LE(keptError, (1.0 + 1e-9) / csm::kCountHysteresis)
        << "frame " << frame << " map " << c;
    }
    last = now;
  }
  EXPECT_EQ(outOfReach, cascades); // every map misses the target
  EXPECT_GT(kept, 0);
  EXPECT_GT(keptWorse, 0); // kept where a map only as good as a fresh one would be drawn again
  EXPECT_LT(rendered, cascades);
  std::printf("kept %d of %d maps, %d of them worse than a fresh one (worst ratio %.3f)\n", kept,
    cascades, keptWorse, worstRatio);
}

// Where the target is in reach, a map kept along a dolly meets the error target at every new view:
// its error there, read by the error model (the kept matrix against a fresh plan, at its own
// resolution), is at most that of a map of the fewest texels that meet the target; fresh maps
// come in steps of RESOLUTION_STEP texels, so a kept map may be a little worse than a fresh one.
TEST(Frames, AlongADollyEveryKeptMapMeetsTheErrorTarget)
{
  BoxOverPlane scene;
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  pass->GetShadowMapBakerPass()->LightSpacePagesOff(); // (the cascades' own behaviour)
  vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
  vtkCascadedShadowMapPlanner* planner = baker->GetPlanner();
  planner->SceneFittedCascadesOff(); // (the maps that follow the view)
  scene.Frame();
  scene.Frame();
  const int imageHeight = scene.Renderer->GetSize()[1];
  int kept = 0, keptBeyondFresh = 0, cascades = 0;
  std::vector<std::vector<double>> last;
  for (int frame = 0; frame < 16; ++frame)
  {
    DollyStep(scene.Renderer->GetActiveCamera());
    scene.Frame();
    const auto& maps = baker->GetLightMaps().at(0);
    std::vector<std::vector<double>> now;
    for (int c = 0; c < maps.GetNumberOfCascades(); ++c)
    {
      const auto& map = maps.Cascades[c];
      int ceiling[2];
      planner->GetCascadeResolutionCeiling(c, ceiling);
      ASSERT_FALSE(planner->GetCascadeErrorTargetOutOfReach(c, imageHeight, ceiling));
      ++cascades;
      if (!KeptFromLastFrame(map, last, now))
      {
        continue; // drawn afresh for this view
      }
      ++kept;
      int fewest[2], fresh[2];
      planner->GetCascadeResolution(c, imageHeight, 1, ceiling, fewest);
      planner->GetCascadeResolution(
        c, imageHeight, vtkCascadedShadowMapBakerPass::RESOLUTION_STEP, ceiling, fresh);
      const double ratio = planner->CompareKeptMap(
        c, map.WorldToMap, 0.0, std::min(map.Resolution[0], map.Resolution[1]));
      const csm::MapSize size(map.Resolution[0], map.Resolution[1]);
      EXPECT_LE(csm::keptMapError(ratio, size, csm::MapSize(fewest[0], fewest[1])), 1.0 + 1e-9)
        << "frame " << frame << " map " << c;
      keptBeyondFresh +=
        csm::keptMapError(ratio, size, csm::MapSize(fresh[0], fresh[1])) > 1.0 + 1e-9 ? 1 : 0;
    }
    last = now;
  }
  EXPECT_GT(kept, 0);
  EXPECT_GT(keptBeyondFresh, 0); // (kept where it meets the target, not only a fresh map's error)
  std::printf("kept %d of %d maps, %d of them worse than a fresh map of whole steps\n", kept,
    cascades, keptBeyondFresh);
}

namespace
{
/// Posts over the ground (each scene its own mappers): 0.4 wide, 2 high, every 3 units in x and
/// z over |x|, |z| <= 21; their shadows fall on the ground everywhere the view goes.
void AddPosts(BoxOverPlane& scene, std::vector<vtkSmartPointer<vtkActor>>& keep)
{
  vtkNew<vtkCubeSource> post;
  post->SetBounds(-0.2, 0.2, 0.0, 2.0, -0.2, 0.2);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(post->GetOutputPort());
  for (int i = -7; i <= 7; ++i)
  {
    for (int k = -7; k <= 7; ++k)
    {
      auto actor = vtkSmartPointer<vtkActor>::New();
      actor->SetMapper(mapper);
      actor->SetPosition(3.0 * i + 1.5, 0.0, 3.0 * k + 1.5);
      scene.Renderer->AddActor(actor);
      keep.push_back(actor);
    }
  }
}
} // namespace

// A camera moving sideways past posts on a ground, the light across its path: the maps that no
// longer cover the view move with it by whole texels. A moved map holds the texels it kept
// exactly shifted, draws only the strips that came in, meets the error target at the new view,
// and shadows the frame as a chain that draws every map afresh does.
TEST(Frames, AMapMovedWithTheViewKeepsItsTexelsShiftedAndDrawsOnlyTheStrips)
{
  BoxOverPlaneSettings settings;
  settings.GroundHalfWidth = 24.0;
  settings.LightPosition[0] = 0.0; // (across the move: the maps' depths stay)
  settings.LightPosition[1] = 10.0;
  settings.LightPosition[2] = 4.0;
  settings.CameraPosition[0] = 0.0;
  settings.CameraPosition[1] = 5.0;
  settings.CameraPosition[2] = 9.0;
  BoxOverPlane moving(settings), fresh(settings);
  std::vector<vtkSmartPointer<vtkActor>> posts;
  AddPosts(moving, posts);
  AddPosts(fresh, posts);
  moving.Renderer->RemoveActor(moving.Box); // (the posts only)
  fresh.Renderer->RemoveActor(fresh.Box);
  auto plain = fresh.Frame();
  vtkCascadedShadowMapBakerPass* passes[2];
  for (int k = 0; k < 2; ++k)
  {
    BoxOverPlane& scene = k == 0 ? moving : fresh;
    passes[k] = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer)->GetShadowMapBakerPass();
    passes[k]->GetPlanner()->SceneFittedCascadesOff(); // (the maps that follow the view)
    passes[k]->LightSpacePagesOff();
    // Orthographic maps move exactly: a warped one's moves end sooner (math.Reuse tests).
    passes[k]->GetPlanner()->SetWarpMode(vtkCascadedShadowMapPlanner::WARP_NONE);
  }
  passes[1]->MoveKeptMapsOff();
  passes[1]->SetMapSlack(0.0); // every map drawn afresh at each step
  const double target = passes[0]->GetPlanner()->GetErrorTarget();
  const double length = std::sqrt(16.0 + 100.0);
  const double lightDirection[3] = { 0.0, -10.0 / length, -4.0 / length };
  moving.Frame();
  fresh.Frame();
  int movedMaps = 0, checkedError = 0;
  double texels[2] = { 0.0, 0.0 };
  long darkened[2] = { 0, 0 }, differing = 0, pixels = 0;
  for (int frame = 0; frame < 16; ++frame)
  {
    const auto before = passes[0]->GetLightMaps(moving.Renderer).at(0);
    const std::vector<std::vector<float>> beforeDepths =
      csmTest::AllCascadeDepths(moving.Window, before);
    for (BoxOverPlane* scene : { &moving, &fresh })
    {
      vtkCamera* camera = scene->Renderer->GetActiveCamera();
      double p[3], f[3];
      camera->GetPosition(p);
      camera->GetFocalPoint(f);
      camera->SetPosition(p[0] + 0.3, p[1], p[2]);
      camera->SetFocalPoint(f[0] + 0.3, f[1], f[2]);
    }
    auto shadowed = moving.Frame();
    auto reference = fresh.Frame();
    for (int k = 0; k < 2; ++k)
    {
      texels[k] += passes[k]->GetLastFrameStatistics().TexelsRendered;
    }
    darkened[0] += DarkenedPixels(shadowed, plain);
    darkened[1] += DarkenedPixels(reference, plain);
    differing += csmTest::DifferingPixels(shadowed, reference, 40);
    pixels += long(settings.Size[0]) * settings.Size[1];
    EXPECT_EQ(passes[1]->GetLastFrameStatistics().CascadesMoved, 0);
    const auto& after = passes[0]->GetLightMaps(moving.Renderer).at(0);
    std::vector<std::vector<float>> afterDepths;
    for (int c = 0; c < after.GetNumberOfCascades(); ++c)
    {
      const auto& map = after.Cascades[c];
      if (map.Moved[0] == 0 && map.Moved[1] == 0)
      {
        continue;
      }
      ++movedMaps;
      // The map it moved: the earlier one in the same tile, of the same size.
      int old = -1;
      for (int k = 0; k < before.GetNumberOfCascades(); ++k)
      {
        old = std::equal(map.Tile, map.Tile + 4, before.Cascades[k].Tile) ? k : old;
      }
      ASSERT_GE(old, 0);
      ASSERT_EQ(before.Cascades[old].Resolution[0], map.Resolution[0]);
      ASSERT_EQ(before.Cascades[old].Resolution[1], map.Resolution[1]);
      if (afterDepths.empty())
      {
        afterDepths = csmTest::AllCascadeDepths(moving.Window, after);
      }
      const std::vector<float>& depths = afterDepths[c];
      const int w = map.Resolution[0], h = map.Resolution[1];
      const int s = map.Moved[0], t = map.Moved[1];
      long shifted = 0, wrong = 0, held = 0;
      for (int y = std::max(0, -t); y < h - std::max(0, t); ++y)
      {
        for (int x = std::max(0, -s); x < w - std::max(0, s); ++x)
        {
          const float kept = beforeDepths[old][size_t(y + t) * w + (x + s)];
          wrong += depths[size_t(y) * w + x] != kept;
          held += kept < 1.0f;
          ++shifted;
        }
      }
      EXPECT_GT(shifted, 0);
      EXPECT_GT(held, 0) << "the kept part holds casters";
      EXPECT_EQ(wrong, 0) << "frame " << frame << ", cascade " << c << " moved " << s << ", " << t;
      int samples = 0;
      const double error =
        LargestGroundError(moving.Renderer, after, c, lightDirection, &samples, 24.0);
      if (samples > 0)
      {
        EXPECT_LE(error, target * 1.001) << "frame " << frame << " cascade " << c;
        ++checkedError;
      }
    }
  }
  EXPECT_GE(movedMaps, 4);
  EXPECT_GE(checkedError, 4);
  // Strips, not maps: far fewer texels than the chain that draws every map afresh.
  EXPECT_LT(texels[0], 0.35 * texels[1]);
  // The same shadows: orthographic maps share their texel grid in the world (csm::snapToTexels)
  // whether moved or drawn afresh, so the images agree to a few pixels (0 on llvmpipe; without
  // the strips, 1 % of the darkened pixels and 2,000 pixels differ).
  EXPECT_GT(darkened[1], 16 * 1000);
  EXPECT_NEAR(double(darkened[0]), double(darkened[1]), 0.002 * darkened[1]);
  EXPECT_LT(differing, pixels / 2000);
  std::printf("moved %d, texels %.3g of %.3g, darkened %ld / %ld, differing %ld of %ld\n",
    movedMaps, texels[0], texels[1], darkened[0], darkened[1], differing, pixels);
}
