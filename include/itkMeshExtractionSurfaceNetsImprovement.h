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
#ifndef itkMeshExtractionSurfaceNetsImprovement_h
#define itkMeshExtractionSurfaceNetsImprovement_h

#include "MeshExtractionExport.h"
#include "itkMeshExtractionEdgeSwapCriteria.h"
#include "itkMeshExtractionSurfaceNets.h"

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

namespace itk
{
namespace MeshExtraction
{
class TriangleAABBTree;
struct SelfIntersectionCache;

/** \brief The triangles of a SurfaceNet with the twin of every half-edge, for edge
 * swapping. Half-edge 3f + k runs from triangles[f][k] to triangles[f][k+1]; the
 * surface is closed, so every half-edge has a twin.
 * \ingroup MeshExtraction */
struct MeshExtraction_EXPORT SurfaceNetTriangles
{
  std::vector<TriangleIndices> triangles;
  std::vector<std::uint32_t>   twin;
  std::vector<std::uint32_t>   valence;

  /** Twins and valences from the triangles (throws if the surface is not closed and manifold). */
  void
  BuildConnectivity(std::size_t numberOfPoints);
  /** Gives the faces new corners (face, corners) that cover the same part of the
   * surface together, as the two triangles of an edge swap do either way, and updates
   * the twins and valences there only: the result is BuildConnectivity()'s, in time
   * proportional to the faces replaced (throws if they do not close up). */
  void
  ReplaceTriangles(const std::vector<std::pair<std::uint32_t, TriangleIndices>> & replacements);
  /** True if the vertices u and v share an edge (walks the fan of u). */
  bool
  HasEdge(std::uint32_t u, std::uint32_t v, std::uint32_t halfEdgeFromU) const;
  /** The net's links (neighbour lists) from the triangles' edges. */
  void
  FillLinks(SurfaceNet & net) const;
};

/** The two triangles an edge swap replaced, to undo it. */
struct EdgeSwapRecord
{
  std::uint32_t   first;
  std::uint32_t   second;
  TriangleIndices oldFirst;
  TriangleIndices oldSecond;
};

/** One sweep of edge swaps over all edges, in index order, that EvaluateEdgeSwap()
 * accepts (thesis 2.2.6 and 4.5.1; the decision EdgeSwapQuadEdgeMeshFilter uses).
 * A triangle takes part in at most one swap per sweep, so each swap can be undone
 * on its own. `physical` are the node positions in millimetres. */
MeshExtraction_EXPORT std::vector<EdgeSwapRecord>
                      SwapEdges(const std::vector<Vec3> &          physical,
                                SurfaceNetTriangles &              mesh,
                                const EdgeSwapParameters &         parameters,
                                const std::vector<std::uint64_t> * refused = nullptr);

/** Key of the undirected edge (u, v), for the sorted list of refused edges. */
inline std::uint64_t
EdgeKey(std::uint32_t u, std::uint32_t v)
{
  return (static_cast<std::uint64_t>(std::min(u, v)) << 32) | std::max(u, v);
}

/** \brief The signed volume of each component of a closed mesh (positive for an outer
 * surface, negative for a cavity's), measured where the high-quality mode starts.
 *
 * A component of a few triangles (a voxel on its own, a few nodes across) can turn
 * inside out, or close onto itself, in one move or swap while none of its faces
 * flips, folds or crosses another at the end of it; its volume tells (as in
 * UndoFoldingMoves, which compares each step of the scale-space refinement with its
 * start). The components are those of the vertices, which swaps and moves do not
 * change.
 * \ingroup MeshExtraction */
struct MeshExtraction_EXPORT ComponentVolumes
{
  std::vector<std::uint32_t> vertexComponent; ///< component of each vertex (the largest uint32 if in no triangle)
  std::vector<Vec3>          origin;          ///< per component: a vertex's start position, to measure from
  std::vector<double>        reference;       ///< per component: 6 x the signed volume at the start

  /** Labels the components of `triangles` and measures their volumes at `points`. */
  void
  Initialize(const std::vector<TriangleIndices> & triangles, const std::vector<Vec3> & points);
  /** True for each component whose volume at `points` has another sign than its
   * reference or less than a quarter of its magnitude (none if not initialised). */
  std::vector<bool>
  Collapsed(const std::vector<TriangleIndices> & triangles, const std::vector<Vec3> & points) const;
};

/** A fold: two triangles sharing an edge whose normals make more than 120 degrees.
 * Neither needs to have flipped on its own, yet the surface doubles back. */
constexpr double FoldCosine = -0.5;

/** Undo swaps whose triangles intersect other triangles or fold against a
 * neighbour, or that leave their component collapsed (`volumes`, if given), until
 * none does; their edges are added to `refused` (kept sorted) so later sweeps do not
 * try them again. Returns the number of swaps undone. With `tree` (the same one on
 * every call for one mesh), its shape is built once and refitted afterwards
 * (TriangleAABBTree::Refit), which PullBackInvalidMoves shares. */
MeshExtraction_EXPORT std::size_t
                      UndoIntersectingSwaps(const std::vector<Vec3> &     physical,
                                            SurfaceNetTriangles &         mesh,
                                            std::vector<EdgeSwapRecord> & swaps,
                                            std::vector<std::uint64_t> *  refused = nullptr,
                                            TriangleAABBTree *            tree = nullptr,
                                            const ComponentVolumes *      volumes = nullptr);

/** After nodes moved from `start` to `positions` (continuous index), pull back the
 * nodes of triangles that flipped against their orientation at `start`, became
 * degenerate (q_area <= tolerance, measured in millimetres), fold against a
 * neighbour where they did not at `start` (or fold more sharply where they did), or
 * intersect another triangle, and the moved nodes of components that collapsed
 * (`volumes`, if given): halve their move once, then reset it, until no such
 * triangle or component is left. Checks run on the physical positions that will be
 * written (`roundToFloat`). Returns the number of nodes pulled back. `tree`: as for
 * UndoIntersectingSwaps (built once, then refitted); `cache`: kept between the calls
 * for one mesh, so that a check after small moves tests only what may have changed
 * (SelfIntersectionCache; same result). */
MeshExtraction_EXPORT std::size_t
                      PullBackInvalidMoves(LargeBlockVector<Vec3> &       positions,
                                           const LargeBlockVector<Vec3> & start,
                                           const SurfaceNetTriangles &    mesh,
                                           const Vec3 &                   origin,
                                           const Matrix<double, 3, 3> &   indexToPhysical,
                                           double                         degenerateQAreaTolerance,
                                           bool                           roundToFloat = false,
                                           TriangleAABBTree *             tree = nullptr,
                                           SelfIntersectionCache *        cache = nullptr,
                                           const ComponentVolumes *       volumes = nullptr);

} // namespace MeshExtraction
} // namespace itk

#endif
