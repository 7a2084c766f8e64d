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
#include "itkSphereDifferenceImplicitSurface.h"
#include "itkImplicitSurfaceTestHelpers.h"

using namespace ImplicitSurfaceTest;

TEST(SphereDifferenceImplicitSurface, DistanceMatchesClosedFormsInTheDentAndAtTheCrease)
{
  auto d = itk::SphereDifferenceImplicitSurface::New();
  d->SetCenterA(P(0, 0, 0));
  d->SetRadiusA(1);
  d->SetCenterB(P(1, 0, 0));
  d->SetRadiusB(0.5);
  EXPECT_NEAR(d->Evaluate(P(0, 0, 0)), -0.5, 1e-12);  // A's centre: the bottom of the dent
  EXPECT_NEAR(d->Evaluate(P(0.6, 0, 0)), 0.1, 1e-12); // in the dent
  EXPECT_NEAR(d->Evaluate(P(-1.5, 0, 0)), 0.5, 1e-12);
  EXPECT_NEAR(d->Evaluate(P(-0.5, 0, 0)), -0.5, 1e-12);
  // Crease circle: centre (0.875, 0, 0), radius sqrt(1 - 0.875^2).
  const double    rho = std::sqrt(1.0 - 0.875 * 0.875);
  const PointType inDentNearRim = P(0.95, 0.45, 0);
  EXPECT_NEAR(d->Evaluate(inDentNearRim), std::hypot(0.95 - 0.875, 0.45 - rho), 1e-12);
  ITK_EXPECT_VECTOR_NEAR(d->ClosestSurfacePoint(inDentNearRim), P(0.875, rho, 0), 1e-12);
  for (const PointType & p : { P(0, 0, 0), P(1, 0, 0), P(0.6, 0, 0), P(0.95, 0.45, 0), P(0.875, 0, 0) })
  {
    ExpectConsistentAt(*d, p, "indented sphere");
  }
}

TEST(SphereDifferenceImplicitSurface, BruteForceSamplingAgreesWithTheExactDistance)
{
  const PointType a = P(0, 0, 0), b = P(2, 1, -1);
  const double    ra = 3, rb = 1.5;
  auto            d = itk::SphereDifferenceImplicitSurface::New();
  d->SetCenterA(a);
  d->SetRadiusA(ra);
  d->SetCenterB(b);
  d->SetRadiusB(rb);
  std::vector<PointType> samples;
  double                 gapA = 0.0, gapB = 0.0;
  for (const PointType & s : SampleSphere(a, ra, 300, gapA))
  {
    if (s.EuclideanDistanceTo(b) >= rb)
    {
      samples.push_back(s);
    }
  }
  for (const PointType & s : SampleSphere(b, rb, 300, gapB))
  {
    if (s.EuclideanDistanceTo(a) <= ra)
    {
      samples.push_back(s);
    }
  }
  auto queries = RandomPointsAround(*d, 80, 81);
  queries.push_back(b);
  queries.push_back(a);
  ExpectBruteForceAgrees(*d, samples, std::max(gapA, gapB), queries, "difference");
}

TEST(SphereDifferenceImplicitSurface, EmptyDifferenceOrBadRadiusThrows)
{
  auto d = itk::SphereDifferenceImplicitSurface::New();
  ExpectThrowsMentioning([&] { d->SetRadiusB(0); }, "RadiusB");
  d->SetCenterB(P(0.2, 0, 0));
  d->SetRadiusB(2); // contains A
  ExpectThrowsMentioning([&] { d->Evaluate(P(0, 0, 0)); }, "contains ball A");
}
