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
#ifndef itkTaubinSmoothingQuadEdgeMeshFilter_hxx
#define itkTaubinSmoothingQuadEdgeMeshFilter_hxx

#include "itkTaubinSmoothingQuadEdgeMeshFilter.h"
#include "itkMeshExtractionParallel.h"

#include <cmath>

namespace itk
{
template <typename TInputMesh, typename TOutputMesh>
void
TaubinSmoothingQuadEdgeMeshFilter<TInputMesh, TOutputMesh>::VerifyParameters() const
{
  if (m_NumberOfIterations < 0)
  {
    itkExceptionMacro(<< "NumberOfIterations must be >= 0, got " << m_NumberOfIterations);
  }
  if (!(m_Lambda > 0.0 && m_Lambda <= 1.0))
  {
    itkExceptionMacro(<< "Lambda must be in (0, 1], got " << m_Lambda);
  }
  if (m_PassBandFrequency > 0.0)
  {
    // mu = 1 / (k_PB - 1/lambda) is negative iff k_PB < 1/lambda, and then
    // mu < -lambda iff k_PB > 0.
    if (!(m_PassBandFrequency < 1.0 / m_Lambda) || !std::isfinite(m_PassBandFrequency))
    {
      itkExceptionMacro(<< "PassBandFrequency must be in (0, 1/Lambda) = (0, " << 1.0 / m_Lambda << "), got "
                        << m_PassBandFrequency);
    }
  }
  else if (m_PassBandFrequency < 0.0 || std::isnan(m_PassBandFrequency))
  {
    itkExceptionMacro(<< "PassBandFrequency must be > 0 (or 0 to use Mu), got " << m_PassBandFrequency);
  }
  const double mu = this->GetEffectiveMu();
  if (!(mu < -m_Lambda) || !std::isfinite(mu))
  {
    itkExceptionMacro(<< "Taubin smoothing needs mu < -lambda < 0 (thesis eq. 2.14), got lambda = " << m_Lambda
                      << " and mu = " << mu);
  }
  if (!(m_DegenerateQAreaTolerance >= 0.0 && m_DegenerateQAreaTolerance < 1.0))
  {
    itkExceptionMacro(<< "DegenerateQAreaTolerance must be in [0, 1), got " << m_DegenerateQAreaTolerance);
  }
  switch (m_Weights)
  {
    case SmoothingWeightsEnum::Uniform:
    case SmoothingWeightsEnum::InverseEdgeLength:
    case SmoothingWeightsEnum::Area:
    case SmoothingWeightsEnum::Cotangent:
    case SmoothingWeightsEnum::AngleBisector:
      break;
    default:
      itkExceptionMacro(<< "Unknown Weights " << static_cast<int>(m_Weights));
  }
  if (m_UpdateMode != SmoothingUpdateEnum::Batch && m_UpdateMode != SmoothingUpdateEnum::Immediate)
  {
    itkExceptionMacro(<< "Unknown UpdateMode " << static_cast<int>(m_UpdateMode));
  }
}

template <typename TInputMesh, typename TOutputMesh>
void
TaubinSmoothingQuadEdgeMeshFilter<TInputMesh, TOutputMesh>::GenerateData()
{
  // Every stage, including the free functions below, runs on this filter's work units.
  const MeshExtraction::detail::ScopedNumberOfWorkUnits workUnits(this->GetNumberOfWorkUnits());
  m_NumberOfMoves = 0;
  m_NumberOfShortenedMoves = 0;
  m_NumberOfRejectedMoves = 0;
  m_NumberOfUndoneMoves = 0;
  m_NumberOfMovableVertices = 0;

  const InputMeshType * input = this->GetInput();
  if (input == nullptr)
  {
    itkExceptionMacro(<< "No input mesh: call SetInput() before Update()");
  }
  this->VerifyParameters();
  const std::string nonTriangle =
    MeshExtraction::detail::QuadEdgeMeshVertexSmoother<InputMeshType>::DescribeNonTriangleFace(*input);
  if (!nonTriangle.empty())
  {
    itkExceptionMacro(<< nonTriangle);
  }

  this->CopyInputMeshToOutputMesh();
  SmootherType smoother;
  smoother.Initialize(this->GetOutput(), m_FixBoundary);
  m_NumberOfMovableVertices = smoother.GetNumberOfMovableVertices();

  typename SmootherType::StepParameters step;
  step.weights = m_Weights;
  step.update = m_UpdateMode;
  step.preventInversions = m_PreventInversions;
  step.maximumShortenings = m_MaximumNumberOfShortenings;
  step.degenerateQAreaTolerance = m_DegenerateQAreaTolerance;
  step.coefficients = m_CoefficientsMethod;
  step.numberOfWorkUnits = this->GetNumberOfWorkUnits();
  const double mu = this->GetEffectiveMu();

  typename SmootherType::Counters counters;
  this->UpdateProgress(0.0f);
  for (int iteration = 0; iteration < m_NumberOfIterations; ++iteration)
  {
    step.move.factor = m_Lambda;
    smoother.Step(step, counters);
    step.move.factor = mu;
    smoother.Step(step, counters, false); // guarded against the orientations before the lambda step
    if (m_PreventInversions && m_PreventSelfIntersections)
    {
      m_NumberOfUndoneMoves += smoother.UndoFoldingMoves(m_DegenerateQAreaTolerance); // against the pair's start
    }
    this->UpdateProgress(static_cast<float>(iteration + 1) / static_cast<float>(m_NumberOfIterations));
  }
  this->UpdateProgress(1.0f);
  m_NumberOfMoves = counters.moves;
  m_NumberOfShortenedMoves = counters.shortened;
  m_NumberOfRejectedMoves = counters.rejected;
}

template <typename TInputMesh, typename TOutputMesh>
void
TaubinSmoothingQuadEdgeMeshFilter<TInputMesh, TOutputMesh>::PrintSelf(std::ostream & os, Indent indent) const
{
  Superclass::PrintSelf(os, indent);
  os << indent << "Lambda: " << m_Lambda << std::endl;
  os << indent << "Mu: " << m_Mu << std::endl;
  os << indent << "PassBandFrequency: " << m_PassBandFrequency << std::endl;
  os << indent << "EffectiveMu: " << this->GetEffectiveMu() << std::endl;
  os << indent << "NumberOfIterations: " << m_NumberOfIterations << std::endl;
  os << indent << "Weights: " << m_Weights << std::endl;
  os << indent << "UpdateMode: " << m_UpdateMode << std::endl;
  os << indent << "PreventInversions: " << (m_PreventInversions ? "On" : "Off") << std::endl;
  os << indent << "PreventSelfIntersections: " << (m_PreventSelfIntersections ? "On" : "Off") << std::endl;
  os << indent << "MaximumNumberOfShortenings: " << m_MaximumNumberOfShortenings << std::endl;
  os << indent << "DegenerateQAreaTolerance: " << m_DegenerateQAreaTolerance << std::endl;
  os << indent << "FixBoundary: " << (m_FixBoundary ? "On" : "Off") << std::endl;
  os << indent << "CoefficientsMethod: " << (m_CoefficientsMethod ? "set" : "(none)") << std::endl;
  os << indent << "NumberOfMoves: " << m_NumberOfMoves << std::endl;
  os << indent << "NumberOfShortenedMoves: " << m_NumberOfShortenedMoves << std::endl;
  os << indent << "NumberOfRejectedMoves: " << m_NumberOfRejectedMoves << std::endl;
  os << indent << "NumberOfUndoneMoves: " << m_NumberOfUndoneMoves << std::endl;
  os << indent << "NumberOfMovableVertices: " << m_NumberOfMovableVertices << std::endl;
}
} // namespace itk

#endif
