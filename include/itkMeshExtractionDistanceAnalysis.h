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
#ifndef itkMeshExtractionDistanceAnalysis_h
#define itkMeshExtractionDistanceAnalysis_h

#include "MeshExtractionExport.h"
#include "itkMeshExtractionIndexedTriangleMesh.h"
#include "itkMeshExtractionMeshSurfaceDistanceReport.h"
#include "itkMeshExtractionTriangleAABBTree.h"

#include <vector>

namespace itk
{
class ImplicitSurfaceFunction;

namespace MeshExtraction
{
namespace detail
{
/** Count, mean, RMS, maximum and (with `signedDistances`) signed mean of `distances`. */
MeshExtraction_EXPORT DistanceStatistics
ComputeDistanceStatistics(const std::vector<double> & distances, const std::vector<double> * signedDistances = nullptr);

/** Options of the distance computation. */
struct SurfaceDistanceOptions
{
  /** Extra samples per triangle for the maximum and Hausdorff distance: a
   * barycentric lattice with this many subdivisions per edge (0: vertices and
   * centroids only). */
  unsigned int samplingLevel{ 2 };
  /** Measure the reverse direction too (reference -> mesh), for the symmetric
   * Hausdorff distance. */
  bool symmetric{ true };
  /** Spacing (mm) of the samples taken on an implicit reference surface for the
   * reverse direction; 0 = half the mesh's mean edge length. */
  double       implicitSampleSpacing{ 0.0 };
  unsigned int numberOfWorkUnits{ 0 };
};

/** Unsigned distance from every point to the triangles of `tree` (exact
 * point-to-triangle distance), multithreaded. */
MeshExtraction_EXPORT std::vector<double>
                      DistancesToTriangles(const std::vector<Vec3> & points,
                                           const TriangleAABBTree &  tree,
                                           unsigned int              numberOfWorkUnits = 0);

/** Signed distance from every point to an implicit surface, multithreaded. */
MeshExtraction_EXPORT std::vector<double>
                      SignedDistancesToSurface(const std::vector<Vec3> &       points,
                                               const ImplicitSurfaceFunction & surface,
                                               unsigned int                    numberOfWorkUnits = 0);

/** Vertices, centroids and (samplingLevel > 0) barycentric lattice points of a mesh. */
MeshExtraction_EXPORT std::vector<Vec3>
                      SampleTriangles(const IndexedTriangleMesh & mesh, unsigned int samplingLevel);

/** Points on an implicit surface no farther than sqrt(3) * spacing from any
 * surface point: grid points near the surface projected onto it. An unbounded
 * surface (infinite GetBounds, e.g. a plane) is sampled inside `clip` only; the
 * samples of a bounded one are clipped to `clip` too if it is given. */
MeshExtraction_EXPORT std::vector<Vec3>
SampleImplicitSurface(const ImplicitSurfaceFunction & surface, double spacing, const AxisAlignedBox * clip = nullptr);

/** Distances of `mesh` to a reference mesh or (if referenceMesh is null) to an
 * implicit surface. vertexDistances and centroidDistances receive the per-vertex
 * and per-triangle values (signed for an implicit surface). */
MeshExtraction_EXPORT MeshSurfaceDistanceReport
ComputeSurfaceDistances(const IndexedTriangleMesh &     mesh,
                        const IndexedTriangleMesh *     referenceMesh,
                        const ImplicitSurfaceFunction * referenceSurface,
                        const SurfaceDistanceOptions &  options,
                        std::vector<double> *           vertexDistances = nullptr,
                        std::vector<double> *           centroidDistances = nullptr);

} // namespace detail
} // namespace MeshExtraction
} // namespace itk

#endif
