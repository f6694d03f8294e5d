// SPDX-License-Identifier: BSD-3-Clause
// csm-demo: renders a scene with cascaded generalized-LiSPSM shadows (or VTK's own shadow pass,
// or none), interactively or offscreen to a PNG, and times orbiting frames.
#include "csmFileChecks.h"
#include "csmHeadless.h"
#include "csmScenes.h"
#include "csmTechnique.h"

#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCascadedShadowMapBakerPass.h"
#include "vtkCascadedShadowMapPass.h"
#include "vtkCascadedShadowMapPlanner.h"
#include "vtkInteractorStyleTrackballCamera.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkPNGWriter.h"
#include "vtkRenderPass.h"
#include "vtkRenderWindow.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkRenderer.h"
#include "vtkTextActor.h"
#include "vtkTextProperty.h"
#include "vtkTimerLog.h"
#include "vtkWindowToImageFilter.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <dlfcn.h>
#include <sstream>
#include <string>
#include <vector>

namespace
{
const char* const kWarps[] = { "none", "psm", "lispsm", "generalized" };
const char* const kPartitions[] = { "single", "uniform", "log", "practical", "adaptive" };
/// --partition: the split schemes, then face partitioning (FP+W), face partitions with two
/// z-partitions each (FP+ZP+W) and camera space shadow maps: the comparison techniques, in a build
/// with them.
const char* const kPartitionChoices[] = { "single", "uniform", "log", "practical", "adaptive",
  "face", "face-zp", "cssm" };
#if CSM_COMPARISON_TECHNIQUES
constexpr int kPartitionChoiceCount = 8;
#else
constexpr int kPartitionChoiceCount = 5;
#endif
const char* const kDebug[] = { "off", "cascades", "error", "factor" };
const char* const kKernels[] = { "grid", "jittered" };

struct Options
{
  csmScenes::ShadowOptions Shadow;
  std::string Scene = "platform";
  long long Triangles = 250000;
  bool TrianglesGiven = false;
  int Width = 800, Height = 600;
  bool Offscreen = false;
  std::string Out;
  int Frames = 0;
  double Orbit = 360.0;     // degrees the camera turns over --frames
  bool Interactive = false; // --frames as a user dragging the camera (desired update rate 15)
  bool Breakdown = false;   // --frames: also the median planning and map times (glFinish-bracketed)
  std::string Keys;         // keys of the window pressed in turn before the image or frames
  bool HaveLight = false;
  double Light[3] = { -0.45, -1.0, -0.35 };
  bool HaveGamma = false;
  double Gamma = 90.0;
};

/// One error line and exit status 2; option errors point to --help.
[[noreturn]] void fail(const std::string& message, bool seeHelp = true)
{
  std::fprintf(stderr, "csm-demo: error: %s%s\n", message.c_str(), seeHelp ? " (see --help)" : "");
  std::exit(2);
}

/// VTK here renders through GLX: without an X display it crashes (SIGSEGV or an abort inside
/// VTK). Say so before VTK touches X. Built with the OSMesa window (CSM_OSMESA), --offscreen
/// renders through OSMesa and needs no display (unless CSM_HEADLESS=x turned it off); the
/// interactive window still does.
void requireDisplay(bool offscreen)
{
  const char* display = std::getenv("DISPLAY");
  const char* headless = std::getenv("CSM_HEADLESS");
  if ((!display || !*display) && csmHeadless::Available() && offscreen)
    fail(std::string("no X display (DISPLAY is not set), and CSM_HEADLESS=") +
        (headless ? headless : "") +
        " in the environment turned the OSMesa window off, so --offscreen renders through X "
        "too: unset CSM_HEADLESS to render with no X server, or set DISPLAY or run csm-demo "
        "under xvfb-run -a",
      false);
  if (!display || !*display)
    fail(csmHeadless::Available()
        ? "no X display (DISPLAY is not set; the interactive window needs one): set DISPLAY, run "
          "csm-demo under xvfb-run -a, or render with --offscreen (OSMesa, no X server)"
        : "no X display (DISPLAY is not set; csm-demo needs one, also with --offscreen: this "
          "build has no OSMesa): set DISPLAY or run it under xvfb-run -a",
      false);
  void* x11 = dlopen("libX11.so.6", RTLD_NOW | RTLD_LOCAL);
  using Open = void* (*)(const char*);
  using Close = int (*)(void*);
  auto xOpen = x11 ? reinterpret_cast<Open>(dlsym(x11, "XOpenDisplay")) : nullptr;
  auto xClose = x11 ? reinterpret_cast<Close>(dlsym(x11, "XCloseDisplay")) : nullptr;
  if (xOpen && xClose)
  {
    void* connection = xOpen(display);
    if (!connection)
      fail(std::string("cannot open the X display '") + display +
          "': start an X server for it, or run csm-demo under xvfb-run -a",
        false);
    xClose(connection);
  }
}

void usage()
{
  const Options o; // the defaults: csm-demo's own, and the pass's (ShadowOptions reads them)
  const csmScenes::ShadowOptions& d = o.Shadow;
  // The comparison techniques' choices, in a build with them.
  std::ostringstream comparisonUsage;
#if CSM_COMPARISON_TECHNIQUES
  comparisonUsage
    << " |\n"
       "                     face (face partitioning, Lloyd et al. 2006, 5.1: FP+W) |\n"
       "                     face-zp (two z-partitions per face: FP+ZP+W) |\n"
       "                     cssm (camera space shadow maps: one map, or four in the\n"
       "                     dueling frustum case)\n"
       "  --cssm-focus D     cssm's focus range: the view depth in front of which the view\n"
       "                     gets half the map; 0: sqrt(near far) of the fitted range ["
    << d.CameraSpaceFocus << "]";
#endif
  const std::string comparison = comparisonUsage.str();
  std::printf(
    "usage: csm-demo [options]        (defaults in [])\n"
    "  --scene S          platform | platform-beams (its bars as lines drawn as tubes) |\n"
    "                     towers | FILE (.vtp .vtk .stl .ply .obj .glb .gltf) [%s]\n"
    "  --triangles N      platform size in triangles, 1000..%lld (its finest\n"
    "                     tessellation) [%lld]\n"
    "  --technique T      csm (ours) | vtk (vtkShadowMapPass) | none [%s]\n"
    "  --warp W           none | psm | lispsm | generalized [%s]\n"
    "  --partition P      single | uniform | log | practical | adaptive [%s]%s\n"
    "  --cascades K       1..%d [%d]      --lambda L  practical weight [%g]\n"
    "  --adaptive-cascades on|off  the fewest cascades, up to K, that meet --error-target [%s]\n"
    "  --cull-closed on|off  closed casters drawn into the maps from behind only [%s]\n"
    "  --compact-casters on|off  casters drawn into the maps from compact spatial blocks [%s]\n"
    "  --cull-without-receivers on|off  casters that shadow nothing (a ground under\n"
    "                     everything) left out of the maps [%s]\n"
    "  --visible-fit on|off  cascades begin at the nearest sample the view shows [%s]\n"
    "  --footprint-fit on|off  with --visible-fit, each cascade's map covers only where the\n"
    "                     view has samples at its depths [%s]\n"
    "  --scene-fitted on|off  the farthest cascade may be a map fixed in the world of what\n"
    "                     can be in shadow, kept while the scene and light stay [%s]\n"
    "  --move-maps on|off  kept maps move with the view, only the strips that came in\n"
    "                     drawn [%s]\n"
    "  --pages on|off     the scene-fitted map refined by light-space pages where the maps\n"
    "                     would follow the view [%s]\n"
    "  --alpha A          adaptive ratio > 1 [%g]\n"
    "  --resolution R     texels per cascade side at most, 64..8192 [%d]\n"
    "  --error-target M   each cascade's resolution for aliasing error <= M (texel/pixel);\n"
    "                     0: always --resolution [%g]\n"
    "  --pcf N            1 | 3 | 5 | 7 [%d]   --kernel grid | jittered [%s]\n"
    "  --bias B           constant depth bias [%g]   --slope-bias S [%g]\n"
    "  --closed-bias F    share of the constant bias for closed surfaces drawn into the\n"
    "                     maps from behind, 0..1 [%g]\n"
    "  --blend F          cascade blend band, 0..0.5 [%g]\n"
    "  --depth-clamp on|off [%s]      --darkness D  0..1 [%g]\n"
    "  --debug D          off | cascades | error | factor [%s]\n"
    "  --reuse-factors on|off  a frame drawn as the last one reads each pixel's shadow\n"
    "                     factors from it instead of the lookup [%s]\n"
    "  --light X,Y,Z      direction the light travels (world) [%g,%g,%g]\n"
    "  --gamma DEG        light at this angle to the view (0 behind, 90 overhead, 180 facing)\n"
    "  --size WxH         window size [%dx%d]\n"
    "  --offscreen        no window; with --out writes the image (%s)\n"
    "  --out FILE.png     write the rendered image\n"
    "  --frames N         render N frames orbiting the scene, print median_frame_ms\n"
    "  --orbit DEG        degrees the camera turns over the frames [%g]; 0: a still camera\n"
    "  --interactive      render --frames as while the user drags the camera (the window's\n"
    "                     desired update rate at the interactor's 15 fps)\n"
    "  --breakdown        also print the first frame's and (with --frames) the median\n"
    "                     planning and map times\n"
    "  --keys K           press the window's keys K in turn (each one renders a frame, with\n"
    "                     the window's text), then render the image or --frames; e.g. tt\n"
    "keys (interactive): w warp, p partition, c cascades, f PCF size, k kernel, d debug view,\n"
    "  t technique, l light angle +15 deg\n",
    o.Scene.c_str(), csmScenes::PlatformMaxTriangles(), o.Triangles, d.Technique.c_str(),
    kWarps[d.Warp], kPartitions[d.Partition], comparison.c_str(),
    vtkCascadedShadowMapPlanner::MAXIMUM_NUMBER_OF_CASCADES, d.Cascades, d.Lambda,
    d.AdaptiveCascades ? "on" : "off", d.CullClosedCasters ? "on" : "off",
    d.CompactCasters ? "on" : "off", d.CullCastersWithoutReceivers ? "on" : "off",
    d.VisibleDepthFit ? "on" : "off", d.VisibleFootprintFit ? "on" : "off",
    d.SceneFittedCascades ? "on" : "off", d.MoveKeptMaps ? "on" : "off",
    d.LightSpacePages ? "on" : "off", d.Alpha, d.Resolution, d.ErrorTarget, d.PCF,
    kKernels[d.Kernel], d.ConstantBias, d.SlopeBias, d.ClosedSurfaceBiasFactor, d.Blend,
    d.DepthClamp ? "on" : "off", d.Darkness, kDebug[d.Debug], d.ReuseShadowFactors ? "on" : "off",
    o.Light[0], o.Light[1], o.Light[2], o.Width, o.Height,
    csmHeadless::Available() ? "through OSMesa: no X display needed"
                             : "needs an X display: xvfb-run -a",
    o.Orbit);
}

double number(const std::string& flag, const char* text)
{
  if (!text)
    fail(flag + " needs a value");
  char* end = nullptr;
  const double value = std::strtod(text, &end);
  if (end == text || *end != '\0' || !std::isfinite(value))
    fail(flag + " needs a finite number, got '" + text + "'");
  return value;
}

int choice(const std::string& flag, const char* text, const char* const* names, int count)
{
  for (int i = 0; text && i < count; ++i)
    if (std::strcmp(text, names[i]) == 0)
      return i;
  std::string all;
  for (int i = 0; i < count; ++i)
    all += std::string(i ? ", " : "") + names[i];
  fail(flag + " must be one of " + all);
}

Options parse(int argc, char** argv)
{
  Options o;
  for (int i = 1; i < argc; ++i)
  {
    const std::string f = argv[i];
    const char* v = i + 1 < argc ? argv[i + 1] : nullptr;
    auto next = [&]() { ++i; };
    if (f == "--help" || f == "-h")
    {
      usage();
      std::exit(0);
    }
    else if (f == "--offscreen")
      o.Offscreen = true;
    else if (f == "--interactive")
      o.Interactive = true;
    else if (f == "--breakdown")
      o.Breakdown = true;
    else if (f == "--scene")
    {
      if (!v)
        fail("--scene needs a value");
      o.Scene = v;
      next();
    }
    else if (f == "--keys")
    {
      if (!v || !*v || std::strspn(v, "wpcfkdtl") != std::strlen(v))
        fail("--keys needs keys of the window: w p c f k d t l");
      o.Keys = v;
      next();
    }
    else if (f == "--out")
    {
      if (!v)
        fail("--out needs a file name");
      o.Out = v;
      next();
    }
    else if (f == "--technique")
    {
      const char* const names[] = { "csm", "vtk", "none" };
      o.Shadow.Technique = names[choice(f, v, names, 3)];
      next();
    }
    else if (f == "--warp")
    {
      o.Shadow.Warp = choice(f, v, kWarps, 4);
      next();
    }
    else if (f == "--partition")
    {
      // (A comparison technique in a build without them: say why, not just "must be one of".)
      for (int i = kPartitionChoiceCount; v && i < 8; ++i)
        if (std::strcmp(v, kPartitionChoices[i]) == 0)
          fail(csmScenes::NoComparisonTechniques(f + " " + v), false);
      const int partition = choice(f, v, kPartitionChoices, kPartitionChoiceCount);
#if CSM_COMPARISON_TECHNIQUES
      o.Shadow.FacePartitions = partition == 5 || partition == 6 ? partition - 4 : 0;
      o.Shadow.CameraSpace = partition == 7;
#endif
      o.Shadow.Partition = partition >= 5 ? o.Shadow.Partition : partition;
      next();
    }
    else if (f == "--kernel")
    {
      o.Shadow.Kernel = choice(f, v, kKernels, 2);
      next();
    }
    else if (f == "--debug")
    {
      o.Shadow.Debug = choice(f, v, kDebug, 4);
      next();
    }
    else if (f == "--adaptive-cascades")
    {
      const char* const names[] = { "off", "on" };
      o.Shadow.AdaptiveCascades = choice(f, v, names, 2) == 1;
      next();
    }
    else if (f == "--cull-closed")
    {
      const char* const names[] = { "off", "on" };
      o.Shadow.CullClosedCasters = choice(f, v, names, 2) == 1;
      next();
    }
    else if (f == "--compact-casters")
    {
      const char* const names[] = { "off", "on" };
      o.Shadow.CompactCasters = choice(f, v, names, 2) == 1;
      next();
    }
    else if (f == "--cull-without-receivers")
    {
      const char* const names[] = { "off", "on" };
      o.Shadow.CullCastersWithoutReceivers = choice(f, v, names, 2) == 1;
      next();
    }
    else if (f == "--visible-fit")
    {
      const char* const names[] = { "off", "on" };
      o.Shadow.VisibleDepthFit = choice(f, v, names, 2) == 1;
      next();
    }
    else if (f == "--footprint-fit")
    {
      const char* const names[] = { "off", "on" };
      o.Shadow.VisibleFootprintFit = choice(f, v, names, 2) == 1;
      next();
    }
    else if (f == "--reuse-factors")
    {
      const char* const names[] = { "off", "on" };
      o.Shadow.ReuseShadowFactors = choice(f, v, names, 2) == 1;
      next();
    }
    else if (f == "--move-maps")
    {
      const char* const names[] = { "off", "on" };
      o.Shadow.MoveKeptMaps = choice(f, v, names, 2) == 1;
      next();
    }
    else if (f == "--pages")
    {
      const char* const names[] = { "off", "on" };
      o.Shadow.LightSpacePages = choice(f, v, names, 2) == 1;
      next();
    }
    else if (f == "--scene-fitted")
    {
      const char* const names[] = { "off", "on" };
      o.Shadow.SceneFittedCascades = choice(f, v, names, 2) == 1;
      next();
    }
    else if (f == "--depth-clamp")
    {
      const char* const names[] = { "off", "on" };
      o.Shadow.DepthClamp = choice(f, v, names, 2) == 1;
      next();
    }
    else if (f == "--size")
    {
      int w = 0, h = 0;
      char extra = 0;
      if (!v || std::sscanf(v, "%dx%d%c", &w, &h, &extra) != 2 || w < 16 || h < 16 || w > 8192 ||
        h > 8192)
        fail("--size needs WxH with 16..8192 pixels each, e.g. 800x600");
      o.Width = w;
      o.Height = h;
      next();
    }
    else if (f == "--light")
    {
      char extra = 0;
      if (!v || std::sscanf(v, "%lf,%lf,%lf%c", &o.Light[0], &o.Light[1], &o.Light[2], &extra) != 3)
        fail("--light needs X,Y,Z");
      if (!std::isfinite(o.Light[0]) || !std::isfinite(o.Light[1]) || !std::isfinite(o.Light[2]))
        fail("--light needs finite numbers");
      // A direction: scaled so that its length neither overflows nor underflows.
      const double largest =
        std::max({ std::abs(o.Light[0]), std::abs(o.Light[1]), std::abs(o.Light[2]) });
      if (largest == 0.0)
        fail("--light needs a non-zero direction");
      for (double& component : o.Light)
        component /= largest;
      o.HaveLight = true;
      next();
    }
    else
    {
      static const char* const numeric[] = { "--triangles", "--cascades", "--resolution",
        "--error-target", "--pcf", "--lambda", "--alpha", "--bias", "--slope-bias", "--closed-bias",
        "--blend", "--darkness", "--gamma", "--frames", "--orbit", "--cssm-focus" };
      if (std::none_of(
            std::begin(numeric), std::end(numeric), [&](const char* known) { return f == known; }))
        fail("unknown option '" + f + "'");
      const double value = number(f, v);
      next();
      auto whole = [&](double lo, double hi)
      {
        if (value != std::floor(value) || value < lo || value > hi)
          fail(f + " needs a whole number in [" + std::to_string(int(lo)) + ", " +
            std::to_string(int(hi)) + "]");
        return static_cast<int>(value);
      };
      auto range = [&](double lo, double hi)
      {
        if (value < lo || value > hi)
        {
          std::ostringstream bounds;
          bounds << f << " must be in [" << lo << ", " << hi << "]";
          fail(bounds.str());
        }
        return value;
      };
      if (f == "--triangles")
      {
        const long long most = csmScenes::PlatformMaxTriangles();
        if (value < 1000 || value > static_cast<double>(most))
          fail("--triangles must be in [1000, " + std::to_string(most) +
            "] (the platform's finest tessellation)");
        o.Triangles = static_cast<long long>(value);
        o.TrianglesGiven = true;
      }
      else if (f == "--cascades")
        o.Shadow.Cascades = whole(1, vtkCascadedShadowMapPlanner::MAXIMUM_NUMBER_OF_CASCADES);
      else if (f == "--resolution")
        o.Shadow.Resolution = whole(64, 8192);
      else if (f == "--error-target")
        o.Shadow.ErrorTarget = range(0, 1.0e6);
      else if (f == "--cssm-focus")
      {
#if CSM_COMPARISON_TECHNIQUES
        o.Shadow.CameraSpaceFocus = range(0, 1.0e300);
#else
        fail(csmScenes::NoComparisonTechniques(f), false);
#endif
      }
      else if (f == "--pcf")
      {
        o.Shadow.PCF = whole(1, 7);
        if (o.Shadow.PCF % 2 == 0)
          fail("--pcf must be 1, 3, 5 or 7");
      }
      else if (f == "--lambda")
        o.Shadow.Lambda = range(0, 1);
      else if (f == "--alpha")
      {
        if (!(value > 1.0))
          fail("--alpha must be > 1");
        o.Shadow.Alpha = value;
      }
      else if (f == "--bias")
        o.Shadow.ConstantBias = range(0, 1);
      else if (f == "--slope-bias")
        o.Shadow.SlopeBias = range(0, 100);
      else if (f == "--closed-bias")
        o.Shadow.ClosedSurfaceBiasFactor = range(0, 1);
      else if (f == "--blend")
        o.Shadow.Blend = range(0, 0.5);
      else if (f == "--darkness")
        o.Shadow.Darkness = range(0, 1);
      else if (f == "--gamma")
      {
        o.Gamma = range(0, 180);
        o.HaveGamma = true;
      }
      else if (f == "--frames")
        o.Frames = whole(1, 100000);
      else if (f == "--orbit")
        o.Orbit = range(0, 3600);
      else
        fail("unknown option '" + f + "'");
    }
  }
  if (o.Offscreen && o.Out.empty() && o.Frames == 0)
    fail("--offscreen needs --out FILE.png or --frames N");
  if (!o.Out.empty())
  {
    const std::string error = csmScenes::CheckOutputFile(o.Out); // before the scene and render
    if (!error.empty())
      fail("--out: " + error, false);
  }
  return o;
}

struct App
{
  Options Opt;
  vtkRenderer* Renderer = nullptr;
  vtkRenderWindow* Window = nullptr;
  vtkLight* Key = nullptr;
  vtkTextActor* Text = nullptr;
  vtkCommand* KeyCommand = nullptr; // set to abort once the demo has used a key
  csmScenes::Installed Passes;
  double LastFrameMs = 0.0;

  void PlaceLight()
  {
    vtkCamera* camera = this->Renderer->GetActiveCamera();
    double d[3];
    if (this->Opt.HaveGamma)
    {
      double v[3], up[3];
      camera->GetDirectionOfProjection(v);
      camera->GetViewUp(up);
      const double g = vtkMath::RadiansFromDegrees(this->Opt.Gamma);
      for (int i = 0; i < 3; ++i)
        d[i] = std::cos(g) * v[i] - std::sin(g) * up[i];
    }
    else
      std::copy(this->Opt.Light, this->Opt.Light + 3, d);
    double focal[3];
    camera->GetFocalPoint(focal);
    this->Key->SetFocalPoint(focal);
    this->Key->SetPosition(focal[0] - d[0], focal[1] - d[1], focal[2] - d[2]);
  }

  /// Installs the technique's pass chain; the chain it replaces frees its maps, textures and
  /// shaders now, not when the window goes.
  void Apply()
  {
    if (vtkRenderPass* dropped = this->Renderer->GetPass())
      dropped->ReleaseGraphicsResources(this->Window);
    this->Passes = csmScenes::InstallTechnique(this->Renderer, this->Opt.Shadow);
  }

  /// The window's text: technique, options, last frame time.
  void AddText()
  {
    vtkNew<vtkTextActor> text;
    text->GetTextProperty()->SetFontSize(14);
    text->GetTextProperty()->SetColor(0.05, 0.05, 0.1);
    text->SetDisplayPosition(8, 8);
    this->Renderer->AddActor2D(text);
    this->Text = text;
    this->UpdateText();
  }

  void UpdateText()
  {
    if (!this->Text)
      return;
    const auto& s = this->Opt.Shadow;
    std::ostringstream t;
    t << "technique " << s.Technique << " | " << s.Resolution << "^2 | frame "
      << static_cast<int>(this->LastFrameMs) << " ms";
    if (s.Technique == "csm")
      t << "\nwarp " << kWarps[s.Warp] << " | partition "
#if CSM_COMPARISON_TECHNIQUES
        << (s.CameraSpace             ? "cssm"
               : s.FacePartitions > 0 ? kPartitionChoices[4 + s.FacePartitions]
                                      : kPartitions[s.Partition])
#else
        << kPartitions[s.Partition]
#endif
        << " | cascades " << s.Cascades << " | pcf " << s.PCF << " " << kKernels[s.Kernel]
        << " | debug " << kDebug[s.Debug];
    this->Text->SetInput(t.str().c_str());
  }

  /// A key of the window (w p c f k d t l): changes the option, renders a frame. False for any
  /// other key.
  bool Press(const std::string& key)
  {
    auto& s = this->Opt.Shadow;
    if (key == "w")
      s.Warp = (s.Warp + 1) % 4;
    else if (key == "p")
      s.Partition = (s.Partition + 1) % 5;
    else if (key == "c")
      s.Cascades = s.Cascades % 4 + 1;
    else if (key == "f")
      s.PCF = s.PCF >= 7 ? 1 : s.PCF + 2;
    else if (key == "k")
      s.Kernel = 1 - s.Kernel;
    else if (key == "d")
      s.Debug = (s.Debug + 1) % 4;
    else if (key == "t")
      s.Technique = s.Technique == "csm" ? "vtk" : s.Technique == "vtk" ? "none" : "csm";
    else if (key == "l")
    {
      this->Opt.HaveGamma = true;
      this->Opt.Gamma = std::fmod(this->Opt.Gamma + 15.0, 195.0);
      this->PlaceLight();
    }
    else
      return false;
    if (this->Passes.Cascaded && key != "t")
      csmScenes::Configure(this->Passes.Cascaded, s);
    else
      this->Apply();
    this->UpdateText();
    this->Window->Render();
    return true;
  }

  /// The demo's keys are its own: the interactor style does not see them too (its w, p and f
  /// would make every actor wireframe, add a pick outline, which VTK's shadow pass cannot
  /// shade, and fly the camera).
  static void OnKey(vtkObject* caller, unsigned long, void* data, void*)
  {
    App* app = static_cast<App*>(data);
    auto* interactor = static_cast<vtkRenderWindowInteractor*>(caller);
    if (app->Press(interactor->GetKeySym() ? interactor->GetKeySym() : "") && app->KeyCommand)
      app->KeyCommand->SetAbortFlag(1);
  }

  /// The window's text and keys on the interactor, ahead of its style's own keys.
  void Connect(
    vtkRenderWindowInteractor* interactor, vtkInteractorObserver* style, vtkCallbackCommand* onKey)
  {
    if (!this->Text)
      this->AddText();
    interactor->SetInteractorStyle(style);
    interactor->SetRenderWindow(this->Window);
    onKey->SetCallback(App::OnKey);
    onKey->SetClientData(this);
    interactor->AddObserver(vtkCommand::CharEvent, onKey, 1.0); // the style's: priority 0
    this->KeyCommand = onKey;
  }

  static void OnEndRender(vtkObject*, unsigned long, void* data, void*)
  {
    App* app = static_cast<App*>(data);
    app->LastFrameMs = 1000.0 * app->Renderer->GetLastRenderTimeInSeconds();
  }
};
} // namespace

int main(int argc, char** argv)
{
  App app;
  app.Opt = parse(argc, argv);

  csmScenes::Scene scene;
  if (app.Opt.TrianglesGiven && app.Opt.Scene != "platform")
  {
    std::fprintf(stderr, "csm-demo: note: --triangles sizes the platform scene only; ignored\n");
  }
  if (app.Opt.Scene == "platform")
    scene = csmScenes::Platform(app.Opt.Triangles);
  else if (app.Opt.Scene == "platform-beams")
    scene = csmScenes::PlatformBeams();
  else if (app.Opt.Scene == "towers")
    scene = csmScenes::Towers();
  else
  {
    std::string error;
    if (!csmScenes::FromFile(app.Opt.Scene, scene, error))
      fail(error, false);
  }
  // --offscreen: the OSMesa window where built with it; the interactive window is VTK's own.
  if (!app.Opt.Offscreen)
    csmHeadless::UseOSMesa(false);
  if (!csmHeadless::UsingOSMesa())
    requireDisplay(app.Opt.Offscreen);

  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkRenderWindow> window;
  window->SetSize(app.Opt.Width, app.Opt.Height);
  window->SetMultiSamples(0);
  window->SetOffScreenRendering(app.Opt.Offscreen ? 1 : 0);
  window->AddRenderer(renderer);
  window->SetWindowName("csm-demo");
  renderer->SetBackground(0.75, 0.82, 0.9);
  renderer->AutomaticLightCreationOff();
  app.Renderer = renderer;
  app.Window = window;

  csmScenes::Install(scene, renderer, double(app.Opt.Width) / app.Opt.Height);
  vtkNew<vtkLight> key;
  key->SetLightTypeToSceneLight();
  key->SetPositional(false);
  key->SetIntensity(0.85);
  renderer->AddLight(key);
  vtkNew<vtkLight> fill; // a dim headlight: no shadows, keeps shadowed parts readable
  fill->SetLightTypeToHeadlight();
  fill->SetIntensity(0.25);
  renderer->AddLight(fill);
  app.Key = key;
  app.PlaceLight();
  app.Apply();

  std::printf("scene %s: %lld triangles, ", scene.Name.c_str(), scene.Triangles);
  if (scene.Lines > 0)
    std::printf("%lld lines, ", scene.Lines);
  std::printf("%zu actors\n", scene.Actors.size());

  vtkNew<vtkRenderWindowInteractor> interactor;
  vtkNew<vtkInteractorStyleTrackballCamera> style;
  vtkNew<vtkCallbackCommand> onKey;
  if (!app.Opt.Keys.empty())
  {
    // As typed in the window after a click at its centre.
    app.Connect(interactor, style, onKey);
    interactor->Initialize();
    interactor->SetEventPosition(app.Opt.Width / 2, app.Opt.Height / 2);
    interactor->LeftButtonPressEvent();
    interactor->LeftButtonReleaseEvent();
    for (const char key : app.Opt.Keys)
    {
      const char sym[2] = { key, '\0' };
      interactor->SetKeyEventInformation(0, 0, key, 1, sym);
      interactor->KeyPressEvent();
      interactor->CharEvent();
      std::printf("key %c: technique %s\n", key, app.Opt.Shadow.Technique.c_str());
    }
  }

  if (app.Passes.Cascaded)
    app.Passes.Cascaded->GetShadowMapBakerPass()->SetMeasureTimes(app.Opt.Breakdown);
  // The first image's own time (what a user waits for once the scene is loaded: buffers
  // uploaded, first maps drawn), with --breakdown its planning and map times.
  bool renderedFirst = false;
  auto renderFirst = [&]()
  {
    vtkNew<vtkTimerLog> firstTimer;
    firstTimer->StartTimer();
    window->Render();
    window->WaitForCompletion();
    firstTimer->StopTimer();
    renderedFirst = true;
    std::printf("first_frame_ms: %.3f\n", 1000.0 * firstTimer->GetElapsedTime());
    if (app.Passes.Cascaded && app.Opt.Breakdown)
    {
      const auto& first = app.Passes.Cascaded->GetShadowMapBakerPass()->GetLastFrameStatistics();
      std::printf("first_plan_ms: %.3f  first_map_ms: %.3f\n", 1000.0 * first.PlanSeconds,
        1000.0 * first.MapSeconds);
    }
  };

  if (app.Opt.Frames > 0)
  {
    std::vector<double> times, planTimes, mapTimes;
    int cascadesRendered = 0, cascadesKept = 0, closedCasters = 0, compactCasters = 0,
        blocksDrawn = 0, withoutReceivers = 0;
    double texelsRendered = 0.0;
    vtkNew<vtkTimerLog> timer;
    renderFirst(); // warm-up: shader compilation, first maps
    if (app.Opt.Interactive)
      window->SetDesiredUpdateRate(15.0); // as vtkRenderWindowInteractor while dragging
    for (int i = 0; i < app.Opt.Frames; ++i)
    {
      renderer->GetActiveCamera()->Azimuth(app.Opt.Orbit / app.Opt.Frames);
      if (scene.ClippingRange[1] <= 0.0)
        renderer->ResetCameraClippingRange();
      timer->StartTimer();
      window->Render();
      window->WaitForCompletion(); // glFinish: the frame is done on the GPU
      timer->StopTimer();
      times.push_back(1000.0 * timer->GetElapsedTime());
      if (app.Passes.Cascaded)
      {
        const auto& stats = app.Passes.Cascaded->GetShadowMapBakerPass()->GetLastFrameStatistics();
        cascadesRendered += stats.CascadesRendered;
        cascadesKept += stats.CascadesKept;
        closedCasters = stats.ClosedCasters;
        compactCasters = stats.CompactCasters;
        blocksDrawn += stats.BlocksDrawn;
        withoutReceivers += stats.CastersWithoutReceivers;
        texelsRendered += stats.TexelsRendered;
        planTimes.push_back(1000.0 * stats.PlanSeconds);
        mapTimes.push_back(1000.0 * stats.MapSeconds);
      }
    }
    window->SetDesiredUpdateRate(0.0001); // the interactor's still rate
    auto median = [](std::vector<double> v)
    {
      std::sort(v.begin(), v.end());
      return v[v.size() / 2];
    };
    std::printf("median_frame_ms: %.3f\n", median(times));
    if (app.Passes.Cascaded)
      std::printf("maps_rendered: %d  maps_kept: %d  (over %d frames), texels rendered per "
                  "frame: %.2f M\n",
        cascadesRendered, cascadesKept, app.Opt.Frames, texelsRendered / app.Opt.Frames / 1e6);
    if (app.Passes.Cascaded && app.Opt.Breakdown)
      std::printf(
        "median_plan_ms: %.3f  median_map_ms: %.3f\n", median(planTimes), median(mapTimes));
    if (app.Passes.Cascaded)
      std::printf("closed_casters: %d of %d actors (drawn into the maps from behind)\n",
        closedCasters, renderer->GetActors()->GetNumberOfItems());
    if (app.Passes.Cascaded)
      std::printf("compact_casters: %d of %d actors, blocks drawn: %d (over %d frames)\n",
        compactCasters, renderer->GetActors()->GetNumberOfItems(), blocksDrawn, app.Opt.Frames);
    if (app.Passes.Cascaded)
      std::printf("casters left out of a rendered map (they shadow nothing): %d (over %d frames)\n",
        withoutReceivers, app.Opt.Frames);
  }

  if (!app.Opt.Out.empty() || app.Opt.Offscreen)
  {
    if (renderedFirst)
      window->Render();
    else
      renderFirst();
    if (!app.Opt.Out.empty())
    {
      vtkNew<vtkWindowToImageFilter> grab;
      grab->SetInput(window);
      grab->ReadFrontBufferOff();
      grab->Update();
      vtkNew<vtkPNGWriter> writer;
      writer->SetFileName(app.Opt.Out.c_str());
      writer->SetInputConnection(grab->GetOutputPort());
      writer->Write();
      if (writer->GetErrorCode() != 0)
        fail("cannot write '" + app.Opt.Out + "'", false);
      std::printf("wrote %s\n", app.Opt.Out.c_str());
    }
    if (app.Opt.Offscreen)
      return 0;
  }

  if (!app.KeyCommand)
    app.Connect(interactor, style, onKey);
  vtkNew<vtkCallbackCommand> onEnd;
  onEnd->SetCallback(App::OnEndRender);
  onEnd->SetClientData(&app);
  renderer->AddObserver(vtkCommand::EndEvent, onEnd);
  window->Render();
  interactor->Start();
  return 0;
}
