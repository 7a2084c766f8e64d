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
#include "itkMeshExtractionTriangleGeometry.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>

namespace itk
{
namespace
{
using MeshExtraction::Cross;
using MeshExtraction::Dot;
using MeshExtraction::MakeVec3;
using MeshExtraction::Norm;
using MeshExtraction::SquaredNorm;
using MeshExtraction::Vec3;
using PointType = ImplicitSurfaceFunction::InputType;
using MatrixType = ImplicitSurfaceFunction::MatrixType;

constexpr double Infinity = std::numeric_limits<double>::infinity();

/** Relative tolerance of the "is this boundary candidate inside another ball" tests
 * of the union and the difference: a candidate within this relative distance of a
 * sphere counts as on it, so that points of an intersection circle or of coincident
 * spheres are not discarded because of rounding. */
constexpr double CoverTolerance = 1e-12;

inline Vec3
ToVec(const PointType & p)
{
  return MakeVec3(p[0], p[1], p[2]);
}

inline PointType
ToPoint(const Vec3 & v)
{
  PointType p;
  p[0] = v[0];
  p[1] = v[1];
  p[2] = v[2];
  return p;
}

/** R^T v: physical direction to the local frame of an orthogonal R. */
inline Vec3
ToLocal(const MatrixType & r, const Vec3 & v)
{
  Vec3 out;
  for (unsigned int j = 0; j < 3; ++j)
  {
    out[j] = r(0, j) * v[0] + r(1, j) * v[1] + r(2, j) * v[2];
  }
  return out;
}

/** R v: local frame to physical direction. */
inline Vec3
ToPhysical(const MatrixType & r, const Vec3 & v)
{
  Vec3 out;
  for (unsigned int i = 0; i < 3; ++i)
  {
    out[i] = r(i, 0) * v[0] + r(i, 1) * v[1] + r(i, 2) * v[2];
  }
  return out;
}

/** A unit vector perpendicular to the unit vector u. */
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
  Vec3 w = Cross(u, axis);
  w /= Norm(w);
  return w;
}

/** The unit direction of the component of d perpendicular to the unit vector
 * `axis`, and that component's length in `length`. The component is projected
 * twice, so that the direction is perpendicular to the axis to rounding even when d
 * is almost parallel to it; when d is parallel to the axis (to rounding) every
 * perpendicular direction is equally good and a fixed one is returned. */
Vec3
RadialDirection(const Vec3 & d, const Vec3 & axis, double & length)
{
  Vec3 w = d - axis * Dot(d, axis);
  w -= axis * Dot(w, axis);
  length = Norm(w);
  if (length > 1e-14 * Norm(d))
  {
    return w / length;
  }
  return AnyUnitPerpendicular(axis);
}

/** Closest point to p on the closed rectangle corner + s e0 + t e1, s, t in [0, 1],
 * where e0 and e1 are orthogonal and non-zero. */
Vec3
ClosestPointOnRectangle(const Vec3 & p, const Vec3 & corner, const Vec3 & e0, const Vec3 & e1)
{
  const Vec3   d = p - corner;
  const double s = std::clamp(Dot(d, e0) / SquaredNorm(e0), 0.0, 1.0);
  const double t = std::clamp(Dot(d, e1) / SquaredNorm(e1), 0.0, 1.0);
  return corner + e0 * s + e1 * t;
}

/** A circle in 3-D: centre, unit normal of its plane, radius. */
struct Circle
{
  Vec3   center;
  Vec3   axis;
  double radius;
};

/** Closest point to p on the circle. Every point is equally close when p is on the
 * circle's axis; a fixed one is returned then. */
Vec3
ClosestPointOnCircle(const Vec3 & p, const Circle & c)
{
  double unused = 0.0;
  return c.center + RadialDirection(p - c.center, c.axis, unused) * c.radius;
}

/** The circle where two spheres cross; false when they do not cross in a circle of
 * positive radius (apart, nested, tangent or concentric). */
bool
IntersectTwoSpheres(const Vec3 & c0, double r0, const Vec3 & c1, double r1, Circle & circle)
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

/** The points common to three spheres (trilateration); returns how many (0, 1, 2).
 * Spheres with collinear centres meet in a circle or not at all: 0 is returned, and
 * the circle is found as a pairwise intersection circle instead. */
unsigned int
IntersectThreeSpheres(const Vec3 & c0,
                      double       r0,
                      const Vec3 & c1,
                      double       r1,
                      const Vec3 & c2,
                      double       r2,
                      Vec3 (&points)[2])
{
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

/** True when q is in the interior of the ball (c, r), beyond rounding. */
inline bool
StrictlyInsideBall(const Vec3 & q, const Vec3 & c, double r)
{
  return Norm(q - c) < r * (1.0 - CoverTolerance);
}

/** True when q is outside the ball (c, r), beyond rounding. */
inline bool
StrictlyOutsideBall(const Vec3 & q, const Vec3 & c, double r)
{
  return Norm(q - c) > r * (1.0 + CoverTolerance);
}

/** Keeps the best (closest) candidate of a search. */
struct NearestCandidate
{
  double distance{ Infinity };
  Vec3   point{ MakeVec3(0.0, 0.0, 0.0) };

  void
  Consider(const Vec3 & p, const Vec3 & q)
  {
    const double d = Norm(p - q);
    if (d < distance)
    {
      distance = d;
      point = q;
    }
  }
  void
  Consider(double d, const Vec3 & q)
  {
    if (d < distance)
    {
      distance = d;
      point = q;
    }
  }
};

/** The point of sphere (c, r) closest to p: the radial projection, or a fixed point
 * when p is the centre. The distance |p - q| is returned in `distance`. */
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

// ---------------------------------------------------------------------------------
// Distance from a point to an ellipse / ellipsoid, after D. Eberly, "Distance from a
// Point to an Ellipse, an Ellipsoid, or a Hyperellipsoid", Geometric Tools (2013).
// Semi-axes are sorted e0 >= e1 (>= e2) > 0 and the point is in the first octant
// (y_i >= 0). The closest point x satisfies x_i = r_i y_i / (s + r_i) with
// r_i = (e_i / e_last)^2, where s is the unique root of the strictly decreasing
// F(s) = sum (r_i z_i / (s + r_i))^2 - 1, z_i = y_i / e_i, on (z_last - 1, inf).
// Bisection runs until the bracket cannot shrink (machine precision).
// ---------------------------------------------------------------------------------

constexpr int MaximumBisectionIterations =
  std::numeric_limits<double>::digits - std::numeric_limits<double>::min_exponent + 8;

double
EllipseRoot(double r0, double z0, double z1, double g)
{
  const double n0 = r0 * z0;
  double       s0 = z1 - 1.0;
  double       s1 = (g < 0.0 ? 0.0 : std::hypot(n0, z1) - 1.0);
  double       s = 0.0;
  for (int i = 0; i < MaximumBisectionIterations; ++i)
  {
    s = 0.5 * (s0 + s1);
    if (s == s0 || s == s1)
    {
      break;
    }
    const double ratio0 = n0 / (s + r0);
    const double ratio1 = z1 / (s + 1.0);
    const double value = ratio0 * ratio0 + ratio1 * ratio1 - 1.0;
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
EllipsoidRoot(double r0, double r1, double z0, double z1, double z2, double g)
{
  const double n0 = r0 * z0;
  const double n1 = r1 * z1;
  double       s0 = z2 - 1.0;
  double       s1 = (g < 0.0 ? 0.0 : std::hypot(n0, n1, z2) - 1.0);
  double       s = 0.0;
  for (int i = 0; i < MaximumBisectionIterations; ++i)
  {
    s = 0.5 * (s0 + s1);
    if (s == s0 || s == s1)
    {
      break;
    }
    const double ratio0 = n0 / (s + r0);
    const double ratio1 = n1 / (s + r1);
    const double ratio2 = z2 / (s + 1.0);
    const double value = ratio0 * ratio0 + ratio1 * ratio1 + ratio2 * ratio2 - 1.0;
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
  // y2 == 0: the closest point may leave the plane x2 = 0 (points near the centre).
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

template <typename TValue>
std::string
ToString(const TValue & value)
{
  std::ostringstream s;
  s.precision(17);
  s << value;
  return s.str();
}

} // namespace

// =================================================================================
// ImplicitSurfaceFunction
// =================================================================================

ImplicitSurfaceFunction::OutputType
ImplicitSurfaceFunction::EvaluateWithClosestPoint(const InputType & point, InputType & closest) const
{
  closest = this->ClosestSurfacePoint(point);
  return this->Evaluate(point);
}

void
ImplicitSurfaceFunction::VerifyParameters() const
{
  if (!m_ParameterError.empty())
  {
    itkExceptionMacro(<< "Invalid parameters: " << m_ParameterError);
  }
}

void
ImplicitSurfaceFunction::ParametersChanged()
{
  m_ParameterError = this->CheckParameterConsistency();
  this->Modified();
}

void
ImplicitSurfaceFunction::RequirePositive(const char * parameterName, double value) const
{
  if (!(std::isfinite(value) && value > 0.0))
  {
    itkExceptionMacro(<< parameterName << " must be a finite number > 0, got " << value);
  }
}

void
ImplicitSurfaceFunction::RequirePositive(const char * parameterName, const VectorType & value) const
{
  for (unsigned int i = 0; i < 3; ++i)
  {
    if (!(std::isfinite(value[i]) && value[i] > 0.0))
    {
      itkExceptionMacro(<< parameterName << " must have finite components > 0, got " << value << " (component " << i
                        << " is " << value[i] << ")");
    }
  }
}

void
ImplicitSurfaceFunction::RequireFinite(const char * parameterName, const InputType & value) const
{
  for (unsigned int i = 0; i < 3; ++i)
  {
    if (!std::isfinite(value[i]))
    {
      itkExceptionMacro(<< parameterName << " must have finite coordinates, got " << value);
    }
  }
}

ImplicitSurfaceFunction::VectorType
ImplicitSurfaceFunction::RequireDirection(const char * parameterName, const VectorType & value) const
{
  const Vec3   v = MakeVec3(value[0], value[1], value[2]);
  const double l = Norm(v);
  if (!(std::isfinite(l) && l > 0.0))
  {
    itkExceptionMacro(<< parameterName << " must be a finite, non-zero vector, got " << value);
  }
  return v / l;
}

ImplicitSurfaceFunction::MatrixType
ImplicitSurfaceFunction::RequireRotation(const char * parameterName, const MatrixType & value) const
{
  double maximumError = 0.0;
  for (unsigned int i = 0; i < 3; ++i)
  {
    for (unsigned int j = 0; j < 3; ++j)
    {
      double dot = 0.0;
      for (unsigned int k = 0; k < 3; ++k)
      {
        dot += value(k, i) * value(k, j);
      }
      const double error = std::abs(dot - (i == j ? 1.0 : 0.0));
      maximumError = std::isfinite(error) ? std::max(maximumError, error) : Infinity;
    }
  }
  if (!(maximumError <= 1e-6))
  {
    itkExceptionMacro(<< parameterName << " must be an orthogonal matrix (orthonormal columns within 1e-6), got "
                      << value << "with max |R^T R - I| = " << maximumError);
  }
  // Gram-Schmidt on the columns, so that R^T R = I to rounding and distances
  // computed in the local frame are distances in physical space.
  Vec3 c[3];
  for (unsigned int j = 0; j < 3; ++j)
  {
    c[j] = MakeVec3(value(0, j), value(1, j), value(2, j));
  }
  c[0] /= Norm(c[0]);
  c[1] -= c[0] * Dot(c[1], c[0]);
  c[1] /= Norm(c[1]);
  c[2] -= c[0] * Dot(c[2], c[0]);
  c[2] -= c[1] * Dot(c[2], c[1]);
  c[2] /= Norm(c[2]);
  MatrixType out;
  for (unsigned int i = 0; i < 3; ++i)
  {
    for (unsigned int j = 0; j < 3; ++j)
    {
      out(i, j) = c[j][i];
    }
  }
  return out;
}

void
ImplicitSurfaceFunction::PrintSelf(std::ostream & os, Indent indent) const
{
  Superclass::PrintSelf(os, indent);
  os << indent << "ParametersValid: " << (m_ParameterError.empty() ? "true" : "false") << std::endl;
  if (!m_ParameterError.empty())
  {
    os << indent << "ParameterError: " << m_ParameterError << std::endl;
  }
}

// =================================================================================
// PlaneImplicitSurface
// =================================================================================

PlaneImplicitSurface::PlaneImplicitSurface()
{
  m_Point.Fill(0.0);
  m_Normal.Fill(0.0);
  m_Normal[2] = 1.0;
}

void
PlaneImplicitSurface::SetPoint(const InputType & point)
{
  this->RequireFinite("Point", point);
  m_Point = point;
  this->ParametersChanged();
}

void
PlaneImplicitSurface::SetNormal(const VectorType & normal)
{
  m_Normal = this->RequireDirection("Normal", normal);
  this->ParametersChanged();
}

PlaneImplicitSurface::OutputType
PlaneImplicitSurface::Evaluate(const InputType & point) const
{
  this->ThrowIfParametersInvalid();
  return Dot(ToVec(point) - ToVec(m_Point), m_Normal);
}

PlaneImplicitSurface::InputType
PlaneImplicitSurface::ClosestSurfacePoint(const InputType & point) const
{
  InputType closest;
  this->EvaluateWithClosestPoint(point, closest);
  return closest;
}

PlaneImplicitSurface::OutputType
PlaneImplicitSurface::EvaluateWithClosestPoint(const InputType & point, InputType & closest) const
{
  this->ThrowIfParametersInvalid();
  const Vec3   p = ToVec(point);
  const double d = Dot(p - ToVec(m_Point), m_Normal);
  closest = ToPoint(p - m_Normal * d);
  return d;
}

void
PlaneImplicitSurface::GetBounds(InputType & lower, InputType & upper) const
{
  this->ThrowIfParametersInvalid();
  for (unsigned int i = 0; i < 3; ++i)
  {
    lower[i] = -Infinity;
    upper[i] = Infinity;
    // A plane perpendicular to axis i has one coordinate i.
    if (m_Normal[(i + 1) % 3] == 0.0 && m_Normal[(i + 2) % 3] == 0.0)
    {
      lower[i] = upper[i] = m_Point[i];
    }
  }
}

void
PlaneImplicitSurface::PrintSelf(std::ostream & os, Indent indent) const
{
  Superclass::PrintSelf(os, indent);
  os << indent << "Point: " << m_Point << std::endl;
  os << indent << "Normal: " << m_Normal << std::endl;
}

// =================================================================================
// SphereImplicitSurface
// =================================================================================

SphereImplicitSurface::SphereImplicitSurface()
{
  m_Center.Fill(0.0);
}

void
SphereImplicitSurface::SetCenter(const InputType & center)
{
  this->RequireFinite("Center", center);
  m_Center = center;
  this->ParametersChanged();
}

void
SphereImplicitSurface::SetRadius(double radius)
{
  this->RequirePositive("Radius", radius);
  m_Radius = radius;
  this->ParametersChanged();
}

SphereImplicitSurface::OutputType
SphereImplicitSurface::Evaluate(const InputType & point) const
{
  this->ThrowIfParametersInvalid();
  return Norm(ToVec(point) - ToVec(m_Center)) - m_Radius;
}

SphereImplicitSurface::InputType
SphereImplicitSurface::ClosestSurfacePoint(const InputType & point) const
{
  InputType closest;
  this->EvaluateWithClosestPoint(point, closest);
  return closest;
}

SphereImplicitSurface::OutputType
SphereImplicitSurface::EvaluateWithClosestPoint(const InputType & point, InputType & closest) const
{
  this->ThrowIfParametersInvalid();
  const Vec3 p = ToVec(point);
  const Vec3 c = ToVec(m_Center);
  double     unused = 0.0;
  closest = ToPoint(RadialProjection(p, c, m_Radius, unused));
  return Norm(p - c) - m_Radius;
}

void
SphereImplicitSurface::GetBounds(InputType & lower, InputType & upper) const
{
  this->ThrowIfParametersInvalid();
  for (unsigned int i = 0; i < 3; ++i)
  {
    lower[i] = m_Center[i] - m_Radius;
    upper[i] = m_Center[i] + m_Radius;
  }
}

void
SphereImplicitSurface::PrintSelf(std::ostream & os, Indent indent) const
{
  Superclass::PrintSelf(os, indent);
  os << indent << "Center: " << m_Center << std::endl;
  os << indent << "Radius: " << m_Radius << std::endl;
}

// =================================================================================
// EllipsoidImplicitSurface
// =================================================================================

EllipsoidImplicitSurface::EllipsoidImplicitSurface()
{
  m_Center.Fill(0.0);
  m_SemiAxes.Fill(1.0);
  m_Rotation.SetIdentity();
}

void
EllipsoidImplicitSurface::SetCenter(const InputType & center)
{
  this->RequireFinite("Center", center);
  m_Center = center;
  this->ParametersChanged();
}

void
EllipsoidImplicitSurface::SetSemiAxes(const VectorType & semiAxes)
{
  this->RequirePositive("SemiAxes", semiAxes);
  m_SemiAxes = semiAxes;
  this->ParametersChanged();
}

void
EllipsoidImplicitSurface::SetRotation(const MatrixType & rotation)
{
  m_Rotation = this->RequireRotation("Rotation", rotation);
  this->ParametersChanged();
}

EllipsoidImplicitSurface::OutputType
EllipsoidImplicitSurface::Evaluate(const InputType & point) const
{
  InputType closest;
  return this->EvaluateWithClosestPoint(point, closest);
}

EllipsoidImplicitSurface::InputType
EllipsoidImplicitSurface::ClosestSurfacePoint(const InputType & point) const
{
  InputType closest;
  this->EvaluateWithClosestPoint(point, closest);
  return closest;
}

EllipsoidImplicitSurface::OutputType
EllipsoidImplicitSurface::EvaluateWithClosestPoint(const InputType & point, InputType & closest) const
{
  this->ThrowIfParametersInvalid();
  const Vec3 q = ToLocal(m_Rotation, ToVec(point) - ToVec(m_Center));

  // Sort the axes by decreasing semi-axis and fold the point into the first octant.
  std::array<unsigned int, 3> order{ { 0, 1, 2 } };
  std::stable_sort(
    order.begin(), order.end(), [this](unsigned int a, unsigned int b) { return m_SemiAxes[a] > m_SemiAxes[b]; });
  double e[3];
  double y[3];
  double x[3];
  double level = 0.0;
  for (unsigned int k = 0; k < 3; ++k)
  {
    e[k] = m_SemiAxes[order[k]];
    y[k] = std::abs(q[order[k]]);
    level += (q[k] / m_SemiAxes[k]) * (q[k] / m_SemiAxes[k]);
  }
  const double distance = DistancePointEllipsoid(e, y, x);

  Vec3 local;
  for (unsigned int k = 0; k < 3; ++k)
  {
    local[order[k]] = std::copysign(x[k], q[order[k]]);
  }
  closest = ToPoint(ToVec(m_Center) + ToPhysical(m_Rotation, local));
  return level < 1.0 ? -distance : distance;
}

void
EllipsoidImplicitSurface::GetBounds(InputType & lower, InputType & upper) const
{
  this->ThrowIfParametersInvalid();
  for (unsigned int i = 0; i < 3; ++i)
  {
    // Support function of the ellipsoid along axis i.
    const double halfExtent =
      std::hypot(m_Rotation(i, 0) * m_SemiAxes[0], m_Rotation(i, 1) * m_SemiAxes[1], m_Rotation(i, 2) * m_SemiAxes[2]);
    lower[i] = m_Center[i] - halfExtent;
    upper[i] = m_Center[i] + halfExtent;
  }
}

void
EllipsoidImplicitSurface::PrintSelf(std::ostream & os, Indent indent) const
{
  Superclass::PrintSelf(os, indent);
  os << indent << "Center: " << m_Center << std::endl;
  os << indent << "SemiAxes: " << m_SemiAxes << std::endl;
  os << indent << "Rotation: " << std::endl << m_Rotation;
}

// =================================================================================
// TorusImplicitSurface
// =================================================================================

TorusImplicitSurface::TorusImplicitSurface()
{
  m_Center.Fill(0.0);
  m_Axis.Fill(0.0);
  m_Axis[2] = 1.0;
}

void
TorusImplicitSurface::SetCenter(const InputType & center)
{
  this->RequireFinite("Center", center);
  m_Center = center;
  this->ParametersChanged();
}

void
TorusImplicitSurface::SetAxis(const VectorType & axis)
{
  m_Axis = this->RequireDirection("Axis", axis);
  this->ParametersChanged();
}

void
TorusImplicitSurface::SetMajorRadius(double radius)
{
  this->RequirePositive("MajorRadius", radius);
  m_MajorRadius = radius;
  this->ParametersChanged();
}

void
TorusImplicitSurface::SetMinorRadius(double radius)
{
  this->RequirePositive("MinorRadius", radius);
  m_MinorRadius = radius;
  this->ParametersChanged();
}

void
TorusImplicitSurface::SetRadii(double majorRadius, double minorRadius)
{
  this->RequirePositive("MajorRadius", majorRadius);
  this->RequirePositive("MinorRadius", minorRadius);
  m_MajorRadius = majorRadius;
  m_MinorRadius = minorRadius;
  this->ParametersChanged();
}

std::string
TorusImplicitSurface::CheckParameterConsistency() const
{
  if (!(m_MinorRadius < m_MajorRadius))
  {
    return "MinorRadius must be smaller than MajorRadius (a ring torus), got MinorRadius = " + ToString(m_MinorRadius) +
           " and MajorRadius = " + ToString(m_MajorRadius);
  }
  return {};
}

TorusImplicitSurface::OutputType
TorusImplicitSurface::Evaluate(const InputType & point) const
{
  this->ThrowIfParametersInvalid();
  const Vec3   d = ToVec(point) - ToVec(m_Center);
  const double h = Dot(d, m_Axis);
  double       rho = 0.0;
  RadialDirection(d, m_Axis, rho); // as in EvaluateWithClosestPoint, to the last bit
  return std::hypot(rho - m_MajorRadius, h) - m_MinorRadius;
}

TorusImplicitSurface::InputType
TorusImplicitSurface::ClosestSurfacePoint(const InputType & point) const
{
  InputType closest;
  this->EvaluateWithClosestPoint(point, closest);
  return closest;
}

TorusImplicitSurface::OutputType
TorusImplicitSurface::EvaluateWithClosestPoint(const InputType & point, InputType & closest) const
{
  this->ThrowIfParametersInvalid();
  const Vec3   p = ToVec(point);
  const Vec3   c = ToVec(m_Center);
  const Vec3   d = p - c;
  const double h = Dot(d, m_Axis);
  double       rho = 0.0;
  // On the axis every core point is equally close, and a fixed one is used.
  const Vec3   radial = RadialDirection(d, m_Axis, rho);
  const Vec3   core = c + radial * m_MajorRadius;
  const Vec3   v = p - core;
  const double l = Norm(v);
  closest = ToPoint(l > 0.0 ? core + v * (m_MinorRadius / l) : core + radial * m_MinorRadius);
  return std::hypot(rho - m_MajorRadius, h) - m_MinorRadius;
}

void
TorusImplicitSurface::GetBounds(InputType & lower, InputType & upper) const
{
  this->ThrowIfParametersInvalid();
  for (unsigned int i = 0; i < 3; ++i)
  {
    // Extent of the core circle along axis i, plus the tube.
    const double halfExtent = m_MajorRadius * std::sqrt(std::max(0.0, 1.0 - m_Axis[i] * m_Axis[i])) + m_MinorRadius;
    lower[i] = m_Center[i] - halfExtent;
    upper[i] = m_Center[i] + halfExtent;
  }
}

void
TorusImplicitSurface::PrintSelf(std::ostream & os, Indent indent) const
{
  Superclass::PrintSelf(os, indent);
  os << indent << "Center: " << m_Center << std::endl;
  os << indent << "Axis: " << m_Axis << std::endl;
  os << indent << "MajorRadius: " << m_MajorRadius << std::endl;
  os << indent << "MinorRadius: " << m_MinorRadius << std::endl;
}

// =================================================================================
// BoxImplicitSurface
// =================================================================================

BoxImplicitSurface::BoxImplicitSurface()
{
  m_Center.Fill(0.0);
  m_HalfSizes.Fill(1.0);
  m_Rotation.SetIdentity();
}

void
BoxImplicitSurface::SetCenter(const InputType & center)
{
  this->RequireFinite("Center", center);
  m_Center = center;
  this->ParametersChanged();
}

void
BoxImplicitSurface::SetHalfSizes(const VectorType & halfSizes)
{
  this->RequirePositive("HalfSizes", halfSizes);
  m_HalfSizes = halfSizes;
  this->ParametersChanged();
}

void
BoxImplicitSurface::SetRotation(const MatrixType & rotation)
{
  m_Rotation = this->RequireRotation("Rotation", rotation);
  this->ParametersChanged();
}

BoxImplicitSurface::OutputType
BoxImplicitSurface::Evaluate(const InputType & point) const
{
  InputType closest;
  return this->EvaluateWithClosestPoint(point, closest);
}

BoxImplicitSurface::InputType
BoxImplicitSurface::ClosestSurfacePoint(const InputType & point) const
{
  InputType closest;
  this->EvaluateWithClosestPoint(point, closest);
  return closest;
}

BoxImplicitSurface::OutputType
BoxImplicitSurface::EvaluateWithClosestPoint(const InputType & point, InputType & closest) const
{
  this->ThrowIfParametersInvalid();
  const Vec3 q = ToLocal(m_Rotation, ToVec(point) - ToVec(m_Center));
  Vec3       onSurface = q;
  bool       outside = false;
  for (unsigned int i = 0; i < 3; ++i)
  {
    if (std::abs(q[i]) > m_HalfSizes[i])
    {
      outside = true;
      onSurface[i] = std::copysign(m_HalfSizes[i], q[i]);
    }
  }
  double distance = 0.0;
  if (outside)
  {
    distance = Norm(q - onSurface);
  }
  else
  {
    // Inside: the nearest face is the one with the largest |q_i| - h_i (<= 0).
    unsigned int face = 0;
    double       depth = std::abs(q[0]) - m_HalfSizes[0];
    for (unsigned int i = 1; i < 3; ++i)
    {
      const double d = std::abs(q[i]) - m_HalfSizes[i];
      if (d > depth)
      {
        depth = d;
        face = i;
      }
    }
    onSurface[face] = q[face] < 0.0 ? -m_HalfSizes[face] : m_HalfSizes[face];
    distance = depth;
  }
  closest = ToPoint(ToVec(m_Center) + ToPhysical(m_Rotation, onSurface));
  return distance;
}

void
BoxImplicitSurface::GetBounds(InputType & lower, InputType & upper) const
{
  this->ThrowIfParametersInvalid();
  for (unsigned int i = 0; i < 3; ++i)
  {
    double halfExtent = 0.0;
    for (unsigned int j = 0; j < 3; ++j)
    {
      halfExtent += std::abs(m_Rotation(i, j)) * m_HalfSizes[j];
    }
    lower[i] = m_Center[i] - halfExtent;
    upper[i] = m_Center[i] + halfExtent;
  }
}

void
BoxImplicitSurface::PrintSelf(std::ostream & os, Indent indent) const
{
  Superclass::PrintSelf(os, indent);
  os << indent << "Center: " << m_Center << std::endl;
  os << indent << "HalfSizes: " << m_HalfSizes << std::endl;
  os << indent << "Rotation: " << std::endl << m_Rotation;
}

// =================================================================================
// SphereUnionImplicitSurface
// =================================================================================

SphereUnionImplicitSurface::SphereUnionImplicitSurface()
{
  // An empty union is invalid until AddSphere() is called.
  this->ParametersChanged();
}

void
SphereUnionImplicitSurface::AddSphere(const InputType & center, double radius)
{
  this->RequireFinite("sphere center", center);
  this->RequirePositive("sphere radius", radius);
  m_Centers.push_back(center);
  m_Radii.push_back(radius);
  this->ParametersChanged();
}

void
SphereUnionImplicitSurface::RemoveAllSpheres()
{
  m_Centers.clear();
  m_Radii.clear();
  this->ParametersChanged();
}

const SphereUnionImplicitSurface::InputType &
SphereUnionImplicitSurface::GetSphereCenter(unsigned int i) const
{
  if (i >= m_Centers.size())
  {
    itkExceptionMacro(<< "Sphere index " << i << " out of range: the union has " << m_Centers.size() << " spheres");
  }
  return m_Centers[i];
}

double
SphereUnionImplicitSurface::GetSphereRadius(unsigned int i) const
{
  if (i >= m_Radii.size())
  {
    itkExceptionMacro(<< "Sphere index " << i << " out of range: the union has " << m_Radii.size() << " spheres");
  }
  return m_Radii[i];
}

std::string
SphereUnionImplicitSurface::CheckParameterConsistency() const
{
  if (m_Centers.empty())
  {
    return "the union has no spheres: call AddSphere() at least once";
  }
  return {};
}

SphereUnionImplicitSurface::OutputType
SphereUnionImplicitSurface::Evaluate(const InputType & point) const
{
  InputType closest;
  return this->EvaluateWithClosestPoint(point, closest);
}

SphereUnionImplicitSurface::InputType
SphereUnionImplicitSurface::ClosestSurfacePoint(const InputType & point) const
{
  InputType closest;
  this->EvaluateWithClosestPoint(point, closest);
  return closest;
}

SphereUnionImplicitSurface::OutputType
SphereUnionImplicitSurface::EvaluateWithClosestPoint(const InputType & point, InputType & closest) const
{
  this->ThrowIfParametersInvalid();
  const Vec3        p = ToVec(point);
  const size_t      n = m_Centers.size();
  std::vector<Vec3> c(n);
  for (size_t i = 0; i < n; ++i)
  {
    c[i] = ToVec(m_Centers[i]);
  }
  // A boundary candidate must not lie in the interior of any ball.
  const auto onBoundary = [&](const Vec3 & q) {
    for (size_t j = 0; j < n; ++j)
    {
      if (StrictlyInsideBall(q, c[j], m_Radii[j]))
      {
        return false;
      }
    }
    return true;
  };

  bool             inside = false;
  NearestCandidate best;
  NearestCandidate fallback; // nearest sphere point, whether on the boundary or not
  // 1. Radial projections onto each sphere.
  for (size_t i = 0; i < n; ++i)
  {
    inside = inside || Norm(p - c[i]) <= m_Radii[i];
    double     d = 0.0;
    const Vec3 q = RadialProjection(p, c[i], m_Radii[i], d);
    fallback.Consider(d, q);
    if (d < best.distance && onBoundary(q))
    {
      best.Consider(d, q);
    }
    // The centre sees all of the sphere at the same distance: any boundary point of
    // it will do, and the circles and triple points below provide one when the
    // fixed radial point is covered.
  }
  // 2. The closest point of each pairwise intersection circle.
  for (size_t i = 0; i < n; ++i)
  {
    for (size_t j = i + 1; j < n; ++j)
    {
      Circle circle;
      if (!IntersectTwoSpheres(c[i], m_Radii[i], c[j], m_Radii[j], circle))
      {
        continue;
      }
      const Vec3 q = ClosestPointOnCircle(p, circle);
      if (Norm(p - q) < best.distance && onBoundary(q))
      {
        best.Consider(p, q);
      }
      // 3. The triple points on this circle (ends of the uncovered arcs).
      for (size_t k = j + 1; k < n; ++k)
      {
        Vec3               t[2];
        const unsigned int count = IntersectThreeSpheres(c[i], m_Radii[i], c[j], m_Radii[j], c[k], m_Radii[k], t);
        for (unsigned int m = 0; m < count; ++m)
        {
          if (Norm(p - t[m]) < best.distance && onBoundary(t[m]))
          {
            best.Consider(p, t[m]);
          }
        }
      }
    }
  }
  if (!std::isfinite(best.distance))
  {
    // Only reachable in degenerate configurations (four or more spheres through one
    // point, tangencies) where rounding removed every candidate.
    best = fallback;
  }
  closest = ToPoint(best.point);
  return inside ? -best.distance : best.distance;
}

void
SphereUnionImplicitSurface::GetBounds(InputType & lower, InputType & upper) const
{
  this->ThrowIfParametersInvalid();
  lower.Fill(Infinity);
  upper.Fill(-Infinity);
  for (size_t s = 0; s < m_Centers.size(); ++s)
  {
    for (unsigned int i = 0; i < 3; ++i)
    {
      lower[i] = std::min(lower[i], m_Centers[s][i] - m_Radii[s]);
      upper[i] = std::max(upper[i], m_Centers[s][i] + m_Radii[s]);
    }
  }
}

void
SphereUnionImplicitSurface::PrintSelf(std::ostream & os, Indent indent) const
{
  Superclass::PrintSelf(os, indent);
  os << indent << "NumberOfSpheres: " << m_Centers.size() << std::endl;
  for (size_t s = 0; s < m_Centers.size(); ++s)
  {
    os << indent << "Sphere " << s << ": center " << m_Centers[s] << ", radius " << m_Radii[s] << std::endl;
  }
}

// =================================================================================
// SphereDifferenceImplicitSurface
// =================================================================================

SphereDifferenceImplicitSurface::SphereDifferenceImplicitSurface()
{
  m_CenterA.Fill(0.0);
  m_CenterB.Fill(0.0);
  m_CenterB[0] = 1.0;
}

void
SphereDifferenceImplicitSurface::SetCenterA(const InputType & center)
{
  this->RequireFinite("CenterA", center);
  m_CenterA = center;
  this->ParametersChanged();
}

void
SphereDifferenceImplicitSurface::SetRadiusA(double radius)
{
  this->RequirePositive("RadiusA", radius);
  m_RadiusA = radius;
  this->ParametersChanged();
}

void
SphereDifferenceImplicitSurface::SetCenterB(const InputType & center)
{
  this->RequireFinite("CenterB", center);
  m_CenterB = center;
  this->ParametersChanged();
}

void
SphereDifferenceImplicitSurface::SetRadiusB(double radius)
{
  this->RequirePositive("RadiusB", radius);
  m_RadiusB = radius;
  this->ParametersChanged();
}

std::string
SphereDifferenceImplicitSurface::CheckParameterConsistency() const
{
  const double distance = m_CenterA.EuclideanDistanceTo(m_CenterB);
  if (distance + m_RadiusA <= m_RadiusB)
  {
    return "ball B (CenterB = " + ToString(m_CenterB) + ", RadiusB = " + ToString(m_RadiusB) +
           ") contains ball A (CenterA = " + ToString(m_CenterA) + ", RadiusA = " + ToString(m_RadiusA) +
           "): A minus B is empty";
  }
  return {};
}

SphereDifferenceImplicitSurface::OutputType
SphereDifferenceImplicitSurface::Evaluate(const InputType & point) const
{
  InputType closest;
  return this->EvaluateWithClosestPoint(point, closest);
}

SphereDifferenceImplicitSurface::InputType
SphereDifferenceImplicitSurface::ClosestSurfacePoint(const InputType & point) const
{
  InputType closest;
  this->EvaluateWithClosestPoint(point, closest);
  return closest;
}

SphereDifferenceImplicitSurface::OutputType
SphereDifferenceImplicitSurface::EvaluateWithClosestPoint(const InputType & point, InputType & closest) const
{
  this->ThrowIfParametersInvalid();
  const Vec3 p = ToVec(point);
  const Vec3 a = ToVec(m_CenterA);
  const Vec3 b = ToVec(m_CenterB);
  const bool inside = Norm(p - a) <= m_RadiusA && Norm(p - b) >= m_RadiusB;

  NearestCandidate best;
  NearestCandidate fallback;
  double           d = 0.0;
  // Sphere A where it is not inside B.
  const Vec3 qa = RadialProjection(p, a, m_RadiusA, d);
  fallback.Consider(d, qa);
  if (!StrictlyInsideBall(qa, b, m_RadiusB))
  {
    best.Consider(d, qa);
  }
  // Sphere B where it is inside A.
  const Vec3 qb = RadialProjection(p, b, m_RadiusB, d);
  if (!StrictlyOutsideBall(qb, a, m_RadiusA))
  {
    best.Consider(d, qb);
  }
  // Their intersection circle (also covers a point at either centre, which lies on
  // the circle's axis and so is equally far from all of it).
  Circle circle;
  if (IntersectTwoSpheres(a, m_RadiusA, b, m_RadiusB, circle))
  {
    best.Consider(p, ClosestPointOnCircle(p, circle));
  }
  if (!std::isfinite(best.distance))
  {
    best = fallback;
  }
  closest = ToPoint(best.point);
  return inside ? -best.distance : best.distance;
}

void
SphereDifferenceImplicitSurface::GetBounds(InputType & lower, InputType & upper) const
{
  this->ThrowIfParametersInvalid();
  for (unsigned int i = 0; i < 3; ++i)
  {
    lower[i] = m_CenterA[i] - m_RadiusA;
    upper[i] = m_CenterA[i] + m_RadiusA;
  }
}

void
SphereDifferenceImplicitSurface::PrintSelf(std::ostream & os, Indent indent) const
{
  Superclass::PrintSelf(os, indent);
  os << indent << "CenterA: " << m_CenterA << std::endl;
  os << indent << "RadiusA: " << m_RadiusA << std::endl;
  os << indent << "CenterB: " << m_CenterB << std::endl;
  os << indent << "RadiusB: " << m_RadiusB << std::endl;
}

// =================================================================================
// NarrowCleftImplicitSurface
// =================================================================================

NarrowCleftImplicitSurface::NarrowCleftImplicitSurface()
{
  m_Center.Fill(0.0);
  m_HalfSizes.Fill(10.0);
  m_Rotation.SetIdentity();
  this->UpdateRectangles();
}

void
NarrowCleftImplicitSurface::SetCenter(const InputType & center)
{
  this->RequireFinite("Center", center);
  m_Center = center;
  this->ParametersChanged();
}

void
NarrowCleftImplicitSurface::SetHalfSizes(const VectorType & halfSizes)
{
  this->RequirePositive("HalfSizes", halfSizes);
  m_HalfSizes = halfSizes;
  this->UpdateRectangles();
  this->ParametersChanged();
}

void
NarrowCleftImplicitSurface::SetSlotWidth(double width)
{
  this->RequirePositive("SlotWidth", width);
  m_SlotWidth = width;
  this->UpdateRectangles();
  this->ParametersChanged();
}

void
NarrowCleftImplicitSurface::SetSlotDepth(double depth)
{
  this->RequirePositive("SlotDepth", depth);
  m_SlotDepth = depth;
  this->UpdateRectangles();
  this->ParametersChanged();
}

void
NarrowCleftImplicitSurface::SetRotation(const MatrixType & rotation)
{
  m_Rotation = this->RequireRotation("Rotation", rotation);
  this->ParametersChanged();
}

std::string
NarrowCleftImplicitSurface::CheckParameterConsistency() const
{
  if (!(m_SlotWidth < 2.0 * m_HalfSizes[0]))
  {
    return "SlotWidth must be smaller than the block's width 2 * HalfSizes[0], got SlotWidth = " +
           ToString(m_SlotWidth) + " and HalfSizes = " + ToString(m_HalfSizes);
  }
  if (!(m_SlotDepth < 2.0 * m_HalfSizes[2]))
  {
    return "SlotDepth must be smaller than the block's height 2 * HalfSizes[2], got SlotDepth = " +
           ToString(m_SlotDepth) + " and HalfSizes = " + ToString(m_HalfSizes);
  }
  return {};
}

void
NarrowCleftImplicitSurface::UpdateRectangles()
{
  const double X = m_HalfSizes[0];
  const double Y = m_HalfSizes[1];
  const double Z = m_HalfSizes[2];
  const double s = 0.5 * m_SlotWidth;
  const double floorZ = Z - m_SlotDepth;
  const auto   v = [](double x, double y, double z) { return MakeVec3(x, y, z); };

  m_Rectangles.clear();
  const auto add = [this](const Vec3 & corner, const Vec3 & e0, const Vec3 & e1) {
    m_Rectangles.push_back(Rectangle{ corner, e0, e1 });
  };
  // Bottom face z = -Z.
  add(v(-X, -Y, -Z), v(2 * X, 0, 0), v(0, 2 * Y, 0));
  // Top face z = +Z on both sides of the slot.
  add(v(-X, -Y, Z), v(X - s, 0, 0), v(0, 2 * Y, 0));
  add(v(s, -Y, Z), v(X - s, 0, 0), v(0, 2 * Y, 0));
  // Outer faces x = -X and x = +X.
  add(v(-X, -Y, -Z), v(0, 2 * Y, 0), v(0, 0, 2 * Z));
  add(v(X, -Y, -Z), v(0, 2 * Y, 0), v(0, 0, 2 * Z));
  // Slot walls x = -s and x = +s, from the floor to the top.
  add(v(-s, -Y, floorZ), v(0, 2 * Y, 0), v(0, 0, m_SlotDepth));
  add(v(s, -Y, floorZ), v(0, 2 * Y, 0), v(0, 0, m_SlotDepth));
  // Slot floor z = floorZ.
  add(v(-s, -Y, floorZ), v(2 * s, 0, 0), v(0, 2 * Y, 0));
  // The U-shaped faces y = -Y and y = +Y: the part below the floor and the two prongs.
  for (const double y : { -Y, Y })
  {
    add(v(-X, y, -Z), v(2 * X, 0, 0), v(0, 0, floorZ + Z));
    add(v(-X, y, floorZ), v(X - s, 0, 0), v(0, 0, m_SlotDepth));
    add(v(s, y, floorZ), v(X - s, 0, 0), v(0, 0, m_SlotDepth));
  }
}

NarrowCleftImplicitSurface::OutputType
NarrowCleftImplicitSurface::Evaluate(const InputType & point) const
{
  InputType closest;
  return this->EvaluateWithClosestPoint(point, closest);
}

NarrowCleftImplicitSurface::InputType
NarrowCleftImplicitSurface::ClosestSurfacePoint(const InputType & point) const
{
  InputType closest;
  this->EvaluateWithClosestPoint(point, closest);
  return closest;
}

NarrowCleftImplicitSurface::OutputType
NarrowCleftImplicitSurface::EvaluateWithClosestPoint(const InputType & point, InputType & closest) const
{
  this->ThrowIfParametersInvalid();
  const Vec3 q = ToLocal(m_Rotation, ToVec(point) - ToVec(m_Center));
  double     bestSquared = Infinity;
  Vec3       bestPoint = q;
  for (const Rectangle & r : m_Rectangles)
  {
    const Vec3   c = ClosestPointOnRectangle(q, r.corner, r.edge0, r.edge1);
    const double d2 = SquaredNorm(q - c);
    if (d2 < bestSquared)
    {
      bestSquared = d2;
      bestPoint = c;
    }
  }
  const double floorZ = m_HalfSizes[2] - m_SlotDepth;
  const bool   inBlock =
    std::abs(q[0]) <= m_HalfSizes[0] && std::abs(q[1]) <= m_HalfSizes[1] && std::abs(q[2]) <= m_HalfSizes[2];
  const bool inSlot = std::abs(q[0]) < 0.5 * m_SlotWidth && q[2] > floorZ;
  closest = ToPoint(ToVec(m_Center) + ToPhysical(m_Rotation, bestPoint));
  const double distance = std::sqrt(bestSquared);
  return (inBlock && !inSlot) ? -distance : distance;
}

void
NarrowCleftImplicitSurface::GetBounds(InputType & lower, InputType & upper) const
{
  this->ThrowIfParametersInvalid();
  for (unsigned int i = 0; i < 3; ++i)
  {
    double halfExtent = 0.0;
    for (unsigned int j = 0; j < 3; ++j)
    {
      halfExtent += std::abs(m_Rotation(i, j)) * m_HalfSizes[j];
    }
    lower[i] = m_Center[i] - halfExtent;
    upper[i] = m_Center[i] + halfExtent;
  }
}

void
NarrowCleftImplicitSurface::PrintSelf(std::ostream & os, Indent indent) const
{
  Superclass::PrintSelf(os, indent);
  os << indent << "Center: " << m_Center << std::endl;
  os << indent << "HalfSizes: " << m_HalfSizes << std::endl;
  os << indent << "SlotWidth: " << m_SlotWidth << std::endl;
  os << indent << "SlotDepth: " << m_SlotDepth << std::endl;
  os << indent << "Rotation: " << std::endl << m_Rotation;
}

} // namespace itk
