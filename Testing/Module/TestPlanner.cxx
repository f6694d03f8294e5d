// SPDX-License-Identifier: BSD-3-Clause
// vtkCascadedShadowMapPlanner: VTK camera and light in, the math's cascades out.
#include "csmAtlas.h"        // csm::resolutionCeilingForCount
#include "csmCascadeCount.h" // csm::computeShadowSetupForError
#include "csmTestHelpers.h"  // ErrorCounter
#include "csmVTKMath.h"      // csmCascadeReachesBox
#include "vtkCascadedShadowMapPlanner.h"

#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkLight.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

namespace
{
using csmTest::ErrorCounter;

void project(vtkMatrix4x4* m, const double p[3], double ndc[3])
{
  const double h[4] = { p[0], p[1], p[2], 1.0 };
  double out[4];
  m->MultiplyPoint(h, out);
  for (int i = 0; i < 3; ++i)
    ndc[i] = out[i] / out[3];
}

/// A camera 40 units from a scene of 40 x 16 x 40 under a directional light from above.
struct LitScene
{
  vtkNew<vtkCamera> Camera;
  vtkNew<vtkLight> Light;
  const double Bounds[6] = { -20, 20, -1, 15, -20, 20 };
  LitScene()
  {
    this->Camera->SetPosition(0, 5, 40);
    this->Camera->SetFocalPoint(0, 0, 0);
    this->Camera->SetViewUp(0, 1, 0);
    this->Camera->SetClippingRange(0.5, 500);
    this->Light->SetLightTypeToSceneLight();
    this->Light->SetPositional(false);
    this->Light->SetPosition(10, 100, 0);
    this->Light->SetFocalPoint(0, 0, 0);
  }
};
}

TEST(Planner, DefaultsArePapersRecommendation)
{
  vtkNew<vtkCascadedShadowMapPlanner> planner;
  // Up to 8 cascades, as many as the error target needs (Barroso & Celes use 2-4; more only
  // where four cannot reach it).
  EXPECT_EQ(planner->GetNumberOfCascades(), 8);
  EXPECT_TRUE(planner->GetAdaptiveCascades());
  EXPECT_EQ(planner->GetWarpMode(), vtkCascadedShadowMapPlanner::WARP_GENERALIZED);
  EXPECT_EQ(planner->GetSplitScheme(), vtkCascadedShadowMapPlanner::SPLIT_ADAPTIVE);
  EXPECT_DOUBLE_EQ(planner->GetAlpha(), 2.0);
  planner->SetNumberOfCascades(20);
  EXPECT_EQ(planner->GetNumberOfCascades(), 8);
  planner->SetNumberOfCascades(0);
  EXPECT_EQ(planner->GetNumberOfCascades(), 1);
  std::ostringstream os;
  planner->Print(os);
  EXPECT_NE(os.str().find("WarpMode: generalized"), std::string::npos);
}

TEST(Planner, PlansForAVtkCameraAndLight)
{
  LitScene scene;
  vtkCamera* camera = scene.Camera;
  camera->SetViewAngle(40);
  vtkLight* light = scene.Light;
  const double* bounds = scene.Bounds;
  vtkNew<vtkCascadedShadowMapPlanner> planner;
  planner->SetNumberOfCascades(3);
  ASSERT_EQ(planner->Plan(camera, 16.0 / 9.0, light, bounds), 3);
  EXPECT_STREQ(planner->GetLastMessage(), "");
  EXPECT_GT(planner->GetGammaDegrees(), 80.0);
  EXPECT_LT(planner->GetGammaDegrees(), 100.0);
  // Splits cover the part of the view that holds the scene, near to far.
  EXPECT_GT(planner->GetCascadeNear(0), 0.5);
  EXPECT_LT(planner->GetCascadeFar(2), 500.0);
  for (int i = 0; i < 2; ++i)
    EXPECT_DOUBLE_EQ(planner->GetCascadeFar(i), planner->GetCascadeNear(i + 1));
  // The focal point (inside the scene, in view) lands in the map of the cascade holding it.
  vtkNew<vtkMatrix4x4> m;
  const double focal[3] = { 0, 0, 0 };
  const double depth = std::sqrt(25.0 + 1600.0);
  for (int i = 0; i < 3; ++i)
  {
    if (depth >= planner->GetCascadeNear(i) && depth <= planner->GetCascadeFar(i))
    {
      planner->GetCascadeMatrix(i, m);
      double ndc[3];
      project(m, focal, ndc);
      for (double c : ndc)
        EXPECT_LE(std::abs(c), 1.0);
    }
  }
  EXPECT_GT(planner->GetStorageTotal(), planner->GetStorageOptimal());
}

TEST(Planner, HorizontalViewAngleIsConverted)
{
  vtkNew<vtkCamera> camera;
  camera->SetPosition(0, 0, 10);
  camera->SetClippingRange(1, 100);
  camera->SetViewAngle(60);
  const double down[3] = { 0, -1, 0 };
  vtkNew<vtkCascadedShadowMapPlanner> planner;
  planner->SetSplitScheme(vtkCascadedShadowMapPlanner::SPLIT_SINGLE);
  planner->SetWarpMode(vtkCascadedShadowMapPlanner::WARP_LISPSM);
  planner->Plan(camera, 2.0, down, nullptr);
  const double vertical = planner->GetStorageTotal();
  camera->UseHorizontalViewAngleOn();
  camera->SetViewAngle(2.0 * std::atan(2.0 * std::tan(M_PI / 6.0)) * 180.0 / M_PI);
  planner->Plan(camera, 2.0, down, nullptr);
  EXPECT_NEAR(planner->GetStorageTotal(), vertical, 1e-9 * vertical);
  // Overhead light, one LiSPSM map: Lloyd et al. 2006, Eq. 12 with f/n = 100, theta = 30 deg.
  EXPECT_NEAR(vertical, 99.0 / (2.0 * std::tan(M_PI / 6.0)), 1e-6 * vertical);
}

TEST(Planner, BadInputGivesNoCascadesAndAMessage)
{
  vtkObject::GlobalWarningDisplayOff();
  vtkNew<vtkCamera> camera;
  vtkNew<vtkCascadedShadowMapPlanner> planner;
  const double nanLight[3] = { NAN, -1, 0 };
  EXPECT_EQ(planner->Plan(camera, 1.0, nanLight, nullptr), 0);
  EXPECT_NE(std::string(planner->GetLastMessage()).find("light direction"), std::string::npos);
  EXPECT_EQ(planner->Plan(camera, 1.0, static_cast<vtkLight*>(nullptr), nullptr), 0);
  const double down[3] = { 0, -1, 0 };
  const double empty[6] = { 1, -1, 1, -1, 1, -1 }; // VTK's bounds of nothing
  EXPECT_EQ(planner->Plan(camera, 1.0, down, empty), 0);
  EXPECT_EQ(planner->Plan(camera, 0.0, down, nullptr), 0); // zero-size viewport
  vtkNew<vtkMatrix4x4> m;
  m->Zero();
  planner->GetCascadeMatrix(0, m); // out of range: identity, not garbage
  EXPECT_TRUE(m->IsIdentity());
  vtkObject::GlobalWarningDisplayOn();
}

// vtkSetClampMacro lets NaN through: the planner refuses it for Lambda, Alpha and ErrorTarget.
TEST(Planner, NonFiniteOptionsAreRefused)
{
  vtkNew<vtkCascadedShadowMapPlanner> planner;
  ErrorCounter errors(planner);
  planner->SetLambda(0.25);
  planner->SetAlpha(3.0);
  const vtkMTimeType time = planner->GetMTime();
  planner->SetLambda(NAN);
  planner->SetAlpha(NAN);
  planner->SetAlpha(INFINITY);
  planner->SetErrorTarget(NAN);
  EXPECT_DOUBLE_EQ(planner->GetLambda(), 0.25);
  EXPECT_DOUBLE_EQ(planner->GetAlpha(), 3.0);
  EXPECT_DOUBLE_EQ(planner->GetErrorTarget(), 0.7); // the default stays
  EXPECT_EQ(errors.Count, 4);
  EXPECT_EQ(planner->GetMTime(), time);
  planner->SetLambda(7.0); // finite values are still clamped, without a message
  EXPECT_DOUBLE_EQ(planner->GetLambda(), 1.0);
  planner->SetErrorTarget(-2.0);
  EXPECT_DOUBLE_EQ(planner->GetErrorTarget(), 0.0);
  EXPECT_EQ(errors.Count, 4);
}

// A degenerate light beside a good one is reported once, not on every plan.
TEST(Planner, BadLightIsReportedOncePerChange)
{
  vtkNew<vtkCamera> camera;
  camera->SetPosition(0, 5, 10);
  camera->SetFocalPoint(0, 0, 0);
  vtkNew<vtkLight> good, bad;
  good->SetPositional(false);
  good->SetPosition(0, 10, 0);
  good->SetFocalPoint(0, 0, 0);
  bad->SetPositional(false);
  bad->SetPosition(1, 1, 1);
  bad->SetFocalPoint(1, 1, 1); // no direction
  const double bounds[6] = { -5, 5, 0, 2, -5, 5 };
  vtkNew<vtkCascadedShadowMapPlanner> planner;
  ErrorCounter errors(planner);
  for (int frame = 0; frame < 20; ++frame)
  {
    EXPECT_GT(planner->Plan(camera, 1.0, good.Get(), bounds), 0);
    EXPECT_EQ(planner->Plan(camera, 1.0, bad.Get(), bounds), 0);
  }
  EXPECT_EQ(errors.Count, 1);
  bad->SetFocalPoint(1, 1, 1); // unchanged: no MTime change
  planner->Plan(camera, 1.0, bad.Get(), bounds);
  EXPECT_EQ(errors.Count, 1);
  bad->SetPosition(2, 2, 2); // changed, still bad: reported again, once
  bad->SetFocalPoint(2, 2, 2);
  planner->Plan(camera, 1.0, bad.Get(), bounds);
  planner->Plan(camera, 1.0, bad.Get(), bounds);
  EXPECT_EQ(errors.Count, 2);
}

TEST(Planner, CascadeReachesBoxAndCascadeAtDepth)
{
  // An orthographic light clip volume [-1, 1]^3 (identity matrix).
  const double identity[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
  const double inside[6] = { -0.5, 0.5, -0.5, 0.5, -0.5, 0.5 };
  const double beside[6] = { 2.0, 3.0, -0.5, 0.5, -0.5, 0.5 };
  const double nearer[6] = { -0.5, 0.5, -0.5, 0.5, -3.0, -2.0 }; // in front of the near plane
  EXPECT_TRUE(csmCascadeReachesBox(identity, inside, false));
  EXPECT_FALSE(csmCascadeReachesBox(identity, beside, true));
  EXPECT_FALSE(csmCascadeReachesBox(identity, nearer, false));
  EXPECT_TRUE(csmCascadeReachesBox(identity, nearer, true));
  const double far[2] = { 4.0, 40.0 };
  EXPECT_EQ(vtkCascadedShadowMapPlanner::GetCascadeAtDepth(3.0, 1.0, far, 2), 0);
  EXPECT_EQ(vtkCascadedShadowMapPlanner::GetCascadeAtDepth(5.0, 1.0, far, 2), 1);
  EXPECT_EQ(vtkCascadedShadowMapPlanner::GetCascadeAtDepth(50.0, 1.0, far, 2), -1);
}

TEST(Planner, AdaptiveCascadesTakeTheFewestThatMeetTheTarget)
{
  // A short view (f/n = 10) with the light overhead: one cascade meets m <= 1.5 in a 600-pixel
  // image with 2048-texel maps (csm::computeShadowSetupForError); a long one (f/n = 100) with
  // the light behind the viewer needs more than two. Without the image, NumberOfCascades.
  vtkNew<vtkCamera> camera;
  camera->SetPosition(0, 0, 0);
  camera->SetFocalPoint(0, 0, -1);
  camera->SetViewAngle(40);
  camera->SetClippingRange(1, 10);
  const double down[3] = { 0, -1, 0 };
  const double behind[3] = { 0, 0, -1 };
  vtkNew<vtkCascadedShadowMapPlanner> planner;
  planner->SetNumberOfCascades(8);
  planner->SetErrorTarget(1.5);
  EXPECT_TRUE(planner->GetAdaptiveCascades()); // the default
  EXPECT_EQ(planner->Plan(camera, 4.0 / 3.0, down, nullptr, 600, 2048), 1);
  EXPECT_EQ(planner->Plan(camera, 4.0 / 3.0, down, nullptr), 8); // no image: no error model
  // Hysteresis: after 8, one cascade (error 1.24 on a 2048² map, 0.62 on the 4096² that the
  // atlas of four 2048² tiles gives a single cascade) meets a target of 0.7 but not by the margin
  // (0.8 x 0.7); 8 still meet it and stay.
  planner->SetErrorTarget(0.7);
  EXPECT_EQ(planner->Plan(camera, 4.0 / 3.0, down, nullptr, 600, 2048), 8);
  planner->SetErrorTarget(1.5);
  planner->AdaptiveCascadesOff();
  EXPECT_EQ(planner->Plan(camera, 4.0 / 3.0, down, nullptr, 600, 2048), 8);
  planner->AdaptiveCascadesOn();
  camera->SetClippingRange(1, 100);
  const int count = planner->Plan(camera, 4.0 / 3.0, behind, nullptr, 600, 2048);
  EXPECT_GT(count, 2);
  EXPECT_LE(count, 8);
  for (int i = 0; i < count; ++i)
  {
    EXPECT_LE(planner->GetCascadeMaximumAliasing(i) * 600.0 /
        csm::resolutionCeilingForCount(count, 8, 2048).width,
      1.5);
  }
}

// The atlas is planned with the cascades: its texture, each cascade's tile and largest map, the
// same ones the count was judged with; a GL texture limit shrinks the tiles the count is judged
// on, not only the texture.
TEST(Planner, PlansTheAtlasWithTheCascades)
{
  LitScene scene;
  vtkCamera* camera = scene.Camera;
  vtkLight* light = scene.Light;
  const double* bounds = scene.Bounds;
  vtkNew<vtkCascadedShadowMapPlanner> planner;
  planner->SetNumberOfCascades(4);
  planner->AdaptiveCascadesOff();
  planner->SetAtlasResolution(2048);
  ASSERT_EQ(planner->Plan(camera, 1.0, light, bounds, 480, 2048), 4);
  int size[2], tile[4], ceiling[2], resolution[2];
  planner->GetAtlasSize(size);
  EXPECT_EQ(size[0], 4096);
  EXPECT_EQ(size[1], 4096);
  EXPECT_FALSE(planner->GetAtlasShrunk());
  for (int i = 0; i < 4; ++i)
  {
    planner->GetCascadeTile(i, tile);
    EXPECT_EQ(tile[0], (i % 2) * 2048) << i;
    EXPECT_EQ(tile[1], (i / 2) * 2048) << i;
    EXPECT_EQ(tile[2], 2048);
    planner->GetCascadeResolutionCeiling(i, ceiling);
    EXPECT_EQ(ceiling[0], 2048);
    planner->GetCascadeResolution(i, 480, 64, resolution);
    EXPECT_LE(resolution[0], ceiling[0]);
    EXPECT_GT(resolution[0], 0);
  }
  planner->GetCascadeTile(4, tile); // beyond the plan: an empty tile
  EXPECT_EQ(tile[2], 0);
  // A texture limit of 2048 texels: tiles of 1024, and the maps within them.
  planner->SetMaximumTextureSize(2048);
  ASSERT_EQ(planner->Plan(camera, 1.0, light, bounds, 480, 2048), 4);
  planner->GetAtlasSize(size);
  EXPECT_EQ(size[0], 2048);
  EXPECT_TRUE(planner->GetAtlasShrunk());
  for (int i = 0; i < 4; ++i)
  {
    planner->GetCascadeTile(i, tile);
    EXPECT_EQ(tile[2], 1024);
    planner->GetCascadeResolution(i, 480, 64, resolution);
    EXPECT_LE(resolution[0], 1024);
    EXPECT_LE(resolution[1], 1024);
  }
}

// A map serves the very view it was planned for, orthographic or warped, scene-fitted or not
// (an orthographic map that follows the view is snapped to its texel grid within its room; a
// scene-fitted one is not snapped, or its edge would cut into the scene).
TEST(Planner, EveryMapServesTheViewItWasPlannedFor)
{
  LitScene scene;
  for (int warp :
    { vtkCascadedShadowMapPlanner::WARP_NONE, vtkCascadedShadowMapPlanner::WARP_GENERALIZED })
  {
    vtkNew<vtkCascadedShadowMapPlanner> planner;
    planner->SetWarpMode(warp);
    planner->SetAtlasResolution(2048);
    // A ground and a block on it: casters whose shadows a scene-fitted map can hold.
    const double ground[6] = { -20, 20, -1, 0, -20, 20 }, block[6] = { -2, 2, 0, 15, -2, 2 };
    planner->AddReceiverBounds(ground);
    planner->AddReceiverBounds(block);
    planner->AddCasterLoad(ground, 2.0, 0);
    planner->AddCasterLoad(block, 12.0, 1);
    bool sceneFitted = false;
    for (double distance : { 40.0, 400.0, 4000.0 })
    {
      scene.Camera->SetPosition(0, 5, distance);
      scene.Camera->SetClippingRange(0.5, 2.0 * distance);
      const int count =
        planner->Plan(scene.Camera, 4.0 / 3.0, scene.Light, scene.Bounds, 480, 2048);
      ASSERT_GT(count, 0);
      for (int c = 0; c < count; ++c)
      {
        int ceiling[2], resolution[2];
        planner->GetCascadeResolutionCeiling(c, ceiling);
        planner->GetCascadeResolution(c, 480, 64, ceiling, resolution);
        vtkNew<vtkMatrix4x4> m;
        planner->GetCascadeMatrix(c, m, 0.0, resolution);
        EXPECT_NEAR(planner->CompareKeptMap(c, m->GetData(), 0.0, resolution[0]), 1.0, 1e-6)
          << "warp " << warp << ", distance " << distance << ", cascade " << c;
        sceneFitted = sceneFitted || planner->GetCascadeSceneFitted(c);
      }
    }
    EXPECT_TRUE(sceneFitted) << "warp " << warp;
  }
}
