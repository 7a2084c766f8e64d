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
#include "itkMeshExtractionContourNetwork.h"
#include "itkMeshExtractionPredicates.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <utility>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
namespace
{
const char * const AxisNames[3] = { "x", "y", "z" };

std::string
PlaneName(unsigned int axis, std::int64_t position)
{
  std::ostringstream s;
  s << AxisNames[axis] << " = " << position;
  return s.str();
}

/** Rule 1: contours per axis, planes in the grid, four points each, none twice. */
std::string
CheckContourSet(const ContourNetwork & network)
{
  std::array<std::size_t, 3> perAxis{ { 0, 0, 0 } };
  for (std::size_t c = 0; c < network.contours.size(); ++c)
  {
    const Contour &    contour = network.contours[c];
    std::ostringstream s;
    if (contour.axis > 2)
    {
      s << "contour " << c << " has axis " << contour.axis << ", not 0, 1 or 2";
      return s.str();
    }
    if (contour.position < 0 || contour.position >= network.grid.size[contour.axis])
    {
      s << "contour " << c << " (" << PlaneName(contour.axis, contour.position) << ") lies outside the grid";
      return s.str();
    }
    if (contour.points.size() < 4)
    {
      s << "contour " << c << " (" << PlaneName(contour.axis, contour.position) << ") has " << contour.points.size()
        << " control points, fewer than 4";
      return s.str();
    }
    ++perAxis[contour.axis];
  }
  for (unsigned int a = 0; a < 3; ++a)
  {
    if (perAxis[a] == 0)
    {
      return std::string("the model has no contour in a plane ") + AxisNames[a] + " = constant";
    }
  }
  return std::string();
}

/** Rule 2 (after the membership BuildContourAdjacency checks): positions. */
std::string
CheckControlPointPositions(const ContourNetwork & network, const OccupiedContourPlanes & planes)
{
  for (std::uint32_t p = 0; p < network.points.size(); ++p)
  {
    const ContourControlPoint & point = network.points[p];
    std::ostringstream          s;
    for (const auto c : point.contours)
    {
      const Contour & contour = network.contours[c];
      if (point.x[contour.axis] != static_cast<double>(contour.position))
      {
        s << "control point " << p << " is not in the plane " << PlaneName(contour.axis, contour.position)
          << " of its contour " << c;
        return s.str();
      }
    }
    const unsigned int f = LineAxis(network, p);
    const double       x = point.x[f];
    if (!std::isfinite(x) || x < 0.0 || x > static_cast<double>(network.grid.size[f] - 1))
    {
      s << "control point " << p << " lies outside the grid (" << AxisNames[f] << " = " << x << ")";
      return s.str();
    }
    if (IsOccupied(planes, f, x))
    {
      s << "control point " << p << " lies in the plane " << AxisNames[f] << " = " << x
        << ", which holds a contour it is not on";
      return s.str();
    }
  }
  return std::string();
}

/** Rule 3: each contour crosses the other's plane at every control point. */
std::string
CheckTransversality(const ContourNetwork & network, const ContourAdjacency & adjacency)
{
  for (std::uint32_t p = 0; p < network.points.size(); ++p)
  {
    for (unsigned int s = 0; s < 2; ++s)
    {
      const Contour &     other = network.contours[network.points[p].contours[1 - s]];
      const double        plane = static_cast<double>(other.position);
      const std::uint32_t before = adjacency.Neighbour(network, p, s, -1);
      const std::uint32_t after = adjacency.Neighbour(network, p, s, +1);
      const double        a = network.points[before].x[other.axis] - plane;
      const double        b = network.points[after].x[other.axis] - plane;
      if (!(a * b < 0.0))
      {
        std::ostringstream m;
        m << "contour " << network.points[p].contours[s] << " does not cross the plane "
          << PlaneName(other.axis, other.position) << " at control point " << p << ": its neighbours " << before
          << " and " << after << " are not on either side";
        return m.str();
      }
    }
  }
  return std::string();
}

/** Rule 4: no segment passes a plane in use between its control points. */
std::string
CheckSegmentCrossings(const ContourNetwork & network, const OccupiedContourPlanes & planes)
{
  for (std::uint32_t c = 0; c < network.contours.size(); ++c)
  {
    const Contour &   contour = network.contours[c];
    const std::size_t n = contour.points.size();
    for (std::size_t k = 0; k < n; ++k)
    {
      const Vec3 & u = network.points[contour.points[k]].x;
      const Vec3 & v = network.points[contour.points[(k + 1) % n]].x;
      for (unsigned int b = 0; b < 3; ++b)
      {
        if (b == contour.axis)
        {
          continue;
        }
        const double lo = std::min(u[b], v[b]);
        const double hi = std::max(u[b], v[b]);
        const auto   first =
          std::upper_bound(planes[b].begin(), planes[b].end(), static_cast<std::int64_t>(std::floor(lo)));
        if (first != planes[b].end() && static_cast<double>(*first) > lo && static_cast<double>(*first) < hi)
        {
          std::ostringstream s;
          s << "the segment of contour " << c << " from control point " << contour.points[k] << " to "
            << contour.points[(k + 1) % n] << " crosses the plane " << PlaneName(b, *first)
            << " away from a control point";
          return s.str();
        }
      }
    }
  }
  return std::string();
}

/** Rule 5: control points on one line, and of one contour, in different voxels. */
std::string
CheckVoxelSeparation(const ContourNetwork & network, const ContourLines & lines)
{
  for (const auto & line : lines.lines)
  {
    for (std::size_t r = 1; r < line.size(); ++r)
    {
      if (VoxelOf(network.points[line[r - 1]].x) == VoxelOf(network.points[line[r]].x))
      {
        std::ostringstream s;
        s << "control points " << line[r - 1] << " and " << line[r]
          << " on one line lie in one voxel (a point may not reach or pass its neighbours on its line)";
        return s.str();
      }
    }
  }
  for (std::uint32_t c = 0; c < network.contours.size(); ++c)
  {
    std::vector<std::pair<ContourVoxel, std::uint32_t>> voxels;
    for (const auto p : network.contours[c].points)
    {
      voxels.emplace_back(VoxelOf(network.points[p].x), p);
    }
    std::sort(voxels.begin(), voxels.end());
    for (std::size_t i = 1; i < voxels.size(); ++i)
    {
      if (voxels[i - 1].first == voxels[i].first)
      {
        std::ostringstream s;
        s << "control points " << voxels[i - 1].second << " and " << voxels[i].second << " of contour " << c
          << " lie in one voxel";
        return s.str();
      }
    }
  }
  return std::string();
}

struct PlaneSegment
{
  double        a[2];
  double        b[2];
  std::uint32_t pa;
  std::uint32_t pb;
  std::uint32_t contour;
};

bool
OnSegment(const double a[2], const double b[2], const double p[2])
{
  return std::min(a[0], b[0]) <= p[0] && p[0] <= std::max(a[0], b[0]) && std::min(a[1], b[1]) <= p[1] &&
         p[1] <= std::max(a[1], b[1]);
}

/** Closed segments meet (exact orientations). */
bool
SegmentsMeet(const PlaneSegment & s, const PlaneSegment & t)
{
  const int d1 = Orient2D(s.a, s.b, t.a);
  const int d2 = Orient2D(s.a, s.b, t.b);
  const int d3 = Orient2D(t.a, t.b, s.a);
  const int d4 = Orient2D(t.a, t.b, s.b);
  if (d1 * d2 < 0 && d3 * d4 < 0)
  {
    return true;
  }
  return (d1 == 0 && OnSegment(s.a, s.b, t.a)) || (d2 == 0 && OnSegment(s.a, s.b, t.b)) ||
         (d3 == 0 && OnSegment(t.a, t.b, s.a)) || (d4 == 0 && OnSegment(t.a, t.b, s.b));
}

/** Rule 6: the contours of each plane are simple and do not meet each other. */
std::string
CheckPlanarPolygons(const ContourNetwork & network)
{
  std::map<std::pair<unsigned int, std::int64_t>, std::vector<PlaneSegment>> planes;
  for (std::uint32_t c = 0; c < network.contours.size(); ++c)
  {
    const Contour &    contour = network.contours[c];
    const unsigned int i = (contour.axis + 1) % 3;
    const unsigned int j = (contour.axis + 2) % 3;
    auto &             segments = planes[{ contour.axis, contour.position }];
    const std::size_t  n = contour.points.size();
    for (std::size_t k = 0; k < n; ++k)
    {
      const Vec3 & u = network.points[contour.points[k]].x;
      const Vec3 & v = network.points[contour.points[(k + 1) % n]].x;
      segments.push_back({ { u[i], u[j] }, { v[i], v[j] }, contour.points[k], contour.points[(k + 1) % n], c });
    }
  }
  for (const auto & plane : planes)
  {
    const auto & segments = plane.second;
    for (std::size_t s = 0; s < segments.size(); ++s)
    {
      for (std::size_t t = s + 1; t < segments.size(); ++t)
      {
        const PlaneSegment & a = segments[s];
        const PlaneSegment & b = segments[t];
        const bool           adjacent = a.pa == b.pa || a.pa == b.pb || a.pb == b.pa || a.pb == b.pb;
        if (!adjacent && SegmentsMeet(a, b))
        {
          std::ostringstream m;
          m << "in the plane " << PlaneName(plane.first.first, plane.first.second) << " the segment " << a.pa << "-"
            << a.pb << " of contour " << a.contour << " meets the segment " << b.pa << "-" << b.pb << " of contour "
            << b.contour;
          return m.str();
        }
      }
    }
  }
  return std::string();
}

/** 6 x the volume the faces enclose in index space, each fanned from its centroid. */
double
SixVolume(const ContourNetwork & network, const std::vector<std::vector<std::uint32_t>> & faces)
{
  double volume = 0.0;
  for (const auto & face : faces)
  {
    Vec3 centre(0.0);
    for (const auto p : face)
    {
      centre += network.points[p].x;
    }
    centre /= static_cast<double>(face.size());
    for (std::size_t k = 0; k < face.size(); ++k)
    {
      const Vec3 & a = network.points[face[k]].x;
      const Vec3 & b = network.points[face[(k + 1) % face.size()]].x;
      volume += Dot(centre, Cross(a, b));
    }
  }
  return volume;
}

/** Rule 7: the faces close a sphere, facing outward. */
std::string
CheckFaces(const ContourNetwork & network, const ContourAdjacency & adjacency, const ContourLines & lines)
{
  const auto faces = TraceContourFaces(ContourRotations(network, adjacency, lines));
  if (faces.empty())
  {
    return "the contour segments do not bound faces consistently (the surface would pass through itself)";
  }
  const std::size_t v = network.points.size();
  if (faces.size() != v + 2)
  {
    std::ostringstream s;
    s << "the contours bound " << faces.size() << " faces with " << v << " control points and " << 2 * v
      << " segments: not a sphere (V - E + F = " << static_cast<long long>(faces.size()) - static_cast<long long>(v)
      << ")";
    return s.str();
  }
  for (const auto & face : faces)
  {
    if (face.size() < 3)
    {
      return "a face of the surface has fewer than three corners";
    }
  }
  if (!(SixVolume(network, faces) > 0.0))
  {
    return "the surface faces inward (the control points along some line are out of order)";
  }
  return std::string();
}

/** Rule 8: scan conversions valid, and disjoint within a plane. */
std::string
CheckScanConversions(const ContourNetwork & network)
{
  std::map<std::pair<unsigned int, std::int64_t>, std::vector<std::pair<ContourVoxel, std::uint32_t>>> planes;
  for (std::uint32_t c = 0; c < network.contours.size(); ++c)
  {
    const auto        voxels = ScanConvertContour(network, c);
    const std::string problem = DescribeInvalidScanConversion(network, c, voxels);
    if (!problem.empty())
    {
      return problem;
    }
    auto & list = planes[{ network.contours[c].axis, network.contours[c].position }];
    for (const auto & v : voxels)
    {
      list.emplace_back(v, c);
    }
  }
  for (auto & plane : planes)
  {
    auto & list = plane.second;
    std::sort(list.begin(), list.end());
    for (std::size_t i = 1; i < list.size(); ++i)
    {
      if (list[i - 1].first == list[i].first)
      {
        std::ostringstream s;
        s << "contours " << list[i - 1].second << " and " << list[i].second << " of the plane "
          << PlaneName(plane.first.first, plane.first.second) << " pass through one voxel";
        return s.str();
      }
    }
  }
  return std::string();
}
} // namespace

std::string
CheckContourNetwork(const ContourNetwork & network)
{
  std::string problem = DescribeInvalidGrid(network.grid);
  if (problem.empty())
  {
    problem = CheckContourSet(network);
  }
  ContourAdjacency adjacency;
  if (problem.empty())
  {
    problem = BuildContourAdjacency(network, adjacency);
  }
  const OccupiedContourPlanes planes = OccupiedPlanes(network);
  if (problem.empty())
  {
    problem = CheckControlPointPositions(network, planes);
  }
  if (problem.empty())
  {
    problem = CheckTransversality(network, adjacency);
  }
  if (problem.empty())
  {
    problem = CheckSegmentCrossings(network, planes);
  }
  if (!problem.empty())
  {
    return problem;
  }
  const ContourLines lines = BuildContourLines(network);
  problem = CheckVoxelSeparation(network, lines);
  if (problem.empty())
  {
    problem = CheckPlanarPolygons(network);
  }
  if (problem.empty())
  {
    problem = CheckFaces(network, adjacency, lines);
  }
  if (problem.empty())
  {
    problem = CheckScanConversions(network);
  }
  return problem;
}
} // namespace detail
} // namespace MeshExtraction
} // namespace itk
