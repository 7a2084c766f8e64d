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
#ifndef itkMeshExtractionSurfaceNet_h
#define itkMeshExtractionSurfaceNet_h

#include "MeshExtractionExport.h"
#include "itkMeshExtractionLargeBlockVector.h"
#include "itkMeshExtractionTriangleGeometry.h"

#include <array>
#include <cstddef>
#include <cstdint>

namespace itk
{
namespace MeshExtraction
{
/** A surface cell: the lower-corner voxel index of the cell (each in [-1, N-1])
 * and its configuration. */
struct SurfaceCell
{
  std::int32_t  x;
  std::int32_t  y;
  std::int32_t  z;
  std::uint8_t  configuration;
  std::uint8_t  faceRules{ 0 }; ///< bit f: ambiguous face f cuts off its outside corners
  std::uint32_t firstNode{ 0 };
};

/** \brief The SurfaceNet: nodes in continuous index space, each constrained to a
 * box inside its cell, and the quadrilaterals that join them (one per voxel edge
 * that crosses the surface, counter-clockwise seen from outside).
 * \ingroup MeshExtraction
 */
struct MeshExtraction_EXPORT SurfaceNet
{
  std::array<std::int64_t, 3>     size{ { 0, 0, 0 } }; ///< image size in voxels
  LargeBlockVector<SurfaceCell>   cells;               ///< sorted by (z, y, x)
  LargeBlockVector<std::uint32_t> rowStart;            ///< cells of cell-row (y, z): [rowStart[r], rowStart[r+1])

  LargeBlockVector<Vec3>                         positions; ///< node positions, continuous index
  LargeBlockVector<Vec3>                         boxLower;  ///< node constraint box, continuous index
  LargeBlockVector<Vec3>                         boxUpper;
  LargeBlockVector<std::uint32_t>                nodeCell; ///< cell of each node
  LargeBlockVector<std::array<std::uint32_t, 4>> quads;
  LargeBlockVector<std::uint8_t>                 quadAxis; ///< axis of the crossing voxel edge, +4 if outward is -axis
  LargeBlockVector<std::uint32_t>                neighborStart; ///< node links (the quads' edges): compressed rows
  LargeBlockVector<std::uint32_t>                neighbors;
  std::size_t                                    numberOfSplitCells{ 0 };

  /** The row of cells at (y, z), y and z in [-1, N-1]: its cells are
   * [rowStart[row], rowStart[row + 1]). */
  std::int64_t
  RowOf(std::int64_t y, std::int64_t z) const
  {
    return (z + 1) * (size[1] + 1) + (y + 1);
  }

  /** Index of the surface cell with lower corner (x, y, z), or -1. */
  std::int64_t
  FindCell(std::int64_t x, std::int64_t y, std::int64_t z) const;
};

} // namespace MeshExtraction
} // namespace itk

#endif
