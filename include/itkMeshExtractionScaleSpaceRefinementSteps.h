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
#ifndef itkMeshExtractionScaleSpaceRefinementSteps_h
#define itkMeshExtractionScaleSpaceRefinementSteps_h

#include "MeshExtractionExport.h"
#include "itkMeshExtractionEnums.h"

#include <cstdint>
#include <iosfwd>
#include <limits>
#include <string>
#include <vector>

namespace itk
{
namespace MeshExtraction
{
/** \brief One row of the step table of ScaleSpaceEdgeMeshRefinementFilter: the state
 * of the mesh after one operation of the protocol (thesis Table 4.1).
 *
 * Quantities that do not apply to the row are NaN (doubles) or -1 (counts).
 * \ingroup MeshExtraction
 */
struct ScaleSpaceRefinementStep
{
  MeshExtractionEnums::RefinementOperation operation{ MeshExtractionEnums::RefinementOperation::Initial };
  unsigned int                             cycle{ 0 }; ///< 0 for the first ED and ES, then 1, 2, ...
  std::size_t                              numberOfPoints{ 0 };
  std::size_t                              numberOfTriangles{ 0 };
  double                                   meanMinimumAngle{ 0.0 }; ///< degrees, "Average Min. Angle"
  double                                   meanQArea{ 0.0 };        ///< "Average Quality"
  double                                   minimumQArea{ 0.0 };
  /** ED rows: mean distance of the triangle centroids to the edge the detector finds
   * from them (thesis section 4.2.3), mm. */
  double inaccuracy{ std::numeric_limits<double>::quiet_NaN() };
  /** With a reference surface: mean and variance of the signed distance of the
   * vertices to it (for a sphere, mean radius = radius + mean). */
  double referenceDistanceMean{ std::numeric_limits<double>::quiet_NaN() };
  double referenceDistanceVariance{ std::numeric_limits<double>::quiet_NaN() };
  /** ED: vertices moved; ES: edges swapped (and kept); S: vertices moved. */
  std::int64_t changes{ -1 };
  /** ED, S: moves the no-inversion guard rejected plus moves undone because they
   * folded the surface; ES: new triangles that cut through the surface (undone, or
   * their corners locked before swapping again). */
  std::int64_t rejectedMoves{ -1 };
  /** ED: largest vertex displacement; S: largest distance of a vertex from its
   * position after the last ED (the travel that ends a cycle), mm. */
  double maximumTravel{ std::numeric_limits<double>::quiet_NaN() };
  /** ED: mean vertex displacement (how far the mesh was from the edges found); S:
   * mean distance of the vertices from their positions after the last ED, mm. */
  double meanTravel{ std::numeric_limits<double>::quiet_NaN() };
  /** Integrity after the step: degenerate triangles (q_area <= 1e-6), non-manifold
   * edges plus vertices, and (ED, S: same connectivity as before the step) triangles
   * whose normal turned by more than 90 degrees during the step. */
  std::int64_t degenerateTriangles{ 0 };
  std::int64_t nonManifold{ 0 };
  std::int64_t invertedTriangles{ -1 };
  double       seconds{ 0.0 }; ///< time of the operation (not of the measurements)
};

/** "Org", "ED", "ES" or "S" (the abbreviations of thesis Table 4.1). */
MeshExtraction_EXPORT std::string
                      RefinementOperationAbbreviation(MeshExtractionEnums::RefinementOperation operation);

/** Prints the steps as a table with the columns of thesis Table 4.1 (operation,
 * average minimum angle, average quality, average inaccuracy, mean radius or mean
 * distance, variance) followed by the cycle, the changes, the rejected moves, the
 * mean and largest travel, the integrity counts and the time. With a finite `referenceRadius` the
 * distance column is the mean radius, referenceRadius + mean signed distance. */
MeshExtraction_EXPORT void
PrintScaleSpaceRefinementTable(std::ostream &                                os,
                               const std::vector<ScaleSpaceRefinementStep> & steps,
                               double referenceRadius = std::numeric_limits<double>::quiet_NaN());

/** The steps as CSV, one row per step, with a header line. */
MeshExtraction_EXPORT void
WriteScaleSpaceRefinementCSV(std::ostream & os, const std::vector<ScaleSpaceRefinementStep> & steps);

} // namespace MeshExtraction
} // namespace itk

#endif
