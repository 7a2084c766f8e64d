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
#ifndef itkSurfaceMeshFileWriter_hxx
#define itkSurfaceMeshFileWriter_hxx

#include "itkMeshExtractionMeshFile.h"
#include "itkMeshExtractionWholeFile.h"

namespace itk
{
template <typename TInputMesh>
SurfaceMeshFileWriter<TInputMesh>::SurfaceMeshFileWriter()
{
  this->SetNumberOfRequiredInputs(1);
}

template <typename TInputMesh>
void
SurfaceMeshFileWriter<TInputMesh>::SetInput(const InputMeshType * mesh)
{
  this->ProcessObject::SetNthInput(0, const_cast<InputMeshType *>(mesh));
}

template <typename TInputMesh>
auto
SurfaceMeshFileWriter<TInputMesh>::GetInput() const -> const InputMeshType *
{
  return itkDynamicCastInDebugMode<const InputMeshType *>(this->GetPrimaryInput());
}

template <typename TInputMesh>
void
SurfaceMeshFileWriter<TInputMesh>::Write()
{
  const InputMeshType * input = this->GetInput();
  if (input == nullptr)
  {
    itkExceptionMacro("no input mesh: call SetInput before Write");
  }
  if (m_FileName.empty())
  {
    itkExceptionMacro("no file name: call SetFileName before Write");
  }
  const_cast<InputMeshType *>(input)->Update();
  this->InvokeEvent(StartEvent());
  this->GenerateData();
  this->InvokeEvent(EndEvent());
}

template <typename TInputMesh>
void
SurfaceMeshFileWriter<TInputMesh>::GenerateData()
{
  MeshExtraction::MeshFileWriteOptions options;
  switch (m_Encoding)
  {
    case MeshFileEncodingEnum::Default:
      options.encoding = MeshExtraction::MeshFileWriteOptions::Encoding::Default;
      break;
    case MeshFileEncodingEnum::ASCII:
      options.encoding = MeshExtraction::MeshFileWriteOptions::Encoding::ASCII;
      break;
    case MeshFileEncodingEnum::Binary:
      options.encoding = MeshExtraction::MeshFileWriteOptions::Encoding::Binary;
      break;
  }
  options.vtkLegacyVersion = m_VTKLegacyVersion == VTKLegacyVersionEnum::V5_1
                               ? MeshExtraction::MeshFileWriteOptions::VTKLegacyVersion::V5_1
                               : MeshExtraction::MeshFileWriteOptions::VTKLegacyVersion::V4_2;
  const MeshExtraction::PolygonMesh faces = MeshExtraction::MakePolygonMeshFromMesh(*this->GetInput());
  const MeshExtraction::MeshFileFormat format = MeshExtraction::MeshFileFormatFromFileName(m_FileName);
  if (format == MeshExtraction::MeshFileFormat::Unknown)
  {
    itkExceptionMacro("cannot write '" << m_FileName
                                       << "': its extension names no format the module writes (.vtk, .vtp, .ply, "
                                          ".stl, .obj, .off)");
  }
  MeshExtraction::WriteWhole(m_FileName, [&](const std::string & partial) {
    MeshExtraction::WritePolygonMeshFile(partial, faces, format, options);
  });
}

template <typename TInputMesh>
void
SurfaceMeshFileWriter<TInputMesh>::PrintSelf(std::ostream & os, Indent indent) const
{
  Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << m_FileName << std::endl;
  os << indent << "Encoding: " << m_Encoding << std::endl;
  os << indent << "VTKLegacyVersion: " << m_VTKLegacyVersion << std::endl;
}
} // namespace itk

#endif
