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
#include <limits>
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

int
SideOf(double x, double plane)
{
  return x > plane ? 1 : (x < plane ? -1 : 0);
}

/** The two contours of a new control point, the one of the smaller axis first. */
std::array<std::uint32_t, 2>
OrderedContours(const ContourNetwork & network, std::uint32_t a, std::uint32_t b)
{
  return network.contours[a].axis < network.contours[b].axis ? std::array<std::uint32_t, 2>{ { a, b } }
                                                             : std::array<std::uint32_t, 2>{ { b, a } };
}

/** Removes the marked points from every contour and the marked contours, and renumbers
 * what stays in its order; returns the new identifier of every old point (or max). */
std::vector<std::uint32_t>
RemovePointsAndContours(ContourNetwork &          network,
                        const std::vector<bool> & dropPoint,
                        const std::vector<bool> & dropContour)
{
  constexpr std::uint32_t          gone = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t>       newPoint(network.points.size(), gone);
  std::vector<std::uint32_t>       newContour(network.contours.size(), gone);
  std::vector<ContourControlPoint> points;
  std::vector<Contour>             contours;
  for (std::size_t c = 0; c < network.contours.size(); ++c)
  {
    if (!dropContour[c])
    {
      newContour[c] = static_cast<std::uint32_t>(contours.size());
      contours.push_back(network.contours[c]);
    }
  }
  for (std::size_t p = 0; p < network.points.size(); ++p)
  {
    if (!dropPoint[p])
    {
      newPoint[p] = static_cast<std::uint32_t>(points.size());
      ContourControlPoint point = network.points[p];
      point.contours = { { newContour[point.contours[0]], newContour[point.contours[1]] } };
      points.push_back(point);
    }
  }
  for (auto & contour : contours)
  {
    std::vector<std::uint32_t> list;
    for (const auto p : contour.points)
    {
      if (!dropPoint[p])
      {
        list.push_back(newPoint[p]);
      }
    }
    contour.points.swap(list);
  }
  network.points.swap(points);
  network.contours.swap(contours);
  return newPoint;
}

/** Inserts the new point x into the list of contour h just before (before = true) or
 * just after control point p. */
void
InsertBeside(ContourNetwork & network, std::uint32_t h, std::uint32_t p, std::uint32_t x, bool before)
{
  auto &     list = network.contours[h].points;
  const auto at = std::find(list.begin(), list.end(), p);
  list.insert(before ? at : at + 1, x);
}

/** Fig. 5.8: p passes the plane index[f] = c with its four neighbours on its side: a
 * new four-point contour in that plane where the segments from p (at `target`) to its
 * neighbours cross it. */
void
InsertLoopAround(ContourNetwork &         network,
                 const ContourAdjacency & adjacency,
                 std::uint32_t            p,
                 unsigned int             f,
                 std::int64_t             c,
                 double                   target)
{
  const std::array<std::uint32_t, 4> n = adjacency.Neighbours(network, p);
  Vec3                               from = network.points[p].x;
  from[f] = target;
  const auto loop = static_cast<std::uint32_t>(network.contours.size());
  network.contours.push_back(Contour{ f, c, {} });
  std::array<std::uint32_t, 4> created{};
  for (unsigned int k = 0; k < 4; ++k)
  {
    const Vec3 & q = network.points[n[k]].x;
    const double t = (static_cast<double>(c) - target) / (q[f] - target);
    Vec3         x = from + (q - from) * t;
    x[f] = static_cast<double>(c);
    const std::uint32_t host = network.points[p].contours[k / 2];
    x[network.contours[host].axis] = static_cast<double>(network.contours[host].position);
    created[k] = static_cast<std::uint32_t>(network.points.size());
    network.points.push_back(ContourControlPoint{ x, OrderedContours(network, host, loop) });
    InsertBeside(network, host, p, created[k], k % 2 == 0);
  }
  // Around p in the plane of its two contours' axes (alpha, beta): on contour 0 the
  // neighbours differ along beta, on contour 1 along alpha.
  const unsigned int  alpha = network.contours[network.points[p].contours[0]].axis;
  const unsigned int  beta = network.contours[network.points[p].contours[1]].axis;
  const bool          aSwap = network.points[created[1]].x[beta] < network.points[created[0]].x[beta];
  const bool          bSwap = network.points[created[3]].x[alpha] < network.points[created[2]].x[alpha];
  const std::uint32_t aPlus = aSwap ? created[0] : created[1];
  const std::uint32_t aMinus = aSwap ? created[1] : created[0];
  const std::uint32_t bPlus = bSwap ? created[2] : created[3];
  const std::uint32_t bMinus = bSwap ? created[3] : created[2];
  network.contours[loop].points = { bPlus, aPlus, bMinus, aMinus };
}

/** The reverse of InsertLoopAround: p passes back through the plane of the four-point
 * contour that surrounds it; that contour goes. Returns the problem, or empty; `p`
 * gets p's new identifier. */
std::string
RemoveLoopAround(ContourNetwork & network, const ContourAdjacency & adjacency, std::uint32_t & p)
{
  const std::array<std::uint32_t, 4> n = adjacency.Neighbours(network, p);
  std::uint32_t                      loop = std::numeric_limits<std::uint32_t>::max();
  for (unsigned int k = 0; k < 4; ++k)
  {
    const auto &        owners = network.points[n[k]].contours;
    const std::uint32_t host = network.points[p].contours[k / 2];
    const std::uint32_t other = owners[0] == host ? owners[1] : owners[0];
    if (k > 0 && other != loop)
    {
      return "its neighbours in that plane are on different contours";
    }
    loop = other;
  }
  if (network.contours[loop].points.size() != 4)
  {
    return "the contour of its neighbours in that plane has more than these four control points";
  }
  std::vector<bool> dropPoint(network.points.size(), false);
  std::vector<bool> dropContour(network.contours.size(), false);
  for (const auto q : n)
  {
    dropPoint[q] = true;
  }
  dropContour[loop] = true;
  p = RemovePointsAndContours(network, dropPoint, dropContour)[p];
  return std::string();
}

/** p (on its way to `target`) passes the plane index[f] = c that holds contours. */
std::string
PassPlane(ContourNetwork & network, std::uint32_t & p, unsigned int f, std::int64_t c, double target)
{
  ContourAdjacency adjacency;
  std::string      problem = BuildContourAdjacency(network, adjacency);
  if (!problem.empty())
  {
    return problem;
  }
  const double                       plane = static_cast<double>(c);
  const int                          own = SideOf(network.points[p].x[f], plane);
  const std::array<std::uint32_t, 4> n = adjacency.Neighbours(network, p);
  unsigned int                       same = 0;
  unsigned int                       in = 0;
  std::uint32_t                      blocking = n[0];
  for (const auto q : n)
  {
    const int side = SideOf(network.points[q].x[f], plane);
    same += side == own ? 1 : 0;
    in += side == 0 ? 1 : 0;
    blocking = side == own ? blocking : q;
  }
  if (same == 4)
  {
    InsertLoopAround(network, adjacency, p, f, c, target);
    return std::string();
  }
  if (in == 4)
  {
    problem = RemoveLoopAround(network, adjacency, p);
  }
  if (in != 4 || !problem.empty())
  {
    std::ostringstream s;
    s << "it would pass the plane " << AxisNames[f] << " = " << c << " where its neighbour " << blocking
      << " lies on a contour: a control point would join two contours of one plane (Fig. 5.9); add a contour "
         "between them first";
    if (!problem.empty())
    {
      s << " (" << problem << ")";
    }
    return s.str();
  }
  return std::string();
}

/** A crossing of a contour segment with a new plane. */
struct PlaneCrossing
{
  std::uint32_t host;    ///< the contour of the segment
  std::size_t   segment; ///< its index in the host
  Vec3          x;       ///< where the new control point goes
};

/** Where segment k of contour h crosses the plane index[a] = c: on the curve if it
 * crosses the plane once there (Catmull-Rom), on the chord otherwise. */
Vec3
CrossingPoint(const ContourNetwork & network, std::uint32_t h, std::size_t k, unsigned int a, double c, bool onCurve)
{
  const auto & list = network.contours[h].points;
  const Vec3 & u = network.points[list[k]].x;
  const Vec3 & v = network.points[list[(k + 1) % list.size()]].x;
  Vec3         x = u + (v - u) * ((c - u[a]) / (v[a] - u[a]));
  if (onCurve && network.interpolation == ContourInterpolation::CatmullRom)
  {
    constexpr unsigned int steps = 32;
    unsigned int           changes = 0;
    double                 lo = 0.0;
    for (unsigned int i = 0; i < steps; ++i)
    {
      const double t0 = static_cast<double>(i) / steps;
      const double t1 = static_cast<double>(i + 1) / steps;
      if (SideOf(EvaluateContourSegment(network, h, k, t0)[a], c) *
            SideOf(EvaluateContourSegment(network, h, k, t1)[a], c) <=
          0)
      {
        ++changes;
        lo = t0;
      }
    }
    if (changes == 1)
    {
      double    hi = lo + 1.0 / steps;
      const int sideLo = SideOf(EvaluateContourSegment(network, h, k, lo)[a], c);
      for (unsigned int i = 0; i < 50; ++i)
      {
        const double mid = 0.5 * (lo + hi);
        (SideOf(EvaluateContourSegment(network, h, k, mid)[a], c) == sideLo ? lo : hi) = mid;
      }
      x = EvaluateContourSegment(network, h, k, 0.5 * (lo + hi));
    }
  }
  x[a] = c;
  x[network.contours[h].axis] = static_cast<double>(network.contours[h].position);
  return x;
}

/** The non-crossing pairing of the crossings met around a face, each pair joining a
 * crossing into the half-space with one out of it, of least total length. */
std::vector<std::pair<std::size_t, std::size_t>>
PairAroundFace(const std::vector<std::size_t> &   order,
               const std::vector<PlaneCrossing> & crossings,
               const ContourGrid &                grid)
{
  const std::size_t                     m = order.size();
  std::vector<std::vector<double>>      best(m + 1, std::vector<double>(m + 1, 0.0));
  std::vector<std::vector<std::size_t>> choice(m + 1, std::vector<std::size_t>(m + 1, 0));
  auto                                  distance = [&](std::size_t i, std::size_t j) {
    return (GridToPhysical(grid, crossings[order[i]].x) - GridToPhysical(grid, crossings[order[j]].x)).GetNorm();
  };
  // best[i][j]: the pairing of order[i..j) (j - i even).
  for (std::size_t length = 2; length <= m; length += 2)
  {
    for (std::size_t i = 0; i + length <= m; ++i)
    {
      const std::size_t j = i + length;
      best[i][j] = std::numeric_limits<double>::infinity();
      for (std::size_t k = i + 1; k < j; k += 2)
      {
        const double cost = distance(i, k) + best[i + 1][k] + best[k + 1][j];
        if (cost < best[i][j])
        {
          best[i][j] = cost;
          choice[i][j] = k;
        }
      }
    }
  }
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  std::vector<std::pair<std::size_t, std::size_t>> stack{ { 0, m } };
  while (!stack.empty())
  {
    const auto range = stack.back();
    stack.pop_back();
    if (range.second <= range.first)
    {
      continue;
    }
    const std::size_t k = choice[range.first][range.second];
    pairs.emplace_back(order[range.first], order[k]);
    stack.emplace_back(range.first + 1, k);
    stack.emplace_back(k + 1, range.second);
  }
  return pairs;
}

/** The crossings of the plane index[a] = c with the contour segments. */
std::vector<PlaneCrossing>
FindPlaneCrossings(const ContourNetwork &                                           network,
                   unsigned int                                                     a,
                   std::int64_t                                                     c,
                   bool                                                             onCurve,
                   std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t> & bySegment)
{
  std::vector<PlaneCrossing> crossings;
  const double               plane = static_cast<double>(c);
  for (std::uint32_t h = 0; h < network.contours.size(); ++h)
  {
    const auto &      list = network.contours[h].points;
    const std::size_t n = list.size();
    if (network.contours[h].axis == a)
    {
      continue;
    }
    for (std::size_t k = 0; k < n; ++k)
    {
      const std::uint32_t u = list[k];
      const std::uint32_t v = list[(k + 1) % n];
      if (SideOf(network.points[u].x[a], plane) * SideOf(network.points[v].x[a], plane) < 0)
      {
        bySegment[{ std::min(u, v), std::max(u, v) }] = crossings.size();
        crossings.push_back({ h, k, CrossingPoint(network, h, k, a, plane, onCurve) });
      }
    }
  }
  return crossings;
}

/** Links the crossings into loops through the faces they cut (Fig. 5.7): the partners
 * of every crossing in its two faces, then the cycles they form. */
std::string
LinkCrossings(const ContourNetwork &                                                 network,
              const std::vector<PlaneCrossing> &                                     crossings,
              const std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t> & bySegment,
              std::vector<std::vector<std::size_t>> &                                loops)
{
  std::vector<std::vector<std::size_t>> partners(crossings.size());
  for (const auto & face : ContourFaces(network))
  {
    std::vector<std::size_t> order;
    for (std::size_t i = 0; i < face.size(); ++i)
    {
      const std::uint32_t u = face[i];
      const std::uint32_t v = face[(i + 1) % face.size()];
      const auto          found = bySegment.find({ std::min(u, v), std::max(u, v) });
      if (found != bySegment.end())
      {
        order.push_back(found->second);
      }
    }
    if (order.size() % 2 != 0)
    {
      return "a face is cut an odd number of times";
    }
    for (const auto & pair : PairAroundFace(order, crossings, network.grid))
    {
      partners[pair.first].push_back(pair.second);
      partners[pair.second].push_back(pair.first);
    }
  }
  std::vector<bool> visited(crossings.size(), false);
  for (std::size_t start = 0; start < crossings.size(); ++start)
  {
    if (visited[start])
    {
      continue;
    }
    std::vector<std::size_t> loop;
    std::size_t              previous = crossings.size();
    std::size_t              current = start;
    while (!visited[current])
    {
      if (partners[current].size() != 2)
      {
        return "a crossing is not linked through both of its faces";
      }
      visited[current] = true;
      loop.push_back(current);
      const std::size_t next = partners[current][0] != previous ? partners[current][0] : partners[current][1];
      previous = current;
      current = next;
    }
    if (loop.size() < 4)
    {
      std::ostringstream s;
      s << "the crossings would form a contour of " << loop.size() << " control points, fewer than 4";
      return s.str();
    }
    loops.push_back(std::move(loop));
  }
  return std::string();
}

/** Inserts the crossings into their contours and adds the loops as contours of the plane. */
void
InsertPlaneContours(ContourNetwork &                              network,
                    unsigned int                                  a,
                    std::int64_t                                  c,
                    const std::vector<PlaneCrossing> &            crossings,
                    const std::vector<std::vector<std::size_t>> & loops)
{
  const auto                 firstPoint = static_cast<std::uint32_t>(network.points.size());
  const auto                 firstContour = static_cast<std::uint32_t>(network.contours.size());
  std::vector<std::uint32_t> loopOf(crossings.size(), 0);
  for (std::size_t l = 0; l < loops.size(); ++l)
  {
    Contour contour{ a, c, {} };
    for (const auto x : loops[l])
    {
      loopOf[x] = firstContour + static_cast<std::uint32_t>(l);
      contour.points.push_back(firstPoint + static_cast<std::uint32_t>(x));
    }
    network.contours.push_back(std::move(contour));
  }
  std::map<std::uint32_t, std::vector<std::size_t>> byHost;
  for (std::size_t x = 0; x < crossings.size(); ++x)
  {
    network.points.push_back(
      ContourControlPoint{ crossings[x].x, OrderedContours(network, crossings[x].host, loopOf[x]) });
    byHost[crossings[x].host].push_back(x);
  }
  for (const auto & host : byHost)
  {
    const auto &             old = network.contours[host.first].points;
    std::vector<std::size_t> after(old.size(), crossings.size());
    for (const auto x : host.second)
    {
      after[crossings[x].segment] = x;
    }
    std::vector<std::uint32_t> list;
    for (std::size_t k = 0; k < old.size(); ++k)
    {
      list.push_back(old[k]);
      if (after[k] < crossings.size())
      {
        list.push_back(firstPoint + static_cast<std::uint32_t>(after[k]));
      }
    }
    network.contours[host.first].points.swap(list);
  }
}

std::string
Refusal(const std::string & what, const std::string & why)
{
  return what + ": " + why;
}
} // namespace

std::string
MakeTemplateNetwork(const ContourGrid &                 grid,
                    const std::array<std::int64_t, 3> & center,
                    const std::array<double, 3> &       radii,
                    ContourInterpolation                interpolation,
                    ContourNetwork &                    network)
{
  std::string problem = DescribeInvalidGrid(grid);
  if (!problem.empty())
  {
    return problem;
  }
  for (unsigned int a = 0; a < 3; ++a)
  {
    std::ostringstream s;
    if (!(radii[a] >= 1.0) || !std::isfinite(radii[a]))
    {
      s << "the template's radius along " << AxisNames[a] << " is " << radii[a] << ", not at least one voxel";
      return s.str();
    }
    const double lo = static_cast<double>(center[a]) - radii[a];
    const double hi = static_cast<double>(center[a]) + radii[a];
    if (lo < 0.0 || hi > static_cast<double>(grid.size[a] - 1))
    {
      s << "the template (centre " << center[a] << ", radius " << radii[a] << " along " << AxisNames[a]
        << ") does not fit in the grid's " << grid.size[a] << " voxels";
      return s.str();
    }
  }
  ContourNetwork result;
  result.grid = grid;
  result.interpolation = interpolation;
  for (unsigned int a = 0; a < 3; ++a)
  {
    result.contours.push_back(Contour{ a, center[a], {} });
  }
  // Points 2a and 2a + 1 lie on the line along axis a, on the contours of the other two axes.
  for (unsigned int a = 0; a < 3; ++a)
  {
    for (const double sign : { -1.0, 1.0 })
    {
      Vec3 x;
      for (unsigned int i = 0; i < 3; ++i)
      {
        x[i] = static_cast<double>(center[i]);
      }
      x[a] += sign * radii[a];
      const std::uint32_t c0 = a == 0 ? 1 : 0;
      const std::uint32_t c1 = a == 2 ? 1 : 2;
      result.points.push_back(ContourControlPoint{ x, { { c0, c1 } } });
    }
  }
  result.contours[0].points = { 3, 5, 2, 4 }; // x plane: y+, z+, y-, z-
  result.contours[1].points = { 1, 5, 0, 4 }; // y plane: x+, z+, x-, z-
  result.contours[2].points = { 1, 3, 0, 2 }; // z plane: x+, y+, x-, y-
  problem = CheckContourNetwork(result);
  if (problem.empty())
  {
    network = std::move(result);
  }
  return problem;
}

std::array<double, 2>
ControlPointRange(const ContourNetwork & network, std::uint32_t p)
{
  const unsigned int f = LineAxis(network, p);
  const auto &       own = network.points[p];
  double             lo = 0.0;
  double             hi = static_cast<double>(network.grid.size[f] - 1);
  for (std::uint32_t q = 0; q < network.points.size(); ++q)
  {
    const auto & other = network.points[q];
    if (q == p || LineAxis(network, q) != f || other.x[(f + 1) % 3] != own.x[(f + 1) % 3] ||
        other.x[(f + 2) % 3] != own.x[(f + 2) % 3])
    {
      continue;
    }
    const double voxel = std::floor(other.x[f] + 0.5);
    if (other.x[f] < own.x[f])
    {
      lo = std::max(lo, voxel + 0.5);
    }
    else
    {
      hi = std::min(hi, std::nextafter(voxel - 0.5, -std::numeric_limits<double>::infinity()));
    }
  }
  return { { lo, hi } };
}

std::string
MoveContourControlPoint(ContourNetwork & network, std::uint32_t p, double coordinate)
{
  std::ostringstream what;
  what << "control point " << p << " cannot move";
  if (p >= network.points.size())
  {
    return Refusal(what.str(), "there is no such control point");
  }
  const unsigned int f = LineAxis(network, p);
  what << " to " << AxisNames[f] << " = " << coordinate;
  const std::array<double, 2> range = ControlPointRange(network, p);
  if (!(coordinate >= range[0] && coordinate <= range[1]))
  {
    std::ostringstream s;
    s << "it may move within [" << range[0] << ", " << range[1]
      << "] only: the grid, short of its neighbours' voxels on its line (Fig. 5.4)";
    return Refusal(what.str(), s.str());
  }
  const OccupiedContourPlanes planes = OccupiedPlanes(network);
  if (IsOccupied(planes, f, coordinate))
  {
    return Refusal(what.str(), "that is a plane with contours; a control point must lie between them");
  }
  // The planes passed, in the order p meets them.
  const double              from = network.points[p].x[f];
  std::vector<std::int64_t> passed;
  for (const auto c : planes[f])
  {
    const double x = static_cast<double>(c);
    if ((from < x && x < coordinate) || (coordinate < x && x < from))
    {
      passed.push_back(c);
    }
  }
  if (coordinate < from)
  {
    std::reverse(passed.begin(), passed.end());
  }
  ContourNetwork candidate = network;
  std::uint32_t  moving = p;
  for (const auto c : passed)
  {
    const std::string problem = PassPlane(candidate, moving, f, c, coordinate);
    if (!problem.empty())
    {
      return Refusal(what.str(), problem);
    }
  }
  candidate.points[moving].x[f] = coordinate;
  const std::string problem = CheckContourNetwork(candidate);
  if (!problem.empty())
  {
    return Refusal(what.str(), problem);
  }
  network = std::move(candidate);
  return std::string();
}

std::string
AddContourPlane(ContourNetwork & network, unsigned int axis, std::int64_t position)
{
  std::ostringstream what;
  what << "no contour can be added in the plane " << (axis < 3 ? AxisNames[axis] : "?") << " = " << position;
  if (axis > 2 || position < 0 || position >= network.grid.size[axis])
  {
    return Refusal(what.str(), "it is not a plane of the grid");
  }
  if (IsOccupied(OccupiedPlanes(network), axis, static_cast<double>(position)))
  {
    return Refusal(what.str(), "it already holds contours");
  }
  for (std::uint32_t p = 0; p < network.points.size(); ++p)
  {
    if (LineAxis(network, p) == axis && network.points[p].x[axis] == static_cast<double>(position))
    {
      std::ostringstream s;
      s << "control point " << p << " lies in it (section 5.2.4)";
      return Refusal(what.str(), s.str());
    }
  }
  std::string problem;
  // On the Catmull-Rom curves first; if that breaks a rule, on the control polygon.
  for (const bool onCurve : { true, false })
  {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t> bySegment;
    const auto crossings = FindPlaneCrossings(network, axis, position, onCurve, bySegment);
    if (crossings.size() < 4)
    {
      std::ostringstream s;
      s << "it cuts the model in " << crossings.size() << " points, fewer than 4 (section 5.2.4)";
      return Refusal(what.str(), s.str());
    }
    std::vector<std::vector<std::size_t>> loops;
    problem = LinkCrossings(network, crossings, bySegment, loops);
    if (!problem.empty())
    {
      return Refusal(what.str(), problem);
    }
    ContourNetwork candidate = network;
    InsertPlaneContours(candidate, axis, position, crossings, loops);
    problem = CheckContourNetwork(candidate);
    if (problem.empty())
    {
      network = std::move(candidate);
      return problem;
    }
    if (network.interpolation != ContourInterpolation::CatmullRom)
    {
      break;
    }
  }
  return Refusal(what.str(), problem);
}

std::string
RemoveContourPlane(ContourNetwork & network, unsigned int axis, std::int64_t position)
{
  std::ostringstream what;
  what << "the contours of the plane " << (axis < 3 ? AxisNames[axis] : "?") << " = " << position
       << " cannot be removed";
  const OccupiedContourPlanes planes = OccupiedPlanes(network);
  if (axis > 2 || !IsOccupied(planes, axis, static_cast<double>(position)))
  {
    return Refusal(what.str(), "the plane holds no contour");
  }
  if (planes[axis].size() < 2)
  {
    return Refusal(what.str(), "it is the last plane of its axis (section 5.2.4)");
  }
  std::vector<bool> dropPoint(network.points.size(), false);
  std::vector<bool> dropContour(network.contours.size(), false);
  for (std::size_t c = 0; c < network.contours.size(); ++c)
  {
    if (network.contours[c].axis == axis && network.contours[c].position == position)
    {
      dropContour[c] = true;
      for (const auto p : network.contours[c].points)
      {
        dropPoint[p] = true;
      }
    }
  }
  for (std::size_t c = 0; c < network.contours.size(); ++c)
  {
    std::size_t left = 0;
    for (const auto p : network.contours[c].points)
    {
      left += dropPoint[p] ? 0 : 1;
    }
    if (!dropContour[c] && left < 4)
    {
      std::ostringstream s;
      s << "contour " << c << " would keep " << left << " control points, fewer than 4 (section 5.2.4)";
      return Refusal(what.str(), s.str());
    }
  }
  ContourNetwork candidate = network;
  RemovePointsAndContours(candidate, dropPoint, dropContour);
  const std::string problem = CheckContourNetwork(candidate);
  if (!problem.empty())
  {
    return Refusal(what.str(), problem);
  }
  network = std::move(candidate);
  return std::string();
}
} // namespace detail
} // namespace MeshExtraction
} // namespace itk
