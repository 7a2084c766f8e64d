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
#ifndef itkMeshExtractionTriangleGeometry_h
#define itkMeshExtractionTriangleGeometry_h

#include "MeshExtractionExport.h"
#include "itkVector.h"
#include "itkMath.h"

#include <algorithm>
#include <cmath>

namespace itk
{
/** \namespace itk::MeshExtraction
 * \brief The module's public utility types: phantoms, the calculators' reports, the
 * indexed triangle mesh and its conversions, the SurfaceNet, geodesic spheres, landmark
 * files and the small triangle geometry below. Everything else the filters share lives
 * in the nested namespace itk::MeshExtraction::detail, whose headers say so in their
 * first line: it is not part of the public API and may change without notice.
 *
 * All triangle geometry of the module lives in this header: angles, areas,
 * normals, the quality measures of the thesis (section 4.2.3), closest point on a
 * triangle and ray-triangle intersection. Every filter and calculator calls these
 * functions so that a triangle is measured the same way everywhere.
 * Computation is in double precision whatever the mesh's coordinate type.
 *
 * The small primitives (Dot, Cross, norms, normals, q_area, cotangents, closest point
 * on a triangle, ray-triangle test, ...) are inline here: they run in the inner loops
 * of relaxation, smoothing, edge swaps and tree queries, where a call that the
 * compiler cannot inline would cost as much as the arithmetic. The larger measures
 * that are not in such loops (MeasureTriangle, the circumcircle) are in
 * src/itkMeshExtractionTriangleGeometry.cxx.
 *
 * \ingroup MeshExtraction
 */
namespace MeshExtraction
{
using Vec3 = Vector<double, 3>;

inline Vec3
MakeVec3(double x, double y, double z)
{
  Vec3 v;
  v[0] = x;
  v[1] = y;
  v[2] = z;
  return v;
}

/** Any point-like object with operator[] (itk::Point of float or double, ...). */
template <typename TPoint>
inline Vec3
ToVec3(const TPoint & p)
{
  return MakeVec3(static_cast<double>(p[0]), static_cast<double>(p[1]), static_cast<double>(p[2]));
}

inline double
Dot(const Vec3 & a, const Vec3 & b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

inline Vec3
Cross(const Vec3 & a, const Vec3 & b)
{
  return MakeVec3(a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]);
}

inline double
SquaredNorm(const Vec3 & a)
{
  return Dot(a, a);
}

inline double
Norm(const Vec3 & a)
{
  return std::sqrt(Dot(a, a));
}

/** Angle in radians between two vectors, in [0, pi]; 0 when either is zero.
 * atan2(|u x v|, u.v) stays accurate near 0 and pi, where acos does not. */
inline double
AngleBetween(const Vec3 & u, const Vec3 & v)
{
  return std::atan2(Norm(Cross(u, v)), Dot(u, v));
}

/** Interior angle at `apex` of the triangle (apex, p, q). */
inline double
AngleAtVertex(const Vec3 & apex, const Vec3 & p, const Vec3 & q)
{
  return AngleBetween(p - apex, q - apex);
}

/** Un-normalised normal (b-a)x(c-a): its length is twice the area, its direction
 * follows the counter-clockwise order a, b, c (right-hand rule). */
inline Vec3
TriangleNormal(const Vec3 & a, const Vec3 & b, const Vec3 & c)
{
  return Cross(b - a, c - a);
}

inline double
TriangleArea(const Vec3 & a, const Vec3 & b, const Vec3 & c)
{
  return 0.5 * Norm(TriangleNormal(a, b, c));
}

inline Vec3
TriangleCentroid(const Vec3 & a, const Vec3 & b, const Vec3 & c)
{
  return (a + b + c) * (1.0 / 3.0);
}

/** Unit normal, or the zero vector for a degenerate triangle. */
inline Vec3
TriangleUnitNormal(const Vec3 & a, const Vec3 & b, const Vec3 & c)
{
  Vec3         n = TriangleNormal(a, b, c);
  const double l = Norm(n);
  if (l > 0.0)
  {
    n *= 1.0 / l;
  }
  return n;
}

/** The measures of one triangle (thesis section 4.2.3 and chapter 3).
 * edgeLength[i] is the edge opposite vertex i; angle[i] is the angle at vertex i. */
struct TriangleMeasures
{
  double edgeLength[3];
  double angle[3];
  double area;
  double qLength; ///< shortest / longest edge
  double qAngle;  ///< smallest / largest angle
  double qArea;   ///< 4 sqrt(3) A / (e1^2 + e2^2 + e3^2)
  double minAngle;
  double maxAngle;
};

/** Measure a triangle. A triangle with a zero-length edge gets qLength = qAngle =
 * qArea = 0, minimum angle 0 and maximum angle pi. */
MeshExtraction_EXPORT TriangleMeasures
MeasureTriangle(const Vec3 & a, const Vec3 & b, const Vec3 & c);

/** Closest point on segment [a, b] to p. */
inline Vec3
ClosestPointOnSegment(const Vec3 & p, const Vec3 & a, const Vec3 & b)
{
  const Vec3   ab = b - a;
  const double l2 = SquaredNorm(ab);
  if (!(l2 > 0.0))
  {
    return a;
  }
  const double t = std::clamp(Dot(p - a, ab) / l2, 0.0, 1.0);
  return a + ab * t;
}

/** Closest point on the closed triangle (a, b, c) to p, found by the Voronoi-region
 * classification of Ericson, "Real-Time Collision Detection", section 5.1.5.
 * Degenerate triangles fall back to the closest of the three edges. */
inline Vec3
ClosestPointOnTriangle(const Vec3 & p, const Vec3 & a, const Vec3 & b, const Vec3 & c)
{
  const Vec3   ab = b - a;
  const Vec3   ac = c - a;
  const Vec3   ap = p - a;
  const double d1 = Dot(ab, ap);
  const double d2 = Dot(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0)
  {
    return a;
  }
  const Vec3   bp = p - b;
  const double d3 = Dot(ab, bp);
  const double d4 = Dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3)
  {
    return b;
  }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 && d1 - d3 > 0.0)
  {
    return a + ab * (d1 / (d1 - d3));
  }
  const Vec3   cp = p - c;
  const double d5 = Dot(ab, cp);
  const double d6 = Dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6)
  {
    return c;
  }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 && d2 - d6 > 0.0)
  {
    return a + ac * (d2 / (d2 - d6));
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 && (d4 - d3) + (d5 - d6) > 0.0)
  {
    return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  }
  const double sum = va + vb + vc;
  if (sum > 0.0)
  {
    const double v = vb / sum;
    const double w = vc / sum;
    return a + ab * v + ac * w;
  }
  // Degenerate (collinear or coincident) triangle: closest of the three edges.
  const Vec3   q0 = ClosestPointOnSegment(p, a, b);
  const Vec3   q1 = ClosestPointOnSegment(p, b, c);
  const Vec3   q2 = ClosestPointOnSegment(p, c, a);
  const double e0 = SquaredNorm(p - q0);
  const double e1 = SquaredNorm(p - q1);
  const double e2 = SquaredNorm(p - q2);
  if (e0 <= e1 && e0 <= e2)
  {
    return q0;
  }
  return e1 <= e2 ? q1 : q2;
}

inline double
SquaredDistancePointTriangle(const Vec3 & p, const Vec3 & a, const Vec3 & b, const Vec3 & c)
{
  return SquaredNorm(p - ClosestPointOnTriangle(p, a, b, c));
}

/** Result of a ray-triangle test. `ambiguous` flags hits too close to an edge, a
 * vertex, or a ray parallel to the plane to be counted reliably (callers retry with
 * another direction). */
struct RayTriangleHit
{
  bool   hit{ false };
  bool   ambiguous{ false };
  double t{ 0.0 };
};

/** Moller-Trumbore ray/triangle test for t > tMin, with a relative tolerance on the
 * barycentric coordinates that marks grazing hits as ambiguous. */
inline RayTriangleHit
IntersectRayTriangle(const Vec3 & origin,
                     const Vec3 & direction,
                     const Vec3 & a,
                     const Vec3 & b,
                     const Vec3 & c,
                     double       tMin,
                     double       tolerance = 1e-9)
{
  RayTriangleHit r;
  const Vec3     e1 = b - a;
  const Vec3     e2 = c - a;
  const Vec3     pv = Cross(direction, e2);
  const double   det = Dot(e1, pv);
  const double   scale = Norm(e1) * Norm(e2) * Norm(direction);
  if (!(scale > 0.0))
  {
    return r; // degenerate triangle: it has no interior to cross
  }
  const Vec3 tv = origin - a;
  const Vec3 qv = Cross(tv, e1);
  if (std::abs(det) <= tolerance * scale)
  {
    // Parallel to the plane: ambiguous only if the ray lies in the plane.
    const Vec3 n = Cross(e1, e2);
    if (std::abs(Dot(tv, n)) <= tolerance * Norm(n) * (Norm(tv) + 1e-300))
    {
      r.ambiguous = true;
    }
    return r;
  }
  const double inv = 1.0 / det;
  const double u = Dot(tv, pv) * inv;
  const double v = Dot(direction, qv) * inv;
  const double t = Dot(e2, qv) * inv;
  const double tol = 1e-7;
  if (u < -tol || v < -tol || u + v > 1.0 + tol || t <= tMin)
  {
    return r;
  }
  if (u < tol || v < tol || u + v > 1.0 - tol)
  {
    r.ambiguous = true;
    return r;
  }
  r.hit = true;
  r.t = t;
  return r;
}

// --- mesh improvement ---
// Geometry of the smoothing and edge-swap filters (thesis sections 2.2.3-2.2.6, 4.5.1).

/** q_area = 4 sqrt(3) A / (e1^2 + e2^2 + e3^2) of the triangle (a, b, c), the same
 * value as MeasureTriangle(a, b, c).qArea without the angles; 0 when all three
 * points coincide. */
inline double
TriangleQArea(const Vec3 & a, const Vec3 & b, const Vec3 & c)
{
  const Vec3   ab = b - a;
  const Vec3   ac = c - a;
  const double sumSq = SquaredNorm(ab) + SquaredNorm(ac) + SquaredNorm(c - b);
  if (!(sumSq > 0.0))
  {
    return 0.0;
  }
  return std::min(1.0, 2.0 * std::sqrt(3.0) * Norm(Cross(ab, ac)) / sumSq);
}

/** Cotangent of the angle at `apex` of the triangle (apex, p, q): the weight of
 * the edge opposite `apex` in the cotangent (Desbrun) Laplacian. 0 for a
 * degenerate triangle, whose angle has no finite cotangent. */
inline double
Cotangent(const Vec3 & apex, const Vec3 & p, const Vec3 & q)
{
  const Vec3   u = p - apex;
  const Vec3   v = q - apex;
  const double s = Norm(Cross(u, v));
  if (!(s > 0.0))
  {
    return 0.0;
  }
  return Dot(u, v) / s;
}

/** Perpendicular projection of `p` onto the line through `origin` along
 * `direction`; `origin` if the direction is the zero vector. */
inline Vec3
ProjectOntoLine(const Vec3 & p, const Vec3 & origin, const Vec3 & direction)
{
  const double l2 = SquaredNorm(direction);
  if (!(l2 > 0.0))
  {
    return origin;
  }
  return origin + direction * (Dot(p - origin, direction) / l2);
}

/** Unit direction of the line bisecting the angle at `apex` between the rays to
 * `p` and `q` (thesis Figure 2.16): the sum of the two unit vectors. When the rays
 * are (nearly) opposite that sum vanishes and the bisector is the direction
 * perpendicular to the rays in the plane normal to `normal`. The zero vector if
 * neither is defined (a zero-length ray). The line bisects the reflex angle too. */
inline Vec3
AngleBisectorDirection(const Vec3 & apex, const Vec3 & p, const Vec3 & q, const Vec3 & normal)
{
  const Vec3   u = p - apex;
  const Vec3   v = q - apex;
  const double lu = Norm(u);
  const double lv = Norm(v);
  if (!(lu > 0.0) || !(lv > 0.0))
  {
    return Vec3(0.0);
  }
  Vec3         b = u * (1.0 / lu) + v * (1.0 / lv);
  const double lb = Norm(b);
  if (lb > 1e-6)
  {
    return b * (1.0 / lb);
  }
  b = Cross(normal, v * (1.0 / lv) - u * (1.0 / lu));
  const double l = Norm(b);
  return l > 0.0 ? b * (1.0 / l) : Vec3(0.0);
}

/** Sum of the two angles opposite the edge (a, b): the angle at c in the triangle
 * (a, b, c) plus the angle at d in the triangle (b, a, d). The edge is locally
 * Delaunay when the sum is at most pi; for a planar quad a sum above pi means d
 * lies inside the circumcircle of (a, b, c) (thesis Figure 2.18), and this form
 * extends the test to the non-planar quads of a surface mesh. */
inline double
OppositeAngleSum(const Vec3 & a, const Vec3 & b, const Vec3 & c, const Vec3 & d)
{
  return AngleAtVertex(c, a, b) + AngleAtVertex(d, b, a);
}

/** Circumcentre of the triangle (a, b, c), in its plane; the centroid for a
 * degenerate triangle (which has no circumcircle). */
MeshExtraction_EXPORT Vec3
TriangleCircumcenter(const Vec3 & a, const Vec3 & b, const Vec3 & c);

/** Whether d, projected onto the plane of (a, b, c), lies strictly inside the
 * circumcircle of (a, b, c) (relative tolerance 1e-12 on the squared radius). */
MeshExtraction_EXPORT bool
IsInsideCircumcircle(const Vec3 & a, const Vec3 & b, const Vec3 & c, const Vec3 & d);

// --- scale-space edge detection ---

/** x rounded, component by component, to the coordinate type T of a mesh (float for
 * itk::QuadEdgeMesh<double, 3>), so that a check made on the result sees exactly what
 * the mesh will hold. The rounded value goes through a volatile temporary: GCC 12.2
 * at -O2 drops a (double)(float) round trip in loops it vectorizes (SLP), returning
 * the unrounded value for two of the three components. */
template <typename T>
inline Vec3
RoundToCoordinateType(const Vec3 & x)
{
  Vec3 r;
  for (unsigned int d = 0; d < 3; ++d)
  {
    volatile T rounded = static_cast<T>(x[d]);
    r[d] = static_cast<double>(rounded);
  }
  return r;
}

} // namespace MeshExtraction
} // namespace itk

#endif
