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
// Editing connected orthogonal contours stays interactive (issue 31): one control-point
// move, which re-scan-converts the contours it touches, and the closed mesh made again
// from the model, for a model of about 20 contours (the 3-contour template on a 64^3 grid
// with contours added in all three directions, planes 6 voxels apart first). The time per edit is the move and the
// re-mesh together.

#include "itkOrthogonalContourModel.h"
#include "itkOrthogonalContourModelToMeshFilter.h"
#include "itkQuadEdgeMesh.h"

#include <benchmark/benchmark.h>

namespace
{
using ModelType = itk::OrthogonalContourModel;
using MeshType = itk::QuadEdgeMesh<double, 3>;

/** The template of radius 20 voxels about the centre of a 64^3 grid, and the contours of
 * planes at the offsets below in every direction, until there are 20 (a plane the model
 * refuses is left out). */
ModelType::Pointer
TwentyContourModel(ModelType::InterpolationEnum interpolation)
{
  auto                model = ModelType::New();
  ModelType::SizeType size;
  size.Fill(64);
  ModelType::SpacingType spacing;
  spacing.Fill(1.0);
  ModelType::PointType origin;
  origin.Fill(0.0);
  ModelType::DirectionType direction;
  direction.SetIdentity();
  model->SetGrid(size, spacing, origin, direction);
  model->SetInterpolation(interpolation);
  ModelType::IndexType center;
  center.Fill(32);
  ModelType::RadiiType radii;
  radii.Fill(20.0);
  model->InitializeTemplate(center, radii);
  for (const int offset : { 6, -6, 12, -12, 18, -18, 3, -3, 9, -9, 15, -15, 1, -1, 4, -4 })
  {
    for (unsigned int axis = 0; axis < 3 && model->GetNumberOfContours() < 20; ++axis)
    {
      model->AddContour(axis, 32 + offset);
    }
  }
  return model;
}

void
MoveAndRemesh(benchmark::State & state, ModelType::InterpolationEnum interpolation)
{
  const auto model = TwentyContourModel(interpolation);
  auto       filter = itk::OrthogonalContourModelToMeshFilter<MeshType>::New();
  filter->SetInput(model);
  // A control point that can move half a voxel along its line and back: the first the
  // model lets do both (a move that would bring points of other lines into one voxel is
  // refused).
  unsigned int point = model->GetNumberOfControlPoints();
  double       targets[2] = { 0.0, 0.0 };
  for (unsigned int p = 0; p < model->GetNumberOfControlPoints(); ++p)
  {
    const double start = model->GetControlPointIndex(p)[model->GetControlPointLineAxis(p)];
    if (model->MoveControlPoint(p, start + 0.5) && model->MoveControlPoint(p, start))
    {
      point = p;
      targets[0] = start + 0.5;
      targets[1] = start;
      break;
    }
  }
  if (point == model->GetNumberOfControlPoints())
  {
    state.SkipWithError("no control point can move half a voxel and back");
    return;
  }
  std::size_t edits = 0;
  for (auto _ : state)
  {
    if (!model->MoveControlPoint(point, targets[edits++ % 2]))
    {
      state.SkipWithError(model->GetRefusalReason().c_str());
      break;
    }
    filter->Update();
    benchmark::DoNotOptimize(filter->GetOutput()->GetNumberOfFaces());
  }
  state.counters["contours"] = static_cast<double>(model->GetNumberOfContours());
  state.counters["triangles"] = static_cast<double>(filter->GetOutput()->GetNumberOfFaces());
}
} // namespace

BENCHMARK_CAPTURE(MoveAndRemesh, Linear, ModelType::InterpolationEnum::Linear)
  ->Name("OrthogonalContourModel/MoveAndRemesh/Linear")
  ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(MoveAndRemesh, CatmullRom, ModelType::InterpolationEnum::CatmullRom)
  ->Name("OrthogonalContourModel/MoveAndRemesh/CatmullRom")
  ->Unit(benchmark::kMillisecond);
