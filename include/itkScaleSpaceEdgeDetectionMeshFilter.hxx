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
#ifndef itkScaleSpaceEdgeDetectionMeshFilter_hxx
#define itkScaleSpaceEdgeDetectionMeshFilter_hxx

#include "itkScaleSpaceEdgeDetectionMeshFilter.h"
#include "itkMeshExtractionParallel.h"

namespace itk
{
template <typename TInputMesh, typename TImage, typename TOutputMesh>
ScaleSpaceEdgeDetectionMeshFilter<TInputMesh, TImage, TOutputMesh>::ScaleSpaceEdgeDetectionMeshFilter()
{
  // The image is a named input; GenerateData() reports a missing one.
  this->AddOptionalInputName("InputImage");
}

template <typename TInputMesh, typename TImage, typename TOutputMesh>
MeshExtraction::detail::ScaleSpaceEdgeDetectionParameters
ScaleSpaceEdgeDetectionMeshFilter<TInputMesh, TImage, TOutputMesh>::MakeParameters() const
{
  MeshExtraction::detail::ScaleSpaceEdgeDetectionParameters p;
  p.maximumDeviation = m_MaximumDeviation;
  p.minimumScale = m_MinimumScale;
  p.scalesPerOctave = m_NumberOfScalesPerOctave;
  p.searchDirection = m_SearchDirection;
  p.subSampleRefinement = m_SubSampleRefinement;
  p.preventInversions = m_PreventInversions;
  p.maximumShortenings = m_MaximumNumberOfShortenings;
  p.degenerateQAreaTolerance = m_DegenerateQAreaTolerance;
  p.computeInaccuracy = m_ComputeInaccuracy;
  p.numberOfWorkUnits = this->GetNumberOfWorkUnits();
  return p;
}

template <typename TInputMesh, typename TImage, typename TOutputMesh>
void
ScaleSpaceEdgeDetectionMeshFilter<TInputMesh, TImage, TOutputMesh>::GenerateData()
{
  // Every stage, including the free functions below, runs on this filter's work units.
  const MeshExtraction::detail::ScopedNumberOfWorkUnits workUnits(this->GetNumberOfWorkUnits());
  m_Result = MeshExtraction::ScaleSpaceEdgeDetectionResult();
  const InputMeshType * input = this->GetInput();
  if (input == nullptr)
  {
    itkExceptionMacro(<< "No input mesh: call SetInput() before Update()");
  }
  const MeshExtraction::detail::ScaleSpaceEdgeDetectionParameters parameters = this->MakeParameters();
  std::string                                                     problem = DetectorType::CheckParameters(parameters);
  if (problem.empty())
  {
    problem = MeshExtraction::detail::ScaleSpaceEdgeDetector<InputMeshType, ImageType>::CheckInputs(
      input, this->GetInputImage());
  }
  if (!problem.empty())
  {
    itkExceptionMacro(<< problem);
  }

  this->CopyInputMeshToOutputMesh();
  this->UpdateProgress(0.0f);
  m_Result = m_Detector.Run(*this->GetOutput(), *this->GetInputImage(), parameters);
  this->UpdateProgress(1.0f);
}

template <typename TInputMesh, typename TImage, typename TOutputMesh>
void
ScaleSpaceEdgeDetectionMeshFilter<TInputMesh, TImage, TOutputMesh>::PrintSelf(std::ostream & os, Indent indent) const
{
  Superclass::PrintSelf(os, indent);
  os << indent << "MaximumDeviation: " << m_MaximumDeviation << std::endl;
  os << indent << "MinimumScale: " << m_MinimumScale << std::endl;
  os << indent << "NumberOfScalesPerOctave: " << m_NumberOfScalesPerOctave << std::endl;
  os << indent << "SearchDirection: " << m_SearchDirection << std::endl;
  os << indent << "SubSampleRefinement: " << (m_SubSampleRefinement ? "On" : "Off") << std::endl;
  os << indent << "PreventInversions: " << (m_PreventInversions ? "On" : "Off") << std::endl;
  os << indent << "MaximumNumberOfShortenings: " << m_MaximumNumberOfShortenings << std::endl;
  os << indent << "DegenerateQAreaTolerance: " << m_DegenerateQAreaTolerance << std::endl;
  os << indent << "ComputeInaccuracy: " << (m_ComputeInaccuracy ? "On" : "Off") << std::endl;
  os << indent << "Scales:";
  for (const double s : m_Result.scales)
  {
    os << ' ' << s;
  }
  os << std::endl;
  os << indent << "NumberOfMovedVertices: " << m_Result.movedVertices << std::endl;
  os << indent << "NumberOfShortenedMoves: " << m_Result.shortenedMoves << std::endl;
  os << indent << "NumberOfRejectedMoves: " << m_Result.rejectedMoves << std::endl;
  os << indent << "NumberOfUndoneMoves: " << m_Result.undoneMoves << std::endl;
  os << indent << "NumberOfNormalFallbacks: " << m_Result.normalFallbacks << std::endl;
  os << indent << "MeanDisplacement: " << m_Result.meanDisplacement << std::endl;
  os << indent << "MaximumDisplacement: " << m_Result.maximumDisplacement << std::endl;
  os << indent << "Inaccuracy: " << m_Result.inaccuracy << std::endl;
}
} // namespace itk

#endif
