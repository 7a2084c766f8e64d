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
#include "itkMeshExtractionQualityAnalysis.h"
#include "itkMeshExtractionParallel.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
namespace
{
constexpr double RadiansToDegrees = 180.0 / itk::Math::pi;

/** Linearly interpolated percentile; partially reorders `values` (nth_element). */
double
Percentile(std::vector<double> & values, double fraction)
{
  if (values.empty())
  {
    return 0.0;
  }
  const double position = fraction * static_cast<double>(values.size() - 1);
  const auto   lower = static_cast<std::size_t>(std::floor(position));
  std::nth_element(values.begin(), values.begin() + lower, values.end());
  const double low = values[lower];
  if (lower + 1 >= values.size())
  {
    return low;
  }
  const double high = *std::min_element(values.begin() + lower + 1, values.end());
  const double w = position - static_cast<double>(lower);
  return (1.0 - w) * low + w * high;
}

} // namespace

ValueStatistics
ComputeValueStatistics(std::vector<double> values, double lower, double upper, unsigned int bins)
{
  ValueStatistics s;
  s.histogramLower = lower;
  s.histogramUpper = upper;
  s.histogram.assign(bins, 0);
  s.count = values.size();
  if (values.empty())
  {
    return s;
  }
  const double width = (upper - lower) / bins;
  double       sum = 0.0;
  for (double v : values)
  {
    sum += v;
    long bin = width > 0.0 ? static_cast<long>(std::floor((v - lower) / width)) : 0;
    bin = std::clamp<long>(bin, 0, static_cast<long>(bins) - 1);
    ++s.histogram[static_cast<std::size_t>(bin)];
  }
  s.mean = sum / static_cast<double>(values.size());
  const auto range = std::minmax_element(values.begin(), values.end());
  s.minimum = *range.first;
  s.maximum = *range.second;
  s.percentile01 = Percentile(values, 0.01);
  s.percentile05 = Percentile(values, 0.05);
  s.median = Percentile(values, 0.5);
  s.percentile95 = Percentile(values, 0.95);
  return s;
}


namespace
{
/** Throws unless `reference` has the points and triangles of `mesh` by index. */
void
CheckSameConnectivity(const IndexedTriangleMesh & mesh, const IndexedTriangleMesh & reference)
{
  if (reference.points.size() != mesh.points.size() || reference.triangles != mesh.triangles)
  {
    itkGenericExceptionMacro("TriangleMeshQualityCalculator: the reference mesh must have the same connectivity as "
                             "the mesh (it has "
                             << reference.points.size() << " points and " << reference.triangles.size()
                             << " triangles, the mesh " << mesh.points.size() << " and " << mesh.triangles.size()
                             << ", or the triangles differ).");
  }
}

/** MeasureTriangle for every triangle, on the work units. */
void
MeasureAllTriangles(const IndexedTriangleMesh & mesh, std::vector<TriangleMeasures> & m)
{
  m.resize(mesh.triangles.size());
  ParallelForBlocks(mesh.triangles.size(), 8192, [&](std::size_t begin, std::size_t end, std::size_t) {
    for (std::size_t f = begin; f < end; ++f)
    {
      const auto & t = mesh.triangles[f];
      m[f] = MeasureTriangle(mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]]);
    }
  });
}

/** The shape statistics of the triangles (the q's and the angles, with their
 * histograms), the share of q_angle < 0.3, the degenerate triangles and the area. */
void
SummariseTriangleShapes(const std::vector<TriangleMeasures> & m,
                        double                                degenerateQAreaTolerance,
                        TriangleMeshQualityReport &           r)
{
  const std::size_t   numberOfTriangles = m.size();
  std::vector<double> qLength(numberOfTriangles);
  std::vector<double> qAngle(numberOfTriangles);
  std::vector<double> qArea(numberOfTriangles);
  std::vector<double> minAngle(numberOfTriangles);
  std::vector<double> maxAngle(numberOfTriangles);
  std::size_t         below03 = 0;
  for (std::size_t f = 0; f < numberOfTriangles; ++f)
  {
    qLength[f] = m[f].qLength;
    qAngle[f] = m[f].qAngle;
    qArea[f] = m[f].qArea;
    minAngle[f] = m[f].minAngle * RadiansToDegrees;
    maxAngle[f] = m[f].maxAngle * RadiansToDegrees;
    below03 += m[f].qAngle < 0.3 ? 1 : 0;
    r.degenerateTriangles += m[f].qArea <= degenerateQAreaTolerance ? 1 : 0;
    r.totalArea += m[f].area;
  }
  r.fractionQAngleBelow03 = numberOfTriangles ? static_cast<double>(below03) / numberOfTriangles : 0.0;
  r.qLength = ComputeValueStatistics(std::move(qLength));
  r.qAngle = ComputeValueStatistics(std::move(qAngle));
  r.qArea = ComputeValueStatistics(std::move(qArea));
  r.minimumAngle = ComputeValueStatistics(std::move(minAngle), 0.0, 60.0, 12);
  r.maximumAngle = ComputeValueStatistics(std::move(maxAngle), 60.0, 180.0, 12);
}

/** The statistics of the edge lengths, histogram on [0, longest edge]. */
ValueStatistics
EdgeLengthStatistics(const IndexedTriangleMesh & mesh, const MeshTopology & topo)
{
  std::vector<double> lengths(topo.edges.size());
  double              longest = 0.0;
  for (std::size_t e = 0; e < topo.edges.size(); ++e)
  {
    lengths[e] = Norm(mesh.points[topo.edges[e].a] - mesh.points[topo.edges[e].b]);
    longest = std::max(longest, lengths[e]);
  }
  return ComputeValueStatistics(std::move(lengths), 0.0, longest > 0.0 ? longest : 1.0, 10);
}

/** Smoothness |2 pi - sum of incident angles| of the interior vertices (thesis
 * section 3.3): their mean and number, and each vertex's value if asked for. */
void
SummariseSmoothness(const IndexedTriangleMesh &           mesh,
                    const MeshTopology &                  topo,
                    const std::vector<TriangleMeasures> & m,
                    TriangleMeshQualityReport &           r,
                    std::vector<double> *                 vertexSmoothness)
{
  std::vector<double> angleSum(mesh.points.size(), 0.0);
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f)
  {
    for (unsigned int k = 0; k < 3; ++k)
    {
      angleSum[mesh.triangles[f][k]] += m[f].angle[k];
    }
  }
  if (vertexSmoothness)
  {
    vertexSmoothness->assign(mesh.points.size(), 0.0);
  }
  double sum = 0.0;
  for (std::size_t v = 0; v < mesh.points.size(); ++v)
  {
    if (topo.vertexIsInterior[v])
    {
      const double s = std::abs(2.0 * itk::Math::pi - angleSum[v]);
      sum += s;
      ++r.numberOfInteriorVertices;
      if (vertexSmoothness)
      {
        (*vertexSmoothness)[v] = s;
      }
    }
  }
  r.meanSmoothness = r.numberOfInteriorVertices ? sum / r.numberOfInteriorVertices : 0.0;
}

/** The valence histogram of the referenced vertices and their share of valence 6. */
void
SummariseValences(const MeshTopology & topo, std::size_t numberOfPoints, TriangleMeshQualityReport & r)
{
  std::size_t valence6 = 0;
  for (std::size_t v = 0; v < numberOfPoints; ++v)
  {
    const std::size_t d = topo.vertexEdgeOffsets[v + 1] - topo.vertexEdgeOffsets[v];
    if (d == 0 && topo.vertexTriangleOffsets[v + 1] == topo.vertexTriangleOffsets[v])
    {
      continue;
    }
    if (r.valenceHistogram.size() <= d)
    {
      r.valenceHistogram.resize(d + 1, 0);
    }
    ++r.valenceHistogram[d];
    valence6 += d == 6 ? 1 : 0;
  }
  r.fractionValence6 =
    topo.numberOfReferencedVertices ? static_cast<double>(valence6) / topo.numberOfReferencedVertices : 0.0;
}

/** Sum over the components of (2 - chi - b) / 2, chi the component's Euler
 * characteristic and b its boundary loops (for a manifold, oriented mesh). */
std::int64_t
Genus(const MeshTopology & topo, std::size_t numberOfPoints, std::size_t numberOfTriangles)
{
  std::vector<std::int64_t> chi(topo.numberOfComponents, 0);
  for (std::size_t v = 0; v < numberOfPoints; ++v)
  {
    if (topo.vertexTriangleOffsets[v + 1] > topo.vertexTriangleOffsets[v])
    {
      ++chi[topo.triangleComponent[topo.vertexTriangles[topo.vertexTriangleOffsets[v]]]];
    }
  }
  for (const auto & e : topo.edges)
  {
    --chi[topo.triangleComponent[topo.incidences[e.firstIncidence].triangle]];
  }
  for (std::size_t f = 0; f < numberOfTriangles; ++f)
  {
    ++chi[topo.triangleComponent[f]];
  }
  std::int64_t genus = 0;
  for (std::size_t c = 0; c < topo.numberOfComponents; ++c)
  {
    genus += (2 - chi[c] - static_cast<std::int64_t>(topo.componentBoundaryLoops[c])) / 2;
  }
  return genus;
}

/** Integrity from the topology: non-manifold, boundary and inconsistent edges,
 * non-manifold vertices, boundary loops, components, Euler characteristic and (for
 * a manifold, consistently oriented mesh) the genus. */
void
SummariseTopology(const MeshTopology &        topo,
                  std::size_t                 numberOfPoints,
                  std::size_t                 numberOfTriangles,
                  TriangleMeshQualityReport & r)
{
  r.nonManifoldEdges = static_cast<std::int64_t>(topo.numberOfNonManifoldEdges);
  r.nonManifoldVertices = static_cast<std::int64_t>(topo.numberOfNonManifoldVertices);
  r.boundaryEdges = static_cast<std::int64_t>(topo.numberOfBoundaryEdges);
  r.boundaryLoops = static_cast<std::int64_t>(topo.numberOfBoundaryLoops);
  r.inconsistentlyOrientedEdges = static_cast<std::int64_t>(topo.numberOfInconsistentEdges);
  r.connectedComponents = static_cast<std::int64_t>(topo.numberOfComponents);
  r.eulerCharacteristic = static_cast<std::int64_t>(topo.numberOfReferencedVertices) -
                          static_cast<std::int64_t>(topo.edges.size()) + static_cast<std::int64_t>(numberOfTriangles);
  if (r.IsManifold() && r.IsConsistentlyOriented() && numberOfTriangles > 0)
  {
    r.genus = Genus(topo, numberOfPoints, numberOfTriangles);
  }
}

/** Signed volume by the divergence theorem, summed over the triangles in order. */
double
EnclosedVolume(const IndexedTriangleMesh & mesh)
{
  double volume = 0.0;
  for (const auto & t : mesh.triangles)
  {
    volume += Dot(mesh.points[t[0]], Cross(mesh.points[t[1]], mesh.points[t[2]])) / 6.0;
  }
  return volume;
}

/** Non-degenerate triangles whose normal turned by 90 degrees or more against
 * `reference` (same connectivity). */
std::int64_t
CountInvertedVersusReference(const IndexedTriangleMesh &           mesh,
                             const IndexedTriangleMesh &           reference,
                             const std::vector<TriangleMeasures> & m,
                             double                                degenerateQAreaTolerance)
{
  std::int64_t inverted = 0;
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f)
  {
    const auto & t = mesh.triangles[f];
    if (m[f].qArea <= degenerateQAreaTolerance)
    {
      continue;
    }
    const Vec3 n = TriangleNormal(mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]]);
    const Vec3 nr = TriangleNormal(reference.points[t[0]], reference.points[t[1]], reference.points[t[2]]);
    inverted += Dot(n, nr) <= 0.0 ? 1 : 0;
  }
  return inverted;
}

/** Non-degenerate triangles of a closed mesh that face into the enclosed volume, and
 * those whose side the rays could not tell (ClassifyTriangleOrientation). */
void
CountInvertedVersusOutward(const IndexedTriangleMesh &           mesh,
                           const std::vector<TriangleMeasures> & m,
                           double                                degenerateQAreaTolerance,
                           TriangleMeshQualityReport &           r)
{
  const std::vector<int> side = ClassifyTriangleOrientation(mesh, degenerateQAreaTolerance);
  r.invertedTrianglesVersusOutward = 0;
  r.undeterminedOrientationTriangles = 0;
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f)
  {
    if (m[f].qArea <= degenerateQAreaTolerance)
    {
      continue;
    }
    r.invertedTrianglesVersusOutward += side[f] < 0 ? 1 : 0;
    r.undeterminedOrientationTriangles += side[f] == 0 ? 1 : 0;
  }
}

/** The self-intersecting pairs (FindSelfIntersections), the triangles in them, and
 * the first few pairs for inspection. */
void
SummariseSelfIntersections(const IndexedTriangleMesh & mesh,
                           std::size_t                 maximumReportedIntersections,
                           TriangleMeshQualityReport & r)
{
  const auto        pairs = FindSelfIntersections(mesh);
  std::vector<bool> involved(mesh.triangles.size(), false);
  for (const auto & p : pairs)
  {
    involved[p.first] = true;
    involved[p.second] = true;
  }
  r.selfIntersectingPairs = static_cast<std::int64_t>(pairs.size());
  r.selfIntersectingTriangles = std::count(involved.begin(), involved.end(), true);
  r.intersectingPairs.assign(pairs.begin(), pairs.begin() + std::min(pairs.size(), maximumReportedIntersections));
}
} // namespace

TriangleMeshQualityReport
AnalyzeTriangleMesh(const IndexedTriangleMesh &        mesh,
                    const TriangleMeshQualityOptions & options,
                    const IndexedTriangleMesh *        reference,
                    std::vector<TriangleMeasures> *    measuresOut,
                    std::vector<double> *              vertexSmoothness)
{
  TriangleMeshQualityReport r;
  const std::size_t         numberOfTriangles = mesh.triangles.size();
  r.numberOfPoints = mesh.points.size();
  r.numberOfTriangles = numberOfTriangles;
  r.numberOfSplitQuads = mesh.numberOfSplitQuads;
  if (reference != nullptr)
  {
    CheckSameConnectivity(mesh, *reference);
  }
  const double tolerance = options.degenerateQAreaTolerance;

  // Per-triangle measures, then their statistics and histograms.
  std::vector<TriangleMeasures>   localMeasures;
  std::vector<TriangleMeasures> & m = measuresOut ? *measuresOut : localMeasures;
  MeasureAllTriangles(mesh, m);
  const MeshTopology topo = BuildMeshTopology(mesh);
  r.numberOfEdges = topo.edges.size();
  r.numberOfReferencedPoints = topo.numberOfReferencedVertices;
  r.unreferencedPoints = static_cast<std::int64_t>(mesh.points.size() - topo.numberOfReferencedVertices);
  SummariseTriangleShapes(m, tolerance, r);
  r.edgeLength = EdgeLengthStatistics(mesh, topo);

  // Vertices.
  SummariseSmoothness(mesh, topo, m, r, vertexSmoothness);
  SummariseValences(topo, mesh.points.size(), r);

  // Integrity: edges, components, Euler characteristic; volume; orientation;
  // self-intersections.
  SummariseTopology(topo, mesh.points.size(), numberOfTriangles, r);
  r.enclosedVolume = EnclosedVolume(mesh);
  if (reference != nullptr)
  {
    r.invertedTrianglesVersusReference = CountInvertedVersusReference(mesh, *reference, m, tolerance);
  }
  if (options.computeOutwardOrientation && r.IsClosed())
  {
    CountInvertedVersusOutward(mesh, m, tolerance, r);
  }
  if (options.computeSelfIntersections)
  {
    SummariseSelfIntersections(mesh, options.maximumReportedIntersections, r);
  }
  return r;
}

} // namespace detail
} // namespace MeshExtraction
} // namespace itk
