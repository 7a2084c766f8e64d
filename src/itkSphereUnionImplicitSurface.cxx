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
#include "itkSphereUnionImplicitSurface.h"
#include "itkMeshExtractionClosedFormGeometry.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace itk
{
namespace
{
using MeshExtraction::Norm;
using MeshExtraction::ToVec3;
using MeshExtraction::Vec3;
using MeshExtraction::detail::Circle3;
using MeshExtraction::detail::ClosestPointOnCircle;
using MeshExtraction::detail::Infinity;
using MeshExtraction::detail::IntersectThreeSpheres;
using MeshExtraction::detail::IntersectTwoSpheres;
using MeshExtraction::detail::NearestCandidate;
using MeshExtraction::detail::Point3;
using MeshExtraction::detail::RadialProjection;
using MeshExtraction::detail::StrictlyInsideBall;
using MeshExtraction::detail::ToPoint3;

/** The search for the point of the union's boundary closest to p, over the candidates
 * of the class documentation in a fixed order: the radial projections onto the
 * spheres, then for each pair of spheres the closest point of their intersection
 * circle followed by the triple points on that circle. A candidate counts only when
 * it lies on the boundary, i.e. in no ball's interior. */
class UnionBoundarySearch
{
public:
  UnionBoundarySearch(const Vec3 & p, const std::vector<Point3> & centers, const std::vector<double> & radii)
      : m_P(p)
      , m_Centers(centers.size())
      , m_Radii(radii)
  {
    for (size_t i = 0; i < centers.size(); ++i)
    {
      m_Centers[i] = ToVec3(centers[i]);
    }
  }

  /** The radial projection onto each sphere; returns whether p is in a ball. */
  bool
  ConsiderRadialProjections()
  {
    bool inside = false;
    for (size_t i = 0; i < m_Centers.size(); ++i)
    {
      inside = inside || Norm(m_P - m_Centers[i]) <= m_Radii[i];
      double     d = 0.0;
      const Vec3 q = RadialProjection(m_P, m_Centers[i], m_Radii[i], d);
      m_NearestSpherePoint.Consider(d, q);
      this->ConsiderIfOnBoundary(d, q);
      // The centre sees all of the sphere at the same distance: any boundary point of
      // it will do, and the circles and triple points provide one when the fixed
      // radial point is covered.
    }
    return inside;
  }

  /** The closest point of each pairwise intersection circle, and the triple points on
   * the circle (the ends of its uncovered arcs). */
  void
  ConsiderIntersectionCircles()
  {
    const size_t n = m_Centers.size();
    for (size_t i = 0; i < n; ++i)
    {
      for (size_t j = i + 1; j < n; ++j)
      {
        Circle3 circle;
        if (!IntersectTwoSpheres(m_Centers[i], m_Radii[i], m_Centers[j], m_Radii[j], circle))
        {
          continue;
        }
        const Vec3 q = ClosestPointOnCircle(m_P, circle);
        this->ConsiderIfOnBoundary(Norm(m_P - q), q);
        this->ConsiderTriplePoints(i, j);
      }
    }
  }

  /** The closest boundary candidate; the nearest sphere point, whether on the boundary
   * or not, in the degenerate configurations (four or more spheres through one point,
   * tangencies) where rounding removed every candidate. */
  const NearestCandidate &
  Nearest() const
  {
    return std::isfinite(m_Nearest.distance) ? m_Nearest : m_NearestSpherePoint;
  }

private:
  /** In no ball's interior. */
  bool
  IsOnBoundary(const Vec3 & q) const
  {
    for (size_t k = 0; k < m_Centers.size(); ++k)
    {
      if (StrictlyInsideBall(q, m_Centers[k], m_Radii[k]))
      {
        return false;
      }
    }
    return true;
  }

  void
  ConsiderIfOnBoundary(double d, const Vec3 & q)
  {
    if (d < m_Nearest.distance && this->IsOnBoundary(q))
    {
      m_Nearest.Consider(d, q);
    }
  }

  /** The points common to spheres i, j and each later sphere k. */
  void
  ConsiderTriplePoints(size_t i, size_t j)
  {
    for (size_t k = j + 1; k < m_Centers.size(); ++k)
    {
      Vec3               t[2];
      const unsigned int count =
        IntersectThreeSpheres(m_Centers[i], m_Radii[i], m_Centers[j], m_Radii[j], m_Centers[k], m_Radii[k], t);
      for (unsigned int m = 0; m < count; ++m)
      {
        this->ConsiderIfOnBoundary(Norm(m_P - t[m]), t[m]);
      }
    }
  }

  const Vec3                  m_P;
  std::vector<Vec3>           m_Centers;
  const std::vector<double> & m_Radii;
  NearestCandidate            m_Nearest;
  NearestCandidate            m_NearestSpherePoint;
};
} // namespace

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
  UnionBoundarySearch search(ToVec3(point), m_Centers, m_Radii);
  const bool          inside = search.ConsiderRadialProjections();
  search.ConsiderIntersectionCircles();
  const NearestCandidate & best = search.Nearest();
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

} // namespace itk
