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
// The simulated user of the connected orthogonal contours (thesis section 5.3, Table 5.1):
// a user who knows the reference surface and shapes the contour model toward it, with or
// without edge-assisted moves (EDEMS). Shared by meshextraction-contours-study and the
// OrthogonalContourModel tests.
#ifndef MeshExtractionContourUser_h
#define MeshExtractionContourUser_h

#include "itkImplicitSurfaceFunction.h"
#include "itkOrthogonalContourModelEdgeDetector.h"
#include "itkMeshSurfaceDistanceCalculator.h"
#include "itkOrthogonalContourModel.h"
#include "itkOrthogonalContourModelToMeshFilter.h"
#include "itkQuadEdgeMesh.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace MeshExtractionContourUser
{
using ModelType = itk::OrthogonalContourModel;
using MeshType = itk::QuadEdgeMesh<double, 3>;

/** The physical point of a continuous index of the model's grid. */
inline itk::Point<double, 3>
PhysicalOf(const ModelType & model, const ModelType::ContinuousIndexType & x)
{
  itk::Point<double, 3> p = model.GetOrigin();
  for (unsigned int i = 0; i < 3; ++i)
  {
    for (unsigned int j = 0; j < 3; ++j)
    {
      p[i] += model.GetDirection()(i, j) * model.GetSpacing()[j] * x[j];
    }
  }
  return p;
}

/** Where `surface` crosses control point p's line, the crossing nearest the point
 * within its range (continuous index along the line); NaN if there is none. */
inline double
SurfaceCrossing(const ModelType & model, unsigned int p, const itk::ImplicitSurfaceFunction & surface)
{
  const unsigned int axis = model.GetControlPointLineAxis(p);
  const auto         range = model.GetControlPointRange(p);
  auto               x = model.GetControlPointIndex(p);
  const double       start = x[axis];
  auto               f = [&](double t) {
    x[axis] = t;
    return surface.Evaluate(PhysicalOf(model, x));
  };
  double       best = std::numeric_limits<double>::quiet_NaN();
  const double step = 0.25;
  double       a = range[0];
  double       fa = f(a);
  while (a < range[1])
  {
    const double b = std::min(a + step, range[1]);
    const double fb = f(b);
    if ((fa <= 0.0) != (fb <= 0.0))
    {
      double lo = a;
      double hi = b;
      for (int i = 0; i < 50; ++i)
      {
        const double mid = 0.5 * (lo + hi);
        ((f(mid) <= 0.0) == (fa <= 0.0) ? lo : hi) = mid;
      }
      const double t = 0.5 * (lo + hi);
      best = std::isnan(best) || std::abs(t - start) < std::abs(best - start) ? t : best;
    }
    a = b;
    fa = fb;
  }
  return best;
}

/** What a simulated user did. */
struct UserWork
{
  unsigned int relocations{ 0 };
  double       voxelsTravelled{ 0.0 };
};

/** Moves every control point more than `tolerance` voxels from the surface along its
 * line onto it (one relocation each); refused moves are skipped. */
inline UserWork
SnapToSurface(ModelType & model, const itk::ImplicitSurfaceFunction & surface, double tolerance)
{
  std::vector<ModelType::ContinuousIndexType> starts;
  for (unsigned int p = 0; p < model.GetNumberOfControlPoints(); ++p)
  {
    starts.push_back(model.GetControlPointIndex(p));
  }
  UserWork work;
  for (const auto & start : starts)
  {
    for (unsigned int p = 0; p < model.GetNumberOfControlPoints(); ++p)
    {
      if (model.GetControlPointIndex(p) != start)
      {
        continue;
      }
      const double target = SurfaceCrossing(model, p, surface);
      const double from = start[model.GetControlPointLineAxis(p)];
      if (!std::isnan(target) && std::abs(target - from) > tolerance && model.MoveControlPoint(p, target))
      {
        ++work.relocations;
        work.voxelsTravelled += std::abs(target - from);
      }
      break;
    }
  }
  return work;
}

/** Mean and largest |distance| (mm) from the contour curves to the surface, and the
 * continuous index of the sample farthest from it. */
struct ContourError
{
  double                         mean{ 0.0 };
  double                         maximum{ 0.0 };
  ModelType::ContinuousIndexType worst;
};

inline ContourError
MeasureContourError(const ModelType & model, const itk::ImplicitSurfaceFunction & surface)
{
  ContourError error;
  std::size_t  count = 0;
  for (unsigned int c = 0; c < model.GetNumberOfContours(); ++c)
  {
    for (const auto & x : model.SampleContour(c, 8))
    {
      const double d = std::abs(surface.Evaluate(PhysicalOf(model, x)));
      error.mean += d;
      ++count;
      if (d >= error.maximum)
      {
        error.maximum = d;
        error.worst = x;
      }
    }
  }
  error.mean /= static_cast<double>(std::max<std::size_t>(count, 1));
  return error;
}

/** The distance report of the model's mesh to the exact surface. */
inline itk::MeshExtraction::MeshSurfaceDistanceReport
MeshDistance(const ModelType * model, const itk::ImplicitSurfaceFunction * surface)
{
  auto filter = itk::OrthogonalContourModelToMeshFilter<MeshType>::New();
  filter->SetInput(model);
  filter->Update();
  auto calculator = itk::MeshSurfaceDistanceCalculator<MeshType>::New();
  calculator->SetMesh(filter->GetOutput());
  calculator->SetReferenceSurface(surface);
  calculator->Compute();
  return calculator->GetReport();
}

/** Adds a contour where the contour error is largest: in the plane halfway between
 * the occupied planes around the worst sample, on the axis with the widest gap there;
 * nearby planes when that one is refused. Returns whether a contour was added. */
inline bool
AddContourAtWorstError(ModelType & model, const ModelType::ContinuousIndexType & worst)
{
  struct Candidate
  {
    double       gap;
    unsigned int axis;
    double       middle;
  };
  // Beyond the last occupied plane the model ends at its control points, not at the
  // image's border: a small structure in a large image gets planes through itself.
  double extent[3][2];
  for (unsigned int axis = 0; axis < 3; ++axis)
  {
    extent[axis][0] = static_cast<double>(model.GetSize()[axis]);
    extent[axis][1] = -1.0;
  }
  for (unsigned int p = 0; p < model.GetNumberOfControlPoints(); ++p)
  {
    const auto x = model.GetControlPointIndex(p);
    for (unsigned int axis = 0; axis < 3; ++axis)
    {
      extent[axis][0] = std::min(extent[axis][0], x[axis] - 1.0);
      extent[axis][1] = std::max(extent[axis][1], x[axis] + 1.0);
    }
  }
  std::vector<Candidate> candidates;
  for (unsigned int axis = 0; axis < 3; ++axis)
  {
    double below = std::max(-1.0, extent[axis][0]);
    double above = std::min(static_cast<double>(model.GetSize()[axis]), extent[axis][1]);
    for (unsigned int c = 0; c < model.GetNumberOfContours(); ++c)
    {
      const auto position = static_cast<double>(model.GetContourPosition(c));
      if (model.GetContourAxis(c) == axis)
      {
        below = position <= worst[axis] ? std::max(below, position) : below;
        above = position > worst[axis] ? std::min(above, position) : above;
      }
    }
    candidates.push_back({ above - below, axis, 0.5 * (above + below) });
  }
  std::sort(
    candidates.begin(), candidates.end(), [](const Candidate & a, const Candidate & b) { return a.gap > b.gap; });
  for (const auto & candidate : candidates)
  {
    for (const int shift : { 0, 1, -1, 2, -2, 3, -3, 4, -4, 6, -6 })
    {
      const auto position = static_cast<itk::IndexValueType>(std::round(candidate.middle)) + shift;
      if (model.AddContour(candidate.axis, position))
      {
        return true;
      }
    }
  }
  return false;
}
/** What the simulated user did and reached. */
struct UserRun
{
  unsigned int relocations{ 0 };
  unsigned int contoursAdded{ 0 };
  unsigned int edgeDetectionRuns{ 0 };
  double       voxelsTravelled{ 0.0 };
  double       voxelsTravelledByEdgeDetection{ 0.0 };
  ContourError error;
};

/** The simulated user of issue 31 (thesis section 5.3): from the template, it runs
 * EDEMS (when given a detector), puts back on the surface every control point more
 * than half a voxel off it, and adds a contour where the contour error is largest,
 * until the mean contour error is at most `target` or the model has `maximumContours`. */
template <typename TDetector>
UserRun
SimulateUser(ModelType &                          model,
             const itk::ImplicitSurfaceFunction & surface,
             TDetector *                          detector,
             double                               target,
             unsigned int                         maximumContours)
{
  UserRun run;
  for (;;)
  {
    if (detector != nullptr)
    {
      detector->MoveAllControlPoints();
      ++run.edgeDetectionRuns;
      run.voxelsTravelledByEdgeDetection += detector->GetDistanceTravelled();
    }
    const UserWork work = SnapToSurface(model, surface, 0.5);
    run.relocations += work.relocations;
    run.voxelsTravelled += work.voxelsTravelled;
    run.error = MeasureContourError(model, surface);
    if (run.error.mean <= target || model.GetNumberOfContours() >= maximumContours ||
        !AddContourAtWorstError(model, run.error.worst))
    {
      return run;
    }
    ++run.contoursAdded;
  }
}
} // namespace MeshExtractionContourUser

#endif
