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
// The validity guard for the node moves of the high-quality SurfaceNets mode:
// PullBackInvalidMoves.
#include "itkMeshExtractionValidityGuard.h"
#include "itkMeshExtractionClosedSurfaceEdgeSwap.h"
#include "itkMeshExtractionParallel.h"
#include "itkMeshExtractionQualityAnalysis.h"
#include "itkMeshExtractionTriangleAABBTree.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
namespace
{
constexpr std::uint32_t None = std::numeric_limits<std::uint32_t>::max();

/** The per-triangle loops are independent per triangle: they run on the work units in
 * blocks of this many triangles (the results do not depend on their number). */
constexpr std::size_t BlockSize = 8192;

/** The margin of the SelfIntersectionCache, as a fraction of the mean edge length at
 * the start: a wider margin keeps more pairs of faces near each other to test, a
 * narrower one makes more faces count as moved after a relaxation. It does not change
 * what is found. */
constexpr double CacheMarginPerMeanEdge = 0.4;

/** A face's normal (not normalised) with its length. */
struct FaceNormal
{
  Vec3   normal;
  double length;
};

/** The faces fold (ValidityThresholds::FoldCosine, with n.m / (|n| |m|)). */
inline bool
Folded(const FaceNormal & n, const FaceNormal & m)
{
  return Dot(n.normal, m.normal) < ValidityThresholds::FoldCosine * n.length * m.length;
}

/** The cosine of the angle between the normals went down from (n0, m0) to (n, m)
 * (both as n.m / (|n| |m|)). */
inline bool
FoldClosed(const FaceNormal & n0, const FaceNormal & m0, const FaceNormal & n, const FaceNormal & m)
{
  return Dot(n.normal, m.normal) * n0.length * m0.length < Dot(n0.normal, m0.normal) * n.length * m.length;
}

/** \brief The steps of PullBackInvalidMoves() on one relaxation's moves.
 *
 * Nodes only move back toward `start`, so one tree of boxes around both positions of
 * every triangle serves every round. Each round checks the faces at the nodes that
 * changed (candidates) and pulls back the nodes of the invalid ones. */
class MovePullBack
{
public:
  MovePullBack(LargeBlockVector<Vec3> &       positions,
               const LargeBlockVector<Vec3> & start,
               const SurfaceNetTriangles &    mesh,
               const Vec3 &                   origin,
               const Matrix<double, 3, 3> &   indexToPhysical,
               double                         tolerance,
               bool                           roundToFloat,
               SelfIntersectionCache *        cache,
               const ComponentVolumes *       volumes)
      : m_Positions(positions)
      , m_Start(start)
      , m_Mesh(mesh)
      , m_Origin(origin)
      , m_IndexToPhysical(indexToPhysical)
      , m_Tolerance(tolerance)
      , m_RoundToFloat(roundToFloat)
      , m_Cache(cache)
      , m_Volumes(volumes)
  {}

  std::size_t
  Run(TriangleAABBTree * sharedTree)
  {
    this->MeasureStart();
    m_Check.triangles = m_Mesh.triangles;
    m_Check.points = ToPhysical(m_Positions, m_Origin, m_IndexToPhysical, m_RoundToFloat);
    AxisAlignedBoxArray boxes = this->FoldsAtStartAndBoxes();
    if (m_Cache != nullptr)
    {
      this->GrowBoxesByCacheMargin(boxes);
    }
    TriangleAABBTree   localTree;
    TriangleAABBTree & tree = sharedTree != nullptr ? *sharedTree : localTree;
    BuildOrRefitTree(tree, m_Check, boxes);

    const std::size_t n = m_Positions.size();
    m_Moved.assign(n, false);
    m_Pulls.assign(n, 0);
    m_ChangedVertex.assign(n, false);
    for (std::size_t v = 0; v < n; ++v)
    {
      m_ChangedVertex[v] = m_Positions[v] != m_Start[v]; // `start` is valid: only moved nodes matter
    }
    // The normals at m_Check.points: the start normals until a face's vertex moves (the
    // same points, made by the same ToPhysical, so the same bits).
    m_Normals = m_StartNormals;
    for (unsigned int round = 0; round < ValidityThresholds::MaximumRepairRounds; ++round)
    {
      if (round > 0)
      {
        m_Check.points = ToPhysical(m_Positions, m_Origin, m_IndexToPhysical, m_RoundToFloat);
      }
      this->CollectCandidates();
      this->UpdateCandidateNormals();
      const std::vector<std::uint32_t> badNodes = this->BadNodes(tree);
      std::fill(m_ChangedVertex.begin(), m_ChangedVertex.end(), false);
      if (badNodes.empty())
      {
        break;
      }
      this->PullBack(badNodes);
      if (round + 1 == ValidityThresholds::MaximumRepairRounds)
      {
        m_Positions = m_Start; // not expected; `start` was valid
      }
    }
    return static_cast<std::size_t>(std::count(m_Moved.begin(), m_Moved.end(), true));
  }

private:
  FaceNormal
  NormalOf(const Vec3 * points, std::size_t f) const
  {
    const auto & t = m_Mesh.triangles[f];
    const Vec3   n = TriangleNormal(points[t[0]], points[t[1]], points[t[2]]);
    return FaceNormal{ n, Norm(n) };
  }

  /** The start's physical points and each face's normal there: every fold test reads
   * two faces' normals instead of computing both again, once from each side of every
   * edge. */
  void
  MeasureStart()
  {
    const std::size_t numberOfTriangles = m_Mesh.triangles.size();
    m_StartPhysical.resize(m_Start.size());
    ToPhysical(m_Start.data(), m_Start.size(), m_Origin, m_IndexToPhysical, m_RoundToFloat, m_StartPhysical.data());
    m_StartNormals.resize(numberOfTriangles);
    ParallelForBlocks(numberOfTriangles, BlockSize, [&](std::size_t begin, std::size_t end, std::size_t) {
      for (std::size_t f = begin; f < end; ++f)
      {
        m_StartNormals[f] = this->NormalOf(m_StartPhysical.data(), f);
      }
    });
  }

  /** Which edges of each face fold at the start (bit k: edge k), and the box of each
   * face around its corners now and at the start. */
  AxisAlignedBoxArray
  FoldsAtStartAndBoxes()
  {
    const std::size_t numberOfTriangles = m_Mesh.triangles.size();
    m_FoldedAtStart.assign(numberOfTriangles, 0);
    AxisAlignedBoxArray boxes(numberOfTriangles);
    ParallelForBlocks(numberOfTriangles, BlockSize, [&](std::size_t begin, std::size_t end, std::size_t) {
      for (std::size_t f = begin; f < end; ++f)
      {
        for (unsigned int k = 0; k < 3; ++k)
        {
          if (Folded(m_StartNormals[f], m_StartNormals[m_Mesh.twin[3 * f + k] / 3]))
          {
            m_FoldedAtStart[f] |= static_cast<std::uint8_t>(1u << k);
          }
        }
        for (std::uint32_t v : m_Mesh.triangles[f])
        {
          boxes[f].Add(m_Check.points[v]);
          boxes[f].Add(m_StartPhysical[v]);
        }
      }
    });
    return boxes;
  }

  /** The cache needs boxes grown by half its margin, which is set on the first call. */
  void
  GrowBoxesByCacheMargin(AxisAlignedBoxArray & boxes) const
  {
    if (!(m_Cache->margin > 0.0))
    {
      double      sum = 0.0;
      std::size_t count = 0;
      for (const auto & t : m_Mesh.triangles)
      {
        for (unsigned int k = 0; k < 3; ++k)
        {
          const double length = std::sqrt(SquaredNorm(m_StartPhysical[t[k]] - m_StartPhysical[t[(k + 1) % 3]]));
          if (std::isfinite(length))
          {
            sum += length;
            ++count;
          }
        }
      }
      m_Cache->margin = count > 0 ? CacheMarginPerMeanEdge * sum / static_cast<double>(count) : 0.0;
    }
    for (auto & box : boxes)
    {
      for (unsigned int d = 0; d < 3; ++d)
      {
        box.lower[d] -= 0.5 * m_Cache->margin;
        box.upper[d] += 0.5 * m_Cache->margin;
      }
    }
  }

  /** The faces with a vertex that changed since the last round. */
  void
  CollectCandidates()
  {
    m_Candidates.clear();
    for (std::uint32_t f = 0; f < m_Mesh.triangles.size(); ++f)
    {
      const auto & t = m_Mesh.triangles[f];
      if (m_ChangedVertex[t[0]] || m_ChangedVertex[t[1]] || m_ChangedVertex[t[2]])
      {
        m_Candidates.push_back(f);
      }
    }
  }

  void
  UpdateCandidateNormals()
  {
    ParallelForBlocks(m_Candidates.size(), BlockSize, [&](std::size_t begin, std::size_t end, std::size_t) {
      for (std::size_t i = begin; i < end; ++i)
      {
        m_Normals[m_Candidates[i]] = this->NormalOf(m_Check.points.data(), m_Candidates[i]);
      }
    });
  }

  /** The nodes of the candidates that flipped, degenerated or fold anew, of those that
   * intersect another face, and the moved nodes of collapsed components, sorted. */
  std::vector<std::uint32_t>
  BadNodes(const TriangleAABBTree & tree) const
  {
    std::vector<std::uint32_t> badNodes = this->NodesOfFlippedDegenerateOrFoldedFaces();
    const auto &               triangles = m_Mesh.triangles;
    for (const auto & p : FindSelfIntersections(m_Check, m_Candidates, tree, m_Cache))
    {
      badNodes.insert(badNodes.end(), triangles[p.first].begin(), triangles[p.first].end());
      badNodes.insert(badNodes.end(), triangles[p.second].begin(), triangles[p.second].end());
    }
    this->AddMovedNodesOfCollapsedComponents(badNodes);
    std::sort(badNodes.begin(), badNodes.end());
    badNodes.erase(std::unique(badNodes.begin(), badNodes.end()), badNodes.end());
    return badNodes;
  }

  /** Per block of candidates (the nodes are sorted and made unique afterwards, so the
   * blocks' order does not matter). */
  std::vector<std::uint32_t>
  NodesOfFlippedDegenerateOrFoldedFaces() const
  {
    std::vector<std::vector<std::uint32_t>> badPerBlock((m_Candidates.size() + BlockSize - 1) / BlockSize);
    ParallelForBlocks(m_Candidates.size(), BlockSize, [&](std::size_t begin, std::size_t end, std::size_t block) {
      for (std::size_t i = begin; i < end; ++i)
      {
        this->AddNodesIfInvalid(m_Candidates[i], badPerBlock[block]);
      }
    });
    std::vector<std::uint32_t> badNodes;
    for (const auto & bad : badPerBlock)
    {
      badNodes.insert(badNodes.end(), bad.begin(), bad.end());
    }
    return badNodes;
  }

  /** Face f flipped against its start or degenerated: its nodes; f folds against a
   * neighbour anew, or a fold at `start` closed further: the nodes of both. Left
   * alone, the faces of a fold can close onto each other (two nodes with the same
   * 1-ring, pulled to one point, leave a component of no volume). */
  void
  AddNodesIfInvalid(std::uint32_t f, std::vector<std::uint32_t> & bad) const
  {
    const auto & triangles = m_Mesh.triangles;
    const auto & t = triangles[f];
    const Vec3 & a = m_Check.points[t[0]];
    const Vec3 & b = m_Check.points[t[1]];
    const Vec3 & c = m_Check.points[t[2]];
    if (!(Dot(m_Normals[f].normal, m_StartNormals[f].normal) > 0.0) || !(TriangleQArea(a, b, c) > m_Tolerance))
    {
      bad.insert(bad.end(), t.begin(), t.end());
      return;
    }
    for (unsigned int k = 0; k < 3; ++k)
    {
      const std::uint32_t g = m_Mesh.twin[3 * f + k] / 3;
      if (((m_FoldedAtStart[f] >> k) & 1u)
            ? FoldClosed(m_StartNormals[f], m_StartNormals[g], m_Normals[f], m_Normals[g])
            : Folded(m_Normals[f], m_Normals[g]))
      {
        const auto & u = triangles[g];
        bad.insert(bad.end(), t.begin(), t.end());
        bad.insert(bad.end(), u.begin(), u.end());
      }
    }
  }

  /** Components turned inside out or flattened: all their moved nodes. */
  void
  AddMovedNodesOfCollapsedComponents(std::vector<std::uint32_t> & badNodes) const
  {
    if (m_Volumes == nullptr)
    {
      return;
    }
    const std::vector<bool> collapsed = m_Volumes->Collapsed(m_Mesh.triangles, m_Check.points);
    if (std::find(collapsed.begin(), collapsed.end(), true) == collapsed.end())
    {
      return;
    }
    for (std::uint32_t v = 0; v < m_Positions.size(); ++v)
    {
      const std::uint32_t c = m_Volumes->vertexComponent[v];
      if (c != None && collapsed[c] && m_Positions[v] != m_Start[v])
      {
        badNodes.push_back(v);
      }
    }
  }

  /** Halves the move of each bad node that is not back yet, or resets it after
   * PullBackHalvingsBeforeReset halvings. */
  void
  PullBack(const std::vector<std::uint32_t> & badNodes)
  {
    for (std::uint32_t v : badNodes)
    {
      if (m_Positions[v] == m_Start[v])
      {
        continue; // already back: the other nodes of its triangles will move
      }
      m_Moved[v] = true;
      m_ChangedVertex[v] = true;
      m_Positions[v] = ++m_Pulls[v] > ValidityThresholds::PullBackHalvingsBeforeReset
                         ? m_Start[v]
                         : m_Start[v] + (m_Positions[v] - m_Start[v]) * 0.5;
    }
  }

  LargeBlockVector<Vec3> &       m_Positions;
  const LargeBlockVector<Vec3> & m_Start;
  const SurfaceNetTriangles &    m_Mesh;
  const Vec3 &                   m_Origin;
  const Matrix<double, 3, 3> &   m_IndexToPhysical;
  const double                   m_Tolerance;
  const bool                     m_RoundToFloat;
  SelfIntersectionCache *        m_Cache;
  const ComponentVolumes *       m_Volumes;

  LargeBlockVector<Vec3>       m_StartPhysical;
  LargeBlockVector<FaceNormal> m_StartNormals;
  LargeBlockVector<FaceNormal> m_Normals; ///< at m_Check.points
  std::vector<std::uint8_t>    m_FoldedAtStart;
  IndexedTriangleMesh          m_Check; ///< the physical points that will be written, with the triangles
  std::vector<bool>            m_Moved;
  std::vector<unsigned int>    m_Pulls;
  std::vector<bool>            m_ChangedVertex;
  std::vector<std::uint32_t>   m_Candidates;
};
} // namespace

std::size_t
PullBackInvalidMoves(LargeBlockVector<Vec3> &       positions,
                     const LargeBlockVector<Vec3> & start,
                     const SurfaceNetTriangles &    mesh,
                     const Vec3 &                   origin,
                     const Matrix<double, 3, 3> &   indexToPhysical,
                     double                         tolerance,
                     bool                           roundToFloat,
                     TriangleAABBTree *             tree,
                     SelfIntersectionCache *        cache,
                     const ComponentVolumes *       volumes)
{
  return MovePullBack(positions, start, mesh, origin, indexToPhysical, tolerance, roundToFloat, cache, volumes)
    .Run(tree);
}

} // namespace detail
} // namespace MeshExtraction
} // namespace itk
