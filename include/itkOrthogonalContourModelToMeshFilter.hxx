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
#ifndef itkOrthogonalContourModelToMeshFilter_hxx
#define itkOrthogonalContourModelToMeshFilter_hxx

#include "itkMeshExtractionIndexedTriangleMesh.h"

#include <cmath>

namespace itk
{
template <typename TOutputMesh>
OrthogonalContourModelToMeshFilter<TOutputMesh>::OrthogonalContourModelToMeshFilter()
{
  this->SetNumberOfRequiredInputs(1);
}

template <typename TOutputMesh>
void
OrthogonalContourModelToMeshFilter<TOutputMesh>::SetInput(const ModelType * model)
{
  this->ProcessObject::SetNthInput(0, const_cast<ModelType *>(model));
}

template <typename TOutputMesh>
auto
OrthogonalContourModelToMeshFilter<TOutputMesh>::GetInput() const -> const ModelType *
{
  return dynamic_cast<const ModelType *>(this->ProcessObject::GetInput(0));
}

template <typename TOutputMesh>
void
OrthogonalContourModelToMeshFilter<TOutputMesh>::GenerateData()
{
  const ModelType * model = this->GetInput();
  if (model == nullptr)
  {
    itkExceptionMacro(<< "No input model: call SetInput() with an OrthogonalContourModel before Update()");
  }
  if (!(m_TargetEdgeLength >= 0.0) || !std::isfinite(m_TargetEdgeLength))
  {
    itkExceptionMacro(<< "TargetEdgeLength must be a finite length >= 0 mm, got " << m_TargetEdgeLength);
  }
  const std::string problem = model->CheckInvariants();
  if (!problem.empty())
  {
    itkExceptionMacro(<< "The input model is not valid: " << problem);
  }
  MeshExtraction::detail::ContourSurfaceParameters parameters;
  parameters.targetEdgeLength = m_TargetEdgeLength;
  const MeshExtraction::IndexedTriangleMesh surface =
    MeshExtraction::detail::BuildContourSurface(model->GetNetwork(), parameters);
  if (surface.triangles.empty())
  {
    itkExceptionMacro(<< "The model's faces do not make a valid closed surface (closed, 2-manifold, outward, "
                         "without degenerate or intersecting triangles)");
  }
  OutputMeshType * output = this->GetOutput();
  output->Initialize();
  MeshExtraction::FillMesh(surface, *output);
}

template <typename TOutputMesh>
void
OrthogonalContourModelToMeshFilter<TOutputMesh>::PrintSelf(std::ostream & os, Indent indent) const
{
  Superclass::PrintSelf(os, indent);
  os << indent << "TargetEdgeLength: " << m_TargetEdgeLength << '\n';
}
} // namespace itk

#endif
