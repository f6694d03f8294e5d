// SPDX-License-Identifier: BSD-3-Clause
// Closed surfaces: the meshes whose shadow maps may hold only the faces turned away from the light.
#include "csmClosedSurface.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/matrix.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

namespace
{
using Triangles = std::vector<std::array<std::int64_t, 3>>;

/// A box [lo, hi]^3 as 12 triangles wound counter-clockwise seen from outside. With splitCorners,
/// every face has its own four points (as vtkPolyDataNormals splits them at sharp edges).
void box(double lo, double hi, bool splitCorners, std::vector<glm::dvec3>& p, Triangles& t)
{
  static const int faces[6][4] = { { 0, 2, 3, 1 }, { 4, 5, 7, 6 }, { 0, 1, 5, 4 }, { 2, 6, 7, 3 },
    { 0, 4, 6, 2 }, { 1, 3, 7, 5 } };
  const auto corner = [&](int i)
  { return glm::dvec3((i & 1) ? hi : lo, (i & 2) ? hi : lo, (i & 4) ? hi : lo); };
  const std::int64_t base = static_cast<std::int64_t>(p.size());
  if (!splitCorners)
  {
    for (int i = 0; i < 8; ++i)
      p.push_back(corner(i));
  }
  for (const auto& f : faces)
  {
    std::int64_t id[4];
    for (int k = 0; k < 4; ++k)
    {
      if (splitCorners)
      {
        id[k] = static_cast<std::int64_t>(p.size());
        p.push_back(corner(f[k]));
      }
      else
      {
        id[k] = base + f[k];
      }
    }
    t.push_back({ id[0], id[1], id[2] });
    t.push_back({ id[0], id[2], id[3] });
  }
}
}

TEST(ClosedSurface, ABoxIsClosedWithItsVolume)
{
  std::vector<glm::dvec3> p;
  Triangles t;
  box(-1.0, 2.0, false, p, t);
  const csm::SurfaceClosure c = csm::classifySurface(p, t);
  EXPECT_TRUE(c.closed);
  EXPECT_NEAR(std::abs(c.volume), 27.0, 1e-12);
}

TEST(ClosedSurface, PointsSplitAtEdgesStillClose)
{
  std::vector<glm::dvec3> p;
  Triangles t;
  box(0.0, 1.0, true, p, t); // -0 and +0 corners too: lo = 0.0 below
  ASSERT_EQ(p.size(), 24u);
  p[0].x = -0.0;
  EXPECT_TRUE(csm::classifySurface(p, t).closed);
}

TEST(ClosedSurface, OrientationGivesTheVolumeSign)
{
  std::vector<glm::dvec3> p;
  Triangles t;
  box(0.0, 1.0, false, p, t);
  const double outward = csm::classifySurface(p, t).volume;
  for (auto& tri : t)
    std::swap(tri[1], tri[2]);
  const double inward = csm::classifySurface(p, t).volume;
  EXPECT_GT(outward, 0.0); // counter-clockwise seen from outside: positive
  EXPECT_NEAR(outward, -inward, 1e-12);
  EXPECT_NEAR(std::abs(outward), 1.0, 1e-12);
}

TEST(ClosedSurface, FarFromTheOriginTheVolumeKeepsItsDigits)
{
  std::vector<glm::dvec3> p;
  Triangles t;
  box(0.0, 1.0, false, p, t);
  for (auto& q : p)
    q += glm::dvec3(1e7, -3e6, 2e7);
  const csm::SurfaceClosure c = csm::classifySurface(p, t);
  EXPECT_TRUE(c.closed);
  EXPECT_NEAR(std::abs(c.volume), 1.0, 1e-6);
}

TEST(ClosedSurface, AMissingFaceASheetAndAFlippedTriangleAreOpen)
{
  std::vector<glm::dvec3> p;
  Triangles t;
  box(0.0, 1.0, false, p, t);
  Triangles missing(t.begin(), t.end() - 2);
  EXPECT_FALSE(csm::classifySurface(p, missing).closed);
  Triangles sheet(t.begin(), t.begin() + 2);
  EXPECT_FALSE(csm::classifySurface(p, sheet).closed);
  Triangles flipped = t;
  std::swap(flipped[5][1], flipped[5][2]);
  EXPECT_FALSE(csm::classifySurface(p, flipped).closed);
  // A sheet with both windings (a double-sided plate, a wall drawn as both its sides) has an
  // empty boundary but no thickness: not a solid (its exit layer would be the plate itself, at
  // the depth of its lit side: a tie under grazing light). A box 1e-4 thick is one.
  Triangles twoSided = sheet;
  for (auto tri : sheet)
  {
    std::swap(tri[1], tri[2]);
    twoSided.push_back(tri);
  }
  EXPECT_FALSE(csm::classifySurface(p, twoSided).closed);
  std::vector<glm::dvec3> q;
  Triangles thin;
  box(0.0, 1.0, false, q, thin);
  for (glm::dvec3& corner : q)
  {
    corner.z *= 1e-4; // 1 x 1 x 1e-4: thickness 1e-4 of a size of 1.4
  }
  EXPECT_TRUE(csm::classifySurface(q, thin).closed);
  // The box and, apart from it, the plate with both windings: balanced edges and the box's
  // volume, but no solid at the plate.
  std::vector<glm::dvec3> r = p;
  Triangles boxAndPlate = t;
  box(2.0, 3.0, false, r, boxAndPlate); // (the plate: this box's first face, both ways)
  boxAndPlate.resize(t.size());
  const Triangles plate(twoSided);
  for (auto tri : plate)
  {
    for (auto& i : tri)
    {
      i += 8; // the second box's corners
    }
    boxAndPlate.push_back(tri);
  }
  EXPECT_FALSE(csm::classifySurface(r, boxAndPlate).closed);
  boxAndPlate.resize(t.size());
  EXPECT_TRUE(csm::classifySurface(r, boxAndPlate).closed); // (the box alone)
  // The plate's back triangulated along its other diagonal (its quad 0 2 3 1 reversed as 1 3 2 0,
  // fanned from its first corner): no two triangles on the same corners, the whole mesh thick,
  // but the plate is a part that encloses nothing.
  const Triangles front(sheet);
  const Triangles back = { { 1, 3, 2 }, { 1, 2, 0 } };
  for (const Triangles& side : { front, back })
  {
    for (auto tri : side)
    {
      for (auto& i : tri)
      {
        i += 8;
      }
      boxAndPlate.push_back(tri);
    }
  }
  EXPECT_FALSE(csm::classifySurface(r, boxAndPlate).closed);
  csm::SurfaceTopology topology;
  EXPECT_FALSE(csm::classifySurface(r, boxAndPlate, nullptr, &topology).closed);
  for (glm::dvec3& corner : r)
  {
    corner.y += 0.5; // the same welds and triangles: the parts come from the topology kept
  }
  EXPECT_FALSE(csm::classifySurface(r, boxAndPlate, nullptr, &topology).closed);
  boxAndPlate.resize(t.size());
  EXPECT_TRUE(csm::classifySurface(r, boxAndPlate, nullptr, &topology).closed);
  EXPECT_TRUE(csm::classifySurface(r, boxAndPlate, nullptr, &topology).closed); // (kept)
}

TEST(ClosedSurface, TwoBoxesSharingAnEdgeAndDegenerateTrianglesStayClosed)
{
  std::vector<glm::dvec3> p;
  Triangles t;
  box(0.0, 1.0, false, p, t);
  box(1.0, 2.0, true, p, t); // touches the first box at the corner (1,1,1)
  t.push_back({ 0, 0, 3 });  // degenerate: ignored
  t.push_back({ 1, 8 + 1, 1 });
  EXPECT_TRUE(csm::classifySurface(p, t).closed);
}

TEST(ClosedSurface, BadInputIsOpen)
{
  std::vector<glm::dvec3> p;
  Triangles t;
  EXPECT_FALSE(csm::classifySurface(p, t).closed); // empty
  box(0.0, 1.0, false, p, t);
  Triangles outOfRange = t;
  outOfRange[3][2] = 99;
  EXPECT_FALSE(csm::classifySurface(p, outOfRange).closed);
  outOfRange[3][2] = -1;
  EXPECT_FALSE(csm::classifySurface(p, outOfRange).closed);
  std::vector<glm::dvec3> nan = p;
  nan[2].y = std::numeric_limits<double>::quiet_NaN();
  const csm::SurfaceClosure c = csm::classifySurface(nan, t);
  EXPECT_FALSE(c.closed);
  EXPECT_EQ(c.volume, 0.0);
  Triangles degenerate = { { 0, 0, 1 }, { 2, 2, 2 } };
  EXPECT_FALSE(csm::classifySurface(p, degenerate).closed);
}

// Which meshes cannot shadow themselves: planes, and closed convex solids.
TEST(ClosedSurface, PlanesAndConvexSolidsCannotShadowThemselves)
{
  {
    std::vector<glm::dvec3> p;
    Triangles t;
    box(-1.0, 2.0, true, p, t);
    const csm::SurfaceClosure c = csm::classifySurface(p, t);
    EXPECT_TRUE(c.closed);
    EXPECT_TRUE(c.convex);
    EXPECT_FALSE(c.planar);
    EXPECT_FALSE(c.canShadowItself());
  }
  {
    // Two disjoint boxes in one mesh: closed, not convex (one may shadow the other).
    std::vector<glm::dvec3> p;
    Triangles t;
    box(0.0, 1.0, false, p, t);
    box(2.0, 3.0, false, p, t);
    const csm::SurfaceClosure c = csm::classifySurface(p, t);
    EXPECT_TRUE(c.closed);
    EXPECT_FALSE(c.convex);
    EXPECT_TRUE(c.canShadowItself());
  }
  {
    // A box with one face pushed in (a dent): closed, not convex.
    std::vector<glm::dvec3> p;
    Triangles t;
    box(0.0, 1.0, false, p, t);
    p.push_back({ 0.5, 0.5, 0.6 }); // a point inside, under the top face z = 1
    const std::int64_t centre = static_cast<std::int64_t>(p.size()) - 1;
    // Replace the top face (corners 4 5 7 6, wound { 4, 5, 7 }, { 4, 7, 6 }) by a fan to the
    // centre.
    t.erase(std::remove_if(t.begin(), t.end(),
              [](const std::array<std::int64_t, 3>& tri)
              { return tri[0] == 4 && (tri[1] == 5 || tri[1] == 7); }),
      t.end());
    t.push_back({ 4, 5, centre });
    t.push_back({ 5, 7, centre });
    t.push_back({ 7, 6, centre });
    t.push_back({ 6, 4, centre });
    const csm::SurfaceClosure c = csm::classifySurface(p, t);
    EXPECT_TRUE(c.closed);
    EXPECT_FALSE(c.convex);
    EXPECT_TRUE(c.canShadowItself());
  }
  {
    // A tilted grid of 3 x 3 points far from the origin: planar, open.
    std::vector<glm::dvec3> p;
    Triangles t;
    const glm::dvec3 origin(1.0e6, -2.0e5, 3.0e5), u(1.0, 0.5, 0.0), v(0.0, 0.3, 1.0);
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i)
        p.push_back(origin + double(i) * u + double(j) * v);
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i)
      {
        const std::int64_t a = 3 * j + i;
        t.push_back({ a, a + 1, a + 4 });
        t.push_back({ a, a + 4, a + 3 });
      }
    csm::SurfaceClosure c = csm::classifySurface(p, t);
    EXPECT_FALSE(c.closed);
    EXPECT_TRUE(c.planar);
    EXPECT_FALSE(c.canShadowItself());
    // One corner lifted off the plane by 1 % of the grid: not planar, may shadow itself.
    p[8] += 0.03 * glm::normalize(glm::cross(u, v));
    c = csm::classifySurface(p, t);
    EXPECT_FALSE(c.planar);
    EXPECT_TRUE(c.canShadowItself());
  }
  {
    // Bad input stays on the safe side: it may shadow itself.
    std::vector<glm::dvec3> p = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 } };
    Triangles t = { { 0, 1, 7 } };
    EXPECT_TRUE(csm::classifySurface(p, t).canShadowItself());
    p[2].x = std::numeric_limits<double>::quiet_NaN();
    t = { { 0, 1, 2 } };
    EXPECT_TRUE(csm::classifySurface(p, t).canShadowItself());
    t = { { 0, 0, 1 } }; // degenerate only
    EXPECT_TRUE(csm::classifySurface(p, t).canShadowItself());
  }
}

// Stopped (another thread set the flag): the answer is open, the safe one.
TEST(ClosedSurface, StoppedGivesTheOpenAnswer)
{
  std::vector<glm::dvec3> p;
  Triangles t;
  box(-1.0, 2.0, false, p, t);
  std::atomic<bool> stop(false);
  EXPECT_TRUE(csm::classifySurface(p, t, &stop).closed);
  stop = true;
  const csm::SurfaceClosure c = csm::classifySurface(p, t, &stop);
  EXPECT_FALSE(c.closed);
  EXPECT_EQ(c.volume, 0.0);
}

// A deforming mesh classified with its last topology gets the answers of a fresh classification
// at every step: points moved together (the same weld), a dent, a corner torn apart and joined
// again (another weld), a triangle turned (other triangles).
TEST(ClosedSurface, TheLastTopologyGivesTheFreshAnswers)
{
  std::vector<glm::dvec3> p;
  Triangles t;
  box(0.0, 1.0, true, p, t);
  csm::SurfaceTopology topology;
  const auto same = [&](const char* step)
  {
    SCOPED_TRACE(step);
    const csm::SurfaceClosure fresh = csm::classifySurface(p, t);
    const csm::SurfaceClosure kept = csm::classifySurface(p, t, nullptr, &topology);
    EXPECT_EQ(kept.closed, fresh.closed);
    EXPECT_EQ(kept.volume, fresh.volume);
    EXPECT_EQ(kept.planar, fresh.planar);
    EXPECT_EQ(kept.convex, fresh.convex);
    EXPECT_TRUE(topology.known);
    EXPECT_EQ(topology.closed, fresh.closed);
    return fresh;
  };
  EXPECT_TRUE(same("first").convex);
  for (glm::dvec3& q : p) // stretched and moved: every copy of a corner with it
    q = glm::dvec3(2.0 * q.x + 5.0, q.y - 3.0, 0.5 * q.z);
  const csm::SurfaceClosure moved = same("moved");
  EXPECT_TRUE(moved.closed);
  EXPECT_NEAR(std::abs(moved.volume), 1.0, 1e-12);
  const glm::dvec3 top = p[t[2][0]]; // a corner of the top face: every copy pushed in
  for (glm::dvec3& q : p)
    if (q == top)
      q.z -= 0.4;
  const csm::SurfaceClosure dented = same("dented");
  EXPECT_TRUE(dented.closed);
  EXPECT_FALSE(dented.convex);
  const glm::dvec3 before = p[0];
  p[0] += glm::dvec3(0.25, 0.0, 0.0); // one copy of a corner torn off the others
  EXPECT_FALSE(same("torn").closed);
  p[0] = before;
  EXPECT_TRUE(same("joined again").closed);
  std::swap(t[0][1], t[0][2]); // one triangle turned: the same weld, other edges
  EXPECT_FALSE(same("a triangle turned").closed);
  std::swap(t[0][1], t[0][2]);
  EXPECT_TRUE(same("turned back").closed);
  p[3].y = std::numeric_limits<double>::quiet_NaN(); // bad input: open, nothing known
  EXPECT_FALSE(csm::classifySurface(p, t, nullptr, &topology).closed);
  EXPECT_FALSE(topology.known);
}

// Which of a view's faces a closed surface's outward ones are: a projection of negative
// determinant (perspective, orthographic) keeps the winding, a positive one mirrors it; not closed
// or a matrix that is not finite: no answer.
TEST(ClosedSurface, TheOutwardFacesAreTheFrontFacesOfAUsualProjection)
{
  const glm::dmat4 perspective = glm::perspective(0.5, 1.5, 0.1, 100.0);
  const glm::dmat4 orthographic = glm::ortho(-1.0, 1.0, -1.0, 1.0, 0.1, 100.0);
  const glm::dmat4 mirrored = glm::scale(perspective, glm::dvec3(-1.0, 1.0, 1.0));
  ASSERT_LT(glm::determinant(perspective), 0.0);
  ASSERT_LT(glm::determinant(orthographic), 0.0);
  EXPECT_EQ(csm::closedFaceTowardViewer(1, glm::determinant(perspective)), 1);
  EXPECT_EQ(csm::closedFaceTowardViewer(1, glm::determinant(orthographic)), 1);
  EXPECT_EQ(csm::closedFaceTowardViewer(-1, glm::determinant(perspective)), -1);
  EXPECT_EQ(csm::closedFaceTowardViewer(1, glm::determinant(mirrored)), -1);
  EXPECT_EQ(csm::closedFaceTowardViewer(-1, glm::determinant(mirrored)), 1);
  EXPECT_EQ(csm::closedFaceTowardViewer(0, glm::determinant(perspective)), 0);
  EXPECT_EQ(csm::closedFaceTowardViewer(1, std::numeric_limits<double>::quiet_NaN()), 0);
  EXPECT_EQ(csm::closedFaceTowardViewer(1, std::numeric_limits<double>::infinity()), 0);
}

// A box wound inside out beside a box (of another volume: the two do not cancel): not closed.
// A box inside a larger one wound inside out (a cavity), two boxes along a shared edge: closed.
TEST(ClosedSurface, APartWoundInsideOutIsOpenACavityIsNot)
{
  std::vector<glm::dvec3> q;
  Triangles two;
  box(0.0, 1.0, false, q, two);
  const size_t second = q.size();
  box(1.0, 2.0, false, q, two);
  for (size_t i = second; i < q.size(); ++i)
  {
    q[i].z -= 1.0; // (1..2, 1..2, 0..1): its edge x = 1, y = 1 is the first's
  }
  EXPECT_TRUE(csm::classifySurface(q, two).closed);
  const auto withInsideOut = [](double lo, double hi, double innerLo, double innerHi)
  {
    std::vector<glm::dvec3> corners;
    Triangles both;
    box(lo, hi, false, corners, both);
    const size_t inner = both.size();
    box(innerLo, innerHi, false, corners, both);
    for (size_t k = inner; k < both.size(); ++k)
    {
      std::swap(both[k][1], both[k][2]);
    }
    return csm::classifySurface(corners, both);
  };
  EXPECT_FALSE(withInsideOut(0.0, 1.0, 2.0, 4.0).closed);
  // Many boxes wound either way, more of them one way (no cavities to find): open, at once.
  std::vector<glm::dvec3> many;
  Triangles mixed;
  for (int k = 0; k < 4001; ++k)
  {
    const size_t first = mixed.size();
    box(2.0 * k, 2.0 * k + 1.0, false, many, mixed);
    for (size_t i = first; k % 2 == 1 && i < mixed.size(); ++i)
    {
      std::swap(mixed[i][1], mixed[i][2]);
    }
  }
  EXPECT_FALSE(csm::classifySurface(many, mixed).closed);
  const csm::SurfaceClosure shell = withInsideOut(0.0, 3.0, 1.0, 2.0);
  EXPECT_TRUE(shell.closed);
  EXPECT_NEAR(std::abs(shell.volume), 27.0 - 1.0, 1e-9);
}
