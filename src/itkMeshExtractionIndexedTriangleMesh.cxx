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
#include "itkMeshExtractionIndexedTriangleMesh.h"
#include "itkMeshExtractionDisjointSets.h"

#include <algorithm>
#include <limits>
#include <numeric>

namespace itk
{
namespace MeshExtraction
{
namespace
{
using detail::DisjointSets;

constexpr std::uint32_t NoEdge = std::numeric_limits<std::uint32_t>::max();

void
BuildRows(std::size_t                                                  n,
          const std::vector<std::pair<std::uint32_t, std::uint32_t>> & pairs,
          std::vector<std::uint32_t> &                                 offsets,
          std::vector<std::uint32_t> &                                 values)
{
  offsets.assign(n + 1, 0);
  for (const auto & p : pairs)
  {
    ++offsets[p.first + 1];
  }
  std::partial_sum(offsets.begin(), offsets.end(), offsets.begin());
  values.resize(pairs.size());
  std::vector<std::uint32_t> cursor(offsets.begin(), offsets.end() - 1);
  for (const auto & p : pairs)
  {
    values[cursor[p.first]++] = p.second;
  }
}
/** A side of a triangle, keyed by its undirected edge (smaller vertex in the high
 * bits). */
struct HalfEdge
{
  std::uint64_t key;
  std::uint32_t triangle;
  std::uint32_t side;
};

/** The half-edges of the triangles (sides with two distinct vertices) sorted by key,
 * then triangle, then side: the groups of equal keys are the edges. */
std::vector<HalfEdge>
SortedHalfEdges(const IndexedTriangleMesh & mesh)
{
  std::vector<HalfEdge> halfEdges;
  halfEdges.reserve(3 * mesh.triangles.size());
  for (std::uint32_t f = 0; f < mesh.triangles.size(); ++f)
  {
    const auto & t = mesh.triangles[f];
    for (std::uint32_t k = 0; k < 3; ++k)
    {
      const std::uint32_t u = t[k];
      const std::uint32_t v = t[(k + 1) % 3];
      if (u == v)
      {
        continue; // a repeated vertex: no edge (the triangle is degenerate)
      }
      const std::uint64_t key = (static_cast<std::uint64_t>(std::min(u, v)) << 32) | std::max(u, v);
      halfEdges.push_back({ key, f, k });
    }
  }
  std::sort(halfEdges.begin(), halfEdges.end(), [](const HalfEdge & x, const HalfEdge & y) {
    return x.key != y.key ? x.key < y.key : (x.triangle != y.triangle ? x.triangle < y.triangle : x.side < y.side);
  });
  return halfEdges;
}

/** 1. The edges, their incidences and the triangles' sides' edges from the sorted
 * half-edges, counting boundary, non-manifold and inconsistently oriented edges. */
void
BuildEdges(const IndexedTriangleMesh & mesh, MeshTopology & topo)
{
  const std::vector<HalfEdge> halfEdges = SortedHalfEdges(mesh);
  topo.triangleEdges.assign(mesh.triangles.size(), { NoEdge, NoEdge, NoEdge });
  topo.incidences.reserve(halfEdges.size());
  for (std::size_t i = 0; i < halfEdges.size();)
  {
    std::size_t        j = i;
    MeshTopology::Edge edge{};
    edge.a = static_cast<std::uint32_t>(halfEdges[i].key >> 32);
    edge.b = static_cast<std::uint32_t>(halfEdges[i].key & 0xffffffffu);
    edge.firstIncidence = static_cast<std::uint32_t>(topo.incidences.size());
    const auto edgeIndex = static_cast<std::uint32_t>(topo.edges.size());
    for (; j < halfEdges.size() && halfEdges[j].key == halfEdges[i].key; ++j)
    {
      const HalfEdge & h = halfEdges[j];
      const bool       forward = mesh.triangles[h.triangle][h.side] == edge.a;
      topo.incidences.push_back({ h.triangle, forward });
      topo.triangleEdges[h.triangle][h.side] = edgeIndex;
    }
    edge.numberOfIncidences = static_cast<std::uint32_t>(j - i);
    if (edge.numberOfIncidences == 1)
    {
      ++topo.numberOfBoundaryEdges;
    }
    else if (edge.numberOfIncidences > 2)
    {
      ++topo.numberOfNonManifoldEdges;
    }
    else if (topo.incidences[edge.firstIncidence].forward == topo.incidences[edge.firstIncidence + 1].forward)
    {
      ++topo.numberOfInconsistentEdges;
    }
    topo.edges.push_back(edge);
    i = j;
  }
}

/** 2. Vertex -> triangles (each triangle once per distinct vertex) and vertex -> edges. */
void
BuildVertexRows(const IndexedTriangleMesh & mesh, MeshTopology & topo)
{
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  pairs.reserve(3 * mesh.triangles.size());
  for (std::uint32_t f = 0; f < mesh.triangles.size(); ++f)
  {
    const auto & t = mesh.triangles[f];
    for (unsigned int k = 0; k < 3; ++k)
    {
      if (k == 0 || (t[k] != t[0] && (k == 1 || t[k] != t[1])))
      {
        pairs.emplace_back(t[k], f);
      }
    }
  }
  BuildRows(mesh.points.size(), pairs, topo.vertexTriangleOffsets, topo.vertexTriangles);
  pairs.clear();
  for (std::uint32_t e = 0; e < topo.edges.size(); ++e)
  {
    pairs.emplace_back(topo.edges[e].a, e);
    pairs.emplace_back(topo.edges[e].b, e);
  }
  BuildRows(mesh.points.size(), pairs, topo.vertexEdgeOffsets, topo.vertexEdges);
}

/** 3. Connected components of triangles (joined across shared edges), numbered in
 * the order of their first triangles. */
void
LabelComponents(std::size_t numberOfTriangles, MeshTopology & topo)
{
  DisjointSets triangleSets(numberOfTriangles);
  for (const auto & e : topo.edges)
  {
    for (std::uint32_t k = 1; k < e.numberOfIncidences; ++k)
    {
      triangleSets.Join(topo.incidences[e.firstIncidence].triangle, topo.incidences[e.firstIncidence + k].triangle);
    }
  }
  topo.triangleComponent.assign(numberOfTriangles, 0);
  std::vector<std::uint32_t> label(numberOfTriangles, NoEdge);
  for (std::uint32_t f = 0; f < numberOfTriangles; ++f)
  {
    const std::uint32_t root = triangleSets.Find(f);
    if (label[root] == NoEdge)
    {
      label[root] = static_cast<std::uint32_t>(topo.numberOfComponents++);
    }
    topo.triangleComponent[f] = label[root];
  }
}

/** The work arrays of CountFans, kept between vertices. */
struct FanScratchSets
{
  std::vector<std::uint32_t> local;
  std::vector<std::uint32_t> localParent;
};

/** The number of fans of the triangles at vertex v: the sets of them connected
 * through edges at v. `allEdgesManifold` tells whether every edge at v has two
 * triangles. */
std::size_t
CountFans(const MeshTopology & topo, std::uint32_t v, FanScratchSets & scratch, bool & allEdgesManifold)
{
  std::vector<std::uint32_t> & local = scratch.local;
  std::vector<std::uint32_t> & localParent = scratch.localParent;
  local.assign(topo.vertexTriangles.begin() + topo.vertexTriangleOffsets[v],
               topo.vertexTriangles.begin() + topo.vertexTriangleOffsets[v + 1]);
  localParent.resize(local.size());
  std::iota(localParent.begin(), localParent.end(), 0u);
  auto find = [&localParent](std::uint32_t x) {
    while (localParent[x] != x)
    {
      x = localParent[x] = localParent[localParent[x]];
    }
    return x;
  };
  auto position = [&local](std::uint32_t triangle) {
    return static_cast<std::uint32_t>(std::find(local.begin(), local.end(), triangle) - local.begin());
  };
  allEdgesManifold = true;
  for (std::uint32_t i = topo.vertexEdgeOffsets[v]; i < topo.vertexEdgeOffsets[v + 1]; ++i)
  {
    const MeshTopology::Edge & e = topo.edges[topo.vertexEdges[i]];
    allEdgesManifold = allEdgesManifold && e.numberOfIncidences == 2;
    const std::uint32_t first = position(topo.incidences[e.firstIncidence].triangle);
    for (std::uint32_t k = 1; k < e.numberOfIncidences; ++k)
    {
      const std::uint32_t a = find(first);
      const std::uint32_t b = find(position(topo.incidences[e.firstIncidence + k].triangle));
      localParent[std::max(a, b)] = std::min(a, b);
    }
  }
  std::size_t fans = 0;
  for (std::uint32_t i = 0; i < local.size(); ++i)
  {
    fans += find(i) == i ? 1 : 0;
  }
  return fans;
}

/** 4. Fans around each vertex: a vertex whose triangles are not all connected
 *    through edges at that vertex is non-manifold (a "bow-tie"); one with a single
 *    fan and only manifold edges is interior. */
void
ClassifyVertices(std::size_t numberOfPoints, MeshTopology & topo)
{
  topo.vertexIsInterior.assign(numberOfPoints, false);
  topo.vertexIsNonManifold.assign(numberOfPoints, false);
  FanScratchSets scratch;
  for (std::uint32_t v = 0; v < numberOfPoints; ++v)
  {
    if (topo.vertexTriangleOffsets[v] == topo.vertexTriangleOffsets[v + 1])
    {
      continue;
    }
    ++topo.numberOfReferencedVertices;
    bool              allEdgesManifold = true;
    const std::size_t fans = CountFans(topo, v, scratch, allEdgesManifold);
    if (fans > 1)
    {
      topo.vertexIsNonManifold[v] = true;
      ++topo.numberOfNonManifoldVertices;
    }
    topo.vertexIsInterior[v] = fans == 1 && allEdgesManifold;
  }
}

/** 5. Boundary loops: connected sets of boundary edges, counted per component. */
void
CountBoundaryLoops(std::size_t numberOfPoints, MeshTopology & topo)
{
  topo.componentBoundaryLoops.assign(topo.numberOfComponents, 0);
  if (topo.numberOfBoundaryEdges == 0)
  {
    return;
  }
  DisjointSets vertexSets(numberOfPoints);
  for (const auto & e : topo.edges)
  {
    if (e.numberOfIncidences == 1)
    {
      vertexSets.Join(e.a, e.b);
    }
  }
  std::vector<bool> seen(numberOfPoints, false);
  for (const auto & e : topo.edges)
  {
    if (e.numberOfIncidences != 1)
    {
      continue;
    }
    const std::uint32_t root = vertexSets.Find(e.a);
    if (!seen[root])
    {
      seen[root] = true;
      ++topo.numberOfBoundaryLoops;
      ++topo.componentBoundaryLoops[topo.triangleComponent[topo.incidences[e.firstIncidence].triangle]];
    }
  }
}
} // namespace

namespace detail
{
void
SplitQuad(const IndexedTriangleMesh & mesh, const std::uint32_t q[4], TriangleIndices & t0, TriangleIndices & t1)
{
  const double d02 = SquaredNorm(mesh.points[q[0]] - mesh.points[q[2]]);
  const double d13 = SquaredNorm(mesh.points[q[1]] - mesh.points[q[3]]);
  if (d02 <= d13)
  {
    t0 = { q[0], q[1], q[2] };
    t1 = { q[0], q[2], q[3] };
  }
  else
  {
    t0 = { q[0], q[1], q[3] };
    t1 = { q[1], q[2], q[3] };
  }
}

PointIdentifierMap::PointIdentifierMap(IdentifierType maximumIdentifier, std::size_t numberOfPoints)
    : m_MaximumIdentifier(maximumIdentifier)
    , m_Dense(maximumIdentifier < 4 * static_cast<IdentifierType>(numberOfPoints) + 1024)
    , m_Table(m_Dense ? maximumIdentifier + 1 : 0, Missing)
{}

void
PointIdentifierMap::ThrowMissingPoint(IdentifierType id, IdentifierType cellId)
{
  itkGenericExceptionMacro("MeshExtraction: cell " << cellId << " references point " << id
                                                   << ", which the mesh does not have.");
}
} // namespace detail

std::uint32_t
MeshTopology::Neighbor(std::uint32_t triangle, unsigned int side) const
{
  const Edge & e = edges[triangleEdges[triangle][side]];
  if (e.numberOfIncidences != 2)
  {
    return std::numeric_limits<std::uint32_t>::max();
  }
  const Incidence & i0 = incidences[e.firstIncidence];
  return i0.triangle == triangle ? incidences[e.firstIncidence + 1].triangle : i0.triangle;
}

MeshTopology
BuildMeshTopology(const IndexedTriangleMesh & mesh)
{
  MeshTopology topo;
  BuildEdges(mesh, topo);
  BuildVertexRows(mesh, topo);
  LabelComponents(mesh.triangles.size(), topo);
  ClassifyVertices(mesh.points.size(), topo);
  CountBoundaryLoops(mesh.points.size(), topo);
  return topo;
}

} // namespace MeshExtraction
} // namespace itk
