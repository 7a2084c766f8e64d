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
#include "itkMeshExtractionScaleSpaceEdgeDetector.h"

#include <cmath>
#include <sstream>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
std::string
DescribeInvalidEdgeDetectionParameters(const ScaleSpaceEdgeDetectionParameters & p)
{
  std::ostringstream s;
  if (!(p.maximumDeviation > 0.0) || !std::isfinite(p.maximumDeviation))
  {
    s << "MaximumDeviation must be a positive, finite distance in mm (the capture range of the edge detector), got "
      << p.maximumDeviation;
  }
  else if (!(p.minimumScale >= 0.0) || !std::isfinite(p.minimumScale))
  {
    s << "MinimumScale must be >= 0 mm (0: the voxel length), got " << p.minimumScale;
  }
  else if (p.scalesPerOctave == 0)
  {
    s << "NumberOfScalesPerOctave must be >= 1, got 0";
  }
  else if (const double scales = p.minimumScale > 0.0 && p.maximumDeviation > p.minimumScale
                                   ? 1.0 + p.scalesPerOctave * std::log2(p.maximumDeviation / p.minimumScale)
                                   : 1.0;
           scales > MaximumNumberOfEdgeDetectionScales)
  {
    // Each scale is a blurred copy of the image: a bound on the work one setting can ask for.
    s << "the scales from MaximumDeviation " << p.maximumDeviation << " mm down to MinimumScale " << p.minimumScale
      << " mm at " << p.scalesPerOctave << " per octave would be " << std::ceil(scales) << " blurred images; at most "
      << MaximumNumberOfEdgeDetectionScales << " (raise MinimumScale or lower NumberOfScalesPerOctave)";
  }
  else if (!(p.degenerateQAreaTolerance >= 0.0 && p.degenerateQAreaTolerance < 1.0))
  {
    s << "DegenerateQAreaTolerance must be in [0, 1), got " << p.degenerateQAreaTolerance;
  }
  else if (p.searchDirection != MeshExtractionEnums::EdgeSearchDirection::ImageGradient &&
           p.searchDirection != MeshExtractionEnums::EdgeSearchDirection::VertexNormal)
  {
    s << "Unknown SearchDirection " << static_cast<int>(p.searchDirection);
  }
  return s.str();
}

std::vector<Vec3>
VertexNormalSums(const IndexedTriangleMesh & mesh)
{
  std::vector<Vec3> normals(mesh.points.size(), Vec3(0.0));
  for (const auto & t : mesh.triangles)
  {
    const Vec3 normal = TriangleNormal(mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]]);
    for (const auto v : t)
    {
      normals[v] += normal;
    }
  }
  return normals;
}

void
TriangleCentroidsAndNormals(const std::vector<Vec3> &            points,
                            const std::vector<TriangleIndices> & triangles,
                            std::vector<Vec3> &                  centroids,
                            std::vector<Vec3> &                  normals)
{
  centroids.clear();
  normals.clear();
  centroids.reserve(triangles.size());
  normals.reserve(triangles.size());
  for (const auto & t : triangles)
  {
    centroids.push_back(TriangleCentroid(points[t[0]], points[t[1]], points[t[2]]));
    normals.push_back(TriangleNormal(points[t[0]], points[t[1]], points[t[2]]));
  }
}

bool
IsValidEdgeDetectionMove(const IndexedTriangleMesh & mesh,
                         const MeshTopology &        topology,
                         const std::vector<Vec3> &   startPositions,
                         std::size_t                 v,
                         const Vec3 &                candidate,
                         double                      tolerance)
{
  const auto & x = mesh.points;
  for (std::uint32_t k = topology.vertexTriangleOffsets[v]; k < topology.vertexTriangleOffsets[v + 1]; ++k)
  {
    const auto & t = mesh.triangles[topology.vertexTriangles[k]];
    Vec3         now[3];
    Vec3         moved[3];
    Vec3         then[3];
    for (unsigned int c = 0; c < 3; ++c)
    {
      now[c] = x[t[c]];
      moved[c] = t[c] == v ? candidate : x[t[c]];
      then[c] = startPositions[t[c]];
    }
    const Vec3   oldNormal = TriangleNormal(now[0], now[1], now[2]);
    const Vec3   newNormal = TriangleNormal(moved[0], moved[1], moved[2]);
    const double oldQ = TriangleQArea(now[0], now[1], now[2]);
    const double newQ = TriangleQArea(moved[0], moved[1], moved[2]);
    if (oldQ > 0.0 && !(Dot(oldNormal, newNormal) > 0.0))
    {
      return false;
    }
    if (oldQ > tolerance ? !(newQ > tolerance) : !(newQ >= oldQ))
    {
      return false;
    }
    if (TriangleQArea(then[0], then[1], then[2]) > 0.0 &&
        !(Dot(TriangleNormal(then[0], then[1], then[2]), newNormal) > 0.0))
    {
      return false;
    }
  }
  return true;
}

} // namespace detail
} // namespace MeshExtraction
} // namespace itk
