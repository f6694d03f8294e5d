// SPDX-License-Identifier: BSD-3-Clause
#include "csmTruth.h"

#include "vtkActor.h"
#include "vtkActorCollection.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkImageData.h"
#include "vtkMapper.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkTriangleFilter.h"
#include "vtkUnsignedCharArray.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace csmTruth
{

struct RayScene::Internals
{
  RTCDevice Device = nullptr;
  RTCScene Scene = nullptr;
  double Origin[3] = { 0, 0, 0 };       // world position of the Embree origin
  double Scale = 1.0;                   // size of the scene, for ray offsets
  bool Tubes = false;                   // the scene holds tubes sized for one camera
  std::vector<unsigned> TubeGeometries; // Embree geometry ids of the tubes
  ~Internals()
  {
    if (this->Scene)
      rtcReleaseScene(this->Scene);
    if (this->Device)
      rtcReleaseDevice(this->Device);
  }
};

RayScene::RayScene()
  : Internal(new Internals)
{
}

RayScene::~RayScene() = default;

namespace
{
/// The world size of one pixel of the main view at a view depth d: pixel[0] + pixel[1] d (as the
/// mapper widens lines: a width in pixels of the viewport's height).
void PixelWorld(vtkRenderer* renderer, int height, double pixel[2])
{
  int w = 0, h = 0, x = 0, y = 0;
  renderer->GetTiledSizeAndOrigin(&w, &h, &x, &y);
  if (height > 0 && h > 0)
    w = static_cast<int>(std::lround(double(w) * height / h));
  h = height > 0 ? height : h;
  vtkMatrix4x4* projection = renderer->GetActiveCamera()->GetProjectionTransformMatrix(
    double(std::max(w, 1)) / std::max(h, 1), -1, 1);
  const double p11 = projection->GetElement(1, 1);
  const double size = h > 0 && std::isfinite(p11) && p11 != 0.0 ? 2.0 / (h * p11) : 0.0;
  pixel[0] = size * projection->GetElement(3, 3);  // parallel: constant
  pixel[1] = -size * projection->GetElement(3, 2); // perspective: grows with depth
}

/// The lines of an actor drawn as tubes, as Embree cone linear curves (flat caps where a
/// polyline ends), radius from each vertex's depth in the main view. Returns the segments.
long long AddTubes(RTCDevice device, RTCScene scene, vtkActor* actor, vtkPolyData* data,
  vtkRenderer* renderer, const double pixel[2], const double origin[3],
  std::vector<unsigned>& tubeGeometries)
{
  vtkProperty* property = actor->GetProperty();
  vtkCellArray* lines = data->GetLines();
  if (!property->GetRenderLinesAsTubes() || property->GetLineWidth() <= 1.0f || !lines ||
    lines->GetNumberOfCells() == 0)
    return 0;
  vtkNew<vtkMatrix4x4> matrix;
  actor->GetMatrix(matrix);
  vtkMatrix4x4* worldToView = renderer->GetActiveCamera()->GetModelViewTransformMatrix();
  const double halfWidth = 0.5 * property->GetLineWidth();
  // Each polyline's points in order (a vertex per point of the cell), one segment per pair.
  std::vector<float> vertices;
  std::vector<unsigned> segments;
  std::vector<unsigned char> flags;
  vtkIdType n;
  const vtkIdType* ids;
  for (lines->InitTraversal(); lines->GetNextCell(n, ids);)
  {
    if (n < 2)
      continue;
    const unsigned first = static_cast<unsigned>(vertices.size() / 4);
    for (vtkIdType k = 0; k < n; ++k)
    {
      double p[4] = { 0, 0, 0, 1 }, w[4], v[4];
      data->GetPoint(ids[k], p);
      matrix->MultiplyPoint(p, w);
      for (int c = 0; c < 3; ++c)
        w[c] /= w[3];
      w[3] = 1.0;
      worldToView->MultiplyPoint(w, v);
      const double depth = std::max(0.0, -v[2] / v[3]);
      for (int c = 0; c < 3; ++c)
        vertices.push_back(static_cast<float>(w[c] - origin[c]));
      vertices.push_back(static_cast<float>(halfWidth * (pixel[0] + pixel[1] * depth)));
    }
    for (vtkIdType k = 0; k + 1 < n; ++k)
    {
      segments.push_back(first + static_cast<unsigned>(k));
      flags.push_back(static_cast<unsigned char>((k > 0 ? RTC_CURVE_FLAG_NEIGHBOR_LEFT : 0) |
        (k + 2 < n ? RTC_CURVE_FLAG_NEIGHBOR_RIGHT : 0)));
    }
  }
  if (segments.empty())
    return 0;
  RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_CONE_LINEAR_CURVE);
  auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0,
    RTC_FORMAT_FLOAT4, 4 * sizeof(float), vertices.size() / 4));
  std::copy(vertices.begin(), vertices.end(), vb);
  auto* ib = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
    geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT, sizeof(unsigned), segments.size()));
  std::copy(segments.begin(), segments.end(), ib);
  auto* fb = static_cast<unsigned char*>(rtcSetNewGeometryBuffer(
    geometry, RTC_BUFFER_TYPE_FLAGS, 0, RTC_FORMAT_UCHAR, sizeof(unsigned char), flags.size()));
  std::copy(flags.begin(), flags.end(), fb);
  rtcCommitGeometry(geometry);
  tubeGeometries.push_back(rtcAttachGeometry(scene, geometry));
  rtcReleaseGeometry(geometry);
  return static_cast<long long>(segments.size());
}
} // namespace

bool RayScene::TubesFollowCamera() const
{
  return this->Internal->Tubes;
}

long long RayScene::Build(vtkRenderer* renderer, int height)
{
  auto& in = *this->Internal;
  if (in.Scene)
    rtcReleaseScene(in.Scene);
  in.Scene = nullptr;
  in.Tubes = false;
  in.TubeGeometries.clear();
  if (!in.Device)
    in.Device = rtcNewDevice(nullptr);
  if (!in.Device)
    return 0;
  double bounds[6];
  renderer->ComputeVisiblePropBounds(bounds);
  if (!(bounds[0] <= bounds[1]))
    return 0;
  for (int i = 0; i < 3; ++i)
    in.Origin[i] = 0.5 * (bounds[2 * i] + bounds[2 * i + 1]);
  in.Scale =
    std::max({ bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4], 1e-9 });
  in.Scene = rtcNewScene(in.Device);
  long long triangles = 0;
  double pixel[2];
  PixelWorld(renderer, height, pixel);
  vtkActorCollection* actors = renderer->GetActors();
  vtkCollectionSimpleIterator it;
  actors->InitTraversal(it);
  while (vtkActor* actor = actors->GetNextActor(it))
  {
    if (!actor->GetVisibility() || !actor->GetMapper())
      continue;
    auto* data = vtkPolyData::SafeDownCast(actor->GetMapper()->GetInputDataObject(0, 0));
    if (!data)
      continue;
    const long long tubes =
      AddTubes(in.Device, in.Scene, actor, data, renderer, pixel, in.Origin, in.TubeGeometries);
    in.Tubes = in.Tubes || tubes > 0;
    triangles += tubes;
    vtkNew<vtkTriangleFilter> triangulate;
    triangulate->SetInputData(data);
    triangulate->PassVertsOff();
    triangulate->PassLinesOff();
    triangulate->Update();
    vtkPolyData* tris = triangulate->GetOutput();
    const vtkIdType np = tris->GetNumberOfPoints();
    const vtkIdType nt = tris->GetNumberOfPolys();
    if (np == 0 || nt == 0)
      continue;
    vtkNew<vtkMatrix4x4> matrix;
    actor->GetMatrix(matrix);
    RTCGeometry geometry = rtcNewGeometry(in.Device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), np));
    for (vtkIdType i = 0; i < np; ++i)
    {
      double p[4] = { 0, 0, 0, 1 };
      tris->GetPoint(i, p);
      double w[4];
      matrix->MultiplyPoint(p, w);
      for (int c = 0; c < 3; ++c)
        vertices[3 * i + c] = static_cast<float>(w[c] / w[3] - in.Origin[c]);
    }
    auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), nt));
    vtkIdType n;
    const vtkIdType* ids;
    vtkIdType t = 0;
    vtkCellArray* polys = tris->GetPolys();
    for (polys->InitTraversal(); polys->GetNextCell(n, ids) && t < nt; ++t)
      for (int c = 0; c < 3; ++c)
        indices[3 * t + c] = static_cast<unsigned>(ids[c]);
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(in.Scene, geometry);
    rtcReleaseGeometry(geometry);
    triangles += nt;
  }
  rtcCommitScene(in.Scene);
  return triangles;
}

namespace
{
/// The primary ray through window point (px, py) (in pixels from the lower left) of a
/// width x height view whose clip -> world matrix is clipToWorld: its origin on the near plane,
/// the vector to the far plane, and that vector's length.
double PrimaryRay(vtkMatrix4x4* clipToWorld, double px, double py, int width, int height,
  double origin[3], double dir[3])
{
  const double x = 2.0 * px / width - 1.0, y = 2.0 * py / height - 1.0;
  double nearH[4] = { x, y, -1, 1 }, farH[4] = { x, y, 1, 1 }, a[4], b[4];
  clipToWorld->MultiplyPoint(nearH, a);
  clipToWorld->MultiplyPoint(farH, b);
  for (int c = 0; c < 3; ++c)
  {
    origin[c] = a[c] / a[3];
    dir[c] = b[c] / b[3] - origin[c];
  }
  return std::sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
}
} // namespace

std::vector<Surface> RayScene::CastPrimary(vtkCamera* camera, int width, int height) const
{
  const auto& in = *this->Internal;
  std::vector<Surface> surfaces(static_cast<size_t>(width) * height);
  if (!in.Scene)
    return surfaces;
  vtkNew<vtkMatrix4x4> inverse;
  vtkMatrix4x4::Invert(
    camera->GetCompositeProjectionTransformMatrix(double(width) / height, -1, 1), inverse);
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  for (int j = 0; j < height; ++j)
  {
    for (int i = 0; i < width; ++i)
    {
      double origin[3], dir[3];
      const double length = PrimaryRay(inverse, i + 0.5, j + 0.5, width, height, origin, dir);
      RTCRayHit rh;
      rh.ray.org_x = float(origin[0] - in.Origin[0]);
      rh.ray.org_y = float(origin[1] - in.Origin[1]);
      rh.ray.org_z = float(origin[2] - in.Origin[2]);
      rh.ray.dir_x = float(dir[0] / length);
      rh.ray.dir_y = float(dir[1] / length);
      rh.ray.dir_z = float(dir[2] / length);
      rh.ray.tnear = 0.0f;
      rh.ray.tfar = float(length);
      rh.ray.mask = 0xFFFFFFFF;
      rh.ray.flags = 0;
      rh.ray.time = 0.0f;
      rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
      rtcIntersect1(in.Scene, &context, &rh);
      Surface& s = surfaces[static_cast<size_t>(j) * width + i];
      if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID)
        continue;
      s.Hit = true;
      s.OnTube = std::find(in.TubeGeometries.begin(), in.TubeGeometries.end(), rh.hit.geomID) !=
        in.TubeGeometries.end();
      s.Distance = rh.ray.tfar;
      double n[3] = { rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z };
      const double nl = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      const double d[3] = { dir[0] / length, dir[1] / length, dir[2] / length };
      const double facing = (n[0] * d[0] + n[1] * d[1] + n[2] * d[2]) > 0 ? -1.0 : 1.0;
      for (int c = 0; c < 3; ++c)
      {
        s.Position[c] = origin[c] + d[c] * rh.ray.tfar;
        s.Normal[c] = nl > 0 ? facing * n[c] / nl : 0.0;
      }
    }
  }
  return surfaces;
}

bool RayScene::Occluded(const Surface& s, const double lightDirection[3]) const
{
  const auto& in = *this->Internal;
  const double l = std::sqrt(lightDirection[0] * lightDirection[0] +
    lightDirection[1] * lightDirection[1] + lightDirection[2] * lightDirection[2]);
  // A triangle's hit lies within a few float ulps of its plane: Embree holds coordinates
  // relative to in.Origin in single precision, so the error grows with the distance from there
  // and along the primary ray. Lift the shadow ray off the surface by a few times that, no more:
  // any lift moves the point tested, and under a grazing light a lift h moves its shadow by
  // h / tan(angle) along the receiver (a lift of 1e-5 of the scene's size moved the towers'
  // ground shadows by 0.66 units at 5 degrees, ~20 pixels near the camera). Tubes (Embree's
  // cone curves, pixel-thin) are hit less precisely: they keep the scene-sized lift.
  const double fromOrigin = std::max({ std::abs(s.Position[0] - in.Origin[0]),
    std::abs(s.Position[1] - in.Origin[1]), std::abs(s.Position[2] - in.Origin[2]) });
  const double eps = s.OnTube
    ? 1e-5 * in.Scale + 1e-4 * s.Distance
    : 8.0 * std::numeric_limits<float>::epsilon() * (fromOrigin + s.Distance) + 1e-9 * in.Scale;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay ray;
  ray.org_x = float(s.Position[0] - in.Origin[0] + s.Normal[0] * eps);
  ray.org_y = float(s.Position[1] - in.Origin[1] + s.Normal[1] * eps);
  ray.org_z = float(s.Position[2] - in.Origin[2] + s.Normal[2] * eps);
  ray.dir_x = float(-lightDirection[0] / l);
  ray.dir_y = float(-lightDirection[1] / l);
  ray.dir_z = float(-lightDirection[2] / l);
  ray.tnear = 0.0f;
  ray.tfar = std::numeric_limits<float>::infinity();
  ray.mask = 0xFFFFFFFF;
  ray.flags = 0;
  ray.time = 0.0f;
  rtcOccluded1(in.Scene, &context, &ray);
  return ray.tfar < 0.0f; // Embree sets tfar to -inf on a hit
}

std::vector<char> RayScene::ShadowEdges(vtkCamera* camera, int width, int height,
  const std::vector<Surface>& surfaces, const std::vector<char>& comparable,
  const std::vector<char>& occluded, const double lightDirection[3]) const
{
  const size_t n = static_cast<size_t>(width) * height;
  std::vector<char> edges(n, 0);
  if (!this->Internal->Scene || surfaces.size() != n || comparable.size() != n ||
    occluded.size() != n)
    return edges;
  vtkNew<vtkMatrix4x4> inverse;
  vtkMatrix4x4::Invert(
    camera->GetCompositeProjectionTransformMatrix(double(width) / height, -1, 1), inverse);
  for (int j = 0; j < height; ++j)
  {
    for (int i = 0; i < width; ++i)
    {
      const size_t k = static_cast<size_t>(j) * width + i;
      if (!comparable[k])
        continue;
      const Surface& s = surfaces[k];
      for (int corner = 0; corner < 4 && !edges[k]; ++corner)
      {
        double origin[3], dir[3];
        PrimaryRay(inverse, i + (corner & 1), j + (corner >> 1), width, height, origin, dir);
        // Where that ray meets the plane of the centre's surface.
        double toPlane = 0.0, along = 0.0;
        for (int c = 0; c < 3; ++c)
        {
          toPlane += (s.Position[c] - origin[c]) * s.Normal[c];
          along += dir[c] * s.Normal[c];
        }
        if (along == 0.0 || !std::isfinite(toPlane / along) || toPlane / along <= 0.0)
        {
          edges[k] = 1; // the plane seen edge-on there: nothing sure about this pixel
          break;
        }
        Surface q = s;
        const double t = toPlane / along;
        double length = 0.0;
        for (int c = 0; c < 3; ++c)
        {
          q.Position[c] = origin[c] + t * dir[c];
          length += (t * dir[c]) * (t * dir[c]);
        }
        q.Distance = std::sqrt(length);
        edges[k] = this->Occluded(q, lightDirection) != (occluded[k] != 0);
      }
    }
  }
  return edges;
}

std::vector<char> ComparablePixels(
  const std::vector<Surface>& surfaces, int width, int height, const double lightDirection[3])
{
  std::vector<char> ok(surfaces.size(), 0);
  const double l = std::sqrt(lightDirection[0] * lightDirection[0] +
    lightDirection[1] * lightDirection[1] + lightDirection[2] * lightDirection[2]);
  for (int j = 1; j + 1 < height; ++j)
  {
    for (int i = 1; i + 1 < width; ++i)
    {
      const size_t k = static_cast<size_t>(j) * width + i;
      const Surface& s = surfaces[k];
      if (!s.Hit)
        continue;
      const double facing = -(s.Normal[0] * lightDirection[0] + s.Normal[1] * lightDirection[1] +
                              s.Normal[2] * lightDirection[2]) /
        l;
      if (facing <= 0.05)
        continue;
      bool edge = false;
      for (size_t n : { k - 1, k + 1, k - width, k + width })
        edge = edge || !surfaces[n].Hit ||
          std::abs(surfaces[n].Distance - s.Distance) > 0.02 * s.Distance;
      ok[k] = !edge;
    }
  }
  return ok;
}

PixelClass ClassifyPixel(bool comparable, bool occluded, float factor)
{
  if (!comparable || std::isnan(factor))
    return PixelClass::NotCompared;
  const bool dark = factor < 0.5f;
  if (dark != occluded)
    return dark ? PixelClass::FalseShadow : PixelClass::FalseLight;
  return dark ? PixelClass::Shadowed : PixelClass::Lit;
}

Classification Classify(const std::vector<Surface>& surfaces, const std::vector<char>& comparable,
  const std::vector<char>& occluded, const std::vector<float>& factor,
  const std::vector<char>* edges)
{
  Classification c;
  const bool withEdges = edges && edges->size() == surfaces.size();
  for (size_t k = 0; k < surfaces.size(); ++k)
  {
    const PixelClass p = ClassifyPixel(comparable[k], occluded[k], factor[k]);
    c.Considered += p != PixelClass::NotCompared;
    c.FalseShadow += p == PixelClass::FalseShadow;
    c.FalseLight += p == PixelClass::FalseLight;
    if (withEdges && p != PixelClass::NotCompared && !(*edges)[k])
    {
      ++c.OffEdge;
      c.OffEdgeWrong += p == PixelClass::FalseShadow || p == PixelClass::FalseLight;
    }
  }
  return c;
}

std::vector<float> FactorFromRenders(vtkImageData* shadowed, vtkImageData* plain)
{
  auto* a = vtkUnsignedCharArray::SafeDownCast(shadowed->GetPointData()->GetScalars());
  auto* b = vtkUnsignedCharArray::SafeDownCast(plain->GetPointData()->GetScalars());
  std::vector<float> factor(b ? b->GetNumberOfTuples() : 0, NAN);
  if (!a || !b || a->GetNumberOfTuples() != b->GetNumberOfTuples())
    return factor;
  const int nc = a->GetNumberOfComponents();
  for (vtkIdType i = 0; i < b->GetNumberOfTuples(); ++i)
  {
    double la = 0, lb = 0;
    for (int c = 0; c < 3; ++c)
    {
      la += a->GetValue(nc * i + c);
      lb += b->GetValue(nc * i + c);
    }
    if (lb >= 3 * 12.0) // too dark to measure a ratio
      factor[i] = static_cast<float>(la / lb);
  }
  return factor;
}

Stats Summarize(std::vector<double> values)
{
  Stats s;
  if (values.empty())
    return s;
  std::sort(values.begin(), values.end());
  s.Max = values.back();
  s.P95 = values[static_cast<size_t>(0.95 * (values.size() - 1))];
  double sum = 0;
  for (double v : values)
    sum += v;
  s.Mean = sum / values.size();
  return s;
}

} // namespace csmTruth
