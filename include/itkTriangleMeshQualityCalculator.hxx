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
#ifndef itkTriangleMeshQualityCalculator_hxx
#define itkTriangleMeshQualityCalculator_hxx

#include "itkTriangleMeshQualityCalculator.h"
#include "itkMeshExtractionIndexedTriangleMesh.h"
#include "itkMeshExtractionQualityAnalysis.h"

namespace itk
{
template <typename TMesh>
void
TriangleMeshQualityCalculator<TMesh>::Compute()
{
  if (m_Mesh.IsNull())
  {
    itkExceptionMacro("No mesh set: call SetMesh() before Compute().");
  }
  const MeshExtraction::IndexedTriangleMesh mesh = MeshExtraction::MakeIndexedTriangleMesh(*m_Mesh);
  MeshExtraction::IndexedTriangleMesh       reference;
  if (m_ReferenceMesh.IsNotNull())
  {
    reference = MeshExtraction::MakeIndexedTriangleMesh(*m_ReferenceMesh);
  }
  MeshExtraction::detail::TriangleMeshQualityOptions options;
  options.degenerateQAreaTolerance = m_DegenerateQAreaTolerance;
  options.computeSelfIntersections = m_ComputeSelfIntersections;
  options.computeOutwardOrientation = m_ComputeOutwardOrientation;
  m_Report = MeshExtraction::detail::AnalyzeTriangleMesh(
    mesh, options, m_ReferenceMesh.IsNotNull() ? &reference : nullptr, &m_TriangleMeasures, &m_VertexSmoothness);
  m_TriangleCellIdentifiers = mesh.cellIds;
}

template <typename TMesh>
void
TriangleMeshQualityCalculator<TMesh>::PrintSelf(std::ostream & os, Indent indent) const
{
  Superclass::PrintSelf(os, indent);
  os << indent << "Mesh: " << m_Mesh.GetPointer() << '\n';
  os << indent << "ReferenceMesh: " << m_ReferenceMesh.GetPointer() << '\n';
  os << indent << "DegenerateQAreaTolerance: " << m_DegenerateQAreaTolerance << '\n';
  os << indent << "ComputeSelfIntersections: " << m_ComputeSelfIntersections << '\n';
  os << indent << "ComputeOutwardOrientation: " << m_ComputeOutwardOrientation << '\n';
  os << indent << "Triangles measured: " << m_Report.numberOfTriangles << '\n';
}
} // namespace itk

#endif
