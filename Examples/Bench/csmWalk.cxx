// SPDX-License-Identifier: BSD-3-Clause
// csm-bench --walk: the camera paths a user takes through a structure, every frame a normal
// (not interactive) render: a close orbit of 2 degrees a frame, a dolly of 1 % of the model a
// frame and a still camera at their first view, at 640x480 with a 60 degree view. Ours at its
// defaults against VTK's pass as it comes (its default 1024^2 map) and the unshadowed frame,
// interleaved in rounds in one process; medians of the frame times, and per frame what our maps
// cost: maps rendered and kept, texels and caster cells drawn.
#include "csmWalk.h"

#include "csmFileChecks.h"
#include "csmScenes.h"
#include "csmTechnique.h"
#include "csmTruth.h"

#include "vtkActor.h"
#include "vtkAppendPolyData.h"
#include "vtkCamera.h"
#include "vtkCascadedShadowMapBakerPass.h"
#include "vtkCascadedShadowMapPass.h"
#include "vtkCubeSource.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderPass.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkWindowToImageFilter.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace
{
struct WalkOptions
{
  std::vector<std::string> Scenes = { "engine", "towers", "lattice" };
  int Frames = 20;
  int Rounds = 3;
  int Size[2] = { 640, 480 };
  bool CameraLight = false;
  bool PerFrame = false;
  bool Variants = false;      ///< also ours with the cascades fitted to the boxes, maps not moved
  std::vector<double> Slacks; ///< also ours with these MapSlack values
  bool Interactive = false;   ///< frames as while the user drags (the interactor's update rate)
  bool Accuracy = true;       ///< each path's misclassified pixels and flicker against the truth
  std::string Out = "walk.csv";
  std::string Engine;
};

[[noreturn]] void walkFail(const std::string& message)
{
  std::fprintf(stderr, "csm-bench --walk: error: %s (see --help)\n", message.c_str());
  std::exit(2);
}

/// A cubic lattice of thin square bars (n nodes a side, spacing 1, bars 4 % of it thick) on a
/// ground plate: a structure full of thin bars whose shadows fall on each other.
csmScenes::Scene Lattice(int n)
{
  vtkNew<vtkAppendPolyData> bars;
  const double t = 0.02;
  for (int i = 0; i < n; ++i)
  {
    for (int j = 0; j < n; ++j)
    {
      for (int k = 0; k < n; ++k)
      {
        const double p[3] = { double(i), double(j) + 0.2, double(k) };
        for (int axis = 0; axis < 3; ++axis)
        {
          if ((axis == 0 ? i : axis == 1 ? j : k) == n - 1)
          {
            continue;
          }
          vtkNew<vtkCubeSource> bar;
          double b[6] = { p[0] - t, p[0] + t, p[1] - t, p[1] + t, p[2] - t, p[2] + t };
          b[2 * axis + 1] += 1.0;
          bar->SetBounds(b);
          bar->Update();
          bars->AddInputData(bar->GetOutput());
        }
      }
    }
  }
  vtkNew<vtkCubeSource> plate;
  plate->SetBounds(-2.0, n + 1.0, -0.05, 0.0, -2.0, n + 1.0);
  plate->Update();
  bars->Update();
  csmScenes::Scene scene;
  scene.Name = "lattice";
  for (vtkPolyData* data : { bars->GetOutput(), plate->GetOutput() })
  {
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputData(data);
    auto actor = vtkSmartPointer<vtkActor>::New();
    actor->SetMapper(mapper);
    actor->GetProperty()->SetColor(0.8, 0.8, 0.75);
    scene.Actors.push_back(actor);
    scene.Triangles += csmScenes::CountTriangles(data);
  }
  const double c = 0.5 * (n - 1);
  const double bounds[6] = { -2.0, n + 1.0, -0.05, n - 0.8, -2.0, n + 1.0 };
  std::copy(bounds, bounds + 6, scene.Bounds);
  scene.FocalPoint[0] = c, scene.FocalPoint[1] = 0.5 * c, scene.FocalPoint[2] = c;
  scene.CameraPosition[0] = c + 1.6 * n, scene.CameraPosition[1] = 0.9 * n;
  scene.CameraPosition[2] = c + 1.3 * n;
  return scene;
}

struct Pose
{
  double Eye[3], Focal[3];
};

/// The paths a walk times.
enum class PathKind
{
  Orbit,
  Dolly,
  Still
};

std::string pathNameOf(PathKind kind)
{
  return kind == PathKind::Orbit ? "orbit" : (kind == PathKind::Dolly ? "dolly" : "still");
}

/// A path of frames: the close orbit (2 degrees a frame about the vertical through the focal
/// point), the dolly (toward the focal point, 1 % of the model's diagonal a frame) or the still
/// camera at the paths' first view (every frame drawn again, nothing changed: the floor of the
/// lookup and the frame's fixed costs).
std::vector<Pose> Path(const csmScenes::Scene& scene, double closeness, PathKind kind, int frames)
{
  const bool orbit = kind == PathKind::Orbit;
  const double* f = scene.FocalPoint;
  double eye[3];
  for (int c = 0; c < 3; ++c)
  {
    eye[c] = f[c] + closeness * (scene.CameraPosition[c] - f[c]);
  }
  const double* b = scene.Bounds;
  const double diagonal = std::sqrt(
    (b[1] - b[0]) * (b[1] - b[0]) + (b[3] - b[2]) * (b[3] - b[2]) + (b[5] - b[4]) * (b[5] - b[4]));
  double toward[3] = { f[0] - eye[0], f[1] - eye[1], f[2] - eye[2] };
  const double distance =
    std::sqrt(toward[0] * toward[0] + toward[1] * toward[1] + toward[2] * toward[2]);
  // (A path that would pass the focal point takes smaller steps.)
  const double step = std::min(0.01 * diagonal, 0.8 * distance / std::max(frames, 1));
  std::vector<Pose> poses;
  for (int path = 0; path < frames; ++path)
  {
    const int i = kind == PathKind::Still ? 0 : path;
    Pose p;
    if (orbit)
    {
      const double a = i * 2.0 * M_PI / 180.0;
      const double x = eye[0] - f[0], z = eye[2] - f[2];
      p.Eye[0] = f[0] + std::cos(a) * x - std::sin(a) * z;
      p.Eye[1] = eye[1];
      p.Eye[2] = f[2] + std::sin(a) * x + std::cos(a) * z;
      std::copy(f, f + 3, p.Focal);
    }
    else
    {
      for (int c = 0; c < 3; ++c)
      {
        p.Eye[c] = eye[c] + i * step * toward[c] / distance;
        p.Focal[c] = p.Eye[c] + toward[c]; // looking ahead, as far as at the start
      }
    }
    poses.push_back(p);
  }
  return poses;
}

struct Technique
{
  std::string Label;
  csmScenes::ShadowOptions Shadow;
  double Slack = -1.0; ///< MapSlack (-1: the default)
  std::vector<double> Ms;
  double Texels = 0.0, Cells = 0.0;
  long long MapsRendered = 0, MapsKept = 0, MapsMoved = 0, Frames = 0;
};

/// What a path's accuracy pass measures of one technique against the truth.
struct PathAccuracy
{
  csmTruth::Classification Errors;
  long long FlickerCompared = 0, Flickered = 0;
  double FlickerPct() const
  {
    return FlickerCompared ? 100.0 * double(Flickered) / double(FlickerCompared) : 0.0;
  }
};

/// The light of a walk: the scene's key light (or at gammaDeg from the first view's direction),
/// as a scene light or a camera light (then fixed to the camera, as ParaView's key light is).
void SetLight(
  vtkLight* light, vtkCamera* camera, const Pose& first, double gammaDeg, bool cameraLight)
{
  double travel[3] = { csmWalk::kSceneLightTravel[0], csmWalk::kSceneLightTravel[1],
    csmWalk::kSceneLightTravel[2] };
  if (gammaDeg >= 0.0)
  {
    csmScenes::LightAtGamma(first.Eye, first.Focal, gammaDeg, travel);
  }
  if (!cameraLight)
  {
    csmWalk::SetSceneLight(light, travel);
    return;
  }
  light->SetPositional(false);
  light->SetFocalPoint(0, 0, 0);
  // The same direction in the first view's camera coordinates.
  camera->SetPosition(first.Eye);
  camera->SetFocalPoint(first.Focal);
  camera->SetViewUp(0, 1, 0);
  camera->OrthogonalizeViewUp();
  vtkMatrix4x4* view = camera->GetViewTransformMatrix();
  double toward[4] = { -travel[0], -travel[1], -travel[2], 0.0 }, inCamera[4];
  view->MultiplyPoint(toward, inCamera);
  light->SetLightTypeToCameraLight();
  light->SetPosition(inCamera[0], inCamera[1], inCamera[2]);
}

/// The camera at a pose of a path, its clipping range as the timed rounds set it.
void applyPose(vtkRenderer* renderer, const csmScenes::Scene& scene, const Pose& p)
{
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(p.Eye);
  camera->SetFocalPoint(p.Focal);
  camera->SetViewUp(0, 1, 0);
  camera->OrthogonalizeViewUp();
  if (scene.ClippingRange[1] > 0)
    camera->SetClippingRange(scene.ClippingRange);
  else
    renderer->ResetCameraClippingRange();
}

/// Every frame of a path once more, the props white and diffuse under the walk's light alone
/// (rays: the scene's triangles): the plain frame, then each technique's (its chain kept across
/// the frames, as in the timed rounds), against the ray-cast truth: misclassified pixels, and
/// flicker, the pixels compared in two consecutive frames whose class (shadowed or lit) changes
/// while the truth's does not (as csm-bench's dolly counts it).
std::vector<PathAccuracy> measurePathAccuracy(vtkRenderer* renderer, vtkRenderWindow* window,
  vtkLight* light, const csmScenes::Scene& scene, csmTruth::RayScene& rays,
  const std::vector<Pose>& poses, double gamma, bool cameraLight,
  const std::vector<csmScenes::ShadowOptions>& techniques, int width, int height)
{
  std::vector<PathAccuracy> result(techniques.size());
  std::vector<vtkSmartPointer<vtkRenderPass>> chains;
  for (const csmScenes::ShadowOptions& options : techniques)
  {
    csmScenes::Installed installed;
    chains.push_back(csmScenes::BuildChain(options, installed));
  }
  SetLight(light, renderer->GetActiveCamera(), poses.front(), gamma, cameraLight);
  std::vector<std::vector<char>> lastClass(techniques.size());
  std::vector<char> lastOccluded;
  for (int i = -1; i < static_cast<int>(poses.size()); ++i)
  {
    applyPose(renderer, scene, poses[std::max(i, 0)]);
    if (rays.TubesFollowCamera())
      rays.Build(renderer, height); // tubes as wide as this view draws them
    renderer->SetPass(nullptr);
    window->Render();
    auto plain = csmWalk::GrabFrame(window);
    double position[3], focal[3];
    light->GetTransformedPosition(position);
    light->GetTransformedFocalPoint(focal);
    const double travel[3] = { focal[0] - position[0], focal[1] - position[1],
      focal[2] - position[2] };
    const csmWalk::FrameTruth truth =
      csmWalk::CastTruth(rays, renderer->GetActiveCamera(), width, height, travel);
    for (size_t t = 0; t < techniques.size(); ++t)
    {
      renderer->SetPass(chains[t]);
      window->Render();
      if (i < 0)
        continue; // the first view, as in the timed rounds
      std::vector<float> factor;
      result[t].Errors.Add(csmWalk::ClassifyFrame(window, plain, truth, &factor));
      std::vector<char> classes(truth.Surfaces.size(), -1);
      for (size_t k = 0; k < truth.Surfaces.size(); ++k)
        if (truth.Comparable[k])
          classes[k] = factor[k] < 0.5f ? 1 : 0;
      for (size_t k = 0; k < classes.size() && !lastClass[t].empty(); ++k)
      {
        if (classes[k] < 0 || lastClass[t][k] < 0)
          continue;
        ++result[t].FlickerCompared;
        result[t].Flickered +=
          classes[k] != lastClass[t][k] && truth.Occluded[k] == lastOccluded[k];
      }
      lastClass[t] = std::move(classes);
    }
    if (i >= 0)
      lastOccluded = truth.Occluded;
  }
  for (auto& chain : chains)
    chain->ReleaseGraphicsResources(window);
  renderer->SetPass(nullptr);
  return result;
}

WalkOptions ParseWalk(int argc, char** argv)
{
  WalkOptions o;
  for (int i = 1; i < argc; ++i)
  {
    const std::string f = argv[i];
    const bool hasValue = i + 1 < argc;
    if (f == "--walk")
      continue;
    else if (f == "--help" || f == "-h")
    {
      std::printf("%s", csmWalk::Usage().c_str());
      std::exit(0);
    }
    else if (f == "--camera-light")
      o.CameraLight = true;
    else if (f == "--per-frame")
      o.PerFrame = true;
    else if (f == "--variants")
      o.Variants = true;
    else if (f == "--no-accuracy")
      o.Accuracy = false;
    else if (f == "--interactive")
      o.Interactive = true;
    else if (f == "--slack" && hasValue)
    {
      std::stringstream list(argv[++i]);
      std::string value;
      while (std::getline(list, value, ','))
        o.Slacks.push_back(std::atof(value.c_str()));
    }
    else if ((f == "--scenes" || f == "--frames" || f == "--rounds" || f == "--out" ||
               f == "--size" || f == "--slack") &&
      !hasValue)
      walkFail(f + " needs a value");
    else if (f == "--scenes")
    {
      o.Scenes.clear();
      std::stringstream list(argv[++i]);
      std::string name;
      while (std::getline(list, name, ','))
      {
        if (name != "engine" && name != "towers" && name != "lattice" && name != "platform" &&
          !csmScenes::NamesAFile(name))
          walkFail("unknown scene '" + name +
            "' (engine, towers, lattice, platform, or a model file: a path with its extension)");
        o.Scenes.push_back(name);
      }
    }
    else if (f == "--frames")
    {
      o.Frames = std::atoi(argv[++i]);
      if (o.Frames < 3 || o.Frames > 1000)
        walkFail("--frames must be in [3, 1000]");
    }
    else if (f == "--rounds")
    {
      o.Rounds = std::atoi(argv[++i]);
      if (o.Rounds < 1 || o.Rounds > 20)
        walkFail("--rounds must be in [1, 20]");
    }
    else if (f == "--size")
    {
      if (std::sscanf(argv[++i], "%dx%d", &o.Size[0], &o.Size[1]) != 2 || o.Size[0] < 64 ||
        o.Size[1] < 64 || o.Size[0] > 4096 || o.Size[1] > 4096)
        walkFail("--size needs WxH, 64..4096 each");
    }
    else if (f == "--out")
      o.Out = argv[++i];
    else
      walkFail("unknown option '" + f + "' for --walk");
  }
  const std::string error = csmScenes::CheckOutputFile(o.Out);
  if (!error.empty())
    walkFail("--out: " + error);
  return o;
}
} // namespace

std::string csmWalk::Usage()
{
  const WalkOptions o;
  std::string scenes;
  for (const std::string& name : o.Scenes)
    scenes += (scenes.empty() ? "" : ",") + name;
  char text[1600];
  std::snprintf(text, sizeof(text),
    "csm-bench --walk [--scenes a,b,...] [--frames N] [--rounds N] [--size WxH] [--out FILE.csv]\n"
    "                 [--camera-light] [--per-frame] [--variants] [--slack s,...] [--interactive]\n"
    "The camera paths users take close to a structure (an orbit of 2 degrees and a dolly of 1 %%\n"
    "of the model a frame, and a still camera at their first view, every frame a normal\n"
    "render): VTK's pass as it comes, ours and the\n"
    "unshadowed frame side by side, with the maps drawn and kept and the texels and caster cells\n"
    "drawn a frame.\n"
    "  --scenes      engine, towers, lattice, platform, or a model file [%s]\n"
    "  --frames N    frames a path, 3..1000 [%d]\n"
    "  --rounds N    rounds of every path, 1..20 [%d]\n"
    "  --size WxH    the window, 64..4096 each [%dx%d]\n"
    "  --out FILE    the CSV written [%s]\n"
    "  --camera-light  a light that turns with the camera (as ParaView's light kit)\n"
    "  --per-frame   each frame's maps, their times and how far a kept map missed\n"
    "  --variants    also ours with the cascades fitted to the boxes, maps not moved, no\n"
    "                footprint and no light-space pages\n"
    "  --slack s,... also ours with these MapSlack values\n"
    "  --interactive frames as while the user drags (the interactor's update rate)\n"
    "  --no-accuracy without the misclassified pixels and flicker against the ray-cast\n"
    "                truth (Embree), measured after the timed rounds on every frame of every\n"
    "                path with white diffuse materials, VTK's pass and ours\n",
    scenes.c_str(), o.Frames, o.Rounds, o.Size[0], o.Size[1], o.Out.c_str());
  return text;
}

int csmWalk::Run(int argc, char** argv, const std::string& engineModel)
{
  const WalkOptions o = ParseWalk(argc, argv);
  std::ofstream csv(o.Out);
  if (!csv)
    walkFail("cannot write '" + o.Out + "'");
  csv << "scene,path,light,label,median_ms,frames,maps_rendered_per_frame,maps_kept_per_frame,"
         "texels_per_frame,caster_cells_per_frame,maps_moved_per_frame,misclassified_pct,"
         "flicker_pct,off_edge_misclassified_pct\n";
  std::printf("walk: %dx%d, 60 degree view, %d frames a path, %d rounds; %s light\n", o.Size[0],
    o.Size[1], o.Frames, o.Rounds, o.CameraLight ? "camera" : "scene");
  for (const std::string& name : o.Scenes)
  {
    csmScenes::Scene scene;
    // How close the walk starts (a share of the default view's distance) and the light.
    double closeness = 0.4, gamma = -1.0;
    if (name == "towers")
    {
      scene = csmScenes::Towers();
      closeness = 1.0;
    }
    else if (name == "lattice")
    {
      scene = Lattice(10);
      closeness = 0.45;
      gamma = 15.0;
    }
    else if (name == "platform")
    {
      scene = csmScenes::Platform(250000);
    }
    else
    {
      std::string error;
      if (!csmScenes::FromFile(name == "engine" ? engineModel : name, scene, error))
      {
        std::fprintf(
          stderr, "csm-bench --walk: skipping scene %s: %s\n", name.c_str(), error.c_str());
        continue;
      }
    }
    vtkNew<vtkRenderer> renderer;
    vtkNew<vtkRenderWindow> window;
    vtkNew<vtkLight> light;
    csmWalk::ShowScene(renderer, window, light, scene, o.Size);
    window->SetDesiredUpdateRate(o.Interactive ? 15.0 : 0.0001);
    vtkCamera* camera = renderer->GetActiveCamera();
    camera->SetViewAngle(60.0);
    std::printf("scene %s: %lld triangles\n", name.c_str(), scene.Triangles);
    // The CSV's rows of this scene (label -> row without its accuracy), by path.
    std::vector<std::vector<std::pair<std::string, std::string>>> rows;
    const std::vector<PathKind> kinds = { PathKind::Orbit, PathKind::Dolly, PathKind::Still };
    for (const PathKind kind : kinds)
    {
      rows.emplace_back();
      const std::string pathName = pathNameOf(kind);
      const std::vector<Pose> poses = Path(scene, closeness, kind, o.Frames);
      std::vector<Technique> techniques(3);
      techniques[0].Label = "none";
      techniques[0].Shadow.Technique = "none";
      techniques[1].Label = "vtk default";
      techniques[1].Shadow.Technique = "vtk";
      techniques[1].Shadow.Resolution = 1024; // vtkShadowMapBakerPass's own default
      techniques[2].Label = "default";
      for (double slack : o.Slacks)
      {
        techniques.emplace_back();
        techniques.back().Label = "slack " + std::to_string(slack).substr(0, 4);
        techniques.back().Slack = slack;
      }
      if (o.Variants)
      {
        techniques.emplace_back();
        techniques.back().Label = "boxes fit";
        techniques.back().Shadow.VisibleDepthFit = false;
        techniques.emplace_back();
        techniques.back().Label = "not moved";
        techniques.back().Shadow.MoveKeptMaps = false;
        techniques.emplace_back();
        techniques.back().Label = "no footprint";
        techniques.back().Shadow.VisibleFootprintFit = false;
        techniques.emplace_back();
        techniques.back().Label = "no pages";
        techniques.back().Shadow.LightSpacePages = false;
      }
      for (int round = 0; round < o.Rounds; ++round)
      {
        for (Technique& t : techniques)
        {
          SetLight(light, camera, poses.front(), gamma, o.CameraLight);
          const csmScenes::Installed passes = csmScenes::InstallTechnique(renderer, t.Shadow);
          vtkCascadedShadowMapBakerPass* baker =
            passes.Cascaded ? passes.Cascaded->GetShadowMapBakerPass() : nullptr;
          if (baker && t.Slack >= 0.0)
            baker->SetMapSlack(t.Slack);
          if (baker && o.PerFrame)
            baker->MeasureTimesOn(); // (glFinish between the steps: per-frame times only)
          for (int i = -1; i < static_cast<int>(poses.size()); ++i)
          {
            applyPose(renderer, scene, poses[std::max(i, 0)]); // (-1: the first view, not timed)
            const auto start = std::chrono::steady_clock::now();
            window->Render();
            window->WaitForCompletion();
            const double ms = 1000.0 *
              std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            if (i < 1)
            {
              continue; // the first frame of a path builds the shaders and the first maps
            }
            t.Ms.push_back(ms);
            ++t.Frames;
            if (baker)
            {
              t.MapsRendered += baker->GetLastFrameStatistics().CascadesRendered;
              t.MapsKept += baker->GetLastFrameStatistics().CascadesKept;
              t.MapsMoved += baker->GetLastFrameStatistics().CascadesMoved;
              t.Texels += baker->GetLastFrameStatistics().TexelsRendered;
              t.Cells += baker->GetLastFrameStatistics().CellsDrawn;
              const auto& stats = baker->GetLastFrameStatistics();
              // (The planning time holds the visible-depth pass; the rest of the frame is the
              // main view with the lookup.)
              const double planMs = 1e3 * stats.PlanSeconds, clearMs = 1e3 * stats.ClearSeconds,
                           mapsMs = 1e3 * stats.MapSeconds;
              if (o.PerFrame)
                std::printf(
                  "    %s %s frame %d: %.1f ms, maps %d rendered %d kept (%d moved), "
                  "%.2f M texels, %.0f k cells (%d blocks), pages %d drawn of %d needed (%d "
                  "resident), near %.3g; depth pass (%d stood "
                  "in by their boxes) and plan %.1f ms, maps %.1f ms (clears and moves %.1f), "
                  "view and lookup %.1f ms\n",
                  name.c_str(), pathName.c_str(), i, ms,
                  baker->GetLastFrameStatistics().CascadesRendered,
                  baker->GetLastFrameStatistics().CascadesKept,
                  baker->GetLastFrameStatistics().CascadesMoved,
                  1e-6 * baker->GetLastFrameStatistics().TexelsRendered,
                  1e-3 * baker->GetLastFrameStatistics().CellsDrawn, stats.BlocksDrawn,
                  stats.PagesDrawn, stats.PagesNeeded, stats.PagesResident,
                  baker->GetLightMaps().empty() ? 0.0 : baker->GetLightMaps()[0].SplitNear,
                  stats.DepthPassStandIns, planMs, mapsMs, clearMs,
                  std::max(0.0, ms - planMs - mapsMs));
              if (o.PerFrame && !baker->GetLightMaps().empty())
              {
                const auto& maps = baker->GetLightMaps()[0];
                for (int c = 0; c < maps.GetNumberOfCascades(); ++c)
                  std::printf(
                    "      map %d: %dx%d of %dx%d, to depth %.3g%s, moved %d, %d, %.1f ms, "
                    "kept map's error %.3g of a fresh one's\n",
                    c, maps.Cascades[c].Resolution[0], maps.Cascades[c].Resolution[1],
                    maps.Cascades[0].Tile[2], maps.Cascades[0].Tile[3], maps.Cascades[c].SplitFar,
                    maps.Cascades[c].IsSceneFitted() ? " (scene-fitted)" : "",
                    maps.Cascades[c].Moved[0], maps.Cascades[c].Moved[1],
                    1e3 * baker->GetLastFrameStatistics().GetCascadeSeconds(c),
                    c < vtkCascadedShadowMapPlanner::MAXIMUM_NUMBER_OF_CASCADES
                      ? baker->GetLastFrameStatistics().KeptError[c]
                      : 0.0);
              }
            }
          }
          // (Each pass chain gives back its GL objects before it goes.)
          if (vtkRenderPass* chain = renderer->GetPass())
          {
            chain->ReleaseGraphicsResources(window);
          }
          renderer->SetPass(nullptr);
        }
      }
      const double none = csmWalk::Median(techniques[0].Ms),
                   vtk = csmWalk::Median(techniques[1].Ms);
      for (const Technique& t : techniques)
      {
        const double frames = std::max<long long>(t.Frames, 1);
        std::printf("  %-6s %-7s %-12s %7.1f ms  %5.2fx vtk default  %5.2fx unshadowed",
          name.c_str(), pathName.c_str(), t.Label.c_str(), csmWalk::Median(t.Ms),
          csmWalk::Median(t.Ms) / vtk, csmWalk::Median(t.Ms) / none);
        if (t.Shadow.Technique == "csm")
          std::printf("  maps %.2f rendered %.2f kept (%.2f moved), %.2f M texels, %.0f k cells a "
                      "frame",
            t.MapsRendered / frames, t.MapsKept / frames, t.MapsMoved / frames,
            1e-6 * t.Texels / frames, 1e-3 * t.Cells / frames);
        std::printf("\n");
        std::ostringstream row;
        row << name << "," << pathName << "," << (o.CameraLight ? "camera" : "scene") << ","
            << t.Label << "," << csmWalk::Median(t.Ms) << "," << t.Frames << ","
            << t.MapsRendered / frames << "," << t.MapsKept / frames << "," << t.Texels / frames
            << "," << t.Cells / frames << "," << t.MapsMoved / frames;
        rows.back().emplace_back(t.Label, row.str());
      }
      std::fflush(stdout);
    }
    // Accuracy along every path: VTK's pass as it comes and ours at its defaults.
    std::map<std::pair<size_t, std::string>, PathAccuracy> accuracy;
    if (o.Accuracy)
    {
      csmTruth::RayScene rays;
      for (const auto& actor : scene.Actors)
      {
        actor->GetProperty()->SetColor(1, 1, 1);
        actor->GetProperty()->SetAmbient(0.0);
        actor->GetProperty()->SetDiffuse(1.0);
        actor->GetProperty()->SetSpecular(0.0);
      }
      renderer->SetBackground(0, 0, 0);
      rays.Build(renderer, o.Size[1]);
      std::vector<csmScenes::ShadowOptions> measured(2);
      measured[0].Technique = "vtk";
      measured[0].Resolution = 1024;
      const std::string labels[2] = { "vtk default", "default" };
      for (size_t path = 0; path < kinds.size(); ++path)
      {
        const std::vector<PathAccuracy> a = measurePathAccuracy(renderer, window, light, scene,
          rays, Path(scene, closeness, kinds[path], o.Frames), gamma, o.CameraLight, measured,
          o.Size[0], o.Size[1]);
        std::printf("  %-6s %-7s accuracy", name.c_str(), pathNameOf(kinds[path]).c_str());
        for (size_t t = 0; t < a.size(); ++t)
        {
          accuracy[{ path, labels[t] }] = a[t];
          std::printf("%s %s %.3f %% misclassified (%.3f %% off shadow edges), flicker %.3f %%",
            t ? ";" : ":", labels[t].c_str(), a[t].Errors.MismatchPct(),
            a[t].Errors.OffEdgeMismatchPct(), a[t].FlickerPct());
        }
        std::printf("\n");
      }
    }
    for (size_t path = 0; path < rows.size(); ++path)
    {
      for (const auto& [label, row] : rows[path])
      {
        const auto found = accuracy.find({ path, label });
        csv << row << "," << (found == accuracy.end() ? NAN : found->second.Errors.MismatchPct())
            << "," << (found == accuracy.end() ? NAN : found->second.FlickerPct()) << ","
            << (found == accuracy.end() ? NAN : found->second.Errors.OffEdgeMismatchPct()) << "\n";
      }
    }
  }
  return 0;
}

vtkSmartPointer<vtkImageData> csmWalk::GrabFrame(vtkRenderWindow* window)
{
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->ReadFrontBufferOff();
  grab->ShouldRerenderOff();
  grab->Update();
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->DeepCopy(grab->GetOutput());
  return image;
}

csmWalk::FrameTruth csmWalk::CastTruth(
  const csmTruth::RayScene& rays, vtkCamera* camera, int width, int height, const double travel[3])
{
  FrameTruth truth;
  truth.Surfaces = rays.CastPrimary(camera, width, height);
  truth.Comparable = csmTruth::ComparablePixels(truth.Surfaces, width, height, travel);
  truth.Occluded.assign(truth.Surfaces.size(), 0);
  for (size_t k = 0; k < truth.Surfaces.size(); ++k)
    truth.Occluded[k] = truth.Comparable[k] && rays.Occluded(truth.Surfaces[k], travel) ? 1 : 0;
  truth.Edges = rays.ShadowEdges(
    camera, width, height, truth.Surfaces, truth.Comparable, truth.Occluded, travel);
  return truth;
}

csmTruth::Classification csmWalk::ClassifyFrame(vtkRenderWindow* window, vtkImageData* plain,
  const FrameTruth& truth, std::vector<float>* factors)
{
  std::vector<float> factor = csmTruth::FactorFromRenders(csmWalk::GrabFrame(window), plain);
  const csmTruth::Classification c =
    csmTruth::Classify(truth.Surfaces, truth.Comparable, truth.Occluded, factor, &truth.Edges);
  if (factors)
    *factors = std::move(factor);
  return c;
}

double csmWalk::Median(std::vector<double> values)
{
  if (values.empty())
    return NAN;
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

void csmWalk::SetSceneLight(vtkLight* light, const double travel[3])
{
  light->SetLightTypeToSceneLight();
  light->SetPositional(false);
  light->SetFocalPoint(0, 0, 0);
  light->SetPosition(-travel[0], -travel[1], -travel[2]);
}

void csmWalk::ShowScene(vtkRenderer* renderer, vtkRenderWindow* window, vtkLight* light,
  const csmScenes::Scene& scene, const int size[2])
{
  window->SetMultiSamples(0);
  window->SetOffScreenRendering(1);
  window->SetSize(size[0], size[1]);
  window->AddRenderer(renderer);
  csmScenes::Install(scene, renderer, double(size[0]) / size[1]);
  renderer->AutomaticLightCreationOff();
  renderer->RemoveAllLights();
  renderer->AddLight(light);
}
