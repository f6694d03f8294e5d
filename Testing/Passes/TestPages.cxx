// SPDX-License-Identifier: BSD-3-Clause
// Light-space pages (vtkCascadedShadowMapBakerPass::LightSpacePages): a camera turning over a
// field of posts draws only the pages that come into view, keeps the base, shades every frame as
// a chain that draws every page afresh, every visible sample finds the page of its level, two
// viewports sharing a pass keep their own pages, and the lights and views pages cannot serve keep
// the cascades.
#include "vtkActor.h"
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
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"

#include "csmPages.h"
#include "csmTestHelpers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

namespace
{
using csmTest::BoxOverPlane;
using csmTest::BoxOverPlaneSettings;

/// A field of 15 x 15 posts on a wide ground seen from close by, the light from the side: the
/// cascades would follow the view (the one scene-fitted map is far too coarse near the eye).
BoxOverPlaneSettings FieldSettings(int width = 320, int height = 240)
{
  BoxOverPlaneSettings settings;
  settings.Size[0] = width;
  settings.Size[1] = height;
  settings.GroundHalfWidth = 24.0;
  settings.LightPosition[0] = 6.0;
  settings.LightPosition[1] = 10.0;
  settings.LightPosition[2] = 3.0;
  settings.CameraPosition[0] = 0.0;
  settings.CameraPosition[1] = 2.5;
  settings.CameraPosition[2] = 9.0;
  return settings;
}

struct Field
{
  explicit Field(double azimuth, int width = 320, int height = 240)
    : Scene(FieldSettings(width, height))
  {
    this->Scene.Renderer->RemoveActor(this->Scene.Box);
    this->Post->SetBounds(-0.2, 0.2, 0.0, 2.0, -0.2, 0.2);
    this->Mapper->SetInputConnection(this->Post->GetOutputPort());
    for (int i = -7; i <= 7; ++i)
    {
      for (int k = -7; k <= 7; ++k)
      {
        auto actor = vtkSmartPointer<vtkActor>::New();
        actor->SetMapper(this->Mapper);
        actor->SetPosition(3.0 * i + 1.5, 0.0, 3.0 * k + 1.5);
        this->Scene.Renderer->AddActor(actor);
        this->Posts.push_back(actor);
      }
    }
    this->Pass = vtkCascadedShadowMapPass::UseShadowsOn(this->Scene.Renderer);
    this->Baker = this->Pass->GetShadowMapBakerPass();
    this->Turn(azimuth);
  }
  void Turn(double degrees)
  {
    this->Scene.Renderer->GetActiveCamera()->Azimuth(degrees);
    this->Scene.Renderer->ResetCameraClippingRange();
  }
  const vtkCascadedShadowMapBakerPass::LightMaps& Maps() const
  {
    return this->Baker->GetLightMaps(this->Scene.Renderer).at(0);
  }
  BoxOverPlane Scene;
  vtkNew<vtkCubeSource> Post;
  vtkNew<vtkPolyDataMapper> Mapper;
  std::vector<vtkSmartPointer<vtkActor>> Posts;
  vtkCascadedShadowMapPass* Pass = nullptr;
  vtkCascadedShadowMapBakerPass* Baker = nullptr;
};

/// Pixels of the frame whose surface needs a level finer than the base, and of those the ones
/// whose page the table does not hold (the lookup's own choice, csm::pageLevelRead), from the
/// window's depth after the frame.
void SamplesFindTheirPages(Field& field, long& needing, long& missing)
{
  needing = missing = 0;
  vtkRenderer* renderer = field.Scene.Renderer;
  const auto& maps = field.Maps();
  ASSERT_TRUE(maps.Pages.Active);
  csm::PageLevels levels;
  levels.baseTexels = glm::dvec2(maps.Pages.BaseTexels[0], maps.Pages.BaseTexels[1]);
  levels.baseDepth = maps.Pages.BaseDepth;
  levels.count = maps.Pages.Levels;
  const int* size = field.Scene.Window->GetSize();
  std::vector<float> depths(static_cast<size_t>(size[0]) * size[1]);
  field.Scene.Window->GetZbufferData(0, 0, size[0] - 1, size[1] - 1, depths.data());
  vtkCamera* camera = renderer->GetActiveCamera();
  vtkNew<vtkMatrix4x4> toWorld;
  toWorld->DeepCopy(
    camera->GetCompositeProjectionTransformMatrix(renderer->GetTiledAspectRatio(), -1, 1));
  toWorld->Invert();
  double eye[3], direction[3];
  camera->GetPosition(eye);
  camera->GetDirectionOfProjection(direction);
  const double* base = maps.Cascades[0].WorldToMap;
  for (int y = 0; y < size[1]; ++y)
  {
    for (int x = 0; x < size[0]; ++x)
    {
      const float z = depths[static_cast<size_t>(y) * size[0] + x];
      if (!(z < 1.0f))
      {
        continue;
      }
      const double ndc[4] = { 2.0 * (x + 0.5) / size[0] - 1.0, 2.0 * (y + 0.5) / size[1] - 1.0,
        2.0 * z - 1.0, 1.0 };
      double p[4];
      toWorld->MultiplyPoint(ndc, p);
      for (int a = 0; a < 3; ++a)
      {
        p[a] /= p[3];
      }
      const double depth = (p[0] - eye[0]) * direction[0] + (p[1] - eye[1]) * direction[1] +
        (p[2] - eye[2]) * direction[2];
      const double bx = 0.5 * (base[0] * p[0] + base[1] * p[1] + base[2] * p[2] + base[3]) + 0.5;
      const double by = 0.5 * (base[4] * p[0] + base[5] * p[1] + base[6] * p[2] + base[7]) + 0.5;
      const double f = levels.fineness(depth);
      if (levels.levelAt(f) == 0 || bx < 0.0 || bx > 1.0 || by < 0.0 || by > 1.0)
      {
        continue;
      }
      ++needing;
      missing += csm::pageLevelRead(levels, maps.Pages.Table, bx, by, f) == 0 ? 1 : 0;
    }
  }
}
} // namespace

// An orbit of 2 degrees a frame: after the first paged frame the base is kept and only the pages
// that came into view are drawn, every visible sample finds the page of its level, and each frame
// is the one a chain that draws every page afresh draws, with shadows.
TEST(Pages, AnOrbitDrawsOnlyThePagesThatComeIntoViewAndShadesAsAFreshChain)
{
  Field moving(0.0);
  moving.Scene.Frame(); // (paged at once: the visible-depth pass keeps the samples)
  ASSERT_TRUE(moving.Maps().Pages.Active);
  EXPECT_EQ(moving.Baker->GetLastFrameStatistics().PagesDrawn,
    moving.Baker->GetLastFrameStatistics().PagesNeeded);
  long drawn = 0, needed = 0;
  for (int frame = 1; frame <= 8; ++frame)
  {
    moving.Turn(2.0);
    auto image = moving.Scene.Frame();
    const auto& stats = moving.Baker->GetLastFrameStatistics();
    ASSERT_TRUE(moving.Maps().Pages.Active) << frame;
    EXPECT_GE(moving.Maps().Pages.Levels, 2);
    EXPECT_EQ(stats.CascadesRendered, 0) << frame; // the base kept
    EXPECT_GT(stats.PagesNeeded, 0);
    EXPECT_LE(stats.TexelsRendered,
      double(stats.PagesDrawn) * (csm::kPageTexels + csm::kPageInterior) *
        (csm::kPageTexels + csm::kPageInterior)); // (batches: their pages and borders)
    drawn += stats.PagesDrawn;
    needed += stats.PagesNeeded;
    long needing = 0, missing = 0;
    SamplesFindTheirPages(moving, needing, missing);
    EXPECT_GT(needing, 1000) << frame;
    EXPECT_EQ(missing, 0) << frame;
    // A fresh chain's first frame of this view (every page drawn).
    Field fresh(2.0 * frame);
    auto again = fresh.Scene.Frame();
    EXPECT_EQ(fresh.Baker->GetLastFrameStatistics().PagesDrawn,
      fresh.Baker->GetLastFrameStatistics().PagesNeeded);
    // (The same texels: a page's are its level's and place's alone; its slot, elsewhere in the
    // atlas, is read through float coordinates rounded otherwise, which turns a compare at a
    // texel's edge now and then: a few pixels by one tap of the kernel.)
    EXPECT_LE(csmTest::DifferingPixels(image, again, 0), 8) << frame;
    EXPECT_EQ(csmTest::DifferingPixels(image, again, 24), 0) << frame;
    if (frame == 8)
    {
      fresh.Scene.Renderer->SetPass(nullptr);
      auto plain = fresh.Scene.Frame();
      EXPECT_GT(csmTest::DifferingPixels(image, plain, 24), 2000); // the posts' shadows
    }
  }
  EXPECT_LT(drawn, needed / 4); // a turn of 2 degrees brings in few pages
}

// Two viewports of one window sharing one pass chain, each close to the field from its own side:
// each renderer keeps its own base and pages, and each half of every frame of an orbit is what
// its view alone draws.
TEST(Pages, TwoViewportsSharingAPassKeepTheirOwnPages)
{
  Field pair(0.0, 640);
  vtkRenderer* left = pair.Scene.Renderer;
  left->SetViewport(0.0, 0.0, 0.5, 1.0);
  vtkNew<vtkRenderer> right;
  right->SetViewport(0.5, 0.0, 1.0, 1.0);
  right->SetBackground(left->GetBackground());
  right->AutomaticLightCreationOff();
  right->AddLight(pair.Scene.Light);
  right->AddActor(pair.Scene.Ground);
  for (const auto& post : pair.Posts)
  {
    right->AddActor(post);
  }
  right->GetActiveCamera()->DeepCopy(left->GetActiveCamera());
  pair.Scene.Window->AddRenderer(right);
  right->SetPass(left->GetPass());
  const double rightFrom = 130.0;
  right->GetActiveCamera()->Azimuth(rightFrom);
  right->ResetCameraClippingRange();
  pair.Scene.Frame();
  for (int frame = 1; frame <= 3; ++frame)
  {
    pair.Turn(2.0);
    right->GetActiveCamera()->Azimuth(2.0);
    right->ResetCameraClippingRange();
    auto both = pair.Scene.Frame();
    for (vtkRenderer* renderer : { left, static_cast<vtkRenderer*>(right) })
    {
      const auto& maps = pair.Baker->GetLightMaps(renderer);
      ASSERT_EQ(maps.size(), 1u);
      EXPECT_TRUE(maps[0].Pages.Active) << frame;
    }
    for (int half = 0; half < 2; ++half)
    {
      // (Alone in the same half of the same window: the blend bands' dither is by window pixel.)
      Field alone((half ? rightFrom : 0.0) + 2.0 * frame, 640);
      alone.Scene.Renderer->SetViewport(0.5 * half, 0.0, 0.5 + 0.5 * half, 1.0);
      auto image = alone.Scene.Frame();
      long differing = 0, far = 0;
      for (int y = 0; y < 240; ++y)
      {
        for (int x = 0; x < 320; ++x)
        {
          int most = 0;
          for (int c = 0; c < 3; ++c)
          {
            most = std::max(most,
              static_cast<int>(std::abs(both->GetScalarComponentAsDouble(x + 320 * half, y, 0, c) -
                image->GetScalarComponentAsDouble(x + 320 * half, y, 0, c))));
          }
          differing += most > 0;
          far += most > 24;
        }
      }
      EXPECT_LE(differing, 8) << frame << " " << half;
      EXPECT_EQ(far, 0) << frame << " " << half;
      if (frame == 3)
      {
        alone.Scene.Renderer->SetPass(nullptr);
        EXPECT_GT(csmTest::DifferingPixels(image, alone.Scene.Frame(), 24), 2000); // shadows
      }
    }
  }
}

// The pool holds the pages a view reads: 416 for a view of 640x480 or less whatever Resolution
// (at 4096 the atlas keeps the base, 8192 a side, and the 512 pages beside it: 12288 x 8192
// texels, 402 MB, where 3 x 3.5 Resolution would be 704 MB; at the default 2048 it is 3 x 3.5
// Resolution), in proportion for a larger view (1280x720: 3 x 416 pages, base and pool in a
// square) up to 4 x 416 (1920x1080 would take 6.75 x). Every visible sample finds the page of its
// level.
TEST(Pages, ThePoolIsSizedForTheViewNotForTheResolution)
{
  struct Case
  {
    int Resolution, Width, Height, AtlasWidth, AtlasHeight, LeastPool;
  };
  for (const Case& c :
    { Case{ 2048, 320, 240, 6144, 7168, 416 }, Case{ 4096, 320, 240, 12288, 8192, 416 },
      Case{ 2048, 1280, 720, 9984, 9984, 1248 }, Case{ 2048, 1920, 1080, 11264, 11264, 1664 } })
  {
    Field field(0.0, c.Width, c.Height);
    field.Baker->SetResolution(c.Resolution);
    field.Scene.Renderer->GetActiveCamera()->Dolly(3.0); // (close enough for pages at 4096)
    field.Scene.Renderer->ResetCameraClippingRange();
    field.Scene.Frame();
    field.Turn(2.0);
    field.Scene.Frame();
    ASSERT_TRUE(field.Maps().Pages.Active) << c.Resolution << " " << c.Width;
    const int* atlas = field.Maps().AtlasSize;
    EXPECT_EQ(atlas[0], c.AtlasWidth) << c.Resolution << " " << c.Width;
    EXPECT_EQ(atlas[1], c.AtlasHeight) << c.Resolution << " " << c.Width;
    const int basePages = 2 * c.Resolution / csm::kPageTexels;
    const int poolPages =
      (atlas[0] / csm::kPageTexels) * (atlas[1] / csm::kPageTexels) - basePages * basePages;
    EXPECT_GE(poolPages, c.LeastPool);
    EXPECT_LT(poolPages, c.LeastPool * 5 / 4);
    long needing = 0, missing = 0;
    SamplesFindTheirPages(field, needing, missing);
    EXPECT_GT(needing, 1000) << c.Resolution << " " << c.Width;
    EXPECT_EQ(missing, 0) << c.Resolution << " " << c.Width;
  }
}

// Pages serve a scene light seen through a perspective view; a light that follows the camera
// (nothing of its maps can be kept) and a parallel view keep the cascades.
TEST(Pages, CameraLightsAndParallelViewsKeepTheCascades)
{
  {
    Field field(0.0);
    field.Scene.Light->SetLightTypeToCameraLight();
    field.Scene.Light->SetPosition(0.3, 1.0, 1.0);
    field.Scene.Light->SetFocalPoint(0.0, 0.0, 0.0);
    for (int frame = 0; frame < 3; ++frame)
    {
      field.Turn(2.0);
      field.Scene.Frame();
      EXPECT_FALSE(field.Maps().Pages.Active);
      EXPECT_GT(field.Maps().GetNumberOfCascades(), 0);
    }
  }
  {
    Field field(0.0);
    field.Scene.Renderer->GetActiveCamera()->ParallelProjectionOn();
    field.Scene.Renderer->GetActiveCamera()->SetParallelScale(4.0);
    for (int frame = 0; frame < 3; ++frame)
    {
      field.Turn(2.0);
      field.Scene.Frame();
      EXPECT_FALSE(field.Maps().Pages.Active);
    }
  }
  {
    Field field(0.0); // the same field and view with a scene light: pages
    for (int frame = 0; frame < 3; ++frame)
    {
      field.Turn(2.0);
      field.Scene.Frame();
    }
    EXPECT_TRUE(field.Maps().Pages.Active);
  }
}

// A post that moves redraws the base's texels and the pages its boxes (before and after) reach
// across the light, no other, and the frame is the one a chain that draws every page afresh
// draws.
TEST(Pages, AMovedPostRedrawsOnlyThePagesItsBoxesReachAndShadesAsAFreshChain)
{
  Field moving(0.0);
  moving.Scene.Frame();
  for (int frame = 0; frame < 2; ++frame)
  {
    moving.Turn(2.0);
    moving.Scene.Frame();
  }
  ASSERT_TRUE(moving.Maps().Pages.Active);
  const int resident = moving.Baker->GetLastFrameStatistics().PagesResident;
  vtkActor* post = moving.Posts[7 * 15 + 8]; // (the post at (1.5, 4.5): near the eye)
  post->AddPosition(0.6, 0.0, 0.0);
  auto image = moving.Scene.Frame();
  const auto& stats = moving.Baker->GetLastFrameStatistics();
  ASSERT_TRUE(moving.Maps().Pages.Active);
  EXPECT_EQ(stats.CascadesRendered, 0); // the base patched, not drawn whole
  EXPECT_EQ(stats.CascadesPatched, 1);
  EXPECT_GT(stats.PagesDrawn, 0);
  EXPECT_LT(stats.PagesDrawn * 4, resident);
  Field fresh(4.0);
  fresh.Posts[7 * 15 + 8]->AddPosition(0.6, 0.0, 0.0);
  fresh.Turn(-2.0);
  fresh.Scene.Frame();
  fresh.Turn(2.0);
  auto again = fresh.Scene.Frame();
  ASSERT_TRUE(fresh.Maps().Pages.Active);
  EXPECT_LE(csmTest::DifferingPixels(image, again, 0), 8);
  EXPECT_EQ(csmTest::DifferingPixels(image, again, 24), 0);
  // The post's own shadow moved: the frame differs from the one before the move.
  moving.Posts[7 * 15 + 8]->AddPosition(-0.6, 0.0, 0.0);
  auto back = moving.Scene.Frame();
  EXPECT_GT(csmTest::DifferingPixels(image, back, 24), 50);
}

// The scene-fitted map that serves a far view alone is the base of the pages a near view needs:
// coming close draws only the pages (the map kept, its texels carried into the larger atlas),
// each frame as a fresh chain's, and moving away again keeps the pages and draws nothing.
TEST(Pages, TheSceneFittedMapOfAFarViewIsTheBaseOfTheNearViewsPages)
{
  Field field(0.0);
  vtkCamera* camera = field.Scene.Renderer->GetActiveCamera();
  camera->Dolly(0.2);
  field.Scene.Renderer->ResetCameraClippingRange();
  auto far = field.Scene.Frame();
  ASSERT_FALSE(field.Maps().Pages.Active);
  ASSERT_EQ(field.Maps().Cascades.size(), 1u);
  EXPECT_TRUE(field.Maps().Cascades[0].IsSceneFitted());
  camera->Dolly(5.0);
  field.Scene.Renderer->ResetCameraClippingRange();
  auto nearImage = field.Scene.Frame();
  const auto& stats = field.Baker->GetLastFrameStatistics();
  ASSERT_TRUE(field.Maps().Pages.Active);
  EXPECT_EQ(stats.CascadesRendered, 0); // the scene-fitted map kept as the base
  EXPECT_GT(stats.PagesDrawn, 0);
  EXPECT_EQ(stats.PagesDrawn, stats.PagesNeeded);
  EXPECT_LE(stats.TexelsRendered,
    double(stats.PagesDrawn) * (csm::kPageTexels + csm::kPageInterior) *
      (csm::kPageTexels + csm::kPageInterior));
  Field fresh(0.0);
  auto again = fresh.Scene.Frame();
  ASSERT_TRUE(fresh.Maps().Pages.Active);
  EXPECT_LE(csmTest::DifferingPixels(nearImage, again, 0), 8);
  EXPECT_EQ(csmTest::DifferingPixels(nearImage, again, 24), 0);
  camera->Dolly(0.2);
  field.Scene.Renderer->ResetCameraClippingRange();
  auto farAgain = field.Scene.Frame();
  ASSERT_TRUE(field.Maps().Pages.Active); // (stays paged: nothing to draw)
  EXPECT_EQ(field.Baker->GetLastFrameStatistics().CascadesRendered, 0);
  EXPECT_EQ(field.Baker->GetLastFrameStatistics().PagesDrawn, 0);
  EXPECT_EQ(field.Baker->GetLastFrameStatistics().TexelsRendered, 0.0);
  fresh.Scene.Renderer->SetPass(nullptr);
  auto plain = fresh.Scene.Frame();
  EXPECT_GT(csmTest::DifferingPixels(again, plain, 24), 2000); // the posts' shadows
  // Far again, the same shadows as the scene-fitted map alone drew, but where pages refine it
  // (the pages meet a share of the target: a few pixels along the shadows' edges).
  field.Scene.Renderer->SetPass(nullptr);
  auto plainFar = field.Scene.Frame();
  const long shadowed = csmTest::DifferingPixels(far, plainFar, 24);
  EXPECT_GT(shadowed, 1000);
  EXPECT_LT(csmTest::DifferingPixels(far, farAgain, 24) * 20, shadowed);
}

// Where the cascades would follow the view but the view's samples need no page (the near ground
// lies where no post's shadow can fall, outside the base), the base serves alone in an atlas of
// its own size: the atlas grows around it (an allocation that costs a frame) only when a page is
// needed. The frames are those of a fresh chain.
TEST(Pages, NoPageNeededLeavesTheAtlasAtTheBasesSize)
{
  auto nearViewOfFarPosts = [](double azimuth)
  {
    auto field = std::make_unique<Field>(0.0);
    for (auto& post : field->Posts)
    {
      if (post->GetPosition()[2] > -12.0)
      {
        field->Scene.Renderer->RemoveActor(post);
      }
    }
    vtkCamera* camera = field->Scene.Renderer->GetActiveCamera();
    camera->SetPosition(0.0, 1.25, 14.5);
    camera->SetFocalPoint(0.0, 0.0, 10.0);
    field->Turn(azimuth);
    return field;
  };
  auto moving = nearViewOfFarPosts(0.0);
  const int base = 2 * moving->Baker->GetResolution();
  int followingWanted = 0;
  for (int frame = 1; frame <= 6; ++frame)
  {
    moving->Turn(2.0);
    auto image = moving->Scene.Frame();
    const auto& maps = moving->Maps();
    EXPECT_EQ(moving->Baker->GetLastFrameStatistics().PagesNeeded, 0) << frame;
    EXPECT_FALSE(maps.Pages.Active) << frame;
    ASSERT_EQ(maps.GetNumberOfCascades(), 1) << frame;
    EXPECT_TRUE(maps.Cascades[0].IsSceneFitted()) << frame;
    EXPECT_EQ(maps.AtlasSize[0], base) << frame;
    EXPECT_EQ(maps.AtlasSize[1], base) << frame;
    vtkCascadedShadowMapPlanner* planner = moving->Baker->GetPlanner();
    followingWanted += planner->GetNumberOfPlannedCascades() > 1 ? 1 : 0;
    auto fresh = nearViewOfFarPosts(2.0 * frame);
    EXPECT_EQ(csmTest::DifferingPixels(image, fresh->Scene.Frame(), 24), 0) << frame;
  }
  EXPECT_GT(followingWanted, 0); // (the cascades would have followed the view)
}
