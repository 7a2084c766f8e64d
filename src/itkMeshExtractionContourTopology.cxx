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

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <tuple>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
Vec3
GridToPhysical(const ContourGrid & grid, const Vec3 & index)
{
  Vec3 p;
  for (unsigned int i = 0; i < 3; ++i)
  {
    p[i] = grid.origin[i];
    for (unsigned int j = 0; j < 3; ++j)
    {
      p[i] += grid.direction[3 * i + j] * grid.spacing[j] * index[j];
    }
  }
  return p;
}

Vec3
PhysicalToGrid(const ContourGrid & grid, const Vec3 & physical)
{
  Vec3 index;
  for (unsigned int j = 0; j < 3; ++j)
  {
    double s = 0.0;
    for (unsigned int i = 0; i < 3; ++i)
    {
      s += grid.direction[3 * i + j] * (physical[i] - grid.origin[i]);
    }
    index[j] = s / grid.spacing[j];
  }
  return index;
}

std::string
DescribeInvalidGrid(const ContourGrid & grid)
{
  std::ostringstream s;
  for (unsigned int a = 0; a < 3; ++a)
  {
    if (grid.size[a] < 1)
    {
      s << "the grid's size along axis " << a << " is " << grid.size[a] << ", not at least 1";
      return s.str();
    }
    if (!(grid.spacing[a] > 0.0) || !std::isfinite(grid.spacing[a]))
    {
      s << "the grid's spacing along axis " << a << " is " << grid.spacing[a] << ", not a positive number";
      return s.str();
    }
    if (!std::isfinite(grid.origin[a]))
    {
      s << "the grid's origin is not finite";
      return s.str();
    }
  }
  for (unsigned int i = 0; i < 3; ++i)
  {
    for (unsigned int j = 0; j < 3; ++j)
    {
      double dot = 0.0;
      for (unsigned int k = 0; k < 3; ++k)
      {
        dot += grid.direction[3 * k + i] * grid.direction[3 * k + j];
      }
      if (!(std::abs(dot - (i == j ? 1.0 : 0.0)) <= 1e-6))
      {
        return "the grid's direction matrix is not orthonormal";
      }
    }
  }
  return std::string();
}

ContourVoxel
VoxelOf(const Vec3 & x)
{
  return { { static_cast<std::int64_t>(std::floor(x[0] + 0.5)),
             static_cast<std::int64_t>(std::floor(x[1] + 0.5)),
             static_cast<std::int64_t>(std::floor(x[2] + 0.5)) } };
}

unsigned int
LineAxis(const ContourNetwork & network, std::uint32_t p)
{
  const auto & c = network.points[p].contours;
  return 3u - network.contours[c[0]].axis - network.contours[c[1]].axis;
}

std::uint32_t
ContourAdjacency::Neighbour(const ContourNetwork & network, std::uint32_t p, unsigned int s, int step) const
{
  const auto &      list = network.contours[network.points[p].contours[s]].points;
  const std::size_t n = list.size();
  const std::size_t i = slot[p][s];
  return list[step > 0 ? (i + 1) % n : (i + n - 1) % n];
}

std::array<std::uint32_t, 4>
ContourAdjacency::Neighbours(const ContourNetwork & network, std::uint32_t p) const
{
  return { { this->Neighbour(network, p, 0, -1),
             this->Neighbour(network, p, 0, +1),
             this->Neighbour(network, p, 1, -1),
             this->Neighbour(network, p, 1, +1) } };
}

namespace
{
constexpr std::uint32_t NoSlot = 0xffffffffu;

/** Records where contour c lists each of its points; names the first problem. */
std::string
RecordContourSlots(const ContourNetwork & network, std::uint32_t c, ContourAdjacency & adjacency)
{
  const Contour & contour = network.contours[c];
  for (std::size_t i = 0; i < contour.points.size(); ++i)
  {
    const std::uint32_t p = contour.points[i];
    std::ostringstream  s;
    if (p >= network.points.size())
    {
      s << "contour " << c << " lists control point " << p << ", which does not exist";
      return s.str();
    }
    const auto &   owners = network.points[p].contours;
    const unsigned which = owners[0] == c ? 0u : (owners[1] == c ? 1u : 2u);
    if (which == 2u)
    {
      s << "contour " << c << " lists control point " << p << ", which is on contours " << owners[0] << " and "
        << owners[1];
      return s.str();
    }
    if (adjacency.slot[p][which] != NoSlot)
    {
      s << "contour " << c << " lists control point " << p << " twice";
      return s.str();
    }
    adjacency.slot[p][which] = static_cast<std::uint32_t>(i);
  }
  return std::string();
}
} // namespace

std::string
BuildContourAdjacency(const ContourNetwork & network, ContourAdjacency & adjacency)
{
  const std::size_t nc = network.contours.size();
  adjacency.slot.assign(network.points.size(), { { NoSlot, NoSlot } });
  for (std::size_t p = 0; p < network.points.size(); ++p)
  {
    const auto &       c = network.points[p].contours;
    std::ostringstream s;
    if (c[0] >= nc || c[1] >= nc)
    {
      s << "control point " << p << " names a contour that does not exist";
      return s.str();
    }
    if (!(network.contours[c[0]].axis < network.contours[c[1]].axis))
    {
      s << "control point " << p << " is on contours " << c[0] << " and " << c[1]
        << ", which are not of two different axes (the smaller first)";
      return s.str();
    }
  }
  for (std::uint32_t c = 0; c < nc; ++c)
  {
    const std::string problem = RecordContourSlots(network, c, adjacency);
    if (!problem.empty())
    {
      return problem;
    }
  }
  for (std::size_t p = 0; p < network.points.size(); ++p)
  {
    if (adjacency.slot[p][0] == NoSlot || adjacency.slot[p][1] == NoSlot)
    {
      std::ostringstream s;
      s << "control point " << p << " is not listed by both its contours";
      return s.str();
    }
  }
  return std::string();
}

ContourLines
BuildContourLines(const ContourNetwork & network)
{
  ContourLines      result;
  const std::size_t n = network.points.size();
  result.lineOf.assign(n, 0);
  result.rank.assign(n, 0);
  std::map<std::tuple<unsigned int, std::int64_t, std::int64_t>, std::uint32_t> index;
  for (std::uint32_t p = 0; p < n; ++p)
  {
    const unsigned int f = LineAxis(network, p);
    const auto &       c = network.points[p].contours;
    const auto         key = std::make_tuple(f, network.contours[c[0]].position, network.contours[c[1]].position);
    const auto         found = index.emplace(key, static_cast<std::uint32_t>(result.lines.size()));
    if (found.second)
    {
      result.lines.emplace_back();
    }
    result.lineOf[p] = found.first->second;
    result.lines[found.first->second].push_back(p);
  }
  for (auto & line : result.lines)
  {
    const unsigned int f = line.empty() ? 0u : LineAxis(network, line.front());
    std::sort(line.begin(), line.end(), [&](std::uint32_t a, std::uint32_t b) {
      return network.points[a].x[f] < network.points[b].x[f] ||
             (network.points[a].x[f] == network.points[b].x[f] && a < b);
    });
    for (std::size_t r = 0; r < line.size(); ++r)
    {
      result.rank[line[r]] = static_cast<std::uint32_t>(r);
    }
  }
  return result;
}

OccupiedContourPlanes
OccupiedPlanes(const ContourNetwork & network)
{
  OccupiedContourPlanes planes;
  for (const auto & c : network.contours)
  {
    planes[c.axis].push_back(c.position);
  }
  for (auto & list : planes)
  {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  return planes;
}

bool
IsOccupied(const OccupiedContourPlanes & planes, unsigned int axis, double position)
{
  if (position != std::floor(position))
  {
    return false;
  }
  return std::binary_search(planes[axis].begin(), planes[axis].end(), static_cast<std::int64_t>(position));
}

std::vector<std::array<std::uint32_t, 4>>
ContourRotations(const ContourNetwork & network, const ContourAdjacency & adjacency, const ContourLines & lines)
{
  std::vector<std::array<std::uint32_t, 4>> rotations(network.points.size());
  for (std::uint32_t p = 0; p < network.points.size(); ++p)
  {
    const unsigned int alpha = network.contours[network.points[p].contours[0]].axis;
    const unsigned int beta = network.contours[network.points[p].contours[1]].axis;
    // On contour 0 (plane of axis alpha) the neighbours differ along beta; on contour 1 along alpha.
    std::uint32_t aMinus = adjacency.Neighbour(network, p, 0, -1);
    std::uint32_t aPlus = adjacency.Neighbour(network, p, 0, +1);
    if (network.points[aPlus].x[beta] < network.points[aMinus].x[beta])
    {
      std::swap(aMinus, aPlus);
    }
    std::uint32_t bMinus = adjacency.Neighbour(network, p, 1, -1);
    std::uint32_t bPlus = adjacency.Neighbour(network, p, 1, +1);
    if (network.points[bPlus].x[alpha] < network.points[bMinus].x[alpha])
    {
      std::swap(bMinus, bPlus);
    }
    // Counter-clockwise in the (alpha, beta) plane seen from +f when (alpha, beta, f) is
    // right-handed; the surface faces +f at the odd ranks of the line, -f at the even.
    const bool rightHanded = (alpha + 1) % 3 == beta;
    const bool facesPlusF = lines.rank[p] % 2 == 1;
    if (rightHanded == facesPlusF)
    {
      rotations[p] = { { bPlus, aPlus, bMinus, aMinus } };
    }
    else
    {
      rotations[p] = { { bPlus, aMinus, bMinus, aPlus } };
    }
  }
  return rotations;
}

std::vector<std::vector<std::uint32_t>>
TraceContourFaces(const std::vector<std::array<std::uint32_t, 4>> & rotations)
{
  std::vector<std::vector<std::uint32_t>> faces;
  std::vector<std::array<bool, 4>>        used(rotations.size(), { { false, false, false, false } });
  for (std::uint32_t start = 0; start < rotations.size(); ++start)
  {
    for (unsigned int j0 = 0; j0 < 4; ++j0)
    {
      if (used[start][j0])
      {
        continue;
      }
      std::vector<std::uint32_t> face;
      std::uint32_t              u = start;
      unsigned int               j = j0;
      // A face has at most as many corners as there are directed segments.
      for (std::size_t guard = 0; !used[u][j] && guard <= 4 * rotations.size(); ++guard)
      {
        used[u][j] = true;
        face.push_back(u);
        const std::uint32_t v = rotations[u][j];
        unsigned int        i = 0;
        while (i < 4 && rotations[v][i] != u)
        {
          ++i;
        }
        if (i == 4)
        {
          return {}; // u is not a neighbour of its neighbour v: no consistent faces
        }
        u = v;
        j = (i + 3) % 4;
      }
      if (u != start || j != j0)
      {
        return {};
      }
      faces.push_back(std::move(face));
    }
  }
  return faces;
}

std::vector<std::vector<std::uint32_t>>
ContourFaces(const ContourNetwork & network)
{
  ContourAdjacency adjacency;
  if (!BuildContourAdjacency(network, adjacency).empty())
  {
    return {};
  }
  return TraceContourFaces(ContourRotations(network, adjacency, BuildContourLines(network)));
}
} // namespace detail
} // namespace MeshExtraction
} // namespace itk
