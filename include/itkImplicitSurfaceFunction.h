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
#ifndef itkImplicitSurfaceFunction_h
#define itkImplicitSurfaceFunction_h

#include "itkSpatialFunction.h"
#include "itkMatrix.h"
#include "itkPoint.h"
#include "itkVector.h"
#include "itkMeshExtractionMacros.h"
#include "MeshExtractionExport.h"

#include <string>
#include <vector>

namespace itk
{
/** \class ImplicitSurfaceFunction
 * \brief A closed analytic surface in 3-D physical space with an exact signed distance.
 *
 * The reference shapes against which the module's extraction accuracy is measured.
 * All values are in physical units (mm):
 *
 * - Evaluate(p) is the exact signed Euclidean distance from p to the surface:
 *   negative inside, zero on the surface, positive outside. "Exact" means the true
 *   distance (to rounding), not a bound and not an approximation, so that
 *   |Evaluate(p)| == |p - ClosestSurfacePoint(p)| and Evaluate is 1-Lipschitz.
 * - ClosestSurfacePoint(p) is a point of the surface at that distance (one of
 *   them where several are equally close, e.g. at the centre of a sphere).
 * - GetBounds() gives an axis-aligned box that contains the surface.
 * - IsInside(p) is Evaluate(p) <= 0.
 *
 * A parameter that is invalid on its own (a non-positive radius, a zero normal, a
 * non-orthogonal rotation, a NaN) is rejected by its Set method with an
 * itk::ExceptionObject naming the parameter and the value. Constraints between
 * parameters (minor radius < major radius, slot narrower than the block, ...) can
 * be violated temporarily while parameters are changed one by one; they are checked
 * by VerifyParameters(), which Evaluate, ClosestSurfacePoint, GetBounds and
 * ImplicitSurfaceImageSource call, so an invalid combination is never evaluated.
 *
 * Evaluation is const and thread safe: concrete classes keep no mutable state.
 *
 * \ingroup MeshExtraction
 */
class MeshExtraction_EXPORT ImplicitSurfaceFunction : public SpatialFunction<double, 3, Point<double, 3>>
{
public:
  ITK_DISALLOW_COPY_AND_MOVE(ImplicitSurfaceFunction);

  using Self = ImplicitSurfaceFunction;
  using Superclass = SpatialFunction<double, 3, Point<double, 3>>;
  using Pointer = SmartPointer<Self>;
  using ConstPointer = SmartPointer<const Self>;

  itkOverrideGetNameOfClassMacro(ImplicitSurfaceFunction);

  using InputType = Superclass::InputType;
  using OutputType = Superclass::OutputType;
  using PointType = InputType;
  using VectorType = Vector<double, 3>;
  using MatrixType = Matrix<double, 3, 3>;

  /** Exact signed distance (mm) from `point` to the surface, negative inside. */
  OutputType
  Evaluate(const InputType & point) const override = 0;

  /** The surface point closest to `point`. */
  virtual InputType
  ClosestSurfacePoint(const InputType & point) const = 0;

  /** Signed distance and closest surface point in one computation. The default
   * calls Evaluate and ClosestSurfacePoint; concrete classes compute both at once. */
  virtual OutputType
  EvaluateWithClosestPoint(const InputType & point, InputType & closest) const;

  /** An axis-aligned box [lower, upper] that contains the surface. Unbounded
   * surfaces (the plane) report infinite coordinates. */
  virtual void
  GetBounds(InputType & lower, InputType & upper) const = 0;

  /** Evaluate(point) <= 0: inside or on the surface. */
  bool
  IsInside(const InputType & point) const
  {
    return this->Evaluate(point) <= 0.0;
  }

  /** Throws an itk::ExceptionObject describing the first violated constraint
   * between parameters; does nothing when the parameters are consistent. */
  void
  VerifyParameters() const;

  /** True when VerifyParameters() would not throw. */
  bool
  AreParametersValid() const
  {
    return m_ParameterError.empty();
  }

protected:
  ImplicitSurfaceFunction() = default;
  ~ImplicitSurfaceFunction() override = default;
  void
  PrintSelf(std::ostream & os, Indent indent) const override;

  /** Concrete classes: describe the first violated constraint between parameters,
   * or return an empty string. */
  virtual std::string
  CheckParameterConsistency() const
  {
    return {};
  }

  /** Concrete classes call this at the end of every Set method: it re-checks the
   * constraints between parameters and calls Modified(). */
  void
  ParametersChanged();

  /** The fast check at the top of every evaluation. */
  void
  ThrowIfParametersInvalid() const
  {
    if (!m_ParameterError.empty())
    {
      this->VerifyParameters();
    }
  }

  /** Throws unless `value` is finite and > 0. */
  void
  RequirePositive(const char * parameterName, double value) const;
  /** Throws unless every component is finite and > 0. */
  void
  RequirePositive(const char * parameterName, const VectorType & value) const;
  /** Throws unless every component is finite. */
  void
  RequireFinite(const char * parameterName, const InputType & value) const;
  /** Throws unless `value` is finite and not the zero vector; returns it normalised. */
  VectorType
  RequireDirection(const char * parameterName, const VectorType & value) const;
  /** Throws unless `value` is orthogonal (columns orthonormal) within 1e-6; returns
   * it re-orthonormalised to rounding so that distances stay exact. */
  MatrixType
  RequireRotation(const char * parameterName, const MatrixType & value) const;

  /** `value` with 17 significant digits, for the messages of
   * CheckParameterConsistency(). */
  static std::string
  ParameterText(double value);
  static std::string
  ParameterText(const InputType & value);
  static std::string
  ParameterText(const VectorType & value);

private:
  std::string m_ParameterError;
};

/** \class PlaneImplicitSurface
 * \brief The plane through Point with normal Normal; inside is the half-space the
 * normal points away from.
 *
 * Evaluate(p) = (p - Point) . n / |n|. The plane is unbounded: GetBounds reports
 * -/+ infinity, except along a coordinate axis the normal is parallel to.
 * Defaults: Point (0,0,0), Normal (0,0,1).
 * \ingroup MeshExtraction
 */
class MeshExtraction_EXPORT PlaneImplicitSurface : public ImplicitSurfaceFunction
{
public:
  ITK_DISALLOW_COPY_AND_MOVE(PlaneImplicitSurface);
  using Self = PlaneImplicitSurface;
  using Superclass = ImplicitSurfaceFunction;
  using Pointer = SmartPointer<Self>;
  using ConstPointer = SmartPointer<const Self>;
  itkOverrideGetNameOfClassMacro(PlaneImplicitSurface);
  itkNewMacro(Self);

  /** A point of the plane. */
  void
  SetPoint(const InputType & point);
  itkGetConstReferenceMacro(Point, InputType);
  /** The normal (any non-zero length; stored normalised). */
  void
  SetNormal(const VectorType & normal);
  itkGetConstReferenceMacro(Normal, VectorType);

  OutputType
  Evaluate(const InputType & point) const override;
  InputType
  ClosestSurfacePoint(const InputType & point) const override;
  OutputType
  EvaluateWithClosestPoint(const InputType & point, InputType & closest) const override;
  void
  GetBounds(InputType & lower, InputType & upper) const override;

protected:
  PlaneImplicitSurface();
  ~PlaneImplicitSurface() override = default;
  void
  PrintSelf(std::ostream & os, Indent indent) const override;

private:
  InputType  m_Point;
  VectorType m_Normal;
};

/** \class SphereImplicitSurface
 * \brief The sphere of radius Radius around Center: Evaluate(p) = |p - Center| - Radius.
 *
 * Defaults: Center (0,0,0), Radius 1.
 * \ingroup MeshExtraction
 */
class MeshExtraction_EXPORT SphereImplicitSurface : public ImplicitSurfaceFunction
{
public:
  ITK_DISALLOW_COPY_AND_MOVE(SphereImplicitSurface);
  using Self = SphereImplicitSurface;
  using Superclass = ImplicitSurfaceFunction;
  using Pointer = SmartPointer<Self>;
  using ConstPointer = SmartPointer<const Self>;
  itkOverrideGetNameOfClassMacro(SphereImplicitSurface);
  itkNewMacro(Self);

  void
  SetCenter(const InputType & center);
  itkGetConstReferenceMacro(Center, InputType);
  /** Radius > 0. */
  void
  SetRadius(double radius);
  itkGetConstMacro(Radius, double);

  OutputType
  Evaluate(const InputType & point) const override;
  InputType
  ClosestSurfacePoint(const InputType & point) const override;
  OutputType
  EvaluateWithClosestPoint(const InputType & point, InputType & closest) const override;
  void
  GetBounds(InputType & lower, InputType & upper) const override;

protected:
  SphereImplicitSurface();
  ~SphereImplicitSurface() override = default;
  void
  PrintSelf(std::ostream & os, Indent indent) const override;

private:
  InputType m_Center;
  double    m_Radius{ 1.0 };
};

/** \class EllipsoidImplicitSurface
 * \brief An ellipsoid with semi-axes SemiAxes along the columns of Rotation,
 * centred at Center.
 *
 * A point x is on the surface when q = Rotation^T (x - Center) satisfies
 * sum_i (q_i / SemiAxes_i)^2 = 1. The distance is exact: the closest point is the
 * root of Eberly's monotone secular function, found by bisection to machine
 * precision (D. Eberly, "Distance from a Point to an Ellipse, an Ellipsoid, or a
 * Hyperellipsoid", Geometric Tools, 2013), with the special cases of points on the
 * principal planes, on the axes and at the centre handled explicitly.
 *
 * Defaults: Center (0,0,0), SemiAxes (1,1,1), Rotation identity.
 * \ingroup MeshExtraction
 */
class MeshExtraction_EXPORT EllipsoidImplicitSurface : public ImplicitSurfaceFunction
{
public:
  ITK_DISALLOW_COPY_AND_MOVE(EllipsoidImplicitSurface);
  using Self = EllipsoidImplicitSurface;
  using Superclass = ImplicitSurfaceFunction;
  using Pointer = SmartPointer<Self>;
  using ConstPointer = SmartPointer<const Self>;
  itkOverrideGetNameOfClassMacro(EllipsoidImplicitSurface);
  itkNewMacro(Self);

  void
  SetCenter(const InputType & center);
  itkGetConstReferenceMacro(Center, InputType);
  /** The three semi-axis lengths, each > 0, in any order. */
  void
  SetSemiAxes(const VectorType & semiAxes);
  itkGetConstReferenceMacro(SemiAxes, VectorType);
  /** Orthogonal matrix whose column i is the direction of semi-axis i (local to
   * physical). Checked orthogonal within 1e-6 and re-orthonormalised. */
  void
  SetRotation(const MatrixType & rotation);
  itkGetConstReferenceMacro(Rotation, MatrixType);

  OutputType
  Evaluate(const InputType & point) const override;
  InputType
  ClosestSurfacePoint(const InputType & point) const override;
  OutputType
  EvaluateWithClosestPoint(const InputType & point, InputType & closest) const override;
  void
  GetBounds(InputType & lower, InputType & upper) const override;

protected:
  EllipsoidImplicitSurface();
  ~EllipsoidImplicitSurface() override = default;
  void
  PrintSelf(std::ostream & os, Indent indent) const override;

private:
  InputType  m_Center;
  VectorType m_SemiAxes;
  MatrixType m_Rotation;
};

/** \class TorusImplicitSurface
 * \brief A ring torus: the points at distance MinorRadius from the circle of radius
 * MajorRadius around Axis through Center.
 *
 * Evaluate(p) = sqrt((rho - R)^2 + h^2) - r, with h the height of p along the axis
 * and rho its distance from the axis. Requires 0 < MinorRadius < MajorRadius.
 * Defaults: Center (0,0,0), Axis (0,0,1), MajorRadius 2, MinorRadius 1.
 * \ingroup MeshExtraction
 */
class MeshExtraction_EXPORT TorusImplicitSurface : public ImplicitSurfaceFunction
{
public:
  ITK_DISALLOW_COPY_AND_MOVE(TorusImplicitSurface);
  using Self = TorusImplicitSurface;
  using Superclass = ImplicitSurfaceFunction;
  using Pointer = SmartPointer<Self>;
  using ConstPointer = SmartPointer<const Self>;
  itkOverrideGetNameOfClassMacro(TorusImplicitSurface);
  itkNewMacro(Self);

  void
  SetCenter(const InputType & center);
  itkGetConstReferenceMacro(Center, InputType);
  /** The axis of symmetry (any non-zero length; stored normalised). */
  void
  SetAxis(const VectorType & axis);
  itkGetConstReferenceMacro(Axis, VectorType);
  /** R > 0, the radius of the core circle. */
  void
  SetMajorRadius(double radius);
  itkGetConstMacro(MajorRadius, double);
  /** r > 0, the radius of the tube; r < R is checked by VerifyParameters(). */
  void
  SetMinorRadius(double radius);
  itkGetConstMacro(MinorRadius, double);
  /** Both radii at once. */
  void
  SetRadii(double majorRadius, double minorRadius);

  OutputType
  Evaluate(const InputType & point) const override;
  InputType
  ClosestSurfacePoint(const InputType & point) const override;
  OutputType
  EvaluateWithClosestPoint(const InputType & point, InputType & closest) const override;
  void
  GetBounds(InputType & lower, InputType & upper) const override;

protected:
  TorusImplicitSurface();
  ~TorusImplicitSurface() override = default;
  void
  PrintSelf(std::ostream & os, Indent indent) const override;
  std::string
  CheckParameterConsistency() const override;

private:
  InputType  m_Center;
  VectorType m_Axis;
  double     m_MajorRadius{ 2.0 };
  double     m_MinorRadius{ 1.0 };
};

/** \class BoxImplicitSurface
 * \brief A rectangular box with half-sizes HalfSizes along the columns of Rotation,
 * centred at Center (the thin-plate phantom).
 *
 * Exact distance: outside, the distance to the clamped point; inside, the distance
 * to the nearest face.
 * Defaults: Center (0,0,0), HalfSizes (1,1,1), Rotation identity.
 * \ingroup MeshExtraction
 */
class MeshExtraction_EXPORT BoxImplicitSurface : public ImplicitSurfaceFunction
{
public:
  ITK_DISALLOW_COPY_AND_MOVE(BoxImplicitSurface);
  using Self = BoxImplicitSurface;
  using Superclass = ImplicitSurfaceFunction;
  using Pointer = SmartPointer<Self>;
  using ConstPointer = SmartPointer<const Self>;
  itkOverrideGetNameOfClassMacro(BoxImplicitSurface);
  itkNewMacro(Self);

  void
  SetCenter(const InputType & center);
  itkGetConstReferenceMacro(Center, InputType);
  /** Half the edge lengths, each > 0. */
  void
  SetHalfSizes(const VectorType & halfSizes);
  itkGetConstReferenceMacro(HalfSizes, VectorType);
  /** Orthogonal matrix whose column i is the direction of box axis i. */
  void
  SetRotation(const MatrixType & rotation);
  itkGetConstReferenceMacro(Rotation, MatrixType);

  OutputType
  Evaluate(const InputType & point) const override;
  InputType
  ClosestSurfacePoint(const InputType & point) const override;
  OutputType
  EvaluateWithClosestPoint(const InputType & point, InputType & closest) const override;
  void
  GetBounds(InputType & lower, InputType & upper) const override;

protected:
  BoxImplicitSurface();
  ~BoxImplicitSurface() override = default;
  void
  PrintSelf(std::ostream & os, Indent indent) const override;

private:
  InputType  m_Center;
  VectorType m_HalfSizes;
  MatrixType m_Rotation;
};

/** \class SphereUnionImplicitSurface
 * \brief The boundary of the union of N balls (e.g. two overlapping spheres).
 *
 * Exact for points inside and outside the union. The closest boundary point is
 * one of: the radial projection onto a sphere that is not inside another ball; the
 * point of a pairwise intersection circle closest to p that is not inside a third
 * ball; a triple intersection point not inside a fourth ball. Cost is O(N^4) per
 * evaluation, meant for a handful of spheres. At least one sphere is required.
 * Default: no spheres.
 * \ingroup MeshExtraction
 */
class MeshExtraction_EXPORT SphereUnionImplicitSurface : public ImplicitSurfaceFunction
{
public:
  ITK_DISALLOW_COPY_AND_MOVE(SphereUnionImplicitSurface);
  using Self = SphereUnionImplicitSurface;
  using Superclass = ImplicitSurfaceFunction;
  using Pointer = SmartPointer<Self>;
  using ConstPointer = SmartPointer<const Self>;
  itkOverrideGetNameOfClassMacro(SphereUnionImplicitSurface);
  itkNewMacro(Self);

  /** Adds the ball of radius `radius` (> 0) around `center`. */
  void
  AddSphere(const InputType & center, double radius);
  void
  RemoveAllSpheres();
  unsigned int
  GetNumberOfSpheres() const
  {
    return static_cast<unsigned int>(m_Centers.size());
  }
  /** Throws for i >= GetNumberOfSpheres(). */
  const InputType &
  GetSphereCenter(unsigned int i) const;
  double
  GetSphereRadius(unsigned int i) const;

  OutputType
  Evaluate(const InputType & point) const override;
  InputType
  ClosestSurfacePoint(const InputType & point) const override;
  OutputType
  EvaluateWithClosestPoint(const InputType & point, InputType & closest) const override;
  void
  GetBounds(InputType & lower, InputType & upper) const override;

protected:
  SphereUnionImplicitSurface();
  ~SphereUnionImplicitSurface() override = default;
  void
  PrintSelf(std::ostream & os, Indent indent) const override;
  std::string
  CheckParameterConsistency() const override;

private:
  std::vector<InputType> m_Centers;
  std::vector<double>    m_Radii;
};

/** \class SphereDifferenceImplicitSurface
 * \brief Ball A minus ball B: the "indented sphere" when B cuts into A's surface.
 *
 * The solid is A without the interior of B; its boundary is the part of sphere A
 * outside B, the part of sphere B inside A, and their intersection circle. The
 * distance is exact (closest point among the radial projections onto both spheres
 * that lie on the boundary and the closest point of the circle). B may also lie
 * wholly inside A (a hollow ball) or miss A; B must not contain A.
 * Defaults: A = (0,0,0), radius 1; B = (1,0,0), radius 0.5.
 * \ingroup MeshExtraction
 */
class MeshExtraction_EXPORT SphereDifferenceImplicitSurface : public ImplicitSurfaceFunction
{
public:
  ITK_DISALLOW_COPY_AND_MOVE(SphereDifferenceImplicitSurface);
  using Self = SphereDifferenceImplicitSurface;
  using Superclass = ImplicitSurfaceFunction;
  using Pointer = SmartPointer<Self>;
  using ConstPointer = SmartPointer<const Self>;
  itkOverrideGetNameOfClassMacro(SphereDifferenceImplicitSurface);
  itkNewMacro(Self);

  void
  SetCenterA(const InputType & center);
  itkGetConstReferenceMacro(CenterA, InputType);
  void
  SetRadiusA(double radius);
  itkGetConstMacro(RadiusA, double);
  void
  SetCenterB(const InputType & center);
  itkGetConstReferenceMacro(CenterB, InputType);
  void
  SetRadiusB(double radius);
  itkGetConstMacro(RadiusB, double);

  OutputType
  Evaluate(const InputType & point) const override;
  InputType
  ClosestSurfacePoint(const InputType & point) const override;
  OutputType
  EvaluateWithClosestPoint(const InputType & point, InputType & closest) const override;
  void
  GetBounds(InputType & lower, InputType & upper) const override;

protected:
  SphereDifferenceImplicitSurface();
  ~SphereDifferenceImplicitSurface() override = default;
  void
  PrintSelf(std::ostream & os, Indent indent) const override;
  std::string
  CheckParameterConsistency() const override;

private:
  InputType m_CenterA;
  double    m_RadiusA{ 1.0 };
  InputType m_CenterB;
  double    m_RadiusB{ 0.5 };
};

/** \class NarrowCleftImplicitSurface
 * \brief A U-shaped block: a box with a slot cut from its top face.
 *
 * In the block's frame (origin Center, axes the columns of Rotation) the block is
 * |x| <= HalfSizes[0], |y| <= HalfSizes[1], |z| <= HalfSizes[2], and the slot
 * removes |x| < SlotWidth/2, z > HalfSizes[2] - SlotDepth through the whole y
 * extent. The boundary is tiled exactly by 14 axis-aligned rectangles (bottom, two
 * top strips, two outer x faces, two slot walls, the slot floor, and the U-shaped
 * front and back faces as three rectangles each); the distance is the minimum over
 * them and the sign comes from the inside test.
 * Requires SlotWidth < 2 HalfSizes[0] and SlotDepth < 2 HalfSizes[2].
 * Defaults: Center (0,0,0), HalfSizes (10,10,10), SlotWidth 1.5, SlotDepth 10,
 * Rotation identity.
 * \ingroup MeshExtraction
 */
class MeshExtraction_EXPORT NarrowCleftImplicitSurface : public ImplicitSurfaceFunction
{
public:
  ITK_DISALLOW_COPY_AND_MOVE(NarrowCleftImplicitSurface);
  using Self = NarrowCleftImplicitSurface;
  using Superclass = ImplicitSurfaceFunction;
  using Pointer = SmartPointer<Self>;
  using ConstPointer = SmartPointer<const Self>;
  itkOverrideGetNameOfClassMacro(NarrowCleftImplicitSurface);
  itkNewMacro(Self);

  void
  SetCenter(const InputType & center);
  itkGetConstReferenceMacro(Center, InputType);
  /** Half the block's edge lengths, each > 0. */
  void
  SetHalfSizes(const VectorType & halfSizes);
  itkGetConstReferenceMacro(HalfSizes, VectorType);
  /** Width of the slot along the block's x axis, > 0. */
  void
  SetSlotWidth(double width);
  itkGetConstMacro(SlotWidth, double);
  /** Depth of the slot below the top face (along -z), > 0. */
  void
  SetSlotDepth(double depth);
  itkGetConstMacro(SlotDepth, double);
  /** Orthogonal matrix whose column i is the direction of the block's axis i. */
  void
  SetRotation(const MatrixType & rotation);
  itkGetConstReferenceMacro(Rotation, MatrixType);

  OutputType
  Evaluate(const InputType & point) const override;
  InputType
  ClosestSurfacePoint(const InputType & point) const override;
  OutputType
  EvaluateWithClosestPoint(const InputType & point, InputType & closest) const override;
  void
  GetBounds(InputType & lower, InputType & upper) const override;

protected:
  NarrowCleftImplicitSurface();
  ~NarrowCleftImplicitSurface() override = default;
  void
  PrintSelf(std::ostream & os, Indent indent) const override;
  std::string
  CheckParameterConsistency() const override;

private:
  /** A closed rectangle corner + s * edge0 + t * edge1, s, t in [0,1], in the
   * block's frame; edge0 and edge1 are orthogonal. */
  struct Rectangle
  {
    VectorType corner;
    VectorType edge0;
    VectorType edge1;
  };
  void
  UpdateRectangles();

  InputType              m_Center;
  VectorType             m_HalfSizes;
  double                 m_SlotWidth{ 1.5 };
  double                 m_SlotDepth{ 10.0 };
  MatrixType             m_Rotation;
  std::vector<Rectangle> m_Rectangles;
};

} // namespace itk

#endif
