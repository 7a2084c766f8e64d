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
#include "itkSphereImplicitSurface.h"
#include "itkImplicitSurfaceTestHelpers.h"

using namespace ImplicitSurfaceTest;

TEST(SphereImplicitSurface, DistanceIsRadialDistanceMinusRadius)
{
  auto sphere = itk::SphereImplicitSurface::New();
  sphere->SetCenter(P(1, 2, 3));
  sphere->SetRadius(2);
  EXPECT_DOUBLE_EQ(sphere->Evaluate(P(1, 2, 3)), -2.0);
  EXPECT_DOUBLE_EQ(sphere->Evaluate(P(2, 2, 3)), -1.0);
  EXPECT_DOUBLE_EQ(sphere->Evaluate(P(1, 2, 8)), 3.0);
  EXPECT_NEAR(sphere->Evaluate(P(4, 6, 3)), 3.0, 1e-15);
  ITK_EXPECT_VECTOR_NEAR(sphere->ClosestSurfacePoint(P(4, 6, 3)), P(1 + 1.2, 2 + 1.6, 3), 1e-12);
  ExpectConsistentAt(*sphere, P(1, 2, 3), "sphere centre");
  PointType lower, upper;
  sphere->GetBounds(lower, upper);
  ITK_EXPECT_VECTOR_NEAR(lower, P(-1, 0, 1), 0);
  ITK_EXPECT_VECTOR_NEAR(upper, P(3, 4, 5), 0);
}

TEST(SphereImplicitSurface, NonPositiveOrNaNRadiusThrowsNamingTheRadius)
{
  auto sphere = itk::SphereImplicitSurface::New();
  for (const double r : { 0.0, -1.0, std::nan(""), std::numeric_limits<double>::infinity() })
  {
    ExpectThrowsMentioning([&] { sphere->SetRadius(r); }, "Radius");
  }
  EXPECT_EQ(sphere->GetRadius(), 1.0);
}
