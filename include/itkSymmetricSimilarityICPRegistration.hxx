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
#ifndef itkSymmetricSimilarityICPRegistration_hxx
#define itkSymmetricSimilarityICPRegistration_hxx

#include "itkSymmetricSimilarityICPRegistration.h"
#include "itkMeshExtractionSymmetricICP.h"

namespace itk
{
template <typename TMesh>
void
SymmetricSimilarityICPRegistration<TMesh>::Update()
{
  using namespace MeshExtraction::detail;
  const auto              fixed = CheckedTriangleMesh(m_FixedMesh.GetPointer(), "fixed");
  const auto              moving = CheckedTriangleMesh(m_MovingMesh.GetPointer(), "moving");
  const ClosestPointQuery onFixed(fixed, m_Correspondence);
  const ClosestPointQuery onMoving(moving, m_Correspondence);
  SymmetricICPSettings    settings;
  settings.correspondence = m_Correspondence;
  settings.maximumIterations = m_MaximumNumberOfIterations;
  settings.relativeTolerance = m_RelativeTolerance;
  settings.initial = m_InitialTransform.GetPointer();
  const SymmetricICPResult result = RunSymmetricICP(onFixed, onMoving, settings);
  m_Transform = result.fixedToMoving;
  m_HalfTransform = result.half;
  m_InitialMeanSquaredDistance = result.initialE2;
  m_MeanSquaredDistance = result.e2;
  m_MeanDistance = result.meanDistance;
  m_NumberOfIterations = result.iterations;
}

template <typename TMesh>
void
SymmetricSimilarityICPRegistration<TMesh>::PrintSelf(std::ostream & os, Indent indent) const
{
  Superclass::PrintSelf(os, indent);
  os << indent << "Correspondence: " << m_Correspondence << '\n';
  os << indent << "MaximumNumberOfIterations: " << m_MaximumNumberOfIterations << '\n';
  os << indent << "RelativeTolerance: " << m_RelativeTolerance << '\n';
  os << indent << "MeanSquaredDistance: " << m_MeanSquaredDistance << '\n';
  os << indent << "NumberOfIterations: " << m_NumberOfIterations << '\n';
}
} // namespace itk

#endif
