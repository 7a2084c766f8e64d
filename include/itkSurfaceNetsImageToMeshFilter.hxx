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
#ifndef itkSurfaceNetsImageToMeshFilter_hxx
#define itkSurfaceNetsImageToMeshFilter_hxx

#include "itkSurfaceNetsImageToMeshFilter.h"
#include "itkMeshExtractionCellBlock.h"
#include "itkMeshExtractionParallel.h"
#include "itkMeshExtractionIndexedTriangleMesh.h"
#include "itkMeshExtractionQualityAnalysis.h"
#include "itkMeshExtractionSurfaceNetsClassification.h"
#include "itkMeshExtractionLabelSurface.h"
#include "itkMeshExtractionSurfaceNetsHighQuality.h"
#include "itkMeshExtractionSliverRemoval.h"
#include "itkMeshExtractionSurfaceNetsRelaxation.h"
#include "itkMeshExtractionTriangleAABBTree.h"
#include "itkMinimumMaximumImageCalculator.h"
#include "itkNearestNeighborInterpolateImageFunction.h"
#include "itkResampleImageFilter.h"
#include "itkQuadrilateralCell.h"
#include "itkTriangleCell.h"

#include <algorithm>
#include <cmath>

namespace itk
{
template <typename TInputImage, typename TOutputMesh, typename TLabelImage>
SurfaceNetsImageToMeshFilter<TInputImage, TOutputMesh, TLabelImage>::SurfaceNetsImageToMeshFilter()
{
  this->AddOptionalInputName("LabelImage");
}

template <typename TInputImage, typename TOutputMesh, typename TLabelImage>
void
SurfaceNetsImageToMeshFilter<TInputImage, TOutputMesh, TLabelImage>::VerifyParameters() const
{
  if (!std::isfinite(m_IsoValue))
  {
    itkExceptionMacro("IsoValue must be finite, got " << m_IsoValue << '.');
  }
  if (!(m_ConvergenceThreshold >= 0.0))
  {
    itkExceptionMacro("ConvergenceThreshold must be >= 0 voxels, got " << m_ConvergenceThreshold << '.');
  }
  if (!(m_SmoothingWeight >= 0.0 && m_SmoothingWeight <= 1.0))
  {
    itkExceptionMacro("SmoothingWeight must be in [0, 1], got " << m_SmoothingWeight << '.');
  }
  if (!(m_ProjectionWeight >= 0.0 && m_ProjectionWeight <= 1.0))
  {
    itkExceptionMacro("ProjectionWeight must be in [0, 1], got " << m_ProjectionWeight << '.');
  }
  if (m_GradientMethod == GradientEnum::GaussianDerivative && !(m_GradientSigma > 0.0))
  {
    itkExceptionMacro("GradientSigma must be > 0 mm for Gaussian-derivative gradients, got " << m_GradientSigma << '.');
  }
  if (m_HighQuality && m_Triangulation == TriangulationEnum::Quadrilaterals)
  {
    itkExceptionMacro("HighQuality swaps edges of triangles: it cannot keep Quadrilaterals.");
  }
  if (!(m_HighQualityCellDilation >= 0.0 && m_HighQualityCellDilation <= 0.5))
  {
    itkExceptionMacro("HighQualityCellDilation must be in [0, 0.5] voxels, got " << m_HighQualityCellDilation << '.');
  }
  if (!(m_ConvergedSwapFraction >= 0.0 && m_ConvergedSwapFraction <= 1.0))
  {
    itkExceptionMacro("ConvergedSwapFraction must be in [0, 1], got " << m_ConvergedSwapFraction << '.');
  }
  if (!(m_HighQualityTargetEdgeLength >= 0.0 && std::isfinite(m_HighQualityTargetEdgeLength)))
  {
    itkExceptionMacro("HighQualityTargetEdgeLength must be a finite length >= 0 mm (0: the mean spacing), got "
                      << m_HighQualityTargetEdgeLength << '.');
  }
  if (!(m_MinimumComponentVolume >= 0.0 && std::isfinite(m_MinimumComponentVolume)))
  {
    itkExceptionMacro("MinimumComponentVolume must be a finite volume >= 0 mm^3, got " << m_MinimumComponentVolume
                                                                                       << '.');
  }
  if (!(m_LabelSurfaceSigma >= 0.0 && m_LabelSurfaceSigma <= 16.0))
  {
    itkExceptionMacro("LabelSurfaceSigma must be in [0, 16] voxels, got " << m_LabelSurfaceSigma << '.');
  }
  if (!(m_CellMargin >= 0.0 && m_CellMargin <= 0.25))
  {
    itkExceptionMacro("CellMargin must be in [0, 0.25] voxels, got " << m_CellMargin << '.');
  }
}

template <typename TInputImage, typename TOutputMesh, typename TLabelImage>
void
SurfaceNetsImageToMeshFilter<TInputImage, TOutputMesh, TLabelImage>::VerifyLabelImageGrid(
  const InputImageType * input,
  const LabelImageType * labels) const
{
  if (labels->GetBufferedRegion().GetSize() != input->GetBufferedRegion().GetSize() ||
      !labels->GetSpacing().GetVnlVector().is_equal(input->GetSpacing().GetVnlVector(), 1e-6) ||
      labels->GetOrigin().EuclideanDistanceTo(input->GetOrigin()) > 1e-6 ||
      !labels->GetDirection().GetVnlMatrix().is_equal(input->GetDirection().GetVnlMatrix(), 1e-6))
  {
    itkExceptionMacro("LabelImage must have the input's grid: size "
                      << input->GetBufferedRegion().GetSize() << ", spacing " << input->GetSpacing() << ", origin "
                      << input->GetOrigin() << "; it has size " << labels->GetBufferedRegion().GetSize() << ", spacing "
                      << labels->GetSpacing() << ", origin " << labels->GetOrigin() << '.');
  }
}

template <typename TInputImage, typename TOutputMesh, typename TLabelImage>
void
SurfaceNetsImageToMeshFilter<TInputImage, TOutputMesh, TLabelImage>::ClassifyCells()
{
  const InputImageType *                                            input = this->GetSampledInput();
  const MeshExtraction::detail::SurfaceNetsClassificationStatistics greyscale =
    (this->GetSampledLabelImage() != nullptr || m_ClassifyByLabel) ? this->ClassifyCellsByLabel()
                                                                   : this->ClassifyCellsByIsoValue();
  if (greyscale.foundNaN)
  {
    itkExceptionMacro("The input image has a NaN voxel at index " << BufferIndex(input, greyscale.nanVoxel) << '.');
  }
}

template <typename TInputImage, typename TOutputMesh, typename TLabelImage>
template <typename TImage>
auto
SurfaceNetsImageToMeshFilter<TInputImage, TOutputMesh, TLabelImage>::BufferIndex(const TImage *       image,
                                                                                 const std::int64_t * local) ->
  typename TImage::IndexType
{
  auto i = image->GetBufferedRegion().GetIndex();
  for (unsigned int d = 0; d < 3; ++d)
  {
    i[d] += local[d];
  }
  return i;
}

template <typename TInputImage, typename TOutputMesh, typename TLabelImage>
MeshExtraction::detail::SurfaceNetsClassificationStatistics
SurfaceNetsImageToMeshFilter<TInputImage, TOutputMesh, TLabelImage>::ClassifyCellsByLabel()
{
  using namespace MeshExtraction;
  using namespace MeshExtraction::detail;
  const InputImageType *              input = this->GetSampledInput();
  const LabelImageType *              labels = this->GetSampledLabelImage();
  const unsigned int                  workUnits = this->GetNumberOfWorkUnits();
  const double                        label = m_LabelValue;
  SurfaceNetsClassificationStatistics greyscale;
  SurfaceNetsClassificationStatistics stats;
  if (labels != nullptr)
  {
    this->VerifyLabelImageGrid(input, labels);
    stats = ClassifySurfaceCells(
      labels, SurfaceNetsVoxelRange<typename LabelImageType::PixelType>::FromLabel(label), m_Net, workUnits);
    // The greyscale range and NaN check, for the relaxation.
    SurfaceNet scratch;
    greyscale = ClassifySurfaceCells(input, SurfaceNetsVoxelRange<InputPixelType>::Never(), scratch, workUnits);
  }
  else
  {
    stats = ClassifySurfaceCells(input, SurfaceNetsVoxelRange<InputPixelType>::FromLabel(label), m_Net, workUnits);
    greyscale = stats;
  }
  if (stats.foundNaN)
  {
    itkExceptionMacro("The label image has a NaN voxel at index " << BufferIndex(input, stats.nanVoxel) << '.');
  }
  if (stats.insideVoxels == 0)
  {
    itkExceptionMacro("No voxel has the label " << m_LabelValue << " (the labels range over [" << stats.minimum << ", "
                                                << stats.maximum << "]): there is no surface.");
  }
  return greyscale;
}

template <typename TInputImage, typename TOutputMesh, typename TLabelImage>
MeshExtraction::detail::SurfaceNetsClassificationStatistics
SurfaceNetsImageToMeshFilter<TInputImage, TOutputMesh, TLabelImage>::ClassifyCellsByIsoValue()
{
  using namespace MeshExtraction;
  using namespace MeshExtraction::detail;
  const InputImageType * input = this->GetSampledInput();
  const auto range = SurfaceNetsVoxelRange<InputPixelType>::FromIsoValue(m_IsoValue, m_InsideIsAboveIsoValue);
  SurfaceNetsClassificationStatistics greyscale =
    ClassifySurfaceCells(input, range, m_Net, this->GetNumberOfWorkUnits(), false);
  // The extremes are needed only where there may be no surface (no voxel inside, or
  // every voxel inside: a constant image), and then there is no NaN: read them then.
  if (!greyscale.foundNaN &&
      (greyscale.insideVoxels == 0 || greyscale.insideVoxels == input->GetBufferedRegion().GetNumberOfPixels()))
  {
    auto extremes = MinimumMaximumImageCalculator<InputImageType>::New();
    extremes->SetImage(input);
    extremes->SetRegion(input->GetBufferedRegion());
    extremes->Compute();
    greyscale.minimum = static_cast<double>(extremes->GetMinimum());
    greyscale.maximum = static_cast<double>(extremes->GetMaximum());
  }
  if (!greyscale.foundNaN && greyscale.minimum == greyscale.maximum)
  {
    itkExceptionMacro("The input image is constant (every voxel is " << greyscale.minimum
                                                                     << "): there is no iso-surface.");
  }
  if (!greyscale.foundNaN && greyscale.insideVoxels == 0)
  {
    itkExceptionMacro("No voxel is inside: the image ranges over ["
                      << greyscale.minimum << ", " << greyscale.maximum << "] and the object is the voxels "
                      << (m_InsideIsAboveIsoValue ? ">= " : "<= ") << m_IsoValue
                      << " (IsoValue, InsideIsAboveIsoValue = " << m_InsideIsAboveIsoValue << ").");
  }
  return greyscale;
}

template <typename TInputImage, typename TOutputMesh, typename TLabelImage>
MeshExtraction::detail::SurfaceNetsRelaxationResult
SurfaceNetsImageToMeshFilter<TInputImage, TOutputMesh, TLabelImage>::RelaxNet(
  RelaxationEnum                                 relaxation,
  unsigned int                                   iterations,
  MeshExtraction::detail::SurfaceNetsCellCache * cellCache)
{
  using namespace MeshExtraction;
  using namespace MeshExtraction::detail;
  const InputImageType *          input = this->GetSampledInput();
  SurfaceNetsRelaxationParameters p;
  p.kind = relaxation;
  p.maximumNumberOfIterations = iterations;
  p.convergenceThreshold = m_ConvergenceThreshold;
  p.smoothingWeight = m_SmoothingWeight;
  p.projectionWeight = m_ProjectionWeight;
  p.sequential = m_SequentialRelaxation;
  p.isoValue = m_IsoValue;
  p.centralDifferences = m_GradientMethod == GradientEnum::CentralDifference;
  p.numberOfWorkUnits = this->GetNumberOfWorkUnits();
  for (unsigned int r = 0; r < 3; ++r)
  {
    for (unsigned int c = 0; c < 3; ++c)
    {
      p.indexToPhysical[r][c] = input->GetDirection()[r][c] * input->GetSpacing()[c];
    }
  }
  const float progressStart = this->GetProgress();
  const float progressSpan = m_HighQuality ? 0.05f : 0.45f;
  auto        progress = [this, progressStart, progressSpan](double fraction) {
    this->UpdateProgress(static_cast<float>(progressStart + progressSpan * fraction));
  };

  if (m_LabelSurface)
  {
    // The label's smooth surface: its zero level, outside above, by central differences.
    const SurfaceNetsSampler<LabelSurfaceImageType> target(m_LabelSurface.GetPointer(), 0.0, 1.0);
    p.isoValue = 0.0;
    p.centralDifferences = true;
    return RelaxSurfaceNet(
      m_Net, &target, [&target](const Vec3 & q, std::uint32_t) { return target.Gradient(q); }, p, progress, cellCache);
  }
  const SurfaceNetsSampler<InputImageType> sampler(input, m_IsoValue, m_InsideIsAboveIsoValue ? -1.0 : 1.0);

  if (relaxation != RelaxationEnum::Gradient && relaxation != RelaxationEnum::Combined)
  {
    // No step to the iso-surface: no gradient.
    return RelaxSurfaceNet(
      m_Net, &sampler, [](const Vec3 &, std::uint32_t) { return MakeVec3(0, 0, 0); }, p, progress, cellCache);
  }
  if (m_GradientMethod == GradientEnum::GaussianDerivative)
  {
    const SurfaceNetsGaussianGradient<InputImageType> gaussian(input, m_Net, m_GradientSigma);
    return RelaxSurfaceNet(
      m_Net,
      &sampler,
      [this, &gaussian](const Vec3 & q, std::uint32_t node) { return gaussian.Gradient(q, m_Net.nodeCell[node]); },
      p,
      progress,
      cellCache);
  }
  return RelaxSurfaceNet(
    m_Net, &sampler, [&sampler](const Vec3 & q, std::uint32_t) { return sampler.Gradient(q); }, p, progress, cellCache);
}

template <typename TInputImage, typename TOutputMesh, typename TLabelImage>
void
SurfaceNetsImageToMeshFilter<TInputImage, TOutputMesh, TLabelImage>::RunHighQualityMode(
  std::vector<MeshExtraction::TriangleIndices> & triangles,
  MeshExtraction::detail::SurfaceNetsCellCache * cellCache)
{
  using namespace MeshExtraction;
  using namespace MeshExtraction::detail;
  Matrix<double, 3, 3> M;
  Vec3                 first;
  this->GetGeometry(M, first);
  SurfaceNetsHighQualityParameters parameters;
  parameters.numberOfRounds = m_NumberOfHighQualityRounds;
  parameters.iterations = m_HighQualityIterations;
  parameters.cellDilation = m_HighQualityCellDilation;
  parameters.convergedSwapFraction = m_ConvergedSwapFraction;
  parameters.roundToFloat = std::is_same<typename OutputMeshType::PointType::ValueType, float>::value;
  const RelaxationEnum relaxation =
    (m_ClassifyByLabel && !m_LabelSurface) ? RelaxationEnum::Averaging : RelaxationEnum::Combined;
  SurfaceNetsHighQuality mode(
    m_Net,
    first,
    M,
    parameters,
    [this, relaxation, cellCache](unsigned int iterations) { this->RelaxNet(relaxation, iterations, cellCache); },
    [this](unsigned int roundsDone) {
      this->UpdateProgress(0.35f + 0.45f * static_cast<float>(roundsDone) / m_NumberOfHighQualityRounds);
    });
  const SurfaceNetsHighQualityResult result = mode.Run(triangles);
  m_NumberOfSwaps = result.numberOfSwaps;
  m_NumberOfRoundsPerformed = result.numberOfRounds;
  m_NumberOfNodesMovedBack += result.numberOfNodesMovedBack;
}

template <typename TInputImage, typename TOutputMesh, typename TLabelImage>
auto
SurfaceNetsImageToMeshFilter<TInputImage, TOutputMesh, TLabelImage>::GetSampledInput() const -> const InputImageType *
{
  return m_SampledInput ? m_SampledInput.GetPointer()
                        : static_cast<const InputImageType *>(this->ProcessObject::GetInput(0));
}

template <typename TInputImage, typename TOutputMesh, typename TLabelImage>
auto
SurfaceNetsImageToMeshFilter<TInputImage, TOutputMesh, TLabelImage>::GetSampledLabelImage() const
  -> const LabelImageType *
{
  return m_SampledLabelImage ? m_SampledLabelImage.GetPointer()
                             : static_cast<const LabelImageType *>(this->ProcessObject::GetInput("LabelImage"));
}

template <typename TInputImage, typename TOutputMesh, typename TLabelImage>
double
SurfaceNetsImageToMeshFilter<TInputImage, TOutputMesh, TLabelImage>::IsotropicResamplingSpacing(
  const InputImageType * image)
{
  const auto & spacing = image->GetSpacing();
  const double smallest = std::min({ spacing[0], spacing[1], spacing[2] });
  const double largest = std::max({ spacing[0], spacing[1], spacing[2] });
  return largest - smallest > 1e-6 * largest ? smallest : 0.0;
}

template <typename TInputImage, typename TOutputMesh, typename TLabelImage>
void
SurfaceNetsImageToMeshFilter<TInputImage, TOutputMesh, TLabelImage>::ResampleInputs()
{
  m_SampledInput = nullptr;
  m_SampledLabelImage = nullptr;
  const InputImageType * input = this->GetInput();
  const double           smallest = m_ResampleToIsotropicVoxels ? IsotropicResamplingSpacing(input) : 0.0;
  if (smallest == 0.0)
  {
    return;
  }
  const auto & spacing = input->GetSpacing();
  const auto & region = input->GetBufferedRegion();
  if constexpr (std::is_floating_point<InputPixelType>::value)
  {
    // Interpolation would spread a NaN to its neighbours: name the input's own voxel.
    const InputPixelType * buffer = input->GetBufferPointer();
    for (SizeValueType i = 0; i < region.GetNumberOfPixels(); ++i)
    {
      if (std::isnan(buffer[i]))
      {
        itkExceptionMacro("The input image has a NaN voxel at index " << input->ComputeIndex(i) << '.');
      }
    }
  }
  // The grid: cubic voxels of the smallest spacing from the buffer's first voxel,
  // with the input's direction, as many as fit up to its last voxel.
  typename InputImageType::SpacingType isotropic;
  isotropic.Fill(smallest);
  typename InputImageType::SizeType size;
  for (unsigned int d = 0; d < 3; ++d)
  {
    const double extent = static_cast<double>(region.GetSize()[d] - 1) * spacing[d];
    size[d] = static_cast<SizeValueType>(std::floor(extent / smallest + 1e-9)) + 1;
  }
  typename InputImageType::PointType origin;
  input->TransformIndexToPhysicalPoint(region.GetIndex(), origin);
  auto resample = [&](const auto * image, bool nearest) {
    using ImageType = std::remove_cv_t<std::remove_pointer_t<decltype(image)>>;
    // A copy that shares the buffer, so that the resampling does not reach upstream.
    auto source = ImageType::New();
    source->Graft(image);
    auto filter = ResampleImageFilter<ImageType, ImageType>::New();
    filter->SetInput(source);
    filter->SetOutputSpacing(isotropic);
    filter->SetOutputOrigin(origin);
    filter->SetOutputDirection(input->GetDirection());
    filter->SetSize(size);
    if (nearest)
    {
      filter->SetInterpolator(NearestNeighborInterpolateImageFunction<ImageType, double>::New());
    }
    filter->SetNumberOfWorkUnits(this->GetNumberOfWorkUnits());
    filter->Update();
    return typename ImageType::ConstPointer(filter->GetOutput());
  };
  const LabelImageType * labels = this->GetLabelImage();
  if (labels != nullptr)
  {
    this->VerifyLabelImageGrid(input, labels);
  }
  m_SampledInput = resample(input, m_ClassifyByLabel);
  if (labels != nullptr)
  {
    m_SampledLabelImage = resample(labels, true);
  }
}

template <typename TInputImage, typename TOutputMesh, typename TLabelImage>
void
SurfaceNetsImageToMeshFilter<TInputImage, TOutputMesh, TLabelImage>::GetGeometry(Matrix<double, 3, 3> & M,
                                                                                 MeshExtraction::Vec3 & first) const
{
  const InputImageType * input = this->GetSampledInput();
  for (unsigned int r = 0; r < 3; ++r)
  {
    for (unsigned int c = 0; c < 3; ++c)
    {
      M[r][c] = input->GetDirection()[r][c] * input->GetSpacing()[c];
    }
  }
  // Net positions are relative to the buffer's first voxel.
  ContinuousIndex<double, 3> start;
  for (unsigned int d = 0; d < 3; ++d)
  {
    start[d] = static_cast<double>(input->GetBufferedRegion().GetIndex(d));
  }
  Point<double, 3> point;
  input->TransformContinuousIndexToPhysicalPoint(start, point);
  first = MeshExtraction::ToVec3(point);
}

template <typename TInputImage, typename TOutputMesh, typename TLabelImage>
MeshExtraction::detail::QuadSplit
SurfaceNetsImageToMeshFilter<TInputImage, TOutputMesh, TLabelImage>::GetQuadSplit() const
{
  switch (m_Triangulation)
  {
    case TriangulationEnum::Delaunay:
      return MeshExtraction::detail::QuadSplit::Delaunay;
    case TriangulationEnum::Quadrilaterals:
      return MeshExtraction::detail::QuadSplit::KeepQuads;
    default:
      return MeshExtraction::detail::QuadSplit::ShortestDiagonal;
  }
}

template <typename TInputImage, typename TOutputMesh, typename TLabelImage>
void
SurfaceNetsImageToMeshFilter<TInputImage, TOutputMesh, TLabelImage>::MakeOutputMesh(
  const MeshExtraction::LargeBlockVector<std::array<std::uint32_t, 4>> & polygons,
  unsigned int                                                           polygonSize,
  const MeshExtraction::Vec3 *                                           points,
  const std::vector<std::uint32_t> *                                     keptPoints)
{
  OutputMeshType * output = this->GetOutput();
  output->Initialize();
  this->MakeOutputPoints(points, keptPoints);
  if constexpr (MeshExtraction::detail::IsQuadEdgeMesh<OutputMeshType>::value)
  {
    typename OutputMeshType::PointIdList ids(polygonSize);
    for (std::size_t f = 0; f < polygons.size(); ++f)
    {
      for (unsigned int k = 0; k < polygonSize; ++k)
      {
        ids[k] = polygons[f][k];
      }
      if (output->AddFace(ids) == nullptr)
      {
        itkExceptionMacro("Internal error: the QuadEdgeMesh refused face " << f << " of the SurfaceNet.");
      }
    }
  }
  else
  {
    this->MakeOutputCells(polygons, polygonSize);
  }
}

template <typename TInputImage, typename TOutputMesh, typename TLabelImage>
void
SurfaceNetsImageToMeshFilter<TInputImage, TOutputMesh, TLabelImage>::MakeOutputPoints(
  const MeshExtraction::Vec3 *       points,
  const std::vector<std::uint32_t> * keptPoints)
{
  using namespace MeshExtraction;
  using namespace MeshExtraction::detail;
  Matrix<double, 3, 3> M;
  Vec3                 first;
  this->GetGeometry(M, first);
  const std::size_t numberOfPoints = keptPoints != nullptr ? keptPoints->size() : m_Net.positions.size();
  OutputMeshType *  output = this->GetOutput();
  using PointType = typename OutputMeshType::PointType;
  using CoordinateType = typename PointType::ValueType;
  // Each node's physical point: the face split's, or made as it is stored (no array
  // of them in between).
  auto toPoint = [&](std::size_t n) {
    const std::size_t i = keptPoints != nullptr ? (*keptPoints)[n] : n;
    Vec3              physical;
    if (points != nullptr)
    {
      physical = points[i];
    }
    else
    {
      ToPhysical(&m_Net.positions[i], 1, first, M, false, &physical);
    }
    PointType p;
    for (unsigned int d = 0; d < 3; ++d)
    {
      p[d] = static_cast<CoordinateType>(physical[d]);
    }
    return p;
  };
  using PointsContainer = typename OutputMeshType::PointsContainer;
  if constexpr (std::is_same<PointsContainer,
                             VectorContainer<typename PointsContainer::ElementIdentifier, PointType>>::value)
  {
    // Fill the container's vector directly: InsertElement marks the container
    // modified (a time stamp and an event) for every point.
    auto   container = PointsContainer::New();
    auto & vector = container->CastToSTLContainer();
    vector.reserve(numberOfPoints);
    for (std::size_t i = 0; i < numberOfPoints; ++i)
    {
      vector.push_back(toPoint(i));
    }
    output->SetPoints(container);
  }
  else
  {
    output->GetPoints()->Reserve(numberOfPoints);
    for (std::size_t i = 0; i < numberOfPoints; ++i)
    {
      output->SetPoint(static_cast<typename OutputMeshType::PointIdentifier>(i), toPoint(i));
    }
  }
}

template <typename TInputImage, typename TOutputMesh, typename TLabelImage>
void
SurfaceNetsImageToMeshFilter<TInputImage, TOutputMesh, TLabelImage>::MakeOutputCells(
  const MeshExtraction::LargeBlockVector<std::array<std::uint32_t, 4>> & polygons,
  unsigned int                                                           polygonSize)
{
  OutputMeshType * output = this->GetOutput();
  using CellType = typename OutputMeshType::CellType;
  using CellsContainer = typename OutputMeshType::CellsContainer;
  if constexpr (std::is_same<CellsContainer,
                             VectorContainer<typename CellsContainer::ElementIdentifier, CellType *>>::value)
  {
    // As for the points. The cells are made in one block (BlockAllocatedCell)
    // instead of one heap object each, which was most of the time of an itk::Mesh
    // output; the mesh still owns and deletes each cell (its default,
    // CellsAllocatedDynamicallyCellByCell), and the block goes with the last.
    auto container = CellsContainer::New();
    output->SetCells(container);
    auto & vector = container->CastToSTLContainer();
    vector.assign(polygons.size(), nullptr);
    if (polygonSize == 3)
    {
      this->MakeBlockAllocatedCells(static_cast<TriangleCell<CellType> *>(nullptr), polygons, vector);
    }
    else
    {
      this->MakeBlockAllocatedCells(static_cast<QuadrilateralCell<CellType> *>(nullptr), polygons, vector);
    }
  }
  else
  {
    // Another cells container: one heap cell per face, through SetCell.
    for (std::size_t f = 0; f < polygons.size(); ++f)
    {
      CellType *                         made = polygonSize == 3 ? static_cast<CellType *>(new TriangleCell<CellType>)
                                                                 : static_cast<CellType *>(new QuadrilateralCell<CellType>);
      typename CellType::CellAutoPointer cell;
      cell.TakeOwnership(made);
      for (unsigned int k = 0; k < polygonSize; ++k)
      {
        cell->SetPointId(k, polygons[f][k]);
      }
      output->SetCell(static_cast<typename OutputMeshType::CellIdentifier>(f), cell);
    }
  }
}

template <typename TInputImage, typename TOutputMesh, typename TLabelImage>
template <typename TCell, typename TCellVector>
void
SurfaceNetsImageToMeshFilter<TInputImage, TOutputMesh, TLabelImage>::MakeBlockAllocatedCells(
  TCell *,
  const MeshExtraction::LargeBlockVector<std::array<std::uint32_t, 4>> & polygons,
  TCellVector &                                                          vector)
{
  try
  {
    MeshExtraction::detail::BlockAllocatedCell<TCell>::MakeCells(polygons.size(), vector.begin());
  }
  catch (const std::bad_alloc &)
  {
    itkExceptionMacro("Out of memory while making the " << polygons.size() << " cells of the output mesh.");
  }
  // Then the ids, through the cell type's own SetPointId (no virtual call per id). In
  // a second pass rather than as each cell is made: that changes the order of the
  // heap's allocations, which made later runs of a process much slower.
  constexpr unsigned int polygonSize = TCell::NumberOfPoints;
  MeshExtraction::detail::ParallelForBlocks(
    polygons.size(), 16384, [&](std::size_t begin, std::size_t end, std::size_t) {
      for (std::size_t f = begin; f < end; ++f)
      {
        auto * cell = static_cast<TCell *>(vector[f]);
        for (unsigned int k = 0; k < polygonSize; ++k)
        {
          cell->TCell::SetPointId(static_cast<int>(k), polygons[f][k]);
        }
      }
    });
}

template <typename TInputImage, typename TOutputMesh, typename TLabelImage>
void
SurfaceNetsImageToMeshFilter<TInputImage, TOutputMesh, TLabelImage>::GenerateData()
{
  // Every stage, including the free functions they call, runs on this filter's work units.
  const MeshExtraction::detail::ScopedNumberOfWorkUnits workUnits(this->GetNumberOfWorkUnits());
  const RelaxationEnum                                  requestedRelaxation = this->PrepareInputs();
  MeshExtraction::detail::SurfaceNetsCellCache          cellCache; // the high-quality stage's cells, read once
  Faces                                                 faces;
  this->UpdateProgress(0.0f);
  this->ClassifyCells(); // 1
  this->UpdateProgress(0.2f);
  this->BuildNet(); // 2
  this->UpdateProgress(0.3f);
  const RelaxationEnum relaxation = this->MakeLabelSurface(requestedRelaxation);
  const auto           initial = this->RelaxNodes(relaxation, cellCache); // 3
  this->RemoveSelfIntersections(relaxation, initial, faces);              // 4
  this->UpdateProgress(m_HighQuality ? 0.35f : 0.8f);
  this->FormFaces(faces);                      // 5
  this->RunHighQualityStage(faces, cellCache); // 6
  this->UpdateProgress(0.85f);
  this->RemoveSmallComponents(faces); // 7
  this->DropUnusedNodes(faces);
  this->MakeOutputMesh(faces.polygons,
                       faces.polygonSize,
                       faces.PhysicalPoints(),
                       faces.keptPoints.empty() ? nullptr : &faces.keptPoints); // 8
  this->ReleaseResampledInputs();
  m_LabelSurface = nullptr;
  this->UpdateProgress(1.0f);
}

template <typename TInputImage, typename TOutputMesh, typename TLabelImage>
auto
SurfaceNetsImageToMeshFilter<TInputImage, TOutputMesh, TLabelImage>::MakeLabelSurface(RelaxationEnum relaxation)
  -> RelaxationEnum
{
  namespace ME = MeshExtraction;
  using MaskType = Image<std::uint8_t, 3>;
  m_LabelSurface = nullptr;
  if (!m_HighQuality || !m_ClassifyByLabel || m_LabelSurfaceSigma <= 0.0 || m_Net.cells.empty() ||
      relaxation == RelaxationEnum::None)
  {
    return relaxation;
  }
  // The mask over the surface cells' box and a margin, beyond the image as outside.
  const std::int64_t margin = ME::detail::LabelSurfaceMargin(m_LabelSurfaceSigma);
  std::int64_t       lower[3] = { m_Net.cells[0].x, m_Net.cells[0].y, m_Net.cells[0].z };
  std::int64_t       upper[3] = { lower[0], lower[1], lower[2] };
  for (const ME::SurfaceCell & c : m_Net.cells)
  {
    const std::int64_t at[3] = { c.x, c.y, c.z };
    for (unsigned int d = 0; d < 3; ++d)
    {
      lower[d] = std::min(lower[d], at[d]);
      upper[d] = std::max(upper[d], at[d] + 1);
    }
  }
  const InputImageType *        input = this->GetSampledInput();
  const auto                    inside = ME::detail::SurfaceNetsVoxelRange<InputPixelType>::FromLabel(m_LabelValue);
  auto                          mask = MaskType::New();
  typename MaskType::RegionType maskRegion;
  for (unsigned int d = 0; d < 3; ++d)
  {
    lower[d] -= margin;
    upper[d] += margin;
    maskRegion.SetIndex(d, 0);
    maskRegion.SetSize(d, static_cast<SizeValueType>(upper[d] - lower[d] + 1));
  }
  mask->SetRegions(maskRegion);
  mask->Allocate();
  const auto             imageSize = input->GetBufferedRegion().GetSize();
  const std::int64_t     size[3] = { static_cast<std::int64_t>(imageSize[0]),
                                     static_cast<std::int64_t>(imageSize[1]),
                                     static_cast<std::int64_t>(imageSize[2]) };
  const InputPixelType * buffer = input->GetBufferPointer();
  std::uint8_t *         m = mask->GetBufferPointer();
  const std::int64_t     mx = upper[0] - lower[0] + 1;
  const std::int64_t     my = upper[1] - lower[1] + 1;
  const std::int64_t     mz = upper[2] - lower[2] + 1;
  ME::detail::ParallelForBlocks(static_cast<std::size_t>(mz), 1, [&](std::size_t begin, std::size_t end, std::size_t) {
    for (std::int64_t k = static_cast<std::int64_t>(begin); k < static_cast<std::int64_t>(end); ++k)
    {
      const std::int64_t z = lower[2] + k;
      for (std::int64_t j = 0; j < my; ++j)
      {
        const std::int64_t y = lower[1] + j;
        std::uint8_t *     row = m + (k * my + j) * mx;
        const bool         inImage = z >= 0 && z < size[2] && y >= 0 && y < size[1];
        for (std::int64_t i = 0; i < mx; ++i)
        {
          const std::int64_t x = lower[0] + i;
          row[i] = static_cast<std::uint8_t>(inImage && x >= 0 && x < size[0] &&
                                             inside(buffer[(z * size[1] + y) * size[0] + x]));
        }
      }
    }
  });
  auto function = LabelSurfaceImageType::New();
  function->SetRegions(maskRegion);
  function->Allocate();
  ME::detail::MakeLabelSurfaceFunction(mask, m_LabelSurfaceSigma, function, this->GetNumberOfWorkUnits());
  mask = nullptr;

  // The function on the input's grid: computed values in the box, "far outside" (the
  // margin) elsewhere, where no node reaches.
  m_LabelSurface = LabelSurfaceImageType::New();
  typename LabelSurfaceImageType::RegionType region;
  region.SetSize({ { imageSize[0], imageSize[1], imageSize[2] } });
  m_LabelSurface->SetRegions(region);
  m_LabelSurface->Allocate();
  const float   far = static_cast<float>(margin);
  const float * f = function->GetBufferPointer();
  float *       out = m_LabelSurface->GetBufferPointer();
  ME::detail::ParallelForBlocks(
    static_cast<std::size_t>(size[2]), 1, [&](std::size_t begin, std::size_t end, std::size_t) {
      for (std::int64_t z = static_cast<std::int64_t>(begin); z < static_cast<std::int64_t>(end); ++z)
      {
        for (std::int64_t y = 0; y < size[1]; ++y)
        {
          float * row = out + (z * size[1] + y) * size[0];
          if (z < lower[2] || z > upper[2] || y < lower[1] || y > upper[1])
          {
            std::fill(row, row + size[0], far);
            continue;
          }
          const float *      from = f + ((z - lower[2]) * my + (y - lower[1])) * mx;
          const std::int64_t x0 = std::max<std::int64_t>(0, lower[0]);
          const std::int64_t x1 = std::min<std::int64_t>(size[0] - 1, upper[0]);
          std::fill(row, row + x0, far);
          std::copy(from + (x0 - lower[0]), from + (x1 - lower[0]) + 1, row + x0);
          std::fill(row + x1 + 1, row + size[0], far);
        }
      }
    });
  return RelaxationEnum::Combined;
}

template <typename TInputImage, typename TOutputMesh, typename TLabelImage>
auto
SurfaceNetsImageToMeshFilter<TInputImage, TOutputMesh, TLabelImage>::PrepareInputs() -> RelaxationEnum
{
  if (this->GetInput() == nullptr)
  {
    itkExceptionMacro("No input image: call SetInput() first.");
  }
  if (this->GetInput()->GetLargestPossibleRegion().GetNumberOfPixels() == 0)
  {
    itkExceptionMacro("The input image has no voxels (its size is "
                      << this->GetInput()->GetLargestPossibleRegion().GetSize() << ").");
  }
  this->VerifyParameters();
  // Resampled copies, when asked for, replace the inputs for every stage. They are
  // released at the end (after an exception, by the next run or the filter's end).
  this->ResampleInputs();
  RelaxationEnum relaxation = m_Relaxation;
  const bool     haveGreyscale = !m_ClassifyByLabel;
  if (relaxation == RelaxationEnum::Automatic)
  {
    relaxation = haveGreyscale ? RelaxationEnum::Combined : RelaxationEnum::Averaging;
  }
  if (!haveGreyscale && (relaxation == RelaxationEnum::Gradient || relaxation == RelaxationEnum::Combined))
  {
    itkExceptionMacro("Relaxation " << relaxation
                                    << " steps to a greyscale iso-surface, but the input is a label image "
                                       "(ClassifyByLabel): use Averaging, or give the greyscale image as input "
                                       "and the labels as LabelImage.");
  }
  return relaxation;
}

template <typename TInputImage, typename TOutputMesh, typename TLabelImage>
void
SurfaceNetsImageToMeshFilter<TInputImage, TOutputMesh, TLabelImage>::BuildNet()
{
  MeshExtraction::detail::BuildSurfaceNet(m_Net, m_CellMargin, this->GetNumberOfWorkUnits());
  m_NumberOfNodes = m_Net.positions.size();
  m_NumberOfSplitCells = m_Net.numberOfSplitCells;
}

template <typename TInputImage, typename TOutputMesh, typename TLabelImage>
auto
SurfaceNetsImageToMeshFilter<TInputImage, TOutputMesh, TLabelImage>::RelaxNodes(
  RelaxationEnum                                 relaxation,
  MeshExtraction::detail::SurfaceNetsCellCache & cellCache) -> MeshExtraction::LargeBlockVector<MeshExtraction::Vec3>
{
  // The start positions, toward which stage 4 moves nodes back (a copy only when it runs).
  MeshExtraction::LargeBlockVector<MeshExtraction::Vec3> initial;
  if (this->PreventsSelfIntersections(relaxation))
  {
    initial = m_Net.positions;
  }
  // In the high-quality mode, the nodes' cells are read once for this relaxation and
  // those that follow (otherwise the memory goes with this relaxation).
  const auto relaxed = this->RelaxNet(relaxation, m_MaximumNumberOfIterations, m_HighQuality ? &cellCache : nullptr);
  m_NumberOfIterations = relaxed.iterations;
  m_LastMaximumRelocation = relaxed.lastMaximumRelocation;
  return initial;
}

template <typename TInputImage, typename TOutputMesh, typename TLabelImage>
void
SurfaceNetsImageToMeshFilter<TInputImage, TOutputMesh, TLabelImage>::RemoveSelfIntersections(
  RelaxationEnum                                                 relaxation,
  const MeshExtraction::LargeBlockVector<MeshExtraction::Vec3> & initial,
  Faces &                                                        faces)
{
  m_NumberOfNodesMovedBack = 0;
  if (!this->PreventsSelfIntersections(relaxation))
  {
    return;
  }
  Matrix<double, 3, 3> M;
  MeshExtraction::Vec3 first;
  this->GetGeometry(M, first);
  // The faces of the final positions, and the nodes' physical points they were made with
  // (rounded to float for a float mesh, as the output rounds them anyway), so that the
  // stages after need not make them again.
  m_NumberOfNodesMovedBack = MeshExtraction::detail::RemoveSurfaceNetSelfIntersections(
    m_Net, initial, first, M, this->GetQuadSplit(), RoundsToFloat, &faces.polygons, &faces.checkedPoints);
}

template <typename TInputImage, typename TOutputMesh, typename TLabelImage>
void
SurfaceNetsImageToMeshFilter<TInputImage, TOutputMesh, TLabelImage>::FormFaces(Faces & faces)
{
  if (!faces.polygons.empty())
  {
    return; // stage 4 made them of the final positions
  }
  Matrix<double, 3, 3> M;
  MeshExtraction::Vec3 first;
  this->GetGeometry(M, first);
  MeshExtraction::detail::MakeSurfaceNetFaces(
    m_Net, first, M, this->GetQuadSplit(), faces.points, faces.polygons, faces.polygonSize);
}

template <typename TInputImage, typename TOutputMesh, typename TLabelImage>
void
SurfaceNetsImageToMeshFilter<TInputImage, TOutputMesh, TLabelImage>::RunHighQualityStage(
  Faces &                                        faces,
  MeshExtraction::detail::SurfaceNetsCellCache & cellCache)
{
  m_NumberOfSwaps = 0;
  m_NumberOfRoundsPerformed = 0;
  if (!m_HighQuality)
  {
    return;
  }
  std::vector<MeshExtraction::TriangleIndices> triangles(faces.polygons.size());
  for (std::size_t f = 0; f < faces.polygons.size(); ++f)
  {
    triangles[f] = { faces.polygons[f][0], faces.polygons[f][1], faces.polygons[f][2] };
  }
  this->RunHighQualityMode(triangles, &cellCache);
  m_NumberOfCollapses = 0;
  m_NumberOfSliverSwaps = 0;
  m_NumberOfSliverMoves = 0;
  m_NumberOfSplits = 0;
  m_NumberOfRemeshingCollapses = 0;
  m_NumberOfRemeshingSwaps = 0;
  m_NumberOfRemeshingRounds = 0;
  if (m_HighQualitySliverRemoval || m_HighQualityRemeshing)
  {
    const std::size_t numberOfNodes = m_Net.positions.size();
    this->RemoveSlivers(triangles);
    // Collapsed nodes, and nodes of splits taken back, are in no face.
    faces.removedNodes =
      m_NumberOfCollapses + m_NumberOfRemeshingCollapses > 0 || m_Net.positions.size() != numberOfNodes;
    faces.polygons.resize(triangles.size());
  }
  for (std::size_t f = 0; f < faces.polygons.size(); ++f)
  {
    faces.polygons[f] = { triangles[f][0], triangles[f][1], triangles[f][2], 0 };
  }
  faces.movedNodes = true; // their points are made anew
}

namespace MeshExtraction
{
namespace detail
{
/** Projects a continuous index onto the iso-surface of the sampler's trilinear
 * interpolation (where the high-quality relaxation puts the nodes) by Newton steps
 * along the interpolated gradient, each at most half a voxel; false where that does not
 * come within `tolerance` of the iso-value, or goes further than a voxel. */
template <typename TSampler>
bool
ProjectOntoIsoSurface(const TSampler & sampler, double isoValue, Vec3 & index)
{
  constexpr unsigned int NewtonSteps = 8;
  constexpr double       MaximumStep = 0.5;
  constexpr double       MaximumDistance = 1.0;
  const Vec3             start = index;
  Vec3                   x = index;
  double                 f = sampler.Interpolate(x) - isoValue;
  const double           tolerance = 1e-6 * (std::abs(f) + std::abs(isoValue) + 1e-12);
  for (unsigned int k = 0; k < NewtonSteps && std::abs(f) > tolerance; ++k)
  {
    const Vec3   g = sampler.Gradient(x);
    const double gg = SquaredNorm(g);
    if (!(gg > 0.0) || !std::isfinite(gg))
    {
      return false;
    }
    Vec3         step = g * (-f / gg);
    const double length = Norm(step);
    if (length > MaximumStep)
    {
      step *= MaximumStep / length;
    }
    x += step;
    f = sampler.Interpolate(x) - isoValue;
  }
  if (!(std::abs(f) <= 1e-3 * (std::abs(sampler.Interpolate(start) - isoValue) + tolerance) + tolerance) ||
      SquaredNorm(x - start) > MaximumDistance * MaximumDistance)
  {
    return false;
  }
  index = x;
  return true;
}
} // namespace detail
} // namespace MeshExtraction

template <typename TInputImage, typename TOutputMesh, typename TLabelImage>
void
SurfaceNetsImageToMeshFilter<TInputImage, TOutputMesh, TLabelImage>::RemoveSlivers(
  std::vector<MeshExtraction::TriangleIndices> & triangles)
{
  using namespace MeshExtraction;
  using namespace MeshExtraction::detail;
  Matrix<double, 3, 3> M;
  Vec3                 first;
  this->GetGeometry(M, first);
  SliverRemovalParameters parameters;
  parameters.degenerateQAreaTolerance = ValidityThresholds::HighQualityDegenerateQAreaTolerance;
  parameters.roundToFloat = RoundsToFloat;
  if (!m_HighQualitySliverRemoval)
  {
    parameters.maximumNumberOfPasses = 0;
  }
  if (m_HighQualityRemeshing)
  {
    parameters.remeshingIterations = m_HighQualityRemeshingIterations;
    parameters.targetEdgeLength = m_HighQualityTargetEdgeLength;
    if (!(parameters.targetEdgeLength > 0.0))
    {
      // The mean spacing: the lengths of the index axes in physical space.
      double sum = 0.0;
      for (unsigned int c = 0; c < 3; ++c)
      {
        sum += std::sqrt(M[0][c] * M[0][c] + M[1][c] * M[1][c] + M[2][c] * M[2][c]);
      }
      parameters.targetEdgeLength = sum / 3.0;
    }
    // Edges far shorter than the voxels resolve nothing more of the image: a bound on
    // how much the mesh can grow (about 16-fold in triangles at the smallest target).
    double smallestSpacing = std::numeric_limits<double>::infinity();
    for (unsigned int c = 0; c < 3; ++c)
    {
      smallestSpacing = std::min(smallestSpacing, std::sqrt(M[0][c] * M[0][c] + M[1][c] * M[1][c] + M[2][c] * M[2][c]));
    }
    if (parameters.targetEdgeLength < MinimumTargetEdgeLengthInVoxels * smallestSpacing)
    {
      itkExceptionMacro("HighQualityTargetEdgeLength "
                        << parameters.targetEdgeLength << " mm is below " << MinimumTargetEdgeLengthInVoxels
                        << " of the smallest voxel spacing (" << smallestSpacing
                        << " mm): the mesh would grow without resolving more; use at least "
                        << MinimumTargetEdgeLengthInVoxels * smallestSpacing << " mm.");
    }
  }
  SliverRemovalResult result;
  if (m_LabelSurface)
  {
    const SurfaceNetsSampler<LabelSurfaceImageType> target(m_LabelSurface.GetPointer(), 0.0, 1.0);
    const SurfaceProjection project = [&target](Vec3 & index) { return ProjectOntoIsoSurface(target, 0.0, index); };
    result = MeshExtraction::detail::RemoveSlivers(m_Net.positions, triangles, first, M, project, parameters);
  }
  else if (m_ClassifyByLabel)
  {
    // The label surface is only averaged (LabelSurfaceSigma 0): no surface to project
    // onto, so nodes stay where they are and collapses keep an end.
    result = MeshExtraction::detail::RemoveSlivers(m_Net.positions, triangles, first, M, nullptr, parameters);
  }
  else
  {
    const SurfaceNetsSampler<InputImageType> sampler(
      this->GetSampledInput(), m_IsoValue, m_InsideIsAboveIsoValue ? -1.0 : 1.0);
    const double            iso = m_IsoValue;
    const SurfaceProjection project = [&sampler, iso](Vec3 & index) {
      return ProjectOntoIsoSurface(sampler, iso, index);
    };
    result = MeshExtraction::detail::RemoveSlivers(m_Net.positions, triangles, first, M, project, parameters);
  }
  m_NumberOfCollapses = result.numberOfCollapses - result.numberOfRemeshingCollapses;
  m_NumberOfSliverSwaps = result.numberOfSwaps - result.numberOfRemeshingSwaps;
  m_NumberOfSliverMoves = result.numberOfMoves;
  m_NumberOfSplits = result.numberOfSplits;
  m_NumberOfRemeshingCollapses = result.numberOfRemeshingCollapses;
  m_NumberOfRemeshingSwaps = result.numberOfRemeshingSwaps;
  m_NumberOfRemeshingRounds = result.numberOfRemeshingRounds;
}

template <typename TInputImage, typename TOutputMesh, typename TLabelImage>
void
SurfaceNetsImageToMeshFilter<TInputImage, TOutputMesh, TLabelImage>::RemoveSmallComponents(Faces & faces)
{
  m_NumberOfComponentsRemoved = 0;
  m_NumberOfFacesRemoved = 0;
  faces.keptPoints.clear();
  if (!(m_MinimumComponentVolume > 0.0))
  {
    return;
  }
  // The volumes are those of the output: the nodes in physical space, as written.
  const std::size_t                 numberOfNodes = m_Net.positions.size();
  std::vector<MeshExtraction::Vec3> physical(numberOfNodes);
  if (const MeshExtraction::Vec3 * made = faces.PhysicalPoints())
  {
    std::copy(made, made + numberOfNodes, physical.begin());
  }
  else
  {
    Matrix<double, 3, 3> M;
    MeshExtraction::Vec3 first;
    this->GetGeometry(M, first);
    MeshExtraction::detail::ToPhysical(m_Net.positions.data(), numberOfNodes, first, M, RoundsToFloat, physical.data());
  }
  auto removal = MeshExtraction::detail::RemoveSmallComponents(
    faces.polygons, faces.polygonSize, physical, m_MinimumComponentVolume);
  if (removal.numberOfComponents > 0 && faces.polygons.empty())
  {
    itkExceptionMacro("MinimumComponentVolume "
                      << m_MinimumComponentVolume << " mm^3 removes every component: the largest of the "
                      << removal.numberOfComponents << " encloses " << removal.largestVolume << " mm^3.");
  }
  m_NumberOfComponentsRemoved = removal.numberOfComponents;
  m_NumberOfFacesRemoved = removal.numberOfFaces;
  faces.keptPoints = std::move(removal.keptPoints);
}

template <typename TInputImage, typename TOutputMesh, typename TLabelImage>
void
SurfaceNetsImageToMeshFilter<TInputImage, TOutputMesh, TLabelImage>::DropUnusedNodes(Faces & faces)
{
  if (!faces.removedNodes || !faces.keptPoints.empty())
  {
    return; // every node is in a face, or stage 7 renumbered the faces onto those that are
  }
  constexpr std::uint32_t    unused = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> newIndex(m_Net.positions.size(), unused);
  for (const auto & q : faces.polygons)
  {
    for (unsigned int k = 0; k < faces.polygonSize; ++k)
    {
      newIndex[q[k]] = 0;
    }
  }
  for (std::size_t v = 0; v < newIndex.size(); ++v)
  {
    if (newIndex[v] != unused)
    {
      newIndex[v] = static_cast<std::uint32_t>(faces.keptPoints.size());
      faces.keptPoints.push_back(static_cast<std::uint32_t>(v));
    }
  }
  for (auto & q : faces.polygons)
  {
    for (unsigned int k = 0; k < faces.polygonSize; ++k)
    {
      q[k] = newIndex[q[k]];
    }
  }
}

template <typename TInputImage, typename TOutputMesh, typename TLabelImage>
void
SurfaceNetsImageToMeshFilter<TInputImage, TOutputMesh, TLabelImage>::ReleaseResampledInputs()
{
  m_SampledInput = nullptr;
  m_SampledLabelImage = nullptr;
}

template <typename TInputImage, typename TOutputMesh, typename TLabelImage>
void
SurfaceNetsImageToMeshFilter<TInputImage, TOutputMesh, TLabelImage>::PrintSelf(std::ostream & os, Indent indent) const
{
  Superclass::PrintSelf(os, indent);
  os << indent << "IsoValue: " << m_IsoValue << '\n';
  os << indent << "InsideIsAboveIsoValue: " << m_InsideIsAboveIsoValue << '\n';
  os << indent << "ClassifyByLabel: " << m_ClassifyByLabel << '\n';
  os << indent << "LabelValue: " << m_LabelValue << '\n';
  os << indent << "Relaxation: " << m_Relaxation << '\n';
  os << indent << "MaximumNumberOfIterations: " << m_MaximumNumberOfIterations << '\n';
  os << indent << "ConvergenceThreshold: " << m_ConvergenceThreshold << '\n';
  os << indent << "SmoothingWeight: " << m_SmoothingWeight << '\n';
  os << indent << "ProjectionWeight: " << m_ProjectionWeight << '\n';
  os << indent << "SequentialRelaxation: " << m_SequentialRelaxation << '\n';
  os << indent << "GradientMethod: " << m_GradientMethod << '\n';
  os << indent << "GradientSigma: " << m_GradientSigma << '\n';
  os << indent << "Triangulation: " << m_Triangulation << '\n';
  os << indent << "CellMargin: " << m_CellMargin << '\n';
  os << indent << "PreventSelfIntersections: " << m_PreventSelfIntersections << '\n';
  os << indent << "HighQuality: " << m_HighQuality << '\n';
  os << indent << "NumberOfHighQualityRounds: " << m_NumberOfHighQualityRounds << '\n';
  os << indent << "HighQualityIterations: " << m_HighQualityIterations << '\n';
  os << indent << "HighQualityCellDilation: " << m_HighQualityCellDilation << '\n';
  os << indent << "HighQualitySliverRemoval: " << m_HighQualitySliverRemoval << '\n';
  os << indent << "HighQualityRemeshing: " << m_HighQualityRemeshing << '\n';
  os << indent << "HighQualityTargetEdgeLength: " << m_HighQualityTargetEdgeLength << '\n';
  os << indent << "HighQualityRemeshingIterations: " << m_HighQualityRemeshingIterations << '\n';
  os << indent << "NumberOfRemeshingRounds: " << m_NumberOfRemeshingRounds << '\n';
  os << indent << "MinimumComponentVolume: " << m_MinimumComponentVolume << '\n';
  os << indent << "ResampleToIsotropicVoxels: " << m_ResampleToIsotropicVoxels << '\n';
  os << indent << "LabelSurfaceSigma: " << m_LabelSurfaceSigma << '\n';
  os << indent << "ConvergedSwapFraction: " << m_ConvergedSwapFraction << '\n';
  os << indent << "NumberOfSwaps: " << m_NumberOfSwaps << '\n';
  os << indent << "NumberOfRoundsPerformed: " << m_NumberOfRoundsPerformed << '\n';
  os << indent << "NumberOfComponentsRemoved: " << m_NumberOfComponentsRemoved << '\n';
  os << indent << "NumberOfFacesRemoved: " << m_NumberOfFacesRemoved << '\n';
  os << indent << "NumberOfIterations: " << m_NumberOfIterations << '\n';
  os << indent << "LastMaximumRelocation: " << m_LastMaximumRelocation << '\n';
  os << indent << "NumberOfNodes: " << m_NumberOfNodes << '\n';
  os << indent << "NumberOfSplitCells: " << m_NumberOfSplitCells << '\n';
  os << indent << "NumberOfNodesMovedBack: " << m_NumberOfNodesMovedBack << '\n';
}
} // namespace itk

#endif
