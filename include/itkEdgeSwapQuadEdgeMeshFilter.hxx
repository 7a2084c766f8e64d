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
auto
EdgeSwapQuadEdgeMeshFilter<TInputMesh, TOutputMesh>::SortedEdges(const OutputMeshType * mesh) -> std::vector<PointPair>
{
  std::vector<PointPair> edges;
  const auto *           edgeCells = mesh->GetEdgeCells();
  edges.reserve(edgeCells->Size());
  for (auto it = edgeCells->Begin(); it != edgeCells->End(); ++it)
  {
    const auto * cell = it.Value();
    if (cell == nullptr || cell->GetNumberOfPoints() != 2)
    {
      continue;
    }
    auto                        p = cell->PointIdsBegin();
    const OutputPointIdentifier a = *p;
    const OutputPointIdentifier b = *(p + 1);
    edges.emplace_back(std::min(a, b), std::max(a, b));
  }
  std::sort(edges.begin(), edges.end());
  return edges;
}

template <typename TInputMesh, typename TOutputMesh>
void
EdgeSwapQuadEdgeMeshFilter<TInputMesh, TOutputMesh>::CountValences(const OutputMeshType *      mesh,
                                                                   std::vector<int> &          valence,
                                                                   std::vector<std::uint8_t> & onBoundary)
{
  const auto *          points = mesh->GetPoints();
  OutputPointIdentifier largestId = 0;
  for (auto it = points->Begin(); it != points->End(); ++it)
  {
    largestId = std::max(largestId, it.Index());
  }
  valence.assign(static_cast<std::size_t>(largestId) + 1, 0);
  onBoundary.assign(static_cast<std::size_t>(largestId) + 1, 0);
  for (auto it = points->Begin(); it != points->End(); ++it)
  {
    valence[it.Index()] = std::max(0, it.Value().GetValence());
    onBoundary[it.Index()] = it.Value().IsInternal() ? 0 : 1;
  }
}

template <typename TInputMesh, typename TOutputMesh>
bool
EdgeSwapQuadEdgeMeshFilter<TInputMesh, TOutputMesh>::IsLocked(OutputPointIdentifier p) const
{
  return std::binary_search(m_LockedPoints.begin(), m_LockedPoints.end(), p) ||
         std::binary_search(m_CrossingLockedPoints.begin(), m_CrossingLockedPoints.end(), p);
}

template <typename TInputMesh, typename TOutputMesh>
MeshExtraction::detail::EdgeSwapQuad
EdgeSwapQuadEdgeMeshFilter<TInputMesh, TOutputMesh>::MakeQuad(OutputMeshType *                  mesh,
                                                              const OutputPointIdentifier       corners[4],
                                                              const std::vector<int> &          valence,
                                                              const std::vector<std::uint8_t> & onBoundary)
{
  using MeshExtraction::ToVec3;
  const OutputPointIdentifier          a = corners[0];
  const OutputPointIdentifier          b = corners[1];
  const OutputPointIdentifier          c = corners[2];
  const OutputPointIdentifier          d = corners[3];
  auto *                               points = mesh->GetPoints();
  MeshExtraction::detail::EdgeSwapQuad quad;
  quad.a = ToVec3(points->ElementAt(a));
  quad.b = ToVec3(points->ElementAt(b));
  quad.c = ToVec3(points->ElementAt(c));
  quad.d = ToVec3(points->ElementAt(d));
  quad.valenceA = static_cast<unsigned int>(valence[a]);
  quad.valenceB = static_cast<unsigned int>(valence[b]);
  quad.valenceC = static_cast<unsigned int>(valence[c]);
  quad.valenceD = static_cast<unsigned int>(valence[d]);
  quad.boundaryA = onBoundary[a] != 0;
  quad.boundaryB = onBoundary[b] != 0;
  quad.boundaryC = onBoundary[c] != 0;
  quad.boundaryD = onBoundary[d] != 0;
  quad.sameApex = c == d;
  quad.oppositeEdgeExists = !quad.sameApex && mesh->FindEdge(c, d) != nullptr;
  return quad;
}

template <typename TInputMesh, typename TOutputMesh>
auto
EdgeSwapQuadEdgeMeshFilter<TInputMesh, TOutputMesh>::SwapPass(
  OutputMeshType *                                   mesh,
  const MeshExtraction::detail::EdgeSwapParameters & parameters) -> SizeValueType
{
  if (mesh->GetEdgeCells() == nullptr)
  {
    return 0;
  }
  // The edges as (smaller, larger) point identifiers, in increasing order: the
  // order does not depend on where the quad-edge structure keeps them.
  const std::vector<PointPair> edges = SortedEdges(mesh);
  // Valences and boundary flags once per pass (walking a point's edge ring through
  // the quad-edge structure is slow), kept up to date as edges are swapped: a swap
  // takes an edge from a and b and gives one to c and d; boundaries do not change.
  std::vector<int>          valence;
  std::vector<std::uint8_t> onBoundary;
  CountValences(mesh, valence, onBoundary);
  const bool    anyLocked = !m_LockedPoints.empty() || !m_CrossingLockedPoints.empty();
  auto          flip = FlipEdgeFunctionType::New();
  SizeValueType swaps = 0;
  for (const auto & ab : edges)
  {
    OutputQEType * e = mesh->FindEdge(ab.first, ab.second);
    if (e == nullptr || !e->IsInternal() || !e->IsLnextOfTriangle() || !e->GetSym()->IsLnextOfTriangle())
    {
      continue; // swapped away earlier in this pass, on a boundary, or not between two triangles
    }
    const OutputPointIdentifier q[4] = {
      e->GetOrigin(), e->GetDestination(), e->GetLnext()->GetDestination(), e->GetSym()->GetLnext()->GetDestination()
    };
    if (anyLocked && (this->IsLocked(q[0]) || this->IsLocked(q[1]) || this->IsLocked(q[2]) || this->IsLocked(q[3])))
    {
      continue;
    }
    const MeshExtraction::detail::EdgeSwapDecision decision =
      MeshExtraction::detail::EvaluateEdgeSwap(MakeQuad(mesh, q, valence, onBoundary), parameters);
    if (decision.verdict == MeshExtraction::detail::EdgeSwapVerdict::NoImprovement)
    {
      continue;
    }
    if (!decision.Swap() || !this->Flip(flip, mesh, e, q))
    {
      ++m_NumberOfRefusedSwaps;
      continue;
    }
    --valence[q[0]];
    --valence[q[1]];
    ++valence[q[2]];
    ++valence[q[3]];
    ++swaps;
  }
  return swaps;
}

template <typename TInputMesh, typename TOutputMesh>
bool
EdgeSwapQuadEdgeMeshFilter<TInputMesh, TOutputMesh>::Flip(FlipEdgeFunctionType *      flip,
                                                          OutputMeshType *            mesh,
                                                          OutputQEType *              e,
                                                          const OutputPointIdentifier corners[4])
{
  flip->SetInput(mesh);
  OutputQEType * result = flip->Evaluate(e);
  if (result == nullptr)
  {
    // FlipEdge checks what CheckEdgeSwap checked and leaves the mesh unchanged
    // when it refuses; count it as refused.
    return false;
  }
  const OutputPointIdentifier o = result->GetOrigin();
  const OutputPointIdentifier t = result->GetDestination();
  const OutputPointIdentifier c = corners[2];
  const OutputPointIdentifier d = corners[3];
  if (!((o == c && t == d) || (o == d && t == c)) || !result->IsInternal())
  {
    itkExceptionMacro(<< "QuadEdgeMeshEulerOperatorFlipEdgeFunction turned edge (" << corners[0] << ", " << corners[1]
                      << ") into (" << o << ", " << t << ") instead of (" << c << ", " << d << ")");
  }
  return true;
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
void
EdgeSwapQuadEdgeMeshFilter<TInputMesh, TOutputMesh>::SwapFromInput(
  bool                                               again,
  const MeshExtraction::detail::EdgeSwapParameters & parameters)
{
  if (again)
  {
    this->GetOutput()->Initialize(); // the copy adds to what the output holds
  }
  this->CopyInputMeshToOutputMesh();
  m_NumberOfSwaps = 0;
  m_NumberOfRefusedSwaps = 0;
  m_NumberOfIterations = 0;
  ++m_NumberOfAttempts;
  for (int pass = 0; pass < m_MaximumNumberOfIterations; ++pass)
  {
    const SizeValueType swaps = this->SwapPass(this->GetOutput(), parameters);
    m_NumberOfSwaps += swaps;
    ++m_NumberOfIterations;
    this->UpdateProgress(static_cast<float>(pass + 1) / static_cast<float>(m_MaximumNumberOfIterations));
    if (swaps == 0)
    {
      break;
    }
  }
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
  // The input's edges: a triangle with another edge is new.
  std::vector<MeshExtraction::detail::PointIdentifierEdge> inputEdges;
  if (m_PreventSelfIntersections)
  {
    inputEdges = MeshExtraction::detail::EdgesByPointIdentifier(MeshExtraction::MakeIndexedTriangleMesh(*input));
  }
  this->UpdateProgress(0.0f);
  // Swap from the input; with PreventSelfIntersections, the validity guard's lock and
  // retry: the corners of new triangles that cross another triangle are locked and the
  // swaps made again from the input, until none crosses or the attempts run out.
  constexpr unsigned int attempts = MeshExtraction::detail::ValidityThresholds::MaximumSwapAttempts;
  for (unsigned int attempt = 0; attempt < attempts; ++attempt)
  {
    this->SwapFromInput(attempt > 0, parameters);
    if (!m_PreventSelfIntersections || m_NumberOfSwaps == 0)
    {
      break;
    }
    const MeshExtraction::IndexedTriangleMesh indexed = MeshExtraction::MakeIndexedTriangleMesh(*this->GetOutput());
    const std::vector<std::uint32_t> crossing = MeshExtraction::detail::FindCrossingNewTriangles(indexed, inputEdges);
    m_NumberOfCrossingTriangles += crossing.size();
    if (crossing.empty())
    {
      break;
    }
    if (attempt + 1 == attempts)
    {
      this->GetOutput()->Initialize(); // still crossing: keep the input
      this->CopyInputMeshToOutputMesh();
      m_NumberOfSwaps = 0;
      m_KeptInput = true;
      break;
    }
    this->LockCorners(indexed, crossing);
  }
  this->UpdateProgress(1.0f);
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
