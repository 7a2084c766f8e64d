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
#ifndef itkMeshExtractionMeshSurfaceDistanceReport_h
#define itkMeshExtractionMeshSurfaceDistanceReport_h

#include "MeshExtractionExport.h"

#include <cstddef>
#include <iosfwd>
#include <string>

namespace itk
{
namespace MeshExtraction
{
/** \brief Mean (thesis eq. 3.7, the modified Hausdorff distance), RMS and maximum of
 * a set of unsigned distances, plus the signed mean where a sign is known.
 * \ingroup MeshExtraction */
struct DistanceStatistics
{
  std::size_t count{ 0 };
  double      mean{ 0.0 };
  double      rms{ 0.0 };
  double      maximum{ 0.0 };
  double      signedMean{ 0.0 }; ///< mean signed distance (negative inside); 0 for a mesh reference
};

/** \brief Distances between a mesh and a reference surface. \ingroup MeshExtraction */
struct MeshExtraction_EXPORT MeshSurfaceDistanceReport
{
  DistanceStatistics vertices;           ///< mesh vertices -> reference
  DistanceStatistics faceCentroids;      ///< mesh triangle centroids -> reference
  DistanceStatistics meshSamples;        ///< vertices, centroids and lattice samples -> reference
  DistanceStatistics referenceSamples;   ///< reference samples -> mesh (the reverse direction)
  double             hausdorff{ 0.0 };   ///< max(meshSamples.maximum, referenceSamples.maximum)
  bool               symmetric{ false }; ///< the reverse direction was measured
  std::string        referenceDescription;

  void
  Print(std::ostream & os, const std::string & title = std::string()) const;
  void
  PrintJSON(std::ostream & os) const;
};

} // namespace MeshExtraction
} // namespace itk

#endif
