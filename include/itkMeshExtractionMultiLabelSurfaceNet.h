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
#ifndef itkMeshExtractionMultiLabelSurfaceNet_h
#define itkMeshExtractionMultiLabelSurfaceNet_h

#include "MeshExtractionExport.h"
#include "itkMeshExtractionIndexedTriangleMesh.h"
#include "itkMeshExtractionSurfaceNets.h"
#include "itkMeshExtractionTriangleGeometry.h"
#include "itkMatrix.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace itk
{
namespace MeshExtraction
{
/** \brief The surfaces of many labels in one pass, with one copy of every face two
 * labels share (see MultiLabelSurfaceNetsImageToMeshFilter).
 *
 * Labels are numbered 1..K here (0 is the background: every voxel of no chosen
 * label, and everything outside the image). Each label has the topology of its own
 * binary SurfaceNet (its sheets, its face rules), so its surface is a closed
 * 2-manifold by the same construction as a single label's; the nodes of the labels
 * that meet in a cell are one node wherever their sheets share a crossing voxel edge,
 * so the face between two labels is the same triangles in both surfaces.
 * \ingroup MeshExtraction
 */
struct MeshExtraction_EXPORT MultiLabelSurfaceNet
{
  std::vector<Vec3> positions; ///< one per node, continuous index
  std::vector<Vec3> points;    ///< the same in physical space (as written)
  /** Every face once: between labels faceLabels[f][0] < faceLabels[f][1], its normal
   * pointing out of the lower label (the background, 0, is the lowest). */
  std::vector<TriangleIndices>              triangles;
  std::vector<std::array<std::uint32_t, 2>> faceLabels;
  /** Per corner of each face, the vertex of the lower (side 0) and of the higher label's
   * own surface (LabelSurface numbering before compaction; none for the background). */
  std::vector<std::array<std::array<std::uint32_t, 3>, 2>> sideVertices;
  std::vector<std::uint32_t>                               sideVertexNode; ///< the node of every label-surface vertex
  std::vector<std::uint32_t> labelVertexStart; ///< label k's vertices: [start[k], start[k + 1])
  /** Label k's faces, increasing: labelFaces[labelFaceStart[k] .. labelFaceStart[k + 1]). */
  std::vector<std::uint32_t> labelFaceStart;
  std::vector<std::uint32_t> labelFaces;
  /** The label-surface vertices of pinched nodes, sorted, and their own points: moved a
   * little from the node toward their sheet, so that the label does not touch itself. */
  std::vector<std::pair<std::uint32_t, Vec3>> pinchedVertexPoints;
  std::uint32_t                               numberOfLabels{ 0 };

  // What the pass did.
  std::size_t  numberOfJunctionNodes{ 0 }; ///< nodes on voxel edges of three or more labels
  std::size_t  numberOfFixedNodes{ 0 };    ///< nodes that do not move (several per cell, ends of junction lines)
  std::size_t  numberOfPinchedNodes{ 0 };  ///< nodes where one label's surface touches itself
  std::size_t  numberOfNodesMovedBack{ 0 };
  unsigned int iterations{ 0 };

  /** Label k's closed surface (1 <= k <= numberOfLabels), outward: its points (copies of
   * `points`, one per vertex of its own net: where the label touches itself across a
   * diagonal that another label crosses, two vertices near the node, see
   * pinchedVertexPoints) and triangles; with `vertexNodes`, the node of each point. */
  void
  LabelSurface(std::uint32_t                  k,
               std::vector<Vec3> &            surfacePoints,
               std::vector<TriangleIndices> & surfaceTriangles,
               std::vector<std::uint32_t> *   vertexNodes = nullptr) const;
};

namespace detail
{
/** Settings of MakeMultiLabelSurfaceNet (the SNA relaxation of the single-label mode). */
struct MultiLabelSurfaceNetParameters
{
  unsigned int         maximumNumberOfIterations{ 10 };
  double               convergenceThreshold{ 1e-3 }; ///< voxels
  double               cellMargin{ 0.01 };           ///< voxels
  QuadSplit            split{ QuadSplit::ShortestDiagonal };
  bool                 roundToFloat{ false }; ///< the output stores float coordinates
  Vec3                 origin{ MakeVec3(0, 0, 0) };
  Matrix<double, 3, 3> indexToPhysical; ///< direction * diag(spacing)
  unsigned int         numberOfWorkUnits{ 0 };
};

/** The multi-label net of `labels` (size[0] * size[1] * size[2] voxels, x fastest;
 * values 0..numberOfLabels, 0 the background): the nodes relaxed by averaging (nodes on
 * junctions of three or more labels only along their junction line), then moved back
 * where faces cross, as in the single-label mode. Every label 1..numberOfLabels must
 * have a voxel. */
MeshExtraction_EXPORT MultiLabelSurfaceNet
MakeMultiLabelSurfaceNet(const std::uint32_t *                  labels,
                         const std::array<std::int64_t, 3> &    size,
                         std::uint32_t                          numberOfLabels,
                         const MultiLabelSurfaceNetParameters & parameters);

} // namespace detail
} // namespace MeshExtraction
} // namespace itk

#endif
