// SPDX-License-Identifier: BSD-3-Clause
#include "csmPartFamily.h"
#include "csmSolidBuilder.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkMath.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace csmPartFamily
{
namespace
{
using Vec = csmScenes::SolidBuilder::Vec;
using P2 = std::array<double, 2>;

/// How a profile's corner is cut: left sharp, rounded by a fillet of `Size` radius in `Facets`
/// facets, or cut by a chamfer `Size` long on each side.
struct Corner
{
  P2 At;
  enum Kind
  {
    Sharp,
    Fillet,
    Chamfer
  } Cut = Sharp;
  double Size = 0.0;
  int Facets = 1;
};

Corner Sharp(double x, double y)
{
  return { { x, y }, Corner::Sharp, 0.0, 1 };
}
Corner Round(double x, double y, double r, int facets)
{
  return { { x, y }, Corner::Fillet, r, facets };
}
Corner Cut(double x, double y, double c)
{
  return { { x, y }, Corner::Chamfer, c, 1 };
}

P2 Unit(const P2& from, const P2& to)
{
  const double dx = to[0] - from[0], dy = to[1] - from[1], l = std::hypot(dx, dy);
  return { dx / l, dy / l };
}

/// The polygon of a profile whose corners (counter-clockwise) are right angles, cut as each says.
std::vector<P2> Outline(const std::vector<Corner>& corners)
{
  std::vector<P2> points;
  const size_t n = corners.size();
  for (size_t i = 0; i < n; ++i)
  {
    const Corner& c = corners[i];
    if (c.Cut == Corner::Sharp)
    {
      points.push_back(c.At);
      continue;
    }
    const P2 u1 = Unit(c.At, corners[(i + n - 1) % n].At), u2 = Unit(c.At, corners[(i + 1) % n].At);
    const double s = c.Size;
    if (c.Cut == Corner::Chamfer)
    {
      points.push_back({ c.At[0] + s * u1[0], c.At[1] + s * u1[1] });
      points.push_back({ c.At[0] + s * u2[0], c.At[1] + s * u2[1] });
      continue;
    }
    // The arc from c + s u1 to c + s u2 around c + s (u1 + u2), tangent to both sides.
    const P2 o = { c.At[0] + s * (u1[0] + u2[0]), c.At[1] + s * (u1[1] + u2[1]) };
    for (int k = 0; k <= c.Facets; ++k)
    {
      const double phi = 0.5 * vtkMath::Pi() * k / c.Facets;
      points.push_back({ o[0] - s * (std::cos(phi) * u2[0] + std::sin(phi) * u1[0]),
        o[1] - s * (std::cos(phi) * u2[1] + std::sin(phi) * u1[1]) });
    }
  }
  return points;
}

double Cross(const P2& a, const P2& b, const P2& c)
{
  return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

/// Triangles of a simple counter-clockwise polygon (ear clipping), as index triples.
std::vector<std::array<size_t, 3>> Triangulate(const std::vector<P2>& polygon)
{
  std::vector<size_t> left(polygon.size());
  for (size_t i = 0; i < left.size(); ++i)
    left[i] = i;
  std::vector<std::array<size_t, 3>> triangles;
  while (left.size() > 3)
  {
    const size_t n = left.size();
    size_t ear = n;
    for (size_t i = 0; i < n && ear == n; ++i)
    {
      const P2 &a = polygon[left[(i + n - 1) % n]], &b = polygon[left[i]],
               &c = polygon[left[(i + 1) % n]];
      if (Cross(a, b, c) <= 1e-15)
        continue;
      bool empty = true;
      for (size_t j = 0; j < n && empty; ++j)
      {
        const P2& p = polygon[left[j]];
        if (j == i || j == (i + 1) % n || j == (i + n - 1) % n)
          continue;
        empty = !(Cross(a, b, p) >= 0 && Cross(b, c, p) >= 0 && Cross(c, a, p) >= 0);
      }
      if (empty)
        ear = i;
    }
    if (ear == n)
      ear = 0; // degenerate input: clip anyway
    triangles.push_back({ left[(ear + n - 1) % n], left[ear], left[(ear + 1) % n] });
    left.erase(left.begin() + static_cast<long>(ear));
  }
  triangles.push_back({ left[0], left[1], left[2] });
  return triangles;
}

/// A profile in the xy plane extruded along z from z0 to z1, moved by `at`.
void Extrude(csmScenes::SolidBuilder& solid, const std::vector<Corner>& corners, double z0,
  double z1, const Vec& at = { 0, 0, 0 })
{
  const std::vector<P2> outline = Outline(corners);
  auto point = [&](const P2& p, double z) { return Vec{ at[0] + p[0], at[1] + p[1], at[2] + z }; };
  for (const auto& t : Triangulate(outline))
  {
    solid.Triangle(
      point(outline[t[0]], z0), point(outline[t[1]], z0), point(outline[t[2]], z0), { 0, 0, -1 });
    solid.Triangle(
      point(outline[t[0]], z1), point(outline[t[1]], z1), point(outline[t[2]], z1), { 0, 0, 1 });
  }
  for (size_t i = 0; i < outline.size(); ++i)
  {
    const P2 &p = outline[i], &q = outline[(i + 1) % outline.size()];
    solid.Quad(
      point(p, z0), point(q, z0), point(q, z1), point(p, z1), { q[1] - p[1], p[0] - q[0], 0.0 });
  }
}

void Box(csmScenes::SolidBuilder& solid, const Vec& lo, const Vec& hi)
{
  Extrude(solid,
    { Sharp(lo[0], lo[1]), Sharp(hi[0], lo[1]), Sharp(hi[0], hi[1]), Sharp(lo[0], hi[1]) }, lo[2],
    hi[2]);
}

/// A cylinder standing on y = y0, `height` tall, around (cx, cz).
void Cylinder(csmScenes::SolidBuilder& solid, double cx, double y0, double cz, double radius,
  double height, int facets)
{
  const Vec bottom = { cx, y0, cz }, top = { cx, y0 + height, cz };
  for (int k = 0; k < facets; ++k)
  {
    const double a = 2.0 * vtkMath::Pi() * k / facets, b = 2.0 * vtkMath::Pi() * (k + 1) / facets;
    const Vec p0 = { cx + radius * std::cos(a), y0, cz + radius * std::sin(a) };
    const Vec p1 = { cx + radius * std::cos(b), y0, cz + radius * std::sin(b) };
    const Vec q0 = { p0[0], y0 + height, p0[2] }, q1 = { p1[0], y0 + height, p1[2] };
    solid.Triangle(bottom, p0, p1, { 0, -1, 0 });
    solid.Triangle(top, q0, q1, { 0, 1, 0 });
    solid.Quad(p0, p1, q1, q0, { std::cos(0.5 * (a + b)), 0, std::sin(0.5 * (a + b)) });
  }
}

/// A plate from lo to hi (its faces along y) with a round vertical hole through its middle.
void PlateWithHole(
  csmScenes::SolidBuilder& solid, const Vec& lo, const Vec& hi, double radius, int facets)
{
  const double cx = 0.5 * (lo[0] + hi[0]), cz = 0.5 * (lo[2] + hi[2]);
  auto circle = [&](double y)
  {
    std::vector<Vec> points;
    for (int k = 0; k < facets; ++k)
    {
      const double a = 2.0 * vtkMath::Pi() * k / facets;
      points.push_back({ cx + radius * std::cos(a), y, cz + radius * std::sin(a) });
    }
    return points;
  };
  const auto bottom = circle(lo[1]), top = circle(hi[1]);
  for (int f = 0; f < 2; ++f)
  {
    const double y = f ? hi[1] : lo[1];
    const Vec corners[4] = { { hi[0], y, hi[2] }, { lo[0], y, hi[2] }, { lo[0], y, lo[2] },
      { hi[0], y, lo[2] } };
    solid.PlateWithHole(corners, f ? top : bottom, { 0, f ? 1.0 : -1.0, 0 });
  }
  for (int k = 0; k < facets; ++k)
  {
    const int m = (k + 1) % facets;
    const double a = 2.0 * vtkMath::Pi() * (k + 0.5) / facets;
    solid.Quad(bottom[k], bottom[m], top[m], top[k], { -std::cos(a), 0, -std::sin(a) });
  }
  const Vec sides[4][4] = {
    { { lo[0], lo[1], lo[2] }, { lo[0], hi[1], lo[2] }, { lo[0], hi[1], hi[2] },
      { lo[0], lo[1], hi[2] } },
    { { hi[0], lo[1], lo[2] }, { hi[0], hi[1], lo[2] }, { hi[0], hi[1], hi[2] },
      { hi[0], lo[1], hi[2] } },
    { { lo[0], lo[1], lo[2] }, { hi[0], lo[1], lo[2] }, { hi[0], hi[1], lo[2] },
      { lo[0], hi[1], lo[2] } },
    { { lo[0], lo[1], hi[2] }, { hi[0], lo[1], hi[2] }, { hi[0], hi[1], hi[2] },
      { lo[0], hi[1], hi[2] } },
  };
  const Vec outward[4] = { { -1, 0, 0 }, { 1, 0, 0 }, { 0, 0, -1 }, { 0, 0, 1 } };
  for (int s = 0; s < 4; ++s)
    solid.Quad(sides[s][0], sides[s][1], sides[s][2], sides[s][3], outward[s]);
}

/// A hollow rectangular section along z: outer corners lo, hi (x, y), walls `wall` thick.
void HollowBox(csmScenes::SolidBuilder& solid, const Vec& lo, const Vec& hi, double wall)
{
  const P2 outer[4] = { { lo[0], lo[1] }, { hi[0], lo[1] }, { hi[0], hi[1] }, { lo[0], hi[1] } };
  const P2 inner[4] = { { lo[0] + wall, lo[1] + wall }, { hi[0] - wall, lo[1] + wall },
    { hi[0] - wall, hi[1] - wall }, { lo[0] + wall, hi[1] - wall } };
  auto at = [](const P2& p, double z) { return Vec{ p[0], p[1], z }; };
  for (int i = 0; i < 4; ++i)
  {
    const int j = (i + 1) % 4;
    const Vec out = { outer[j][1] - outer[i][1], outer[i][0] - outer[j][0], 0.0 };
    const Vec in = { -out[0], -out[1], 0.0 };
    solid.Quad(
      at(outer[i], lo[2]), at(outer[j], lo[2]), at(outer[j], hi[2]), at(outer[i], hi[2]), out);
    solid.Quad(
      at(inner[i], lo[2]), at(inner[j], lo[2]), at(inner[j], hi[2]), at(inner[i], hi[2]), in);
    for (int e = 0; e < 2; ++e)
    {
      const double z = e ? hi[2] : lo[2];
      solid.Quad(at(outer[i], z), at(outer[j], z), at(inner[j], z), at(inner[i], z),
        { 0, 0, e ? 1.0 : -1.0 });
    }
  }
}

vtkSmartPointer<vtkActor> Actor(csmScenes::SolidBuilder& solid)
{
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(solid.Finish());
  mapper->ScalarVisibilityOff();
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(1, 1, 1);
  actor->GetProperty()->SetAmbient(0.0);
  actor->GetProperty()->SetDiffuse(1.0);
  actor->GetProperty()->SetSpecular(0.0);
  return actor;
}

csmScenes::Scene Member(const std::string& name, std::vector<vtkSmartPointer<vtkActor>> actors)
{
  csmScenes::Scene scene;
  scene.Name = name;
  scene.Actors = std::move(actors);
  double b[6] = { 1e300, -1e300, 1e300, -1e300, 1e300, -1e300 };
  for (const auto& actor : scene.Actors)
  {
    const double* a = actor->GetBounds();
    for (int i = 0; i < 3; ++i)
    {
      b[2 * i] = std::min(b[2 * i], a[2 * i]);
      b[2 * i + 1] = std::max(b[2 * i + 1], a[2 * i + 1]);
    }
    scene.Triangles += csmScenes::CountTriangles(
      vtkPolyData::SafeDownCast(actor->GetMapper()->GetInputDataObject(0, 0)));
  }
  std::copy(b, b + 6, scene.Bounds);
  return scene;
}

/// An L lying on its outer side: legs lh along +x and lv along +y, `t` thick, its inner corner
/// cut as `inner` says.
std::vector<Corner> LProfile(double lh, double lv, double t, Corner inner)
{
  inner.At = { t, t };
  return { Sharp(0, 0), Sharp(lh, 0), Sharp(lh, t), inner, Sharp(t, lv), Sharp(0, lv) };
}
} // namespace

std::vector<csmScenes::Scene> Members()
{
  std::vector<csmScenes::Scene> members;
  {
    csmScenes::SolidBuilder s; // a thick L, its inner bend filleted
    Extrude(s, LProfile(0.14, 0.10, 0.03, Round(0, 0, 0.01, 8)), 0.0, 0.10);
    members.push_back(Member("l-fillet", { Actor(s) }));
  }
  {
    csmScenes::SolidBuilder s; // a thin L, its inner bend chamfered
    Extrude(s, LProfile(0.12, 0.09, 0.004, Cut(0, 0, 0.006)), 0.0, 0.08);
    members.push_back(Member("l-thin-chamfer", { Actor(s) }));
  }
  {
    csmScenes::SolidBuilder s; // a U channel opening up, both inner corners filleted
    const double w = 0.12, h = 0.07, t = 0.01, r = 0.008;
    Extrude(s,
      { Sharp(0, 0), Sharp(w, 0), Sharp(w, h), Sharp(w - t, h), Round(w - t, t, r, 6),
        Round(t, t, r, 6), Sharp(t, h), Sharp(0, h) },
      0.0, 0.12);
    members.push_back(Member("u-channel", { Actor(s) }));
  }
  {
    csmScenes::SolidBuilder s; // an inverted T: one inner corner sharp, the other chamfered
    const double w = 0.12, tf = 0.012, ts = 0.016, h = 0.08, m = 0.5 * w;
    Extrude(s,
      { Sharp(0, 0), Sharp(w, 0), Sharp(w, tf), Sharp(m + 0.5 * ts, tf), Sharp(m + 0.5 * ts, h),
        Sharp(m - 0.5 * ts, h), Cut(m - 0.5 * ts, tf, 0.004), Sharp(0, tf) },
      0.0, 0.10);
    members.push_back(Member("t-profile", { Actor(s) }));
  }
  {
    csmScenes::SolidBuilder base, tube; // a hollow box section lying on a plate
    Box(base, { -0.06, -0.012, -0.04 }, { 0.18, 0.0, 0.20 });
    HollowBox(tube, { 0.0, 0.0, 0.0 }, { 0.10, 0.07, 0.16 }, 0.006);
    members.push_back(Member("box-section", { Actor(base), Actor(tube) }));
  }
  {
    csmScenes::SolidBuilder base, parts; // a plate with a hole, a boss and a plate on it
    PlateWithHole(base, { 0.0, -0.015, 0.0 }, { 0.20, 0.0, 0.16 }, 0.02, 32);
    Cylinder(parts, 0.05, 0.0, 0.04, 0.015, 0.04, 24);
    Box(parts, { 0.11, 0.0, 0.09 }, { 0.19, 0.01, 0.15 });
    members.push_back(Member("plate-boss", { Actor(base), Actor(parts) }));
  }
  {
    csmScenes::SolidBuilder s; // steps stacked from thick to thin, touching
    Box(s, { 0.0, 0.0, 0.0 }, { 0.20, 0.03, 0.12 });
    Box(s, { 0.0, 0.03, 0.0 }, { 0.14, 0.042, 0.12 });
    Box(s, { 0.0, 0.042, 0.0 }, { 0.08, 0.046, 0.12 });
    members.push_back(Member("steps", { Actor(s) }));
  }
  {
    csmScenes::SolidBuilder base, parts; // an L on a plate, a block in its inner corner
    Box(base, { -0.04, -0.01, -0.04 }, { 0.18, 0.0, 0.14 });
    Extrude(parts, LProfile(0.12, 0.10, 0.015, Round(0, 0, 0.006, 6)), 0.0, 0.10);
    Box(parts, { 0.015 + 0.006, 0.015, 0.03 }, { 0.05, 0.055, 0.08 });
    members.push_back(Member("l-on-base", { Actor(base), Actor(parts) }));
  }
  return members;
}

std::vector<View> Views(int members, bool full)
{
  std::vector<std::array<double, 2>> lights;
  if (full)
  {
    for (double e : { 5.0, 10.0, 20.0, 30.0, 45.0, 60.0, 80.0 })
      for (int a = 0; a < 360; a += 30)
        lights.push_back({ e, double(a) });
  }
  else
  {
    lights = { { 5, 20 }, { 12, 60 }, { 20, 35 }, { 20, 160 }, { 35, 300 }, { 50, 100 },
      { 65, 230 }, { 80, 35 } };
  }
  std::vector<View> views;
  for (int m = 0; m < members; ++m)
    for (bool close : { true, false })
      for (const auto& l : lights)
        views.push_back({ m, close, l[0], l[1] });
  return views;
}

void LightDirection(const View& view, double direction[3])
{
  const double e = vtkMath::RadiansFromDegrees(view.Elevation);
  const double a = vtkMath::RadiansFromDegrees(view.Azimuth);
  direction[0] = std::cos(e) * std::cos(a);
  direction[1] = -std::sin(e);
  direction[2] = -std::cos(e) * std::sin(a);
}

void PlaceCamera(const View& view, const csmScenes::Scene& member, vtkRenderer* renderer)
{
  const double* b = member.Bounds;
  const double centre[3] = { 0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5]) };
  const double diagonal = std::sqrt(
    (b[1] - b[0]) * (b[1] - b[0]) + (b[3] - b[2]) * (b[3] - b[2]) + (b[5] - b[4]) * (b[5] - b[4]));
  double toEye[3] = { 0.8, 0.6, 1.0 };
  if (!view.Close)
  {
    toEye[0] = 0.35;
    toEye[1] = 0.9;
  }
  vtkMath::Normalize(toEye);
  const double distance = (view.Close ? 1.1 : 3.0) * diagonal;
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetFocalPoint(centre);
  camera->SetPosition(centre[0] + distance * toEye[0], centre[1] + distance * toEye[1],
    centre[2] + distance * toEye[2]);
  camera->SetViewUp(0, 1, 0);
  camera->SetViewAngle(30.0);
  camera->OrthogonalizeViewUp();
  renderer->ResetCameraClippingRange();
}

} // namespace csmPartFamily
