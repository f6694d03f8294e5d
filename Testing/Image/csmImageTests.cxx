// Image regression tests of the cascaded shadow passes, one scene per CTest test:
//   csmImageTests <name> -B <baseline dir> -V <name>.png -T <output dir>
// Each test renders the scene with our shadows and compares it against its committed baseline
// (vtkTesting), then renders it again without shadows and counts the pixels the shadows
// darkened: a scene where shadows must appear must have at least the expected count.
#include "csmScenes.h"
#include "csmTechnique.h"

#include "vtkCamera.h"
#include "vtkCascadedShadowMapBakerPass.h"
#include "vtkCascadedShadowMapPass.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkTesting.h"
#include "vtkUnsignedCharArray.h"
#include "vtkWindowToImageFilter.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <map>
#include <string>

namespace
{
constexpr double kPlatformFill = 0.25;

struct Test
{
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkRenderWindow> Window;
  csmScenes::ShadowOptions Options;
  int Width = 640;
  int Height = 480;
  long MinShadowPixels = 2000; // pixels the shadows must darken
  long MaxShadowPixels = -1;   // -1: no upper limit
};

vtkLight* AddDirectional(vtkRenderer* renderer, const double d[3], double intensity)
{
  vtkNew<vtkLight> light;
  light->SetLightTypeToSceneLight();
  light->SetPositional(false);
  light->SetFocalPoint(0, 0, 0);
  light->SetPosition(-d[0], -d[1], -d[2]);
  light->SetIntensity(intensity);
  renderer->AddLight(light);
  return light;
}

void AddFill(vtkRenderer* renderer, double intensity)
{
  vtkNew<vtkLight> fill;
  fill->SetLightTypeToHeadlight();
  fill->SetIntensity(intensity);
  renderer->AddLight(fill);
}

/// Light at gammaDeg to the view direction, in the plane of view and view-up.
void LightAtGamma(Test& t, double gammaDeg, double intensity = 0.85)
{
  vtkCamera* camera = t.Renderer->GetActiveCamera();
  double v[3], up[3], d[3];
  camera->GetDirectionOfProjection(v);
  camera->GetViewUp(up);
  const double g = gammaDeg * M_PI / 180.0;
  for (int i = 0; i < 3; ++i)
    d[i] = std::cos(g) * v[i] - std::sin(g) * up[i];
  AddDirectional(t.Renderer, d, intensity);
  AddFill(t.Renderer, kPlatformFill);
}

void Platform(Test& t, double offset = 0.0)
{
  csmScenes::Install(csmScenes::Platform(250000, offset), t.Renderer, double(t.Width) / t.Height);
}

std::map<std::string, std::function<void(Test&)>> Cases()
{
  std::map<std::string, std::function<void(Test&)>> cases;
  cases["TestPlatformPerpendicular"] = [](Test& t) {
    Platform(t);
    LightAtGamma(t, 90.0);
    t.MinShadowPixels = 8000;
  };
  cases["TestPlatformNearlyBehind"] = [](Test& t) {
    Platform(t);
    LightAtGamma(t, 2.0); // light almost along the view: shadows mostly hidden behind casters
    t.MinShadowPixels = 200;
  };
  cases["TestPlatformDuelingFrusta"] = [](Test& t) {
    Platform(t);
    // Low camera looking up at the derrick; the light comes from behind it toward the camera
    // and down: light and view directions nearly opposite (dueling frusta).
    vtkCamera* camera = t.Renderer->GetActiveCamera();
    camera->SetPosition(100.0, 5.0, 125.0);
    camera->SetFocalPoint(0.0, 50.0, 0.0);
    camera->SetViewAngle(60.0);
    camera->SetViewUp(0.0, 1.0, 0.0);
    camera->OrthogonalizeViewUp();
    t.Renderer->ResetCameraClippingRange();
    LightAtGamma(t, 178.0); // light facing the viewer
    t.MinShadowPixels = 8000;
  };
  cases["TestTowersLongRange"] = [](Test& t) {
    csmScenes::Install(csmScenes::Towers(), t.Renderer, double(t.Width) / t.Height);
    const double d[3] = { 0.8, -1.0, 0.25 };
    AddDirectional(t.Renderer, d, 0.85);
    AddFill(t.Renderer, kPlatformFill);
    t.Options.Cascades = 4;
    t.MinShadowPixels = 3000;
  };
  cases["TestPlatformWide"] = [](Test& t) {
    t.Width = 800;
    t.Height = 300;
    Platform(t);
    LightAtGamma(t, 60.0);
    t.MinShadowPixels = 5000;
  };
  cases["TestPlatformThreeLights"] = [](Test& t) {
    Platform(t);
    const double key[3] = { -0.45, -1.0, -0.35 };
    const double second[3] = { 0.7, -0.6, -0.2 };
    AddDirectional(t.Renderer, key, 0.55);
    AddDirectional(t.Renderer, second, 0.4);
    vtkNew<vtkLight> spot;
    spot->SetLightTypeToSceneLight();
    spot->SetPositional(true);
    spot->SetPosition(-10, 75, 25);
    spot->SetFocalPoint(-10, 0, 10);
    spot->SetConeAngle(30);
    spot->SetIntensity(0.6);
    t.Renderer->AddLight(spot);
    AddFill(t.Renderer, 0.15);
    t.MinShadowPixels = 8000;
  };
  cases["TestPlatformParallel"] = [](Test& t) {
    Platform(t);
    t.Renderer->GetActiveCamera()->ParallelProjectionOn();
    t.Renderer->GetActiveCamera()->SetParallelScale(55.0);
    t.Renderer->ResetCameraClippingRange();
    LightAtGamma(t, 70.0);
    t.MinShadowPixels = 8000;
  };
  cases["TestPlatformFarFromOrigin"] = [](Test& t) {
    Platform(t, 1.0e6);
    LightAtGamma(t, 90.0);
    t.MinShadowPixels = 8000;
  };
  cases["TestPlatformDebugCascades"] = [](Test& t) {
    Platform(t);
    LightAtGamma(t, 60.0);
    t.Options.Cascades = 3;
    t.Options.Debug = vtkCascadedShadowMapPass::DEBUG_CASCADES;
    t.MinShadowPixels = 0; // the debug colours replace the shading
  };
  cases["TestPlatformDebugError"] = [](Test& t) {
    Platform(t);
    LightAtGamma(t, 60.0);
    t.Options.Debug = vtkCascadedShadowMapPass::DEBUG_ERROR;
    t.MinShadowPixels = 0;
  };
  cases["TestEngineCAD"] = [](Test& t) {
    csmScenes::Scene scene;
    std::string error;
    const char* file = "/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb";
    if (!csmScenes::FromFile(file, scene, error))
    {
      std::fprintf(stderr, "%s\n", error.c_str());
      std::exit(1);
    }
    csmScenes::Install(scene, t.Renderer, double(t.Width) / t.Height);
    const double d[3] = { -0.3, -1.0, -0.5 };
    AddDirectional(t.Renderer, d, 0.85);
    AddFill(t.Renderer, kPlatformFill);
    t.MinShadowPixels = 5000;
  };
  return cases;
}

vtkSmartPointer<vtkImageData> Grab(vtkRenderWindow* window)
{
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->ReadFrontBufferOff();
  grab->Update();
  vtkSmartPointer<vtkImageData> image = vtkSmartPointer<vtkImageData>::New();
  image->DeepCopy(grab->GetOutput());
  return image;
}

/// Pixels at least 15% darker with shadows than without.
long DarkenedPixels(vtkImageData* shadowed, vtkImageData* plain)
{
  auto* a = vtkUnsignedCharArray::SafeDownCast(shadowed->GetPointData()->GetScalars());
  auto* b = vtkUnsignedCharArray::SafeDownCast(plain->GetPointData()->GetScalars());
  if (!a || !b || a->GetNumberOfTuples() != b->GetNumberOfTuples())
    return -1;
  const int nc = a->GetNumberOfComponents();
  long count = 0;
  for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
  {
    double la = 0, lb = 0;
    for (int c = 0; c < 3 && c < nc; ++c)
    {
      la += a->GetValue(nc * i + c);
      lb += b->GetValue(nc * i + c);
    }
    count += la < 0.85 * lb - 6.0;
  }
  return count;
}
} // namespace

int main(int argc, char* argv[])
{
  const auto cases = Cases();
  if (argc < 2 || !cases.count(argv[1]))
  {
    std::fprintf(stderr, "usage: csmImageTests <test> -B <baselines> -V <image> -T <dir>\ntests:");
    for (const auto& c : cases)
      std::fprintf(stderr, " %s", c.first.c_str());
    std::fprintf(stderr, "\n");
    return 1;
  }
  bool hasBaselineArgument = false;
  for (int i = 2; i < argc; ++i)
    hasBaselineArgument = hasBaselineArgument || std::strcmp(argv[i], "-V") == 0;
  if (!hasBaselineArgument)
  {
    std::fprintf(stderr, "missing -V <baseline image>: the comparison would not run\n");
    return 1;
  }

  Test t;
  t.Window->SetMultiSamples(0);
  t.Window->SetOffScreenRendering(1);
  t.Window->AddRenderer(t.Renderer);
  t.Renderer->SetBackground(0.75, 0.82, 0.9);
  t.Renderer->AutomaticLightCreationOff();
  cases.at(argv[1])(t);
  t.Window->SetSize(t.Width, t.Height);
  if (const char* debug = std::getenv("CSM_TEST_DEBUG_VIEW")) // diagnosis: render a debug view
    t.Options.Debug = std::atoi(debug);
  if (const char* technique = std::getenv("CSM_TEST_TECHNIQUE"))
    t.Options.Technique = technique;

  csmScenes::InstallTechnique(t.Renderer, t.Options);
  t.Window->Render();
  vtkSmartPointer<vtkImageData> shadowed = Grab(t.Window);
  // vtkTesting reads argv from index 1; our test name is not one of its flags.
  const int result = vtkTesting::Test(argc, argv, t.Window, 0.15);

  csmScenes::ShadowOptions none = t.Options;
  none.Technique = "none";
  csmScenes::InstallTechnique(t.Renderer, none);
  t.Window->Render();
  vtkSmartPointer<vtkImageData> plain = Grab(t.Window);
  const long darkened = DarkenedPixels(shadowed, plain);
  std::printf("shadowed_pixels: %ld (at least %ld)\n", darkened, t.MinShadowPixels);

  bool ok = result == vtkTesting::PASSED;
  if (result != vtkTesting::PASSED)
    std::printf("image comparison: %s\n", result == vtkTesting::FAILED ? "FAILED" : "NOT RUN");
  if (darkened < t.MinShadowPixels)
  {
    std::printf("too few shadowed pixels\n");
    ok = false;
  }
  return ok ? 0 : 1;
}
