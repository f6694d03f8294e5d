// SPDX-License-Identifier: BSD-3-Clause
#include "csmConvexBody.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <utility>

namespace csm
{

ConvexBody ConvexBody::hexahedron(const std::array<glm::dvec3, 8>& c)
{
  ConvexBody body;
  body.Faces = {
    { c[0], c[1], c[2], c[3] }, // near
    { c[4], c[7], c[6], c[5] }, // far
    { c[0], c[4], c[5], c[1] },
    { c[1], c[5], c[6], c[2] },
    { c[2], c[6], c[7], c[3] },
    { c[3], c[7], c[4], c[0] },
  };
  return body;
}

namespace
{
/// The face that closes a cut: the points of the body on the plane, ordered around their
/// centroid in the plane, those within epsilon of the one before dropped.
void closeCut(
  const Plane& plane, double epsilon, const ConvexBody::Polygon& cut, ConvexBody::Polygon& face)
{
  glm::dvec3 centre(0.0);
  for (const glm::dvec3& p : cut)
  {
    centre += p;
  }
  centre /= double(cut.size());
  const glm::dvec3 n = glm::normalize(plane.normal);
  const glm::dvec3 helper = std::abs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  const glm::dvec3 u = glm::normalize(glm::cross(n, helper));
  const glm::dvec3 v = glm::cross(n, u);
  // (Each point's angle computed once, not in every comparison.)
  thread_local std::vector<std::pair<double, glm::dvec3>> around;
  around.clear();
  for (const glm::dvec3& p : cut)
  {
    around.emplace_back(std::atan2(glm::dot(p - centre, v), glm::dot(p - centre, u)), p);
  }
  std::sort(around.begin(), around.end(),
    [](const std::pair<double, glm::dvec3>& a, const std::pair<double, glm::dvec3>& b)
    { return a.first < b.first; });
  for (const auto& angleAndPoint : around)
  {
    const glm::dvec3& p = angleAndPoint.second;
    if (face.empty() || glm::length(p - face.back()) > epsilon)
    {
      face.push_back(p);
    }
  }
}
} // namespace

void ConvexBody::clip(const Plane& plane, double epsilon)
{
  // A plane with every vertex more than epsilon inside leaves the body as it is, one with every
  // vertex more than epsilon outside leaves nothing: the faces below would come out the same,
  // at the cost of building every face again (a body is clipped by many planes that cut it
  // nowhere: a receiver box's planes against a partition far from its walls).
  bool allInside = true, allOutside = true;
  for (const Polygon& face : this->Faces)
  {
    for (const glm::dvec3& p : face)
    {
      const double d = glm::dot(plane.normal, p) + plane.offset;
      allInside = allInside && d > epsilon;
      allOutside = allOutside && d < -epsilon;
    }
  }
  if (allInside)
  {
    return;
  }
  if (allOutside)
  {
    this->Faces.clear();
    return;
  }
  // The clipped faces are built in buffers kept from call to call (this thread's), and swapped
  // into the body: a plan clips thousands of small bodies a frame, and allocating each face
  // anew cost more than the arithmetic.
  thread_local std::vector<Polygon> kept;
  thread_local Polygon cut; // points of the body on the plane: the new face
  size_t used = 0;
  auto nextFace = [&]() -> Polygon&
  {
    if (used == kept.size())
    {
      kept.emplace_back();
    }
    Polygon& face = kept[used++];
    face.clear();
    return face;
  };
  cut.clear();
  for (const Polygon& face : this->Faces)
  {
    Polygon& out = nextFace();
    const size_t count = face.size();
    for (size_t i = 0; i < count; ++i)
    {
      const glm::dvec3& p = face[i];
      const glm::dvec3& q = face[(i + 1) % count];
      const double dp = glm::dot(plane.normal, p) + plane.offset;
      const double dq = glm::dot(plane.normal, q) + plane.offset;
      const bool pIn = dp >= -epsilon;
      const bool qIn = dq >= -epsilon;
      if (pIn)
      {
        out.push_back(p);
        if (std::abs(dp) <= epsilon)
        {
          cut.push_back(p);
        }
      }
      if (pIn != qIn && std::abs(dp) > epsilon && std::abs(dq) > epsilon)
      {
        const glm::dvec3 x = p + (q - p) * (dp / (dp - dq));
        out.push_back(x);
        cut.push_back(x);
      }
    }
    if (out.size() < 3)
    {
      --used; // (dropped: its buffer serves the next face)
    }
  }
  if (cut.size() >= 3)
  {
    closeCut(plane, epsilon, cut, nextFace());
    if (kept[used - 1].size() < 3)
    {
      --used;
    }
  }
  // The body takes the new faces; its old faces' buffers stay for the next clip.
  this->Faces.resize(used);
  for (size_t i = 0; i < used; ++i)
  {
    std::swap(this->Faces[i], kept[i]);
  }
}

std::vector<glm::dvec3> ConvexBody::vertices(double epsilon) const
{
  std::vector<glm::dvec3> result;
  for (const Polygon& face : this->Faces)
  {
    for (const glm::dvec3& p : face)
    {
      const bool known = std::any_of(result.begin(), result.end(),
        [&](const glm::dvec3& q) { return glm::length(p - q) <= epsilon; });
      if (!known)
      {
        result.push_back(p);
      }
    }
  }
  return result;
}

std::array<Plane, 6> boxPlanes(const glm::dvec3& lo, const glm::dvec3& hi)
{
  return { {
    { { 1, 0, 0 }, -lo.x },
    { { -1, 0, 0 }, hi.x },
    { { 0, 1, 0 }, -lo.y },
    { { 0, -1, 0 }, hi.y },
    { { 0, 0, 1 }, -lo.z },
    { { 0, 0, -1 }, hi.z },
  } };
}

} // namespace csm
