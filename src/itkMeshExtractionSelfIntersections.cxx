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
#include "itkMeshExtractionSelfIntersections.h"
#include "itkMeshExtractionParallel.h"
#include "itkMeshExtractionPredicates.h"
#include "itkMeshExtractionTriangleAABBTree.h"

#include <algorithm>
#include <numeric>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
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
  if (2 * asked.size() > valid.size())
  {
    // Most faces asked (a smoothing step moves nearly all): the tree against itself
    // visits each overlapping pair once, where a query per face meets each twice.
    return IntersectingOverlappingPairs(
      mesh, tree, [&probed](std::uint32_t f, std::uint32_t g) { return probed[f] || probed[g]; });
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

} // namespace detail
} // namespace MeshExtraction
} // namespace itk
