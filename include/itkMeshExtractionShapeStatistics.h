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
#ifndef itkMeshExtractionShapeStatistics_h
#define itkMeshExtractionShapeStatistics_h

// Internal to MeshExtraction (namespace detail): not part of the public API. Procrustes
// alignment and principal component analysis of shapes in correspondence (thesis
// section 7.2), and the model file (statismo's HDF5 layout).

#include "MeshExtractionExport.h"
#include "itkMeshExtractionIndexedTriangleMesh.h"

#include <string>
#include <vector>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
/** Shapes in correspondence: each the same number of points, point k of every shape
 * the same anatomical point. */
using Shape = std::vector<Vec3>;

/** A similarity as rotation (row-major 3x3), scale and translation: p -> s R p + t. */
struct SimilarityParameters
{
  double rotation[3][3]{ { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } };
  double scale{ 1.0 };
  Vec3   translation{ 0.0 };

  Vec3
  Apply(const Vec3 & p) const;
  SimilarityParameters
  Inverse() const;
};

/** The similarity (or, without `withScale`, the rigid transform) taking `from` onto
 * `to` in the least-squares sense (Umeyama). */
MeshExtraction_EXPORT SimilarityParameters
AlignShape(const Shape & from, const Shape & to, bool withScale);

/** outer o inner: p -> outer(inner(p)). */
MeshExtraction_EXPORT SimilarityParameters
Compose(const SimilarityParameters & outer, const SimilarityParameters & inner);

MeshExtraction_EXPORT Shape
ApplySimilarity(const SimilarityParameters & t, const Shape & shape);

/** Generalised Procrustes analysis: every shape aligned to the mean, the mean kept at
 * the average centroid size and re-estimated until it moves less than `tolerance` (mm,
 * RMS) or `maximumIterations`. Returns the aligned shapes; `transforms` (optional) the
 * similarity of each shape into the mean's frame. */
MeshExtraction_EXPORT std::vector<Shape>
                      GeneralizedProcrustes(const std::vector<Shape> &          shapes,
                                            bool                                withScale,
                                            std::vector<SimilarityParameters> * transforms = nullptr,
                                            double                              tolerance = 1e-6,
                                            unsigned int                        maximumIterations = 20);

/** A principal component model: x = mean + basis b (thesis eq. 7.2). */
struct MeshExtraction_EXPORT PrincipalComponentModel
{
  std::vector<double>              mean;                 ///< 3n
  std::vector<std::vector<double>> basis;                ///< per mode, 3n, orthonormal
  std::vector<double>              variances;            ///< per mode, descending, 1/(m-1) convention
  double                           totalVariance{ 0.0 }; ///< of all m-1 modes before truncation
  double                           noiseVariance{ 0.0 };

  std::size_t
  NumberOfModes() const
  {
    return variances.size();
  }
  /** mean + sum b_i basis_i. */
  Shape
  Synthesize(const std::vector<double> & b) const;
  /** The coefficients of `shape` (already in the model's frame): basis^T (x - mean). */
  std::vector<double>
  Project(const Shape & shape) const;
};

/** PCA of aligned shapes by a thin SVD of the centred data (never a 3n x 3n
 * covariance): variances s_k^2 / (m - 1); the modes that explain `varianceFraction` of
 * the total (1: all m - 1). Throws for fewer than two shapes or shapes of different sizes. */
MeshExtraction_EXPORT PrincipalComponentModel
BuildPrincipalComponents(const std::vector<Shape> & shapes, double varianceFraction);

/** Writes the model in statismo's HDF5 layout (version 0.9): /model/mean, pcaBasis (3n x k,
 * orthonormal columns), pcaVariance, noiseVariance; /representer as
 * itkStandardMeshRepresenter (points 3 x n, cells 3 x f); /modelinfo; /version. */
MeshExtraction_EXPORT void
WriteStatismoModel(const std::string &                  fileName,
                   const PrincipalComponentModel &      model,
                   const std::vector<TriangleIndices> & triangles,
                   const std::string &                  builderInfo);

/** Reads a file written by WriteStatismoModel (or statismo, with a mesh representer);
 * throws naming the file and what is missing. */
MeshExtraction_EXPORT PrincipalComponentModel
ReadStatismoModel(const std::string & fileName, std::vector<TriangleIndices> & triangles);
} // namespace detail
} // namespace MeshExtraction
} // namespace itk

#endif
