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
#ifndef itkMeshExtractionMeshConversion_h
#define itkMeshExtractionMeshConversion_h

#include "MeshExtractionExport.h"
#include "itkMeshExtractionTriangleGeometry.h"
#include "itkCommonEnums.h"
#include "itkIntTypes.h"
#include "itkMacro.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <unordered_map>
#include <vector>

namespace itk
{
namespace MeshExtraction
{
struct IndexedTriangleMesh;

namespace detail
{
/** \file
 * The steps of MakeIndexedTriangleMesh and FillMesh (itkMeshExtractionIndexedTriangleMesh.h):
 * the point identifier map, the copy of the points and of one cell. The output mesh
 * is a template parameter (TIndexedTriangleMesh, an IndexedTriangleMesh) so that this
 * header needs only its declaration. */

/** Split a quad (a, b, c, d) of `mesh` along its shorter diagonal into two triangles
 * (TriangleIndices). */
MeshExtraction_EXPORT void
SplitQuad(const IndexedTriangleMesh &    mesh,
          const std::uint32_t            q[4],
          std::array<std::uint32_t, 3> & t0,
          std::array<std::uint32_t, 3> & t1);

template <typename T, typename = void>
struct IsQuadEdgeMesh : std::false_type
{};
template <typename T>
struct IsQuadEdgeMesh<T, std::void_t<typename T::QEPrimal>> : std::true_type
{};

/** Source point identifier -> index of the point in an IndexedTriangleMesh: a table
 * where the identifiers are compact (the largest below 4 per point plus 1024), else
 * a hash map. Insert and IndexOf stay inline: they run once per point and once per
 * corner of every cell. */
class MeshExtraction_EXPORT PointIdentifierMap
{
public:
  static constexpr std::uint32_t Missing = std::numeric_limits<std::uint32_t>::max();

  PointIdentifierMap(IdentifierType maximumIdentifier, std::size_t numberOfPoints);

  void
  Insert(IdentifierType id, std::uint32_t index)
  {
    if (m_Dense)
    {
      m_Table[id] = index;
    }
    else
    {
      m_Hash.emplace(id, index);
    }
  }

  /** The index of point `id`; an itk::ExceptionObject naming cell `cellId` if the
   * mesh has no such point. */
  std::uint32_t
  IndexOf(IdentifierType id, IdentifierType cellId) const
  {
    std::uint32_t index = Missing;
    if (m_Dense)
    {
      if (id <= m_MaximumIdentifier)
      {
        index = m_Table[id];
      }
    }
    else
    {
      const auto found = m_Hash.find(id);
      if (found != m_Hash.end())
      {
        index = found->second;
      }
    }
    if (index == Missing)
    {
      ThrowMissingPoint(id, cellId);
    }
    return index;
  }

private:
  [[noreturn]] static void
  ThrowMissingPoint(IdentifierType id, IdentifierType cellId);

  IdentifierType                                    m_MaximumIdentifier;
  bool                                              m_Dense;
  std::vector<std::uint32_t>                        m_Table;
  std::unordered_map<IdentifierType, std::uint32_t> m_Hash;
};

/** Appends the points of a mesh's point container to `out` (points and pointIds, in
 * container order) and returns the map from their identifiers to their indices. */
template <typename TPointsContainer, typename TIndexedTriangleMesh>
PointIdentifierMap
CopyPoints(const TPointsContainer & points, TIndexedTriangleMesh & out)
{
  if (points.Size() >= std::numeric_limits<std::uint32_t>::max())
  {
    itkGenericExceptionMacro("MeshExtraction: mesh has " << points.Size()
                                                         << " points, more than the supported 2^32 - 1.");
  }
  out.points.reserve(points.Size());
  out.pointIds.reserve(points.Size());
  IdentifierType maxId = 0;
  for (auto it = points.Begin(); it != points.End(); ++it)
  {
    maxId = std::max<IdentifierType>(maxId, it.Index());
  }
  PointIdentifierMap map(maxId, points.Size());
  for (auto it = points.Begin(); it != points.End(); ++it)
  {
    map.Insert(it.Index(), static_cast<std::uint32_t>(out.points.size()));
    out.points.push_back(ToVec3(it.Value()));
    out.pointIds.push_back(it.Index());
  }
  return map;
}

/** Appends cell `cellId` to `out`: a triangle as it is, a quadrilateral split along
 * its shorter diagonal, a vertex or line cell only counted; any other polygon raises
 * an itk::ExceptionObject. */
template <typename TCell, typename TIndexedTriangleMesh>
void
AppendCell(const TCell & cell, IdentifierType cellId, const PointIdentifierMap & map, TIndexedTriangleMesh & out)
{
  const auto type = cell.GetType();
  if (type == CellGeometryEnum::VERTEX_CELL || type == CellGeometryEnum::LINE_CELL ||
      type == CellGeometryEnum::QUADRATIC_EDGE_CELL)
  {
    ++out.numberOfIgnoredCells;
    return;
  }
  const auto n = cell.GetNumberOfPoints();
  if (n != 3 && n != 4)
  {
    itkGenericExceptionMacro("MeshExtraction: cell " << cellId << " is a polygon with " << n
                                                     << " points; only triangles and quadrilaterals "
                                                        "(split along the shorter diagonal) are measured.");
  }
  std::uint32_t ids[4];
  unsigned int  k = 0;
  for (auto p = cell.PointIdsBegin(); p != cell.PointIdsEnd() && k < 4; ++p)
  {
    ids[k++] = map.IndexOf(*p, cellId);
  }
  if (n == 3)
  {
    out.triangles.push_back({ ids[0], ids[1], ids[2] });
    out.cellIds.push_back(cellId);
    return;
  }
  std::array<std::uint32_t, 3> t0;
  std::array<std::uint32_t, 3> t1;
  SplitQuad(out, ids, t0, t1);
  out.triangles.push_back(t0);
  out.triangles.push_back(t1);
  out.cellIds.push_back(cellId);
  out.cellIds.push_back(cellId);
  ++out.numberOfSplitQuads;
}

} // namespace detail
} // namespace MeshExtraction
} // namespace itk

#endif
