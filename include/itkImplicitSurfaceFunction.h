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
 * The shapes, one class per header (itk<Class>.h): PlaneImplicitSurface,
 * SphereImplicitSurface, EllipsoidImplicitSurface, TorusImplicitSurface,
 * BoxImplicitSurface, SphereUnionImplicitSurface, SphereDifferenceImplicitSurface
 * and NarrowCleftImplicitSurface. Their closed-form geometry (frames, spheres,
 * circles, ellipsoid distance) is in itkMeshExtractionClosedFormGeometry.h.
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

} // namespace itk

// This header also declares every shape: code that includes only it (written when
// the shapes were declared here, and the module's tests, examples and filters that
// name a shape) keeps compiling. Each shape header includes this one first, so any
// include order works.
#include "itkPlaneImplicitSurface.h"
#include "itkSphereImplicitSurface.h"
#include "itkEllipsoidImplicitSurface.h"
#include "itkTorusImplicitSurface.h"
#include "itkBoxImplicitSurface.h"
#include "itkSphereUnionImplicitSurface.h"
#include "itkSphereDifferenceImplicitSurface.h"
#include "itkNarrowCleftImplicitSurface.h"

#endif
