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
#include "itkMeshExtractionClosedFormGeometry.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
// =================================================================================
// Frames
// =================================================================================

double
OrthogonalityError(const Matrix3 & m)
{
  double maximumError = 0.0;
  for (unsigned int i = 0; i < 3; ++i)
  {
    for (unsigned int j = 0; j < 3; ++j)
    {
      double dot = 0.0;
      for (unsigned int k = 0; k < 3; ++k)
      {
        dot += m(k, i) * m(k, j);
      }
      const double error = std::abs(dot - (i == j ? 1.0 : 0.0));
      maximumError = std::isfinite(error) ? std::max(maximumError, error) : Infinity;
    }
  }
  return maximumError;
}

Matrix3
OrthonormalizeColumns(const Matrix3 & m)
{
  Vec3 c[3];
  for (unsigned int j = 0; j < 3; ++j)
  {
    c[j] = MakeVec3(m(0, j), m(1, j), m(2, j));
  }
  c[0] = Normalized(c[0]);
  c[1] = Normalized(RemoveComponent(c[1], c[0]));
  c[2] = RemoveComponent(c[2], c[0]);
  c[2] = Normalized(RemoveComponent(c[2], c[1]));
  Matrix3 out;
  for (unsigned int i = 0; i < 3; ++i)
  {
    for (unsigned int j = 0; j < 3; ++j)
    {
      out(i, j) = c[j][i];
    }
  }
  return out;
}

namespace
{
constexpr double DegreesToRadians = 3.14159265358979323846 / 180.0;
} // namespace

Matrix3
RotationAboutZ(double degrees)
{
  const double a = degrees * DegreesToRadians;
  Matrix3      r;
  r.SetIdentity();
  r(0, 0) = std::cos(a);
  r(0, 1) = -std::sin(a);
  r(1, 0) = std::sin(a);
  r(1, 1) = std::cos(a);
  return r;
}

Matrix3
RotationAboutX(double degrees)
{
  const double a = degrees * DegreesToRadians;
  Matrix3      r;
  r.SetIdentity();
  r(1, 1) = std::cos(a);
  r(1, 2) = -std::sin(a);
  r(2, 1) = std::sin(a);
  r(2, 2) = std::cos(a);
  return r;
}

Matrix3
FrameFromNormal(const Vec3 & unitNormal, const Vec3 & edge)
{
  const Vec3 e0 = Normalized(RemoveComponent(edge, unitNormal));
  const Vec3 e1 = Cross(unitNormal, e0);
  Matrix3    frame;
  for (unsigned int i = 0; i < 3; ++i)
  {
    frame(i, 0) = e0[i];
    frame(i, 1) = e1[i];
    frame(i, 2) = unitNormal[i];
  }
  return frame;
}

Vec3
AnyUnitPerpendicular(const Vec3 & u)
{
  // Cross with the coordinate axis least aligned with u.
  unsigned int k = 0;
  for (unsigned int i = 1; i < 3; ++i)
  {
    if (std::abs(u[i]) < std::abs(u[k]))
    {
      k = i;
    }
  }
  Vec3 axis = MakeVec3(0.0, 0.0, 0.0);
  axis[k] = 1.0;
  return Normalized(Cross(u, axis));
}

Vec3
RadialDirection(const Vec3 & d, const Vec3 & axis, double & length)
{
  const Vec3 w = RemoveComponent(RemoveComponent(d, axis), axis);
  length = Norm(w);
  if (length > 1e-14 * Norm(d))
  {
    return w / length;
  }
  return AnyUnitPerpendicular(axis);
}

double
RotatedBoxHalfExtent(const Matrix3 & rotation, const Vec3 & halfSizes, unsigned int i)
{
  double halfExtent = 0.0;
  for (unsigned int j = 0; j < 3; ++j)
  {
    halfExtent += std::abs(rotation(i, j)) * halfSizes[j];
  }
  return halfExtent;
}

// =================================================================================
// Spheres, circles and rectangles
// =================================================================================

Vec3
RadialProjection(const Vec3 & p, const Vec3 & c, double r, double & distance)
{
  const Vec3   d = p - c;
  const double l = Norm(d);
  distance = std::abs(l - r);
  if (l > 0.0)
  {
    return c + d * (r / l);
  }
  return c + MakeVec3(r, 0.0, 0.0);
}

Vec3
ClosestPointOnCircle(const Vec3 & p, const Circle3 & c)
{
  double unused = 0.0;
  return c.center + RadialDirection(p - c.center, c.axis, unused) * c.radius;
}

bool
IntersectTwoSpheres(const Vec3 & c0, double r0, const Vec3 & c1, double r1, Circle3 & circle)
{
  const Vec3   d = c1 - c0;
  const double distance = Norm(d);
  if (!(distance > std::abs(r0 - r1)) || !(distance < r0 + r1))
  {
    return false;
  }
  const double a = (distance * distance + r0 * r0 - r1 * r1) / (2.0 * distance);
  const double rho2 = r0 * r0 - a * a;
  if (!(rho2 > 0.0))
  {
    return false;
  }
  circle.axis = d / distance;
  circle.center = c0 + circle.axis * a;
  circle.radius = std::sqrt(rho2);
  return true;
}

unsigned int
IntersectThreeSpheres(const Vec3 & c0,
                      double       r0,
                      const Vec3 & c1,
                      double       r1,
                      const Vec3 & c2,
                      double       r2,
                      Vec3 (&points)[2])
{
  // The frame ex (towards c1), ey (towards c2, perpendicular to ex), ez at c0.
  Vec3         ex = c1 - c0;
  const double d = Norm(ex);
  if (!(d > 0.0))
  {
    return 0;
  }
  ex /= d;
  const Vec3   t = c2 - c0;
  const double i = Dot(ex, t);
  Vec3         ey = t - ex * i;
  const double j = Norm(ey);
  if (!(j > 1e-12 * (d + Norm(t))))
  {
    return 0;
  }
  ey /= j;
  const Vec3   ez = Cross(ex, ey);
  const double x = (r0 * r0 - r1 * r1 + d * d) / (2.0 * d);
  const double y = (r0 * r0 - r2 * r2 + i * i + j * j) / (2.0 * j) - (i / j) * x;
  const double z2 = r0 * r0 - x * x - y * y;
  if (z2 < 0.0)
  {
    return 0;
  }
  const double z = std::sqrt(z2);
  const Vec3   base = c0 + ex * x + ey * y;
  points[0] = base + ez * z;
  points[1] = base - ez * z;
  return z > 0.0 ? 2 : 1;
}

Vec3
ClosestPointOnRectangle(const Vec3 & p, const Vec3 & corner, const Vec3 & e0, const Vec3 & e1)
{
  const Vec3   d = p - corner;
  const double s = std::clamp(Dot(d, e0) / SquaredNorm(e0), 0.0, 1.0);
  const double t = std::clamp(Dot(d, e1) / SquaredNorm(e1), 0.0, 1.0);
  return corner + e0 * s + e1 * t;
}

// =================================================================================
// Ellipses and ellipsoids, after D. Eberly, "Distance from a Point to an Ellipse, an
// Ellipsoid, or a Hyperellipsoid", Geometric Tools (2013).
// Semi-axes are sorted e0 >= e1 (>= e2) > 0 and the point is in the first octant
// (y_i >= 0). The closest point x satisfies x_i = r_i y_i / (s + r_i) with
// r_i = (e_i / e_last)^2, where s is the unique root of the strictly decreasing
// F(s) = sum (r_i z_i / (s + r_i))^2 - 1, z_i = y_i / e_i, on (z_last - 1, inf).
// Bisection runs until the bracket cannot shrink (machine precision).
// =================================================================================

namespace
{
constexpr int MaximumBisectionIterations =
  std::numeric_limits<double>::digits - std::numeric_limits<double>::min_exponent + 8;

/** The root s of F on [s0, s1] by bisection; `secular` evaluates F. */
template <typename TSecular>
double
BisectSecularRoot(double s0, double s1, const TSecular & secular)
{
  double s = 0.0;
  for (int i = 0; i < MaximumBisectionIterations; ++i)
  {
    s = 0.5 * (s0 + s1);
    if (s == s0 || s == s1)
    {
      break;
    }
    const double value = secular(s);
    if (value > 0.0)
    {
      s0 = s;
    }
    else if (value < 0.0)
    {
      s1 = s;
    }
    else
    {
      break;
    }
  }
  return s;
}

double
EllipseRoot(double r0, double z0, double z1, double g)
{
  const double n0 = r0 * z0;
  const double s0 = z1 - 1.0;
  const double s1 = (g < 0.0 ? 0.0 : std::hypot(n0, z1) - 1.0);
  return BisectSecularRoot(s0, s1, [=](double s) {
    const double ratio0 = n0 / (s + r0);
    const double ratio1 = z1 / (s + 1.0);
    return ratio0 * ratio0 + ratio1 * ratio1 - 1.0;
  });
}

double
EllipsoidRoot(double r0, double r1, double z0, double z1, double z2, double g)
{
  const double n0 = r0 * z0;
  const double n1 = r1 * z1;
  const double s0 = z2 - 1.0;
  const double s1 = (g < 0.0 ? 0.0 : std::hypot(n0, n1, z2) - 1.0);
  return BisectSecularRoot(s0, s1, [=](double s) {
    const double ratio0 = n0 / (s + r0);
    const double ratio1 = n1 / (s + r1);
    const double ratio2 = z2 / (s + 1.0);
    return ratio0 * ratio0 + ratio1 * ratio1 + ratio2 * ratio2 - 1.0;
  });
}

/** e0 >= e1 > 0, y0, y1 >= 0. */
double
DistancePointEllipse(double e0, double e1, double y0, double y1, double & x0, double & x1)
{
  if (y1 > 0.0)
  {
    if (y0 > 0.0)
    {
      const double z0 = y0 / e0;
      const double z1 = y1 / e1;
      const double g = z0 * z0 + z1 * z1 - 1.0;
      if (g != 0.0)
      {
        const double r0 = (e0 / e1) * (e0 / e1);
        const double sbar = EllipseRoot(r0, z0, z1, g);
        x0 = r0 * y0 / (sbar + r0);
        x1 = y1 / (sbar + 1.0);
        return std::hypot(x0 - y0, x1 - y1);
      }
      x0 = y0;
      x1 = y1;
      return 0.0;
    }
    // y0 == 0: the closest point is the end of the minor axis.
    x0 = 0.0;
    x1 = e1;
    return std::abs(y1 - e1);
  }
  // y1 == 0
  const double numer0 = e0 * y0;
  const double denom0 = e0 * e0 - e1 * e1;
  if (numer0 < denom0)
  {
    // Inside the evolute's reach on the major axis: the closest point is off axis.
    const double xde0 = numer0 / denom0;
    x0 = e0 * xde0;
    x1 = e1 * std::sqrt(std::max(0.0, 1.0 - xde0 * xde0));
    return std::hypot(x0 - y0, x1);
  }
  x0 = e0;
  x1 = 0.0;
  return std::abs(y0 - e0);
}

/** A point with all three coordinates > 0: the root of the secular function, or the
 * point itself when it is on the surface. */
double
DistancePointEllipsoidInOpenOctant(const double (&e)[3], const double (&y)[3], double (&x)[3])
{
  const double z0 = y[0] / e[0];
  const double z1 = y[1] / e[1];
  const double z2 = y[2] / e[2];
  const double g = z0 * z0 + z1 * z1 + z2 * z2 - 1.0;
  if (g != 0.0)
  {
    const double r0 = (e[0] / e[2]) * (e[0] / e[2]);
    const double r1 = (e[1] / e[2]) * (e[1] / e[2]);
    const double sbar = EllipsoidRoot(r0, r1, z0, z1, z2, g);
    x[0] = r0 * y[0] / (sbar + r0);
    x[1] = r1 * y[1] / (sbar + r1);
    x[2] = y[2] / (sbar + 1.0);
    return std::hypot(x[0] - y[0], x[1] - y[1], x[2] - y[2]);
  }
  x[0] = y[0];
  x[1] = y[1];
  x[2] = y[2];
  return 0.0;
}

/** A point with y2 == 0: the closest point may leave the plane x2 = 0 (points near
 * the centre); otherwise it is the closest point of the ellipse in that plane. */
double
DistancePointEllipsoidOnMinorPlane(const double (&e)[3], const double (&y)[3], double (&x)[3])
{
  const double denom0 = e[0] * e[0] - e[2] * e[2];
  const double denom1 = e[1] * e[1] - e[2] * e[2];
  const double numer0 = e[0] * y[0];
  const double numer1 = e[1] * y[1];
  if (numer0 < denom0 && numer1 < denom1)
  {
    const double xde0 = numer0 / denom0;
    const double xde1 = numer1 / denom1;
    const double discr = 1.0 - xde0 * xde0 - xde1 * xde1;
    if (discr > 0.0)
    {
      x[0] = e[0] * xde0;
      x[1] = e[1] * xde1;
      x[2] = e[2] * std::sqrt(discr);
      return std::hypot(x[0] - y[0], x[1] - y[1], x[2]);
    }
  }
  x[2] = 0.0;
  return DistancePointEllipse(e[0], e[1], y[0], y[1], x[0], x[1]);
}

/** e0 >= e1 >= e2 > 0, y0, y1, y2 >= 0. */
double
DistancePointEllipsoid(const double (&e)[3], const double (&y)[3], double (&x)[3])
{
  if (y[2] > 0.0)
  {
    if (y[1] > 0.0)
    {
      if (y[0] > 0.0)
      {
        return DistancePointEllipsoidInOpenOctant(e, y, x);
      }
      x[0] = 0.0;
      return DistancePointEllipse(e[1], e[2], y[1], y[2], x[1], x[2]);
    }
    if (y[0] > 0.0)
    {
      x[1] = 0.0;
      return DistancePointEllipse(e[0], e[2], y[0], y[2], x[0], x[2]);
    }
    x[0] = 0.0;
    x[1] = 0.0;
    x[2] = e[2];
    return std::abs(y[2] - e[2]);
  }
  return DistancePointEllipsoidOnMinorPlane(e, y, x);
}
} // namespace

double
ClosestPointOnEllipsoid(const Vec3 & semiAxes, const Vec3 & q, Vec3 & closest)
{
  // Sort the axes by decreasing semi-axis and fold the point into the first octant.
  std::array<unsigned int, 3> order{ { 0, 1, 2 } };
  std::stable_sort(
    order.begin(), order.end(), [&semiAxes](unsigned int a, unsigned int b) { return semiAxes[a] > semiAxes[b]; });
  double e[3];
  double y[3];
  double x[3];
  for (unsigned int k = 0; k < 3; ++k)
  {
    e[k] = semiAxes[order[k]];
    y[k] = std::abs(q[order[k]]);
  }
  const double distance = DistancePointEllipsoid(e, y, x);
  // Unfold: back to the original axis order and the octant of q.
  for (unsigned int k = 0; k < 3; ++k)
  {
    closest[order[k]] = std::copysign(x[k], q[order[k]]);
  }
  return distance;
}

} // namespace detail
} // namespace MeshExtraction
} // namespace itk
