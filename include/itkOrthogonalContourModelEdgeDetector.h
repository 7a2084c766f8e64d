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
#ifndef itkOrthogonalContourModelEdgeDetector_h
#define itkOrthogonalContourModelEdgeDetector_h

#include "itkMeshExtractionGaussianScaleSpace.h"
#include "itkObject.h"
#include "itkOrthogonalContourModel.h"

#include <vector>

namespace itk
{
/** \class OrthogonalContourModelEdgeDetector
 * \brief Edge-detection assisted moves of an OrthogonalContourModel's control points
 * (EDEMS, thesis section 5.2.5): each control point moves along its line to the
 * largest gradient magnitude of the image within CaptureRange.
 *
 * The search is that of chapter 4 (ScaleSpaceEdgeDetectionMeshFilter): the gradient
 * magnitude of the image convolved with ITK's Gaussian derivative operators, sampled
 * at five points of a window that shrinks from scale CaptureRange down to
 * MinimumScale (ScalesPerOctave scales per doubling), coarse to fine, refined to a
 * parabola's vertex at the finest scale. Here the line of the search is the control
 * point's own line (the intersection of its two contours' planes), the only direction
 * the model lets it move in.
 *
 * A move goes through OrthogonalContourModel::MoveControlPoint: it stops short of the
 * neighbours on the line (the target is clamped to GetControlPointRange), may add or
 * remove a contour as a manual move would, and is skipped when the model refuses it
 * (counted in GetNumberOfRefusedMoves). The targets of a call are all found before the
 * first move, so the order of the points does not matter.
 *
 * The model's grid must be the image's (size, spacing, origin, direction).
 *
 * \sa OrthogonalContourModel, ScaleSpaceEdgeDetectionMeshFilter
 * \ingroup MeshExtraction
 */
template <typename TImage>
class ITK_TEMPLATE_EXPORT OrthogonalContourModelEdgeDetector : public Object
{
public:
  ITK_DISALLOW_COPY_AND_MOVE(OrthogonalContourModelEdgeDetector);

  using Self = OrthogonalContourModelEdgeDetector;
  using Superclass = Object;
  using Pointer = SmartPointer<Self>;
  using ConstPointer = SmartPointer<const Self>;

  itkNewMacro(Self);
  itkOverrideGetNameOfClassMacro(OrthogonalContourModelEdgeDetector);

  using ImageType = TImage;
  using ModelType = OrthogonalContourModel;
  using IdentifierListType = ModelType::IdentifierListType;
  static_assert(ImageType::ImageDimension == 3, "OrthogonalContourModelEdgeDetector works on 3-D images");

  itkSetConstObjectMacro(Image, ImageType);
  itkGetConstObjectMacro(Image, ImageType);
  itkSetObjectMacro(Model, ModelType);
  itkGetModifiableObjectMacro(Model, ModelType);

  /** How far a point may move (mm) and the largest scale. Required, > 0. */
  itkSetMacro(CaptureRange, double);
  itkGetConstMacro(CaptureRange, double);
  /** The smallest scale, mm; 0 (default): the smallest voxel spacing. */
  itkSetMacro(MinimumScale, double);
  itkGetConstMacro(MinimumScale, double);
  itkSetMacro(ScalesPerOctave, unsigned int);
  itkGetConstMacro(ScalesPerOctave, unsigned int);

  /** The coordinate along its line (continuous index) of the edge found for control
   * point p, within its range. */
  double
  FindEdge(unsigned int p);

  /** Moves the control points `points` to their edges; returns how many moved. */
  unsigned int
  MoveControlPoints(const IdentifierListType & points);
  /** All control points of the plane index[axis] = position (the active view). */
  unsigned int
  MoveControlPointsInPlane(unsigned int axis, IndexValueType position);
  /** Every control point of the model. */
  unsigned int
  MoveAllControlPoints();

  /** Of the last Move... call: the moves the model refused, and the distance the
   * points travelled along their lines (voxels). */
  itkGetConstMacro(NumberOfRefusedMoves, unsigned int);
  itkGetConstMacro(DistanceTravelled, double);

protected:
  OrthogonalContourModelEdgeDetector() = default;
  ~OrthogonalContourModelEdgeDetector() override = default;
  void
  PrintSelf(std::ostream & os, Indent indent) const override;

private:
  /** Throws for a missing image or model, a bad parameter, or grids that differ. */
  void
  CheckInputs() const;
  /** The scale space over the box of `points` plus the capture range. */
  void
  PrepareScaleSpace(const IdentifierListType & points);
  /** The edge of point p with the scale space prepared. */
  double
  SearchEdge(unsigned int p) const;

  typename ImageType::ConstPointer                                    m_Image;
  ModelType::Pointer                                                  m_Model;
  double                                                              m_CaptureRange{ 0.0 };
  double                                                              m_MinimumScale{ 0.0 };
  unsigned int                                                        m_ScalesPerOctave{ 4 };
  unsigned int                                                        m_NumberOfRefusedMoves{ 0 };
  double                                                              m_DistanceTravelled{ 0.0 };
  std::vector<double>                                                 m_Scales;
  MeshExtraction::detail::GaussianGradientMagnitudeScaleSpace<TImage> m_ScaleSpace;
};
} // namespace itk

#ifndef ITK_MANUAL_INSTANTIATION
#  include "itkOrthogonalContourModelEdgeDetector.hxx"
#endif

#endif
