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
#ifndef itkSphereUnionImplicitSurface_h
#define itkSphereUnionImplicitSurface_h

#include "itkImplicitSurfaceFunction.h"
#include "MeshExtractionExport.h"

#include <vector>
#include <string>

namespace itk
{
/** \class SphereUnionImplicitSurface
 * \brief The boundary of the union of N balls (e.g. two overlapping spheres).
 *
 * Exact for points inside and outside the union. The closest boundary point is
 * one of: the radial projection onto a sphere that is not inside another ball; the
 * point of a pairwise intersection circle closest to p that is not inside a third
 * ball; a triple intersection point not inside a fourth ball. Cost is O(N^4) per
 * evaluation, meant for a handful of spheres. At least one sphere is required.
 * Default: no spheres.
 * \ingroup MeshExtraction
 */
class MeshExtraction_EXPORT SphereUnionImplicitSurface : public ImplicitSurfaceFunction
{
public:
  ITK_DISALLOW_COPY_AND_MOVE(SphereUnionImplicitSurface);
  using Self = SphereUnionImplicitSurface;
  using Superclass = ImplicitSurfaceFunction;
  using Pointer = SmartPointer<Self>;
  using ConstPointer = SmartPointer<const Self>;
  itkOverrideGetNameOfClassMacro(SphereUnionImplicitSurface);
  itkNewMacro(Self);

  /** Adds the ball of radius `radius` (> 0) around `center`. */
  void
  AddSphere(const InputType & center, double radius);
  void
  RemoveAllSpheres();
  unsigned int
  GetNumberOfSpheres() const
  {
    return static_cast<unsigned int>(m_Centers.size());
  }
  /** Throws for i >= GetNumberOfSpheres(). */
  const InputType &
  GetSphereCenter(unsigned int i) const;
  double
  GetSphereRadius(unsigned int i) const;

  OutputType
  Evaluate(const InputType & point) const override;
  InputType
  ClosestSurfacePoint(const InputType & point) const override;
  OutputType
  EvaluateWithClosestPoint(const InputType & point, InputType & closest) const override;
  void
  GetBounds(InputType & lower, InputType & upper) const override;

protected:
  SphereUnionImplicitSurface();
  ~SphereUnionImplicitSurface() override = default;
  void
  PrintSelf(std::ostream & os, Indent indent) const override;
  std::string
  CheckParameterConsistency() const override;

private:
  std::vector<InputType> m_Centers;
  std::vector<double>    m_Radii;
};
} // namespace itk

#endif
