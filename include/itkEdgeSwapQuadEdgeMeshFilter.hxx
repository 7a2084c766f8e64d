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
#ifndef itkEdgeSwapQuadEdgeMeshFilter_hxx
#define itkEdgeSwapQuadEdgeMeshFilter_hxx

#include "itkEdgeSwapQuadEdgeMeshFilter.h"
#include "itkMeshExtractionEdgeSwapPasses.h"
#include "itkMeshExtractionIndexedTriangleMesh.h"
#include "itkMeshExtractionParallel.h"
#include "itkMeshExtractionQualityAnalysis.h"
#include "itkMeshExtractionQuadEdgeMeshVertexSmoother.h"
#include "itkMeshExtractionValidityGuard.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace itk
{
template <typename TInputMesh, typename TOutputMesh>
void
EdgeSwapQuadEdgeMeshFilter<TInputMesh, TOutputMesh>::VerifyParameters() const
{
  if (m_MaximumNumberOfIterations < 0)
  {
    itkExceptionMacro(<< "MaximumNumberOfIterations must be >= 0, got " << m_MaximumNumberOfIterations);
  }
  if (!(m_FeatureAngle > 0.0 && m_FeatureAngle <= 180.0))
  {
    itkExceptionMacro(<< "FeatureAngle must be in (0, 180] degrees, got " << m_FeatureAngle);
  }
  if (!(m_DegenerateQAreaTolerance >= 0.0 && m_DegenerateQAreaTolerance < 1.0))
  {
    itkExceptionMacro(<< "DegenerateQAreaTolerance must be in [0, 1), got " << m_DegenerateQAreaTolerance);
  }
  if (!(m_MinimumQAreaRatio >= 0.0) || !std::isfinite(m_MinimumQAreaRatio))
  {
    itkExceptionMacro(<< "MinimumQAreaRatio must be a finite number >= 0, got " << m_MinimumQAreaRatio);
  }
  if (m_Criterion != EdgeSwapCriterionEnum::Regularity && m_Criterion != EdgeSwapCriterionEnum::Delaunay &&
      m_Criterion != EdgeSwapCriterionEnum::ShortestEdge)
  {
    itkExceptionMacro(<< "Unknown Criterion " << static_cast<int>(m_Criterion));
  }
}

template <typename TInputMesh, typename TOutputMesh>
MeshExtraction::detail::EdgeSwapParameters
EdgeSwapQuadEdgeMeshFilter<TInputMesh, TOutputMesh>::MakeSwapParameters() const
{
  MeshExtraction::detail::EdgeSwapParameters parameters;
  parameters.criterion = m_Criterion;
  parameters.minimumValence = 3;
  parameters.featureAngle = m_FeatureAngle * itk::Math::pi / 180.0;
  parameters.degenerateQAreaTolerance = m_DegenerateQAreaTolerance;
  parameters.minimumQAreaRatio = m_MinimumQAreaRatio;
  return parameters;
}

template <typename TInputMesh, typename TOutputMesh>
std::vector<std::uint8_t>
EdgeSwapQuadEdgeMeshFilter<TInputMesh, TOutputMesh>::LockFlags(const MeshExtraction::IndexedTriangleMesh & mesh) const
{
  std::vector<std::uint8_t> locked;
  if (m_LockedPoints.empty() && m_CrossingLockedPoints.empty())
  {
    return locked;
  }
  locked.assign(mesh.points.size(), 0);
  for (std::size_t i = 0; i < mesh.points.size(); ++i)
  {
    const auto id = static_cast<OutputPointIdentifier>(mesh.pointIds[i]);
    locked[i] = std::binary_search(m_LockedPoints.begin(), m_LockedPoints.end(), id) ||
                std::binary_search(m_CrossingLockedPoints.begin(), m_CrossingLockedPoints.end(), id);
  }
  return locked;
}

template <typename TInputMesh, typename TOutputMesh>
void
EdgeSwapQuadEdgeMeshFilter<TInputMesh, TOutputMesh>::LockCorners(const MeshExtraction::IndexedTriangleMesh & mesh,
                                                                 const std::vector<std::uint32_t> &          triangles)
{
  for (const std::uint32_t f : triangles)
  {
    for (const std::uint32_t v : mesh.triangles[f])
    {
      m_CrossingLockedPoints.push_back(mesh.pointIds[v]);
    }
  }
  std::sort(m_CrossingLockedPoints.begin(), m_CrossingLockedPoints.end());
  m_CrossingLockedPoints.erase(std::unique(m_CrossingLockedPoints.begin(), m_CrossingLockedPoints.end()),
                               m_CrossingLockedPoints.end());
}

template <typename TInputMesh, typename TOutputMesh>
void
EdgeSwapQuadEdgeMeshFilter<TInputMesh, TOutputMesh>::GenerateData()
{
  // Every stage, including the free functions below, runs on this filter's work units.
  const MeshExtraction::detail::ScopedNumberOfWorkUnits workUnits(this->GetNumberOfWorkUnits());
  m_NumberOfSwaps = 0;
  m_NumberOfRefusedSwaps = 0;
  m_NumberOfIterations = 0;

  const InputMeshType * input = this->GetInput();
  if (input == nullptr)
  {
    itkExceptionMacro(<< "No input mesh: call SetInput() before Update()");
  }
  this->VerifyParameters();
  const std::string nonTriangle =
    MeshExtraction::detail::QuadEdgeMeshVertexSmoother<InputMeshType>::DescribeNonTriangleFace(*input);
  if (!nonTriangle.empty())
  {
    itkExceptionMacro(<< nonTriangle);
  }

  m_NumberOfCrossingTriangles = 0;
  m_NumberOfAttempts = 0;
  m_KeptInput = false;
  m_CrossingLockedPoints.clear();
  const MeshExtraction::detail::EdgeSwapParameters parameters = this->MakeSwapParameters();
  const MeshExtraction::IndexedTriangleMesh        start = MeshExtraction::MakeIndexedTriangleMesh(*input);
  // The input's edges: a triangle with another edge is new.
  std::vector<MeshExtraction::detail::PointIdentifierEdge> inputEdges;
  if (m_PreventSelfIntersections)
  {
    inputEdges = MeshExtraction::detail::EdgesByPointIdentifier(start);
  }
  this->UpdateProgress(0.0f);
  // Swap from the input; with PreventSelfIntersections, the validity guard's lock and
  // retry: the corners of new triangles that cross another triangle are locked and the
  // swaps made again from the input, until none crosses or the attempts run out.
  constexpr unsigned int              attempts = MeshExtraction::detail::ValidityThresholds::MaximumSwapAttempts;
  // The swaps change triangles only: each attempt starts from the input's triangles.
  MeshExtraction::IndexedTriangleMesh swapped = start;
  for (unsigned int attempt = 0; attempt < attempts; ++attempt)
  {
    if (attempt > 0)
    {
      swapped.triangles = start.triangles;
    }
    ++m_NumberOfAttempts;
    const MeshExtraction::detail::EdgeSwapPassCounts counts = MeshExtraction::detail::SwapEdgesInPasses(
      swapped, parameters, this->LockFlags(swapped), m_MaximumNumberOfIterations, [this](int passes) {
        this->UpdateProgress(static_cast<float>(passes) / static_cast<float>(m_MaximumNumberOfIterations));
      });
    m_NumberOfSwaps = counts.swaps;
    m_NumberOfRefusedSwaps = counts.refused;
    m_NumberOfIterations = counts.passes;
    if (!m_PreventSelfIntersections || m_NumberOfSwaps == 0)
    {
      break;
    }
    const std::vector<std::uint32_t> crossing = MeshExtraction::detail::FindCrossingNewTriangles(swapped, inputEdges);
    m_NumberOfCrossingTriangles += crossing.size();
    if (crossing.empty())
    {
      break;
    }
    if (attempt + 1 == attempts)
    {
      m_NumberOfSwaps = 0; // still crossing: keep the input
      m_KeptInput = true;
      break;
    }
    this->LockCorners(swapped, crossing);
  }
  if (m_NumberOfSwaps == 0)
  {
    this->CopyInputMeshToOutputMesh();
  }
  else
  {
    this->BuildOutput(swapped);
  }
  this->UpdateProgress(1.0f);
}

template <typename TInputMesh, typename TOutputMesh>
void
EdgeSwapQuadEdgeMeshFilter<TInputMesh, TOutputMesh>::BuildOutput(const MeshExtraction::IndexedTriangleMesh & swapped)
{
  this->CopyInputMeshToOutputMeshPoints();
  this->CopyInputMeshToOutputMeshPointData();
  OutputMeshType * output = this->GetOutput();
  for (std::size_t f = 0; f < swapped.triangles.size(); ++f)
  {
    const auto &                t = swapped.triangles[f];
    const OutputPointIdentifier p0 = static_cast<OutputPointIdentifier>(swapped.pointIds[t[0]]);
    const OutputPointIdentifier p1 = static_cast<OutputPointIdentifier>(swapped.pointIds[t[1]]);
    const OutputPointIdentifier p2 = static_cast<OutputPointIdentifier>(swapped.pointIds[t[2]]);
    if (output->AddFaceTriangle(p0, p1, p2) == nullptr)
    {
      itkExceptionMacro(<< "the QuadEdgeMesh refused swapped triangle (" << p0 << ", " << p1 << ", " << p2 << ")");
    }
  }
  // Edges without a face on either side are not in the triangles; keep them.
  const auto * edges = this->GetInput()->GetEdgeCells();
  if (edges != nullptr)
  {
    for (auto it = edges->Begin(); it != edges->End(); ++it)
    {
      const auto * edge = dynamic_cast<const typename InputMeshType::EdgeCellType *>(it.Value());
      // ITK's quad-edge queries are not const.
      auto * qe = edge != nullptr ? const_cast<typename InputMeshType::QEType *>(edge->GetQEGeom()) : nullptr;
      if (qe != nullptr && qe->IsWire())
      {
        output->AddEdge(static_cast<OutputPointIdentifier>(qe->GetOrigin()),
                        static_cast<OutputPointIdentifier>(qe->GetDestination()));
      }
    }
  }
}

template <typename TInputMesh, typename TOutputMesh>
void
EdgeSwapQuadEdgeMeshFilter<TInputMesh, TOutputMesh>::PrintSelf(std::ostream & os, Indent indent) const
{
  Superclass::PrintSelf(os, indent);
  os << indent << "Criterion: " << m_Criterion << std::endl;
  os << indent << "MaximumNumberOfIterations: " << m_MaximumNumberOfIterations << std::endl;
  os << indent << "FeatureAngle: " << m_FeatureAngle << std::endl;
  os << indent << "DegenerateQAreaTolerance: " << m_DegenerateQAreaTolerance << std::endl;
  os << indent << "MinimumQAreaRatio: " << m_MinimumQAreaRatio << std::endl;
  os << indent << "PreventSelfIntersections: " << (m_PreventSelfIntersections ? "On" : "Off") << std::endl;
  os << indent << "LockedPoints: " << m_LockedPoints.size() << std::endl;
  os << indent << "NumberOfSwaps: " << m_NumberOfSwaps << std::endl;
  os << indent << "NumberOfRefusedSwaps: " << m_NumberOfRefusedSwaps << std::endl;
  os << indent << "NumberOfIterations: " << m_NumberOfIterations << std::endl;
  os << indent << "NumberOfCrossingTriangles: " << m_NumberOfCrossingTriangles << std::endl;
  os << indent << "NumberOfAttempts: " << m_NumberOfAttempts << std::endl;
  os << indent << "KeptInput: " << (m_KeptInput ? "true" : "false") << std::endl;
}
} // namespace itk

#endif
