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
// The validity guard for edge swaps: the swaps of one sweep of the indexed engine
// undone one by one (UndoIntersectingSwaps), and the crossing new triangles that
// EdgeSwapQuadEdgeMeshFilter locks (FindCrossingNewTriangles).
#include "itkMeshExtractionValidityGuard.h"
#include "itkMeshExtractionClosedSurfaceEdgeSwap.h"
#include "itkMeshExtractionParallel.h"
#include "itkMeshExtractionQualityAnalysis.h"
#include "itkMeshExtractionTriangleAABBTree.h"

#include <algorithm>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
namespace
{
/** \brief The steps of UndoIntersectingSwaps() on the swaps of one sweep.
 *
 * The node positions are fixed, and a swapped pair, swapped or not, stays inside the
 * box of its four corners, so one tree serves every round: find the swapped triangles
 * that cross another, fold against a neighbour or leave their component collapsed,
 * undo their swaps, and check the restored triangles again. */
class SwapUndo
{
public:
  SwapUndo(const std::vector<Vec3> &     physical,
           SurfaceNetTriangles &         mesh,
           std::vector<EdgeSwapRecord> & swaps,
           std::vector<std::uint64_t> *  refused,
           const ComponentVolumes *      volumes)
      : m_Physical(physical)
      , m_Mesh(mesh)
      , m_Swaps(swaps)
      , m_Refused(refused)
      , m_Volumes(volumes)
  {
    m_Check.points = physical;
    m_Check.triangles = mesh.triangles;
  }

  std::size_t
  Run(TriangleAABBTree * sharedTree)
  {
    const AxisAlignedBoxArray boxes = this->BoxesAroundSwaps();
    if (m_Swaps.empty())
    {
      return 0;
    }
    TriangleAABBTree   localTree;
    TriangleAABBTree & tree = sharedTree != nullptr ? *sharedTree : localTree;
    BuildOrRefitTree(tree, m_Check, boxes);
    std::size_t undone = 0;
    while (!m_Changed.empty())
    {
      bool                    anyBad = false;
      const std::vector<bool> bad = this->InvalidTriangles(tree, anyBad);
      if (!anyBad)
      {
        break;
      }
      const auto restored = this->TakeBackSwaps(bad, undone);
      if (m_Changed.empty())
      {
        // Defects that no swap of this sweep caused: not expected, leave them to the
        // caller's checks.
        break;
      }
      m_Mesh.ReplaceTriangles(restored);
      for (const auto & r : restored)
      {
        m_Check.triangles[r.first] = r.second; // the rest is as before
      }
    }
    if (m_Refused != nullptr)
    {
      std::sort(m_Refused->begin(), m_Refused->end());
      m_Refused->erase(std::unique(m_Refused->begin(), m_Refused->end()), m_Refused->end());
    }
    return undone;
  }

private:
  /** Each triangle's box; the two triangles of a swap both get the box of the pair,
   * which holds them swapped or not. The swapped triangles are the first to check. */
  AxisAlignedBoxArray
  BoxesAroundSwaps()
  {
    AxisAlignedBoxArray boxes(m_Mesh.triangles.size());
    ParallelForBlocks(m_Mesh.triangles.size(), 8192, [&](std::size_t begin, std::size_t end, std::size_t) {
      for (std::size_t f = begin; f < end; ++f)
      {
        boxes[f] = TriangleBox(m_Check, static_cast<std::uint32_t>(f));
      }
    });
    for (const auto & s : m_Swaps)
    {
      AxisAlignedBox quad = boxes[s.first];
      quad.Add(boxes[s.second]);
      boxes[s.first] = quad;
      boxes[s.second] = quad;
      m_Changed.push_back(s.first);
      m_Changed.push_back(s.second);
    }
    return boxes;
  }

  /** The changed triangles that cross another triangle or fold against a neighbour,
   * and the swaps in collapsed components; `anyBad` says whether there is one. */
  std::vector<bool>
  InvalidTriangles(const TriangleAABBTree & tree, bool & anyBad) const
  {
    const auto        pairs = FindSelfIntersections(m_Check, m_Changed, tree);
    std::vector<bool> bad(m_Mesh.triangles.size(), false);
    anyBad = !pairs.empty();
    for (const auto & p : pairs)
    {
      bad[p.first] = true;
      bad[p.second] = true;
    }
    this->MarkFolds(bad, anyBad);
    this->MarkCollapsedComponents(bad, anyBad);
    return bad;
  }

  /** Folds against a neighbour (twins are those of the current triangles). */
  void
  MarkFolds(std::vector<bool> & bad, bool & anyBad) const
  {
    for (std::uint32_t f : m_Changed)
    {
      const auto & t = m_Mesh.triangles[f];
      const Vec3   n = TriangleNormal(m_Physical[t[0]], m_Physical[t[1]], m_Physical[t[2]]);
      for (unsigned int k = 0; k < 3; ++k)
      {
        const std::uint32_t g = m_Mesh.twin[3 * f + k] / 3;
        const auto &        u = m_Mesh.triangles[g];
        const Vec3          m = TriangleNormal(m_Physical[u[0]], m_Physical[u[1]], m_Physical[u[2]]);
        if (Dot(n, m) < ValidityThresholds::FoldCosine * Norm(n) * Norm(m))
        {
          bad[f] = true;
          bad[g] = true;
          anyBad = true;
        }
      }
    }
  }

  /** Components that a swap turned inside out or flattened: their swaps are undone. */
  void
  MarkCollapsedComponents(std::vector<bool> & bad, bool & anyBad) const
  {
    if (m_Volumes == nullptr)
    {
      return;
    }
    const std::vector<bool> collapsed = m_Volumes->Collapsed(m_Check.triangles, m_Physical);
    for (const auto & s : m_Swaps)
    {
      if (collapsed[m_Volumes->vertexComponent[m_Mesh.triangles[s.first][0]]])
      {
        bad[s.first] = true;
        anyBad = true;
      }
    }
  }

  /** The swaps with a bad triangle, undone: their old triangles (to restore), their
   * edges refused, their triangles the next to check; the others are kept. */
  std::vector<std::pair<std::uint32_t, TriangleIndices>>
  TakeBackSwaps(const std::vector<bool> & bad, std::size_t & undone)
  {
    m_Changed.clear();
    std::vector<EdgeSwapRecord>                            kept;
    std::vector<std::pair<std::uint32_t, TriangleIndices>> restored;
    for (const auto & s : m_Swaps)
    {
      if (bad[s.first] || bad[s.second])
      {
        this->Refuse(s);
        restored.emplace_back(s.first, s.oldFirst);
        restored.emplace_back(s.second, s.oldSecond);
        m_Changed.push_back(s.first);
        m_Changed.push_back(s.second);
        ++undone;
      }
      else
      {
        kept.push_back(s);
      }
    }
    if (!m_Changed.empty())
    {
      m_Swaps.swap(kept);
    }
    return restored;
  }

  /** The swapped edge, which runs between the two corners the old triangles share,
   * goes to the refused edges. */
  void
  Refuse(const EdgeSwapRecord & s) const
  {
    if (m_Refused == nullptr)
    {
      return;
    }
    const auto & t = s.oldFirst;
    for (unsigned int k = 0; k < 3; ++k)
    {
      const std::uint32_t a = t[k];
      const std::uint32_t b = t[(k + 1) % 3];
      const auto &        u = s.oldSecond;
      if ((u[0] == a || u[1] == a || u[2] == a) && (u[0] == b || u[1] == b || u[2] == b))
      {
        m_Refused->push_back(EdgeKey(a, b));
      }
    }
  }

  const std::vector<Vec3> &     m_Physical;
  SurfaceNetTriangles &         m_Mesh;
  std::vector<EdgeSwapRecord> & m_Swaps;
  std::vector<std::uint64_t> *  m_Refused;
  const ComponentVolumes *      m_Volumes;
  IndexedTriangleMesh           m_Check;   ///< the physical points with the current triangles
  std::vector<std::uint32_t>    m_Changed; ///< the triangles to check
};
} // namespace

void
BuildOrRefitTree(TriangleAABBTree & tree, const IndexedTriangleMesh & mesh, const AxisAlignedBoxArray & boxes)
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

std::size_t
UndoIntersectingSwaps(const std::vector<Vec3> &     physical,
                      SurfaceNetTriangles &         mesh,
                      std::vector<EdgeSwapRecord> & swaps,
                      std::vector<std::uint64_t> *  refused,
                      TriangleAABBTree *            tree,
                      const ComponentVolumes *      volumes)
{
  return SwapUndo(physical, mesh, swaps, refused, volumes).Run(tree);
}

std::vector<PointIdentifierEdge>
EdgesByPointIdentifier(const IndexedTriangleMesh & mesh)
{
  std::vector<PointIdentifierEdge> edges;
  for (const auto & t : mesh.triangles)
  {
    for (unsigned int k = 0; k < 3; ++k)
    {
      const IdentifierType a = mesh.pointIds[t[k]];
      const IdentifierType b = mesh.pointIds[t[(k + 1) % 3]];
      edges.emplace_back(std::min(a, b), std::max(a, b));
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  return edges;
}

std::vector<std::uint32_t>
FindCrossingNewTriangles(const IndexedTriangleMesh & mesh, const std::vector<PointIdentifierEdge> & oldEdges)
{
  std::vector<std::uint8_t>  isNew(mesh.triangles.size(), 0);
  std::vector<std::uint32_t> queries;
  for (std::uint32_t f = 0; f < mesh.triangles.size(); ++f)
  {
    const auto & t = mesh.triangles[f];
    for (unsigned int k = 0; k < 3 && !isNew[f]; ++k)
    {
      const IdentifierType a = mesh.pointIds[t[k]];
      const IdentifierType b = mesh.pointIds[t[(k + 1) % 3]];
      isNew[f] =
        std::binary_search(oldEdges.begin(), oldEdges.end(), PointIdentifierEdge(std::min(a, b), std::max(a, b))) ? 0
                                                                                                                  : 1;
    }
    if (isNew[f])
    {
      queries.push_back(f);
    }
  }
  std::vector<std::uint32_t> crossing;
  for (const auto & pair : FindSelfIntersections(mesh, &queries))
  {
    for (const std::uint32_t f : { pair.first, pair.second })
    {
      if (isNew[f])
      {
        crossing.push_back(f);
      }
    }
  }
  std::sort(crossing.begin(), crossing.end());
  crossing.erase(std::unique(crossing.begin(), crossing.end()), crossing.end());
  return crossing;
}

} // namespace detail
} // namespace MeshExtraction
} // namespace itk
