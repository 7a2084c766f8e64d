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
#include "itkMeshExtractionRayParity.h"
#include "itkMeshExtractionParallel.h"
#include "itkMeshExtractionSelfIntersections.h"
#include "itkMeshExtractionTriangleAABBTree.h"

#include <cmath>
#include <limits>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
namespace
{
Vec3
AnyPerpendicular(const Vec3 & n)
{
  const Vec3 axis = std::abs(n[0]) < 0.6 ? MakeVec3(1, 0, 0) : MakeVec3(0, 1, 0);
  Vec3       u = Cross(n, axis);
  return u * (1.0 / Norm(u));
}

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

} // namespace detail
} // namespace MeshExtraction
} // namespace itk
