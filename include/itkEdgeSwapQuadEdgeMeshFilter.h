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
#ifndef itkEdgeSwapQuadEdgeMeshFilter_h
#define itkEdgeSwapQuadEdgeMeshFilter_h

#include "itkMeshExtractionEdgeSwapCriteria.h"
#include "itkMeshExtractionIndexedTriangleMesh.h"
#include "itkMeshExtractionEnums.h"
#include "itkMeshExtractionMacros.h"
#include "itkMeshExtractionValidityGuard.h"
#include "itkQuadEdgeMeshToQuadEdgeMeshFilter.h"

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

namespace itk
{
/** \class EdgeSwapQuadEdgeMeshFilter
 * \brief Swaps edges of a triangle mesh while that improves a criterion, never
 * making the mesh invalid (thesis sections 2.2.6, 4.2.2 and 4.5.1).
 *
 * Two triangles sharing an edge form a quad; swapping the edge replaces it with the
 * quad's other diagonal. Criterion:
 * - Regularity (default): the relaxation index E_b = sum (d_i - 6)^2 over the quad's
 *   four corners drops (thesis eq. 2.16; d_i the number of edges at corner i, aiming
 *   at 4 instead of 6 for vertices on a boundary). It promotes valence 6 and so
 *   near-equilateral triangles, and cannot oscillate;
 * - Delaunay: the two angles opposite the edge sum to more than pi (the fourth
 *   corner lies inside the circumcircle of the other three, Figure 2.18);
 * - ShortestEdge: the other diagonal is shorter.
 *
 * A swap that improves the criterion is made only if it passes the checks of
 * section 4.5.1 (MeshExtraction::detail::CheckEdgeSwap, shared with other mesh types):
 * both corners of the old edge keep at least 3 edges (2 on a boundary, the tip of a
 * single triangle); neither new triangle is
 * degenerate (q_area > DegenerateQAreaTolerance, default 1e-4); each new triangle's
 * normal makes an angle below 90 degrees with each old one (so a concave quad is
 * never swapped); the dihedral angle of the old pair and of the new pair is at most
 * FeatureAngle (degrees, default 60), so sharp features are neither cut nor made;
 * and the new edge does not exist yet, so the mesh stays manifold without duplicate
 * edges. Optionally (MinimumQAreaRatio > 0, default 0; beyond the thesis) a swap must
 * also keep the worse of its two triangles at that fraction of the old worse one's
 * q_area: on marching-cubes meshes pure regularity swaps raise the share of valence
 * 6 but lower the mean q_area until the mesh is smoothed, and a ratio of 1 avoids
 * that.
 *
 * The filter makes passes over all edges, in increasing order of their (smaller,
 * larger) point identifiers, each edge judged on the mesh as the earlier swaps of
 * the pass left it; it stops after a pass without a swap or after
 * MaximumNumberOfIterations passes (default 20, >= 0). The result is deterministic.
 * Only internal edges between two triangles are candidates; boundary edges stay.
 * Edges next to a locked point (SetLockedPoints: an edge whose two triangles have a
 * locked corner) are not swapped either, so the triangles around those points stay
 * as they are.
 *
 * The checks above are local: on a rough surface a new triangle can still cut through
 * a nearby part of the surface. With PreventSelfIntersections (default on; beyond the
 * thesis) the validity guard (itkMeshExtractionValidityGuard.h) searches the new
 * triangles for crossings once the passes end (exact test,
 * MeshExtraction::detail::FindCrossingNewTriangles); the corners of those that cross are
 * locked and the passes run again from the input, up to
 * MeshExtraction::detail::ValidityThresholds::MaximumSwapAttempts times, after which the input
 * is kept unswapped. The output then crosses itself nowhere the input did not.
 *
 * The passes run on flat arrays (MeshExtraction::detail::SwapEdgesInPasses: half-edges
 * and their twins), not on the QuadEdgeMesh: a swap there is a few array writes, where
 * ITK's Euler operator (QuadEdgeMeshEulerOperatorFlipEdgeFunction) allocates and frees
 * edges and faces and walks the quad-edge rings, which on meshes of millions of
 * triangles made the passes most of the filter's time. The decisions are those the
 * Euler operator's passes took; the output is built once, after the last attempt.
 * The high-quality SurfaceNets mode and the refinement of closed surfaces swap with
 * another engine, MeshExtraction::detail::SwapEdges, which takes the same decision but
 * needs a closed surface and lets a triangle take part in one swap per sweep, so that
 * the guard can undo each swap on its own (see itkMeshExtractionClosedSurfaceEdgeSwap.h).
 * Here a later swap of a pass may build on an earlier one, so a swap cannot be undone
 * alone: the guard locks and retries instead.
 * Points keep their identifiers, positions and point data. Without a swap the output
 * is a copy of the input; after swaps its triangles are made anew in the input's face
 * order (the two triangles of a swap in place of the old two), with new cell
 * identifiers, and face (cell) data is not carried over. Edges without a face (wire
 * edges) are kept.
 *
 * GetNumberOfSwaps() counts the swaps made, GetNumberOfRefusedSwaps() the
 * improving swaps that a check refused (once per pass), GetNumberOfIterations()
 * the passes made. A missing input, a non-triangle face or a parameter out of range
 * raises an ExceptionObject.
 *
 * \sa LaplacianSmoothingQuadEdgeMeshFilter
 * \ingroup MeshExtraction
 */
template <typename TInputMesh, typename TOutputMesh = TInputMesh>
class ITK_TEMPLATE_EXPORT EdgeSwapQuadEdgeMeshFilter : public QuadEdgeMeshToQuadEdgeMeshFilter<TInputMesh, TOutputMesh>
{
public:
  ITK_DISALLOW_COPY_AND_MOVE(EdgeSwapQuadEdgeMeshFilter);

  using Self = EdgeSwapQuadEdgeMeshFilter;
  using Superclass = QuadEdgeMeshToQuadEdgeMeshFilter<TInputMesh, TOutputMesh>;
  using Pointer = SmartPointer<Self>;
  using ConstPointer = SmartPointer<const Self>;

  itkOverrideGetNameOfClassMacro(EdgeSwapQuadEdgeMeshFilter);
  itkNewMacro(Self);

  using InputMeshType = TInputMesh;
  using OutputMeshType = TOutputMesh;
  using OutputQEType = typename OutputMeshType::QEType;
  using OutputPointIdentifier = typename OutputMeshType::PointIdentifier;
  using EdgeSwapCriterionEnum = MeshExtractionEnums::EdgeSwapCriterion;

  static_assert(OutputMeshType::PointDimension == 3, "EdgeSwapQuadEdgeMeshFilter works on 3-D surface meshes");

  /** Regularity (default), Delaunay or ShortestEdge. */
  itkSetEnumMacro(Criterion, EdgeSwapCriterionEnum);
  itkGetEnumMacro(Criterion, EdgeSwapCriterionEnum);

  /** Largest number of passes over the edges, >= 0 (default 20). */
  itkSetMacro(MaximumNumberOfIterations, int);
  itkGetConstMacro(MaximumNumberOfIterations, int);

  /** Largest dihedral angle in degrees, in (0, 180], between the two triangles at an
   * edge before or after a swap (default 60). */
  itkSetMacro(FeatureAngle, double);
  itkGetConstMacro(FeatureAngle, double);

  /** A swap may not create a triangle with q_area at or below this, in [0, 1)
   * (default 1e-4). */
  itkSetMacro(DegenerateQAreaTolerance, double);
  itkGetConstMacro(DegenerateQAreaTolerance, double);

  /** A swap must leave its worst new triangle with at least this times the q_area of
   * the worst old one, >= 0 (default 0: no requirement). */
  itkSetMacro(MinimumQAreaRatio, double);
  itkGetConstMacro(MinimumQAreaRatio, double);

  /** Undo swaps whose triangles cut through the surface (default on; see the class
   * documentation). */
  itkSetMacro(PreventSelfIntersections, bool);
  itkGetConstMacro(PreventSelfIntersections, bool);
  itkBooleanMacro(PreventSelfIntersections);

  /** Points around which no edge is swapped (default none). Identifiers that are not
   * points of the mesh are ignored. */
  void
  SetLockedPoints(const std::vector<OutputPointIdentifier> & points)
  {
    m_LockedPoints = points;
    std::sort(m_LockedPoints.begin(), m_LockedPoints.end());
    m_LockedPoints.erase(std::unique(m_LockedPoints.begin(), m_LockedPoints.end()), m_LockedPoints.end());
    this->Modified();
  }
  const std::vector<OutputPointIdentifier> &
  GetLockedPoints() const
  {
    return m_LockedPoints;
  }

  /** Results of the last update. */
  itkGetConstMacro(NumberOfSwaps, SizeValueType);
  itkGetConstMacro(NumberOfRefusedSwaps, SizeValueType);
  itkGetConstMacro(NumberOfIterations, int);
  /** With PreventSelfIntersections: new triangles found crossing the surface (over all
   * attempts), the attempts made (1 if none crossed), and whether the last attempt
   * still crossed, so that the input was kept. */
  itkGetConstMacro(NumberOfCrossingTriangles, SizeValueType);
  itkGetConstMacro(NumberOfAttempts, unsigned int);
  itkGetConstMacro(KeptInput, bool);

protected:
  EdgeSwapQuadEdgeMeshFilter() = default;
  ~EdgeSwapQuadEdgeMeshFilter() override = default;
  void
  PrintSelf(std::ostream & os, Indent indent) const override;

  /** Checks, copies the input, then swap passes until none swaps. */
  void
  GenerateData() override;

  void
  VerifyParameters() const;

private:
  /** The decision's parameters from the filter's settings. */
  MeshExtraction::detail::EdgeSwapParameters
  MakeSwapParameters() const;
  /** One flag per point of `mesh`: locked by SetLockedPoints() or by the guard. */
  std::vector<std::uint8_t>
  LockFlags(const MeshExtraction::IndexedTriangleMesh & mesh) const;
  /** The corners of `triangles` of `mesh` join the crossing-locked points. */
  void
  LockCorners(const MeshExtraction::IndexedTriangleMesh & mesh, const std::vector<std::uint32_t> & triangles);
  /** The output: the input's points, point data and wire edges, and the triangles of
   * `swapped`. */
  void
  BuildOutput(const MeshExtraction::IndexedTriangleMesh & swapped);

  EdgeSwapCriterionEnum m_Criterion{ EdgeSwapCriterionEnum::Regularity };
  int                   m_MaximumNumberOfIterations{ 20 };
  double                m_FeatureAngle{ 60.0 };
  double m_DegenerateQAreaTolerance{ MeshExtraction::detail::ValidityThresholds::DegenerateQAreaTolerance };
  double m_MinimumQAreaRatio{ 0.0 };

  bool m_PreventSelfIntersections{ true };

  std::vector<OutputPointIdentifier> m_LockedPoints;
  std::vector<OutputPointIdentifier> m_CrossingLockedPoints; ///< sorted; locked by PreventSelfIntersections

  SizeValueType m_NumberOfCrossingTriangles{ 0 };
  unsigned int  m_NumberOfAttempts{ 0 };
  bool          m_KeptInput{ false };
  SizeValueType m_NumberOfSwaps{ 0 };
  SizeValueType m_NumberOfRefusedSwaps{ 0 };
  int           m_NumberOfIterations{ 0 };
};
} // namespace itk

#ifndef ITK_MANUAL_INSTANTIATION
#  include "itkEdgeSwapQuadEdgeMeshFilter.hxx"
#endif

#endif
