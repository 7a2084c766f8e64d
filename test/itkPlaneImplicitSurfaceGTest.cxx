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
#include "itkPlaneImplicitSurface.h"
#include "itkImplicitSurfaceTestHelpers.h"

using namespace ImplicitSurfaceTest;

TEST(PlaneImplicitSurface, SignedDistanceIsProjectionOnTheUnitNormalNegativeOppositeTheNormal)
{
  auto plane = itk::PlaneImplicitSurface::New();
  plane->SetPoint(P(1, 1, 1));
  plane->SetNormal(V(1, 2, 3));
  const double l = std::sqrt(14.0);
  EXPECT_NEAR(plane->GetNormal().GetNorm(), 1.0, 1e-15);
  EXPECT_NEAR(plane->Evaluate(P(1, 1, 1)), 0.0, 1e-15);
  EXPECT_NEAR(plane->Evaluate(P(2, 3, 4)), (1 + 4 + 9) / l, 1e-12);
  EXPECT_NEAR(plane->Evaluate(P(0, 0, 0)), -6.0 / l, 1e-12);
  EXPECT_TRUE(plane->IsInside(P(0, 0, 0)));
  EXPECT_FALSE(plane->IsInside(P(2, 3, 4)));
  ITK_EXPECT_VECTOR_NEAR(plane->ClosestSurfacePoint(P(2, 3, 4)), P(1, 1, 1), 1e-12);
}

TEST(PlaneImplicitSurface, BoundsAreInfiniteUnlessThePlaneIsAxisAligned)
{
  auto plane = itk::PlaneImplicitSurface::New();
  plane->SetPoint(P(1, 2, 3));
  plane->SetNormal(V(0, 0, -2));
  PointType lower, upper;
  plane->GetBounds(lower, upper);
  EXPECT_EQ(lower[2], 3.0);
  EXPECT_EQ(upper[2], 3.0);
  EXPECT_TRUE(std::isinf(lower[0]) && std::isinf(upper[1]));
  plane->SetNormal(V(1, 1, 0));
  plane->GetBounds(lower, upper);
  EXPECT_TRUE(std::isinf(lower[2]) && std::isinf(upper[2]));
}

TEST(PlaneImplicitSurface, ZeroOrNonFiniteParametersThrow)
{
  auto plane = itk::PlaneImplicitSurface::New();
  ExpectThrowsMentioning([&] { plane->SetNormal(V(0, 0, 0)); }, "Normal");
  ExpectThrowsMentioning([&] { plane->SetPoint(P(0, std::nan(""), 0)); }, "Point");
}
