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
#ifndef itkMeshExtractionVertexSmoothing_h
#define itkMeshExtractionVertexSmoothing_h

#include "itkMeshExtractionEnums.h"
#include "itkMeshExtractionTriangleGeometry.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

namespace itk
{
namespace MeshExtraction
{
namespace detail
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
 * 3. GuardVertexMove() (the validity guard, itkMeshExtractionValidityGuard.h): the
 *    move is taken whole, or halved until no incident triangle flips or degenerates,
 *    or rejected.
 *
 * They are inline here rather than in src/: the smoothing filters' template loops call
 * them for every vertex of every iteration.
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

} // namespace detail
} // namespace MeshExtraction
} // namespace itk

#endif
