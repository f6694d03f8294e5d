// SPDX-License-Identifier: BSD-3-Clause
// Face partitioning (Lloyd et al. 2006, §5.1): the partitions tile the view frustum, their storage
// factors are the maxima of Lloyd's m over them, and Fig. 12's comparison with one warped map.
#include "csmAliasing.h"
#include "csmFacePartition.h"
#include "csmMathTestHelpers.h"
#include "csmSetup.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

namespace
{
constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;

using csmMathTest::camera; // eye at the origin looking down -z, up +y

// gammaDeg: 0 light from behind, 90 overhead, 180 facing the viewer; sideways tilts it toward +x.
glm::dvec3 lightAt(double gammaDeg, double sideways = 0.0)
{
  return { sideways, -std::sin(gammaDeg * kDeg), -std::cos(gammaDeg * kDeg) };
}

csm::FacePartitioning partitions(const csm::Camera& cam, const glm::dvec3& light, int k,
  csm::WarpMode warp = csm::WarpMode::LiSPSM)
{
  csm::FacePartitionSettings s;
  s.warp = warp;
  s.k = k;
  return csm::computeFacePartitions(cam, light, s);
}

double singleWarp(const csm::Camera& cam, const glm::dvec3& light, int k,
  csm::WarpMode warp = csm::WarpMode::Generalized)
{
  csm::Settings s;
  s.warp = warp;
  s.split.scheme = csm::SplitScheme::Log;
  s.split.k = k;
  return csm::computeShadowSetup(cam, light, nullptr, s).storageTotal;
}

/// A convex body as the half-spaces of its hull, found from its vertices alone (independent of
/// how computeFacePartitions clipped it): every plane through three vertices with all vertices on
/// one side.
struct Hull
{
  std::vector<glm::dvec3> normals;
  std::vector<double> offsets; // inside: dot(normal, p) + offset >= 0

  Hull(const std::vector<glm::dvec3>& v, double scale)
  {
    const double tolerance = 1e-9 * scale;
    for (size_t i = 0; i < v.size(); ++i)
      for (size_t j = i + 1; j < v.size(); ++j)
        for (size_t k = j + 1; k < v.size(); ++k)
        {
          glm::dvec3 normal = glm::cross(v[j] - v[i], v[k] - v[i]);
          if (glm::length(normal) < 1e-9 * scale * scale)
            continue;
          normal = glm::normalize(normal);
          double lo = 0.0, hi = 0.0;
          for (const glm::dvec3& p : v)
          {
            const double d = glm::dot(normal, p - v[i]);
            lo = std::min(lo, d);
            hi = std::max(hi, d);
          }
          if (lo >= -tolerance)
          {
            this->normals.push_back(normal);
            this->offsets.push_back(-glm::dot(normal, v[i]));
          }
          else if (hi <= tolerance)
          {
            this->normals.push_back(-normal);
            this->offsets.push_back(glm::dot(normal, v[i]));
          }
        }
  }

  /// Inside with the margin (negative: a tolerance, positive: strictly inside by it).
  bool contains(const glm::dvec3& p, double margin) const
  {
    for (size_t i = 0; i < this->normals.size(); ++i)
      if (glm::dot(this->normals[i], p) + this->offsets[i] < margin)
        return false;
    return true;
  }
};

bool finite(const glm::dmat4& m)
{
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r]))
        return false;
  return true;
}

void expectAllFinite(const csm::FacePartitioning& fp)
{
  EXPECT_TRUE(std::isfinite(fp.gammaDeg));
  EXPECT_TRUE(std::isfinite(fp.storageTotal));
  for (const csm::FacePartition& p : fp.partitions)
  {
    EXPECT_TRUE(finite(p.map.wsToClip));
    EXPECT_FALSE(std::isnan(p.map.nPrime));
    EXPECT_TRUE(std::isfinite(p.map.Mx) && std::isfinite(p.map.Mz) && std::isfinite(p.map.storage));
    EXPECT_GT(p.map.storage, 0.0);
    for (const glm::dvec3& q : p.map.wsBody)
    {
      const glm::dvec4 h = p.map.wsToClip * glm::dvec4(q, 1.0);
      ASSERT_GT(h.w, 0.0);
      for (int i = 0; i < 3; ++i)
        EXPECT_LE(std::abs(h[i] / h.w), 1.0 + 1e-9);
    }
  }
}

/// Every sampled point of the frustum lies in exactly one partition: in at least one with a
/// tolerance of 1e-9 of the far distance, and strictly inside (by that much) at most one.
void expectExactCover(
  const csm::Camera& cam, const csm::FacePartitioning& fp, int samples, const char* what)
{
  ASSERT_EQ(fp.status, csm::Status::Ok) << what << ": " << fp.message;
  const double scale = cam.vsFar;
  std::vector<Hull> hulls;
  for (const csm::FacePartition& p : fp.partitions)
    hulls.emplace_back(p.map.wsBody, scale);
  std::mt19937_64 random(12);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double tanY = std::tan(0.5 * cam.fovyDeg * kDeg);
  const double tanX = tanY * cam.aspect;
  int uncovered = 0, overlapping = 0, misplaced = 0;
  for (int s = 0; s < samples; ++s)
  {
    // Depth log-uniform, so that the near part (the stretched near face) gets its share.
    const double d = cam.vsNear * std::pow(cam.vsFar / cam.vsNear, unit(random));
    const glm::dvec3 p = cam.wsPosition +
      glm::dvec3((2 * unit(random) - 1) * tanX * d, (2 * unit(random) - 1) * tanY * d, -d);
    int loose = 0, strict = 0;
    for (const Hull& h : hulls)
    {
      loose += h.contains(p, -1e-9 * scale);
      strict += h.contains(p, 1e-9 * scale);
    }
    uncovered += loose == 0;
    overlapping += strict > 1;
    // The lookup's choice by the pieces' planes is a piece that holds the point.
    const int chosen = csm::partitionAt(fp, p);
    misplaced += chosen < 0 || !hulls[chosen].contains(p, -1e-9 * scale);
  }
  EXPECT_EQ(uncovered, 0) << what;
  EXPECT_EQ(overlapping, 0) << what;
  EXPECT_EQ(misplaced, 0) << what;
}
} // namespace

// Lloyd et al. 2006, §5.1: the planes through the face edges and the light split the frustum into
// partitions that cover it without overlap, for every light direction (near face stretched over).
TEST(FacePartition, CoversTheFrustumExactly)
{
  const double gammas[] = { 0, 5, 20, 29.9, 30, 30.1, 45, 60, 89, 90, 100, 150, 180 };
  csm::Camera moved = camera(0.5, 400.0, 45.0, 1.6);
  moved.wsPosition = { 300.0, -30.0, 100.0 }; // the planes in world space, not around the eye
  for (const csm::Camera& cam : { camera(1.0, 50.0, 60.0), camera(0.5, 400.0, 45.0, 1.6), moved })
  {
    for (double g : gammas)
    {
      for (double sideways : { 0.0, 0.4 })
      {
        for (int k : { 1, 3 })
        {
          const csm::FacePartitioning fp = partitions(cam, lightAt(g, sideways), k);
          char what[96];
          std::snprintf(
            what, sizeof what, "gamma %g sideways %g k %d aspect %g", g, sideways, k, cam.aspect);
          expectExactCover(cam, fp, 1500, what);
          expectAllFinite(fp);
          EXPECT_EQ(fp.partitions.size() % k, 0u) << what;
        }
      }
    }
  }
  // Light from behind: all four side faces; overhead: only the top face; between the half field of
  // view and 90 deg: three (the bottom face turns away from the light).
  const csm::Camera cam = camera(1.0, 50.0, 60.0);
  EXPECT_EQ(partitions(cam, lightAt(0.0), 2).partitions.size(), 8u);
  EXPECT_EQ(partitions(cam, lightAt(20.0), 1).partitions.size(), 4u);
  EXPECT_EQ(partitions(cam, lightAt(60.0), 1).partitions.size(), 3u);
  const csm::FacePartitioning overhead = partitions(cam, lightAt(90.0), 1);
  ASSERT_EQ(overhead.partitions.size(), 1u);
  EXPECT_EQ(overhead.partitions[0].face, csm::FrustumFace::Top);
}

// Lloyd et al. 2006, §4.4: S = M_x M_z with M the maxima of m over the partition. Dense samples of
// each partition (through csm::aliasingAt with the partition's map axes) never exceed the
// vertices' maxima and reach them within 1e-3; finite differences of the map agree with the
// gradient aliasingAt uses.
TEST(FacePartition, StorageIsTheMaximumOfLloydsM)
{
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (double g : { 0.0, 15.0, 50.0, 120.0 })
  {
    for (double aspect : { 1.0, 1.5 })
    {
      const csm::Camera cam = camera(1.0, 200.0, 50.0, aspect);
      const glm::dvec3 light = lightAt(g, 0.2);
      const csm::FacePartitioning fp = partitions(cam, light, 2);
      ASSERT_EQ(fp.status, csm::Status::Ok);
      double total = 0.0;
      for (const csm::FacePartition& part : fp.partitions)
      {
        const csm::Cascade& c = part.map;
        const std::vector<glm::dvec3>& v = c.wsBody;
        glm::dvec3 centroid(0.0);
        for (const glm::dvec3& q : v)
          centroid += q / double(v.size());
        std::vector<glm::dvec3> samples;
        for (const glm::dvec3& q : v)
          samples.push_back(q + 1e-7 * (centroid - q)); // just inside, at every vertex
        for (int s = 0; s < 4000; ++s)
        {
          // Random convex combinations, weighted toward single vertices (exponents).
          glm::dvec3 p(0.0);
          double sum = 0.0;
          for (const glm::dvec3& q : v)
          {
            const double w = std::pow(unit(random), 6.0);
            p += w * q;
            sum += w;
          }
          samples.push_back(p / sum);
        }
        double mx = 0.0, mz = 0.0;
        for (size_t s = 0; s < samples.size(); ++s)
        {
          const glm::dvec3& p = samples[s];
          const csm::Aliasing m = csm::aliasingAt(c.wsToClip, cam, part.wsMapX, part.wsMapZ, p);
          mx = std::max(mx, m.mx);
          mz = std::max(mz, m.mz);
          if (s % 97 == 0)
          {
            // Lloyd et al. 2006, Eq. 2-4 by central differences of s, t in [0, 1].
            auto st = [&](const glm::dvec3& q)
            {
              const glm::dvec4 h = c.wsToClip * glm::dvec4(q, 1.0);
              return glm::dvec2(0.5 * h.x / h.w + 0.5, 0.5 * h.y / h.w + 0.5);
            };
            const double step = 1e-7 * glm::length(p);
            const double dsdx =
              std::abs(st(p + step * part.wsMapX).x - st(p - step * part.wsMapX).x) / (2 * step);
            const double dtdz =
              std::abs(st(p + step * part.wsMapZ).y - st(p - step * part.wsMapZ).y) / (2 * step);
            const double wi = 2.0 * std::tan(25.0 * kDeg) * std::max(-p.z, cam.vsNear);
            EXPECT_NEAR(1.0 / dsdx / wi, m.mx, 1e-6 * m.mx);
            EXPECT_NEAR(1.0 / dtdz / wi, m.mz, 1e-6 * m.mz);
          }
        }
        const double sampled = mx * mz / aspect;
        EXPECT_LE(sampled, c.storage * (1.0 + 1e-9));
        EXPECT_GE(sampled, c.storage * (1.0 - 1e-3))
          << csm::toString(part.face) << " " << part.zIndex << " gamma " << g;
        total += c.storage;
      }
      EXPECT_NEAR(total, fp.storageTotal, 1e-12 * total);
    }
  }
}

// Lloyd et al. 2006, Eq. 19: with the light overhead only the top face faces it, its partition is
// the whole frustum and its map the single warped map: FP(+ZP)+W = (ZP+)W, which is Eq. 18.
TEST(FacePartition, OverheadEqualsSingleWarp)
{
  const double tanTheta = std::tan(30.0 * kDeg);
  for (auto warp : { csm::WarpMode::PSM, csm::WarpMode::LiSPSM, csm::WarpMode::Generalized })
  {
    for (double ratio : { 10.0, 100.0, 1000.0 })
    {
      for (int k = 1; k <= 4; ++k)
      {
        const csm::Camera cam = camera(1.0, ratio, 60.0);
        const csm::FacePartitioning fp = partitions(cam, lightAt(90.0), k, warp);
        ASSERT_EQ(fp.status, csm::Status::Ok);
        ASSERT_EQ(fp.partitions.size(), size_t(k));
        const double w = singleWarp(cam, lightAt(90.0), k, warp);
        EXPECT_NEAR(fp.storageTotal, w, 1e-9 * w) << csm::toString(warp) << " k " << k;
        const double r = std::pow(ratio, 1.0 / k);
        EXPECT_NEAR(fp.storageTotal, k * (r - 1.0) / (2.0 * tanTheta), 1e-6 * w); // Eq. 18
      }
    }
  }
}

// Lloyd et al. 2006, Fig. 12 (f/n = 1000, theta = 30 deg: fovy 60): face partitioning gives nothing
// with the light overhead and a large gain with the light behind the viewer, where one warped map
// falls back to the orthographic map of S = (f/n)^2 (Eq. 20).
TEST(FacePartition, Figure12OverheadAndBehind)
{
  const csm::Camera cam = camera(1.0, 1000.0, 60.0);
  const double overheadFP = partitions(cam, lightAt(90.0), 1).storageTotal;
  const double overheadW = singleWarp(cam, lightAt(90.0), 1);
  EXPECT_NEAR(overheadFP, overheadW, 1e-9 * overheadW);
  EXPECT_NEAR(overheadW, 999.0 / (2.0 * std::tan(30.0 * kDeg)), 1e-6 * overheadW); // 865.2
  std::printf("f/n 1000, theta 30: gamma 90: S_FP %.6g, S_W %.6g\n", overheadFP, overheadW);
  for (double g : { 0.0, 5.0, 10.0 })
  {
    const double fp = partitions(cam, lightAt(g), 1).storageTotal;
    const double w = singleWarp(cam, lightAt(g), 1);
    std::printf("f/n 1000, theta 30: gamma %g: S_FP %.6g, S_W %.6g (generalized), %.6g (lispsm)\n",
      g, fp, w, singleWarp(cam, lightAt(g), 1, csm::WarpMode::LiSPSM));
    EXPECT_LT(fp, 0.01 * w) << "gamma " << g;
  }
  EXPECT_NEAR(singleWarp(cam, lightAt(0.0), 1), 1e6, 1e-6 * 1e6); // Eq. 20, k = 1
  // Light behind (gamma 0): Eq. 21 for the paper's partitions with the near face as a fifth map,
  // 4 S_overhead^{ZP+W}(theta = 45 deg) + 1 = 2 k ((f/n)^(1/k) - 1) + 1 (for a square image at
  // gamma 0 a side face's trapezoid does not depend on theta). With the near face stretched over
  // instead, each partition beyond the first along a face is exactly Eq. 18's self-similar piece,
  // and the first pays for the stretched near face.
  for (int k = 1; k <= 4; ++k)
  {
    const double r = std::pow(1000.0, 1.0 / k);
    const csm::FacePartitioning fp = partitions(cam, lightAt(0.0), k);
    ASSERT_EQ(fp.partitions.size(), size_t(4 * k));
    for (const csm::FacePartition& p : fp.partitions)
    {
      if (p.zIndex > 0)
        EXPECT_NEAR(p.map.storage, (r - 1.0) / 2.0, 1e-9 * r);
    }
    const double eq21 = 2.0 * k * (r - 1.0) + 1.0;
    std::printf("gamma 0, k %d (%d maps): S_FP+ZP+W %.6g, Eq. 21 with a near-face map %.6g, "
                "ZP+W with %d maps %.6g\n",
      k, 4 * k, fp.storageTotal, eq21, 4 * k, singleWarp(cam, lightAt(0.0), 4 * k));
    EXPECT_GT(fp.storageTotal, eq21 - 1.0);
    EXPECT_LT(fp.storageTotal, 1.2 * eq21); // measured: +3 % (k 1) to +15 % (k 4)
  }
}

TEST(FacePartition, LightBehindAndInFrontAgree)
{
  const csm::Camera cam = camera(1.0, 300.0, 50.0, 1.3);
  for (double g : { 0.0, 10.0, 40.0, 70.0 })
  {
    const double behind = partitions(cam, lightAt(g, 0.1), 2).storageTotal;
    const double front = partitions(cam, -lightAt(g, 0.1), 2).storageTotal;
    EXPECT_NEAR(behind, front, 1e-9 * behind) << g;
  }
}

// Degenerate inputs: a clear status and message, no NaN. Light parallel to the view is the case
// face partitioning is made for; a light along a side edge or in a face's plane sees faces edge-on.
TEST(FacePartition, DegenerateInputs)
{
  const csm::Camera cam = camera(1.0, 100.0, 60.0);
  const double nan = std::nan("");
  for (const glm::dvec3& bad :
    { glm::dvec3(nan, -1, 0), glm::dvec3(0.0), glm::dvec3(INFINITY, 0, 0) })
  {
    const csm::FacePartitioning fp = partitions(cam, bad, 1);
    EXPECT_EQ(fp.status, csm::Status::InvalidInput);
    EXPECT_EQ(fp.message, "light direction must be finite and non-zero");
    EXPECT_TRUE(fp.partitions.empty());
    EXPECT_EQ(fp.storageTotal, 0.0);
  }
  csm::Camera parallel = cam;
  parallel.parallel = true;
  EXPECT_EQ(partitions(parallel, lightAt(0.0), 1).status, csm::Status::InvalidInput);
  EXPECT_NE(partitions(parallel, lightAt(0.0), 1).message.find("perspective"), std::string::npos);
  EXPECT_EQ(partitions(cam, lightAt(0.0), 0).status, csm::Status::InvalidInput);
  EXPECT_EQ(partitions(cam, lightAt(0.0), 65).status, csm::Status::InvalidInput);
  csm::Camera badCamera = cam;
  badCamera.vsNear = nan;
  EXPECT_EQ(
    partitions(badCamera, lightAt(0.0), 1).message, "camera near distance must be finite and > 0");

  const double tanY = std::tan(30.0 * kDeg);
  const glm::dvec3 edgeOn[] = {
    { 0, 0, -1 },       // parallel to the view, from behind
    { 0, 0, 1 },        // parallel, from the front
    { tanY, tanY, -1 }, // along a side edge: the top and right faces are edge-on
    { 0, -tanY, -1 },   // in the bottom face's plane (gamma = theta)
    { 0, -1, 0 },       // overhead: left, right and near faces edge-on
  };
  for (const glm::dvec3& light : edgeOn)
  {
    const csm::FacePartitioning fp = partitions(cam, light, 2);
    ASSERT_EQ(fp.status, csm::Status::Ok) << fp.message;
    expectAllFinite(fp);
    expectExactCover(cam, fp, 1000, "edge-on");
  }
  EXPECT_EQ(partitions(cam, glm::dvec3(tanY, tanY, -1), 1).partitions.size(), 2u);
  EXPECT_EQ(partitions(cam, glm::dvec3(0, 0, 1), 1).partitions.size(), 4u);
}
