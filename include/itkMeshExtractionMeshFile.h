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
#ifndef itkMeshExtractionMeshFile_h
#define itkMeshExtractionMeshFile_h

#include "MeshExtractionExport.h"
#include "itkMeshExtractionIndexedTriangleMesh.h"
#include "itkMeshExtractionMeshValidation.h"
#include "itkPolygonCell.h"
#include "itkQuadrilateralCell.h"

#include <cstdint>
#include <limits>
#include <type_traits>
#include <string>
#include <utility>
#include <vector>

namespace itk
{
namespace MeshExtraction
{
/** \brief The surface-mesh file formats the module reads and writes itself.
 *
 * They are parsed by the module (no VTK needed), every count and index checked
 * against the file: a truncated file, an index out of range, a coordinate that is not
 * finite or a header whose counts do not match the data is an itk::ExceptionObject
 * naming the file and the problem, never a crash or a hang.
 *
 * - VTKLegacy: `.vtk`, DATASET POLYDATA, versions 2.0 to 4.2 (POLYGONS n size with a
 *   count before each cell) and 5.1 (OFFSETS and CONNECTIVITY arrays, what VTK 9
 *   writes by default), ASCII and BINARY; VERTICES and LINES are skipped,
 *   TRIANGLE_STRIPS become triangles, POINT_DATA and CELL_DATA are not read.
 * - VTKXMLPolyData: `.vtp`, ascii, binary and appended (raw or base64) data arrays,
 *   UInt32 or UInt64 headers, zlib-compressed or not (VTK's default compressor);
 *   several pieces are joined.
 * - PLY: `.ply`, ASCII and binary of either byte order.
 * - STL: `.stl`, binary and ASCII; the corners of the facets are joined into shared
 *   vertices where their coordinates are equal.
 * - OBJ: `.obj`, `v` and `f` lines (v, v/t, v/t/n and v//n corners, negative
 *   indices); other lines are skipped.
 * - OFF: `.off`, ASCII (OFF, COFF, NOFF headers).
 * \ingroup MeshExtraction
 */
enum class MeshFileFormat : std::uint8_t
{
  Unknown,
  VTKLegacy,
  VTKXMLPolyData,
  PLY,
  STL,
  OBJ,
  OFF
};

/** The format a file name's extension names (case-insensitive), or Unknown. */
MeshExtraction_EXPORT MeshFileFormat
MeshFileFormatFromFileName(const std::string & fileName);

/** "VTK legacy", "VTK XML PolyData", "PLY", "STL", "OBJ", "OFF" (or "unknown"). */
MeshExtraction_EXPORT const char *
MeshFileFormatName(MeshFileFormat format);

/** \brief A surface mesh as mesh files hold it: points and polygons.
 *
 * Polygon p is polygonIndices[polygonOffsets[p]] .. polygonIndices[polygonOffsets[p + 1] - 1];
 * every index is below points.size() and every coordinate is finite (the readers
 * check both).
 * \ingroup MeshExtraction
 */
struct MeshExtraction_EXPORT PolygonMesh
{
  std::vector<Vec3>          points;
  std::vector<std::uint32_t> polygonOffsets{ 0 };
  std::vector<std::uint32_t> polygonIndices;
  /** Vertex and line cells of the file, which are not part of a surface. */
  std::size_t numberOfIgnoredCells{ 0 };
  /** Unsigned integer arrays of values per polygon (e.g. the two labels of each face of a
   * multi-label surface), written by the VTK writers (.vtk as a FIELD of CELL_DATA,
   * .vtp as CellData); the other formats and the readers leave them out. */
  struct CellArray
  {
    std::string                name;
    unsigned int               components{ 1 };
    std::vector<std::uint32_t> values; ///< components x number of polygons
  };
  std::vector<CellArray> cellArrays;

  std::size_t
  NumberOfPolygons() const
  {
    return polygonOffsets.size() - 1;
  }
  std::size_t
  PolygonSize(std::size_t p) const
  {
    return polygonOffsets[p + 1] - polygonOffsets[p];
  }
  const std::uint32_t *
  Polygon(std::size_t p) const
  {
    return polygonIndices.data() + polygonOffsets[p];
  }
  void
  AddPolygon(const std::uint32_t * corners, std::size_t numberOfCorners);
};

/** How WritePolygonMeshFile encodes a file. */
struct MeshFileWriteOptions
{
  enum class Encoding : std::uint8_t
  {
    /** The format's usual one: ASCII for VTK legacy, OBJ and OFF; binary for VTP, PLY
     * and STL. */
    Default,
    ASCII,
    Binary
  };
  enum class VTKLegacyVersion : std::uint8_t
  {
    V4_2, ///< POLYGONS with a count before each cell: read by every VTK and ITK
    V5_1  ///< OFFSETS and CONNECTIVITY arrays: VTK 9's default
  };
  Encoding         encoding{ Encoding::Default };
  VTKLegacyVersion vtkLegacyVersion{ VTKLegacyVersion::V4_2 };
};

/** Reads a mesh file in the format its extension names; an itk::ExceptionObject
 * naming the file for an unknown extension, an unreadable or a malformed file. */
MeshExtraction_EXPORT PolygonMesh
ReadPolygonMeshFile(const std::string & fileName);
/** The same in a given format, whatever the extension. */
MeshExtraction_EXPORT PolygonMesh
ReadPolygonMeshFile(const std::string & fileName, MeshFileFormat format);

/** Writes a mesh in the format the file name's extension names (coordinates in
 * double precision, except binary STL, which holds only single precision); an
 * itk::ExceptionObject naming the file if the extension is unknown, the encoding
 * does not exist for the format (binary OBJ or OFF) or the file cannot be written. */
MeshExtraction_EXPORT void
WritePolygonMeshFile(const std::string &          fileName,
                     const PolygonMesh &          mesh,
                     const MeshFileWriteOptions & options = MeshFileWriteOptions());
/** The same in a given format, whatever the extension. */
MeshExtraction_EXPORT void
WritePolygonMeshFile(const std::string &          fileName,
                     const PolygonMesh &          mesh,
                     MeshFileFormat               format,
                     const MeshFileWriteOptions & options = MeshFileWriteOptions());

/** The triangles of the polygons: triangles as they are, quadrilaterals split along
 * their shorter diagonal (counted in numberOfSplitQuads), larger polygons fanned from
 * their first corner; cellIds holds each triangle's polygon. Polygons of fewer than
 * three corners are counted in numberOfIgnoredCells. */
MeshExtraction_EXPORT IndexedTriangleMesh
TriangulatePolygonMesh(const PolygonMesh & mesh);

/** The triangles of an indexed mesh as polygons. */
MeshExtraction_EXPORT PolygonMesh
MakePolygonMesh(const IndexedTriangleMesh & mesh);

/** Fills an empty itk::Mesh with the points and polygons (point i and cell p get
 * identifiers i and p): triangle, quadrilateral and polygon cells, as ITK's mesh
 * readers make them. */
template <typename TMesh>
void
FillMeshWithPolygons(const PolygonMesh & in, TMesh & mesh)
{
  using PointType = typename TMesh::PointType;
  using CoordinateType = typename PointType::ValueType;
  using CellType = typename TMesh::CellType;
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
  for (std::size_t f = 0; f < in.NumberOfPolygons(); ++f)
  {
    const std::size_t                  n = in.PolygonSize(f);
    typename CellType::CellAutoPointer cell;
    if (n == 3)
    {
      cell.TakeOwnership(new TriangleCell<CellType>);
    }
    else if (n == 4)
    {
      cell.TakeOwnership(new QuadrilateralCell<CellType>);
    }
    else
    {
      cell.TakeOwnership(new PolygonCell<CellType>(static_cast<unsigned int>(n)));
    }
    for (std::size_t k = 0; k < n; ++k)
    {
      cell->SetPointId(static_cast<int>(k), in.Polygon(f)[k]);
    }
    mesh.SetCell(static_cast<typename TMesh::CellIdentifier>(f), cell);
  }
}

/** An itk::ExceptionObject naming `what`, the point and the value if a coordinate's
 * magnitude exceeds `limit` (the largest value of the mesh's coordinate type, named
 * `typeName`): such a point would become infinite there. */
MeshExtraction_EXPORT void
RequireCoordinatesWithin(const PolygonMesh & polygons, double limit, const char * typeName, const std::string & what);

/** \brief Fills an empty itk::Mesh with the polygons as they are, or an empty
 * itk::QuadEdgeMesh with their triangles (TriangulatePolygonMesh), refused with the
 * reasons, before any face is added, unless they are manifold and consistently
 * oriented (RequireQuadEdgeMeshTriangles; `what` names the mesh in that message).
 * Coordinates beyond the range of the mesh's coordinate type (1e40 for float points)
 * are refused too (RequireCoordinatesWithin).
 * \ingroup MeshExtraction
 */
template <typename TMesh>
void
FillSurfaceMesh(const PolygonMesh & polygons, TMesh & mesh, const std::string & what)
{
  using CoordinateType = typename TMesh::PointType::ValueType;
  RequireCoordinatesWithin(polygons,
                           static_cast<double>(std::numeric_limits<CoordinateType>::max()),
                           std::is_same_v<CoordinateType, float> ? "float" : "double",
                           what);
  if constexpr (detail::IsQuadEdgeMesh<TMesh>::value)
  {
    const IndexedTriangleMesh triangles = TriangulatePolygonMesh(polygons);
    RequireQuadEdgeMeshTriangles(triangles, what);
    FillMesh(triangles, mesh);
  }
  else
  {
    FillMeshWithPolygons(polygons, mesh);
  }
}

/** \brief Reads a surface mesh file into an itk::Mesh (as polygons) or an
 * itk::QuadEdgeMesh (triangulated; FillSurfaceMesh).
 *
 * Formats: those of MeshFileFormat. Coordinates are taken as they are (physical
 * millimetres for the module's meshes).
 * \ingroup MeshExtraction
 */
template <typename TMesh>
typename TMesh::Pointer
ReadSurfaceMeshFile(const std::string & fileName)
{
  auto mesh = TMesh::New();
  FillSurfaceMesh(ReadPolygonMeshFile(fileName), *mesh, "'" + fileName + "'");
  return mesh;
}

/** The points and faces of an itk::Mesh or itk::QuadEdgeMesh as polygons: triangles,
 * quadrilaterals and larger faces as they are (points compacted in the order of the
 * point container); vertex and line cells (a QuadEdgeMesh's edges) are counted in
 * numberOfIgnoredCells. A cell naming a point the mesh has not is an
 * itk::ExceptionObject. */
template <typename TMesh>
PolygonMesh
MakePolygonMeshFromMesh(const TMesh & mesh)
{
  PolygonMesh  out;
  const auto * points = mesh.GetPoints();
  const auto * cells = mesh.GetCells();
  if (points == nullptr || points->Size() == 0 || cells == nullptr)
  {
    return out;
  }
  IndexedTriangleMesh              copy;
  const detail::PointIdentifierMap map = detail::CopyPoints(*points, copy);
  out.points = std::move(copy.points);
  std::vector<std::uint32_t> corners;
  for (auto it = cells->Begin(); it != cells->End(); ++it)
  {
    const auto * cell = it.Value();
    if (cell == nullptr || cell->GetNumberOfPoints() < 3)
    {
      out.numberOfIgnoredCells += cell == nullptr ? 0 : 1;
      continue;
    }
    corners.clear();
    for (auto p = cell->PointIdsBegin(); p != cell->PointIdsEnd(); ++p)
    {
      corners.push_back(map.IndexOf(*p, it.Index()));
    }
    out.AddPolygon(corners.data(), corners.size());
  }
  return out;
}

/** \brief Writes the faces of an itk::Mesh or itk::QuadEdgeMesh (a QuadEdgeMesh's edge
 * cells left out) in the format the file name's extension names: quadrilaterals and
 * larger polygons as they are, except in STL, which holds only triangles (there they
 * are split as TriangulatePolygonMesh splits them).
 * \ingroup MeshExtraction
 */
template <typename TMesh>
void
WriteSurfaceMeshFile(const TMesh &                mesh,
                     const std::string &          fileName,
                     const MeshFileWriteOptions & options = MeshFileWriteOptions())
{
  WritePolygonMeshFile(fileName, MakePolygonMeshFromMesh(mesh), options);
}

} // namespace MeshExtraction
} // namespace itk

#endif
