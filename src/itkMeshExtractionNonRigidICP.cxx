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
#include "itkMeshExtractionNonRigidICP.h"
#include "itkMeshExtractionParallel.h"
#include "itkMeshExtractionValidityGuard.h"
#include "itkMeshExtractionTriangleAABBTree.h"
#include "itk_eigen.h"
#include ITK_EIGEN(Dense)
#include ITK_EIGEN(SVD)
#include ITK_EIGEN(Sparse)
#include ITK_EIGEN(SparseCholesky)

#include <algorithm>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
namespace
{
/** Vertices per block of the parallel loops. */
constexpr std::size_t Block = 2048;

/** Unit normals of the triangles; area-weighted unit normals and areas (a third of their
 * triangles' area) of the vertices. */
void
SurfaceNormalsAndAreas(const IndexedTriangleMesh & mesh,
                       std::vector<Vec3> &         triangleNormals,
                       std::vector<double> &       vertexAreas,
                       std::vector<Vec3> &         vertexNormals)
{
  const auto & P = mesh.points;
  triangleNormals.resize(mesh.triangles.size());
  std::vector<Vec3> weighted(mesh.triangles.size()); // |n| = twice the area
  ParallelForBlocks(mesh.triangles.size(), Block, [&](std::size_t begin, std::size_t end, std::size_t) {
    for (std::size_t f = begin; f < end; ++f)
    {
      const TriangleIndices & t = mesh.triangles[f];
      weighted[f] = Cross(P[t[1]] - P[t[0]], P[t[2]] - P[t[0]]);
      const double length = Norm(weighted[f]);
      triangleNormals[f] = length > 0.0 ? weighted[f] * (1.0 / length) : weighted[f];
    }
  });
  vertexAreas.assign(P.size(), 0.0);
  vertexNormals.assign(P.size(), MakeVec3(0, 0, 0));
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f)
  {
    const double third = Norm(weighted[f]) / 6.0;
    for (std::uint32_t v : mesh.triangles[f])
    {
      vertexAreas[v] += third;
      vertexNormals[v] += weighted[f];
    }
  }
  for (Vec3 & n : vertexNormals)
  {
    const double length = Norm(n);
    n = length > 0.0 ? n * (1.0 / length) : n;
  }
}

Eigen::Vector3d
ToEigen(const Vec3 & v)
{
  return Eigen::Vector3d(v[0], v[1], v[2]);
}

Vec3
FromEigen(const Eigen::Vector3d & v)
{
  return MakeVec3(v[0], v[1], v[2]);
}
} // namespace

NonRigidTarget::NonRigidTarget(const ClosestPointQuery & surface)
    : m_Surface(surface)
{
  SurfaceNormalsAndAreas(surface.GetMesh(), triangleNormals, vertexAreas, vertexNormals);
}

// ---- the template's factorised systems ------------------------------------------------

struct NonRigidTemplate::Factors
{
  using SparseMatrix = Eigen::SparseMatrix<double>;
  using Cholesky = Eigen::SimplicialLLT<SparseMatrix, Eigen::Lower, Eigen::AMDOrdering<int>>;
  std::vector<std::unique_ptr<Cholesky>> levels;
};

NonRigidTemplate::NonRigidTemplate(const std::vector<TriangleIndices> & triangles,
                                   std::size_t                          numberOfPoints,
                                   const NonRigidSettings &             settings)
    : m_Triangles(triangles)
    , m_NumberOfPoints(numberOfPoints)
    , m_Settings(settings)
    , m_Factors(std::make_unique<Factors>())
{
  for (const TriangleIndices & t : triangles)
  {
    for (unsigned int k = 0; k < 3; ++k)
    {
      const std::uint32_t a = t[k];
      const std::uint32_t b = t[(k + 1) % 3];
      m_Edges.push_back({ std::min(a, b), std::max(a, b) });
    }
  }
  std::sort(m_Edges.begin(), m_Edges.end());
  m_Edges.erase(std::unique(m_Edges.begin(), m_Edges.end()), m_Edges.end());
  std::vector<double> degree(numberOfPoints, 0.0);
  for (const auto & e : m_Edges)
  {
    degree[e[0]] += 1.0;
    degree[e[1]] += 1.0;
  }
  for (double alpha : settings.stiffness)
  {
    // I + alpha L: 1 + alpha deg(v) on the diagonal, -alpha for each edge.
    std::vector<Eigen::Triplet<double>> entries;
    entries.reserve(numberOfPoints + 2 * m_Edges.size());
    for (std::size_t v = 0; v < numberOfPoints; ++v)
    {
      entries.emplace_back(static_cast<int>(v), static_cast<int>(v), 1.0 + alpha * degree[v]);
    }
    for (const auto & e : m_Edges)
    {
      entries.emplace_back(static_cast<int>(e[0]), static_cast<int>(e[1]), -alpha);
      entries.emplace_back(static_cast<int>(e[1]), static_cast<int>(e[0]), -alpha);
    }
    Factors::SparseMatrix K(static_cast<Eigen::Index>(numberOfPoints), static_cast<Eigen::Index>(numberOfPoints));
    K.setFromTriplets(entries.begin(), entries.end());
    auto cholesky = std::make_unique<Factors::Cholesky>(K);
    if (cholesky->info() != Eigen::Success)
    {
      itkGenericExceptionMacro("The non-rigid stage cannot factorise I + " << alpha << " L of the template ("
                                                                           << numberOfPoints << " points).");
    }
    m_Factors->levels.push_back(std::move(cholesky));
  }
}

NonRigidTemplate::~NonRigidTemplate() = default;

void
NonRigidTemplate::Solve(std::size_t level, const std::vector<Vec3> & rhs, std::vector<Vec3> & x) const
{
  const Factors::Cholesky & cholesky = *m_Factors->levels.at(level);
  x.resize(rhs.size());
  // The three coordinates are independent systems with the same factors.
  ParallelForBlocks(3, 1, [&](std::size_t d, std::size_t, std::size_t) {
    Eigen::VectorXd b(static_cast<Eigen::Index>(rhs.size()));
    for (std::size_t v = 0; v < rhs.size(); ++v)
    {
      b[static_cast<Eigen::Index>(v)] = rhs[v][d];
    }
    const Eigen::VectorXd solution = cholesky.solve(b);
    for (std::size_t v = 0; v < rhs.size(); ++v)
    {
      x[v][d] = solution[static_cast<Eigen::Index>(v)];
    }
  });
}

// ---- one match ---------------------------------------------------------------------------

namespace
{
/** The state of one non-rigid match and its steps: the template's surface where it is
 * now, the pulls of both directions, the ARAP local and global steps. */
class NonRigidMatch
{
public:
  NonRigidMatch(const NonRigidTemplate & shape, const std::vector<Vec3> & start, const NonRigidTarget & target)
      : m_Template(shape)
      , m_Target(target)
      , m_Rest(start)
      , m_ForwardHints(start.size(), std::numeric_limits<std::uint32_t>::max())
      , m_BackwardHints(target.GetMesh().points.size(), std::numeric_limits<std::uint32_t>::max())
  {
    m_Surface.points = start;
    m_Surface.triangles = shape.GetTriangles();
    m_Tree.Build(m_Surface);
    if (shape.GetSettings().preventFolds)
    {
      m_Topology = BuildMeshTopology(m_Surface);
    }
  }

  /** One iteration at stiffness level `level`. */
  void
  Iterate(std::size_t level)
  {
    this->UpdateTemplateSurface();
    this->PullForward();
    this->PullBackward();
    const std::vector<Vec3> targets = this->PulledPositions();
    this->FitLocalRotations();
    const double      alpha = m_Template.GetSettings().stiffness[level];
    std::vector<Vec3> rhs = this->RotatedRestEdges();
    for (std::size_t v = 0; v < rhs.size(); ++v)
    {
      rhs[v] = targets[v] + rhs[v] * alpha;
    }
    m_Template.Solve(level, rhs, m_Surface.points);
  }

  /** The moves since `checkpoint` (a surface free of folds and crossings) that make
   * triangles cross, fold, turn over or degenerate, undone. */
  void
  UndoFoldsSince(const std::vector<Vec3> & checkpoint)
  {
    UndoFoldingMoves(m_Surface, m_Topology, checkpoint, ValidityThresholds::DegenerateQAreaTolerance);
  }

  const std::vector<Vec3> &
  GetPoints() const
  {
    return m_Surface.points;
  }

private:
  /** Normals and areas of the template where it is now, and its tree refitted. */
  void
  UpdateTemplateSurface()
  {
    SurfaceNormalsAndAreas(m_Surface, m_TriangleNormals, m_VertexAreas, m_VertexNormals);
    AxisAlignedBoxArray boxes(m_Surface.triangles.size());
    for (std::uint32_t f = 0; f < boxes.size(); ++f)
    {
      boxes[f] = TriangleBox(m_Surface, f);
    }
    m_Tree.Refit(m_Surface, boxes);
  }

  /** Forward pairs: each template vertex to its closest point on the target, weighted by
   * its area, unless the target's triangle faces the other way (the far side of a thin
   * process). */
  void
  PullForward()
  {
    const auto & X = m_Surface.points;
    m_Pull.assign(X.size(), MakeVec3(0, 0, 0));
    m_Weight.assign(X.size(), 0.0);
    ParallelForBlocks(X.size(), Block, [&](std::size_t begin, std::size_t end, std::size_t) {
      for (std::size_t v = begin; v < end; ++v)
      {
        const SurfacePoint s = m_Target.GetSurface().FindOne(X[v], m_ForwardHints[v]);
        m_ForwardHints[v] = s.triangle;
        if (Dot(m_Target.triangleNormals[s.triangle], m_VertexNormals[v]) >= 0.0)
        {
          m_Pull[v] = (s.point - X[v]) * m_VertexAreas[v];
          m_Weight[v] = m_VertexAreas[v];
        }
      }
    });
  }

  /** Backward pairs: each target vertex to its closest point on the template, its
   * residual shared by the corners of that triangle by their barycentric weights times
   * the target vertex's area; the same facing test. */
  void
  PullBackward()
  {
    const IndexedTriangleMesh & target = m_Target.GetMesh();
    struct Pair
    {
      std::uint32_t triangle;
      double        weights[3];
      Vec3          residual;
      bool          valid;
    };
    std::vector<Pair> pairs(target.points.size());
    ParallelForBlocks(target.points.size(), Block, [&](std::size_t begin, std::size_t end, std::size_t) {
      for (std::size_t j = begin; j < end; ++j)
      {
        const Vec3 &                    y = target.points[j];
        const TriangleAABBTree::Nearest nearest = m_Tree.FindNearest(y, m_BackwardHints[j]);
        m_BackwardHints[j] = nearest.triangle;
        const TriangleIndices & t = m_Surface.triangles[nearest.triangle];
        Pair &                  pair = pairs[j];
        pair.triangle = nearest.triangle;
        pair.valid = Dot(m_TriangleNormals[nearest.triangle], m_Target.vertexNormals[j]) >= 0.0;
        pair.residual = y - nearest.point;
        BarycentricWeights(
          nearest.point, m_Surface.points[t[0]], m_Surface.points[t[1]], m_Surface.points[t[2]], pair.weights);
      }
    });
    // Gathered in target-vertex order: the sums do not depend on the threads.
    for (std::size_t j = 0; j < pairs.size(); ++j)
    {
      if (!pairs[j].valid)
      {
        continue;
      }
      const TriangleIndices & t = m_Surface.triangles[pairs[j].triangle];
      for (unsigned int k = 0; k < 3; ++k)
      {
        const double w = m_Target.vertexAreas[j] * pairs[j].weights[k];
        m_Pull[t[k]] += pairs[j].residual * w;
        m_Weight[t[k]] += w;
      }
    }
  }

  /** c_v = x_v + the weighted mean of the pulls on v (x_v where nothing pulls). */
  std::vector<Vec3>
  PulledPositions() const
  {
    std::vector<Vec3> c = m_Surface.points;
    for (std::size_t v = 0; v < c.size(); ++v)
    {
      if (m_Weight[v] > 0.0)
      {
        c[v] += m_Pull[v] * (1.0 / m_Weight[v]);
      }
    }
    return c;
  }

  /** The local step: R_v = argmin sum_u |(x_v - x_u) - R (x0_v - x0_u)|^2 over v's
   * neighbours u, the rotation of the SVD of sum (x_v - x_u)(x0_v - x0_u)^T. */
  void
  FitLocalRotations()
  {
    const auto &                 X = m_Surface.points;
    std::vector<Eigen::Matrix3d> covariance(X.size(), Eigen::Matrix3d::Zero());
    for (const auto & e : m_Template.GetEdges())
    {
      const Eigen::Matrix3d c = ToEigen(X[e[0]] - X[e[1]]) * ToEigen(m_Rest[e[0]] - m_Rest[e[1]]).transpose();
      covariance[e[0]] += c;
      covariance[e[1]] += c;
    }
    m_Rotations.resize(X.size());
    ParallelForBlocks(X.size(), Block, [&](std::size_t begin, std::size_t end, std::size_t) {
      for (std::size_t v = begin; v < end; ++v)
      {
        Eigen::JacobiSVD<Eigen::Matrix3d> svd(covariance[v], Eigen::ComputeFullU | Eigen::ComputeFullV);
        Eigen::Vector3d                   d(1.0, 1.0, (svd.matrixU() * svd.matrixV().transpose()).determinant());
        d[2] = d[2] < 0.0 ? -1.0 : 1.0;
        m_Rotations[v] = svd.matrixU() * d.asDiagonal() * svd.matrixV().transpose();
      }
    });
  }

  /** b_v = sum_u (R_v + R_u)/2 (x0_v - x0_u): the rest edges turned by the local rotations. */
  std::vector<Vec3>
  RotatedRestEdges() const
  {
    std::vector<Vec3> b(m_Rest.size(), MakeVec3(0, 0, 0));
    for (const auto & e : m_Template.GetEdges())
    {
      const Vec3 turned =
        FromEigen(0.5 * (m_Rotations[e[0]] + m_Rotations[e[1]]) * ToEigen(m_Rest[e[0]] - m_Rest[e[1]]));
      b[e[0]] += turned;
      b[e[1]] -= turned;
    }
    return b;
  }

  const NonRigidTemplate &     m_Template;
  const NonRigidTarget &       m_Target;
  const std::vector<Vec3>      m_Rest;
  IndexedTriangleMesh          m_Surface;  ///< the template where it is now
  MeshTopology                 m_Topology; ///< the template's, for the fold check
  TriangleAABBTree             m_Tree;
  std::vector<std::uint32_t>   m_ForwardHints, m_BackwardHints;
  std::vector<Vec3>            m_TriangleNormals, m_VertexNormals;
  std::vector<double>          m_VertexAreas;
  std::vector<Vec3>            m_Pull;
  std::vector<double>          m_Weight;
  std::vector<Eigen::Matrix3d> m_Rotations;
};
} // namespace

std::vector<Vec3>
MatchNonRigid(const NonRigidTemplate &            shape,
              const std::vector<Vec3> &           start,
              const NonRigidTarget &              target,
              const std::function<void(double)> & progress)
{
  if (start.size() != shape.GetNumberOfPoints())
  {
    itkGenericExceptionMacro("The non-rigid match got " << start.size() << " points for a template of "
                                                        << shape.GetNumberOfPoints() << '.');
  }
  NonRigidMatch     match(shape, start, target);
  const auto &      settings = shape.GetSettings();
  const std::size_t total = settings.stiffness.size() * settings.iterationsPerLevel;
  std::size_t       done = 0;
  std::vector<Vec3> checkpoint = start;
  for (std::size_t level = 0; level < settings.stiffness.size(); ++level)
  {
    for (unsigned int iteration = 0; iteration < settings.iterationsPerLevel; ++iteration)
    {
      match.Iterate(level);
      ++done;
      // The fold check every few iterations (and after the last), against the surface
      // of the previous check: each check searches the whole surface.
      if (settings.preventFolds && (done % std::max(1u, settings.foldCheckInterval) == 0 || done == total))
      {
        match.UndoFoldsSince(checkpoint);
        checkpoint = match.GetPoints();
      }
      if (progress)
      {
        progress(static_cast<double>(done) / static_cast<double>(total));
      }
    }
  }
  return match.GetPoints();
}
} // namespace detail
} // namespace MeshExtraction
} // namespace itk
