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
#include "itkMeshExtractionParallel.h"

#include <cmath>

namespace itk
{
namespace MeshExtraction
{
namespace detail
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

namespace
{
/** Fine grid points per axis of a coarse block of SampleImplicitSurface. */
constexpr unsigned int SampleBlockSize = 8;

bool
Contains(const AxisAlignedBox & box, const Vec3 & q)
{
  return box.lower[0] <= q[0] && q[0] <= box.upper[0] && box.lower[1] <= q[1] && q[1] <= box.upper[1] &&
         box.lower[2] <= q[2] && q[2] <= box.upper[2];
}

/** The surface's bounds, clipped to `clip` if given; false if nothing is left. Throws
 * if the bounds are not finite. */
bool
ClippedSurfaceBounds(const ImplicitSurfaceFunction &      surface,
                     const AxisAlignedBox *               clip,
                     ImplicitSurfaceFunction::InputType & lower,
                     ImplicitSurfaceFunction::InputType & upper)
{
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
      return false;
    }
  }
  return true;
}

/** The fine grid of SampleImplicitSurface: points lower - spacing + g spacing, g < count. */
struct SampleGrid
{
  ImplicitSurfaceFunction::InputType lower;
  double                             spacing;
  std::size_t                        count[3];
};

/** Appends to `found` the samples of the coarse block `bi` of the grid: its grid points
 * within half a cell diagonal of the surface, projected onto it (and kept if inside
 * `clip`). A block whose centre is too far from the surface for any of its points is
 * skipped with one evaluation. */
void
SampleBlock(const ImplicitSurfaceFunction & surface,
            const SampleGrid &              grid,
            const std::size_t               bi[3],
            const AxisAlignedBox *          clip,
            std::vector<Vec3> &             found)
{
  constexpr unsigned int             Block = SampleBlockSize;
  const double                       spacing = grid.spacing;
  const double                       halfDiagonal = 0.5 * std::sqrt(3.0) * spacing;
  ImplicitSurfaceFunction::InputType p;
  for (unsigned int d = 0; d < 3; ++d)
  {
    p[d] = grid.lower[d] - spacing + (bi[d] * Block + 0.5 * (Block - 1)) * spacing;
  }
  const double cellRadius = 0.5 * std::sqrt(3.0) * (Block - 1) * spacing;
  if (std::abs(surface.Evaluate(p)) > cellRadius + halfDiagonal)
  {
    return;
  }
  for (unsigned int k = 0; k < Block; ++k)
  {
    for (unsigned int j = 0; j < Block; ++j)
    {
      for (unsigned int i = 0; i < Block; ++i)
      {
        const std::size_t g[3] = { bi[0] * Block + i, bi[1] * Block + j, bi[2] * Block + k };
        if (g[0] >= grid.count[0] || g[1] >= grid.count[1] || g[2] >= grid.count[2])
        {
          continue;
        }
        for (unsigned int d = 0; d < 3; ++d)
        {
          p[d] = grid.lower[d] - spacing + g[d] * spacing;
        }
        if (std::abs(surface.Evaluate(p)) <= halfDiagonal)
        {
          const Vec3 q = ToVec3(surface.ClosestSurfacePoint(p));
          if (clip == nullptr || Contains(*clip, q))
          {
            found.push_back(q);
          }
        }
      }
    }
  }
}
} // namespace

std::vector<Vec3>
SampleImplicitSurface(const ImplicitSurfaceFunction & surface, double spacing, const AxisAlignedBox * clip)
{
  if (!(spacing > 0.0))
  {
    itkGenericExceptionMacro("SampleImplicitSurface: spacing must be positive, got " << spacing << '.');
  }
  SampleGrid                         grid;
  ImplicitSurfaceFunction::InputType upper;
  if (!ClippedSurfaceBounds(surface, clip, grid.lower, upper))
  {
    return {};
  }
  grid.spacing = spacing;
  for (unsigned int d = 0; d < 3; ++d)
  {
    grid.count[d] = static_cast<std::size_t>(std::ceil((upper[d] - grid.lower[d]) / spacing)) + 3;
  }
  // Coarse blocks of SampleBlockSize^3 grid points, on the work units; the samples
  // in block order.
  constexpr unsigned int         Block = SampleBlockSize;
  const std::size_t              blocks[3] = { (grid.count[0] + Block - 1) / Block,
                                               (grid.count[1] + Block - 1) / Block,
                                               (grid.count[2] + Block - 1) / Block };
  const std::size_t              numberOfBlocks = blocks[0] * blocks[1] * blocks[2];
  std::vector<std::vector<Vec3>> found(numberOfBlocks);
  ParallelForBlocks(numberOfBlocks, 16, [&](std::size_t begin, std::size_t end, std::size_t) {
    for (std::size_t b = begin; b < end; ++b)
    {
      const std::size_t bi[3] = { b % blocks[0], (b / blocks[0]) % blocks[1], b / (blocks[0] * blocks[1]) };
      SampleBlock(surface, grid, bi, clip, found[b]);
    }
  });
  std::vector<Vec3> samples;
  for (const auto & f : found)
  {
    samples.insert(samples.end(), f.begin(), f.end());
  }
  return samples;
}

namespace
{
/** The distances from `samples` to the reference: unsigned, and for an implicit
 * surface signed too (negative inside). Sets the report's description of the
 * reference. */
void
DistancesToReference(const std::vector<Vec3> &       samples,
                     const IndexedTriangleMesh *     referenceMesh,
                     const ImplicitSurfaceFunction * referenceSurface,
                     unsigned int                    workUnits,
                     MeshSurfaceDistanceReport &     report,
                     std::vector<double> &           unsignedDistances,
                     std::vector<double> &           signedDistances)
{
  if (referenceMesh != nullptr)
  {
    if (referenceMesh->triangles.empty())
    {
      itkGenericExceptionMacro("MeshSurfaceDistanceCalculator: the reference mesh has no triangles.");
    }
    report.referenceDescription = "reference mesh";
    TriangleAABBTree referenceTree;
    referenceTree.Build(*referenceMesh);
    unsignedDistances = DistancesToTriangles(samples, referenceTree, workUnits);
    return;
  }
  report.referenceDescription = std::string("implicit surface (") + referenceSurface->GetNameOfClass() + ")";
  signedDistances = SignedDistancesToSurface(samples, *referenceSurface, workUnits);
  unsignedDistances.resize(signedDistances.size());
  for (std::size_t i = 0; i < signedDistances.size(); ++i)
  {
    unsignedDistances[i] = std::abs(signedDistances[i]);
  }
}

/** The statistics of the mesh's vertices, centroids and all its samples from the
 * distances of SampleTriangles' samples (the vertices, then per triangle its centroid
 * followed by its lattice points), and the values of the vertices and centroids if
 * asked for (signed where known). */
void
SummariseMeshSamples(const IndexedTriangleMesh & mesh,
                     unsigned int                samplingLevel,
                     const std::vector<double> & unsignedDistances,
                     const std::vector<double> & signedDistances,
                     MeshSurfaceDistanceReport & report,
                     std::vector<double> *       vertexDistances,
                     std::vector<double> *       centroidDistances)
{
  const std::size_t   numberOfVertices = mesh.points.size();
  const std::size_t   numberOfTriangles = mesh.triangles.size();
  const bool          haveSign = !signedDistances.empty();
  const std::size_t   perTriangle = samplingLevel == 0 ? 1 : 1 + ((samplingLevel + 2) * (samplingLevel + 3)) / 2 - 3;
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
}

/** Half the mean length of the triangles' edges (each edge once per triangle). */
double
HalfMeanEdgeLength(const IndexedTriangleMesh & mesh)
{
  double sum = 0.0;
  for (const auto & t : mesh.triangles)
  {
    sum += Norm(mesh.points[t[0]] - mesh.points[t[1]]) + Norm(mesh.points[t[1]] - mesh.points[t[2]]) +
           Norm(mesh.points[t[2]] - mesh.points[t[0]]);
  }
  return 0.5 * sum / (3.0 * mesh.triangles.size());
}

/** Samples of an implicit reference for the reverse direction (SampleImplicitSurface
 * at `spacing`, 0: HalfMeanEdgeLength); an unbounded reference (a plane) is sampled
 * over the mesh's bounding box only, which the report's description says. */
std::vector<Vec3>
ImplicitReferenceSamples(const IndexedTriangleMesh &     mesh,
                         const ImplicitSurfaceFunction & referenceSurface,
                         double                          spacing,
                         MeshSurfaceDistanceReport &     report)
{
  if (!(spacing > 0.0))
  {
    spacing = HalfMeanEdgeLength(mesh);
  }
  ImplicitSurfaceFunction::InputType lower;
  ImplicitSurfaceFunction::InputType upper;
  referenceSurface.GetBounds(lower, upper);
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
  return SampleImplicitSurface(referenceSurface, spacing, unbounded ? &meshBox : nullptr);
}

/** The reverse direction: the distances from samples of the reference to the mesh,
 * and the symmetric Hausdorff distance. */
void
MeasureReverseDirection(const IndexedTriangleMesh &     mesh,
                        const IndexedTriangleMesh *     referenceMesh,
                        const ImplicitSurfaceFunction * referenceSurface,
                        const SurfaceDistanceOptions &  options,
                        MeshSurfaceDistanceReport &     report)
{
  const std::vector<Vec3> referenceSamples =
    referenceMesh != nullptr ? SampleTriangles(*referenceMesh, options.samplingLevel)
                             : ImplicitReferenceSamples(mesh, *referenceSurface, options.implicitSampleSpacing, report);
  TriangleAABBTree meshTree;
  meshTree.Build(mesh);
  const std::vector<double> reverse = DistancesToTriangles(referenceSamples, meshTree, options.numberOfWorkUnits);
  report.referenceSamples = ComputeDistanceStatistics(reverse);
  report.hausdorff = std::max(report.hausdorff, report.referenceSamples.maximum);
  report.symmetric = true;
}
} // namespace

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
  MeshSurfaceDistanceReport report;
  const std::vector<Vec3>   samples = SampleTriangles(mesh, options.samplingLevel);
  std::vector<double>       unsignedDistances;
  std::vector<double>       signedDistances;
  DistancesToReference(
    samples, referenceMesh, referenceSurface, options.numberOfWorkUnits, report, unsignedDistances, signedDistances);
  SummariseMeshSamples(
    mesh, options.samplingLevel, unsignedDistances, signedDistances, report, vertexDistances, centroidDistances);
  if (options.symmetric)
  {
    MeasureReverseDirection(mesh, referenceMesh, referenceSurface, options, report);
  }
  return report;
}

} // namespace detail
} // namespace MeshExtraction
} // namespace itk
