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
#ifndef itkLaplacianSmoothingQuadEdgeMeshFilter_h
#define itkLaplacianSmoothingQuadEdgeMeshFilter_h

#include "itkMeshExtractionEnums.h"
#include "itkMeshExtractionMacros.h"
#include "itkMeshExtractionQuadEdgeMeshVertexSmoother.h"
#include "itkQuadEdgeMeshParamMatrixCoefficients.h"
#include "itkQuadEdgeMeshToQuadEdgeMeshFilter.h"

namespace itk
{
/** \class LaplacianSmoothingQuadEdgeMeshFilter
 * \brief Laplacian smoothing of a triangle mesh that never inverts a triangle
 * (P.W. de Bruin's thesis, sections 2.2.3-2.2.4, 4.2.2 and 4.5.1).
 *
 * Every iteration moves each vertex v towards its smoothing target
 * S(v) = v + sum_j w_j (v_j - v) / sum_j w_j over its linked neighbours v_j:
 *
 * - Weights: Uniform (default; the average of the neighbours), InverseEdgeLength
 *   (w_j = 1/|v_j - v|), Area (the area-weighted average of the incident triangles'
 *   centroids), Cotangent (Desbrun: cot alpha_j + cot beta_j, clamped at 0) or
 *   AngleBisector (the average of the projections of v onto the bisectors of the
 *   1-ring polygon's angles, thesis Figure 2.16). Alternatively any ITK
 *   MatrixCoefficients object (SetCoefficientsMethod) gives the edge weights.
 * - UpdateMode: Batch (default; every target from the mesh at the start of the
 *   iteration, as in thesis section 4.2.2) or Immediate (vertices move one by one in
 *   increasing point identifier order and see the earlier moves).
 * - RelaxationFactor r in (0, 1] (default 1): the move is r (S(v) - v).
 * - MovementConstraint: None (default); Centroid, S_C = 1/3 v + 2/3 S(v) (thesis
 *   section 4.2.2); Safe, the move clipped to the distance to the nearest
 *   neighbour (thesis Figure 4.8).
 * - VolumePreservation (default off): the move's component along the 1-ring
 *   normal (the sum of the incident triangles' normals) is removed, which keeps the
 *   volume of the cone spanned by the ring (thesis eq. 2.7-2.10) and so,
 *   approximately, the enclosed volume.
 * - PreventInversions (default on): a guard beyond the thesis, which admits that
 *   even centroid smoothing can invert triangles (Figure 4.7). A move is accepted
 *   only if no incident triangle's normal turns by 90 degrees or more against its
 *   orientation before the move, nor against its orientation at the start of the
 *   iteration, and no triangle's q_area drops to DegenerateQAreaTolerance (default
 *   1e-4) or below; otherwise it is halved, up to MaximumNumberOfShortenings times
 *   (default 5), and then rejected. The checks are made against the current
 *   positions of the neighbours, in Batch mode too, and on the positions rounded to
 *   the mesh's coordinate type, so they hold for the mesh that comes out: after
 *   every iteration no triangle is inverted or degenerate with respect to the mesh
 *   before it. The guard is local: it does not look for non-adjacent parts of the
 *   surface that a vertex might pass through. GetNumberOfShortenedMoves() and
 *   GetNumberOfRejectedMoves() report how often it intervened.
 * - PreventSelfIntersections (default on; with PreventInversions): after every
 *   iteration, the moves that made the surface cut through itself or fold, or turned
 *   a closed component inside out, go back to where the iteration started them
 *   (MeshExtraction::detail::UndoFoldingMoves: exact intersection tests of the triangles that
 *   moved, signed volumes), so a valid closed surface stays valid; so do, against the
 *   input, the moves that shrink a closed component below a thousandth of its volume
 *   or move a surface past a component (its nesting parity changes, a ray test per
 *   component when there are several). It costs a self-intersection search per
 *   iteration (the 256^3 sphere's 222,528 triangles: see benchmark/README.md).
 *   GetNumberOfUndoneMoves() counts the vertices moved back.
 * - FixBoundary (default on): vertices on the boundary of an open mesh do not move.
 *   Non-manifold vertices never move.
 * - NumberOfIterations (default 1, >= 0).
 *
 * The connectivity is not changed: the output has the input's points (by
 * identifier) and faces. The targets of a Batch iteration are computed on ITK's
 * multithreader with the ProcessObject's NumberOfWorkUnits; the result does not
 * depend on the number of threads.
 *
 * The input must be a triangle mesh; another polygon raises an ExceptionObject, as
 * do a missing input and parameters out of range.
 *
 * ITK's SmoothingQuadEdgeMeshFilter computes the same uniform, batch, unguarded
 * step (with OnesMatrixCoefficients) but has no constraint, guard, immediate mode or
 * fixed boundary, and its coefficients object defaults to null; this filter reuses
 * its MatrixCoefficients family through SetCoefficientsMethod().
 *
 * \sa TaubinSmoothingQuadEdgeMeshFilter, EdgeSwapQuadEdgeMeshFilter
 * \ingroup MeshExtraction
 */
template <typename TInputMesh, typename TOutputMesh = TInputMesh>
class ITK_TEMPLATE_EXPORT LaplacianSmoothingQuadEdgeMeshFilter
    : public QuadEdgeMeshToQuadEdgeMeshFilter<TInputMesh, TOutputMesh>
{
public:
  ITK_DISALLOW_COPY_AND_MOVE(LaplacianSmoothingQuadEdgeMeshFilter);

  using Self = LaplacianSmoothingQuadEdgeMeshFilter;
  using Superclass = QuadEdgeMeshToQuadEdgeMeshFilter<TInputMesh, TOutputMesh>;
  using Pointer = SmartPointer<Self>;
  using ConstPointer = SmartPointer<const Self>;

  itkOverrideGetNameOfClassMacro(LaplacianSmoothingQuadEdgeMeshFilter);
  itkNewMacro(Self);

  using InputMeshType = TInputMesh;
  using OutputMeshType = TOutputMesh;
  using CoefficientsComputation = MatrixCoefficients<OutputMeshType>;

  using SmoothingWeightsEnum = MeshExtractionEnums::SmoothingWeights;
  using SmoothingUpdateEnum = MeshExtractionEnums::SmoothingUpdate;
  using MovementConstraintEnum = MeshExtractionEnums::MovementConstraint;

  static_assert(OutputMeshType::PointDimension == 3, "LaplacianSmoothingQuadEdgeMeshFilter smooths 3-D surface meshes");

  /** Weights of the smoothing target (default Uniform). */
  itkSetEnumMacro(Weights, SmoothingWeightsEnum);
  itkGetEnumMacro(Weights, SmoothingWeightsEnum);

  /** Batch (default) or Immediate. */
  itkSetEnumMacro(UpdateMode, SmoothingUpdateEnum);
  itkGetEnumMacro(UpdateMode, SmoothingUpdateEnum);

  /** None (default), Centroid or Safe. */
  itkSetEnumMacro(MovementConstraint, MovementConstraintEnum);
  itkGetEnumMacro(MovementConstraint, MovementConstraintEnum);

  /** Scale of each move, in (0, 1] (default 1). */
  itkSetMacro(RelaxationFactor, double);
  itkGetConstMacro(RelaxationFactor, double);

  /** Number of smoothing iterations, >= 0 (default 1). */
  itkSetMacro(NumberOfIterations, int);
  itkGetConstMacro(NumberOfIterations, int);

  /** Approximate volume preservation, thesis eq. 2.7-2.10 (default off). */
  itkSetMacro(VolumePreservation, bool);
  itkGetConstMacro(VolumePreservation, bool);
  itkBooleanMacro(VolumePreservation);

  /** The no-inversion guard (default on). */
  itkSetMacro(PreventInversions, bool);
  itkGetConstMacro(PreventInversions, bool);
  itkBooleanMacro(PreventInversions);

  /** Undo moves that make the surface cross itself (default on; needs
   * PreventInversions; see the class documentation). */
  itkSetMacro(PreventSelfIntersections, bool);
  itkGetConstMacro(PreventSelfIntersections, bool);
  itkBooleanMacro(PreventSelfIntersections);

  /** How often the guard halves a move before rejecting it (default 5). */
  itkSetMacro(MaximumNumberOfShortenings, unsigned int);
  itkGetConstMacro(MaximumNumberOfShortenings, unsigned int);

  /** q_area at or below which the guard counts a triangle as degenerate, in [0, 1)
   * (default 1e-4). */
  itkSetMacro(DegenerateQAreaTolerance, double);
  itkGetConstMacro(DegenerateQAreaTolerance, double);

  /** Keep the boundary vertices of open meshes in place (default on). */
  itkSetMacro(FixBoundary, bool);
  itkGetConstMacro(FixBoundary, bool);
  itkBooleanMacro(FixBoundary);

  /** Optional ITK edge weights (e.g. OnesMatrixCoefficients,
   * ConformalMatrixCoefficients); when set they replace Weights. The object is not
   * owned and must outlive the filter's updates. Default: none. */
  void
  SetCoefficientsMethod(const CoefficientsComputation * method)
  {
    if (m_CoefficientsMethod != method)
    {
      m_CoefficientsMethod = method;
      this->Modified();
    }
  }
  const CoefficientsComputation *
  GetCoefficientsMethod() const
  {
    return m_CoefficientsMethod;
  }

  /** Counters of the last update: moves attempted (non-zero displacements), moves
   * the guard shortened, moves it rejected, and the vertices that could move. */
  itkGetConstMacro(NumberOfMoves, SizeValueType);
  itkGetConstMacro(NumberOfShortenedMoves, SizeValueType);
  itkGetConstMacro(NumberOfRejectedMoves, SizeValueType);
  /** Vertices moved back by PreventSelfIntersections (over all iterations). */
  itkGetConstMacro(NumberOfUndoneMoves, SizeValueType);
  itkGetConstMacro(NumberOfMovableVertices, SizeValueType);

protected:
  /** The per-vertex smoother the filter runs (internal: itk::MeshExtraction::detail). */
  using SmootherType = MeshExtraction::detail::QuadEdgeMeshVertexSmoother<OutputMeshType>;

  LaplacianSmoothingQuadEdgeMeshFilter() = default;
  ~LaplacianSmoothingQuadEdgeMeshFilter() override = default;
  void
  PrintSelf(std::ostream & os, Indent indent) const override;

  /** Checks the parameters and the input, copies it to the output, then smooths:
   * NumberOfIterations steps of the shared vertex smoother. */
  void
  GenerateData() override;

  /** Throws an ExceptionObject naming the first parameter out of range. */
  void
  VerifyParameters() const;

private:
  SmoothingWeightsEnum            m_Weights{ SmoothingWeightsEnum::Uniform };
  SmoothingUpdateEnum             m_UpdateMode{ SmoothingUpdateEnum::Batch };
  MovementConstraintEnum          m_MovementConstraint{ MovementConstraintEnum::None };
  double                          m_RelaxationFactor{ 1.0 };
  int                             m_NumberOfIterations{ 1 };
  bool                            m_VolumePreservation{ false };
  bool                            m_PreventInversions{ true };
  bool                            m_PreventSelfIntersections{ true };
  unsigned int                    m_MaximumNumberOfShortenings{ 5 };
  double                          m_DegenerateQAreaTolerance{ 1e-4 };
  bool                            m_FixBoundary{ true };
  const CoefficientsComputation * m_CoefficientsMethod{ nullptr };

  SizeValueType m_NumberOfMoves{ 0 };
  SizeValueType m_NumberOfShortenedMoves{ 0 };
  SizeValueType m_NumberOfRejectedMoves{ 0 };
  SizeValueType m_NumberOfUndoneMoves{ 0 };
  SizeValueType m_NumberOfMovableVertices{ 0 };
};
} // namespace itk

#ifndef ITK_MANUAL_INSTANTIATION
#  include "itkLaplacianSmoothingQuadEdgeMeshFilter.hxx"
#endif

#endif
