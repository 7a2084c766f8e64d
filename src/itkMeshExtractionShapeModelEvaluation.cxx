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
#include "itkMeshExtractionShapeModelEvaluation.h"
#include "itkMeshExtractionParallel.h"
#include "itkMeshExtractionSymmetricICP.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <random>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
namespace
{
constexpr double NaN = std::numeric_limits<double>::quiet_NaN();

/** The mean distance of `points` to the surface of `query`'s mesh. */
double
MeanDistanceToSurface(const std::vector<Vec3> & points, const ClosestPointQuery & query)
{
  const std::vector<SurfacePoint> closest = query.Find(points);
  double                          sum = 0.0;
  for (std::size_t k = 0; k < points.size(); ++k)
  {
    sum += Norm(points[k] - closest[k].point);
  }
  return sum / static_cast<double>(points.size());
}

double
MeanVertexDistance(const Shape & a, const Shape & b)
{
  double sum = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k)
  {
    sum += Norm(a[k] - b[k]);
  }
  return sum / static_cast<double>(a.size());
}

/** The model's shape for the first b.size() modes (fewer if the model has fewer). */
Shape
Reconstruct(const PrincipalComponentModel & model, std::vector<double> b)
{
  b.resize(std::min(b.size(), model.NumberOfModes()));
  return model.Synthesize(b);
}

IndexedTriangleMesh
MovedMesh(const IndexedTriangleMesh & mesh, const SimilarityParameters & transform)
{
  IndexedTriangleMesh out;
  out.points = ApplySimilarity(transform, mesh.points);
  out.triangles = mesh.triangles;
  return out;
}

double
Median(std::vector<double> values)
{
  if (values.empty())
  {
    return NaN;
  }
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}
} // namespace

std::vector<double>
CumulativeVarianceFractions(const std::vector<double> & variances)
{
  double total = 0.0;
  for (double v : variances)
  {
    total += v;
  }
  std::vector<double> fractions;
  double              sum = 0.0;
  for (double v : variances)
  {
    sum += v;
    fractions.push_back(total > 0.0 ? sum / total : 0.0);
  }
  return fractions;
}

GeneralizationResult
LeaveOneOutGeneralization(const std::vector<Shape> &               corresponded,
                          const std::vector<IndexedTriangleMesh> & originals,
                          unsigned int                             modes)
{
  const std::vector<Shape> aligned = GeneralizedProcrustes(corresponded, true);
  GeneralizationResult     result;
  for (std::size_t i = 0; i < corresponded.size(); ++i)
  {
    std::vector<Shape> others;
    for (std::size_t j = 0; j < aligned.size(); ++j)
    {
      if (j != i)
      {
        others.push_back(aligned[j]);
      }
    }
    const PrincipalComponentModel model = BuildPrincipalComponents(others, 1.0);
    const Shape                   mean = model.Synthesize({});
    const SimilarityParameters    toMean = AlignShape(corresponded[i], mean, true);
    std::vector<double>           b = model.Project(ApplySimilarity(toMean, corresponded[i]));
    b.resize(std::min<std::size_t>(b.size(), modes));
    const Shape reconstruction = ApplySimilarity(toMean.Inverse(), Reconstruct(model, b));
    result.vertexToVertex.push_back(MeanVertexDistance(reconstruction, corresponded[i]));
    const ClosestPointQuery original(originals[i], MeshExtractionEnums::Correspondence::PointToSurface);
    result.vertexToSurface.push_back(MeanDistanceToSurface(reconstruction, original));
  }
  for (std::size_t i = 0; i < corresponded.size(); ++i)
  {
    result.meanVertexToVertex += result.vertexToVertex[i] / static_cast<double>(corresponded.size());
    result.meanVertexToSurface += result.vertexToSurface[i] / static_cast<double>(corresponded.size());
  }
  return result;
}

namespace
{
/** `count` random coefficient vectors b_k ~ N(0, lambda_k), clipped to +-2 sqrt(lambda_k). */
std::vector<std::vector<double>>
RandomCoefficients(const PrincipalComponentModel & model, unsigned int modes, unsigned int count, std::uint32_t seed)
{
  std::mt19937                     random(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  const std::size_t                k = std::min<std::size_t>(modes, model.NumberOfModes());
  std::vector<std::vector<double>> samples(count, std::vector<double>(k));
  for (auto & b : samples)
  {
    for (std::size_t m = 0; m < k; ++m)
    {
      const double sd = std::sqrt(model.variances[m]);
      b[m] = std::clamp(normal(random) * sd, -2.0 * sd, 2.0 * sd);
    }
  }
  return samples;
}
} // namespace

SpecificityResult
Specificity(const std::vector<Shape> &                aligned,
            const std::vector<SimilarityParameters> & toModel,
            const std::vector<IndexedTriangleMesh> &  originals,
            const SpecificitySettings &               settings)
{
  const PrincipalComponentModel model = BuildPrincipalComponents(aligned, 1.0);
  const auto          coefficients = RandomCoefficients(model, settings.modes, settings.samples, settings.seed);
  std::vector<double> nearest(coefficients.size());
  ParallelForBlocks(coefficients.size(), 16, [&](std::size_t begin, std::size_t end, std::size_t) {
    for (std::size_t s = begin; s < end; ++s)
    {
      const Shape shape = model.Synthesize(coefficients[s]);
      nearest[s] = std::numeric_limits<double>::infinity();
      for (const Shape & training : aligned)
      {
        nearest[s] = std::min(nearest[s], MeanVertexDistance(shape, training));
      }
    }
  });
  SpecificityResult result;
  for (double d : nearest)
  {
    result.vertexToVertex += d / static_cast<double>(nearest.size());
  }
  for (double d : nearest)
  {
    result.vertexToVertexDeviation += (d - result.vertexToVertex) * (d - result.vertexToVertex);
  }
  result.vertexToVertexDeviation = std::sqrt(result.vertexToVertexDeviation / static_cast<double>(nearest.size()));
  // Vertex to surface: the original training surfaces in the model's frame.
  std::vector<IndexedTriangleMesh>                moved;
  std::vector<std::unique_ptr<ClosestPointQuery>> surfaces;
  for (std::size_t j = 0; j < originals.size(); ++j)
  {
    moved.push_back(MovedMesh(originals[j], toModel[j]));
  }
  for (const IndexedTriangleMesh & mesh : moved)
  {
    surfaces.push_back(std::make_unique<ClosestPointQuery>(mesh, MeshExtractionEnums::Correspondence::PointToSurface));
  }
  const std::size_t count = std::min<std::size_t>(settings.surfaceSamples, coefficients.size());
  for (std::size_t s = 0; s < count; ++s)
  {
    const Shape       shape = model.Synthesize(coefficients[s]);
    std::vector<Vec3> points;
    for (std::size_t k = 0; k < shape.size(); k += std::max(1u, settings.surfaceStride))
    {
      points.push_back(shape[k]);
    }
    double best = std::numeric_limits<double>::infinity();
    for (const auto & surface : surfaces)
    {
      best = std::min(best, MeanDistanceToSurface(points, *surface));
    }
    result.vertexToSurface += best / static_cast<double>(count);
  }
  return result;
}

std::vector<std::vector<double>>
EigenvectorStability(const std::vector<Shape> &       aligned,
                     const std::vector<std::size_t> & subsetSizes,
                     unsigned int                     modes)
{
  const PrincipalComponentModel    full = BuildPrincipalComponents(aligned, 1.0);
  std::vector<std::vector<double>> angles;
  for (std::size_t size : subsetSizes)
  {
    if (size < 2 || size > aligned.size())
    {
      itkGenericExceptionMacro("A subset of " << size << " of " << aligned.size() << " shapes has no eigenvectors.");
    }
    const PrincipalComponentModel subset =
      BuildPrincipalComponents(std::vector<Shape>(aligned.begin(), aligned.begin() + size), 1.0);
    std::vector<double> row(modes, NaN);
    for (std::size_t m = 0; m < modes && m < subset.NumberOfModes() && m < full.NumberOfModes(); ++m)
    {
      double dot = 0.0;
      for (std::size_t r = 0; r < full.basis[m].size(); ++r)
      {
        dot += full.basis[m][r] * subset.basis[m][r];
      }
      row[m] = std::acos(std::min(1.0, std::abs(dot)));
    }
    angles.push_back(row);
  }
  return angles;
}

LandmarkTransferResult
TransferLandmarks(const std::vector<Shape> &           corresponded,
                  const std::vector<TriangleIndices> & triangles,
                  const std::vector<MeshLandmarks> &   landmarks)
{
  LandmarkTransferResult result;
  for (const MeshLandmarks & m : landmarks)
  {
    for (const std::string & id : m.ids)
    {
      if (std::find(result.ids.begin(), result.ids.end(), id) == result.ids.end())
      {
        result.ids.push_back(id);
      }
    }
  }
  const std::size_t n = corresponded.size();
  result.error.assign(n, std::vector<std::vector<double>>(n, std::vector<double>(result.ids.size(), NaN)));
  // A landmark of mesh j by id: its index in j's list, or none.
  auto find = [&](std::size_t j, const std::string & id) {
    const auto & ids = landmarks[j].ids;
    return static_cast<std::size_t>(std::find(ids.begin(), ids.end(), id) - ids.begin());
  };
  for (std::size_t i = 0; i < n; ++i)
  {
    IndexedTriangleMesh surface;
    surface.points = corresponded[i];
    surface.triangles = triangles;
    const ClosestPointQuery         query(surface, MeshExtractionEnums::Correspondence::PointToSurface);
    const std::vector<SurfacePoint> carried = query.Find(landmarks[i].points);
    for (std::size_t l = 0; l < landmarks[i].ids.size(); ++l)
    {
      const std::size_t column = static_cast<std::size_t>(
        std::find(result.ids.begin(), result.ids.end(), landmarks[i].ids[l]) - result.ids.begin());
      const TriangleIndices & t = triangles[carried[l].triangle];
      for (std::size_t j = 0; j < n; ++j)
      {
        const std::size_t own = find(j, landmarks[i].ids[l]);
        if (j == i || own == landmarks[j].ids.size())
        {
          continue;
        }
        const Vec3 p = corresponded[j][t[0]] * carried[l].weights[0] + corresponded[j][t[1]] * carried[l].weights[1] +
                       corresponded[j][t[2]] * carried[l].weights[2];
        result.error[i][j][column] = Norm(p - landmarks[j].points[own]);
      }
    }
  }
  std::vector<double> all;
  result.meanPerLandmark.assign(result.ids.size(), 0.0);
  std::vector<std::size_t> perLandmark(result.ids.size(), 0);
  for (const auto & row : result.error)
  {
    for (const auto & cell : row)
    {
      for (std::size_t l = 0; l < cell.size(); ++l)
      {
        if (!std::isnan(cell[l]))
        {
          all.push_back(cell[l]);
          result.meanPerLandmark[l] += cell[l];
          ++perLandmark[l];
        }
      }
    }
  }
  for (std::size_t l = 0; l < perLandmark.size(); ++l)
  {
    result.meanPerLandmark[l] = perLandmark[l] > 0 ? result.meanPerLandmark[l] / perLandmark[l] : NaN;
  }
  result.count = all.size();
  for (double e : all)
  {
    result.mean += e / static_cast<double>(all.size());
  }
  result.mean = all.empty() ? NaN : result.mean;
  result.median = Median(all);
  return result;
}

SurfaceFitResult
MeasureSurfaceFit(const std::vector<Shape> &               corresponded,
                  const std::vector<TriangleIndices> &     triangles,
                  const std::vector<IndexedTriangleMesh> & originals)
{
  SurfaceFitResult result;
  for (std::size_t i = 0; i < corresponded.size(); ++i)
  {
    const ClosestPointQuery original(originals[i], MeshExtractionEnums::Correspondence::PointToSurface);
    IndexedTriangleMesh     surface;
    surface.points = corresponded[i];
    surface.triangles = triangles;
    const ClosestPointQuery onCorresponded(surface, MeshExtractionEnums::Correspondence::PointToSurface);
    result.forward += MeanDistanceToSurface(corresponded[i], original) / static_cast<double>(corresponded.size());
    result.backward +=
      MeanDistanceToSurface(originals[i].points, onCorresponded) / static_cast<double>(corresponded.size());
  }
  return result;
}
} // namespace detail
} // namespace MeshExtraction
} // namespace itk
