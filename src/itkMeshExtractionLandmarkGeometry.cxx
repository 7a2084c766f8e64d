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
#include "itkMeshExtractionLandmarkGeometry.h"
#include "itkVersor.h"

#include <cmath>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
Vector<double, 3>
PerpendicularPart(const Vector<double, 3> & v, const Vector<double, 3> & u)
{
  return v - u * (v * u);
}

Matrix<double, 3, 3>
AxisAngleRotation(const Vector<double, 3> & axis, double angle)
{
  Versor<double> versor;
  versor.Set(axis, angle);
  return versor.GetMatrix();
}

Matrix<double, 3, 3>
ShortestArcRotation(const Vector<double, 3> & from, const Vector<double, 3> & to)
{
  const Vector<double, 3> axis = CrossProduct(from, to);
  const double            sine = axis.GetNorm();
  const double            cosine = from * to;
  if (sine > 1e-12)
  {
    return AxisAngleRotation(axis / sine, std::atan2(sine, cosine));
  }
  Matrix<double, 3, 3> identity;
  identity.SetIdentity();
  if (cosine > 0.0)
  {
    return identity;
  }
  // Opposite directions: a half turn about any axis perpendicular to `from`; the one
  // closest to the coordinate axis least aligned with it.
  unsigned int least = 0;
  for (unsigned int d = 1; d < 3; ++d)
  {
    if (std::abs(from[d]) < std::abs(from[least]))
    {
      least = d;
    }
  }
  Vector<double, 3> e;
  e.Fill(0.0);
  e[least] = 1.0;
  Vector<double, 3> perpendicular = PerpendicularPart(e, from);
  perpendicular.Normalize();
  return AxisAngleRotation(perpendicular, itk::Math::pi);
}
} // namespace detail
} // namespace MeshExtraction
} // namespace itk
