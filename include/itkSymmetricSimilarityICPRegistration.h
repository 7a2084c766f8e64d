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
#ifndef itkSymmetricSimilarityICPRegistration_h
#define itkSymmetricSimilarityICPRegistration_h

#include "itkMeshExtractionEnums.h"
#include "itkMeshExtractionMacros.h"
#include "itkObject.h"
#include "itkObjectFactory.h"
#include "itkSimilarity3DTransform.h"

namespace itk
{
/** \class SymmetricSimilarityICPRegistration
 * \brief Matches two triangle meshes by a similarity transform with the symmetric
 * iterative closest point method of P.W. de Bruin's thesis (section 7.2.1).
 *
 * The meshes may have different vertex counts and topologies. Each iteration finds
 * the closest points of A (the fixed mesh) on B (the moving mesh) and of B on A, then
 * the similarity Q(p) = sRp + t that minimises eq. 7.3,
 *   E^2 = 1/n_A sum |Q(a_i) - Q^-1(b'_i)|^2 + 1/n_B sum |Q(a'_j) - Q^-1(b_j)|^2,
 * both shapes moved into an intermediate frame so that neither is preferred; the
 * fixed-to-moving transform is Q o Q. The minimisation is ITK's
 * PointSetToPointSetRegistrationMethod with LevenbergMarquardtOptimizer and
 * SymmetricPairedPointSetMetric (exact Jacobian), started from half of the least-squares
 * similarity of the pairs. Correspondence is point-to-point (the nearest vertex) or
 * point-to-surface (the nearest point on the triangles; the default, thesis 7.3.1).
 * The start aligns the centroids, the principal axes (the four right-handed sign
 * choices; the one of least E^2 is kept) and the mean distance to the centre, unless
 * an initial transform is given. The iterations stop when E^2 improves by less than
 * RelativeTolerance (or stops improving).
 *
 * The transforms are itk::Similarity3DTransform centred at A's centroid (meshes may lie
 * far from the origin), mapping fixed (A) points to moving (B) points as ITK's
 * registration does.
 *
 * Errors (itk::ExceptionObject): a missing mesh, a mesh without triangles, a
 * coordinate that is not finite.
 * \ingroup MeshExtraction
 */
template <typename TMesh>
class ITK_TEMPLATE_EXPORT SymmetricSimilarityICPRegistration : public Object
{
public:
  ITK_DISALLOW_COPY_AND_MOVE(SymmetricSimilarityICPRegistration);

  using Self = SymmetricSimilarityICPRegistration;
  using Superclass = Object;
  using Pointer = SmartPointer<Self>;
  using ConstPointer = SmartPointer<const Self>;

  itkNewMacro(Self);
  itkOverrideGetNameOfClassMacro(SymmetricSimilarityICPRegistration);

  using MeshType = TMesh;
  using TransformType = Similarity3DTransform<double>;
  using CorrespondenceEnum = MeshExtractionEnums::Correspondence;

  itkSetConstObjectMacro(FixedMesh, MeshType);
  itkGetConstObjectMacro(FixedMesh, MeshType);
  itkSetConstObjectMacro(MovingMesh, MeshType);
  itkGetConstObjectMacro(MovingMesh, MeshType);

  /** Default PointToSurface. */
  itkSetEnumMacro(Correspondence, CorrespondenceEnum);
  itkGetEnumMacro(Correspondence, CorrespondenceEnum);
  /** Default 100. */
  itkSetMacro(MaximumNumberOfIterations, unsigned int);
  itkGetConstMacro(MaximumNumberOfIterations, unsigned int);
  /** The iterations stop when E^2 improves by less than this fraction (default 1e-6). */
  itkSetMacro(RelativeTolerance, double);
  itkGetConstMacro(RelativeTolerance, double);
  /** A start (fixed to moving) instead of the principal axes; null: none (default). */
  itkSetConstObjectMacro(InitialTransform, TransformType);
  itkGetConstObjectMacro(InitialTransform, TransformType);

  /** Runs the registration. */
  void
  Update();

  /** After Update(): Q o Q (fixed to moving), Q, E^2 before and after, the mean
   * closest-point distance in both directions (moving frame, mm), the iterations. */
  itkGetModifiableObjectMacro(Transform, TransformType);
  itkGetModifiableObjectMacro(HalfTransform, TransformType);
  itkGetConstMacro(InitialMeanSquaredDistance, double);
  itkGetConstMacro(MeanSquaredDistance, double);
  itkGetConstMacro(MeanDistance, double);
  itkGetConstMacro(NumberOfIterations, unsigned int);

protected:
  SymmetricSimilarityICPRegistration() = default;
  ~SymmetricSimilarityICPRegistration() override = default;
  void
  PrintSelf(std::ostream & os, Indent indent) const override;

private:
  typename MeshType::ConstPointer m_FixedMesh;
  typename MeshType::ConstPointer m_MovingMesh;
  TransformType::ConstPointer     m_InitialTransform;
  CorrespondenceEnum              m_Correspondence{ CorrespondenceEnum::PointToSurface };
  unsigned int                    m_MaximumNumberOfIterations{ 100 };
  double                          m_RelativeTolerance{ 1e-6 };
  TransformType::Pointer          m_Transform;
  TransformType::Pointer          m_HalfTransform;
  double                          m_InitialMeanSquaredDistance{ 0.0 };
  double                          m_MeanSquaredDistance{ 0.0 };
  double                          m_MeanDistance{ 0.0 };
  unsigned int                    m_NumberOfIterations{ 0 };
};
} // namespace itk

#ifndef ITK_MANUAL_INSTANTIATION
#  include "itkSymmetricSimilarityICPRegistration.hxx"
#endif

#endif
