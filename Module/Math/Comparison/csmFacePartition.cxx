// SPDX-License-Identifier: BSD-3-Clause
#include "csmFacePartition.h"

#include "csmAliasing.h"
#include "csmConvexBody.h"
#include "csmGeometry.h"
#include "csmSetup.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace csm
{
namespace
{
/// As in computeShadowSetup: beyond n' = kOrthoRatio * (light-space depth of the body) the map
/// is made orthographic (< 0.2 % in storage, and no cancellation in t = A - B/z').
constexpr double kOrthoRatio = 1.0e3;
/// A face whose unit normal has a smaller component along the light is seen edge-on: its
/// partition has (relatively) no volume and gets no map.
constexpr double kEdgeOn = 1e-12;

/// The perspective view volume with the eye at the origin (camera-centred world space).
struct Pyramid
{
  glm::dvec3 view, up, right; // orthonormal
  /// The side edges at unit depth, counter-clockwise seen from the eye: (-,-), (+,-), (+,+),
  /// (-,+) in (right, up). Face i lies between edges i and i + 1 (FrustumFace order).
  std::array<glm::dvec3, 4> edges;

  glm::dvec3 edgePoint(int i, double vsDepth) const { return this->edges[i & 3] * vsDepth; }
};

Pyramid pyramid(const Camera& camera)
{
  Pyramid p;
  p.view = glm::normalize(camera.wsDirection);
  glm::dvec3 up = camera.wsViewUp - glm::dot(camera.wsViewUp, p.view) * p.view;
  if (!(glm::length(up) > 1e-9))
  {
    // As computeShadowSetup: any perpendicular when view-up is parallel to the view.
    const glm::dvec3 helper = std::abs(p.view.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    up = glm::cross(p.view, helper);
  }
  p.up = glm::normalize(up);
  p.right = glm::cross(p.view, p.up);
  const double tanY = std::tan(0.5 * camera.fovyDeg * kDegree);
  const double tanX = tanY * camera.aspect;
  const double signX[4] = { -1, 1, 1, -1 };
  const double signY[4] = { -1, -1, 1, 1 };
  for (int i = 0; i < 4; ++i)
  {
    p.edges[i] = p.view + p.right * (signX[i] * tanX) + p.up * (signY[i] * tanY);
  }
  return p;
}

/// The frustum [d0, d1] as a hexahedron (near corners, then far corners, same winding).
ConvexBody frustum(const Pyramid& p, double d0, double d1)
{
  std::array<glm::dvec3, 8> corners;
  for (int i = 0; i < 4; ++i)
  {
    corners[i] = p.edgePoint(i, d0);
    corners[4 + i] = p.edgePoint(i, d1);
  }
  return ConvexBody::hexahedron(corners);
}

/// The plane through the eye holding the side edge `edge` and the light direction y, facing the
/// side where `inside` lies (Lloyd et al. 2006, §5.1: the planes through the face edges and the
/// light).
Plane wedgePlane(const glm::dvec3& edge, const glm::dvec3& y, const glm::dvec3& inside)
{
  glm::dvec3 normal = glm::normalize(glm::cross(edge, y));
  if (glm::dot(normal, inside) < 0.0)
  {
    normal = -normal;
  }
  return { normal, 0.0 };
}

/// The plane through the face's edge at view depth d (from edgePoint(a, d) to edgePoint(b, d))
/// and the light direction y, facing the eye (eyeSide) or away from it.
Plane splitPlane(const Pyramid& p, int a, int b, double d, const glm::dvec3& y, bool eyeSide)
{
  const glm::dvec3 normal = glm::normalize(glm::cross(p.edges[b] - p.edges[a], y));
  Plane plane{ normal, -glm::dot(normal, p.edgePoint(a, d)) };
  // The eye (the origin) has the value `offset`: positive on the kept side for eyeSide.
  if ((plane.offset < 0.0) == eyeSide)
  {
    plane.normal = -plane.normal;
    plane.offset = -plane.offset;
  }
  return plane;
}

/// A piece's points in its light space, with a minimum thickness on each axis (as
/// computeShadowSetup's lightSpacePoints) so that a flat sliver keeps a finite focus.
std::vector<glm::dvec3> lightSpacePoints(const std::vector<glm::dvec3>& cwsBody,
  const glm::dvec3& x, const glm::dvec3& y, const glm::dvec3& z, double vsNear)
{
  std::vector<glm::dvec3> ls;
  glm::dvec3 lo(kInf), hi(-kInf);
  for (const glm::dvec3& p : cwsBody)
  {
    ls.emplace_back(glm::dot(p, x), glm::dot(p, y), glm::dot(p, z));
    lo = glm::min(lo, ls.back());
    hi = glm::max(hi, ls.back());
  }
  const glm::dvec3 size = hi - lo;
  const double minSize = 1e-6 * std::max({ size.x, size.y, size.z, vsNear });
  const glm::dvec3 centre = 0.5 * (lo + hi);
  for (int axis = 0; axis < 3; ++axis)
  {
    if (size[axis] < minSize)
    {
      glm::dvec3 offset(0.0);
      offset[axis] = minSize;
      ls.push_back(centre - offset);
      ls.push_back(centre + offset);
    }
  }
  return ls;
}

glm::dmat4 lightView(
  const glm::dvec3& x, const glm::dvec3& y, const glm::dvec3& z, const glm::dvec3& wsEye)
{
  glm::dmat4 m(1.0); // rows x, y, z: world -> light space with the eye at the origin
  for (int c = 0; c < 3; ++c)
  {
    m[c] = glm::dvec4(x[c], y[c], z[c], 0.0);
  }
  m[3] = glm::dvec4(-glm::dot(x, wsEye), -glm::dot(y, wsEye), -glm::dot(z, wsEye), 1.0);
  return m;
}

/// Why computeFacePartitions cannot partition (empty: it can).
std::string inputError(
  const Camera& camera, const glm::dvec3& wsLightDirection, const FacePartitionSettings& settings)
{
  std::string message = cameraError(camera);
  if (message.empty())
  {
    message = lightDirectionError(wsLightDirection);
  }
  if (message.empty() && camera.parallel)
  {
    message = "face partitioning needs a perspective camera (a parallel view has no faces "
              "that widen with depth)";
  }
  if (message.empty() && (settings.k < 1 || settings.k > kMaxSplits))
  {
    message = "number of z-partitions per face must be in [1, 64]";
  }
  return message;
}

/// What the pieces of one side face share: the face's side edges (a, b), its light space (x, y,
/// z: Lloyd et al. 2006, §5.1) and the wedge planes through its side edges and the light.
struct Face
{
  int index = 0;
  int a = 0, b = 1;
  glm::dvec3 x{ 0.0 }, y{ 0.0 }, z{ 0.0 };
  Plane wedgeA, wedgeB;
  glm::dmat4 wsToLs{ 1.0 };
};

/// The side face `index` when the folded light enters through it (false: it does not, or sees
/// it edge-on).
bool enteredFace(const Pyramid& p, int index, const glm::dvec3& y, const glm::dvec3& yFolded,
  const glm::dvec3& wsEye, Face& face)
{
  face.index = index;
  face.a = index;
  face.b = (index + 1) & 3;
  const glm::dvec3& ea = p.edges[face.a];
  const glm::dvec3& eb = p.edges[face.b];
  glm::dvec3 normal = glm::normalize(glm::cross(ea, eb));
  if (glm::dot(normal, p.view) > 0.0)
  {
    normal = -normal; // outward: the pyramid widens with depth
  }
  if (!(glm::dot(normal, yFolded) < -kEdgeOn))
  {
    return false; // the folded light does not enter through this face (or sees it edge-on)
  }
  // Lloyd et al. 2006, §5.1: the bisector of the side edges projected along the light.
  const glm::dvec3 eaProjected = glm::normalize(ea - glm::dot(ea, y) * y);
  const glm::dvec3 ebProjected = glm::normalize(eb - glm::dot(eb, y) * y);
  face.y = y;
  face.z = glm::normalize(eaProjected + ebProjected);
  face.x = glm::cross(y, face.z);
  face.wedgeA = wedgePlane(ea, y, eb);
  face.wedgeB = wedgePlane(eb, y, ea);
  face.wsToLs = lightView(face.x, face.y, face.z, wsEye);
  return true;
}

/// Piece i of the face (between splits[i] and splits[i + 1]): its half-spaces and its body
/// (camera-centred world space). False when it has no volume.
bool cutPiece(const Pyramid& p, const Face& face, const std::vector<double>& splits, int i,
  double n, double f, double epsilon, std::vector<Plane>& cuts, std::vector<glm::dvec3>& cwsBody)
{
  cuts = { face.wedgeA, face.wedgeB };
  if (i > 0)
  {
    cuts.push_back(splitPlane(p, face.a, face.b, splits[i], face.y, false));
  }
  if (i + 2 < static_cast<int>(splits.size()))
  {
    cuts.push_back(splitPlane(p, face.a, face.b, splits[i + 1], face.y, true));
  }
  ConvexBody body = frustum(p, n, f);
  for (const Plane& cut : cuts)
  {
    body.clip(cut, epsilon);
  }
  cwsBody = body.vertices(epsilon);
  // No volume: cannot happen for a face the light enters, but be safe.
  return cwsBody.size() >= 4;
}

/// The warped map of a piece between the face's split depths s0 and s1 (its body cwsBody, the
/// near depth n): matrix, n', gamma_lim and the aliasing maxima (map.wsBody already set).
void warpPiece(const Pyramid& p, const Face& face, const Camera& camera,
  const std::vector<glm::dvec3>& cwsBody, double s0, double s1, double n, WarpMode warpMode,
  Cascade& map)
{
  const int a = face.a, b = face.b;
  const glm::dvec3 &x = face.x, &z = face.z;
  const glm::dvec3& ea = p.edges[a];
  const glm::dvec3& eb = p.edges[b];
  // The face's trapezoid of this piece seen from the light: n, f its nearest and farthest
  // ls z from the eye, a, b half its widths along ls x at s_i and s_i+1.
  PartitionShape shape;
  shape.n = std::min(glm::dot(p.edgePoint(a, s0), z), glm::dot(p.edgePoint(b, s0), z));
  shape.f = std::max(glm::dot(p.edgePoint(a, s1), z), glm::dot(p.edgePoint(b, s1), z));
  shape.a = 0.5 * std::abs(glm::dot(eb - ea, x)) * s0;
  shape.b = 0.5 * std::abs(glm::dot(eb - ea, x)) * s1;
  map.gammaLimDeg = gammaLim(shape) / kDegree;

  const std::vector<glm::dvec3> lsPoints = lightSpacePoints(cwsBody, x, face.y, z, n);
  double lsZMin = kInf, lsZMax = -kInf;
  for (const glm::dvec3& q : lsPoints)
  {
    lsZMin = std::min(lsZMin, q.z);
    lsZMax = std::max(lsZMax, q.z);
  }
  const double lsDepth = lsZMax - lsZMin;
  // Seen from the light the piece is a trapezoid opening along z, as the frustum is for an
  // overhead light: the warp mode's n' at gamma = 90 deg (Lloyd et al. 2006, §5.1 fits LiSPSM).
  double warp = shape.n > 0.0 ? nPrime(warpMode, 0.5 * kPi, shape) : kInf;
  if (!(warp <= kOrthoRatio * lsDepth))
  {
    warp = kInf;
  }
  warp = std::max(warp, 1e-9 * lsDepth);
  map.nPrime = warp;
  // The centre lies n' before the face's near edge (Lloyd et al. 2006, §4.1: n' is measured
  // to the near plane of the trapezoid) when that is outside the body, else n' before the
  // body (PSM's n' = n with the near face stretched over).
  const double zNear = shape.n - warp < lsZMin ? shape.n : lsZMin;
  const glm::dmat4 lsToWarped = warpMatrix(warp, zNear);
  map.wsToClip = focusMatrix(lsPoints, lsToWarped) * lsToWarped * face.wsToLs;

  // Lloyd et al. 2006, §4.4 and Eq. 12: maxima over the vertices, along the map's own axes.
  for (const glm::dvec3& q : map.wsBody)
  {
    const Aliasing m = aliasingAt(map.wsToClip, camera, x, z, q);
    map.Mx = std::max(map.Mx, m.mx);
    map.Mz = std::max(map.Mz, m.mz);
  }
  map.storage = map.Mx * map.Mz / camera.aspect;
}

/// Piece i of the face as a FacePartition (false: it has no volume).
bool facePiece(const Pyramid& p, const Face& face, const Camera& camera,
  const std::vector<double>& splits, int i, double epsilon, WarpMode warpMode, FacePartition& part)
{
  std::vector<Plane> cuts;
  std::vector<glm::dvec3> cwsBody;
  if (!cutPiece(p, face, splits, i, camera.vsNear, camera.vsFar, epsilon, cuts, cwsBody))
  {
    return false;
  }
  part.face = static_cast<FrustumFace>(face.index);
  part.zIndex = i;
  part.wsMapX = face.x;
  part.wsMapZ = face.z;
  for (const Plane& cut : cuts)
  {
    // From camera-centred to world space: dot(N, p - eye) + d = dot(N, p) + d - dot(N, eye).
    part.wsPlanes.emplace_back(cut.normal, cut.offset - glm::dot(cut.normal, camera.wsPosition));
  }
  Cascade& map = part.map;
  map.vsNear = splits[i];
  map.vsFar = splits[i + 1];
  for (const glm::dvec3& q : cwsBody)
  {
    map.wsBody.push_back(q + camera.wsPosition);
  }
  warpPiece(p, face, camera, cwsBody, map.vsNear, map.vsFar, camera.vsNear, warpMode, map);
  return true;
}
} // namespace

FacePartitioning computeFacePartitions(
  const Camera& camera, const glm::dvec3& wsLightDirection, const FacePartitionSettings& settings)
{
  FacePartitioning result;
  result.message = inputError(camera, wsLightDirection, settings);
  if (!result.message.empty())
  {
    result.status = Status::InvalidInput;
    return result;
  }

  const Pyramid p = pyramid(camera);
  const glm::dvec3 y = glm::normalize(wsLightDirection); // the light's direction of travel
  result.gammaDeg = std::atan2(glm::length(glm::cross(p.view, y)), glm::dot(p.view, y)) / kDegree;
  // Folded: travelling away from the viewer; its entry faces are the ones to partition by.
  const glm::dvec3 yFolded = glm::dot(p.view, y) >= 0.0 ? y : -y;
  const double n = camera.vsNear;
  const double f = camera.vsFar;
  SplitParameters split;
  split.scheme = SplitScheme::Log; // Lloyd et al. 2006, Eq. 15-16
  split.k = settings.k;
  result.splits = splitDepths(split, n, f, 0.0);
  const double epsilon = 1e-12 * (f + glm::length(p.edgePoint(2, f)));

  for (int index = 0; index < 4; ++index)
  {
    Face face;
    if (!enteredFace(p, index, y, yFolded, camera.wsPosition, face))
    {
      continue;
    }
    for (int i = 0; i + 1 < static_cast<int>(result.splits.size()); ++i)
    {
      FacePartition part;
      if (facePiece(p, face, camera, result.splits, i, epsilon, settings.warp, part))
      {
        result.storageTotal += part.map.storage;
        result.partitions.push_back(std::move(part));
      }
    }
  }

  result.storageOptimal = std::log(f / n) / (2.0 * std::tan(0.5 * camera.fovyDeg * kDegree));
  if (result.partitions.empty())
  {
    // Some side face always faces a light that travels away from the viewer.
    result.status = Status::InvalidInput;
    result.message = "no face of the view frustum faces the light";
    return result;
  }
  result.status = Status::Ok;
  return result;
}

int partitionAt(const FacePartitioning& partitioning, const glm::dvec3& wsPoint)
{
  int best = -1;
  double bestDistance = -kInf;
  for (size_t i = 0; i < partitioning.partitions.size(); ++i)
  {
    double distance = kInf;
    for (const glm::dvec4& plane : partitioning.partitions[i].wsPlanes)
    {
      distance = std::min(distance, glm::dot(glm::dvec3(plane), wsPoint) + plane.w);
    }
    if (distance > bestDistance)
    {
      best = static_cast<int>(i);
      bestDistance = distance;
    }
  }
  return best;
}

const char* toString(FrustumFace face)
{
  switch (face)
  {
    case FrustumFace::Bottom:
      return "bottom";
    case FrustumFace::Right:
      return "right";
    case FrustumFace::Top:
      return "top";
    case FrustumFace::Left:
      return "left";
  }
  return "?";
}

} // namespace csm
