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

#include <algorithm>
#include <numeric>

namespace itk
{
namespace MeshExtraction
{
void
TriangleAABBTree::Build(const IndexedTriangleMesh & mesh, const std::vector<std::uint32_t> * subset)
{
  m_Mesh = &mesh;
  m_Nodes.clear();
  m_Triangles.clear();
  m_Boxes.clear();
  if (subset != nullptr)
  {
    m_Triangles = *subset;
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
  std::vector<AxisAlignedBox> boxes(n);
  std::vector<Vec3>           centroids(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    boxes[i] = TriangleBox(mesh, m_Triangles[i]);
    for (unsigned int d = 0; d < 3; ++d)
    {
      centroids[i][d] = 0.5 * (boxes[i].lower[d] + boxes[i].upper[d]);
    }
  }
  // Sort a permutation of the slots; boxes and triangles follow it at the end.
  std::vector<std::uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);

  constexpr std::uint32_t LeafSize = 4;
  struct Task
  {
    std::uint32_t node;
    std::uint32_t begin;
    std::uint32_t end;
  };
  m_Nodes.reserve(2 * (n / LeafSize + 1));
  m_Nodes.emplace_back();
  std::vector<Task> tasks;
  tasks.push_back({ 0, 0, static_cast<std::uint32_t>(n) });
  while (!tasks.empty())
  {
    const Task task = tasks.back();
    tasks.pop_back();
    AxisAlignedBox bounds;
    AxisAlignedBox centroidBounds;
    for (std::uint32_t i = task.begin; i < task.end; ++i)
    {
      bounds.Add(boxes[order[i]]);
      centroidBounds.Add(centroids[order[i]]);
    }
    m_Nodes[task.node].box = bounds;
    const std::uint32_t count = task.end - task.begin;
    if (count <= LeafSize)
    {
      m_Nodes[task.node].first = task.begin;
      m_Nodes[task.node].count = count;
      continue;
    }
    unsigned int axis = 0;
    for (unsigned int d = 1; d < 3; ++d)
    {
      if (centroidBounds.upper[d] - centroidBounds.lower[d] > centroidBounds.upper[axis] - centroidBounds.lower[axis])
      {
        axis = d;
      }
    }
    const std::uint32_t middle = task.begin + count / 2;
    std::nth_element(order.begin() + task.begin,
                     order.begin() + middle,
                     order.begin() + task.end,
                     [&centroids, axis](std::uint32_t a, std::uint32_t b) {
                       return centroids[a][axis] < centroids[b][axis] ||
                              (centroids[a][axis] == centroids[b][axis] && a < b);
                     });
    const auto left = static_cast<std::uint32_t>(m_Nodes.size());
    m_Nodes.emplace_back();
    m_Nodes.emplace_back();
    m_Nodes[task.node].first = left;
    m_Nodes[task.node].count = 0;
    tasks.push_back({ left, task.begin, middle });
    tasks.push_back({ left + 1, middle, task.end });
  }
  std::vector<std::uint32_t>  triangles(n);
  std::vector<AxisAlignedBox> sortedBoxes(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    triangles[i] = m_Triangles[order[i]];
    sortedBoxes[i] = boxes[order[i]];
  }
  m_Triangles.swap(triangles);
  m_Boxes.swap(sortedBoxes);
}

TriangleAABBTree::Nearest
TriangleAABBTree::FindNearest(const Vec3 & p) const
{
  Nearest best;
  if (m_Nodes.empty())
  {
    return best;
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

} // namespace MeshExtraction
} // namespace itk
