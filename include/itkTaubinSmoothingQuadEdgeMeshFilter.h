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
#ifndef itkTaubinSmoothingQuadEdgeMeshFilter_h
#define itkTaubinSmoothingQuadEdgeMeshFilter_h

#include "itkMeshExtractionEnums.h"
#include "itkMeshExtractionMacros.h"
#include "itkMeshExtractionQuadEdgeMeshVertexSmoother.h"
#include "itkQuadEdgeMeshParamMatrixCoefficients.h"
#include "itkQuadEdgeMeshToQuadEdgeMeshFilter.h"

namespace itk
{
/** \class TaubinSmoothingQuadEdgeMeshFilter
 * \brief Taubin's lambda|mu smoothing of a triangle mesh: a low-pass filter that does
 * not shrink, with the no-inversion guard (thesis section 2.2.4, eq. 2.11-2.14).
 *
 * Each iteration is two Laplacian steps with the same weights: x <- x + lambda dx,
 * then x <- x + mu dx, dx = S(x) - x, with 0 < lambda and mu < -lambda, so that the
 * transfer function f(k) = (1 - lambda k)(1 - mu k) passes the low frequencies
 * (including the curvature of a sphere, which plain Laplacian smoothing removes by
 * shrinking) and damps the high ones.
 *
 * - Lambda in (0, 1] (default 0.5) and Mu < -Lambda (default -0.53); or
 *   PassBandFrequency k_PB > 0 (default 0: unused), from which
 *   mu = 1 / (k_PB - 1/lambda), i.e. 1/lambda + 1/mu = k_PB (Taubin's pass-band
 *   frequency, typically 0.01-0.1; it must lie in (0, 1/lambda), which is exactly
 *   the range giving mu < -lambda). GetEffectiveMu() gives the mu in use.
 * - NumberOfIterations >= 0 (default 10): lambda|mu pairs.
 * - Weights, UpdateMode, PreventInversions, PreventSelfIntersections,
 *   MaximumNumberOfShortenings, DegenerateQAreaTolerance, FixBoundary and
 *   CoefficientsMethod as in LaplacianSmoothingQuadEdgeMeshFilter (defaults Uniform,
 *   Batch, on, on, 5, 1e-4, on, none; the self-intersection check after each pair). The guard checks both steps of
 * every pair, each move against the orientations before the move and at the start of the pair, so that no iteration
 *   turns a triangle by 90 degrees or more; GetNumberOfShortenedMoves() and
 *   GetNumberOfRejectedMoves() count over both steps.
 *
 * The output has the input's connectivity. Bad parameters, a missing input or a
 * non-triangle face raise an ExceptionObject.
 *
 * \sa LaplacianSmoothingQuadEdgeMeshFilter
 * \ingroup MeshExtraction
 */
template <typename TInputMesh, typename TOutputMesh = TInputMesh>
class ITK_TEMPLATE_EXPORT TaubinSmoothingQuadEdgeMeshFilter
    : public QuadEdgeMeshToQuadEdgeMeshFilter<TInputMesh, TOutputMesh>
{
public:
  ITK_DISALLOW_COPY_AND_MOVE(TaubinSmoothingQuadEdgeMeshFilter);

  using Self = TaubinSmoothingQuadEdgeMeshFilter;
  using Superclass = QuadEdgeMeshToQuadEdgeMeshFilter<TInputMesh, TOutputMesh>;
  using Pointer = SmartPointer<Self>;
  using ConstPointer = SmartPointer<const Self>;

  itkOverrideGetNameOfClassMacro(TaubinSmoothingQuadEdgeMeshFilter);
  itkNewMacro(Self);

  using InputMeshType = TInputMesh;
  using OutputMeshType = TOutputMesh;
  using CoefficientsComputation = MatrixCoefficients<OutputMeshType>;

  using SmoothingWeightsEnum = MeshExtractionEnums::SmoothingWeights;
  using SmoothingUpdateEnum = MeshExtractionEnums::SmoothingUpdate;

  static_assert(OutputMeshType::PointDimension == 3, "TaubinSmoothingQuadEdgeMeshFilter smooths 3-D surface meshes");

  /** The shrinking step factor, in (0, 1] (default 0.5). */
  itkSetMacro(Lambda, double);
  itkGetConstMacro(Lambda, double);

  /** The inflating step factor, < -Lambda (default -0.53); ignored when
   * PassBandFrequency > 0. */
  itkSetMacro(Mu, double);
  itkGetConstMacro(Mu, double);

  /** k_PB: when > 0, mu = 1 / (k_PB - 1/lambda) (default 0: use Mu). */
  itkSetMacro(PassBandFrequency, double);
  itkGetConstMacro(PassBandFrequency, double);

  /** The mu the filter uses: Mu, or the one derived from PassBandFrequency. */
  double
  GetEffectiveMu() const
  {
    if (m_PassBandFrequency > 0.0)
    {
      return 1.0 / (m_PassBandFrequency - 1.0 / m_Lambda);
    }
    return m_Mu;
  }

  /** Number of lambda|mu pairs, >= 0 (default 10). */
  itkSetMacro(NumberOfIterations, int);
  itkGetConstMacro(NumberOfIterations, int);

  itkSetEnumMacro(Weights, SmoothingWeightsEnum);
  itkGetEnumMacro(Weights, SmoothingWeightsEnum);
  itkSetEnumMacro(UpdateMode, SmoothingUpdateEnum);
  itkGetEnumMacro(UpdateMode, SmoothingUpdateEnum);

  itkSetMacro(PreventInversions, bool);
  itkGetConstMacro(PreventInversions, bool);
  itkBooleanMacro(PreventInversions);
  itkSetMacro(PreventSelfIntersections, bool);
  itkGetConstMacro(PreventSelfIntersections, bool);
  itkBooleanMacro(PreventSelfIntersections);
  itkSetMacro(MaximumNumberOfShortenings, unsigned int);
  itkGetConstMacro(MaximumNumberOfShortenings, unsigned int);
  itkSetMacro(DegenerateQAreaTolerance, double);
  itkGetConstMacro(DegenerateQAreaTolerance, double);
  itkSetMacro(FixBoundary, bool);
  itkGetConstMacro(FixBoundary, bool);
  itkBooleanMacro(FixBoundary);

  /** Optional ITK edge weights replacing Weights (not owned). */
  void
  SetCoefficientsMethod(const CoefficientsComputation * method)
  {
    if (m_CoefficientsMethod != method)
    {
      m_CoefficientsMethod = method;
      this->Modified();
    }
  }
  const CoefficientsComputation *
  GetCoefficientsMethod() const
  {
    return m_CoefficientsMethod;
  }

  /** Counters of the last update, over both steps of every pair. */
  itkGetConstMacro(NumberOfMoves, SizeValueType);
  itkGetConstMacro(NumberOfShortenedMoves, SizeValueType);
  itkGetConstMacro(NumberOfRejectedMoves, SizeValueType);
  /** Vertices moved back by PreventSelfIntersections (over all iterations). */
  itkGetConstMacro(NumberOfUndoneMoves, SizeValueType);
  itkGetConstMacro(NumberOfMovableVertices, SizeValueType);

protected:
  /** The per-vertex smoother the filter runs (internal: itk::MeshExtraction::detail). */
  using SmootherType = MeshExtraction::detail::QuadEdgeMeshVertexSmoother<OutputMeshType>;

  TaubinSmoothingQuadEdgeMeshFilter() = default;
  ~TaubinSmoothingQuadEdgeMeshFilter() override = default;
  void
  PrintSelf(std::ostream & os, Indent indent) const override;

  /** Checks, copies the input, then NumberOfIterations times a lambda step and a mu
   * step of the shared vertex smoother. */
  void
  GenerateData() override;

  void
  VerifyParameters() const;

private:
  double                          m_Lambda{ 0.5 };
  double                          m_Mu{ -0.53 };
  double                          m_PassBandFrequency{ 0.0 };
  int                             m_NumberOfIterations{ 10 };
  SmoothingWeightsEnum            m_Weights{ SmoothingWeightsEnum::Uniform };
  SmoothingUpdateEnum             m_UpdateMode{ SmoothingUpdateEnum::Batch };
  bool                            m_PreventInversions{ true };
  bool                            m_PreventSelfIntersections{ true };
  unsigned int                    m_MaximumNumberOfShortenings{ 5 };
  double                          m_DegenerateQAreaTolerance{ 1e-4 };
  bool                            m_FixBoundary{ true };
  const CoefficientsComputation * m_CoefficientsMethod{ nullptr };

  SizeValueType m_NumberOfMoves{ 0 };
  SizeValueType m_NumberOfShortenedMoves{ 0 };
  SizeValueType m_NumberOfRejectedMoves{ 0 };
  SizeValueType m_NumberOfUndoneMoves{ 0 };
  SizeValueType m_NumberOfMovableVertices{ 0 };
};
} // namespace itk

#ifndef ITK_MANUAL_INSTANTIATION
#  include "itkTaubinSmoothingQuadEdgeMeshFilter.hxx"
#endif

#endif
