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
#include "itkMeshExtractionSliverRemoval.h"

#include "itkMeshExtractionParallel.h"
#include "itkMeshExtractionSelfIntersections.h"
#include "itkMeshExtractionSurfaceNets.h"
#include "itkMeshExtractionTriangleGeometry.h"
#include "itkMeshExtractionValidityGuard.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <tuple>
#include <utility>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
namespace
{
/** A changed triangle may turn at most this far (cosine of the angle) from the one it
 * replaces: an operation reshapes the surface's triangles, it must not reshape the
 * surface. */
constexpr double ReplacementCosine = 0.2;
/** An operation is made only if it raises the smallest q_angle of the triangles it
 * changes by more than this. */
constexpr double MinimumGain = 1e-3;

/** One operation as it can be undone: the triangles, incidence lists and nodes it changed. */
struct Operation
{
  std::vector<std::pair<std::uint32_t, TriangleIndices>>            triangles; ///< slot, old value
  std::vector<std::pair<std::uint32_t, bool>>                       alive;     ///< slot, old flag
  std::vector<std::pair<std::uint32_t, std::vector<std::uint32_t>>> incident;  ///< node, old list
  std::vector<std::pair<std::uint32_t, std::pair<Vec3, Vec3>>>      nodes;     ///< node, old index / physical
  std::vector<std::uint32_t>                                        changed;   ///< alive slots it made
  std::vector<std::uint32_t>                                        dead;      ///< slots it removed
  std::uint32_t component{ std::numeric_limits<std::uint32_t>::max() };        ///< the component it changed
  double        sixVolumeChange{ 0.0 };                                        ///< of that component's 6 x volume
};

enum class Kind : std::uint8_t
{
  Collapse,
  Swap,
  Move,
  Split
};

/** The isotropic remeshing refuses a collapse or a swap that leaves a triangle with a
 * smaller q_angle than this, unless the triangles it replaces had one as small: the
 * remeshing evens out the edge lengths, and must not make the slivers it is there to
 * avoid. */
constexpr double RemeshingQAngleFloor = 0.3;

struct Candidate
{
  Kind          kind;
  std::uint32_t a;
  std::uint32_t b; ///< the other end of the edge (Collapse, Swap, Split)
  Vec3          index;
  double        score;
};

class SliverRemover
{
public:
  SliverRemover(LargeBlockVector<Vec3> &        positions,
                std::vector<TriangleIndices> &  triangles,
                const Vec3 &                    origin,
                const Matrix<double, 3, 3> &    indexToPhysical,
                const SurfaceProjection &       project,
                const SliverRemovalParameters & parameters)
      : m_Index(positions)
      , m_Output(triangles)
      , m_Physical(m_Check.points)
      , m_Triangles(m_Check.triangles)
      , m_Origin(origin)
      , m_M(indexToPhysical)
      , m_MInverse(indexToPhysical.GetInverse())
      , m_Project(project)
      , m_Parameters(parameters)
  {
    m_Check.triangles.swap(triangles);
    m_Physical.resize(m_Index.size());
    ToPhysical(m_Index.data(), m_Index.size(), m_Origin, m_M, m_Parameters.roundToFloat, m_Physical.data());
    m_Boxes.resize(m_Triangles.size());
    for (std::uint32_t f = 0; f < m_Triangles.size(); ++f)
    {
      m_Boxes[f] = TriangleBox(m_Check, f);
    }
    m_Tree.Build(m_Check, nullptr, &m_Boxes);
    m_Owner.assign(m_Triangles.size(), -1);
    m_Alive.assign(m_Triangles.size(), true);
    m_Incident.resize(m_Index.size());
    for (std::uint32_t f = 0; f < m_Triangles.size(); ++f)
    {
      for (std::uint32_t v : m_Triangles[f])
      {
        m_Incident[v].push_back(f);
      }
    }
    m_Volumes.Initialize(m_Triangles, m_Physical);
    m_SixVolume = m_Volumes.reference;
    m_IsStale.assign(m_Triangles.size(), false);
    m_Failed.assign(m_Triangles.size(), 0);
    m_Changed.assign(m_Index.size(), 0);
    m_Lock.assign(m_Index.size(), 0);
  }

  SliverRemovalResult
  Run()
  {
    if (m_Parameters.targetEdgeLength > 0.0 && m_Project)
    {
      this->Remesh(m_Parameters.targetEdgeLength);
    }
    m_FirstSliverPass = true;
    m_Worklist.clear();
    for (unsigned int pass = 0; pass < m_Parameters.maximumNumberOfPasses; ++pass)
    {
      ++m_Stamp;
      m_Operations.clear();
      this->OperateAroundSlivers(m_Parameters.sliverQAngle);
      ++m_Result.numberOfPasses;
      if (m_Operations.empty())
      {
        break;
      }
      this->UndoInvalidOperations();
    }
    this->Compact();
    return m_Result;
  }

private:
  // --- geometry ---
  Vec3
  ToPhysicalPoint(const Vec3 & index) const
  {
    Vec3 p;
    ToPhysical(&index, 1, m_Origin, m_M, m_Parameters.roundToFloat, &p);
    return p;
  }
  Vec3
  ToIndex(const Vec3 & physical) const
  {
    return m_MInverse * (physical - m_Origin);
  }
  double
  QAngle(std::uint32_t f) const
  {
    const auto & t = m_Triangles[f];
    return MeasureTriangle(m_Physical[t[0]], m_Physical[t[1]], m_Physical[t[2]]).qAngle;
  }
  Vec3
  Normal(std::uint32_t f) const
  {
    const auto & t = m_Triangles[f];
    return Cross(m_Physical[t[1]] - m_Physical[t[0]], m_Physical[t[2]] - m_Physical[t[0]]);
  }
  static Vec3
  Unit(const Vec3 & v)
  {
    const double n = Norm(v);
    return n > 0.0 ? v * (1.0 / n) : v;
  }

  // --- connectivity ---
  /** The alive triangles on the edge (a, b). */
  std::vector<std::uint32_t>
  EdgeTriangles(std::uint32_t a, std::uint32_t b) const
  {
    std::vector<std::uint32_t> on;
    for (std::uint32_t f : m_Incident[a])
    {
      const auto & t = m_Triangles[f];
      if (t[0] == b || t[1] == b || t[2] == b)
      {
        on.push_back(f);
      }
    }
    return on;
  }
  std::vector<std::uint32_t>
  Neighbours(std::uint32_t v) const
  {
    std::vector<std::uint32_t> n;
    for (std::uint32_t f : m_Incident[v])
    {
      for (std::uint32_t w : m_Triangles[f])
      {
        if (w != v)
        {
          n.push_back(w);
        }
      }
    }
    std::sort(n.begin(), n.end());
    n.erase(std::unique(n.begin(), n.end()), n.end());
    return n;
  }
  static std::uint32_t
  Third(const TriangleIndices & t, std::uint32_t a, std::uint32_t b)
  {
    for (std::uint32_t v : t)
    {
      if (v != a && v != b)
      {
        return v;
      }
    }
    return a;
  }
  /** Whether the triangle runs from a to b. */
  static bool
  RunsFrom(const TriangleIndices & t, std::uint32_t a, std::uint32_t b)
  {
    for (unsigned int k = 0; k < 3; ++k)
    {
      if (t[k] == a && t[(k + 1) % 3] == b)
      {
        return true;
      }
    }
    return false;
  }

  // --- operations, applied so that they can be undone ---
  void
  SaveIncident(Operation & op, std::uint32_t v) const
  {
    for (const auto & saved : op.incident)
    {
      if (saved.first == v)
      {
        return;
      }
    }
    op.incident.emplace_back(v, m_Incident[v]);
  }
  void
  SetNode(Operation & op, std::uint32_t v, const Vec3 & index)
  {
    op.nodes.emplace_back(v, std::make_pair(m_Index[v], m_Physical[v]));
    m_Index[v] = index;
    m_Physical[v] = this->ToPhysicalPoint(index);
  }
  static void
  Erase(std::vector<std::uint32_t> & list, std::uint32_t f)
  {
    list.erase(std::remove(list.begin(), list.end(), f), list.end());
  }

  /** Collapses the edge (a, b) onto a at `index`; false (nothing changed) where the mesh
   * would not stay 2-manifold. */
  bool
  ApplyCollapse(Operation & op, std::uint32_t a, std::uint32_t b, const Vec3 & index)
  {
    const auto on = this->EdgeTriangles(a, b);
    if (on.size() != 2)
    {
      return false;
    }
    const std::uint32_t        c = Third(m_Triangles[on[0]], a, b);
    const std::uint32_t        d = Third(m_Triangles[on[1]], a, b);
    const auto                 na = this->Neighbours(a);
    const auto                 nb = this->Neighbours(b);
    std::vector<std::uint32_t> common;
    std::set_intersection(na.begin(), na.end(), nb.begin(), nb.end(), std::back_inserter(common));
    // The link condition: a and b share exactly the two nodes across the edge, and
    // neither of those nor the merged node is left with fewer than three neighbours.
    if (c == d || common.size() != 2 || this->Neighbours(c).size() <= 3 || this->Neighbours(d).size() <= 3 ||
        na.size() + nb.size() < 3 + 4)
    {
      return false;
    }
    for (std::uint32_t v : { a, b, c, d })
    {
      this->SaveIncident(op, v);
    }
    for (std::uint32_t f : on)
    {
      op.alive.emplace_back(f, true);
      m_Alive[f] = false;
      for (std::uint32_t v : m_Triangles[f])
      {
        Erase(m_Incident[v], f);
      }
      op.triangles.emplace_back(f, m_Triangles[f]);
      m_Triangles[f] = { a, a, a }; // no area, no volume, not a proper face
      op.dead.push_back(f);
    }
    for (std::uint32_t f : m_Incident[b])
    {
      op.triangles.emplace_back(f, m_Triangles[f]);
      for (auto & v : m_Triangles[f])
      {
        v = v == b ? a : v;
      }
      m_Incident[a].push_back(f);
    }
    m_Incident[b].clear();
    this->SetNode(op, a, index);
    op.changed = m_Incident[a];
    return true;
  }

  /** Swaps the edge (a, b); false where the swapped edge exists or a node would be left
   * with fewer than three neighbours. */
  bool
  ApplySwap(Operation & op, std::uint32_t a, std::uint32_t b)
  {
    auto on = this->EdgeTriangles(a, b);
    if (on.size() != 2)
    {
      return false;
    }
    if (!RunsFrom(m_Triangles[on[0]], a, b))
    {
      std::swap(on[0], on[1]);
    }
    const std::uint32_t c = Third(m_Triangles[on[0]], a, b);
    const std::uint32_t d = Third(m_Triangles[on[1]], a, b);
    if (c == d || !this->EdgeTriangles(c, d).empty() || this->Neighbours(a).size() <= 3 ||
        this->Neighbours(b).size() <= 3)
    {
      return false;
    }
    for (std::uint32_t v : { a, b, c, d })
    {
      this->SaveIncident(op, v);
    }
    op.triangles.emplace_back(on[0], m_Triangles[on[0]]);
    op.triangles.emplace_back(on[1], m_Triangles[on[1]]);
    // (a, b, c) and (b, a, d) become (c, a, d) and (d, b, c): the same orientation.
    m_Triangles[on[0]] = { c, a, d };
    m_Triangles[on[1]] = { d, b, c };
    Erase(m_Incident[b], on[0]);
    Erase(m_Incident[a], on[1]);
    m_Incident[d].push_back(on[0]);
    m_Incident[c].push_back(on[1]);
    op.changed = { on[0], on[1] };
    return true;
  }

  /** A new node at `index`, in component `component`, in no triangle yet. */
  std::uint32_t
  NewNode(Operation & op, const Vec3 & index, std::uint32_t component)
  {
    const auto v = static_cast<std::uint32_t>(m_Index.size());
    m_Index.push_back(index);
    m_Physical.push_back(this->ToPhysicalPoint(index));
    m_Incident.emplace_back();
    m_Lock.push_back(0);
    m_Changed.push_back(0);
    m_Volumes.vertexComponent.push_back(component);
    op.incident.emplace_back(v, std::vector<std::uint32_t>()); // undone: in no triangle again
    return v;
  }
  /** A new triangle slot holding t (undone: dead). */
  std::uint32_t
  NewTriangle(Operation & op, const TriangleIndices & t)
  {
    const auto f = static_cast<std::uint32_t>(m_Triangles.size());
    m_Triangles.push_back(t);
    m_Alive.push_back(true);
    m_Boxes.push_back(TriangleBox(m_Check, f));
    m_Owner.push_back(-1);
    m_IsStale.push_back(false);
    m_Failed.push_back(0);
    op.triangles.emplace_back(f, TriangleIndices{ t[0], t[0], t[0] });
    op.alive.emplace_back(f, false);
    return f;
  }
  /** The sizes of the node and triangle arrays, to go back to after trying a split. */
  std::pair<std::size_t, std::size_t>
  Sizes() const
  {
    return { m_Index.size(), m_Triangles.size() };
  }
  void
  Truncate(const std::pair<std::size_t, std::size_t> & sizes)
  {
    const std::size_t nodes = sizes.first;
    const std::size_t slots = sizes.second;
    if (m_Index.size() > nodes)
    {
      m_Index.resize(nodes);
      m_Physical.resize(nodes);
      m_Incident.resize(nodes);
      m_Lock.resize(nodes);
      m_Changed.resize(nodes);
      m_Volumes.vertexComponent.resize(nodes);
    }
    if (m_Triangles.size() > slots)
    {
      m_Triangles.resize(slots);
      m_Alive.resize(slots);
      m_Boxes.resize(slots);
      m_Owner.resize(slots);
      m_IsStale.resize(slots);
      m_Failed.resize(slots);
    }
  }

  /** Splits the edge (a, b) at a new node at `index`: (a, b, c) and (b, a, d) become
   * (a, m, c), (m, b, c), (b, m, d) and (m, a, d), the same orientation. op.changed
   * lists the old slot running from a to b, its new neighbour, then the other old slot
   * and its new neighbour. */
  bool
  ApplySplit(Operation & op, std::uint32_t a, std::uint32_t b, const Vec3 & index)
  {
    auto on = this->EdgeTriangles(a, b);
    if (on.size() != 2)
    {
      return false;
    }
    if (!RunsFrom(m_Triangles[on[0]], a, b))
    {
      std::swap(on[0], on[1]);
    }
    if (!RunsFrom(m_Triangles[on[0]], a, b) || !RunsFrom(m_Triangles[on[1]], b, a))
    {
      return false;
    }
    const std::uint32_t c = Third(m_Triangles[on[0]], a, b);
    const std::uint32_t d = Third(m_Triangles[on[1]], a, b);
    if (c == d)
    {
      return false;
    }
    for (std::uint32_t v : { a, b, c, d })
    {
      this->SaveIncident(op, v);
    }
    const std::uint32_t m = this->NewNode(op, index, m_Volumes.vertexComponent[a]);
    op.nodes.emplace_back(m, std::make_pair(index, m_Physical[m]));
    op.triangles.emplace_back(on[0], m_Triangles[on[0]]);
    op.triangles.emplace_back(on[1], m_Triangles[on[1]]);
    m_Triangles[on[0]] = { a, m, c };
    m_Triangles[on[1]] = { b, m, d };
    const std::uint32_t s0 = this->NewTriangle(op, { m, b, c });
    const std::uint32_t s1 = this->NewTriangle(op, { m, a, d });
    Erase(m_Incident[a], on[1]);
    m_Incident[a].push_back(s1);
    Erase(m_Incident[b], on[0]);
    m_Incident[b].push_back(s0);
    m_Incident[c].push_back(s0);
    m_Incident[d].push_back(s1);
    m_Incident[m] = { on[0], s0, on[1], s1 };
    op.changed = { on[0], s0, on[1], s1 };
    return true;
  }

  void
  ApplyMove(Operation & op, std::uint32_t v, const Vec3 & index)
  {
    this->SetNode(op, v, index);
    op.changed = m_Incident[v];
  }

  void
  Undo(const Operation & op)
  {
    for (auto it = op.nodes.rbegin(); it != op.nodes.rend(); ++it)
    {
      m_Index[it->first] = it->second.first;
      m_Physical[it->first] = it->second.second;
    }
    for (auto it = op.triangles.rbegin(); it != op.triangles.rend(); ++it)
    {
      m_Triangles[it->first] = it->second;
    }
    for (const auto & [f, flag] : op.alive)
    {
      m_Alive[f] = flag;
    }
    for (const auto & [v, list] : op.incident)
    {
      m_Incident[v] = list;
    }
  }

  // --- evaluation ---
  /** The smallest q_angle of `slots` (alive ones). */
  double
  MinimumQAngle(const std::vector<std::uint32_t> & slots) const
  {
    double q = 1.0;
    for (std::uint32_t f : slots)
    {
      if (m_Alive[f])
      {
        q = std::min(q, this->QAngle(f));
      }
    }
    return q;
  }
  /** The alive triangles around the nodes of triangle f's neighbourhood that `kind`
   * changes: what the operation's score is measured against. */
  std::vector<std::uint32_t>
  Star(std::initializer_list<std::uint32_t> nodes) const
  {
    std::vector<std::uint32_t> star;
    for (std::uint32_t v : nodes)
    {
      star.insert(star.end(), m_Incident[v].begin(), m_Incident[v].end());
    }
    std::sort(star.begin(), star.end());
    star.erase(std::unique(star.begin(), star.end()), star.end());
    return star;
  }
  /** The smallest cosine between triangle f's normal and those of its neighbours across
   * its edges (2 where it has none). */
  double
  SharpestFold(std::uint32_t f) const
  {
    const auto & t = m_Triangles[f];
    const Vec3   n = Unit(this->Normal(f));
    double       sharpest = 2.0;
    for (unsigned int k = 0; k < 3; ++k)
    {
      for (std::uint32_t g : this->EdgeTriangles(t[k], t[(k + 1) % 3]))
      {
        if (g != f)
        {
          sharpest = std::min(sharpest, Dot(n, Unit(this->Normal(g))));
        }
      }
    }
    return sharpest;
  }
  /** The fold an operation on `star` may leave: none sharper than FoldCosine, or than
   * the sharpest there already. */
  double
  FoldLimit(const std::vector<std::uint32_t> & star) const
  {
    double sharpest = 2.0;
    for (std::uint32_t f : star)
    {
      sharpest = std::min(sharpest, this->SharpestFold(f));
    }
    return std::min(sharpest - 1e-9, ValidityThresholds::FoldCosine);
  }
  /** Whether the applied operation left no degenerate triangle, none turned over against
   * `reference` (the old normals by slot, or one normal for all) and none folded against a
   * neighbour beyond `foldLimit`. */
  bool
  PassesGuards(const Operation &                                   op,
               const std::vector<std::pair<std::uint32_t, Vec3>> & reference,
               const Vec3 &                                        common,
               double                                              foldLimit) const
  {
    for (std::uint32_t f : op.changed)
    {
      Vec3 before = common;
      for (const auto & [slot, normal] : reference)
      {
        if (slot == f)
        {
          before = normal;
        }
      }
      if (!this->IsAcceptable(f, before, foldLimit))
      {
        return false;
      }
    }
    return true;
  }
  /** The guard on one changed triangle: not degenerate, turned less than
   * ReplacementCosine allows from `before` (its unit normal before the change), and
   * folded against no neighbour beyond `foldLimit`. */
  bool
  IsAcceptable(std::uint32_t f, const Vec3 & before, double foldLimit) const
  {
    const auto & t = m_Triangles[f];
    return TriangleQArea(m_Physical[t[0]], m_Physical[t[1]], m_Physical[t[2]]) >
             m_Parameters.degenerateQAreaTolerance &&
           Dot(Unit(this->Normal(f)), before) > ReplacementCosine && this->SharpestFold(f) > foldLimit;
  }
  std::vector<std::pair<std::uint32_t, Vec3>>
  Normals(const std::vector<std::uint32_t> & slots) const
  {
    std::vector<std::pair<std::uint32_t, Vec3>> normals;
    for (std::uint32_t f : slots)
    {
      normals.emplace_back(f, Unit(this->Normal(f)));
    }
    return normals;
  }
  /** Applies the candidate; false if it could not be made. */
  bool
  Apply(Operation & op, const Candidate & c)
  {
    switch (c.kind)
    {
      case Kind::Collapse:
        return this->ApplyCollapse(op, c.a, c.b, c.index);
      case Kind::Swap:
        return this->ApplySwap(op, c.a, c.b);
      case Kind::Move:
        this->ApplyMove(op, c.a, c.index);
        return true;
      case Kind::Split:
        return this->ApplySplit(op, c.a, c.b, c.index);
    }
    return false;
  }
  /** Tries the candidate: its score (-1 if invalid or not above `toBeat`), the mesh
   * unchanged. */
  double
  Try(Candidate c, double toBeat)
  {
    if (c.kind == Kind::Split)
    {
      return this->TrySplit(c, toBeat);
    }
    double q = 0.0; // the smallest q_angle the operation leaves (the guards do not move nodes)
    {
      // First only the shapes: most candidates lose, and the guards' normals and folds
      // around the star cost more than the operation.
      Operation first;
      if (!this->Apply(first, c))
      {
        return -1.0;
      }
      q = this->MinimumQAngle(first.changed);
      this->Undo(first);
      if (!(q > toBeat))
      {
        return -1.0;
      }
    }
    std::vector<std::uint32_t> star;
    Vec3                       common = MakeVec3(0, 0, 0);
    if (c.kind == Kind::Swap)
    {
      star = this->EdgeTriangles(c.a, c.b);
      for (std::uint32_t f : star)
      {
        common += this->Normal(f); // area-weighted: a sliver's own normal counts little
      }
      common = Unit(common);
    }
    else
    {
      star = c.kind == Kind::Collapse ? this->Star({ c.a, c.b }) : this->Star({ c.a });
    }
    const auto   reference = c.kind == Kind::Swap ? std::vector<std::pair<std::uint32_t, Vec3>>() : this->Normals(star);
    const double foldLimit = this->FoldLimit(star);
    Operation    op;
    if (!this->Apply(op, c))
    {
      return -1.0;
    }
    const bool valid = this->PassesGuards(op, reference, common, foldLimit);
    this->Undo(op);
    return valid ? q : -1.0;
  }

  /** Try for a split: each new triangle is held to the normal of the one it halves. */
  double
  TrySplit(const Candidate & c, double toBeat)
  {
    const auto on = this->EdgeTriangles(c.a, c.b);
    if (on.size() != 2)
    {
      return -1.0;
    }
    const auto   normals = this->Normals(on);
    const double foldLimit = this->FoldLimit(on);
    const auto   sizes = this->Sizes();
    Operation    op;
    double       score = -1.0;
    if (this->Apply(op, c))
    {
      std::vector<std::pair<std::uint32_t, Vec3>> reference;
      for (unsigned int k = 0; k < 4; ++k)
      {
        const std::uint32_t halved = op.changed[k - k % 2];
        for (const auto & [slot, normal] : normals)
        {
          if (slot == halved)
          {
            reference.emplace_back(op.changed[k], normal);
          }
        }
      }
      const double q = this->MinimumQAngle(op.changed);
      if (q > toBeat && this->PassesGuards(op, reference, MakeVec3(0, 0, 0), foldLimit))
      {
        score = q;
      }
      this->Undo(op);
    }
    this->Truncate(sizes);
    return score;
  }

  /** 6 x the volume of every component as the mesh is now (dead slots add nothing). */
  std::vector<double>
  CurrentSixVolumes() const
  {
    return ComponentSixVolumes(m_Triangles, m_Physical, m_Volumes.origin, [&](std::size_t f) {
      const std::uint32_t c = m_Volumes.vertexComponent[m_Triangles[f][0]];
      return c < m_Volumes.origin.size() ? c : 0u;
    });
  }

  /** The share of `slots` in 6 x the volume of `component` (ComponentSixVolumes' terms). */
  double
  SixVolume(const std::vector<std::uint32_t> & slots, std::uint32_t component) const
  {
    if (component >= m_Volumes.origin.size())
    {
      return 0.0;
    }
    const Vec3 & o = m_Volumes.origin[component];
    double       volume = 0.0;
    for (std::uint32_t f : slots)
    {
      const auto & t = m_Triangles[f];
      volume += Dot(m_Physical[t[0]] - o, Cross(m_Physical[t[1]] - o, m_Physical[t[2]] - o));
    }
    return volume;
  }

  static std::tuple<Kind, std::uint32_t, std::uint32_t, double, double, double>
  Key(const Candidate & c)
  {
    return { c.kind, c.a, c.b, c.index[0], c.index[1], c.index[2] };
  }

  /** Whether a node of `slots`, or one of their neighbours, changed in a pass after `stamp`. */
  bool
  ChangedSince(const std::vector<std::uint32_t> & slots, std::uint32_t stamp) const
  {
    for (std::uint32_t f : slots)
    {
      for (std::uint32_t v : m_Triangles[f])
      {
        if (m_Changed[v] >= stamp)
        {
          return true;
        }
        for (std::uint32_t g : m_Incident[v])
        {
          for (std::uint32_t w : m_Triangles[g])
          {
            if (m_Changed[w] >= stamp)
            {
              return true;
            }
          }
        }
      }
    }
    return false;
  }

  bool
  Locked(const std::vector<std::uint32_t> & slots) const
  {
    for (std::uint32_t f : slots)
    {
      for (std::uint32_t v : m_Triangles[f])
      {
        if (m_Lock[v] == m_Stamp)
        {
          return true;
        }
      }
    }
    return false;
  }
  void
  Lock(const std::vector<std::uint32_t> & slots)
  {
    for (std::uint32_t f : slots)
    {
      for (std::uint32_t v : m_Triangles[f])
      {
        m_Lock[v] = m_Stamp;
      }
    }
  }

  /** The candidates around sliver f. */
  std::vector<Candidate>
  Candidates(std::uint32_t f) const
  {
    std::vector<Candidate> candidates;
    const TriangleIndices  t = m_Triangles[f];
    for (unsigned int k = 0; k < 3; ++k)
    {
      const std::uint32_t a = t[k];
      const std::uint32_t b = t[(k + 1) % 3];
      candidates.push_back({ Kind::Collapse, a, b, m_Index[a], 0.0 });
      candidates.push_back({ Kind::Collapse, a, b, m_Index[b], 0.0 });
      Vec3 middle = (m_Index[a] + m_Index[b]) * 0.5;
      if (m_Project && m_Project(middle))
      {
        candidates.push_back({ Kind::Collapse, a, b, middle, 0.0 });
      }
      candidates.push_back({ Kind::Swap, a, b, m_Index[a], 0.0 });
      if (m_Project)
      {
        // Onto the centroid of both ends' neighbours: the merged node where smoothing
        // would put it.
        const auto na = this->Neighbours(a);
        const auto nb = this->Neighbours(b);
        Vec3       centroid = MakeVec3(0, 0, 0);
        double     count = 0.0;
        for (const auto * list : { &na, &nb })
        {
          for (std::uint32_t w : *list)
          {
            if (w != a && w != b)
            {
              centroid += m_Index[w];
              count += 1.0;
            }
          }
        }
        if (count > 0.0)
        {
          centroid *= 1.0 / count;
          if (m_Project(centroid))
          {
            candidates.push_back({ Kind::Collapse, a, b, centroid, 0.0 });
          }
        }
      }
      if (m_Project)
      {
        const auto neighbours = this->Neighbours(a);
        Vec3       centroid = MakeVec3(0, 0, 0);
        for (std::uint32_t w : neighbours)
        {
          centroid += m_Index[w];
        }
        centroid *= 1.0 / static_cast<double>(neighbours.size());
        Vec3 half = (centroid + m_Index[a]) * 0.5;
        if (m_Project(centroid))
        {
          candidates.push_back({ Kind::Move, a, a, centroid, 0.0 });
        }
        if (m_Project(half))
        {
          candidates.push_back({ Kind::Move, a, a, half, 0.0 });
        }
        // Toward the apex of the equilateral triangle on the opposite edge, in the
        // sliver's plane: the position that mends the sliver itself.
        const std::uint32_t b2 = t[(k + 1) % 3];
        const std::uint32_t c2 = t[(k + 2) % 3];
        const Vec3          pb = m_Physical[b2];
        const Vec3          pc = m_Physical[c2];
        const Vec3          n = Unit(Cross(pb - m_Physical[a], pc - m_Physical[a]));
        const Vec3          edge = pc - pb;
        const Vec3          up = Unit(Cross(n, edge)); // in the plane, toward a for a counter-clockwise (a, b, c)
        const Vec3          apex = (pb + pc) * 0.5 + up * (0.8660254037844386 * Norm(edge));
        for (double w : { 1.0, 0.5 })
        {
          const Vec3 target = m_Physical[a] * (1.0 - w) + apex * w;
          Vec3       index = this->ToIndex(target);
          if (m_Project(index))
          {
            candidates.push_back({ Kind::Move, a, a, index, 0.0 });
          }
        }
      }
    }
    return candidates;
  }

  void
  OperateAroundSlivers(double threshold)
  {
    std::vector<std::pair<double, std::uint32_t>> slivers;
    auto                                          consider = [&](std::uint32_t f) {
      if (m_Alive[f])
      {
        const double q = this->QAngle(f);
        if (q < threshold)
        {
          slivers.emplace_back(q, f);
        }
      }
    };
    if (m_FirstSliverPass)
    {
      m_FirstSliverPass = false;
      for (std::uint32_t f = 0; f < m_Triangles.size(); ++f)
      {
        consider(f);
      }
    }
    else
    {
      // Only the slivers left by the last pass and the triangles it changed.
      std::sort(m_Worklist.begin(), m_Worklist.end());
      m_Worklist.erase(std::unique(m_Worklist.begin(), m_Worklist.end()), m_Worklist.end());
      for (std::uint32_t f : m_Worklist)
      {
        consider(f);
      }
    }
    std::sort(slivers.begin(), slivers.end());
    m_Worklist.clear();
    for (const auto & sliver : slivers)
    {
      m_Worklist.push_back(sliver.second);
    }
    for (const auto & [q0, f] : slivers)
    {
      if (!m_Alive[f] || this->QAngle(f) >= threshold)
      {
        continue; // gone, or mended by an earlier operation
      }
      const TriangleIndices t = m_Triangles[f];
      const auto            around = this->Star({ t[0], t[1], t[2] });
      if (this->Locked(around))
      {
        continue;
      }
      if (m_Failed[f] > 0 && !this->ChangedSince(around, m_Failed[f]))
      {
        continue; // nothing helped before, and nothing around it changed since
      }
      Candidate best{ Kind::Move, 0, 0, MakeVec3(0, 0, 0), -1.0 };
      for (Candidate c : this->Candidates(f))
      {
        if (!m_Refused.empty() && m_Refused.count(Key(c)) > 0)
        {
          continue;
        }
        const std::vector<std::uint32_t> star =
          c.kind == Kind::Swap ? this->EdgeTriangles(c.a, c.b)
                               : (c.kind == Kind::Collapse ? this->Star({ c.a, c.b }) : this->Star({ c.a }));
        const double before = this->MinimumQAngle(star);
        c.score = this->Try(c, std::max(before + MinimumGain, best.score));
        if (c.score > before + MinimumGain && c.score > best.score)
        {
          best = c;
        }
      }
      if (best.score < 0.0)
      {
        m_Failed[f] = m_Stamp;
        continue;
      }
      this->Make(best);
    }
  }

  /** The triangles a candidate changes (or removes). */
  std::vector<std::uint32_t>
  Affected(const Candidate & c) const
  {
    switch (c.kind)
    {
      case Kind::Swap:
      case Kind::Split:
        return this->EdgeTriangles(c.a, c.b);
      case Kind::Collapse:
        return this->Star({ c.a, c.b });
      case Kind::Move:
        break;
    }
    return this->Star({ c.a });
  }

  /** Makes a candidate that Try found valid, as an operation of this pass: its
   * component's volume kept up to date, its neighbourhood locked for the rest of the
   * pass. */
  void
  Make(const Candidate & c)
  {
    const std::vector<std::uint32_t> affected = this->Affected(c);
    const std::size_t                slots = m_Triangles.size();
    Operation                        op;
    op.component = m_Volumes.vertexComponent[c.a];
    const double before = this->SixVolume(affected, op.component);
    this->Apply(op, c);
    std::vector<std::uint32_t> after = affected;
    for (std::uint32_t f : op.changed)
    {
      if (f >= slots)
      {
        after.push_back(f); // a split's new triangles
      }
    }
    op.sixVolumeChange = this->SixVolume(after, op.component) - before;
    if (op.component < m_SixVolume.size())
    {
      m_SixVolume[op.component] += op.sixVolumeChange;
    }
    this->Lock(op.changed);
    for (const auto & saved : op.incident)
    {
      m_Lock[saved.first] = m_Stamp;
    }
    m_Made.push_back(c);
    m_Operations.push_back(std::move(op));
  }

  // --- isotropic remeshing ---
  /** Calls visit(a, b, length) for every edge once (a < b; every edge of a closed
   * mesh is in two triangles, once each way). */
  template <typename TVisit>
  void
  ForEachEdge(TVisit && visit) const
  {
    for (std::uint32_t f = 0; f < m_Triangles.size(); ++f)
    {
      if (!m_Alive[f])
      {
        continue;
      }
      const auto & t = m_Triangles[f];
      for (unsigned int k = 0; k < 3; ++k)
      {
        const std::uint32_t a = t[k];
        const std::uint32_t b = t[(k + 1) % 3];
        if (a < b)
        {
          visit(a, b, Norm(m_Physical[a] - m_Physical[b]));
        }
      }
    }
  }

  /** Calls visit(a, b, c, d, on) for every edge (a, b) once (a < b) with its two
   * triangles `on` and their third nodes c and d. */
  template <typename TVisit>
  void
  ForEachEdgeWithItsTriangles(TVisit && visit) const
  {
    this->ForEachEdge([&](std::uint32_t a, std::uint32_t b, double) {
      const auto on = this->EdgeTriangles(a, b);
      if (on.size() == 2)
      {
        visit(a, b, Third(m_Triangles[on[0]], a, b), Third(m_Triangles[on[1]], a, b), on);
      }
    });
  }

  /** One pass of remeshing candidates, in order, each with the smallest q_angle its
   * triangles must keep in `score`: those Try finds valid are made where nothing of
   * this pass locked their neighbourhood, then the crossing check undoes what it must.
   * `accept` may refuse a candidate at the moment it comes up. Returns the operations
   * kept. */
  template <typename TAccept>
  std::size_t
  RemeshingPass(const std::vector<Candidate> & candidates, TAccept && accept)
  {
    ++m_Stamp;
    m_Operations.clear();
    m_Made.clear();
    for (Candidate c : candidates)
    {
      const auto affected = this->Affected(c);
      if (affected.empty() || this->Locked(affected) || !accept(c) ||
          (!m_Refused.empty() && m_Refused.count(Key(c)) > 0))
      {
        continue;
      }
      if (this->Try(c, c.score) >= 0.0)
      {
        this->Make(c);
      }
    }
    if (m_Operations.empty())
    {
      return 0;
    }
    const std::size_t undone = m_Result.numberOfUndone;
    const std::size_t made = m_Operations.size();
    this->UndoInvalidOperations();
    return made - (m_Result.numberOfUndone - undone);
  }

  /** The smallest q_angle a collapse or swap must leave: that of the triangles it
   * replaces if below RemeshingQAngleFloor, else the floor. */
  double
  Floor(const std::vector<std::uint32_t> & affected) const
  {
    return std::min(this->MinimumQAngle(affected), RemeshingQAngleFloor) - 1e-12;
  }

  std::size_t
  SplitLongEdges(double longest)
  {
    std::vector<std::pair<double, std::pair<std::uint32_t, std::uint32_t>>> edges;
    this->ForEachEdge([&](std::uint32_t a, std::uint32_t b, double length) {
      if (length > longest)
      {
        edges.push_back({ -length, { a, b } });
      }
    });
    std::sort(edges.begin(), edges.end());
    std::vector<Candidate> candidates;
    for (const auto & e : edges)
    {
      const std::uint32_t a = e.second.first;
      const std::uint32_t b = e.second.second;
      candidates.push_back({ Kind::Split, a, b, (m_Index[a] + m_Index[b]) * 0.5, 0.0 });
    }
    return this->RemeshingPass(candidates, [this](Candidate & c) {
      // Projected only now: most candidates of a pass are locked by then.
      Vec3 middle = c.index;
      if (m_Project(middle))
      {
        c.index = middle; // else on the edge, where the relaxation projects it later
      }
      return true;
    });
  }

  std::size_t
  CollapseShortEdges(double shortest, double longest)
  {
    std::vector<std::pair<double, std::pair<std::uint32_t, std::uint32_t>>> edges;
    this->ForEachEdge([&](std::uint32_t a, std::uint32_t b, double length) {
      if (length < shortest)
      {
        edges.push_back({ length, { a, b } });
      }
    });
    std::sort(edges.begin(), edges.end());
    std::vector<Candidate> candidates;
    for (const auto & e : edges)
    {
      const std::uint32_t a = e.second.first;
      const std::uint32_t b = e.second.second;
      candidates.push_back({ Kind::Collapse, a, b, (m_Index[a] + m_Index[b]) * 0.5, 0.0 });
    }
    return this->RemeshingPass(candidates, [&](Candidate & c) {
      if (!m_Project(c.index))
      {
        return false;
      }
      // No edge of the merged node may be long enough to be split again.
      const Vec3 p = this->ToPhysicalPoint(c.index);
      for (std::uint32_t v : { c.a, c.b })
      {
        for (std::uint32_t w : this->Neighbours(v))
        {
          if (w != c.a && w != c.b && Norm(m_Physical[w] - p) >= longest)
          {
            return false;
          }
        }
      }
      c.score = this->Floor(this->Affected(c));
      return true;
    });
  }

  /** Swaps that bring the valences of the four nodes nearer 6. */
  std::size_t
  SwapTowardValenceSix()
  {
    std::vector<Candidate> candidates;
    auto                   deviation = [](std::size_t valence) { return std::abs(static_cast<double>(valence) - 6.0); };
    this->ForEachEdgeWithItsTriangles(
      [&](std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d, const auto &) {
        const std::size_t va = m_Incident[a].size();
        const std::size_t vb = m_Incident[b].size();
        const std::size_t vc = m_Incident[c].size();
        const std::size_t vd = m_Incident[d].size();
        const double      before = deviation(va) + deviation(vb) + deviation(vc) + deviation(vd);
        const double      after = deviation(va - 1) + deviation(vb - 1) + deviation(vc + 1) + deviation(vd + 1);
        if (after < before)
        {
          candidates.push_back({ Kind::Swap, a, b, m_Index[a], 0.0 });
        }
      });
    return this->RemeshingPass(candidates, [&](Candidate & c) {
      c.score = this->Floor(this->Affected(c));
      return true;
    });
  }

  /** Boxes of every triangle anew, and the tree refitted (or built anew, `rebuild`). */
  void
  RefitAll(bool rebuild)
  {
    ParallelForBlocks(m_Triangles.size(), 16384, [&](std::size_t begin, std::size_t end, std::size_t) {
      for (std::size_t f = begin; f < end; ++f)
      {
        m_Boxes[f] = TriangleBox(m_Check, static_cast<std::uint32_t>(f));
      }
    });
    for (std::uint32_t f : m_Stale)
    {
      m_IsStale[f] = false;
    }
    m_Stale.clear();
    if (rebuild)
    {
      m_Tree.Build(m_Check, nullptr, &m_Boxes);
    }
    else
    {
      m_Tree.Refit(m_Check, m_Boxes);
    }
  }

  /** One step of tangential relaxation: every node to the centroid of its neighbours,
   * within its tangent plane, then projected onto the surface; all at once, then the moves that leave a triangle
   * degenerate, turned, folded or crossing another, or a component collapsed, are taken back until none is left. */
  void
  Relax(double settledMove)
  {
    const double            settled = settledMove * settledMove;
    const std::size_t       n = m_Index.size();
    const std::vector<Vec3> oldIndex(m_Index.begin(), m_Index.end());
    const std::vector<Vec3> oldPhysical = m_Physical;
    std::vector<Vec3>       target(n);
    std::vector<char>       moves(n, 0);
    ParallelForBlocks(n, 4096, [&](std::size_t begin, std::size_t end, std::size_t) {
      for (std::size_t v = begin; v < end; ++v)
      {
        if (m_Incident[v].empty())
        {
          continue;
        }
        // The mean of the neighbours (each twice around a closed fan), within the
        // tangent plane of the area-weighted normal.
        Vec3   centroid = MakeVec3(0, 0, 0);
        Vec3   normal = MakeVec3(0, 0, 0);
        double count = 0.0;
        for (std::uint32_t f : m_Incident[v])
        {
          for (std::uint32_t w : m_Triangles[f])
          {
            if (w != v)
            {
              centroid += m_Physical[w];
              count += 1.0;
            }
          }
          normal += this->Normal(f);
        }
        if (!(count > 0.0))
        {
          continue;
        }
        centroid *= 1.0 / count;
        const Vec3 unit = Unit(normal);
        const Vec3 p = m_Physical[v];
        const Vec3 tangential = centroid - unit * Dot(centroid - p, unit);
        if (SquaredNorm(tangential - p) < settled)
        {
          continue; // settled: its triangles stay as they are, and need no check
        }
        Vec3 index = this->ToIndex(tangential);
        if (m_Project(index) && SquaredNorm(index - m_Index[v]) > 1e-12)
        {
          target[v] = index;
          moves[v] = 1;
        }
      }
    });
    std::vector<std::uint32_t> moved;
    for (std::uint32_t v = 0; v < n; ++v)
    {
      if (moves[v])
      {
        moved.push_back(v);
        m_Index[v] = target[v];
        m_Physical[v] = this->ToPhysicalPoint(target[v]);
      }
    }
    std::vector<char> isMoved = moves;
    std::size_t       reverted = 0;
    auto              revert = [&](std::uint32_t v, std::vector<std::uint32_t> & touched) {
      if (isMoved[v])
      {
        isMoved[v] = 0;
        m_Index[v] = oldIndex[v];
        m_Physical[v] = oldPhysical[v];
        touched.insert(touched.end(), m_Incident[v].begin(), m_Incident[v].end());
        ++reverted;
      }
    };
    auto oldNormal = [&](std::uint32_t f) {
      const auto & t = m_Triangles[f];
      return Unit(Cross(oldPhysical[t[1]] - oldPhysical[t[0]], oldPhysical[t[2]] - oldPhysical[t[0]]));
    };
    auto anyMoved = [&](std::uint32_t f) {
      const auto & t = m_Triangles[f];
      return isMoved[t[0]] || isMoved[t[1]] || isMoved[t[2]];
    };
    auto incidentOf = [&](const std::vector<std::uint32_t> & nodes) {
      std::vector<std::uint32_t> slots;
      for (std::uint32_t v : nodes)
      {
        slots.insert(slots.end(), m_Incident[v].begin(), m_Incident[v].end());
      }
      std::sort(slots.begin(), slots.end());
      slots.erase(std::unique(slots.begin(), slots.end()), slots.end());
      return slots;
    };
    // The guards on single triangles, until no moved node is left in a failing one.
    auto guard = [&](std::vector<std::uint32_t> check) {
      while (!check.empty())
      {
        std::sort(check.begin(), check.end());
        check.erase(std::unique(check.begin(), check.end()), check.end());
        std::vector<std::uint32_t> touched;
        for (std::uint32_t f : check)
        {
          if (!m_Alive[f] || !anyMoved(f))
          {
            continue;
          }
          if (!this->IsAcceptable(f, oldNormal(f), ValidityThresholds::FoldCosine))
          {
            for (std::uint32_t v : m_Triangles[f])
            {
              revert(v, touched);
            }
          }
        }
        // A fold is between two triangles: the neighbours of reverted nodes' triangles
        // are checked again too (their fold with a reverted triangle changed).
        check.clear();
        for (std::uint32_t f : touched)
        {
          check.push_back(f);
          const auto & t = m_Triangles[f];
          for (unsigned int k = 0; k < 3; ++k)
          {
            for (std::uint32_t g : this->EdgeTriangles(t[k], t[(k + 1) % 3]))
            {
              check.push_back(g);
            }
          }
        }
      }
    };
    std::vector<std::uint32_t> initialCheck = incidentOf(moved);
    guard(initialCheck);
    std::vector<std::uint32_t> queries;
    for (std::uint32_t f : initialCheck)
    {
      if (anyMoved(f))
      {
        queries.push_back(f);
      }
    }
    bool                clean = false;
    std::vector<double> volumes;
    for (unsigned int round = 0; round < ValidityThresholds::MaximumRepairRounds && !clean; ++round)
    {
      clean = true;
      // Components pressed flat or turned inside out: all their moves back.
      volumes = this->CurrentSixVolumes();
      std::vector<std::uint32_t> touched;
      for (std::uint32_t v : moved)
      {
        const std::uint32_t c = m_Volumes.vertexComponent[v];
        if (isMoved[v] && c < volumes.size() &&
            IsCollapsedComponent(m_Volumes.reference[c],
                                 volumes[c],
                                 m_Volumes.reference[c],
                                 ValidityThresholds::HighQualityCollapseFraction))
        {
          revert(v, touched);
        }
      }
      this->RefitAll(false);
      std::vector<std::uint32_t> asked;
      for (std::uint32_t f : queries)
      {
        if (m_Alive[f])
        {
          asked.push_back(f);
        }
      }
      for (const auto & [f, g] : FindSelfIntersections(m_Check, asked, m_Tree))
      {
        for (std::uint32_t h : { f, g })
        {
          for (std::uint32_t v : m_Triangles[h])
          {
            revert(v, touched);
          }
        }
      }
      if (!touched.empty())
      {
        clean = false;
        guard(touched);
        // The reverted nodes' triangles are new to the surface: they are asked next.
        queries = incidentOf([&] {
          std::vector<std::uint32_t> nodes;
          for (std::uint32_t f : touched)
          {
            nodes.insert(nodes.end(), m_Triangles[f].begin(), m_Triangles[f].end());
          }
          return nodes;
        }());
      }
    }
    if (!clean)
    {
      std::vector<std::uint32_t> touched;
      for (std::uint32_t v : moved)
      {
        revert(v, touched);
      }
      this->RefitAll(false);
    }
    for (std::uint32_t v : moved)
    {
      if (isMoved[v])
      {
        ++m_Result.numberOfRelaxedNodes;
        m_Changed[v] = m_Stamp;
      }
    }
    m_Result.numberOfRelaxationUndone += reverted;
    // The components' volumes as they are now, for the operations after: those of the
    // clean round, which moved nothing back.
    m_SixVolume = clean ? std::move(volumes) : this->CurrentSixVolumes();
  }

  void
  Remesh(double targetEdgeLength)
  {
    m_Remeshing = true;
    const double longest = targetEdgeLength * 4.0 / 3.0;
    const double shortest = targetEdgeLength * 4.0 / 5.0;
    // A node whose relaxation would move it less than this stays: such moves no longer
    // change the triangles' shapes, and each moved node's triangles must be checked.
    const double settledMove = 0.01 * targetEdgeLength;
    // One pass of each kind per round: what the locks of a pass left is made in the
    // next round, after the relaxation, where the edges' lengths have changed anyway.
    // A round that changes nothing leaves the mesh where the next one starts, so the
    // rounds stop there (a fixed point: the result is the same as with all of them).
    for (unsigned int iteration = 0; iteration < m_Parameters.remeshingIterations; ++iteration)
    {
      std::size_t changes = this->SplitLongEdges(longest);
      changes += this->CollapseShortEdges(shortest, longest);
      changes += this->SwapTowardValenceSix();
      ++m_Stamp;
      changes += this->RelaxAndCount(settledMove);
      ++m_Result.numberOfRemeshingRounds;
      if (changes == 0)
      {
        break;
      }
    }
    // Then the shapes alone: swaps that raise the smaller q_angle of an edge's two
    // triangles, and relaxation, in turn.
    for (unsigned int step = 0; step < m_Parameters.remeshingIterations; ++step)
    {
      std::size_t changes = this->SwapTowardQuality();
      ++m_Stamp;
      changes += this->RelaxAndCount(settledMove);
      ++m_Result.numberOfRemeshingRounds;
      if (changes == 0)
      {
        break;
      }
    }
    m_Remeshing = false;
  }

  /** Relax, returning the nodes it moved (and kept). */
  std::size_t
  RelaxAndCount(double settledMove)
  {
    const std::size_t before = m_Result.numberOfRelaxedNodes;
    this->Relax(settledMove);
    return m_Result.numberOfRelaxedNodes - before;
  }

  /** Swaps that raise the smaller q_angle of the edge's two triangles. */
  std::size_t
  SwapTowardQuality()
  {
    std::vector<Candidate> candidates;
    std::vector<double>    qAngle(m_Triangles.size(), 1.0); // each triangle's, once, not once per edge
    ParallelForBlocks(qAngle.size(), 16384, [&](std::size_t begin, std::size_t end, std::size_t) {
      for (std::size_t f = begin; f < end; ++f)
      {
        if (m_Alive[f])
        {
          qAngle[f] = this->QAngle(static_cast<std::uint32_t>(f));
        }
      }
    });
    this->ForEachEdgeWithItsTriangles(
      [&](std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d, const auto & on) {
        const double before = std::min(qAngle[on[0]], qAngle[on[1]]);
        const double after = std::min(MeasureTriangle(m_Physical[c], m_Physical[a], m_Physical[d]).qAngle,
                                      MeasureTriangle(m_Physical[d], m_Physical[b], m_Physical[c]).qAngle);
        if (after > before + MinimumGain)
        {
          candidates.push_back({ Kind::Swap, a, b, m_Index[a], before + MinimumGain });
        }
      });
    return this->RemeshingPass(candidates, [&](Candidate &) { return true; });
  }

  /** Undoes the operations whose triangles cross others or whose component collapsed,
   * until none is left. */
  void
  UndoInvalidOperations()
  {
    std::vector<bool> undone(m_Operations.size(), false);
    auto              undo = [&](std::size_t i) {
      this->Undo(m_Operations[i]);
      m_SixVolume[m_Operations[i].component] -= m_Operations[i].sixVolumeChange;
      undone[i] = true;
    };
    // Components pressed flat or turned inside out (their volumes kept up to date by
    // each operation's change).
    for (std::size_t i = 0; i < m_Operations.size(); ++i)
    {
      const std::uint32_t c = m_Operations[i].component;
      if (c < m_SixVolume.size() && IsCollapsedComponent(m_Volumes.reference[c],
                                                         m_SixVolume[c],
                                                         m_Volumes.reference[c],
                                                         ValidityThresholds::HighQualityCollapseFraction))
      {
        undo(i);
      }
    }
    std::size_t numberOfQueries = 0;
    for (const Operation & op : m_Operations)
    {
      this->MarkStale(op);
      numberOfQueries += op.changed.size();
    }
    this->RefitIfManyStale(numberOfQueries);
    // Crossing faces, again after each undo (an undone operation's old faces are checked
    // against the operations kept).
    bool any = true;
    for (unsigned int round = 0; round < ValidityThresholds::MaximumRepairRounds && any; ++round)
    {
      std::vector<std::uint32_t> queries;
      for (std::size_t i = 0; i < m_Operations.size(); ++i)
      {
        if (!undone[i])
        {
          for (std::uint32_t f : m_Operations[i].changed)
          {
            m_Owner[f] = static_cast<std::int64_t>(i);
            queries.push_back(f);
          }
        }
      }
      any = false;
      for (const auto & [f, g] : this->Crossings(queries))
      {
        for (std::uint32_t h : { f, g })
        {
          if (m_Owner[h] >= 0 && !undone[m_Owner[h]])
          {
            undo(static_cast<std::size_t>(m_Owner[h]));
            any = true;
          }
        }
      }
      for (std::uint32_t f : queries)
      {
        m_Owner[f] = -1;
      }
    }
    if (any)
    {
      // The rounds ran out before the last undo was checked: back to the pass's start,
      // which was valid.
      for (std::size_t i = m_Operations.size(); i-- > 0;)
      {
        if (!undone[i])
        {
          undo(i);
        }
      }
    }
    for (std::size_t i = 0; i < m_Operations.size(); ++i)
    {
      if (undone[i])
      {
        ++m_Result.numberOfUndone;
        m_Refused.insert(Key(m_Made[i]));
        continue;
      }
      m_Worklist.insert(m_Worklist.end(), m_Operations[i].changed.begin(), m_Operations[i].changed.end());
      for (const auto & saved : m_Operations[i].incident)
      {
        m_Changed[saved.first] = m_Stamp;
      }
      for (std::uint32_t f : m_Operations[i].changed)
      {
        for (std::uint32_t v : m_Triangles[f])
        {
          m_Changed[v] = m_Stamp;
        }
      }
      for (const auto & saved : m_Operations[i].nodes)
      {
        m_Changed[saved.first] = m_Stamp;
      }
      switch (m_Made[i].kind)
      {
        case Kind::Collapse:
          ++m_Result.numberOfCollapses;
          m_Result.numberOfRemeshingCollapses += m_Remeshing ? 1 : 0;
          break;
        case Kind::Swap:
          ++m_Result.numberOfSwaps;
          m_Result.numberOfRemeshingSwaps += m_Remeshing ? 1 : 0;
          break;
        case Kind::Move:
          ++m_Result.numberOfMoves;
          break;
        case Kind::Split:
          ++m_Result.numberOfSplits;
          break;
      }
    }
    m_Made.clear();
  }

  /** The triangles whose boxes in the tree are out of date: changed since the last refit. */
  void
  MarkStale(std::uint32_t f)
  {
    if (!m_IsStale[f])
    {
      m_IsStale[f] = true;
      m_Stale.push_back(f);
    }
  }
  void
  MarkStale(const Operation & op)
  {
    for (const auto & saved : op.triangles)
    {
      this->MarkStale(saved.first);
    }
    for (std::uint32_t f : op.changed)
    {
      this->MarkStale(f);
    }
  }
  /** Refits the tree (a pass over all triangles) where testing the out-of-date
   * triangles one by one against `numberOfQueries` faces would cost more. */
  void
  RefitIfManyStale(std::size_t numberOfQueries)
  {
    if (m_Tree.GetNumberOfTriangles() != m_Triangles.size())
    {
      // Splits added triangles the tree does not hold: built anew over all of them.
      this->RefitAll(true);
      return;
    }
    if (m_Stale.size() * numberOfQueries < 4 * m_Triangles.size())
    {
      return;
    }
    for (std::uint32_t f : m_Stale)
    {
      m_Boxes[f] = TriangleBox(m_Check, f);
      m_IsStale[f] = false;
    }
    m_Stale.clear();
    m_Tree.Refit(m_Check, m_Boxes);
  }
  /** The pairs of crossing faces that include one of `queries`: through the tree, and
   * against the triangles whose boxes in it are out of date one by one. */
  std::vector<std::pair<std::uint32_t, std::uint32_t>>
  Crossings(const std::vector<std::uint32_t> & queries) const
  {
    auto pairs = FindSelfIntersections(m_Check, queries, m_Tree);
    if (m_Stale.empty())
    {
      return pairs;
    }
    std::vector<AxisAlignedBox> staleBoxes(m_Stale.size());
    for (std::size_t k = 0; k < m_Stale.size(); ++k)
    {
      staleBoxes[k] = TriangleBox(m_Check, m_Stale[k]);
    }
    for (std::uint32_t q : queries)
    {
      if (!MeshFaceIsProper(m_Check, q))
      {
        continue;
      }
      const AxisAlignedBox box = TriangleBox(m_Check, q);
      for (std::size_t k = 0; k < m_Stale.size(); ++k)
      {
        const std::uint32_t g = m_Stale[k];
        if (g != q && box.Overlaps(staleBoxes[k]) && MeshFaceIsProper(m_Check, g) && MeshFacesIntersect(m_Check, q, g))
        {
          pairs.emplace_back(std::min(q, g), std::max(q, g));
        }
      }
    }
    return pairs;
  }

  void
  Compact()
  {
    std::size_t kept = 0;
    for (std::size_t f = 0; f < m_Triangles.size(); ++f)
    {
      if (m_Alive[f])
      {
        m_Triangles[kept++] = m_Triangles[f];
      }
    }
    m_Triangles.resize(kept);
    m_Output.swap(m_Triangles);
  }

  LargeBlockVector<Vec3> &                m_Index;
  bool                                    m_FirstSliverPass{ true };
  bool                                    m_Remeshing{ false }; ///< the isotropic remeshing is running
  std::vector<TriangleIndices> &          m_Output;
  IndexedTriangleMesh                     m_Check; ///< the physical points and the triangles (dead: one node thrice)
  std::vector<Vec3> &                     m_Physical;
  std::vector<TriangleIndices> &          m_Triangles;
  AxisAlignedBoxArray                     m_Boxes;
  TriangleAABBTree                        m_Tree;
  std::vector<std::int64_t>               m_Owner; ///< per triangle: the operation of this pass that changed it, or -1
  const Vec3                              m_Origin;
  const Matrix<double, 3, 3>              m_M;
  const Matrix<double, 3, 3>              m_MInverse;
  const SurfaceProjection &               m_Project;
  const SliverRemovalParameters           m_Parameters;
  std::vector<bool>                       m_Alive;
  std::vector<std::vector<std::uint32_t>> m_Incident;
  ComponentVolumes                        m_Volumes;
  std::vector<std::uint32_t>              m_Lock;
  std::uint32_t                           m_Stamp{ 0 };
  std::vector<Operation>                  m_Operations;
  std::vector<std::uint32_t>              m_Stale;
  std::vector<std::uint32_t> m_Failed;  ///< per triangle: the pass in which no candidate helped it (0: none)
  std::vector<std::uint32_t> m_Changed; ///< per node: the last pass whose kept operations changed its faces
  std::vector<bool>          m_IsStale;
  std::vector<double>        m_SixVolume; ///< per component: 6 x its signed volume now
  std::vector<Candidate>     m_Made;      ///< per operation of this pass: what it was
  /** Operations undone by a check, never tried again (a pass would make them again). */
  std::set<std::tuple<Kind, std::uint32_t, std::uint32_t, double, double, double>> m_Refused;
  std::vector<std::uint32_t> m_Worklist; ///< the triangles the next pass looks at
  SliverRemovalResult        m_Result;
};
} // namespace

SliverRemovalResult
RemoveSlivers(LargeBlockVector<Vec3> &        positions,
              std::vector<TriangleIndices> &  triangles,
              const Vec3 &                    origin,
              const Matrix<double, 3, 3> &    indexToPhysical,
              const SurfaceProjection &       project,
              const SliverRemovalParameters & parameters)
{
  if (triangles.empty())
  {
    return {};
  }
  SliverRemover remover(positions, triangles, origin, indexToPhysical, project, parameters);
  return remover.Run();
}

} // namespace detail
} // namespace MeshExtraction
} // namespace itk
