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
#ifndef itkBoxImplicitSurface_h
#define itkBoxImplicitSurface_h

#include "itkImplicitSurfaceFunction.h"
#include "MeshExtractionExport.h"

namespace itk
{
/** \class BoxImplicitSurface
 * \brief A rectangular box with half-sizes HalfSizes along the columns of Rotation,
 * centred at Center (the thin-plate phantom).
 *
 * Exact distance: outside, the distance to the clamped point; inside, the distance
 * to the nearest face.
 * Defaults: Center (0,0,0), HalfSizes (1,1,1), Rotation identity.
 * \ingroup MeshExtraction
 */
class MeshExtraction_EXPORT BoxImplicitSurface : public ImplicitSurfaceFunction
{
public:
  ITK_DISALLOW_COPY_AND_MOVE(BoxImplicitSurface);
  using Self = BoxImplicitSurface;
  using Superclass = ImplicitSurfaceFunction;
  using Pointer = SmartPointer<Self>;
  using ConstPointer = SmartPointer<const Self>;
  itkOverrideGetNameOfClassMacro(BoxImplicitSurface);
  itkNewMacro(Self);

  void
  SetCenter(const InputType & center);
  itkGetConstReferenceMacro(Center, InputType);
  /** Half the edge lengths, each > 0. */
  void
  SetHalfSizes(const VectorType & halfSizes);
  itkGetConstReferenceMacro(HalfSizes, VectorType);
  /** Orthogonal matrix whose column i is the direction of box axis i. */
  void
  SetRotation(const MatrixType & rotation);
  itkGetConstReferenceMacro(Rotation, MatrixType);

  OutputType
  Evaluate(const InputType & point) const override;
  InputType
  ClosestSurfacePoint(const InputType & point) const override;
  OutputType
  EvaluateWithClosestPoint(const InputType & point, InputType & closest) const override;
  void
  GetBounds(InputType & lower, InputType & upper) const override;

protected:
  BoxImplicitSurface();
  ~BoxImplicitSurface() override = default;
  void
  PrintSelf(std::ostream & os, Indent indent) const override;

private:
  InputType  m_Center;
  VectorType m_HalfSizes;
  MatrixType m_Rotation;
};
} // namespace itk

#endif
