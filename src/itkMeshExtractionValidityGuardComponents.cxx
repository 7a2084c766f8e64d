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
// The validity guard's component checks: the one definition of a collapsed
// component, the volumes it is measured against, and the filter that tells which
// components a move can have passed.
#include "itkMeshExtractionValidityGuard.h"
#include "itkMeshExtractionParallel.h"
#include "itkMeshExtractionQualityAnalysis.h"
#include "itkMeshExtractionTriangleAABBTree.h"

#include <algorithm>
#include <cmath>
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

/** The path of each component's ComponentRayVertices vertex from its start to its
 * current position, as a box, with the components that have such a vertex sorted by
 * the lower x of their boxes. */
struct ComponentPaths
{
  std::vector<std::uint32_t>  vertex;
  std::vector<AxisAlignedBox> path;
  std::vector<std::uint32_t>  order;
  std::vector<double>         lowerX; ///< path[order[i]].lower[0]
  double                      widest{ 0.0 };
};

ComponentPaths
SortedComponentPaths(const IndexedTriangleMesh & mesh,
                     const MeshTopology &        topology,
                     const std::vector<Vec3> &   startPositions)
{
  const std::size_t components = topology.numberOfComponents;
  ComponentPaths    p;
  p.vertex = ComponentRayVertices(mesh, topology);
  p.path.resize(components);
  for (std::uint32_t c = 0; c < components; ++c)
  {
    if (p.vertex[c] != None)
    {
      p.path[c].Add(startPositions[p.vertex[c]]);
      p.path[c].Add(mesh.points[p.vertex[c]]);
      p.order.push_back(c);
      p.widest = std::max(p.widest, p.path[c].upper[0] - p.path[c].lower[0]);
    }
  }
  const auto & path = p.path;
  std::sort(p.order.begin(), p.order.end(), [&path](std::uint32_t a, std::uint32_t b) {
    return path[a].lower[0] < path[b].lower[0] || (path[a].lower[0] == path[b].lower[0] && a < b);
  });
  p.lowerX.resize(p.order.size());
  for (std::size_t i = 0; i < p.order.size(); ++i)
  {
    p.lowerX[i] = p.path[p.order[i]].lower[0];
  }
  return p;
}

/** Appends to `found` the components of other triangles than f's own whose path box
 * overlaps the box of f's start and end, where f or the component's vertex moved. */
void
ComponentsTriangleMayHavePassed(const IndexedTriangleMesh &  mesh,
                                const MeshTopology &         topology,
                                const std::vector<Vec3> &    startPositions,
                                const ComponentPaths &       p,
                                std::size_t                  f,
                                std::vector<std::uint32_t> & found)
{
  const auto &   t = mesh.triangles[f];
  AxisAlignedBox box;
  bool           moved = false;
  for (const auto v : t)
  {
    box.Add(startPositions[v]);
    box.Add(mesh.points[v]);
    moved = moved || mesh.points[v] != startPositions[v];
  }
  const std::uint32_t own = topology.triangleComponent[f];
  for (auto i = static_cast<std::size_t>(std::lower_bound(p.lowerX.begin(), p.lowerX.end(), box.lower[0] - p.widest) -
                                         p.lowerX.begin());
       i < p.order.size() && p.lowerX[i] <= box.upper[0];
       ++i)
  {
    const std::uint32_t c = p.order[i];
    if (c != own && (moved || mesh.points[p.vertex[c]] != startPositions[p.vertex[c]]) && box.Overlaps(p.path[c]))
    {
      found.push_back(c);
    }
  }
}
} // namespace

bool
IsCollapsedComponent(double start, double now, double reference, double fraction)
{
  const bool turnedInsideOut = (start > 0.0 && !(now > 0.0)) || (start < 0.0 && !(now < 0.0));
  return turnedInsideOut || std::abs(now) < fraction * std::abs(reference);
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
    collapsed[c] =
      IsCollapsedComponent(reference[c], volume[c], reference[c], ValidityThresholds::HighQualityCollapseFraction);
  }
  return collapsed;
}

ComponentReference
MakeComponentReference(const IndexedTriangleMesh & mesh, const MeshTopology & topology)
{
  ComponentReference r;
  std::vector<Vec3>  origin(topology.numberOfComponents);
  for (std::size_t f = mesh.triangles.size(); f-- > 0;)
  {
    origin[topology.triangleComponent[f]] = mesh.points[mesh.triangles[f][0]];
  }
  r.sixVolumes = ComponentSixVolumes(
    mesh.triangles, mesh.points, origin, [&topology](std::size_t f) { return topology.triangleComponent[f]; });
  r.nesting = ComponentNestingParity(mesh, topology);
  return r;
}

std::vector<std::uint32_t>
ComponentsAMoveMayHavePassed(const IndexedTriangleMesh & mesh,
                             const MeshTopology &        topology,
                             const std::vector<Vec3> &   startPositions)
{
  const std::size_t                       components = topology.numberOfComponents;
  const ComponentPaths                    paths = SortedComponentPaths(mesh, topology, startPositions);
  constexpr std::size_t                   blockSize = 8192;
  std::vector<std::vector<std::uint32_t>> found((mesh.triangles.size() + blockSize - 1) / blockSize);
  ParallelForBlocks(mesh.triangles.size(), blockSize, [&](std::size_t begin, std::size_t end, std::size_t block) {
    for (std::size_t f = begin; f < end; ++f)
    {
      ComponentsTriangleMayHavePassed(mesh, topology, startPositions, paths, f, found[block]);
    }
  });
  std::vector<std::uint8_t> flagged(components, 0);
  for (const auto & list : found)
  {
    for (const auto c : list)
    {
      flagged[c] = 1;
    }
  }
  std::vector<std::uint32_t> result;
  for (std::uint32_t c = 0; c < components; ++c)
  {
    if (flagged[c])
    {
      result.push_back(c);
    }
  }
  return result;
}

} // namespace detail
} // namespace MeshExtraction
} // namespace itk
