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
#ifndef itkMeshExtractionClosedFormGeometry_h
#define itkMeshExtractionClosedFormGeometry_h

#include "itkMatrix.h"
#include "itkPoint.h"
#include "itkMeshExtractionTriangleGeometry.h"
#include "MeshExtractionExport.h"

#include <limits>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
/** \file
 * \brief The closed-form geometry of the analytic surfaces and the phantoms, written
 * once: orthonormal frames (Gram-Schmidt, rotations about an axis, a frame from a
 * normal), local and physical coordinates of a rotated shape, spheres and their
 * intersection circles and triple points, and the closest point on a circle, a
 * rectangle and an ellipsoid.
 *
 * Every ImplicitSurfaceFunction and MakePhantomSurface() use these functions, so a
 * frame is orthonormalised and a closest point is found the same way everywhere.
 * Vectors are MeshExtraction::Vec3 (itkMeshExtractionTriangleGeometry.h); matrices
 * are 3x3 of double. The one-line conversions are inline, as they sit inside every
 * evaluation; the rest is compiled in src/itkMeshExtractionClosedFormGeometry.cxx.
 *
 * \ingroup MeshExtraction
 */

using Matrix3 = Matrix<double, 3, 3>;
using Point3 = Point<double, 3>;

constexpr double Infinity = std::numeric_limits<double>::infinity();

// ---------------------------------------------------------------------------------
// Points, vectors and frames
// ---------------------------------------------------------------------------------

inline Point3
ToPoint3(const Vec3 & v)
{
  Point3 p;
  p[0] = v[0];
  p[1] = v[1];
  p[2] = v[2];
  return p;
}

/** v / |v|. */
inline Vec3
Normalized(const Vec3 & v)
{
  return v / Norm(v);
}

/** v minus its component along the unit vector `axis` (one Gram-Schmidt step). */
inline Vec3
RemoveComponent(const Vec3 & v, const Vec3 & axis)
{
  return v - axis * Dot(v, axis);
}

/** R^T v: physical direction to the local frame of an orthogonal R. */
inline Vec3
ToLocalFrame(const Matrix3 & r, const Vec3 & v)
{
  Vec3 out;
  for (unsigned int j = 0; j < 3; ++j)
  {
    out[j] = r(0, j) * v[0] + r(1, j) * v[1] + r(2, j) * v[2];
  }
  return out;
}

/** R v: local frame to physical direction. */
inline Vec3
ToPhysicalFrame(const Matrix3 & r, const Vec3 & v)
{
  Vec3 out;
  for (unsigned int i = 0; i < 3; ++i)
  {
    out[i] = r(i, 0) * v[0] + r(i, 1) * v[1] + r(i, 2) * v[2];
  }
  return out;
}

/** The coordinates of `point` in the frame with origin `center` and axes the columns
 * of the orthogonal `rotation`. */
inline Vec3
LocalCoordinates(const Point3 & center, const Matrix3 & rotation, const Point3 & point)
{
  return ToLocalFrame(rotation, ToVec3(point) - ToVec3(center));
}

/** The physical point of the local coordinates `local` (the inverse of
 * LocalCoordinates). */
inline Point3
PhysicalPoint(const Point3 & center, const Matrix3 & rotation, const Vec3 & local)
{
  return ToPoint3(ToVec3(center) + ToPhysicalFrame(rotation, local));
}

/** max |M^T M - I| over the entries; infinity when an entry is not finite. */
MeshExtraction_EXPORT double
OrthogonalityError(const Matrix3 & m);

/** Gram-Schmidt on the columns of a (nearly) orthogonal m, so that the result's
 * columns are orthonormal to rounding and distances computed in its frame are
 * distances in physical space. */
MeshExtraction_EXPORT Matrix3
OrthonormalizeColumns(const Matrix3 & m);

/** The rotation by `degrees` about the third axis. */
MeshExtraction_EXPORT Matrix3
RotationAboutZ(double degrees);

/** The rotation by `degrees` about the first axis. */
MeshExtraction_EXPORT Matrix3
RotationAboutX(double degrees);

/** The orthonormal frame whose third column is the unit vector `unitNormal`, whose
 * first column is `edge` projected onto the plane perpendicular to it (normalised),
 * and whose second is their cross product (right-handed). */
MeshExtraction_EXPORT Matrix3
FrameFromNormal(const Vec3 & unitNormal, const Vec3 & edge);

/** A unit vector perpendicular to the unit vector u. */
MeshExtraction_EXPORT Vec3
AnyUnitPerpendicular(const Vec3 & u);

/** The unit direction of the component of d perpendicular to the unit vector
 * `axis`, and that component's length in `length`. The component is projected
 * twice, so that the direction is perpendicular to the axis to rounding even when d
 * is almost parallel to it; when d is parallel to the axis (to rounding) every
 * perpendicular direction is equally good and a fixed one is returned. */
MeshExtraction_EXPORT Vec3
RadialDirection(const Vec3 & d, const Vec3 & axis, double & length);

/** Half the extent along physical axis i of the box with half-sizes `halfSizes`
 * along the columns of `rotation`: sum_j |rotation(i, j)| halfSizes[j]. */
MeshExtraction_EXPORT double
RotatedBoxHalfExtent(const Matrix3 & rotation, const Vec3 & halfSizes, unsigned int i);

// ---------------------------------------------------------------------------------
// Spheres, circles and rectangles
// ---------------------------------------------------------------------------------

/** Relative tolerance of the "is this boundary candidate inside another ball" tests
 * of the sphere union and difference: a candidate within this relative distance of
 * a sphere counts as on it, so that points of an intersection circle or of
 * coincident spheres are not discarded because of rounding. */
constexpr double BallCoverTolerance = 1e-12;

/** True when q is in the interior of the ball (c, r), beyond rounding. */
inline bool
StrictlyInsideBall(const Vec3 & q, const Vec3 & c, double r)
{
  return Norm(q - c) < r * (1.0 - BallCoverTolerance);
}

/** True when q is outside the ball (c, r), beyond rounding. */
inline bool
StrictlyOutsideBall(const Vec3 & q, const Vec3 & c, double r)
{
  return Norm(q - c) > r * (1.0 + BallCoverTolerance);
}

/** The point of sphere (c, r) closest to p: the radial projection, or a fixed point
 * when p is the centre. The distance |p - q| is returned in `distance`. */
MeshExtraction_EXPORT Vec3
RadialProjection(const Vec3 & p, const Vec3 & c, double r, double & distance);

/** A circle in 3-D: centre, unit normal of its plane, radius. */
struct Circle3
{
  Vec3   center;
  Vec3   axis;
  double radius;
};

/** Closest point to p on the circle. Every point is equally close when p is on the
 * circle's axis; a fixed one is returned then. */
MeshExtraction_EXPORT Vec3
ClosestPointOnCircle(const Vec3 & p, const Circle3 & c);

/** The circle where two spheres cross; false when they do not cross in a circle of
 * positive radius (apart, nested, tangent or concentric). */
MeshExtraction_EXPORT bool
IntersectTwoSpheres(const Vec3 & c0, double r0, const Vec3 & c1, double r1, Circle3 & circle);

/** The points common to three spheres (trilateration); returns how many (0, 1, 2).
 * Spheres with collinear centres meet in a circle or not at all: 0 is returned, and
 * the circle is found as a pairwise intersection circle instead. */
MeshExtraction_EXPORT unsigned int
IntersectThreeSpheres(const Vec3 & c0,
                      double       r0,
                      const Vec3 & c1,
                      double       r1,
                      const Vec3 & c2,
                      double       r2,
                      Vec3 (&points)[2]);

/** Closest point to p on the closed rectangle corner + s e0 + t e1, s, t in [0, 1],
 * where e0 and e1 are orthogonal and non-zero. */
MeshExtraction_EXPORT Vec3
ClosestPointOnRectangle(const Vec3 & p, const Vec3 & corner, const Vec3 & e0, const Vec3 & e1);

/** Keeps the best (closest) candidate of a search for the closest surface point. */
struct NearestCandidate
{
  double distance{ Infinity };
  Vec3   point{ MakeVec3(0.0, 0.0, 0.0) };

  /** Considers q as the closest point to p. */
  void
  Consider(const Vec3 & p, const Vec3 & q)
  {
    this->Consider(Norm(p - q), q);
  }
  /** Considers q at the distance d. */
  void
  Consider(double d, const Vec3 & q)
  {
    if (d < distance)
    {
      distance = d;
      point = q;
    }
  }
};

// ---------------------------------------------------------------------------------
// Ellipsoids
// ---------------------------------------------------------------------------------

/** The closest point `closest` to q on the axis-aligned ellipsoid centred at the
 * origin with semi-axes `semiAxes` (each > 0, any order), and the distance |q -
 * closest|. Exact to machine precision, after D. Eberly, "Distance from a Point to
 * an Ellipse, an Ellipsoid, or a Hyperellipsoid", Geometric Tools (2013): the axes
 * are sorted by decreasing length, q is folded into the first octant, and the
 * closest point is the root of a monotone secular function found by bisection, with
 * the points on the principal planes, on the axes and at the centre handled
 * explicitly. */
MeshExtraction_EXPORT double
ClosestPointOnEllipsoid(const Vec3 & semiAxes, const Vec3 & q, Vec3 & closest);

} // namespace detail
} // namespace MeshExtraction
} // namespace itk

#endif
