// SPDX-License-Identifier: BSD-3-Clause
// csm-bench: speed against error. Renders scenes along camera paths and light sweeps with VTK's
// shadow pass and with cascaded variants at equal total shadow-map texels, measures frame time
// (median, interleaved, glFinish in each frame), misclassified pixels against Embree ground
// truth and the perspective aliasing m, and writes a CSV and a plot (vtkChartXY).
#include "csmChanges.h"
#include "csmFileChecks.h"
#include "csmPages.h"
#include "csmScenes.h"
#include "csmTechnique.h"
#include "csmTruth.h"
#include "csmWalk.h"

#include "vtkActor.h"
#include "vtkAxis.h"
#include "vtkCamera.h"
#include "vtkCascadedShadowMapBakerPass.h"
#include "vtkCascadedShadowMapPass.h"
#include "vtkCascadedShadowMapPlanner.h"
#include "vtkChartLegend.h"
#include "vtkChartMatrix.h"
#include "vtkChartXY.h"
#include "vtkContextScene.h"
#include "vtkContextView.h"
#include "vtkDoubleArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkPNGWriter.h"
#include "vtkPen.h"
#include "vtkPlot.h"
#include "vtkPlotPoints.h"
#include "vtkProperty.h"
#include "vtkRenderPass.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkShadowMapBakerPass.h"
#include "vtkShadowMapPass.h"
#include "vtkStringArray.h"
#include "vtkTable.h"
#include "vtkTextProperty.h"
#include "vtkTimerLog.h"
#include "vtkWindowToImageFilter.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace
{
const char* const kWarps[] = { "none", "psm", "lispsm", "generalized" };
const char* const kPartitions[] = { "single", "uniform", "log", "practical", "adaptive" };

struct Options
{
  bool Quick = false;
  std::string Out = "csm-bench.csv";
  std::string Plot;
  int Width = 800, Height = 600;
  int Frames = 30;                 // per camera path (orbit, fly-through)
  int Budget = 4096;               // total texels = Budget^2
  int Rounds = 3;                  // interleaving rounds
  int AccuracyEvery = 10;          // accuracy on every n-th path frame
  int InteractiveFrames = 30;      // interactive orbit: 2 degrees a frame, as a user drags
  int StillFrames = 8;             // the default view, camera still
  int DollyFrames = 12;            // flicker: consecutive frames of a dolly toward the focal point
  bool Breakdown = false;          // per frame: planning and map times, maps rendered
  std::string ErrorImages;         // folder for one image per measured view and technique
  std::vector<std::string> Labels; // only these techniques (empty: all of the mode)
  std::vector<std::string> Scenes = { "platform", "platform-beams", "platform-2m", "towers",
    "engine" };
};

[[noreturn]] void fail(const std::string& message)
{
  std::fprintf(stderr, "csm-bench: error: %s (see --help)\n", message.c_str());
  std::exit(2);
}

struct Technique
{
  std::string Label;
  csmScenes::ShadowOptions Shadow;
  long long Texels = 0;
  double MemoryMB = 0;
  vtkSmartPointer<vtkRenderPass> Chain;
  csmScenes::Installed Passes;
  std::vector<double> Times;            // coarse orbit + fly-through
  std::vector<double> InteractiveTimes; // interactive orbit
  std::vector<double> StillTimes;       // still camera
  std::vector<double> PlanMs, MapMs;    // --breakdown: per timed frame
  double TexelsRendered = 0.0;          // map texels rendered over the timed frames
  long long MapsRendered = 0, MapsKept = 0;
  long long DepthPasses = 0; // depth-only passes that measured the visible depths (VisibleDepthFit)
  long long CascadesPlanned = 0, FramesPlanned = 0; // k_used: cascades of the first light a frame
  csmTruth::Classification Errors;
  std::vector<double> M;
  std::vector<double> Storage;
  std::vector<double> StorageOverOptimal; // Lloyd et al. 2006: S / S_opt (App. C) per measured view
  std::vector<double> NearFit;            // first cascade's near / camera near, per timed frame
  std::vector<double> MathUs;
  // Flicker along the dolly: compared pixels of consecutive frames, and those whose class
  // (shadowed: factor < 0.5) changed while the truth's did not.
  long long FlickerCompared = 0, Flickered = 0;
  std::vector<char> LastShadowed; // previous dolly frame, per pixel (-1: not compared)
  double FlickerPct() const { return FlickerCompared ? 100.0 * Flickered / FlickerCompared : NAN; }
};

std::vector<Technique> Techniques(const Options& o)
{
  std::vector<Technique> list;
  auto add = [&](const std::string& label, const std::string& technique, int warp, int partition,
               int k, int pcf)
  {
    Technique t;
    t.Label = label;
    t.Shadow.Technique = technique;
    t.Shadow.Warp = warp;
    t.Shadow.Partition = partition;
    t.Shadow.Cascades = k;
    t.Shadow.PCF = pcf;
    // The technique as labelled: k cascades, each map at its share of the budget (not the
    // pass's defaults, which choose the count and the texels from the error target).
    t.Shadow.AdaptiveCascades = false;
    t.Shadow.ErrorTarget = 0.0;
    t.Shadow.Resolution = static_cast<int>(std::lround(o.Budget / std::sqrt(double(k))));
    t.Texels = static_cast<long long>(k) * t.Shadow.Resolution * t.Shadow.Resolution;
    // VTK: an R32F colour map plus a depth renderbuffer; ours: one 32-bit depth texel.
    t.MemoryMB = (technique == "vtk" ? 8.0 : 4.0) * t.Texels / (1024.0 * 1024.0);
    list.push_back(t);
  };
  add("vtk", "vtk", 0, 0, 1, 1);
  // The pass as a user gets it (every option at the pass's default: up to 8 cascades, as many
  // as meet the error target), and the same with two fixed cascades.
  auto addDefaults =
    [&](const std::string& label, int fixedCascades, bool cullClosed = true, bool visibleFit = true)
  {
    Technique t; // default-constructed ShadowOptions: the pass's defaults
    t.Label = label;
    if (fixedCascades > 0)
    {
      t.Shadow.Cascades = fixedCascades;
      t.Shadow.AdaptiveCascades = false;
    }
    t.Shadow.CullClosedCasters = t.Shadow.CullClosedCasters && cullClosed;
    t.Shadow.VisibleDepthFit = t.Shadow.VisibleDepthFit && visibleFit;
    t.Texels =
      static_cast<long long>(t.Shadow.Cascades) * t.Shadow.Resolution * t.Shadow.Resolution;
    t.MemoryMB = 4.0 * t.Texels / (1024.0 * 1024.0);
    list.push_back(t);
  };
  addDefaults("default", 0);
  addDefaults("default k2 fixed", 2);
  if (!o.Quick)
  {
    // The defaults with closed casters drawn with both sides, as before CullClosedCasters.
    addDefaults("default both sides", 0, false);
    // The defaults with the cascades fitted to the scene's boxes, as before VisibleDepthFit.
    addDefaults("default boxes fit", 0, true, false);
    // The defaults with maps sized for a smaller error (more texels where the view needs them):
    // the error target's trade of speed against error.
    for (double target : { 1.0, 0.5 })
    {
      std::ostringstream label;
      label << "default target " << target;
      addDefaults(label.str(), 0);
      list.back().Shadow.ErrorTarget = target;
    }
    using P = vtkCascadedShadowMapPlanner;
    add("uniform", "csm", P::WARP_NONE, P::SPLIT_SINGLE, 1, 1);
    add("lispsm k1", "csm", P::WARP_LISPSM, P::SPLIT_SINGLE, 1, 1);
    add("pssm k4", "csm", P::WARP_NONE, P::SPLIT_PRACTICAL, 4, 1);
    add("log+lispsm k4", "csm", P::WARP_LISPSM, P::SPLIT_LOG, 4, 1);
    const int ours[2] = { P::WARP_GENERALIZED, P::SPLIT_ADAPTIVE };
    add("ours k2 pcf1", "csm", ours[0], ours[1], 2, 1);
    add("ours k2 pcf3", "csm", ours[0], ours[1], 2, 3);
    add("ours k2 pcf5", "csm", ours[0], ours[1], 2, 5);
    add("ours k3 pcf5", "csm", ours[0], ours[1], 3, 5);
    add("ours k4 pcf5", "csm", ours[0], ours[1], 4, 5);
#if CSM_COMPARISON_TECHNIQUES
    // Face partitioning (Lloyd et al. 2006, §5.1): a generalized-warped map per side face the
    // light enters (up to 4, FP+W), or two log z-partitions per face (up to 8, FP+ZP+W), in the
    // atlas of four maps of half the budget (the same texels as the rows above).
    add("fp-w", "csm", P::WARP_GENERALIZED, P::SPLIT_ADAPTIVE, 4, 3);
    list.back().Shadow.FacePartitions = 1;
    add("fp-zp-w", "csm", P::WARP_GENERALIZED, P::SPLIT_ADAPTIVE, 4, 3);
    list.back().Shadow.FacePartitions = 2;
    // Camera space shadow maps (Kolić & Mihajlović): one map of the budget, or four sharing it
    // in the dueling frustum case.
    add("cssm", "csm", P::WARP_GENERALIZED, P::SPLIT_ADAPTIVE, 1, 3);
    list.back().Shadow.CameraSpace = true;
#endif
  }
  if (!o.Labels.empty())
  {
    for (const std::string& label : o.Labels)
      if (std::none_of(
            list.begin(), list.end(), [&](const Technique& t) { return t.Label == label; }))
        fail("no technique labelled '" + label + "' in this mode");
    list.erase(std::remove_if(list.begin(), list.end(),
                 [&](const Technique& t) {
                   return std::find(o.Labels.begin(), o.Labels.end(), t.Label) == o.Labels.end();
                 }),
      list.end());
  }
  return list;
}

struct View
{
  double Position[3], Focal[3], Up[3];
  double Light[3];
  std::string Name;
  bool Timed;
  bool Measured;
};

double Dot(const double a[3], const double b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/// The camera paths (orbit, fly-through: timed, every n-th measured) and the light sweep
/// (gamma 0..180 at the scene's default view: measured).
std::vector<View> Views(const csmScenes::Scene& scene, const Options& o)
{
  std::vector<View> views;
  const double* eye = scene.CameraPosition;
  const double* focal = scene.FocalPoint;
  const double key[3] = { -0.45, -1.0, -0.35 };
  double radius = std::hypot(eye[0] - focal[0], eye[2] - focal[2]);
  for (int i = 0; i < o.Frames; ++i)
  {
    View v;
    const double a = 2.0 * M_PI * i / o.Frames + std::atan2(eye[2] - focal[2], eye[0] - focal[0]);
    v.Position[0] = focal[0] + radius * std::cos(a);
    v.Position[1] = eye[1];
    v.Position[2] = focal[2] + radius * std::sin(a);
    std::copy(focal, focal + 3, v.Focal);
    v.Up[0] = 0, v.Up[1] = 1, v.Up[2] = 0;
    std::copy(key, key + 3, v.Light);
    v.Name = "orbit" + std::to_string(i);
    v.Timed = true;
    v.Measured = i % o.AccuracyEvery == 0;
    views.push_back(v);
  }
  for (int i = 0; i < o.Frames; ++i)
  {
    // Fly from the default eye through the focal point's neighbourhood, looking ahead.
    View v;
    const double t = 0.9 * i / o.Frames;
    for (int c = 0; c < 3; ++c)
    {
      v.Position[c] = eye[c] + t * (focal[c] - eye[c]);
      v.Focal[c] = focal[c] + (focal[c] - eye[c]) * 0.5;
    }
    v.Position[1] = std::max(v.Position[1], focal[1] * 0.5 + 1.0);
    v.Up[0] = 0, v.Up[1] = 1, v.Up[2] = 0;
    std::copy(key, key + 3, v.Light);
    v.Name = "fly" + std::to_string(i);
    v.Timed = true;
    v.Measured = i % o.AccuracyEvery == o.AccuracyEvery / 2;
    views.push_back(v);
  }
  const std::vector<double> gammas = o.Quick
    ? std::vector<double>{ 45.0 }
    : std::vector<double>{ 0, 10, 30, 60, 90, 120, 150, 170, 180 };
  for (double g : gammas)
  {
    View v;
    std::copy(eye, eye + 3, v.Position);
    std::copy(focal, focal + 3, v.Focal);
    v.Up[0] = 0, v.Up[1] = 1, v.Up[2] = 0;
    csmScenes::LightAtGamma(eye, focal, g, v.Light);
    v.Name = "gamma" + std::to_string(static_cast<int>(g));
    v.Timed = false;
    v.Measured = true;
    views.push_back(v);
  }
  return views;
}

void Apply(const View& v, vtkRenderer* renderer, vtkLight* light, const csmScenes::Scene& scene)
{
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(v.Position);
  camera->SetFocalPoint(v.Focal);
  camera->SetViewUp(v.Up);
  camera->OrthogonalizeViewUp();
  if (scene.ClippingRange[1] > 0)
    camera->SetClippingRange(scene.ClippingRange);
  else
    renderer->ResetCameraClippingRange();
  light->SetFocalPoint(0, 0, 0);
  light->SetPosition(-v.Light[0], -v.Light[1], -v.Light[2]);
}

/// The misclassified pixels of one view: false shadow red, false light blue, the pixels
/// classified right light grey (lit) and dark grey (shadowed), those not compared the plain
/// render darkened.
bool WriteErrorImage(const std::string& file, vtkImageData* plain,
  const std::vector<char>& comparable, const std::vector<char>& occluded,
  const std::vector<float>& factor, const std::vector<char>& edges)
{
  vtkNew<vtkImageData> image;
  image->DeepCopy(plain);
  auto* rgb = static_cast<unsigned char*>(image->GetScalarPointer());
  const int channels = image->GetNumberOfScalarComponents();
  for (size_t k = 0; k < comparable.size(); ++k)
  {
    unsigned char* px = rgb + k * channels;
    const unsigned char grey = static_cast<unsigned char>((px[0] + px[1] + px[2]) / 9);
    unsigned char out[3] = { grey, grey, grey };
    switch (csmTruth::ClassifyPixel(comparable[k], occluded[k], factor[k]))
    {
      case csmTruth::PixelClass::FalseShadow: // (dark red where a shadow edge crosses the pixel)
        out[0] = edges[k] ? 150 : 255, out[1] = out[2] = 0;
        break;
      case csmTruth::PixelClass::FalseLight: // (dark blue there)
        out[2] = edges[k] ? 150 : 255, out[0] = out[1] = 0;
        break;
      case csmTruth::PixelClass::Shadowed:
        out[0] = out[1] = out[2] = 90;
        break;
      case csmTruth::PixelClass::Lit:
        out[0] = out[1] = out[2] = 200;
        break;
      case csmTruth::PixelClass::NotCompared:
        break;
    }
    for (int c = 0; c < 3 && c < channels; ++c)
      px[c] = out[c];
  }
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(file.c_str());
  writer->SetInputData(image);
  writer->Write();
  if (writer->GetErrorCode() != 0)
  {
    std::fprintf(stderr, "csm-bench: error: cannot write %s\n", file.c_str());
    return false;
  }
  return true;
}

/// Texels per pixel of the map at a point: max(m_x, m_z) of Lloyd Eq. 2-4, scaled to the map
/// and image resolutions.
/// The level of a light's pages the lookup reads at world point p, view depth `depth` (0: the
/// base, or no pages).
int PageLevelAt(const vtkCascadedShadowMapBakerPass::LightMaps& lm, const double p[3], double depth)
{
  if (!lm.Pages.Active || lm.Cascades.size() != 1)
    return 0;
  csm::PageLevels levels;
  levels.baseTexels = glm::dvec2(lm.Pages.BaseTexels[0], lm.Pages.BaseTexels[1]);
  levels.baseDepth = lm.Pages.BaseDepth;
  levels.count = lm.Pages.Levels;
  const double* w = lm.Cascades[0].WorldToMap; // (orthographic: w = 1)
  const double bx = 0.5 * (w[0] * p[0] + w[1] * p[1] + w[2] * p[2] + w[3]) + 0.5;
  const double by = 0.5 * (w[4] * p[0] + w[5] * p[1] + w[6] * p[2] + w[7]) + 0.5;
  return csm::pageLevelRead(levels, lm.Pages.Table, bx, by, levels.fineness(depth));
}

double AliasingAt(const Technique& t, vtkRenderer* renderer, const double light[3],
  const double p[3], int imageHeight)
{
  vtkCamera* camera = renderer->GetActiveCamera();
  const double aspect = renderer->GetTiledAspectRatio();
  double m[2] = { 0, 0 };
  // Texels along the map axes that follow light space x and z.
  double resolution[2] = { double(t.Shadow.Resolution), double(t.Shadow.Resolution) };
  if (t.Passes.Cascaded)
  {
    const auto& maps = t.Passes.Cascaded->GetShadowMapBakerPass()->GetLightMaps();
    if (maps.empty() || maps[0].GetNumberOfCascades() == 0)
      return NAN;
    double dir[3], eye[3];
    camera->GetDirectionOfProjection(dir);
    camera->GetPosition(eye);
    const double q[3] = { p[0] - eye[0], p[1] - eye[1], p[2] - eye[2] };
    const double depth = Dot(q, dir);
    const auto& lm = maps[0];
    double splitFar[vtkCascadedShadowMapPlanner::MAXIMUM_NUMBER_OF_CASCADES] = {};
    for (int i = 0; i < lm.GetNumberOfCascades(); ++i)
      splitFar[i] = lm.Cascades[i].SplitFar;
    int c = vtkCascadedShadowMapPlanner::GetCascadeAtDepth(
      depth, lm.SplitNear, splitFar, lm.GetNumberOfCascades());
    if (c < 0)
      return NAN;
    // The map the lookup takes: this cascade's where it holds the point, else the next one's
    // (a kept map may miss its slice's edge); none where neither does (a scene-fitted map holds
    // only what can be in shadow: the point is lit without a map, and has no m).
    auto holds = [&](int i)
    {
      double h[4];
      const double ph[4] = { p[0], p[1], p[2], 1.0 };
      for (int r = 0; r < 4; ++r)
        h[r] = lm.Cascades[i].WorldToMap[4 * r] * ph[0] +
          lm.Cascades[i].WorldToMap[4 * r + 1] * ph[1] +
          lm.Cascades[i].WorldToMap[4 * r + 2] * ph[2] +
          lm.Cascades[i].WorldToMap[4 * r + 3] * ph[3];
      return h[3] > 0.0 && std::abs(h[0]) <= h[3] && std::abs(h[1]) <= h[3] && h[2] <= h[3];
    };
    if (!holds(c))
    {
      if (c + 1 < lm.GetNumberOfCascades() && holds(c + 1))
        ++c;
      else
        return NAN;
    }
    // The resolution this view's map was rendered at (t along light space x if it was turned).
    // With light-space pages, the level the lookup reads there, whose texels are square in the
    // world: as a map whose t row spans what its s row does, with as many texels.
    double worldToMap[16];
    std::copy(lm.Cascades[c].WorldToMap, lm.Cascades[c].WorldToMap + 16, worldToMap);
    const bool turned = lm.Cascades[c].Turned;
    resolution[0] = lm.Cascades[c].Resolution[turned ? 1 : 0];
    resolution[1] = lm.Cascades[c].Resolution[turned ? 0 : 1];
    const int level = PageLevelAt(lm, p, depth);
    if (level > 0)
    {
      const double s = std::sqrt(Dot(worldToMap, worldToMap));
      const double t = std::sqrt(Dot(worldToMap + 4, worldToMap + 4));
      for (int k = 4; k < 8; ++k)
        worldToMap[k] *= s / t;
      resolution[0] = resolution[1] = lm.Pages.BaseTexels[0] * std::exp2(level);
    }
    vtkCascadedShadowMapPlanner::ComputeAliasing(camera, aspect, light, worldToMap, p, m);
  }
  else if (t.Passes.Vtk)
  {
    auto* cameras = t.Passes.Vtk->GetShadowMapBakerPass()->GetLightCameras();
    if (!cameras || cameras->empty())
      return NAN;
    vtkCamera* lc = (*cameras)[0];
    // As VTK's lookup builds it: projection with aspect 1, times the light's view.
    vtkMatrix4x4* composite = lc->GetCompositeProjectionTransformMatrix(1.0, -1, 1);
    vtkCascadedShadowMapPlanner::ComputeAliasing(camera, aspect, light, composite->GetData(), p, m);
  }
  else
    return NAN;
  return std::max(m[0] / resolution[0], m[1] / resolution[1]) * imageHeight;
}

/// After a timed frame: what the baker did (maps rendered and kept; with --breakdown, the
/// planning and map times).
void Account(Technique& t, vtkRenderer* renderer)
{
  if (!t.Passes.Cascaded)
    return;
  vtkCascadedShadowMapBakerPass* baker = t.Passes.Cascaded->GetShadowMapBakerPass();
  t.MapsRendered += baker->GetLastFrameStatistics().CascadesRendered;
  t.MapsKept += baker->GetLastFrameStatistics().CascadesKept;
  t.DepthPasses += baker->GetLastFrameStatistics().VisibleDepthsMeasured ? 1 : 0;
  t.TexelsRendered += baker->GetLastFrameStatistics().TexelsRendered;
  if (!baker->GetLightMaps().empty())
  {
    t.CascadesPlanned += baker->GetLightMaps()[0].GetNumberOfCascades();
    ++t.FramesPlanned;
    const double cameraNear = renderer->GetActiveCamera()->GetClippingRange()[0];
    if (cameraNear > 0.0 && baker->GetLightMaps()[0].GetNumberOfCascades() > 0)
      t.NearFit.push_back(baker->GetLightMaps()[0].SplitNear / cameraNear);
  }
  if (baker->GetMeasureTimes())
  {
    t.PlanMs.push_back(1000.0 * baker->GetLastFrameStatistics().PlanSeconds);
    t.MapMs.push_back(1000.0 * baker->GetLastFrameStatistics().MapSeconds);
  }
}

double Median(std::vector<double> v)
{
  if (v.empty())
    return NAN;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

double Mean(const std::vector<double>& v)
{
  double sum = 0.0;
  for (double x : v)
    sum += x;
  return v.empty() ? NAN : sum / v.size();
}

/// --breakdown: the mean time to render one map (over the timed frames that rendered any).
double PerMap(const Technique& t)
{
  double sum = 0.0;
  for (double x : t.MapMs)
    sum += x;
  return t.MapMs.empty() || t.MapsRendered == 0 ? NAN : sum / t.MapsRendered;
}

double Percentile(std::vector<double> v, double q)
{
  if (v.empty())
    return NAN;
  std::sort(v.begin(), v.end());
  return v[static_cast<size_t>(q * (v.size() - 1))];
}

struct Row
{
  std::string Scene;
  const Technique* T;
};

bool Plot(const std::vector<std::pair<std::string, std::vector<Technique>>>& results,
  const std::string& file)
{
  vtkNew<vtkContextView> view;
  view->GetRenderWindow()->SetOffScreenRendering(1);
  view->GetRenderWindow()->SetMultiSamples(0);
  const int rows = static_cast<int>(results.size());
  view->GetRenderWindow()->SetSize(1100, 380 * rows);
  view->GetRenderer()->SetBackground(1, 1, 1);
  vtkNew<vtkChartMatrix> matrix;
  matrix->SetSize(vtkVector2i(2, rows));
  matrix->SetGutter(vtkVector2f(70, 60));
  view->GetScene()->AddItem(matrix);
  for (int r = 0; r < rows; ++r)
  {
    const auto& scene = results[rows - 1 - r]; // first scene at the top
    for (int col = 0; col < 2; ++col)
    {
      vtkChart* chart = matrix->GetChart(vtkVector2i(col, r));
      chart->SetTitle(
        scene.first + (col == 0 ? ": misclassified % vs frame ms" : ": max m vs frame ms"));
      chart->GetAxis(vtkAxis::BOTTOM)->SetTitle("median frame time (ms, software Mesa)");
      chart->GetAxis(vtkAxis::LEFT)
        ->SetTitle(col == 0 ? "misclassified pixels (%)" : "max m (texels per pixel)");
      if (col == 1)
        chart->GetAxis(vtkAxis::LEFT)->SetLogScale(true);
      // One series per technique family, and the Pareto front (lower time and error) as a line.
      std::vector<std::pair<double, double>> points;
      for (const std::string family : { "vtk", "baselines", "ours" })
      {
        vtkNew<vtkTable> table;
        vtkNew<vtkDoubleArray> x, y;
        x->SetName("ms");
        y->SetName(family.c_str());
        table->AddColumn(x);
        table->AddColumn(y);
        for (const Technique& t : scene.second)
        {
          const bool isOurs = t.Label.rfind("ours", 0) == 0 || t.Label.rfind("default", 0) == 0;
          const std::string f = t.Label == "vtk" ? "vtk" : isOurs ? "ours" : "baselines";
          if (f != family)
            continue;
          const double ms = Median(t.Times);
          const double err = col == 0 ? t.Errors.MismatchPct() : csmTruth::Summarize(t.M).Max;
          if (!std::isfinite(ms) || !std::isfinite(err))
            continue;
          table->InsertNextBlankRow();
          const vtkIdType k = table->GetNumberOfRows() - 1;
          table->SetValue(k, 0, ms);
          table->SetValue(k, 1, err);
          points.emplace_back(ms, err);
        }
        vtkPlot* plot = chart->AddPlot(vtkChart::POINTS);
        plot->SetInputData(table, 0, 1);
        const unsigned char color[3][3] = { { 220, 40, 40 }, { 120, 120, 120 }, { 30, 80, 220 } };
        const int ci = family == "vtk" ? 0 : family == "baselines" ? 1 : 2;
        plot->SetColor(color[ci][0], color[ci][1], color[ci][2], 255);
        plot->SetWidth(2.0);
        vtkPlotPoints::SafeDownCast(plot)->SetMarkerSize(12);
      }
      std::sort(points.begin(), points.end());
      vtkNew<vtkTable> front;
      vtkNew<vtkDoubleArray> fx, fy;
      fx->SetName("ms");
      fy->SetName("Pareto front");
      front->AddColumn(fx);
      front->AddColumn(fy);
      double best = INFINITY;
      for (const auto& p : points)
        if (p.second < best)
        {
          best = p.second;
          front->InsertNextBlankRow();
          front->SetValue(front->GetNumberOfRows() - 1, 0, p.first);
          front->SetValue(front->GetNumberOfRows() - 1, 1, p.second);
        }
      if (front->GetNumberOfRows() >= 2) // a line needs two points
      {
        vtkPlot* line = chart->AddPlot(vtkChart::LINE);
        line->SetInputData(front, 0, 1);
        line->SetColor(0, 0, 0, 255);
        line->SetWidth(1.5);
      }
      vtkChartXY* xy = vtkChartXY::SafeDownCast(chart);
      xy->SetShowLegend(r == rows - 1 && col == 0);
      // Top left: VTK's pass usually sits top right (slow and often wrong).
      xy->GetLegend()->SetHorizontalAlignment(vtkChartLegend::LEFT);
    }
  }
  view->GetRenderWindow()->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(view->GetRenderWindow());
  grab->Update();
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(file.c_str());
  writer->SetInputConnection(grab->GetOutputPort());
  writer->Write();
  return writer->GetErrorCode() == 0;
}

Options Parse(int argc, char** argv)
{
  Options o;
  bool framesGiven = false, budgetGiven = false, sizeGiven = false, scenesGiven = false;
  for (int i = 1; i < argc; ++i)
  {
    const std::string f = argv[i];
    const char* v = i + 1 < argc ? argv[i + 1] : nullptr;
    if (f == "--help" || f == "-h")
    {
      std::printf(
        "usage: csm-bench [--quick] [--breakdown] [--out FILE.csv] [--plot FILE.png]\n"
        "                 [--size WxH] [--frames N] [--budget TEXELS_SIDE] [--scenes a,b,...]\n"
        "scenes: platform, platform-beams (its bars as lines drawn as tubes), platform-2m,\n"
        "towers, engine, or a model file (.vtp .vtk .stl .ply .obj .glb .gltf, on a\n"
        "ground). --quick: platform (or --scenes),\n"
        "640x480, 6 frames a path, budget 2048, VTK's pass and ours with the defaults.\n"
        "Timed paths: coarse orbit + fly-through (interleaved), an interactive orbit of\n"
        "2 degrees a frame and a still camera. --breakdown: per frame, the planning and\n"
        "map times (glFinish around them) and the maps rendered / kept; each path\n"
        "frame printed with its clear, each map's size and time, and the rest (the\n"
        "main view with the lookup).\n"
        "--labels a,b,...: only these techniques (their labels as in the CSV; the comparison\n"
        "techniques fp-w, fp-zp-w and cssm in a build with -DCSM_COMPARISON_TECHNIQUES=ON).\n"
        "--error-images DIR: per measured view and technique, DIR/scene-label-view.png:\n"
        "false shadow red, false light blue (darker where a shadow edge crosses the pixel),\n"
        "right light / dark grey, not compared dark.\n"
        "\nThe other modes:\n\n%s\n%s",
        csmWalk::Usage().c_str(), csmChanges::Usage().c_str());
      std::exit(0);
    }
    else if (f == "--quick")
      o.Quick = true;
    else if (f == "--breakdown")
      o.Breakdown = true;
    else if ((f == "--out" || f == "--plot" || f == "--size" || f == "--frames" ||
               f == "--budget" || f == "--scenes" || f == "--error-images" || f == "--labels") &&
      !v)
      fail(f + " needs a value");
    else if (f == "--out")
      o.Out = argv[++i];
    else if (f == "--plot")
      o.Plot = argv[++i];
    else if (f == "--error-images")
      o.ErrorImages = argv[++i];
    else if (f == "--labels")
    {
      std::stringstream list(argv[++i]);
      std::string label;
      while (std::getline(list, label, ','))
      {
#if !CSM_COMPARISON_TECHNIQUES
        if (label == "fp-w" || label == "fp-zp-w" || label == "cssm")
          fail(csmScenes::NoComparisonTechniques("--labels " + label));
#endif
        o.Labels.push_back(label);
      }
    }
    else if (f == "--size")
    {
      char extra;
      if (std::sscanf(argv[++i], "%dx%d%c", &o.Width, &o.Height, &extra) != 2 || o.Width < 64 ||
        o.Height < 64 || o.Width > 4096 || o.Height > 4096)
        fail("--size needs WxH, 64..4096 each");
      sizeGiven = true;
    }
    else if (f == "--frames")
    {
      o.Frames = std::atoi(argv[++i]);
      if (o.Frames < 2 || o.Frames > 10000)
        fail("--frames must be in [2, 10000]");
      framesGiven = true;
    }
    else if (f == "--budget")
    {
      o.Budget = std::atoi(argv[++i]);
      if (o.Budget < 256 || o.Budget > 8192)
        fail("--budget must be in [256, 8192]");
      budgetGiven = true;
    }
    else if (f == "--scenes")
    {
      o.Scenes.clear();
      std::stringstream list(argv[++i]);
      std::string name;
      while (std::getline(list, name, ','))
      {
        if (name != "platform" && name != "platform-beams" && name != "platform-2m" &&
          name != "towers" && name != "engine" && !csmScenes::NamesAFile(name))
          fail("unknown scene '" + name + "' (or a model file: a path with its extension)");
        o.Scenes.push_back(name);
      }
      scenesGiven = true;
    }
    else
      fail("unknown option '" + f + "'");
  }
  if (o.Quick)
  {
    if (!framesGiven)
      o.Frames = 6;
    if (!budgetGiven)
      o.Budget = 2048;
    if (!sizeGiven)
      o.Width = 640, o.Height = 480;
    if (!scenesGiven)
      o.Scenes = { "platform" };
    o.Rounds = 2;
    o.AccuracyEvery = 6;
    o.InteractiveFrames = 10;
    o.StillFrames = 4;
    o.DollyFrames = 6;
  }
  Techniques(o); // fails here on a label the mode does not have
  // Where the results go, checked before any scene is built or rendered.
  if (!o.ErrorImages.empty())
  {
    const std::string error = csmScenes::CheckOutputFolder(o.ErrorImages);
    if (!error.empty())
      fail("--error-images: " + error);
  }
  if (!o.Plot.empty())
  {
    const std::string error = csmScenes::CheckOutputFile(o.Plot);
    if (!error.empty())
      fail("--plot: " + error);
  }
  return o;
}
} // namespace

int main(int argc, char** argv)
{
  for (int i = 1; i < argc; ++i)
  {
    if (std::string(argv[i]) == "--walk")
    {
      return csmWalk::Run(argc, argv, CSM_ENGINE_MODEL); // the path comes from CMake
    }
    if (std::string(argv[i]) == "--changes")
    {
      return csmChanges::Run(argc, argv, CSM_ENGINE_MODEL);
    }
  }
  const Options o = Parse(argc, argv);
  std::ofstream csv(o.Out);
  if (!csv)
    fail("cannot write '" + o.Out + "'");
  std::ofstream detail(o.Out + ".views.csv");
  csv << "scene,technique,label,warp,partition,cascades,resolution,pcf,texels,memory_mb,median_ms,"
         "p10_ms,p90_ms,math_us,mismatch_pct,false_shadow_pct,false_light_pct,max_m,p95_m,mean_m,"
         "storage,frames,measured_pixels,interactive_ms,still_ms,plan_ms,map_ms,map_ms_per_map,"
         "texels_per_map,flicker_pct,k_used,near_fit,storage_over_optimal,"
         "maps_rendered_per_frame,maps_kept_per_frame,depth_passes_per_frame\n";
  detail << "scene,label,view,mismatch_pct,false_shadow_pct,false_light_pct,max_m,p95_m,mean_m,"
            "off_edge_mismatch_pct\n";
  std::vector<std::pair<std::string, std::vector<Technique>>> results;

  for (const std::string& sceneName : o.Scenes)
  {
    csmScenes::Scene scene;
    if (sceneName == "platform")
      scene = csmScenes::Platform(250000);
    else if (sceneName == "platform-beams")
      scene = csmScenes::PlatformBeams();
    else if (sceneName == "platform-2m")
      scene = csmScenes::Platform(2100000); // >= 2M triangles
    else if (sceneName == "towers")
      scene = csmScenes::Towers();
    else
    {
      // The engine's path comes from CMake; any other name is a model file.
      std::string error;
      if (!csmScenes::FromFile(
            sceneName == "engine" ? CSM_ENGINE_MODEL : sceneName.c_str(), scene, error))
      {
        std::fprintf(
          stderr, "csm-bench: skipping scene %s: %s\n", sceneName.c_str(), error.c_str());
        continue;
      }
    }
    std::printf("scene %s: %lld triangles", sceneName.c_str(), scene.Triangles);
    if (scene.Lines > 0)
      std::printf(", %lld lines drawn as tubes", scene.Lines);
    std::printf("\n");
    std::fflush(stdout);

    vtkNew<vtkRenderer> renderer;
    vtkNew<vtkRenderWindow> window;
    window->SetSize(o.Width, o.Height);
    window->SetMultiSamples(0);
    window->SetOffScreenRendering(1);
    window->AddRenderer(renderer);
    renderer->SetBackground(0.75, 0.82, 0.9);
    renderer->AutomaticLightCreationOff();
    csmScenes::Install(scene, renderer, double(o.Width) / o.Height);
    vtkNew<vtkLight> key;
    key->SetLightTypeToSceneLight();
    key->SetPositional(false);
    key->SetIntensity(0.85);
    renderer->AddLight(key);
    vtkNew<vtkLight> fill;
    fill->SetLightTypeToHeadlight();
    fill->SetIntensity(0.25);
    renderer->AddLight(fill);

    std::vector<Technique> techniques = Techniques(o);
    for (Technique& t : techniques)
    {
      t.Chain = csmScenes::BuildChain(t.Shadow, t.Passes);
      if (t.Passes.Cascaded)
        t.Passes.Cascaded->GetShadowMapBakerPass()->SetMeasureTimes(o.Breakdown);
    }
    const std::vector<View> views = Views(scene, o);

    // Timing: rounds of blocks, each technique rendering every Rounds-th frame of the paths,
    // after one untimed warm-up frame (shader set-up when the chain changes).
    vtkNew<vtkTimerLog> timer;
    for (int round = 0; round < o.Rounds; ++round)
    {
      for (Technique& t : techniques)
      {
        renderer->SetPass(t.Chain);
        bool warm = false;
        for (size_t i = 0; i < views.size(); ++i)
        {
          if (!views[i].Timed || static_cast<int>(i) % o.Rounds != round)
            continue;
          Apply(views[i], renderer, key, scene);
          if (!warm)
          {
            window->Render();
            window->WaitForCompletion();
            warm = true;
          }
          timer->StartTimer();
          window->Render();
          window->WaitForCompletion(); // glFinish: the frame is done
          timer->StopTimer();
          t.Times.push_back(1000.0 * timer->GetElapsedTime());
          Account(t, renderer);
          if (o.Breakdown)
          {
            // Each path frame: its time, and what the baker did in it.
            std::printf("    %-18s frame %2zu %7.1f ms", t.Label.c_str(), i, t.Times.back());
            if (t.Passes.Cascaded)
            {
              auto* b = t.Passes.Cascaded->GetShadowMapBakerPass();
              std::printf("  plan %.1f  maps %.1f ms  rendered %d kept %d of k %d  %.2f M texels"
                          "  %d blocks",
                1000.0 * b->GetLastFrameStatistics().PlanSeconds,
                1000.0 * b->GetLastFrameStatistics().MapSeconds,
                b->GetLastFrameStatistics().CascadesRendered,
                b->GetLastFrameStatistics().CascadesKept,
                b->GetLightMaps().empty() ? 0 : b->GetLightMaps()[0].GetNumberOfCascades(),
                1e-6 * b->GetLastFrameStatistics().TexelsRendered,
                b->GetLastFrameStatistics().BlocksDrawn);
              // The rest of the frame: the main view with the lookup.
              std::printf("  rest %.1f ms  clear %.1f ms",
                t.Times.back() -
                  1000.0 *
                    (b->GetLastFrameStatistics().PlanSeconds +
                      b->GetLastFrameStatistics().MapSeconds),
                1000.0 * b->GetLastFrameStatistics().ClearSeconds);
              if (!b->GetLightMaps().empty())
              {
                const auto& maps = b->GetLightMaps()[0];
                for (int c = 0; c < maps.GetNumberOfCascades(); ++c)
                {
                  std::printf(" %dx%d%s", maps.Cascades[c].Resolution[0],
                    maps.Cascades[c].Resolution[1], maps.Cascades[c].IsSceneFitted() ? "f" : "");
                  if (b->GetLastFrameStatistics().GetCascadeSeconds(c) > 0.0)
                    std::printf(
                      " %.1fms", 1000.0 * b->GetLastFrameStatistics().GetCascadeSeconds(c));
                }
              }
            }
            std::printf("\n");
          }
        }
      }
    }

    // The interactive orbit (2 degrees a frame, the window's desired update rate raised as
    // vtkRenderWindowInteractor does while the user drags) and the still camera: consecutive
    // frames for each technique (maps kept across frames are what these measure), the
    // techniques taking turns over the rounds.
    for (int round = 0; round < o.Rounds; ++round)
    {
      for (Technique& t : techniques)
      {
        renderer->SetPass(t.Chain);
        for (int path = 0; path < 2; ++path)
        {
          const bool interactive = path == 0;
          const int frames = interactive ? o.InteractiveFrames : o.StillFrames;
          View v = views[0]; // the default view's orbit start
          Apply(v, renderer, key, scene);
          window->Render(); // untimed: the first frame of a path renders every map
          window->WaitForCompletion();
          window->SetDesiredUpdateRate(interactive ? 15.0 : 0.0001);
          for (int i = 0; i < frames; ++i)
          {
            if (interactive)
            {
              renderer->GetActiveCamera()->Azimuth(2.0);
              if (scene.ClippingRange[1] <= 0)
                renderer->ResetCameraClippingRange();
            }
            timer->StartTimer();
            window->Render();
            window->WaitForCompletion();
            timer->StopTimer();
            (interactive ? t.InteractiveTimes : t.StillTimes)
              .push_back(1000.0 * timer->GetElapsedTime());
            Account(t, renderer);
          }
          window->SetDesiredUpdateRate(0.0001);
        }
      }
    }

    // Accuracy: white, diffuse-only materials and the key light alone, so that the render with
    // shadows over the render without is the shadow factor.
    csmTruth::RayScene rays;
    rays.Build(renderer, o.Height);
    for (const auto& actor : scene.Actors)
    {
      actor->GetProperty()->SetColor(1, 1, 1);
      actor->GetProperty()->SetAmbient(0.0);
      actor->GetProperty()->SetDiffuse(1.0);
      actor->GetProperty()->SetSpecular(0.0);
    }
    fill->SwitchOff();
    key->SetIntensity(1.0);
    renderer->SetBackground(0, 0, 0);
    long long measuredPixels = 0;
    vtkNew<vtkCascadedShadowMapPlanner> planner;
    for (const View& v : views)
    {
      if (!v.Measured)
        continue;
      Apply(v, renderer, key, scene);
      if (rays.TubesFollowCamera())
        rays.Build(renderer, o.Height); // tubes as wide as this view draws them
      renderer->SetPass(nullptr);
      window->Render();
      auto plain = csmWalk::GrabFrame(window);
      const auto surfaces = rays.CastPrimary(renderer->GetActiveCamera(), o.Width, o.Height);
      const auto comparable = csmTruth::ComparablePixels(surfaces, o.Width, o.Height, v.Light);
      std::vector<char> occluded(surfaces.size(), 0);
      for (size_t k = 0; k < surfaces.size(); ++k)
        occluded[k] = comparable[k] && rays.Occluded(surfaces[k], v.Light);
      const auto edges = rays.ShadowEdges(
        renderer->GetActiveCamera(), o.Width, o.Height, surfaces, comparable, occluded, v.Light);
      for (Technique& t : techniques)
      {
        renderer->SetPass(t.Chain);
        window->Render();
        auto shadowed = csmWalk::GrabFrame(window);
        const auto factor = csmTruth::FactorFromRenders(shadowed, plain);
        const csmTruth::Classification c =
          csmTruth::Classify(surfaces, comparable, occluded, factor, &edges);
        if (!o.ErrorImages.empty())
        {
          std::string name = sceneName + "-" + t.Label + "-" + v.Name + ".png";
          std::replace(name.begin(), name.end(), ' ', '_');
          if (!WriteErrorImage(
                o.ErrorImages + "/" + name, plain, comparable, occluded, factor, edges))
            std::exit(1); // (said why)
        }
        t.Errors.Add(c);
        std::vector<double> m;
        for (size_t k = 0; k < surfaces.size(); k += 1)
        {
          if (!comparable[k])
            continue;
          const double value = AliasingAt(t, renderer, v.Light, surfaces[k].Position, o.Height);
          if (std::isfinite(value))
            m.push_back(value);
        }
        const csmTruth::Stats ms = csmTruth::Summarize(m);
        t.M.insert(t.M.end(), m.begin(), m.end());
        detail << sceneName << "," << t.Label << "," << v.Name << "," << c.MismatchPct() << ","
               << c.FalseShadowPct() << "," << c.FalseLightPct() << "," << ms.Max << "," << ms.P95
               << "," << ms.Mean << "," << c.OffEdgeMismatchPct() << "\n";
        if (t.Passes.Cascaded)
        {
          // The analytic storage factor of this frame and the time of the math that plans it.
          vtkCascadedShadowMapBakerPass* baker = t.Passes.Cascaded->GetShadowMapBakerPass();
          planner->SetNumberOfCascades(baker->GetPlanner()->GetNumberOfCascades());
          planner->SetWarpMode(baker->GetPlanner()->GetWarpMode());
          planner->SetSplitScheme(baker->GetPlanner()->GetSplitScheme());
          double bounds[6];
          renderer->ComputeVisiblePropBounds(bounds);
          planner->ClearReceiverBounds();
          for (const auto& actor : scene.Actors)
            planner->AddReceiverBounds(actor->GetBounds());
          const double aspect = double(o.Width) / o.Height;
          timer->StartTimer();
          for (int r = 0; r < 20; ++r)
            planner->Plan(renderer->GetActiveCamera(), aspect, v.Light, bounds);
          timer->StopTimer();
          t.MathUs.push_back(1e6 * timer->GetElapsedTime() / 20.0);
          t.Storage.push_back(planner->GetStorageTotal());
          t.StorageOverOptimal.push_back(planner->GetStorageTotal() / planner->GetStorageOptimal());
        }
      }
      measuredPixels += std::count(comparable.begin(), comparable.end(), 1);
    }

    // Temporal stability: a dolly toward the focal point (1 % of the distance a frame) with the
    // light 15 degrees from the view direction (behind the viewer), the hard case for cascades
    // that follow the view; every frame measured. Flicker = compared pixels (in both frames of a
    // consecutive pair) whose shadowed/lit class changes while the truth's does not.
    {
      View dolly = views[0];
      csmScenes::LightAtGamma(dolly.Position, dolly.Focal, 15.0, dolly.Light);
      double dir[3] = { dolly.Focal[0] - dolly.Position[0], dolly.Focal[1] - dolly.Position[1],
        dolly.Focal[2] - dolly.Position[2] };
      const double distance = std::sqrt(Dot(dir, dir));
      for (double& c : dir)
        c /= distance;
      std::vector<char> lastOccluded;
      for (Technique& t : techniques)
        t.LastShadowed.clear();
      for (int frame = 0; frame < o.DollyFrames; ++frame)
      {
        View v = dolly;
        for (int c = 0; c < 3; ++c)
          v.Position[c] = dolly.Position[c] + 0.01 * frame * distance * dir[c];
        Apply(v, renderer, key, scene);
        if (rays.TubesFollowCamera())
          rays.Build(renderer, o.Height);
        renderer->SetPass(nullptr);
        window->Render();
        auto plain = csmWalk::GrabFrame(window);
        const auto surfaces = rays.CastPrimary(renderer->GetActiveCamera(), o.Width, o.Height);
        const auto comparable = csmTruth::ComparablePixels(surfaces, o.Width, o.Height, v.Light);
        std::vector<char> occluded(surfaces.size(), -1);
        for (size_t k = 0; k < surfaces.size(); ++k)
          if (comparable[k])
            occluded[k] = rays.Occluded(surfaces[k], v.Light) ? 1 : 0;
        for (Technique& t : techniques)
        {
          renderer->SetPass(t.Chain);
          window->Render();
          auto shadowed = csmWalk::GrabFrame(window);
          const auto factor = csmTruth::FactorFromRenders(shadowed, plain);
          std::vector<char> classes(surfaces.size(), -1);
          for (size_t k = 0; k < surfaces.size(); ++k)
            if (comparable[k])
              classes[k] = factor[k] < 0.5f ? 1 : 0;
          if (!t.LastShadowed.empty())
          {
            for (size_t k = 0; k < classes.size(); ++k)
            {
              if (classes[k] < 0 || t.LastShadowed[k] < 0)
                continue;
              ++t.FlickerCompared;
              t.Flickered += classes[k] != t.LastShadowed[k] && occluded[k] == lastOccluded[k];
            }
          }
          t.LastShadowed = classes;
        }
        lastOccluded = occluded;
      }
    }

    auto timedFrames = [](const Technique& t)
    {
      return std::max<double>(
        1.0, double(t.Times.size() + t.InteractiveTimes.size() + t.StillTimes.size()));
    };
    for (const Technique& t : techniques)
    {
      const csmTruth::Stats ms = csmTruth::Summarize(t.M);
      const bool csm = t.Shadow.Technique == "csm";
      csv << sceneName << "," << t.Shadow.Technique << "," << t.Label << ","
          << (csm ? kWarps[t.Shadow.Warp] : "none") << ","
          << (!csm ? "single"
#if CSM_COMPARISON_TECHNIQUES
                 : t.Shadow.CameraSpace         ? "cssm"
                 : t.Shadow.FacePartitions == 1 ? "face"
                 : t.Shadow.FacePartitions == 2 ? "face+log"
#endif
                                                : kPartitions[t.Shadow.Partition])
          << "," << t.Shadow.Cascades << "," << t.Shadow.Resolution << ","
          << (csm ? t.Shadow.PCF : 1) << "," << t.Texels << "," << t.MemoryMB << ","
          << Median(t.Times) << "," << Percentile(t.Times, 0.1) << "," << Percentile(t.Times, 0.9)
          << "," << (csm ? Median(t.MathUs) : NAN) << "," << t.Errors.MismatchPct() << ","
          << t.Errors.FalseShadowPct() << "," << t.Errors.FalseLightPct() << "," << ms.Max << ","
          << ms.P95 << "," << ms.Mean << "," << (csm ? Median(t.Storage) : NAN) << ","
          << t.Times.size() << "," << measuredPixels << "," << Median(t.InteractiveTimes) << ","
          << Median(t.StillTimes) << "," << Median(t.PlanMs) << "," << Mean(t.MapMs) << ","
          << PerMap(t) << ","
          << (csm && t.MapsRendered > 0 ? t.TexelsRendered / t.MapsRendered : NAN) << ","
          << t.FlickerPct() << ","
          << (t.FramesPlanned ? double(t.CascadesPlanned) / t.FramesPlanned : NAN) << ","
          << Median(t.NearFit) << "," << Median(t.StorageOverOptimal) << ","
          << (csm ? double(t.MapsRendered) / timedFrames(t) : NAN) << ","
          << (csm ? double(t.MapsKept) / timedFrames(t) : NAN) << ","
          << (csm ? double(t.DepthPasses) / timedFrames(t) : NAN) << "\n";
      std::printf("  %-16s %8.1f ms  mismatch %6.3f%% (shadow %6.3f%%, light %6.3f%%, off shadow "
                  "edges %6.3f%%)  max m %8.2f  p95 m %6.2f  flicker %5.2f%%\n",
        t.Label.c_str(), Median(t.Times), t.Errors.MismatchPct(), t.Errors.FalseShadowPct(),
        t.Errors.FalseLightPct(), t.Errors.OffEdgeMismatchPct(), ms.Max, ms.P95, t.FlickerPct());
      if (t.Label != "vtk")
      {
        const Technique& vtk = techniques.front();
        std::printf("  %-16s time / vtk: paths %.2fx  interactive %.2fx  still %.2fx", "",
          Median(t.Times) / Median(vtk.Times),
          Median(t.InteractiveTimes) / Median(vtk.InteractiveTimes),
          Median(t.StillTimes) / Median(vtk.StillTimes));
        if (csm)
          std::printf("  k %.2f  maps rendered %.2f kept %.2f per frame, %.2f visible-depth passes",
            t.FramesPlanned ? double(t.CascadesPlanned) / t.FramesPlanned : 0.0,
            double(t.MapsRendered) / timedFrames(t), double(t.MapsKept) / timedFrames(t),
            double(t.DepthPasses) / timedFrames(t));
        if (!t.PlanMs.empty())
          std::printf("  plan %.3f ms  maps %.1f ms a frame, %.1f ms a map of %.0f^2 texels",
            Median(t.PlanMs), Mean(t.MapMs), PerMap(t),
            t.MapsRendered > 0 ? std::sqrt(t.TexelsRendered / t.MapsRendered) : 0.0);
        std::printf("\n");
      }
    }
    std::fflush(stdout);
    renderer->SetPass(nullptr);
    for (Technique& t : techniques)
    {
      t.Chain->ReleaseGraphicsResources(window);
      t.Chain = nullptr;
    }
    results.emplace_back(sceneName, std::move(techniques));
  }
  // The exit status says whether the run measured and wrote what it was asked for.
  csv.close();
  detail.close();
  if (!csv || !detail)
  {
    std::fprintf(
      stderr, "csm-bench: error: cannot write %s or %s.views.csv\n", o.Out.c_str(), o.Out.c_str());
    return 1;
  }
  std::printf("wrote %s and %s.views.csv\n", o.Out.c_str(), o.Out.c_str());
  if (results.empty())
  {
    std::fprintf(stderr, "csm-bench: error: no scene was measured\n");
    return 1;
  }
  if (!o.Plot.empty())
  {
    if (!Plot(results, o.Plot))
    {
      std::fprintf(stderr, "csm-bench: error: cannot write %s\n", o.Plot.c_str());
      return 1;
    }
    std::printf("wrote %s\n", o.Plot.c_str());
  }
  return 0;
}
