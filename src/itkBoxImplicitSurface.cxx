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
#include "itkBoxImplicitSurface.h"
#include "itkMeshExtractionClosedFormGeometry.h"

#include <cmath>

namespace itk
{
namespace
{
using MeshExtraction::Norm;
using MeshExtraction::Vec3;
using MeshExtraction::detail::LocalCoordinates;
using MeshExtraction::detail::PhysicalPoint;
using MeshExtraction::detail::RotatedBoxHalfExtent;
} // namespace

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

} // namespace itk
