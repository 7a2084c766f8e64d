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
#ifndef itkLandmarkFreeShapeModelEstimator_hxx
#define itkLandmarkFreeShapeModelEstimator_hxx

#include "itkLandmarkFreeShapeModelEstimator.h"
#include "itkMeshExtractionShapeModelBuilder.h"

namespace itk
{
template <typename TMesh>
void
LandmarkFreeShapeModelEstimator<TMesh>::AddInputMesh(const MeshType * mesh)
{
  m_InputMeshes.push_back(mesh);
  this->Modified();
}

template <typename TMesh>
void
LandmarkFreeShapeModelEstimator<TMesh>::ClearInputMeshes()
{
  m_InputMeshes.clear();
  m_Result.reset();
  this->Modified();
}

template <typename TMesh>
void
LandmarkFreeShapeModelEstimator<TMesh>::Update()
{
  using namespace MeshExtraction::detail;
  std::vector<MeshExtraction::IndexedTriangleMesh> meshes;
  CheckNumberOfTrainingMeshes(m_InputMeshes.size());
  for (std::size_t i = 0; i < m_InputMeshes.size(); ++i)
  {
    const std::string name = TrainingMeshName(i);
    if (m_InputMeshes[i].IsNull())
    {
      itkExceptionMacro(<< name << " is missing (null).");
    }
    meshes.push_back(PrepareTrainingMesh(MeshExtraction::MakeIndexedTriangleMesh(*m_InputMeshes[i]), name));
  }
  const auto report = [this](double fraction) {
    m_Progress = static_cast<float>(fraction);
    this->InvokeEvent(ProgressEvent());
  };
  m_Result = std::make_shared<const ShapeModelBuildResult>(BuildShapeModel(meshes, this->MakeSettings(), report));
}

template <typename TMesh>
MeshExtraction::detail::ShapeModelSettings
LandmarkFreeShapeModelEstimator<TMesh>::MakeSettings() const
{
  MeshExtraction::detail::ShapeModelSettings settings;
  settings.correspondence = m_Correspondence;
  settings.nonRigid = m_NonRigidCorrespondence;
  settings.varianceFraction = m_VarianceFraction;
  settings.maximumNumberOfPasses = m_MaximumNumberOfPasses;
  return settings;
}

template <typename TMesh>
const MeshExtraction::detail::ShapeModelBuildResult &
LandmarkFreeShapeModelEstimator<TMesh>::Result() const
{
  if (!m_Result)
  {
    itkExceptionMacro("No model: call Update() first.");
  }
  return *m_Result;
}

template <typename TMesh>
unsigned int
LandmarkFreeShapeModelEstimator<TMesh>::GetNumberOfModes() const
{
  return static_cast<unsigned int>(this->Result().model.NumberOfModes());
}

template <typename TMesh>
const std::vector<double> &
LandmarkFreeShapeModelEstimator<TMesh>::GetVariances() const
{
  return this->Result().model.variances;
}

template <typename TMesh>
const std::vector<double> &
LandmarkFreeShapeModelEstimator<TMesh>::GetAllVariances() const
{
  return this->Result().allVariances;
}

template <typename TMesh>
double
LandmarkFreeShapeModelEstimator<TMesh>::GetTotalVariance() const
{
  return this->Result().model.totalVariance;
}

template <typename TMesh>
unsigned int
LandmarkFreeShapeModelEstimator<TMesh>::GetNumberOfPasses() const
{
  return static_cast<unsigned int>(this->Result().templateChanges.size());
}

template <typename TMesh>
unsigned int
LandmarkFreeShapeModelEstimator<TMesh>::GetPivotIndex() const
{
  return static_cast<unsigned int>(this->Result().pivot);
}

template <typename TMesh>
const std::vector<double> &
LandmarkFreeShapeModelEstimator<TMesh>::GetMeanSquaredDistancePerPass() const
{
  return this->Result().meanE2PerPass;
}

template <typename TMesh>
const std::vector<double> &
LandmarkFreeShapeModelEstimator<TMesh>::GetTemplateChangePerPass() const
{
  return this->Result().templateChanges;
}

template <typename TMesh>
auto
LandmarkFreeShapeModelEstimator<TMesh>::MakeModelMesh(const std::vector<double> & coordinates) const -> MeshPointer
{
  auto mesh = MeshType::New();
  MeshExtraction::FillMesh(MeshExtraction::detail::ModelMesh(this->Result(), coordinates), *mesh);
  return mesh;
}

template <typename TMesh>
auto
LandmarkFreeShapeModelEstimator<TMesh>::GetMeanMesh() const -> MeshPointer
{
  return this->MakeModelMesh(this->Result().model.mean);
}

template <typename TMesh>
auto
LandmarkFreeShapeModelEstimator<TMesh>::Synthesize(const CoefficientsType & standardDeviations) const -> MeshPointer
{
  return this->MakeModelMesh(
    MeshExtraction::detail::SynthesizeInStandardDeviations(this->Result().model, standardDeviations));
}

template <typename TMesh>
auto
LandmarkFreeShapeModelEstimator<TMesh>::Project(const MeshType * mesh) const -> CoefficientsType
{
  if (mesh == nullptr)
  {
    itkExceptionMacro("No mesh to project.");
  }
  return MeshExtraction::detail::ProjectInStandardDeviations(this->Result(),
                                                             MeshExtraction::MakeIndexedTriangleMesh(*mesh).points);
}

template <typename TMesh>
auto
LandmarkFreeShapeModelEstimator<TMesh>::MatchToModel(const MeshType * mesh) const -> MeshPointer
{
  using namespace MeshExtraction::detail;
  if (mesh == nullptr)
  {
    itkExceptionMacro("No mesh to match.");
  }
  const auto &                              result = this->Result();
  const MeshExtraction::IndexedTriangleMesh prepared =
    PrepareTrainingMesh(MeshExtraction::MakeIndexedTriangleMesh(*mesh), "the mesh to match");
  const TemplateMatch match =
    MatchTemplate(ModelMesh(result, result.model.mean), prepared, this->MakeSettings(), nullptr);
  std::vector<double> coordinates;
  coordinates.reserve(3 * match.corresponded.size());
  for (const auto & p : match.corresponded)
  {
    coordinates.insert(coordinates.end(), { p[0], p[1], p[2] });
  }
  return this->MakeModelMesh(coordinates);
}

template <typename TMesh>
auto
LandmarkFreeShapeModelEstimator<TMesh>::GetCorrespondedMesh(unsigned int i) const -> MeshPointer
{
  const auto & result = this->Result();
  if (i >= result.corresponded.size())
  {
    itkExceptionMacro("No training mesh " << i << ": the model has " << result.corresponded.size() << '.');
  }
  MeshExtraction::IndexedTriangleMesh indexed;
  indexed.points = result.corresponded[i];
  indexed.triangles = result.triangles;
  auto mesh = MeshType::New();
  MeshExtraction::FillMesh(indexed, *mesh);
  return mesh;
}

template <typename TMesh>
void
LandmarkFreeShapeModelEstimator<TMesh>::WriteModel(const std::string & fileName) const
{
  MeshExtraction::detail::WriteShapeModel(fileName, this->Result());
}

template <typename TMesh>
void
LandmarkFreeShapeModelEstimator<TMesh>::PrintSelf(std::ostream & os, Indent indent) const
{
  Superclass::PrintSelf(os, indent);
  os << indent << "NumberOfInputMeshes: " << m_InputMeshes.size() << '\n';
  os << indent << "Correspondence: " << m_Correspondence << '\n';
  os << indent << "NonRigidCorrespondence: " << m_NonRigidCorrespondence << '\n';
  os << indent << "VarianceFraction: " << m_VarianceFraction << '\n';
  os << indent << "MaximumNumberOfPasses: " << m_MaximumNumberOfPasses << '\n';
  os << indent << "Built: " << (m_Result ? "yes" : "no") << '\n';
}
} // namespace itk

#endif
