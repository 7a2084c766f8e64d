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
#ifndef itkSurfaceMeshFileReader_hxx
#define itkSurfaceMeshFileReader_hxx

#include "itkMeshExtractionMeshFile.h"

namespace itk
{
template <typename TOutputMesh>
void
SurfaceMeshFileReader<TOutputMesh>::GenerateData()
{
  if (m_FileName.empty())
  {
    itkExceptionMacro("no file name: call SetFileName before Update");
  }
  const MeshExtraction::PolygonMesh polygons = MeshExtraction::ReadPolygonMeshFile(m_FileName);
  OutputMeshType *                  output = this->GetOutput();
  output->Initialize();
  MeshExtraction::FillSurfaceMesh(polygons, *output, "'" + m_FileName + "'");
  m_NumberOfIgnoredCells = static_cast<SizeValueType>(polygons.numberOfIgnoredCells);
}

template <typename TOutputMesh>
void
SurfaceMeshFileReader<TOutputMesh>::PrintSelf(std::ostream & os, Indent indent) const
{
  Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << m_FileName << std::endl;
  os << indent << "NumberOfIgnoredCells: " << m_NumberOfIgnoredCells << std::endl;
}
} // namespace itk

#endif
