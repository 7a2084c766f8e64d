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
#ifndef itkTorusImplicitSurface_h
#define itkTorusImplicitSurface_h

#include "itkImplicitSurfaceFunction.h"
#include "MeshExtractionExport.h"

#include <string>

namespace itk
{
/** \class TorusImplicitSurface
 * \brief A ring torus: the points at distance MinorRadius from the circle of radius
 * MajorRadius around Axis through Center.
 *
 * Evaluate(p) = sqrt((rho - R)^2 + h^2) - r, with h the height of p along the axis
 * and rho its distance from the axis. Requires 0 < MinorRadius < MajorRadius.
 * Defaults: Center (0,0,0), Axis (0,0,1), MajorRadius 2, MinorRadius 1.
 * \ingroup MeshExtraction
 */
class MeshExtraction_EXPORT TorusImplicitSurface : public ImplicitSurfaceFunction
{
public:
  ITK_DISALLOW_COPY_AND_MOVE(TorusImplicitSurface);
  using Self = TorusImplicitSurface;
  using Superclass = ImplicitSurfaceFunction;
  using Pointer = SmartPointer<Self>;
  using ConstPointer = SmartPointer<const Self>;
  itkOverrideGetNameOfClassMacro(TorusImplicitSurface);
  itkNewMacro(Self);

  void
  SetCenter(const InputType & center);
  itkGetConstReferenceMacro(Center, InputType);
  /** The axis of symmetry (any non-zero length; stored normalised). */
  void
  SetAxis(const VectorType & axis);
  itkGetConstReferenceMacro(Axis, VectorType);
  /** R > 0, the radius of the core circle. */
  void
  SetMajorRadius(double radius);
  itkGetConstMacro(MajorRadius, double);
  /** r > 0, the radius of the tube; r < R is checked by VerifyParameters(). */
  void
  SetMinorRadius(double radius);
  itkGetConstMacro(MinorRadius, double);
  /** Both radii at once. */
  void
  SetRadii(double majorRadius, double minorRadius);

  OutputType
  Evaluate(const InputType & point) const override;
  InputType
  ClosestSurfacePoint(const InputType & point) const override;
  OutputType
  EvaluateWithClosestPoint(const InputType & point, InputType & closest) const override;
  void
  GetBounds(InputType & lower, InputType & upper) const override;

protected:
  TorusImplicitSurface();
  ~TorusImplicitSurface() override = default;
  void
  PrintSelf(std::ostream & os, Indent indent) const override;
  std::string
  CheckParameterConsistency() const override;

private:
  InputType  m_Center;
  VectorType m_Axis;
  double     m_MajorRadius{ 2.0 };
  double     m_MinorRadius{ 1.0 };
};
} // namespace itk

#endif
