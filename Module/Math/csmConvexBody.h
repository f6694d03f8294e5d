// SPDX-License-Identifier: BSD-3-Clause
// A convex polyhedron as a list of planar faces, clipped by planes (the body B of Barroso & Celes
// 2007, §2.3). Pure math: no VTK, no GL.
#pragma once

#include <glm/vec3.hpp>

#include <array>
#include <vector>

namespace csm
{

/// The half-space dot(normal, p) + offset >= 0.
struct Plane
{
  glm::dvec3 normal{ 0.0, 0.0, 1.0 };
  double offset = 0.0;
};

class ConvexBody
{
public:
  using Polygon = std::vector<glm::dvec3>;

  /// A hexahedron from its 8 corners: 4 of the near face then 4 of the far face, each in the
  /// same winding (a view-frustum partition or a box).
  static ConvexBody hexahedron(const std::array<glm::dvec3, 8>& corners);

  /// Keeps the part of the body inside the half-space. Points within `epsilon` of the plane count
  /// as inside. The cut is closed with a new face.
  void clip(const Plane& plane, double epsilon);

  bool empty() const { return this->Faces.empty(); }

  /// The distinct vertices (duplicates closer than `epsilon` merged).
  std::vector<glm::dvec3> vertices(double epsilon) const;

  const std::vector<Polygon>& faces() const { return this->Faces; }

private:
  std::vector<Polygon> Faces;
};

/// The six half-spaces of an axis-aligned box given by its corners (min <= max).
std::array<Plane, 6> boxPlanes(const glm::dvec3& boxMin, const glm::dvec3& boxMax);

} // namespace csm
