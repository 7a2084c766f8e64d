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
#include "itkMeshExtractionSurfaceNetsImprovement.h"
#include "itkMeshExtractionParallel.h"
#include "itkMeshExtractionQualityAnalysis.h"
#include "itkMeshExtractionTriangleAABBTree.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace itk
{
namespace MeshExtraction
{
namespace
{
constexpr std::uint32_t None = std::numeric_limits<std::uint32_t>::max();

/** A tree over all triangles of `mesh` with `boxes`: built the first time, refitted
 * (same shape, new boxes) when it already holds that many triangles. */
void
BuildOrRefit(TriangleAABBTree & tree, const IndexedTriangleMesh & mesh, const AxisAlignedBoxArray & boxes)
{
  if (!tree.IsEmpty() && tree.GetNumberOfTriangles() == mesh.triangles.size())
  {
    tree.Refit(mesh, boxes);
  }
  else
  {
    tree.Build(mesh, nullptr, &boxes);
  }
}

inline std::uint32_t
Previous(std::uint32_t h)
{
  return h - h % 3 + (h % 3 + 2) % 3;
}

/** The ends of half-edge h, the smaller first. */
inline std::pair<std::uint32_t, std::uint32_t>
EdgeEnds(const std::vector<TriangleIndices> & triangles, std::uint32_t h)
{
  const std::uint32_t u = triangles[h / 3][h % 3];
  const std::uint32_t v = triangles[h / 3][(h % 3 + 1) % 3];
  return std::make_pair(std::min(u, v), std::max(u, v));
}

/** Sorts the half-edges [first, last) by their edge and makes the two of each edge
 * twins; throws with `problem` where an edge has one half-edge there, or more than two. */
template <typename TIterator>
void
LinkTwins(const std::vector<TriangleIndices> & triangles,
          std::vector<std::uint32_t> &         twin,
          TIterator                            first,
          TIterator                            last,
          const char *                         problem)
{
  std::sort(first, last, [&triangles](std::uint32_t x, std::uint32_t y) {
    const auto ex = EdgeEnds(triangles, x);
    const auto ey = EdgeEnds(triangles, y);
    return ex != ey ? ex < ey : x < y;
  });
  for (auto i = first; i != last; i += 2)
  {
    const auto ends = EdgeEnds(triangles, *i);
    if (i + 1 == last || EdgeEnds(triangles, *(i + 1)) != ends ||
        (i + 2 != last && EdgeEnds(triangles, *(i + 2)) == ends))
    {
      itkGenericExceptionMacro("SurfaceNets: internal error: " << problem);
    }
    twin[*i] = *(i + 1);
    twin[*(i + 1)] = *i;
  }
}
} // namespace

void
SurfaceNetTriangles::BuildConnectivity(std::size_t numberOfPoints)
{
  // The half-edges grouped by the lower vertex of their edge (counting sort, in
  // half-edge order), then each group sorted by the upper vertex: the two
  // half-edges of an edge meet. O(n), where one sort of all 3n edge keys took
  // 45 ms for 222,528 triangles.
  const std::size_t               n = triangles.size();
  LargeBlockVector<std::uint32_t> start(numberOfPoints + 1, 0);
  for (const auto & t : triangles)
  {
    for (std::uint32_t v : t)
    {
      if (v >= numberOfPoints)
      {
        itkGenericExceptionMacro("SurfaceNets: internal error: a triangle refers to node " << v << " of "
                                                                                           << numberOfPoints << '.');
      }
    }
  }
  const auto numberOfHalfEdges = static_cast<std::uint32_t>(3 * n);
  for (std::uint32_t h = 0; h < numberOfHalfEdges; ++h)
  {
    ++start[EdgeEnds(triangles, h).first + 1];
  }
  std::partial_sum(start.begin(), start.end(), start.begin());
  LargeBlockVector<std::uint32_t> grouped(numberOfHalfEdges);
  {
    LargeBlockVector<std::uint32_t> cursor(start.begin(), start.end() - 1);
    for (std::uint32_t h = 0; h < numberOfHalfEdges; ++h)
    {
      grouped[cursor[EdgeEnds(triangles, h).first]++] = h;
    }
  }
  twin.assign(numberOfHalfEdges, None);
  for (std::size_t a = 0; a < numberOfPoints; ++a)
  {
    LinkTwins(triangles,
              twin,
              grouped.begin() + start[a],
              grouped.begin() + start[a + 1],
              "the triangles do not form a closed 2-manifold.");
  }
  valence.assign(numberOfPoints, 0);
  for (const auto & t : triangles)
  {
    for (std::uint32_t v : t)
    {
      ++valence[v]; // on a closed surface: edges at v = triangles at v
    }
  }
}

void
SurfaceNetTriangles::ReplaceTriangles(const std::vector<std::pair<std::uint32_t, TriangleIndices>> & replacements)
{
  std::vector<std::uint32_t> faces;
  for (const auto & r : replacements)
  {
    faces.push_back(r.first);
  }
  std::sort(faces.begin(), faces.end());
  faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
  auto replaced = [&faces](std::uint32_t f) { return std::binary_search(faces.begin(), faces.end(), f); };
  // The half-edges to pair anew: the faces' own, and the reverse of each of their
  // edges on the border of the part they cover (in faces that stay), which the same
  // part has either way.
  std::vector<std::uint32_t> halfEdges;
  for (std::uint32_t f : faces)
  {
    for (unsigned int k = 0; k < 3; ++k)
    {
      halfEdges.push_back(3 * f + k);
      if (!replaced(twin[3 * f + k] / 3))
      {
        halfEdges.push_back(twin[3 * f + k]);
      }
      --valence[triangles[f][k]];
    }
  }
  for (const auto & r : replacements)
  {
    triangles[r.first] = r.second;
  }
  for (std::uint32_t f : faces)
  {
    for (std::uint32_t v : triangles[f])
    {
      ++valence[v];
    }
  }
  LinkTwins(
    triangles, twin, halfEdges.begin(), halfEdges.end(), "the replaced triangles do not close up with the rest.");
}

bool
SurfaceNetTriangles::HasEdge(std::uint32_t, std::uint32_t v, std::uint32_t fromU) const
{
  // Rotate around u: from half-edge u->x, the previous half-edge of its triangle
  // ends at u; its twin leaves u.
  std::uint32_t h = fromU;
  for (unsigned int guard = 0; guard < 4096; ++guard)
  {
    if (triangles[h / 3][(h % 3 + 1) % 3] == v)
    {
      return true;
    }
    h = twin[Previous(h)];
    if (h == fromU)
    {
      return false;
    }
  }
  return false;
}

void
SurfaceNetTriangles::FillLinks(SurfaceNet & net) const
{
  const std::size_t numberOfNodes = net.positions.size();
  auto &            count = net.neighborStart;
  count.assign(numberOfNodes + 1, 0);
  for (const auto & t : triangles)
  {
    for (unsigned int k = 0; k < 3; ++k)
    {
      ++count[t[k] + 1]; // each half-edge u->v gives v to u once on a closed surface
    }
  }
  std::partial_sum(count.begin(), count.end(), count.begin());
  net.neighbors.assign(count.back(), 0);
  std::vector<std::uint32_t> cursor(count.begin(), count.end() - 1);
  for (const auto & t : triangles)
  {
    for (unsigned int k = 0; k < 3; ++k)
    {
      net.neighbors[cursor[t[k]]++] = t[(k + 1) % 3];
    }
  }
  for (std::size_t v = 0; v < numberOfNodes; ++v)
  {
    std::sort(net.neighbors.begin() + net.neighborStart[v], net.neighbors.begin() + net.neighborStart[v + 1]);
  }
}

std::vector<EdgeSwapRecord>
SwapEdges(const std::vector<Vec3> &          physical,
          SurfaceNetTriangles &              mesh,
          const EdgeSwapParameters &         parameters,
          const std::vector<std::uint64_t> * refused)
{
  std::vector<EdgeSwapRecord> records;
  std::vector<bool>           touched(mesh.triangles.size(), false);
  const auto                  numberOfHalfEdges = static_cast<std::uint32_t>(mesh.twin.size());
  for (std::uint32_t h = 0; h < numberOfHalfEdges; ++h)
  {
    const std::uint32_t t = mesh.twin[h];
    if (t < h)
    {
      continue; // each edge once
    }
    const std::uint32_t f = h / 3;
    const std::uint32_t g = t / 3;
    if (touched[f] || touched[g] || f == g)
    {
      continue;
    }
    const std::uint32_t k = h % 3;
    const std::uint32_t m = t % 3;
    const std::uint32_t a = mesh.triangles[f][k];
    const std::uint32_t b = mesh.triangles[f][(k + 1) % 3];
    const std::uint32_t c = mesh.triangles[f][(k + 2) % 3];
    const std::uint32_t d = mesh.triangles[g][(m + 2) % 3];
    EdgeSwapQuad        q;
    q.a = physical[a];
    q.b = physical[b];
    q.c = physical[c];
    q.d = physical[d];
    q.valenceA = mesh.valence[a];
    q.valenceB = mesh.valence[b];
    q.valenceC = mesh.valence[c];
    q.valenceD = mesh.valence[d];
    q.sameApex = c == d;
    // The criterion first, then (for the few edges it would swap) the lookups and
    // the checks.
    double gain = 0.0;
    if (!EdgeSwapImproves(q, parameters, gain))
    {
      continue;
    }
    if (refused != nullptr && std::binary_search(refused->begin(), refused->end(), EdgeKey(a, b)))
    {
      continue;
    }
    q.oppositeEdgeExists = !q.sameApex && mesh.HasEdge(c, d, 3 * f + (k + 2) % 3);
    if (CheckEdgeSwap(q, parameters) != EdgeSwapVerdict::Swap)
    {
      continue;
    }
    records.push_back({ f, g, mesh.triangles[f], mesh.triangles[g] });
    // f = (a, b, c), g = (b, a, d)  ->  f = (a, d, c), g = (d, b, c).
    const std::uint32_t bc = mesh.twin[3 * f + (k + 1) % 3];
    const std::uint32_t ca = mesh.twin[3 * f + (k + 2) % 3];
    const std::uint32_t ad = mesh.twin[3 * g + (m + 1) % 3];
    const std::uint32_t db = mesh.twin[3 * g + (m + 2) % 3];
    mesh.triangles[f] = { a, d, c };
    mesh.triangles[g] = { d, b, c };
    auto link = [&mesh](std::uint32_t x, std::uint32_t y) {
      mesh.twin[x] = y;
      mesh.twin[y] = x;
    };
    link(3 * f + 0, ad);
    link(3 * f + 1, 3 * g + 2);
    link(3 * f + 2, ca);
    link(3 * g + 0, db);
    link(3 * g + 1, bc);
    --mesh.valence[a];
    --mesh.valence[b];
    ++mesh.valence[c];
    ++mesh.valence[d];
    touched[f] = true;
    touched[g] = true;
  }
  return records;
}

void
ComponentVolumes::Initialize(const std::vector<TriangleIndices> & triangles, const std::vector<Vec3> & points)
{
  // Union-find over the vertices, joined along the triangles' edges.
  std::vector<std::uint32_t> parent(points.size());
  std::iota(parent.begin(), parent.end(), std::uint32_t{ 0 });
  auto find = [&parent](std::uint32_t v) {
    while (parent[v] != v)
    {
      parent[v] = parent[parent[v]];
      v = parent[v];
    }
    return v;
  };
  for (const auto & t : triangles)
  {
    for (unsigned int k = 0; k < 2; ++k)
    {
      const std::uint32_t a = find(t[k]);
      const std::uint32_t b = find(t[k + 1]);
      if (a != b)
      {
        parent[std::max(a, b)] = std::min(a, b);
      }
    }
  }
  vertexComponent.assign(points.size(), None);
  origin.clear();
  std::vector<std::uint32_t> label(points.size(), None);
  for (const auto & t : triangles)
  {
    for (std::uint32_t v : t)
    {
      const std::uint32_t root = find(v);
      if (label[root] == None)
      {
        label[root] = static_cast<std::uint32_t>(origin.size());
        origin.push_back(points[v]);
      }
      vertexComponent[v] = label[root];
    }
  }
  reference =
    ComponentSixVolumes(triangles, points, origin, [&](std::size_t f) { return vertexComponent[triangles[f][0]]; });
}

std::vector<bool>
ComponentVolumes::Collapsed(const std::vector<TriangleIndices> & triangles, const std::vector<Vec3> & points) const
{
  std::vector<bool> collapsed(reference.size(), false);
  if (reference.empty())
  {
    return collapsed;
  }
  const std::vector<double> volume =
    ComponentSixVolumes(triangles, points, origin, [&](std::size_t f) { return vertexComponent[triangles[f][0]]; });
  for (std::size_t c = 0; c < reference.size(); ++c)
  {
    // Not (same sign and at least a quarter of the magnitude); NaN counts as collapsed.
    collapsed[c] = !(volume[c] * reference[c] > 0.0 && std::abs(volume[c]) >= 0.25 * std::abs(reference[c]));
  }
  return collapsed;
}

std::size_t
UndoIntersectingSwaps(const std::vector<Vec3> &     physical,
                      SurfaceNetTriangles &         mesh,
                      std::vector<EdgeSwapRecord> & swaps,
                      std::vector<std::uint64_t> *  refused,
                      TriangleAABBTree *            sharedTree,
                      const ComponentVolumes *      volumes)
{
  std::size_t         undone = 0;
  IndexedTriangleMesh check;
  check.points = physical;
  check.triangles = mesh.triangles;
  // Positions are fixed here: a swapped pair, swapped or not, stays inside the box of
  // its four corners, so one tree serves every check below.
  AxisAlignedBoxArray boxes(mesh.triangles.size());
  ParallelForBlocks(mesh.triangles.size(), 8192, [&](std::size_t begin, std::size_t end, std::size_t) {
    for (std::size_t f = begin; f < end; ++f)
    {
      boxes[f] = TriangleBox(check, static_cast<std::uint32_t>(f));
    }
  });
  std::vector<std::uint32_t> changed;
  for (const auto & s : swaps)
  {
    AxisAlignedBox quad = boxes[s.first];
    quad.Add(boxes[s.second]);
    boxes[s.first] = quad;
    boxes[s.second] = quad;
    changed.push_back(s.first);
    changed.push_back(s.second);
  }
  if (swaps.empty())
  {
    return 0;
  }
  TriangleAABBTree   localTree;
  TriangleAABBTree & tree = sharedTree != nullptr ? *sharedTree : localTree;
  BuildOrRefit(tree, check, boxes);
  while (!changed.empty())
  {
    const auto        pairs = FindSelfIntersections(check, changed, tree);
    std::vector<bool> bad(mesh.triangles.size(), false);
    bool              anyBad = !pairs.empty();
    for (const auto & p : pairs)
    {
      bad[p.first] = true;
      bad[p.second] = true;
    }
    // Folds against a neighbour (twins are those of the current triangles).
    for (std::uint32_t f : changed)
    {
      const auto & t = mesh.triangles[f];
      const Vec3   n = TriangleNormal(physical[t[0]], physical[t[1]], physical[t[2]]);
      for (unsigned int k = 0; k < 3; ++k)
      {
        const std::uint32_t g = mesh.twin[3 * f + k] / 3;
        const auto &        u = mesh.triangles[g];
        const Vec3          m = TriangleNormal(physical[u[0]], physical[u[1]], physical[u[2]]);
        if (Dot(n, m) < FoldCosine * Norm(n) * Norm(m))
        {
          bad[f] = true;
          bad[g] = true;
          anyBad = true;
        }
      }
    }
    // Components that a swap turned inside out or flattened: their swaps are undone.
    if (volumes != nullptr)
    {
      const std::vector<bool> collapsed = volumes->Collapsed(check.triangles, physical);
      for (const auto & s : swaps)
      {
        if (collapsed[volumes->vertexComponent[mesh.triangles[s.first][0]]])
        {
          bad[s.first] = true;
          anyBad = true;
        }
      }
    }
    if (!anyBad)
    {
      break;
    }
    changed.clear();
    std::vector<EdgeSwapRecord>                            kept;
    std::vector<std::pair<std::uint32_t, TriangleIndices>> restored;
    for (const auto & s : swaps)
    {
      if (bad[s.first] || bad[s.second])
      {
        if (refused != nullptr)
        {
          // The swapped edge runs between the two corners the old triangles share.
          const auto & t = s.oldFirst;
          for (unsigned int k = 0; k < 3; ++k)
          {
            const std::uint32_t a = t[k];
            const std::uint32_t b = t[(k + 1) % 3];
            const auto &        u = s.oldSecond;
            if ((u[0] == a || u[1] == a || u[2] == a) && (u[0] == b || u[1] == b || u[2] == b))
            {
              refused->push_back(EdgeKey(a, b));
            }
          }
        }
        restored.emplace_back(s.first, s.oldFirst);
        restored.emplace_back(s.second, s.oldSecond);
        changed.push_back(s.first);
        changed.push_back(s.second);
        ++undone;
      }
      else
      {
        kept.push_back(s);
      }
    }
    if (changed.empty())
    {
      // Defects that no swap of this sweep caused: not expected, leave them to the
      // caller's checks.
      break;
    }
    swaps.swap(kept);
    mesh.ReplaceTriangles(restored);
    for (const auto & r : restored)
    {
      check.triangles[r.first] = r.second; // the rest is as before
    }
  }
  if (refused != nullptr)
  {
    std::sort(refused->begin(), refused->end());
    refused->erase(std::unique(refused->begin(), refused->end()), refused->end());
  }
  return undone;
}

std::size_t
PullBackInvalidMoves(LargeBlockVector<Vec3> &       positions,
                     const LargeBlockVector<Vec3> & start,
                     const SurfaceNetTriangles &    mesh,
                     const Vec3 &                   origin,
                     const Matrix<double, 3, 3> &   M,
                     double                         tolerance,
                     bool                           roundToFloat,
                     TriangleAABBTree *             sharedTree,
                     SelfIntersectionCache *        cache,
                     const ComponentVolumes *       volumes)
{
  const auto &           triangles = mesh.triangles;
  const std::size_t      numberOfTriangles = triangles.size();
  LargeBlockVector<Vec3> startPhysical(start.size());
  ToPhysical(start.data(), start.size(), origin, M, roundToFloat, startPhysical.data());
  // The per-triangle loops below are independent per triangle: they run on the work
  // units (the results do not depend on their number).
  constexpr std::size_t BlockSize = 8192;
  // Each face's normal (not normalised) with its length, at `start` and, below, at the
  // current positions: every fold test reads two faces' of them instead of computing
  // both normals and lengths again, once from each side of every edge.
  struct FaceNormal
  {
    Vec3   normal;
    double length;
  };
  auto faceNormal = [&triangles](const auto & points, std::size_t f) {
    const auto & t = triangles[f];
    const Vec3   n = TriangleNormal(points[t[0]], points[t[1]], points[t[2]]);
    return FaceNormal{ n, Norm(n) };
  };
  LargeBlockVector<FaceNormal> startNormals(numberOfTriangles);
  ParallelForBlocks(numberOfTriangles, BlockSize, [&](std::size_t begin, std::size_t end, std::size_t) {
    for (std::size_t f = begin; f < end; ++f)
    {
      startNormals[f] = faceNormal(startPhysical, f);
    }
  });
  auto folded = [](const FaceNormal & n, const FaceNormal & m) {
    return Dot(n.normal, m.normal) < FoldCosine * n.length * m.length;
  };
  // The cosine of the angle between the normals went down (both as n.m / (|n| |m|)).
  auto foldClosed = [](const FaceNormal & n0, const FaceNormal & m0, const FaceNormal & n, const FaceNormal & m) {
    return Dot(n.normal, m.normal) * n0.length * m0.length < Dot(n0.normal, m0.normal) * n.length * m.length;
  };
  std::vector<std::uint8_t> foldedAtStart(numberOfTriangles, 0);
  IndexedTriangleMesh       check;
  check.triangles = triangles;
  check.points = ToPhysical(positions, origin, M, roundToFloat);
  // Nodes only move back toward `start`: a tree of boxes around both positions of
  // every triangle serves every round.
  AxisAlignedBoxArray boxes(numberOfTriangles);
  ParallelForBlocks(numberOfTriangles, BlockSize, [&](std::size_t begin, std::size_t end, std::size_t) {
    for (std::size_t f = begin; f < end; ++f)
    {
      for (unsigned int k = 0; k < 3; ++k)
      {
        if (folded(startNormals[f], startNormals[mesh.twin[3 * f + k] / 3]))
        {
          foldedAtStart[f] |= static_cast<std::uint8_t>(1u << k);
        }
      }
      for (std::uint32_t v : triangles[f])
      {
        boxes[f].Add(check.points[v]);
        boxes[f].Add(startPhysical[v]);
      }
    }
  });
  if (cache != nullptr)
  {
    // The cache needs boxes grown by half its margin: 0.4 of the mean edge length,
    // set on the first call (0.3, 0.5 and 0.65 made the checks of a high-quality run
    // on the 256^3 sphere slower: 340-380 ms against 290-300 ms).
    if (!(cache->margin > 0.0))
    {
      double      sum = 0.0;
      std::size_t count = 0;
      for (const auto & t : triangles)
      {
        for (unsigned int k = 0; k < 3; ++k)
        {
          const double length = std::sqrt(SquaredNorm(startPhysical[t[k]] - startPhysical[t[(k + 1) % 3]]));
          if (std::isfinite(length))
          {
            sum += length;
            ++count;
          }
        }
      }
      cache->margin = count > 0 ? 0.4 * sum / static_cast<double>(count) : 0.0;
    }
    for (auto & box : boxes)
    {
      for (unsigned int d = 0; d < 3; ++d)
      {
        box.lower[d] -= 0.5 * cache->margin;
        box.upper[d] += 0.5 * cache->margin;
      }
    }
  }
  TriangleAABBTree   localTree;
  TriangleAABBTree & tree = sharedTree != nullptr ? *sharedTree : localTree;
  BuildOrRefit(tree, check, boxes);

  std::vector<bool>         moved(positions.size(), false);
  std::vector<unsigned int> pulls(positions.size(), 0);
  std::vector<bool>         changedVertex(positions.size(), false);
  for (std::size_t v = 0; v < positions.size(); ++v)
  {
    changedVertex[v] = positions[v] != start[v]; // `start` is valid: only moved nodes matter
  }
  std::vector<std::uint32_t> candidateList; // kept from round to round
  // The normals at check.points: the start normals until a face's vertex moves (the
  // same points, made by the same ToPhysical, so the same bits); each round computes
  // those of its candidates.
  LargeBlockVector<FaceNormal> normals = startNormals;
  for (unsigned int round = 0; round < 64; ++round)
  {
    if (round > 0)
    {
      check.points = ToPhysical(positions, origin, M, roundToFloat);
    }
    std::vector<std::uint32_t> & candidates = candidateList;
    candidates.clear();
    for (std::uint32_t f = 0; f < numberOfTriangles; ++f)
    {
      const auto & t = triangles[f];
      if (changedVertex[t[0]] || changedVertex[t[1]] || changedVertex[t[2]])
      {
        candidates.push_back(f);
      }
    }
    ParallelForBlocks(candidates.size(), BlockSize, [&](std::size_t begin, std::size_t end, std::size_t) {
      for (std::size_t i = begin; i < end; ++i)
      {
        normals[candidates[i]] = faceNormal(check.points, candidates[i]);
      }
    });
    // Flipped, degenerate or newly folded candidates, per block (the nodes are sorted
    // and made unique below, so the blocks' order does not matter).
    std::vector<std::vector<std::uint32_t>> badPerBlock((candidates.size() + BlockSize - 1) / BlockSize);
    ParallelForBlocks(candidates.size(), BlockSize, [&](std::size_t begin, std::size_t end, std::size_t block) {
      auto & bad = badPerBlock[block];
      for (std::size_t i = begin; i < end; ++i)
      {
        const std::uint32_t f = candidates[i];
        const auto &        t = triangles[f];
        const Vec3 &        a = check.points[t[0]];
        const Vec3 &        b = check.points[t[1]];
        const Vec3 &        c = check.points[t[2]];
        if (!(Dot(normals[f].normal, startNormals[f].normal) > 0.0) || !(TriangleQArea(a, b, c) > tolerance))
        {
          bad.insert(bad.end(), t.begin(), t.end());
          continue;
        }
        for (unsigned int k = 0; k < 3; ++k)
        {
          const std::uint32_t g = mesh.twin[3 * f + k] / 3;
          // A new fold, or a fold at `start` that closed further: left alone, the
          // faces of a fold can close onto each other (two nodes with the same
          // 1-ring, pulled to one point, leave a component of no volume).
          if (((foldedAtStart[f] >> k) & 1u) ? foldClosed(startNormals[f], startNormals[g], normals[f], normals[g])
                                             : folded(normals[f], normals[g]))
          {
            const auto & u = triangles[g];
            bad.insert(bad.end(), t.begin(), t.end());
            bad.insert(bad.end(), u.begin(), u.end());
          }
        }
      }
    });
    std::vector<std::uint32_t> badNodes;
    for (const auto & bad : badPerBlock)
    {
      badNodes.insert(badNodes.end(), bad.begin(), bad.end());
    }
    for (const auto & p : FindSelfIntersections(check, candidates, tree, cache))
    {
      badNodes.insert(badNodes.end(), triangles[p.first].begin(), triangles[p.first].end());
      badNodes.insert(badNodes.end(), triangles[p.second].begin(), triangles[p.second].end());
    }
    if (volumes != nullptr)
    {
      // Components turned inside out or flattened: all their moved nodes.
      const std::vector<bool> collapsed = volumes->Collapsed(triangles, check.points);
      if (std::find(collapsed.begin(), collapsed.end(), true) != collapsed.end())
      {
        for (std::uint32_t v = 0; v < positions.size(); ++v)
        {
          const std::uint32_t c = volumes->vertexComponent[v];
          if (c != None && collapsed[c] && positions[v] != start[v])
          {
            badNodes.push_back(v);
          }
        }
      }
    }
    std::sort(badNodes.begin(), badNodes.end());
    badNodes.erase(std::unique(badNodes.begin(), badNodes.end()), badNodes.end());
    std::fill(changedVertex.begin(), changedVertex.end(), false);
    if (badNodes.empty())
    {
      break;
    }
    for (std::uint32_t v : badNodes)
    {
      if (positions[v] == start[v])
      {
        continue; // already back: the other nodes of its triangles will move
      }
      moved[v] = true;
      changedVertex[v] = true;
      positions[v] = ++pulls[v] > 1 ? start[v] : start[v] + (positions[v] - start[v]) * 0.5;
    }
    if (round == 63)
    {
      positions = start; // not expected; `start` was valid
    }
  }
  return static_cast<std::size_t>(std::count(moved.begin(), moved.end(), true));
}

} // namespace MeshExtraction
} // namespace itk
