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
#include "itkMeshExtractionMultiLabelSurfaceNet.h"
#include "itkMeshExtractionDisjointSets.h"
#include "itkMeshExtractionParallel.h"
#include "itkMeshExtractionSelfIntersections.h"
#include "itkMeshExtractionSurfaceNetsClassification.h"
#include "itkMeshExtractionSurfaceNetsRelaxation.h"
#include "itkMeshExtractionValidityGuard.h"
#include "itkImage.h"
#include "itkMacro.h"
#include "itkMultiThreaderBase.h"

#include <algorithm>
#include <limits>
#include <map>
#include <numeric>

namespace itk
{
namespace MeshExtraction
{
namespace
{
constexpr std::uint32_t NoVertex = std::numeric_limits<std::uint32_t>::max();
/** How far a label's vertex moves from a node where the label touches itself, toward its
 * own sheet: a fiftieth of the way (a few thousandths of a voxel), enough to keep the
 * two sheets apart in the written coordinates and little enough that the faces at that
 * node stay where the neighbouring label's copies are, within that distance. */
constexpr double PinchSeparation = 0.02;
} // namespace

void
MultiLabelSurfaceNet::LabelSurface(std::uint32_t                  k,
                                   std::vector<Vec3> &            surfacePoints,
                                   std::vector<TriangleIndices> & surfaceTriangles,
                                   std::vector<std::uint32_t> *   vertexNodes) const
{
  if (k == 0 || k > numberOfLabels)
  {
    itkGenericExceptionMacro("MultiLabelSurfaceNet: no label " << k << " (the labels are 1.." << numberOfLabels
                                                               << ").");
  }
  const std::uint32_t        first = labelVertexStart[k];
  const std::uint32_t        count = labelVertexStart[k + 1] - first;
  std::vector<std::uint32_t> newIndex(count, NoVertex);
  surfacePoints.clear();
  surfaceTriangles.clear();
  if (vertexNodes != nullptr)
  {
    vertexNodes->clear();
  }
  for (std::size_t at = labelFaceStart[k]; at < labelFaceStart[k + 1]; ++at)
  {
    const std::uint32_t f = labelFaces[at];
    const unsigned int  side = faceLabels[f][0] == k ? 0u : 1u;
    TriangleIndices     t;
    for (unsigned int i = 0; i < 3; ++i)
    {
      const std::uint32_t v = sideVertices[f][side][i] - first;
      if (newIndex[v] == NoVertex)
      {
        newIndex[v] = static_cast<std::uint32_t>(surfacePoints.size());
        const auto pinch = std::lower_bound(pinchedVertexPoints.begin(),
                                            pinchedVertexPoints.end(),
                                            first + v,
                                            [](const auto & a, std::uint32_t b) { return a.first < b; });
        surfacePoints.push_back(pinch != pinchedVertexPoints.end() && pinch->first == first + v
                                  ? pinch->second
                                  : points[sideVertexNode[first + v]]);
        if (vertexNodes != nullptr)
        {
          vertexNodes->push_back(sideVertexNode[first + v]);
        }
      }
      t[i] = newIndex[v];
    }
    if (side == 1)
    {
      std::swap(t[1], t[2]); // the face points out of the lower label: into this one
    }
    surfaceTriangles.push_back(t);
  }
}

namespace detail
{
namespace
{
using MaskImageType = Image<std::uint8_t, 3>;

/** A label's own binary net over its crop of the image. */
struct LabelNet
{
  SurfaceNet                  net;
  std::array<std::int64_t, 3> offset{ { 0, 0, 0 } }; ///< the crop's first voxel in the image
  std::uint32_t               firstVertex{ 0 };      ///< its node 0 among all labels' vertices
};

/** One node of one label's net, where the cells of all labels meet. */
struct CellRecord
{
  std::uint64_t cell;   ///< CellKey of the cell
  std::uint32_t label;  ///< 1..K
  std::uint32_t vertex; ///< label vertex (net node + firstVertex)
  std::uint16_t edges;  ///< bit e: crossing edge e belongs to this node's sheet
  bool          fixed;  ///< fixed in its own net (a cell of several sheets)
};

std::uint64_t
CellKey(std::int64_t x, std::int64_t y, std::int64_t z)
{
  return (static_cast<std::uint64_t>(z + 1) << 42) | (static_cast<std::uint64_t>(y + 1) << 21) |
         static_cast<std::uint64_t>(x + 1);
}

std::array<std::int64_t, 3>
CellOfKey(std::uint64_t key)
{
  const std::uint64_t mask = (std::uint64_t{ 1 } << 21) - 1;
  return { static_cast<std::int64_t>(key & mask) - 1,
           static_cast<std::int64_t>((key >> 21) & mask) - 1,
           static_cast<std::int64_t>(key >> 42) - 1 };
}

/** The label of voxel (x, y, z): 0 outside the image. */
struct LabelLookup
{
  const std::uint32_t *       labels;
  std::array<std::int64_t, 3> size;
  std::uint32_t
  operator()(std::int64_t x, std::int64_t y, std::int64_t z) const
  {
    if (x < 0 || y < 0 || z < 0 || x >= size[0] || y >= size[1] || z >= size[2])
    {
      return 0;
    }
    return labels[(z * size[1] + y) * size[0] + x];
  }
};

/** Each label's bounding box (voxels), in one pass; throws for a value above K or a
 * label without a voxel. */
std::vector<std::array<std::int64_t, 6>>
LabelBoxes(const LabelLookup & lookup, std::uint32_t numberOfLabels)
{
  std::vector<std::array<std::int64_t, 6>> boxes(numberOfLabels + 1,
                                                 { { std::numeric_limits<std::int64_t>::max(),
                                                     std::numeric_limits<std::int64_t>::max(),
                                                     std::numeric_limits<std::int64_t>::max(),
                                                     -1,
                                                     -1,
                                                     -1 } });
  const auto &                             size = lookup.size;
  std::size_t                              i = 0;
  for (std::int64_t z = 0; z < size[2]; ++z)
  {
    for (std::int64_t y = 0; y < size[1]; ++y)
    {
      for (std::int64_t x = 0; x < size[0]; ++x, ++i)
      {
        const std::uint32_t label = lookup.labels[i];
        if (label == 0)
        {
          continue;
        }
        if (label > numberOfLabels)
        {
          itkGenericExceptionMacro("MultiLabelSurfaceNet: voxel (" << x << ", " << y << ", " << z
                                                                   << ") has label index " << label << ", above the "
                                                                   << numberOfLabels << " labels.");
        }
        auto &             b = boxes[label];
        const std::int64_t at[3] = { x, y, z };
        for (unsigned int d = 0; d < 3; ++d)
        {
          b[d] = std::min(b[d], at[d]);
          b[d + 3] = std::max(b[d + 3], at[d]);
        }
      }
    }
  }
  for (std::uint32_t k = 1; k <= numberOfLabels; ++k)
  {
    if (boxes[k][3] < 0)
    {
      itkGenericExceptionMacro("MultiLabelSurfaceNet: label index " << k << " has no voxel.");
    }
  }
  return boxes;
}

/** The face rules of label k's net where its two corners of an ambiguous face are
 * diagonal and the other diagonal holds other labels. The single-label net keeps k's
 * corners apart there (6-connected). Two different labels on the other diagonal (one may
 * be the background) are kept apart by k anyway, so k's corners join across the face:
 * kept apart, both of k's sheets would share their crossing edges with the same
 * neighbouring sheet, and so one node, where k's surface would touch itself. The same
 * label on both (a checkerboard of two labels) must be cut by one of them: the lower
 * label joins. Both cells of a face see the same corners, so they choose alike. */
void
PreferFaceRules(const LabelLookup & lookup, std::uint32_t k, LabelNet & out)
{
  const SurfaceNetsCellTable & table = SurfaceNetsCellTable::Get();
  for (SurfaceCell & c : out.net.cells)
  {
    const unsigned int ambiguous = table.ambiguousFaces[c.configuration];
    if (ambiguous == 0)
    {
      continue;
    }
    for (unsigned int f = 0; f < 6; ++f)
    {
      if (!((ambiguous >> f) & 1u))
      {
        continue;
      }
      // The corners not of k: faceCorners[f][i] for the i whose bit is clear.
      std::uint32_t other[2];
      unsigned int  n = 0;
      for (unsigned int i = 0; i < 4; ++i)
      {
        const unsigned int corner = table.faceCorners[f][i];
        if (!((c.configuration >> corner) & 1u))
        {
          other[n++] = lookup(c.x + out.offset[0] + (corner & 1u),
                              c.y + out.offset[1] + ((corner >> 1) & 1u),
                              c.z + out.offset[2] + ((corner >> 2) & 1u));
        }
      }
      const bool join = other[0] != other[1] || (other[0] != 0 && k < other[0]);
      if (join)
      {
        c.faceRules = static_cast<std::uint8_t>(c.faceRules | (1u << f));
      }
    }
  }
}

/** Label k's binary net over its box and one voxel around it (clipped to the image). */
void
BuildLabelNet(const LabelLookup &                    lookup,
              std::uint32_t                          k,
              const std::array<std::int64_t, 6> &    box,
              const MultiLabelSurfaceNetParameters & parameters,
              LabelNet &                             out)
{
  MaskImageType::RegionType region;
  for (unsigned int d = 0; d < 3; ++d)
  {
    const std::int64_t lower = std::max<std::int64_t>(0, box[d] - 1);
    const std::int64_t upper = std::min<std::int64_t>(lookup.size[d] - 1, box[d + 3] + 1);
    out.offset[d] = lower;
    region.SetIndex(d, 0);
    region.SetSize(d, static_cast<SizeValueType>(upper - lower + 1));
  }
  auto mask = MaskImageType::New();
  mask->SetRegions(region);
  mask->Allocate();
  std::uint8_t *     m = mask->GetBufferPointer();
  const std::int64_t nx = static_cast<std::int64_t>(region.GetSize(0));
  const std::int64_t ny = static_cast<std::int64_t>(region.GetSize(1));
  const std::int64_t nz = static_cast<std::int64_t>(region.GetSize(2));
  for (std::int64_t z = 0; z < nz; ++z)
  {
    for (std::int64_t y = 0; y < ny; ++y)
    {
      const std::uint32_t * row =
        lookup.labels + ((z + out.offset[2]) * lookup.size[1] + (y + out.offset[1])) * lookup.size[0] + out.offset[0];
      std::uint8_t * to = m + (z * ny + y) * nx;
      for (std::int64_t x = 0; x < nx; ++x)
      {
        to[x] = static_cast<std::uint8_t>(row[x] == k);
      }
    }
  }
  ClassifySurfaceCells(
    mask.GetPointer(), SurfaceNetsVoxelRange<std::uint8_t>::FromLabel(1.0), out.net, parameters.numberOfWorkUnits);
  PreferFaceRules(lookup, k, out);
  BuildSurfaceNet(out.net, parameters.cellMargin, parameters.numberOfWorkUnits);
}

/** The voxel-edge numbers, in a cell, of a quad's four corners (AddQuadAlong's order). */
std::array<unsigned int, 4>
QuadCornerEdges(unsigned int axis, bool outwardIsNegative)
{
  const unsigned int a = 4 * axis;
  if (!outwardIsNegative)
  {
    return { { a + 0, a + 1, a + 3, a + 2 } }; // { nbc, nc, n, nb }
  }
  return { { a + 2, a + 3, a + 1, a + 0 } }; // { nb, n, nc, nbc }
}

/** \brief The vertices of the labels' own surfaces at pinched nodes (where a label's two
 * sheets share a node: it touches itself there), and the faces near them.
 *
 * In its own surface such a vertex sits a little off the node, toward the centre of its
 * sheet's crossing edges (PinchSeparation), so that the label's two sheets do not touch.
 * Those faces are checked for crossings within the label's surface: its faces with a
 * node within two cells of a pinched node's cell, the only ones a face at that node
 * can reach (nodes stay in their cells). */
class PinchedVertices
{
public:
  PinchedVertices(const std::vector<CellRecord> &                                  records,
                  const std::vector<std::size_t> &                                 pinched,
                  const std::vector<std::uint32_t> &                               nodeOfVertex,
                  const LargeBlockVector<std::array<std::uint32_t, 4>> &           quads,
                  const std::vector<std::array<std::uint32_t, 2>> &                quadLabels,
                  const std::vector<std::array<std::array<std::uint32_t, 4>, 2>> & quadSides,
                  const std::vector<std::uint64_t> &                               nodeCell,
                  std::uint32_t                                                    numberOfLabels)
      : m_Quads(quads)
      , m_QuadSides(quadSides)
      , m_Candidates(numberOfLabels + 1)
  {
    const SurfaceNetsCellTable &            table = SurfaceNetsCellTable::Get();
    std::vector<std::vector<std::uint64_t>> nearCells(numberOfLabels + 1);
    for (const std::size_t r : pinched)
    {
      const CellRecord & record = records[r];
      const auto         cell = CellOfKey(record.cell);
      m_Entries.push_back({ record.vertex,
                            nodeOfVertex[record.vertex],
                            MakeVec3(cell[0], cell[1], cell[2]) + table.CentreOfEdges(record.edges) });
      for (std::int64_t dz = -2; dz <= 2; ++dz)
      {
        for (std::int64_t dy = -2; dy <= 2; ++dy)
        {
          for (std::int64_t dx = -2; dx <= 2; ++dx)
          {
            if (cell[0] + dx >= -1 && cell[1] + dy >= -1 && cell[2] + dz >= -1)
            {
              nearCells[record.label].push_back(CellKey(cell[0] + dx, cell[1] + dy, cell[2] + dz));
            }
          }
        }
      }
    }
    std::sort(m_Entries.begin(), m_Entries.end(), [](const Entry & a, const Entry & b) { return a.vertex < b.vertex; });
    for (auto & cells : nearCells)
    {
      std::sort(cells.begin(), cells.end());
      cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
    }
    for (std::size_t q = 0; q < quads.size(); ++q)
    {
      for (unsigned int side = 0; side < 2; ++side)
      {
        const std::uint32_t label = quadLabels[q][side];
        if (label == 0 || nearCells[label].empty())
        {
          continue;
        }
        for (const std::uint32_t node : quads[q])
        {
          if (std::binary_search(nearCells[label].begin(), nearCells[label].end(), nodeCell[node]))
          {
            m_Candidates[label].emplace_back(static_cast<std::uint32_t>(q), static_cast<std::uint8_t>(side));
            break;
          }
        }
      }
    }
  }

  /** The number of pinched nodes. */
  std::size_t
  NumberOfNodes() const
  {
    std::vector<std::uint32_t> nodes;
    for (const Entry & e : m_Entries)
    {
      nodes.push_back(e.node);
    }
    std::sort(nodes.begin(), nodes.end());
    return static_cast<std::size_t>(std::unique(nodes.begin(), nodes.end()) - nodes.begin());
  }

  /** Each pinched vertex (sorted) and its point in its label's surface, for the nodes at
   * `positions`. */
  std::vector<std::pair<std::uint32_t, Vec3>>
  Points(const LargeBlockVector<Vec3> & positions, const MultiLabelSurfaceNetParameters & parameters) const
  {
    std::vector<std::pair<std::uint32_t, Vec3>> points;
    points.reserve(m_Entries.size());
    for (const Entry & e : m_Entries)
    {
      points.emplace_back(e.vertex, this->Point(e, positions, parameters));
    }
    return points;
  }

  /** Adds to `badNodes` the nodes of the faces near pinched nodes that cross another face
   * of their label's surface (with the pinched vertices off their nodes), or that are
   * degenerate there while not all at the start (`atStart` of the face's nodes). */
  template <typename TAtStart>
  void
  FindCrossings(const LargeBlockVector<Vec3> &                         positions,
                const std::vector<Vec3> &                              physical,
                const LargeBlockVector<std::array<std::uint32_t, 4>> & polygons,
                const MultiLabelSurfaceNetParameters &                 parameters,
                TAtStart &&                                            atStart,
                std::vector<std::uint32_t> &                           badNodes) const
  {
    for (const auto & candidates : m_Candidates)
    {
      if (candidates.empty())
      {
        continue;
      }
      IndexedTriangleMesh                    local;
      std::vector<std::uint32_t>             localNode;
      std::vector<TriangleIndices>           nodeTriangles;
      std::vector<std::uint32_t>             queries;
      std::map<std::uint32_t, std::uint32_t> localOf;
      for (const auto & candidate : candidates)
      {
        const auto & quad = m_Quads[candidate.first];
        for (std::size_t t = 2 * std::size_t{ candidate.first }; t < 2 * std::size_t{ candidate.first } + 2; ++t)
        {
          TriangleIndices tri;
          TriangleIndices nodes;
          bool            pinchedCorner = false;
          for (unsigned int i = 0; i < 3; ++i)
          {
            const std::uint32_t node = polygons[t][i];
            const auto corner = static_cast<std::size_t>(std::find(quad.begin(), quad.end(), node) - quad.begin());
            const std::uint32_t vertex = m_QuadSides[candidate.first][candidate.second][corner];
            const Entry *       entry = this->Find(vertex);
            pinchedCorner = pinchedCorner || entry != nullptr;
            auto found = localOf.find(vertex);
            if (found == localOf.end())
            {
              found = localOf.emplace(vertex, static_cast<std::uint32_t>(local.points.size())).first;
              local.points.push_back(entry != nullptr ? this->Point(*entry, positions, parameters) : physical[node]);
              localNode.push_back(node);
            }
            tri[i] = found->second;
            nodes[i] = node;
          }
          if (pinchedCorner)
          {
            queries.push_back(static_cast<std::uint32_t>(local.triangles.size()));
            if (TriangleQArea(local.points[tri[0]], local.points[tri[1]], local.points[tri[2]]) <=
                  ValidityThresholds::DegenerateQAreaTolerance &&
                !atStart(nodes))
            {
              badNodes.insert(badNodes.end(), nodes.begin(), nodes.end());
            }
          }
          local.triangles.push_back(tri);
          nodeTriangles.push_back(nodes);
        }
      }
      for (const auto & p : FindSelfIntersections(local, &queries))
      {
        badNodes.insert(badNodes.end(), nodeTriangles[p.first].begin(), nodeTriangles[p.first].end());
        badNodes.insert(badNodes.end(), nodeTriangles[p.second].begin(), nodeTriangles[p.second].end());
      }
    }
  }

private:
  struct Entry
  {
    std::uint32_t vertex; ///< label vertex
    std::uint32_t node;
    Vec3          centre; ///< its sheet's centre, continuous index
  };

  const Entry *
  Find(std::uint32_t vertex) const
  {
    const auto found = std::lower_bound(
      m_Entries.begin(), m_Entries.end(), vertex, [](const Entry & e, std::uint32_t v) { return e.vertex < v; });
    return found != m_Entries.end() && found->vertex == vertex ? &*found : nullptr;
  }

  static Vec3
  Point(const Entry & e, const LargeBlockVector<Vec3> & positions, const MultiLabelSurfaceNetParameters & parameters)
  {
    const Vec3 moved = positions[e.node] + (e.centre - positions[e.node]) * PinchSeparation;
    Vec3       point;
    ToPhysical(&moved, 1, parameters.origin, parameters.indexToPhysical, parameters.roundToFloat, &point);
    return point;
  }

  const LargeBlockVector<std::array<std::uint32_t, 4>> &           m_Quads;
  const std::vector<std::array<std::array<std::uint32_t, 4>, 2>> & m_QuadSides;
  std::vector<Entry>                                               m_Entries;
  std::vector<std::vector<std::pair<std::uint32_t, std::uint8_t>>> m_Candidates; ///< per label: (quad, side)
};

} // namespace

MultiLabelSurfaceNet
MakeMultiLabelSurfaceNet(const std::uint32_t *                  labels,
                         const std::array<std::int64_t, 3> &    size,
                         std::uint32_t                          numberOfLabels,
                         const MultiLabelSurfaceNetParameters & parameters)
{
  const SurfaceNetsCellTable & table = SurfaceNetsCellTable::Get();
  for (unsigned int d = 0; d < 3; ++d)
  {
    if (size[d] < 1 || size[d] >= (std::int64_t{ 1 } << 21) - 2)
    {
      itkGenericExceptionMacro("MultiLabelSurfaceNet: the image size " << size[d] << " along axis " << d
                                                                       << " is out of range.");
    }
  }
  if (numberOfLabels == 0)
  {
    itkGenericExceptionMacro("MultiLabelSurfaceNet: no label to extract.");
  }
  const LabelLookup lookup{ labels, size };
  const auto        boxes = LabelBoxes(lookup, numberOfLabels);

  // 1. Each label's own net.
  std::vector<LabelNet> nets(numberOfLabels + 1);
  MultiLabelSurfaceNet  result;
  result.numberOfLabels = numberOfLabels;
  result.labelVertexStart.assign(numberOfLabels + 2, 0);
  // Many labels: one label per work unit, each net on one; a few: one after another,
  // each on all of them.
  const unsigned int workUnits = parameters.numberOfWorkUnits > 0 ? parameters.numberOfWorkUnits
                                 : ThreadNumberOfWorkUnits() > 0  ? ThreadNumberOfWorkUnits()
                                                                 : MultiThreaderBase::GetGlobalDefaultNumberOfThreads();
  if (numberOfLabels >= 4 * workUnits)
  {
    MultiLabelSurfaceNetParameters one = parameters;
    one.numberOfWorkUnits = 1;
    ParallelForBlocks(
      numberOfLabels,
      1,
      [&](std::size_t begin, std::size_t end, std::size_t) {
        for (std::size_t i = begin; i < end; ++i)
        {
          const auto k = static_cast<std::uint32_t>(i + 1);
          BuildLabelNet(lookup, k, boxes[k], one, nets[k]);
        }
      },
      parameters.numberOfWorkUnits);
  }
  else
  {
    for (std::uint32_t k = 1; k <= numberOfLabels; ++k)
    {
      BuildLabelNet(lookup, k, boxes[k], parameters, nets[k]);
    }
  }
  std::size_t numberOfVertices = 0;
  for (std::uint32_t k = 1; k <= numberOfLabels; ++k)
  {
    nets[k].firstVertex = static_cast<std::uint32_t>(numberOfVertices);
    result.labelVertexStart[k] = nets[k].firstVertex;
    numberOfVertices += nets[k].net.positions.size();
    if (numberOfVertices >= NoVertex)
    {
      itkGenericExceptionMacro("MultiLabelSurfaceNet: more than 2^32 - 1 nodes.");
    }
  }
  result.labelVertexStart[numberOfLabels + 1] = static_cast<std::uint32_t>(numberOfVertices);

  // 2. The nodes of all labels per cell, sorted by cell.
  std::vector<CellRecord> records;
  records.reserve(numberOfVertices);
  for (std::uint32_t k = 1; k <= numberOfLabels; ++k)
  {
    const LabelNet & ln = nets[k];
    for (const SurfaceCell & c : ln.net.cells)
    {
      const unsigned int sheets = table.NumberOfSheets(c.configuration, c.faceRules);
      std::uint16_t      edges[12] = {};
      for (unsigned int e = 0; e < 12; ++e)
      {
        const std::int8_t s = table.SheetOfEdge(c.configuration, c.faceRules, e);
        if (s >= 0)
        {
          edges[s] = static_cast<std::uint16_t>(edges[s] | (1u << e));
        }
      }
      const std::uint64_t key = CellKey(c.x + ln.offset[0], c.y + ln.offset[1], c.z + ln.offset[2]);
      for (unsigned int s = 0; s < sheets; ++s)
      {
        records.push_back({ key, k, ln.firstVertex + c.firstNode + s, edges[s], sheets > 1 });
      }
    }
  }
  std::sort(records.begin(), records.end(), [](const CellRecord & a, const CellRecord & b) {
    return a.cell != b.cell ? a.cell < b.cell : a.vertex < b.vertex;
  });

  // 3. Nodes: the labels' sheets that share a crossing voxel edge in a cell are one.
  DisjointSets sets(numberOfVertices);
  for (std::size_t b = 0; b < records.size();)
  {
    std::size_t e = b + 1;
    while (e < records.size() && records[e].cell == records[b].cell)
    {
      ++e;
    }
    for (std::size_t i = b; i < e; ++i)
    {
      for (std::size_t j = i + 1; j < e; ++j)
      {
        if (records[i].edges & records[j].edges)
        {
          sets.Join(records[i].vertex, records[j].vertex);
        }
      }
    }
    b = e;
  }
  std::vector<std::uint32_t> nodeOfVertex(numberOfVertices, NoVertex);
  std::vector<std::uint32_t> nodeOfRoot(numberOfVertices, NoVertex);
  std::vector<std::uint64_t> nodeCell;
  std::vector<std::uint16_t> nodeEdges;
  std::vector<std::uint8_t>  nodeFixed;
  std::vector<std::size_t>   nodeRecords; // the first record of the node's cell
  std::vector<std::size_t>   pinched;     // records of a label with another sheet in the same node
  result.sideVertexNode.assign(numberOfVertices, 0);
  for (std::size_t b = 0; b < records.size();)
  {
    std::size_t e = b;
    const auto  firstNodeOfCell = static_cast<std::uint32_t>(nodeCell.size());
    while (e < records.size() && records[e].cell == records[b].cell)
    {
      const CellRecord &  r = records[e];
      const std::uint32_t root = sets.Find(r.vertex);
      if (nodeOfRoot[root] == NoVertex)
      {
        nodeOfRoot[root] = static_cast<std::uint32_t>(nodeCell.size());
        nodeCell.push_back(r.cell);
        nodeEdges.push_back(0);
        nodeFixed.push_back(0);
        nodeRecords.push_back(b);
      }
      const std::uint32_t node = nodeOfRoot[root];
      nodeEdges[node] = static_cast<std::uint16_t>(nodeEdges[node] | r.edges);
      nodeFixed[node] = static_cast<std::uint8_t>(nodeFixed[node] | (r.fixed ? 1u : 0u));
      nodeOfVertex[r.vertex] = node;
      result.sideVertexNode[r.vertex] = node;
      ++e;
    }
    const auto nodesInCell = static_cast<std::uint32_t>(nodeCell.size()) - firstNodeOfCell;
    for (std::uint32_t n = firstNodeOfCell; n < nodeCell.size(); ++n)
    {
      nodeFixed[n] = static_cast<std::uint8_t>(nodeFixed[n] | (nodesInCell > 1 ? 1u : 0u));
    }
    // A label with two sheets in one node touches itself there.
    for (std::size_t i = b; i < e; ++i)
    {
      for (std::size_t j = b; j < e; ++j)
      {
        if (i != j && records[i].label == records[j].label &&
            nodeOfVertex[records[i].vertex] == nodeOfVertex[records[j].vertex])
        {
          pinched.push_back(i);
          break;
        }
      }
    }
    b = e;
  }
  const std::size_t numberOfNodes = nodeCell.size();

  // 4. The labels around each node (both ends of its crossing edges): three or more
  // make a junction.
  std::vector<std::uint32_t> labelSetStart(numberOfNodes + 1, 0);
  std::vector<std::uint32_t> labelSets;
  for (std::size_t n = 0; n < numberOfNodes; ++n)
  {
    const auto    cell = CellOfKey(nodeCell[n]);
    std::uint32_t found[24];
    unsigned int  count = 0;
    for (unsigned int e = 0; e < 12; ++e)
    {
      if (!((nodeEdges[n] >> e) & 1u))
      {
        continue;
      }
      for (unsigned int end = 0; end < 2; ++end)
      {
        const unsigned int k = table.edgeCorners[e][end];
        found[count++] = lookup(cell[0] + (k & 1u), cell[1] + ((k >> 1) & 1u), cell[2] + ((k >> 2) & 1u));
      }
    }
    std::sort(found, found + count);
    const auto last = std::unique(found, found + count);
    labelSets.insert(labelSets.end(), found, last);
    labelSetStart[n + 1] = static_cast<std::uint32_t>(labelSets.size());
  }
  auto labelCount = [&](std::size_t n) { return labelSetStart[n + 1] - labelSetStart[n]; };
  auto sameLabels = [&](std::size_t a, std::size_t b) {
    return labelCount(a) == labelCount(b) && std::equal(labelSets.begin() + labelSetStart[a],
                                                        labelSets.begin() + labelSetStart[a + 1],
                                                        labelSets.begin() + labelSetStart[b]);
  };

  // 5. Every face once, from the net of its lower label (the background's from the
  // label's), pointing out of the lower label.
  SurfaceNet                                faces; // the nodes' quads, for the relaxation and MakeSurfaceNetFaces
  std::vector<std::array<std::uint32_t, 2>> quadLabels;
  std::vector<std::array<std::array<std::uint32_t, 4>, 2>> quadSides;
  for (std::uint32_t k = 1; k <= numberOfLabels; ++k)
  {
    const LabelNet & ln = nets[k];
    for (std::size_t q = 0; q < ln.net.quads.size(); ++q)
    {
      const auto &        quad = ln.net.quads[q];
      const unsigned int  axis = ln.net.quadAxis[q] & 3u;
      const bool          negative = (ln.net.quadAxis[q] & 4u) != 0;
      const std::uint32_t base = negative ? quad[1] : quad[2]; // the cell whose edge 4a+3 it is
      const SurfaceCell & c = ln.net.cells[ln.net.nodeCell[base]];
      const std::int64_t  x = c.x + ln.offset[0];
      const std::int64_t  y = c.y + ln.offset[1];
      const std::int64_t  z = c.z + ln.offset[2];
      // The voxel edge's two ends: corner 7 - (1 << axis) (low) and corner 7 (high).
      const std::int64_t  lowCorner[3] = { x + (axis != 0), y + (axis != 1), z + (axis != 2) };
      const std::uint32_t other =
        negative ? lookup(lowCorner[0], lowCorner[1], lowCorner[2]) : lookup(x + 1, y + 1, z + 1);
      if (other == k)
      {
        itkGenericExceptionMacro("MultiLabelSurfaceNet: internal error: a face inside label " << k << '.');
      }
      if (other != 0 && other < k)
      {
        continue; // made from the other label's net
      }
      std::array<std::uint32_t, 4>                nodes;
      std::array<std::array<std::uint32_t, 4>, 2> sides;
      const auto                                  edges = QuadCornerEdges(axis, negative);
      for (unsigned int i = 0; i < 4; ++i)
      {
        const std::uint32_t v = ln.firstVertex + quad[i];
        nodes[i] = nodeOfVertex[v];
        sides[0][i] = v;
        sides[1][i] = NoVertex;
        if (other == 0)
        {
          continue;
        }
        // The other label's sheet of the same voxel edge in this corner's cell.
        const std::uint64_t cell = nodeCell[nodes[i]];
        for (std::size_t r = nodeRecords[nodes[i]]; r < records.size() && records[r].cell == cell; ++r)
        {
          if (records[r].label == other && ((records[r].edges >> edges[i]) & 1u))
          {
            sides[1][i] = records[r].vertex;
            break;
          }
        }
        if (sides[1][i] == NoVertex || nodeOfVertex[sides[1][i]] != nodes[i])
        {
          itkGenericExceptionMacro("MultiLabelSurfaceNet: internal error: a face between labels "
                                   << k << " and " << other << " lacks its node in label " << other << '.');
        }
      }
      std::uint8_t quadAxis = ln.net.quadAxis[q];
      if (other == 0)
      {
        // Out of the background, into k: the other way round, k's vertices on side 1.
        std::reverse(nodes.begin(), nodes.end());
        std::reverse(sides[0].begin(), sides[0].end());
        std::swap(sides[0], sides[1]);
        quadAxis = static_cast<std::uint8_t>(quadAxis ^ 4u);
        quadLabels.push_back({ { 0, k } });
      }
      else
      {
        quadLabels.push_back({ { k, other } });
      }
      faces.quads.push_back(nodes);
      faces.quadAxis.push_back(quadAxis);
      quadSides.push_back(sides);
    }
    nets[k].net = SurfaceNet(); // its cells and quads are no longer needed
  }

  // 6. Start positions, constraint boxes and links. A node alone in its cell starts at
  // the centre and moves in the cell shrunk by the margin; several nodes in a cell, and
  // a node of several sheets of one label's net, stay at the centre of their crossing
  // edges' midpoints, which keeps them apart (as in the single-label net). A node on a
  // junction of three or more labels averages only its neighbours on the same junction
  // line; one that has not two of them (a corner where junction lines meet or end)
  // stays.
  // The links, per node: the quads' edges both ways, counted, placed, then each node's
  // few sorted and made unique.
  std::vector<std::uint32_t> linkStart(numberOfNodes + 1, 0);
  for (const auto & q : faces.quads)
  {
    for (const std::uint32_t n : q)
    {
      linkStart[n + 1] += 2;
    }
  }
  std::partial_sum(linkStart.begin(), linkStart.end(), linkStart.begin());
  std::vector<std::uint32_t> links(linkStart.back());
  {
    std::vector<std::uint32_t> fill(linkStart.begin(), linkStart.end() - 1);
    for (const auto & q : faces.quads)
    {
      for (unsigned int i = 0; i < 4; ++i)
      {
        links[fill[q[i]]++] = q[(i + 1) % 4];
        links[fill[q[i]]++] = q[(i + 3) % 4];
      }
    }
  }
  std::vector<std::uint32_t> linkEnd(numberOfNodes);
  ParallelForBlocks(
    numberOfNodes,
    8192,
    [&](std::size_t begin, std::size_t end, std::size_t) {
      for (std::size_t n = begin; n < end; ++n)
      {
        const auto first = links.begin() + linkStart[n];
        std::sort(first, links.begin() + linkStart[n + 1]);
        linkEnd[n] = static_cast<std::uint32_t>(std::unique(first, links.begin() + linkStart[n + 1]) - links.begin());
      }
    },
    parameters.numberOfWorkUnits);
  faces.neighborStart.assign(numberOfNodes + 1, 0);
  std::vector<std::uint8_t> junction(numberOfNodes, 0);
  for (std::size_t n = 0; n < numberOfNodes; ++n)
  {
    junction[n] = labelCount(n) >= 3 ? 1 : 0;
    result.numberOfJunctionNodes += junction[n];
  }
  {
    for (std::size_t n = 0; n < numberOfNodes; ++n)
    {
      const std::size_t begin = faces.neighbors.size();
      for (std::size_t l = linkStart[n]; l < linkEnd[n]; ++l)
      {
        const std::uint32_t m = links[l];
        if (!junction[n] || (junction[m] && sameLabels(n, m)))
        {
          faces.neighbors.push_back(m);
        }
      }
      if (junction[n] && faces.neighbors.size() - begin != 2)
      {
        nodeFixed[n] = 1;
      }
      faces.neighborStart[n + 1] = static_cast<std::uint32_t>(faces.neighbors.size());
    }
  }
  faces.positions.resize(numberOfNodes);
  faces.boxLower.resize(numberOfNodes);
  faces.boxUpper.resize(numberOfNodes);
  faces.nodeCell.assign(numberOfNodes, 0);
  const double margin = parameters.cellMargin;
  for (std::size_t n = 0; n < numberOfNodes; ++n)
  {
    const auto cell = CellOfKey(nodeCell[n]);
    const Vec3 corner = MakeVec3(cell[0], cell[1], cell[2]);
    if (nodeFixed[n])
    {
      faces.positions[n] = corner + table.CentreOfEdges(nodeEdges[n]);
      faces.boxLower[n] = faces.positions[n];
      faces.boxUpper[n] = faces.positions[n];
      ++result.numberOfFixedNodes;
    }
    else
    {
      faces.positions[n] = corner + MakeVec3(0.5, 0.5, 0.5);
      faces.boxLower[n] = corner + MakeVec3(margin, margin, margin);
      faces.boxUpper[n] = corner + MakeVec3(1 - margin, 1 - margin, 1 - margin);
    }
  }
  const LargeBlockVector<Vec3> start = faces.positions;

  // 7. SNA: every node to the average of its neighbours, within its box.
  SurfaceNetsRelaxationParameters relaxation;
  relaxation.kind = SurfaceNetsImageToMeshFilterEnums::Relaxation::Averaging;
  relaxation.maximumNumberOfIterations = parameters.maximumNumberOfIterations;
  relaxation.convergenceThreshold = parameters.convergenceThreshold;
  relaxation.centralDifferences = false;
  relaxation.indexToPhysical = parameters.indexToPhysical;
  relaxation.numberOfWorkUnits = parameters.numberOfWorkUnits;
  const SurfaceNetsSampler<MaskImageType> * noSampler = nullptr;
  result.iterations = RelaxSurfaceNet(
                        faces, noSampler, [](const Vec3 &, std::uint32_t) { return MakeVec3(0, 0, 0); }, relaxation)
                        .iterations;

  // 8. Where faces cross (of one label or of two) or one is degenerate, the nodes of
  // those faces move back toward the start: halved a few times, then reset. The start
  // is free of crossings, so this ends. Where a label touches itself (a pinched node),
  // its own surface has its two vertices there a little apart (PinchSeparation), which
  // its faces near that node are checked with too.
  IndexedTriangleMesh                            mesh; // its points: the nodes' physical points
  std::vector<Vec3> &                            physical = mesh.points;
  LargeBlockVector<std::array<std::uint32_t, 4>> polygons;
  unsigned int                                   polygonSize = 3;
  const PinchedVertices                          pinches(
    records, pinched, nodeOfVertex, faces.quads, quadLabels, quadSides, nodeCell, numberOfLabels);
  std::vector<std::uint8_t>  halvings(numberOfNodes, 0);
  std::vector<std::uint8_t>  movedBack(numberOfNodes, 0);
  std::vector<std::uint8_t>  moved(numberOfNodes, 0); // in the last round
  std::vector<std::uint32_t> queries;
  auto                       atStart = [&](const TriangleIndices & tri) {
    return faces.positions[tri[0]] == start[tri[0]] && faces.positions[tri[1]] == start[tri[1]] &&
           faces.positions[tri[2]] == start[tri[2]];
  };
  physical.resize(numberOfNodes);
  auto makeFaces = [&]() {
    ToPhysical(faces.positions.data(),
               numberOfNodes,
               parameters.origin,
               parameters.indexToPhysical,
               parameters.roundToFloat,
               physical.data());
    MakeSurfaceNetFaces(faces, parameters.indexToPhysical, parameters.split, physical.data(), polygons, polygonSize);
  };
  for (unsigned int round = 0;; ++round)
  {
    makeFaces();
    mesh.triangles.resize(polygons.size());
    for (std::size_t t = 0; t < polygons.size(); ++t)
    {
      mesh.triangles[t] = { { polygons[t][0], polygons[t][1], polygons[t][2] } };
    }
    // After the first round only the faces of quads with a node moved back can have
    // changed: both triangles of such a quad (its diagonal may have turned, giving a
    // triangle without the moved node).
    queries.clear();
    for (std::size_t q = 0; round > 0 && q < faces.quads.size(); ++q)
    {
      const auto & quad = faces.quads[q];
      if (moved[quad[0]] || moved[quad[1]] || moved[quad[2]] || moved[quad[3]])
      {
        queries.push_back(static_cast<std::uint32_t>(2 * q));
        queries.push_back(static_cast<std::uint32_t>(2 * q + 1));
      }
    }
    std::vector<std::uint32_t> badNodes;
    for (const auto & p : round == 0 ? FindSelfIntersections(mesh) : FindSelfIntersections(mesh, &queries))
    {
      badNodes.insert(badNodes.end(), mesh.triangles[p.first].begin(), mesh.triangles[p.first].end());
      badNodes.insert(badNodes.end(), mesh.triangles[p.second].begin(), mesh.triangles[p.second].end());
    }
    // A face pressed flat (three nodes of a junction line in a row, say) goes back too,
    // unless all its nodes are at the start already.
    auto checkFlat = [&](const TriangleIndices & tri) {
      if (TriangleQArea(physical[tri[0]], physical[tri[1]], physical[tri[2]]) <=
            ValidityThresholds::DegenerateQAreaTolerance &&
          !atStart(tri))
      {
        badNodes.insert(badNodes.end(), tri.begin(), tri.end());
      }
    };
    if (round == 0)
    {
      std::for_each(mesh.triangles.begin(), mesh.triangles.end(), checkFlat);
    }
    for (const std::uint32_t t : queries)
    {
      checkFlat(mesh.triangles[t]);
    }
    pinches.FindCrossings(faces.positions, physical, polygons, parameters, atStart, badNodes);
    if (badNodes.empty())
    {
      break;
    }
    if (round == ValidityThresholds::MaximumRepairRounds)
    {
      faces.positions = start;
      std::fill(movedBack.begin(), movedBack.end(), 1);
      makeFaces();
      break;
    }
    std::fill(moved.begin(), moved.end(), 0);
    for (const std::uint32_t n : badNodes)
    {
      if (moved[n])
      {
        continue;
      }
      moved[n] = 1;
      movedBack[n] = 1;
      if (++halvings[n] > ValidityThresholds::SurfaceNetsHalvingsBeforeReset)
      {
        faces.positions[n] = start[n];
      }
      else
      {
        faces.positions[n] = start[n] + (faces.positions[n] - start[n]) * 0.5;
      }
    }
  }
  result.numberOfNodesMovedBack = static_cast<std::size_t>(std::count(movedBack.begin(), movedBack.end(), 1));

  // 9. The result: nodes, and per face its labels and its vertices in both labels.
  result.positions.assign(faces.positions.begin(), faces.positions.end());
  result.points = physical;
  result.pinchedVertexPoints = pinches.Points(faces.positions, parameters);
  result.numberOfPinchedNodes = pinches.NumberOfNodes();
  result.triangles.resize(polygons.size());
  result.faceLabels.resize(polygons.size());
  result.sideVertices.resize(polygons.size());
  for (std::size_t t = 0; t < polygons.size(); ++t)
  {
    const std::size_t q = t / 2;
    const auto &      quad = faces.quads[q];
    for (unsigned int i = 0; i < 3; ++i)
    {
      const std::uint32_t node = polygons[t][i];
      const unsigned int  corner = static_cast<unsigned int>(std::find(quad.begin(), quad.end(), node) - quad.begin());
      result.triangles[t][i] = node;
      result.sideVertices[t][0][i] = quadSides[q][0][corner];
      result.sideVertices[t][1][i] = quadSides[q][1][corner];
    }
    result.faceLabels[t] = quadLabels[q];
  }
  result.labelFaceStart.assign(numberOfLabels + 2, 0);
  for (const auto & pair : result.faceLabels)
  {
    ++result.labelFaceStart[pair[0] + 1];
    ++result.labelFaceStart[pair[1] + 1];
  }
  std::partial_sum(result.labelFaceStart.begin(), result.labelFaceStart.end(), result.labelFaceStart.begin());
  result.labelFaces.resize(result.labelFaceStart.back());
  {
    std::vector<std::uint32_t> fill(result.labelFaceStart.begin(), result.labelFaceStart.end() - 1);
    for (std::size_t f = 0; f < result.faceLabels.size(); ++f)
    {
      for (const std::uint32_t label : result.faceLabels[f])
      {
        result.labelFaces[fill[label]++] = static_cast<std::uint32_t>(f);
      }
    }
  }
  return result;
}

} // namespace detail
} // namespace MeshExtraction
} // namespace itk
