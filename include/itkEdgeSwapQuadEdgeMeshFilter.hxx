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
EdgeSwapQuadEdgeMeshFilter<TInputMesh, TOutputMesh>::SwapPass(OutputMeshType *                           mesh,
                                                              const MeshExtraction::EdgeSwapParameters & parameters)
  -> SizeValueType
{
  using MeshExtraction::ToVec3;
  // The edges as (smaller, larger) point identifiers, in increasing order: the
  // order does not depend on where the quad-edge structure keeps them.
  std::vector<std::pair<OutputPointIdentifier, OutputPointIdentifier>> edges;
  const auto *                                                         edgeCells = mesh->GetEdgeCells();
  if (edgeCells == nullptr)
  {
    return 0;
  }
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

  auto IsLocked = [this](OutputPointIdentifier p) {
    return std::binary_search(m_LockedPoints.begin(), m_LockedPoints.end(), p) ||
           std::binary_search(m_CrossingLockedPoints.begin(), m_CrossingLockedPoints.end(), p);
  };
  // Valences and boundary flags once per pass (walking a point's edge ring through
  // the quad-edge structure is slow), kept up to date as edges are swapped: a swap
  // takes an edge from a and b and gives one to c and d; boundaries do not change.
  auto *                points = mesh->GetPoints();
  OutputPointIdentifier largestId = 0;
  for (auto it = points->Begin(); it != points->End(); ++it)
  {
    largestId = std::max(largestId, it.Index());
  }
  std::vector<int>          valence(static_cast<std::size_t>(largestId) + 1, 0);
  std::vector<std::uint8_t> onBoundary(static_cast<std::size_t>(largestId) + 1, 0);
  for (auto it = points->Begin(); it != points->End(); ++it)
  {
    valence[it.Index()] = std::max(0, it.Value().GetValence());
    onBoundary[it.Index()] = it.Value().IsInternal() ? 0 : 1;
  }
  auto          flip = FlipEdgeFunctionType::New();
  SizeValueType swaps = 0;
  for (const auto & ab : edges)
  {
    OutputQEType * e = mesh->FindEdge(ab.first, ab.second);
    if (e == nullptr || !e->IsInternal() || !e->IsLnextOfTriangle() || !e->GetSym()->IsLnextOfTriangle())
    {
      continue; // swapped away earlier in this pass, on a boundary, or not between two triangles
    }
    const OutputPointIdentifier a = e->GetOrigin();
    const OutputPointIdentifier b = e->GetDestination();
    const OutputPointIdentifier c = e->GetLnext()->GetDestination();
    const OutputPointIdentifier d = e->GetSym()->GetLnext()->GetDestination();
    if ((!m_LockedPoints.empty() || !m_CrossingLockedPoints.empty()) &&
        (IsLocked(a) || IsLocked(b) || IsLocked(c) || IsLocked(d)))
    {
      continue;
    }
    const auto & pa = points->ElementAt(a);
    const auto & pb = points->ElementAt(b);
    const auto & pc = points->ElementAt(c);
    const auto & pd = points->ElementAt(d);

    MeshExtraction::EdgeSwapQuad quad;
    quad.a = ToVec3(pa);
    quad.b = ToVec3(pb);
    quad.c = ToVec3(pc);
    quad.d = ToVec3(pd);
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

    const MeshExtraction::EdgeSwapDecision decision = MeshExtraction::EvaluateEdgeSwap(quad, parameters);
    if (decision.verdict == MeshExtraction::EdgeSwapVerdict::NoImprovement)
    {
      continue;
    }
    if (!decision.Swap())
    {
      ++m_NumberOfRefusedSwaps;
      continue;
    }
    flip->SetInput(mesh);
    OutputQEType * result = flip->Evaluate(e);
    if (result == nullptr)
    {
      // FlipEdge checks what CheckEdgeSwap checked and leaves the mesh unchanged
      // when it refuses; count it as refused.
      ++m_NumberOfRefusedSwaps;
      continue;
    }
    const OutputPointIdentifier o = result->GetOrigin();
    const OutputPointIdentifier t = result->GetDestination();
    if (!((o == c && t == d) || (o == d && t == c)) || !result->IsInternal())
    {
      itkExceptionMacro(<< "QuadEdgeMeshEulerOperatorFlipEdgeFunction turned edge (" << a << ", " << b << ") into ("
                        << o << ", " << t << ") instead of (" << c << ", " << d << ")");
    }
    --valence[a];
    --valence[b];
    ++valence[c];
    ++valence[d];
    ++swaps;
  }
  return swaps;
}

template <typename TInputMesh, typename TOutputMesh>
void
EdgeSwapQuadEdgeMeshFilter<TInputMesh, TOutputMesh>::GenerateData()
{
  // Every stage, including the free functions below, runs on this filter's work units.
  const MeshExtraction::ScopedNumberOfWorkUnits workUnits(this->GetNumberOfWorkUnits());
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
    MeshExtraction::QuadEdgeMeshVertexSmoother<InputMeshType>::DescribeNonTriangleFace(*input);
  if (!nonTriangle.empty())
  {
    itkExceptionMacro(<< nonTriangle);
  }

  m_NumberOfCrossingTriangles = 0;
  m_NumberOfAttempts = 0;
  m_KeptInput = false;
  m_CrossingLockedPoints.clear();
  OutputMeshType * output = this->GetOutput();

  MeshExtraction::EdgeSwapParameters parameters;
  parameters.criterion = m_Criterion;
  parameters.minimumValence = 3;
  parameters.featureAngle = m_FeatureAngle * itk::Math::pi / 180.0;
  parameters.degenerateQAreaTolerance = m_DegenerateQAreaTolerance;
  parameters.minimumQAreaRatio = m_MinimumQAreaRatio;

  // The input's edges, by point identifiers: a triangle with another edge is new.
  using Edge = std::pair<OutputPointIdentifier, OutputPointIdentifier>;
  std::vector<Edge> inputEdges;
  if (m_PreventSelfIntersections)
  {
    const MeshExtraction::IndexedTriangleMesh indexed = MeshExtraction::MakeIndexedTriangleMesh(*input);
    for (const auto & t : indexed.triangles)
    {
      for (unsigned int k = 0; k < 3; ++k)
      {
        const OutputPointIdentifier a = indexed.pointIds[t[k]];
        const OutputPointIdentifier b = indexed.pointIds[t[(k + 1) % 3]];
        inputEdges.emplace_back(std::min(a, b), std::max(a, b));
      }
    }
    std::sort(inputEdges.begin(), inputEdges.end());
    inputEdges.erase(std::unique(inputEdges.begin(), inputEdges.end()), inputEdges.end());
  }
  constexpr unsigned int MaximumNumberOfAttempts = 8;
  this->UpdateProgress(0.0f);
  for (unsigned int attempt = 0; attempt < MaximumNumberOfAttempts; ++attempt)
  {
    if (attempt > 0)
    {
      output->Initialize(); // the copy adds to what the output holds
    }
    this->CopyInputMeshToOutputMesh();
    m_NumberOfSwaps = 0;
    m_NumberOfRefusedSwaps = 0;
    m_NumberOfIterations = 0;
    ++m_NumberOfAttempts;
    for (int pass = 0; pass < m_MaximumNumberOfIterations; ++pass)
    {
      const SizeValueType swaps = this->SwapPass(output, parameters);
      m_NumberOfSwaps += swaps;
      ++m_NumberOfIterations;
      this->UpdateProgress(static_cast<float>(pass + 1) / static_cast<float>(m_MaximumNumberOfIterations));
      if (swaps == 0)
      {
        break;
      }
    }
    if (!m_PreventSelfIntersections || m_NumberOfSwaps == 0)
    {
      break;
    }
    // New triangles that cross another triangle: lock their corners and start again.
    const MeshExtraction::IndexedTriangleMesh indexed = MeshExtraction::MakeIndexedTriangleMesh(*output);
    std::vector<std::uint8_t>                 isNew(indexed.triangles.size(), 0);
    std::vector<std::uint32_t>                queries;
    for (std::uint32_t f = 0; f < indexed.triangles.size(); ++f)
    {
      const auto & t = indexed.triangles[f];
      for (unsigned int k = 0; k < 3 && !isNew[f]; ++k)
      {
        const OutputPointIdentifier a = indexed.pointIds[t[k]];
        const OutputPointIdentifier b = indexed.pointIds[t[(k + 1) % 3]];
        isNew[f] =
          std::binary_search(inputEdges.begin(), inputEdges.end(), Edge(std::min(a, b), std::max(a, b))) ? 0 : 1;
      }
      if (isNew[f])
      {
        queries.push_back(f);
      }
    }
    std::vector<std::uint32_t> crossing;
    for (const auto & pair : MeshExtraction::FindSelfIntersections(indexed, &queries))
    {
      for (const std::uint32_t f : { pair.first, pair.second })
      {
        if (isNew[f])
        {
          crossing.push_back(f);
        }
      }
    }
    std::sort(crossing.begin(), crossing.end());
    crossing.erase(std::unique(crossing.begin(), crossing.end()), crossing.end());
    m_NumberOfCrossingTriangles += crossing.size();
    if (crossing.empty())
    {
      break;
    }
    if (attempt + 1 == MaximumNumberOfAttempts)
    {
      output->Initialize(); // still crossing: keep the input
      this->CopyInputMeshToOutputMesh();
      m_NumberOfSwaps = 0;
      m_KeptInput = true;
      break;
    }
    for (const std::uint32_t f : crossing)
    {
      for (const std::uint32_t v : indexed.triangles[f])
      {
        m_CrossingLockedPoints.push_back(indexed.pointIds[v]);
      }
    }
    std::sort(m_CrossingLockedPoints.begin(), m_CrossingLockedPoints.end());
    m_CrossingLockedPoints.erase(std::unique(m_CrossingLockedPoints.begin(), m_CrossingLockedPoints.end()),
                                 m_CrossingLockedPoints.end());
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
