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
#ifndef itkMeshExtractionQualityAnalysis_h
#define itkMeshExtractionQualityAnalysis_h

#include "MeshExtractionExport.h"
#include "itkMeshExtractionBuffer.h"
#include "itkMeshExtractionIndexedTriangleMesh.h"

#include <array>
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

/** Statistics of `values` with a histogram of `bins` bins on [lower, upper]. */
MeshExtraction_EXPORT ValueStatistics
ComputeValueStatistics(std::vector<double> values, double lower = 0.0, double upper = 1.0, unsigned int bins = 10);

/** What TriangleMeshQualityCalculator computes beyond the per-triangle measures. */
struct TriangleMeshQualityOptions
{
  /** A triangle is degenerate if its q_area is at most this (collinear within
   * rounding; includes repeated and coincident vertices). */
  double degenerateQAreaTolerance{ 1e-6 };
  /** Pairs of faces that intersect away from their shared vertices and edges
   * (exact predicates, AABB tree). */
  bool computeSelfIntersections{ true };
  /** For closed meshes: triangles whose normal points into the enclosed volume,
   * by ray-crossing parity. */
  bool computeOutwardOrientation{ true };
  /** Number of intersecting pairs kept in the report for inspection. */
  std::size_t maximumReportedIntersections{ 20 };
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

  bool
  IsClosed() const
  {
    return boundaryEdges == 0 && numberOfTriangles > 0;
  }
  bool
  IsManifold() const
  {
    return nonManifoldEdges == 0 && nonManifoldVertices == 0;
  }
  bool
  IsConsistentlyOriented() const
  {
    return inconsistentlyOrientedEdges == 0;
  }
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

/** Measure a triangle mesh. `reference`, if given, must have the same points and
 * triangles by index (an itk::ExceptionObject otherwise); triangles whose normal
 * turned by more than 90 degrees against it count as inverted. `measures`, if
 * given, receives the measures of every triangle. */
MeshExtraction_EXPORT TriangleMeshQualityReport
AnalyzeTriangleMesh(const IndexedTriangleMesh &        mesh,
                    const TriangleMeshQualityOptions & options,
                    const IndexedTriangleMesh *        reference = nullptr,
                    std::vector<TriangleMeasures> *    measures = nullptr,
                    std::vector<double> *              vertexSmoothness = nullptr);

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

} // namespace MeshExtraction
} // namespace itk

#endif
