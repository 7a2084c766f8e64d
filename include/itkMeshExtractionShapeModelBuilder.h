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
#ifndef itkMeshExtractionShapeModelBuilder_h
#define itkMeshExtractionShapeModelBuilder_h

// Internal to MeshExtraction (namespace detail): not part of the public API. The
// engine of itk::LandmarkFreeShapeModelEstimator (thesis section 7.2.2 with a
// non-rigid correspondence stage): training meshes made ready, the template passes,
// Procrustes analysis and PCA.

#include "MeshExtractionExport.h"
#include "itkMeshExtractionEnums.h"
#include "itkMeshExtractionIndexedTriangleMesh.h"
#include "itkMeshExtractionNonRigidICP.h"
#include "itkMeshExtractionShapeStatistics.h"
#include "itkMeshExtractionSymmetricICP.h"

#include <functional>
#include <string>
#include <vector>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
struct ShapeModelSettings
{
  /** Of the similarity ICP and, without the non-rigid stage, of the resampling. The
   * non-rigid stage always pairs points with surfaces. */
  MeshExtractionEnums::Correspondence correspondence{ MeshExtractionEnums::Correspondence::PointToSurface };
  /** Deform the template onto each mesh (NonRigidICP); off: the thesis' resampling by
   * closest points after the similarity ICP. */
  bool         nonRigid{ true };
  double       varianceFraction{ 0.95 };
  unsigned int maximumNumberOfPasses{ 2 };
  double       passTolerance{ 0.01 }; ///< mm: fewer passes when the template moves less (RMS)
  /** The similarity ICP stops when E^2 improves by less than this fraction: tighter
   * moves the transforms by a small fraction of a degree and costs twice the iterations. */
  double           icpRelativeTolerance{ 1e-5 };
  NonRigidSettings nonRigidSettings;
};

/** A training mesh made ready for the model: its largest vertex-connected component
 * (unreferenced vertices and other components dropped, an island of a few vertices is
 * common in segmentations), with its triangles turned outward if they all faced inward.
 * Throws itk::ExceptionObject naming `name` for a mesh without triangles, a coordinate
 * that is not finite, or a largest component that is open (boundary edges), not
 * manifold or inconsistently oriented. */
MeshExtraction_EXPORT IndexedTriangleMesh
PrepareTrainingMesh(const IndexedTriangleMesh & mesh,
                    const std::string &         name,
                    std::size_t *               droppedVertices = nullptr);

struct ShapeModelBuildResult
{
  std::vector<TriangleIndices>      triangles; ///< the model's topology: the pivot mesh's
  std::size_t                       pivot{ 0 };
  std::vector<Shape>                corresponded;    ///< per mesh, on the model topology, in its own frame
  std::vector<SimilarityParameters> toModel;         ///< per mesh, its frame to the model's (Procrustes)
  std::vector<Shape>                aligned;         ///< per mesh, corresponded and in the model's frame
  std::vector<double>               e2;              ///< per mesh, eq. 7.3 of the last pass's similarity ICP
  std::vector<double>               meanE2PerPass;   ///< mean of eq. 7.3 over the meshes, per pass
  std::vector<double>               templateChanges; ///< per pass, RMS move of the template (mm, after the gauge fix)
  PrincipalComponentModel           model;           ///< the modes up to the variance fraction
  std::vector<double>               allVariances;    ///< all m - 1 variances, for the compactness curve
};

/** The landmark-free shape model of prepared meshes (PrepareTrainingMesh): pivot = the
 * mesh with most vertices, its vertices the first template; each pass matches the
 * template to every mesh by the symmetric similarity ICP (warm-started from the previous
 * pass), corresponds it (non-rigid match, or closest points), and the template becomes
 * the mean of the corresponded meshes taken back to its frame, similarity-aligned to the
 * previous template (the gauge fix: averaging closest points shrinks and drifts the
 * mean otherwise). Then a similarity Procrustes analysis (scale removed) and PCA of the
 * last pass's corresponded meshes. Throws for fewer than two meshes. */
MeshExtraction_EXPORT ShapeModelBuildResult
BuildShapeModel(const std::vector<IndexedTriangleMesh> & meshes,
                const ShapeModelSettings &               settings,
                const std::function<void(double)> &      progress = {});

/** The steps of BuildShapeModel, for builds that spread the per-mesh matches over
 * processes or machines (meshextraction-cohort shape-model on Dask): the same arithmetic
 * in the same order, so such a build gives the same model as BuildShapeModel. */

/** The pivot: the first of the prepared meshes with most vertices, the first template. */
MeshExtraction_EXPORT std::size_t
ChoosePivot(const std::vector<IndexedTriangleMesh> & meshes);

/** One prepared mesh matched to the template of a pass. */
struct TemplateMatch
{
  Shape                corresponded;   ///< the template's points on the mesh, in the mesh's frame
  SimilarityParameters templateToMesh; ///< the similarity ICP's result
  double               e2{ 0.0 };      ///< eq. 7.3 at the end of the ICP
};

/** Matches the template to `mesh` (both prepared): the symmetric similarity ICP from
 * `initial` (null: the initial estimate of centroids, axes and sizes), then the
 * correspondence (non-rigid, or closest points). From the second pass on, `initial` is
 * the mesh's previous match composed with the inverse of the pass's gauge. */
MeshExtraction_EXPORT TemplateMatch
MatchTemplate(const IndexedTriangleMesh &         templateMesh,
              const IndexedTriangleMesh &         mesh,
              const ShapeModelSettings &          settings,
              const SimilarityParameters *        initial,
              const std::function<void(double)> & progress = {});

/** Throws unless `match` has a point for each of the template's (it was matched to it). */
MeshExtraction_EXPORT void
CheckMatchOfTemplate(const IndexedTriangleMesh & templateMesh, const TemplateMatch & match);

/** The end of a pass: the mean of the matches taken back to the template's frame,
 * similarity-aligned to the template (`gauge`: mean to new template), with the old points
 * kept where the mean would cross or fold (non-rigid builds); `change` is the RMS move
 * of the template (mm). Throws for no matches or a match of another template. */
struct RenewedTemplate
{
  Shape                points;
  SimilarityParameters gauge;
  double               change{ 0.0 };
};
MeshExtraction_EXPORT RenewedTemplate
RenewTemplate(const IndexedTriangleMesh &        templateMesh,
              const std::vector<TemplateMatch> & matches,
              const ShapeModelSettings &         settings);

/** Procrustes analysis and PCA of result.corresponded (the last pass's matches): fills
 * aligned, toModel, model and allVariances. */
MeshExtraction_EXPORT void
FinishShapeModel(ShapeModelBuildResult & result, double varianceFraction);

/** "input mesh i": how errors and reports name training mesh i. */
MeshExtraction_EXPORT std::string
                      TrainingMeshName(std::size_t i);

/** Throws unless there are at least two training meshes. */
MeshExtraction_EXPORT void
CheckNumberOfTrainingMeshes(std::size_t numberOfMeshes);

/** The model's topology with the points of `coordinates` (3n, x y z per point). */
MeshExtraction_EXPORT IndexedTriangleMesh
ModelMesh(const ShapeModelBuildResult & result, const std::vector<double> & coordinates);

/** mean + sum_i s_i sqrt(lambda_i) basis_i (3n); throws for more coefficients than modes. */
MeshExtraction_EXPORT std::vector<double>
SynthesizeInStandardDeviations(const PrincipalComponentModel & model, const std::vector<double> & standardDeviations);

/** The coefficients, in standard deviations, of a shape on the model's topology after its
 * similarity alignment to the mean; throws for a shape of another number of points. */
MeshExtraction_EXPORT std::vector<double>
                      ProjectInStandardDeviations(const ShapeModelBuildResult & result, const Shape & shape);

/** The model in statismo's HDF5 layout, with a line on how it was built. */
MeshExtraction_EXPORT void
WriteShapeModel(const std::string & fileName, const ShapeModelBuildResult & result);

/** Similarity3DTransform (centre at the origin) of the parameters, and back. */
MeshExtraction_EXPORT SimilarityTransform::Pointer
                      ToSimilarityTransform(const SimilarityParameters & parameters);
MeshExtraction_EXPORT SimilarityParameters
ToSimilarityParameters(const SimilarityTransform & transform);
} // namespace detail
} // namespace MeshExtraction
} // namespace itk

#endif
