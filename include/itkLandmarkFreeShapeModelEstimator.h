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
#ifndef itkLandmarkFreeShapeModelEstimator_h
#define itkLandmarkFreeShapeModelEstimator_h

#include "itkEventObject.h"
#include "itkMeshExtractionEnums.h"
#include "itkMeshExtractionMacros.h"
#include "itkObject.h"
#include "itkObjectFactory.h"

#include <memory>
#include <string>
#include <vector>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
struct ShapeModelBuildResult;
struct ShapeModelSettings;
} // namespace detail
} // namespace MeshExtraction

/** \class LandmarkFreeShapeModelEstimator
 * \brief A statistical shape model (mean and principal modes) of closed triangle meshes
 * without landmarks, after P.W. de Bruin's thesis (chapter 7), with a non-rigid
 * correspondence stage.
 *
 * The training meshes may have different vertex counts, topologies and poses. The mesh
 * with most vertices is the pivot: its topology becomes the model's. Each template pass
 * matches the template to every mesh by the symmetric similarity ICP (thesis 7.2.1,
 * SymmetricSimilarityICPRegistration), then corresponds it: by default an
 * as-rigid-as-possible regularised, symmetric non-rigid ICP deforms the template onto
 * the mesh (annealed from stiff to loose); without it (NonRigidCorrespondenceOff) the
 * template's vertices go to their closest points, as in the thesis. The template then
 * becomes the mean of the corresponded meshes, similarity-aligned to the previous
 * template. After the passes a generalised Procrustes analysis (similarity, scale
 * removed) aligns the corresponded meshes, and principal component analysis by a thin
 * SVD of the centred data (variance 1/(m - 1)) keeps the modes that explain
 * VarianceFraction of the total variance.
 *
 * Each training mesh is reduced to its largest connected component and turned outward
 * if it faced inward. Errors (itk::ExceptionObject, naming the mesh by its index): fewer
 * than two meshes, a missing or empty mesh, a coordinate that is not finite, a largest
 * component that is open, not manifold or inconsistently oriented.
 *
 * The model is written in statismo's HDF5 layout (WriteModel) with a mesh representer.
 * \ingroup MeshExtraction
 */
template <typename TMesh>
class ITK_TEMPLATE_EXPORT LandmarkFreeShapeModelEstimator : public Object
{
public:
  ITK_DISALLOW_COPY_AND_MOVE(LandmarkFreeShapeModelEstimator);

  using Self = LandmarkFreeShapeModelEstimator;
  using Superclass = Object;
  using Pointer = SmartPointer<Self>;
  using ConstPointer = SmartPointer<const Self>;

  itkNewMacro(Self);
  itkOverrideGetNameOfClassMacro(LandmarkFreeShapeModelEstimator);

  using MeshType = TMesh;
  using MeshPointer = typename MeshType::Pointer;
  using MeshConstPointer = typename MeshType::ConstPointer;
  using CorrespondenceEnum = MeshExtractionEnums::Correspondence;
  using CoefficientsType = std::vector<double>;

  /** The training meshes, in order (their index names them in errors and results). */
  void
  AddInputMesh(const MeshType * mesh);
  void
  ClearInputMeshes();
  unsigned int
  GetNumberOfInputMeshes() const
  {
    return static_cast<unsigned int>(m_InputMeshes.size());
  }

  /** Of the similarity ICP and, without the non-rigid stage, of the closest points.
   * Default PointToSurface. */
  itkSetEnumMacro(Correspondence, CorrespondenceEnum);
  itkGetEnumMacro(Correspondence, CorrespondenceEnum);
  /** The non-rigid correspondence stage; default on. */
  itkSetMacro(NonRigidCorrespondence, bool);
  itkGetConstMacro(NonRigidCorrespondence, bool);
  itkBooleanMacro(NonRigidCorrespondence);
  /** The fraction of the total variance the kept modes explain (default 0.95; 1: all). */
  itkSetClampMacro(VarianceFraction, double, 1e-6, 1.0);
  itkGetConstMacro(VarianceFraction, double);
  /** At most this many template passes (default 2). */
  itkSetClampMacro(MaximumNumberOfPasses, unsigned int, 1, 100);
  itkGetConstMacro(MaximumNumberOfPasses, unsigned int);

  /** Builds the model; ProgressEvent is invoked as it goes (GetProgress). */
  void
  Update();
  itkGetConstMacro(Progress, float);

  /** After Update(): the model's modes, their variances (descending) and the total
   * variance of all m - 1 modes. */
  unsigned int
  GetNumberOfModes() const;
  const std::vector<double> &
  GetVariances() const;
  /** The variances of all m - 1 modes, kept or not (the compactness curve). */
  const std::vector<double> &
  GetAllVariances() const;
  double
  GetTotalVariance() const;
  /** The template passes run and the index of the pivot mesh. */
  unsigned int
  GetNumberOfPasses() const;
  unsigned int
  GetPivotIndex() const;
  /** Per template pass, the mean over the meshes of eq. 7.3 (E^2, mm^2) of the similarity
   * ICP, and the RMS move of the template (mm). */
  const std::vector<double> &
  GetMeanSquaredDistancePerPass() const;
  const std::vector<double> &
  GetTemplateChangePerPass() const;

  /** The mean mesh, in the model's (Procrustes) frame, on the model's topology. */
  MeshPointer
  GetMeanMesh() const;
  /** mean + sum_i b_i sqrt(lambda_i) u_i: the coefficients in standard deviations (fewer
   * than the modes: the others are 0). */
  MeshPointer
  Synthesize(const CoefficientsType & standardDeviations) const;
  /** The coefficients, in standard deviations, of a mesh on the model's topology (e.g.
   * GetCorrespondedMesh) after its similarity alignment to the mean. */
  CoefficientsType
  Project(const MeshType * mesh) const;
  /** A closed mesh of any topology (a new subject) on the model's topology: the model's
   * mean matched to it as the build matches its meshes (similarity ICP and the
   * correspondence), in the mesh's frame. Project() of the result gives its
   * coefficients. Throws for an empty, open, non-manifold or non-finite mesh. */
  MeshPointer
  MatchToModel(const MeshType * mesh) const;
  /** Training mesh i on the model's topology, in its own frame. */
  MeshPointer
  GetCorrespondedMesh(unsigned int i) const;

  /** Writes the model in statismo's HDF5 layout (version 0.9, itkStandardMeshRepresenter). */
  void
  WriteModel(const std::string & fileName) const;

protected:
  LandmarkFreeShapeModelEstimator() = default;
  ~LandmarkFreeShapeModelEstimator() override = default;
  void
  PrintSelf(std::ostream & os, Indent indent) const override;

private:
  MeshPointer
  MakeModelMesh(const std::vector<double> & coordinates) const;
  /** The builder's settings from this object's. */
  MeshExtraction::detail::ShapeModelSettings
  MakeSettings() const;
  const MeshExtraction::detail::ShapeModelBuildResult &
  Result() const;

  std::vector<MeshConstPointer> m_InputMeshes;
  CorrespondenceEnum            m_Correspondence{ CorrespondenceEnum::PointToSurface };
  bool                          m_NonRigidCorrespondence{ true };
  double                        m_VarianceFraction{ 0.95 };
  unsigned int                  m_MaximumNumberOfPasses{ 2 };
  float                         m_Progress{ 0.0f };
  std::shared_ptr<const MeshExtraction::detail::ShapeModelBuildResult> m_Result;
};
} // namespace itk

#ifndef ITK_MANUAL_INSTANTIATION
#  include "itkLandmarkFreeShapeModelEstimator.hxx"
#endif

#endif
