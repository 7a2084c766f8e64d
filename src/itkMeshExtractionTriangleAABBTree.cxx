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
#include "itkMeshExtractionTriangleAABBTree.h"
#include "itkMacro.h"

#include <algorithm>
#include <numeric>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
namespace
{
/** Sort (code, slot) pairs by code, then slot: LSD radix sort on 16-bit digits of the
 * code (a digit that every key shares is skipped) over slots in increasing order, so
 * the stable passes leave equal codes in slot order, as std::sort of the pairs does,
 * in linear time. */
void
SortKeys(LargeBlockVector<std::pair<std::uint64_t, std::uint32_t>> & keys)
{
  const std::size_t n = keys.size();
  if (n < 2048)
  {
    std::sort(keys.begin(), keys.end());
    return;
  }
  LargeBlockVector<std::pair<std::uint64_t, std::uint32_t>> buffer(n);
  std::vector<std::uint32_t>                                count(1u << 16);
  for (unsigned int shift = 0; shift < 64; shift += 16)
  {
    std::fill(count.begin(), count.end(), 0u);
    for (const auto & k : keys)
    {
      ++count[(k.first >> shift) & 0xffffu];
    }
    if (count[(keys[0].first >> shift) & 0xffffu] == n)
    {
      continue; // every key has this digit
    }
    std::uint32_t sum = 0;
    for (auto & c : count)
    {
      const std::uint32_t here = c;
      c = sum;
      sum += here;
    }
    for (const auto & k : keys)
    {
      buffer[count[(k.first >> shift) & 0xffffu]++] = k;
    }
    keys.swap(buffer);
  }
}

Vec3
BoxCentre(const AxisAlignedBox & box)
{
  Vec3 c;
  for (unsigned int d = 0; d < 3; ++d)
  {
    c[d] = 0.5 * (box.lower[d] + box.upper[d]);
  }
  return c;
}

/** The low 21 bits of x spread to every third bit (bit i to bit 3 i). */
std::uint64_t
SpreadBits(std::uint64_t x)
{
  x &= 0x1fffff;
  x = (x | (x << 32)) & 0x1f00000000ffffULL;
  x = (x | (x << 16)) & 0x1f0000ff0000ffULL;
  x = (x | (x << 8)) & 0x100f00f00f00f00fULL;
  x = (x | (x << 4)) & 0x10c30c30c30c30c3ULL;
  x = (x | (x << 2)) & 0x1249249249249249ULL;
  return x;
}

/** The 63-bit Morton (Z-order) codes of the centres of the n slots' boxes, boxOf(i),
 * quantised to 21 bits per axis over the centres' bounds, paired with their slots and
 * sorted (SortKeys). */
template <typename TBoxOf>
LargeBlockVector<std::pair<std::uint64_t, std::uint32_t>>
SortedMortonKeys(std::size_t n, TBoxOf && boxOf)
{
  AxisAlignedBox centreBounds;
  for (std::size_t i = 0; i < n; ++i)
  {
    centreBounds.Add(BoxCentre(boxOf(i)));
  }
  LargeBlockVector<std::pair<std::uint64_t, std::uint32_t>> keys(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    const Vec3    centre = BoxCentre(boxOf(i));
    std::uint64_t code = 0;
    for (unsigned int d = 0; d < 3; ++d)
    {
      const double extent = centreBounds.upper[d] - centreBounds.lower[d];
      const double t = extent > 0.0 ? (centre[d] - centreBounds.lower[d]) / extent : 0.0;
      const auto   q = static_cast<std::uint64_t>(std::clamp(t, 0.0, 1.0) * 2097151.0);
      code |= SpreadBits(q) << d;
    }
    keys[i] = { code, static_cast<std::uint32_t>(i) };
  }
  SortKeys(keys);
  return keys;
}

/** Where the sorted keys [begin, end) split: where the highest bit in which their
 * codes differ changes (the codes share the bits above it, and those with it clear
 * come first), so that each half is one octree cell. Past depth 48, or among equal
 * codes, in the middle: the depth, and so the traversal stacks of the queries, stay
 * below 48 + log2(n) < 128. */
std::uint32_t
SplitPosition(const LargeBlockVector<std::pair<std::uint64_t, std::uint32_t>> & keys,
              std::uint32_t                                                     begin,
              std::uint32_t                                                     end,
              std::uint32_t                                                     depth)
{
  const std::uint64_t firstCode = keys[begin].first;
  const std::uint64_t lastCode = keys[end - 1].first;
  if (firstCode == lastCode || depth >= 48)
  {
    return begin + (end - begin) / 2;
  }
  const std::uint64_t differ = firstCode ^ lastCode;
  unsigned int        bit = 63;
  while (((differ >> bit) & 1u) == 0)
  {
    --bit;
  }
  const auto split = std::partition_point(
    keys.begin() + begin, keys.begin() + end, [bit](const std::pair<std::uint64_t, std::uint32_t> & k) {
      return ((k.first >> bit) & 1u) == 0;
    });
  return static_cast<std::uint32_t>(split - keys.begin());
}
} // namespace

void
TriangleAABBTree::Build(const IndexedTriangleMesh &        mesh,
                        const std::vector<std::uint32_t> * subset,
                        const AxisAlignedBoxArray *        givenBoxes)
{
  m_Mesh = &mesh;
  m_Nodes.clear();
  m_Triangles.clear();
  m_Boxes.clear();
  if (subset != nullptr)
  {
    m_Triangles.assign(subset->begin(), subset->end());
  }
  else
  {
    m_Triangles.resize(mesh.triangles.size());
    std::iota(m_Triangles.begin(), m_Triangles.end(), 0u);
  }
  const std::size_t n = m_Triangles.size();
  if (n == 0)
  {
    return;
  }
  // The slots' boxes, in their final (sorted) order at the end; until then, read
  // where they are (given boxes are not copied twice).
  AxisAlignedBoxArray computedBoxes(givenBoxes ? 0 : n);
  for (std::size_t i = 0; i < computedBoxes.size(); ++i)
  {
    computedBoxes[i] = TriangleBox(mesh, m_Triangles[i]);
  }
  auto boxOf = [&](std::size_t i) -> const AxisAlignedBox & {
    return givenBoxes ? (*givenBoxes)[m_Triangles[i]] : computedBoxes[i];
  };
  // Order the slots along a Morton (Z-order) curve of the box centres, then split
  // every range where the highest differing bit of its codes changes (Karras' linear
  // BVH): each half is one octree cell, so boxes stay tight (splitting in the middle
  // of the range instead lets a node span two distant cells, which slows the
  // nearest-point queries down).
  const MortonKeys keys = SortedMortonKeys(n, boxOf);
  this->BuildNodes(keys);
  LargeBlockVector<std::uint32_t> triangles(n);
  AxisAlignedBoxArray             sortedBoxes(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    triangles[i] = m_Triangles[keys[i].second];
    sortedBoxes[i] = boxOf(keys[i].second);
  }
  m_Triangles.swap(triangles);
  m_Boxes.swap(sortedBoxes);
  this->FitNodeBoxes();
}

void
TriangleAABBTree::BuildNodes(const MortonKeys & keys)
{
  constexpr std::uint32_t LeafSize = 16;
  struct Task
  {
    std::uint32_t node;
    std::uint32_t begin;
    std::uint32_t end;
    std::uint32_t depth;
  };
  const std::size_t n = keys.size();
  m_Nodes.reserve(2 * (n / LeafSize + 1));
  m_Nodes.emplace_back();
  std::vector<Task> tasks;
  tasks.push_back({ 0, 0, static_cast<std::uint32_t>(n), 0 });
  while (!tasks.empty())
  {
    const Task task = tasks.back();
    tasks.pop_back();
    const std::uint32_t count = task.end - task.begin;
    if (count <= LeafSize)
    {
      m_Nodes[task.node].first = task.begin;
      m_Nodes[task.node].count = count;
      continue;
    }
    const std::uint32_t middle = SplitPosition(keys, task.begin, task.end, task.depth);
    const auto          left = static_cast<std::uint32_t>(m_Nodes.size());
    m_Nodes.emplace_back();
    m_Nodes.emplace_back();
    m_Nodes[task.node].first = left;
    m_Nodes[task.node].count = 0;
    tasks.push_back({ left, task.begin, middle, task.depth + 1 });
    tasks.push_back({ left + 1, middle, task.end, task.depth + 1 });
  }
}

std::vector<TriangleAABBTree::NodePair>
TriangleAABBTree::SplitOverlappingPairs(std::size_t minimumNumberOfPairs) const
{
  std::vector<NodePair> pairs;
  if (m_Nodes.empty())
  {
    return pairs;
  }
  pairs.emplace_back(0, 0);
  for (;;)
  {
    std::vector<NodePair> next;
    bool                  split = false;
    for (const auto & p : pairs)
    {
      split = this->SplitPair(p, next) || split;
    }
    pairs.swap(next);
    if (!split || pairs.size() >= minimumNumberOfPairs)
    {
      return pairs;
    }
  }
}

void
TriangleAABBTree::FitNodeBoxes()
{
  // Bottom-up: children always come after their parent.
  for (std::size_t k = m_Nodes.size(); k-- > 0;)
  {
    Node & node = m_Nodes[k];
    node.box = AxisAlignedBox();
    if (node.count > 0)
    {
      for (std::uint32_t i = node.first; i < node.first + node.count; ++i)
      {
        node.box.Add(m_Boxes[i]);
      }
    }
    else
    {
      node.box.Add(m_Nodes[node.first].box);
      node.box.Add(m_Nodes[node.first + 1].box);
    }
  }
}

void
TriangleAABBTree::Refit(const IndexedTriangleMesh & mesh, const AxisAlignedBoxArray & boxes)
{
  if (boxes.size() != mesh.triangles.size() || m_Triangles.size() != boxes.size())
  {
    itkGenericExceptionMacro("TriangleAABBTree::Refit: the tree holds "
                             << m_Triangles.size() << " triangles, the mesh has " << mesh.triangles.size() << " and "
                             << boxes.size() << " boxes were given; Refit needs a tree over all of them.");
  }
  m_Mesh = &mesh;
  for (std::size_t i = 0; i < m_Triangles.size(); ++i)
  {
    m_Boxes[i] = boxes[m_Triangles[i]];
  }
  this->FitNodeBoxes();
}

TriangleAABBTree::Nearest
TriangleAABBTree::FindNearest(const Vec3 & p) const
{
  return this->FindNearest(p, std::numeric_limits<std::uint32_t>::max());
}

TriangleAABBTree::Nearest
TriangleAABBTree::FindNearest(const Vec3 & p, std::uint32_t hint) const
{
  Nearest best;
  if (m_Nodes.empty())
  {
    return best;
  }
  if (hint < m_Mesh->triangles.size())
  {
    // A triangle near p (the answer of a query nearby) bounds the search from the start.
    const auto & t = m_Mesh->triangles[hint];
    best.point = ClosestPointOnTriangle(p, m_Mesh->points[t[0]], m_Mesh->points[t[1]], m_Mesh->points[t[2]]);
    best.squaredDistance = SquaredNorm(p - best.point);
    best.triangle = hint;
  }
  struct Entry
  {
    std::uint32_t node;
    double        squaredDistance;
  };
  Entry        stack[128];
  unsigned int top = 0;
  stack[top++] = { 0, m_Nodes[0].box.SquaredDistance(p) };
  while (top > 0)
  {
    const Entry entry = stack[--top];
    if (entry.squaredDistance >= best.squaredDistance)
    {
      continue;
    }
    const Node & node = m_Nodes[entry.node];
    if (node.count > 0)
    {
      for (std::uint32_t i = node.first; i < node.first + node.count; ++i)
      {
        if (m_Boxes[i].SquaredDistance(p) >= best.squaredDistance)
        {
          continue;
        }
        const auto & t = m_Mesh->triangles[m_Triangles[i]];
        const Vec3   q = ClosestPointOnTriangle(p, m_Mesh->points[t[0]], m_Mesh->points[t[1]], m_Mesh->points[t[2]]);
        const double d2 = SquaredNorm(p - q);
        if (d2 < best.squaredDistance || (d2 == best.squaredDistance && m_Triangles[i] < best.triangle))
        {
          best.squaredDistance = d2;
          best.triangle = m_Triangles[i];
          best.point = q;
        }
      }
      continue;
    }
    const double dl = m_Nodes[node.first].box.SquaredDistance(p);
    const double dr = m_Nodes[node.first + 1].box.SquaredDistance(p);
    // Visit the nearer child first: push it last.
    if (dl <= dr)
    {
      stack[top++] = { node.first + 1, dr };
      stack[top++] = { node.first, dl };
    }
    else
    {
      stack[top++] = { node.first, dl };
      stack[top++] = { node.first + 1, dr };
    }
  }
  return best;
}

} // namespace detail
} // namespace MeshExtraction
} // namespace itk
