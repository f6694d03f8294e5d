// SPDX-License-Identifier: BSD-3-Clause
// The depth comparison of unwarped (orthographic) maps with a flat ground drawn into them: they
// shade the box over the plane as the standard map does.
#include "vtkActor.h"
#include "vtkCascadedShadowMapBakerPass.h"
#include "vtkCascadedShadowMapPass.h"
#include "vtkCascadedShadowMapPlanner.h"
#include "vtkCubeSource.h"
#include "vtkPolyDataMapper.h"
#include "vtkRenderer.h"

#include "csmTestHelpers.h"

#include <gtest/gtest.h>

#include <cstdio>

namespace
{
using csmTest::BoxOverPlane;
using csmTest::DarkenedPixels;
} // namespace

// Light straight down onto a flat ground that is drawn into the maps (a small pillar reaches
// through it, so the ground may shadow the pillar's foot): the unwarped maps darken what the
// standard (warped) map darkens, for 2, 4 and 8 cascades. A far cascade holds only the ground,
// whose depth along the light is one value: its map's depth range must still leave the
// constant bias room above the rounding of the lookup.
TEST(Passes, UnwarpedMapsOfAGroundInTheMapsDarkenWhatTheStandardMapDarkens)
{
  BoxOverPlane scene;
  vtkNew<vtkCubeSource> pillarSource;
  pillarSource->SetBounds(5.0, 5.4, -1.0, 0.6, 2.0, 2.4);
  vtkNew<vtkPolyDataMapper> pillarMapper;
  pillarMapper->SetInputConnection(pillarSource->GetOutputPort());
  vtkNew<vtkActor> pillar;
  pillar->SetMapper(pillarMapper);
  scene.Renderer->AddActor(pillar);
  auto plain = scene.Render();
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(scene.Renderer);
  pass->GetShadowMapBakerPass()->LightSpacePagesOff(); // (the cascades' own behaviour)
  vtkCascadedShadowMapBakerPass* baker = pass->GetShadowMapBakerPass();
  baker->GetPlanner()->AdaptiveCascadesOff();
  for (int cascades : { 2, 4, 8 })
  {
    baker->GetPlanner()->SetNumberOfCascades(cascades);
    baker->GetPlanner()->SetWarpMode(vtkCascadedShadowMapPlanner::WARP_GENERALIZED);
    const long standard = DarkenedPixels(scene.Render(), plain);
    baker->GetPlanner()->SetWarpMode(vtkCascadedShadowMapPlanner::WARP_NONE);
    const long unwarped = DarkenedPixels(scene.Render(), plain);
    ASSERT_EQ(baker->GetLightMaps().size(), 1u);
    EXPECT_GE(baker->GetLightMaps()[0].GetNumberOfCascades(), 2) << cascades;
    EXPECT_EQ(baker->GetLastFrameStatistics().CastersWithoutReceivers, 0)
      << cascades; // the ground is drawn
    EXPECT_GT(standard, 800) << cascades;
    EXPECT_NEAR(unwarped, standard, 0.1 * standard) << cascades << " cascades";
    std::printf("%d cascades: standard map %ld darkened pixels, unwarped %ld\n", cascades, standard,
      unwarped);
  }
}
