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
#ifndef itkEllipsoidImplicitSurface_h
#define itkEllipsoidImplicitSurface_h

#include "itkImplicitSurfaceFunction.h"
#include "MeshExtractionExport.h"

namespace itk
{
/** \class EllipsoidImplicitSurface
 * \brief An ellipsoid with semi-axes SemiAxes along the columns of Rotation,
 * centred at Center.
 *
 * A point x is on the surface when q = Rotation^T (x - Center) satisfies
 * sum_i (q_i / SemiAxes_i)^2 = 1. The distance is exact: the closest point is the
 * root of Eberly's monotone secular function, found by bisection to machine
 * precision (D. Eberly, "Distance from a Point to an Ellipse, an Ellipsoid, or a
 * Hyperellipsoid", Geometric Tools, 2013), with the special cases of points on the
 * principal planes, on the axes and at the centre handled explicitly.
 *
 * Defaults: Center (0,0,0), SemiAxes (1,1,1), Rotation identity.
 * \ingroup MeshExtraction
 */
class MeshExtraction_EXPORT EllipsoidImplicitSurface : public ImplicitSurfaceFunction
{
public:
  ITK_DISALLOW_COPY_AND_MOVE(EllipsoidImplicitSurface);
  using Self = EllipsoidImplicitSurface;
  using Superclass = ImplicitSurfaceFunction;
  using Pointer = SmartPointer<Self>;
  using ConstPointer = SmartPointer<const Self>;
  itkOverrideGetNameOfClassMacro(EllipsoidImplicitSurface);
  itkNewMacro(Self);

  void
  SetCenter(const InputType & center);
  itkGetConstReferenceMacro(Center, InputType);
  /** The three semi-axis lengths, each > 0, in any order. */
  void
  SetSemiAxes(const VectorType & semiAxes);
  itkGetConstReferenceMacro(SemiAxes, VectorType);
  /** Orthogonal matrix whose column i is the direction of semi-axis i (local to
   * physical). Checked orthogonal within 1e-6 and re-orthonormalised. */
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
  EllipsoidImplicitSurface();
  ~EllipsoidImplicitSurface() override = default;
  void
  PrintSelf(std::ostream & os, Indent indent) const override;

private:
  InputType  m_Center;
  VectorType m_SemiAxes;
  MatrixType m_Rotation;
};
} // namespace itk

#endif
