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
#ifndef itkMeshExtractionSymmetricICP_h
#define itkMeshExtractionSymmetricICP_h

// Internal to MeshExtraction (namespace detail): not part of the public API. The
// engine of itk::SymmetricSimilarityICPRegistration and of the shape model's matching
// (thesis section 7.2.1), on indexed triangle meshes.

#include "MeshExtractionExport.h"
#include "itkMeshExtractionEnums.h"
#include "itkMeshExtractionIndexedTriangleMesh.h"
#include "itkMeshExtractionTriangleAABBTree.h"
#include "itkMacro.h"
#include "itkSimilarity3DTransform.h"

#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <vector>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
/** The triangles of `mesh` as arrays; throws naming `role` when it has none or a
 * coordinate is not finite. */
template <typename TMesh>
IndexedTriangleMesh
CheckedTriangleMesh(const TMesh * mesh, const char * role)
{
  if (mesh == nullptr)
  {
    itkGenericExceptionMacro("No " << role << " mesh: set it first.");
  }
  IndexedTriangleMesh indexed = MakeIndexedTriangleMesh(*mesh);
  if (indexed.triangles.empty())
  {
    itkGenericExceptionMacro("The " << role << " mesh has no triangles (" << mesh->GetNumberOfPoints() << " points, "
                                    << mesh->GetNumberOfCells() << " cells).");
  }
  for (std::size_t i = 0; i < indexed.points.size(); ++i)
  {
    for (unsigned int d = 0; d < 3; ++d)
    {
      if (!std::isfinite(indexed.points[i][d]))
      {
        itkGenericExceptionMacro("The " << role << " mesh's point " << indexed.pointIds[i]
                                        << " has a coordinate that is not finite.");
      }
    }
  }
  return indexed;
}

/** A point of a mesh's surface: the triangle and the barycentric weights of its
 * corners (for point-to-point correspondence, a vertex: weight 1 on one corner). */
struct SurfacePoint
{
  std::uint32_t triangle{ 0 };
  double        weights[3]{ 1.0, 0.0, 0.0 };
  Vec3          point{ 0.0 };
};

/** Barycentric weights of p (a point of triangle abc) at a, b and c; a degenerate
 * triangle gives all the weight to a. */
MeshExtraction_EXPORT void
BarycentricWeights(const Vec3 & p, const Vec3 & a, const Vec3 & b, const Vec3 & c, double w[3]);

/** Closest points on one mesh: its vertices (a k-d tree) or its triangles (the
 * module's AABB tree). Built once; queries are thread-safe. */
class MeshExtraction_EXPORT ClosestPointQuery
{
public:
  using CorrespondenceEnum = MeshExtractionEnums::Correspondence;

  ClosestPointQuery(const IndexedTriangleMesh & mesh, CorrespondenceEnum correspondence);
  ~ClosestPointQuery();
  ClosestPointQuery(const ClosestPointQuery &) = delete;
  ClosestPointQuery &
  operator=(const ClosestPointQuery &) = delete;

  /** The closest point to each of `points` (in parallel). With `hints` (one per point,
   * e.g. the answers for nearby points), point-to-surface searches start from their
   * triangles. */
  std::vector<SurfacePoint>
  Find(const std::vector<Vec3> & points, const std::vector<SurfacePoint> * hints = nullptr) const;
  SurfacePoint
  FindOne(const Vec3 & p, std::uint32_t hintTriangle = std::numeric_limits<std::uint32_t>::max()) const;

  const IndexedTriangleMesh &
  GetMesh() const
  {
    return m_Mesh;
  }

private:
  struct VertexTree;
  const IndexedTriangleMesh & m_Mesh;
  CorrespondenceEnum          m_Correspondence;
  TriangleAABBTree            m_Triangles;
  std::unique_ptr<VertexTree> m_Vertices;
  std::vector<std::uint32_t>  m_VertexTriangle; ///< a triangle of each vertex
  std::vector<std::uint8_t>   m_VertexCorner;   ///< the vertex's corner in it
};

using SimilarityTransform = Similarity3DTransform<double>;

/** The similarity that, applied twice, gives `full` (Q with Q o Q = full): half the
 * rotation angle, the square root of the scale, the fixed point's translation. Its
 * centre is `center`. */
MeshExtraction_EXPORT SimilarityTransform::Pointer
                      HalfSimilarity(const SimilarityTransform & full, const Vec3 & center);

/** Q o Q as one similarity (centre of Q). */
MeshExtraction_EXPORT SimilarityTransform::Pointer
                      ComposeWithItself(const SimilarityTransform & half);

/** The similarity T of the weighted pairs (f_k, m_k), centred at `center`: Umeyama's
 * least squares, minimising sum w |T(f_k) - m_k|^2; or, with `symmetricScale`, the same
 * rotation with Horn's symmetric scale sqrt(sum w |m - mean m|^2 / sum w |f - mean f|^2),
 * whose half Q minimises eq. 7.3 exactly. */
MeshExtraction_EXPORT SimilarityTransform::Pointer
                      FitSimilarity(const std::vector<Vec3> &   fixed,
                                    const std::vector<Vec3> &   moving,
                                    const std::vector<double> & weights,
                                    const Vec3 &                center,
                                    bool                        symmetricScale = false);

/** Moments of a triangulated surface, weighted by area so that they do not depend on
 * the tessellation (two meshes of one shape at different resolutions get the same):
 * the centroid of the surface, its principal axes (the eigenvectors of the surface's
 * second moment about the centroid, as columns, largest first, right-handed) and the
 * mean distance of the vertices to the centroid, each vertex weighted by a third of the
 * area of its triangles. */
struct SurfaceMoments
{
  Vec3                 centroid{ 0.0 };
  Matrix<double, 3, 3> axes;
  double               meanDistance{ 0.0 };
  double               area{ 0.0 };
};

MeshExtraction_EXPORT SurfaceMoments
ComputeSurfaceMoments(const IndexedTriangleMesh & mesh);

/** The initial estimates of thesis 7.2.1: centroids aligned, principal axes aligned (the
 * four right-handed sign choices), the mean distance to the centre equalised; all from
 * the area-weighted moments. Centred at the fixed mesh's centroid. */
MeshExtraction_EXPORT std::vector<SimilarityTransform::Pointer>
                      PrincipalAxesCandidates(const SurfaceMoments & fixed, const SurfaceMoments & moving);

struct SymmetricICPSettings
{
  MeshExtractionEnums::Correspondence correspondence{ MeshExtractionEnums::Correspondence::PointToSurface };
  unsigned int                        maximumIterations{ 100 };
  double                              relativeTolerance{ 1e-6 }; ///< of E^2, between iterations
  unsigned int                        levenbergMarquardtIterations{ 10 };
  bool                                initialAlignment{ true }; ///< principal axes; else `initial`
  const SimilarityTransform *         initial{ nullptr };       ///< fixed to moving, when given
  bool                                measureInitialE2{ true }; ///< E^2 of the start, for SymmetricICPResult
  std::function<void(double)>         progress;
};

struct SymmetricICPResult
{
  SimilarityTransform::Pointer fixedToMoving;       ///< Q o Q
  SimilarityTransform::Pointer half;                ///< Q
  double                       initialE2{ 0.0 };    ///< NaN unless measureInitialE2
  double                       e2{ 0.0 };           ///< thesis eq. 7.3 at the end
  double                       meanDistance{ 0.0 }; ///< mean closest-point distance, both ways, in the moving frame
  unsigned int                 iterations{ 0 };
};

/** Symmetric similarity ICP (thesis 7.2.1): each iteration finds the closest points of
 * A on B and of B on A (for the current Q o Q), then the Q minimising eq. 7.3 with ITK's
 * PointSetToPointSetRegistrationMethod, LevenbergMarquardtOptimizer and
 * SymmetricPairedPointSetMetric, started from the half of the least-squares fit; it stops
 * when E^2 stops improving. Without a given start, each of the four principal-axes
 * candidates is first tried by a few closed-form iterations on a random sample of
 * vertices of each mesh with nearest-vertex pairs (cheap, and it picks the same
 * candidate as full iterations would), and the one of least E^2 is kept. */
MeshExtraction_EXPORT SymmetricICPResult
RunSymmetricICP(const ClosestPointQuery &    fixed,
                const ClosestPointQuery &    moving,
                const SymmetricICPSettings & settings);

/** E^2 (eq. 7.3) of Q with the closest points for Q o Q, over all points or over a sample
 * of at most `sampleLimit` points of each mesh. */
MeshExtraction_EXPORT double
SymmetricE2(const ClosestPointQuery &   fixed,
            const ClosestPointQuery &   moving,
            const SimilarityTransform & half,
            std::size_t                 sampleLimit = 0);

/** The points of `mesh` mapped by `transform`. */
MeshExtraction_EXPORT std::vector<Vec3>
                      TransformPoints(const std::vector<Vec3> & points, const Transform<double, 3, 3> & transform);
} // namespace detail
} // namespace MeshExtraction
} // namespace itk

#endif
