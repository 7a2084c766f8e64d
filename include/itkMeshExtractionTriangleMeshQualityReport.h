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
#ifndef itkMeshExtractionTriangleMeshQualityReport_h
#define itkMeshExtractionTriangleMeshQualityReport_h

#include "MeshExtractionExport.h"

#include <cstddef>
#include <cstdint>
#include <iosfwd>
#include <string>
#include <utility>
#include <vector>

namespace itk
{
namespace MeshExtraction
{
/** \brief Summary of one per-element measure: mean, extremes, percentiles and a
 * histogram of `histogram.size()` equal bins on [histogramLower, histogramUpper]
 * (values outside are clamped into the end bins). \ingroup MeshExtraction */
struct ValueStatistics
{
  std::size_t              count{ 0 };
  double                   mean{ 0.0 };
  double                   minimum{ 0.0 };
  double                   maximum{ 0.0 };
  double                   percentile01{ 0.0 }; ///< 1st percentile
  double                   percentile05{ 0.0 }; ///< 5th percentile
  double                   median{ 0.0 };
  double                   percentile95{ 0.0 }; ///< 95th percentile
  double                   histogramLower{ 0.0 };
  double                   histogramUpper{ 1.0 };
  std::vector<std::size_t> histogram;
};

/** \brief Everything the quality calculator measures.
 *
 * Counts that were not computed (no reference mesh, an open mesh for the outward
 * test, self-intersections switched off) are -1.
 * \ingroup MeshExtraction
 */
struct MeshExtraction_EXPORT TriangleMeshQualityReport
{
  // Size
  std::size_t numberOfPoints{ 0 };
  std::size_t numberOfReferencedPoints{ 0 };
  std::size_t numberOfTriangles{ 0 };
  std::size_t numberOfSplitQuads{ 0 };
  std::size_t numberOfEdges{ 0 };

  // Triangle shape (thesis section 4.2.3); angles in degrees.
  ValueStatistics qLength;
  ValueStatistics qAngle;
  ValueStatistics qArea;
  ValueStatistics minimumAngle;
  ValueStatistics maximumAngle;
  ValueStatistics edgeLength;
  double          fractionQAngleBelow03{ 0.0 }; ///< share of triangles with q_angle < 0.3

  // Vertices
  double                   meanSmoothness{ 0.0 }; ///< mean |2 pi - sum of angles| over interior vertices (sec. 3.3)
  std::size_t              numberOfInteriorVertices{ 0 };
  std::vector<std::size_t> valenceHistogram;        ///< [d] = number of vertices with d incident edges
  double                   fractionValence6{ 0.0 }; ///< share of referenced vertices with valence 6

  // Integrity
  std::int64_t degenerateTriangles{ 0 };
  std::int64_t invertedTrianglesVersusReference{ -1 };
  std::int64_t invertedTrianglesVersusOutward{ -1 };
  std::int64_t undeterminedOrientationTriangles{ -1 };
  std::int64_t nonManifoldEdges{ 0 };
  std::int64_t nonManifoldVertices{ 0 };
  std::int64_t boundaryEdges{ 0 };
  std::int64_t boundaryLoops{ 0 };
  std::int64_t inconsistentlyOrientedEdges{ 0 };
  std::int64_t unreferencedPoints{ 0 };
  std::int64_t connectedComponents{ 0 };
  std::int64_t eulerCharacteristic{ 0 };
  std::int64_t genus{ -1 }; ///< sum over components of (2 - chi - b) / 2; -1 unless manifold and oriented
  std::int64_t selfIntersectingPairs{ -1 };
  std::int64_t selfIntersectingTriangles{ -1 };
  std::vector<std::pair<std::uint32_t, std::uint32_t>> intersectingPairs; ///< the first few, by triangle index
  double                                               totalArea{ 0.0 };
  double enclosedVolume{ 0.0 }; ///< signed (divergence theorem); meaningful for closed surfaces

  /** No boundary edge, and at least one triangle. */
  bool
  IsClosed() const;
  /** No non-manifold edge or vertex. */
  bool
  IsManifold() const;
  /** No two triangles run an edge the same way. */
  bool
  IsConsistentlyOriented() const;
  /** Closed, 2-manifold, consistently and outward oriented, with no degenerate,
   * inverted or self-intersecting triangles (checks that were not run do not count). */
  bool
  IsValidClosedSurface() const;

  /** Human-readable table. */
  void
  Print(std::ostream & os, const std::string & title = std::string()) const;
  /** One JSON object (no trailing newline). */
  void
  PrintJSON(std::ostream & os) const;
};

} // namespace MeshExtraction
} // namespace itk

#endif
