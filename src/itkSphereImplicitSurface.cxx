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
#include "itkMeshExtractionClosedFormGeometry.h"

namespace itk
{
namespace
{
using MeshExtraction::Norm;
using MeshExtraction::ToVec3;
using MeshExtraction::Vec3;
using MeshExtraction::detail::RadialProjection;
using MeshExtraction::detail::ToPoint3;
} // namespace

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

} // namespace itk
