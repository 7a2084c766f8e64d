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
#ifndef itkMeshExtractionScaleSpaceEdgeDetectionResult_h
#define itkMeshExtractionScaleSpaceEdgeDetectionResult_h

#include <cstddef>
#include <limits>
#include <vector>

namespace itk
{
namespace MeshExtraction
{
/** What one scale-space edge-detection step did (ScaleSpaceEdgeDetectionMeshFilter::GetResult).
 * \ingroup MeshExtraction */
struct ScaleSpaceEdgeDetectionResult
{
  std::vector<double> scales; ///< coarse to fine, mm
  std::size_t         numberOfVertices{ 0 };
  std::size_t         movedVertices{ 0 };      ///< vertices whose position changed
  std::size_t         shortenedMoves{ 0 };     ///< moves the guard shortened
  std::size_t         rejectedMoves{ 0 };      ///< moves the guard cancelled
  std::size_t         undoneMoves{ 0 };        ///< moves undone because they folded the surface
  std::size_t         normalFallbacks{ 0 };    ///< searches along the normal for want of a gradient
  double              meanDisplacement{ 0.0 }; ///< mm, over all vertices
  double              maximumDisplacement{ 0.0 };
  /** Mean and largest distance from the triangle centroids to the edge the detector
   * finds from them (NaN when not computed). */
  double inaccuracy{ std::numeric_limits<double>::quiet_NaN() };
  double maximumInaccuracy{ std::numeric_limits<double>::quiet_NaN() };
  bool   scaleSpaceBuilt{ false }; ///< the scale space was (re)computed for this step
  double scaleSpaceSeconds{ 0.0 }; ///< time of that computation
  double searchSeconds{ 0.0 };     ///< searches from the vertices
  double applySeconds{ 0.0 };      ///< the guarded moves and the fold check
  double inaccuracySeconds{ 0.0 }; ///< searches from the centroids
  double seconds{ 0.0 };           ///< time of the whole step
};

} // namespace MeshExtraction
} // namespace itk

#endif
