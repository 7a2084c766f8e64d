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
#ifndef itkMeshExtractionSurfaceNets_h
#define itkMeshExtractionSurfaceNets_h

#include "MeshExtractionExport.h"
#include "itkMeshExtractionLargeBlockVector.h"
#include "itkMeshExtractionSurfaceNet.h"
#include "itkMeshExtractionTriangleGeometry.h"
#include "itkMatrix.h"

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
/** \brief The SurfaceNets cell: corner, edge and face numbering and, for each of
 * the 256 inside/outside configurations, its surface sheets.
 *
 * A cell is the cube between 8 neighbouring voxel centres; corner k sits at
 * offset (k & 1, (k >> 1) & 1, (k >> 2) & 1) and bit k of the configuration is set
 * when that voxel is inside. Edge 4a + ob + 2oc runs along axis a at offsets ob,
 * oc on the two following axes b = a+1, c = a+2 (mod 3). Face 2f + s is the face
 * at offset s along axis f, its corners and edges listed in cyclic order.
 *
 * A sheet is one loop of the surface on the cell's faces; each becomes one node of
 * the net. On an ambiguous face (inside corners on a diagonal, four crossing
 * edges) the two surface segments either cut off the two inside corners
 * (separate, the default: a 6-connected object) or the two outside corners (the
 * face's bit set in `faceRules`). Both cells sharing a face use the same rule, so
 * the loops are consistent; BuildSurfaceNet flips a face's rule where its two
 * segments would otherwise join the same pair of nodes twice, which keeps the
 * net a 2-manifold.
 * \ingroup MeshExtraction
 */
struct MeshExtraction_EXPORT SurfaceNetsCellTable
{
  std::array<std::array<std::uint8_t, 2>, 12> edgeCorners; ///< corners at the low and high end of each edge
  std::array<std::array<std::uint8_t, 4>, 6>  faceCorners;
  std::array<std::array<std::uint8_t, 4>, 6>  faceEdges;      ///< faceEdges[f][i] joins faceCorners[f][i] and [i+1]
  std::array<std::uint8_t, 256>               ambiguousFaces; ///< bit f: face f has four crossing edges

  std::uint8_t
  NumberOfSheets(std::uint8_t configuration, std::uint8_t faceRules) const
  {
    return m_NumberOfSheets[configuration * 64u + faceRules];
  }
  /** The sheet of a crossing edge, -1 for an edge that does not cross the surface. */
  std::int8_t
  SheetOfEdge(std::uint8_t configuration, std::uint8_t faceRules, unsigned int edge) const
  {
    return m_SheetOfEdge[configuration * 64u + faceRules][edge];
  }

  /** The centre of the midpoints of the edges in `edges` (bit e: edge e, at least one),
   * in the cell's local coordinates: where a node of those edges keeps apart from the
   * cell's other nodes. */
  Vec3
  CentreOfEdges(unsigned int edges) const;

  static const SurfaceNetsCellTable &
  Get();

private:
  SurfaceNetsCellTable();
  std::vector<std::uint8_t>                m_NumberOfSheets;
  std::vector<std::array<std::int8_t, 12>> m_SheetOfEdge;
};

/** The voxel index of corner k of `cell` (bit 0 of k: +x, bit 1: +y, bit 2: +z), in
 * 64-bit signed arithmetic: a cell at -1 has its first corners at -1, outside the
 * image (with the 32-bit coordinate and an unsigned bit, -1 came out as 2^32 - 1). */
inline std::array<std::int64_t, 3>
CornerVoxel(const SurfaceCell & cell, unsigned int k)
{
  return { std::int64_t{ cell.x } + (k & 1u),
           std::int64_t{ cell.y } + ((k >> 1) & 1u),
           std::int64_t{ cell.z } + ((k >> 2) & 1u) };
}

/** Turn the surface cells of an image (sorted by z, y, x) into a net: one node
 * per sheet, the quads, the links, and the nodes' constraint boxes: the cell
 * shrunk by `margin` voxels, with the node starting at the cell centre (thesis
 * 3.2.1). In a cell with several sheets each node is fixed at the centre of its
 * sheet's edge midpoints, which keeps the sheets apart. Multithreaded,
 * deterministic. */
MeshExtraction_EXPORT void
BuildSurfaceNet(SurfaceNet & net, double margin, unsigned int numberOfWorkUnits = 0);

/** Iterations run and the last largest relocation (voxels) of a relaxation. */
struct SurfaceNetsRelaxationResult
{
  unsigned int iterations{ 0 };
  double       lastMaximumRelocation{ 0.0 };
};

/** The way quads become faces. */
enum class QuadSplit : std::uint8_t
{
  ShortestDiagonal,
  Delaunay,
  KeepQuads
};

/** Each coordinate of `points[0 .. numberOfPoints)` rounded to float: what a mesh of
 * float coordinates stores. */
MeshExtraction_EXPORT void
RoundToFloat(Vec3 * points, std::size_t numberOfPoints);

/** Node positions in physical space: origin + matrix * index, rounded to float when
 * the output mesh stores float coordinates (so that checks see what is written),
 * into `physical[0 .. numberOfPoints)`. */
MeshExtraction_EXPORT void
ToPhysical(const Vec3 *                 index,
           std::size_t                  numberOfPoints,
           const Vec3 &                 origin,
           const Matrix<double, 3, 3> & indexToPhysical,
           bool                         roundToFloat,
           Vec3 *                       physical);
template <typename TAllocator>
std::vector<Vec3>
ToPhysical(const std::vector<Vec3, TAllocator> & index,
           const Vec3 &                          origin,
           const Matrix<double, 3, 3> &          indexToPhysical,
           bool                                  roundToFloat = false)
{
  std::vector<Vec3> physical(index.size());
  ToPhysical(index.data(), index.size(), origin, indexToPhysical, roundToFloat, physical.data());
  return physical;
}

/** Faces of the net, from its nodes' physical points `points[0 .. number of nodes)`
 * (ToPhysical with `indexToPhysical`). A quad is split along the diagonal the
 * criterion prefers unless that would give a triangle facing away from the quad's
 * voxel-edge direction; then the other diagonal is used. `polygons` receives
 * triangles, or quads for KeepQuads. */
MeshExtraction_EXPORT void
MakeSurfaceNetFaces(const SurfaceNet &                               net,
                    const Matrix<double, 3, 3> &                     indexToPhysical,
                    QuadSplit                                        split,
                    const Vec3 *                                     points,
                    LargeBlockVector<std::array<std::uint32_t, 4>> & polygons,
                    unsigned int &                                   polygonSize);
/** The same, with the physical points (p = origin + matrix * index) made into
 * `points` (a std::vector or a LargeBlockVector of Vec3). */
template <typename TPoints>
void
MakeSurfaceNetFaces(const SurfaceNet &                               net,
                    const Vec3 &                                     origin,
                    const Matrix<double, 3, 3> &                     indexToPhysical,
                    QuadSplit                                        split,
                    TPoints &                                        points,
                    LargeBlockVector<std::array<std::uint32_t, 4>> & polygons,
                    unsigned int &                                   polygonSize)
{
  points.resize(net.positions.size());
  ToPhysical(net.positions.data(), net.positions.size(), origin, indexToPhysical, false, points.data());
  MakeSurfaceNetFaces(net, indexToPhysical, split, points.data(), polygons, polygonSize);
}

// The self-intersection check after the relaxation (stage 3b),
// FindSurfaceNetSelfIntersections and RemoveSurfaceNetSelfIntersections, is part of the
// validity guard: itkMeshExtractionValidityGuard.h.

/** What RemoveSmallComponents removed, and the nodes left (new index -> old index). */
struct SmallComponentRemoval
{
  std::vector<std::uint32_t> keptPoints;              ///< empty when nothing was removed
  std::size_t                numberOfComponents{ 0 }; ///< components removed
  std::size_t                numberOfFaces{ 0 };      ///< faces removed
  double                     largestVolume{ 0.0 };    ///< the largest component's volume (magnitude)
};

/** Removes from `polygons` (triangles, or quads if `polygonSize` is 4) every component
 * (faces joined by shared nodes) whose enclosed volume, in the units of `points`
 * cubed, is below `minimumVolume` in magnitude: an island outside the object and a
 * cavity inside it alike. The faces left are renumbered onto the nodes they use, in
 * the order of their old indices (SmallComponentRemoval::keptPoints). Nothing changes
 * when no component is that small. */
MeshExtraction_EXPORT SmallComponentRemoval
RemoveSmallComponents(LargeBlockVector<std::array<std::uint32_t, 4>> & polygons,
                      unsigned int                                     polygonSize,
                      const std::vector<Vec3> &                        points,
                      double                                           minimumVolume);

} // namespace detail
} // namespace MeshExtraction
} // namespace itk

#endif
