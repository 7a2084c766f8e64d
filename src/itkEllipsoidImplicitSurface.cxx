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
#include "itkMeshExtractionClosedFormGeometry.h"

#include <cmath>

namespace itk
{
namespace
{
using MeshExtraction::Vec3;
using MeshExtraction::detail::ClosestPointOnEllipsoid;
using MeshExtraction::detail::LocalCoordinates;
using MeshExtraction::detail::PhysicalPoint;
} // namespace

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

} // namespace itk
