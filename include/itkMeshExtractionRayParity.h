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
#ifndef itkMeshExtractionRayParity_h
#define itkMeshExtractionRayParity_h

#include "MeshExtractionExport.h"
#include "itkMeshExtractionIndexedTriangleMesh.h"

#include <cstdint>
#include <vector>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
/** \file
 * \brief Which side a closed surface's triangles face, and which components lie inside
 * which, by the parity of the crossings of rays with the surface (an AABB tree of the
 * triangles, ray-triangle tests that flag grazing hits, retried along other rays).
 * \ingroup MeshExtraction
 */

/** Orientation of every closed-surface triangle by ray-crossing parity: +1 if its
 * normal points out of the enclosed volume, -1 if into it, 0 if undetermined
 * (every ray tried grazed an edge or vertex) or degenerate. */
MeshExtraction_EXPORT std::vector<int>
ClassifyTriangleOrientation(const IndexedTriangleMesh & mesh, double degenerateQAreaTolerance = 1e-6);

/** For every component of `mesh` (numbered as in `topology`), the vertex its nesting
 * rays start from (ComponentNestingParity): the first vertex of its first triangle;
 * UINT32_MAX for a component without triangles. */
MeshExtraction_EXPORT std::vector<std::uint32_t>
                      ComponentRayVertices(const IndexedTriangleMesh & mesh, const MeshTopology & topology);

/** For every component of `mesh` (numbered as in `topology`), whether it lies inside
 * an odd (1) or even (0) number of the other components: the parity of the crossings
 * of a ray from its ComponentRayVertices vertex with the other components' triangles; -1 if the
 * component has a boundary or every ray tried grazed an edge or vertex. A component
 * the rest of the surface swept over (a surface moving past a small piece in one
 * step, leaving no intersection behind) changes its parity, and with it whether its
 * triangles face out. Empty if the mesh has fewer than two components. */
MeshExtraction_EXPORT std::vector<std::int8_t>
                      ComponentNestingParity(const IndexedTriangleMesh & mesh, const MeshTopology & topology);

} // namespace detail
} // namespace MeshExtraction
} // namespace itk

#endif
