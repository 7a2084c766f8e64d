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
#ifndef itkMeshExtractionPredicates_h
#define itkMeshExtractionPredicates_h

#include "MeshExtractionExport.h"
#include "itkMeshExtractionTriangleGeometry.h"
#include "itkIntTypes.h"

#include <cstdint>
#include <vector>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
/** \brief Exact geometric predicates on double coordinates.
 *
 * Each predicate first evaluates its determinant in floating point with a
 * forward error bound (Shewchuk's static filter); only when the sign is not
 * certified does it recompute the determinant exactly, as a sum of exact
 * products held in a floating-point expansion. The sign returned is therefore
 * always the sign of the exact determinant of the given doubles.
 *
 * \ingroup MeshExtraction
 */

/** Sign of det[b-a, c-a] in 2-D: +1 if (a, b, c) turns counter-clockwise, -1 if
 * clockwise, 0 if the three points are collinear. */
MeshExtraction_EXPORT int
Orient2D(const double a[2], const double b[2], const double c[2]);

/** Sign of det[b-a, c-a, d-a] = ((b-a) x (c-a)) . (d-a): +1 if d lies on the side
 * the normal of the counter-clockwise triangle (a, b, c) points to, -1 on the other
 * side, 0 if the four points are coplanar. */
MeshExtraction_EXPORT int
Orient3D(const Vec3 & a, const Vec3 & b, const Vec3 & c, const Vec3 & d);

/** The sign of Orient3D computed always with the full exact expansion (no
 * floating-point filter, no shortcut): for testing the exact path. */
MeshExtraction_EXPORT int
Orient3DExact(const Vec3 & a, const Vec3 & b, const Vec3 & c, const Vec3 & d);

/** True if a, b and c are collinear (or coincide), decided exactly. */
MeshExtraction_EXPORT bool
IsTriangleDegenerateExact(const Vec3 & a, const Vec3 & b, const Vec3 & c);

/** True if the closed segment [a, b] and the closed, non-degenerate triangle
 * (p, q, r) share at least one point. Exact. */
MeshExtraction_EXPORT bool
SegmentIntersectsTriangle(const Vec3 & a, const Vec3 & b, const Vec3 & p, const Vec3 & q, const Vec3 & r);

/** True if two closed, non-degenerate triangles share at least one point. Exact. */
MeshExtraction_EXPORT bool
TrianglesIntersect(const Vec3 P[3], const Vec3 Q[3]);

/** Self-intersection test for two faces of one mesh: true if the triangles share a
 * point other than the vertices and edge they have in common by vertex id (so mesh
 * neighbours touching along their common edge or vertex do not count, as in CGAL's
 * "strict" self-intersections). Identical vertex triples always count. Both
 * triangles must be non-degenerate. Exact. */
MeshExtraction_EXPORT bool
FacesIntersect(const Vec3 P[3], const IdentifierType pid[3], const Vec3 Q[3], const IdentifierType qid[3]);

/** A certificate that the faces around a vertex v meet only at v and along their
 * common edges. `ring` holds the fan's other k vertices in cyclic order, face i
 * being (v, ring[i], ring[(i + 1) % k]). True if, seen along one direction (the
 * fan's summed normal N), every face turns counter-clockwise and the faces go
 * around v exactly once: the fan then projects one-to-one onto a plane normal to N,
 * and a common point of two faces would project onto v or onto their common edge.
 * The signs det[N, a - v, b - v] are decided by a floating-point filter (Orient3D's
 * static bound); false means "not certified", not "intersecting". */
MeshExtraction_EXPORT bool
FanIsEmbeddedStar(const Vec3 & v, const Vec3 * ring, unsigned int k);

/** A face at a vertex, as seen from it: the face (v, next, last), counter-clockwise. */
struct FanCorner
{
  std::uint32_t next;
  std::uint32_t last;
};

/** The work arrays of CertifyFan, kept between calls. */
struct FanScratch
{
  std::vector<std::uint8_t>  used;
  std::vector<std::uint32_t> ring;
  std::vector<Vec3>          ringPoints;
};

/** FanIsEmbeddedStar for the k faces at vertex v of a consistently oriented mesh,
 * given in any order: they are chained into the fan's ring (each face (v, x, y) is
 * followed by the one that starts at y), which must close after visiting every face
 * once, through distinct vertices. False (not certified) otherwise. */
MeshExtraction_EXPORT bool
CertifyFan(const Vec3 * points, std::uint32_t v, const FanCorner * corners, std::size_t k, FanScratch & scratch);

} // namespace detail
} // namespace MeshExtraction
} // namespace itk

#endif
