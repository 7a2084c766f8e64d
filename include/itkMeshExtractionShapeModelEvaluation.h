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
#ifndef itkMeshExtractionShapeModelEvaluation_h
#define itkMeshExtractionShapeModelEvaluation_h

// Internal to MeshExtraction (namespace detail): not part of the public API. The
// measures the field uses to judge a shape model built from corresponded meshes:
// compactness, generalisation, specificity, eigenvector stability (thesis Table 7.2)
// and landmark transfer.

#include "MeshExtractionExport.h"
#include "itkMeshExtractionIndexedTriangleMesh.h"
#include "itkMeshExtractionShapeStatistics.h"

#include <cstdint>
#include <string>
#include <vector>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
/** sum_{i<=k} lambda_i / sum lambda_i for every k (the compactness curve, thesis Fig. 7.2). */
MeshExtraction_EXPORT std::vector<double>
                      CumulativeVarianceFractions(const std::vector<double> & variances);

/** Leave-one-out generalisation with `modes` modes, of corresponded meshes (each in its
 * own frame; `originals` the training meshes they were built from): for every mesh,
 * the model of the others (a similarity Procrustes analysis of all meshes, then PCA of
 * the others' aligned shapes), the left-out mesh aligned to that model's mean by a
 * similarity, projected on the modes, reconstructed and taken back to its frame.
 * Vertex-to-vertex: the mean distance of the reconstruction's vertices to the
 * corresponded mesh's; vertex-to-surface: to the original mesh's surface (mm). */
struct GeneralizationResult
{
  std::vector<double> vertexToVertex;
  std::vector<double> vertexToSurface;
  double              meanVertexToVertex{ 0.0 };
  double              meanVertexToSurface{ 0.0 };
};
MeshExtraction_EXPORT GeneralizationResult
LeaveOneOutGeneralization(const std::vector<Shape> &               corresponded,
                          const std::vector<IndexedTriangleMesh> & originals,
                          unsigned int                             modes);

/** Specificity with `modes` modes: random shapes of the model (b_k drawn from
 * N(0, lambda_k), clipped to +-2 sqrt(lambda_k); a fixed seed) against the nearest
 * training shape. Vertex-to-vertex: the mean distance to the corresponding vertices of
 * the nearest aligned training shape, over `samples` shapes; vertex-to-surface: the
 * mean distance of every `surfaceStride`-th vertex to the nearest original training
 * surface (moved into the model's frame by `toModel`), over the first `surfaceSamples`
 * shapes. */
struct SpecificitySettings
{
  unsigned int  modes{ 3 };
  unsigned int  samples{ 1000 };
  unsigned int  surfaceSamples{ 50 };
  unsigned int  surfaceStride{ 4 };
  std::uint32_t seed{ 0 };
};
struct SpecificityResult
{
  double vertexToVertex{ 0.0 };
  double vertexToVertexDeviation{ 0.0 }; ///< standard deviation over the samples
  double vertexToSurface{ 0.0 };
};
MeshExtraction_EXPORT SpecificityResult
Specificity(const std::vector<Shape> &                aligned,
            const std::vector<SimilarityParameters> & toModel,
            const std::vector<IndexedTriangleMesh> &  originals,
            const SpecificitySettings &               settings);

/** Thesis Table 7.2: for each subset size s, the angles (radians, in [0, pi/2]) between
 * the first `modes` eigenvectors of the first s aligned shapes and those of all of them
 * (the same Procrustes frame; a subset of s shapes has s - 1 eigenvectors, the missing
 * angles are NaN). */
MeshExtraction_EXPORT std::vector<std::vector<double>>
                      EigenvectorStability(const std::vector<Shape> &       aligned,
                                           const std::vector<std::size_t> & subsetSizes,
                                           unsigned int                     modes);

/** The landmarks of one training mesh, in its frame. */
struct MeshLandmarks
{
  std::vector<std::string> ids;
  std::vector<Vec3>        points;
};

/** Landmark transfer over all ordered pairs (i, j), i != j: landmark l of mesh i goes to
 * its closest point on i's corresponded mesh (a triangle and barycentric weights), is
 * carried to the same triangle and weights on j's corresponded mesh and measured against
 * j's own landmark l (mm, in j's frame). A landmark is used where both meshes have it. */
struct LandmarkTransferResult
{
  std::vector<std::string>                      ids;
  std::vector<std::vector<std::vector<double>>> error; ///< [i][j][landmark], NaN where not measured
  std::vector<double>                           meanPerLandmark;
  double                                        mean{ 0.0 };
  double                                        median{ 0.0 };
  std::size_t                                   count{ 0 };
};
MeshExtraction_EXPORT LandmarkTransferResult
TransferLandmarks(const std::vector<Shape> &           corresponded,
                  const std::vector<TriangleIndices> & triangles,
                  const std::vector<MeshLandmarks> &   landmarks);

/** How well the corresponded meshes cover the originals: the mean distance of their
 * vertices to the original surfaces (forward) and of the originals' vertices to their
 * surfaces (backward), averaged over the meshes (mm). */
struct SurfaceFitResult
{
  double forward{ 0.0 };
  double backward{ 0.0 };
};
MeshExtraction_EXPORT SurfaceFitResult
MeasureSurfaceFit(const std::vector<Shape> &               corresponded,
                  const std::vector<TriangleIndices> &     triangles,
                  const std::vector<IndexedTriangleMesh> & originals);
} // namespace detail
} // namespace MeshExtraction
} // namespace itk

#endif
