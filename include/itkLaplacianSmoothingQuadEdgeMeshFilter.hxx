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
#ifndef itkLaplacianSmoothingQuadEdgeMeshFilter_hxx
#define itkLaplacianSmoothingQuadEdgeMeshFilter_hxx

#include "itkLaplacianSmoothingQuadEdgeMeshFilter.h"
#include "itkMeshExtractionParallel.h"

#include <cmath>

namespace itk
{
template <typename TInputMesh, typename TOutputMesh>
void
LaplacianSmoothingQuadEdgeMeshFilter<TInputMesh, TOutputMesh>::VerifyParameters() const
{
  if (m_NumberOfIterations < 0)
  {
    itkExceptionMacro(<< "NumberOfIterations must be >= 0, got " << m_NumberOfIterations);
  }
  if (!(m_RelaxationFactor > 0.0 && m_RelaxationFactor <= 1.0))
  {
    itkExceptionMacro(<< "RelaxationFactor must be in (0, 1], got " << m_RelaxationFactor);
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
  if (m_MovementConstraint != MovementConstraintEnum::None &&
      m_MovementConstraint != MovementConstraintEnum::Centroid && m_MovementConstraint != MovementConstraintEnum::Safe)
  {
    itkExceptionMacro(<< "Unknown MovementConstraint " << static_cast<int>(m_MovementConstraint));
  }
}

template <typename TInputMesh, typename TOutputMesh>
void
LaplacianSmoothingQuadEdgeMeshFilter<TInputMesh, TOutputMesh>::GenerateData()
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
  OutputMeshType * output = this->GetOutput();

  SmootherType smoother;
  smoother.Initialize(output, m_FixBoundary);
  m_NumberOfMovableVertices = smoother.GetNumberOfMovableVertices();

  typename SmootherType::StepParameters step;
  step.weights = m_Weights;
  step.update = m_UpdateMode;
  step.move.factor = m_RelaxationFactor;
  step.move.constraint = m_MovementConstraint;
  step.move.volumePreservation = m_VolumePreservation;
  step.preventInversions = m_PreventInversions;
  step.maximumShortenings = m_MaximumNumberOfShortenings;
  step.degenerateQAreaTolerance = m_DegenerateQAreaTolerance;
  step.coefficients = m_CoefficientsMethod;
  step.numberOfWorkUnits = this->GetNumberOfWorkUnits();

  typename SmootherType::Counters counters;
  this->UpdateProgress(0.0f);
  for (int iteration = 0; iteration < m_NumberOfIterations; ++iteration)
  {
    smoother.Step(step, counters);
    if (m_PreventInversions && m_PreventSelfIntersections)
    {
      m_NumberOfUndoneMoves += smoother.UndoFoldingMoves(m_DegenerateQAreaTolerance);
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
LaplacianSmoothingQuadEdgeMeshFilter<TInputMesh, TOutputMesh>::PrintSelf(std::ostream & os, Indent indent) const
{
  Superclass::PrintSelf(os, indent);
  os << indent << "Weights: " << m_Weights << std::endl;
  os << indent << "UpdateMode: " << m_UpdateMode << std::endl;
  os << indent << "MovementConstraint: " << m_MovementConstraint << std::endl;
  os << indent << "RelaxationFactor: " << m_RelaxationFactor << std::endl;
  os << indent << "NumberOfIterations: " << m_NumberOfIterations << std::endl;
  os << indent << "VolumePreservation: " << (m_VolumePreservation ? "On" : "Off") << std::endl;
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
