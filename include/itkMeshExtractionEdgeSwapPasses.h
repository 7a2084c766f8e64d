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
#ifndef itkMeshExtractionEdgeSwapPasses_h
#define itkMeshExtractionEdgeSwapPasses_h

#include "MeshExtractionExport.h"
#include "itkMeshExtractionEdgeSwapCriteria.h"
#include "itkMeshExtractionIndexedTriangleMesh.h"

#include <cstdint>
#include <functional>
#include <vector>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
/** \file
 * \brief EdgeSwapQuadEdgeMeshFilter's passes, made on flat arrays.
 *
 * A pass visits the edges that the mesh has when it starts, ordered by their
 * (smaller, larger) point identifiers, and judges each on the mesh that the earlier
 * swaps of the pass left: an edge swapped away is skipped, one that a swap made again
 * is judged, a triangle may be swapped more than once. The quad of edge (a, b), a the
 * smaller identifier, has c on the left of a -> b and d on its right; valences are
 * counted when the pass starts and updated by each swap; a corner is on a boundary if
 * one of its edges has a triangle on one side only. These are the rules by which the
 * filter swapped on the QuadEdgeMesh itself with ITK's Euler operator; on arrays
 * (half-edges with their twins, an edge index per half-edge) a pass takes a fraction of
 * the time and no memory per swap, and the filter builds its output mesh once.
 *
 * The mesh may have boundaries and must be a consistently oriented triangle mesh in
 * which every edge has at most two triangles (what a QuadEdgeMesh holds).
 * \ingroup MeshExtraction
 */

/** What the passes did. */
struct EdgeSwapPassCounts
{
  std::size_t swaps{ 0 };
  /** Swaps that improve the criterion but fail a check (EdgeSwapVerdict other than Swap). */
  std::size_t refused{ 0 };
  int         passes{ 0 };
};

/** Swaps edges of `mesh` in place, pass after pass, until a pass swaps nothing or
 * `maximumNumberOfPasses` are made. `locked` (one flag per point, or empty) marks the
 * points around which no edge is swapped. `afterPass` (optional) is called with the
 * number of passes made. Throws an itk::ExceptionObject if an edge has more than two
 * triangles or two triangles that run it in the same direction. */
MeshExtraction_EXPORT EdgeSwapPassCounts
SwapEdgesInPasses(IndexedTriangleMesh &              mesh,
                  const EdgeSwapParameters &         parameters,
                  const std::vector<std::uint8_t> &  locked,
                  int                                maximumNumberOfPasses,
                  const std::function<void(int)> &   afterPass = {});

} // namespace detail
} // namespace MeshExtraction
} // namespace itk

#endif
