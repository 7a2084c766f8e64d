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
#ifndef itkScaleSpaceEdgeMeshRefinementFilter_hxx
#define itkScaleSpaceEdgeMeshRefinementFilter_hxx

#include "itkScaleSpaceEdgeMeshRefinementFilter.h"
#include "itkMeshExtractionParallel.h"
#include "itkMeshExtractionDistanceAnalysis.h"
#include "itkMeshExtractionClosedSurfaceEdgeSwap.h"
#include "itkMeshExtractionQualityAnalysis.h"
#include "itkQuadEdgeMeshEulerOperatorFlipEdgeFunction.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <utility>

namespace itk
{
template <typename TInputMesh, typename TImage, typename TOutputMesh>
ScaleSpaceEdgeMeshRefinementFilter<TInputMesh, TImage, TOutputMesh>::ScaleSpaceEdgeMeshRefinementFilter()
{
  // The image is a named input; GenerateData() reports a missing one.
  this->AddOptionalInputName("InputImage");
}

template <typename TInputMesh, typename TImage, typename TOutputMesh>
MeshExtraction::detail::ScaleSpaceEdgeDetectionParameters
ScaleSpaceEdgeMeshRefinementFilter<TInputMesh, TImage, TOutputMesh>::MakeDetectorParameters() const
{
  MeshExtraction::detail::ScaleSpaceEdgeDetectionParameters p;
  p.maximumDeviation = m_MaximumDeviation;
  p.minimumScale = m_MinimumScale;
  p.scalesPerOctave = m_NumberOfScalesPerOctave;
  p.searchDirection = m_SearchDirection;
  p.subSampleRefinement = m_SubSampleRefinement;
  p.computeInaccuracy = m_ComputeInaccuracy;
  p.numberOfWorkUnits = this->GetNumberOfWorkUnits();
  return p;
}

template <typename TInputMesh, typename TImage, typename TOutputMesh>
std::vector<MeshExtraction::Vec3>
ScaleSpaceEdgeMeshRefinementFilter<TInputMesh, TImage, TOutputMesh>::Positions() const
{
  std::vector<MeshExtraction::Vec3> positions;
  const auto *                      points = m_Working->GetPoints();
  positions.reserve(points->Size());
  for (auto it = points->Begin(); it != points->End(); ++it)
  {
    positions.push_back(MeshExtraction::ToVec3(it.Value()));
  }
  return positions;
}

template <typename TInputMesh, typename TImage, typename TOutputMesh>
auto
ScaleSpaceEdgeMeshRefinementFilter<TInputMesh, TImage, TOutputMesh>::Record(
  OperationEnum                             operation,
  unsigned int                              cycle,
  double                                    seconds,
  const std::vector<MeshExtraction::Vec3> * before) -> StepType &
{
  using MeshExtraction::Dot;
  using MeshExtraction::TriangleNormal;
  using MeshExtraction::TriangleQArea;
  StepType step;
  step.operation = operation;
  step.cycle = cycle;
  step.seconds = seconds;

  // What TriangleMeshQualityCalculator measures, on the arrays the filter keeps (the
  // working mesh's points in container order and its triangles): converting the
  // QuadEdgeMesh again for every step took longer than the measurement.
  const std::vector<MeshExtraction::Vec3> positions = this->Positions();
  MeshExtraction::IndexedTriangleMesh     current;
  current.points = positions;
  current.triangles = m_Triangles;
  current.pointIds = m_PointIds;
  MeshExtraction::detail::TriangleMeshQualityOptions options;
  options.computeSelfIntersections = false;
  options.computeOutwardOrientation = false;
  const MeshExtraction::TriangleMeshQualityReport report = MeshExtraction::detail::AnalyzeTriangleMesh(current, options);
  step.numberOfPoints = report.numberOfPoints;
  step.numberOfTriangles = report.numberOfTriangles;
  step.meanMinimumAngle = report.minimumAngle.mean;
  step.meanQArea = report.qArea.mean;
  step.minimumQArea = report.qArea.minimum;
  step.degenerateTriangles = report.degenerateTriangles;
  step.nonManifold = report.nonManifoldEdges + report.nonManifoldVertices;

  if (before != nullptr && before->size() == positions.size())
  {
    std::int64_t turned = 0;
    for (const auto & t : m_Triangles)
    {
      // Turned by more than 90 degrees (the guards allow anything below 90; a
      // relative tolerance keeps rounding at exactly 90 degrees from counting).
      const auto & b = *before;
      const auto   n0 = TriangleNormal(b[t[0]], b[t[1]], b[t[2]]);
      const auto   n1 = TriangleNormal(positions[t[0]], positions[t[1]], positions[t[2]]);
      if (TriangleQArea(b[t[0]], b[t[1]], b[t[2]]) > 0.0 &&
          Dot(n0, n1) < -1e-6 * MeshExtraction::Norm(n0) * MeshExtraction::Norm(n1))
      {
        ++turned;
      }
    }
    step.invertedTriangles = turned;
  }
  if (m_ReferenceSurface)
  {
    const std::vector<double> d =
      MeshExtraction::detail::SignedDistancesToSurface(positions, *m_ReferenceSurface, this->GetNumberOfWorkUnits());
    double sum = 0.0;
    for (const double x : d)
    {
      sum += x;
    }
    const double mean = d.empty() ? 0.0 : sum / static_cast<double>(d.size());
    double       squares = 0.0;
    for (const double x : d)
    {
      squares += (x - mean) * (x - mean);
    }
    step.referenceDistanceMean = mean;
    step.referenceDistanceVariance = d.empty() ? 0.0 : squares / static_cast<double>(d.size());
  }
  m_Steps.push_back(step);
  return m_Steps.back();
}

template <typename TInputMesh, typename TImage, typename TOutputMesh>
void
ScaleSpaceEdgeMeshRefinementFilter<TInputMesh, TImage, TOutputMesh>::SetArrays(
  const MeshExtraction::IndexedTriangleMesh & mesh)
{
  m_Triangles = mesh.triangles;
  m_PointIds = mesh.pointIds;
  m_Topology = MeshExtraction::BuildMeshTopology(mesh);
}

template <typename TInputMesh, typename TImage, typename TOutputMesh>
void
ScaleSpaceEdgeMeshRefinementFilter<TInputMesh, TImage, TOutputMesh>::EdgeDetection(unsigned int cycle)
{
  const std::vector<MeshExtraction::Vec3>             before = this->Positions();
  const MeshExtraction::ScaleSpaceEdgeDetectionResult result =
    m_Detector.Run(*m_Working, *this->GetInputImage(), this->MakeDetectorParameters());
  StepType & step = this->Record(OperationEnum::EdgeDetection, cycle, result.seconds, &before);
  step.inaccuracy = result.inaccuracy;
  step.changes = static_cast<std::int64_t>(result.movedVertices);
  step.rejectedMoves = static_cast<std::int64_t>(result.rejectedMoves + result.undoneMoves);
  step.maximumTravel = result.maximumDisplacement;
  step.meanTravel = result.meanDisplacement;
  m_AfterEdgeDetection = this->Positions();
}

template <typename TInputMesh, typename TImage, typename TOutputMesh>
void
ScaleSpaceEdgeMeshRefinementFilter<TInputMesh, TImage, TOutputMesh>::EdgeSwap(unsigned int cycle)
{
  if (m_Topology.numberOfBoundaryEdges == 0 && m_Topology.numberOfNonManifoldEdges == 0 &&
      m_Topology.numberOfInconsistentEdges == 0 && m_Topology.numberOfNonManifoldVertices == 0)
  {
    this->ClosedSurfaceEdgeSwap(cycle);
    return;
  }
  this->QuadEdgeEdgeSwap(cycle);
}

template <typename TInputMesh, typename TImage, typename TOutputMesh>
void
ScaleSpaceEdgeMeshRefinementFilter<TInputMesh, TImage, TOutputMesh>::ClosedSurfaceEdgeSwap(unsigned int cycle)
{
  // The swap engine of the high-quality SurfaceNets (MeshExtraction::detail::SwapEdges, the
  // decision of EdgeSwapQuadEdgeMeshFilter with its default parameters) on an indexed
  // copy: sweeps until none swaps (at most 20, the filter's default), each followed by
  // undoing the swaps whose triangles cut through the surface or fold against a
  // neighbour (MeshExtraction::detail::UndoIntersectingSwaps; those edges are not tried again).
  const auto                                  start = std::chrono::steady_clock::now();
  const MeshExtraction::IndexedTriangleMesh   indexed = MeshExtraction::MakeIndexedTriangleMesh(*m_Working);
  MeshExtraction::detail::SurfaceNetTriangles surface;
  surface.triangles = indexed.triangles;
  surface.BuildConnectivity(indexed.points.size());
  const MeshExtraction::detail::EdgeSwapParameters parameters;
  std::vector<std::uint64_t>                       refused;
  std::int64_t                                     kept = 0;
  std::int64_t                                     undone = 0;
  for (unsigned int sweep = 0; sweep < 20; ++sweep)
  {
    std::vector<MeshExtraction::detail::EdgeSwapRecord> swaps =
      MeshExtraction::detail::SwapEdges(indexed.points, surface, parameters, &refused);
    if (swaps.empty())
    {
      break;
    }
    undone += static_cast<std::int64_t>(
      MeshExtraction::detail::UndoIntersectingSwaps(indexed.points, surface, swaps, &refused));
    kept += static_cast<std::int64_t>(swaps.size());
  }

  auto         rebuilt = OutputMeshType::New();
  const auto * points = m_Working->GetPoints();
  for (auto it = points->Begin(); it != points->End(); ++it)
  {
    typename OutputMeshType::PointType p; // coordinates only: a quad-edge point also holds its old edge
    for (unsigned int d = 0; d < 3; ++d)
    {
      p[d] = it.Value()[d];
    }
    rebuilt->SetPoint(it.Index(), p);
  }
  for (std::size_t f = 0; f < surface.triangles.size(); ++f)
  {
    const auto & t = surface.triangles[f];
    if (rebuilt->AddFaceTriangle(indexed.pointIds[t[0]], indexed.pointIds[t[1]], indexed.pointIds[t[2]]) == nullptr)
    {
      itkExceptionMacro(<< "Internal error: the QuadEdgeMesh refused triangle " << f << " after the edge swaps");
    }
  }
  m_Working = rebuilt;
  // The rebuilt mesh's points are the same, in the same order, and its faces are the
  // swapped triangles in this order: its arrays need no conversion back.
  MeshExtraction::IndexedTriangleMesh swapped;
  swapped.points = indexed.points;
  swapped.pointIds = indexed.pointIds;
  swapped.triangles = std::move(surface.triangles);
  this->SetArrays(swapped);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  StepType &   step = this->Record(OperationEnum::EdgeSwap, cycle, seconds, nullptr);
  step.changes = kept;
  step.rejectedMoves = undone;
}

template <typename TInputMesh, typename TImage, typename TOutputMesh>
void
ScaleSpaceEdgeMeshRefinementFilter<TInputMesh, TImage, TOutputMesh>::QuadEdgeEdgeSwap(unsigned int cycle)
{
  const auto start = std::chrono::steady_clock::now();
  // EdgeSwapQuadEdgeMeshFilter checks each swap locally, and (PreventSelfIntersections)
  // keeps new triangles from cutting through a neighbouring part of a rough surface:
  // their corners are locked and the swaps made again, up to 8 times, after which the
  // mesh before the step is kept.
  auto swap = EdgeSwapFilterType::New();
  swap->SetInput(m_Working);
  swap->SetNumberOfWorkUnits(this->GetNumberOfWorkUnits());
  swap->Update();
  typename OutputMeshType::Pointer swapped = swap->GetOutput();
  swapped->DisconnectPipeline();
  m_Working = swapped;
  const SizeValueType swaps = swap->GetNumberOfSwaps();
  const SizeValueType cutting = swap->GetNumberOfCrossingTriangles();
  this->SetArrays(MeshExtraction::MakeIndexedTriangleMesh(*m_Working));
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  StepType &   step = this->Record(OperationEnum::EdgeSwap, cycle, seconds, nullptr);
  step.changes = static_cast<std::int64_t>(swaps);
  step.rejectedMoves = static_cast<std::int64_t>(cutting);
}

template <typename TInputMesh, typename TImage, typename TOutputMesh>
double
ScaleSpaceEdgeMeshRefinementFilter<TInputMesh, TImage, TOutputMesh>::Smoothing(unsigned int   cycle,
                                                                               SmootherType & smoother)
{
  const std::vector<MeshExtraction::Vec3> before = this->Positions();
  const auto                              start = std::chrono::steady_clock::now();
  typename SmootherType::StepParameters   parameters;
  parameters.weights = MeshExtractionEnums::SmoothingWeights::Uniform;
  parameters.update = MeshExtractionEnums::SmoothingUpdate::Batch;
  parameters.move.constraint = MeshExtractionEnums::MovementConstraint::Centroid;
  parameters.numberOfWorkUnits = this->GetNumberOfWorkUnits();
  typename SmootherType::Counters counters;
  smoother.Step(parameters, counters);

  // The smoothing guard checks one vertex at a time: undo the moves that fold the
  // surface or make it cut through itself (see MeshExtraction::detail::UndoFoldingMoves).
  const std::size_t undone = smoother.UndoFoldingMoves(parameters.degenerateQAreaTolerance);
  const double      seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  const std::vector<MeshExtraction::Vec3> after = this->Positions();
  double                                  travel = 0.0;
  double                                  sum = 0.0;
  for (std::size_t i = 0; i < after.size() && i < m_AfterEdgeDetection.size(); ++i)
  {
    const double d = MeshExtraction::Norm(after[i] - m_AfterEdgeDetection[i]);
    travel = std::max(travel, d);
    sum += d;
  }
  StepType & step = this->Record(OperationEnum::Smoothing, cycle, seconds, &before);
  step.changes = static_cast<std::int64_t>(counters.moves - counters.rejected) - static_cast<std::int64_t>(undone);
  step.rejectedMoves = static_cast<std::int64_t>(counters.rejected + undone);
  step.maximumTravel = travel;
  step.meanTravel = after.empty() ? 0.0 : sum / static_cast<double>(after.size());
  return travel;
}

template <typename TInputMesh, typename TImage, typename TOutputMesh>
void
ScaleSpaceEdgeMeshRefinementFilter<TInputMesh, TImage, TOutputMesh>::GenerateData()
{
  // Every stage, including the free functions below, runs on this filter's work units.
  const MeshExtraction::detail::ScopedNumberOfWorkUnits workUnits(this->GetNumberOfWorkUnits());
  m_Steps.clear();
  m_NumberOfCycles = 0;
  m_TargetQualityReached = false;

  const InputMeshType * input = this->GetInput();
  if (input == nullptr)
  {
    itkExceptionMacro(<< "No input mesh: call SetInput() before Update()");
  }
  std::string problem = DetectorType::CheckParameters(this->MakeDetectorParameters());
  if (problem.empty() && !(m_TargetQuality > 0.0 && m_TargetQuality <= 1.0))
  {
    problem = "TargetQuality (the mean q_area to reach) must be in (0, 1], got " + std::to_string(m_TargetQuality);
  }
  if (problem.empty() && m_MaximumNumberOfSmoothingSteps == 0)
  {
    problem = "MaximumNumberOfSmoothingSteps must be >= 1, got 0";
  }
  if (problem.empty() && (!(m_MinimumQualityImprovement >= 0.0) || !std::isfinite(m_MinimumQualityImprovement)))
  {
    problem =
      "MinimumQualityImprovement must be a finite number >= 0, got " + std::to_string(m_MinimumQualityImprovement);
  }
  if (problem.empty())
  {
    problem = MeshExtraction::detail::ScaleSpaceEdgeDetector<InputMeshType, ImageType>::CheckInputs(
      input, this->GetInputImage());
  }
  if (!problem.empty())
  {
    itkExceptionMacro(<< problem);
  }

  m_Working = OutputMeshType::New();
  CopyMeshToMesh(input, m_Working.GetPointer());
  this->SetArrays(MeshExtraction::MakeIndexedTriangleMesh(*m_Working));
  this->UpdateProgress(0.0f);

  // Thesis section 4.2.4: ED, ES, then cycles of S..., ED, ES until the target.
  this->Record(OperationEnum::Initial, 0, 0.0, nullptr);
  this->EdgeDetection(0);
  this->EdgeSwap(0);
  double previous = m_Steps.back().meanQArea;
  while (m_Steps.back().meanQArea < m_TargetQuality && m_NumberOfCycles < m_MaximumNumberOfCycles)
  {
    const unsigned int cycle = ++m_NumberOfCycles;
    SmootherType       smoother;
    smoother.Initialize(m_Working, true);
    for (unsigned int s = 0; s < m_MaximumNumberOfSmoothingSteps; ++s)
    {
      const double travel = this->Smoothing(cycle, smoother);
      if (m_Steps.back().meanQArea >= m_TargetQuality || travel > m_MaximumDeviation)
      {
        break;
      }
    }
    this->EdgeDetection(cycle);
    this->EdgeSwap(cycle);
    this->UpdateProgress(static_cast<float>(cycle) / static_cast<float>(m_MaximumNumberOfCycles));
    const double quality = m_Steps.back().meanQArea;
    if (quality < m_TargetQuality && quality - previous < m_MinimumQualityImprovement)
    {
      break; // converged below the target
    }
    previous = quality;
  }
  m_TargetQualityReached = m_Steps.back().meanQArea >= m_TargetQuality;

  CopyMeshToMesh(m_Working.GetPointer(), this->GetOutput());
  m_Working = nullptr;
  m_AfterEdgeDetection.clear();
  m_Triangles.clear();
  m_PointIds.clear();
  m_Topology = MeshExtraction::MeshTopology();
  m_Detector.ReleaseScaleSpace();
  this->UpdateProgress(1.0f);
}

template <typename TInputMesh, typename TImage, typename TOutputMesh>
void
ScaleSpaceEdgeMeshRefinementFilter<TInputMesh, TImage, TOutputMesh>::PrintSelf(std::ostream & os, Indent indent) const
{
  Superclass::PrintSelf(os, indent);
  os << indent << "MaximumDeviation: " << m_MaximumDeviation << std::endl;
  os << indent << "TargetQuality: " << m_TargetQuality << std::endl;
  os << indent << "MaximumNumberOfCycles: " << m_MaximumNumberOfCycles << std::endl;
  os << indent << "MaximumNumberOfSmoothingSteps: " << m_MaximumNumberOfSmoothingSteps << std::endl;
  os << indent << "MinimumQualityImprovement: " << m_MinimumQualityImprovement << std::endl;
  os << indent << "MinimumScale: " << m_MinimumScale << std::endl;
  os << indent << "NumberOfScalesPerOctave: " << m_NumberOfScalesPerOctave << std::endl;
  os << indent << "SearchDirection: " << m_SearchDirection << std::endl;
  os << indent << "SubSampleRefinement: " << (m_SubSampleRefinement ? "On" : "Off") << std::endl;
  os << indent << "ComputeInaccuracy: " << (m_ComputeInaccuracy ? "On" : "Off") << std::endl;
  os << indent << "ReferenceSurface: " << (m_ReferenceSurface ? "set" : "(none)") << std::endl;
  os << indent << "NumberOfCycles: " << m_NumberOfCycles << std::endl;
  os << indent << "TargetQualityReached: " << (m_TargetQualityReached ? "true" : "false") << std::endl;
  os << indent << "Steps: " << m_Steps.size() << std::endl;
}
} // namespace itk

#endif
