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
// The validity guard after the SurfaceNets relaxation (stage 3b): the crossing faces
// found from the net's cells (FindSurfaceNetSelfIntersections) and their nodes moved
// back toward the cell centres (RemoveSurfaceNetSelfIntersections).
#include "itkMeshExtractionValidityGuard.h"
#include "itkMeshExtractionMacros.h"
#include "itkMeshExtractionParallel.h"
#include "itkMeshExtractionPredicates.h"
#include "itkMeshExtractionQualityAnalysis.h"
#include "vnl/vnl_det.h"
#include "vnl/vnl_inverse.h"

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
using FacePairs = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

/** Cells per block of the parallel passes over cells. */
constexpr std::size_t CellBlockSize = 2048;

/** m: the nodes' smallest distance to a face of their cell (index space). */
double
SmallestDistanceToCellFaces(const SurfaceNet & net)
{
  double margin = std::numeric_limits<double>::max();
  for (std::size_t i = 0; i < net.positions.size(); ++i)
  {
    const SurfaceCell & c = net.cells[net.nodeCell[i]];
    const double        corner[3] = { static_cast<double>(c.x), static_cast<double>(c.y), static_cast<double>(c.z) };
    for (unsigned int k = 0; k < 3; ++k)
    {
      margin = std::min(margin, std::min(net.positions[i][k] - corner[k], corner[k] + 1.0 - net.positions[i][k]));
    }
  }
  return margin;
}

/** Whether quads whose blocks of cells share no cell stay apart in the coordinates as
 * computed. Such blocks are 2m apart in index space, at least 2m * s in physical
 * space, s >= 1 / |M^-1|_F the smallest singular value of M. A point moves by at most
 * delta when computed (origin + M index, a few double roundings of magnitudes up to
 * `bound`) and rounded to float: demand 4 delta < m s. */
bool
CellBlocksKeepQuadsApart(const SurfaceNet &           net,
                         const Vec3 &                 origin,
                         const Matrix<double, 3, 3> & indexToPhysical,
                         bool                         roundedToFloat,
                         double                       margin)
{
  double bound = 0.0;
  double rowSum = 0.0;
  for (unsigned int r = 0; r < 3; ++r)
  {
    double row = 0.0;
    for (unsigned int c = 0; c < 3; ++c)
    {
      row += std::abs(indexToPhysical[r][c]);
    }
    rowSum = std::max(rowSum, row);
    bound = std::max(bound, std::abs(origin[r]));
  }
  bound += rowSum * (static_cast<double>(std::max({ net.size[0], net.size[1], net.size[2] })) + 1.0);
  const double unit = (roundedToFloat ? std::ldexp(1.0, -24) : 0.0) + 8.0 * std::ldexp(1.0, -53);
  const double delta = std::sqrt(3.0) * unit * bound;
  if (vnl_det(indexToPhysical.GetVnlMatrix()) == 0.0)
  {
    return false;
  }
  const vnl_matrix_fixed<double, 3, 3> inverse = vnl_inverse(indexToPhysical.GetVnlMatrix());
  const double                         smallestStretch = 1.0 / inverse.frobenius_norm();
  return margin > 0.0 && 4.0 * delta < margin * smallestStretch;
}

/** The cells of each quad, ascending, and the quads of each cell: those with a node in
 * it (a quad's four nodes lie in four different cells), as compressed rows. */
struct QuadCellIncidence
{
  UninitializedArray<std::array<std::uint32_t, 4>> quadCells;
  std::vector<std::uint32_t>                       start; ///< the quads of cell c: [start[c], start[c+1])
  UninitializedArray<std::uint32_t>                quadsOfCell;

  explicit QuadCellIncidence(const SurfaceNet & net)
      : quadCells(net.quads.size())
      , start(net.cells.size() + 1, 0)
  {
    const std::size_t numberOfQuads = net.quads.size();
    for (std::size_t q = 0; q < numberOfQuads; ++q)
    {
      for (unsigned int v = 0; v < 4; ++v)
      {
        quadCells[q][v] = net.nodeCell[net.quads[q][v]];
        ++start[quadCells[q][v] + 1];
      }
      std::sort(quadCells[q].begin(), quadCells[q].end());
    }
    std::partial_sum(start.begin(), start.end(), start.begin());
    quadsOfCell.Allocate(start.back());
    std::vector<std::uint32_t> cursor(start.begin(), start.end() - 1);
    for (std::uint32_t q = 0; q < numberOfQuads; ++q)
    {
      for (std::uint32_t c : quadCells[q])
      {
        quadsOfCell[cursor[c]++] = q;
      }
    }
  }
};

/** Which faces changed, and the cells of their nodes: only pairs with a changed face
 * are sought, in those cells. */
struct ChangedFaces
{
  const std::vector<std::uint32_t> * list{ nullptr };
  std::vector<bool>                  face;
  std::vector<bool>                  cell;

  ChangedFaces(const SurfaceNet & net, const IndexedTriangleMesh & mesh, const std::vector<std::uint32_t> * changed)
      : list(changed)
  {
    if (changed == nullptr)
    {
      return;
    }
    face.assign(mesh.triangles.size(), false);
    cell.assign(net.cells.size(), false);
    for (std::uint32_t f : *changed)
    {
      if (f < mesh.triangles.size())
      {
        face[f] = true;
        for (std::uint32_t v : net.quads[f / 2])
        {
          cell[net.nodeCell[v]] = true;
        }
      }
    }
  }

  bool
  SkipsCell(std::size_t c) const
  {
    return list != nullptr && !cell[c];
  }
};

/** The nodes of cell c: [first, end). */
inline std::uint32_t
EndNodeOfCell(const SurfaceNet & net, std::size_t c)
{
  return c + 1 < net.cells.size() ? net.cells[c + 1].firstNode : static_cast<std::uint32_t>(net.positions.size());
}

/** Nodes whose fan of faces is certified (FanIsEmbeddedStar): two faces that meet at
 * such a node have no other common point, or only their common edge. On a relaxed net
 * nearly every node is one, and the exact tests are left to the pairs that share no
 * certified node. Each node's fan: its corners in the faces of its cell's quads (every
 * quad with a node in the cell). */
std::vector<std::uint8_t>
CertifiedStarNodes(const SurfaceNet &          net,
                   const IndexedTriangleMesh & mesh,
                   const QuadCellIncidence &   incidence,
                   const ChangedFaces &        changed,
                   unsigned int                numberOfWorkUnits)
{
  std::vector<std::uint8_t> starNode(net.positions.size(), 0);
  ParallelForBlocks(
    net.cells.size(),
    CellBlockSize,
    [&](std::size_t begin, std::size_t end, std::size_t) {
      std::vector<FanCorner> fan;
      FanScratch             scratch;
      for (std::size_t c = begin; c < end; ++c)
      {
        if (changed.SkipsCell(c))
        {
          continue;
        }
        for (std::uint32_t node = net.cells[c].firstNode; node < EndNodeOfCell(net, c); ++node)
        {
          fan.clear();
          for (std::uint32_t k = incidence.start[c]; k < incidence.start[c + 1]; ++k)
          {
            for (unsigned int s = 0; s < 2; ++s)
            {
              const auto & face = mesh.triangles[2 * incidence.quadsOfCell[k] + s];
              for (unsigned int j = 0; j < 3; ++j)
              {
                if (face[j] == node)
                {
                  fan.push_back({ face[(j + 1) % 3], face[(j + 2) % 3] });
                }
              }
            }
          }
          starNode[node] = CertifyFan(mesh.points.data(), node, fan.data(), fan.size(), scratch) ? 1 : 0;
        }
      }
    },
    numberOfWorkUnits);
  return starNode;
}

/** A face's bounding box rounded outward to float. Most pairs tested are rejected by
 * their boxes, which then takes two boxes instead of six points; the float box holds
 * the face's double box, so a pair it rejects is one the double boxes would have
 * rejected. */
struct FaceBox
{
  float lower[3];
  float upper[3];
};

/** Which faces are not degenerate (the others never intersect), decided once per face:
 * a face at a certified node is not (the certificate found it turning strictly); and
 * each face's FaceBox. */
void
ProperFacesAndBoxes(const IndexedTriangleMesh &       mesh,
                    const std::vector<std::uint8_t> & starNode,
                    std::vector<std::uint8_t> &       valid,
                    UninitializedArray<FaceBox> &     faceBox,
                    unsigned int                      numberOfWorkUnits)
{
  valid.resize(mesh.triangles.size());
  faceBox.Allocate(mesh.triangles.size());
  ParallelForBlocks(
    mesh.triangles.size(),
    8 * CellBlockSize,
    [&](std::size_t begin, std::size_t end, std::size_t) {
      constexpr float infinity = std::numeric_limits<float>::infinity();
      for (std::size_t f = begin; f < end; ++f)
      {
        const auto & t = mesh.triangles[f];
        valid[f] =
          starNode[t[0]] || starNode[t[1]] || starNode[t[2]] || MeshFaceIsProper(mesh, static_cast<std::uint32_t>(f));
        for (unsigned int d = 0; d < 3; ++d)
        {
          const double low = std::min({ mesh.points[t[0]][d], mesh.points[t[1]][d], mesh.points[t[2]][d] });
          const double high = std::max({ mesh.points[t[0]][d], mesh.points[t[1]][d], mesh.points[t[2]][d] });
          float        l = static_cast<float>(low);
          float        h = static_cast<float>(high);
          faceBox[f].lower[d] = static_cast<double>(l) > low ? std::nextafter(l, -infinity) : l;
          faceBox[f].upper[d] = static_cast<double>(h) < high ? std::nextafter(h, infinity) : h;
        }
      }
    },
    numberOfWorkUnits);
}

/** \brief The search for crossing faces among the quads of one cell at a time.
 *
 * Every pair of quads that share a cell is tested once, in the first cell they share;
 * the two faces of one quad once, in the quad's first cell. */
class CellPairSearch
{
public:
  CellPairSearch(const SurfaceNet &                  net,
                 const IndexedTriangleMesh &         mesh,
                 const QuadCellIncidence &           incidence,
                 const ChangedFaces &                changed,
                 const std::vector<std::uint8_t> &   starNode,
                 const std::vector<std::uint8_t> &   valid,
                 const UninitializedArray<FaceBox> & faceBox)
      : m_Net(net)
      , m_Mesh(mesh)
      , m_Incidence(incidence)
      , m_Changed(changed)
      , m_StarNode(starNode)
      , m_Valid(valid)
      , m_FaceBox(faceBox)
  {}

  /** The crossing pairs first found in cell c, into `found`. */
  void
  SearchCell(std::size_t c, FacePairs & found)
  {
    if (!this->CollectQuads(c))
    {
      return; // every face of the cell meets every other at its certified node
    }
    for (std::size_t i = 0; i < m_Quads.size(); ++i)
    {
      const Quad & a = m_Quads[i];
      if (a.cells[0] == c)
      {
        this->TestFaces(a, 0, a, 1, found);
      }
      for (std::size_t j = i + 1; j < m_Quads.size(); ++j)
      {
        const Quad & b = m_Quads[j];
        if ((a.apart | b.apart) == 0 || !FirstSharedCellIs(a, b, c))
        {
          continue;
        }
        for (unsigned int s = 0; s < 2; ++s)
        {
          for (unsigned int t = 0; t < 2; ++t)
          {
            if (((a.apart >> s) | (b.apart >> t)) & 1u)
            {
              this->TestFaces(a, s, b, t, found);
            }
          }
        }
      }
    }
  }

private:
  /** A quad of the cell, with its cells and its two faces' vertices. */
  struct Quad
  {
    std::uint32_t index;
    std::uint32_t cells[4];
    std::uint32_t faces[2][3];
    unsigned int  apart; ///< bit s: face s may meet other faces of the cell away from a certified node
  };

  /** The quads of cell c; false if no face of them needs a test. A cell with one node,
   * certified: every quad of the cell has that node, and two faces that both have it
   * do not intersect, so only faces without it (one face of a quad not split through
   * the node) need pairs here. */
  bool
  CollectQuads(std::size_t c)
  {
    m_Quads.clear();
    const std::uint32_t firstNode = m_Net.cells[c].firstNode;
    const bool          singleStar = EndNodeOfCell(m_Net, c) == firstNode + 1 && m_StarNode[firstNode];
    unsigned int        anyApart = 0;
    for (std::uint32_t k = m_Incidence.start[c]; k < m_Incidence.start[c + 1]; ++k)
    {
      Quad quad;
      quad.index = m_Incidence.quadsOfCell[k];
      quad.apart = 0;
      std::copy(m_Incidence.quadCells[quad.index].begin(), m_Incidence.quadCells[quad.index].end(), quad.cells);
      for (unsigned int s = 0; s < 2; ++s)
      {
        const auto & face = m_Mesh.triangles[2 * quad.index + s];
        std::copy(face.begin(), face.end(), quad.faces[s]);
        const bool hasNode = face[0] == firstNode || face[1] == firstNode || face[2] == firstNode;
        quad.apart |= (!singleStar || !hasNode) ? (1u << s) : 0u;
      }
      anyApart |= quad.apart;
      m_Quads.push_back(quad);
    }
    return anyApart != 0;
  }

  /** Whether c is the first cell quads a and b share: their cell lists are ascending
   * and contain c, so no common cell may come before c. */
  static bool
  FirstSharedCellIs(const Quad & a, const Quad & b, std::size_t c)
  {
    unsigned int x = 0;
    unsigned int y = 0;
    while (a.cells[x] < c && b.cells[y] < c)
    {
      if (a.cells[x] == b.cells[y])
      {
        return false;
      }
      if (a.cells[x] < b.cells[y])
      {
        ++x;
      }
      else
      {
        ++y;
      }
    }
    return true;
  }

  /** Face s of quad a against face t of quad b. Faces that meet at a certified node do
   * not intersect. Faces with a common vertex always have overlapping boxes; the
   * others are tested only if their boxes overlap. */
  MESHEXTRACTION_ALWAYS_INLINE void
  TestFaces(const Quad & a, unsigned int s, const Quad & b, unsigned int t, FacePairs & found) const
  {
    const std::uint32_t f = 2 * a.index + s;
    const std::uint32_t g = 2 * b.index + t;
    if (!m_Valid[f] || !m_Valid[g] || (m_Changed.list != nullptr && !m_Changed.face[f] && !m_Changed.face[g]))
    {
      return;
    }
    const std::uint32_t * p = a.faces[s];
    const std::uint32_t * q = b.faces[t];
    bool                  common = false;
    for (unsigned int i = 0; i < 3; ++i)
    {
      if (p[i] == q[0] || p[i] == q[1] || p[i] == q[2])
      {
        if (m_StarNode[p[i]])
        {
          return;
        }
        common = true;
      }
    }
    if (!common)
    {
      const FaceBox & P = m_FaceBox[f];
      const FaceBox & Q = m_FaceBox[g];
      if (!(P.lower[0] <= Q.upper[0] && Q.lower[0] <= P.upper[0] && P.lower[1] <= Q.upper[1] &&
            Q.lower[1] <= P.upper[1] && P.lower[2] <= Q.upper[2] && Q.lower[2] <= P.upper[2]))
      {
        return;
      }
    }
    if (MeshFacesIntersect(m_Mesh, f, g))
    {
      found.emplace_back(std::min(f, g), std::max(f, g));
    }
  }

  const SurfaceNet &                  m_Net;
  const IndexedTriangleMesh &         m_Mesh;
  const QuadCellIncidence &           m_Incidence;
  const ChangedFaces &                m_Changed;
  const std::vector<std::uint8_t> &   m_StarNode;
  const std::vector<std::uint8_t> &   m_Valid;
  const UninitializedArray<FaceBox> & m_FaceBox;
  std::vector<Quad>                   m_Quads; ///< of the current cell
};

/** The faces of the net as they will be written, for the check: split by `split`
 * (shortest diagonal for KeepQuads), the points rounded as ToPhysical with
 * `roundToFloat` rounds them. `polygons` keeps the faces. */
void
MakeFacesToCheck(const SurfaceNet &                               net,
                 const Vec3 &                                     origin,
                 const Matrix<double, 3, 3> &                     indexToPhysical,
                 QuadSplit                                        split,
                 bool                                             roundToFloat,
                 LargeBlockVector<std::array<std::uint32_t, 4>> & polygons,
                 IndexedTriangleMesh &                            mesh)
{
  std::vector<Vec3> points;
  unsigned int      polygonSize = 3;
  MakeSurfaceNetFaces(net,
                      origin,
                      indexToPhysical,
                      split == QuadSplit::KeepQuads ? QuadSplit::ShortestDiagonal : split,
                      points,
                      polygons,
                      polygonSize);
  if (roundToFloat)
  {
    // The points as ToPhysical with roundToFloat makes them: the face split's, each
    // coordinate rounded (not computed a second time).
    RoundToFloat(points.data(), points.size());
  }
  mesh.points = std::move(points);
  mesh.triangles.resize(polygons.size());
  for (std::size_t f = 0; f < polygons.size(); ++f)
  {
    mesh.triangles[f] = { polygons[f][0], polygons[f][1], polygons[f][2] };
  }
}

/** The faces with a node in `nodes`. */
std::vector<std::uint32_t>
FacesAtNodes(const IndexedTriangleMesh & mesh, const std::vector<bool> & nodes)
{
  std::vector<std::uint32_t> faces;
  for (std::uint32_t f = 0; f < mesh.triangles.size(); ++f)
  {
    const auto & t = mesh.triangles[f];
    if (nodes[t[0]] || nodes[t[1]] || nodes[t[2]])
    {
      faces.push_back(f);
    }
  }
  return faces;
}

/** The nodes of the faces of `pairs`, sorted, each once. */
std::vector<std::uint32_t>
NodesOfPairs(const IndexedTriangleMesh & mesh, const FacePairs & pairs)
{
  std::vector<std::uint32_t> nodes;
  for (const auto & p : pairs)
  {
    for (std::uint32_t v : mesh.triangles[p.first])
    {
      nodes.push_back(v);
    }
    for (std::uint32_t v : mesh.triangles[p.second])
    {
      nodes.push_back(v);
    }
  }
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  return nodes;
}
} // namespace

bool
FindSurfaceNetSelfIntersections(const SurfaceNet &                 net,
                                const IndexedTriangleMesh &        mesh,
                                const Vec3 &                       origin,
                                const Matrix<double, 3, 3> &       indexToPhysical,
                                bool                               roundedToFloat,
                                const std::vector<std::uint32_t> * changed,
                                FacePairs &                        pairs,
                                unsigned int                       numberOfWorkUnits)
{
  pairs.clear();
  if (mesh.triangles.size() != 2 * net.quads.size() || mesh.points.size() != net.positions.size())
  {
    return false;
  }
  const double margin = SmallestDistanceToCellFaces(net);
  if (!CellBlocksKeepQuadsApart(net, origin, indexToPhysical, roundedToFloat, margin))
  {
    return false;
  }
  const QuadCellIncidence     incidence(net);
  const ChangedFaces          changedFaces(net, mesh, changed);
  const auto                  starNode = CertifiedStarNodes(net, mesh, incidence, changedFaces, numberOfWorkUnits);
  std::vector<std::uint8_t>   valid;
  UninitializedArray<FaceBox> faceBox;
  ProperFacesAndBoxes(mesh, starNode, valid, faceBox, numberOfWorkUnits);
  const std::size_t      numberOfCells = net.cells.size();
  std::vector<FacePairs> found((numberOfCells + CellBlockSize - 1) / CellBlockSize);
  ParallelForBlocks(
    numberOfCells,
    CellBlockSize,
    [&](std::size_t begin, std::size_t end, std::size_t block) {
      CellPairSearch search(net, mesh, incidence, changedFaces, starNode, valid, faceBox);
      for (std::size_t c = begin; c < end; ++c)
      {
        if (!changedFaces.SkipsCell(c))
        {
          search.SearchCell(c, found[block]);
        }
      }
    },
    numberOfWorkUnits);
  pairs = SortedPairs(found);
  return true;
}

std::size_t
RemoveSurfaceNetSelfIntersections(SurfaceNet &                                     net,
                                  const LargeBlockVector<Vec3> &                   initial,
                                  const Vec3 &                                     origin,
                                  const Matrix<double, 3, 3> &                     indexToPhysical,
                                  QuadSplit                                        split,
                                  bool                                             roundToFloat,
                                  LargeBlockVector<std::array<std::uint32_t, 4>> * faces,
                                  std::vector<Vec3> *                              facePoints)
{
  if (faces != nullptr)
  {
    faces->clear();
  }
  if (facePoints != nullptr)
  {
    facePoints->clear();
  }
  std::vector<bool>                              moved(net.positions.size(), false);
  std::vector<bool>                              movedLastRound(net.positions.size(), false);
  std::vector<unsigned int>                      pulls(net.positions.size(), 0);
  LargeBlockVector<std::array<std::uint32_t, 4>> polygons;
  IndexedTriangleMesh                            mesh;
  for (unsigned int round = 0;; ++round)
  {
    MakeFacesToCheck(net, origin, indexToPhysical, split, roundToFloat, polygons, mesh);
    // After the first round only faces at moved nodes can have changed.
    const std::vector<std::uint32_t> changed =
      round > 0 ? FacesAtNodes(mesh, movedLastRound) : std::vector<std::uint32_t>();
    FacePairs pairs;
    if (!FindSurfaceNetSelfIntersections(
          net, mesh, origin, indexToPhysical, roundToFloat, round > 0 ? &changed : nullptr, pairs))
    {
      pairs = FindSelfIntersections(mesh, round > 0 ? &changed : nullptr);
    }
    if (pairs.empty())
    {
      if (faces != nullptr && split != QuadSplit::KeepQuads)
      {
        *faces = std::move(polygons); // the faces of the final positions
        if (facePoints != nullptr)
        {
          *facePoints = std::move(mesh.points);
        }
      }
      break;
    }
    std::fill(movedLastRound.begin(), movedLastRound.end(), false);
    if (round == ValidityThresholds::MaximumRepairRounds)
    {
      // Not expected: fall back to the unrelaxed net, which is intersection-free.
      for (std::size_t i = 0; i < net.positions.size(); ++i)
      {
        moved[i] = moved[i] || net.positions[i] != initial[i];
      }
      net.positions = initial;
      break;
    }
    // Halve the relocation of each node of a crossing face, or reset it.
    for (std::uint32_t v : NodesOfPairs(mesh, pairs))
    {
      moved[v] = true;
      movedLastRound[v] = true;
      net.positions[v] = ++pulls[v] > ValidityThresholds::SurfaceNetsHalvingsBeforeReset
                           ? initial[v]
                           : initial[v] + (net.positions[v] - initial[v]) * 0.5;
    }
  }
  return static_cast<std::size_t>(std::count(moved.begin(), moved.end(), true));
}

} // namespace detail
} // namespace MeshExtraction
} // namespace itk
