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
// libFuzzer harness for SurfaceNets on small volumes: the first bytes choose the grid
// (1 to 7 voxels per axis), the relaxation, the triangulation, the high-quality mode and
// its isotropic remeshing (bit 6);
// the rest are the voxels (signed bytes, the object where they are >= 0). The filter may
// refuse an input (a constant image) with an itk::ExceptionObject; every mesh it emits
// must be a valid closed surface (closed, 2-manifold, outward, no degenerate, inverted or
// self-intersecting triangle), or the harness aborts with the report. With bit 5 of the
// settings the voxels are labels instead (byte modulo 2 to 5: up to 4 labels and the
// background) for MultiLabelSurfaceNetsImageToMeshFilter, and every label's surface must
// be valid.

#include "itkMultiLabelSurfaceNetsImageToMeshFilter.h"
#include "itkSurfaceNetsImageToMeshFilter.h"
#include "itkTriangleMeshQualityCalculator.h"

#include <cstdint>
#include <cstdlib>
#include <iostream>

extern "C" int
LLVMFuzzerTestOneInput(const std::uint8_t * data, std::size_t size)
{
  if (size < 4)
  {
    return 0;
  }
  using ImageType = itk::Image<float, 3>;
  using MeshType = itk::QuadEdgeMesh<double, 3>;
  using FilterType = itk::SurfaceNetsImageToMeshFilter<ImageType, MeshType>;
  using Relaxation = itk::SurfaceNetsImageToMeshFilterEnums::Relaxation;
  using Triangulation = itk::SurfaceNetsImageToMeshFilterEnums::Triangulation;

  ImageType::SizeType gridSize;
  for (unsigned int d = 0; d < 3; ++d)
  {
    gridSize[d] = 1 + data[d] % 7;
  }
  const std::uint8_t settings = data[3];
  auto               image = ImageType::New();
  image->SetRegions(gridSize);
  image->Allocate();
  const std::size_t voxels = image->GetBufferedRegion().GetNumberOfPixels();
  float *           buffer = image->GetBufferPointer();
  for (std::size_t i = 0; i < voxels; ++i)
  {
    // The bytes after the settings, repeated when there are fewer than voxels.
    const std::size_t available = size - 4;
    buffer[i] = available > 0 ? static_cast<float>(static_cast<std::int8_t>(data[4 + i % available])) : 0.0f;
  }
  if (settings & 32)
  {
    // Labels 0 .. K (K = 1 to 4) of the same bytes, in one pass.
    using LabelImageType = itk::Image<std::uint8_t, 3>;
    using LabelMeshType = itk::Mesh<double, 3>;
    const unsigned int labelCount = 2 + (settings >> 6);
    auto               labels = LabelImageType::New();
    labels->SetRegions(gridSize);
    labels->Allocate();
    const std::size_t available = size - 4;
    for (std::size_t i = 0; i < voxels; ++i)
    {
      labels->GetBufferPointer()[i] =
        static_cast<std::uint8_t>(available > 0 ? data[4 + i % available] % labelCount : 0u);
    }
    auto multi = itk::MultiLabelSurfaceNetsImageToMeshFilter<LabelImageType, LabelMeshType>::New();
    multi->SetInput(labels);
    multi->SetMaximumNumberOfIterations((settings & 1) ? 0 : 10);
    multi->SetNumberOfWorkUnits(1);
    try
    {
      multi->Update();
    }
    catch (const itk::ExceptionObject &)
    {
      return 0; // a refusal with a message (only the background)
    }
    for (const auto label : multi->GetExtractedLabels())
    {
      auto calculator = itk::TriangleMeshQualityCalculator<LabelMeshType>::New();
      calculator->SetMesh(multi->GetLabelSurface(label));
      calculator->Compute();
      if (!calculator->GetReport().IsValidClosedSurface())
      {
        std::cerr << "MultiLabelSurfaceNets emitted an invalid surface of label " << static_cast<int>(label)
                  << " (grid " << gridSize << ", settings " << static_cast<int>(settings) << "):\n";
        calculator->GetReport().Print(std::cerr);
        std::abort();
      }
    }
    return 0;
  }
  static const Relaxation relaxations[] = {
    Relaxation::Automatic, Relaxation::None, Relaxation::Averaging, Relaxation::Gradient, Relaxation::Combined
  };
  auto filter = FilterType::New();
  filter->SetInput(image);
  filter->SetIsoValue(0.0);
  filter->SetRelaxation(relaxations[settings % 5]);
  filter->SetTriangulation((settings & 8) ? Triangulation::Delaunay : Triangulation::ShortestDiagonal);
  filter->SetHighQuality((settings & 16) != 0);
  filter->SetHighQualityRemeshing((settings & 64) != 0);
  filter->SetNumberOfWorkUnits(1);
  try
  {
    filter->Update();
  }
  catch (const itk::ExceptionObject &)
  {
    return 0; // a refusal with a message (e.g. no voxel inside)
  }
  auto quality = itk::TriangleMeshQualityCalculator<MeshType>::New();
  quality->SetMesh(filter->GetOutput());
  quality->Compute();
  const auto report = quality->GetReport();
  if (!report.IsValidClosedSurface())
  {
    std::cerr << "SurfaceNets emitted an invalid surface (grid " << gridSize << ", settings "
              << static_cast<int>(settings) << "):\n";
    report.Print(std::cerr);
    std::abort();
  }
  return 0;
}
