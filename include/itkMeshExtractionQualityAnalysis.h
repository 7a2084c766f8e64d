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
#ifndef itkMeshExtractionQualityAnalysis_h
#define itkMeshExtractionQualityAnalysis_h

#include "MeshExtractionExport.h"
#include "itkMeshExtractionIndexedTriangleMesh.h"
#include "itkMeshExtractionTriangleMeshQualityReport.h"
// The two checks the report runs, each a unit of its own, declared here too for
// the code that includes this header for them.
#include "itkMeshExtractionRayParity.h"
#include "itkMeshExtractionSelfIntersections.h"

#include <vector>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
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

} // namespace detail
} // namespace MeshExtraction
} // namespace itk

#endif
