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
#include "itkSphereUnionImplicitSurface.h"
#include "itkImplicitSurfaceTestHelpers.h"

using namespace ImplicitSurfaceTest;

TEST(SphereUnionImplicitSurface, InsideDistanceUsesTheIntersectionCircleAtTheCrease)
{
  // Two unit spheres whose centres are one radius apart.
  auto u = itk::SphereUnionImplicitSurface::New();
  u->AddSphere(P(0, 0, 0), 1);
  u->AddSphere(P(1, 0, 0), 1);
  const double rho = std::sqrt(0.75); // crease circle: centre (0.5, 0, 0), radius rho
  EXPECT_NEAR(u->Evaluate(P(0.5, 0, 0)), -rho, 1e-12);
  EXPECT_NEAR(u->Evaluate(P(0.5, 0.3, 0)), -(rho - 0.3), 1e-12);
  ITK_EXPECT_VECTOR_NEAR(u->ClosestSurfacePoint(P(0.5, 0.3, 0)), P(0.5, rho, 0), 1e-12);
  EXPECT_NEAR(u->Evaluate(P(0, 0, 0)), -1.0, 1e-12); // a centre: the far side of its sphere
  EXPECT_NEAR(u->Evaluate(P(-0.5, 0, 0)), -0.5, 1e-12);
  EXPECT_NEAR(u->Evaluate(P(3, 0, 0)), 1.0, 1e-12);
  // Outside near the crease: the nearer sphere's radial projection.
  EXPECT_NEAR(u->Evaluate(P(0.5, 1.0, 0)), std::sqrt(1.25) - 1.0, 1e-12);
  for (const PointType & p : { P(0.5, 0, 0), P(0, 0, 0), P(1, 0, 0), P(0.5, 0.3, 0), P(0.5, 0.866, 0.01) })
  {
    ExpectConsistentAt(*u, p, "two spheres");
  }
}

TEST(SphereUnionImplicitSurface, OutsideDistanceIsTheSmallestSphereDistance)
{
  auto u = itk::SphereUnionImplicitSurface::New();
  u->AddSphere(P(0, 0, 0), 1.5);
  u->AddSphere(P(2, 0.3, 0), 1.2);
  u->AddSphere(P(1, 1.6, 0.4), 1.3);
  for (const PointType & p : RandomPointsAround(*u, 1000, 71))
  {
    double smallest = std::numeric_limits<double>::infinity();
    for (unsigned int i = 0; i < u->GetNumberOfSpheres(); ++i)
    {
      smallest = std::min(smallest, p.EuclideanDistanceTo(u->GetSphereCenter(i)) - u->GetSphereRadius(i));
    }
    if (smallest > 0.0)
    {
      EXPECT_NEAR(u->Evaluate(p), smallest, 1e-12) << p;
    }
    else
    {
      EXPECT_LE(u->Evaluate(p), 0.0) << p;
      EXPECT_LE(u->Evaluate(p), smallest + 1e-12) << p; // never shallower than the deepest ball
    }
  }
}

TEST(SphereUnionImplicitSurface, InsideThreeSpheresTheTriplePointIsClosest)
{
  // Three unit spheres with centres on an equilateral triangle of side 1.
  auto u = itk::SphereUnionImplicitSurface::New();
  u->AddSphere(P(0, 0, 0), 1);
  u->AddSphere(P(1, 0, 0), 1);
  u->AddSphere(P(0.5, std::sqrt(0.75), 0), 1);
  const PointType centroid = P(0.5, std::sqrt(0.75) / 3.0, 0);
  EXPECT_NEAR(u->Evaluate(centroid), -std::sqrt(2.0 / 3.0), 1e-12);
  const PointType q = u->ClosestSurfacePoint(centroid);
  EXPECT_NEAR(q[0], centroid[0], 1e-12);
  EXPECT_NEAR(q[1], centroid[1], 1e-12);
  EXPECT_NEAR(std::abs(q[2]), std::sqrt(2.0 / 3.0), 1e-12);
}

TEST(SphereUnionImplicitSurface, BruteForceSamplingAgreesWithTheExactDistance)
{
  auto u = itk::SphereUnionImplicitSurface::New();
  u->AddSphere(P(0, 0, 0), 1.5);
  u->AddSphere(P(2, 0.3, 0), 1.2);
  u->AddSphere(P(1, 1.6, 0.4), 1.3);
  std::vector<PointType> samples;
  double                 gap = 0.0;
  for (unsigned int i = 0; i < u->GetNumberOfSpheres(); ++i)
  {
    double     g = 0.0;
    const auto all = SampleSphere(u->GetSphereCenter(i), u->GetSphereRadius(i), 300, g);
    gap = std::max(gap, g);
    for (const PointType & s : all)
    {
      bool covered = false;
      for (unsigned int j = 0; j < u->GetNumberOfSpheres(); ++j)
      {
        covered = covered || (j != i && s.EuclideanDistanceTo(u->GetSphereCenter(j)) < u->GetSphereRadius(j));
      }
      if (!covered)
      {
        samples.push_back(s);
      }
    }
  }
  auto queries = RandomPointsAround(*u, 80, 72);
  queries.push_back(P(1, 0.5, 0.1)); // deep inside, where all three overlap
  queries.push_back(P(0, 0, 0));     // a centre
  ExpectBruteForceAgrees(*u, samples, gap, queries, "union");
}

TEST(SphereUnionImplicitSurface, EmptyUnionOrBadSphereOrIndexThrows)
{
  auto u = itk::SphereUnionImplicitSurface::New();
  EXPECT_FALSE(u->AreParametersValid());
  ExpectThrowsMentioning([&] { u->Evaluate(P(0, 0, 0)); }, "AddSphere");
  ExpectThrowsMentioning([&] { u->AddSphere(P(0, 0, 0), -1); }, "radius");
  u->AddSphere(P(0, 0, 0), 1);
  EXPECT_TRUE(u->AreParametersValid());
  ExpectThrowsMentioning([&] { u->GetSphereRadius(1); }, "out of range");
  u->RemoveAllSpheres();
  EXPECT_FALSE(u->AreParametersValid());
}
