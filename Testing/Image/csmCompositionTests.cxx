// SPDX-License-Identifier: BSD-3-Clause
// Our shadows composed with VTK's other render passes, one CTest test per composition:
//   csmCompositionTests <name> -B <baseline dir> -V <name>.png -T <output dir>
// Each test renders one scene three ways:
//   composed:      the other pass and our shadows together (compared against the baseline);
//   without ours:  the same chain without our passes: the composed image must be darker where
//                  the shadows fall (the shadow survives the composition);
//   without other: our shadows alone: the composed image must show the other pass's effect.
// The two comparison images are written beside the test's image in the -T folder.
#include "csmTestHelpers.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCameraPass.h"
#include "vtkCascadedShadowMapBakerPass.h"
#include "vtkCascadedShadowMapPass.h"
#include "vtkCubeSource.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkPNGWriter.h"
#include "vtkPointData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderPassCollection.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSSAOPass.h"
#include "vtkSequencePass.h"
#include "vtkSphereSource.h"
#include "vtkTesting.h"
#include "vtkToneMappingPass.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace
{
using csmTest::DarkenedPixels;
using csmTest::Grab;
using Image = vtkSmartPointer<vtkImageData>;

/// Ground, a pillar standing on it (ambient occlusion where they meet), a sphere above the ground
/// (its shadow in the open); a directional scene light (shadowed) and a weak headlight (not).
struct Scene
{
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkRenderWindow> Window;
  vtkNew<vtkActor> Pillar;
  vtkNew<vtkActor> Sphere;
  vtkNew<vtkLight> Sun;
  vtkNew<vtkLight> Fill;
  std::string OutputDir;

  Scene()
  {
    vtkSmartPointer<vtkActor> ground = csmTest::GroundPlane(8.0, 16);
    ground->GetProperty()->SetColor(0.85, 0.85, 0.8);
    this->Renderer->AddActor(ground);
    vtkNew<vtkCubeSource> pillar;
    pillar->SetBounds(-3.5, -1.5, 0.0, 3.0, -2.5, -0.5);
    vtkNew<vtkPolyDataMapper> pillarMapper;
    pillarMapper->SetInputConnection(pillar->GetOutputPort());
    this->Pillar->SetMapper(pillarMapper);
    this->Pillar->GetProperty()->SetColor(0.35, 0.55, 0.85);
    this->Renderer->AddActor(this->Pillar);
    vtkNew<vtkSphereSource> sphere;
    sphere->SetCenter(1.5, 2.6, 1.5);
    sphere->SetRadius(0.9);
    sphere->SetThetaResolution(48);
    sphere->SetPhiResolution(24);
    vtkNew<vtkPolyDataMapper> sphereMapper;
    sphereMapper->SetInputConnection(sphere->GetOutputPort());
    this->Sphere->SetMapper(sphereMapper);
    this->Sphere->GetProperty()->SetColor(0.9, 0.45, 0.2);
    this->Renderer->AddActor(this->Sphere);

    this->Renderer->AutomaticLightCreationOff();
    this->Sun->SetLightTypeToSceneLight();
    this->Sun->SetPositional(false);
    this->Sun->SetPosition(0.3, 1.0, -0.8); // light travels along (-0.3, -1, 0.8): shadows in front
    this->Sun->SetFocalPoint(0, 0, 0);
    this->Renderer->AddLight(this->Sun);
    this->Fill->SetLightTypeToHeadlight();
    this->Fill->SetIntensity(0.25);
    this->Renderer->AddLight(this->Fill);
    this->Renderer->SetBackground(0.75, 0.82, 0.9);

    this->Window->SetSize(400, 300);
    this->Window->SetMultiSamples(0);
    this->Window->SetOffScreenRendering(1);
    this->Window->AddRenderer(this->Renderer);
    vtkCamera* camera = this->Renderer->GetActiveCamera();
    camera->SetPosition(7.0, 7.5, 12.0);
    camera->SetFocalPoint(0.0, 0.6, 0.0);
    camera->SetViewUp(0, 1, 0);
    this->Renderer->ResetCameraClippingRange();
  }

  /// Sets the renderer's pass, after releasing the graphics resources of the one it replaces
  /// (VTK's image-processing passes expect it before they are destroyed).
  void SetPass(vtkRenderPass* pass)
  {
    if (vtkRenderPass* old = this->Renderer->GetPass())
      old->ReleaseGraphicsResources(this->Window);
    this->Renderer->SetPass(pass);
  }

  Image Render()
  {
    this->Window->Render();
    return Grab(this->Window);
  }

  void Save(vtkImageData* image, const std::string& name) const
  {
    if (this->OutputDir.empty())
      return;
    vtkNew<vtkPNGWriter> writer;
    writer->SetFileName((this->OutputDir + "/" + name + ".png").c_str());
    writer->SetInputData(image);
    writer->Write();
  }
};

/// Our shadows as VTK's shadow pair is used: camera pass -> sequence (baker, shadow pass). The
/// shadow pass draws through the renderer's own geometry path (opaque, translucent with depth
/// peeling or not, FXAA, volumes, overlays).
vtkSmartPointer<vtkRenderPass> ShadowChain()
{
  vtkNew<vtkCascadedShadowMapPass> shadows;
  vtkNew<vtkRenderPassCollection> passes;
  passes->AddItem(shadows->GetShadowMapBakerPass());
  passes->AddItem(shadows);
  vtkNew<vtkSequencePass> sequence;
  sequence->SetPasses(passes);
  auto camera = vtkSmartPointer<vtkCameraPass>::New();
  camera->SetDelegatePass(sequence);
  return camera;
}

/// Pixels whose brightness (R + G + B) differs by more than `levels`, and of them those that lie
/// in a flat region of `reference` (its 3x3 neighbourhood's brightness within `flat` levels).
void ChangedPixels(vtkImageData* a, vtkImageData* b, vtkImageData* reference, int levels, int flat,
  long& changed, long& changedInFlat)
{
  changed = changedInFlat = 0;
  int dims[3];
  a->GetDimensions(dims);
  auto* pa = vtkUnsignedCharArray::SafeDownCast(a->GetPointData()->GetScalars());
  auto* pb = vtkUnsignedCharArray::SafeDownCast(b->GetPointData()->GetScalars());
  auto* pr = vtkUnsignedCharArray::SafeDownCast(reference->GetPointData()->GetScalars());
  const int n = pa->GetNumberOfComponents();
  auto brightness = [n](vtkUnsignedCharArray* p, vtkIdType i)
  { return int(p->GetValue(n * i)) + p->GetValue(n * i + 1) + p->GetValue(n * i + 2); };
  for (int y = 1; y + 1 < dims[1]; ++y)
  {
    for (int x = 1; x + 1 < dims[0]; ++x)
    {
      const vtkIdType i = vtkIdType(y) * dims[0] + x;
      if (std::abs(brightness(pa, i) - brightness(pb, i)) <= levels)
        continue;
      ++changed;
      int lo = 3 * 255, hi = 0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
        {
          const int v = brightness(pr, i + vtkIdType(dy) * dims[0] + dx);
          lo = std::min(lo, v);
          hi = std::max(hi, v);
        }
      changedInFlat += hi - lo <= flat;
    }
  }
}

/// Pixels with a channel at 255.
long SaturatedPixels(vtkImageData* image)
{
  auto* p = vtkUnsignedCharArray::SafeDownCast(image->GetPointData()->GetScalars());
  const int n = p->GetNumberOfComponents();
  long count = 0;
  for (vtkIdType i = 0; i < p->GetNumberOfTuples(); ++i)
    count +=
      p->GetValue(n * i) == 255 || p->GetValue(n * i + 1) == 255 || p->GetValue(n * i + 2) == 255;
  return count;
}

/// The pixels an actor covers: it alone, unlit white on black.
std::vector<char> Silhouette(Scene& scene, vtkActor* actor)
{
  vtkRenderPass* pass = scene.Renderer->GetPass();
  if (pass)
    pass->Register(nullptr);
  scene.Renderer->SetPass(nullptr);
  double background[3];
  scene.Renderer->GetBackground(background);
  scene.Renderer->SetBackground(0, 0, 0);
  vtkPropCollection* props = scene.Renderer->GetViewProps();
  std::vector<int> visible;
  props->InitTraversal();
  while (vtkProp* prop = props->GetNextProp())
  {
    visible.push_back(prop->GetVisibility());
    prop->SetVisibility(prop == actor);
  }
  const double opacity = actor->GetProperty()->GetOpacity();
  actor->GetProperty()->SetOpacity(1.0);
  actor->GetProperty()->LightingOff();
  Image image = scene.Render();
  actor->GetProperty()->LightingOn();
  actor->GetProperty()->SetOpacity(opacity);
  size_t k = 0;
  props->InitTraversal();
  while (vtkProp* prop = props->GetNextProp())
    prop->SetVisibility(visible[k++]);
  scene.Renderer->SetBackground(background);
  scene.Renderer->SetPass(pass);
  if (pass)
    pass->UnRegister(nullptr);
  auto* p = vtkUnsignedCharArray::SafeDownCast(image->GetPointData()->GetScalars());
  std::vector<char> mask(p->GetNumberOfTuples());
  for (vtkIdType i = 0; i < p->GetNumberOfTuples(); ++i)
    mask[i] = p->GetComponent(i, 0) + p->GetComponent(i, 1) + p->GetComponent(i, 2) > 0;
  return mask;
}

/// Pixels of the mask whose brightness differs by more than `levels` from both a's and b's.
long DifferingFromBoth(
  vtkImageData* image, vtkImageData* a, vtkImageData* b, const std::vector<char>& mask, int levels)
{
  auto* p = vtkUnsignedCharArray::SafeDownCast(image->GetPointData()->GetScalars());
  auto* pa = vtkUnsignedCharArray::SafeDownCast(a->GetPointData()->GetScalars());
  auto* pb = vtkUnsignedCharArray::SafeDownCast(b->GetPointData()->GetScalars());
  const int n = p->GetNumberOfComponents();
  auto brightness = [n](vtkUnsignedCharArray* q, vtkIdType i)
  { return int(q->GetValue(n * i)) + q->GetValue(n * i + 1) + q->GetValue(n * i + 2); };
  long count = 0;
  for (vtkIdType i = 0; i < p->GetNumberOfTuples() && i < vtkIdType(mask.size()); ++i)
    count += mask[i] && std::abs(brightness(p, i) - brightness(pa, i)) > levels &&
      std::abs(brightness(p, i) - brightness(pb, i)) > levels;
  return count;
}

std::vector<char> Inverted(std::vector<char> mask)
{
  for (char& inside : mask)
    inside = !inside;
  return mask;
}

struct Result
{
  Image Composed;
  bool Ok = true;
  void Expect(bool condition, const char* what)
  {
    if (!condition)
    {
      std::printf("FAILED: %s\n", what);
      this->Ok = false;
    }
  }
};

// ---- SSAO: vtkSSAOPass with the shadow chain as its delegate. ----
// SSAO renders its delegate into its own framebuffer (colour, view-space position and normal,
// depth), then darkens the colour by the occlusion it computes from position and normal.
Result SSAO(Scene& scene)
{
  Result r;
  auto ssaoOf = [](vtkRenderPass* delegate)
  {
    auto ssao = vtkSmartPointer<vtkSSAOPass>::New();
    ssao->SetRadius(0.6);
    ssao->SetBias(0.01);
    ssao->SetKernelSize(64);
    ssao->BlurOn();
    ssao->SetDelegatePass(delegate);
    return ssao;
  };
  vtkNew<vtkRenderStepsPass> steps;
  scene.SetPass(ssaoOf(steps));
  Image withoutOurs = scene.Render();
  scene.SetPass(ShadowChain());
  Image withoutOther = scene.Render();
  scene.SetPass(ssaoOf(ShadowChain()));
  r.Composed = scene.Render();
  scene.Save(withoutOurs, "TestCompositionSSAO-without-csm");
  scene.Save(withoutOther, "TestCompositionSSAO-without-ssao");

  const long shadow = DarkenedPixels(r.Composed, withoutOurs);
  const long occluded = DarkenedPixels(r.Composed, withoutOther);
  const long brightened = DarkenedPixels(withoutOther, r.Composed);
  std::printf("shadowed_pixels (SSAO with ours against SSAO alone): %ld\n", shadow);
  std::printf("occluded_pixels (SSAO with ours against ours alone): %ld, brightened: %ld\n",
    occluded, brightened);
  r.Expect(shadow >= 1000, "the shadows darken at least 1000 pixels under SSAO");
  r.Expect(occluded >= 200, "SSAO darkens at least 200 pixels of the shadowed image");
  r.Expect(brightened == 0, "SSAO brightens no pixel");
  return r;
}

// ---- FXAA: renderer->UseFXAAOn() with the shadow chain. ----
// The renderer runs FXAA in its geometry path after the translucent geometry, which the shadow
// pass calls: the shadowed image is anti-aliased, shadow edges included.
Result FXAA(Scene& scene)
{
  Result r;
  scene.Renderer->UseFXAAOn();
  Image withoutOurs = scene.Render();
  scene.SetPass(ShadowChain());
  r.Composed = scene.Render();
  scene.Renderer->UseFXAAOff();
  Image withoutOther = scene.Render();
  scene.Renderer->UseFXAAOn(); // the composed chain again, for the baseline comparison
  scene.Save(withoutOurs, "TestCompositionFXAA-without-csm");
  scene.Save(withoutOther, "TestCompositionFXAA-without-fxaa");

  const long shadow = DarkenedPixels(r.Composed, withoutOurs);
  long changed = 0, changedInFlat = 0;
  ChangedPixels(r.Composed, withoutOther, withoutOther, 9, 24, changed, changedInFlat);
  std::printf("shadowed_pixels (FXAA with ours against FXAA alone): %ld\n", shadow);
  std::printf("antialiased_pixels (FXAA with ours against ours alone): %ld, in flat regions: %ld\n",
    changed, changedInFlat);
  r.Expect(shadow >= 1000, "the shadows darken at least 1000 pixels under FXAA");
  r.Expect(changed >= 300, "FXAA changes at least 300 pixels of the shadowed image");
  r.Expect(changedInFlat <= changed / 50, "FXAA changes edges only (at most 2 % in flat regions)");
  return r;
}

// ---- Tone mapping: vtkToneMappingPass with the shadow chain as its delegate. ----
// A light of intensity 2.5 saturates the lit ground without tone mapping; Reinhard's operator
// (c / (1 + c)) keeps every channel below 255 and the shadows dark.
Result ToneMapping(Scene& scene)
{
  Result r;
  scene.Sun->SetIntensity(2.5);
  auto toneOf = [](vtkRenderPass* delegate)
  {
    auto tone = vtkSmartPointer<vtkToneMappingPass>::New();
    tone->SetToneMappingType(vtkToneMappingPass::Reinhard);
    tone->SetDelegatePass(delegate);
    return tone;
  };
  vtkNew<vtkRenderStepsPass> steps;
  scene.SetPass(toneOf(steps));
  Image withoutOurs = scene.Render();
  scene.SetPass(ShadowChain());
  Image withoutOther = scene.Render();
  scene.SetPass(toneOf(ShadowChain()));
  r.Composed = scene.Render();
  scene.Save(withoutOurs, "TestCompositionToneMapping-without-csm");
  scene.Save(withoutOther, "TestCompositionToneMapping-without-tonemapping");

  const long shadow = DarkenedPixels(r.Composed, withoutOurs);
  const long saturatedBefore = SaturatedPixels(withoutOther);
  const long saturatedAfter = SaturatedPixels(r.Composed);
  std::printf("shadowed_pixels (tone mapping with ours against tone mapping alone): %ld\n", shadow);
  std::printf(
    "saturated_pixels: %ld without tone mapping, %ld with\n", saturatedBefore, saturatedAfter);
  r.Expect(shadow >= 1000, "the shadows darken at least 1000 pixels under tone mapping");
  r.Expect(saturatedBefore >= 10000, "the lit ground saturates without tone mapping");
  r.Expect(saturatedAfter <= saturatedBefore / 100, "tone mapping keeps the lit ground below 255");
  return r;
}

// ---- Translucent actors under depth peeling: renderer->UseDepthPeelingOn(). ----
// A translucent box (opacity 0.4) stands where the sphere's shadow falls on its top. It
// receives the shadow (the lookup is in every lit polydata shader, translucent ones too) and
// casts none (the maps hold opaque geometry only): outside its own pixels the image is the
// same with and without it, where the same box made opaque darkens the ground beside it.
Result DepthPeeling(Scene& scene)
{
  Result r;
  vtkNew<vtkCubeSource> glass;
  glass->SetBounds(0.0, 3.0, 0.0, 1.5, 0.5, 3.5);
  vtkNew<vtkPolyDataMapper> glassMapper;
  glassMapper->SetInputConnection(glass->GetOutputPort());
  vtkNew<vtkActor> box;
  box->SetMapper(glassMapper);
  box->GetProperty()->SetColor(0.3, 0.8, 0.4);
  box->GetProperty()->SetOpacity(0.4);
  scene.Renderer->AddActor(box);
  scene.Window->SetAlphaBitPlanes(1);
  scene.Renderer->UseDepthPeelingOn();
  scene.Renderer->SetMaximumNumberOfPeels(8);
  scene.Renderer->SetOcclusionRatio(0.0);
  const std::vector<char> boxPixels = Silhouette(scene, box);
  const std::vector<char> elsewhere = Inverted(boxPixels);

  Image withoutOurs = scene.Render();
  scene.SetPass(ShadowChain());
  r.Composed = scene.Render();
  const bool peeled = scene.Renderer->GetLastRenderingUsedDepthPeeling() != 0;
  scene.Renderer->UseDepthPeelingOff();
  Image withoutOther = scene.Render();
  scene.Renderer->UseDepthPeelingOn();
  box->VisibilityOff();
  Image withoutBox = scene.Render();
  box->VisibilityOn();
  box->GetProperty()->SetOpacity(1.0);
  Image opaqueBox = scene.Render();
  box->GetProperty()->SetOpacity(0.4);
  scene.Save(withoutOurs, "TestCompositionDepthPeeling-without-csm");
  scene.Save(withoutOther, "TestCompositionDepthPeeling-without-peeling");
  scene.Save(opaqueBox, "TestCompositionDepthPeeling-opaque-box");

  long boxArea = 0;
  const long received = DarkenedPixels(r.Composed, withoutOurs, &boxPixels, &boxArea);
  const long shadow = DarkenedPixels(r.Composed, withoutOurs);
  const long castTranslucent = DarkenedPixels(r.Composed, withoutBox, &elsewhere);
  const long castOpaque = DarkenedPixels(opaqueBox, withoutBox, &elsewhere);
  const long blended = DifferingFromBoth(r.Composed, opaqueBox, withoutBox, boxPixels, 8);
  std::printf("depth peeling used: %s\n", peeled ? "yes" : "no");
  std::printf("shadowed_pixels (ours against none, depth peeling): %ld, on the translucent box: "
              "%ld of its %ld\n",
    shadow, received, boxArea);
  std::printf("pixels outside the box it darkens: translucent %ld, opaque %ld\n", castTranslucent,
    castOpaque);
  std::printf(
    "box pixels blended (unlike both the opaque box's and those without it): %ld\n", blended);
  r.Expect(peeled, "the renderer used depth peeling under the shadow pass");
  r.Expect(shadow >= 1000, "the shadows darken at least 1000 pixels with depth peeling");
  r.Expect(received >= 500, "the translucent box receives the sphere's shadow (>= 500 pixels)");
  r.Expect(castOpaque >= 500, "the box made opaque casts a shadow beside it (>= 500 pixels)");
  r.Expect(castTranslucent <= 20, "the translucent box casts no shadow (<= 20 pixels)");
  r.Expect(blended >= boxArea / 2, "the translucent box is blended with what lies behind it");
  return r;
}

const std::map<std::string, std::function<Result(Scene&)>> kCases = {
  { "TestCompositionSSAO", SSAO },
  { "TestCompositionFXAA", FXAA },
  { "TestCompositionToneMapping", ToneMapping },
  { "TestCompositionDepthPeeling", DepthPeeling },
};
}

int main(int argc, char* argv[])
{
  if (argc < 2 || !kCases.count(argv[1]))
  {
    std::fprintf(stderr, "usage: csmCompositionTests <test> -B <baselines> -V <image> -T <dir>\n");
    return 1;
  }
  bool hasBaseline = false;
  Scene scene;
  for (int i = 2; i < argc; ++i)
  {
    hasBaseline = hasBaseline || std::strcmp(argv[i], "-V") == 0;
    if (std::strcmp(argv[i], "-T") == 0 && i + 1 < argc)
      scene.OutputDir = argv[i + 1];
  }
  if (!hasBaseline)
  {
    std::fprintf(stderr, "missing -V <baseline image>: the comparison would not run\n");
    return 1;
  }
  Result r = kCases.at(argv[1])(scene);
  // The composed frame again, for vtkTesting (it grabs the window as it is).
  scene.Window->Render();
  const int result = vtkTesting::Test(argc, argv, scene.Window, 0.15);
  r.Expect(result == vtkTesting::PASSED, "the image matches its baseline");
  return r.Ok ? 0 : 1;
}
