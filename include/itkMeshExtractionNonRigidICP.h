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
#ifndef itkMeshExtractionNonRigidICP_h
#define itkMeshExtractionNonRigidICP_h

// Internal to MeshExtraction (namespace detail): not part of the public API. The
// non-rigid correspondence stage of the landmark-free shape model: an
// as-rigid-as-possible (ARAP) regularised, symmetric non-rigid ICP that deforms the
// model's template onto each training mesh after the similarity ICP of thesis 7.2.1.

#include "MeshExtractionExport.h"
#include "itkMeshExtractionIndexedTriangleMesh.h"
#include "itkMeshExtractionSymmetricICP.h"

#include <functional>
#include <memory>
#include <vector>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
/** The schedule of the non-rigid stage: the ARAP stiffness alpha of each level, stiff
 * to loose (the template first moves nearly rigidly per region, then follows the
 * target's detail), and the iterations per level. */
struct NonRigidSettings
{
  std::vector<double> stiffness{ 100.0, 25.0, 6.0, 1.5, 0.4 };
  unsigned int        iterationsPerLevel{ 10 };
  /** Moves that make triangles cross, fold, turn over or degenerate are undone
   * (UndoFoldingMoves against the surface of the previous check, every
   * foldCheckInterval iterations and after the last), so that a template free of
   * self-intersections stays so. */
  bool         preventFolds{ true };
  unsigned int foldCheckInterval{ 5 };
};

/** The target of non-rigid matches: a closed triangle mesh with its closest-point query
 * (point-to-surface), its triangles' unit normals and its vertices' areas (a third of
 * their triangles' area) and unit normals (area weighted). Built once per mesh; it
 * serves every match against it. `surface` must answer point-to-surface and outlive
 * this object. */
class MeshExtraction_EXPORT NonRigidTarget
{
public:
  explicit NonRigidTarget(const ClosestPointQuery & surface);

  const IndexedTriangleMesh &
  GetMesh() const
  {
    return m_Surface.GetMesh();
  }
  const ClosestPointQuery &
  GetSurface() const
  {
    return m_Surface;
  }

  std::vector<Vec3>   triangleNormals;
  std::vector<double> vertexAreas;
  std::vector<Vec3>   vertexNormals;

private:
  const ClosestPointQuery & m_Surface;
};

/** The template side of non-rigid matches: its triangles and edges, and the sparse
 * Cholesky factors of I + alpha L (L = D - A, the graph Laplacian of the triangles) for
 * every level's alpha. The template's topology never changes while a model is built, so
 * the factors are computed once and shared by every match of every pass. */
class MeshExtraction_EXPORT NonRigidTemplate
{
public:
  NonRigidTemplate(const std::vector<TriangleIndices> & triangles,
                   std::size_t                          numberOfPoints,
                   const NonRigidSettings &             settings);
  ~NonRigidTemplate();
  NonRigidTemplate(const NonRigidTemplate &) = delete;
  NonRigidTemplate &
  operator=(const NonRigidTemplate &) = delete;

  /** x solving (I + alpha_level L) x = rhs, one coordinate at a time. */
  void
  Solve(std::size_t level, const std::vector<Vec3> & rhs, std::vector<Vec3> & x) const;

  const std::vector<TriangleIndices> &
  GetTriangles() const
  {
    return m_Triangles;
  }
  /** The edges, each once as (smaller, larger) vertex index. */
  const std::vector<std::array<std::uint32_t, 2>> &
  GetEdges() const
  {
    return m_Edges;
  }
  std::size_t
  GetNumberOfPoints() const
  {
    return m_NumberOfPoints;
  }
  const NonRigidSettings &
  GetSettings() const
  {
    return m_Settings;
  }

private:
  struct Factors;
  std::vector<TriangleIndices>              m_Triangles;
  std::vector<std::array<std::uint32_t, 2>> m_Edges;
  std::size_t                               m_NumberOfPoints;
  NonRigidSettings                          m_Settings;
  std::unique_ptr<Factors>                  m_Factors;
};

/** ARAP-regularised symmetric non-rigid ICP: the template with points `start` (already
 * in the target's frame, e.g. moved there by the similarity ICP; also the ARAP rest
 * shape) deformed onto the target. Each iteration pulls every template vertex towards
 * its closest point on the target (forward) and every target vertex pulls the corners
 * of its closest template triangle (backward, so the template reaches into processes
 * it would otherwise miss), weighted by vertex areas, a pair kept only where the two
 * surfaces face the same way; then the local step fits each vertex's rotation of its
 * rest edges and the global step solves (I + alpha L) x = c + alpha b, which minimises
 * sum |x_v - c_v|^2 + alpha/2 sum_v sum_u |(x_v - x_u) - R_v (x0_v - x0_u)|^2 for these
 * pairs and rotations. With NonRigidSettings::preventFolds, the moves of each iteration
 * that would make the surface cross or fold are undone. Returns one point per template
 * vertex, in the target's frame.
 * `progress` (optional) receives the fraction done. */
MeshExtraction_EXPORT std::vector<Vec3>
                      MatchNonRigid(const NonRigidTemplate &            shape,
                                    const std::vector<Vec3> &           start,
                                    const NonRigidTarget &              target,
                                    const std::function<void(double)> & progress = {});
} // namespace detail
} // namespace MeshExtraction
} // namespace itk

#endif
