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
#ifndef itkOrthogonalContourModel_h
#define itkOrthogonalContourModel_h

#include "MeshExtractionExport.h"
#include "itkContinuousIndex.h"
#include "itkDataObject.h"
#include "itkFixedArray.h"
#include "itkImageBase.h"
#include "itkMeshExtractionContourNetwork.h"
#include "itkMeshExtractionMacros.h"
#include "itkOrthogonalContourModelEnums.h"

#include <string>
#include <vector>

namespace itk
{
/** \class OrthogonalContourModel
 * \brief A closed surface shaped by planar contours in the three orthogonal planes of
 * an image's voxel grid, joined at control points (P.W. de Bruin's thesis, chapter 5:
 * interactive segmentation with connected orthogonal contours).
 *
 * Every contour lies in a plane index[axis] = position (a whole index: it passes
 * through voxel centres) and is a closed curve through its control points, straight
 * (Linear) or a centripetal Catmull-Rom spline (CatmullRom, the default), see
 * OrthogonalContourModelEnums. A control point lies exactly where two contours of
 * different axes cross: it is on both, has four neighbours (two on each), and can
 * move only along the intersection line of their two planes (Fig. 5.3b), its "line",
 * whose axis is the third one. Coordinates are continuous indices of the grid (voxel
 * units); GetControlPoint() and the mesh (OrthogonalContourModelToMeshFilter) are in
 * physical coordinates (origin, spacing and direction of the grid).
 *
 * The model starts as the three-contour template (InitializeTemplate, Fig. 5.3a) and
 * changes only through operations that keep its rules; one that would break a rule is
 * refused: it returns false, GetRefusalReason() says why, and the model is unchanged.
 * - MoveControlPoint (Fig. 5.4): along the point's line, not into or past the voxel
 *   of another control point on that line. Passing a plane that holds contours adds a
 *   contour there around the point when its four neighbours lie on its side
 *   (an indentation or a protrusion, Fig. 5.8), removes that contour again when the
 *   point goes back, and is refused when a neighbour lies on a contour of the plane
 *   (Fig. 5.9: add a contour between them first).
 * - AddContour (Figs. 5.5-5.7): a plane free of contours and control points that cuts
 *   the model in at least four points; the crossings are linked through the faces of
 *   the surface into one loop, or into concentric or disjoint loops.
 * - RemoveContour / RemoveContourPlane (section 5.2.4): all the contours of a plane,
 *   if another plane of that axis stays and every other contour keeps four points.
 * The rules (CheckInvariants() names the first one broken; empty when none is):
 * at least one contour per axis, four control points per contour; every control point
 * on exactly two contours of different axes and in no other plane that holds
 * contours; at every control point each contour crosses the other's plane; no contour
 * segment crosses a plane that holds contours away from a control point (every
 * intersection is a control point); control points on one line, and of one contour,
 * in different voxels; the contours of a plane simple and apart; the faces close a
 * sphere facing outward; the scan conversion of every contour a closed 4-connected
 * path with one point per voxel through its control points' voxels, and contours of
 * one plane sharing no voxel. The rules are those of the control polygon; the
 * interpolation shapes the curves between the control points.
 *
 * Identifiers of control points and contours are indices; AddContour, RemoveContour
 * and a MoveControlPoint that adds or removes a contour renumber them (keeping the
 * order of what stays), so look them up again after those.
 *
 * The model is saved and read as JSON (Write, Read; see
 * MeshExtraction::detail::ContourNetworkToJSON for the format). GetVolume() and
 * GetArea() measure the surface that OrthogonalContourModelToMeshFilter makes.
 *
 * \sa OrthogonalContourModelToMeshFilter, OrthogonalContourModelEdgeDetector
 * \ingroup MeshExtraction
 */
class MeshExtraction_EXPORT OrthogonalContourModel : public DataObject
{
public:
  ITK_DISALLOW_COPY_AND_MOVE(OrthogonalContourModel);

  using Self = OrthogonalContourModel;
  using Superclass = DataObject;
  using Pointer = SmartPointer<Self>;
  using ConstPointer = SmartPointer<const Self>;

  itkNewMacro(Self);
  itkOverrideGetNameOfClassMacro(OrthogonalContourModel);

  using InterpolationEnum = OrthogonalContourModelEnums::Interpolation;
  using ContinuousIndexType = ContinuousIndex<double, 3>;
  using IndexType = Index<3>;
  using PointType = Point<double, 3>;
  using SizeType = Size<3>;
  using SpacingType = Vector<double, 3>;
  using DirectionType = Matrix<double, 3, 3>;
  using RadiiType = Vector<double, 3>;
  using IdentifierListType = std::vector<unsigned int>;

  /** The voxel grid: that of `image` (its largest possible region's size; the region
   * must start at index 0), or given. Clears the contours. Throws for an invalid grid. */
  void
  SetGrid(const ImageBase<3> * image);
  void
  SetGrid(const SizeType &      size,
          const SpacingType &   spacing,
          const PointType &     origin,
          const DirectionType & direction);
  SizeType
  GetSize() const;
  SpacingType
  GetSpacing() const;
  PointType
  GetOrigin() const;
  DirectionType
  GetDirection() const;

  /** The three-contour template (Fig. 5.3a): the planes through `center` and six
   * control points at center +/- radii[a] (voxels, >= 1) along each axis a; with
   * Catmull-Rom a sphere (an ellipsoid), with straight lines an octahedron. Throws
   * when it does not fit in the grid. */
  void
  InitializeTemplate(const IndexType & center, const RadiiType & radii);

  /** Linear or CatmullRom (default). A change that would break a rule (the scan
   * conversion of the new curves) is refused: returns false. */
  bool
  SetInterpolation(InterpolationEnum interpolation);
  InterpolationEnum
  GetInterpolation() const
  {
    return m_Network.interpolation;
  }

  unsigned int
  GetNumberOfContours() const
  {
    return static_cast<unsigned int>(m_Network.contours.size());
  }
  unsigned int
  GetNumberOfControlPoints() const
  {
    return static_cast<unsigned int>(m_Network.points.size());
  }

  /** The axis (0, 1, 2) and position (whole index) of contour c's plane. */
  unsigned int
  GetContourAxis(unsigned int c) const;
  IndexValueType
  GetContourPosition(unsigned int c) const;
  /** Its control points in order around it. */
  IdentifierListType
  GetContourControlPoints(unsigned int c) const;

  /** Control point p: continuous index, physical point, the axis of its line, its two
   * contours (the one of the smaller axis first), its four neighbours (before and
   * after on the first contour, before and after on the second), and the interval of
   * coordinates along its line it may move in (the grid, short of the voxels of its
   * neighbours on the line). */
  ContinuousIndexType
  GetControlPointIndex(unsigned int p) const;
  PointType
  GetControlPoint(unsigned int p) const;
  unsigned int
  GetControlPointLineAxis(unsigned int p) const;
  FixedArray<unsigned int, 2>
  GetControlPointContours(unsigned int p) const;
  FixedArray<unsigned int, 4>
  GetControlPointNeighbours(unsigned int p) const;
  FixedArray<double, 2>
  GetControlPointRange(unsigned int p) const;

  /** The contours of the plane index[axis] = position, and their control points. */
  IdentifierListType
  GetContoursInPlane(unsigned int axis, IndexValueType position) const;
  IdentifierListType
  GetControlPointsInPlane(unsigned int axis, IndexValueType position) const;

  /** Where the contour curves cross the plane index[axis] = position (in a plane
   * without contours: the model's intersection points, which AddContour would link). */
  std::vector<ContinuousIndexType>
  GetPlaneIntersections(unsigned int axis, double position) const;

  /** Moves control point p along its line to `coordinate` (continuous index along the
   * line's axis). False, with the reason in GetRefusalReason(), if refused. */
  bool
  MoveControlPoint(unsigned int p, double coordinate);

  /** Adds the contours of the plane index[axis] = position. */
  bool
  AddContour(unsigned int axis, IndexValueType position);

  /** Removes contour c together with any other contour of its plane. */
  bool
  RemoveContour(unsigned int c);

  /** Removes the contours of the plane index[axis] = position. */
  bool
  RemoveContourPlane(unsigned int axis, IndexValueType position);

  /** Why the last operation was refused (empty after one that succeeded). */
  const std::string &
  GetRefusalReason() const
  {
    return m_RefusalReason;
  }

  /** The first rule the model breaks, or an empty string. */
  std::string
  CheckInvariants() const;

  /** The voxels of contour c's scan conversion (thesis section 5.2.2), in order around
   * it: 4-connected, one per voxel, through the voxels of its control points. */
  std::vector<IndexType>
  GetScanConversion(unsigned int c) const;

  /** Points along contour c's curve, `samplesPerSegment` per segment, continuous index. */
  std::vector<ContinuousIndexType>
  SampleContour(unsigned int c, unsigned int samplesPerSegment) const;

  /** The faces (the polygons enclosed by contour segments), each its control points
   * counter-clockwise seen from outside. */
  std::vector<IdentifierListType>
  GetFaces() const;

  /** Enclosed volume (mm^3) and area (mm^2) of the surface that
   * OrthogonalContourModelToMeshFilter makes with its default settings. */
  double
  GetVolume() const;
  double
  GetArea() const;

  /** The model as JSON text, and back (throws, leaving the model unchanged, for text
   * that is not a valid model). */
  std::string
  ToJSON() const;
  void
  FromJSON(const std::string & text, const std::string & source = "JSON text");

  /** Writes and reads the model file (JSON); throw naming the file and the problem. */
  void
  Write(const std::string & fileName) const;
  void
  Read(const std::string & fileName);

  /** Copies the whole model (grid, interpolation, contours, control points). */
  void
  DeepCopy(const OrthogonalContourModel * other);
  void
  Graft(const DataObject * data) override;
  /** Back to no contours (the grid stays). */
  void
  Initialize() override;

protected:
  OrthogonalContourModel() = default;
  ~OrthogonalContourModel() override = default;
  void
  PrintSelf(std::ostream & os, Indent indent) const override;

private:
  template <typename TOutputMesh>
  friend class OrthogonalContourModelToMeshFilter;
  using NetworkType = MeshExtraction::detail::ContourNetwork;

  /** The model's data, for the module's filters. */
  const NetworkType &
  GetNetwork() const
  {
    return m_Network;
  }

  void
  CheckControlPoint(unsigned int p) const;
  void
  CheckContour(unsigned int c) const;
  /** Records the outcome of an operation: the reason, Modified() on success. */
  bool
  Finish(const std::string & refusal);

  NetworkType m_Network;
  std::string m_RefusalReason;
};
} // namespace itk

#endif
