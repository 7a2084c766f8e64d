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
#ifndef itkMeshExtractionVertexSmoothing_h
#define itkMeshExtractionVertexSmoothing_h

#include "itkMeshExtractionEnums.h"
#include "itkMeshExtractionIndexedTriangleMesh.h"
#include "itkMeshExtractionParallel.h"
#include "itkMeshExtractionQualityAnalysis.h"
#include "itkMeshExtractionTriangleAABBTree.h"
#include "itkMeshExtractionTriangleGeometry.h"

#include <cmath>
#include <cstddef>
#include <algorithm>
#include <limits>
#include <vector>

namespace itk
{
namespace MeshExtraction
{
/** \file
 * \brief One smoothing move of one vertex, as pure functions of the vertex and its
 * ordered 1-ring (thesis sections 2.2.3-2.2.4, 4.2.2 and 4.5.1).
 *
 * LaplacianSmoothingQuadEdgeMeshFilter and TaubinSmoothingQuadEdgeMeshFilter call
 * these on a QuadEdgeMesh; any other mesh representation (e.g. a SurfaceNet) can
 * call them on its own 1-rings and get exactly the same moves:
 *
 * 1. LaplacianTarget(): the smoothing target S(v) for a choice of weights;
 * 2. SmoothingDisplacement(): the move from v towards S(v) after the relaxation
 *    factor, the movement constraint (centroid, safe) and the approximate volume
 *    preservation of eq. 2.7-2.10;
 * 3. GuardVertexMove(): the no-inversion guard: the move is taken whole, or
 *    halved until no incident triangle flips or degenerates, or rejected.
 *
 * \ingroup MeshExtraction
 */

/** A vertex and its linked neighbours in counter-clockwise order seen from the
 * side its triangles' normals point to: the incident triangles are
 * (center, ring[i], ring[i+1]). For a closed ring (an interior vertex) i runs over
 * 0..size-1 with indices modulo size; for an open ring (a boundary vertex) over
 * 0..size-2, ring[0] and ring[size-1] being its neighbours along the boundary.
 * \ingroup MeshExtraction */
struct VertexOneRing
{
  Vec3         center;
  const Vec3 * ring{ nullptr };
  std::size_t  size{ 0 };
  bool         closed{ true };

  std::size_t
  NumberOfTriangles() const
  {
    return closed ? size : (size > 0 ? size - 1 : 0);
  }
  /** The two ring vertices of incident triangle t: (center, First(t), Second(t)). */
  const Vec3 &
  First(std::size_t t) const
  {
    return ring[t];
  }
  const Vec3 &
  Second(std::size_t t) const
  {
    return ring[t + 1 == size ? 0 : t + 1];
  }
};

/** Sum of the (un-normalised) normals of the incident triangles: twice the
 * area-weighted vertex normal, N of thesis eq. 2.7. */
inline Vec3
OneRingNormal(const VertexOneRing & r)
{
  Vec3 n(0.0);
  for (std::size_t t = 0; t < r.NumberOfTriangles(); ++t)
  {
    n += TriangleNormal(r.center, r.First(t), r.Second(t));
  }
  return n;
}

/** Distance from the vertex to its nearest linked neighbour. */
inline double
NearestNeighbourDistance(const VertexOneRing & r)
{
  double d2 = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < r.size; ++i)
  {
    d2 = std::min(d2, SquaredNorm(r.ring[i] - r.center));
  }
  return std::sqrt(d2);
}

/** The average of the linked neighbours. */
inline Vec3
UniformLaplacianTarget(const VertexOneRing & r)
{
  Vec3 s(0.0);
  for (std::size_t i = 0; i < r.size; ++i)
  {
    s += r.ring[i];
  }
  return r.size > 0 ? s * (1.0 / static_cast<double>(r.size)) : r.center;
}

/** v + sum_j w_j (v_j - v) / sum_j w_j for weights w[0..size-1]; the uniform target
 * when the weights do not have a positive sum. */
inline Vec3
WeightedLaplacianTarget(const VertexOneRing & r, const double * w)
{
  Vec3   s(0.0);
  double sum = 0.0;
  for (std::size_t i = 0; i < r.size; ++i)
  {
    s += (r.ring[i] - r.center) * w[i];
    sum += w[i];
  }
  if (!(sum > 0.0) || !std::isfinite(sum))
  {
    return UniformLaplacianTarget(r);
  }
  return r.center + s * (1.0 / sum);
}

/** The smoothing target S(v) (thesis eq. 2.6 and section 2.2.4):
 * - Uniform: the average of the linked neighbours;
 * - InverseEdgeLength: weights 1 / |v_j - v| (a neighbour on top of v gets no weight);
 * - Area: the average of the incident triangles' centroids weighted by their areas;
 * - Cotangent: weights cot(alpha_j) + cot(beta_j) of the angles opposite the edge
 *   (only one on a boundary edge), clamped at 0 like ITK's ConformalMatrixCoefficients;
 * - AngleBisector: the average of the perpendicular projections of v onto the
 *   bisectors of the 1-ring polygon's angles at the linked neighbours (Figure 2.16).
 *   The polygon of an open ring has no angle at its two ends, so boundary vertices
 *   use the uniform target.
 * Weights that do not sum to a positive number (all-obtuse cotangents, a zero-area
 * ring) fall back to the uniform target. */
inline Vec3
LaplacianTarget(MeshExtractionEnums::SmoothingWeights weights, const VertexOneRing & r)
{
  using W = MeshExtractionEnums::SmoothingWeights;
  if (r.size == 0)
  {
    return r.center;
  }
  switch (weights)
  {
    case W::Uniform:
      return UniformLaplacianTarget(r);
    case W::InverseEdgeLength:
    {
      Vec3   s(0.0);
      double sum = 0.0;
      for (std::size_t i = 0; i < r.size; ++i)
      {
        const double l = Norm(r.ring[i] - r.center);
        if (l > 0.0)
        {
          s += (r.ring[i] - r.center) * (1.0 / l);
          sum += 1.0 / l;
        }
      }
      return sum > 0.0 ? r.center + s * (1.0 / sum) : UniformLaplacianTarget(r);
    }
    case W::Area:
    {
      Vec3   s(0.0);
      double sum = 0.0;
      for (std::size_t t = 0; t < r.NumberOfTriangles(); ++t)
      {
        const double a = TriangleArea(r.center, r.First(t), r.Second(t));
        s += TriangleCentroid(r.center, r.First(t), r.Second(t)) * a;
        sum += a;
      }
      return sum > 0.0 ? s * (1.0 / sum) : UniformLaplacianTarget(r);
    }
    case W::Cotangent:
    {
      Vec3   s(0.0);
      double sum = 0.0;
      for (std::size_t i = 0; i < r.size; ++i)
      {
        double w = 0.0;
        // Triangle (center, ring[i-1], ring[i]): the angle at ring[i-1] is opposite the edge.
        if (r.closed || i > 0)
        {
          const Vec3 & prev = r.ring[i == 0 ? r.size - 1 : i - 1];
          w += Cotangent(prev, r.center, r.ring[i]);
        }
        // Triangle (center, ring[i], ring[i+1]): the angle at ring[i+1].
        if (r.closed || i + 1 < r.size)
        {
          const Vec3 & next = r.ring[i + 1 == r.size ? 0 : i + 1];
          w += Cotangent(next, r.center, r.ring[i]);
        }
        w = std::max(0.0, w);
        s += (r.ring[i] - r.center) * w;
        sum += w;
      }
      return sum > 0.0 && std::isfinite(sum) ? r.center + s * (1.0 / sum) : UniformLaplacianTarget(r);
    }
    case W::AngleBisector:
    {
      if (!r.closed || r.size < 3)
      {
        return UniformLaplacianTarget(r);
      }
      const Vec3 normal = OneRingNormal(r);
      Vec3       s(0.0);
      for (std::size_t i = 0; i < r.size; ++i)
      {
        const Vec3 & prev = r.ring[i == 0 ? r.size - 1 : i - 1];
        const Vec3 & next = r.ring[i + 1 == r.size ? 0 : i + 1];
        const Vec3   b = AngleBisectorDirection(r.ring[i], prev, next, normal);
        s += ProjectOntoLine(r.center, r.ring[i], b);
      }
      return s * (1.0 / static_cast<double>(r.size));
    }
  }
  return UniformLaplacianTarget(r);
}

/** How one vertex moves towards its smoothing target. */
struct VertexSmoothingParameters
{
  /** Scales the move: the relaxation factor of Laplacian smoothing, lambda or mu
   * (negative) of Taubin smoothing. */
  double                                  factor{ 1.0 };
  MeshExtractionEnums::MovementConstraint constraint{ MeshExtractionEnums::MovementConstraint::None };
  /** Approximate volume preservation (thesis eq. 2.7-2.10). */
  bool volumePreservation{ false };
};

/** The move of the vertex towards `target`:
 * 1. d = target - v; with the Centroid constraint d = 2/3 (target - v), the move to
 *    S_C = 1/3 v + 2/3 S(v) (thesis section 4.2.2);
 * 2. d = factor * d;
 * 3. volume preservation: the component of d along the 1-ring normal N (the sum of
 *    the incident triangles' normals) is removed, v_new = v_avg - lambda N with
 *    lambda = (v_avg - v).N / N.N (eq. 2.8-2.10). The volume of the cone spanned by
 *    the ring and the vertex, sum_f v.N_f (eq. 2.7), is then unchanged;
 * 4. with the Safe constraint |d| is clipped to the distance to the nearest linked
 *    neighbour (thesis Figure 4.8). */
inline Vec3
SmoothingDisplacement(const VertexSmoothingParameters & p, const VertexOneRing & r, const Vec3 & target)
{
  Vec3 d = target - r.center;
  if (p.constraint == MeshExtractionEnums::MovementConstraint::Centroid)
  {
    d *= 2.0 / 3.0;
  }
  d *= p.factor;
  if (p.volumePreservation)
  {
    const Vec3   n = OneRingNormal(r);
    const double n2 = SquaredNorm(n);
    if (n2 > 0.0)
    {
      d -= n * (Dot(d, n) / n2);
    }
  }
  if (p.constraint == MeshExtractionEnums::MovementConstraint::Safe)
  {
    const double limit = NearestNeighbourDistance(r);
    const double l = Norm(d);
    if (l > limit)
    {
      d *= limit / l;
    }
  }
  return d;
}

/** Whether moving the vertex to `newCenter` keeps every incident triangle valid:
 * - a triangle with a defined orientation (q_area > 0) keeps it: the new normal
 *   makes an angle below 90 degrees with the one before the move (dot > 0);
 * - if `reference` is given (the same ring at earlier positions, e.g. at the start
 *   of a smoothing iteration), the new normal also makes an angle below 90 degrees
 *   with the reference triangle's normal, so that the moves of one iteration
 *   together cannot turn a triangle over either;
 * - a triangle with q_area above `degenerateTolerance` stays above it; one already
 *   at or below it may not get worse.
 * Triangles away from the vertex do not change, so these checks, made against the
 * current positions, are exact. */
inline bool
IsValidVertexMove(const VertexOneRing & r,
                  const Vec3 &          newCenter,
                  double                degenerateTolerance,
                  const VertexOneRing * reference = nullptr)
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

/** What became of one guarded move. */
enum class VertexMoveOutcome : std::uint8_t
{
  Unchanged = 0, ///< nothing to do: a zero displacement (after rounding)
  Accepted,      ///< the whole move was made
  Shortened,     ///< a fraction 2^-k of it was made
  Rejected       ///< every fraction tried would have flipped or degenerated a triangle
};

struct GuardedVertexMove
{
  Vec3              position;
  VertexMoveOutcome outcome{ VertexMoveOutcome::Unchanged };
};

/** The no-inversion guard (goes beyond the thesis, whose centroid smoothing can
 * still invert triangles, Figure 4.7; the halving follows CGAL's
 * tangential_relaxation): tries v + d, v + d/2, ..., v + d/2^maximumShortenings and
 * takes the first that IsValidVertexMove() accepts (with the optional `reference`
 * ring); if none is, the vertex stays. `round` maps a candidate to the position the
 * mesh will actually store (e.g. rounded to float coordinates), so that the checks
 * see exactly what is stored. */
template <typename TRound>
GuardedVertexMove
GuardVertexMove(const VertexOneRing & r,
                const Vec3 &          displacement,
                unsigned int          maximumShortenings,
                double                degenerateTolerance,
                TRound &&             round,
                const VertexOneRing * reference = nullptr)
{
  GuardedVertexMove result{ r.center, VertexMoveOutcome::Unchanged };
  double            t = 1.0;
  for (unsigned int k = 0; k <= maximumShortenings; ++k, t *= 0.5)
  {
    const Vec3 candidate = round(r.center + displacement * t);
    if (candidate == r.center)
    {
      // Nothing left to move: a zero move, or every shorter one rounds to v too.
      result.outcome = k == 0 ? VertexMoveOutcome::Unchanged : VertexMoveOutcome::Rejected;
      return result;
    }
    if (IsValidVertexMove(r, candidate, degenerateTolerance, reference))
    {
      result.position = candidate;
      result.outcome = k == 0 ? VertexMoveOutcome::Accepted : VertexMoveOutcome::Shortened;
      return result;
    }
  }
  result.outcome = VertexMoveOutcome::Rejected;
  return result;
}

/** Whether triangle t of `mesh` keeps the orientation it had with the vertices at
 * `startPositions` (its normal turned by less than 90 degrees) and does not become
 * degenerate (q_area <= tolerance; if it already was, it may not get worse): the
 * per-triangle checks of IsValidVertexMove(). \ingroup MeshExtraction */
inline bool
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

/** What a series of smoothing steps keeps of a mesh's components before the first
 * step, for UndoFoldingMoves: each component's ComponentSixVolumes (measured from
 * the first vertex of its first triangle) and its ComponentNestingParity. */
struct ComponentReference
{
  std::vector<double>      sixVolumes;
  std::vector<std::int8_t> nesting;
};

/** The ComponentReference of `mesh`, whose topology is `topology`. */
inline ComponentReference
MakeComponentReference(const IndexedTriangleMesh & mesh, const MeshTopology & topology)
{
  ComponentReference r;
  std::vector<Vec3>  origin(topology.numberOfComponents);
  for (std::size_t f = mesh.triangles.size(); f-- > 0;)
  {
    origin[topology.triangleComponent[f]] = mesh.points[mesh.triangles[f][0]];
  }
  r.sixVolumes = ComponentSixVolumes(
    mesh.triangles, mesh.points, origin, [&topology](std::size_t f) { return topology.triangleComponent[f]; });
  r.nesting = ComponentNestingParity(mesh, topology);
  return r;
}

/** The components whose ComponentNestingParity the move of every vertex of `mesh`
 * from startPositions to mesh.points can have changed, in increasing order. A
 * component's parity is that of its ComponentRayVertices vertex v against the other
 * components. Along
 * the straight path from start to end it changes only where v passes through a
 * triangle T of another component, or T through v, so then v or T moved and the box
 * of v's path overlaps the box of T's start and end: a component for which no such
 * T exists keeps its parity. A pass over the triangles against the components'
 * vertex boxes sorted along x: far cheaper than ComponentNestingParity's tree. */
inline std::vector<std::uint32_t>
ComponentsAMoveMayHavePassed(const IndexedTriangleMesh & mesh,
                             const MeshTopology &        topology,
                             const std::vector<Vec3> &   startPositions)
{
  constexpr std::uint32_t          none = std::numeric_limits<std::uint32_t>::max();
  const std::size_t                components = topology.numberOfComponents;
  const std::vector<std::uint32_t> vertex = ComponentRayVertices(mesh, topology);
  std::vector<AxisAlignedBox>      path(components);
  std::vector<std::uint32_t>       order;
  double                           widest = 0.0;
  for (std::uint32_t c = 0; c < components; ++c)
  {
    if (vertex[c] != none)
    {
      path[c].Add(startPositions[vertex[c]]);
      path[c].Add(mesh.points[vertex[c]]);
      order.push_back(c);
      widest = std::max(widest, path[c].upper[0] - path[c].lower[0]);
    }
  }
  std::sort(order.begin(), order.end(), [&path](std::uint32_t a, std::uint32_t b) {
    return path[a].lower[0] < path[b].lower[0] || (path[a].lower[0] == path[b].lower[0] && a < b);
  });
  std::vector<double> lowerX(order.size());
  for (std::size_t i = 0; i < order.size(); ++i)
  {
    lowerX[i] = path[order[i]].lower[0];
  }
  constexpr std::size_t                   blockSize = 8192;
  std::vector<std::vector<std::uint32_t>> found((mesh.triangles.size() + blockSize - 1) / blockSize);
  ParallelForBlocks(mesh.triangles.size(), blockSize, [&](std::size_t begin, std::size_t end, std::size_t block) {
    for (std::size_t f = begin; f < end; ++f)
    {
      const auto &   t = mesh.triangles[f];
      AxisAlignedBox box;
      bool           moved = false;
      for (const auto v : t)
      {
        box.Add(startPositions[v]);
        box.Add(mesh.points[v]);
        moved = moved || mesh.points[v] != startPositions[v];
      }
      const std::uint32_t own = topology.triangleComponent[f];
      for (auto i = static_cast<std::size_t>(std::lower_bound(lowerX.begin(), lowerX.end(), box.lower[0] - widest) -
                                             lowerX.begin());
           i < order.size() && lowerX[i] <= box.upper[0];
           ++i)
      {
        const std::uint32_t c = order[i];
        if (c != own && (moved || mesh.points[vertex[c]] != startPositions[vertex[c]]) && box.Overlaps(path[c]))
        {
          found[block].push_back(c);
        }
      }
    }
  });
  std::vector<std::uint8_t> flagged(components, 0);
  for (const auto & list : found)
  {
    for (const auto c : list)
    {
      flagged[c] = 1;
    }
  }
  std::vector<std::uint32_t> result;
  for (std::uint32_t c = 0; c < components; ++c)
  {
    if (flagged[c])
    {
      result.push_back(c);
    }
  }
  return result;
}

/** A closed component that a series of steps shrinks below this fraction of its
 * volume before the first (ComponentReference) goes back (UndoFoldingMoves). */
constexpr double CollapsedComponentVolumeFraction = 1e-3;

/** Vertex moves checked one vertex at a time (the guards of the edge detector and of
 * the smoothing filters) can together still fold the surface (two triangles of a
 * ring crossing each other) or make it pass through another part. Given the mesh
 * after such moves and the positions before them, this finds the triangles that
 * changed and now intersect another triangle (exact predicates,
 * FindSelfIntersections) or are turned over or degenerate against the start
 * (IsValidTriangleAgainstStart), moves their vertices back to the start, and repeats
 * with the triangles around the vertices moved back, until none is left: at worst
 * everything is back where it started. Intersections between triangles that did not
 * change are left alone. A closed component whose enclosed (signed) volume changed
 * sign has turned inside out as a whole — a small component, e.g. the 12 triangles
 * around one voxel, can do that without any triangle crossing another — and goes back
 * to the start entirely; so does one pressed flat (less than a hundredth of its
 * volume left).
 *
 * With `reference` (MakeComponentReference before the first of a series of steps,
 * on the same topology), two more things that ten Laplacian steps did to the 12
 * triangles around one voxel, each step within the rules above, are undone: a
 * component shrunk below CollapsedComponentVolumeFraction of its reference volume
 * (a speck) goes back; and where a component's ComponentNestingParity changed (a
 * surface moved past it in one step, leaving no intersection behind, so that its
 * triangles now face the wrong way), it goes back, and so do the moved triangles of
 * the other components whose boxes, before and after the step, overlap its own.
 * The parity test (a tree and a ray per component) runs only if
 * ComponentsAMoveMayHavePassed names a component. Returns the number of vertices
 * moved back.
 * \ingroup MeshExtraction */
inline std::size_t
UndoFoldingMoves(IndexedTriangleMesh &      mesh,
                 const MeshTopology &       topology,
                 const std::vector<Vec3> &  startPositions,
                 double                     tolerance,
                 const ComponentReference * reference = nullptr)
{
  const std::size_t          n = mesh.points.size();
  std::vector<std::uint8_t>  queued(mesh.triangles.size(), 0);
  std::vector<std::uint32_t> queries;
  auto                       queueAround = [&](std::size_t v) {
    for (std::uint32_t k = topology.vertexTriangleOffsets[v]; k < topology.vertexTriangleOffsets[v + 1]; ++k)
    {
      const std::uint32_t t = topology.vertexTriangles[k];
      if (!queued[t])
      {
        queued[t] = 1;
        queries.push_back(t);
      }
    }
  };
  for (std::size_t v = 0; v < n; ++v)
  {
    if (mesh.points[v] != startPositions[v])
    {
      queueAround(v);
    }
  }
  // Closed components whose signed volume changed sign (turned inside out): all their
  // vertices go back. Returns the vertices moved back.
  auto undoInvertedComponents = [&]() {
    const std::size_t         components = topology.numberOfComponents;
    std::vector<Vec3>         origin(components);
    std::vector<std::uint8_t> hasOrigin(components, 0);
    for (std::size_t f = 0; f < mesh.triangles.size(); ++f)
    {
      const std::uint32_t c = topology.triangleComponent[f];
      if (!hasOrigin[c])
      {
        hasOrigin[c] = 1;
        origin[c] = startPositions[mesh.triangles[f][0]];
      }
    }
    auto                      componentOf = [&topology](std::size_t f) { return topology.triangleComponent[f]; };
    const std::vector<double> startVolume = ComponentSixVolumes(mesh.triangles, startPositions, origin, componentOf);
    const std::vector<double> volume = ComponentSixVolumes(mesh.triangles, mesh.points, origin, componentOf);
    std::vector<std::uint8_t> inverted(components, 0);
    bool                      any = false;
    for (std::size_t c = 0; c < components; ++c)
    {
      const bool closed = c >= topology.componentBoundaryLoops.size() || topology.componentBoundaryLoops[c] == 0;
      // Inside out, or flattened to less than a hundredth of its volume (a uniform
      // Laplacian step takes a voxel's 12 triangles to about a third; cotangent
      // weights, unconstrained, could press them flat, two sheets on each other).
      const bool flattened =
        std::abs(volume[c]) < 0.01 * std::abs(startVolume[c]) ||
        (reference && c < reference->sixVolumes.size() && std::abs(volume[c]) < std::abs(startVolume[c]) &&
         std::abs(volume[c]) < CollapsedComponentVolumeFraction * std::abs(reference->sixVolumes[c]));
      if (closed &&
          ((startVolume[c] > 0.0 && !(volume[c] > 0.0)) || (startVolume[c] < 0.0 && !(volume[c] < 0.0)) || flattened))
      {
        inverted[c] = 1;
        any = true;
      }
    }
    std::vector<std::uint32_t> back;
    if (any)
    {
      for (std::size_t f = 0; f < mesh.triangles.size(); ++f)
      {
        if (inverted[topology.triangleComponent[f]])
        {
          for (const auto v : mesh.triangles[f])
          {
            if (mesh.points[v] != startPositions[v])
            {
              mesh.points[v] = startPositions[v];
              back.push_back(v);
            }
          }
        }
      }
    }
    return back;
  };

  // Components whose nesting parity changed: they go back, with the moved triangles
  // of other components whose boxes (before and after) overlap theirs.
  auto undoNestingChanges = [&]() {
    std::vector<std::uint32_t> back;
    if (!reference || reference->nesting.empty() || mesh.points == startPositions ||
        ComponentsAMoveMayHavePassed(mesh, topology, startPositions).empty())
    {
      return back;
    }
    const std::vector<std::int8_t> nesting = ComponentNestingParity(mesh, topology);
    const std::size_t              components = topology.numberOfComponents;
    std::vector<std::uint8_t>      changed(components, 0);
    std::vector<std::uint32_t>     changedList;
    for (std::size_t c = 0; c < components && c < reference->nesting.size(); ++c)
    {
      if (nesting[c] >= 0 && reference->nesting[c] >= 0 && nesting[c] != reference->nesting[c])
      {
        changed[c] = 1;
        changedList.push_back(static_cast<std::uint32_t>(c));
      }
    }
    if (changedList.empty())
    {
      return back;
    }
    std::vector<AxisAlignedBox> componentBox(components);
    auto                        sweptBox = [&](std::size_t f) {
      AxisAlignedBox box;
      for (const auto v : mesh.triangles[f])
      {
        box.Add(mesh.points[v]);
        box.Add(startPositions[v]);
      }
      return box;
    };
    for (std::size_t f = 0; f < mesh.triangles.size(); ++f)
    {
      const std::uint32_t c = topology.triangleComponent[f];
      if (changed[c])
      {
        componentBox[c].Add(sweptBox(f));
      }
    }
    auto sendBack = [&](std::uint32_t v) {
      if (mesh.points[v] != startPositions[v])
      {
        mesh.points[v] = startPositions[v];
        back.push_back(v);
      }
    };
    for (std::size_t f = 0; f < mesh.triangles.size(); ++f)
    {
      const std::uint32_t c = topology.triangleComponent[f];
      if (changed[c])
      {
        for (const auto v : mesh.triangles[f])
        {
          sendBack(v);
        }
        continue;
      }
      const auto & t = mesh.triangles[f];
      if (mesh.points[t[0]] == startPositions[t[0]] && mesh.points[t[1]] == startPositions[t[1]] &&
          mesh.points[t[2]] == startPositions[t[2]])
      {
        continue;
      }
      const AxisAlignedBox box = sweptBox(f);
      for (const std::uint32_t b : changedList)
      {
        if (box.Overlaps(componentBox[b]))
        {
          for (const auto v : t)
          {
            sendBack(v);
          }
          break;
        }
      }
    }
    return back;
  };

  std::size_t undone = 0;
  for (const auto v : undoInvertedComponents())
  {
    ++undone;
    queueAround(v); // the component is back, but what moved around it may now cut it
  }
  while (true)
  {
    if (queries.empty())
    {
      // Settled: last, whether a surface moved past a component.
      const std::vector<std::uint32_t> back = undoNestingChanges();
      undone += back.size();
      for (const auto v : back)
      {
        queueAround(v);
      }
      if (queries.empty())
      {
        break;
      }
    }
    std::sort(queries.begin(), queries.end());
    std::vector<std::uint32_t> bad;
    for (const auto t : queries)
    {
      if (!IsValidTriangleAgainstStart(mesh, startPositions, t, tolerance))
      {
        bad.push_back(t);
      }
    }
    for (const auto & pair : FindSelfIntersections(mesh, &queries))
    {
      bad.push_back(pair.first);
      bad.push_back(pair.second);
    }
    std::fill(queued.begin(), queued.end(), 0);
    queries.clear();
    std::vector<std::uint32_t> back;
    for (const auto t : bad)
    {
      for (const auto v : mesh.triangles[t])
      {
        if (mesh.points[v] != startPositions[v])
        {
          mesh.points[v] = startPositions[v];
          back.push_back(v);
        }
      }
    }
    undone += back.size();
    for (const auto v : back)
    {
      queueAround(v);
    }
    if (queries.empty())
    {
      // Moving vertices back can in turn leave a component inside out.
      for (const auto v : undoInvertedComponents())
      {
        ++undone;
        queueAround(v);
      }
    }
  }
  return undone;
}

} // namespace MeshExtraction
} // namespace itk

#endif
