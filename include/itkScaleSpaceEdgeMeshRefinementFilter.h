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
#ifndef itkScaleSpaceEdgeMeshRefinementFilter_h
#define itkScaleSpaceEdgeMeshRefinementFilter_h

#include "itkEdgeSwapQuadEdgeMeshFilter.h"
#include "itkImplicitSurfaceFunction.h"
#include "itkMeshExtractionEnums.h"
#include "itkMeshExtractionMacros.h"
#include "itkMeshExtractionQuadEdgeMeshVertexSmoother.h"
#include "itkMeshExtractionScaleSpaceEdgeDetector.h"
#include "itkMeshExtractionScaleSpaceRefinementSteps.h"
#include "itkQuadEdgeMeshToQuadEdgeMeshFilter.h"

#include <iosfwd>
#include <sstream>
#include <string>
#include <vector>

namespace itk
{
/** \class ScaleSpaceEdgeMeshRefinementFilter
 * \brief Moves an approximate triangle mesh onto the edges of an image and makes its
 * triangles well formed, alternating scale-space edge detection and mesh improvement
 * (P.W. de Bruin's thesis, chapter 4: the protocol of section 4.2.4).
 *
 * The protocol, each operation recorded as a row of GetSteps() (thesis Table 4.1):
 * 1. ED: one scale-space edge-detection step (ScaleSpaceEdgeDetectionMeshFilter's
 *    engine): every vertex moves to the edge within MaximumDeviation of it;
 * 2. ES: regularity edge swaps with the decision and default parameters of
 *    EdgeSwapQuadEdgeMeshFilter (on a closed 2-manifold surface through the indexed
 *    swap engine of the high-quality SurfaceNets, MeshExtraction::detail::SwapEdges, which is
 *    much faster on large meshes; on other meshes through the filter itself);
 * 3. S: centroid smoothing steps S_C = 1/3 v + 2/3 S_L(v) (uniform, batch, with the
 *    no-inversion guard of LaplacianSmoothingQuadEdgeMeshFilter), repeated until a
 *    vertex has travelled farther than the capture range (MaximumDeviation) from its
 *    position after the last ED, the mean q_area reaches TargetQuality, or
 *    MaximumNumberOfSmoothingSteps (default 20) steps were made;
 * 4. ED and ES again; the protocol stops after an ES once the mean q_area is at least
 *    TargetQuality, so it always ends with ED and ES on the edges. It also stops
 *    after MaximumNumberOfCycles cycles of steps 3-4 (default 10), or when a cycle
 *    raised the mean q_area by less than MinimumQualityImprovement (default 0.001)
 *    (GetTargetQualityReached() then says false).
 *
 * The only parameters one must give are the initial mesh (SetInput), the image
 * (SetInputImage), the maximum deviation of the mesh from the object's edge
 * (MaximumDeviation, mm, required > 0) and the target quality (TargetQuality, the
 * mean q_area, in (0, 1], default 0.9). The detector's MinimumScale,
 * NumberOfScalesPerOctave, SearchDirection and SubSampleRefinement are passed on (see
 * ScaleSpaceEdgeDetectionMeshFilter). The scale space of the image is computed once
 * for the whole protocol.
 *
 * Every row holds the mean minimum angle and mean q_area, the inaccuracy after an ED
 * (mean distance of the triangle centroids to the edge the detector finds from them,
 * section 4.2.3; ComputeInaccuracy, default on), the number of changes, the moves the
 * guard rejected, the travel, integrity counts (degenerate triangles, non-manifold
 * edges and vertices, triangles turned over by the step), the time, and, if a
 * ReferenceSurface (the exact surface, e.g. of a phantom) is given, the mean and
 * variance of the vertices' signed distances to it: for a sphere, mean radius and
 * radius variance as in Table 4.1. PrintSteps() prints the table.
 *
 * Every operation keeps a valid mesh valid. The guards of the edge detector and of
 * the smoothing look at one vertex at a time, and the edge swap at one quad at a
 * time, so after each ED and S the moves that made the surface fold or cut through
 * itself, or turned a closed component inside out, are undone
 * (MeshExtraction::detail::UndoFoldingMoves, exact intersection tests, signed volumes), and
 * after each ES the swaps whose new triangles intersect the surface or fold against
 * a neighbour are undone and not tried again (closed surfaces), or the corners of
 * those triangles are locked and the swaps made again from the mesh before the ES
 * (EdgeSwapQuadEdgeMeshFilter's PreventSelfIntersections: at most eight attempts,
 * then the ES is dropped; other meshes); the step table counts them with the
 * rejected moves.
 *
 * The output has the input's point identifiers; faces are re-created by the swaps.
 * The input must be a triangle mesh inside the image or within a voxel of its faces (a
 * SurfaceNets mesh of an object that touches the image border closes it there, up to
 * a voxel outside; the scale space is clamped at the faces); a missing image, an empty
 * mesh, a non-triangle face, a vertex farther outside or a parameter out of range raises
 * an ExceptionObject that names it. The edge detection and smoothing are
 * multithreaded (NumberOfWorkUnits); the result does not depend on the number of
 * threads.
 *
 * \sa ScaleSpaceEdgeDetectionMeshFilter, EdgeSwapQuadEdgeMeshFilter,
 * LaplacianSmoothingQuadEdgeMeshFilter
 * \ingroup MeshExtraction
 */
template <typename TInputMesh, typename TImage, typename TOutputMesh = TInputMesh>
class ITK_TEMPLATE_EXPORT ScaleSpaceEdgeMeshRefinementFilter
    : public QuadEdgeMeshToQuadEdgeMeshFilter<TInputMesh, TOutputMesh>
{
public:
  ITK_DISALLOW_COPY_AND_MOVE(ScaleSpaceEdgeMeshRefinementFilter);

  using Self = ScaleSpaceEdgeMeshRefinementFilter;
  using Superclass = QuadEdgeMeshToQuadEdgeMeshFilter<TInputMesh, TOutputMesh>;
  using Pointer = SmartPointer<Self>;
  using ConstPointer = SmartPointer<const Self>;

  itkOverrideGetNameOfClassMacro(ScaleSpaceEdgeMeshRefinementFilter);
  itkNewMacro(Self);

  using InputMeshType = TInputMesh;
  using OutputMeshType = TOutputMesh;
  using ImageType = TImage;
  using EdgeSwapFilterType = EdgeSwapQuadEdgeMeshFilter<OutputMeshType, OutputMeshType>;
  using StepType = MeshExtraction::ScaleSpaceRefinementStep;
  using StepsType = std::vector<StepType>;
  using EdgeSearchDirectionEnum = MeshExtractionEnums::EdgeSearchDirection;
  using OperationEnum = MeshExtractionEnums::RefinementOperation;

  static_assert(OutputMeshType::PointDimension == 3, "ScaleSpaceEdgeMeshRefinementFilter works on 3-D surface meshes");
  static_assert(ImageType::ImageDimension == 3, "ScaleSpaceEdgeMeshRefinementFilter needs a 3-D image");

  /** The image whose edges the mesh moves to. */
  itkSetInputMacro(InputImage, ImageType);
  itkGetInputMacro(InputImage, ImageType);

  /** The largest distance between the initial mesh and the object's edge, mm, > 0
   * (required; default 0): the capture range of the edge detector. */
  itkSetMacro(MaximumDeviation, double);
  itkGetConstMacro(MaximumDeviation, double);

  /** The mean q_area to reach, in (0, 1] (default 0.9). */
  itkSetMacro(TargetQuality, double);
  itkGetConstMacro(TargetQuality, double);

  /** Largest number of cycles (S..., ED, ES) after the first ED and ES (default 10). */
  itkSetMacro(MaximumNumberOfCycles, unsigned int);
  itkGetConstMacro(MaximumNumberOfCycles, unsigned int);

  /** Largest number of smoothing steps in one cycle, >= 1 (default 20). */
  itkSetMacro(MaximumNumberOfSmoothingSteps, unsigned int);
  itkGetConstMacro(MaximumNumberOfSmoothingSteps, unsigned int);

  /** Stop when a cycle raised the mean q_area by less than this, >= 0 (default 0.001). */
  itkSetMacro(MinimumQualityImprovement, double);
  itkGetConstMacro(MinimumQualityImprovement, double);

  /** Passed on to the edge detector (see ScaleSpaceEdgeDetectionMeshFilter). */
  itkSetMacro(MinimumScale, double);
  itkGetConstMacro(MinimumScale, double);
  itkSetMacro(NumberOfScalesPerOctave, unsigned int);
  itkGetConstMacro(NumberOfScalesPerOctave, unsigned int);
  itkSetEnumMacro(SearchDirection, EdgeSearchDirectionEnum);
  itkGetEnumMacro(SearchDirection, EdgeSearchDirectionEnum);
  itkSetMacro(SubSampleRefinement, bool);
  itkGetConstMacro(SubSampleRefinement, bool);
  itkBooleanMacro(SubSampleRefinement);

  /** Measure the inaccuracy after every ED (default on). */
  itkSetMacro(ComputeInaccuracy, bool);
  itkGetConstMacro(ComputeInaccuracy, bool);
  itkBooleanMacro(ComputeInaccuracy);

  /** Optional exact surface for the distance columns of the step table. */
  itkSetConstObjectMacro(ReferenceSurface, ImplicitSurfaceFunction);
  itkGetConstObjectMacro(ReferenceSurface, ImplicitSurfaceFunction);

  /** The step table of the last update. */
  const StepsType &
  GetSteps() const
  {
    return m_Steps;
  }
  /** Cycles made after the first ED and ES. */
  itkGetConstMacro(NumberOfCycles, unsigned int);
  /** Whether the last update ended with the mean q_area at or above TargetQuality. */
  itkGetConstMacro(TargetQualityReached, bool);

  /** Prints GetSteps() (MeshExtraction::PrintScaleSpaceRefinementTable). With a
   * finite `referenceRadius`, the distance column shows the mean radius. */
  void
  PrintSteps(std::ostream & os, double referenceRadius = std::numeric_limits<double>::quiet_NaN()) const
  {
    MeshExtraction::PrintScaleSpaceRefinementTable(os, m_Steps, referenceRadius);
  }

  /** GetSteps() as CSV with a header row (MeshExtraction::WriteScaleSpaceRefinementCSV;
   * empty fields where a quantity does not apply). For Python, where the step structure
   * is not wrapped: csv.DictReader(io.StringIO(f.GetStepsAsCSV())). */
  std::string
  GetStepsAsCSV() const
  {
    std::ostringstream os;
    MeshExtraction::WriteScaleSpaceRefinementCSV(os, m_Steps);
    return os.str();
  }

protected:
  /** The edge detector and the per-vertex smoother the protocol runs (internal:
   * itk::MeshExtraction::detail). */
  using DetectorType = MeshExtraction::detail::ScaleSpaceEdgeDetector<OutputMeshType, ImageType>;
  using SmootherType = MeshExtraction::detail::QuadEdgeMeshVertexSmoother<OutputMeshType>;

  ScaleSpaceEdgeMeshRefinementFilter();
  ~ScaleSpaceEdgeMeshRefinementFilter() override = default;
  void
  PrintSelf(std::ostream & os, Indent indent) const override;

  /** Checks, then the protocol: ED, ES, { S..., ED, ES } until the target. */
  void
  GenerateData() override;

  MeshExtraction::detail::ScaleSpaceEdgeDetectionParameters
  MakeDetectorParameters() const;

  /** The protocol's operations on the working mesh, each adding a row. */
  void
  EdgeDetection(unsigned int cycle);
  void
  EdgeSwap(unsigned int cycle);
  /** ES on a closed 2-manifold: the indexed swap engine (fast). */
  void
  ClosedSurfaceEdgeSwap(unsigned int cycle);
  /** ES on any other mesh: EdgeSwapQuadEdgeMeshFilter, which redoes cutting swaps with locked points. */
  void
  QuadEdgeEdgeSwap(unsigned int cycle);
  /** Returns the travel since the last ED. */
  double
  Smoothing(unsigned int cycle, SmootherType & smoother);

  /** Adds a row measuring the working mesh; `before` (positions in point order
   * before the step, same connectivity) gives the turned-over count. */
  StepType &
  Record(OperationEnum operation, unsigned int cycle, double seconds, const std::vector<MeshExtraction::Vec3> * before);

  std::vector<MeshExtraction::Vec3>
  Positions() const;

  /** Keeps the triangles, point identifiers and topology of `mesh`, the working mesh as
   * arrays (points in the container's order). */
  void
  SetArrays(const MeshExtraction::IndexedTriangleMesh & mesh);

private:
  double                  m_MaximumDeviation{ 0.0 };
  double                  m_TargetQuality{ 0.9 };
  unsigned int            m_MaximumNumberOfCycles{ 10 };
  unsigned int            m_MaximumNumberOfSmoothingSteps{ 20 };
  double                  m_MinimumQualityImprovement{ 0.001 };
  double                  m_MinimumScale{ 0.0 };
  unsigned int            m_NumberOfScalesPerOctave{ 4 };
  EdgeSearchDirectionEnum m_SearchDirection{ EdgeSearchDirectionEnum::ImageGradient };
  bool                    m_SubSampleRefinement{ true };
  bool                    m_ComputeInaccuracy{ true };

  ImplicitSurfaceFunction::ConstPointer m_ReferenceSurface;

  StepsType    m_Steps;
  unsigned int m_NumberOfCycles{ 0 };
  bool         m_TargetQualityReached{ false };

  // Working state of one update.
  typename OutputMeshType::Pointer             m_Working;
  DetectorType                                 m_Detector;
  std::vector<MeshExtraction::Vec3>            m_AfterEdgeDetection;
  std::vector<MeshExtraction::TriangleIndices> m_Triangles;
  std::vector<IdentifierType>                  m_PointIds; ///< of the points in container order
  MeshExtraction::MeshTopology                 m_Topology;
};
} // namespace itk

#ifndef ITK_MANUAL_INSTANTIATION
#  include "itkScaleSpaceEdgeMeshRefinementFilter.hxx"
#endif

#endif
