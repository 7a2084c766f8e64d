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
#ifndef itkImplicitSurfaceTestHelpers_h
#define itkImplicitSurfaceTestHelpers_h

#include "itkImplicitSurfaceFunction.h"
#include "itkMath.h"
#include "itkGTest.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <vector>

/** Points, rotations, random samples and the checks every exact signed distance
 * function passes, shared by the tests of the implicit surfaces and the phantoms. */
namespace ImplicitSurfaceTest
{
using SurfaceType = itk::ImplicitSurfaceFunction;
using PointType = SurfaceType::InputType;
using VectorType = SurfaceType::VectorType;
using MatrixType = SurfaceType::MatrixType;

constexpr double Tolerance = 1e-9;

inline PointType
P(double x, double y, double z)
{
  PointType p;
  p[0] = x;
  p[1] = y;
  p[2] = z;
  return p;
}

inline VectorType
V(double x, double y, double z)
{
  VectorType v;
  v[0] = x;
  v[1] = y;
  v[2] = z;
  return v;
}

/** A proper rotation from Euler angles (radians), R = Rz(a) Ry(b) Rx(c). */
inline MatrixType
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

inline PointType
Transform(const MatrixType & r, const PointType & center, const PointType & local)
{
  VectorType v = r * V(local[0], local[1], local[2]);
  return center + v;
}

/** Uniform random points in the box [lower - margin, upper + margin]. */
inline std::vector<PointType>
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

inline std::vector<PointType>
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
inline void
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

/** Dense samples of a sphere's surface (latitude-longitude), and the largest
 * distance from any surface point to its nearest sample. */
inline std::vector<PointType>
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
inline void
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

inline void
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

/** A rotation about (1, 1, 1) by 40 degrees: not a permutation of the axes. */
inline MatrixType
TiltedDirection()
{
  const double angle = 40.0 * itk::Math::pi / 180.0;
  const double c = std::cos(angle), s = std::sin(angle), t = 1.0 - c;
  const double k = 1.0 / std::sqrt(3.0);
  MatrixType   d;
  d(0, 0) = t * k * k + c;
  d(0, 1) = t * k * k - s * k;
  d(0, 2) = t * k * k + s * k;
  d(1, 0) = t * k * k + s * k;
  d(1, 1) = t * k * k + c;
  d(1, 2) = t * k * k - s * k;
  d(2, 0) = t * k * k - s * k;
  d(2, 1) = t * k * k + s * k;
  d(2, 2) = t * k * k + c;
  return d;
}
} // namespace ImplicitSurfaceTest

#endif
