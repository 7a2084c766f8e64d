/*=========================================================================
 *
 *  Copyright NumFOCUS
 *
 *  Licensed under the Apache License, Version 2.0 (the "License");
 *  you may not use this file except in compliance with the License.
 *  You may obtain a copy of the License at
 *
 *         https://www.apache.org/licenses/LICENSE-2.0.txt
 *
 *  Unless required by applicable law or agreed to in writing, software
 *  distributed under the License is distributed on an "AS IS" BASIS,
 *  WITHOUT WARRANTIES OR CONDITIONS OF ANY KIND, either express or implied.
 *  See the License for the specific language governing permissions and
 *  limitations under the License.
 *
 *=========================================================================*/
#include "itkMeshExtractionBuffer.h"
#include "itkMeshExtractionParallel.h"
#include "itkMeshExtractionPredicates.h"
#include "itkMeshExtractionQualityAnalysis.h"
#include "itkMeshExtractionClosedSurfaceEdgeSwap.h"
#include "itkMeshExtractionTriangleAABBTree.h"
#include "itkMeshExtractionTestHelpers.h"

#include "gtest/gtest.h"

#include <algorithm>
#include <numeric>
#include <chrono>
#include <limits>
#include <mutex>
#include <random>
#include <set>
#include <thread>

using namespace itk::MeshExtraction;
using namespace itk::MeshExtraction::detail;
using MeshExtractionTest::MakeIcosphere;

namespace
{
const double Sqrt3 = std::sqrt(3.0);

TriangleMeasures
Measure(double ax, double ay, double bx, double by, double cx, double cy)
{
  return MeasureTriangle(MakeVec3(ax, ay, 0), MakeVec3(bx, by, 0), MakeVec3(cx, cy, 0));
}
} // namespace

TEST(TriangleMeasures, EquilateralTriangleHasQualityOne)
{
  const TriangleMeasures m = Measure(0, 0, 1, 0, 0.5, Sqrt3 / 2);
  EXPECT_NEAR(m.qLength, 1.0, 1e-12);
  EXPECT_NEAR(m.qAngle, 1.0, 1e-12);
  EXPECT_NEAR(m.qArea, 1.0, 1e-12);
  EXPECT_NEAR(m.minAngle, itk::Math::pi / 3, 1e-12);
  EXPECT_NEAR(m.maxAngle, itk::Math::pi / 3, 1e-12);
  EXPECT_NEAR(m.area, Sqrt3 / 4, 1e-12);
}

TEST(TriangleMeasures, RightIsoscelesTriangleHasQAngleOneHalf)
{
  const TriangleMeasures m = Measure(0, 0, 1, 0, 0, 1);
  EXPECT_NEAR(m.qAngle, 0.5, 1e-12);                    // 45 / 90 degrees
  EXPECT_NEAR(m.qLength, 1.0 / std::sqrt(2.0), 1e-12);  // 1 / sqrt(2)
  EXPECT_NEAR(m.qArea, 4.0 * Sqrt3 * 0.5 / 4.0, 1e-12); // 4 sqrt3 A / (1 + 1 + 2)
  EXPECT_NEAR(m.maxAngle, itk::Math::pi / 2, 1e-12);
}

TEST(TriangleMeasures, DegenerateTrianglesHaveQualityZero)
{
  const TriangleMeasures collinear = Measure(0, 0, 1, 0, 2, 0);
  EXPECT_EQ(collinear.qAngle, 0.0);
  EXPECT_EQ(collinear.qArea, 0.0);
  EXPECT_NEAR(collinear.maxAngle, itk::Math::pi, 1e-12);
  const TriangleMeasures coincident = Measure(0, 0, 0, 0, 1, 0);
  EXPECT_EQ(coincident.qAngle, 0.0);
  EXPECT_EQ(coincident.qArea, 0.0);
  EXPECT_EQ(coincident.qLength, 0.0);
}

TEST(TriangleMeasures, Figure42QAngleAndQAreaFallMonotonicallyButQLengthDoesNot)
{
  // Thesis Figure 4.2: the apex of an equilateral triangle moves along a line
  // until the triangle is degenerate (here to (2, 0), beyond the base).
  double previousAngle = 2.0;
  double previousArea = 2.0;
  bool   qLengthRose = false;
  double previousLength = 2.0;
  for (int i = 0; i <= 100; ++i)
  {
    const double           s = i / 100.0;
    const TriangleMeasures m = Measure(0, 0, 1, 0, 0.5 + 1.5 * s, (Sqrt3 / 2) * (1 - s));
    EXPECT_LT(m.qAngle, previousAngle) << "s = " << s;
    EXPECT_LT(m.qArea, previousArea) << "s = " << s;
    qLengthRose = qLengthRose || m.qLength > previousLength + 1e-12;
    previousAngle = m.qAngle;
    previousArea = m.qArea;
    previousLength = m.qLength;
  }
  EXPECT_NEAR(previousAngle, 0.0, 1e-12);
  EXPECT_NEAR(previousArea, 0.0, 1e-12);
  EXPECT_TRUE(qLengthRose) << "q_length should rise again as the triangle degenerates";
  EXPECT_NEAR(previousLength, 0.5, 1e-12);
}

TEST(TriangleGeometry, ClosestPointOnTriangleMatchesBruteForce)
{
  std::mt19937                           rng(7);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  for (int trial = 0; trial < 200; ++trial)
  {
    const Vec3   a = MakeVec3(u(rng), u(rng), u(rng));
    const Vec3   b = MakeVec3(u(rng), u(rng), u(rng));
    const Vec3   c = MakeVec3(u(rng), u(rng), u(rng));
    const Vec3   p = MakeVec3(u(rng), u(rng), u(rng)) * 2.0;
    const double exact = SquaredDistancePointTriangle(p, a, b, c);
    double       best = std::numeric_limits<double>::max();
    const int    n = 300;
    for (int i = 0; i <= n; ++i)
    {
      for (int j = 0; i + j <= n; ++j)
      {
        const Vec3 q = a + (b - a) * (double(i) / n) + (c - a) * (double(j) / n);
        best = std::min(best, SquaredNorm(p - q));
      }
    }
    EXPECT_LE(exact, best + 1e-12);
    EXPECT_NEAR(std::sqrt(exact), std::sqrt(best), 0.03);
  }
}

TEST(TriangleGeometry, ClosestPointOfDegenerateTriangleIsOnItsSegment)
{
  const Vec3 a = MakeVec3(0, 0, 0);
  const Vec3 b = MakeVec3(1, 0, 0);
  const Vec3 c = MakeVec3(2, 0, 0);
  EXPECT_NEAR(SquaredDistancePointTriangle(MakeVec3(1.5, 1, 0), a, b, c), 1.0, 1e-15);
  EXPECT_NEAR(SquaredDistancePointTriangle(MakeVec3(3, 0, 0), a, a, a), 9.0, 1e-15);
}

// Orientation tests are checked against exact integer arithmetic: coordinates
// are integers below 2^25 scaled by 2^-20, so the determinant fits in __int128.
namespace
{
__int128
ExactOrient3D(const long long a[3], const long long b[3], const long long c[3], const long long d[3])
{
  const __int128 u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
  const __int128 v[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
  const __int128 w[3] = { d[0] - a[0], d[1] - a[1], d[2] - a[2] };
  return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0]);
}
Vec3
Scaled(const long long p[3])
{
  const double s = std::ldexp(1.0, -20);
  return MakeVec3(p[0] * s, p[1] * s, p[2] * s);
}
} // namespace

TEST(ExactPredicates, Orient3DSignIsExactOnNearlyCoplanarPoints)
{
  std::mt19937_64                          rng(11);
  std::uniform_int_distribution<long long> big(-(1LL << 24), 1LL << 24);
  std::uniform_int_distribution<long long> small(-3, 3);
  std::uniform_int_distribution<long long> tiny(-1, 1);
  int                                      naiveWrong = 0;
  for (int trial = 0; trial < 20000; ++trial)
  {
    long long a[3];
    long long u[3];
    long long v[3];
    for (int k = 0; k < 3; ++k)
    {
      a[k] = big(rng);
      u[k] = big(rng) / 4;
      v[k] = big(rng) / 4;
    }
    long long       b[3];
    long long       c[3];
    long long       d[3];
    const long long s = small(rng);
    const long long t = small(rng);
    for (int k = 0; k < 3; ++k)
    {
      b[k] = a[k] + u[k];
      c[k] = a[k] + v[k];
      d[k] = a[k] + s * u[k] + t * v[k] + tiny(rng); // on the plane, or one unit off it
    }
    const __int128 exact = ExactOrient3D(a, b, c, d);
    const int      expected = (exact > 0) - (exact < 0);
    ASSERT_EQ(Orient3D(Scaled(a), Scaled(b), Scaled(c), Scaled(d)), expected) << "trial " << trial;
    ASSERT_EQ(Orient3DExact(Scaled(a), Scaled(b), Scaled(c), Scaled(d)), expected) << "trial " << trial;
    const Vec3   A = Scaled(a);
    const double naive = Dot(Cross(Scaled(b) - A, Scaled(c) - A), Scaled(d) - A);
    naiveWrong += ((naive > 0) - (naive < 0)) != expected ? 1 : 0;
  }
  // The configurations are hard enough that plain double evaluation fails often.
  EXPECT_GT(naiveWrong, 100);
}

TEST(ExactPredicates, Orient2DDetectsCollinearityExactly)
{
  // Points on the line y = x / 3 at scales where rounding of differences matters.
  for (int i = 1; i < 1000; ++i)
  {
    const double a[2] = { 0.0, 0.0 };
    const double b[2] = { 3.0 * i, 1.0 * i };
    const double c[2] = { 3.0 * (i + 7) * 1e7, 1.0 * (i + 7) * 1e7 };
    EXPECT_EQ(Orient2D(a, b, c), 0);
    const double d[2] = { c[0], std::nextafter(c[1], 1e300) };
    EXPECT_EQ(Orient2D(a, b, d), 1);
  }
}

TEST(ExactPredicates, TriangleIntersectionCases)
{
  const Vec3 P[3] = { MakeVec3(0, 0, 0), MakeVec3(2, 0, 0), MakeVec3(0, 2, 0) };
  const Vec3 crossing[3] = { MakeVec3(0.5, 0.5, -1), MakeVec3(0.5, 0.5, 1), MakeVec3(3, 3, 0.2) };
  EXPECT_TRUE(TrianglesIntersect(P, crossing));
  const Vec3 above[3] = { MakeVec3(0, 0, 0.1), MakeVec3(2, 0, 0.1), MakeVec3(0, 2, 0.1) };
  EXPECT_FALSE(TrianglesIntersect(P, above));
  const Vec3 touchingVertex[3] = { MakeVec3(2, 0, 0), MakeVec3(3, 0, 1), MakeVec3(3, 1, -1) };
  EXPECT_TRUE(TrianglesIntersect(P, touchingVertex));
  const Vec3 coplanarInside[3] = { MakeVec3(0.2, 0.2, 0), MakeVec3(0.5, 0.2, 0), MakeVec3(0.2, 0.5, 0) };
  EXPECT_TRUE(TrianglesIntersect(P, coplanarInside));
  const Vec3 coplanarApart[3] = { MakeVec3(2, 2, 0), MakeVec3(3, 2, 0), MakeVec3(2, 3, 0) };
  EXPECT_FALSE(TrianglesIntersect(P, coplanarApart));
}

TEST(ExactPredicates, MeshNeighboursOnlyIntersectAwayFromSharedElements)
{
  const itk::IdentifierType pid[3] = { 0, 1, 2 };
  const Vec3                P[3] = { MakeVec3(0, 0, 0), MakeVec3(2, 0, 0), MakeVec3(0, 2, 0) };
  // Shared edge (0, 1), bent: only the edge is common.
  const itk::IdentifierType e[3] = { 1, 0, 3 };
  const Vec3                bent[3] = { MakeVec3(2, 0, 0), MakeVec3(0, 0, 0), MakeVec3(1, -1, 0.5) };
  EXPECT_FALSE(FacesIntersect(P, pid, bent, e));
  // Shared edge, folded flat on top of the first face: overlap.
  const Vec3 folded[3] = { MakeVec3(2, 0, 0), MakeVec3(0, 0, 0), MakeVec3(0.5, 0.5, 0) };
  EXPECT_TRUE(FacesIntersect(P, pid, folded, e));
  // Shared edge, flat but on the other side: a plane, no overlap.
  const Vec3 flat[3] = { MakeVec3(2, 0, 0), MakeVec3(0, 0, 0), MakeVec3(1, -1, 0) };
  EXPECT_FALSE(FacesIntersect(P, pid, flat, e));
  // Shared vertex 0 only, the faces otherwise apart.
  const itk::IdentifierType v[3] = { 0, 4, 5 };
  const Vec3                apart[3] = { MakeVec3(0, 0, 0), MakeVec3(-1, 0, 1), MakeVec3(0, -1, 1) };
  EXPECT_FALSE(FacesIntersect(P, pid, apart, v));
  // Shared vertex, the far edge of the second face pierces the first.
  const Vec3 pierce[3] = { MakeVec3(0, 0, 0), MakeVec3(1, 0.5, -1), MakeVec3(0.5, 1, 1) };
  EXPECT_TRUE(FacesIntersect(P, pid, pierce, v));
  // Shared vertex, an edge leaving it runs inside the first face (coplanar wedge).
  const Vec3 wedge[3] = { MakeVec3(0, 0, 0), MakeVec3(0.5, 0.5, 0), MakeVec3(0.5, 0.5, 1) };
  EXPECT_TRUE(FacesIntersect(P, pid, wedge, v));
  // Same vertex triple: duplicate face.
  EXPECT_TRUE(FacesIntersect(P, pid, P, pid));
}

namespace
{
/** The fan (v, ring[i], ring[i+1]) around v, spokes at the given angles (radians,
 * about the z axis) with the given radii and heights. */
std::vector<Vec3>
FanRing(const std::vector<double> & angles, const std::vector<double> & radii, const std::vector<double> & heights)
{
  std::vector<Vec3> ring;
  for (std::size_t i = 0; i < angles.size(); ++i)
  {
    ring.push_back(MakeVec3(radii[i] * std::cos(angles[i]), radii[i] * std::sin(angles[i]), heights[i]));
  }
  return ring;
}

/** Does any pair of the fan's faces intersect beyond their common vertex or edge? */
bool
FanSelfIntersects(const Vec3 & v, const std::vector<Vec3> & ring)
{
  const std::size_t k = ring.size();
  for (std::size_t i = 0; i < k; ++i)
  {
    for (std::size_t j = i + 1; j < k; ++j)
    {
      const Vec3                P[3] = { v, ring[i], ring[(i + 1) % k] };
      const Vec3                Q[3] = { v, ring[j], ring[(j + 1) % k] };
      const itk::IdentifierType pid[3] = { 0, 1 + i, 1 + (i + 1) % k };
      const itk::IdentifierType qid[3] = { 0, 1 + j, 1 + (j + 1) % k };
      if (FacesIntersect(P, pid, Q, qid))
      {
        return true;
      }
    }
  }
  return false;
}
} // namespace

TEST(ExactPredicates, CertifyFanChainsTheFacesAtAVertexInAnyOrder)
{
  // Vertex 0 at the origin with a hexagon 1..6 around it, faces (0, i, i+1).
  std::vector<Vec3> points{ MakeVec3(0, 0, 0) };
  for (unsigned int i = 0; i < 6; ++i)
  {
    const double a = 2.0 * itk::Math::pi * i / 6;
    points.push_back(MakeVec3(std::cos(a), std::sin(a), 0.1 * (i % 2)));
  }
  std::vector<FanCorner> fan;
  for (std::uint32_t i = 0; i < 6; ++i)
  {
    fan.push_back({ 1 + i, 1 + (i + 1) % 6 });
  }
  FanScratch scratch;
  EXPECT_TRUE(CertifyFan(points.data(), 0, fan.data(), fan.size(), scratch));
  // Any order of the faces: the ring is chained, not read.
  std::vector<FanCorner> shuffled = { fan[3], fan[0], fan[5], fan[1], fan[4], fan[2] };
  EXPECT_TRUE(CertifyFan(points.data(), 0, shuffled.data(), shuffled.size(), scratch));
  // An open fan (a face missing), a face turned over, a ring through a vertex twice,
  // and no faces: not certified.
  EXPECT_FALSE(CertifyFan(points.data(), 0, fan.data(), 5, scratch));
  std::vector<FanCorner> flipped = fan;
  std::swap(flipped[2].next, flipped[2].last);
  EXPECT_FALSE(CertifyFan(points.data(), 0, flipped.data(), flipped.size(), scratch));
  std::vector<FanCorner> twice = { { 1, 2 }, { 2, 3 }, { 3, 1 }, { 1, 4 }, { 4, 5 }, { 5, 1 } };
  EXPECT_FALSE(CertifyFan(points.data(), 0, twice.data(), twice.size(), scratch));
  EXPECT_FALSE(CertifyFan(points.data(), 0, fan.data(), 0, scratch));
  // A spoke pulled across its neighbour: the ring closes but the fan folds.
  std::vector<Vec3> folded = points;
  folded[3] = MakeVec3(std::cos(2.0 * itk::Math::pi * 3.3 / 6), std::sin(2.0 * itk::Math::pi * 3.3 / 6), 0.1);
  EXPECT_FALSE(CertifyFan(folded.data(), 0, fan.data(), fan.size(), scratch));
}

TEST(ExactPredicates, FanCertificateHoldsOnlyForFansThatGoAroundOnceWithoutFolds)
{
  const Vec3 v = MakeVec3(0, 0, 0);
  auto       regular = [](unsigned int k, double turns) {
    std::vector<double> angles;
    for (unsigned int i = 0; i < k; ++i)
    {
      angles.push_back(2.0 * itk::Math::pi * turns * i / k);
    }
    return angles;
  };
  const std::vector<double> ones(9, 1.0);
  const std::vector<double> flat(9, 0.0);
  // A flat hexagon, and a cone: embedded stars.
  EXPECT_TRUE(FanIsEmbeddedStar(v, FanRing(regular(6, 1), ones, flat).data(), 6));
  EXPECT_TRUE(FanIsEmbeddedStar(v, FanRing(regular(5, 1), ones, std::vector<double>(9, -0.7)).data(), 5));
  // The same hexagon seen from below (clockwise): still a star about the other normal.
  auto reversed = FanRing(regular(6, 1), ones, flat);
  std::reverse(reversed.begin(), reversed.end());
  EXPECT_TRUE(FanIsEmbeddedStar(v, reversed.data(), 6));
  // One spoke pulled across its neighbour: a folded face.
  auto folded = regular(6, 1);
  folded[2] = folded[3] + 0.3;
  EXPECT_FALSE(FanIsEmbeddedStar(v, FanRing(folded, ones, flat).data(), 6));
  EXPECT_TRUE(FanSelfIntersects(v, FanRing(folded, ones, flat)));
  // Nine faces of 80 degrees: around twice, every face counter-clockwise.
  const std::vector<double> twiceRadii = { 1.0, 1.1, 1.2, 1.3, 1.4, 1.5, 1.6, 1.7, 1.8 };
  EXPECT_FALSE(FanIsEmbeddedStar(v, FanRing(regular(9, 2), twiceRadii, flat).data(), 9));
  EXPECT_TRUE(FanSelfIntersects(v, FanRing(regular(9, 2), twiceRadii, flat)));
  // A degenerate face (two spokes in one direction).
  auto                degenerate = regular(6, 1);
  std::vector<double> radii(ones);
  degenerate[3] = degenerate[2];
  radii[3] = 2.0;
  EXPECT_FALSE(FanIsEmbeddedStar(v, FanRing(degenerate, radii, flat).data(), 6));
  // Too few spokes.
  EXPECT_FALSE(FanIsEmbeddedStar(v, FanRing(regular(2, 1), ones, flat).data(), 2));

  // Random fans, from well formed to wildly bent and folded: a certified fan never
  // self-intersects, and every fan whose angles increase around a gently bent cone is
  // certified (the certificate is not vacuous).
  std::mt19937_64                        rng(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int                                    certified = 0;
  int                                    intersecting = 0;
  for (int trial = 0; trial < 20000; ++trial)
  {
    const unsigned int  k = 3 + static_cast<unsigned int>(unit(rng) * 8);
    const int           kind = trial % 4; // 0: gentle; 1: jittered angles; 2: steep; 3: random directions
    std::vector<double> angles = regular(k, 1);
    std::vector<double> r(k);
    std::vector<double> h(k);
    for (unsigned int i = 0; i < k; ++i)
    {
      r[i] = 0.2 + unit(rng);
      h[i] = (kind == 2 ? 3.0 : 0.3) * (unit(rng) - 0.5);
      if (kind == 1)
      {
        angles[i] += 2.5 * (unit(rng) - 0.5) * 2.0 * itk::Math::pi / k;
      }
      else if (kind == 3)
      {
        angles[i] = 2.0 * itk::Math::pi * unit(rng);
      }
      else
      {
        angles[i] += 0.4 * (unit(rng) - 0.5) * 2.0 * itk::Math::pi / k;
      }
    }
    const std::vector<Vec3> ring = FanRing(angles, r, h);
    const Vec3              apex = MakeVec3(0.0, 0.0, 0.1 * (unit(rng) - 0.5));
    const bool              star = FanIsEmbeddedStar(apex, ring.data(), k);
    const bool              intersects = FanSelfIntersects(apex, ring);
    certified += star ? 1 : 0;
    intersecting += intersects ? 1 : 0;
    ASSERT_FALSE(star && intersects) << "trial " << trial << ": a certified fan self-intersects";
    if (kind == 0)
    {
      ASSERT_TRUE(star) << "trial " << trial << ": a gently bent fan is not certified";
    }
  }
  EXPECT_GT(certified, 5000);
  EXPECT_GT(intersecting, 1000); // the random fans include many folded ones
}

TEST(TriangleAABBTree, NearestTriangleMatchesBruteForce)
{
  const IndexedTriangleMesh mesh = MakeIcosphere(3, 5.0);
  TriangleAABBTree          tree;
  tree.Build(mesh);
  std::mt19937                           rng(3);
  std::uniform_real_distribution<double> u(-8.0, 8.0);
  for (int trial = 0; trial < 500; ++trial)
  {
    const Vec3 p = MakeVec3(u(rng), u(rng), u(rng));
    double     best = std::numeric_limits<double>::max();
    for (const auto & t : mesh.triangles)
    {
      best = std::min(best, SquaredDistancePointTriangle(p, mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]]));
    }
    EXPECT_DOUBLE_EQ(tree.FindNearest(p).squaredDistance, best);
  }
}

TEST(TriangleAABBTree, RefitAfterMovesAndSwapsAnswersLikeAFreshBuild)
{
  // A tree built once, then refitted after the vertices moved and triangles changed
  // vertices (as edge swaps do): overlapping-box pairs and nearest points are those of
  // a tree built from scratch, and the self-intersections those of the full search.
  IndexedTriangleMesh mesh = MakeIcosphere(3, 5.0);
  TriangleAABBTree    refitted;
  auto                boxesOf = [](const IndexedTriangleMesh & m) {
    AxisAlignedBoxArray boxes(m.triangles.size());
    for (std::uint32_t f = 0; f < m.triangles.size(); ++f)
    {
      boxes[f] = TriangleBox(m, f);
    }
    return boxes;
  };
  refitted.Build(mesh, nullptr, nullptr);
  std::mt19937                           rng(9);
  std::uniform_real_distribution<double> jitter(-0.4, 0.4);
  for (int round = 0; round < 4; ++round)
  {
    SCOPED_TRACE(round);
    for (auto & p : mesh.points)
    {
      p += MakeVec3(jitter(rng), jitter(rng), jitter(rng));
    }
    // Exchange vertices between some triangles (the sets need not stay a mesh here).
    for (std::size_t f = 0; f + 7 < mesh.triangles.size(); f += 37)
    {
      std::swap(mesh.triangles[f][0], mesh.triangles[f + 7][1]);
    }
    const auto boxes = boxesOf(mesh);
    refitted.Refit(mesh, boxes);
    TriangleAABBTree fresh;
    fresh.Build(mesh, nullptr, &boxes);
    auto pairsOf = [](const TriangleAABBTree & tree) {
      std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
      for (const auto & start : tree.SplitOverlappingPairs(64))
      {
        tree.VisitOverlappingPairs(
          start, [&](std::uint32_t a, std::uint32_t b) { pairs.emplace_back(std::min(a, b), std::max(a, b)); });
      }
      std::sort(pairs.begin(), pairs.end());
      return pairs;
    };
    const auto pairs = pairsOf(refitted);
    ASSERT_EQ(pairs, pairsOf(fresh));
    ASSERT_FALSE(pairs.empty());
    std::vector<std::uint32_t> all(mesh.triangles.size());
    std::iota(all.begin(), all.end(), 0u);
    EXPECT_EQ(FindSelfIntersections(mesh, all, refitted), FindSelfIntersections(mesh));
    std::uniform_real_distribution<double> u(-8.0, 8.0);
    for (int trial = 0; trial < 100; ++trial)
    {
      const Vec3 p = MakeVec3(u(rng), u(rng), u(rng));
      EXPECT_DOUBLE_EQ(refitted.FindNearest(p).squaredDistance, fresh.FindNearest(p).squaredDistance);
    }
  }
  // A tree over part of the triangles cannot be refitted to all of them.
  TriangleAABBTree           part;
  std::vector<std::uint32_t> half(mesh.triangles.size() / 2);
  std::iota(half.begin(), half.end(), 0u);
  part.Build(mesh, &half);
  EXPECT_THROW(part.Refit(mesh, boxesOf(mesh)), itk::ExceptionObject);
}

TEST(SelfIntersectionCache, FindsThePairsOfTheFullSearchAfterSmallAndLargeMoves)
{
  // Two spheres with a gap of a tenth of an edge between them, moved in small steps
  // (no face "moves" for the cache: the near pairs across the gap must catch the
  // spheres meeting), with single vertices thrown far (queries of moved faces) and
  // faces exchanging vertices (as swaps do). Every search must equal the full one.
  IndexedTriangleMesh       mesh = MakeIcosphere(3, 5.0);
  const IndexedTriangleMesh second = MakeIcosphere(3, 5.0);
  const double edge = std::sqrt(SquaredNorm(mesh.points[mesh.triangles[0][0]] - mesh.points[mesh.triangles[0][1]]));
  const auto   offset = static_cast<std::uint32_t>(mesh.points.size());
  for (const auto & p : second.points)
  {
    mesh.points.push_back(p + MakeVec3(10.0 + 0.1 * edge, 0.0, 0.0));
  }
  for (const auto & t : second.triangles)
  {
    mesh.triangles.push_back({ t[0] + offset, t[1] + offset, t[2] + offset });
  }
  SelfIntersectionCache cache;
  cache.margin = 0.5 * edge;
  TriangleAABBTree           tree;
  std::vector<std::uint32_t> all(mesh.triangles.size());
  std::iota(all.begin(), all.end(), 0u);
  std::mt19937                           rng(3);
  std::uniform_real_distribution<double> jitter(-0.05 * edge, 0.05 * edge);
  std::size_t                            incrementalWithPairs = 0;
  for (int round = 0; round < 12; ++round)
  {
    SCOPED_TRACE(round);
    if (round > 0)
    {
      for (auto & p : mesh.points)
      {
        p += MakeVec3(jitter(rng), jitter(rng), jitter(rng));
      }
    }
    if (round >= 3 && round <= 6)
    {
      // The second sphere closes the gap and goes 0.1 edge into the first per round
      // (0.1 edge since the last rebuild at most: no face moved for the cache).
      for (std::size_t v = offset; v < mesh.points.size(); ++v)
      {
        mesh.points[v][0] -= 0.1 * edge;
      }
    }
    if (round == 8)
    {
      mesh.points[7] = -mesh.points[7]; // through the sphere: its faces moved
    }
    if (round == 10)
    {
      std::swap(mesh.triangles[5][0], mesh.triangles[40][1]);
    }
    AxisAlignedBoxArray boxes(mesh.triangles.size());
    for (std::uint32_t f = 0; f < mesh.triangles.size(); ++f)
    {
      boxes[f] = TriangleBox(mesh, f);
      for (unsigned int d = 0; d < 3; ++d)
      {
        boxes[f].lower[d] -= 0.5 * cache.margin;
        boxes[f].upper[d] += 0.5 * cache.margin;
      }
    }
    tree.Build(mesh, nullptr, &boxes);
    const std::size_t incremental = cache.numberOfIncrementalSearches;
    const auto        pairs = FindSelfIntersections(mesh, all, tree, &cache);
    ASSERT_EQ(pairs, FindSelfIntersections(mesh));
    if (cache.numberOfIncrementalSearches > incremental && !pairs.empty())
    {
      ++incrementalWithPairs;
    }
  }
  EXPECT_GE(cache.numberOfRebuilds, 1u);
  EXPECT_GE(cache.numberOfIncrementalSearches, 6u);
  EXPECT_GE(incrementalWithPairs, 3u); // the spheres meeting, the thrown vertex, the swap
}

TEST(SurfaceNetTriangles, BuildConnectivityPairsEveryHalfEdgeWithItsReverse)
{
  const IndexedTriangleMesh sphere = MakeIcosphere(2, 1.0);
  SurfaceNetTriangles       mesh;
  mesh.triangles = sphere.triangles;
  mesh.BuildConnectivity(sphere.points.size());
  ASSERT_EQ(mesh.twin.size(), 3 * mesh.triangles.size());
  std::vector<std::uint32_t> facesAt(sphere.points.size(), 0);
  for (std::uint32_t h = 0; h < mesh.twin.size(); ++h)
  {
    const std::uint32_t t = mesh.twin[h];
    ASSERT_LT(t, mesh.twin.size());
    EXPECT_NE(t / 3, h / 3);
    EXPECT_EQ(mesh.twin[t], h);
    // h runs u -> v, its twin v -> u.
    EXPECT_EQ(mesh.triangles[h / 3][h % 3], mesh.triangles[t / 3][(t % 3 + 1) % 3]);
    EXPECT_EQ(mesh.triangles[h / 3][(h % 3 + 1) % 3], mesh.triangles[t / 3][t % 3]);
    ++facesAt[mesh.triangles[h / 3][h % 3]];
  }
  EXPECT_EQ(mesh.valence, facesAt);

  SurfaceNetTriangles open = mesh; // a hole: edges with one half-edge
  open.triangles.pop_back();
  EXPECT_THROW(open.BuildConnectivity(sphere.points.size()), itk::ExceptionObject);
  SurfaceNetTriangles fin = mesh; // a third face on an edge
  fin.triangles.push_back(
    { mesh.triangles[0][0], mesh.triangles[0][1], static_cast<std::uint32_t>(sphere.points.size()) });
  EXPECT_THROW(fin.BuildConnectivity(sphere.points.size() + 1), itk::ExceptionObject);
  EXPECT_THROW(mesh.BuildConnectivity(sphere.points.size() - 1), itk::ExceptionObject); // a node out of range
}

TEST(SurfaceNetTriangles, ReplaceTrianglesGivesTheConnectivityOfABuildFromScratch)
{
  // Swap edges of a perturbed sphere (to the shorter diagonal), then undo every other
  // swap, and then all of them, locally: twins and valences must be those that
  // BuildConnectivity gives the same triangles.
  IndexedTriangleMesh              sphere = MakeIcosphere(3, 1.0);
  std::mt19937                     rng(5);
  std::normal_distribution<double> jitter(0.0, 0.04);
  for (auto & p : sphere.points)
  {
    p += MakeVec3(jitter(rng), jitter(rng), jitter(rng));
  }
  SurfaceNetTriangles mesh;
  mesh.triangles = sphere.triangles;
  mesh.BuildConnectivity(sphere.points.size());
  EdgeSwapParameters shortest;
  shortest.criterion = itk::MeshExtractionEnums::EdgeSwapCriterion::ShortestEdge;
  const auto swaps = SwapEdges(sphere.points, mesh, shortest);
  ASSERT_GT(swaps.size(), 20u);
  std::vector<std::pair<std::uint32_t, itk::MeshExtraction::TriangleIndices>> undo;
  for (std::size_t i = 0; i < swaps.size(); i += 2)
  {
    undo.emplace_back(swaps[i].first, swaps[i].oldFirst);
    undo.emplace_back(swaps[i].second, swaps[i].oldSecond);
  }
  SurfaceNetTriangles local = mesh;
  local.ReplaceTriangles(undo);
  SurfaceNetTriangles scratch = local;
  scratch.BuildConnectivity(sphere.points.size());
  EXPECT_EQ(local.triangles, scratch.triangles);
  EXPECT_EQ(local.twin, scratch.twin);
  EXPECT_EQ(local.valence, scratch.valence);
  EXPECT_NE(local.triangles, mesh.triangles);
  // Undoing every swap (neighbouring quads among them) gives back the sphere's own.
  SurfaceNetTriangles                                                         back = mesh;
  std::vector<std::pair<std::uint32_t, itk::MeshExtraction::TriangleIndices>> all;
  for (const auto & s : swaps)
  {
    all.emplace_back(s.first, s.oldFirst);
    all.emplace_back(s.second, s.oldSecond);
  }
  back.ReplaceTriangles(all);
  SurfaceNetTriangles original;
  original.triangles = sphere.triangles;
  original.BuildConnectivity(sphere.points.size());
  EXPECT_EQ(back.triangles, original.triangles);
  EXPECT_EQ(back.twin, original.twin);
  EXPECT_EQ(back.valence, original.valence);

  // Corners that do not cover the same part (those of a face elsewhere): the rest no
  // longer closes up.
  const std::uint32_t                                                               face = undo[0].first;
  const std::vector<std::pair<std::uint32_t, itk::MeshExtraction::TriangleIndices>> wrong{
    { face, local.triangles[(face + local.triangles.size() / 2) % local.triangles.size()] }
  };
  EXPECT_THROW(local.ReplaceTriangles(wrong), itk::ExceptionObject);
}

TEST(ComponentVolumes, FlagAComponentThatTurnsInsideOutOrFlattensAndNoOther)
{
  // Three components: a sphere, a small sphere inside it turned inward (a cavity:
  // negative volume), and a small sphere elsewhere.
  const IndexedTriangleMesh    outer = MakeIcosphere(2, 10.0);
  const IndexedTriangleMesh    inner = MakeIcosphere(1, 2.0, MakeVec3(1.0, 0.0, 0.0));
  const IndexedTriangleMesh    apart = MakeIcosphere(1, 1.0, MakeVec3(20.0, 0.0, 0.0));
  std::vector<Vec3>            points;
  std::vector<TriangleIndices> triangles;
  auto                         add = [&](const IndexedTriangleMesh & m, bool inward) {
    const auto first = static_cast<std::uint32_t>(points.size());
    points.insert(points.end(), m.points.begin(), m.points.end());
    for (auto t : m.triangles)
    {
      if (inward)
      {
        std::swap(t[1], t[2]);
      }
      triangles.push_back({ t[0] + first, t[1] + first, t[2] + first });
    }
  };
  add(outer, false);
  add(inner, true);
  add(apart, false);
  ComponentVolumes volumes;
  EXPECT_EQ(volumes.Collapsed(triangles, points), std::vector<bool>{}); // not initialised
  volumes.Initialize(triangles, points);
  ASSERT_EQ(volumes.reference.size(), 3u);
  EXPECT_GT(volumes.reference[0], 0.0);
  EXPECT_LT(volumes.reference[1], 0.0);
  EXPECT_GT(volumes.reference[2], 0.0);
  EXPECT_EQ(volumes.vertexComponent[outer.points.size()], 1u);
  EXPECT_EQ(volumes.Collapsed(triangles, points), std::vector<bool>(3, false));

  const std::size_t apartFirst = outer.points.size() + inner.points.size();
  auto              moved = [&](double scaleZ, double mirrorX) {
    std::vector<Vec3> p = points;
    for (std::size_t v = apartFirst; v < p.size(); ++v)
    {
      const Vec3 c = MakeVec3(20.0, 0.0, 0.0);
      Vec3       d = p[v] - c;
      d[0] *= mirrorX;
      d[2] *= scaleZ;
      p[v] = c + d;
    }
    return volumes.Collapsed(triangles, p);
  };
  const std::vector<bool> onlyApart{ false, false, true };
  EXPECT_EQ(moved(0.5, 1.0), std::vector<bool>(3, false)); // half its volume: kept
  EXPECT_EQ(moved(0.2, 1.0), onlyApart);                   // a fifth: flattened
  EXPECT_EQ(moved(0.0, 1.0), onlyApart);                   // no volume
  EXPECT_EQ(moved(1.0, -1.0), onlyApart);                  // mirrored: inside out
  // The cavity turned outward, and a NaN point.
  std::vector<Vec3> p = points;
  for (std::size_t v = outer.points.size(); v < apartFirst; ++v)
  {
    p[v] = MakeVec3(1.0, 0.0, 0.0) + (MakeVec3(1.0, 0.0, 0.0) - p[v]);
  }
  EXPECT_EQ(volumes.Collapsed(triangles, p), (std::vector<bool>{ false, true, false }));
  p = points;
  p[0][0] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(volumes.Collapsed(triangles, p), (std::vector<bool>{ true, false, false }));
}

TEST(ParallelForBlocks, ScopedNumberOfWorkUnitsBoundsTheThreadsAndIsRestored)
{
  // A filter's SetNumberOfWorkUnits(1) must reach the free functions it calls.
  auto threadsUsed = []() {
    std::mutex                mutex;
    std::set<std::thread::id> ids;
    std::vector<std::size_t>  covered(4096, 0);
    ParallelForBlocks(covered.size(), 16, [&](std::size_t begin, std::size_t end, std::size_t) {
      for (std::size_t i = begin; i < end; ++i)
      {
        ++covered[i];
      }
      // Long enough that a second thread, if there is one, takes some blocks.
      std::this_thread::sleep_for(std::chrono::microseconds(200));
      std::lock_guard<std::mutex> lock(mutex);
      ids.insert(std::this_thread::get_id());
    });
    EXPECT_EQ(std::count(covered.begin(), covered.end(), 1u), static_cast<std::ptrdiff_t>(covered.size()));
    return ids.size();
  };
  EXPECT_EQ(ThreadNumberOfWorkUnits(), 0u);
  {
    const ScopedNumberOfWorkUnits one(1);
    EXPECT_EQ(ThreadNumberOfWorkUnits(), 1u);
    EXPECT_EQ(threadsUsed(), 1u);
    {
      const ScopedNumberOfWorkUnits two(2);
      EXPECT_EQ(ThreadNumberOfWorkUnits(), 2u);
      if (itk::MultiThreaderBase::GetGlobalDefaultNumberOfThreads() > 1)
      {
        EXPECT_GT(threadsUsed(), 1u);
      }
    }
    EXPECT_EQ(ThreadNumberOfWorkUnits(), 1u);
  }
  EXPECT_EQ(ThreadNumberOfWorkUnits(), 0u);
}

TEST(UninitializedArray, HoldsWhatIsWrittenAlignedForCacheLinesAndHugePages)
{
  // Small arrays are aligned to a cache line, large ones (1 MiB and more) to a 2 MiB
  // page; every element keeps what was written; Allocate replaces the contents.
  UninitializedArray<std::uint32_t> empty;
  EXPECT_TRUE(empty.empty());
  EXPECT_EQ(empty.size(), 0u);
  EXPECT_EQ(empty.data(), nullptr);
  for (const std::size_t n : { std::size_t{ 1 }, std::size_t{ 1000 }, std::size_t{ 300000 }, std::size_t{ 3 } << 20 })
  {
    SCOPED_TRACE(n);
    UninitializedArray<std::uint32_t> a(n);
    ASSERT_EQ(a.size(), n);
    ASSERT_FALSE(a.empty());
    const auto address = reinterpret_cast<std::uintptr_t>(a.data());
    EXPECT_EQ(address % 64, 0u);
    if (n * sizeof(std::uint32_t) >= (std::size_t{ 1 } << 20))
    {
      EXPECT_EQ(address % (std::size_t{ 2 } << 20), 0u);
    }
    for (std::size_t i = 0; i < n; ++i)
    {
      a[i] = static_cast<std::uint32_t>(i * 2654435761u);
    }
    std::size_t  wrong = 0;
    const auto & constant = a;
    for (std::size_t i = 0; i < n; ++i)
    {
      wrong += constant[i] != static_cast<std::uint32_t>(i * 2654435761u) ? 1 : 0;
    }
    EXPECT_EQ(wrong, 0u);
    a.Allocate(7);
    EXPECT_EQ(a.size(), 7u);
    a.Allocate(0);
    EXPECT_TRUE(a.empty());
    EXPECT_EQ(a.data(), nullptr);
  }
}
