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
#ifndef itkMeshSurfaceDistanceCalculator_hxx
#define itkMeshSurfaceDistanceCalculator_hxx

#include "itkMeshSurfaceDistanceCalculator.h"
#include "itkMeshExtractionDistanceAnalysis.h"
#include "itkMeshExtractionIndexedTriangleMesh.h"

namespace itk
{
template <typename TMesh, typename TReferenceMesh>
void
MeshSurfaceDistanceCalculator<TMesh, TReferenceMesh>::SetReferenceMesh(const ReferenceMeshType * reference)
{
  if (m_ReferenceMesh != reference || m_ReferenceSurface.IsNotNull())
  {
    m_ReferenceMesh = reference;
    m_ReferenceSurface = nullptr;
    this->Modified();
  }
}

template <typename TMesh, typename TReferenceMesh>
void
MeshSurfaceDistanceCalculator<TMesh, TReferenceMesh>::SetReferenceSurface(const ImplicitSurfaceFunction * surface)
{
  if (m_ReferenceSurface != surface || m_ReferenceMesh.IsNotNull())
  {
    m_ReferenceSurface = surface;
    m_ReferenceMesh = nullptr;
    this->Modified();
  }
}

template <typename TMesh, typename TReferenceMesh>
void
MeshSurfaceDistanceCalculator<TMesh, TReferenceMesh>::Compute()
{
  if (m_Mesh.IsNull())
  {
    itkExceptionMacro("No mesh set: call SetMesh() before Compute().");
  }
  if (m_ReferenceMesh.IsNull() && m_ReferenceSurface.IsNull())
  {
    itkExceptionMacro("No reference: call SetReferenceMesh() or SetReferenceSurface() before Compute().");
  }
  const MeshExtraction::IndexedTriangleMesh mesh = MeshExtraction::MakeIndexedTriangleMesh(*m_Mesh);
  MeshExtraction::IndexedTriangleMesh       reference;
  if (m_ReferenceMesh.IsNotNull())
  {
    reference = MeshExtraction::MakeIndexedTriangleMesh(*m_ReferenceMesh);
  }
  MeshExtraction::detail::SurfaceDistanceOptions options;
  options.samplingLevel = m_SamplingLevel;
  options.symmetric = m_Symmetric;
  options.implicitSampleSpacing = m_ImplicitSampleSpacing;
  options.numberOfWorkUnits = m_NumberOfWorkUnits;
  m_Report = MeshExtraction::detail::ComputeSurfaceDistances(mesh,
                                                             m_ReferenceMesh.IsNotNull() ? &reference : nullptr,
                                                             m_ReferenceSurface.GetPointer(),
                                                             options,
                                                             &m_VertexDistances,
                                                             &m_FaceCentroidDistances);
}

template <typename TMesh, typename TReferenceMesh>
void
MeshSurfaceDistanceCalculator<TMesh, TReferenceMesh>::PrintSelf(std::ostream & os, Indent indent) const
{
  Superclass::PrintSelf(os, indent);
  os << indent << "Mesh: " << m_Mesh.GetPointer() << '\n';
  os << indent << "ReferenceMesh: " << m_ReferenceMesh.GetPointer() << '\n';
  os << indent << "ReferenceSurface: " << m_ReferenceSurface.GetPointer() << '\n';
  os << indent << "SamplingLevel: " << m_SamplingLevel << '\n';
  os << indent << "Symmetric: " << m_Symmetric << '\n';
  os << indent << "ImplicitSampleSpacing: " << m_ImplicitSampleSpacing << '\n';
  os << indent << "NumberOfWorkUnits: " << m_NumberOfWorkUnits << '\n';
}
} // namespace itk

#endif
