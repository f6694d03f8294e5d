// SPDX-License-Identifier: BSD-3-Clause
// Concave creases in shadow, against the ray-cast truth (Embree): a machined L-bracket
// (csmScenes::Bracket: a faceted fillet on the inside bend, a hole through each leg, one closed
// surface) seen from close up under a light 20 degrees above the horizon, from outside the
// upright leg and across the bend. The bracket is drawn into the maps from behind; its faces
// turned away from the light touch the shadowed faces turned toward it along the fillet's
// facets and the holes' walls, where a depth offset or bias on either side lets light through in
// lines one pixel wide.
#include "csmScenes.h"
#include "csmTestHelpers.h"
#include "csmTruth.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCascadedShadowMapBakerPass.h"
#include "vtkCascadedShadowMapPass.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace
{
constexpr int W = 640, H = 480;

/// A frame and its image (the grab renders it again).
vtkSmartPointer<vtkImageData> Grab(vtkRenderWindow* window)
{
  return csmTest::Grab(window, true);
}

/// The bracket at its default view, plain white with diffuse light only (the truth's factor is
/// the shadowed render over the plain one), under one directional light `elevation` degrees
/// above the horizon, coming from -x and turned `azimuth` degrees toward +z.
struct BracketView
{
  csmScenes::Scene Scene = csmScenes::Bracket();
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkRenderWindow> Window;
  vtkNew<vtkLight> Light;
  double Direction[3]; ///< the light's direction of travel

  BracketView(double elevation, double azimuth)
  {
    const double e = vtkMath::RadiansFromDegrees(elevation);
    const double a = vtkMath::RadiansFromDegrees(azimuth);
    this->Direction[0] = std::cos(e) * std::cos(a);
    this->Direction[1] = -std::sin(e);
    this->Direction[2] = -std::cos(e) * std::sin(a);
    this->Window->SetSize(W, H);
    this->Window->SetMultiSamples(0);
    this->Window->SetOffScreenRendering(1);
    this->Window->AddRenderer(this->Renderer);
    this->Renderer->SetBackground(0, 0, 0);
    this->Renderer->AutomaticLightCreationOff();
    this->Light->SetLightTypeToSceneLight();
    this->Light->SetPositional(false);
    this->Light->SetPosition(-this->Direction[0], -this->Direction[1], -this->Direction[2]);
    this->Light->SetFocalPoint(0, 0, 0);
    this->Renderer->AddLight(this->Light);
    for (auto& actor : this->Scene.Actors)
    {
      actor->GetProperty()->SetColor(1, 1, 1);
      actor->GetProperty()->SetAmbient(0.0);
      actor->GetProperty()->SetDiffuse(1.0);
      actor->GetProperty()->SetSpecular(0.0);
    }
    csmScenes::Install(this->Scene, this->Renderer, double(W) / H);
  }

  /// Misclassified pixels of a factor image against the truth.
  csmTruth::Classification Classify(vtkImageData* shadowed, vtkImageData* plain)
  {
    csmTruth::RayScene rays;
    rays.Build(this->Renderer);
    const auto surfaces = rays.CastPrimary(this->Renderer->GetActiveCamera(), W, H);
    const auto comparable = csmTruth::ComparablePixels(surfaces, W, H, this->Direction);
    std::vector<char> occluded(surfaces.size(), 0);
    for (size_t k = 0; k < surfaces.size(); ++k)
      occluded[k] = comparable[k] && rays.Occluded(surfaces[k], this->Direction);
    return csmTruth::Classify(
      surfaces, comparable, occluded, csmTruth::FactorFromRenders(shadowed, plain));
  }
};
} // namespace

TEST(Creases, TheBracketIsOneClosedSurface)
{
  BracketView view(20.0, 35.0);
  ASSERT_EQ(view.Scene.Actors.size(), 1u);
  EXPECT_EQ(view.Scene.Name, "bracket");
  EXPECT_GT(view.Scene.Triangles, 300);
  vtkCascadedShadowMapPass* pass = vtkCascadedShadowMapPass::UseShadowsOn(view.Renderer);
  view.Window->Render();
  // Closed and consistently wound: drawn into the maps from behind (CullClosedCasters).
  EXPECT_TRUE(pass->GetShadowMapBakerPass()->DrawsFromBehind(view.Scene.Actors[0]));
}

// The defaults misclassify at most 0.05 % of the light-facing pixels (0.063 % before the maps
// held the exit layer at its own depth, with about 50 pixels of light along the fillet's
// facets), and no lit face darkens.
TEST(Creases, LightDoesNotLeakAlongConcaveCreasesInShadow)
{
  BracketView view(20.0, 35.0);
  auto plain = Grab(view.Window);
  vtkCascadedShadowMapPass::UseShadowsOn(view.Renderer);
  auto shadowed = Grab(view.Window);
  const csmTruth::Classification c = view.Classify(shadowed, plain);
  std::printf("considered %ld, false shadow %ld, false light %ld: %.3f%% misclassified\n",
    c.Considered, c.FalseShadow, c.FalseLight, c.MismatchPct());
  EXPECT_GT(c.Considered, 50000);
  EXPECT_LE(c.MismatchPct(), 0.05);
  EXPECT_LE(c.FalseShadow, 5);
  // Without shadows the bend's shadow is all false light: the measure can fail.
  const csmTruth::Classification none = view.Classify(plain, plain);
  EXPECT_GT(none.FalseLight, 10000);
}
