// SPDX-License-Identifier: BSD-3-Clause
#include "csmScenes.h"
#include "csmFileChecks.h"
#include "csmSolidBuilder.h"

#include "vtkActor.h"
#include "vtkAppendPolyData.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkCompositeDataGeometryFilter.h"
#include "vtkDataSetSurfaceFilter.h"
#include "vtkGLTFReader.h"
#include "vtkGenericDataObjectReader.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkOBJReader.h"
#include "vtkPLYReader.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataAlgorithm.h"
#include "vtkPolyDataMapper.h"
#include "vtkPolyDataNormals.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkSTLReader.h"
#include "vtkTriangleFilter.h"
#include "vtkXMLPolyDataReader.h"
#include "vtkXMLPolyDataWriter.h"
#include "vtksys/SystemTools.hxx"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <map>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

namespace csmScenes
{
namespace
{
using Vec = std::array<double, 3>;

Vec operator+(const Vec& a, const Vec& b)
{
  return { a[0] + b[0], a[1] + b[1], a[2] + b[2] };
}
Vec operator-(const Vec& a, const Vec& b)
{
  return { a[0] - b[0], a[1] - b[1], a[2] - b[2] };
}
Vec operator*(double s, const Vec& a)
{
  return { s * a[0], s * a[1], s * a[2] };
}

struct Bar
{
  Vec a, b;
  double radius;
};

/// Bars (closed prisms with `sides` facets and two end caps) and boxes, written straight into a
/// polydata.
class Builder
{
public:
  explicit Builder(double offset = 0.0)
    : Offset(offset)
  {
    this->Points->SetDataTypeToDouble();
  }

  void AddBar(const Bar& bar, int sides)
  {
    Vec axis = bar.b - bar.a;
    double length = vtkMath::Norm(axis.data());
    if (length <= 0.0)
      return;
    Vec u, v;
    vtkMath::Perpendiculars(axis.data(), u.data(), v.data(), 0.0);
    const vtkIdType base = this->Points->GetNumberOfPoints();
    for (int i = 0; i < sides; ++i)
    {
      const double angle = 2.0 * vtkMath::Pi() * i / sides;
      const Vec offset = (bar.radius * std::cos(angle)) * u + (bar.radius * std::sin(angle)) * v;
      this->Points->InsertNextPoint((bar.a + offset).data());
      this->Points->InsertNextPoint((bar.b + offset).data());
    }
    for (int i = 0; i < sides; ++i)
    {
      const vtkIdType j = (i + 1) % sides;
      const vtkIdType a0 = base + 2 * i, a1 = base + 2 * i + 1, b0 = base + 2 * j,
                      b1 = base + 2 * j + 1;
      const vtkIdType t1[3] = { a0, b0, b1 };
      const vtkIdType t2[3] = { a0, b1, a1 };
      this->Polys->InsertNextCell(3, t1);
      this->Polys->InsertNextCell(3, t2);
    }
    // The end caps, with points of their own (flat normals): a bar is a closed solid, as CAD
    // exports beams, so its shadow maps may hold only its faces turned away from the light.
    std::vector<vtkIdType> capA(static_cast<size_t>(sides)), capB(static_cast<size_t>(sides));
    for (int i = 0; i < sides; ++i)
    {
      double p[3];
      this->Points->GetPoint(base + 2 * i, p);
      capA[static_cast<size_t>(sides - 1 - i)] = this->Points->InsertNextPoint(p);
      this->Points->GetPoint(base + 2 * i + 1, p);
      capB[static_cast<size_t>(i)] = this->Points->InsertNextPoint(p);
    }
    this->Polys->InsertNextCell(sides, capA.data());
    this->Polys->InsertNextCell(sides, capB.data());
  }

  void AddBox(const Vec& lo, const Vec& hi)
  {
    static const int faces[6][4] = { { 0, 2, 3, 1 }, { 4, 5, 7, 6 }, { 0, 1, 5, 4 }, { 2, 6, 7, 3 },
      { 0, 4, 6, 2 }, { 1, 3, 7, 5 } };
    const vtkIdType base = this->Points->GetNumberOfPoints();
    for (int i = 0; i < 8; ++i)
    {
      this->Points->InsertNextPoint(
        (i & 1) ? hi[0] : lo[0], (i & 2) ? hi[1] : lo[1], (i & 4) ? hi[2] : lo[2]);
    }
    // Each face gets its own points so that normals stay flat.
    vtkIdType corners[8];
    for (int i = 0; i < 8; ++i)
      corners[i] = base + i;
    for (const auto& f : faces)
    {
      const vtkIdType t1[3] = { corners[f[0]], corners[f[1]], corners[f[2]] };
      const vtkIdType t2[3] = { corners[f[0]], corners[f[2]], corners[f[3]] };
      this->Polys->InsertNextCell(3, t1);
      this->Polys->InsertNextCell(3, t2);
    }
  }

  vtkSmartPointer<vtkPolyData> Finish(bool splitNormals)
  {
    if (this->Offset != 0.0)
    {
      for (vtkIdType i = 0; i < this->Points->GetNumberOfPoints(); ++i)
      {
        double p[3];
        this->Points->GetPoint(i, p);
        this->Points->SetPoint(i, p[0] + this->Offset, p[1], p[2] + this->Offset);
      }
    }
    vtkNew<vtkPolyData> data;
    data->SetPoints(this->Points);
    data->SetPolys(this->Polys);
    vtkNew<vtkPolyDataNormals> normals;
    normals->SetInputData(data);
    normals->SetSplitting(splitNormals);
    normals->SetFeatureAngle(60.0);
    normals->ConsistencyOff();
    normals->AutoOrientNormalsOff();
    normals->Update();
    return normals->GetOutput();
  }

private:
  double Offset = 0.0;
  vtkNew<vtkPoints> Points;
  vtkNew<vtkCellArray> Polys;
};

void Lattice(std::vector<Bar>& bars, const Vec& a, const Vec& b, const Vec& c, const Vec& d,
  int panels, double radius)
{
  // A flat lattice panel a-b (bottom) to d-c (top), X-braced in `panels` bays.
  for (int i = 0; i <= panels; ++i)
  {
    const double t = double(i) / panels;
    const Vec p = a + t * (d - a), q = b + t * (c - b);
    bars.push_back({ p, q, radius });
    if (i < panels)
    {
      const double t2 = double(i + 1) / panels;
      const Vec p2 = a + t2 * (d - a), q2 = b + t2 * (c - b);
      bars.push_back({ p, q2, radius });
      bars.push_back({ q, p2, radius });
    }
  }
  bars.push_back({ a, d, radius * 1.5 });
  bars.push_back({ b, c, radius * 1.5 });
}

void Tower(std::vector<Bar>& bars, const Vec& base, double width, double top, double height,
  int panels, double radius)
{
  const double hw = 0.5 * width, ht = 0.5 * top;
  const Vec b[4] = { base + Vec{ -hw, 0, -hw }, base + Vec{ hw, 0, -hw }, base + Vec{ hw, 0, hw },
    base + Vec{ -hw, 0, hw } };
  const Vec t[4] = { base + Vec{ -ht, height, -ht }, base + Vec{ ht, height, -ht },
    base + Vec{ ht, height, ht }, base + Vec{ -ht, height, ht } };
  for (int i = 0; i < 4; ++i)
  {
    const int j = (i + 1) % 4;
    Lattice(bars, b[i], b[j], t[j], t[i], panels, radius);
  }
}

vtkSmartPointer<vtkActor> MakeActor(
  vtkPolyData* data, double r, double g, double b, double specular = 0.3)
{
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(data);
  mapper->ScalarVisibilityOff();
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(r, g, b);
  actor->GetProperty()->SetSpecular(specular);
  actor->GetProperty()->SetSpecularPower(30.0);
  return actor;
}

vtkSmartPointer<vtkPolyData> Ground(
  double x0, double x1, double z0, double z1, double y, double offset = 0.0, double thickness = 0.5)
{
  Builder builder(offset);
  builder.AddBox({ x0, y - thickness, z0 }, { x1, y, z1 });
  return builder.Finish(true);
}

void Finish(Scene& scene)
{
  double b[6] = { VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX, VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX, VTK_DOUBLE_MAX,
    -VTK_DOUBLE_MAX };
  scene.Triangles = 0;
  scene.Lines = 0;
  for (const auto& actor : scene.Actors)
  {
    const double* a = actor->GetBounds();
    for (int i = 0; i < 3; ++i)
    {
      b[2 * i] = std::min(b[2 * i], a[2 * i]);
      b[2 * i + 1] = std::max(b[2 * i + 1], a[2 * i + 1]);
    }
    auto* data = vtkPolyData::SafeDownCast(actor->GetMapper()->GetInputDataObject(0, 0));
    scene.Triangles += CountTriangles(data);
    scene.Lines += data ? data->GetNumberOfLines() : 0;
  }
  std::copy(b, b + 6, scene.Bounds);
}
} // namespace

long long CountTriangles(vtkPolyData* data)
{
  if (!data)
    return 0;
  long long count = 0;
  vtkCellArray* polys = data->GetPolys();
  vtkIdType n;
  const vtkIdType* ids;
  for (polys->InitTraversal(); polys->GetNextCell(n, ids);)
    count += std::max<vtkIdType>(0, n - 2);
  vtkCellArray* strips = data->GetStrips();
  for (strips->InitTraversal(); strips->GetNextCell(n, ids);)
    count += std::max<vtkIdType>(0, n - 2);
  return count;
}

namespace
{
constexpr int kMaxBarSides = 4096;                  // the finest tessellation of a bar
constexpr long long kPlatformBoxTriangles = 5 * 12; // the sea and four deck boxes
constexpr double deck1 = 28.0, deck2 = 38.0;        // heights of the platform's decks

/// The platform's bars: heavy (legs, main braces, deck columns) and thin (handrails, lattices,
/// gratings).
void PlatformBars(std::vector<Bar>& heavy, std::vector<Bar>& thin)
{
  // Jacket: four battered legs from the sea bed to the lower deck.
  const double legBase = 14.0, legTop = 10.0;
  Vec legB[4], legT[4];
  for (int i = 0; i < 4; ++i)
  {
    const double sx = (i == 0 || i == 3) ? -1 : 1, sz = (i < 2) ? -1 : 1;
    legB[i] = { sx * legBase, -2.0, sz * legBase };
    legT[i] = { sx * legTop, deck1, sz * legTop };
    heavy.push_back({ legB[i], legT[i], 0.9 });
  }
  const int levels = 4;
  for (int i = 0; i < 4; ++i)
  {
    const int j = (i + 1) % 4;
    for (int l = 0; l < levels; ++l)
    {
      const double t0 = double(l) / levels, t1 = double(l + 1) / levels;
      const Vec a0 = legB[i] + t0 * (legT[i] - legB[i]), b0 = legB[j] + t0 * (legT[j] - legB[j]);
      const Vec a1 = legB[i] + t1 * (legT[i] - legB[i]), b1 = legB[j] + t1 * (legT[j] - legB[j]);
      heavy.push_back({ a0, b0, 0.4 });
      heavy.push_back({ a0, b1, 0.3 });
      heavy.push_back({ b0, a1, 0.3 });
    }
  }
  // Deck columns between the two decks.
  for (double x = -15.0; x <= 15.0; x += 7.5)
    for (double z = -15.0; z <= 15.0; z += 7.5)
      heavy.push_back({ { x, deck1 + 1.5, z }, { x, deck2, z }, 0.35 });
  // Handrails around both decks: posts every 1.5 m, top and knee rails.
  auto handrail = [&](double half, double y)
  {
    for (int side = 0; side < 4; ++side)
    {
      for (double s = -half; s < half; s += 1.5)
      {
        const double s2 = std::min(half, s + 1.5);
        auto at = [&](double t, double h) -> Vec
        {
          switch (side)
          {
            case 0:
              return { t, y + h, -half };
            case 1:
              return { half, y + h, t };
            case 2:
              return { -t, y + h, half };
            default:
              return { -half, y + h, -t };
          }
        };
        thin.push_back({ at(s, 0.0), at(s, 1.1), 0.03 });
        thin.push_back({ at(s, 1.1), at(s2, 1.1), 0.03 });
        thin.push_back({ at(s, 0.55), at(s2, 0.55), 0.02 });
      }
    }
  };
  handrail(20.0, deck1 + 1.5);
  handrail(18.0, deck2 + 1.0);
  // Gratings: a walkway grid on a cantilevered deck extension (open lattice floor).
  for (double x = -20.0; x <= -10.0; x += 0.4)
    thin.push_back({ { x, deck1 + 1.5, 20.0 }, { x, deck1 + 1.5, 32.0 }, 0.025 });
  for (double z = 20.0; z <= 32.0; z += 0.4)
    thin.push_back({ { -20.0, deck1 + 1.45, z }, { -10.0, deck1 + 1.45, z }, 0.025 });
  // Lattice derrick on the upper deck.
  Tower(thin, { 6.0, deck2 + 1.0, 4.0 }, 9.0, 2.5, 42.0, 14, 0.12);
  // Crane: pedestal and a lattice boom reaching out over the sea.
  heavy.push_back({ { -14.0, deck2 + 1.0, -14.0 }, { -14.0, deck2 + 9.0, -14.0 }, 1.0 });
  {
    const Vec root{ -14.0, deck2 + 9.0, -14.0 }, tip{ -48.0, deck2 + 30.0, -30.0 };
    const Vec side{ 0.0, 0.0, 1.2 }, up{ 0.0, 1.2, 0.0 };
    Lattice(thin, root - side, root + side, tip + side, tip - side, 16, 0.08);
    Lattice(thin, root - side + up, root + side + up, tip + side + up, tip - side + up, 16, 0.08);
    Lattice(thin, root - side, root - side + up, tip - side + up, tip - side, 16, 0.06);
  }
  // Flare boom: a long triangular lattice at 30 degrees.
  {
    const Vec root{ 20.0, deck1 + 2.0, -6.0 }, tip{ 62.0, deck1 + 26.0, -6.0 };
    const Vec side{ 0.0, 0.0, 1.0 }, up{ 0.0, 1.5, 0.0 };
    Lattice(thin, root - side, root + side, tip + side, tip - side, 20, 0.07);
    Lattice(thin, root - side, root + up, tip + up, tip - side, 20, 0.07);
    Lattice(thin, root + side, root + up, tip + up, tip + side, 20, 0.07);
  }
  // Pipe racks on the lower deck: rows of lattice frames.
  for (int r = 0; r < 4; ++r)
  {
    const double z = -12.0 + 7.0 * r;
    Lattice(thin, { -16.0, deck1 + 1.5, z }, { 14.0, deck1 + 1.5, z }, { 14.0, deck1 + 5.5, z },
      { -16.0, deck1 + 5.5, z }, 12, 0.1);
    for (double y = deck1 + 2.5; y <= deck1 + 5.0; y += 1.2)
      thin.push_back({ { -16.0, y, z - 0.6 }, { 14.0, y, z - 0.6 }, 0.25 });
  }
}
} // namespace

long long PlatformMaxTriangles()
{
  std::vector<Bar> heavy, thin;
  PlatformBars(heavy, thin);
  return (4LL * kMaxBarSides - 4) * static_cast<long long>(heavy.size() + thin.size()) +
    kPlatformBoxTriangles;
}

namespace
{
/// The platform's parts that stay triangles (sea, decks, modules), its default view and bounds,
/// around the bar actors of Platform() or PlatformBeams().
Scene PlatformAround(
  const std::string& name, std::vector<vtkSmartPointer<vtkActor>> bars, double offset)
{
  Builder decks(offset);
  decks.AddBox({ -20.0, deck1, -20.0 }, { 20.0, deck1 + 1.5, 20.0 });
  decks.AddBox({ -18.0, deck2, -18.0 }, { 18.0, deck2 + 1.0, 18.0 });
  decks.AddBox({ -8.0, deck2 + 1.0, -12.0 }, { 0.0, deck2 + 6.0, -4.0 }); // a module
  decks.AddBox({ 10.0, deck1 + 1.5, 8.0 }, { 18.0, deck1 + 8.0, 18.0 });  // a module

  Scene scene;
  scene.Name = name;
  scene.Actors.push_back(
    MakeActor(Ground(-150, 150, -150, 150, 0.0, offset), 0.35, 0.45, 0.55, 0.1));
  for (auto& actor : bars)
    scene.Actors.push_back(actor);
  scene.Actors.push_back(MakeActor(decks.Finish(true), 0.7, 0.7, 0.72));
  Finish(scene);
  const double eye[3] = { 95.0 + offset, 75.0, 120.0 + offset };
  const double focal[3] = { 0.0 + offset, 32.0, 0.0 + offset };
  std::copy(eye, eye + 3, scene.CameraPosition);
  std::copy(focal, focal + 3, scene.FocalPoint);
  return scene;
}

/// Bars as line cells (one segment each), for lines drawn as tubes.
vtkSmartPointer<vtkPolyData> BarLines(const std::vector<Bar>& bars, double offset)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> lines;
  for (const Bar& bar : bars)
  {
    const vtkIdType ids[2] = { points->InsertNextPoint(
                                 bar.a[0] + offset, bar.a[1], bar.a[2] + offset),
      points->InsertNextPoint(bar.b[0] + offset, bar.b[1], bar.b[2] + offset) };
    lines->InsertNextCell(2, ids);
  }
  auto data = vtkSmartPointer<vtkPolyData>::New();
  data->SetPoints(points);
  data->SetLines(lines);
  return data;
}
} // namespace

Scene Platform(long long targetTriangles, double offset)
{
  std::vector<Bar> heavy, thin;
  PlatformBars(heavy, thin);
  // Tessellation from the triangle budget: 2 sides triangles a bar's wall, sides - 2 a cap.
  const long long bars = static_cast<long long>(heavy.size() + thin.size());
  const int sides = static_cast<int>(
    std::max<long long>(4, std::min<long long>(kMaxBarSides, (targetTriangles / bars + 4) / 4)));
  Builder steel(offset), light(offset);
  for (const Bar& bar : heavy)
    steel.AddBar(bar, sides);
  for (const Bar& bar : thin)
    light.AddBar(bar, std::max(4, sides / 2 * 2));
  return PlatformAround("platform",
    { MakeActor(steel.Finish(false), 0.85, 0.75, 0.35),
      MakeActor(light.Finish(false), 0.9, 0.5, 0.2) },
    offset);
}

Scene PlatformBeams(double offset, double heavyPixels, double thinPixels)
{
  std::vector<Bar> heavy, thin;
  PlatformBars(heavy, thin);
  auto steel = MakeActor(BarLines(heavy, offset), 0.85, 0.75, 0.35);
  auto light = MakeActor(BarLines(thin, offset), 0.9, 0.5, 0.2);
  steel->GetProperty()->SetRenderLinesAsTubes(true);
  steel->GetProperty()->SetLineWidth(static_cast<float>(heavyPixels));
  light->GetProperty()->SetRenderLinesAsTubes(true);
  light->GetProperty()->SetLineWidth(static_cast<float>(thinPixels));
  return PlatformAround("platform-beams", { steel, light }, offset);
}

Scene Towers(int count)
{
  std::vector<Bar> bars;
  for (int i = 0; i < count; ++i)
    Tower(bars, { 0.0, 0.0, -40.0 * i }, 4.0, 1.2, 30.0, 8, 0.08);
  Builder builder;
  for (const Bar& bar : bars)
    builder.AddBar(bar, 6);
  Scene scene;
  scene.Name = "towers";
  const double length = 40.0 * count;
  scene.Actors.push_back(MakeActor(Ground(-60, 60, -length - 40, 40, 0.0), 0.45, 0.55, 0.4, 0.05));
  scene.Actors.push_back(MakeActor(builder.Finish(false), 0.75, 0.75, 0.8));
  Finish(scene);
  const double eye[3] = { 5.0, 2.0, 6.0 }, focal[3] = { -1.0, 8.0, -60.0 };
  std::copy(eye, eye + 3, scene.CameraPosition);
  std::copy(focal, focal + 3, scene.FocalPoint);
  scene.ClippingRange[0] = 0.25;
  scene.ClippingRange[1] = 6000.0;
  scene.ViewAngle = 50.0;
  return scene;
}

Scene Bracket()
{
  const double pi = vtkMath::Pi();
  const double lh = 0.14, lv = 0.10, t = 0.02, depth = 0.10, r = 0.012; // legs, thickness, fillet
  const int filletFacets = 8, holeFacets = 32;
  const double holeRadius = 0.012;
  const double hx = 0.5 * (t + r + lh), vy = 0.5 * (t + r + lv), hz = 0.5 * depth;
  // The profile in the xy plane, counter-clockwise: the outer corner at the origin, the lower
  // leg along +x, the upright leg along +y, the fillet's arc around (t + r, t + r).
  std::vector<std::array<double, 2>> profile = { { 0, 0 }, { lh, 0 }, { lh, t } };
  for (int i = 0; i <= filletFacets; ++i)
  {
    const double a = 1.5 * pi - 0.5 * pi * i / filletFacets; // 270 -> 180 degrees
    profile.push_back({ t + r + r * std::cos(a), t + r + r * std::sin(a) });
  }
  profile.push_back({ t, lv });
  profile.push_back({ 0, lv });
  auto at = [](const std::array<double, 2>& p, double z) { return Vec{ p[0], p[1], z }; };
  SolidBuilder solid;
  // Both ends of the extrusion: fans from the outer corner, which sees the whole profile.
  for (size_t i = 1; i + 1 < profile.size(); ++i)
  {
    solid.Triangle(at(profile[0], 0), at(profile[i], 0), at(profile[i + 1], 0), { 0, 0, -1 });
    solid.Triangle(
      at(profile[0], depth), at(profile[i], depth), at(profile[i + 1], depth), { 0, 0, 1 });
  }
  // The flat sides without holes: the lower leg's end, the upright leg's top.
  solid.Quad(at(profile[1], 0), at(profile[2], 0), at(profile[2], depth), at(profile[1], depth),
    { 1, 0, 0 });
  solid.Quad({ t, lv, 0 }, { 0, lv, 0 }, { 0, lv, depth }, { t, lv, depth }, { 0, 1, 0 });
  // The fillet: one strip of quads per facet, outward toward the arc's centre.
  for (int i = 0; i < filletFacets; ++i)
  {
    const auto& p = profile[3 + i];
    const auto& q = profile[4 + i];
    const Vec outward = { t + r - 0.5 * (p[0] + q[0]), t + r - 0.5 * (p[1] + q[1]), 0.0 };
    solid.Quad(at(p, 0), at(q, 0), at(q, depth), at(p, depth), outward);
  }
  // The holes: circles in each leg's two faces, joined by their walls.
  auto circle = [&](int axis, double level, double c0, double c1)
  {
    // axis 1: a hole along y in the plane y = level around (x, z) = (c0, c1); axis 0: along x
    // around (y, z) = (c0, c1). The points go counter-clockwise in the plane's own (u, v).
    std::vector<Vec> points;
    for (int k = 0; k < holeFacets; ++k)
    {
      const double a = 2.0 * pi * k / holeFacets;
      const double u = c0 + holeRadius * std::cos(a), v = c1 + holeRadius * std::sin(a);
      points.push_back(axis == 1 ? Vec{ u, level, v } : Vec{ level, u, v });
    }
    return points;
  };
  const auto bottom = circle(1, 0.0, hx, hz), top = circle(1, t, hx, hz);
  const auto outer = circle(0, 0.0, vy, hz), inner = circle(0, t, vy, hz);
  // Corners in the order of each circle's (u, v): (+, +), (-, +), (-, -), (+, -) about its centre.
  const Vec bottomCorners[4] = { { lh, 0, depth }, { 0, 0, depth }, { 0, 0, 0 }, { lh, 0, 0 } };
  const Vec topCorners[4] = { { lh, t, depth }, { t + r, t, depth }, { t + r, t, 0 },
    { lh, t, 0 } };
  const Vec outerCorners[4] = { { 0, lv, depth }, { 0, 0, depth }, { 0, 0, 0 }, { 0, lv, 0 } };
  const Vec innerCorners[4] = { { t, lv, depth }, { t, t + r, depth }, { t, t + r, 0 },
    { t, lv, 0 } };
  solid.PlateWithHole(bottomCorners, bottom, { 0, -1, 0 });
  solid.PlateWithHole(topCorners, top, { 0, 1, 0 });
  solid.PlateWithHole(outerCorners, outer, { -1, 0, 0 });
  solid.PlateWithHole(innerCorners, inner, { 1, 0, 0 });
  for (int k = 0; k < holeFacets; ++k)
  {
    const int m = (k + 1) % holeFacets;
    const Vec toAxisH = { hx - 0.5 * (top[k][0] + top[m][0]), 0,
      hz - 0.5 * (top[k][2] + top[m][2]) };
    solid.Quad(bottom[k], bottom[m], top[m], top[k], toAxisH);
    const Vec toAxisV = { 0, vy - 0.5 * (inner[k][1] + inner[m][1]),
      hz - 0.5 * (inner[k][2] + inner[m][2]) };
    solid.Quad(outer[k], outer[m], inner[m], inner[k], toAxisV);
  }
  Scene scene;
  scene.Name = "bracket";
  scene.Actors.push_back(MakeActor(solid.Finish(), 0.7, 0.72, 0.75));
  Finish(scene);
  const double eye[3] = { 0.24, 0.17, 0.27 }, focal[3] = { 0.06, 0.02, 0.05 };
  std::copy(eye, eye + 3, scene.CameraPosition);
  std::copy(focal, focal + 3, scene.FocalPoint);
  scene.ViewAngle = 30.0;
  return scene;
}

namespace
{
/// Reads a file's surface in this process: the reader, then the checks of its output, then the
/// surface filter. Returns null with a message when the file cannot be used.
vtkSmartPointer<vtkPolyData> ReadSurfaceHere(
  const std::string& path, const std::string& ext, std::string& error)
{
  vtkSmartPointer<vtkAlgorithm> reader;
  if (ext == ".glb" || ext == ".gltf")
  {
    auto r = vtkSmartPointer<vtkGLTFReader>::New();
    r->SetFileName(path.c_str());
    reader = r;
  }
  else if (ext == ".vtp")
  {
    auto r = vtkSmartPointer<vtkXMLPolyDataReader>::New();
    r->SetFileName(path.c_str());
    reader = r;
  }
  else if (ext == ".vtk")
  {
    auto r = vtkSmartPointer<vtkGenericDataObjectReader>::New();
    r->SetFileName(path.c_str());
    reader = r;
  }
  else if (ext == ".stl")
  {
    auto r = vtkSmartPointer<vtkSTLReader>::New();
    r->SetFileName(path.c_str());
    reader = r;
  }
  else if (ext == ".ply")
  {
    auto r = vtkSmartPointer<vtkPLYReader>::New();
    r->SetFileName(path.c_str());
    reader = r;
  }
  else if (ext == ".obj")
  {
    auto r = vtkSmartPointer<vtkOBJReader>::New();
    r->SetFileName(path.c_str());
    reader = r;
  }
  reader->Update();
  error = CheckReaderOutput(reader->GetOutputDataObject(0));
  if (!error.empty())
    return nullptr;
  vtkSmartPointer<vtkPolyDataAlgorithm> surface;
  if (ext == ".glb" || ext == ".gltf")
    surface = vtkSmartPointer<vtkCompositeDataGeometryFilter>::New();
  else
    surface = vtkSmartPointer<vtkDataSetSurfaceFilter>::New();
  surface->SetInputConnection(reader->GetOutputPort());
  surface->Update();
  vtkSmartPointer<vtkPolyData> output = surface->GetOutput();
  if (!output || output->GetNumberOfPolys() + output->GetNumberOfStrips() == 0)
  {
    error = "no surface in the file";
    return nullptr;
  }
  return output;
}

/// Runs ReadSurfaceHere in a child process, so that a reader that crashes or hangs on a damaged
/// file gives a message, not a dead or stuck demo. The child hands the surface back as a .vtp.
vtkSmartPointer<vtkPolyData> ReadSurface(
  const std::string& path, const std::string& ext, std::string& error)
{
  const char* tmp = std::getenv("TMPDIR");
  std::string name = std::string(tmp && *tmp ? tmp : "/tmp") + "/csm-scene-XXXXXX";
  const int fd = mkstemp(&name[0]);
  int channel[2];
  if (fd < 0 || pipe(channel) != 0)
  {
    error = "cannot create a temporary file in " + name.substr(0, name.rfind('/'));
    return nullptr;
  }
  close(fd);
  std::fflush(stdout);
  std::fflush(stderr);
  const pid_t child = fork();
  if (child == 0)
  {
    close(channel[0]);
    const int null = open("/dev/null", O_WRONLY); // readers' own chatter (up to gigabytes)
    dup2(null, 1);
    dup2(null, 2);
    std::string message;
    vtkSmartPointer<vtkPolyData> surface = ReadSurfaceHere(path, ext, message);
    if (surface)
    {
      vtkNew<vtkXMLPolyDataWriter> writer;
      writer->SetFileName(name.c_str());
      writer->SetInputData(surface);
      writer->SetDataModeToAppended();
      writer->EncodeAppendedDataOff();
      if (!writer->Write())
        message = "cannot write the temporary file " + name;
    }
    if (!message.empty() && write(channel[1], message.data(), message.size()) < 0)
      _exit(3);
    _exit(message.empty() ? 0 : 1);
  }
  close(channel[1]);
  int status = 0;
  bool done = false;
  const int timeoutSeconds = 60;
  for (int waited = 0; child > 0 && waited < 100 * timeoutSeconds; ++waited)
  {
    if (waitpid(child, &status, WNOHANG) == child)
    {
      done = true;
      break;
    }
    usleep(10000);
  }
  if (child > 0 && !done)
  {
    kill(child, SIGKILL);
    waitpid(child, &status, 0);
  }
  std::string message;
  char buffer[512];
  for (ssize_t n; (n = read(channel[0], buffer, sizeof(buffer))) > 0;)
    message.append(buffer, static_cast<size_t>(n));
  close(channel[0]);
  vtkSmartPointer<vtkPolyData> surface;
  if (child < 0)
    error = "cannot start a process to read the file";
  else if (!done)
    error = "reading took longer than " + std::to_string(timeoutSeconds) +
      " s; the file is damaged or too large";
  else if (WIFSIGNALED(status))
    error = std::string("the reader crashed (") + strsignal(WTERMSIG(status)) +
      "); the file is damaged or not a valid " + ext.substr(1) + " file";
  else if (!message.empty())
    error = message;
  else if (WEXITSTATUS(status) != 0)
    error = "the reader failed";
  else
  {
    vtkNew<vtkXMLPolyDataReader> reader;
    reader->SetFileName(name.c_str());
    reader->Update();
    surface = reader->GetOutput();
  }
  std::remove(name.c_str());
  return error.empty() ? surface : nullptr;
}
} // namespace

namespace
{
/// The extensions FromFile reads.
const char* const kModelFormats[] = { ".vtp", ".vtk", ".stl", ".ply", ".obj", ".glb", ".gltf" };

std::string extensionOf(const std::string& path)
{
  return vtksys::SystemTools::LowerCase(vtksys::SystemTools::GetFilenameLastExtension(path));
}
}

bool NamesAFile(const std::string& name)
{
  return std::find(std::begin(kModelFormats), std::end(kModelFormats), extensionOf(name)) !=
    std::end(kModelFormats);
}

bool FromFile(const std::string& path, Scene& scene, std::string& error)
{
  if (vtksys::SystemTools::FileIsDirectory(path))
  {
    error = "cannot read '" + path + "': it is a directory, not a file";
    return false;
  }
  struct stat status;
  if (!vtksys::SystemTools::FileExists(path, true))
  {
    // Why not, as the system says (a loop of symbolic links, a folder without access, ...).
    const int why = stat(path.c_str(), &status) == 0 ? EACCES : errno;
    error = "cannot read '" + path +
      "': " + (why == ENOENT ? std::string("no such file") : std::string(std::strerror(why)));
    return false;
  }
  if (stat(path.c_str(), &status) == 0 && !S_ISREG(status.st_mode))
  {
    // A named pipe would block the checks and the reader; a device may never end.
    error = "cannot read '" + path + "': it is " +
      (S_ISFIFO(status.st_mode)      ? "a named pipe"
          : S_ISSOCK(status.st_mode) ? "a socket"
                                     : "a device") +
      ", not a regular file";
    return false;
  }
  const std::string ext = extensionOf(path);
  if (!NamesAFile(path))
  {
    error = "cannot read '" + path + "': unknown format (use .vtp .vtk .stl .ply .obj .glb .gltf)";
    return false;
  }
  error = CheckFileStructure(path, ext);
  if (!error.empty())
  {
    error = "cannot read '" + path + "': " + error;
    return false;
  }
  vtkObject::GlobalWarningDisplayOff(); // readers report through the error below
  vtkSmartPointer<vtkPolyData> surface = ReadSurface(path, ext, error);
  vtkObject::GlobalWarningDisplayOn();
  if (!surface)
  {
    error = "cannot read '" + path + "': " + error;
    return false;
  }
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputData(surface);
  vtkNew<vtkPolyDataNormals> normals;
  normals->SetInputConnection(triangles->GetOutputPort());
  normals->SetFeatureAngle(45.0);
  normals->Update();
  vtkSmartPointer<vtkPolyData> model = normals->GetOutput();
  double b[6];
  model->GetBounds(b);
  const double size = std::max({ b[1] - b[0], b[3] - b[2], b[5] - b[4] });
  if (!(size > 0.0) || !std::isfinite(size))
  {
    error = "cannot read '" + path + "': the surface has no extent";
    return false;
  }
  scene = Scene();
  scene.Name = vtksys::SystemTools::GetFilenameWithoutLastExtension(path);
  const double cx = 0.5 * (b[0] + b[1]), cz = 0.5 * (b[4] + b[5]);
  scene.Actors.push_back(MakeActor(
    Ground(cx - 2 * size, cx + 2 * size, cz - 2 * size, cz + 2 * size, b[2] - 0.02 * size, 0.0,
      std::min(0.5, 0.05 * size)), // a slab to the model's scale: tiny models stay in view
    0.6, 0.6, 0.62, 0.1));
  scene.Actors.push_back(MakeActor(model, 0.8, 0.8, 0.82, 0.4));
  Finish(scene);
  const double cy = 0.5 * (b[2] + b[3]);
  const double eye[3] = { cx + 1.2 * size, cy + 0.8 * size, cz + 1.6 * size };
  const double focal[3] = { cx, cy, cz };
  std::copy(eye, eye + 3, scene.CameraPosition);
  std::copy(focal, focal + 3, scene.FocalPoint);
  return true;
}

void Install(const Scene& scene, vtkRenderer* renderer, double)
{
  for (const auto& actor : scene.Actors)
    renderer->AddActor(actor);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(scene.CameraPosition);
  camera->SetFocalPoint(scene.FocalPoint);
  camera->SetViewUp(scene.ViewUp);
  camera->SetViewAngle(scene.ViewAngle);
  camera->OrthogonalizeViewUp();
  if (scene.ClippingRange[1] > scene.ClippingRange[0] && scene.ClippingRange[0] > 0)
    camera->SetClippingRange(scene.ClippingRange);
  else
    renderer->ResetCameraClippingRange();
}

void LightAtGamma(const double eye[3], const double focal[3], double gammaDeg, double light[3])
{
  double dir[3] = { focal[0] - eye[0], focal[1] - eye[1], focal[2] - eye[2] };
  vtkMath::Normalize(dir);
  double up[3] = { 0, 1, 0 };
  const double along = vtkMath::Dot(up, dir);
  for (int c = 0; c < 3; ++c)
  {
    up[c] -= along * dir[c];
  }
  vtkMath::Normalize(up);
  const double r = vtkMath::RadiansFromDegrees(gammaDeg);
  for (int c = 0; c < 3; ++c)
  {
    light[c] = std::cos(r) * dir[c] - std::sin(r) * up[c];
  }
}

} // namespace csmScenes
