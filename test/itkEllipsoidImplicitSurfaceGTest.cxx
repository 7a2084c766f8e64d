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
#include "itkEllipsoidImplicitSurface.h"
#include "itkSphereImplicitSurface.h"
#include "itkImplicitSurfaceTestHelpers.h"

using namespace ImplicitSurfaceTest;

TEST(EllipsoidImplicitSurface, DistanceOnTheAxesAndAtTheCentreMatchesClosedForms)
{
  const double a = 5, b = 3, c = 2;
  // Every order of the semi-axes, so that the internal sorting is exercised.
  const double orders[6][3] = { { a, b, c }, { a, c, b }, { b, a, c }, { b, c, a }, { c, a, b }, { c, b, a } };
  for (const auto & order : orders)
  {
    auto e = itk::EllipsoidImplicitSurface::New();
    e->SetSemiAxes(V(order[0], order[1], order[2]));
    // Centre: the end of the shortest axis is closest.
    EXPECT_NEAR(e->Evaluate(P(0, 0, 0)), -c, 1e-12);
    ExpectConsistentAt(*e, P(0, 0, 0), "ellipsoid centre");
    for (unsigned int k = 0; k < 3; ++k)
    {
      const double s = order[k];
      PointType    outside = P(0, 0, 0);
      outside[k] = s + 1.25;
      EXPECT_NEAR(e->Evaluate(outside), 1.25, 1e-12) << "axis " << k;
      outside[k] = -(s + 0.5);
      EXPECT_NEAR(e->Evaluate(outside), 0.5, 1e-12) << "axis " << k;
      // Inside on an axis, close to the end of it: that end is closest.
      PointType inside = P(0, 0, 0);
      inside[k] = s - 0.1 * c;
      if (s == c)
      {
        EXPECT_NEAR(e->Evaluate(inside), -0.1 * c, 1e-12);
      }
      // Inside on a longer axis, near the centre: the closest point leaves the axis
      // (Eberly's "y_last = 0" case): d = c sqrt(1 - x^2 / (s^2 - c^2)) for
      // |x| < (s^2 - c^2) / s.
      if (s > c)
      {
        const double x = 0.3 * (s * s - c * c) / s;
        inside[k] = x;
        EXPECT_NEAR(e->Evaluate(inside), -c * std::sqrt(1.0 - x * x / (s * s - c * c)), 1e-12) << "axis " << k;
        ExpectConsistentAt(*e, inside, "ellipsoid inside on an axis");
      }
    }
  }
}

TEST(EllipsoidImplicitSurface, PointToClosestPointIsAlongTheSurfaceNormal)
{
  auto e = itk::EllipsoidImplicitSurface::New();
  e->SetSemiAxes(V(2, 5, 3));
  PointType lower, upper;
  e->GetBounds(lower, upper);
  for (const PointType & p : RandomPoints(lower, upper, 2.0, 2000, 41))
  {
    const PointType q = e->ClosestSurfacePoint(p);
    VectorType      n = V(q[0] / 4.0, q[1] / 25.0, q[2] / 9.0);
    n.Normalize();
    const VectorType r = p - q;
    // p - q is parallel to the normal, pointing out when p is outside.
    EXPECT_NEAR(itk::CrossProduct(r, n).GetNorm(), 0.0, 1e-9) << p;
    EXPECT_NEAR(r * n, e->Evaluate(p), 1e-9) << p;
  }
}

TEST(EllipsoidImplicitSurface, SphereCaseEqualsTheSphereDistance)
{
  auto e = itk::EllipsoidImplicitSurface::New();
  e->SetCenter(P(1, 1, 1));
  e->SetSemiAxes(V(2, 2, 2));
  auto s = itk::SphereImplicitSurface::New();
  s->SetCenter(P(1, 1, 1));
  s->SetRadius(2);
  for (const PointType & p : RandomPoints(P(-2, -2, -2), P(4, 4, 4), 0.0, 500, 42))
  {
    EXPECT_NEAR(e->Evaluate(p), s->Evaluate(p), 1e-12) << p;
  }
}

TEST(EllipsoidImplicitSurface, RotationAndTranslationMoveTheDistanceField)
{
  auto local = itk::EllipsoidImplicitSurface::New();
  local->SetSemiAxes(V(4, 2.5, 1));
  auto moved = itk::EllipsoidImplicitSurface::New();
  moved->SetSemiAxes(V(4, 2.5, 1));
  const MatrixType r = Rotation(0.4, 1.0, -0.6);
  const PointType  c = P(3, -2, 7);
  moved->SetCenter(c);
  moved->SetRotation(r);
  for (const PointType & q : RandomPoints(P(-5, -5, -5), P(5, 5, 5), 0.0, 500, 43))
  {
    EXPECT_NEAR(moved->Evaluate(Transform(r, c, q)), local->Evaluate(q), 1e-9) << q;
  }
  PointType lower, upper;
  moved->GetBounds(lower, upper);
  // The bounds are tight: the support of the ellipsoid along each axis.
  for (unsigned int i = 0; i < 3; ++i)
  {
    PointType probe = c;
    probe[i] = upper[i];
    EXPECT_GT(moved->Evaluate(probe), -Tolerance);
  }
}

TEST(EllipsoidImplicitSurface, BruteForceSamplingAgreesWithTheExactDistance)
{
  const double a = 4, b = 2.5, c = 1;
  auto         e = itk::EllipsoidImplicitSurface::New();
  e->SetSemiAxes(V(a, b, c));
  std::vector<PointType> samples;
  const unsigned int     n = 400;
  const double           dTheta = itk::Math::pi / n;
  const double           dPhi = 2.0 * itk::Math::pi / (2 * n);
  for (unsigned int i = 0; i <= n; ++i)
  {
    for (unsigned int j = 0; j < 2 * n; ++j)
    {
      const double t = i * dTheta;
      const double f = j * dPhi;
      samples.push_back(P(a * std::sin(t) * std::cos(f), b * std::sin(t) * std::sin(f), c * std::cos(t)));
    }
  }
  auto queries = RandomPoints(P(-a, -b, -c), P(a, b, c), 1.0, 60, 44);
  // Points on the principal planes, the axes and the centre.
  for (const PointType & special :
       { P(0, 0, 0), P(1, 0, 0), P(0, 1, 0), P(0.5, 0.4, 0), P(2, 0, 0.3), P(0, 1.5, 0.2), P(5, 0, 0), P(0, 0, 2) })
  {
    queries.push_back(special);
  }
  ExpectBruteForceAgrees(*e, samples, a * (dTheta + dPhi), queries, "ellipsoid");
}

TEST(EllipsoidImplicitSurface, InvalidSemiAxesOrRotationThrow)
{
  auto e = itk::EllipsoidImplicitSurface::New();
  ExpectThrowsMentioning([&] { e->SetSemiAxes(V(1, 0, 1)); }, "SemiAxes");
  ExpectThrowsMentioning([&] { e->SetSemiAxes(V(1, 2, -3)); }, "SemiAxes");
  MatrixType skew;
  skew.SetIdentity();
  skew(0, 1) = 0.1;
  ExpectThrowsMentioning([&] { e->SetRotation(skew); }, "Rotation");
}
