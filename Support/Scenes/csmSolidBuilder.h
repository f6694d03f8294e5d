// SPDX-License-Identifier: BSD-3-Clause
// Closed surfaces built triangle by triangle, each wound by the outward direction it is given:
// the bracket of csmScenes and the parts of csmPartFamily.
#pragma once

#include "vtkCellArray.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataNormals.h"
#include "vtkSmartPointer.h"

#include <array>
#include <cmath>
#include <map>
#include <vector>

namespace csmScenes
{
/// Triangles of one closed surface, its points welded by position; each triangle is wound so
/// that its normal points along the outward direction it is given.
class SolidBuilder
{
public:
  using Vec = std::array<double, 3>;

  vtkIdType Point(const Vec& p)
  {
    const std::array<long long, 3> key = { std::llround(p[0] * 1e9), std::llround(p[1] * 1e9),
      std::llround(p[2] * 1e9) };
    const auto found = this->Ids.find(key);
    if (found != this->Ids.end())
      return found->second;
    const vtkIdType id = this->Points->InsertNextPoint(p.data());
    this->Ids.emplace(key, id);
    return id;
  }

  void Triangle(const Vec& a, const Vec& b, const Vec& c, const Vec& outward)
  {
    const Vec u = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
    const Vec v = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
    const Vec n = { u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
      u[0] * v[1] - u[1] * v[0] };
    const bool flip = vtkMath::Dot(n.data(), outward.data()) < 0.0;
    const vtkIdType ids[3] = { this->Point(a), this->Point(flip ? c : b),
      this->Point(flip ? b : c) };
    this->Polys->InsertNextCell(3, ids);
  }

  void Quad(const Vec& a, const Vec& b, const Vec& c, const Vec& d, const Vec& outward)
  {
    this->Triangle(a, b, c, outward);
    this->Triangle(a, c, d, outward);
  }

  /// A rectangle with a round hole: corners c00, c10, c11, c01 (counter-clockwise seen from
  /// outward), the hole's points around it in the same order; each corner fans to its quarter of
  /// the hole, so that the rectangle's edges keep only their corners (no T-junction with the
  /// faces beside it).
  void PlateWithHole(const Vec corners[4], const std::vector<Vec>& hole, const Vec& outward)
  {
    const size_t n = hole.size(), quarter = n / 4;
    for (size_t q = 0; q < 4; ++q)
    {
      for (size_t k = q * quarter; k < (q + 1) * quarter; ++k)
        this->Triangle(corners[q], hole[k], hole[(k + 1) % n], outward);
      this->Triangle(corners[q], corners[(q + 1) % 4], hole[((q + 1) * quarter) % n], outward);
    }
  }

  vtkSmartPointer<vtkPolyData> Finish()
  {
    vtkNew<vtkPolyData> data;
    data->SetPoints(this->Points);
    data->SetPolys(this->Polys);
    vtkNew<vtkPolyDataNormals> normals;
    normals->SetInputData(data);
    normals->SetFeatureAngle(30.0);
    normals->SplittingOn();
    normals->ConsistencyOff();
    normals->AutoOrientNormalsOff();
    normals->Update();
    return normals->GetOutput();
  }

private:
  std::map<std::array<long long, 3>, vtkIdType> Ids;
  vtkNew<vtkPoints> Points;
  vtkNew<vtkCellArray> Polys;
};
} // namespace csmScenes
