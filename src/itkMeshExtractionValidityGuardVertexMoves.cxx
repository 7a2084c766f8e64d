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
// The validity guard for vertex moves of the smoothing filters and the edge
// detection: one move at a time (IsValidVertexMove), and a whole step afterwards
// (UndoFoldingMoves).
#include "itkMeshExtractionValidityGuard.h"
#include "itkMeshExtractionQualityAnalysis.h"
#include "itkMeshExtractionTriangleAABBTree.h"

#include <algorithm>
#include <cmath>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
namespace
{
/** \brief The steps of UndoFoldingMoves() on one mesh.
 *
 * A queue of triangles to check (those around the vertices that moved or went back)
 * and three ways a vertex goes back to its start: a queued triangle is invalid or
 * crosses another (CheckQueuedTriangles), its component collapsed
 * (UndoCollapsedComponents), or a surface passed its component
 * (UndoNestingChanges). */
class FoldingMoveUndo
{
public:
  FoldingMoveUndo(IndexedTriangleMesh &      mesh,
                  const MeshTopology &       topology,
                  const std::vector<Vec3> &  startPositions,
                  double                     tolerance,
                  const ComponentReference * reference)
      : m_Mesh(mesh)
      , m_Topology(topology)
      , m_Start(startPositions)
      , m_Tolerance(tolerance)
      , m_Reference(reference)
      , m_Queued(mesh.triangles.size(), 0)
  {}

  /** Collapsed components first; then, until nothing goes back: the queued triangles,
   * the components collapsed by what went back, and last whether a surface moved past
   * a component. Returns the number of vertices moved back. */
  std::size_t
  Run()
  {
    this->QueueMovedVertices();
    std::size_t undone = this->UndoAndQueue(this->UndoCollapsedComponents());
    while (true)
    {
      if (m_Queries.empty())
      {
        // Settled: last, whether a surface moved past a component.
        undone += this->UndoAndQueue(this->UndoNestingChanges());
        if (m_Queries.empty())
        {
          break;
        }
      }
      undone += this->UndoAndQueue(this->CheckQueuedTriangles());
      if (m_Queries.empty())
      {
        // Moving vertices back can in turn leave a component collapsed.
        undone += this->UndoAndQueue(this->UndoCollapsedComponents());
      }
    }
    return undone;
  }

private:
  /** Queues the triangles around the vertices in `back` (sent back): what moved around
   * them may now cut them. Returns their number. */
  std::size_t
  UndoAndQueue(const std::vector<std::uint32_t> & back)
  {
    for (const auto v : back)
    {
      this->QueueAround(v);
    }
    return back.size();
  }

  void
  QueueAround(std::size_t v)
  {
    for (std::uint32_t k = m_Topology.vertexTriangleOffsets[v]; k < m_Topology.vertexTriangleOffsets[v + 1]; ++k)
    {
      const std::uint32_t t = m_Topology.vertexTriangles[k];
      if (!m_Queued[t])
      {
        m_Queued[t] = 1;
        m_Queries.push_back(t);
      }
    }
  }

  void
  QueueMovedVertices()
  {
    for (std::size_t v = 0; v < m_Mesh.points.size(); ++v)
    {
      if (m_Mesh.points[v] != m_Start[v])
      {
        this->QueueAround(v);
      }
    }
  }

  /** Vertex v back to its start, if it moved; then it is listed in `back`. */
  void
  SendBack(std::uint32_t v, std::vector<std::uint32_t> & back)
  {
    if (m_Mesh.points[v] != m_Start[v])
    {
      m_Mesh.points[v] = m_Start[v];
      back.push_back(v);
    }
  }

  /** The queued triangles that are turned over or degenerate against the start, or
   * cross another triangle: their vertices go back. Empties the queue. */
  std::vector<std::uint32_t>
  CheckQueuedTriangles()
  {
    std::sort(m_Queries.begin(), m_Queries.end());
    std::vector<std::uint32_t> bad;
    for (const auto t : m_Queries)
    {
      if (!IsValidTriangleAgainstStart(m_Mesh, m_Start, t, m_Tolerance))
      {
        bad.push_back(t);
      }
    }
    for (const auto & pair : FindSelfIntersections(m_Mesh, &m_Queries))
    {
      bad.push_back(pair.first);
      bad.push_back(pair.second);
    }
    std::fill(m_Queued.begin(), m_Queued.end(), 0);
    m_Queries.clear();
    std::vector<std::uint32_t> back;
    for (const auto t : bad)
    {
      for (const auto v : m_Mesh.triangles[t])
      {
        this->SendBack(v, back);
      }
    }
    return back;
  }

  /** Whether closed component c collapsed in the step (IsCollapsedComponent against
   * the step's start) or, having shrunk in the step, against the reference before
   * the series. */
  bool
  IsCollapsed(std::size_t c, double startVolume, double volume) const
  {
    const bool closed = c >= m_Topology.componentBoundaryLoops.size() || m_Topology.componentBoundaryLoops[c] == 0;
    if (!closed)
    {
      return false;
    }
    return IsCollapsedComponent(startVolume, volume, startVolume, ValidityThresholds::StepCollapseFraction) ||
           (m_Reference && c < m_Reference->sixVolumes.size() && std::abs(volume) < std::abs(startVolume) &&
            IsCollapsedComponent(
              startVolume, volume, m_Reference->sixVolumes[c], ValidityThresholds::SeriesCollapseFraction));
  }

  /** Closed components that collapsed (turned inside out or pressed flat): all their
   * vertices go back. */
  std::vector<std::uint32_t>
  UndoCollapsedComponents()
  {
    const std::size_t         components = m_Topology.numberOfComponents;
    std::vector<Vec3>         origin(components);
    std::vector<std::uint8_t> hasOrigin(components, 0);
    for (std::size_t f = 0; f < m_Mesh.triangles.size(); ++f)
    {
      const std::uint32_t c = m_Topology.triangleComponent[f];
      if (!hasOrigin[c])
      {
        hasOrigin[c] = 1;
        origin[c] = m_Start[m_Mesh.triangles[f][0]];
      }
    }
    const MeshTopology &      topology = m_Topology;
    auto                      componentOf = [&topology](std::size_t f) { return topology.triangleComponent[f]; };
    const std::vector<double> startVolume = ComponentSixVolumes(m_Mesh.triangles, m_Start, origin, componentOf);
    const std::vector<double> volume = ComponentSixVolumes(m_Mesh.triangles, m_Mesh.points, origin, componentOf);
    std::vector<std::uint8_t> collapsed(components, 0);
    bool                      any = false;
    for (std::size_t c = 0; c < components; ++c)
    {
      if (this->IsCollapsed(c, startVolume[c], volume[c]))
      {
        collapsed[c] = 1;
        any = true;
      }
    }
    std::vector<std::uint32_t> back;
    if (any)
    {
      for (std::size_t f = 0; f < m_Mesh.triangles.size(); ++f)
      {
        if (collapsed[m_Topology.triangleComponent[f]])
        {
          for (const auto v : m_Mesh.triangles[f])
          {
            this->SendBack(v, back);
          }
        }
      }
    }
    return back;
  }

  /** The components whose nesting parity differs from the reference's, in increasing
   * order (none without a reference, or when no move can have passed a component). */
  std::vector<std::uint32_t>
  ComponentsWithChangedNesting() const
  {
    std::vector<std::uint32_t> changed;
    if (!m_Reference || m_Reference->nesting.empty() || m_Mesh.points == m_Start ||
        ComponentsAMoveMayHavePassed(m_Mesh, m_Topology, m_Start).empty())
    {
      return changed;
    }
    const std::vector<std::int8_t> nesting = ComponentNestingParity(m_Mesh, m_Topology);
    for (std::size_t c = 0; c < m_Topology.numberOfComponents && c < m_Reference->nesting.size(); ++c)
    {
      if (nesting[c] >= 0 && m_Reference->nesting[c] >= 0 && nesting[c] != m_Reference->nesting[c])
      {
        changed.push_back(static_cast<std::uint32_t>(c));
      }
    }
    return changed;
  }

  /** The box of triangle f at its start and now. */
  AxisAlignedBox
  SweptBox(std::size_t f) const
  {
    AxisAlignedBox box;
    for (const auto v : m_Mesh.triangles[f])
    {
      box.Add(m_Mesh.points[v]);
      box.Add(m_Start[v]);
    }
    return box;
  }

  /** Components whose nesting parity changed: they go back, with the moved triangles
   * of other components whose boxes (before and after) overlap theirs. */
  std::vector<std::uint32_t>
  UndoNestingChanges()
  {
    std::vector<std::uint32_t>       back;
    const std::vector<std::uint32_t> changedList = this->ComponentsWithChangedNesting();
    if (changedList.empty())
    {
      return back;
    }
    const std::size_t         components = m_Topology.numberOfComponents;
    std::vector<std::uint8_t> changed(components, 0);
    for (const std::uint32_t c : changedList)
    {
      changed[c] = 1;
    }
    std::vector<AxisAlignedBox> componentBox(components);
    for (std::size_t f = 0; f < m_Mesh.triangles.size(); ++f)
    {
      const std::uint32_t c = m_Topology.triangleComponent[f];
      if (changed[c])
      {
        componentBox[c].Add(this->SweptBox(f));
      }
    }
    for (std::size_t f = 0; f < m_Mesh.triangles.size(); ++f)
    {
      const auto & t = m_Mesh.triangles[f];
      if (changed[m_Topology.triangleComponent[f]])
      {
        for (const auto v : t)
        {
          this->SendBack(v, back);
        }
        continue;
      }
      if (m_Mesh.points[t[0]] == m_Start[t[0]] && m_Mesh.points[t[1]] == m_Start[t[1]] &&
          m_Mesh.points[t[2]] == m_Start[t[2]])
      {
        continue;
      }
      const AxisAlignedBox box = this->SweptBox(f);
      for (const std::uint32_t b : changedList)
      {
        if (box.Overlaps(componentBox[b]))
        {
          for (const auto v : t)
          {
            this->SendBack(v, back);
          }
          break;
        }
      }
    }
    return back;
  }

  IndexedTriangleMesh &      m_Mesh;
  const MeshTopology &       m_Topology;
  const std::vector<Vec3> &  m_Start;
  const double               m_Tolerance;
  const ComponentReference * m_Reference;
  std::vector<std::uint8_t>  m_Queued;  ///< per triangle: in m_Queries
  std::vector<std::uint32_t> m_Queries; ///< triangles to check
};
} // namespace

bool
IsValidVertexMove(const VertexOneRing & r,
                  const Vec3 &          newCenter,
                  double                degenerateTolerance,
                  const VertexOneRing * reference)
{
  for (std::size_t t = 0; t < r.NumberOfTriangles(); ++t)
  {
    const Vec3 & a = r.First(t);
    const Vec3 & b = r.Second(t);
    const Vec3   oldNormal = TriangleNormal(r.center, a, b);
    const Vec3   newNormal = TriangleNormal(newCenter, a, b);
    const double oldQ = TriangleQArea(r.center, a, b);
    const double newQ = TriangleQArea(newCenter, a, b);
    if (oldQ > 0.0 && !(Dot(oldNormal, newNormal) > 0.0))
    {
      return false;
    }
    if (oldQ > degenerateTolerance ? !(newQ > degenerateTolerance) : !(newQ >= oldQ))
    {
      return false;
    }
    if (reference != nullptr)
    {
      const Vec3 & ra = reference->First(t);
      const Vec3 & rb = reference->Second(t);
      if (TriangleQArea(reference->center, ra, rb) > 0.0 &&
          !(Dot(TriangleNormal(reference->center, ra, rb), newNormal) > 0.0))
      {
        return false;
      }
    }
  }
  return true;
}

bool
IsValidTriangleAgainstStart(const IndexedTriangleMesh & mesh,
                            const std::vector<Vec3> &   startPositions,
                            std::uint32_t               t,
                            double                      tolerance)
{
  const auto & tri = mesh.triangles[t];
  const Vec3 & a = mesh.points[tri[0]];
  const Vec3 & b = mesh.points[tri[1]];
  const Vec3 & c = mesh.points[tri[2]];
  const Vec3 & a0 = startPositions[tri[0]];
  const Vec3 & b0 = startPositions[tri[1]];
  const Vec3 & c0 = startPositions[tri[2]];
  const double q = TriangleQArea(a, b, c);
  const double q0 = TriangleQArea(a0, b0, c0);
  if (q0 > tolerance ? !(q > tolerance) : !(q >= q0))
  {
    return false;
  }
  return !(q0 > 0.0) || Dot(TriangleNormal(a0, b0, c0), TriangleNormal(a, b, c)) > 0.0;
}

std::size_t
UndoFoldingMoves(IndexedTriangleMesh &      mesh,
                 const MeshTopology &       topology,
                 const std::vector<Vec3> &  startPositions,
                 double                     tolerance,
                 const ComponentReference * reference)
{
  return FoldingMoveUndo(mesh, topology, startPositions, tolerance, reference).Run();
}

} // namespace detail
} // namespace MeshExtraction
} // namespace itk
