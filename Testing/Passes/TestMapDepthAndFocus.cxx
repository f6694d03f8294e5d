// SPDX-License-Identifier: BSD-3-Clause
// Camera space maps (a comparison technique, CSM_COMPARISON_TECHNIQUES) focused at any depth:
// they shade the box over the plane as the standard map does.
#include "vtkActor.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCascadedShadowMapBakerPass.h"
#include "vtkCascadedShadowMapPass.h"
#include "vtkCascadedShadowMapPlanner.h"
#include "vtkCommand.h"
#include "vtkCubeSource.h"
#include "vtkPolyDataMapper.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"

#include "csmTestHelpers.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

namespace
{
using csmTest::BoxOverPlane;
using csmTest::DarkenedPixels;

/// Counts the WarningEvents of an object (vtkWarningMacro invokes one per message) and keeps
/// the last message.
struct WarningCounter
{
  int Count = 0;
  std::string Last;
  vtkNew<vtkCallbackCommand> Command;
  explicit WarningCounter(vtkObject* object)
  {
    this->Command->SetClientData(this);
    this->Command->SetCallback(
      [](vtkObject*, unsigned long, void* self, void* message)
      {
        auto* counter = static_cast<WarningCounter*>(self);
        ++counter->Count;
        counter->Last = message ? static_cast<const char*>(message) : "";
      });
    object->AddObserver(vtkCommand::WarningEvent, this->Command);
  }
};

bool MapsAreFinite(const vtkCascadedShadowMapBakerPass::LightMaps& maps)
{
  for (int c = 0; c < maps.GetNumberOfCascades(); ++c)
  {
    for (double v : maps.Cascades[c].WorldToMap)
    {
      if (!std::isfinite(v))
      {
        return false;
      }
    }
    if (!std::isfinite(maps.Cascades[c].DepthW))
    {
      return false;
    }
  }
  return true;
}
} // namespace

// Camera space maps (CameraSpace) at any focus: a focus beyond what the map can focus on in
// this view (past about the middle of the fitted depth range, or beyond the view) is clamped
// to the farthest one it can, with one warning per focus; the box's shadow stays as the
// standard map gives it, and no matrix holds a NaN or an infinity.
TEST(Passes, CameraSpaceMapsKeepTheShadowAtAnyFocus)
{
  BoxOverPlane scene; // the camera is 21 from the origin
  auto plain = scene.Render();
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  pass->SetPCFSize(
    1); // hard shadows: the maps differ in size (see CameraSpaceMapShadesLikeCascades)
  vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
  const long standard = DarkenedPixels(scene.Render(), plain);
  EXPECT_GT(standard, 800);
  WarningCounter warnings(baker->GetPlanner());
  baker->GetPlanner()->CameraSpaceOn();
  int expectedWarnings = 0;
  for (double focus : { 10.0, 25.0, 100.0, 500.0, 1.0e6 })
  {
    baker->GetPlanner()->SetCameraSpaceFocus(focus);
    const long cssm = DarkenedPixels(scene.Render(), plain);
    ASSERT_EQ(baker->GetLightMaps().size(), 1u);
    const auto& maps = baker->GetLightMaps()[0];
    EXPECT_EQ(maps.GetNumberOfCascades(), 1) << focus;
    EXPECT_GT(maps.Cascades[0].DepthW, 0.0) << focus;
    EXPECT_TRUE(MapsAreFinite(maps)) << focus;
    EXPECT_NEAR(cssm, standard, 0.1 * standard) << "focus " << focus;
    expectedWarnings += focus > 20.0; // the view's fitted range ends about 32 from the eye
    EXPECT_EQ(warnings.Count, expectedWarnings) << focus;
    // Said once per focus: the next frames are quiet.
    scene.Renderer->GetActiveCamera()->Azimuth(1.0);
    scene.Render();
    scene.Renderer->GetActiveCamera()->Azimuth(-1.0);
    EXPECT_EQ(warnings.Count, expectedWarnings) << focus;
    std::printf(
      "focus %g: standard map %ld darkened pixels, camera space map %ld\n", focus, standard, cssm);
  }
  EXPECT_NE(warnings.Last.find("CameraSpaceFocus"), std::string::npos) << warnings.Last;
}
