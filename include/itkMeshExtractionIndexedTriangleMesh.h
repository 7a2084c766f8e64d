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
#ifndef itkMeshExtractionIndexedTriangleMesh_h
#define itkMeshExtractionIndexedTriangleMesh_h

#include "MeshExtractionExport.h"
#include "itkMeshExtractionMeshConversion.h"
#include "itkMeshExtractionTriangleGeometry.h"
#include "itkCellInterface.h"
#include "itkCommonEnums.h"
#include "itkTriangleCell.h"
#include "itkMacro.h"

#include <array>
#include <cstdint>
#include <vector>

namespace itk
{
namespace MeshExtraction
{
using TriangleIndices = std::array<std::uint32_t, 3>;

/** \brief A triangle mesh as flat arrays: the common input of the calculators.
 *
 * Points are compacted to 0..N-1 in the order of the mesh's point container;
 * `pointIds` and `cellIds` map back to the identifiers of the source mesh.
 * \ingroup MeshExtraction
 */
struct IndexedTriangleMesh
{
  std::vector<Vec3>            points;
  std::vector<TriangleIndices> triangles;
  std::vector<IdentifierType>  pointIds; ///< source point identifier of each point
  std::vector<IdentifierType>  cellIds;  ///< source cell identifier of each triangle
  std::size_t                  numberOfSplitQuads{ 0 };
  std::size_t                  numberOfIgnoredCells{ 0 }; ///< vertex and line cells (QuadEdgeMesh edges)
};

/** \brief Edges and incidences of an indexed triangle mesh.
 *
 * Built once by sorting the 3F half-edges; everything the integrity checks need
 * (boundary, non-manifold and inconsistently oriented edges, valences, fans around
 * vertices, components) is derived from it.
 * \ingroup MeshExtraction
 */
struct MeshTopology
{
  struct Edge
  {
    std::uint32_t a; ///< smaller vertex index
    std::uint32_t b; ///< larger vertex index
    std::uint32_t firstIncidence;
    std::uint32_t numberOfIncidences; ///< number of triangles using the edge
  };
  /** A triangle using an edge, and whether it runs the edge from a to b. */
  struct Incidence
  {
    std::uint32_t triangle;
    bool          forward;
  };
  std::vector<Edge>      edges;
  std::vector<Incidence> incidences;
  /** Edge of each triangle side: side k joins corners k and k+1. */
  std::vector<std::array<std::uint32_t, 3>> triangleEdges;
  /** Vertex -> incident triangles (compressed rows). */
  std::vector<std::uint32_t> vertexTriangleOffsets;
  std::vector<std::uint32_t> vertexTriangles;
  /** Vertex -> incident edges (compressed rows). */
  std::vector<std::uint32_t> vertexEdgeOffsets;
  std::vector<std::uint32_t> vertexEdges;

  std::size_t                numberOfReferencedVertices{ 0 };
  std::size_t                numberOfBoundaryEdges{ 0 };
  std::size_t                numberOfNonManifoldEdges{ 0 };
  std::size_t                numberOfInconsistentEdges{ 0 }; ///< two triangles running the edge the same way
  std::size_t                numberOfNonManifoldVertices{ 0 };
  std::size_t                numberOfComponents{ 0 };
  std::size_t                numberOfBoundaryLoops{ 0 };
  std::vector<std::uint32_t> triangleComponent;      ///< component of each triangle
  std::vector<bool>          vertexIsInterior;       ///< referenced, manifold, not on a boundary
  std::vector<bool>          vertexIsNonManifold;    ///< its triangles form more than one fan
  std::vector<std::uint32_t> componentBoundaryLoops; ///< boundary loops per component

  /** The other triangle on the side of a manifold edge, or -1 (max uint32). */
  std::uint32_t
  Neighbor(std::uint32_t triangle, unsigned int side) const;
};

/** Build the topology of an indexed triangle mesh (O(F log F), deterministic). */
MeshExtraction_EXPORT MeshTopology
BuildMeshTopology(const IndexedTriangleMesh & mesh);

/** Copy an itk::Mesh or itk::QuadEdgeMesh into flat arrays.
 *
 * Triangles are kept; quadrilaterals are split along their shorter diagonal and
 * counted in numberOfSplitQuads; vertex and line cells (a QuadEdgeMesh stores its
 * edges as line cells) are skipped; any other polygon raises an
 * itk::ExceptionObject naming the cell and its number of points, as do cells that
 * reference missing points. */
template <typename TMesh>
IndexedTriangleMesh
MakeIndexedTriangleMesh(const TMesh & mesh)
{
  IndexedTriangleMesh out;
  const auto *        points = mesh.GetPoints();
  if (points == nullptr || points->Size() == 0)
  {
    return out;
  }
  const detail::PointIdentifierMap map = detail::CopyPoints(*points, out);
  const auto *                     cells = mesh.GetCells();
  if (cells == nullptr)
  {
    return out;
  }
  out.triangles.reserve(cells->Size());
  out.cellIds.reserve(cells->Size());
  for (auto it = cells->Begin(); it != cells->End(); ++it)
  {
    if (it.Value() != nullptr)
    {
      detail::AppendCell(*it.Value(), it.Index(), map, out);
    }
  }
  return out;
}

/** Fill an empty itk::Mesh or itk::QuadEdgeMesh with the points and triangles of an
 * indexed mesh (point i gets identifier i). For a QuadEdgeMesh, a triangle the
 * quad-edge structure refuses (non-manifold edge, inconsistent orientation) raises
 * an itk::ExceptionObject instead of being dropped silently. */
template <typename TMesh>
void
FillMesh(const IndexedTriangleMesh & in, TMesh & mesh)
{
  using PointType = typename TMesh::PointType;
  using CoordinateType = typename PointType::ValueType;
  mesh.GetPoints()->Reserve(in.points.size());
  for (std::size_t i = 0; i < in.points.size(); ++i)
  {
    PointType p;
    for (unsigned int d = 0; d < 3; ++d)
    {
      p[d] = static_cast<CoordinateType>(in.points[i][d]);
    }
    mesh.SetPoint(static_cast<typename TMesh::PointIdentifier>(i), p);
  }
  if constexpr (detail::IsQuadEdgeMesh<TMesh>::value)
  {
    for (std::size_t f = 0; f < in.triangles.size(); ++f)
    {
      const auto & t = in.triangles[f];
      if (mesh.AddFaceTriangle(t[0], t[1], t[2]) == nullptr)
      {
        itkGenericExceptionMacro("MeshExtraction: the QuadEdgeMesh refused triangle "
                                 << f << " (" << t[0] << ", " << t[1] << ", " << t[2]
                                 << "): it would make a non-manifold edge, reuse an edge in the same "
                                    "direction, or repeat a vertex.");
      }
    }
  }
  else
  {
    using CellType = typename TMesh::CellType;
    using TriangleCellType = TriangleCell<CellType>;
    for (std::size_t f = 0; f < in.triangles.size(); ++f)
    {
      typename CellType::CellAutoPointer cell;
      cell.TakeOwnership(new TriangleCellType);
      for (unsigned int k = 0; k < 3; ++k)
      {
        cell->SetPointId(k, in.triangles[f][k]);
      }
      mesh.SetCell(static_cast<typename TMesh::CellIdentifier>(f), cell);
    }
  }
}

} // namespace MeshExtraction
} // namespace itk

#endif
