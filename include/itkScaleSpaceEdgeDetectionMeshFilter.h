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
#ifndef itkScaleSpaceEdgeDetectionMeshFilter_h
#define itkScaleSpaceEdgeDetectionMeshFilter_h

#include "itkMeshExtractionEnums.h"
#include "itkMeshExtractionMacros.h"
#include "itkMeshExtractionScaleSpaceEdgeDetector.h"
#include "itkQuadEdgeMeshToQuadEdgeMeshFilter.h"

namespace itk
{
/** \class ScaleSpaceEdgeDetectionMeshFilter
 * \brief One scale-space edge-detection step (ED): every vertex of a triangle mesh
 * moves to the edge of the object found coarse-to-fine in a Gaussian scale space of
 * the image (P.W. de Bruin's thesis, sections 2.1.3, 4.2.1 and 4.2.3).
 *
 * Inputs: the mesh (SetInput) and a 3-D scalar image (SetInputImage) in the same
 * physical space. For every vertex:
 * - the search line passes through it along the image gradient at the vertex, the
 *   Gaussian derivative at the largest scale (SearchDirection ImageGradient, default),
 *   or along the area-weighted vertex normal (VertexNormal); where the gradient
 *   vanishes the normal is used (counted by GetNumberOfNormalFallbacks());
 * - the scales run from sigma_max = MaximumDeviation (the capture range: the largest
 *   distance between the mesh and the edge, a required parameter) down to sigma_min =
 *   MinimumScale (default 0: the voxel length, the smallest spacing), sampled
 *   logarithmically with NumberOfScalesPerOctave per doubling (default 4; the thesis
 *   gives the rule sigma_i = 2^(i/n) but no value of n), see
 *   MeshExtraction::detail::ScaleSpaceScales();
 * - at each scale the Gaussian gradient magnitude is sampled at five points 0.5 sigma
 *   apart in a window of width 2 sigma centred on the current estimate; the largest
 *   centres the next scale's window; a window that would leave the capture range
 *   [-MaximumDeviation, MaximumDeviation] is translated back along the line. The
 *   vertex moves to the final estimate: with SubSampleRefinement (default on, beyond
 *   the thesis) to the vertex of the parabola through the finest scale's largest
 *   sample and its neighbours; without it to that sample (the thesis' detector,
 *   uncertainty half a step, 0.25 sigma_min).
 *
 * Scales and distances are physical (mm): the Gaussian is isotropic in physical space
 * on anisotropic voxels, and the direction matrix is honoured. The gradient
 * magnitudes are separable convolutions of the mesh's region of the image with ITK's
 * GaussianDerivativeOperator kernels (MeshExtraction::detail::GaussianGradientMagnitudeScaleSpace),
 * computed once and kept for later updates while the image and the scales stay the
 * same and the mesh stays in the region; ReleaseScaleSpace() frees them.
 *
 * The searches run on ITK's multithreader (the ProcessObject's NumberOfWorkUnits); the
 * moves are then applied one by one in point order, each through the no-inversion
 * guard of LaplacianSmoothingQuadEdgeMeshFilter (PreventInversions, default on): a
 * move that would turn an incident triangle by 90 degrees or more, or make it
 * degenerate (q_area <= DegenerateQAreaTolerance, default 1e-4), is halved up to
 * MaximumNumberOfShortenings times (default 5) and otherwise rejected. As that guard
 * sees one vertex at a time, the moved triangles are then tested against the whole
 * mesh with exact predicates: the vertices of a triangle that now intersects another
 * one (a fold, or the surface passing through itself) or is turned over go back to
 * where they were, repeatedly, until none is left (GetNumberOfUndoneMoves()). So a
 * valid input gives a valid output. The result does not depend on the number of
 * threads.
 *
 * With ComputeInaccuracy (default on) the detector is also run from every triangle
 * centroid of the result: GetInaccuracy() is the mean distance from the centroids to
 * the edge (thesis section 4.2.3), GetMaximumInaccuracy() the largest.
 *
 * The connectivity, point identifiers and point data are those of the input. A
 * missing image, an empty mesh, a face that is not a triangle, a vertex outside the
 * image or a parameter out of range raises an ExceptionObject that names it.
 *
 * \sa ScaleSpaceEdgeMeshRefinementFilter
 * \ingroup MeshExtraction
 */
template <typename TInputMesh, typename TImage, typename TOutputMesh = TInputMesh>
class ITK_TEMPLATE_EXPORT ScaleSpaceEdgeDetectionMeshFilter
    : public QuadEdgeMeshToQuadEdgeMeshFilter<TInputMesh, TOutputMesh>
{
public:
  ITK_DISALLOW_COPY_AND_MOVE(ScaleSpaceEdgeDetectionMeshFilter);

  using Self = ScaleSpaceEdgeDetectionMeshFilter;
  using Superclass = QuadEdgeMeshToQuadEdgeMeshFilter<TInputMesh, TOutputMesh>;
  using Pointer = SmartPointer<Self>;
  using ConstPointer = SmartPointer<const Self>;

  itkOverrideGetNameOfClassMacro(ScaleSpaceEdgeDetectionMeshFilter);
  itkNewMacro(Self);

  using InputMeshType = TInputMesh;
  using OutputMeshType = TOutputMesh;
  using ImageType = TImage;
  using EdgeSearchDirectionEnum = MeshExtractionEnums::EdgeSearchDirection;

  static_assert(OutputMeshType::PointDimension == 3, "ScaleSpaceEdgeDetectionMeshFilter works on 3-D surface meshes");
  static_assert(ImageType::ImageDimension == 3, "ScaleSpaceEdgeDetectionMeshFilter needs a 3-D image");

  /** The image whose edges the vertices move to. */
  itkSetInputMacro(InputImage, ImageType);
  itkGetInputMacro(InputImage, ImageType);

  /** The capture range and largest scale, mm, > 0 (required; default 0). */
  itkSetMacro(MaximumDeviation, double);
  itkGetConstMacro(MaximumDeviation, double);

  /** The smallest scale, mm, >= 0 (default 0: the voxel length, the smallest spacing). */
  itkSetMacro(MinimumScale, double);
  itkGetConstMacro(MinimumScale, double);

  /** Scales per doubling of sigma, >= 1 (default 4). */
  itkSetMacro(NumberOfScalesPerOctave, unsigned int);
  itkGetConstMacro(NumberOfScalesPerOctave, unsigned int);

  /** ImageGradient (default) or VertexNormal. */
  itkSetEnumMacro(SearchDirection, EdgeSearchDirectionEnum);
  itkGetEnumMacro(SearchDirection, EdgeSearchDirectionEnum);

  /** Refine the finest scale's maximum to the vertex of the parabola through it and
   * its two neighbours (default on; beyond the thesis, whose five samples leave an
   * uncertainty of 0.25 sigma_min: off reproduces the thesis' detector exactly). */
  itkSetMacro(SubSampleRefinement, bool);
  itkGetConstMacro(SubSampleRefinement, bool);
  itkBooleanMacro(SubSampleRefinement);

  /** The no-inversion guard (default on). */
  itkSetMacro(PreventInversions, bool);
  itkGetConstMacro(PreventInversions, bool);
  itkBooleanMacro(PreventInversions);

  /** How often the guard halves a move before rejecting it (default 5). */
  itkSetMacro(MaximumNumberOfShortenings, unsigned int);
  itkGetConstMacro(MaximumNumberOfShortenings, unsigned int);

  /** q_area at or below which the guard counts a triangle as degenerate, in [0, 1)
   * (default 1e-4). */
  itkSetMacro(DegenerateQAreaTolerance, double);
  itkGetConstMacro(DegenerateQAreaTolerance, double);

  /** Measure the inaccuracy after the step (default on). */
  itkSetMacro(ComputeInaccuracy, bool);
  itkGetConstMacro(ComputeInaccuracy, bool);
  itkBooleanMacro(ComputeInaccuracy);

  /** Results of the last update. */
  const MeshExtraction::ScaleSpaceEdgeDetectionResult &
  GetResult() const
  {
    return m_Result;
  }
  /** The scales used, coarse to fine, mm. */
  const std::vector<double> &
  GetScales() const
  {
    return m_Result.scales;
  }
  SizeValueType
  GetNumberOfMovedVertices() const
  {
    return static_cast<SizeValueType>(m_Result.movedVertices);
  }
  SizeValueType
  GetNumberOfShortenedMoves() const
  {
    return static_cast<SizeValueType>(m_Result.shortenedMoves);
  }
  SizeValueType
  GetNumberOfRejectedMoves() const
  {
    return static_cast<SizeValueType>(m_Result.rejectedMoves);
  }
  SizeValueType
  GetNumberOfUndoneMoves() const
  {
    return static_cast<SizeValueType>(m_Result.undoneMoves);
  }
  SizeValueType
  GetNumberOfNormalFallbacks() const
  {
    return static_cast<SizeValueType>(m_Result.normalFallbacks);
  }
  double
  GetMeanDisplacement() const
  {
    return m_Result.meanDisplacement;
  }
  double
  GetMaximumDisplacement() const
  {
    return m_Result.maximumDisplacement;
  }
  /** Mean distance from the triangle centroids to the detected edge (NaN without
   * ComputeInaccuracy). */
  double
  GetInaccuracy() const
  {
    return m_Result.inaccuracy;
  }
  double
  GetMaximumInaccuracy() const
  {
    return m_Result.maximumInaccuracy;
  }

  /** Frees the kept scale space. */
  void
  ReleaseScaleSpace()
  {
    m_Detector.ReleaseScaleSpace();
  }

protected:
  /** The edge detector the filter runs (internal: itk::MeshExtraction::detail). */
  using DetectorType = MeshExtraction::detail::ScaleSpaceEdgeDetector<OutputMeshType, ImageType>;

  ScaleSpaceEdgeDetectionMeshFilter();
  ~ScaleSpaceEdgeDetectionMeshFilter() override = default;
  void
  PrintSelf(std::ostream & os, Indent indent) const override;

  /** Checks the parameters and inputs, copies the mesh, then one detection step. */
  void
  GenerateData() override;

  MeshExtraction::detail::ScaleSpaceEdgeDetectionParameters
  MakeParameters() const;

private:
  double                  m_MaximumDeviation{ 0.0 };
  double                  m_MinimumScale{ 0.0 };
  unsigned int            m_NumberOfScalesPerOctave{ 4 };
  EdgeSearchDirectionEnum m_SearchDirection{ EdgeSearchDirectionEnum::ImageGradient };
  bool                    m_SubSampleRefinement{ true };
  bool                    m_PreventInversions{ true };
  unsigned int            m_MaximumNumberOfShortenings{ 5 };
  double                  m_DegenerateQAreaTolerance{ 1e-4 };
  bool                    m_ComputeInaccuracy{ true };

  DetectorType                                  m_Detector;
  MeshExtraction::ScaleSpaceEdgeDetectionResult m_Result;
};
} // namespace itk

#ifndef ITK_MANUAL_INSTANTIATION
#  include "itkScaleSpaceEdgeDetectionMeshFilter.hxx"
#endif

#endif
