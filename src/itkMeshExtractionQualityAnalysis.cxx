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
#include "itkMeshExtractionJSON.h"
#include "itkMeshExtractionParallel.h"
#include "itkMeshExtractionPredicates.h"
#include "itkMeshExtractionTriangleAABBTree.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <numeric>
#include <ostream>
#include <sstream>

namespace itk
{
namespace MeshExtraction
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

void
PrintStatistics(std::ostream & os, const char * name, const ValueStatistics & s)
{
  os << "  " << std::left << std::setw(16) << name << std::right << std::fixed << std::setprecision(4) << std::setw(10)
     << s.mean << std::setw(10) << s.minimum << std::setw(10) << s.percentile05 << std::setw(10) << s.median
     << std::setw(10) << s.maximum << '\n';
}

void
PrintStatisticsJSON(std::ostream & os, const ValueStatistics & s)
{
  os << "{\"count\": " << s.count << ", \"mean\": " << JSONNumber{ s.mean } << ", \"min\": " << JSONNumber{ s.minimum }
     << ", \"max\": " << JSONNumber{ s.maximum } << ", \"p01\": " << JSONNumber{ s.percentile01 }
     << ", \"p05\": " << JSONNumber{ s.percentile05 } << ", \"median\": " << JSONNumber{ s.median }
     << ", \"p95\": " << JSONNumber{ s.percentile95 } << ", \"histogram_range\": [" << JSONNumber{ s.histogramLower }
     << ", " << JSONNumber{ s.histogramUpper } << "], \"histogram\": [";
  for (std::size_t i = 0; i < s.histogram.size(); ++i)
  {
    os << (i ? ", " : "") << s.histogram[i];
  }
  os << "]}";
}

Vec3
AnyPerpendicular(const Vec3 & n)
{
  const Vec3 axis = std::abs(n[0]) < 0.6 ? MakeVec3(1, 0, 0) : MakeVec3(0, 1, 0);
  Vec3       u = Cross(n, axis);
  return u * (1.0 / Norm(u));
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
/** The parity (0 or 1) of the crossings of the ray origin + t direction, t > 0, with
 * the triangles of `tree` that skip(g) does not exclude; -1 if it grazes an edge or a
 * vertex of one (IntersectRayTriangle's ambiguous hit). */
template <typename TSkip>
int
RayCrossingParity(const IndexedTriangleMesh & mesh,
                  const TriangleAABBTree &    tree,
                  const Vec3 &                origin,
                  const Vec3 &                direction,
                  TSkip &&                    skip)
{
  std::size_t crossings = 0;
  bool        ambiguous = false;
  tree.VisitRay(origin, direction, [&](std::uint32_t g) {
    if (ambiguous || skip(g))
    {
      return;
    }
    const auto &         s = mesh.triangles[g];
    const RayTriangleHit hit =
      IntersectRayTriangle(origin, direction, mesh.points[s[0]], mesh.points[s[1]], mesh.points[s[2]], 0.0);
    ambiguous = hit.ambiguous;
    crossings += hit.hit ? 1 : 0;
  });
  return ambiguous ? -1 : static_cast<int>(crossings % 2);
}
} // namespace

std::vector<int>
ClassifyTriangleOrientation(const IndexedTriangleMesh & mesh, double degenerateQAreaTolerance)
{
  const std::size_t          n = mesh.triangles.size();
  std::vector<int>           result(n, 0);
  std::vector<std::uint32_t> valid;
  valid.reserve(n);
  for (std::uint32_t f = 0; f < n; ++f)
  {
    const auto & t = mesh.triangles[f];
    if (MeasureTriangle(mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]]).qArea > degenerateQAreaTolerance)
    {
      valid.push_back(f);
    }
  }
  TriangleAABBTree tree;
  tree.Build(mesh, &valid);
  ParallelForBlocks(valid.size(), 1024, [&](std::size_t begin, std::size_t end, std::size_t) {
    for (std::size_t i = begin; i < end; ++i)
    {
      const std::uint32_t f = valid[i];
      const auto &        t = mesh.triangles[f];
      const Vec3 &        a = mesh.points[t[0]];
      const Vec3 &        b = mesh.points[t[1]];
      const Vec3 &        c = mesh.points[t[2]];
      const Vec3          origin = TriangleCentroid(a, b, c);
      const Vec3          normal = TriangleUnitNormal(a, b, c);
      const Vec3          u = AnyPerpendicular(normal);
      const Vec3          w = Cross(normal, u);
      // Any direction into the open half-space of the normal tells the side the
      // normal points to; retry with tilted rays when one grazes an edge.
      for (unsigned int attempt = 0; attempt < 12; ++attempt)
      {
        Vec3 direction = normal;
        if (attempt > 0)
        {
          const double angle = 2.399963229728653 * attempt; // golden angle
          direction = normal + (u * std::cos(angle) + w * std::sin(angle)) * (0.15 + 0.05 * attempt);
          direction *= 1.0 / Norm(direction);
        }
        const int parity = RayCrossingParity(mesh, tree, origin, direction, [f](std::uint32_t g) { return g == f; });
        if (parity >= 0)
        {
          result[f] = parity == 0 ? 1 : -1;
          break;
        }
      }
    }
  });
  return result;
}

std::vector<std::uint32_t>
ComponentRayVertices(const IndexedTriangleMesh & mesh, const MeshTopology & topology)
{
  std::vector<std::uint32_t> vertex(topology.numberOfComponents, std::numeric_limits<std::uint32_t>::max());
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f)
  {
    const std::uint32_t c = topology.triangleComponent[f];
    if (vertex[c] == std::numeric_limits<std::uint32_t>::max())
    {
      vertex[c] = mesh.triangles[f][0];
    }
  }
  return vertex;
}

std::vector<std::int8_t>
ComponentNestingParity(const IndexedTriangleMesh & mesh, const MeshTopology & topology)
{
  const std::size_t components = topology.numberOfComponents;
  if (components < 2)
  {
    return {};
  }
  std::vector<std::int8_t>         parity(components, -1);
  const std::vector<std::uint32_t> vertex = ComponentRayVertices(mesh, topology);
  std::vector<std::uint32_t>       proper;
  proper.reserve(mesh.triangles.size());
  for (std::uint32_t f = 0; f < mesh.triangles.size(); ++f)
  {
    if (MeshFaceIsProper(mesh, f))
    {
      proper.push_back(f);
    }
  }
  TriangleAABBTree tree;
  tree.Build(mesh, &proper);
  ParallelForBlocks(components, 64, [&](std::size_t begin, std::size_t end, std::size_t) {
    for (std::size_t c = begin; c < end; ++c)
    {
      if ((c < topology.componentBoundaryLoops.size() && topology.componentBoundaryLoops[c] > 0) ||
          vertex[c] == std::numeric_limits<std::uint32_t>::max())
      {
        continue;
      }
      const Vec3 & origin = mesh.points[vertex[c]];
      for (unsigned int attempt = 0; attempt < 12; ++attempt)
      {
        // Directions of no special alignment with the grid, turned by the golden angle.
        const double angle = 0.61 + 2.399963229728653 * attempt;
        const double z = 0.83 - 0.13 * attempt;
        const double r = std::sqrt(1.0 - z * z);
        Vec3         direction;
        direction[0] = r * std::cos(angle);
        direction[1] = r * std::sin(angle);
        direction[2] = z;
        const int p = RayCrossingParity(mesh, tree, origin, direction, [&topology, c](std::uint32_t g) {
          return topology.triangleComponent[g] == c;
        });
        if (p >= 0)
        {
          parity[c] = static_cast<std::int8_t>(p);
          break;
        }
      }
    }
  });
  return parity;
}

std::vector<std::pair<std::uint32_t, std::uint32_t>>
SortedPairs(const std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>> & found)
{
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  for (const auto & blockPairs : found)
  {
    pairs.insert(pairs.end(), blockPairs.begin(), blockPairs.end());
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

bool
MeshFaceIsProper(const IndexedTriangleMesh & mesh, std::uint32_t f)
{
  const auto & t = mesh.triangles[f];
  return t[0] != t[1] && t[1] != t[2] && t[2] != t[0] &&
         !IsTriangleDegenerateExact(mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]]);
}

namespace
{
using FacePair = std::pair<std::uint32_t, std::uint32_t>;
using FacePairBlocks = std::vector<std::vector<FacePair>>;

/** The pairs of triangles whose boxes overlap in `tree` (the tree against itself, each
 * pair once, the first levels' node pairs shared among the threads), that `accept`
 * lets through and that intersect (FacesIntersect), sorted. accept(f, g, list)
 * may also keep the pair in `list`, one of `kept` (a list per block). */
template <typename TAccept>
std::vector<FacePair>
IntersectingOverlappingPairs(const IndexedTriangleMesh & mesh,
                             const TriangleAABBTree &    tree,
                             TAccept &&                  accept,
                             FacePairBlocks &            kept)
{
  const std::vector<TriangleAABBTree::NodePair> starts = tree.SplitOverlappingPairs(4096);
  constexpr std::size_t                         PairsPerBlock = 16;
  const std::size_t                             numberOfBlocks = (starts.size() + PairsPerBlock - 1) / PairsPerBlock;
  FacePairBlocks                                found(numberOfBlocks);
  kept.resize(numberOfBlocks);
  for (auto & block : kept)
  {
    block.clear(); // keeps its memory for the next search
  }
  ParallelForBlocks(starts.size(), PairsPerBlock, [&](std::size_t begin, std::size_t end, std::size_t block) {
    for (std::size_t i = begin; i < end; ++i)
    {
      tree.VisitOverlappingPairs(starts[i], [&](std::uint32_t f, std::uint32_t g) {
        if (accept(f, g, kept[block]) && MeshFacesIntersect(mesh, f, g))
        {
          found[block].emplace_back(std::min(f, g), std::max(f, g));
        }
      });
    }
  });
  return SortedPairs(found);
}

template <typename TAccept>
std::vector<FacePair>
IntersectingOverlappingPairs(const IndexedTriangleMesh & mesh, const TriangleAABBTree & tree, TAccept && accept)
{
  FacePairBlocks none;
  return IntersectingOverlappingPairs(
    mesh, tree, [&accept](std::uint32_t f, std::uint32_t g, std::vector<FacePair> &) { return accept(f, g); }, none);
}

/** The pairs of each face f of `queries` with the faces g of `tree` whose boxes
 * overlap box(f), that `accept` lets through and that intersect (FacesIntersect),
 * sorted; a pair of two queries (isQuery(g)) once, from the later one's query. */
template <typename TBox, typename TIsQuery, typename TAccept>
std::vector<FacePair>
IntersectingQueryPairs(const IndexedTriangleMesh &        mesh,
                       const TriangleAABBTree &           tree,
                       const std::vector<std::uint32_t> & queries,
                       std::size_t                        blockSize,
                       TBox &&                            box,
                       TIsQuery &&                        isQuery,
                       TAccept &&                         accept)
{
  FacePairBlocks found((queries.size() + blockSize - 1) / blockSize);
  ParallelForBlocks(queries.size(), blockSize, [&](std::size_t begin, std::size_t end, std::size_t block) {
    for (std::size_t i = begin; i < end; ++i)
    {
      const std::uint32_t  f = queries[i];
      const auto &         t = mesh.triangles[f];
      const Vec3           P[3] = { mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]] };
      const IdentifierType pid[3] = { t[0], t[1], t[2] };
      tree.VisitOverlapping(box(f), [&](std::uint32_t g) {
        if (g == f || (g < f && isQuery(g)) || !accept(f, g))
        {
          return;
        }
        const auto &         u = mesh.triangles[g];
        const Vec3           Q[3] = { mesh.points[u[0]], mesh.points[u[1]], mesh.points[u[2]] };
        const IdentifierType qid[3] = { u[0], u[1], u[2] };
        if (FacesIntersect(P, pid, Q, qid))
        {
          found[block].emplace_back(std::min(f, g), std::max(f, g));
        }
      });
    }
  });
  return SortedPairs(found);
}

/** The faces of `mesh` that moved since the cache's last rebuild (moved[f] = 1): that
 * changed vertices, or have a vertex 0.45 margin or more from where it was (NaN
 * points count as moved). Returns their number; when the cache does not hold this
 * mesh (another size, or a new margin), every face counts as moved and `moved` is
 * left empty. */
std::size_t
FindMovedFaces(const IndexedTriangleMesh & mesh, const SelfIntersectionCache & cache, std::vector<std::uint8_t> & moved)
{
  const std::size_t n = mesh.triangles.size();
  const std::size_t numberOfPoints = mesh.points.size();
  if (!(n > 0 && cache.points.size() == numberOfPoints && cache.triangles.size() == n &&
        cache.margin == cache.marginOfNearPairs))
  {
    return n;
  }
  const double              limit = 0.45 * cache.margin;
  std::vector<std::uint8_t> far(numberOfPoints);
  for (std::size_t v = 0; v < numberOfPoints; ++v)
  {
    far[v] = SquaredNorm(mesh.points[v] - cache.points[v]) < limit * limit ? 0 : 1;
  }
  moved.resize(n);
  for (std::size_t f = 0; f < n; ++f)
  {
    const auto & t = mesh.triangles[f];
    moved[f] = (t != cache.triangles[f] || far[t[0]] || far[t[1]] || far[t[2]]) ? 1 : 0;
  }
  return static_cast<std::size_t>(std::count(moved.begin(), moved.end(), std::uint8_t{ 1 }));
}

/** The rebuild of SearchWithCache: the whole search (the tree against itself), which
 * also keeps the near pairs in the cache (the tree's boxes contain the grown ones)
 * and the mesh as it is now. */
template <typename TAcceptApart>
std::vector<FacePair>
RebuildSearch(const IndexedTriangleMesh &       mesh,
              const TriangleAABBTree &          tree,
              const AxisAlignedBoxArray &       boxes,
              const std::vector<std::uint8_t> & certified,
              SelfIntersectionCache &           cache,
              TAcceptApart &&                   acceptApart)
{
  const std::size_t n = mesh.triangles.size();
  ++cache.numberOfRebuilds;
  cache.marginOfNearPairs = cache.margin;
  cache.points.assign(mesh.points.begin(), mesh.points.end());
  cache.triangles.assign(mesh.triangles.begin(), mesh.triangles.end());
  const double grow = cache.margin; // both boxes grown by half of it
  auto         near = [&](std::uint32_t f, std::uint32_t g) {
    const AxisAlignedBox & a = boxes[f];
    const AxisAlignedBox & b = boxes[g];
    for (unsigned int d = 0; d < 3; ++d)
    {
      if (a.lower[d] - grow > b.upper[d] || b.lower[d] - grow > a.upper[d])
      {
        return false;
      }
    }
    return true;
  };
  // `accept`, with the common vertices looked up once for both questions.
  return IntersectingOverlappingPairs(
    mesh,
    tree,
    [&](std::uint32_t f, std::uint32_t g, std::vector<FacePair> & nearPairs) {
      if (f >= n || g >= n)
      {
        return false;
      }
      const auto & t = mesh.triangles[f];
      const auto & u = mesh.triangles[g];
      bool         common = false;
      for (std::uint32_t v : t)
      {
        if (v == u[0] || v == u[1] || v == u[2])
        {
          if (certified[v])
          {
            return false;
          }
          common = true;
        }
      }
      if (!common && near(f, g))
      {
        nearPairs.emplace_back(f, g);
      }
      return acceptApart(f, g);
    },
    cache.nearPairs);
}

/** The near pairs of the cache whose faces both did not move and that intersect, in
 * the order of the cache's blocks (one block per work unit at a time). */
template <typename TAcceptApart>
std::vector<FacePair>
IntersectingNearPairs(const IndexedTriangleMesh &       mesh,
                      const SelfIntersectionCache &     cache,
                      const std::vector<std::uint8_t> & moved,
                      TAcceptApart &&                   acceptApart)
{
  FacePairBlocks nearFound(cache.nearPairs.size());
  ParallelForBlocks(cache.nearPairs.size(), 1, [&](std::size_t begin, std::size_t end, std::size_t) {
    for (std::size_t b = begin; b < end; ++b)
    {
      for (const auto & p : cache.nearPairs[b])
      {
        if (!moved[p.first] && !moved[p.second] && acceptApart(p.first, p.second) &&
            MeshFacesIntersect(mesh, p.first, p.second))
        {
          nearFound[b].emplace_back(std::min(p.first, p.second), std::max(p.first, p.second));
        }
      }
    }
  });
  std::vector<FacePair> found;
  for (const auto & block : nearFound)
  {
    found.insert(found.end(), block.begin(), block.end());
  }
  return found;
}

/** Appends to `found` the pairs of faces that did not move, meet at a vertex whose fan
 * is not certified now, and intersect(f, g). */
template <typename TIntersect>
void
AppendIntersectingCornerPairs(const IndexedTriangleMesh &       mesh,
                              const std::vector<std::uint8_t> & moved,
                              const std::vector<std::uint8_t> & certified,
                              TIntersect &&                     intersect,
                              std::vector<FacePair> &           found)
{
  const std::size_t     numberOfPoints = mesh.points.size();
  std::vector<FacePair> corners; // (vertex, face)
  for (std::uint32_t f = 0; f < mesh.triangles.size(); ++f)
  {
    for (std::uint32_t v : mesh.triangles[f])
    {
      if (!moved[f] && v < numberOfPoints && !certified[v])
      {
        corners.emplace_back(v, f);
      }
    }
  }
  std::sort(corners.begin(), corners.end());
  for (std::size_t i = 0; i < corners.size();)
  {
    std::size_t j = i;
    while (j < corners.size() && corners[j].first == corners[i].first)
    {
      ++j;
    }
    for (std::size_t a = i; a < j; ++a)
    {
      for (std::size_t b = a + 1; b < j; ++b)
      {
        const std::uint32_t f = corners[a].second;
        const std::uint32_t g = corners[b].second;
        if (f != g && intersect(f, g))
        {
          found.emplace_back(std::min(f, g), std::max(f, g));
        }
      }
    }
    i = j;
  }
}

/** The intersecting pairs with a face that moved: one tree query each (a pair of two
 * such faces once), sorted. */
template <typename TAccept>
std::vector<FacePair>
IntersectingMovedPairs(const IndexedTriangleMesh &       mesh,
                       const TriangleAABBTree &          tree,
                       const AxisAlignedBoxArray &       boxes,
                       const std::vector<std::uint8_t> & moved,
                       TAccept &&                        accept)
{
  std::vector<std::uint32_t> queries;
  for (std::uint32_t f = 0; f < mesh.triangles.size(); ++f)
  {
    if (moved[f])
    {
      queries.push_back(f);
    }
  }
  return IntersectingQueryPairs(
    mesh,
    tree,
    queries,
    512,
    [&boxes](std::uint32_t f) { return boxes[f]; },
    [&moved](std::uint32_t g) { return moved[g] != 0; },
    accept);
}

/** The full search of FindSelfIntersections (every pair that `accept` lets through
 * and that intersects; `tree` holds boxes that contain the faces' own, `boxes`;
 * certified[v] as CertifiedFans), with a cache: see SelfIntersectionCache. Either a
 * rebuild, or the pairs that may have changed since the last one: near pairs of
 * faces that did not move, faces that meet at a vertex not certified now, and
 * pairs with a face that moved. acceptApart(f, g) is `accept` for two faces without
 * a common vertex. */
template <typename TAccept, typename TAcceptApart>
std::vector<FacePair>
SearchWithCache(const IndexedTriangleMesh &       mesh,
                const TriangleAABBTree &          tree,
                const AxisAlignedBoxArray &       boxes,
                const std::vector<std::uint8_t> & certified,
                SelfIntersectionCache &           cache,
                TAccept &&                        accept,
                TAcceptApart &&                   acceptApart)
{
  std::vector<std::uint8_t> moved;
  if (4 * FindMovedFaces(mesh, cache, moved) > mesh.triangles.size())
  {
    return RebuildSearch(mesh, tree, boxes, certified, cache, acceptApart);
  }
  ++cache.numberOfIncrementalSearches;
  auto intersect = [&](std::uint32_t f, std::uint32_t g) { return accept(f, g) && MeshFacesIntersect(mesh, f, g); };
  std::vector<FacePair> found = IntersectingNearPairs(mesh, cache, moved, acceptApart);
  AppendIntersectingCornerPairs(mesh, moved, certified, intersect, found);
  FacePairBlocks blocks(2);
  blocks[0] = IntersectingMovedPairs(mesh, tree, boxes, moved, accept);
  blocks[1] = std::move(found);
  auto pairs = SortedPairs(blocks);
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  return pairs;
}

/** Per point: 1 if its fan is certified (CertifyFan), from the faces at it in face
 * order. All 0 if a face refers to a point that is not there. */
std::vector<std::uint8_t>
CertifiedFans(const IndexedTriangleMesh & mesh)
{
  const std::size_t             numberOfPoints = mesh.points.size();
  std::vector<std::uint8_t>     certified(numberOfPoints, 0);
  LargeBlockVector<std::size_t> start(numberOfPoints + 1, 0);
  for (const auto & t : mesh.triangles)
  {
    for (std::uint32_t v : t)
    {
      if (v >= numberOfPoints)
      {
        return certified;
      }
      ++start[v + 1];
    }
  }
  std::partial_sum(start.begin(), start.end(), start.begin());
  LargeBlockVector<FanCorner> corners(start.back());
  {
    LargeBlockVector<std::size_t> cursor(start.begin(), start.end() - 1);
    for (const auto & t : mesh.triangles)
    {
      for (unsigned int j = 0; j < 3; ++j)
      {
        corners[cursor[t[j]]++] = FanCorner{ t[(j + 1) % 3], t[(j + 2) % 3] };
      }
    }
  }
  ParallelForBlocks(numberOfPoints, 4096, [&](std::size_t begin, std::size_t end, std::size_t) {
    FanScratch scratch;
    for (std::size_t v = begin; v < end; ++v)
    {
      certified[v] = CertifyFan(mesh.points.data(),
                                static_cast<std::uint32_t>(v),
                                corners.data() + start[v],
                                start[v + 1] - start[v],
                                scratch)
                       ? 1
                       : 0;
    }
  });
  return certified;
}
} // namespace

bool
MeshFacesIntersect(const IndexedTriangleMesh & mesh, std::uint32_t f, std::uint32_t g)
{
  const auto &         t = mesh.triangles[f];
  const auto &         u = mesh.triangles[g];
  const Vec3           P[3] = { mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]] };
  const Vec3           Q[3] = { mesh.points[u[0]], mesh.points[u[1]], mesh.points[u[2]] };
  const IdentifierType pid[3] = { t[0], t[1], t[2] };
  const IdentifierType qid[3] = { u[0], u[1], u[2] };
  return FacesIntersect(P, pid, Q, qid);
}

std::vector<std::pair<std::uint32_t, std::uint32_t>>
FindSelfIntersections(const IndexedTriangleMesh & mesh, const std::vector<std::uint32_t> * queries)
{
  const std::size_t          n = mesh.triangles.size();
  std::vector<std::uint32_t> valid;
  std::vector<bool>          isValid(n, false);
  valid.reserve(n);
  for (std::uint32_t f = 0; f < n; ++f)
  {
    if (MeshFaceIsProper(mesh, f))
    {
      valid.push_back(f);
      isValid[f] = true;
    }
  }
  TriangleAABBTree tree;
  tree.Build(mesh, &valid);
  if (queries == nullptr)
  {
    // All pairs: the tree against itself, each pair of overlapping boxes once.
    return IntersectingOverlappingPairs(mesh, tree, [](std::uint32_t, std::uint32_t) { return true; });
  }
  // The proper faces asked about, each once, sorted: one tree query each.
  std::vector<std::uint32_t> asked;
  for (std::uint32_t f : *queries)
  {
    if (f < n && isValid[f])
    {
      asked.push_back(f);
    }
  }
  std::sort(asked.begin(), asked.end());
  asked.erase(std::unique(asked.begin(), asked.end()), asked.end());
  std::vector<bool> probed(n, false);
  for (std::uint32_t f : asked)
  {
    probed[f] = true;
  }
  return IntersectingQueryPairs(
    mesh,
    tree,
    asked,
    2048,
    [&mesh](std::uint32_t f) { return TriangleBox(mesh, f); },
    [&probed](std::uint32_t g) { return probed[g]; },
    [](std::uint32_t, std::uint32_t) { return true; });
}

namespace
{
/** The queries that are proper faces (an exact test each, on the work units), each
 * once, sorted; probed[f] is set for each. */
std::vector<std::uint32_t>
ProperProbes(const IndexedTriangleMesh & mesh, const std::vector<std::uint32_t> & queries, std::vector<bool> & probed)
{
  const std::size_t         n = mesh.triangles.size();
  std::vector<std::uint8_t> proper(queries.size());
  ParallelForBlocks(queries.size(), 8192, [&](std::size_t begin, std::size_t end, std::size_t) {
    for (std::size_t i = begin; i < end; ++i)
    {
      proper[i] = queries[i] < n && MeshFaceIsProper(mesh, queries[i]) ? 1 : 0;
    }
  });
  std::vector<std::uint32_t> probes;
  for (std::size_t i = 0; i < queries.size(); ++i)
  {
    const std::uint32_t f = queries[i];
    if (proper[i] && !probed[f])
    {
      probed[f] = true;
      probes.push_back(f);
    }
  }
  std::sort(probes.begin(), probes.end());
  return probes;
}

/** The search for many probes (a sweep of swaps or moves over the whole mesh): the
 * tree against itself visits each overlapping pair once, cheaper than one query per
 * probe; with a cache, only what may have changed since its rebuild
 * (SearchWithCache). The faces' own boxes (the tree's may be larger) and validity
 * are computed once per face instead of once per pair. */
std::vector<FacePair>
SweepSearch(const IndexedTriangleMesh & mesh,
            const TriangleAABBTree &    tree,
            const std::vector<bool> &   probed,
            SelfIntersectionCache *     cache)
{
  const std::size_t         n = mesh.triangles.size();
  AxisAlignedBoxArray       boxes(n);
  std::vector<std::uint8_t> usable(n);
  ParallelForBlocks(n, 8192, [&](std::size_t begin, std::size_t end, std::size_t) {
    for (std::size_t f = begin; f < end; ++f)
    {
      boxes[f] = TriangleBox(mesh, static_cast<std::uint32_t>(f));
      usable[f] = probed[f] || MeshFaceIsProper(mesh, static_cast<std::uint32_t>(f));
    }
  });
  // Vertices whose fan is certified (CertifyFan): two faces that meet at one have no
  // other common point, or only their common edge, so they need no test. Nearly all
  // the pairs the tree yields are faces with a common vertex, and nearly every
  // vertex of a valid mesh is certified.
  const std::vector<std::uint8_t> certified = CertifiedFans(mesh);
  auto                            meetAtCertifiedVertex = [&](std::uint32_t f, std::uint32_t g) {
    const auto & t = mesh.triangles[f];
    const auto & u = mesh.triangles[g];
    for (unsigned int i = 0; i < 3; ++i)
    {
      if ((t[i] == u[0] || t[i] == u[1] || t[i] == u[2]) && certified[t[i]])
      {
        return true;
      }
    }
    return false;
  };
  auto acceptApart = [&](std::uint32_t f, std::uint32_t g) {
    return boxes[f].Overlaps(boxes[g]) && (probed[f] || probed[g]) && usable[f] && usable[g];
  };
  auto accept = [&](std::uint32_t f, std::uint32_t g) {
    // The common-vertex test first: it turns away nearly every pair.
    return f < n && g < n && !meetAtCertifiedVertex(f, g) && acceptApart(f, g);
  };
  return cache != nullptr ? SearchWithCache(mesh, tree, boxes, certified, *cache, accept, acceptApart)
                          : IntersectingOverlappingPairs(mesh, tree, accept);
}
} // namespace

std::vector<std::pair<std::uint32_t, std::uint32_t>>
FindSelfIntersections(const IndexedTriangleMesh &        mesh,
                      const std::vector<std::uint32_t> & queries,
                      const TriangleAABBTree &           tree,
                      SelfIntersectionCache *            cache)
{
  std::vector<bool>                probed(mesh.triangles.size(), false);
  const std::vector<std::uint32_t> probes = ProperProbes(mesh, queries, probed);
  if (4 * probes.size() > mesh.triangles.size())
  {
    return SweepSearch(mesh, tree, probed, cache);
  }
  // Few probes: one tree query each.
  return IntersectingQueryPairs(
    mesh,
    tree,
    probes,
    2048,
    [&mesh](std::uint32_t f) { return TriangleBox(mesh, f); },
    [&probed](std::uint32_t g) { return probed[g]; },
    [&](std::uint32_t f, std::uint32_t g) {
      return TriangleBox(mesh, g).Overlaps(TriangleBox(mesh, f)) && MeshFaceIsProper(mesh, g);
    });
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

bool
TriangleMeshQualityReport::IsValidClosedSurface() const
{
  return IsClosed() && IsManifold() && IsConsistentlyOriented() && degenerateTriangles == 0 &&
         invertedTrianglesVersusOutward <= 0 && invertedTrianglesVersusReference <= 0 && selfIntersectingPairs <= 0 &&
         enclosedVolume > 0.0;
}

void
TriangleMeshQualityReport::Print(std::ostream & os, const std::string & title) const
{
  const auto flags = os.flags();
  const auto precision = os.precision();
  if (!title.empty())
  {
    os << title << '\n';
  }
  os << "  points " << numberOfPoints << " (" << numberOfReferencedPoints << " in triangles), triangles "
     << numberOfTriangles;
  if (numberOfSplitQuads)
  {
    os << " (" << numberOfSplitQuads << " quads split)";
  }
  os << ", edges " << numberOfEdges << '\n';
  os << "  " << std::left << std::setw(16) << "measure" << std::right << std::setw(10) << "mean" << std::setw(10)
     << "min" << std::setw(10) << "p05" << std::setw(10) << "median" << std::setw(10) << "max" << '\n';
  PrintStatistics(os, "q_area", qArea);
  PrintStatistics(os, "q_angle", qAngle);
  PrintStatistics(os, "q_length", qLength);
  PrintStatistics(os, "min angle (deg)", minimumAngle);
  PrintStatistics(os, "max angle (deg)", maximumAngle);
  PrintStatistics(os, "edge length", edgeLength);
  os << std::setprecision(4) << "  q_angle < 0.3: " << 100.0 * fractionQAngleBelow03
     << " %   smoothness |2pi-sum|: " << std::setprecision(6) << meanSmoothness
     << "   valence 6: " << std::setprecision(2) << 100.0 * fractionValence6 << " %\n";
  os << "  valence histogram:";
  for (std::size_t d = 0; d < valenceHistogram.size(); ++d)
  {
    if (valenceHistogram[d])
    {
      os << ' ' << d << ':' << valenceHistogram[d];
    }
  }
  os << '\n';
  auto count = [](std::int64_t v) {
    std::ostringstream s;
    if (v < 0)
    {
      s << "n/a";
    }
    else
    {
      s << v;
    }
    return s.str();
  };
  os << "  integrity: degenerate " << degenerateTriangles << ", inverted (outward) "
     << count(invertedTrianglesVersusOutward) << ", inverted (reference) " << count(invertedTrianglesVersusReference)
     << ", self-intersecting pairs " << count(selfIntersectingPairs) << '\n';
  os << "             non-manifold edges " << nonManifoldEdges << ", non-manifold vertices " << nonManifoldVertices
     << ", boundary edges " << boundaryEdges << " in " << boundaryLoops << " loops, inconsistent edges "
     << inconsistentlyOrientedEdges << '\n';
  os << "  topology: components " << connectedComponents << ", Euler characteristic " << eulerCharacteristic
     << ", genus " << count(genus) << ", unreferenced points " << unreferencedPoints << '\n';
  os << std::setprecision(6) << "  area " << totalArea << ", enclosed volume " << enclosedVolume << '\n';
  os << "  valid closed surface: " << (IsValidClosedSurface() ? "yes" : "NO") << '\n';
  os.flags(flags);
  os.precision(precision);
}

void
TriangleMeshQualityReport::PrintJSON(std::ostream & os) const
{
  const auto precision = os.precision();
  os << std::setprecision(10);
  os << "{\"points\": " << numberOfPoints << ", \"referenced_points\": " << numberOfReferencedPoints
     << ", \"triangles\": " << numberOfTriangles << ", \"split_quads\": " << numberOfSplitQuads
     << ", \"edges\": " << numberOfEdges;
  os << ", \"q_area\": ";
  PrintStatisticsJSON(os, qArea);
  os << ", \"q_angle\": ";
  PrintStatisticsJSON(os, qAngle);
  os << ", \"q_length\": ";
  PrintStatisticsJSON(os, qLength);
  os << ", \"min_angle_deg\": ";
  PrintStatisticsJSON(os, minimumAngle);
  os << ", \"max_angle_deg\": ";
  PrintStatisticsJSON(os, maximumAngle);
  os << ", \"edge_length\": ";
  PrintStatisticsJSON(os, edgeLength);
  os << ", \"fraction_q_angle_below_0_3\": " << JSONNumber{ fractionQAngleBelow03 }
     << ", \"mean_smoothness\": " << JSONNumber{ meanSmoothness }
     << ", \"interior_vertices\": " << numberOfInteriorVertices
     << ", \"fraction_valence_6\": " << JSONNumber{ fractionValence6 } << ", \"valence_histogram\": [";
  for (std::size_t d = 0; d < valenceHistogram.size(); ++d)
  {
    os << (d ? ", " : "") << valenceHistogram[d];
  }
  os << "], \"degenerate_triangles\": " << degenerateTriangles
     << ", \"inverted_triangles_vs_reference\": " << invertedTrianglesVersusReference
     << ", \"inverted_triangles_vs_outward\": " << invertedTrianglesVersusOutward
     << ", \"undetermined_orientation_triangles\": " << undeterminedOrientationTriangles
     << ", \"non_manifold_edges\": " << nonManifoldEdges << ", \"non_manifold_vertices\": " << nonManifoldVertices
     << ", \"boundary_edges\": " << boundaryEdges << ", \"boundary_loops\": " << boundaryLoops
     << ", \"inconsistently_oriented_edges\": " << inconsistentlyOrientedEdges
     << ", \"unreferenced_points\": " << unreferencedPoints << ", \"connected_components\": " << connectedComponents
     << ", \"euler_characteristic\": " << eulerCharacteristic << ", \"genus\": " << genus
     << ", \"self_intersecting_pairs\": " << selfIntersectingPairs
     << ", \"self_intersecting_triangles\": " << selfIntersectingTriangles
     << ", \"total_area\": " << JSONNumber{ totalArea } << ", \"enclosed_volume\": " << JSONNumber{ enclosedVolume }
     << ", \"valid_closed_surface\": " << (IsValidClosedSurface() ? "true" : "false") << "}";
  os.precision(precision);
}

} // namespace MeshExtraction
} // namespace itk
