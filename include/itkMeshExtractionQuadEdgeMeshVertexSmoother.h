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
#ifndef itkMeshExtractionQuadEdgeMeshVertexSmoother_h
#define itkMeshExtractionQuadEdgeMeshVertexSmoother_h

#include "itkMeshExtractionIndexedTriangleMesh.h"
#include "itkMeshExtractionParallel.h"
#include "itkMeshExtractionValidityGuard.h"
#include "itkMeshExtractionVertexSmoothing.h"
#include "itkQuadEdgeMeshParamMatrixCoefficients.h"

#include <cstdint>
#include <unordered_map>
#include <string>
#include <vector>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
/** \class QuadEdgeMeshVertexSmoother
 * \brief Smoothing steps on a triangle QuadEdgeMesh, in place: the engine shared by
 * LaplacianSmoothingQuadEdgeMeshFilter and TaubinSmoothingQuadEdgeMeshFilter.
 *
 * Initialize() collects, once, every vertex that may move and its ordered 1-ring
 * (the connectivity does not change while smoothing). A vertex may move if its
 * incident triangles form one closed fan (interior vertex) or, when boundary
 * vertices are not fixed, one open fan (boundary vertex); isolated points, points
 * on wire edges only and non-manifold points (several fans) never move.
 *
 * Step() moves every movable vertex once, in increasing point identifier order,
 * with the pure functions of itkMeshExtractionVertexSmoothing.h and the guard of
 * itkMeshExtractionValidityGuard.h:
 * - Batch: all displacements are computed from the positions at the start of the
 *   step (multithreaded, one result per vertex, so the outcome does not depend on
 *   the number of threads); then they are applied one by one, each through the
 *   no-inversion guard evaluated against the current positions, so that the
 *   guarantee also holds for neighbours that move in the same step (thesis
 *   Figure 4.6);
 * - Immediate: each vertex computes its displacement from the current positions
 *   and moves at once (Gauss-Seidel).
 * With the guard on, no incident triangle of a moving vertex may turn by 90 degrees
 * or more against its orientation before the move nor against its orientation at
 * the start of the step (or of an earlier step, see Step()); so each step leaves
 * every triangle within 90 degrees of where it started, which is what
 * TriangleMeshQualityCalculator counts as "not inverted versus the reference".
 * Every position is rounded to the mesh's coordinate type before it is checked and
 * stored, so the guard sees exactly what the mesh holds.
 *
 * Optionally the weights come from an ITK MatrixCoefficients object (Ones,
 * InverseEuclideanDistance, Conformal, Authalic, ...) evaluated on each 1-ring edge.
 *
 * \ingroup MeshExtraction
 */
template <typename TMesh>
class QuadEdgeMeshVertexSmoother
{
public:
  using MeshType = TMesh;
  using QEType = typename MeshType::QEType;
  using PointIdentifier = typename MeshType::PointIdentifier;
  using CellIdentifier = typename MeshType::CellIdentifier;
  using CoordinateType = typename MeshType::PointType::ValueType;
  using CoefficientsType = MatrixCoefficients<MeshType>;

  struct StepParameters
  {
    MeshExtractionEnums::SmoothingWeights weights{ MeshExtractionEnums::SmoothingWeights::Uniform };
    MeshExtractionEnums::SmoothingUpdate  update{ MeshExtractionEnums::SmoothingUpdate::Batch };
    VertexSmoothingParameters             move;
    bool                                  preventInversions{ true };
    unsigned int                          maximumShortenings{ ValidityThresholds::MaximumShortenings };
    double                                degenerateQAreaTolerance{ ValidityThresholds::DegenerateQAreaTolerance };
    /** If set, replaces `weights`: w_j = (*coefficients)(mesh, edge to v_j). */
    const CoefficientsType * coefficients{ nullptr };
    unsigned int             numberOfWorkUnits{ 0 };
  };

  struct Counters
  {
    std::size_t moves{ 0 };     ///< vertices with a non-zero displacement
    std::size_t shortened{ 0 }; ///< moves the guard shortened
    std::size_t rejected{ 0 };  ///< moves the guard cancelled
  };

  /** The first face of `mesh` that is not a triangle (a polygon cell with other than
   * three points): its identifier and number of points. Returns false if all are
   * triangles. Vertex and line cells are ignored. */
  static bool
  FindNonTriangleFace(const MeshType & mesh, CellIdentifier & cell, unsigned int & numberOfPoints)
  {
    const auto * cells = mesh.GetCells();
    if (cells == nullptr)
    {
      return false;
    }
    for (auto it = cells->Begin(); it != cells->End(); ++it)
    {
      const auto * c = it.Value();
      if (c == nullptr)
      {
        continue;
      }
      const auto type = c->GetType();
      if (type == CellGeometryEnum::VERTEX_CELL || type == CellGeometryEnum::LINE_CELL ||
          type == CellGeometryEnum::QUADRATIC_EDGE_CELL)
      {
        continue;
      }
      if (c->GetNumberOfPoints() != 3)
      {
        cell = it.Index();
        numberOfPoints = static_cast<unsigned int>(c->GetNumberOfPoints());
        return true;
      }
    }
    return false;
  }

  /** Empty if every face of `mesh` is a triangle, else the message that names the
   * first face that is not (the filters' clear error for non-triangle input). */
  static std::string
  DescribeNonTriangleFace(const MeshType & mesh)
  {
    CellIdentifier cell = 0;
    unsigned int   numberOfPoints = 0;
    if (!FindNonTriangleFace(mesh, cell, numberOfPoints))
    {
      return std::string();
    }
    return "The input must be a triangle mesh, but face " + std::to_string(cell) + " has " +
           std::to_string(numberOfPoints) + " points";
  }

  /** Collects the movable vertices of `mesh` and their 1-rings. The mesh must stay
   * alive and keep its connectivity while Step() is used. */
  void
  Initialize(MeshType * mesh, bool fixBoundary)
  {
    m_Mesh = mesh;
    m_FoldCheck = IndexedTriangleMesh();
    m_PointIds.clear();
    m_Positions.clear();
    m_Movable.clear();
    m_Closed.clear();
    m_RingOffsets.assign(1, 0);
    m_Ring.clear();
    m_RingEdges.clear();
    const auto * points = mesh->GetPoints();
    if (points == nullptr)
    {
      return;
    }
    std::unordered_map<PointIdentifier, std::uint32_t> index;
    index.reserve(points->Size());
    m_PointIds.reserve(points->Size());
    m_Positions.reserve(points->Size());
    for (auto it = points->Begin(); it != points->End(); ++it)
    {
      index.emplace(it.Index(), static_cast<std::uint32_t>(m_PointIds.size()));
      m_PointIds.push_back(it.Index());
      m_Positions.push_back(ToVec3(it.Value()));
    }
    std::vector<QEType *> edges;
    std::uint32_t         k = 0;
    for (auto it = points->Begin(); it != points->End(); ++it, ++k)
    {
      QEType * first = it.Value().GetEdge();
      if (first == nullptr)
      {
        continue;
      }
      edges.clear();
      std::size_t gaps = 0;
      std::size_t gapPosition = 0;
      QEType *    e = first;
      do
      {
        if (!e->IsLeftSet())
        {
          ++gaps;
          gapPosition = edges.size();
        }
        edges.push_back(e);
        e = e->GetOnext();
      } while (e != first && e != nullptr && edges.size() <= points->Size());
      const bool closed = gaps == 0;
      if (gaps > 1 || (gaps == 1 && fixBoundary) || edges.size() < (closed ? 3u : 2u))
      {
        continue;
      }
      // An open ring starts right after the edge without a left face, so that its
      // triangles are (v, ring[i], ring[i+1]) for i = 0..size-2.
      const std::size_t start = closed ? 0 : gapPosition + 1;
      bool              complete = true;
      const std::size_t offset = m_Ring.size();
      for (std::size_t i = 0; i < edges.size(); ++i)
      {
        QEType *   edge = edges[(start + i) % edges.size()];
        const auto found = index.find(edge->GetDestination());
        if (found == index.end())
        {
          complete = false;
          break;
        }
        m_Ring.push_back(found->second);
        m_RingEdges.push_back(edge);
      }
      if (!complete)
      {
        m_Ring.resize(offset);
        m_RingEdges.resize(offset);
        continue;
      }
      m_Movable.push_back(k);
      m_Closed.push_back(closed ? 1 : 0);
      m_RingOffsets.push_back(m_Ring.size());
    }
  }

  std::size_t
  GetNumberOfMovableVertices() const
  {
    return m_Movable.size();
  }

  /** One smoothing step (see the class documentation); adds to `counters`. With
   * `newReference` false the guard keeps the reference orientations of the previous
   * step's start (Taubin: the lambda and mu steps of one iteration share it). */
  void
  Step(const StepParameters & p, Counters & counters, bool newReference = true)
  {
    const std::size_t n = m_Movable.size();
    if (n == 0)
    {
      return;
    }
    if (newReference || m_StepStart.size() != m_Positions.size())
    {
      m_StepStart = m_Positions;
    }
    if (p.update == MeshExtractionEnums::SmoothingUpdate::Batch)
    {
      std::vector<Vec3> displacements(n);
      ParallelForBlocks(
        n,
        256,
        [&](std::size_t begin, std::size_t end, std::size_t) {
          std::vector<Vec3>   buffer;
          std::vector<double> weights;
          for (std::size_t j = begin; j < end; ++j)
          {
            const VertexOneRing ring = MakeRing(j, buffer);
            displacements[j] = SmoothingDisplacement(p.move, ring, Target(p, j, ring, weights));
          }
        },
        p.numberOfWorkUnits);
      std::vector<Vec3> buffer;
      std::vector<Vec3> startBuffer;
      for (std::size_t j = 0; j < n; ++j)
      {
        const VertexOneRing start = MakeRing(j, startBuffer, m_StepStart);
        Apply(p, j, MakeRing(j, buffer), start, displacements[j], counters);
      }
    }
    else
    {
      std::vector<Vec3>   buffer;
      std::vector<Vec3>   startBuffer;
      std::vector<double> weights;
      for (std::size_t j = 0; j < n; ++j)
      {
        const VertexOneRing ring = MakeRing(j, buffer);
        const VertexOneRing start = MakeRing(j, startBuffer, m_StepStart);
        Apply(p, j, ring, start, SmoothingDisplacement(p.move, ring, Target(p, j, ring, weights)), counters);
      }
    }
    m_Mesh->GetPoints()->Modified();
    m_Mesh->Modified();
  }

  /** After Step() (or a Taubin pair of steps that share one start): the guard
   * looks at one vertex at a time, so undo the moves that made the surface cut
   * through itself, fold, turn a triangle over or degenerate, or turn a closed
   * component inside out, against the positions at the step's start, and those
   * that collapse a component or move a surface past it, against the mesh at the
   * first call (UndoFoldingMoves with a ComponentReference: exact intersection tests,
   * signed volumes, nesting parity). Returns the number of vertices moved back. The
   * triangles and their topology are read from the mesh on the first call (the
   * smoother does not change them). */
  std::size_t
  UndoFoldingMoves(double degenerateQAreaTolerance)
  {
    if (m_StepStart.size() != m_Positions.size() || m_Positions.empty())
    {
      return 0;
    }
    if (m_FoldCheck.points.size() != m_Positions.size())
    {
      m_FoldCheck = MakeIndexedTriangleMesh(*m_Mesh); // points in the same order as m_Positions
      m_FoldTopology = BuildMeshTopology(m_FoldCheck);
      // Each component's volume and nesting before the first step.
      m_FoldCheck.points = m_StepStart;
      m_Reference = MakeComponentReference(m_FoldCheck, m_FoldTopology);
    }
    m_FoldCheck.points = m_Positions;
    const std::size_t undone = MeshExtraction::detail::UndoFoldingMoves(
      m_FoldCheck, m_FoldTopology, m_StepStart, degenerateQAreaTolerance, &m_Reference);
    if (undone > 0)
    {
      for (std::size_t k = 0; k < m_Positions.size(); ++k)
      {
        if (m_FoldCheck.points[k] != m_Positions[k])
        {
          this->Store(k, m_FoldCheck.points[k]); // a start position: stored exactly
        }
      }
      m_Mesh->GetPoints()->Modified();
      m_Mesh->Modified();
    }
    return undone;
  }

private:
  static Vec3
  Round(const Vec3 & x)
  {
    // Not a plain static_cast round trip, which GCC 12 may drop (see RoundToCoordinateType).
    return RoundToCoordinateType<CoordinateType>(x);
  }

  VertexOneRing
  MakeRing(std::size_t j, std::vector<Vec3> & buffer) const
  {
    return MakeRing(j, buffer, m_Positions);
  }

  VertexOneRing
  MakeRing(std::size_t j, std::vector<Vec3> & buffer, const std::vector<Vec3> & positions) const
  {
    const std::size_t begin = m_RingOffsets[j];
    const std::size_t end = m_RingOffsets[j + 1];
    buffer.resize(end - begin);
    for (std::size_t i = begin; i < end; ++i)
    {
      buffer[i - begin] = positions[m_Ring[i]];
    }
    VertexOneRing ring;
    ring.center = positions[m_Movable[j]];
    ring.ring = buffer.data();
    ring.size = buffer.size();
    ring.closed = m_Closed[j] != 0;
    return ring;
  }

  Vec3
  Target(const StepParameters & p, std::size_t j, const VertexOneRing & ring, std::vector<double> & weights) const
  {
    if (p.coefficients == nullptr)
    {
      return LaplacianTarget(p.weights, ring);
    }
    const std::size_t begin = m_RingOffsets[j];
    weights.resize(ring.size);
    for (std::size_t i = 0; i < ring.size; ++i)
    {
      weights[i] = static_cast<double>((*p.coefficients)(m_Mesh, m_RingEdges[begin + i]));
    }
    return WeightedLaplacianTarget(ring, weights.data());
  }

  void
  Apply(const StepParameters & p,
        std::size_t            j,
        const VertexOneRing &  ring,
        const VertexOneRing &  start,
        const Vec3 &           displacement,
        Counters &             c)
  {
    Vec3 position = ring.center;
    if (p.preventInversions)
    {
      const GuardedVertexMove move =
        GuardVertexMove(ring, displacement, p.maximumShortenings, p.degenerateQAreaTolerance, &Round, &start);
      position = move.position;
      c.moves += move.outcome != VertexMoveOutcome::Unchanged ? 1 : 0;
      c.shortened += move.outcome == VertexMoveOutcome::Shortened ? 1 : 0;
      c.rejected += move.outcome == VertexMoveOutcome::Rejected ? 1 : 0;
    }
    else
    {
      position = Round(ring.center + displacement);
      c.moves += position != ring.center ? 1 : 0;
    }
    if (position != ring.center)
    {
      this->Store(m_Movable[j], position);
    }
  }

  /** Point k (compact index) to `position`, in the smoother and in the mesh. */
  void
  Store(std::size_t k, const Vec3 & position)
  {
    m_Positions[k] = position;
    auto & point = m_Mesh->GetPoints()->ElementAt(m_PointIds[k]);
    for (unsigned int d = 0; d < 3; ++d)
    {
      point[d] = static_cast<CoordinateType>(position[d]);
    }
  }

  MeshType *                   m_Mesh{ nullptr };
  std::vector<PointIdentifier> m_PointIds;    ///< compact index -> point identifier
  std::vector<Vec3>            m_Positions;   ///< compact index -> current position
  std::vector<Vec3>            m_StepStart;   ///< compact index -> position at the start of the step
  std::vector<std::uint32_t>   m_Movable;     ///< compact indices of the movable vertices
  std::vector<std::uint8_t>    m_Closed;      ///< per movable vertex: closed ring
  std::vector<std::size_t>     m_RingOffsets; ///< per movable vertex: its ring in m_Ring
  std::vector<std::uint32_t>   m_Ring;        ///< compact indices of the ring vertices
  std::vector<QEType *>        m_RingEdges;   ///< the edge from the vertex to each ring vertex
  IndexedTriangleMesh          m_FoldCheck;   ///< UndoFoldingMoves: the triangles (points set per call)
  MeshTopology                 m_FoldTopology;
  ComponentReference           m_Reference; ///< the components before the first step
};

} // namespace detail
} // namespace MeshExtraction
} // namespace itk

#endif
