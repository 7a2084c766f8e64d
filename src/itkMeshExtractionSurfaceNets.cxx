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
#include "itkMeshExtractionSurfaceNets.h"
#include "itkMeshExtractionLargeBlockVector.h"
#include "itkMeshExtractionParallel.h"
#include "itkMeshExtractionPredicates.h"
#include "itkMeshExtractionQualityAnalysis.h"

#include "itkMeshExtractionTriangleAABBTree.h"
#include "itkMeshExtractionValidityGuard.h"
#include "vnl/vnl_det.h"
#include "vnl/vnl_inverse.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <numeric>

namespace itk
{
namespace MeshExtraction
{
std::int64_t
SurfaceNet::FindCell(std::int64_t x, std::int64_t y, std::int64_t z) const
{
  if (y < -1 || y >= size[1] || z < -1 || z >= size[2])
  {
    return -1;
  }
  const std::int64_t row = RowOf(y, z);
  const auto         begin = cells.begin() + rowStart[row];
  const auto         end = cells.begin() + rowStart[row + 1];
  const auto         found =
    std::lower_bound(begin, end, x, [](const SurfaceCell & c, std::int64_t value) { return c.x < value; });
  if (found == end || found->x != x)
  {
    return -1;
  }
  return found - cells.begin();
}

namespace detail
{
namespace
{
inline unsigned int
CornerIndex(const unsigned int offset[3])
{
  return offset[0] + 2 * offset[1] + 4 * offset[2];
}

/** The low corner of a cell's voxel edge 4a+3, along axis a at offset 1 on the two
 * other axes (its high corner is 7). */
constexpr unsigned int
UpperEdgeLowCorner(unsigned int a)
{
  return 7u - (1u << a);
}

/** Whether that edge crosses the surface: its two corners differ. */
constexpr bool
CrossesUpperEdge(unsigned int configuration, unsigned int a)
{
  return (((configuration >> UpperEdgeLowCorner(a)) ^ (configuration >> 7)) & 1u) != 0;
}

// -------------------------------------------------------------------------------------
// The cell table: edges, faces, and the sheets of every configuration and face rule.

/** Edge 4a + ob + 2oc: along axis a, at offsets ob and oc on the two following axes. */
void
NumberCellEdges(SurfaceNetsCellTable & table)
{
  for (unsigned int e = 0; e < 12; ++e)
  {
    const unsigned int a = e / 4;
    unsigned int       offset[3] = { 0, 0, 0 };
    offset[(a + 1) % 3] = e & 1;
    offset[(a + 2) % 3] = (e >> 1) & 1;
    table.edgeCorners[e][0] = static_cast<std::uint8_t>(CornerIndex(offset));
    offset[a] = 1;
    table.edgeCorners[e][1] = static_cast<std::uint8_t>(CornerIndex(offset));
  }
}

/** The edge between corners c0 and c1 (12 if they are not neighbours). */
unsigned int
EdgeBetween(const SurfaceNetsCellTable & table, unsigned int c0, unsigned int c1)
{
  for (unsigned int e = 0; e < 12; ++e)
  {
    if ((table.edgeCorners[e][0] == c0 && table.edgeCorners[e][1] == c1) ||
        (table.edgeCorners[e][0] == c1 && table.edgeCorners[e][1] == c0))
    {
      return e;
    }
  }
  return 12u;
}

/** Face 2f + s: at offset s along axis f, its corners and edges in cyclic order. */
void
NumberCellFaces(SurfaceNetsCellTable & table)
{
  for (unsigned int f = 0; f < 3; ++f)
  {
    for (unsigned int s = 0; s < 2; ++s)
    {
      const unsigned int u = (f + 1) % 3;
      const unsigned int v = (f + 2) % 3;
      const unsigned int cyclic[4][2] = { { 0, 0 }, { 1, 0 }, { 1, 1 }, { 0, 1 } };
      for (unsigned int i = 0; i < 4; ++i)
      {
        unsigned int offset[3];
        offset[f] = s;
        offset[u] = cyclic[i][0];
        offset[v] = cyclic[i][1];
        table.faceCorners[2 * f + s][i] = static_cast<std::uint8_t>(CornerIndex(offset));
      }
      for (unsigned int i = 0; i < 4; ++i)
      {
        table.faceEdges[2 * f + s][i] = static_cast<std::uint8_t>(
          EdgeBetween(table, table.faceCorners[2 * f + s][i], table.faceCorners[2 * f + s][(i + 1) % 4]));
      }
    }
  }
}

/** Disjoint sets of a cell's 12 edges: the edges of one sheet end up in one set. */
class EdgeSets
{
public:
  EdgeSets()
  {
    std::iota(m_Parent, m_Parent + 12, 0u);
  }
  unsigned int
  Find(unsigned int x) const
  {
    while (m_Parent[x] != x)
    {
      x = m_Parent[x];
    }
    return x;
  }
  void
  Join(unsigned int a, unsigned int b)
  {
    a = this->Find(a);
    b = this->Find(b);
    if (a != b)
    {
      m_Parent[std::max(a, b)] = std::min(a, b);
    }
  }

private:
  unsigned int m_Parent[12];
};

/** Joins the crossing edges of face f that one segment of the surface connects: the
 * two of a face with two, and on an ambiguous face (four) those around each inside
 * corner (`cutInside`, the default rule) or each outside corner. */
void
JoinSegmentsOfFace(const SurfaceNetsCellTable & table,
                   unsigned int                 configuration,
                   const bool                   crossing[12],
                   unsigned int                 f,
                   bool                         cutInside,
                   EdgeSets &                   sets)
{
  unsigned int crossings[4];
  unsigned int n = 0;
  for (unsigned int i = 0; i < 4; ++i)
  {
    if (crossing[table.faceEdges[f][i]])
    {
      crossings[n++] = table.faceEdges[f][i];
    }
  }
  if (n == 2)
  {
    sets.Join(crossings[0], crossings[1]);
  }
  else if (n == 4)
  {
    for (unsigned int i = 0; i < 4; ++i)
    {
      const bool inside = ((configuration >> table.faceCorners[f][i]) & 1u) != 0;
      if (inside == cutInside)
      {
        sets.Join(table.faceEdges[f][(i + 3) % 4], table.faceEdges[f][i]);
      }
    }
  }
}

/** The sheets of a configuration under face rules `rules` (bit f: ambiguous face f
 * cuts off its outside corners): each crossing edge's sheet, numbered in edge order,
 * into `sheetOfEdge` (-1 for the other edges); returns the number of sheets. */
std::uint8_t
FindSheets(const SurfaceNetsCellTable &  table,
           unsigned int                  configuration,
           const bool                    crossing[12],
           unsigned int                  rules,
           std::array<std::int8_t, 12> & sheetOfEdge)
{
  EdgeSets sets;
  for (unsigned int f = 0; f < 6; ++f)
  {
    JoinSegmentsOfFace(table, configuration, crossing, f, ((rules >> f) & 1u) == 0, sets);
  }
  std::int8_t sheetOfRoot[12];
  std::fill(sheetOfRoot, sheetOfRoot + 12, static_cast<std::int8_t>(-1));
  std::uint8_t sheets = 0;
  for (unsigned int e = 0; e < 12; ++e)
  {
    sheetOfEdge[e] = -1;
    if (!crossing[e])
    {
      continue;
    }
    const unsigned int root = sets.Find(e);
    if (sheetOfRoot[root] < 0)
    {
      sheetOfRoot[root] = static_cast<std::int8_t>(sheets++);
    }
    sheetOfEdge[e] = sheetOfRoot[root];
  }
  return sheets;
}

// -------------------------------------------------------------------------------------
// BuildSurfaceNet's passes: rows of cells, face rules and node numbers, nodes, quads,
// links.

constexpr std::size_t NetBlockSize = 4096;

/** rowStart[r]: the first cell in row r or later, set where the row changes from one
 * cell to the next (the cells are sorted). */
void
IndexCellRows(SurfaceNet & net, unsigned int numberOfWorkUnits)
{
  const std::size_t  numberOfCells = net.cells.size();
  const std::int64_t rows = (net.size[1] + 1) * (net.size[2] + 1);
  net.rowStart.resize(static_cast<std::size_t>(rows) + 1);
  auto rowOf = [&net](const SurfaceCell & c) { return net.RowOf(c.y, c.z); };
  ParallelForBlocks(
    numberOfCells + 1,
    16384,
    [&](std::size_t begin, std::size_t end, std::size_t) {
      for (std::size_t i = begin; i < end; ++i)
      {
        const std::int64_t previous = i == 0 ? -1 : rowOf(net.cells[i - 1]);
        const std::int64_t row = i == numberOfCells ? rows : rowOf(net.cells[i]);
        for (std::int64_t r = previous + 1; r <= row; ++r)
        {
          net.rowStart[static_cast<std::size_t>(r)] = static_cast<std::uint32_t>(i);
        }
      }
    },
    numberOfWorkUnits);
}

/** Whether a cell's face joins its two segments in one sheet. */
bool
OneSheetOnFace(const SurfaceNetsCellTable & table, const SurfaceCell & cell, unsigned int face)
{
  return table.SheetOfEdge(cell.configuration, cell.faceRules, table.faceEdges[face][0]) ==
         table.SheetOfEdge(cell.configuration, cell.faceRules, table.faceEdges[face][2]);
}

/** Ambiguous faces: where the face's two segments would belong to one sheet in both
 * cells that share it (joining the same two nodes twice), cut off the face's other
 * pair of corners instead; that splits the sheet in both cells and never joins sheets
 * elsewhere, so one pass in cell order settles every face. A cell's faces with
 * earlier cells were settled before it, so its rule is final once its later faces
 * are: its nodes (one per sheet) are numbered in the same pass. Returns the number of
 * nodes. */
std::uint32_t
SettleFaceRulesAndNumberNodes(SurfaceNet & net, const SurfaceNetsCellTable & table)
{
  std::uint32_t numberOfNodes = 0;
  net.numberOfSplitCells = 0;
  for (std::size_t i = 0; i < net.cells.size(); ++i)
  {
    SurfaceCell &      c = net.cells[i];
    const unsigned int ambiguous = table.ambiguousFaces[c.configuration];
    for (unsigned int f = 0; f < 3; ++f)
    {
      const unsigned int upper = 2 * f + 1; // the face shared with the next cell along axis f
      if (!((ambiguous >> upper) & 1u))
      {
        continue;
      }
      std::int64_t next[3] = { c.x, c.y, c.z };
      ++next[f];
      const std::int64_t j = net.FindCell(next[0], next[1], next[2]);
      if (j < 0)
      {
        itkGenericExceptionMacro("SurfaceNets: internal error: an ambiguous face lacks its second cell.");
      }
      SurfaceCell & d = net.cells[j];
      if (OneSheetOnFace(table, c, upper) && OneSheetOnFace(table, d, upper - 1))
      {
        c.faceRules = static_cast<std::uint8_t>(c.faceRules ^ (1u << upper));
        d.faceRules = static_cast<std::uint8_t>(d.faceRules ^ (1u << (upper - 1)));
      }
    }
    c.firstNode = numberOfNodes;
    const unsigned int sheets = table.NumberOfSheets(c.configuration, c.faceRules);
    numberOfNodes += sheets;
    net.numberOfSplitCells += sheets > 1 ? 1 : 0;
  }
  return numberOfNodes;
}

/** The centre of the midpoints of sheet s's edges, in the cell's local coordinates.
 * (All edges of a sheet never lie on one face, so this point is at least 1/12 voxel
 * inside the cell.) */
Vec3
SheetCentre(const SurfaceNetsCellTable & table, const SurfaceCell & c, unsigned int s)
{
  unsigned int edges = 0;
  for (unsigned int e = 0; e < 12; ++e)
  {
    if (table.SheetOfEdge(c.configuration, c.faceRules, e) == static_cast<std::int8_t>(s))
    {
      edges |= 1u << e;
    }
  }
  return table.CentreOfEdges(edges);
}

/** Each node's cell, start position and box: the cell shrunk by `margin` voxels, the
 * node at its centre (thesis 3.2.1); in a cell with several sheets each node sits at
 * the centre of its sheet's edge midpoints and stays there, so that the sheets keep
 * apart. */
void
PlaceNodes(SurfaceNet &                 net,
           const SurfaceNetsCellTable & table,
           double                       margin,
           std::uint32_t                numberOfNodes,
           unsigned int                 numberOfWorkUnits)
{
  net.positions.resize(numberOfNodes);
  net.boxLower.resize(numberOfNodes);
  net.boxUpper.resize(numberOfNodes);
  net.nodeCell.resize(numberOfNodes);
  ParallelForBlocks(
    net.cells.size(),
    NetBlockSize,
    [&](std::size_t begin, std::size_t end, std::size_t) {
      for (std::size_t i = begin; i < end; ++i)
      {
        const SurfaceCell & c = net.cells[i];
        const Vec3          corner = MakeVec3(c.x, c.y, c.z);
        const unsigned int  sheets = table.NumberOfSheets(c.configuration, c.faceRules);
        for (unsigned int s = 0; s < sheets; ++s)
        {
          const std::uint32_t node = c.firstNode + s;
          net.nodeCell[node] = static_cast<std::uint32_t>(i);
          Vec3 lower = MakeVec3(margin, margin, margin);
          Vec3 upper = MakeVec3(1 - margin, 1 - margin, 1 - margin);
          Vec3 start = MakeVec3(0.5, 0.5, 0.5);
          if (sheets > 1)
          {
            start = SheetCentre(table, c, s);
            lower = start;
            upper = start;
          }
          for (unsigned int d = 0; d < 3; ++d)
          {
            start[d] = std::clamp(start[d], lower[d], upper[d]);
          }
          net.positions[node] = corner + start;
          net.boxLower[node] = corner + lower;
          net.boxUpper[node] = corner + upper;
        }
      }
    },
    numberOfWorkUnits);
}

/** Cursors into the four rows of cells a cell's quads reach: the neighbours of cell
 * (x, y, z) lie in its own row and the rows at y+1, z+1 and both, at x or x+1. One
 * cursor per row, (dy, dz) = (0, 0), (1, 0), (0, 1), (1, 1), moves forward as x grows
 * (the cells are sorted), instead of a search per neighbour. */
struct NeighbourRowCursors
{
  const SurfaceCell * at[4] = { nullptr, nullptr, nullptr, nullptr };
  const SurfaceCell * last[4] = { nullptr, nullptr, nullptr, nullptr };
  std::int64_t        currentRow = -1;

  /** Cell c's rows, unless they are the current ones. */
  void
  MoveTo(const SurfaceCell &         c,
         const SurfaceCell * const   cells,
         const std::uint32_t * const rowStart,
         std::int64_t                sizeY,
         std::int64_t                sizeZ)
  {
    const std::int64_t row = (std::int64_t{ c.z } + 1) * (sizeY + 1) + (std::int64_t{ c.y } + 1);
    if (row == currentRow)
    {
      return;
    }
    currentRow = row;
    for (unsigned int k = 0; k < 4; ++k)
    {
      const std::int64_t dy = k & 1u;
      const std::int64_t dz = k >> 1;
      at[k] = last[k] = nullptr;
      if (c.y + dy < sizeY && c.z + dz < sizeZ)
      {
        const std::size_t r = static_cast<std::size_t>(row + dz * (sizeY + 1) + dy);
        at[k] = cells + rowStart[r];
        last[k] = cells + rowStart[r + 1];
      }
    }
  }

  /** The cell at x in row k, or null. */
  const SurfaceCell *
  Find(unsigned int k, std::int32_t x)
  {
    while (at[k] != last[k] && at[k]->x < x)
    {
      ++at[k];
    }
    return at[k] != last[k] && at[k]->x == x ? at[k] : nullptr;
  }
};

/** The quad of cell c's crossing voxel edge 4a+3 (along axis a, at offset 1 on the two
 * other axes b and c), counter-clockwise seen from outside, at quads[q] (q advanced);
 * its four cells' nodes are those of that edge's sheet in each. The neighbours one
 * step along b, along c and along both are in rows kb, kc, kbc at x + dxb, dxc, dxbc.
 * Sets `missing` if one of them is not a surface cell. */
template <unsigned int a>
inline void
AddQuadAlong(const SurfaceNetsCellTable &   table,
             const SurfaceCell &            c,
             NeighbourRowCursors &          cursors,
             std::array<std::uint32_t, 4> * quads,
             std::uint8_t *                 quadAxis,
             std::size_t &                  q,
             bool &                         missing)
{
  constexpr unsigned int e = 4 * a + 3;
  constexpr unsigned int b = (a + 1) % 3;
  constexpr unsigned int cAxis = (a + 2) % 3;
  if (!CrossesUpperEdge(c.configuration, a))
  {
    return;
  }
  constexpr unsigned int kb = (b == 1 ? 1 : 0) + (b == 2 ? 2 : 0);
  constexpr unsigned int kc = (cAxis == 1 ? 1 : 0) + (cAxis == 2 ? 2 : 0);
  const SurfaceCell *    cb = cursors.Find(kb, c.x + (b == 0 ? 1 : 0));
  const SurfaceCell *    cc = cursors.Find(kc, c.x + (cAxis == 0 ? 1 : 0));
  const SurfaceCell *    cbc = cursors.Find(kb + kc, c.x + 1 - (a == 0 ? 1 : 0));
  if (cb == nullptr || cc == nullptr || cbc == nullptr)
  {
    missing = true;
    return;
  }
  const std::uint32_t n = c.firstNode + table.SheetOfEdge(c.configuration, c.faceRules, e);
  const std::uint32_t nb = cb->firstNode + table.SheetOfEdge(cb->configuration, cb->faceRules, 4 * a + 2);
  const std::uint32_t nc = cc->firstNode + table.SheetOfEdge(cc->configuration, cc->faceRules, 4 * a + 1);
  const std::uint32_t nbc = cbc->firstNode + table.SheetOfEdge(cbc->configuration, cbc->faceRules, 4 * a + 0);
  if ((c.configuration >> UpperEdgeLowCorner(a)) & 1u)
  {
    quads[q] = { nbc, nc, n, nb }; // outward along +a
    quadAxis[q] = static_cast<std::uint8_t>(a);
  }
  else
  {
    quads[q] = { nb, n, nc, nbc }; // outward along -a
    quadAxis[q] = static_cast<std::uint8_t>(a + 4);
  }
  ++q;
}

/** The quads of cells [begin, end) from quad `q` on; false if a crossing voxel edge
 * lacks one of its four surface cells. */
bool
FillQuadsOfBlock(SurfaceNet &                 net,
                 const SurfaceNetsCellTable & table,
                 std::size_t                  begin,
                 std::size_t                  end,
                 std::size_t                  q)
{
  // Locals, so that the stores to the quads cannot alias them.
  const SurfaceCell * const            cells = net.cells.data();
  const std::uint32_t * const          rowStart = net.rowStart.data();
  const std::int64_t                   sizeY = net.size[1];
  const std::int64_t                   sizeZ = net.size[2];
  std::array<std::uint32_t, 4> * const quads = net.quads.data();
  std::uint8_t * const                 quadAxis = net.quadAxis.data();
  bool                                 missing = false;
  NeighbourRowCursors                  cursors;
  for (std::size_t i = begin; i < end; ++i)
  {
    const SurfaceCell & c = cells[i];
    cursors.MoveTo(c, cells, rowStart, sizeY, sizeZ);
    AddQuadAlong<0>(table, c, cursors, quads, quadAxis, q, missing);
    AddQuadAlong<1>(table, c, cursors, quads, quadAxis, q, missing);
    AddQuadAlong<2>(table, c, cursors, quads, quadAxis, q, missing);
  }
  return !missing;
}

/** The quads: each crossing voxel edge is found once, from the cell that has it as its
 * edge at offset (1, 1) on the two other axes (thesis 3.2.5). Counted per block of
 * cells, then each block fills its own range. */
void
MakeQuads(SurfaceNet & net, const SurfaceNetsCellTable & table, unsigned int numberOfWorkUnits)
{
  const std::size_t        numberOfCells = net.cells.size();
  const std::size_t        numberOfBlocks = (numberOfCells + NetBlockSize - 1) / NetBlockSize;
  std::vector<std::size_t> quadsPerBlock(numberOfBlocks + 1, 0);
  ParallelForBlocks(
    numberOfCells,
    NetBlockSize,
    [&](std::size_t begin, std::size_t end, std::size_t block) {
      std::size_t count = 0;
      for (std::size_t i = begin; i < end; ++i)
      {
        for (unsigned int a = 0; a < 3; ++a)
        {
          count += CrossesUpperEdge(net.cells[i].configuration, a) ? 1 : 0;
        }
      }
      quadsPerBlock[block + 1] = count;
    },
    numberOfWorkUnits);
  std::partial_sum(quadsPerBlock.begin(), quadsPerBlock.end(), quadsPerBlock.begin());
  net.quads.resize(quadsPerBlock.back());
  net.quadAxis.resize(quadsPerBlock.back());
  std::atomic<bool> missingNeighbour{ false };
  ParallelForBlocks(
    numberOfCells,
    NetBlockSize,
    [&](std::size_t begin, std::size_t end, std::size_t block) {
      if (!FillQuadsOfBlock(net, table, begin, end, quadsPerBlock[block]))
      {
        missingNeighbour = true;
      }
    },
    numberOfWorkUnits);
  if (missingNeighbour)
  {
    itkGenericExceptionMacro("SurfaceNets: internal error: a crossing voxel edge lacks one of its four surface cells.");
  }
}

/** Each node's links as the successors of its corners in the quads, gathered in quad
 * order: `degree` the compressed rows' starts (numberOfNodes + 1), `all` the links. */
void
GatherLinks(const SurfaceNet &                net,
            std::uint32_t                     numberOfNodes,
            LargeBlockVector<std::uint32_t> & degree,
            LargeBlockVector<std::uint32_t> & all)
{
  degree.assign(numberOfNodes + 1, 0);
  for (const auto & quad : net.quads)
  {
    for (unsigned int k = 0; k < 4; ++k)
    {
      ++degree[quad[k] + 1];
    }
  }
  std::partial_sum(degree.begin(), degree.end(), degree.begin());
  all.resize(degree.back());
  std::vector<std::uint32_t> cursor(degree.begin(), degree.end() - 1);
  for (const auto & quad : net.quads)
  {
    for (unsigned int k = 0; k < 4; ++k)
    {
      all[cursor[quad[k]]++] = quad[(k + 1) % 4];
    }
  }
}

/** Sorts each node's few links (insertion sort) and drops repeats; unique[v + 1] is
 * the number left of node v. In parallel over blocks of nodes. */
void
SortLinksOfEachNode(LargeBlockVector<std::uint32_t> &       all,
                    const LargeBlockVector<std::uint32_t> & degree,
                    LargeBlockVector<std::uint32_t> &       unique,
                    unsigned int                            numberOfWorkUnits)
{
  const std::size_t numberOfNodes = degree.size() - 1;
  unique.assign(numberOfNodes + 1, 0);
  ParallelForBlocks(
    numberOfNodes,
    NetBlockSize,
    [&](std::size_t begin, std::size_t end, std::size_t) {
      for (std::size_t v = begin; v < end; ++v)
      {
        std::uint32_t * first = all.data() + degree[v];
        std::uint32_t * last = all.data() + degree[v + 1];
        for (std::uint32_t * i = first + 1; i < last; ++i)
        {
          const std::uint32_t value = *i;
          std::uint32_t *     j = i;
          for (; j > first && *(j - 1) > value; --j)
          {
            *j = *(j - 1);
          }
          *j = value;
        }
        unique[v + 1] = static_cast<std::uint32_t>(std::unique(first, last) - first);
      }
    },
    numberOfWorkUnits);
}

/** The links: the edges of the quads. Every link is the edge of two quads, the two
 * crossing voxel edges of its segment on the face between its cells, and the quads
 * are oriented consistently, so a link runs from v to w in one of them and from w to
 * v in the other: each node gathers its links once as the successors of its corners.
 * Repeats, which a consistent net has none of, are dropped. */
void
LinkNodes(SurfaceNet & net, std::uint32_t numberOfNodes, unsigned int numberOfWorkUnits)
{
  LargeBlockVector<std::uint32_t> degree;
  LargeBlockVector<std::uint32_t> all;
  GatherLinks(net, numberOfNodes, degree, all);
  LargeBlockVector<std::uint32_t> unique;
  SortLinksOfEachNode(all, degree, unique, numberOfWorkUnits);
  std::partial_sum(unique.begin(), unique.end(), unique.begin());
  if (unique.back() == degree.back())
  {
    // No repeats (always, in a consistently oriented net): the gathered links are the links.
    net.neighbors = std::move(all);
    net.neighborStart = std::move(degree);
    return;
  }
  net.neighbors.resize(unique.back());
  ParallelForBlocks(
    numberOfNodes,
    NetBlockSize,
    [&](std::size_t begin, std::size_t end, std::size_t) {
      for (std::size_t v = begin; v < end; ++v)
      {
        std::copy_n(all.data() + degree[v], unique[v + 1] - unique[v], net.neighbors.data() + unique[v]);
      }
    },
    numberOfWorkUnits);
  net.neighborStart = std::move(unique);
}
} // namespace

SurfaceNetsCellTable::SurfaceNetsCellTable()
    : m_NumberOfSheets(256 * 64, 0)
    , m_SheetOfEdge(256 * 64)
{
  NumberCellEdges(*this);
  NumberCellFaces(*this);
  for (unsigned int configuration = 0; configuration < 256; ++configuration)
  {
    bool crossing[12];
    for (unsigned int e = 0; e < 12; ++e)
    {
      crossing[e] = ((configuration >> edgeCorners[e][0]) & 1u) != ((configuration >> edgeCorners[e][1]) & 1u);
    }
    ambiguousFaces[configuration] = 0;
    for (unsigned int f = 0; f < 6; ++f)
    {
      unsigned int n = 0;
      for (unsigned int i = 0; i < 4; ++i)
      {
        n += crossing[faceEdges[f][i]] ? 1 : 0;
      }
      ambiguousFaces[configuration] |= static_cast<std::uint8_t>(n == 4 ? (1u << f) : 0u);
    }
    for (unsigned int rules = 0; rules < 64; ++rules)
    {
      m_NumberOfSheets[configuration * 64 + rules] =
        FindSheets(*this, configuration, crossing, rules, m_SheetOfEdge[configuration * 64 + rules]);
    }
  }
}

Vec3
SurfaceNetsCellTable::CentreOfEdges(unsigned int edges) const
{
  Vec3         sum = MakeVec3(0, 0, 0);
  unsigned int count = 0;
  for (unsigned int e = 0; e < 12; ++e)
  {
    if ((edges >> e) & 1u)
    {
      for (unsigned int d = 0; d < 3; ++d)
      {
        sum[d] += 0.5 * (((edgeCorners[e][0] >> d) & 1) + ((edgeCorners[e][1] >> d) & 1));
      }
      ++count;
    }
  }
  return sum * (1.0 / count);
}

const SurfaceNetsCellTable &
SurfaceNetsCellTable::Get()
{
  static const SurfaceNetsCellTable table;
  return table;
}

void
BuildSurfaceNet(SurfaceNet & net, double margin, unsigned int numberOfWorkUnits)
{
  const SurfaceNetsCellTable & table = SurfaceNetsCellTable::Get();
  IndexCellRows(net, numberOfWorkUnits);
  const std::uint32_t numberOfNodes = SettleFaceRulesAndNumberNodes(net, table);
  PlaceNodes(net, table, margin, numberOfNodes, numberOfWorkUnits);
  MakeQuads(net, table, numberOfWorkUnits);
  LinkNodes(net, numberOfNodes, numberOfWorkUnits);
}

namespace
{
/** Whether quad i is split along its diagonal 0-2 (else 1-3): the diagonal `split`
 * prefers (the shorter, or the one whose triangles' smallest angle is larger), unless
 * that gives a triangle facing away from the quad's voxel-edge direction (in index
 * space) and the other diagonal faces it better. */
bool
SplitAlongDiagonal02(const SurfaceNet & net, QuadSplit split, const Vec3 * points, std::size_t i)
{
  const auto &       q = net.quads[i];
  const unsigned int axis = net.quadAxis[i] & 3u;
  const double       sign = (net.quadAxis[i] & 4u) ? -1.0 : 1.0;
  // Orientation in index space, along the quad's voxel edge.
  auto facing = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    return sign * TriangleNormal(net.positions[a], net.positions[b], net.positions[c])[axis];
  };
  const double along02 = std::min(facing(q[0], q[1], q[2]), facing(q[0], q[2], q[3]));
  const double along13 = std::min(facing(q[0], q[1], q[3]), facing(q[1], q[2], q[3]));
  bool         use02;
  if (split == QuadSplit::ShortestDiagonal)
  {
    use02 = SquaredNorm(points[q[0]] - points[q[2]]) <= SquaredNorm(points[q[1]] - points[q[3]]);
  }
  else
  {
    auto smallestAngle = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
      return MeasureTriangle(points[a], points[b], points[c]).minAngle;
    };
    use02 = std::min(smallestAngle(q[0], q[1], q[2]), smallestAngle(q[0], q[2], q[3])) >=
            std::min(smallestAngle(q[0], q[1], q[3]), smallestAngle(q[1], q[2], q[3]));
  }
  if (use02 && !(along02 > 0.0) && along13 > along02)
  {
    return false;
  }
  if (!use02 && !(along13 > 0.0) && along02 > along13)
  {
    return true;
  }
  return use02;
}
} // namespace

void
MakeSurfaceNetFaces(const SurfaceNet &                               net,
                    const Matrix<double, 3, 3> &                     indexToPhysical,
                    QuadSplit                                        split,
                    const Vec3 *                                     points,
                    LargeBlockVector<std::array<std::uint32_t, 4>> & polygons,
                    unsigned int &                                   polygonSize)
{
  // A reflecting direction matrix turns counter-clockwise into clockwise.
  const bool reflect = vnl_det(indexToPhysical.GetVnlMatrix()) < 0.0;
  polygons.clear();
  if (split == QuadSplit::KeepQuads)
  {
    polygonSize = 4;
    polygons.reserve(net.quads.size());
    for (const auto & q : net.quads)
    {
      polygons.push_back(reflect ? std::array<std::uint32_t, 4>{ { q[3], q[2], q[1], q[0] } } : q);
    }
    return;
  }
  polygonSize = 3;
  polygons.resize(2 * net.quads.size());
  ParallelForBlocks(net.quads.size(), 8192, [&](std::size_t begin, std::size_t end, std::size_t) {
    for (std::size_t i = begin; i < end; ++i)
    {
      const auto &                 q = net.quads[i];
      std::array<std::uint32_t, 4> t0;
      std::array<std::uint32_t, 4> t1;
      if (SplitAlongDiagonal02(net, split, points, i))
      {
        t0 = { { q[0], q[1], q[2], 0 } };
        t1 = { { q[0], q[2], q[3], 0 } };
      }
      else
      {
        t0 = { { q[0], q[1], q[3], 0 } };
        t1 = { { q[1], q[2], q[3], 0 } };
      }
      if (reflect)
      {
        std::swap(t0[1], t0[2]);
        std::swap(t1[1], t1[2]);
      }
      polygons[2 * i] = t0;
      polygons[2 * i + 1] = t1;
    }
  });
}

void
RoundToFloat(Vec3 * points, std::size_t numberOfPoints)
{
  // Through a volatile float: g++ 12.2 at -O3 vectorizes a plain round trip through
  // float and, in the loop's scalar remainder (up to three points), rounded only the
  // last coordinate of each point, so checks saw other points than were written.
  for (std::size_t i = 0; i < numberOfPoints; ++i)
  {
    for (unsigned int r = 0; r < 3; ++r)
    {
      volatile float rounded = static_cast<float>(points[i][r]);
      points[i][r] = static_cast<double>(rounded);
    }
  }
}

void
ToPhysical(const Vec3 *                 index,
           std::size_t                  numberOfPoints,
           const Vec3 &                 origin,
           const Matrix<double, 3, 3> & M,
           bool                         roundToFloat,
           Vec3 *                       physical)
{
  for (std::size_t i = 0; i < numberOfPoints; ++i)
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
  if (roundToFloat)
  {
    RoundToFloat(physical, numberOfPoints);
  }
}

namespace
{
/** The polygons as triangles (a quad as two), for the volumes of their components. */
std::vector<TriangleIndices>
PolygonsAsTriangles(const LargeBlockVector<std::array<std::uint32_t, 4>> & polygons, unsigned int polygonSize)
{
  std::vector<TriangleIndices> triangles;
  triangles.reserve(polygons.size() * (polygonSize - 2));
  for (const auto & q : polygons)
  {
    triangles.push_back({ { q[0], q[1], q[2] } });
    if (polygonSize == 4)
    {
      triangles.push_back({ { q[0], q[2], q[3] } });
    }
  }
  return triangles;
}

/** ComponentVolumes::vertexComponent of a node in no face. */
constexpr std::uint32_t NoComponent = std::numeric_limits<std::uint32_t>::max();
} // namespace

SmallComponentRemoval
RemoveSmallComponents(LargeBlockVector<std::array<std::uint32_t, 4>> & polygons,
                      unsigned int                                     polygonSize,
                      const std::vector<Vec3> &                        points,
                      double                                           minimumVolume)
{
  SmallComponentRemoval removal;
  ComponentVolumes      volumes;
  volumes.Initialize(PolygonsAsTriangles(polygons, polygonSize), points);
  // ComponentVolumes keeps 6 x the signed volume of each component.
  std::vector<bool> removed(volumes.reference.size());
  for (std::size_t c = 0; c < removed.size(); ++c)
  {
    removed[c] = std::abs(volumes.reference[c]) < 6.0 * minimumVolume;
    removal.numberOfComponents += removed[c] ? 1 : 0;
    removal.largestVolume = std::max(removal.largestVolume, std::abs(volumes.reference[c]) / 6.0);
  }
  if (removal.numberOfComponents == 0)
  {
    return removal;
  }
  std::vector<std::uint32_t> newIndex(points.size(), NoComponent);
  for (std::size_t v = 0; v < points.size(); ++v)
  {
    const std::uint32_t c = volumes.vertexComponent[v];
    if (c != NoComponent && !removed[c])
    {
      newIndex[v] = static_cast<std::uint32_t>(removal.keptPoints.size());
      removal.keptPoints.push_back(static_cast<std::uint32_t>(v));
    }
  }
  std::size_t kept = 0;
  for (const auto & q : polygons)
  {
    if (newIndex[q[0]] == NoComponent)
    {
      continue;
    }
    std::array<std::uint32_t, 4> renumbered{};
    for (unsigned int k = 0; k < polygonSize; ++k)
    {
      renumbered[k] = newIndex[q[k]];
    }
    polygons[kept++] = renumbered;
  }
  removal.numberOfFaces = polygons.size() - kept;
  polygons.resize(kept);
  return removal;
}

} // namespace detail
} // namespace MeshExtraction
} // namespace itk
