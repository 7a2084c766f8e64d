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
#include "itkMeshExtractionTriangleGeometry.h"

#include <algorithm>
#include <cmath>

namespace itk
{
namespace MeshExtraction
{
TriangleMeasures
MeasureTriangle(const Vec3 & a, const Vec3 & b, const Vec3 & c)
{
  TriangleMeasures m{};
  const Vec3       ab = b - a;
  const Vec3       bc = c - b;
  const Vec3       ca = a - c;
  m.edgeLength[0] = Norm(bc);
  m.edgeLength[1] = Norm(ca);
  m.edgeLength[2] = Norm(ab);
  const double twiceArea = Norm(Cross(ab, -ca));
  m.area = 0.5 * twiceArea;
  const double sumSq =
    m.edgeLength[0] * m.edgeLength[0] + m.edgeLength[1] * m.edgeLength[1] + m.edgeLength[2] * m.edgeLength[2];
  const double minEdge = std::min({ m.edgeLength[0], m.edgeLength[1], m.edgeLength[2] });
  const double maxEdge = std::max({ m.edgeLength[0], m.edgeLength[1], m.edgeLength[2] });
  if (!(minEdge > 0.0))
  {
    m.angle[0] = m.angle[1] = m.angle[2] = 0.0;
    for (unsigned i = 0; i < 3; ++i)
    {
      if (m.edgeLength[i] > 0.0)
      {
        m.angle[i] = itk::Math::pi;
      }
    }
    m.minAngle = 0.0;
    m.maxAngle = itk::Math::pi;
    return m;
  }
  m.angle[0] = AngleBetween(ab, -ca);
  m.angle[1] = AngleBetween(bc, -ab);
  m.angle[2] = AngleBetween(ca, -bc);
  m.minAngle = std::min({ m.angle[0], m.angle[1], m.angle[2] });
  m.maxAngle = std::max({ m.angle[0], m.angle[1], m.angle[2] });
  m.qLength = minEdge / maxEdge;
  m.qAngle = m.maxAngle > 0.0 ? m.minAngle / m.maxAngle : 0.0;
  m.qArea = 4.0 * std::sqrt(3.0) * m.area / sumSq;
  // Rounding can push an equilateral triangle a hair above 1.
  m.qAngle = std::min(m.qAngle, 1.0);
  m.qArea = std::min(m.qArea, 1.0);
  return m;
}

Vec3
TriangleCircumcenter(const Vec3 & a, const Vec3 & b, const Vec3 & c)
{
  const Vec3   ab = b - a;
  const Vec3   ac = c - a;
  const Vec3   n = Cross(ab, ac);
  const double n2 = SquaredNorm(n);
  if (!(n2 > 0.0))
  {
    return TriangleCentroid(a, b, c);
  }
  return a + (Cross(n, ab) * SquaredNorm(ac) + Cross(ac, n) * SquaredNorm(ab)) * (1.0 / (2.0 * n2));
}

bool
IsInsideCircumcircle(const Vec3 & a, const Vec3 & b, const Vec3 & c, const Vec3 & d)
{
  const Vec3   n = TriangleUnitNormal(a, b, c);
  const Vec3   center = TriangleCircumcenter(a, b, c);
  const Vec3   dd = d - n * Dot(d - center, n);
  const double r2 = SquaredNorm(a - center);
  return SquaredNorm(dd - center) < r2 * (1.0 - 1e-12);
}
} // namespace MeshExtraction
} // namespace itk
