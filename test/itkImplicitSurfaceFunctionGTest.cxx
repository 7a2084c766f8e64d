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
#include "itkImplicitSurfaceFunction.h"
#include "itkMeshExtractionPhantoms.h"
#include "itkGTest.h"

#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace
{
using SurfaceType = itk::ImplicitSurfaceFunction;
using PointType = SurfaceType::InputType;
using VectorType = SurfaceType::VectorType;
using MatrixType = SurfaceType::MatrixType;

constexpr double Tolerance = 1e-9;

PointType
P(double x, double y, double z)
{
  PointType p;
  p[0] = x;
  p[1] = y;
  p[2] = z;
  return p;
}

VectorType
V(double x, double y, double z)
{
  VectorType v;
  v[0] = x;
  v[1] = y;
  v[2] = z;
  return v;
}

/** A proper rotation from Euler angles (radians), R = Rz(a) Ry(b) Rx(c). */
MatrixType
Rotation(double a, double b, double c)
{
  MatrixType rz, ry, rx;
  rz.SetIdentity();
  ry.SetIdentity();
  rx.SetIdentity();
  rz(0, 0) = std::cos(a);
  rz(0, 1) = -std::sin(a);
  rz(1, 0) = std::sin(a);
  rz(1, 1) = std::cos(a);
  ry(0, 0) = std::cos(b);
  ry(0, 2) = std::sin(b);
  ry(2, 0) = -std::sin(b);
  ry(2, 2) = std::cos(b);
  rx(1, 1) = std::cos(c);
  rx(1, 2) = -std::sin(c);
  rx(2, 1) = std::sin(c);
  rx(2, 2) = std::cos(c);
  return rz * ry * rx;
}

PointType
Transform(const MatrixType & r, const PointType & center, const PointType & local)
{
  VectorType v = r * V(local[0], local[1], local[2]);
  return center + v;
}

/** Uniform random points in the box [lower - margin, upper + margin]. */
std::vector<PointType>
RandomPoints(const PointType & lower, const PointType & upper, double margin, unsigned int count, unsigned int seed)
{
  std::mt19937_64                        generator(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<PointType>                 points;
  for (unsigned int n = 0; n < count; ++n)
  {
    PointType p;
    for (unsigned int i = 0; i < 3; ++i)
    {
      const double lo = lower[i] - margin;
      const double hi = upper[i] + margin;
      p[i] = lo + (hi - lo) * unit(generator);
    }
    points.push_back(p);
  }
  return points;
}

std::vector<PointType>
RandomPointsAround(const SurfaceType & surface, unsigned int count, unsigned int seed)
{
  PointType lower, upper;
  surface.GetBounds(lower, upper);
  double size = 0.0;
  for (unsigned int i = 0; i < 3; ++i)
  {
    if (!std::isfinite(lower[i]) || !std::isfinite(upper[i]))
    {
      lower[i] = -10.0;
      upper[i] = 10.0;
    }
    size = std::max(size, upper[i] - lower[i]);
  }
  return RandomPoints(lower, upper, 0.25 * size, count, seed);
}

/** The checks every exact signed distance function passes at `p`. */
void
ExpectConsistentAt(const SurfaceType & surface, const PointType & p, const std::string & what)
{
  const double    d = surface.Evaluate(p);
  const PointType q = surface.ClosestSurfacePoint(p);
  PointType       q2;
  const double    d2 = surface.EvaluateWithClosestPoint(p, q2);
  EXPECT_NEAR(std::abs(d), p.EuclideanDistanceTo(q), Tolerance) << what << " at " << p;
  EXPECT_NEAR(surface.Evaluate(q), 0.0, Tolerance) << what << " at " << p << ", closest " << q;
  EXPECT_EQ(d, d2) << what << " at " << p;
  EXPECT_NEAR(q.EuclideanDistanceTo(q2), 0.0, Tolerance) << what << " at " << p;
  EXPECT_EQ(surface.IsInside(p), d <= 0.0) << what << " at " << p;
  PointType lower, upper;
  surface.GetBounds(lower, upper);
  for (unsigned int i = 0; i < 3; ++i)
  {
    EXPECT_GE(q[i], lower[i] - Tolerance) << what << " closest point " << q << " outside the bounds";
    EXPECT_LE(q[i], upper[i] + Tolerance) << what << " closest point " << q << " outside the bounds";
  }
}

/** Named surfaces covering every class, with rotations and offsets. */
std::vector<std::pair<std::string, SurfaceType::Pointer>>
AllSurfaces()
{
  std::vector<std::pair<std::string, SurfaceType::Pointer>> surfaces;
  {
    auto s = itk::PlaneImplicitSurface::New();
    s->SetPoint(P(1, -2, 0.5));
    s->SetNormal(V(1, 2, 3));
    surfaces.emplace_back("plane", s.GetPointer());
  }
  {
    auto s = itk::SphereImplicitSurface::New();
    s->SetCenter(P(1, 2, 3));
    s->SetRadius(2.5);
    surfaces.emplace_back("sphere", s.GetPointer());
  }
  {
    auto s = itk::EllipsoidImplicitSurface::New();
    s->SetCenter(P(-1, 0.5, 2));
    s->SetSemiAxes(V(2, 5, 3));
    s->SetRotation(Rotation(0.3, -0.7, 1.1));
    surfaces.emplace_back("ellipsoid", s.GetPointer());
  }
  {
    auto s = itk::EllipsoidImplicitSurface::New();
    s->SetSemiAxes(V(4, 4, 1.5)); // oblate spheroid: ties in the axis order
    surfaces.emplace_back("oblate spheroid", s.GetPointer());
  }
  {
    auto s = itk::EllipsoidImplicitSurface::New();
    s->SetSemiAxes(V(1.5, 4, 1.5)); // prolate spheroid
    surfaces.emplace_back("prolate spheroid", s.GetPointer());
  }
  {
    auto s = itk::TorusImplicitSurface::New();
    s->SetCenter(P(0.5, 0, -1));
    s->SetAxis(V(1, 1, 4));
    s->SetRadii(4, 1.5);
    surfaces.emplace_back("torus", s.GetPointer());
  }
  {
    auto s = itk::BoxImplicitSurface::New();
    s->SetCenter(P(2, 1, 0));
    s->SetHalfSizes(V(3, 2, 0.5));
    s->SetRotation(Rotation(0.2, 0.4, -0.3));
    surfaces.emplace_back("box", s.GetPointer());
  }
  {
    auto s = itk::SphereUnionImplicitSurface::New();
    s->AddSphere(P(0, 0, 0), 2);
    s->AddSphere(P(2, 0, 0), 2);
    surfaces.emplace_back("two spheres", s.GetPointer());
  }
  {
    auto s = itk::SphereUnionImplicitSurface::New();
    s->AddSphere(P(0, 0, 0), 1.5);
    s->AddSphere(P(2, 0.3, 0), 1.2);
    s->AddSphere(P(1, 1.6, 0.4), 1.3);
    s->AddSphere(P(5, 0, 0), 0.7); // disjoint from the others
    surfaces.emplace_back("four spheres", s.GetPointer());
  }
  {
    auto s = itk::SphereDifferenceImplicitSurface::New();
    s->SetCenterA(P(0, 0, 0));
    s->SetRadiusA(3);
    s->SetCenterB(P(2, 1, -1));
    s->SetRadiusB(1.5);
    surfaces.emplace_back("indented sphere", s.GetPointer());
  }
  {
    auto s = itk::SphereDifferenceImplicitSurface::New();
    s->SetCenterA(P(0, 0, 0));
    s->SetRadiusA(3);
    s->SetCenterB(P(0.5, 0, 0));
    s->SetRadiusB(1);
    surfaces.emplace_back("hollow sphere", s.GetPointer());
  }
  {
    auto s = itk::NarrowCleftImplicitSurface::New();
    s->SetCenter(P(1, 2, 3));
    s->SetHalfSizes(V(5, 4, 3));
    s->SetSlotWidth(1.5);
    s->SetSlotDepth(4);
    s->SetRotation(Rotation(-0.4, 0.25, 0.6));
    surfaces.emplace_back("narrow cleft", s.GetPointer());
  }
  for (const auto shape : itk::MeshExtraction::AllPhantomShapes())
  {
    std::ostringstream name;
    name << "phantom " << shape;
    const auto grid = itk::MeshExtraction::DefaultPhantomGrid(shape);
    surfaces.emplace_back(name.str(), itk::MeshExtraction::MakePhantomSurface(shape, grid));
  }
  return surfaces;
}

/** Dense samples of a sphere's surface (latitude-longitude), and the largest
 * distance from any surface point to its nearest sample. */
std::vector<PointType>
SampleSphere(const PointType & c, double r, unsigned int n, double & gap)
{
  std::vector<PointType> samples;
  const double           dTheta = itk::Math::pi / n;
  const double           dPhi = 2.0 * itk::Math::pi / (2 * n);
  for (unsigned int i = 0; i <= n; ++i)
  {
    const double theta = i * dTheta;
    for (unsigned int j = 0; j < 2 * n; ++j)
    {
      const double phi = j * dPhi;
      samples.push_back(P(c[0] + r * std::sin(theta) * std::cos(phi),
                          c[1] + r * std::sin(theta) * std::sin(phi),
                          c[2] + r * std::cos(theta)));
    }
  }
  gap = r * (dTheta + dPhi);
  return samples;
}

/** The sampled surface is never closer than the exact distance, and the exact
 * distance is within the sampling gap of the sampled one. */
void
ExpectBruteForceAgrees(const SurfaceType &            surface,
                       const std::vector<PointType> & samples,
                       double                         gap,
                       const std::vector<PointType> & queries,
                       const std::string &            what)
{
  ASSERT_FALSE(samples.empty());
  for (const PointType & p : queries)
  {
    double sampled = std::numeric_limits<double>::infinity();
    for (const PointType & s : samples)
    {
      sampled = std::min(sampled, p.EuclideanDistanceTo(s));
    }
    const double exact = std::abs(surface.Evaluate(p));
    EXPECT_GE(sampled, exact - Tolerance) << what << " at " << p;
    EXPECT_LE(sampled, exact + gap) << what << " at " << p;
  }
}

void
ExpectThrowsMentioning(const std::function<void()> & action, const std::string & word)
{
  try
  {
    action();
    ADD_FAILURE() << "expected an itk::ExceptionObject mentioning " << word;
  }
  catch (const itk::ExceptionObject & e)
  {
    EXPECT_NE(std::string(e.GetDescription()).find(word), std::string::npos) << e.GetDescription();
  }
}
} // namespace

// ---------------------------------------------------------------------------------
// Properties shared by every surface
// ---------------------------------------------------------------------------------

TEST(ImplicitSurfaceFunction, DistanceEqualsDistanceToClosestPointWhichLiesOnTheSurface)
{
  for (const auto & entry : AllSurfaces())
  {
    for (const PointType & p : RandomPointsAround(*entry.second, 300, 11))
    {
      ExpectConsistentAt(*entry.second, p, entry.first);
    }
  }
}

TEST(ImplicitSurfaceFunction, IsOneLipschitzOnRandomPointPairs)
{
  for (const auto & entry : AllSurfaces())
  {
    const auto                       a = RandomPointsAround(*entry.second, 500, 21);
    const auto                       b = RandomPointsAround(*entry.second, 500, 22);
    std::mt19937_64                  generator(23);
    std::normal_distribution<double> normal(0.0, 0.05);
    for (size_t i = 0; i < a.size(); ++i)
    {
      // Far pairs and near pairs (where a wrong sign or a bound would show first).
      PointType near = a[i];
      for (unsigned int k = 0; k < 3; ++k)
      {
        near[k] += normal(generator);
      }
      for (const PointType & q : { b[i], near })
      {
        const double difference = std::abs(entry.second->Evaluate(a[i]) - entry.second->Evaluate(q));
        EXPECT_LE(difference, a[i].EuclideanDistanceTo(q) + Tolerance) << entry.first << " " << a[i] << " " << q;
      }
    }
  }
}

TEST(ImplicitSurfaceFunction, DistanceIsExactBecauseNoSurfacePointIsCloserThanTheClaimedDistance)
{
  // Along the segment from p to its closest point q the distance must fall linearly
  // (|d| decreases by exactly the step), which a bound or approximation violates.
  for (const auto & entry : AllSurfaces())
  {
    for (const PointType & p : RandomPointsAround(*entry.second, 100, 31))
    {
      const PointType q = entry.second->ClosestSurfacePoint(p);
      const double    d = entry.second->Evaluate(p);
      for (const double t : { 0.25, 0.5, 0.75 })
      {
        const PointType m = p + (q - p) * t;
        EXPECT_NEAR(entry.second->Evaluate(m), d * (1.0 - t), 1e-8) << entry.first << " at " << p;
      }
    }
  }
}

TEST(ImplicitSurfaceFunction, PrintSelfNamesTheClassAndParameters)
{
  for (const auto & entry : AllSurfaces())
  {
    std::ostringstream os;
    entry.second->Print(os);
    EXPECT_NE(os.str().find(entry.second->GetNameOfClass()), std::string::npos) << entry.first;
    EXPECT_NE(os.str().find("ParametersValid: true"), std::string::npos) << entry.first;
  }
}

TEST(ImplicitSurfaceFunction, SettingAParameterUpdatesTheModifiedTime)
{
  auto                        sphere = itk::SphereImplicitSurface::New();
  const itk::ModifiedTimeType before = sphere->GetMTime();
  sphere->SetRadius(3.0);
  EXPECT_GT(sphere->GetMTime(), before);
}

// ---------------------------------------------------------------------------------
// Plane
// ---------------------------------------------------------------------------------

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

// ---------------------------------------------------------------------------------
// Sphere
// ---------------------------------------------------------------------------------

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

// ---------------------------------------------------------------------------------
// Ellipsoid
// ---------------------------------------------------------------------------------

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

// ---------------------------------------------------------------------------------
// Torus
// ---------------------------------------------------------------------------------

TEST(TorusImplicitSurface, DistanceMatchesClosedFormsOnAxisPlaneAndTube)
{
  auto torus = itk::TorusImplicitSurface::New();
  torus->SetRadii(3, 1);
  EXPECT_NEAR(torus->Evaluate(P(0, 0, 0)), 2.0, 1e-15);                         // centre
  EXPECT_NEAR(torus->Evaluate(P(0, 0, 4)), std::sqrt(9.0 + 16.0) - 1.0, 1e-15); // on the axis
  EXPECT_NEAR(torus->Evaluate(P(3, 0, 0)), -1.0, 1e-15);                        // core circle
  EXPECT_NEAR(torus->Evaluate(P(0, -3, 0.25)), -0.75, 1e-15);                   // inside the tube
  EXPECT_NEAR(torus->Evaluate(P(6, 0, 0)), 2.0, 1e-15);                         // outside, equator
  EXPECT_NEAR(torus->Evaluate(P(0, 3, 2)), 1.0, 1e-15);                         // above the core
  ExpectConsistentAt(*torus, P(0, 0, 0), "torus centre");
  ExpectConsistentAt(*torus, P(3, 0, 0), "torus core circle");
  ExpectConsistentAt(*torus, P(0, 0, 4), "torus axis");
}

TEST(TorusImplicitSurface, TiltedAxisMovesTheDistanceField)
{
  auto local = itk::TorusImplicitSurface::New();
  local->SetRadii(4, 1.5);
  auto             moved = itk::TorusImplicitSurface::New();
  const MatrixType r = Rotation(0.3, 0.8, 0.1);
  const PointType  c = P(1, -1, 2);
  moved->SetCenter(c);
  moved->SetAxis(r * V(0, 0, 7)); // any length
  moved->SetRadii(4, 1.5);
  for (const PointType & q : RandomPoints(P(-6, -6, -3), P(6, 6, 3), 0.0, 500, 51))
  {
    EXPECT_NEAR(moved->Evaluate(Transform(r, c, q)), local->Evaluate(q), 1e-9) << q;
  }
}

TEST(TorusImplicitSurface, MinorRadiusNotBelowMajorRadiusIsRejectedWhenUsed)
{
  auto torus = itk::TorusImplicitSurface::New();
  ExpectThrowsMentioning([&] { torus->SetMinorRadius(0); }, "MinorRadius");
  ExpectThrowsMentioning([&] { torus->SetMajorRadius(-2); }, "MajorRadius");
  ExpectThrowsMentioning([&] { torus->SetAxis(V(0, 0, 0)); }, "Axis");
  // Changing both radii one at a time may pass through an invalid state...
  torus->SetMinorRadius(5);
  EXPECT_FALSE(torus->AreParametersValid());
  ExpectThrowsMentioning([&] { torus->Evaluate(P(0, 0, 0)); }, "MinorRadius");
  ExpectThrowsMentioning([&] { torus->VerifyParameters(); }, "MajorRadius");
  // ... and is accepted once the combination is valid.
  torus->SetMajorRadius(10);
  EXPECT_TRUE(torus->AreParametersValid());
  EXPECT_NEAR(torus->Evaluate(P(0, 0, 0)), 5.0, 1e-15);
  ExpectThrowsMentioning(
    [&] {
      torus->SetRadii(2, 2);
      torus->Evaluate(P(0, 0, 0));
    },
    "MinorRadius");
}

// ---------------------------------------------------------------------------------
// Box
// ---------------------------------------------------------------------------------

TEST(BoxImplicitSurface, DistanceToFacesEdgesAndCornersMatchesClosedForms)
{
  auto box = itk::BoxImplicitSurface::New();
  box->SetHalfSizes(V(3, 2, 1));
  EXPECT_NEAR(box->Evaluate(P(0, 0, 0)), -1.0, 1e-15);                        // centre: nearest face z
  EXPECT_NEAR(box->Evaluate(P(2.5, 0, 0)), -0.5, 1e-15);                      // nearest face x
  EXPECT_NEAR(box->Evaluate(P(5, 0, 0)), 2.0, 1e-15);                         // outside a face
  EXPECT_NEAR(box->Evaluate(P(4, 3, 0)), std::sqrt(2.0), 1e-15);              // outside an edge
  EXPECT_NEAR(box->Evaluate(P(4, -3, 3)), std::sqrt(1.0 + 1.0 + 4.0), 1e-15); // corner
  ExpectConsistentAt(*box, P(0, 0, 0), "box centre");
  ExpectConsistentAt(*box, P(2.5, 1.5, 0.5), "box inside near a corner");
}

TEST(BoxImplicitSurface, RotationAndTranslationMoveTheDistanceField)
{
  auto local = itk::BoxImplicitSurface::New();
  local->SetHalfSizes(V(3, 2, 0.25));
  auto             moved = itk::BoxImplicitSurface::New();
  const MatrixType r = Rotation(-0.5, 0.2, 0.9);
  const PointType  c = P(10, 0, -3);
  moved->SetHalfSizes(V(3, 2, 0.25));
  moved->SetCenter(c);
  moved->SetRotation(r);
  for (const PointType & q : RandomPoints(P(-4, -3, -1), P(4, 3, 1), 0.0, 500, 61))
  {
    EXPECT_NEAR(moved->Evaluate(Transform(r, c, q)), local->Evaluate(q), 1e-9) << q;
  }
}

TEST(BoxImplicitSurface, NonPositiveHalfSizeThrows)
{
  auto box = itk::BoxImplicitSurface::New();
  ExpectThrowsMentioning([&] { box->SetHalfSizes(V(1, 1, 0)); }, "HalfSizes");
}

// ---------------------------------------------------------------------------------
// Union of spheres
// ---------------------------------------------------------------------------------

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

// ---------------------------------------------------------------------------------
// Sphere difference (indented sphere)
// ---------------------------------------------------------------------------------

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

// ---------------------------------------------------------------------------------
// Narrow cleft
// ---------------------------------------------------------------------------------

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

TEST(NarrowCleftImplicitSurface, BruteForceSamplingAgreesWithTheExactDistance)
{
  auto cleft = itk::NarrowCleftImplicitSurface::New();
  cleft->SetHalfSizes(V(5, 4, 3));
  cleft->SetSlotWidth(1.5);
  cleft->SetSlotDepth(4);
  // Sample the boundary of the solid: every grid point of the bounding box's faces
  // and of the slot's faces that is on the boundary (|Evaluate| tiny is not used:
  // membership is decided geometrically).
  const double           X = 5, Y = 4, Z = 3, s = 0.75, f = Z - 4;
  const double           h = 0.05;
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
  auto queries = RandomPointsAround(*cleft, 80, 92);
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

// ---------------------------------------------------------------------------------
// Phantoms
// ---------------------------------------------------------------------------------

TEST(MeshExtractionPhantoms, NamesRoundTripAndUnknownNamesListTheValidOnes)
{
  using namespace itk::MeshExtraction;
  const std::vector<std::string> expected = { "plane",           "sphere",     "two-spheres",
                                              "chapter4-sphere", "ellipsoid",  "indented-sphere",
                                              "torus",           "thin-plate", "narrow-cleft" };
  const auto                     shapes = AllPhantomShapes();
  ASSERT_EQ(shapes.size(), expected.size());
  for (size_t i = 0; i < shapes.size(); ++i)
  {
    EXPECT_EQ(PhantomShapeName(shapes[i]), expected[i]);
    EXPECT_EQ(PhantomShapeFromName(expected[i]), shapes[i]);
    std::ostringstream os;
    os << shapes[i];
    EXPECT_EQ(os.str(), expected[i]);
  }
  try
  {
    PhantomShapeFromName("cube");
    ADD_FAILURE() << "no exception for an unknown name";
  }
  catch (const itk::ExceptionObject & e)
  {
    const std::string message = e.GetDescription();
    EXPECT_NE(message.find("cube"), std::string::npos);
    for (const auto & name : expected)
    {
      EXPECT_NE(message.find(name), std::string::npos) << name;
    }
  }
}

TEST(MeshExtractionPhantoms, DefaultGridsAndImageModesFollowTheThesis)
{
  using namespace itk::MeshExtraction;
  for (const auto shape : AllPhantomShapes())
  {
    const PhantomGrid grid = DefaultPhantomGrid(shape);
    const unsigned    n = shape == PhantomShape::Chapter4Sphere ? 100 : 64;
    for (unsigned int k = 0; k < 3; ++k)
    {
      EXPECT_EQ(grid.size[k], n) << shape;
      EXPECT_EQ(grid.spacing[k], 1.0) << shape;
    }
    const auto parameters = DefaultPhantomImageParameters(shape);
    EXPECT_EQ(DefaultPhantomImageMode(shape), parameters.mode);
    if (shape == PhantomShape::Chapter4Sphere)
    {
      EXPECT_EQ(parameters.mode, itk::MeshExtractionEnums::PhantomImage::BlurredStep);
      EXPECT_EQ(parameters.insideValue, 100.0);
      EXPECT_EQ(parameters.outsideValue, 0.0);
      EXPECT_EQ(parameters.edgeWidth, 1.0);
    }
    else
    {
      EXPECT_EQ(parameters.mode, itk::MeshExtractionEnums::PhantomImage::DistanceMap) << shape;
    }
  }
}

TEST(MeshExtractionPhantoms, ShapesAreCentredInsideTheGridAndSizedByItsSmallestExtent)
{
  using namespace itk::MeshExtraction;
  PhantomGrid grid;
  grid.size[0] = 80;
  grid.size[1] = 60;
  grid.size[2] = 50;
  grid.spacing[0] = 0.8;
  grid.spacing[1] = 1.0;
  grid.spacing[2] = 1.5;
  grid.origin = P(-10, 5, 20);
  grid.direction = Rotation(0.3, 0.2, -0.4);
  const PointType center = PhantomGridCenter(grid);
  const double    extent = PhantomGridSmallestExtent(grid);
  EXPECT_DOUBLE_EQ(extent, 60.0);
  for (const auto shape : AllPhantomShapes())
  {
    const auto surface = MakePhantomSurface(shape, grid);
    if (shape != PhantomShape::Plane)
    {
      // Closed shapes: the centre is inside (or, for the cleft, under the slot) and
      // the surface lies within the grid's field of view.
      PointType lower, upper;
      surface->GetBounds(lower, upper);
      for (unsigned int i = 0; i < 3; ++i)
      {
        EXPECT_NEAR(0.5 * (lower[i] + upper[i]), center[i], 0.2 * extent) << shape;
      }
      for (const PointType & p : RandomPoints(lower, upper, 0.0, 500, 101))
      {
        const PointType  q = surface->ClosestSurfacePoint(p);
        const VectorType local = MatrixType(grid.direction.GetTranspose()) * (q - grid.origin);
        for (unsigned int k = 0; k < 3; ++k)
        {
          EXPECT_GT(local[k] / grid.spacing[k], -0.5) << shape;
          EXPECT_LT(local[k] / grid.spacing[k], grid.size[k] - 0.5) << shape;
        }
      }
    }
    else
    {
      EXPECT_NEAR(std::abs(surface->Evaluate(center)), 0.5 / std::sqrt(14.0) * 0.8, 1e-12);
    }
  }
}

TEST(MeshExtractionPhantoms, DefaultShapesHaveTheDocumentedSizes)
{
  using namespace itk::MeshExtraction;
  const auto chapter4 =
    MakePhantomSurface(PhantomShape::Chapter4Sphere, DefaultPhantomGrid(PhantomShape::Chapter4Sphere));
  const auto sphere4 = dynamic_cast<const itk::SphereImplicitSurface *>(chapter4.GetPointer());
  ASSERT_NE(sphere4, nullptr);
  EXPECT_DOUBLE_EQ(sphere4->GetRadius(), 25.0);
  ITK_EXPECT_VECTOR_NEAR(sphere4->GetCenter(), P(49.5, 49.5, 49.5), 1e-12);

  const auto two = MakePhantomSurface(PhantomShape::TwoSpheres, DefaultPhantomGrid(PhantomShape::TwoSpheres));
  const auto union2 = dynamic_cast<const itk::SphereUnionImplicitSurface *>(two.GetPointer());
  ASSERT_NE(union2, nullptr);
  ASSERT_EQ(union2->GetNumberOfSpheres(), 2u);
  EXPECT_NEAR(
    union2->GetSphereCenter(0).EuclideanDistanceTo(union2->GetSphereCenter(1)), union2->GetSphereRadius(0), 1e-12);

  // The default plane is tilted to every grid axis.
  const auto plane = MakePhantomSurface(PhantomShape::Plane, DefaultPhantomGrid(PhantomShape::Plane));
  const auto plane3 = dynamic_cast<const itk::PlaneImplicitSurface *>(plane.GetPointer());
  ASSERT_NE(plane3, nullptr);
  for (unsigned int k = 0; k < 3; ++k)
  {
    EXPECT_GT(std::abs(plane3->GetNormal()[k]), 0.2);
    EXPECT_LT(std::abs(plane3->GetNormal()[k]), 0.9);
  }

  const auto cleft = MakePhantomSurface(PhantomShape::NarrowCleft, DefaultPhantomGrid(PhantomShape::NarrowCleft));
  const auto cleft3 = dynamic_cast<const itk::NarrowCleftImplicitSurface *>(cleft.GetPointer());
  ASSERT_NE(cleft3, nullptr);
  EXPECT_DOUBLE_EQ(cleft3->GetSlotWidth(), 1.5);

  const auto plate = MakePhantomSurface(PhantomShape::ThinPlate, DefaultPhantomGrid(PhantomShape::ThinPlate));
  const auto plate3 = dynamic_cast<const itk::BoxImplicitSurface *>(plate.GetPointer());
  ASSERT_NE(plate3, nullptr);
  EXPECT_DOUBLE_EQ(2.0 * plate3->GetHalfSizes()[2], 2.0); // 2 voxels thick
}

TEST(MeshExtractionPhantoms, InvalidGridThrows)
{
  using namespace itk::MeshExtraction;
  PhantomGrid grid;
  grid.spacing[1] = 0.0;
  ExpectThrowsMentioning([&] { MakePhantomSurface(PhantomShape::Sphere, grid); }, "spacing");
  grid = PhantomGrid();
  grid.direction(0, 1) = 0.5;
  ExpectThrowsMentioning([&] { MakePhantomSurface(PhantomShape::Sphere, grid); }, "direction");
  grid = PhantomGrid();
  grid.size[2] = 0;
  ExpectThrowsMentioning([&] { MakePhantomSurface(PhantomShape::Sphere, grid); }, "size");
}
