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
#ifndef itkThreeLandmarkIncrementalTransformInitializer_h
#define itkThreeLandmarkIncrementalTransformInitializer_h

#include "itkFixedArray.h"
#include "itkMatrix.h"
#include "itkMeshExtractionEnums.h"
#include "itkMeshExtractionMacros.h"
#include "itkObject.h"
#include "itkObjectFactory.h"
#include "itkPoint.h"
#include "itkTransform.h"
#include "itkVersorRigid3DTransform.h"

#include <vector>

namespace itk
{
/** \class ThreeLandmarkIncrementalTransformInitializer
 * \brief Matches three landmarks placed with unequal certainty, incrementally
 * (P.W. de Bruin's thesis, section 6.2.4), instead of by least squares.
 *
 * The landmarks are A (the most certain), B and C (the least certain), given in the
 * fixed and in the moving space. The transform is built in three steps, each of which
 * leaves the previous steps' matches as they are:
 * 1. A is matched by a translation;
 * 2. B by the rotation about A (the shortest arc) that turns the direction AB onto
 *    its counterpart;
 * 3. C by the rotation about the axis AB that turns C's perpendicular from the axis
 *    onto its counterpart's.
 * So the error of an uncertain landmark is never spread over the certain ones, as a
 * least-squares fit (itk::LandmarkBasedTransformInitializer) spreads it.
 *
 * Direction: the transform maps points of the FIXED space to the MOVING space, as
 * every ITK registration transform does and as ResampleImageFilter uses it (give it
 * the moving image as input and the fixed image's grid as output to see the moving
 * image in the fixed frame), and as LandmarkBasedTransformInitializer computes it.
 * It holds exactly (to rounding):
 * - T(A_fixed) = A_moving;
 * - T(B_fixed) lies on the ray from A_moving through B_moving (on B_moving with a
 *   distension);
 * - T(C_fixed) lies in the half-plane bounded by the line A_moving B_moving that holds
 *   C_moving.
 * The thesis writes the match the other way round, moving onto fixed,
 * T'(p) = A_f + R2 R1 (p - A_m). T' is this transform's inverse
 * (GetInverseTransform()): the rigid incremental match is unique, and built with the
 * roles swapped it is the inverse.
 *
 * Distension (thesis 6.2.2, optional, LandmarkDistension): Isotropic scales by
 * |A_m B_m| / |A_f B_f| about A, so that B lands on its counterpart (needs a
 * Similarity3DTransform or an AffineTransform); AlongAxes scales along AB by that
 * factor and along the perpendicular from AB through C by the ratio of C's distances
 * to the axis, leaving the direction across the plane ABC unscaled (needs an
 * AffineTransform).
 *
 * The transform's centre is A_fixed. TTransform: itk::VersorRigid3DTransform (the
 * default), Similarity3DTransform, Euler3DTransform, AffineTransform<double, 3>, any
 * MatrixOffsetTransformBase in 3-D whose SetMatrix accepts the result, or the base
 * itk::Transform<double, 3, 3> holding one of them (checked at run time).
 *
 * Errors (itk::ExceptionObject, naming the problem): no transform; not exactly three
 * landmarks in either space; a coordinate that is NaN or infinite; A and B at the same
 * place (no axis); C on the line AB (no plane); a distension the transform cannot
 * represent.
 *
 * \ingroup MeshExtraction
 */
template <typename TTransform = VersorRigid3DTransform<double>>
class ITK_TEMPLATE_EXPORT ThreeLandmarkIncrementalTransformInitializer : public Object
{
public:
  ITK_DISALLOW_COPY_AND_MOVE(ThreeLandmarkIncrementalTransformInitializer);

  using Self = ThreeLandmarkIncrementalTransformInitializer;
  using Superclass = Object;
  using Pointer = SmartPointer<Self>;
  using ConstPointer = SmartPointer<const Self>;

  itkNewMacro(Self);
  itkOverrideGetNameOfClassMacro(ThreeLandmarkIncrementalTransformInitializer);

  using TransformType = TTransform;
  using TransformPointer = typename TransformType::Pointer;
  static_assert(TransformType::InputSpaceDimension == 3 && TransformType::OutputSpaceDimension == 3,
                "ThreeLandmarkIncrementalTransformInitializer matches landmarks in 3-D.");
  /** What the transform is reached through: the kind of transform is checked at run
   * time, so TTransform may be a base class (itk::Transform<double, 3, 3>, as the
   * Python wrapping has it) holding any of the transforms listed above. */
  using TransformBase = Transform<typename TransformType::ScalarType, 3, 3>;

  using LandmarkPointType = Point<double, 3>;
  /** A, B, C in this order (as itk::LandmarkBasedTransformInitializer's container). */
  using LandmarkPointContainer = std::vector<LandmarkPointType>;
  using MatrixType = Matrix<double, 3, 3>;
  using VectorType = Vector<double, 3>;
  using DistensionEnum = MeshExtractionEnums::LandmarkDistension;

  /** The transform to set (its type's parameters are overwritten). */
  itkSetObjectMacro(Transform, TransformType);
  itkGetModifiableObjectMacro(Transform, TransformType);

  /** The landmarks A, B, C in the fixed space (the space the transform maps from). */
  void
  SetFixedLandmarks(const LandmarkPointContainer & landmarks)
  {
    m_FixedLandmarks = landmarks;
    this->Modified();
  }
  const LandmarkPointContainer &
  GetFixedLandmarks() const
  {
    return m_FixedLandmarks;
  }
  /** The landmarks A, B, C in the moving space (the space the transform maps to). */
  void
  SetMovingLandmarks(const LandmarkPointContainer & landmarks)
  {
    m_MovingLandmarks = landmarks;
    this->Modified();
  }
  const LandmarkPointContainer &
  GetMovingLandmarks() const
  {
    return m_MovingLandmarks;
  }

  /** Scaling added to the rigid match (default None). */
  itkSetEnumMacro(Distension, DistensionEnum);
  itkGetEnumMacro(Distension, DistensionEnum);

  /** A and B closer than this fraction of the landmarks' extent count as one point,
   * and C closer to the line AB than this fraction as on it (default 1e-6). */
  itkSetMacro(DegeneracyTolerance, double);
  itkGetConstMacro(DegeneracyTolerance, double);

  /** Computes the transform and sets it. */
  virtual void
  InitializeTransform();

  /** After InitializeTransform(): the rotation (fixed to moving directions), the
   * scale factors along AB, along the perpendicular through C and across the plane
   * (1 without distension), and |T(X_fixed) - X_moving| for A, B and C. */
  itkGetConstReferenceMacro(Rotation, MatrixType);
  const FixedArray<double, 3> &
  GetScales() const
  {
    return m_Scales;
  }
  const FixedArray<double, 3> &
  GetLandmarkResiduals() const
  {
    return m_LandmarkResiduals;
  }

protected:
  ThreeLandmarkIncrementalTransformInitializer() = default;
  ~ThreeLandmarkIncrementalTransformInitializer() override = default;
  void
  PrintSelf(std::ostream & os, Indent indent) const override;

private:
  /** Throws unless both containers hold three finite points in a usable configuration. */
  void
  VerifyLandmarks() const;
  void
  VerifyConfiguration(const LandmarkPointContainer & landmarks, const char * space) const;
  /** The scales (along AB, the perpendicular through C, across) and their frame. */
  void
  ComputeDistension(const VectorType & axisFixed, MatrixType & scaling);
  /** Writes centre A_fixed, the linear part and the translation into the transform. */
  void
  SetTransformParameters(const MatrixType & linear);

  TransformPointer       m_Transform;
  LandmarkPointContainer m_FixedLandmarks;
  LandmarkPointContainer m_MovingLandmarks;
  DistensionEnum         m_Distension{ DistensionEnum::None };
  double                 m_DegeneracyTolerance{ 1e-6 };
  MatrixType             m_Rotation;
  FixedArray<double, 3>  m_Scales{ 1.0 };
  FixedArray<double, 3>  m_LandmarkResiduals{ 0.0 };
};
} // namespace itk

#ifndef ITK_MANUAL_INSTANTIATION
#  include "itkThreeLandmarkIncrementalTransformInitializer.hxx"
#endif

#endif
