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
#ifndef itkMeshExtractionSliverRemoval_h
#define itkMeshExtractionSliverRemoval_h

#include "MeshExtractionExport.h"
#include "itkMeshExtractionIndexedTriangleMesh.h"
#include "itkMeshExtractionLargeBlockVector.h"
#include "itkMatrix.h"

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
/** The settings of RemoveSlivers (SurfaceNetsImageToMeshFilter's HighQualitySliverRemoval). */
struct SliverRemovalParameters
{
  /** A triangle whose q_angle (smallest / largest angle) is below this is a sliver: the
   * pass works around it. */
  double sliverQAngle{ 0.3 };
  /** Passes at most (each: operations on disjoint neighbourhoods, then the check); the
   * passes end earlier when one makes no operation. */
  unsigned int maximumNumberOfPasses{ 40 };
  /** A triangle at or below this q_area is degenerate: no operation may leave one. */
  double degenerateQAreaTolerance{ 1e-3 };
  /** The output stores float coordinates: every check sees the rounded points. */
  bool roundToFloat{ false };
  /** Isotropic remeshing before the sliver passes (needs a projection): the target
   * edge length in millimetres, or 0 for none. Edges longer than 4/3 of it are split,
   * edges shorter than 4/5 of it collapsed, edges swapped toward valence 6, and the
   * nodes relaxed along the surface and projected onto it (Botsch and Kobbelt's
   * isotropic remeshing), each change under the same guards as the sliver passes. */
  double targetEdgeLength{ 0.0 };
  /** Rounds of split, collapse, swap and relaxation in the isotropic remeshing (and as
   * many of quality swaps and relaxation), at most: each kind stops at a round that
   * changes nothing. */
  unsigned int remeshingIterations{ 8 };
};

/** What RemoveSlivers did. */
struct SliverRemovalResult
{
  std::size_t  numberOfCollapses{ 0 }; ///< edges collapsed (and kept)
  std::size_t  numberOfSwaps{ 0 };     ///< edges swapped (and kept)
  std::size_t  numberOfMoves{ 0 };     ///< vertices moved (and kept)
  std::size_t  numberOfUndone{ 0 };    ///< operations undone because a face crossed another or a component collapsed
  unsigned int numberOfPasses{ 0 };
  std::size_t  numberOfSplits{ 0 };             ///< edges split by the isotropic remeshing (and kept)
  std::size_t  numberOfRemeshingCollapses{ 0 }; ///< of numberOfCollapses, those of the isotropic remeshing
  std::size_t  numberOfRemeshingSwaps{ 0 };     ///< of numberOfSwaps, those of the isotropic remeshing
  std::size_t numberOfRelaxedNodes{ 0 }; ///< node moves of the remeshing's relaxation (and kept), summed over its steps
  std::size_t numberOfRelaxationUndone{ 0 }; ///< relaxation moves taken back by the guards
  /** Rounds the remeshing ran, of both kinds: they stop early at the first that changes nothing. */
  unsigned int numberOfRemeshingRounds{ 0 };
};

/** Projects a point (continuous index) onto the surface the mesh approximates; false
 * where it cannot (the point is then left where it was). */
using SurfaceProjection = std::function<bool(Vec3 & index)>;

/** \brief Local remeshing around slivers of a closed, 2-manifold, oriented triangle mesh.
 *
 * One node per cell cannot remove a needle between two nodes pinned near a shared cell
 * face, nor the three thin triangles around a node of valence 3: that takes a change of
 * the connectivity. Around every triangle whose q_angle is below
 * SliverRemovalParameters::sliverQAngle, the pass tries the collapse of each of its
 * edges (onto either end, onto the midpoint, or onto the centroid of both ends'
 * neighbours, projected onto the surface), the swap of each edge, and the move of each
 * corner (to the centroid of its neighbours, half-way there, or toward the apex of the
 * equilateral triangle on the opposite edge, or half-way there, projected), and makes
 * the one that raises the smallest q_angle of the triangles it changes the most, if any
 * does. A sliver where none does is tried again only once something near it changed;
 * an operation a check undid is not tried again. An operation is made only where the mesh stays 2-manifold and
 * closed (the link condition; no node of valence below 3), where no changed triangle
 * turns over against the one it replaces, folds against a neighbour or becomes
 * degenerate; after each pass the changed triangles are checked for crossings against
 * the whole mesh (TriangleAABBTree, refitted only when testing the faces changed since
 * the last refit one by one would cost more), and the components' enclosed volumes
 * (kept up to date by each operation) against the start (IsCollapsedComponent), and the
 * operations involved are undone. The operations
 * of one pass touch disjoint neighbourhoods, so each can be undone alone.
 *
 * `positions` are continuous indices (physical = origin + indexToPhysical * index);
 * quality is measured in physical space. Collapsed nodes stay in `positions`, in no
 * triangle; `triangles` loses two triangles per collapse. Sequential and deterministic. */
MeshExtraction_EXPORT SliverRemovalResult
RemoveSlivers(LargeBlockVector<Vec3> &        positions,
              std::vector<TriangleIndices> &  triangles,
              const Vec3 &                    origin,
              const Matrix<double, 3, 3> &    indexToPhysical,
              const SurfaceProjection &       project,
              const SliverRemovalParameters & parameters);

} // namespace detail
} // namespace MeshExtraction
} // namespace itk

#endif
