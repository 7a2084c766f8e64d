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
#include "itkNarrowCleftImplicitSurface.h"
#include "itkImplicitSurfaceTestHelpers.h"

using namespace ImplicitSurfaceTest;

TEST(NarrowCleftImplicitSurface, DistanceMatchesClosedFormsInAndAroundTheSlot)
{
  auto cleft = itk::NarrowCleftImplicitSurface::New();        // block 20^3, slot 1.5 wide, 10 deep (floor z = 0)
  EXPECT_NEAR(cleft->Evaluate(P(0, 0, 5)), 0.75, 1e-12);      // middle of the slot
  EXPECT_NEAR(cleft->Evaluate(P(0, 0, 0.5)), 0.5, 1e-12);     // slot, near the floor
  EXPECT_NEAR(cleft->Evaluate(P(0, 0, -1)), -1.0, 1e-12);     // under the floor
  EXPECT_NEAR(cleft->Evaluate(P(2, 0, 5)), -1.25, 1e-12);     // in a prong
  EXPECT_NEAR(cleft->Evaluate(P(0.9, 0, 0.1)), -0.15, 1e-12); // inner corner of the slot
  EXPECT_NEAR(cleft->Evaluate(P(0, 0, 11)), 1.25, 1e-12);     // above the slot: the rim
  EXPECT_NEAR(cleft->Evaluate(P(0, 11, 5)), 1.25, 1e-12);     // beyond the open end of the slot
  EXPECT_NEAR(cleft->Evaluate(P(12, 0, 0)), 2.0, 1e-12);      // outside a side face
  EXPECT_NEAR(cleft->Evaluate(P(0, 0, 0)), 0.0, 1e-12);       // on the floor
  EXPECT_NEAR(cleft->Evaluate(P(5, 0, 0)), -4.25, 1e-12);     // in a prong, level with the floor
  EXPECT_NEAR(cleft->Evaluate(P(5, 0, -5)), -5.0, 1e-12);     // deep inside, under the floor
  EXPECT_NEAR(cleft->Evaluate(P(11, 11, 11)), std::sqrt(3.0), 1e-12); // outside a corner
  for (const PointType & p : { P(0, 0, 5), P(0.9, 0, 0.1), P(0, 0, 11), P(0, 11, 5), P(0.75, 0, 10) })
  {
    ExpectConsistentAt(*cleft, p, "narrow cleft");
  }
}

TEST(NarrowCleftImplicitSurface, RotationAndTranslationMoveTheDistanceField)
{
  auto local = itk::NarrowCleftImplicitSurface::New();
  local->SetHalfSizes(V(5, 4, 3));
  local->SetSlotDepth(4);
  auto             moved = itk::NarrowCleftImplicitSurface::New();
  const MatrixType r = Rotation(0.7, -0.2, 0.3);
  const PointType  c = P(-3, 4, 1);
  moved->SetHalfSizes(V(5, 4, 3));
  moved->SetSlotDepth(4);
  moved->SetCenter(c);
  moved->SetRotation(r);
  for (const PointType & q : RandomPoints(P(-5, -4, -3), P(5, 4, 3), 1.0, 500, 91))
  {
    EXPECT_NEAR(moved->Evaluate(Transform(r, c, q)), local->Evaluate(q), 1e-9) << q;
  }
}

namespace
{
/** Grid points, `h` apart, of the boundary of the block |x| <= X, |y| <= Y, |z| <= Z
 * without the slot |x| < s, z > f. */
std::vector<PointType>
SampleNarrowCleftBoundary(double X, double Y, double Z, double s, double f, double h)
{
  // Sample the boundary of the solid: every grid point of the bounding box's faces
  // and of the slot's faces that is on the boundary (|Evaluate| tiny is not used:
  // membership is decided geometrically).
  std::vector<PointType> samples;
  const auto             inSolid = [&](double x, double y, double z) {
    const bool inBlock = std::abs(x) <= X && std::abs(y) <= Y && std::abs(z) <= Z;
    return inBlock && !(std::abs(x) < s && z > f);
  };
  const auto range = [&](double lo, double hi) {
    std::vector<double> values;
    const int           n = static_cast<int>(std::ceil((hi - lo) / h));
    for (int i = 0; i <= n; ++i)
    {
      values.push_back(lo + (hi - lo) * i / n);
    }
    return values;
  };
  // Planes x = const, y = const, z = const that carry boundary faces.
  for (const double x : { -X, -s, s, X })
  {
    for (const double y : range(-Y, Y))
    {
      for (const double z : range(-Z, Z))
      {
        if (inSolid(x, y, z))
        {
          samples.push_back(P(x, y, z));
        }
      }
    }
  }
  for (const double y : { -Y, Y })
  {
    for (const double x : range(-X, X))
    {
      for (const double z : range(-Z, Z))
      {
        if (inSolid(x, y, z))
        {
          samples.push_back(P(x, y, z));
        }
      }
    }
  }
  for (const double z : { -Z, f, Z })
  {
    for (const double x : range(-X, X))
    {
      for (const double y : range(-Y, Y))
      {
        // On z = f only the floor |x| <= s is boundary; on z = Z only |x| >= s.
        const bool onFace = (z == f) ? std::abs(x) <= s : (z == Z ? std::abs(x) >= s : true);
        if (onFace && inSolid(x, y, z))
        {
          samples.push_back(P(x, y, z));
        }
      }
    }
  }
  // The planes x = +-s are boundary only where the slot is (z >= f).
  std::vector<PointType> boundary;
  for (const PointType & p : samples)
  {
    const bool slotWallPlane = std::abs(std::abs(p[0]) - s) < 1e-12;
    if (!slotWallPlane || p[2] >= f)
    {
      boundary.push_back(p);
    }
  }
  return boundary;
}
} // namespace

TEST(NarrowCleftImplicitSurface, BruteForceSamplingAgreesWithTheExactDistance)
{
  auto cleft = itk::NarrowCleftImplicitSurface::New();
  cleft->SetHalfSizes(V(5, 4, 3));
  cleft->SetSlotWidth(1.5);
  cleft->SetSlotDepth(4);
  const double X = 5, Y = 4, Z = 3, s = 0.75, f = Z - 4;
  const double h = 0.05;
  const auto   boundary = SampleNarrowCleftBoundary(X, Y, Z, s, f, h);
  auto         queries = RandomPointsAround(*cleft, 80, 92);
  for (const PointType & special : { P(0, 0, 2), P(0, 0, -0.5), P(1, 0, 1.5), P(0, 5, 2), P(0.8, 3.9, -0.9) })
  {
    queries.push_back(special);
  }
  ExpectBruteForceAgrees(*cleft, boundary, std::sqrt(2.0) * h, queries, "cleft");
}

TEST(NarrowCleftImplicitSurface, SlotWiderOrDeeperThanTheBlockIsRejected)
{
  auto cleft = itk::NarrowCleftImplicitSurface::New();
  ExpectThrowsMentioning([&] { cleft->SetSlotWidth(-1); }, "SlotWidth");
  ExpectThrowsMentioning([&] { cleft->SetSlotDepth(0); }, "SlotDepth");
  cleft->SetSlotWidth(25);
  ExpectThrowsMentioning([&] { cleft->Evaluate(P(0, 0, 0)); }, "SlotWidth");
  cleft->SetSlotWidth(1.5);
  cleft->SetSlotDepth(20);
  ExpectThrowsMentioning([&] { cleft->VerifyParameters(); }, "SlotDepth");
  PointType lower, upper;
  ExpectThrowsMentioning([&] { cleft->GetBounds(lower, upper); }, "SlotDepth");
}
