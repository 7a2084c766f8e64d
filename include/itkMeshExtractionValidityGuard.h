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
#ifndef itkMeshExtractionValidityGuard_h
#define itkMeshExtractionValidityGuard_h

#include "MeshExtractionExport.h"
#include "itkMeshExtractionIndexedTriangleMesh.h"
#include "itkMeshExtractionLargeBlockVector.h"
#include "itkMeshExtractionSurfaceNets.h"
#include "itkMeshExtractionTriangleAABBTree.h"
#include "itkMeshExtractionVertexSmoothing.h"
#include "itkMatrix.h"

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
/** \file
 * \brief The validity guard: every check that keeps a mesh valid while its vertices
 * move or its edges are swapped, with one set of thresholds (ValidityThresholds).
 *
 * The module's promise is that every mesh it emits is valid: no triangle turns over
 * (its normal turns by 90 degrees or more) or degenerates, no two triangles that share
 * an edge fold onto each other, no two triangles intersect, and no closed component
 * turns inside out, collapses or is passed by another part of the surface. A change
 * that would break the promise is taken back, never repaired by new geometry: the
 * state before the change was valid. By what changed:
 *
 * - one vertex moves (the smoothing filters, the edge detection): IsValidVertexMove()
 *   and GuardVertexMove(), which halves the move until it is valid;
 * - many vertices moved in one step, checked afterwards:
 *   - UndoFoldingMoves(): the smoothing filters and the edge detection send the
 *     vertices of invalid triangles and collapsed or passed components back to the
 *     step's start;
 *   - PullBackInvalidMoves(): the high-quality SurfaceNets mode halves the moves of
 *     such nodes once, then resets them;
 *   - RemoveSurfaceNetSelfIntersections(): the SurfaceNets relaxation halves the moves
 *     of the nodes of crossing faces several times, then resets them
 *     (FindSurfaceNetSelfIntersections() finds the crossings from the net's cells);
 * - edges are swapped:
 *   - UndoIntersectingSwaps(): the swaps of one sweep of SwapEdges() (the indexed swap
 *     engine of the high-quality mode and of the refinement) are undone one by one;
 *   - FindCrossingNewTriangles(): EdgeSwapQuadEdgeMeshFilter locks the corners of the
 *     new triangles that cross the surface and swaps again from its input;
 * - components: IsCollapsedComponent() is the one definition of a collapsed component;
 *   ComponentVolumes (the high-quality mode) and ComponentReference (a series of
 *   smoothing or detection steps) keep the volumes it compares with.
 *
 * \ingroup MeshExtraction
 */

/** \brief The thresholds of the validity guard, in one place.
 * \ingroup MeshExtraction */
struct ValidityThresholds
{
  /** Two triangles sharing an edge fold when their normals make more than 120 degrees
   * (the cosine is below this): neither has turned over on its own, yet the surface
   * doubles back. A swap may not leave a fold at its triangles (UndoIntersectingSwaps);
   * a move may not make a new fold, nor close further one that was there at its start
   * (PullBackInvalidMoves). */
  static constexpr double FoldCosine = -0.5;

  /** The default DegenerateQAreaTolerance of the filters that move vertices or swap
   * edges of any input mesh (EdgeSwapQuadEdgeMeshFilter, the smoothing filters, the
   * edge detection): a triangle at or below this q_area is degenerate. Small, because
   * those filters get meshes made elsewhere, whose triangles may be poor already: the
   * guard keeps a triangle from becoming flat, not from staying poor. */
  static constexpr double DegenerateQAreaTolerance = 1e-4;

  /** The degenerate q_area tolerance of the high-quality SurfaceNets mode (its swaps
   * and PullBackInvalidMoves). Larger than the filters' default: the mode makes its
   * own triangles from a SurfaceNet, to make them good, so it refuses a swap or a move
   * that would leave a sliver, where a general filter must accept the poor triangles
   * of its input. */
  static constexpr double HighQualityDegenerateQAreaTolerance = 1e-3;

  /** IsCollapsedComponent() in the high-quality mode (ComponentVolumes): against the
   * volume where the mode starts. The mode moves nodes along the iso-surface from a
   * valid, relaxed net and does not mean to shrink anything, so a component that keeps
   * less than a quarter of its volume is being pressed flat; pulling its nodes back
   * costs only the mode's gain there. One reference serves every round. */
  static constexpr double HighQualityCollapseFraction = 0.25;

  /** IsCollapsedComponent() within one smoothing or detection step (UndoFoldingMoves):
   * against the volume at the step's start. Laplacian smoothing shrinks small
   * components by design, a one-voxel component by a large factor in one step, so
   * only a component pressed nearly flat in one step goes back (cotangent weights
   * without a constraint can press two sheets onto each other). */
  static constexpr double StepCollapseFraction = 0.01;

  /** IsCollapsedComponent() over a series of steps (UndoFoldingMoves with a
   * ComponentReference): against the volume before the first step. Every step may
   * stay within StepCollapseFraction while the series still shrinks a component to a
   * speck whose triangles' orientation is left to round-off; the series may shrink a
   * component a great deal (smoothing does), but not below this. */
  static constexpr double SeriesCollapseFraction = 1e-3;

  /** GuardVertexMove(): how often a refused move is halved before the vertex stays
   * (the default of the smoothing filters' MaximumNumberOfShortenings). */
  static constexpr unsigned int MaximumShortenings = 5;

  /** PullBackInvalidMoves(): an invalid move is halved this often, then reset to the
   * start. Fewer than SurfaceNetsHalvingsBeforeReset: in the high-quality mode each
   * relaxation starts from a relaxed, valid mesh on the iso-surface, so its moves are
   * small and little is lost by resetting one, while every halving costs another round
   * of checks over the whole mesh. */
  static constexpr unsigned int PullBackHalvingsBeforeReset = 1;

  /** RemoveSurfaceNetSelfIntersections(): the relocation of a node of crossing faces
   * is halved this often, then reset to the node's cell centre. More than
   * PullBackHalvingsBeforeReset: the SurfaceNets relaxation starts from the cell
   * centres, away from the iso-surface, so a reset loses the node's whole way to the
   * surface: halving keeps as much of it as the mesh allows. */
  static constexpr unsigned int SurfaceNetsHalvingsBeforeReset = 4;

  /** PullBackInvalidMoves() and RemoveSurfaceNetSelfIntersections(): after this many
   * rounds every node is put back at the start, which was valid. Not expected: a node
   * is reset after a few halvings, so the rounds end well before. */
  static constexpr unsigned int MaximumRepairRounds = 64;

  /** EdgeSwapQuadEdgeMeshFilter: how often the swaps are made again from the input
   * with the corners of crossing triangles locked, before the input is kept. */
  static constexpr unsigned int MaximumSwapAttempts = 8;
};

// ---------------------------------------------------------------------------------
// Components
// ---------------------------------------------------------------------------------

/** 6 x the signed volume each component of a closed mesh encloses (positive for an
 * outer surface, negative for a cavity's), summed over `triangles` in order:
 * componentOf(f) < origin.size() names the component of triangle f, and its volume
 * is measured from origin[c] (one of its points, which keeps the round-off small). */
template <typename TComponentOf>
std::vector<double>
ComponentSixVolumes(const std::vector<TriangleIndices> & triangles,
                    const std::vector<Vec3> &            points,
                    const std::vector<Vec3> &            origin,
                    TComponentOf &&                      componentOf)
{
  std::vector<double> volume(origin.size(), 0.0);
  for (std::size_t f = 0; f < triangles.size(); ++f)
  {
    const auto &        t = triangles[f];
    const std::uint32_t c = componentOf(f);
    const Vec3 &        o = origin[c];
    volume[c] += Dot(points[t[0]] - o, Cross(points[t[1]] - o, points[t[2]] - o));
  }
  return volume;
}

/** The one definition of a collapsed component: a closed component whose (6 x signed)
 * volume was `start` before a change and is `now` after it has collapsed if it turned
 * inside out (`now` is not on the side of zero `start` is on: the other sign, zero or
 * NaN) or keeps less than `fraction` of the magnitude of `reference` (the volume at
 * `start`, or at an earlier state it is compared with). A component without a volume
 * at `start` (zero or NaN) cannot turn inside out. The fractions are in
 * ValidityThresholds. */
MeshExtraction_EXPORT bool
IsCollapsedComponent(double start, double now, double reference, double fraction);

/** \brief The signed volume of each component of a closed mesh (positive for an outer
 * surface, negative for a cavity's), measured where the high-quality mode starts.
 *
 * A component of a few triangles (a voxel on its own, a few nodes across) can turn
 * inside out, or close onto itself, in one move or swap while none of its faces
 * flips, folds or crosses another at the end of it; its volume tells (as in
 * UndoFoldingMoves, which compares each step of the smoothing and the edge detection
 * with its start). The components are those of the vertices, which swaps and moves do
 * not change.
 * \ingroup MeshExtraction */
struct MeshExtraction_EXPORT ComponentVolumes
{
  std::vector<std::uint32_t> vertexComponent; ///< component of each vertex (the largest uint32 if in no triangle)
  std::vector<Vec3>          origin;          ///< per component: a vertex's start position, to measure from
  std::vector<double>        reference;       ///< per component: 6 x the signed volume at the start

  /** Labels the components of `triangles` and measures their volumes at `points`. */
  void
  Initialize(const std::vector<TriangleIndices> & triangles, const std::vector<Vec3> & points);
  /** For each component, whether it collapsed at `points` against its reference
   * (IsCollapsedComponent with HighQualityCollapseFraction; none if not initialised). */
  std::vector<bool>
  Collapsed(const std::vector<TriangleIndices> & triangles, const std::vector<Vec3> & points) const;
};

/** What a series of smoothing steps keeps of a mesh's components before the first
 * step, for UndoFoldingMoves: each component's ComponentSixVolumes (measured from
 * the first vertex of its first triangle) and its ComponentNestingParity.
 * \ingroup MeshExtraction */
struct ComponentReference
{
  std::vector<double>      sixVolumes;
  std::vector<std::int8_t> nesting;
};

/** The ComponentReference of `mesh`, whose topology is `topology`. */
MeshExtraction_EXPORT ComponentReference
MakeComponentReference(const IndexedTriangleMesh & mesh, const MeshTopology & topology);

/** The components whose ComponentNestingParity the move of every vertex of `mesh`
 * from startPositions to mesh.points can have changed, in increasing order. A
 * component's parity is that of its ComponentRayVertices vertex v against the other
 * components. Along the straight path from start to end it changes only where v
 * passes through a triangle T of another component, or T through v, so then v or T
 * moved and the box of v's path overlaps the box of T's start and end: a component for
 * which no such T exists keeps its parity. A pass over the triangles against the
 * components' vertex boxes sorted along x: far cheaper than ComponentNestingParity's
 * tree. */
MeshExtraction_EXPORT std::vector<std::uint32_t>
                      ComponentsAMoveMayHavePassed(const IndexedTriangleMesh & mesh,
                                                   const MeshTopology &        topology,
                                                   const std::vector<Vec3> &   startPositions);

// ---------------------------------------------------------------------------------
// One vertex
// ---------------------------------------------------------------------------------

/** Whether moving the vertex to `newCenter` keeps every incident triangle valid:
 * - a triangle with a defined orientation (q_area > 0) keeps it: the new normal
 *   makes an angle below 90 degrees with the one before the move (dot > 0);
 * - if `reference` is given (the same ring at earlier positions, e.g. at the start
 *   of a smoothing iteration), the new normal also makes an angle below 90 degrees
 *   with the reference triangle's normal, so that the moves of one iteration
 *   together cannot turn a triangle over either;
 * - a triangle with q_area above `degenerateTolerance` stays above it; one already
 *   at or below it may not get worse.
 * Triangles away from the vertex do not change, so these checks, made against the
 * current positions, are exact. */
MeshExtraction_EXPORT bool
IsValidVertexMove(const VertexOneRing & r,
                  const Vec3 &          newCenter,
                  double                degenerateTolerance,
                  const VertexOneRing * reference = nullptr);

/** What became of one guarded move. */
enum class VertexMoveOutcome : std::uint8_t
{
  Unchanged = 0, ///< nothing to do: a zero displacement (after rounding)
  Accepted,      ///< the whole move was made
  Shortened,     ///< a fraction 2^-k of it was made
  Rejected       ///< every fraction tried would have flipped or degenerated a triangle
};

struct GuardedVertexMove
{
  Vec3              position;
  VertexMoveOutcome outcome{ VertexMoveOutcome::Unchanged };
};

/** The no-inversion guard (goes beyond the thesis, whose centroid smoothing can
 * still invert triangles, Figure 4.7; the halving follows CGAL's
 * tangential_relaxation): tries v + d, v + d/2, ..., v + d/2^maximumShortenings and
 * takes the first that IsValidVertexMove() accepts (with the optional `reference`
 * ring); if none is, the vertex stays. `round` maps a candidate to the position the
 * mesh will actually store (e.g. rounded to float coordinates), so that the checks
 * see exactly what is stored. */
template <typename TRound>
GuardedVertexMove
GuardVertexMove(const VertexOneRing & r,
                const Vec3 &          displacement,
                unsigned int          maximumShortenings,
                double                degenerateTolerance,
                TRound &&             round,
                const VertexOneRing * reference = nullptr)
{
  GuardedVertexMove result{ r.center, VertexMoveOutcome::Unchanged };
  double            t = 1.0;
  for (unsigned int k = 0; k <= maximumShortenings; ++k, t *= 0.5)
  {
    const Vec3 candidate = round(r.center + displacement * t);
    if (candidate == r.center)
    {
      // Nothing left to move: a zero move, or every shorter one rounds to v too.
      result.outcome = k == 0 ? VertexMoveOutcome::Unchanged : VertexMoveOutcome::Rejected;
      return result;
    }
    if (IsValidVertexMove(r, candidate, degenerateTolerance, reference))
    {
      result.position = candidate;
      result.outcome = k == 0 ? VertexMoveOutcome::Accepted : VertexMoveOutcome::Shortened;
      return result;
    }
  }
  result.outcome = VertexMoveOutcome::Rejected;
  return result;
}

// ---------------------------------------------------------------------------------
// Many vertices, after a step
// ---------------------------------------------------------------------------------

/** Whether triangle t of `mesh` keeps the orientation it had with the vertices at
 * `startPositions` (its normal turned by less than 90 degrees) and does not become
 * degenerate (q_area <= tolerance; if it already was, it may not get worse): the
 * per-triangle checks of IsValidVertexMove(). */
MeshExtraction_EXPORT bool
IsValidTriangleAgainstStart(const IndexedTriangleMesh & mesh,
                            const std::vector<Vec3> &   startPositions,
                            std::uint32_t               t,
                            double                      tolerance);

/** Vertex moves checked one vertex at a time (the guards of the edge detector and of
 * the smoothing filters) can together still fold the surface (two triangles of a
 * ring crossing each other) or make it pass through another part. Given the mesh
 * after such moves and the positions before them, this finds the triangles that
 * changed and now intersect another triangle (exact predicates,
 * FindSelfIntersections) or are turned over or degenerate against the start
 * (IsValidTriangleAgainstStart), moves their vertices back to the start, and repeats
 * with the triangles around the vertices moved back, until none is left: at worst
 * everything is back where it started. Intersections between triangles that did not
 * change are left alone. A closed component that collapsed in the step
 * (IsCollapsedComponent against the step's start with StepCollapseFraction: turned
 * inside out as a whole, which a small component, e.g. the triangles around one voxel,
 * can do without any triangle crossing another, or pressed flat) goes back to the
 * start entirely.
 *
 * With `reference` (MakeComponentReference before the first of a series of steps,
 * on the same topology), two more things that a series of Laplacian steps can do to
 * the triangles around one voxel, each step within the rules above, are undone: a
 * component that shrank in the step and collapsed against its reference volume
 * (SeriesCollapseFraction: a speck) goes back; and where a component's
 * ComponentNestingParity changed (a surface moved past it in one step, leaving no
 * intersection behind, so that its triangles now face the wrong way), it goes back,
 * and so do the moved triangles of the other components whose boxes, before and after
 * the step, overlap its own. The parity test (a tree and a ray per component) runs
 * only if ComponentsAMoveMayHavePassed names a component. Returns the number of
 * vertices moved back.
 * \ingroup MeshExtraction */
MeshExtraction_EXPORT std::size_t
                      UndoFoldingMoves(IndexedTriangleMesh &      mesh,
                                       const MeshTopology &       topology,
                                       const std::vector<Vec3> &  startPositions,
                                       double                     tolerance,
                                       const ComponentReference * reference = nullptr);

struct SelfIntersectionCache;
struct SurfaceNetTriangles;
struct EdgeSwapRecord;

/** Builds `tree` over all triangles of `mesh` with `boxes` the first time, and refits it
 * (same shape, new boxes) when it already holds that many triangles: the tree that
 * UndoIntersectingSwaps and PullBackInvalidMoves share over the rounds of one mesh. */
MeshExtraction_EXPORT void
BuildOrRefitTree(TriangleAABBTree & tree, const IndexedTriangleMesh & mesh, const AxisAlignedBoxArray & boxes);

/** After nodes moved from `start` to `positions` (continuous index), pull back the
 * nodes of triangles that flipped against their orientation at `start`, became
 * degenerate (q_area <= tolerance, measured in millimetres), fold against a
 * neighbour (ValidityThresholds::FoldCosine) where they did not at `start` (or fold
 * more sharply where they did), or intersect another triangle, and the moved nodes of
 * components that collapsed (`volumes`, if given): halve their move
 * (PullBackHalvingsBeforeReset times), then reset it, until no such triangle or
 * component is left. Checks run on the physical positions that will be written
 * (`roundToFloat`). Returns the number of nodes pulled back. `tree`: as for
 * UndoIntersectingSwaps (built once, then refitted); `cache`: kept between the calls
 * for one mesh, so that a check after small moves tests only what may have changed
 * (SelfIntersectionCache; same result). */
MeshExtraction_EXPORT std::size_t
                      PullBackInvalidMoves(LargeBlockVector<Vec3> &       positions,
                                           const LargeBlockVector<Vec3> & start,
                                           const SurfaceNetTriangles &    mesh,
                                           const Vec3 &                   origin,
                                           const Matrix<double, 3, 3> &   indexToPhysical,
                                           double                         degenerateQAreaTolerance,
                                           bool                           roundToFloat = false,
                                           TriangleAABBTree *             tree = nullptr,
                                           SelfIntersectionCache *        cache = nullptr,
                                           const ComponentVolumes *       volumes = nullptr);

/** The self-intersecting face pairs of a SurfaceNet's triangles, found from the net's
 * structure instead of a tree over all faces: the two triangles of quad q are faces
 * 2q and 2q+1 of `mesh` (MakeSurfaceNetFaces with a triangulation), whose points are
 * the nodes in physical space. Every node lies in its own cell, so a quad lies in the
 * 2x2 block of cells around its voxel edge, at least the nodes' smallest distance to
 * their cell's faces (m) inside the block's outer faces; two quads whose blocks share no
 * cell are then at least 2m apart and cannot meet. Only pairs of faces whose quads
 * share a cell are tested (boxes, then FacesIntersect, as FindSelfIntersections),
 * each pair once, in parallel over cells. With `changed`, only pairs that include a
 * changed face are sought.
 *
 * Returns false, leaving `pairs` empty, when that argument does not hold for the
 * coordinates as computed: a node on its cell's face (m = 0) or m smaller than a
 * bound on the rounding of the physical coordinates (`roundedToFloat`: rounded to
 * float as written). Callers then use FindSelfIntersections. Otherwise `pairs` is
 * exactly FindSelfIntersections' result: pairs (i < j) of non-degenerate faces that
 * intersect away from their shared vertices and edge, sorted. */
MeshExtraction_EXPORT bool
FindSurfaceNetSelfIntersections(const SurfaceNet &                                     net,
                                const IndexedTriangleMesh &                            mesh,
                                const Vec3 &                                           origin,
                                const Matrix<double, 3, 3> &                           indexToPhysical,
                                bool                                                   roundedToFloat,
                                const std::vector<std::uint32_t> *                     changed,
                                std::vector<std::pair<std::uint32_t, std::uint32_t>> & pairs,
                                unsigned int                                           numberOfWorkUnits = 0);

/** Stage 3b of SurfaceNets: where relaxed faces cross each other (two sheets
 * pulled toward one iso-surface, e.g. where the object touches itself), move the
 * nodes of the crossing faces back toward `initial` (halving their relocation
 * SurfaceNetsHalvingsBeforeReset times, then resetting it) until no two faces
 * intersect. The unrelaxed net (nodes at cell centres and sheet centres) is free of
 * intersections, so this ends with an intersection-free net. Intersections are found
 * with the exact test of TriangleMeshQualityCalculator on the physical positions that
 * will be written (rounded to float with `roundToFloat`). Returns the number of nodes
 * moved back. With `faces`, the triangles of the final net as MakeSurfaceNetFaces
 * makes them (split by `split`, which must not be KeepQuads), so that they need not be
 * made again; left empty when no faces of the final positions were made. With
 * `points` too, those faces' physical points (as ToPhysical with `roundToFloat` makes
 * them), handed out with the faces and otherwise left empty. */
MeshExtraction_EXPORT std::size_t
                      RemoveSurfaceNetSelfIntersections(SurfaceNet &                                     net,
                                                        const LargeBlockVector<Vec3> &                   initial,
                                                        const Vec3 &                                     origin,
                                                        const Matrix<double, 3, 3> &                     indexToPhysical,
                                                        QuadSplit                                        split,
                                                        bool                                             roundToFloat = false,
                                                        LargeBlockVector<std::array<std::uint32_t, 4>> * faces = nullptr,
                                                        std::vector<Vec3> *                              points = nullptr);

// ---------------------------------------------------------------------------------
// Edge swaps
// ---------------------------------------------------------------------------------

/** Undo swaps whose triangles intersect other triangles or fold against a neighbour
 * (ValidityThresholds::FoldCosine), or that leave their component collapsed
 * (`volumes`, if given), until none does; their edges are added to `refused` (kept
 * sorted) so later sweeps do not try them again. Returns the number of swaps undone.
 * With `tree` (the same one on every call for one mesh), its shape is built once and
 * refitted afterwards (TriangleAABBTree::Refit), which PullBackInvalidMoves shares. */
MeshExtraction_EXPORT std::size_t
                      UndoIntersectingSwaps(const std::vector<Vec3> &     physical,
                                            SurfaceNetTriangles &         mesh,
                                            std::vector<EdgeSwapRecord> & swaps,
                                            std::vector<std::uint64_t> *  refused = nullptr,
                                            TriangleAABBTree *            tree = nullptr,
                                            const ComponentVolumes *      volumes = nullptr);

/** An undirected edge by the identifiers of its points, the smaller first. */
using PointIdentifierEdge = std::pair<IdentifierType, IdentifierType>;

/** The edges of `mesh` by the identifiers of their points (mesh.pointIds), sorted and
 * without duplicates: what FindCrossingNewTriangles() compares a swapped mesh with. */
MeshExtraction_EXPORT std::vector<PointIdentifierEdge>
                      EdgesByPointIdentifier(const IndexedTriangleMesh & mesh);

/** The triangles of `mesh` that are new (they have an edge that is not in `oldEdges`,
 * EdgesByPointIdentifier of the mesh before the swaps) and cross another triangle
 * (exact test, FindSelfIntersections), sorted. EdgeSwapQuadEdgeMeshFilter locks their
 * corners and swaps again from its input (at most MaximumSwapAttempts times). */
MeshExtraction_EXPORT std::vector<std::uint32_t>
FindCrossingNewTriangles(const IndexedTriangleMesh & mesh, const std::vector<PointIdentifierEdge> & oldEdges);

} // namespace detail
} // namespace MeshExtraction
} // namespace itk

#endif
