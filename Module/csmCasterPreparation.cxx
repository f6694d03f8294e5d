// SPDX-License-Identifier: BSD-3-Clause
#include "csmCasterPreparation.h"

#include "csmCasterBlocks.h"
#include "csmDigest.h"
#include "vtkCascadedShadowMapTypes.h" // for MaximumBlocks

#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkDataArray.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

// Every block of a prop has its index in BlockOf, kNoBlock apart.
static_assert(vtkCascadedShadows::MaximumBlocks < csmPreparedBlocks::kNoBlock,
  "a block's index must fit csmPreparedBlocks::BlockOf");

vtkSmartPointer<vtkDataArray> csmOwnCopy(vtkDataArray* source)
{
  auto copy = vtk::TakeSmartPointer(source->NewInstance());
  copy->SetNumberOfComponents(source->GetNumberOfComponents());
  copy->SetNumberOfTuples(source->GetNumberOfTuples());
  const size_t bytes = static_cast<size_t>(source->GetNumberOfValues()) *
    static_cast<size_t>(source->GetDataTypeSize());
  if (!source->HasStandardMemoryLayout())
  {
    copy->DeepCopy(source);
  }
  else if (bytes > 0)
  {
    std::memcpy(copy->GetVoidPointer(0), source->GetVoidPointer(0), bytes);
  }
  return copy;
}

vtkSmartPointer<vtkCellArray> csmOwnCopy(vtkCellArray* source)
{
  auto copy = vtkSmartPointer<vtkCellArray>::New();
  if (source && source->GetOffsetsArray() && source->GetConnectivityArray())
  {
    copy->SetData(
      csmOwnCopy(source->GetOffsetsArray()), csmOwnCopy(source->GetConnectivityArray()));
  }
  return copy;
}

double csmTriangleCount(vtkPolyData* data)
{
  const double polys = static_cast<double>(data->GetPolys()->GetNumberOfConnectivityIds()) -
    2.0 * static_cast<double>(data->GetPolys()->GetNumberOfCells());
  const double strips = static_cast<double>(data->GetStrips()->GetNumberOfConnectivityIds()) -
    2.0 * static_cast<double>(data->GetStrips()->GetNumberOfCells());
  return std::max(0.0, polys) + std::max(0.0, strips);
}

vtkMTimeType csmGeometryTime(vtkPolyData* data)
{
  // The object's own time (SetPoints, SetPolys, Modified()), not its point and cell data's.
  vtkMTimeType time = data->vtkObject::GetMTime();
  for (vtkObject* part : std::initializer_list<vtkObject*>{ data->GetPoints(), data->GetVerts(),
         data->GetLines(), data->GetPolys(), data->GetStrips() })
  {
    time = std::max(time, part ? part->GetMTime() : 0);
  }
  return time;
}

namespace
{
/// Calls f(a, b, c) for every triangle of a polydata's polygons (fans) and strips, wound as
/// drawn; safe beside the main thread's own reading (each traversal has its own iterator).
/// Stops early (returning false) once `stop` is set.
template <typename F>
bool forEachTriangle(vtkPolyData* data, F&& f, const std::atomic<bool>* stop = nullptr)
{
  vtkIdType n;
  const vtkIdType* ids;
  vtkIdType visited = 0;
  auto stopped = [&visited, stop]()
  { return stop && (++visited & 0xfff) == 0 && stop->load(std::memory_order_relaxed); };
  auto polys = vtk::TakeSmartPointer(data->GetPolys()->NewIterator());
  for (polys->GoToFirstCell(); !polys->IsDoneWithTraversal(); polys->GoToNextCell())
  {
    if (stopped())
    {
      return false;
    }
    polys->GetCurrentCell(n, ids);
    for (vtkIdType k = 2; k < n; ++k)
    {
      f(ids[0], ids[k - 1], ids[k]);
    }
  }
  auto strips = vtk::TakeSmartPointer(data->GetStrips()->NewIterator());
  for (strips->GoToFirstCell(); !strips->IsDoneWithTraversal(); strips->GoToNextCell())
  {
    if (stopped())
    {
      return false;
    }
    strips->GetCurrentCell(n, ids);
    for (vtkIdType k = 2; k < n; ++k)
    {
      // Every other triangle of a strip is wound the other way round.
      if (k % 2 == 0)
      {
        f(ids[k - 2], ids[k - 1], ids[k]);
      }
      else
      {
        f(ids[k - 1], ids[k - 2], ids[k]);
      }
    }
  }
  return true;
}

bool trianglesOf(vtkPolyData* data, std::vector<glm::dvec3>& positions,
  std::vector<std::array<std::int64_t, 3>>& triangles, const std::atomic<bool>* stop = nullptr)
{
  // (Cell iterators and GetPoint into a buffer: safe beside the main thread's own reading.)
  vtkPoints* points = data->GetPoints();
  if (!points || points->GetNumberOfPoints() == 0)
  {
    return false;
  }
  positions.resize(static_cast<size_t>(points->GetNumberOfPoints()));
  for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i)
  {
    double p[3];
    points->GetPoint(i, p);
    positions[static_cast<size_t>(i)] = glm::dvec3(p[0], p[1], p[2]);
  }
  triangles.clear();
  return forEachTriangle(
    data,
    [&triangles](vtkIdType a, vtkIdType b, vtkIdType c) {
      triangles.push_back({ a, b, c });
    },
    stop);
}
} // namespace

std::shared_ptr<csmPreparedBlocks> csmPrepareBlocks(
  vtkPolyData* data, std::size_t perBlock, const std::atomic<bool>* stop)
{
  auto result = std::make_shared<csmPreparedBlocks>();
  vtkPoints* points = data->GetPoints();
  const vtkIdType pointCount = points ? points->GetNumberOfPoints() : 0;
  result->Points = pointCount;
  if (pointCount == 0 ||
    pointCount > static_cast<vtkIdType>(std::numeric_limits<std::uint32_t>::max()))
  {
    return result;
  }
  std::vector<std::uint32_t> corners;
  std::vector<glm::vec3> centroids;
  corners.reserve(3 * static_cast<size_t>(csmTriangleCount(data)));
  centroids.reserve(static_cast<size_t>(csmTriangleCount(data)));
  bool valid = true;
  std::vector<std::uint32_t> keptTriangle; // of each kept triangle, its index among all
  std::uint32_t visited = 0;
  valid = forEachTriangle(
            data,
            [&](vtkIdType a, vtkIdType b, vtkIdType c)
            {
              const std::uint32_t triangle = visited++;
              if (a < 0 || b < 0 || c < 0 || a >= pointCount || b >= pointCount || c >= pointCount)
              {
                valid = false;
                return;
              }
              if (a == b || b == c || c == a)
              {
                return; // covers no texel
              }
              keptTriangle.push_back(triangle);
              double pa[3], pb[3], pc[3];
              points->GetPoint(a, pa);
              points->GetPoint(b, pb);
              points->GetPoint(c, pc);
              corners.insert(corners.end(),
                { static_cast<std::uint32_t>(a), static_cast<std::uint32_t>(b),
                  static_cast<std::uint32_t>(c) });
              centroids.emplace_back(static_cast<float>((pa[0] + pb[0] + pc[0]) / 3.0),
                static_cast<float>((pa[1] + pb[1] + pc[1]) / 3.0),
                static_cast<float>((pa[2] + pb[2] + pc[2]) / 3.0));
            },
            stop) &&
    valid;
  if (!valid || centroids.empty())
  {
    return result;
  }
  csm::BlockOrder order = csm::orderIntoBlocks(centroids, perBlock, stop);
  std::vector<glm::vec3>().swap(centroids);
  if (order.blocks.empty() || (stop && stop->load()))
  {
    return result;
  }
  result->Corners.resize(corners.size());
  for (size_t i = 0; i < order.order.size(); ++i)
  {
    std::copy_n(corners.begin() + 3 * static_cast<std::ptrdiff_t>(order.order[i]), 3,
      result->Corners.begin() + 3 * static_cast<std::ptrdiff_t>(i));
  }
  std::vector<std::uint32_t>().swap(corners);
  if (order.blocks.size() < csmPreparedBlocks::kNoBlock)
  {
    result->BlockOf.assign(visited, csmPreparedBlocks::kNoBlock);
    for (size_t b = 0; b < order.blocks.size(); ++b)
    {
      const auto& [first, count] = order.blocks[b];
      for (size_t i = first; i < first + count; ++i)
      {
        result->BlockOf[keptTriangle[order.order[i]]] = static_cast<std::uint16_t>(b);
      }
    }
  }
  std::vector<std::uint32_t>().swap(keptTriangle);
  std::vector<std::uint32_t>().swap(order.order);
  result->Blocks = std::move(order.blocks);
  for (const auto& [first, count] : result->Blocks)
  {
    std::array<double, 6> box = { VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX, VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX,
      VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX };
    for (size_t i = 3 * first; i < 3 * (first + count); ++i)
    {
      double p[3];
      points->GetPoint(result->Corners[i], p);
      for (int k = 0; k < 3; ++k)
      {
        box[2 * k] = std::min(box[2 * k], p[k]);
        box[2 * k + 1] = std::max(box[2 * k + 1], p[k]);
      }
    }
    result->Bounds.push_back(box);
  }
  return result;
}

bool csmCellsKey::operator==(const csmCellsKey& other) const
{
  return this->Polys == other.Polys && this->Strips == other.Strips &&
    this->PolysTime == other.PolysTime && this->StripsTime == other.StripsTime &&
    this->PolyCount == other.PolyCount && this->StripCount == other.StripCount &&
    this->Points == other.Points && this->Digest == other.Digest;
}

bool csmCellsKey::SameCells(const csmCellsKey& other) const
{
  return this->PolyCount == other.PolyCount && this->StripCount == other.StripCount &&
    this->Points == other.Points && this->Digest == other.Digest;
}

namespace
{
/// A digest of an array's bytes (its values as stored), folded into `digest`.
void digestArray(vtkDataArray* array, std::uint64_t& digest)
{
  const size_t bytes = array ? static_cast<size_t>(array->GetNumberOfValues()) *
      static_cast<size_t>(array->GetDataTypeSize())
                             : 0;
  csm::digestBytes(bytes > 0 ? array->GetVoidPointer(0) : nullptr, bytes, digest);
}
}

csmCellsKey csmCellsOf(vtkPolyData* data)
{
  csmCellsKey key;
  vtkCellArray* polys = data->GetPolys();
  vtkCellArray* strips = data->GetStrips();
  key.Polys = polys;
  key.Strips = strips;
  key.PolysTime = polys ? polys->GetMTime() : 0;
  key.StripsTime = strips ? strips->GetMTime() : 0;
  key.PolyCount = polys ? polys->GetNumberOfCells() : 0;
  key.StripCount = strips ? strips->GetNumberOfCells() : 0;
  key.Points = data->GetNumberOfPoints();
  for (vtkCellArray* cells : { polys, strips })
  {
    if (cells)
    {
      digestArray(cells->GetOffsetsArray(), key.Digest);
      digestArray(cells->GetConnectivityArray(), key.Digest);
    }
  }
  return key;
}

bool csmBlockBounds(vtkPolyData* data, const std::vector<std::uint16_t>& blockOf,
  std::size_t blocks, std::vector<std::array<double, 6>>& bounds)
{
  vtkPoints* points = data->GetPoints();
  const vtkIdType pointCount = points ? points->GetNumberOfPoints() : 0;
  bounds.assign(blocks,
    { VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX, VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX, VTK_DOUBLE_MAX,
      -VTK_DOUBLE_MAX });
  size_t triangle = 0;
  bool valid = true;
  forEachTriangle(data,
    [&](vtkIdType a, vtkIdType b, vtkIdType c)
    {
      const size_t t = triangle++;
      if (!valid || t >= blockOf.size() || blockOf[t] >= blocks)
      {
        valid = valid && t < blockOf.size();
        return;
      }
      if (a < 0 || b < 0 || c < 0 || a >= pointCount || b >= pointCount || c >= pointCount)
      {
        valid = false;
        return;
      }
      std::array<double, 6>& box = bounds[blockOf[t]];
      for (const vtkIdType corner : { a, b, c })
      {
        double p[3];
        points->GetPoint(corner, p);
        if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
        {
          valid = false; // (prepared anew, as any mesh with a bad position)
          return;
        }
        for (int k = 0; k < 3; ++k)
        {
          box[2 * k] = std::min(box[2 * k], p[k]);
          box[2 * k + 1] = std::max(box[2 * k + 1], p[k]);
        }
      }
    });
  return valid && triangle == blockOf.size();
}

csm::SurfaceClosure csmClassifyPolyData(
  vtkPolyData* data, const std::atomic<bool>* stop, csm::SurfaceTopology* topology)
{
  std::vector<glm::dvec3> positions;
  std::vector<std::array<std::int64_t, 3>> triangles;
  return trianglesOf(data, positions, triangles, stop)
    ? csm::classifySurface(positions, triangles, stop, topology)
    : csm::SurfaceClosure();
}
