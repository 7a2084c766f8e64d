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
#include "itkMeshExtractionClosedSurfaceEdgeSwap.h"
#include "itkMeshExtractionLargeBlockVector.h"

#include <algorithm>
#include <limits>
#include <numeric>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
namespace
{
constexpr std::uint32_t None = std::numeric_limits<std::uint32_t>::max();

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
  // half-edges of an edge meet. O(n), and each sort is over the few edges at one
  // vertex instead of one sort of all 3n edge keys.
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

} // namespace detail
} // namespace MeshExtraction
} // namespace itk
