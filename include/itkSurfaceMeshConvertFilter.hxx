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
#ifndef itkSurfaceMeshConvertFilter_hxx
#define itkSurfaceMeshConvertFilter_hxx

#include "itkMeshExtractionMeshFile.h"

namespace itk
{
template <typename TInputMesh, typename TOutputMesh>
SurfaceMeshConvertFilter<TInputMesh, TOutputMesh>::SurfaceMeshConvertFilter()
{
  this->SetNumberOfRequiredInputs(1);
}

template <typename TInputMesh, typename TOutputMesh>
void
SurfaceMeshConvertFilter<TInputMesh, TOutputMesh>::SetInput(const InputMeshType * mesh)
{
  this->ProcessObject::SetNthInput(0, const_cast<InputMeshType *>(mesh));
}

template <typename TInputMesh, typename TOutputMesh>
auto
SurfaceMeshConvertFilter<TInputMesh, TOutputMesh>::GetInput() const -> const InputMeshType *
{
  return dynamic_cast<const InputMeshType *>(this->ProcessObject::GetInput(0));
}

template <typename TInputMesh, typename TOutputMesh>
void
SurfaceMeshConvertFilter<TInputMesh, TOutputMesh>::GenerateData()
{
  const InputMeshType * input = this->GetInput();
  if (input == nullptr)
  {
    itkExceptionMacro("no input mesh: call SetInput before Update");
  }
  const MeshExtraction::PolygonMesh faces = MeshExtraction::MakePolygonMeshFromMesh(*input);
  OutputMeshType *                  output = this->GetOutput();
  output->Initialize();
  MeshExtraction::FillSurfaceMesh(faces, *output, "the input mesh");
}
} // namespace itk

#endif
