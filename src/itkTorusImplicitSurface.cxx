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
#include "itkTorusImplicitSurface.h"
#include "itkMeshExtractionClosedFormGeometry.h"

#include <algorithm>
#include <cmath>

namespace itk
{
namespace
{
using MeshExtraction::Dot;
using MeshExtraction::Norm;
using MeshExtraction::ToVec3;
using MeshExtraction::Vec3;
using MeshExtraction::detail::RadialDirection;
using MeshExtraction::detail::ToPoint3;
} // namespace

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

} // namespace itk
