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
#ifndef itkSphereImplicitSurface_h
#define itkSphereImplicitSurface_h

#include "itkImplicitSurfaceFunction.h"
#include "MeshExtractionExport.h"

namespace itk
{
/** \class SphereImplicitSurface
 * \brief The sphere of radius Radius around Center: Evaluate(p) = |p - Center| - Radius.
 *
 * Defaults: Center (0,0,0), Radius 1.
 * \ingroup MeshExtraction
 */
class MeshExtraction_EXPORT SphereImplicitSurface : public ImplicitSurfaceFunction
{
public:
  ITK_DISALLOW_COPY_AND_MOVE(SphereImplicitSurface);
  using Self = SphereImplicitSurface;
  using Superclass = ImplicitSurfaceFunction;
  using Pointer = SmartPointer<Self>;
  using ConstPointer = SmartPointer<const Self>;
  itkOverrideGetNameOfClassMacro(SphereImplicitSurface);
  itkNewMacro(Self);

  void
  SetCenter(const InputType & center);
  itkGetConstReferenceMacro(Center, InputType);
  /** Radius > 0. */
  void
  SetRadius(double radius);
  itkGetConstMacro(Radius, double);

  OutputType
  Evaluate(const InputType & point) const override;
  InputType
  ClosestSurfacePoint(const InputType & point) const override;
  OutputType
  EvaluateWithClosestPoint(const InputType & point, InputType & closest) const override;
  void
  GetBounds(InputType & lower, InputType & upper) const override;

protected:
  SphereImplicitSurface();
  ~SphereImplicitSurface() override = default;
  void
  PrintSelf(std::ostream & os, Indent indent) const override;

private:
  InputType m_Center;
  double    m_Radius{ 1.0 };
};
} // namespace itk

#endif
