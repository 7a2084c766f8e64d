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
// Internal to MeshExtraction (namespace detail): not part of the public API.
#ifndef itkMeshExtractionTriangleAABBTree_h
#define itkMeshExtractionTriangleAABBTree_h

#include "MeshExtractionExport.h"
#include "itkMeshExtractionIndexedTriangleMesh.h"
#include "itkMeshExtractionLargeBlockVector.h"

#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
/** \brief Axis-aligned box in double precision. \ingroup MeshExtraction */
struct AxisAlignedBox
{
  double lower[3]{ std::numeric_limits<double>::max(),
                   std::numeric_limits<double>::max(),
                   std::numeric_limits<double>::max() };
  double upper[3]{ std::numeric_limits<double>::lowest(),
                   std::numeric_limits<double>::lowest(),
                   std::numeric_limits<double>::lowest() };

  void
  Add(const Vec3 & p)
  {
    for (unsigned int d = 0; d < 3; ++d)
    {
      lower[d] = std::min(lower[d], p[d]);
      upper[d] = std::max(upper[d], p[d]);
    }
  }
  void
  Add(const AxisAlignedBox & b)
  {
    for (unsigned int d = 0; d < 3; ++d)
    {
      lower[d] = std::min(lower[d], b.lower[d]);
      upper[d] = std::max(upper[d], b.upper[d]);
    }
  }
  bool
  Overlaps(const AxisAlignedBox & b) const
  {
    return lower[0] <= b.upper[0] && b.lower[0] <= upper[0] && lower[1] <= b.upper[1] && b.lower[1] <= upper[1] &&
           lower[2] <= b.upper[2] && b.lower[2] <= upper[2];
  }
  double
  HalfPerimeter() const
  {
    return (upper[0] - lower[0]) + (upper[1] - lower[1]) + (upper[2] - lower[2]);
  }
  double
  SquaredDistance(const Vec3 & p) const
  {
    double s = 0.0;
    for (unsigned int d = 0; d < 3; ++d)
    {
      const double e = std::max({ lower[d] - p[d], 0.0, p[d] - upper[d] });
      s += e * e;
    }
    return s;
  }
  /** Entry parameter of the ray origin + t * inverseDirection^-1 into the box, or
   * +infinity if the ray misses it. */
  double
  RayEntry(const Vec3 & origin, const double inverseDirection[3]) const
  {
    double tNear = 0.0;
    double tFar = std::numeric_limits<double>::infinity();
    for (unsigned int d = 0; d < 3; ++d)
    {
      double t0 = (lower[d] - origin[d]) * inverseDirection[d];
      double t1 = (upper[d] - origin[d]) * inverseDirection[d];
      if (t0 > t1)
      {
        std::swap(t0, t1);
      }
      if (t0 != t0 || t1 != t1) // 0 * inf: the ray is in the slab's plane
      {
        if (origin[d] < lower[d] || origin[d] > upper[d])
        {
          return std::numeric_limits<double>::infinity();
        }
        continue;
      }
      tNear = std::max(tNear, t0);
      tFar = std::min(tFar, t1);
      if (tNear > tFar)
      {
        return std::numeric_limits<double>::infinity();
      }
    }
    return tNear;
  }
};

/** One box per triangle, on huge pages where large (LargeBlockVector). */
using AxisAlignedBoxArray = LargeBlockVector<AxisAlignedBox>;

inline AxisAlignedBox
TriangleBox(const IndexedTriangleMesh & mesh, std::uint32_t triangle)
{
  AxisAlignedBox b;
  for (std::uint32_t v : mesh.triangles[triangle])
  {
    b.Add(mesh.points[v]);
  }
  return b;
}

/** \brief Bounding-volume hierarchy of axis-aligned boxes over the triangles of
 * an IndexedTriangleMesh: nearest-triangle queries (exact point-to-triangle
 * distance), box-overlap and ray queries.
 *
 * Built top-down by median splits along the widest axis of the triangle centroids,
 * stored depth-first in one array. The tree keeps a pointer to the mesh, which
 * must outlive it. Queries are const and thread-safe.
 *
 * The traversals (VisitOverlapping, VisitOverlappingPairs, VisitRay) are templates
 * on the visitor and stay in this header, as do SplitPair and the box tests of
 * AxisAlignedBox and TriangleBox: they run for every node and primitive a query
 * visits, where a call that cannot be inlined would cost as much as the test itself.
 * Building and refitting, once per tree, are in the .cxx.
 * \ingroup MeshExtraction
 */
class MeshExtraction_EXPORT TriangleAABBTree
{
public:
  struct Nearest
  {
    std::uint32_t triangle{ std::numeric_limits<std::uint32_t>::max() };
    double        squaredDistance{ std::numeric_limits<double>::infinity() };
    Vec3          point{ 0.0 };
  };

  TriangleAABBTree() = default;

  /** Build over all triangles, or over `subset` (triangle indices) if given. With
   * `boxes` (one per triangle of the mesh), those boxes are stored instead of the
   * triangles' own: boxes that enclose a triangle over a range of positions give a
   * tree that stays valid while its vertices move within that range (overlap
   * queries only; FindNearest needs exact boxes). */
  void
  Build(const IndexedTriangleMesh &        mesh,
        const std::vector<std::uint32_t> * subset = nullptr,
        const AxisAlignedBoxArray *        boxes = nullptr);

  /** Keep the tree's shape but give its primitives new boxes (one per triangle of
   * the mesh, as in Build) and recompute the nodes' boxes bottom-up: O(n), for
   * triangles whose vertices moved a little, or that an edge swap exchanged with a
   * neighbour, since Build. Queries stay exact (every box is tight over its
   * children); they only slow down if the boxes wander far. Requires a tree built over
   * all triangles of a mesh with boxes.size() triangles (else throws). */
  void
  Refit(const IndexedTriangleMesh & mesh, const AxisAlignedBoxArray & boxes);

  bool
  IsEmpty() const
  {
    return m_Nodes.empty();
  }

  /** Number of triangles the tree holds. */
  std::size_t
  GetNumberOfTriangles() const
  {
    return m_Triangles.size();
  }

  /** Closest point of the mesh to p (over the triangles in the tree). */
  Nearest
  FindNearest(const Vec3 & p) const;
  /** The same, started from the triangle `hint` (e.g. the answer for a point nearby):
   * faster, and the same distance; where several triangles are equally near, it may name
   * another of them than the search without a hint. */
  Nearest
  FindNearest(const Vec3 & p, std::uint32_t hint) const;

  /** Calls visit(triangle) for every triangle whose box overlaps `box`. */
  template <typename TVisitor>
  void
  VisitOverlapping(const AxisAlignedBox & box, TVisitor && visit) const
  {
    if (m_Nodes.empty())
    {
      return;
    }
    std::uint32_t stack[128];
    unsigned int  top = 0;
    stack[top++] = 0;
    while (top > 0)
    {
      const Node & node = m_Nodes[stack[--top]];
      if (!node.box.Overlaps(box))
      {
        continue;
      }
      if (node.count > 0)
      {
        for (std::uint32_t i = node.first; i < node.first + node.count; ++i)
        {
          if (m_Boxes[i].Overlaps(box))
          {
            visit(m_Triangles[i]);
          }
        }
      }
      else
      {
        stack[top++] = node.first;
        stack[top++] = node.first + 1;
      }
    }
  }

  /** A pair of nodes whose overlapping primitives are still to be visited (see
   * SplitOverlappingPairs and VisitOverlappingPairs). */
  using NodePair = std::pair<std::uint32_t, std::uint32_t>;

  /** The start of a simultaneous traversal of the tree against itself: node pairs
   * that together cover every pair of primitives with overlapping boxes exactly once,
   * split breadth-first until there are at least `minimumNumberOfPairs` (or nothing is
   * left to split), so that VisitOverlappingPairs can work on them in parallel. */
  std::vector<NodePair>
  SplitOverlappingPairs(std::size_t minimumNumberOfPairs) const;

  /** Calls visit(a, b), a != b triangles, once for every unordered pair of primitives
   * under the node pair whose boxes overlap. */
  template <typename TVisitor>
  void
  VisitOverlappingPairs(const NodePair & start, TVisitor && visit) const
  {
    std::vector<NodePair> stack{ start };
    std::vector<NodePair> children;
    while (!stack.empty())
    {
      const NodePair p = stack.back();
      stack.pop_back();
      const Node & a = m_Nodes[p.first];
      const Node & b = m_Nodes[p.second];
      if (a.count > 0 && b.count > 0)
      {
        if (p.first == p.second)
        {
          for (std::uint32_t i = a.first; i < a.first + a.count; ++i)
          {
            for (std::uint32_t j = i + 1; j < a.first + a.count; ++j)
            {
              if (m_Boxes[i].Overlaps(m_Boxes[j]))
              {
                visit(m_Triangles[i], m_Triangles[j]);
              }
            }
          }
        }
        else
        {
          for (std::uint32_t i = a.first; i < a.first + a.count; ++i)
          {
            if (!m_Boxes[i].Overlaps(b.box))
            {
              continue;
            }
            for (std::uint32_t j = b.first; j < b.first + b.count; ++j)
            {
              if (m_Boxes[i].Overlaps(m_Boxes[j]))
              {
                visit(m_Triangles[i], m_Triangles[j]);
              }
            }
          }
        }
        continue;
      }
      children.clear();
      this->SplitPair(p, children);
      stack.insert(stack.end(), children.begin(), children.end());
    }
  }

  /** Calls visit(triangle) for every triangle whose box the ray origin + t d,
   * t >= 0, enters. */
  template <typename TVisitor>
  void
  VisitRay(const Vec3 & origin, const Vec3 & direction, TVisitor && visit) const
  {
    if (m_Nodes.empty())
    {
      return;
    }
    double inverse[3];
    for (unsigned int d = 0; d < 3; ++d)
    {
      inverse[d] = 1.0 / direction[d];
    }
    std::uint32_t stack[128];
    unsigned int  top = 0;
    stack[top++] = 0;
    constexpr double infinity = std::numeric_limits<double>::infinity();
    while (top > 0)
    {
      const Node & node = m_Nodes[stack[--top]];
      if (node.box.RayEntry(origin, inverse) == infinity)
      {
        continue;
      }
      if (node.count > 0)
      {
        for (std::uint32_t i = node.first; i < node.first + node.count; ++i)
        {
          if (m_Boxes[i].RayEntry(origin, inverse) != infinity)
          {
            visit(m_Triangles[i]);
          }
        }
      }
      else
      {
        stack[top++] = node.first;
        stack[top++] = node.first + 1;
      }
    }
  }

private:
  /** (Morton code, slot) of every primitive slot, sorted. */
  using MortonKeys = LargeBlockVector<std::pair<std::uint64_t, std::uint32_t>>;

  /** The nodes, top-down, over the slots in the order of `keys`: each range splits
   * where the highest differing bit of its codes changes, leaves hold up to 16 slots. */
  void
  BuildNodes(const MortonKeys & keys);

  /** Node boxes bottom-up from the primitives' boxes. */
  void
  FitNodeBoxes();

  /** Appends what replaces the node pair p in the traversal: p itself if both are
   * leaves (returns false), nothing if their boxes are apart, else the pairs of
   * children (a node against itself: its two children against themselves and each
   * other). */
  bool
  SplitPair(const NodePair & p, std::vector<NodePair> & out) const
  {
    const Node & a = m_Nodes[p.first];
    const Node & b = m_Nodes[p.second];
    if (p.first == p.second)
    {
      if (a.count > 0)
      {
        out.push_back(p);
        return false;
      }
      out.emplace_back(a.first, a.first);
      out.emplace_back(a.first + 1, a.first + 1);
      if (m_Nodes[a.first].box.Overlaps(m_Nodes[a.first + 1].box))
      {
        out.emplace_back(a.first, a.first + 1);
      }
      return true;
    }
    if (!a.box.Overlaps(b.box))
    {
      return true;
    }
    if (a.count > 0 && b.count > 0)
    {
      out.push_back(p);
      return false;
    }
    // Split the inner node with the larger box (or the only inner one).
    const bool splitA = b.count > 0 || (a.count == 0 && a.box.HalfPerimeter() >= b.box.HalfPerimeter());
    if (splitA)
    {
      out.emplace_back(a.first, p.second);
      out.emplace_back(a.first + 1, p.second);
    }
    else
    {
      out.emplace_back(p.first, b.first);
      out.emplace_back(p.first, b.first + 1);
    }
    return true;
  }

  struct Node
  {
    AxisAlignedBox box;
    std::uint32_t  first{ 0 }; ///< leaf: first primitive slot; inner: index of the left child (right = left + 1)
    std::uint32_t  count{ 0 }; ///< number of primitives; 0 for an inner node
  };

  const IndexedTriangleMesh * m_Mesh{ nullptr };
  // Large arrays on huge pages (LargeBlockVector): the trees of large meshes span
  // thousands of 4 KiB pages, and each first touch of one costs a page fault.
  LargeBlockVector<Node>          m_Nodes;
  LargeBlockVector<std::uint32_t> m_Triangles; ///< triangle of each primitive slot
  AxisAlignedBoxArray             m_Boxes;     ///< box of each primitive slot
};

} // namespace detail
} // namespace MeshExtraction
} // namespace itk

#endif
