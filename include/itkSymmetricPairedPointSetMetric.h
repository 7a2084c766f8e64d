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
#ifndef itkSymmetricPairedPointSetMetric_h
#define itkSymmetricPairedPointSetMetric_h

#include "itkMeshExtractionMacros.h"
#include "itkPointSet.h"
#include "itkPointSetToPointSetMetric.h"

#include <vector>

namespace itk
{
/** \class SymmetricPairedPointSetMetric
 * \brief The stacked residuals of P.W. de Bruin's symmetric distance measure
 * (thesis eq. 7.3) for paired points: w_k (Q(f_k) - Q^-1(m_k)).
 *
 * The k-th point of the fixed point set is paired with the k-th point of the moving
 * point set. Q (the metric's transform, invertible) moves the fixed points forward and
 * the moving points backward into an intermediate frame, so that neither shape is
 * preferred; the minimiser Q is half the fixed-to-moving transform (Q o Q). For the
 * thesis' E^2 the pairs are a_i with its closest point on B (weights 1/sqrt(n_A)) and the
 * closest point on A of b_j with b_j (weights 1/sqrt(n_B)); then the sum of the squared
 * values is E^2.
 *
 * GetValue returns 3 values per pair (x, y, z); GetDerivative the exact Jacobian,
 * d/dp Q(f) + (dQ/dx)^-1 d/dp Q(x) at x = Q^-1(m), for a transform whose Jacobian with
 * respect to its position is constant (similarity, affine). Made for
 * itk::PointSetToPointSetRegistrationMethod with itk::LevenbergMarquardtOptimizer.
 *
 * \ingroup MeshExtraction
 */
template <typename TPointSet = PointSet<double, 3>>
class ITK_TEMPLATE_EXPORT SymmetricPairedPointSetMetric : public PointSetToPointSetMetric<TPointSet, TPointSet>
{
public:
  ITK_DISALLOW_COPY_AND_MOVE(SymmetricPairedPointSetMetric);

  using Self = SymmetricPairedPointSetMetric;
  using Superclass = PointSetToPointSetMetric<TPointSet, TPointSet>;
  using Pointer = SmartPointer<Self>;
  using ConstPointer = SmartPointer<const Self>;

  itkNewMacro(Self);
  itkOverrideGetNameOfClassMacro(SymmetricPairedPointSetMetric);

  using typename Superclass::DerivativeType;
  using typename Superclass::MeasureType;
  using typename Superclass::ParametersType;
  using typename Superclass::TransformType;
  using PointSetType = TPointSet;
  static constexpr unsigned int Dimension = TPointSet::PointDimension;

  /** Per-pair weights (default: all 1). Empty, or one per pair. */
  void
  SetWeights(const std::vector<double> & weights)
  {
    m_Weights = weights;
    this->Modified();
  }
  const std::vector<double> &
  GetWeights() const
  {
    return m_Weights;
  }

  unsigned int
  GetNumberOfValues() const override;

  MeasureType
  GetValue(const ParametersType & parameters) const override;

  void
  GetDerivative(const ParametersType & parameters, DerivativeType & derivative) const override;

  /** Both at once (the derivative needs the values' inverse transform). */
  void
  GetValueAndDerivative(const ParametersType & parameters, MeasureType & value, DerivativeType & derivative) const;

  /** Throws unless both point sets have the same number of points and the weights
   * match them. */
  void
  Initialize() override;

protected:
  SymmetricPairedPointSetMetric() = default;
  ~SymmetricPairedPointSetMetric() override = default;

private:
  double
  Weight(std::size_t k) const
  {
    return m_Weights.empty() ? 1.0 : m_Weights[k];
  }

  std::vector<double> m_Weights;
};
} // namespace itk

#ifndef ITK_MANUAL_INSTANTIATION
#  include "itkSymmetricPairedPointSetMetric.hxx"
#endif

#endif
