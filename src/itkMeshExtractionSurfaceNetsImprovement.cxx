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

#include <algorithm>
#include <numeric>

namespace itk
{
namespace MeshExtraction
{
namespace
{
constexpr std::uint32_t None = std::numeric_limits<std::uint32_t>::max();

inline std::uint32_t
Next(std::uint32_t h)
{
  return h - h % 3 + (h % 3 + 1) % 3;
}
inline std::uint32_t
Previous(std::uint32_t h)
{
  return h - h % 3 + (h % 3 + 2) % 3;
}
} // namespace

std::vector<Vec3>
ToPhysical(const std::vector<Vec3> & index, const Vec3 & origin, const Matrix<double, 3, 3> & M)
{
  std::vector<Vec3> physical(index.size());
  for (std::size_t i = 0; i < index.size(); ++i)
  {
    Vec3 p = origin;
    for (unsigned int r = 0; r < 3; ++r)
    {
      for (unsigned int c = 0; c < 3; ++c)
      {
        p[r] += M[r][c] * index[i][c];
      }
    }
    physical[i] = p;
  }
  return physical;
}

void
SurfaceNetTriangles::BuildConnectivity(std::size_t numberOfPoints)
{
  const std::size_t n = triangles.size();
  struct Key
  {
    std::uint64_t edge;
    std::uint32_t halfEdge;
  };
  std::vector<Key> keys(3 * n);
  for (std::uint32_t f = 0; f < n; ++f)
  {
    for (std::uint32_t k = 0; k < 3; ++k)
    {
      const std::uint32_t u = triangles[f][k];
      const std::uint32_t v = triangles[f][(k + 1) % 3];
      keys[3 * f + k] = { (static_cast<std::uint64_t>(std::min(u, v)) << 32) | std::max(u, v), 3 * f + k };
    }
  }
  std::sort(keys.begin(), keys.end(),
            [](const Key & x, const Key & y) { return x.edge != y.edge ? x.edge < y.edge : x.halfEdge < y.halfEdge; });
  twin.assign(3 * n, None);
  for (std::size_t i = 0; i < keys.size();)
  {
    if (i + 1 >= keys.size() || keys[i + 1].edge != keys[i].edge ||
        (i + 2 < keys.size() && keys[i + 2].edge == keys[i].edge))
    {
      itkGenericExceptionMacro("SurfaceNets: internal error: the triangles do not form a closed 2-manifold.");
    }
    twin[keys[i].halfEdge] = keys[i + 1].halfEdge;
    twin[keys[i + 1].halfEdge] = keys[i].halfEdge;
    i += 2;
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
  const std::size_t          numberOfNodes = net.positions.size();
  std::vector<std::uint32_t> count(numberOfNodes + 1, 0);
  for (const auto & t : triangles)
  {
    for (unsigned int k = 0; k < 3; ++k)
    {
      ++count[t[k] + 1]; // each half-edge u->v gives v to u once on a closed surface
    }
  }
  std::partial_sum(count.begin(), count.end(), count.begin());
  net.neighborStart = count;
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
SwapEdges(const std::vector<Vec3> & physical, SurfaceNetTriangles & mesh, const EdgeSwapParameters & parameters)
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
    const EdgeSwapDecision gainOnly = EvaluateEdgeSwap(q, parameters);
    if (gainOnly.verdict == EdgeSwapVerdict::NoImprovement)
    {
      continue;
    }
    q.oppositeEdgeExists = !q.sameApex && mesh.HasEdge(c, d, 3 * f + (k + 2) % 3);
    if (!EvaluateEdgeSwap(q, parameters).Swap())
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

std::size_t
UndoIntersectingSwaps(const std::vector<Vec3> & physical, SurfaceNetTriangles & mesh, std::vector<EdgeSwapRecord> & swaps)
{
  std::size_t         undone = 0;
  IndexedTriangleMesh check;
  check.points = physical;
  std::vector<std::uint32_t> changed;
  for (const auto & s : swaps)
  {
    changed.push_back(s.first);
    changed.push_back(s.second);
  }
  while (!changed.empty())
  {
    check.triangles = mesh.triangles;
    const auto pairs = FindSelfIntersections(check, &changed);
    if (pairs.empty())
    {
      break;
    }
    std::vector<bool> bad(mesh.triangles.size(), false);
    for (const auto & p : pairs)
    {
      bad[p.first] = true;
      bad[p.second] = true;
    }
    changed.clear();
    std::vector<EdgeSwapRecord> kept;
    for (const auto & s : swaps)
    {
      if (bad[s.first] || bad[s.second])
      {
        mesh.triangles[s.first] = s.oldFirst;
        mesh.triangles[s.second] = s.oldSecond;
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
      // Intersections that no swap of this sweep caused: not expected, leave them to
      // the caller's checks.
      break;
    }
    swaps.swap(kept);
  }
  if (undone > 0)
  {
    mesh.BuildConnectivity(physical.size());
  }
  return undone;
}

std::size_t
PullBackInvalidMoves(std::vector<Vec3> &                  positions,
                     const std::vector<Vec3> &            start,
                     const std::vector<TriangleIndices> & triangles,
                     const Vec3 &                         origin,
                     const Matrix<double, 3, 3> &         M,
                     double                               tolerance)
{
  const std::vector<Vec3> startPhysical = ToPhysical(start, origin, M);
  std::vector<Vec3>       startNormals(triangles.size());
  for (std::size_t f = 0; f < triangles.size(); ++f)
  {
    const auto & t = triangles[f];
    startNormals[f] = TriangleNormal(startPhysical[t[0]], startPhysical[t[1]], startPhysical[t[2]]);
  }
  std::vector<bool>         moved(positions.size(), false);
  std::vector<unsigned int> pulls(positions.size(), 0);
  std::vector<bool>         changedVertex(positions.size(), true);
  IndexedTriangleMesh       check;
  check.triangles = triangles;
  for (unsigned int round = 0; round < 64; ++round)
  {
    check.points = ToPhysical(positions, origin, M);
    std::vector<std::uint32_t> candidates;
    for (std::uint32_t f = 0; f < triangles.size(); ++f)
    {
      const auto & t = triangles[f];
      if (changedVertex[t[0]] || changedVertex[t[1]] || changedVertex[t[2]])
      {
        candidates.push_back(f);
      }
    }
    std::vector<std::uint32_t> badNodes;
    for (std::uint32_t f : candidates)
    {
      const auto & t = triangles[f];
      const Vec3 & a = check.points[t[0]];
      const Vec3 & b = check.points[t[1]];
      const Vec3 & c = check.points[t[2]];
      if (!(Dot(TriangleNormal(a, b, c), startNormals[f]) > 0.0) || !(MeasureTriangle(a, b, c).qArea > tolerance))
      {
        badNodes.insert(badNodes.end(), t.begin(), t.end());
      }
    }
    for (const auto & p : FindSelfIntersections(check, &candidates))
    {
      badNodes.insert(badNodes.end(), triangles[p.first].begin(), triangles[p.first].end());
      badNodes.insert(badNodes.end(), triangles[p.second].begin(), triangles[p.second].end());
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
      positions[v] = ++pulls[v] > 4 ? start[v] : start[v] + (positions[v] - start[v]) * 0.5;
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
