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
#ifndef itkMeshExtractionSelfIntersections_h
#define itkMeshExtractionSelfIntersections_h

#include "MeshExtractionExport.h"
#include "itkMeshExtractionIndexedTriangleMesh.h"
#include "itkMeshExtractionLargeBlockVector.h"

#include <cstddef>
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
 * \brief Pairs of faces of a mesh that intersect away from their shared vertices and
 * edge: exact predicates (FacesIntersect) on the pairs whose boxes overlap in an AABB
 * tree, over the whole mesh, for some query faces, or incrementally with a cache.
 * \ingroup MeshExtraction
 */

/** FacesIntersect for faces f and g of `mesh`. */
MeshExtraction_EXPORT bool
MeshFacesIntersect(const IndexedTriangleMesh & mesh, std::uint32_t f, std::uint32_t g);

/** Face f of `mesh` has three distinct vertices and is not exactly degenerate: the
 * faces the self-intersection searches consider. */
MeshExtraction_EXPORT bool
MeshFaceIsProper(const IndexedTriangleMesh & mesh, std::uint32_t f);

/** The face pairs that the blocks of a parallel search found, in one sorted list. */
MeshExtraction_EXPORT std::vector<std::pair<std::uint32_t, std::uint32_t>>
                      SortedPairs(const std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>> & found);

/** Pairs (i < j) of non-degenerate faces that intersect away from their shared
 * vertices and edge, sorted. With `queries`, only pairs that include one of
 * those triangles are sought (e.g. the faces that moved since the last check). */
MeshExtraction_EXPORT std::vector<std::pair<std::uint32_t, std::uint32_t>>
FindSelfIntersections(const IndexedTriangleMesh & mesh, const std::vector<std::uint32_t> * queries = nullptr);

class TriangleAABBTree;

/** What a search over most of a mesh's faces (FindSelfIntersections with a tree and
 * a cache) keeps for the next search on the same mesh, after its vertices moved a
 * little and a few faces changed vertices (as relaxation and edge swaps do).
 *
 * The caller sets `margin` (> 0, in the mesh's units) and builds the tree with boxes
 * that contain each face's own box grown by margin / 2 on every side. A full search
 * (a "rebuild") keeps the points and faces, and the pairs of faces without a common
 * vertex whose grown boxes overlap ("near pairs"). A later search calls a face
 * "moved" if it changed vertices or one of its vertices is 0.45 margin or more from
 * where it was. Two faces that did not move were more than a margin apart at the
 * rebuild unless they are a near pair, and each moved less than half of it, so they
 * cannot meet now: only near pairs, faces that meet at a vertex whose fan is not
 * certified now (CertifyFan), and pairs with a moved face (one tree query per moved
 * face) are tested. The pairs found are exactly those of the full search. When more
 * than a quarter of the faces moved, or the margin changed, the search is a rebuild
 * again. */
struct SelfIntersectionCache
{
  double margin{ 0.0 };
  double marginOfNearPairs{ 0.0 }; ///< the margin of the last rebuild

  LargeBlockVector<Vec3>                                            points;
  LargeBlockVector<TriangleIndices>                                 triangles;
  std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>> nearPairs; ///< in blocks
  std::size_t                                                       numberOfRebuilds{ 0 };
  std::size_t                                                       numberOfIncrementalSearches{ 0 };
};

/** The same, with a tree built by the caller over all triangles with boxes that
 * contain the triangles' current positions (see TriangleAABBTree::Build): repeated
 * checks while vertices move inside those boxes need no rebuild. With `cache` (the
 * same one on every call for one mesh), a search over more than a quarter of the
 * faces tests only what may have changed since the last full one
 * (SelfIntersectionCache); the result is the same. */
MeshExtraction_EXPORT std::vector<std::pair<std::uint32_t, std::uint32_t>>
                      FindSelfIntersections(const IndexedTriangleMesh &        mesh,
                                            const std::vector<std::uint32_t> & queries,
                                            const TriangleAABBTree &           tree,
                                            SelfIntersectionCache *            cache = nullptr);

} // namespace detail
} // namespace MeshExtraction
} // namespace itk

#endif
