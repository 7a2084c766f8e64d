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
// The triangle geometry of itkMeshExtractionTriangleGeometry.h: the quality measures
// (thesis section 4.2.3) and the closest point on a triangle.

#include "itkMeshExtractionTriangleGeometry.h"

#include "gtest/gtest.h"

#include <cmath>
#include <limits>
#include <random>

using namespace itk::MeshExtraction;

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
