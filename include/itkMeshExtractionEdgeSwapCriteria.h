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
#ifndef itkMeshExtractionEdgeSwapCriteria_h
#define itkMeshExtractionEdgeSwapCriteria_h

#include "MeshExtractionExport.h"
#include "itkMeshExtractionEnums.h"
#include "itkMeshExtractionTriangleGeometry.h"
#include "itkMeshExtractionValidityGuard.h"

#include <cstdint>
#include <iosfwd>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
/** \file
 * \brief The decision whether to swap one edge, as pure functions of the quad
 * around it (thesis sections 2.2.6, 4.2.2 and 4.5.1).
 *
 * EdgeSwapQuadEdgeMeshFilter asks EvaluateEdgeSwap() about every edge of a
 * QuadEdgeMesh; another mesh representation (e.g. a SurfaceNet) can ask it about
 * its own quads and gets exactly the same decisions.
 *
 * The quad: the edge runs from a to b; (a, b, c) is the triangle on its left and
 * (b, a, d) the one on its right, both counter-clockwise seen from the side their
 * normals point to. A swap replaces them with (a, d, c) and (d, b, c): a and b lose
 * one edge each, c and d gain one.
 *
 * The criteria are inline here rather than in src/: both swap engines evaluate them
 * for every edge of every sweep, where a call the compiler cannot inline would cost
 * as much as the arithmetic.
 *
 * \ingroup MeshExtraction
 */
struct EdgeSwapQuad
{
  Vec3 a;
  Vec3 b;
  Vec3 c;
  Vec3 d;
  /** Number of edges at each corner before the swap. */
  unsigned int valenceA{ 6 };
  unsigned int valenceB{ 6 };
  unsigned int valenceC{ 6 };
  unsigned int valenceD{ 6 };
  /** Corners on a mesh boundary aim at valence 4 instead of 6 in the regularity
   * criterion (a regular boundary vertex of a triangulated plane has 4 edges). */
  bool boundaryA{ false };
  bool boundaryB{ false };
  bool boundaryC{ false };
  bool boundaryD{ false };
  /** c == d: the two triangles share all three corners. */
  bool sameApex{ false };
  /** The other diagonal (c, d) is already an edge of the mesh. */
  bool oppositeEdgeExists{ false };
};

struct EdgeSwapParameters
{
  MeshExtractionEnums::EdgeSwapCriterion criterion{ MeshExtractionEnums::EdgeSwapCriterion::Regularity };
  /** No interior corner may be left with fewer edges (thesis 4.5.1: a vertex with
   * two edges is not part of a continuous surface). A corner on a mesh boundary may
   * keep one edge fewer (two edges: the tip of a single triangle). */
  unsigned int minimumValence{ 3 };
  /** Largest dihedral angle, in radians, between the two old triangles and between
   * the two new ones: edges on a sharper crease (a feature) are not swapped and no
   * swap creates one. */
  double featureAngle{ itk::Math::pi / 3.0 };
  /** A swap may not create a triangle with q_area at or below this. */
  double degenerateQAreaTolerance{ ValidityThresholds::DegenerateQAreaTolerance };
  /** The smaller q_area of the two new triangles must be at least this times the
   * smaller q_area of the two old ones (0: no quality requirement). */
  double minimumQAreaRatio{ 0.0 };
};

/** Why EvaluateEdgeSwap() decided as it did. */
enum class EdgeSwapVerdict : std::uint8_t
{
  Swap = 0,           ///< improves the criterion and passes every check
  NoImprovement,      ///< the criterion does not improve
  NotManifold,        ///< c == d, or (c, d) is already an edge: the swap would duplicate an edge
  ValenceTooLow,      ///< a or b would keep fewer than minimumValence edges (one fewer on a boundary)
  DegenerateTriangle, ///< a new triangle would be degenerate
  NormalsDisagree,    ///< a new triangle's normal makes 90 degrees or more with an old one
  FeatureEdge,        ///< the old or the new pair of triangles is folded beyond featureAngle
  LowerQuality        ///< the worst new triangle is below minimumQAreaRatio times the worst old one
};

/** The verdict's name. */
MeshExtraction_EXPORT std::ostream &
                      operator<<(std::ostream & os, EdgeSwapVerdict v);

struct EdgeSwapDecision
{
  EdgeSwapVerdict verdict{ EdgeSwapVerdict::NoImprovement };
  /** How much the swap improves the criterion (> 0 means better): the drop of E_b,
   * the excess of the opposite angles over pi (radians), or the drop in edge length. */
  double gain{ 0.0 };

  bool
  Swap() const
  {
    return verdict == EdgeSwapVerdict::Swap;
  }
};

/** (d - target)^2 with target 6 for interior and 4 for boundary vertices. */
inline double
ValenceDeviation(double valence, bool boundary)
{
  const double dev = valence - (boundary ? 4.0 : 6.0);
  return dev * dev;
}

/** The gain of swapping the edge of `q` for `criterion`:
 * - Regularity: E_b before minus E_b after, E_b = sum over the corners of
 *   (d_i - 6)^2 (eq. 2.16); an integer, so oscillation is impossible;
 * - Delaunay: OppositeAngleSum(a, b, c, d) - pi, positive when d lies inside the
 *   circumcircle of (a, b, c) (Figure 2.18);
 * - ShortestEdge: |a - b| - |c - d|. */
inline double
EdgeSwapGain(MeshExtractionEnums::EdgeSwapCriterion criterion, const EdgeSwapQuad & q)
{
  using C = MeshExtractionEnums::EdgeSwapCriterion;
  switch (criterion)
  {
    case C::Regularity:
    {
      const double before = ValenceDeviation(q.valenceA, q.boundaryA) + ValenceDeviation(q.valenceB, q.boundaryB) +
                            ValenceDeviation(q.valenceC, q.boundaryC) + ValenceDeviation(q.valenceD, q.boundaryD);
      const double after =
        ValenceDeviation(q.valenceA - 1.0, q.boundaryA) + ValenceDeviation(q.valenceB - 1.0, q.boundaryB) +
        ValenceDeviation(q.valenceC + 1.0, q.boundaryC) + ValenceDeviation(q.valenceD + 1.0, q.boundaryD);
      return before - after;
    }
    case C::Delaunay:
      return OppositeAngleSum(q.a, q.b, q.c, q.d) - itk::Math::pi;
    case C::ShortestEdge:
      return Norm(q.a - q.b) - Norm(q.c - q.d);
  }
  return 0.0;
}

/** Whether the criterion counts `gain` as an improvement: > 0 for regularity (an
 * integer), above a relative tolerance for the geometric criteria so that rounding
 * cannot make an edge flip back and forth. */
inline bool
IsEdgeSwapImprovement(MeshExtractionEnums::EdgeSwapCriterion criterion, const EdgeSwapQuad & q, double gain)
{
  using C = MeshExtractionEnums::EdgeSwapCriterion;
  switch (criterion)
  {
    case C::Regularity:
      return gain > 0.5;
    case C::Delaunay:
      return gain > 1e-9;
    case C::ShortestEdge:
      return gain > 1e-9 * Norm(q.a - q.b);
  }
  return false;
}

/** The checks of thesis section 4.5.1 that make a swap safe, whatever the criterion:
 * - manifold: c != d and (c, d) is not already an edge (no duplicate edge);
 * - connectivity: a and b keep at least minimumValence edges (boundary vertices
 *   one fewer);
 * - neither new triangle (a, d, c), (d, b, c) is degenerate;
 * - concavity: each new triangle's normal makes an angle below 90 degrees with each
 *   old triangle's normal (dot > 0): a concave or folded quad is not swapped;
 * - features: the dihedral angle between the two old triangles and the one between
 *   the two new triangles are at most featureAngle;
 * - optionally (beyond the thesis) quality: with minimumQAreaRatio > 0 the worse new
 *   triangle keeps at least that fraction of the worse old triangle's q_area. */
inline EdgeSwapVerdict
CheckEdgeSwap(const EdgeSwapQuad & q, const EdgeSwapParameters & p)
{
  if (q.sameApex || q.oppositeEdgeExists)
  {
    return EdgeSwapVerdict::NotManifold;
  }
  const unsigned int boundaryMinimum = p.minimumValence > 0 ? p.minimumValence - 1 : 0;
  const unsigned int minimumA = q.boundaryA ? boundaryMinimum : p.minimumValence;
  const unsigned int minimumB = q.boundaryB ? boundaryMinimum : p.minimumValence;
  if (q.valenceA < minimumA + 1 || q.valenceB < minimumB + 1)
  {
    return EdgeSwapVerdict::ValenceTooLow;
  }
  const double newQ = std::min(TriangleQArea(q.a, q.d, q.c), TriangleQArea(q.d, q.b, q.c));
  if (!(newQ > p.degenerateQAreaTolerance))
  {
    return EdgeSwapVerdict::DegenerateTriangle;
  }
  const Vec3 n1 = TriangleNormal(q.a, q.b, q.c);
  const Vec3 n2 = TriangleNormal(q.b, q.a, q.d);
  const Vec3 m1 = TriangleNormal(q.a, q.d, q.c);
  const Vec3 m2 = TriangleNormal(q.d, q.b, q.c);
  if (!(Dot(m1, n1) > 0.0) || !(Dot(m1, n2) > 0.0) || !(Dot(m2, n1) > 0.0) || !(Dot(m2, n2) > 0.0))
  {
    return EdgeSwapVerdict::NormalsDisagree;
  }
  if (AngleBetween(n1, n2) > p.featureAngle || AngleBetween(m1, m2) > p.featureAngle)
  {
    return EdgeSwapVerdict::FeatureEdge;
  }
  if (p.minimumQAreaRatio > 0.0 &&
      newQ < p.minimumQAreaRatio * std::min(TriangleQArea(q.a, q.b, q.c), TriangleQArea(q.b, q.a, q.d)))
  {
    return EdgeSwapVerdict::LowerQuality;
  }
  return EdgeSwapVerdict::Swap;
}

/** True when neither angle opposite the edge (a, b) is obtuse: then their sum is at
 * most pi, so the Delaunay criterion cannot improve. Two dot products, where the gain
 * takes two arc tangents; it settles nearly every edge of a good mesh. The sum of the
 * two computed angles is at most pi as well (each arc tangent of a non-negative
 * cosine is at most the double nearest pi/2, and twice that is the double pi), so the
 * decision is the one the gain gives. */
inline bool
NeitherOppositeAngleIsObtuse(const EdgeSwapQuad & q)
{
  return Dot(q.a - q.c, q.b - q.c) >= 0.0 && Dot(q.b - q.d, q.a - q.d) >= 0.0;
}

/** The criterion's half of EvaluateEdgeSwap(): whether swapping the edge of `q`
 * improves the criterion, with its gain in `gain` (left at 0 when the Delaunay
 * criterion is ruled out by NeitherOppositeAngleIsObtuse(), where its exact value is
 * not positive). A caller that must look something up before the checks (whether
 * (c, d) is already an edge) asks this first and CheckEdgeSwap() after. */
inline bool
EdgeSwapImproves(const EdgeSwapQuad & q, const EdgeSwapParameters & p, double & gain)
{
  gain = 0.0;
  if (p.criterion == MeshExtractionEnums::EdgeSwapCriterion::Delaunay && NeitherOppositeAngleIsObtuse(q))
  {
    return false;
  }
  gain = EdgeSwapGain(p.criterion, q);
  return IsEdgeSwapImprovement(p.criterion, q, gain);
}

/** The whole decision: swap when the criterion improves (EdgeSwapImproves()) and
 * CheckEdgeSwap() passes. */
inline EdgeSwapDecision
EvaluateEdgeSwap(const EdgeSwapQuad & q, const EdgeSwapParameters & p)
{
  EdgeSwapDecision decision;
  decision.verdict = EdgeSwapImproves(q, p, decision.gain) ? CheckEdgeSwap(q, p) : EdgeSwapVerdict::NoImprovement;
  return decision;
}

} // namespace detail
} // namespace MeshExtraction
} // namespace itk

#endif
