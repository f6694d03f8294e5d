// SPDX-License-Identifier: BSD-3-Clause
// csm-bench --changes: data that changes while the camera stays, as a time series, a recolouring
// or a moving part does, every step a normal render at the scene's default view: the unshadowed
// frame, VTK's pass as it comes (its default 1024^2 map) and ours at its defaults, interleaved in
// rounds in one process; medians of the step times, the texels ours draws a step, and the
// misclassified pixels of VTK's pass and ours against the ray-cast truth at every step of the
// changes that move geometry.
#include "csmChanges.h"

#include "csmFileChecks.h"
#include "csmScenes.h"
#include "csmTechnique.h"
#include "csmTruth.h"
#include "csmWalk.h"

#include "vtkActor.h"
#include "vtkAppendPolyData.h"
#include "vtkCamera.h"
#include "vtkCascadedShadowMapBakerPass.h"
#include "vtkCascadedShadowMapPass.h"
#include "vtkCubeSource.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkMapper.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderPass.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace
{
struct ChangeOptions
{
  std::vector<std::string> Scenes = { "columns", "platform", "towers", "engine" };
  int Steps = 8;
  int Rounds = 2;
  int Size[2] = { 640, 480 };
  bool Accuracy = true;
  bool StepByStep = false; ///< an untimed still frame after each step (a user stepping a series)
  std::string Out = "changes.csv";
};

[[noreturn]] void changesFail(const std::string& message)
{
  std::fprintf(stderr, "csm-bench --changes: error: %s (see --help)\n", message.c_str());
  std::exit(2);
}

/// What changes a step. Geometry: a part moved, every point moved (a deforming structure), a
/// new polydata for every actor (a reader's time step); the others change no caster.
enum class Change
{
  Nothing,
  Colour,
  Scalars,
  PartMoved,
  Deforming,
  NewDataset
};
const Change kChanges[] = { Change::Nothing, Change::Colour, Change::Scalars, Change::PartMoved,
  Change::Deforming, Change::NewDataset };

const char* nameOf(Change c)
{
  switch (c)
  {
    case Change::Nothing:
      return "nothing";
    case Change::Colour:
      return "colour";
    case Change::Scalars:
      return "scalars";
    case Change::PartMoved:
      return "part moved";
    case Change::Deforming:
      return "deforming";
    case Change::NewDataset:
      return "new dataset";
  }
  return "?";
}

bool movesGeometry(Change c)
{
  return c == Change::PartMoved || c == Change::Deforming || c == Change::NewDataset;
}

/// The scene's actors with the data each step changes: each actor draws a polydata of its own
/// (Current, a copy of the scene's), coloured by a point field in [0, 1].
struct ChangingScene
{
  csmScenes::Scene Scene;
  std::vector<vtkSmartPointer<vtkPolyData>> Current;  ///< per actor (null: not a polydata)
  std::vector<vtkSmartPointer<vtkPolyData>> Original; ///< Current as it was first
  int Part = -1;     ///< the actor a "part moved" step moves (-1: fewer than three parts)
  int Up = 1;        ///< the axis the structure stretches along (the view-up's largest)
  double Centre = 0; ///< along Up
  double Step = 0;   ///< how far a part moves: 0.2 % of the scene's diagonal
};

void setField(vtkPolyData* data, int step)
{
  vtkNew<vtkFloatArray> field;
  field->SetName("field");
  field->SetNumberOfTuples(data->GetNumberOfPoints());
  for (vtkIdType i = 0; i < data->GetNumberOfPoints(); ++i)
  {
    double p[3];
    data->GetPoint(i, p);
    field->SetValue(
      i, static_cast<float>(0.5 + 0.5 * std::sin(0.37 * (p[0] + p[1] + p[2]) + step)));
  }
  data->GetPointData()->SetScalars(field);
}

ChangingScene prepare(const csmScenes::Scene& scene)
{
  ChangingScene s;
  s.Scene = scene;
  const double* b = scene.Bounds;
  s.Step = 0.002 *
    std::sqrt(std::pow(b[1] - b[0], 2) + std::pow(b[3] - b[2], 2) + std::pow(b[5] - b[4], 2));
  for (int axis = 0; axis < 3; ++axis)
    if (std::abs(scene.ViewUp[axis]) > std::abs(scene.ViewUp[s.Up]))
      s.Up = axis;
  s.Centre = 0.5 * (b[2 * s.Up] + b[2 * s.Up + 1]);
  std::vector<int> parts;
  for (const auto& actor : scene.Actors)
  {
    vtkMapper* mapper = actor->GetMapper();
    vtkPolyData* input =
      mapper ? vtkPolyData::SafeDownCast(mapper->GetInputDataObject(0, 0)) : nullptr;
    if (!input)
    {
      s.Current.emplace_back();
      s.Original.emplace_back();
      continue;
    }
    parts.push_back(static_cast<int>(s.Current.size()));
    auto current = vtkSmartPointer<vtkPolyData>::New();
    current->DeepCopy(input);
    setField(current, 0);
    auto original = vtkSmartPointer<vtkPolyData>::New();
    original->DeepCopy(current);
    mapper->SetInputDataObject(current);
    mapper->ScalarVisibilityOn();
    mapper->SetScalarRange(0.0, 1.0);
    s.Current.push_back(current);
    s.Original.push_back(original);
  }
  // The part: of the actors with data, the one in the middle of the list (not the ground,
  // which scenes add first or last).
  if (parts.size() >= 3)
    s.Part = parts[parts.size() / 2];
  return s;
}

/// The deformed points of a step: the structure stretched along Up about its centre by a share
/// that changes every step (a structure swaying under load).
void deform(vtkPoints* points, vtkPoints* original, const ChangingScene& s, int step)
{
  const double stretch = 1.0 + 0.02 * std::sin(0.9 * (step + 1));
  for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i)
  {
    double p[3];
    original->GetPoint(i, p);
    p[s.Up] = s.Centre + stretch * (p[s.Up] - s.Centre);
    points->SetPoint(i, p);
  }
  points->Modified();
}

/// The change of one step (before the render that is timed).
void apply(ChangingScene& s, Change c, int step)
{
  for (size_t a = 0; a < s.Current.size(); ++a)
  {
    vtkActor* actor = s.Scene.Actors[a];
    vtkPolyData* data = s.Current[a];
    if (!data)
      continue;
    if (c == Change::Colour)
      actor->GetProperty()->SetColor(
        0.5 + 0.5 * std::sin(double(step + a)), 0.6, 0.5 + 0.5 * std::cos(double(step)));
    else if (c == Change::Scalars)
      setField(data, step + 1);
    else if (c == Change::PartMoved && static_cast<int>(a) == s.Part)
      actor->SetPosition(s.Step * (step % 2), 0.0, s.Step * (step % 3));
    else if (c == Change::Deforming)
      deform(data->GetPoints(), s.Original[a]->GetPoints(), s, step);
    else if (c == Change::NewDataset)
    {
      auto next = vtkSmartPointer<vtkPolyData>::New();
      next->DeepCopy(s.Original[a]);
      deform(next->GetPoints(), s.Original[a]->GetPoints(), s, step);
      setField(next, step + 1);
      actor->GetMapper()->SetInputDataObject(next);
    }
  }
}

/// Undoes what a change's steps did (its actors' data objects kept where it changed none).
void restore(ChangingScene& s, Change c)
{
  for (size_t a = 0; a < s.Current.size(); ++a)
  {
    if (!s.Current[a])
      continue;
    if (c == Change::Scalars)
      setField(s.Current[a], 0);
    else if (c == Change::PartMoved)
      s.Scene.Actors[a]->SetPosition(0, 0, 0);
    else if (c == Change::Deforming)
      deform(s.Current[a]->GetPoints(), s.Original[a]->GetPoints(), s, -1);
    else if (c == Change::NewDataset)
      s.Scene.Actors[a]->GetMapper()->SetInputDataObject(s.Current[a]);
  }
}

struct Timed
{
  std::vector<double> Ms;
  double Texels = 0.0;
  double FirstTexels = 0.0; ///< the first frame's (every map drawn)
  long long Steps = 0;
};

/// One technique through the steps of one change: two renders first (not timed), then each
/// step's change and its timed render.
void timeSteps(ChangingScene& s, Change c, vtkRenderer* renderer, vtkRenderWindow* window,
  const csmScenes::ShadowOptions& options, int steps, bool stepByStep, Timed& t)
{
  const csmScenes::Installed passes = csmScenes::InstallTechnique(renderer, options);
  vtkCascadedShadowMapBakerPass* baker =
    passes.Cascaded ? passes.Cascaded->GetShadowMapBakerPass() : nullptr;
  window->Render();
  if (baker)
    t.FirstTexels = baker->GetLastFrameStatistics().TexelsRendered;
  window->Render();
  for (int step = 0; step < steps; ++step)
  {
    apply(s, c, step);
    const auto start = std::chrono::steady_clock::now();
    window->Render();
    window->WaitForCompletion();
    t.Ms.push_back(
      1000.0 * std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    ++t.Steps;
    if (baker)
      t.Texels += baker->GetLastFrameStatistics().TexelsRendered;
    if (stepByStep)
      window->Render(); // (the user looks at the step: a still frame, not timed)
  }
  restore(s, c);
  if (vtkRenderPass* chain = renderer->GetPass())
    chain->ReleaseGraphicsResources(window);
  renderer->SetPass(nullptr);
}

/// Misclassified pixels (%) of VTK's pass and ours over the steps of a change that moves
/// geometry, against the truth cast anew at each step (white diffuse materials, no field).
std::vector<double> measureAccuracy(ChangingScene& s, Change c, vtkRenderer* renderer,
  vtkRenderWindow* window, const double travel[3], int steps, int width, int height)
{
  std::vector<csmScenes::ShadowOptions> measured(2);
  measured[0].Technique = "vtk";
  measured[0].Resolution = 1024;
  std::vector<vtkSmartPointer<vtkRenderPass>> chains;
  for (const auto& options : measured)
  {
    csmScenes::Installed installed;
    chains.push_back(csmScenes::BuildChain(options, installed));
  }
  std::vector<csmTruth::Classification> errors(chains.size());
  for (int step = -1; step < steps; ++step)
  {
    if (step >= 0)
      apply(s, c, step);
    csmTruth::RayScene rays;
    rays.Build(renderer, height);
    renderer->SetPass(nullptr);
    window->Render();
    auto plain = csmWalk::GrabFrame(window);
    const csmWalk::FrameTruth truth =
      csmWalk::CastTruth(rays, renderer->GetActiveCamera(), width, height, travel);
    for (size_t t = 0; t < chains.size(); ++t)
    {
      renderer->SetPass(chains[t]);
      window->Render();
      if (step < 0)
        continue; // the first frame, as in the timed steps
      errors[t].Add(csmWalk::ClassifyFrame(window, plain, truth));
    }
  }
  restore(s, c);
  for (auto& chain : chains)
    chain->ReleaseGraphicsResources(window);
  renderer->SetPass(nullptr);
  std::vector<double> pct;
  for (const auto& e : errors)
    pct.push_back(e.MismatchPct());
  return pct;
}

ChangeOptions parseChanges(int argc, char** argv)
{
  ChangeOptions o;
  for (int i = 1; i < argc; ++i)
  {
    const std::string f = argv[i];
    const bool hasValue = i + 1 < argc;
    if (f == "--changes")
      continue;
    else if (f == "--help" || f == "-h")
    {
      std::printf("%s", csmChanges::Usage().c_str());
      std::exit(0);
    }
    else if (f == "--no-accuracy")
      o.Accuracy = false;
    else if (f == "--step-by-step")
      o.StepByStep = true;
    else if ((f == "--scenes" || f == "--steps" || f == "--rounds" || f == "--out" ||
               f == "--size") &&
      !hasValue)
      changesFail(f + " needs a value");
    else if (f == "--scenes")
    {
      o.Scenes.clear();
      std::stringstream list(argv[++i]);
      std::string name;
      while (std::getline(list, name, ','))
      {
        if (name != "engine" && name != "towers" && name != "platform" && name != "columns")
          changesFail("unknown scene '" + name + "' (columns, platform, towers, engine)");
        o.Scenes.push_back(name);
      }
    }
    else if (f == "--steps" || f == "--rounds")
    {
      const int value = std::atoi(argv[++i]);
      if (value < (f == "--steps" ? 2 : 1) || value > 100)
        changesFail(f + (f == "--steps" ? " must be in [2, 100]" : " must be in [1, 100]"));
      (f == "--steps" ? o.Steps : o.Rounds) = value;
    }
    else if (f == "--size")
    {
      if (std::sscanf(argv[++i], "%dx%d", &o.Size[0], &o.Size[1]) != 2 || o.Size[0] < 64 ||
        o.Size[1] < 64 || o.Size[0] > 4096 || o.Size[1] > 4096)
        changesFail("--size needs WxH, 64..4096 each");
    }
    else if (f == "--out")
      o.Out = argv[++i];
    else
      changesFail("unknown option '" + f + "' for --changes");
  }
  const std::string error = csmScenes::CheckOutputFile(o.Out);
  if (!error.empty())
    changesFail("--out: " + error);
  return o;
}

/// 1,600 thin columns in 16 actors of 10 x 10 over a ground (the scene of
/// scripts/bench-changes.py): an assembly of many parts, one of which a "part moved" step moves.
csmScenes::Scene Columns()
{
  csmScenes::Scene scene;
  scene.Name = "columns";
  auto add = [&scene](vtkPolyData* data)
  {
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputData(data);
    auto actor = vtkSmartPointer<vtkActor>::New();
    actor->SetMapper(mapper);
    scene.Actors.push_back(actor);
    scene.Triangles += csmScenes::CountTriangles(data);
  };
  for (int part = 0; part < 16; ++part)
  {
    vtkNew<vtkAppendPolyData> append;
    for (int i = 0; i < 10; ++i)
    {
      for (int j = 0; j < 10; ++j)
      {
        const double x = (part % 4) * 10 + i, z = (part / 4) * 10 + j;
        vtkNew<vtkCubeSource> column;
        column->SetBounds(
          x, x + 0.15, 0, 3 + (static_cast<int>(x) * 7 + static_cast<int>(z) * 3) % 5, z, z + 0.15);
        column->Update();
        append->AddInputData(column->GetOutput());
      }
    }
    append->Update();
    add(append->GetOutput());
  }
  vtkNew<vtkCubeSource> ground;
  ground->SetBounds(-2, 42, -0.05, 0, -2, 42);
  ground->Update();
  add(ground->GetOutput());
  const double bounds[6] = { -2, 42, -0.05, 7, -2, 42 };
  std::copy(bounds, bounds + 6, scene.Bounds);
  const double eye[3] = { 20, 30, -15 }, focal[3] = { 20, 0, 20 };
  std::copy(eye, eye + 3, scene.CameraPosition);
  std::copy(focal, focal + 3, scene.FocalPoint);
  return scene;
}

bool loadScene(const std::string& name, const std::string& engineModel, csmScenes::Scene& scene)
{
  if (name == "towers")
    scene = csmScenes::Towers();
  else if (name == "columns")
    scene = Columns();
  else if (name == "platform")
    scene = csmScenes::Platform(250000);
  else
  {
    std::string error;
    if (!csmScenes::FromFile(engineModel, scene, error))
    {
      std::fprintf(stderr, "csm-bench --changes: skipping scene engine: %s\n", error.c_str());
      return false;
    }
  }
  return true;
}

/// Each change's steps timed for the three techniques in rounds; returns the timings by change.
std::vector<std::vector<Timed>> timeChanges(ChangingScene& s, vtkRenderer* renderer,
  vtkRenderWindow* window, const std::vector<csmScenes::ShadowOptions>& techniques,
  const ChangeOptions& o)
{
  std::vector<std::vector<Timed>> timed;
  for (const Change c : kChanges)
  {
    timed.emplace_back(techniques.size());
    if (c == Change::PartMoved && s.Part < 0)
      continue;
    for (int round = 0; round < o.Rounds; ++round)
      for (size_t t = 0; t < techniques.size(); ++t)
        timeSteps(s, c, renderer, window, techniques[t], o.Steps, o.StepByStep, timed.back()[t]);
  }
  return timed;
}

/// The rows of one scene: each change timed, then (for the changes that move geometry, with
/// white diffuse materials and no field) VTK's pass's and ours' misclassified pixels.
void runScene(const std::string& name, ChangingScene& s, const ChangeOptions& o, std::ofstream& csv)
{
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkRenderWindow> window;
  vtkNew<vtkLight> light; // the walk's scene light
  csmWalk::ShowScene(renderer, window, light, s.Scene, o.Size);
  const double* travel = csmWalk::kSceneLightTravel;
  csmWalk::SetSceneLight(light, travel);
  std::printf("scene %s: %lld triangles, %zu actors%s\n", name.c_str(), s.Scene.Triangles,
    s.Scene.Actors.size(), s.Part < 0 ? " (too few parts to move one)" : "");
  std::vector<csmScenes::ShadowOptions> techniques(3);
  techniques[0].Technique = "none";
  techniques[1].Technique = "vtk";
  techniques[1].Resolution = 1024; // vtkShadowMapBakerPass's own default
  const char* labels[3] = { "none", "vtk default", "default" };
  const std::vector<std::vector<Timed>> timed = timeChanges(s, renderer, window, techniques, o);
  for (size_t a = 0; a < s.Current.size() && o.Accuracy; ++a)
  {
    vtkActor* actor = s.Scene.Actors[a];
    actor->GetMapper()->ScalarVisibilityOff();
    actor->GetProperty()->SetColor(1, 1, 1);
    actor->GetProperty()->SetAmbient(0.0);
    actor->GetProperty()->SetDiffuse(1.0);
    actor->GetProperty()->SetSpecular(0.0);
  }
  renderer->SetBackground(0, 0, 0);
  for (size_t k = 0; k < timed.size(); ++k)
  {
    const Change c = kChanges[k];
    if (timed[k][0].Ms.empty())
      continue;
    std::vector<double> accuracy(techniques.size(), NAN);
    if (o.Accuracy && movesGeometry(c))
    {
      const std::vector<double> e =
        measureAccuracy(s, c, renderer, window, travel, o.Steps, o.Size[0], o.Size[1]);
      accuracy[1] = e[0];
      accuracy[2] = e[1];
    }
    const double none = csmWalk::Median(timed[k][0].Ms), vtk = csmWalk::Median(timed[k][1].Ms);
    for (size_t t = 0; t < techniques.size(); ++t)
    {
      const double ms = csmWalk::Median(timed[k][t].Ms);
      const double texels = timed[k][t].Texels / std::max<long long>(timed[k][t].Steps, 1);
      std::printf("  %-8s %-11s %-12s %7.1f ms  %5.2fx vtk default  %5.2fx unshadowed",
        name.c_str(), nameOf(c), labels[t], ms, ms / vtk, ms / none);
      if (t == 2)
        std::printf("  %.2f M texels a step (first frame %.2f M)", 1e-6 * texels,
          1e-6 * timed[k][t].FirstTexels);
      if (!std::isnan(accuracy[t]))
        std::printf("  %.3f %% misclassified", accuracy[t]);
      std::printf("\n");
      csv << name << "," << nameOf(c) << "," << labels[t] << "," << ms << "," << timed[k][t].Steps
          << ",";
      if (t == 2) // (whole texels: the mean a step rounded)
        csv << std::llround(texels) << "," << std::llround(timed[k][t].FirstTexels);
      else
        csv << "nan,nan";
      csv << "," << accuracy[t] << "\n";
    }
    std::fflush(stdout);
  }
}
} // namespace

std::string csmChanges::Usage()
{
  const ChangeOptions o;
  char text[1400];
  std::snprintf(text, sizeof(text),
    "csm-bench --changes [--scenes a,b,...] [--steps N] [--rounds N] [--size WxH]\n"
    "                    [--out FILE.csv] [--no-accuracy] [--step-by-step]\n"
    "Data that changes while the camera stays at the scene's default view, each actor coloured\n"
    "by a point field: nothing, a new colour on every actor, new scalars on every actor, one\n"
    "part moved, every point moved (a deforming structure), a new polydata for every actor (a\n"
    "reader's time step). Each step a normal render: VTK's pass as it comes, ours and the\n"
    "unshadowed frame side by side, the texels ours draws a step, and for the changes that\n"
    "move geometry the misclassified pixels of VTK's pass and ours against the ray-cast truth\n"
    "(Embree, cast anew each step; white diffuse materials, no field).\n"
    "  --scenes      columns (1,600 thin columns in 16 actors over a ground), platform,\n"
    "                towers, engine [columns,platform,towers,engine]\n"
    "  --steps N     steps a change, 2..100 [%d]\n"
    "  --rounds N    rounds of every change, 1..100 [%d]\n"
    "  --size WxH    the window, 64..4096 each [%dx%d]\n"
    "  --out FILE    the CSV written [%s]\n"
    "  --no-accuracy without the misclassified pixels\n"
    "  --step-by-step a still frame (not timed) after every step, as a user who steps a\n"
    "                time series and looks at each step\n",
    o.Steps, o.Rounds, o.Size[0], o.Size[1], o.Out.c_str());
  return text;
}

int csmChanges::Run(int argc, char** argv, const std::string& engineModel)
{
  const ChangeOptions o = parseChanges(argc, argv);
  std::ofstream csv(o.Out);
  if (!csv)
    changesFail("cannot write '" + o.Out + "'");
  csv
    << "scene,change,label,median_ms,steps,texels_per_step,first_frame_texels,misclassified_pct\n";
  std::printf("changes: %dx%d, %d steps a change, %d rounds; scene light\n", o.Size[0], o.Size[1],
    o.Steps, o.Rounds);
  for (const std::string& name : o.Scenes)
  {
    csmScenes::Scene scene;
    if (!loadScene(name, engineModel, scene))
      continue;
    ChangingScene s = prepare(scene);
    runScene(name, s, o, csv);
  }
  return 0;
}
