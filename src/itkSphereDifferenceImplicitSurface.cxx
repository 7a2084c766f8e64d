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
#include "itkSphereDifferenceImplicitSurface.h"
#include "itkMeshExtractionClosedFormGeometry.h"

#include <cmath>

namespace itk
{
namespace
{
using MeshExtraction::Norm;
using MeshExtraction::ToVec3;
using MeshExtraction::Vec3;
using MeshExtraction::detail::Circle3;
using MeshExtraction::detail::ClosestPointOnCircle;
using MeshExtraction::detail::IntersectTwoSpheres;
using MeshExtraction::detail::NearestCandidate;
using MeshExtraction::detail::RadialProjection;
using MeshExtraction::detail::StrictlyInsideBall;
using MeshExtraction::detail::StrictlyOutsideBall;
using MeshExtraction::detail::ToPoint3;
} // namespace

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

} // namespace itk
