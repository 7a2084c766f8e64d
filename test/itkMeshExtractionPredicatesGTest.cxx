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
// The exact predicates of itkMeshExtractionPredicates.h (internal): orientation,
// triangle intersection and the fan certificate.

#include "itkMeshExtractionPredicates.h"

#include "gtest/gtest.h"

#include <cmath>
#include <random>
#include <vector>

using namespace itk::MeshExtraction;
using namespace itk::MeshExtraction::detail;

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
