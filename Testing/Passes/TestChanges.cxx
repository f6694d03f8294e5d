// SPDX-License-Identifier: BSD-3-Clause
// Data that changes while the camera stays: a change of what a prop casts draws its light's maps
// again (a mesh's moved points keep its compact blocks); a change of colour, scalars, lookup table
// or material draws no texel, and the frame equals a fresh chain's.
#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCascadedShadowMapBakerPass.h"
#include "vtkCascadedShadowMapPass.h"
#include "vtkCascadedShadowMapPlanner.h"
#include "vtkCellArray.h"
#include "vtkFloatArray.h"
#include "vtkIdList.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkLookupTable.h"
#include "vtkMapper.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"

#include "csmTestHelpers.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace
{
using csmTest::BoxOverPlane;
using csmTest::DifferingValues;

/// Our shadows on a renderer, the cascades alone (these tests are the cascades' behaviour under
/// changes; Pages.* tests the light-space pages').
vtkCascadedShadowMapBakerPass* CascadesOn(vtkRenderer* renderer)
{
  vtkCascadedShadowMapBakerPass* baker =
    vtkCascadedShadowMapPass::UseShadowsOn(renderer)->GetShadowMapBakerPass();
  baker->LightSpacePagesOff();
  return baker;
}

/// The box's polydata with a point scalar array "field" (0 everywhere).
vtkPolyData* AddField(BoxOverPlane& scene)
{
  vtkMapper* mapper = scene.Box->GetMapper();
  mapper->Update();
  vtkPolyData* data = vtkPolyData::SafeDownCast(mapper->GetInputDataObject(0, 0));
  vtkNew<vtkFloatArray> field;
  field->SetName("field");
  field->SetNumberOfTuples(data->GetNumberOfPoints());
  field->Fill(0.0);
  data->GetPointData()->SetScalars(field);
  return data;
}

/// A fresh chain's frame of the same scene and view, planned as the last frame of `last` was (a
/// frame planned for casters that change every frame fits no map to the scene: a fresh chain
/// does the same with SceneFittedCascades off); the fresh chain stays on, its baker in `baker`,
/// after a still frame of its own with its defaults.
vtkSmartPointer<vtkImageData> FreshFrame(BoxOverPlane& scene,
  const vtkCascadedShadowMapBakerPass* last, vtkCascadedShadowMapBakerPass*& baker)
{
  const bool changing = last->GetLastFrameStatistics().CastersChanging;
  vtkCascadedShadowMapPass::UseShadowsOff(scene.Renderer);
  scene.Frame();
  baker = CascadesOn(scene.Renderer);
  baker->GetPlanner()->SetSceneFittedCascades(!changing);
  auto image = scene.Frame();
  baker->GetPlanner()->SceneFittedCascadesOn();
  scene.Frame();
  return image;
}

/// The scene's box replaced by 16 boxes in a 4 x 4 grid, of three heights, under cascades
/// (CascadesOn), and the texels its first frame drew.
struct SixteenParts
{
  BoxOverPlane Scene;
  std::vector<vtkSmartPointer<vtkActor>> Parts;
  vtkCascadedShadowMapBakerPass* Baker = nullptr;
  double FirstTexels = 0.0;

  SixteenParts()
  {
    this->Scene.Renderer->RemoveActor(this->Scene.Box);
    for (int i = 0; i < 16; ++i)
    {
      const double x = -6.0 + 4.0 * (i % 4), z = -6.0 + 4.0 * (i / 4);
      this->Parts.push_back(
        csmTest::BoxActor(x - 0.5, x + 0.5, 1.0, 2.5 + 0.25 * (i % 3), z - 0.5, z + 0.5));
      this->Scene.Renderer->AddActor(this->Parts.back());
    }
    this->Baker = CascadesOn(this->Scene.Renderer);
    this->Scene.Frame();
    this->FirstTexels = this->Baker->GetLastFrameStatistics().TexelsRendered;
  }
};

/// Every point of the data moved to (x + dx, y * yScale, z), the points marked modified.
void MoveEveryPoint(vtkPolyData* data, double dx, double yScale)
{
  for (vtkIdType i = 0; i < data->GetNumberOfPoints(); ++i)
  {
    double p[3];
    data->GetPoint(i, p);
    data->GetPoints()->SetPoint(i, p[0] + dx, p[1] * yScale, p[2]);
  }
  data->GetPoints()->Modified();
}

/// The first polygon replaced in place by the same face from its next corner: other point ids
/// (no count, no array time changed), the same shadow.
void TurnFirstFace(vtkPolyData* data)
{
  vtkNew<vtkIdList> face;
  data->GetPolys()->GetCellAtId(0, face);
  const vtkIdType first = face->GetId(0);
  for (vtkIdType k = 0; k + 1 < face->GetNumberOfIds(); ++k)
  {
    face->SetId(k, face->GetId(k + 1));
  }
  face->SetId(face->GetNumberOfIds() - 1, first);
  data->GetPolys()->ReplaceCellAtId(0, face);
}
} // namespace

// Colours, scalars, lookup tables and material: every map kept, no texel drawn, the frame the
// one a fresh chain draws.
TEST(Changes, ColourScalarsAndMaterialDrawNoTexel)
{
  BoxOverPlane scene;
  vtkPolyData* data = AddField(scene);
  vtkCascadedShadowMapBakerPass* baker = CascadesOn(scene.Renderer);
  scene.Frame();
  ASSERT_GT(baker->GetLastFrameStatistics().CascadesRendered, 0);
  scene.Frame();
  EXPECT_EQ(baker->GetLastFrameStatistics().CascadesRendered, 0); // a still frame draws nothing
  vtkNew<vtkLookupTable> table;
  table->SetHueRange(0.0, 0.66);
  const std::vector<std::pair<std::string, std::function<void()>>> changes = {
    { "colour", [&]() { scene.Box->GetProperty()->SetColor(0.2, 0.8, 0.3); } },
    { "specular", [&]() { scene.Box->GetProperty()->SetSpecular(0.7); } },
    { "ambient and diffuse",
      [&]()
      {
        scene.Ground->GetProperty()->SetAmbient(0.3);
        scene.Ground->GetProperty()->SetDiffuse(0.6);
      } },
    { "scalars shown",
      [&]()
      {
        scene.Box->GetMapper()->ScalarVisibilityOn();
        scene.Box->GetMapper()->SetScalarRange(0.0, 1.0);
      } },
    { "scalars of a new time step",
      [&]()
      {
        vtkFloatArray* field = vtkFloatArray::SafeDownCast(data->GetPointData()->GetScalars());
        for (vtkIdType i = 0; i < field->GetNumberOfTuples(); ++i)
        {
          field->SetValue(i, static_cast<float>(i % 3) / 2.0f);
        }
        field->Modified();
      } },
    { "another field array",
      [&]()
      {
        vtkNew<vtkFloatArray> other;
        other->SetName("other");
        other->SetNumberOfTuples(data->GetNumberOfPoints());
        other->Fill(0.5);
        data->GetPointData()->SetScalars(other);
      } },
    { "lookup table and range",
      [&]()
      {
        scene.Box->GetMapper()->SetLookupTable(table);
        scene.Box->GetMapper()->SetScalarRange(0.0, 0.5);
      } },
  };
  for (const auto& [name, change] : changes)
  {
    change();
    auto changed = scene.Frame();
    const auto& statistics = baker->GetLastFrameStatistics();
    EXPECT_EQ(statistics.CascadesRendered, 0) << name;
    EXPECT_EQ(statistics.TexelsRendered, 0.0) << name;
    EXPECT_GT(statistics.CascadesKept, 0) << name;
    EXPECT_EQ(DifferingValues(FreshFrame(scene, baker, baker), changed), 0) << name;
  }
}

// What a prop casts: its place, its points, its representation, its opacity, its visibility:
// each draws the maps again, and the frame is the one a fresh chain draws.
TEST(Changes, WhatAPropCastsDrawsTheMapsAgain)
{
  BoxOverPlane scene;
  vtkPolyData* data = AddField(scene);
  const std::vector<std::pair<std::string, std::function<void()>>> changes = {
    { "moved", [&]() { scene.Box->SetPosition(0.5, 0.0, 0.0); } },
    { "points",
      [&]()
      {
        double p[3];
        data->GetPoint(0, p);
        data->GetPoints()->SetPoint(0, p[0] - 0.5, p[1], p[2]);
        data->GetPoints()->Modified();
      } },
    { "a cell added in place",
      [&]()
      {
        const vtkIdType corners[3] = { 0, 1, 2 };
        data->GetPolys()->InsertNextCell(3, corners);
        data->Modified();
      } },
    { "wireframe", [&]() { scene.Box->GetProperty()->SetRepresentationToWireframe(); } },
    { "translucent", [&]() { scene.Box->GetProperty()->SetOpacity(0.5); } },
    { "opaque again", [&]() { scene.Box->GetProperty()->SetOpacity(1.0); } },
    { "cells emptied in place",
      [&]()
      {
        data->GetPolys()->Initialize();
        data->Modified();
      } },
    { "hidden", [&]() { scene.Box->VisibilityOff(); } },
  };
  vtkCascadedShadowMapBakerPass* baker = CascadesOn(scene.Renderer);
  scene.Frame();
  scene.Frame();
  for (const auto& [name, change] : changes)
  {
    change();
    auto changed = scene.Frame();
    const auto& statistics = baker->GetLastFrameStatistics();
    EXPECT_GT(statistics.TexelsRendered, 0.0) << name;
    std::printf("%s: maps drawn %d, patched %d, texels %.0f, meshes prepared %d\n", name.c_str(),
      statistics.CascadesRendered, statistics.CascadesPatched, statistics.TexelsRendered,
      statistics.PreparedBlocks);
    // Moved points keep the box's compact blocks (their boxes follow the points); a new cell
    // prepares them anew.
    if (name == "points")
    {
      EXPECT_EQ(statistics.PreparedBlocks, 0);
    }
    if (name == "a cell added in place")
    {
      EXPECT_EQ(statistics.PreparedBlocks, 1);
    }
    EXPECT_EQ(DifferingValues(FreshFrame(scene, baker, baker), changed), 0) << name;
  }
}

// A mesh whose points move step after step keeps its compact blocks, their boxes where the points
// are (the frame a fresh chain draws); a cell replaced in place (no count, no array time changed,
// only the polydata modified) prepares them anew from the new cells and draws the maps again.
TEST(Changes, MovedPointsKeepTheBlocksAndReplacedCellsDoNot)
{
  BoxOverPlane scene;
  vtkPolyData* data = AddField(scene);
  vtkCascadedShadowMapBakerPass* baker = CascadesOn(scene.Renderer);
  scene.Frame();
  EXPECT_EQ(baker->GetLastFrameStatistics().PreparedBlocks, 2); // the box and the ground
  scene.Frame();
  for (int step = 0; step < 3; ++step)
  {
    MoveEveryPoint(data, 0.3, 1.1);
    auto moved = scene.Frame();
    EXPECT_EQ(baker->GetLastFrameStatistics().PreparedBlocks, 0) << step;
    EXPECT_EQ(baker->GetLastFrameStatistics().CompactCasters, 2) << step;
    vtkCascadedShadowMapBakerPass* fresh = nullptr;
    EXPECT_EQ(DifferingValues(FreshFrame(scene, baker, fresh), moved), 0) << step;
    baker = fresh;
  }
  TurnFirstFace(data);
  data->Modified();
  auto replaced = scene.Frame();
  EXPECT_EQ(baker->GetLastFrameStatistics().PreparedBlocks, 1);
  EXPECT_GT(baker->GetLastFrameStatistics().TexelsRendered, 0.0); // the maps drawn again
  vtkCascadedShadowMapBakerPass* fresh = nullptr;
  EXPECT_EQ(DifferingValues(FreshFrame(scene, baker, fresh), replaced), 0);
}

// A new polydata each step (a reader's next time step, set as the mapper's input) of the same
// cells as the last keeps the last one's compact blocks, their boxes where the new points are (the
// frame a fresh chain draws); one of other cells prepares them anew; and a prop still drawing the
// last data keeps blocks of its own.
TEST(Changes, ANewPolyDataOfTheSameCellsKeepsTheBlocks)
{
  BoxOverPlane scene;
  vtkPolyDataMapper* mapper = vtkPolyDataMapper::SafeDownCast(scene.Box->GetMapper());
  ASSERT_NE(mapper, nullptr);
  vtkPolyData* first = AddField(scene);
  vtkCascadedShadowMapBakerPass* baker = CascadesOn(scene.Renderer);
  scene.Frame();
  scene.Frame();
  vtkSmartPointer<vtkPolyData> last = first;
  for (int step = 0; step < 3; ++step)
  {
    auto next = vtkSmartPointer<vtkPolyData>::New();
    next->DeepCopy(last);
    MoveEveryPoint(next, 0.3, 1.1);
    mapper->SetInputData(next);
    last = nullptr; // (the last step's data is gone, as a reader's)
    last = next;
    auto stepped = scene.Frame();
    EXPECT_EQ(baker->GetLastFrameStatistics().PreparedBlocks, 0) << step;
    EXPECT_EQ(baker->GetLastFrameStatistics().CompactCasters, 2) << step;
    EXPECT_GT(baker->GetLastFrameStatistics().TexelsRendered, 0.0) << step;
    vtkCascadedShadowMapBakerPass* fresh = nullptr;
    EXPECT_EQ(DifferingValues(FreshFrame(scene, baker, fresh), stepped), 0) << step;
    baker = fresh;
  }
  // Other cells (a face from its next corner): prepared anew.
  auto turned = vtkSmartPointer<vtkPolyData>::New();
  turned->DeepCopy(last);
  TurnFirstFace(turned);
  mapper->SetInputData(turned);
  scene.Frame();
  EXPECT_EQ(baker->GetLastFrameStatistics().PreparedBlocks, 1);
  // A second box drawing that data while the first takes moved copies: each keeps its shadow.
  vtkNew<vtkPolyDataMapper> secondMapper;
  secondMapper->SetInputData(turned);
  vtkNew<vtkActor> second;
  second->SetMapper(secondMapper);
  second->SetPosition(4.0, 0.0, 0.0);
  scene.Renderer->AddActor(second);
  scene.Frame();
  auto moved = vtkSmartPointer<vtkPolyData>::New();
  moved->DeepCopy(turned);
  MoveEveryPoint(moved, -0.3, 0.9);
  mapper->SetInputData(moved);
  auto both = scene.Frame();
  EXPECT_EQ(baker->GetLastFrameStatistics().PreparedBlocks, 1); // the first box's new data
  vtkCascadedShadowMapBakerPass* fresh = nullptr;
  EXPECT_EQ(DifferingValues(FreshFrame(scene, baker, fresh), both), 0);
}

// A frame like the last one (the same view, nothing changed; a screenshot's second render):
// nothing planned, no texel drawn, the same image; a moved light draws its maps again.
TEST(Changes, AFrameAsTheLastDrawsNothing)
{
  BoxOverPlane scene;
  vtkCascadedShadowMapBakerPass* baker = CascadesOn(scene.Renderer);
  scene.Frame();
  scene.Renderer->GetActiveCamera()->Azimuth(20.0);
  scene.Renderer->ResetCameraClippingRange();
  auto moved = scene.Frame();
  ASSERT_GT(
    baker->GetLastFrameStatistics().CascadesKept + baker->GetLastFrameStatistics().CascadesRendered,
    0);
  const int maps =
    baker->GetLastFrameStatistics().CascadesKept + baker->GetLastFrameStatistics().CascadesRendered;
  auto again = scene.Render(); // a frame and the screenshot's render of it
  EXPECT_EQ(baker->GetLastFrameStatistics().CascadesRendered, 0);
  EXPECT_EQ(baker->GetLastFrameStatistics().TexelsRendered, 0.0);
  EXPECT_EQ(baker->GetLastFrameStatistics().CascadesKept, maps);
  EXPECT_EQ(DifferingValues(moved, again), 0);
  scene.Light->SetPosition(2.0, 10.0, 0.0);
  auto lit = scene.Frame();
  EXPECT_GT(baker->GetLastFrameStatistics().CascadesRendered, 0);
  vtkCascadedShadowMapBakerPass* fresh = nullptr;
  EXPECT_EQ(DifferingValues(FreshFrame(scene, baker, fresh), lit), 0);
}

/// A frame after a change of some parts: the kept map patched with at most a quarter of the first
/// frame's texels, none drawn whole, and the image a fresh chain's (baker: that chain's after).
void ExpectOnlyTheirTexels(SixteenParts& assembly, int step)
{
  const double firstTexels = assembly.FirstTexels;
  auto changed = assembly.Scene.Frame();
  const auto& statistics = assembly.Baker->GetLastFrameStatistics();
  std::printf("step %d: maps drawn %d, patched %d, kept %d, texels %.0f of %.0f\n", step,
    statistics.CascadesRendered, statistics.CascadesPatched, statistics.CascadesKept,
    statistics.TexelsRendered, firstTexels);
  EXPECT_GT(statistics.CascadesPatched, 0) << step;
  EXPECT_EQ(statistics.CascadesRendered, 0) << step;
  EXPECT_GT(statistics.TexelsRendered, 0.0) << step;
  EXPECT_LE(statistics.TexelsRendered, 0.25 * firstTexels) << step;
  EXPECT_EQ(DifferingValues(FreshFrame(assembly.Scene, assembly.Baker, assembly.Baker), changed), 0)
    << step;
}

// An assembly of 16 parts, one of them moved (within the others' extent): the kept map draws
// again only the texels of that part's boxes before and after (at most a quarter of the first
// frame's texels), and the frame is the one a fresh chain draws.
TEST(Changes, OnePartOfSixteenMovedDrawsOnlyItsTexels)
{
  SixteenParts assembly;
  ASSERT_GT(assembly.FirstTexels, 0.0);
  for (int still = 0; still < 3; ++still) // (the second frame too: nothing changed)
  {
    assembly.Scene.Frame();
    EXPECT_EQ(assembly.Baker->GetLastFrameStatistics().TexelsRendered, 0.0) << still;
  }
  for (int step = 0; step < 3; ++step)
  {
    assembly.Parts[5]->SetPosition(0.3 * (step + 1), 0.0, -0.3 * step); // an inner part, not higher
    ExpectOnlyTheirTexels(assembly, step);
  }
}

// Props added and removed (one of sixteen parts taken out and another put in, within the
// others' extent): as a moved part, the kept map draws again only the texels of their boxes (a
// change of the prop list taken for a change of everything would draw every map whole), and the
// frame is the one a fresh chain draws.
TEST(Changes, APartAddedAndOneRemovedDrawOnlyTheirTexels)
{
  SixteenParts assembly;
  BoxOverPlane& scene = assembly.Scene;
  ASSERT_GT(assembly.FirstTexels, 0.0);
  scene.Frame();
  for (int step = 0; step < 3; ++step)
  {
    // An inner part out, a new one in beside where it stood (not higher than the others).
    scene.Renderer->RemoveActor(assembly.Parts[5 + step]);
    auto added = csmTest::BoxActor(-1.8 + 0.2 * step, -1.0 + 0.2 * step, 1.0, 2.5, 0.0, 0.6);
    scene.Renderer->AddActor(added);
    assembly.Parts.push_back(added);
    ExpectOnlyTheirTexels(assembly, step);
    scene.Frame();
  }
}

// A part moved or deformed a little: its boxes before and after overlap on the kept map, which
// draws them as one rectangle, so the casters that reach it are drawn once (drawn a rectangle
// each, a deforming structure cost two caster passes a step); the frame a fresh chain's.
TEST(Changes, APartMovedALittleDrawsItsCastersOnce)
{
  SixteenParts assembly;
  vtkActor* part = assembly.Parts[5];          // an inner part: its shadow reaches no other
  const auto trianglesOf = [](vtkActor* actor) // (the maps draw compact casters' triangles)
  {
    actor->GetMapper()->Update();
    vtkCellArray* polys =
      vtkPolyData::SafeDownCast(actor->GetMapper()->GetInputDataObject(0, 0))->GetPolys();
    return static_cast<double>(polys->GetNumberOfConnectivityIds() - 2 * polys->GetNumberOfCells());
  };
  const double cells = trianglesOf(part) + trianglesOf(assembly.Scene.Ground);
  assembly.Scene.Frame();
  part->SetPosition(0.1, 0.0, 0.05);
  auto moved = assembly.Scene.Frame();
  const auto& statistics = assembly.Baker->GetLastFrameStatistics();
  std::printf("patched %d, drawn %d, texels %.0f, cells %.0f of %.0f\n", statistics.CascadesPatched,
    statistics.CascadesRendered, statistics.TexelsRendered, statistics.CellsDrawn, cells);
  ASSERT_GT(statistics.CascadesPatched, 0);
  EXPECT_EQ(statistics.CascadesRendered, 0);
  EXPECT_GT(statistics.CellsDrawn, 0.0);
  EXPECT_LE(statistics.CellsDrawn, cells * statistics.CascadesPatched);
  EXPECT_EQ(DifferingValues(FreshFrame(assembly.Scene, assembly.Baker, assembly.Baker), moved), 0);
}

// Casters that change every frame (a deforming structure): no scene-fitted map (it would draw its
// whole tile every frame) but maps fitted to the view, sized to what the error target needs, from
// the first changed frame on where its changes would draw the kept scene-fitted map whole (a
// time series stepped one step at a time), else from the second; the frame the one a fresh
// chain draws of that plan.
TEST(Changes, CastersChangingEveryFrameGetMapsFittedToTheView)
{
  BoxOverPlane scene;
  vtkPolyData* data = AddField(scene);
  vtkCascadedShadowMapBakerPass* baker = CascadesOn(scene.Renderer);
  scene.Frame();
  const double firstTexels = baker->GetLastFrameStatistics().TexelsRendered;
  ASSERT_GT(firstTexels, 0.0);
  EXPECT_FALSE(baker->GetPlanner()->GetCastersChanging());
  vtkSmartPointer<vtkImageData> deformed;
  for (int step = 0; step < 4; ++step)
  {
    MoveEveryPoint(data, 0.0, step % 2 ? 1.02 : 0.98);
    deformed = scene.Frame();
    const auto& statistics = baker->GetLastFrameStatistics();
    std::printf("step %d: maps drawn %d, patched %d, texels %.0f of %.0f\n", step,
      statistics.CascadesRendered, statistics.CascadesPatched, statistics.TexelsRendered,
      firstTexels);
    EXPECT_TRUE(baker->GetPlanner()->GetCastersChanging()) << step;
    EXPECT_TRUE(statistics.CastersChanging) << step;
    EXPECT_GT(statistics.TexelsRendered, 0.0) << step;
    EXPECT_LT(statistics.TexelsRendered, 0.5 * firstTexels) << step;
  }
  // A still frame after them keeps the maps; stepped one step at a time (a still frame after
  // each), the steps go on with maps fitted to the view, the frame a fresh chain's.
  for (int step = 0; step < 3; ++step)
  {
    scene.Frame();
    EXPECT_EQ(baker->GetLastFrameStatistics().TexelsRendered, 0.0) << step;
    MoveEveryPoint(data, 0.0, step % 2 ? 1.02 : 0.98);
    deformed = scene.Frame();
    EXPECT_TRUE(baker->GetLastFrameStatistics().CastersChanging) << step;
    EXPECT_LT(baker->GetLastFrameStatistics().TexelsRendered, 0.5 * firstTexels) << step;
  }
  vtkCascadedShadowMapBakerPass* fresh = nullptr;
  EXPECT_EQ(DifferingValues(FreshFrame(scene, baker, fresh), deformed), 0);
  baker = fresh;
  // The next move of the camera alone plans the scene-fitted map again.
  scene.Renderer->GetActiveCamera()->Azimuth(2.0);
  scene.Frame();
  EXPECT_FALSE(baker->GetLastFrameStatistics().CastersChanging);
  EXPECT_FALSE(baker->GetPlanner()->GetCastersChanging());
  EXPECT_TRUE(baker->GetPlanner()->GetCascadeSceneFitted(0));
}
