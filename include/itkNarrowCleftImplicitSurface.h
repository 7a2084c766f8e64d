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
#ifndef itkNarrowCleftImplicitSurface_h
#define itkNarrowCleftImplicitSurface_h

#include "itkImplicitSurfaceFunction.h"
#include "MeshExtractionExport.h"

#include <vector>
#include <string>

namespace itk
{
/** \class NarrowCleftImplicitSurface
 * \brief A U-shaped block: a box with a slot cut from its top face.
 *
 * In the block's frame (origin Center, axes the columns of Rotation) the block is
 * |x| <= HalfSizes[0], |y| <= HalfSizes[1], |z| <= HalfSizes[2], and the slot
 * removes |x| < SlotWidth/2, z > HalfSizes[2] - SlotDepth through the whole y
 * extent. The boundary is tiled exactly by 14 axis-aligned rectangles (bottom, two
 * top strips, two outer x faces, two slot walls, the slot floor, and the U-shaped
 * front and back faces as three rectangles each); the distance is the minimum over
 * them and the sign comes from the inside test.
 * Requires SlotWidth < 2 HalfSizes[0] and SlotDepth < 2 HalfSizes[2].
 * Defaults: Center (0,0,0), HalfSizes (10,10,10), SlotWidth 1.5, SlotDepth 10,
 * Rotation identity.
 * \ingroup MeshExtraction
 */
class MeshExtraction_EXPORT NarrowCleftImplicitSurface : public ImplicitSurfaceFunction
{
public:
  ITK_DISALLOW_COPY_AND_MOVE(NarrowCleftImplicitSurface);
  using Self = NarrowCleftImplicitSurface;
  using Superclass = ImplicitSurfaceFunction;
  using Pointer = SmartPointer<Self>;
  using ConstPointer = SmartPointer<const Self>;
  itkOverrideGetNameOfClassMacro(NarrowCleftImplicitSurface);
  itkNewMacro(Self);

  void
  SetCenter(const InputType & center);
  itkGetConstReferenceMacro(Center, InputType);
  /** Half the block's edge lengths, each > 0. */
  void
  SetHalfSizes(const VectorType & halfSizes);
  itkGetConstReferenceMacro(HalfSizes, VectorType);
  /** Width of the slot along the block's x axis, > 0. */
  void
  SetSlotWidth(double width);
  itkGetConstMacro(SlotWidth, double);
  /** Depth of the slot below the top face (along -z), > 0. */
  void
  SetSlotDepth(double depth);
  itkGetConstMacro(SlotDepth, double);
  /** Orthogonal matrix whose column i is the direction of the block's axis i. */
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
  NarrowCleftImplicitSurface();
  ~NarrowCleftImplicitSurface() override = default;
  void
  PrintSelf(std::ostream & os, Indent indent) const override;
  std::string
  CheckParameterConsistency() const override;

private:
  /** A closed rectangle corner + s * edge0 + t * edge1, s, t in [0,1], in the
   * block's frame; edge0 and edge1 are orthogonal. */
  struct Rectangle
  {
    VectorType corner;
    VectorType edge0;
    VectorType edge1;
  };
  void
  UpdateRectangles();

  InputType              m_Center;
  VectorType             m_HalfSizes;
  double                 m_SlotWidth{ 1.5 };
  double                 m_SlotDepth{ 10.0 };
  MatrixType             m_Rotation;
  std::vector<Rectangle> m_Rectangles;
};
} // namespace itk

#endif
