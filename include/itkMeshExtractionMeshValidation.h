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
#ifndef itkMeshExtractionMeshValidation_h
#define itkMeshExtractionMeshValidation_h

#include "MeshExtractionExport.h"
#include "itkMeshExtractionIndexedTriangleMesh.h"

#include <string>

namespace itk
{
namespace MeshExtraction
{
/** \brief What keeps a triangle mesh from being a 2-manifold, consistently oriented
 * surface (open or closed): what a QuadEdgeMesh can hold and the module's mesh
 * filters need.
 *
 * Each count comes with its first example (the lowest index), for messages.
 * \ingroup MeshExtraction
 */
struct MeshExtraction_EXPORT TriangleMeshDefects
{
  static constexpr std::uint64_t None = std::numeric_limits<std::uint64_t>::max();

  std::size_t   numberOfNonFinitePoints{ 0 }; ///< a coordinate NaN or infinite
  std::uint64_t firstNonFinitePoint{ None };
  std::size_t   numberOfIndicesOutOfRange{ 0 }; ///< triangle corners naming no point
  std::uint64_t firstTriangleOutOfRange{ None };
  std::size_t   numberOfRepeatedCorners{ 0 }; ///< triangles naming one point twice
  std::uint64_t firstRepeatedCorner{ None };
  std::size_t   numberOfNonManifoldEdges{ 0 }; ///< edges of more than two triangles
  std::uint64_t firstNonManifoldEdge[2]{ None, None };
  std::size_t   numberOfInconsistentEdges{ 0 }; ///< two triangles running an edge the same way
  std::uint64_t firstInconsistentEdge[2]{ None, None };
  std::size_t   numberOfNonManifoldVertices{ 0 }; ///< triangles forming two or more fans
  std::uint64_t firstNonManifoldVertex{ None };

  bool
  Any() const;

  /** The defects in words, e.g. "1 non-manifold vertex (point 7 at [1, 1, 1]: its
   * triangles form separate fans that meet only there)"; empty without defects. */
  std::string
  Describe(const IndexedTriangleMesh & mesh) const;
};

/** Finds the defects of a triangle mesh. The topological ones (edges, vertices) are
 * looked for only when every index is in range and no triangle repeats a corner. */
MeshExtraction_EXPORT TriangleMeshDefects
FindTriangleMeshDefects(const IndexedTriangleMesh & mesh);

/** An itk::ExceptionObject "<what> is not a manifold, consistently oriented triangle
 * mesh: <defects>" unless the mesh can be put into a QuadEdgeMesh (FillMesh) safely:
 * ITK's QuadEdgeMesh crashes on some non-manifold vertices and drops other faces. */
MeshExtraction_EXPORT void
RequireQuadEdgeMeshTriangles(const IndexedTriangleMesh & mesh, const std::string & what);

} // namespace MeshExtraction
} // namespace itk

#endif
