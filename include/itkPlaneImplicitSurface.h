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
#ifndef itkPlaneImplicitSurface_h
#define itkPlaneImplicitSurface_h

#include "itkImplicitSurfaceFunction.h"
#include "MeshExtractionExport.h"

namespace itk
{
/** \class PlaneImplicitSurface
 * \brief The plane through Point with normal Normal; inside is the half-space the
 * normal points away from.
 *
 * Evaluate(p) = (p - Point) . n / |n|. The plane is unbounded: GetBounds reports
 * -/+ infinity, except along a coordinate axis the normal is parallel to.
 * Defaults: Point (0,0,0), Normal (0,0,1).
 * \ingroup MeshExtraction
 */
class MeshExtraction_EXPORT PlaneImplicitSurface : public ImplicitSurfaceFunction
{
public:
  ITK_DISALLOW_COPY_AND_MOVE(PlaneImplicitSurface);
  using Self = PlaneImplicitSurface;
  using Superclass = ImplicitSurfaceFunction;
  using Pointer = SmartPointer<Self>;
  using ConstPointer = SmartPointer<const Self>;
  itkOverrideGetNameOfClassMacro(PlaneImplicitSurface);
  itkNewMacro(Self);

  /** A point of the plane. */
  void
  SetPoint(const InputType & point);
  itkGetConstReferenceMacro(Point, InputType);
  /** The normal (any non-zero length; stored normalised). */
  void
  SetNormal(const VectorType & normal);
  itkGetConstReferenceMacro(Normal, VectorType);

  OutputType
  Evaluate(const InputType & point) const override;
  InputType
  ClosestSurfacePoint(const InputType & point) const override;
  OutputType
  EvaluateWithClosestPoint(const InputType & point, InputType & closest) const override;
  void
  GetBounds(InputType & lower, InputType & upper) const override;

protected:
  PlaneImplicitSurface();
  ~PlaneImplicitSurface() override = default;
  void
  PrintSelf(std::ostream & os, Indent indent) const override;

private:
  InputType  m_Point;
  VectorType m_Normal;
};
} // namespace itk

#endif
