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
// Internal to MeshExtraction (namespace detail): not part of the public API.
#ifndef itkMeshExtractionSurfaceNetsHighQuality_h
#define itkMeshExtractionSurfaceNetsHighQuality_h

#include "MeshExtractionExport.h"
#include "itkMeshExtractionClosedSurfaceEdgeSwap.h"
#include "itkMeshExtractionQualityAnalysis.h"
#include "itkMeshExtractionSurfaceNets.h"
#include "itkMeshExtractionTriangleAABBTree.h"
#include "itkMeshExtractionValidityGuard.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
/** The settings of the high-quality mode (SurfaceNetsImageToMeshFilter's
 * NumberOfHighQualityRounds, HighQualityIterations, HighQualityCellDilation and
 * ConvergedSwapFraction). */
struct SurfaceNetsHighQualityParameters
{
  unsigned int numberOfRounds{ 8 };            ///< rounds of swaps and relaxation at most
  unsigned int iterations{ 4 };                ///< relaxation iterations per round
  double       cellDilation{ 0.5 };            ///< how far (voxels) a node may leave its cell
  double       convergedSwapFraction{ 0.001 }; ///< fewer swaps than this fraction of the triangles: converged
  bool         roundToFloat{ false };          ///< the output stores float coordinates: check those
};

/** What the high-quality mode did. */
struct SurfaceNetsHighQualityResult
{
  std::size_t  numberOfSwaps{ 0 };          ///< swaps kept
  unsigned int numberOfRounds{ 0 };         ///< rounds that swapped and relaxed (not the last relaxation)
  std::size_t  numberOfNodesMovedBack{ 0 }; ///< nodes the validity guard pulled back
};

/** \class SurfaceNetsHighQuality
 * \brief The high-quality mode of SurfaceNets (thesis 2.3 and 4.2.4 applied to
 * SurfaceNets): rounds of edge swaps and relaxation on the triangles of a relaxed net,
 * every change checked by the validity guard.
 *
 * Run() reads as the mode:
 * 1. the nodes may leave their cells by the cell dilation (nodes fixed in split cells
 *    stay fixed): the swaps and the guard, not the cells, then keep the mesh valid, and
 *    a node reaches the iso-surface near cell corners and spaces out better;
 * 2. rounds, each: regularity swaps (SwapEdges), the invalid ones undone
 *    (UndoIntersectingSwaps), the relaxation on the triangles' 1-rings, the invalid
 *    moves pulled back (PullBackInvalidMoves); a node pulled back is held still in the
 *    later rounds, where the mesh is tight (thin or sharp parts). After the first round,
 *    a round whose swaps are fewer than the converged fraction of the triangles ends
 *    the rounds before it relaxes, and gives its iterations to the last relaxation;
 * 3. Delaunay sweeps: slivers that the constraint pinned get the diagonal that
 *    maximises their smallest angle;
 * 4. the last relaxation, with its pull-back.
 * No component may collapse (ComponentVolumes, measured where the mode starts).
 *
 * The relaxation is the caller's (SurfaceNetsImageToMeshFilter::RelaxNet on the net's
 * links, which this refills from the triangles before each relaxation).
 * \ingroup MeshExtraction */
class MeshExtraction_EXPORT SurfaceNetsHighQuality
{
public:
  /** Relaxes the net (its positions, within its nodes' boxes) with this many
   * iterations at most. */
  using RelaxFunction = std::function<void(unsigned int iterations)>;
  /** Called after each round with the number of rounds done. */
  using ProgressFunction = std::function<void(unsigned int roundsDone)>;

  /** A node that moved less than this (squared, voxels^2) in a relaxation has settled:
   * it keeps its start position, so that its faces stay as they were. */
  static constexpr double SettledSquaredMove = 1e-10;
  /** The Delaunay sweeps after the rounds, at most. */
  static constexpr unsigned int DelaunaySweeps = 2;

  SurfaceNetsHighQuality(SurfaceNet &                             net,
                         const Vec3 &                             origin,
                         const Matrix<double, 3, 3> &             indexToPhysical,
                         const SurfaceNetsHighQualityParameters & parameters,
                         RelaxFunction                            relax,
                         ProgressFunction                         progress = nullptr);

  /** The mode on the net's `triangles` (closed, 2-manifold), which it swaps in place;
   * it moves the net's nodes. */
  SurfaceNetsHighQualityResult
  Run(std::vector<TriangleIndices> & triangles);

private:
  void
  LetNodesLeaveTheirCells();
  /** One sweep of swaps for `criterion`, the invalid ones undone: the swaps kept. */
  std::size_t
  SwapAndUndoInvalidSwaps(MeshExtractionEnums::EdgeSwapCriterion criterion);
  bool
  HaveConverged(std::size_t swaps) const;
  void
  RelaxAndPullBackInvalidMoves(unsigned int iterations);
  void
  FinalDelaunaySweeps();
  /** The nodes' physical points as the output will store them. */
  std::vector<Vec3>
  Physical() const;

  SurfaceNet &                           m_Net;
  const Vec3                             m_Origin;
  const Matrix<double, 3, 3>             m_IndexToPhysical;
  const SurfaceNetsHighQualityParameters m_Parameters;
  RelaxFunction                          m_Relax;
  ProgressFunction                       m_Progress;

  SurfaceNetTriangles          m_Mesh;
  std::vector<std::uint64_t>   m_Refused; ///< edges whose swap had to be undone
  TriangleAABBTree             m_Tree;    ///< one shape for every check, refitted
  SelfIntersectionCache        m_Cache;   ///< what the checks after small moves may skip
  ComponentVolumes             m_Volumes; ///< no component may turn inside out or flatten
  SurfaceNetsHighQualityResult m_Result;
};

} // namespace detail
} // namespace MeshExtraction
} // namespace itk

#endif
