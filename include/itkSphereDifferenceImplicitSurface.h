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
#ifndef itkSphereDifferenceImplicitSurface_h
#define itkSphereDifferenceImplicitSurface_h

#include "itkImplicitSurfaceFunction.h"
#include "MeshExtractionExport.h"

#include <string>

namespace itk
{
/** \class SphereDifferenceImplicitSurface
 * \brief Ball A minus ball B: the "indented sphere" when B cuts into A's surface.
 *
 * The solid is A without the interior of B; its boundary is the part of sphere A
 * outside B, the part of sphere B inside A, and their intersection circle. The
 * distance is exact (closest point among the radial projections onto both spheres
 * that lie on the boundary and the closest point of the circle). B may also lie
 * wholly inside A (a hollow ball) or miss A; B must not contain A.
 * Defaults: A = (0,0,0), radius 1; B = (1,0,0), radius 0.5.
 * \ingroup MeshExtraction
 */
class MeshExtraction_EXPORT SphereDifferenceImplicitSurface : public ImplicitSurfaceFunction
{
public:
  ITK_DISALLOW_COPY_AND_MOVE(SphereDifferenceImplicitSurface);
  using Self = SphereDifferenceImplicitSurface;
  using Superclass = ImplicitSurfaceFunction;
  using Pointer = SmartPointer<Self>;
  using ConstPointer = SmartPointer<const Self>;
  itkOverrideGetNameOfClassMacro(SphereDifferenceImplicitSurface);
  itkNewMacro(Self);

  void
  SetCenterA(const InputType & center);
  itkGetConstReferenceMacro(CenterA, InputType);
  void
  SetRadiusA(double radius);
  itkGetConstMacro(RadiusA, double);
  void
  SetCenterB(const InputType & center);
  itkGetConstReferenceMacro(CenterB, InputType);
  void
  SetRadiusB(double radius);
  itkGetConstMacro(RadiusB, double);

  OutputType
  Evaluate(const InputType & point) const override;
  InputType
  ClosestSurfacePoint(const InputType & point) const override;
  OutputType
  EvaluateWithClosestPoint(const InputType & point, InputType & closest) const override;
  void
  GetBounds(InputType & lower, InputType & upper) const override;

protected:
  SphereDifferenceImplicitSurface();
  ~SphereDifferenceImplicitSurface() override = default;
  void
  PrintSelf(std::ostream & os, Indent indent) const override;
  std::string
  CheckParameterConsistency() const override;

private:
  InputType m_CenterA;
  double    m_RadiusA{ 1.0 };
  InputType m_CenterB;
  double    m_RadiusB{ 0.5 };
};
} // namespace itk

#endif
