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
#include "itkMeshExtractionEdgeSwapPasses.h"

#include "itkMacro.h"

#include <algorithm>
#include <limits>
#include <numeric>
#include <unordered_map>
#include <utility>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
namespace
{
constexpr std::uint32_t None = std::numeric_limits<std::uint32_t>::max();

std::uint64_t
UndirectedKey(std::uint32_t u, std::uint32_t v)
{
  return u < v ? (std::uint64_t{ u } << 32) | v : (std::uint64_t{ v } << 32) | u;
}

/** Half-edge h = 3f + k runs from triangles[f][k] to triangles[f][k + 1]. */
class HalfEdgeSwapper
{
public:
  HalfEdgeSwapper(IndexedTriangleMesh &             mesh,
                  const EdgeSwapParameters &        parameters,
                  const std::vector<std::uint8_t> & locked)
    : m_Mesh(mesh)
    , m_Parameters(parameters)
    , m_Locked(locked)
  {
    this->BuildTwins();
  }

  /** One pass; returns the number of swaps. */
  std::size_t
  Pass(std::size_t & refused)
  {
    this->NumberEdges();
    std::size_t swaps = 0;
    for (std::uint32_t i = 0; i < m_NumberOfListedEdges; ++i)
    {
      const std::uint32_t h = m_Slot[i];
      if (h == None || m_Twin[h] == None)
      {
        continue; // swapped away earlier in this pass, or on a boundary
      }
      // e runs from the edge's corner with the smaller identifier to the other.
      const std::uint32_t e = this->Origin(h) == m_Listed[i].first ? h : m_Twin[h];
      const std::uint32_t t = m_Twin[e];
      const std::uint32_t a = this->Origin(e);
      const std::uint32_t b = this->Origin(t);
      const std::uint32_t c = this->Apex(e);
      const std::uint32_t d = this->Apex(t);
      if (!m_Locked.empty() && (m_Locked[a] != 0 || m_Locked[b] != 0 || m_Locked[c] != 0 || m_Locked[d] != 0))
      {
        continue;
      }
      EdgeSwapQuad quad;
      quad.a = m_Mesh.points[a];
      quad.b = m_Mesh.points[b];
      quad.c = m_Mesh.points[c];
      quad.d = m_Mesh.points[d];
      quad.valenceA = m_Valence[a];
      quad.valenceB = m_Valence[b];
      quad.valenceC = m_Valence[c];
      quad.valenceD = m_Valence[d];
      quad.boundaryA = m_OnBoundary[a] != 0;
      quad.boundaryB = m_OnBoundary[b] != 0;
      quad.boundaryC = m_OnBoundary[c] != 0;
      quad.boundaryD = m_OnBoundary[d] != 0;
      quad.sameApex = c == d;
      double gain = 0.0;
      if (!EdgeSwapImproves(quad, m_Parameters, gain))
      {
        continue;
      }
      quad.oppositeEdgeExists = !quad.sameApex && this->EdgeExists(c, d);
      if (CheckEdgeSwap(quad, m_Parameters) != EdgeSwapVerdict::Swap)
      {
        ++refused;
        continue;
      }
      this->Swap(e);
      --m_Valence[a];
      --m_Valence[b];
      ++m_Valence[c];
      ++m_Valence[d];
      ++swaps;
    }
    return swaps;
  }

private:
  using EdgeCorners = std::pair<std::uint32_t, std::uint32_t>;

  /** The pass's edge order: by the (smaller, larger) point identifiers of the corners. */
  bool
  ByIdentifiers(const EdgeCorners & p, const EdgeCorners & q) const
  {
    const auto & ids = m_Mesh.pointIds;
    return ids[p.first] < ids[q.first] || (ids[p.first] == ids[q.first] && ids[p.second] < ids[q.second]);
  }

  std::uint32_t
  Origin(std::uint32_t h) const
  {
    return m_Mesh.triangles[h / 3][h % 3];
  }
  std::uint32_t
  Apex(std::uint32_t h) const
  {
    return m_Mesh.triangles[h / 3][(h % 3 + 2) % 3];
  }
  std::uint32_t
  Destination(std::uint32_t h) const
  {
    return m_Mesh.triangles[h / 3][(h % 3 + 1) % 3];
  }

  /** Twins by sorting the half-edges by their undirected edge. */
  void
  BuildTwins()
  {
    const std::size_t          n = m_Mesh.triangles.size() * 3;
    std::vector<std::uint64_t> keyed(n);
    for (std::size_t h = 0; h < n; ++h)
    {
      const auto hh = static_cast<std::uint32_t>(h);
      keyed[h] = UndirectedKey(this->Origin(hh), this->Destination(hh));
    }
    std::vector<std::uint32_t> order(n);
    std::iota(order.begin(), order.end(), 0u);
    std::sort(order.begin(), order.end(), [&keyed](std::uint32_t x, std::uint32_t y) {
      return keyed[x] < keyed[y] || (keyed[x] == keyed[y] && x < y);
    });
    m_Twin.assign(n, None);
    for (std::size_t i = 0; i < n;)
    {
      std::size_t j = i + 1;
      while (j < n && keyed[order[j]] == keyed[order[i]])
      {
        ++j;
      }
      if (j - i > 2 || (j - i == 2 && this->Origin(order[i]) == this->Origin(order[i + 1])))
      {
        const std::uint32_t u = this->Origin(order[i]);
        const std::uint32_t v = this->Destination(order[i]);
        itkGenericExceptionMacro("MeshExtraction: cannot swap edges: edge ("
                                 << m_Mesh.pointIds[u] << ", " << m_Mesh.pointIds[v] << ") has " << (j - i)
                                 << " triangles" << (j - i == 2 ? " running it the same way" : ""));
      }
      if (j - i == 2)
      {
        m_Twin[order[i]] = order[i + 1];
        m_Twin[order[i + 1]] = order[i];
      }
      i = j;
    }
  }

  /** The pass's list of edges, by (smaller, larger) point identifier; an edge index per
   * half-edge; valences and boundary flags. */
  void
  NumberEdges()
  {
    const std::size_t n = m_Mesh.triangles.size() * 3;
    m_Listed.clear();
    m_Listed.reserve(n / 2 + 1);
    std::vector<std::uint32_t> first;
    first.reserve(n / 2 + 1);
    for (std::uint32_t h = 0; h < n; ++h)
    {
      if (m_Twin[h] == None || h < m_Twin[h])
      {
        std::uint32_t u = this->Origin(h);
        std::uint32_t v = this->Destination(h);
        if (m_Mesh.pointIds[v] < m_Mesh.pointIds[u])
        {
          std::swap(u, v);
        }
        m_Listed.emplace_back(u, v);
        first.push_back(h);
      }
    }
    std::vector<std::uint32_t> order(m_Listed.size());
    std::iota(order.begin(), order.end(), 0u);
    std::sort(order.begin(), order.end(), [this](std::uint32_t x, std::uint32_t y) {
      return this->ByIdentifiers(m_Listed[x], m_Listed[y]);
    });
    std::vector<std::pair<std::uint32_t, std::uint32_t>> sorted(m_Listed.size());
    m_Slot.assign(m_Listed.size(), None);
    m_EdgeOf.assign(n, None);
    for (std::uint32_t i = 0; i < order.size(); ++i)
    {
      sorted[i] = m_Listed[order[i]];
      const std::uint32_t h = first[order[i]];
      m_Slot[i] = h;
      m_EdgeOf[h] = i;
      if (m_Twin[h] != None)
      {
        m_EdgeOf[m_Twin[h]] = i;
      }
    }
    m_Listed.swap(sorted);
    m_NumberOfListedEdges = static_cast<std::uint32_t>(m_Listed.size());
    m_Created.clear();

    m_Valence.assign(m_Mesh.points.size(), 0);
    m_OnBoundary.assign(m_Mesh.points.size(), 0);
    for (const auto & uv : m_Listed)
    {
      ++m_Valence[uv.first];
      ++m_Valence[uv.second];
    }
    for (std::uint32_t h = 0; h < n; ++h)
    {
      if (m_Twin[h] == None)
      {
        m_OnBoundary[this->Origin(h)] = 1;
        m_OnBoundary[this->Destination(h)] = 1;
      }
    }
  }

  /** The index of edge (u, v) in the pass's list or among the edges the pass made, or
   * None; with `create`, a new index for an edge not seen yet. */
  std::uint32_t
  EdgeIndex(std::uint32_t u, std::uint32_t v, bool create)
  {
    const auto & ids = m_Mesh.pointIds;
    if (ids[v] < ids[u])
    {
      std::swap(u, v);
    }
    const auto end = m_Listed.begin() + m_NumberOfListedEdges;
    const auto it = std::lower_bound(
      m_Listed.begin(), end, std::make_pair(u, v), [this](const EdgeCorners & p, const EdgeCorners & q) {
        return this->ByIdentifiers(p, q);
      });
    if (it != end && it->first == u && it->second == v)
    {
      return static_cast<std::uint32_t>(it - m_Listed.begin());
    }
    const auto found = m_Created.find(UndirectedKey(u, v));
    if (found != m_Created.end())
    {
      return found->second;
    }
    if (!create)
    {
      return None;
    }
    const auto index = static_cast<std::uint32_t>(m_Slot.size());
    m_Slot.push_back(None);
    m_Created.emplace(UndirectedKey(u, v), index);
    return index;
  }

  bool
  EdgeExists(std::uint32_t u, std::uint32_t v)
  {
    const std::uint32_t index = this->EdgeIndex(u, v, false);
    return index != None && m_Slot[index] != None;
  }

  /** Replaces edge e = (a -> b) of triangles (a, b, c) and (b, a, d) by (c, d): the
   * triangles become (c, a, d) and (d, b, c). */
  void
  Swap(std::uint32_t e)
  {
    const std::uint32_t t = m_Twin[e];
    const std::uint32_t f1 = e / 3;
    const std::uint32_t f2 = t / 3;
    const std::uint32_t a = this->Origin(e);
    const std::uint32_t b = this->Origin(t);
    const std::uint32_t c = this->Apex(e);
    const std::uint32_t d = this->Apex(t);
    const std::uint32_t bc = 3 * f1 + (e % 3 + 1) % 3;
    const std::uint32_t ca = 3 * f1 + (e % 3 + 2) % 3;
    const std::uint32_t ad = 3 * f2 + (t % 3 + 1) % 3;
    const std::uint32_t db = 3 * f2 + (t % 3 + 2) % 3;
    const std::uint32_t twinBC = m_Twin[bc];
    const std::uint32_t twinCA = m_Twin[ca];
    const std::uint32_t twinAD = m_Twin[ad];
    const std::uint32_t twinDB = m_Twin[db];
    const std::uint32_t edgeBC = m_EdgeOf[bc];
    const std::uint32_t edgeCA = m_EdgeOf[ca];
    const std::uint32_t edgeAD = m_EdgeOf[ad];
    const std::uint32_t edgeDB = m_EdgeOf[db];
    m_Slot[m_EdgeOf[e]] = None;
    const std::uint32_t edgeCD = this->EdgeIndex(c, d, true);

    m_Mesh.triangles[f1] = { c, a, d };
    m_Mesh.triangles[f2] = { d, b, c };
    const std::uint32_t newCA = 3 * f1;
    const std::uint32_t newAD = 3 * f1 + 1;
    const std::uint32_t newDC = 3 * f1 + 2;
    const std::uint32_t newDB = 3 * f2;
    const std::uint32_t newBC = 3 * f2 + 1;
    const std::uint32_t newCD = 3 * f2 + 2;
    this->Link(newCA, twinCA, edgeCA);
    this->Link(newAD, twinAD, edgeAD);
    this->Link(newDB, twinDB, edgeDB);
    this->Link(newBC, twinBC, edgeBC);
    m_Twin[newDC] = newCD;
    m_Twin[newCD] = newDC;
    m_EdgeOf[newDC] = edgeCD;
    m_EdgeOf[newCD] = edgeCD;
    m_Slot[edgeCD] = newDC;
  }

  void
  Link(std::uint32_t h, std::uint32_t twin, std::uint32_t edge)
  {
    m_Twin[h] = twin;
    if (twin != None)
    {
      m_Twin[twin] = h;
    }
    m_EdgeOf[h] = edge;
    m_Slot[edge] = h;
  }

  IndexedTriangleMesh &             m_Mesh;
  const EdgeSwapParameters &        m_Parameters;
  const std::vector<std::uint8_t> & m_Locked;

  std::vector<std::uint32_t>                           m_Twin;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> m_Listed; ///< the pass's edges, sorted by point identifiers
  std::uint32_t                                        m_NumberOfListedEdges{ 0 };
  std::vector<std::uint32_t>                           m_Slot;   ///< a half-edge of each edge, None once swapped away
  std::vector<std::uint32_t>                           m_EdgeOf; ///< edge index of each half-edge
  std::unordered_map<std::uint64_t, std::uint32_t>     m_Created; ///< edges the pass made that were not listed
  std::vector<unsigned int>                            m_Valence;
  std::vector<std::uint8_t>                            m_OnBoundary;
};
} // namespace

EdgeSwapPassCounts
SwapEdgesInPasses(IndexedTriangleMesh &             mesh,
                  const EdgeSwapParameters &        parameters,
                  const std::vector<std::uint8_t> & locked,
                  int                               maximumNumberOfPasses,
                  const std::function<void(int)> &  afterPass)
{
  EdgeSwapPassCounts counts;
  if (mesh.triangles.empty() || maximumNumberOfPasses <= 0)
  {
    return counts;
  }
  if (!locked.empty() && locked.size() != mesh.points.size())
  {
    itkGenericExceptionMacro("MeshExtraction: " << locked.size() << " lock flags for " << mesh.points.size()
                                                << " points");
  }
  HalfEdgeSwapper swapper(mesh, parameters, locked);
  for (int pass = 0; pass < maximumNumberOfPasses; ++pass)
  {
    const std::size_t swaps = swapper.Pass(counts.refused);
    counts.swaps += swaps;
    ++counts.passes;
    if (afterPass)
    {
      afterPass(counts.passes);
    }
    if (swaps == 0)
    {
      break;
    }
  }
  return counts;
}

} // namespace detail
} // namespace MeshExtraction
} // namespace itk
