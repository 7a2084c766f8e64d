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
#ifndef itkSymmetricPairedPointSetMetric_hxx
#define itkSymmetricPairedPointSetMetric_hxx

#include "itkSymmetricPairedPointSetMetric.h"
#include "vnl/algo/vnl_matrix_inverse.h"

namespace itk
{
template <typename TPointSet>
void
SymmetricPairedPointSetMetric<TPointSet>::Initialize()
{
  Superclass::Initialize();
  const auto n = this->m_FixedPointSet->GetNumberOfPoints();
  if (this->m_MovingPointSet->GetNumberOfPoints() != n)
  {
    itkExceptionMacro("The fixed and moving point sets are paired point by point: they need as many points, got "
                      << n << " and " << this->m_MovingPointSet->GetNumberOfPoints() << '.');
  }
  if (!m_Weights.empty() && m_Weights.size() != n)
  {
    itkExceptionMacro("Weights: one per pair, " << n << ", got " << m_Weights.size() << '.');
  }
}

template <typename TPointSet>
unsigned int
SymmetricPairedPointSetMetric<TPointSet>::GetNumberOfValues() const
{
  return this->m_FixedPointSet.IsNull()
           ? 0u
           : static_cast<unsigned int>(Dimension * this->m_FixedPointSet->GetNumberOfPoints());
}

template <typename TPointSet>
auto
SymmetricPairedPointSetMetric<TPointSet>::GetValue(const ParametersType & parameters) const -> MeasureType
{
  this->SetTransformParameters(parameters);
  const auto inverse = this->m_Transform->GetInverseTransform();
  if (inverse.IsNull())
  {
    itkExceptionMacro("The transform is not invertible at parameters " << parameters << '.');
  }
  MeasureType value(this->GetNumberOfValues());
  auto        fixed = this->m_FixedPointSet->GetPoints()->Begin();
  auto        moving = this->m_MovingPointSet->GetPoints()->Begin();
  for (std::size_t k = 0; fixed != this->m_FixedPointSet->GetPoints()->End(); ++fixed, ++moving, ++k)
  {
    const auto   forward = this->m_Transform->TransformPoint(fixed.Value());
    const auto   backward = inverse->TransformPoint(moving.Value());
    const double w = this->Weight(k);
    for (unsigned int d = 0; d < Dimension; ++d)
    {
      value[Dimension * k + d] = w * (forward[d] - backward[d]);
    }
  }
  return value;
}

template <typename TPointSet>
void
SymmetricPairedPointSetMetric<TPointSet>::GetDerivative(const ParametersType & parameters,
                                                        DerivativeType &       derivative) const
{
  MeasureType value;
  this->GetValueAndDerivative(parameters, value, derivative);
}

template <typename TPointSet>
void
SymmetricPairedPointSetMetric<TPointSet>::GetValueAndDerivative(const ParametersType & parameters,
                                                                MeasureType &          value,
                                                                DerivativeType &       derivative) const
{
  value = this->GetValue(parameters); // sets the parameters
  const auto         inverse = this->m_Transform->GetInverseTransform();
  const unsigned int p = this->m_Transform->GetNumberOfParameters();
  derivative.SetSize(p, this->GetNumberOfValues());
  // (dQ/dx)^-1, constant for the transforms this metric is made for.
  typename TransformType::InputPointType origin;
  origin.Fill(0.0);
  typename TransformType::JacobianPositionType spatial;
  this->m_Transform->ComputeJacobianWithRespectToPosition(origin, spatial);
  const vnl_matrix<double>             spatialInverse = vnl_matrix_inverse<double>(spatial.as_matrix()).as_matrix();
  typename TransformType::JacobianType forward;
  typename TransformType::JacobianType atInverse;
  auto                                 fixed = this->m_FixedPointSet->GetPoints()->Begin();
  auto                                 moving = this->m_MovingPointSet->GetPoints()->Begin();
  for (std::size_t k = 0; fixed != this->m_FixedPointSet->GetPoints()->End(); ++fixed, ++moving, ++k)
  {
    this->m_Transform->ComputeJacobianWithRespectToParameters(fixed.Value(), forward);
    this->m_Transform->ComputeJacobianWithRespectToParameters(inverse->TransformPoint(moving.Value()), atInverse);
    // d/dp Q^-1(m) = -(dQ/dx)^-1 d/dp Q(x) at x = Q^-1(m); the residual subtracts it.
    const vnl_matrix<double> backward = spatialInverse * atInverse;
    const double             w = this->Weight(k);
    for (unsigned int d = 0; d < Dimension; ++d)
    {
      for (unsigned int j = 0; j < p; ++j)
      {
        derivative[j][Dimension * k + d] = w * (forward[d][j] + backward[d][j]);
      }
    }
  }
}
} // namespace itk

#endif
