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
#include "itkNarrowCleftImplicitSurface.h"
#include "itkMeshExtractionClosedFormGeometry.h"

#include <cmath>

namespace itk
{
namespace
{
using MeshExtraction::MakeVec3;
using MeshExtraction::SquaredNorm;
using MeshExtraction::Vec3;
using MeshExtraction::detail::ClosestPointOnRectangle;
using MeshExtraction::detail::Infinity;
using MeshExtraction::detail::LocalCoordinates;
using MeshExtraction::detail::PhysicalPoint;
using MeshExtraction::detail::RotatedBoxHalfExtent;
} // namespace

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
