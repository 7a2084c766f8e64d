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
#include "itkMeshExtractionDistanceAnalysis.h"
#include "itkImplicitSurfaceFunction.h"
#include "itkMeshExtractionJSON.h"
#include "itkMeshExtractionParallel.h"

#include <cmath>
#include <iomanip>
#include <ostream>

namespace itk
{
namespace MeshExtraction
{
DistanceStatistics
ComputeDistanceStatistics(const std::vector<double> & distances, const std::vector<double> * signedDistances)
{
  DistanceStatistics s;
  s.count = distances.size();
  if (distances.empty())
  {
    return s;
  }
  double sum = 0.0;
  double sumSquares = 0.0;
  for (double d : distances)
  {
    sum += d;
    sumSquares += d * d;
    s.maximum = std::max(s.maximum, d);
  }
  s.mean = sum / distances.size();
  s.rms = std::sqrt(sumSquares / distances.size());
  if (signedDistances != nullptr && !signedDistances->empty())
  {
    double signedSum = 0.0;
    for (double d : *signedDistances)
    {
      signedSum += d;
    }
    s.signedMean = signedSum / signedDistances->size();
  }
  return s;
}

std::vector<double>
DistancesToTriangles(const std::vector<Vec3> & points, const TriangleAABBTree & tree, unsigned int numberOfWorkUnits)
{
  std::vector<double> d(points.size(), 0.0);
  if (tree.IsEmpty())
  {
    itkGenericExceptionMacro("MeshSurfaceDistanceCalculator: the reference mesh has no triangles.");
  }
  ParallelForBlocks(
    points.size(),
    4096,
    [&](std::size_t begin, std::size_t end, std::size_t) {
      for (std::size_t i = begin; i < end; ++i)
      {
        d[i] = std::sqrt(tree.FindNearest(points[i]).squaredDistance);
      }
    },
    numberOfWorkUnits);
  return d;
}

std::vector<double>
SignedDistancesToSurface(const std::vector<Vec3> &       points,
                         const ImplicitSurfaceFunction & surface,
                         unsigned int                    numberOfWorkUnits)
{
  std::vector<double> d(points.size(), 0.0);
  ParallelForBlocks(
    points.size(),
    4096,
    [&](std::size_t begin, std::size_t end, std::size_t) {
      ImplicitSurfaceFunction::InputType p;
      for (std::size_t i = begin; i < end; ++i)
      {
        for (unsigned int k = 0; k < 3; ++k)
        {
          p[k] = points[i][k];
        }
        d[i] = surface.Evaluate(p);
      }
    },
    numberOfWorkUnits);
  return d;
}

std::vector<Vec3>
SampleTriangles(const IndexedTriangleMesh & mesh, unsigned int samplingLevel)
{
  std::vector<Vec3> samples;
  samples.reserve(mesh.points.size() + mesh.triangles.size() * (1 + samplingLevel * samplingLevel));
  samples.insert(samples.end(), mesh.points.begin(), mesh.points.end());
  for (const auto & t : mesh.triangles)
  {
    const Vec3 & a = mesh.points[t[0]];
    const Vec3 & b = mesh.points[t[1]];
    const Vec3 & c = mesh.points[t[2]];
    samples.push_back(TriangleCentroid(a, b, c));
    if (samplingLevel == 0)
    {
      continue;
    }
    // Interior and edge lattice points (i, j, k), i + j + k = level + 1, without the corners.
    const unsigned int n = samplingLevel + 1;
    for (unsigned int i = 0; i <= n; ++i)
    {
      for (unsigned int j = 0; i + j <= n; ++j)
      {
        const unsigned int k = n - i - j;
        if (i == n || j == n || k == n)
        {
          continue;
        }
        samples.push_back((a * static_cast<double>(i) + b * static_cast<double>(j) + c * static_cast<double>(k)) *
                          (1.0 / n));
      }
    }
  }
  return samples;
}

std::vector<Vec3>
SampleImplicitSurface(const ImplicitSurfaceFunction & surface, double spacing, const AxisAlignedBox * clip)
{
  if (!(spacing > 0.0))
  {
    itkGenericExceptionMacro("SampleImplicitSurface: spacing must be positive, got " << spacing << '.');
  }
  ImplicitSurfaceFunction::InputType lower;
  ImplicitSurfaceFunction::InputType upper;
  surface.GetBounds(lower, upper);
  for (unsigned int d = 0; d < 3; ++d)
  {
    if (clip != nullptr)
    {
      lower[d] = std::max(lower[d], clip->lower[d]);
      upper[d] = std::min(upper[d], clip->upper[d]);
    }
    if (!std::isfinite(lower[d]) || !std::isfinite(upper[d]))
    {
      itkGenericExceptionMacro("SampleImplicitSurface: the surface " << surface.GetNameOfClass()
                                                                     << " is unbounded; give a clipping box.");
    }
    if (lower[d] > upper[d])
    {
      return {};
    }
  }
  constexpr unsigned int Block = 8; // coarse cells of Block^3 fine grid points
  const double           halfDiagonal = 0.5 * std::sqrt(3.0) * spacing;
  std::size_t            count[3];
  for (unsigned int d = 0; d < 3; ++d)
  {
    count[d] = static_cast<std::size_t>(std::ceil((upper[d] - lower[d]) / spacing)) + 3;
  }
  const std::size_t              blocks[3] = { (count[0] + Block - 1) / Block,
                                               (count[1] + Block - 1) / Block,
                                               (count[2] + Block - 1) / Block };
  const std::size_t              numberOfBlocks = blocks[0] * blocks[1] * blocks[2];
  std::vector<std::vector<Vec3>> found(numberOfBlocks);
  ParallelForBlocks(numberOfBlocks, 16, [&](std::size_t begin, std::size_t end, std::size_t) {
    ImplicitSurfaceFunction::InputType p;
    for (std::size_t b = begin; b < end; ++b)
    {
      const std::size_t bi[3] = { b % blocks[0], (b / blocks[0]) % blocks[1], b / (blocks[0] * blocks[1]) };
      // Skip a coarse cell that cannot hold a fine point within halfDiagonal of the surface.
      for (unsigned int d = 0; d < 3; ++d)
      {
        p[d] = lower[d] - spacing + (bi[d] * Block + 0.5 * (Block - 1)) * spacing;
      }
      const double cellRadius = 0.5 * std::sqrt(3.0) * (Block - 1) * spacing;
      if (std::abs(surface.Evaluate(p)) > cellRadius + halfDiagonal)
      {
        continue;
      }
      for (unsigned int k = 0; k < Block; ++k)
      {
        for (unsigned int j = 0; j < Block; ++j)
        {
          for (unsigned int i = 0; i < Block; ++i)
          {
            const std::size_t g[3] = { bi[0] * Block + i, bi[1] * Block + j, bi[2] * Block + k };
            if (g[0] >= count[0] || g[1] >= count[1] || g[2] >= count[2])
            {
              continue;
            }
            for (unsigned int d = 0; d < 3; ++d)
            {
              p[d] = lower[d] - spacing + g[d] * spacing;
            }
            if (std::abs(surface.Evaluate(p)) <= halfDiagonal)
            {
              const Vec3 q = ToVec3(surface.ClosestSurfacePoint(p));
              if (clip == nullptr || (clip->lower[0] <= q[0] && q[0] <= clip->upper[0] && clip->lower[1] <= q[1] &&
                                      q[1] <= clip->upper[1] && clip->lower[2] <= q[2] && q[2] <= clip->upper[2]))
              {
                found[b].push_back(q);
              }
            }
          }
        }
      }
    }
  });
  std::vector<Vec3> samples;
  for (const auto & f : found)
  {
    samples.insert(samples.end(), f.begin(), f.end());
  }
  return samples;
}

MeshSurfaceDistanceReport
ComputeSurfaceDistances(const IndexedTriangleMesh &     mesh,
                        const IndexedTriangleMesh *     referenceMesh,
                        const ImplicitSurfaceFunction * referenceSurface,
                        const SurfaceDistanceOptions &  options,
                        std::vector<double> *           vertexDistances,
                        std::vector<double> *           centroidDistances)
{
  if (referenceMesh == nullptr && referenceSurface == nullptr)
  {
    itkGenericExceptionMacro("MeshSurfaceDistanceCalculator: no reference: set a reference mesh or a reference "
                             "surface.");
  }
  if (mesh.triangles.empty())
  {
    itkGenericExceptionMacro("MeshSurfaceDistanceCalculator: the mesh has no triangles.");
  }
  const unsigned int        workUnits = options.numberOfWorkUnits;
  MeshSurfaceDistanceReport report;
  const std::vector<Vec3>   samples = SampleTriangles(mesh, options.samplingLevel);
  const std::size_t         numberOfVertices = mesh.points.size();
  const std::size_t         numberOfTriangles = mesh.triangles.size();

  std::vector<double> unsignedDistances;
  std::vector<double> signedDistances;
  TriangleAABBTree    referenceTree;
  if (referenceMesh != nullptr)
  {
    if (referenceMesh->triangles.empty())
    {
      itkGenericExceptionMacro("MeshSurfaceDistanceCalculator: the reference mesh has no triangles.");
    }
    report.referenceDescription = "reference mesh";
    referenceTree.Build(*referenceMesh);
    unsignedDistances = DistancesToTriangles(samples, referenceTree, workUnits);
  }
  else
  {
    report.referenceDescription = std::string("implicit surface (") + referenceSurface->GetNameOfClass() + ")";
    signedDistances = SignedDistancesToSurface(samples, *referenceSurface, workUnits);
    unsignedDistances.resize(signedDistances.size());
    for (std::size_t i = 0; i < signedDistances.size(); ++i)
    {
      unsignedDistances[i] = std::abs(signedDistances[i]);
    }
  }
  const bool haveSign = !signedDistances.empty();
  // Sample layout: vertices, then per triangle its centroid followed by lattice points.
  const std::size_t perTriangle =
    options.samplingLevel == 0 ? 1 : 1 + ((options.samplingLevel + 2) * (options.samplingLevel + 3)) / 2 - 3;
  std::vector<double> v(unsignedDistances.begin(), unsignedDistances.begin() + numberOfVertices);
  std::vector<double> c(numberOfTriangles);
  std::vector<double> vs;
  std::vector<double> cs;
  if (haveSign)
  {
    vs.assign(signedDistances.begin(), signedDistances.begin() + numberOfVertices);
    cs.resize(numberOfTriangles);
  }
  for (std::size_t f = 0; f < numberOfTriangles; ++f)
  {
    c[f] = unsignedDistances[numberOfVertices + f * perTriangle];
    if (haveSign)
    {
      cs[f] = signedDistances[numberOfVertices + f * perTriangle];
    }
  }
  report.vertices = ComputeDistanceStatistics(v, haveSign ? &vs : nullptr);
  report.faceCentroids = ComputeDistanceStatistics(c, haveSign ? &cs : nullptr);
  report.meshSamples = ComputeDistanceStatistics(unsignedDistances, haveSign ? &signedDistances : nullptr);
  report.hausdorff = report.meshSamples.maximum;
  if (vertexDistances)
  {
    *vertexDistances = haveSign ? vs : v;
  }
  if (centroidDistances)
  {
    *centroidDistances = haveSign ? cs : c;
  }

  if (options.symmetric)
  {
    std::vector<Vec3> referenceSamples;
    if (referenceMesh != nullptr)
    {
      referenceSamples = SampleTriangles(*referenceMesh, options.samplingLevel);
    }
    else
    {
      double spacing = options.implicitSampleSpacing;
      if (!(spacing > 0.0))
      {
        double sum = 0.0;
        for (const auto & t : mesh.triangles)
        {
          sum += Norm(mesh.points[t[0]] - mesh.points[t[1]]) + Norm(mesh.points[t[1]] - mesh.points[t[2]]) +
                 Norm(mesh.points[t[2]] - mesh.points[t[0]]);
        }
        spacing = 0.5 * sum / (3.0 * numberOfTriangles);
      }
      // An unbounded reference (a plane) is compared over the mesh's extent only.
      ImplicitSurfaceFunction::InputType lower;
      ImplicitSurfaceFunction::InputType upper;
      referenceSurface->GetBounds(lower, upper);
      const bool     unbounded = !(std::isfinite(lower[0]) && std::isfinite(lower[1]) && std::isfinite(lower[2]) &&
                               std::isfinite(upper[0]) && std::isfinite(upper[1]) && std::isfinite(upper[2]));
      AxisAlignedBox meshBox;
      for (const auto & p : mesh.points)
      {
        meshBox.Add(p);
      }
      if (unbounded)
      {
        report.referenceDescription += ", clipped to the mesh's bounding box";
      }
      referenceSamples = SampleImplicitSurface(*referenceSurface, spacing, unbounded ? &meshBox : nullptr);
    }
    TriangleAABBTree meshTree;
    meshTree.Build(mesh);
    const std::vector<double> reverse = DistancesToTriangles(referenceSamples, meshTree, workUnits);
    report.referenceSamples = ComputeDistanceStatistics(reverse);
    report.hausdorff = std::max(report.hausdorff, report.referenceSamples.maximum);
    report.symmetric = true;
  }
  return report;
}

void
MeshSurfaceDistanceReport::Print(std::ostream & os, const std::string & title) const
{
  const auto flags = os.flags();
  const auto precision = os.precision();
  if (!title.empty())
  {
    os << title << '\n';
  }
  os << "  distance to " << referenceDescription << '\n';
  os << "  " << std::left << std::setw(24) << "from" << std::right << std::setw(10) << "count" << std::setw(14)
     << "mean" << std::setw(14) << "rms" << std::setw(14) << "max" << std::setw(14) << "signed mean" << '\n';
  auto row = [&os](const char * name, const DistanceStatistics & s) {
    os << "  " << std::left << std::setw(24) << name << std::right << std::setw(10) << s.count << std::scientific
       << std::setprecision(4) << std::setw(14) << s.mean << std::setw(14) << s.rms << std::setw(14) << s.maximum
       << std::setw(14) << s.signedMean << std::defaultfloat << '\n';
  };
  row("vertices", vertices);
  row("face centroids", faceCentroids);
  row("mesh samples", meshSamples);
  if (symmetric)
  {
    row("reference samples", referenceSamples);
  }
  os << "  " << (symmetric ? "symmetric" : "one-sided") << " Hausdorff distance " << std::setprecision(6) << hausdorff
     << '\n';
  os.flags(flags);
  os.precision(precision);
}

void
MeshSurfaceDistanceReport::PrintJSON(std::ostream & os) const
{
  const auto precision = os.precision();
  os << std::setprecision(10);
  auto stats = [&os](const DistanceStatistics & s) {
    os << "{\"count\": " << s.count << ", \"mean\": " << JSONNumber{ s.mean } << ", \"rms\": " << JSONNumber{ s.rms }
       << ", \"max\": " << JSONNumber{ s.maximum } << ", \"signed_mean\": " << JSONNumber{ s.signedMean } << "}";
  };
  os << "{\"reference\": " << JSONString{ referenceDescription } << ", \"vertices\": ";
  stats(vertices);
  os << ", \"face_centroids\": ";
  stats(faceCentroids);
  os << ", \"mesh_samples\": ";
  stats(meshSamples);
  os << ", \"reference_samples\": ";
  stats(referenceSamples);
  os << ", \"hausdorff\": " << JSONNumber{ hausdorff } << ", \"symmetric\": " << (symmetric ? "true" : "false") << "}";
  os.precision(precision);
}

} // namespace MeshExtraction
} // namespace itk
