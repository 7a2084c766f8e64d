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
#include "itkPlaneImplicitSurface.h"
#include "itkMeshExtractionClosedFormGeometry.h"

namespace itk
{
namespace
{
using MeshExtraction::Dot;
using MeshExtraction::ToVec3;
using MeshExtraction::Vec3;
using MeshExtraction::detail::Infinity;
using MeshExtraction::detail::ToPoint3;
} // namespace

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

} // namespace itk
