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
#include "itkMeshExtractionClosedFormGeometry.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace itk
{
namespace
{
using MeshExtraction::Circle3;
using MeshExtraction::ClosestPointOnCircle;
using MeshExtraction::ClosestPointOnEllipsoid;
using MeshExtraction::ClosestPointOnRectangle;
using MeshExtraction::Dot;
using MeshExtraction::Infinity;
using MeshExtraction::IntersectThreeSpheres;
using MeshExtraction::IntersectTwoSpheres;
using MeshExtraction::LocalCoordinates;
using MeshExtraction::MakeVec3;
using MeshExtraction::NearestCandidate;
using MeshExtraction::Norm;
using MeshExtraction::PhysicalPoint;
using MeshExtraction::RadialDirection;
using MeshExtraction::RadialProjection;
using MeshExtraction::RotatedBoxHalfExtent;
using MeshExtraction::SquaredNorm;
using MeshExtraction::StrictlyInsideBall;
using MeshExtraction::StrictlyOutsideBall;
using MeshExtraction::ToPoint3;
using MeshExtraction::ToVec3;
using MeshExtraction::Vec3;

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
  const double maximumError = MeshExtraction::OrthogonalityError(value);
  if (!(maximumError <= 1e-6))
  {
    itkExceptionMacro(<< parameterName << " must be an orthogonal matrix (orthonormal columns within 1e-6), got "
                      << value << "with max |R^T R - I| = " << maximumError);
  }
  // Gram-Schmidt on the columns, so that R^T R = I to rounding and distances
  // computed in the local frame are distances in physical space.
  return MeshExtraction::OrthonormalizeColumns(value);
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

namespace
{
template <typename TValue>
std::string
ToText(const TValue & value)
{
  std::ostringstream s;
  s.precision(17);
  s << value;
  return s.str();
}
} // namespace

std::string
ImplicitSurfaceFunction::ParameterText(double value)
{
  return ToText(value);
}

std::string
ImplicitSurfaceFunction::ParameterText(const InputType & value)
{
  return ToText(value);
}

std::string
ImplicitSurfaceFunction::ParameterText(const VectorType & value)
{
  return ToText(value);
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
  return Dot(ToVec3(point) - ToVec3(m_Point), m_Normal);
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
  const Vec3   p = ToVec3(point);
  const double d = Dot(p - ToVec3(m_Point), m_Normal);
  closest = ToPoint3(p - m_Normal * d);
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
  return Norm(ToVec3(point) - ToVec3(m_Center)) - m_Radius;
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
  const Vec3 p = ToVec3(point);
  const Vec3 c = ToVec3(m_Center);
  double     unused = 0.0;
  closest = ToPoint3(RadialProjection(p, c, m_Radius, unused));
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
  const Vec3 q = LocalCoordinates(m_Center, m_Rotation, point);

  Vec3         local;
  const double distance = ClosestPointOnEllipsoid(m_SemiAxes, q, local);
  // The level sum_k (q_k / a_k)^2 of q: below 1 inside.
  double level = 0.0;
  for (unsigned int k = 0; k < 3; ++k)
  {
    level += (q[k] / m_SemiAxes[k]) * (q[k] / m_SemiAxes[k]);
  }
  closest = PhysicalPoint(m_Center, m_Rotation, local);
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
    return "MinorRadius must be smaller than MajorRadius (a ring torus), got MinorRadius = " +
           ParameterText(m_MinorRadius) + " and MajorRadius = " + ParameterText(m_MajorRadius);
  }
  return {};
}

TorusImplicitSurface::OutputType
TorusImplicitSurface::Evaluate(const InputType & point) const
{
  this->ThrowIfParametersInvalid();
  const Vec3   d = ToVec3(point) - ToVec3(m_Center);
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
  const Vec3   p = ToVec3(point);
  const Vec3   c = ToVec3(m_Center);
  const Vec3   d = p - c;
  const double h = Dot(d, m_Axis);
  double       rho = 0.0;
  // On the axis every core point is equally close, and a fixed one is used.
  const Vec3   radial = RadialDirection(d, m_Axis, rho);
  const Vec3   core = c + radial * m_MajorRadius;
  const Vec3   v = p - core;
  const double l = Norm(v);
  closest = ToPoint3(l > 0.0 ? core + v * (m_MinorRadius / l) : core + radial * m_MinorRadius);
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
  const Vec3 q = LocalCoordinates(m_Center, m_Rotation, point);
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
  closest = PhysicalPoint(m_Center, m_Rotation, onSurface);
  return distance;
}

void
BoxImplicitSurface::GetBounds(InputType & lower, InputType & upper) const
{
  this->ThrowIfParametersInvalid();
  for (unsigned int i = 0; i < 3; ++i)
  {
    const double halfExtent = RotatedBoxHalfExtent(m_Rotation, m_HalfSizes, i);
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
  const Vec3        p = ToVec3(point);
  const size_t      n = m_Centers.size();
  std::vector<Vec3> c(n);
  for (size_t i = 0; i < n; ++i)
  {
    c[i] = ToVec3(m_Centers[i]);
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
      Circle3 circle;
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
  closest = ToPoint3(best.point);
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
    return "ball B (CenterB = " + ParameterText(m_CenterB) + ", RadiusB = " + ParameterText(m_RadiusB) +
           ") contains ball A (CenterA = " + ParameterText(m_CenterA) + ", RadiusA = " + ParameterText(m_RadiusA) +
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
  const Vec3 p = ToVec3(point);
  const Vec3 a = ToVec3(m_CenterA);
  const Vec3 b = ToVec3(m_CenterB);
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
  Circle3 circle;
  if (IntersectTwoSpheres(a, m_RadiusA, b, m_RadiusB, circle))
  {
    best.Consider(p, ClosestPointOnCircle(p, circle));
  }
  if (!std::isfinite(best.distance))
  {
    best = fallback;
  }
  closest = ToPoint3(best.point);
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
           ParameterText(m_SlotWidth) + " and HalfSizes = " + ParameterText(m_HalfSizes);
  }
  if (!(m_SlotDepth < 2.0 * m_HalfSizes[2]))
  {
    return "SlotDepth must be smaller than the block's height 2 * HalfSizes[2], got SlotDepth = " +
           ParameterText(m_SlotDepth) + " and HalfSizes = " + ParameterText(m_HalfSizes);
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
  const Vec3 q = LocalCoordinates(m_Center, m_Rotation, point);
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
  closest = PhysicalPoint(m_Center, m_Rotation, bestPoint);
  const double distance = std::sqrt(bestSquared);
  return (inBlock && !inSlot) ? -distance : distance;
}

void
NarrowCleftImplicitSurface::GetBounds(InputType & lower, InputType & upper) const
{
  this->ThrowIfParametersInvalid();
  for (unsigned int i = 0; i < 3; ++i)
  {
    const double halfExtent = RotatedBoxHalfExtent(m_Rotation, m_HalfSizes, i);
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
