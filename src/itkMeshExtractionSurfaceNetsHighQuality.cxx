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
#include "itkMeshExtractionSurfaceNetsHighQuality.h"

#include <utility>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
SurfaceNetsHighQuality::SurfaceNetsHighQuality(SurfaceNet &                             net,
                                               const Vec3 &                             origin,
                                               const Matrix<double, 3, 3> &             indexToPhysical,
                                               const SurfaceNetsHighQualityParameters & parameters,
                                               RelaxFunction                            relax,
                                               ProgressFunction                         progress)
    : m_Net(net)
    , m_Origin(origin)
    , m_IndexToPhysical(indexToPhysical)
    , m_Parameters(parameters)
    , m_Relax(std::move(relax))
    , m_Progress(std::move(progress))
{}

SurfaceNetsHighQualityResult
SurfaceNetsHighQuality::Run(std::vector<TriangleIndices> & triangles)
{
  m_Mesh.triangles = triangles;
  m_Mesh.BuildConnectivity(m_Net.positions.size());
  this->LetNodesLeaveTheirCells();
  m_Result = SurfaceNetsHighQualityResult();
  m_Volumes.Initialize(m_Mesh.triangles, this->Physical());
  unsigned int finalIterations = m_Parameters.iterations;
  for (unsigned int round = 0; round < m_Parameters.numberOfRounds; ++round)
  {
    const std::size_t swaps = this->SwapAndUndoInvalidSwaps(MeshExtractionEnums::EdgeSwapCriterion::Regularity);
    if (round > 0 && this->HaveConverged(swaps))
    {
      // The round's iterations go to the last relaxation, after the Delaunay sweeps
      // (which saves a check, and gives the same mesh where nothing was swapped and the
      // check moves nothing back).
      finalIterations += m_Parameters.iterations;
      break;
    }
    this->RelaxAndPullBackInvalidMoves(m_Parameters.iterations);
    ++m_Result.numberOfRounds;
    if (m_Progress)
    {
      m_Progress(round + 1);
    }
    if (swaps == 0)
    {
      break; // the first round found nothing to swap: it relaxed once
    }
  }
  this->FinalDelaunaySweeps();
  this->RelaxAndPullBackInvalidMoves(finalIterations);
  triangles = m_Mesh.triangles;
  return m_Result;
}

void
SurfaceNetsHighQuality::LetNodesLeaveTheirCells()
{
  const double dilation = m_Parameters.cellDilation;
  for (std::size_t i = 0; i < m_Net.positions.size(); ++i)
  {
    if (m_Net.boxLower[i] == m_Net.boxUpper[i])
    {
      continue; // fixed (a node of a split cell)
    }
    const auto & cell = m_Net.cells[m_Net.nodeCell[i]];
    m_Net.boxLower[i] = MakeVec3(cell.x - dilation, cell.y - dilation, cell.z - dilation);
    m_Net.boxUpper[i] = MakeVec3(cell.x + 1 + dilation, cell.y + 1 + dilation, cell.z + 1 + dilation);
  }
}

std::size_t
SurfaceNetsHighQuality::SwapAndUndoInvalidSwaps(MeshExtractionEnums::EdgeSwapCriterion criterion)
{
  EdgeSwapParameters parameters;
  parameters.criterion = criterion;
  parameters.degenerateQAreaTolerance = ValidityThresholds::HighQualityDegenerateQAreaTolerance;
  const std::vector<Vec3> physical = this->Physical();
  auto                    swaps = SwapEdges(physical, m_Mesh, parameters, &m_Refused);
  UndoIntersectingSwaps(physical, m_Mesh, swaps, &m_Refused, &m_Tree, &m_Volumes);
  m_Result.numberOfSwaps += swaps.size();
  return swaps.size();
}

bool
SurfaceNetsHighQuality::HaveConverged(std::size_t swaps) const
{
  return swaps == 0 ||
         static_cast<double>(swaps) < m_Parameters.convergedSwapFraction * static_cast<double>(m_Mesh.triangles.size());
}

void
SurfaceNetsHighQuality::RelaxAndPullBackInvalidMoves(unsigned int iterations)
{
  m_Mesh.FillLinks(m_Net);
  const LargeBlockVector<Vec3> start = m_Net.positions;
  m_Relax(iterations);
  for (std::size_t i = 0; i < start.size(); ++i)
  {
    if (SquaredNorm(m_Net.positions[i] - start[i]) < SettledSquaredMove)
    {
      m_Net.positions[i] = start[i]; // settled: leave it, and its faces, unchanged
    }
  }
  const LargeBlockVector<Vec3> before = m_Net.positions;
  m_Result.numberOfNodesMovedBack += PullBackInvalidMoves(m_Net.positions,
                                                          start,
                                                          m_Mesh,
                                                          m_Origin,
                                                          m_IndexToPhysical,
                                                          ValidityThresholds::HighQualityDegenerateQAreaTolerance,
                                                          m_Parameters.roundToFloat,
                                                          &m_Tree,
                                                          &m_Cache,
                                                          &m_Volumes);
  // A node pulled back is held still from now on.
  for (std::size_t i = 0; i < start.size(); ++i)
  {
    if (m_Net.positions[i] != before[i])
    {
      m_Net.boxLower[i] = m_Net.positions[i];
      m_Net.boxUpper[i] = m_Net.positions[i];
    }
  }
}

void
SurfaceNetsHighQuality::FinalDelaunaySweeps()
{
  for (unsigned int sweep = 0; sweep < DelaunaySweeps; ++sweep)
  {
    if (this->SwapAndUndoInvalidSwaps(MeshExtractionEnums::EdgeSwapCriterion::Delaunay) == 0)
    {
      break;
    }
  }
}

std::vector<Vec3>
SurfaceNetsHighQuality::Physical() const
{
  return ToPhysical(m_Net.positions, m_Origin, m_IndexToPhysical, m_Parameters.roundToFloat);
}

} // namespace detail
} // namespace MeshExtraction
} // namespace itk
