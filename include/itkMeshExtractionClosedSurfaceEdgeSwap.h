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
#ifndef itkMeshExtractionClosedSurfaceEdgeSwap_h
#define itkMeshExtractionClosedSurfaceEdgeSwap_h

#include "MeshExtractionExport.h"
#include "itkMeshExtractionEdgeSwapCriteria.h"
#include "itkMeshExtractionIndexedTriangleMesh.h"
#include "itkMeshExtractionSurfaceNets.h"
#include "itkMeshExtractionValidityGuard.h"

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
/** \file
 * \brief The swap engine on an indexed closed surface: the high-quality SurfaceNets
 * mode's (SurfaceNetsHighQuality) and the scale-space refinement's on closed meshes.
 *
 * SwapEdges() makes one sweep of swaps over SurfaceNetTriangles (half-edges with their
 * twins) with the decision of EvaluateEdgeSwap(); the validity guard's
 * UndoIntersectingSwaps() then undoes, one by one, the swaps that left the surface
 * invalid (itkMeshExtractionValidityGuard.h).
 *
 * Why two swap engines: EdgeSwapQuadEdgeMeshFilter's passes
 * (itkMeshExtractionEdgeSwapPasses.h) and this engine both swap on flat arrays and take
 * the same decision (itkMeshExtractionEdgeSwapCriteria.h), but they cannot be one engine:
 * - the filter takes any triangle QuadEdgeMesh, with boundaries;
 * - this engine needs a closed 2-manifold (every half-edge has a twin), and lets a
 *   triangle take part in one swap per sweep, so that the guard can undo each swap on
 *   its own, in place, while the nodes keep moving between sweeps. The filter's pass
 *   judges every edge on the mesh that the earlier swaps of the pass left (a triangle
 *   may be swapped again), so one swap cannot be taken back without the ones after it:
 *   its guard locks the corners of crossing triangles and swaps again from its input.
 * The two sweep orders differ too (edges by point identifiers there, half-edges by
 * triangle index here), so one engine serving both would change the meshes of one of
 * them.
 * \ingroup MeshExtraction
 */

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

} // namespace detail
} // namespace MeshExtraction
} // namespace itk

#endif
