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
#ifndef itkOrthogonalContourModelToMeshFilter_h
#define itkOrthogonalContourModelToMeshFilter_h

#include "itkMeshExtractionMacros.h"
#include "itkMeshSource.h"
#include "itkOrthogonalContourModel.h"
#include "itkQuadEdgeMesh.h"

namespace itk
{
/** \class OrthogonalContourModelToMeshFilter
 * \brief The closed surface of an OrthogonalContourModel as a triangle mesh (thesis
 * section 5.2.2: the polygons enclosed by contour segments, triangulated), an initial
 * mesh for ScaleSpaceEdgeMeshRefinementFilter (chapter 4).
 *
 * Every contour segment (the curve between two consecutive control points) is cut
 * into pieces of about TargetEdgeLength; each face of the model (a polygon of contour
 * segments) is filled with rings of points about TargetEdgeLength apart, placed by the
 * mean value coordinates of its boundary mapped onto a circle (a smooth patch through
 * the boundary), and the rings are zipped into triangles. The pieces of a segment are
 * shared by its two faces, so the mesh is closed and 2-manifold (a sphere: V - E + F =
 * 2), and its triangles turn counter-clockwise seen from outside (normals outward).
 * The first points are the model's control points, in order. Coordinates are physical
 * (the model's grid: origin, spacing, direction).
 *
 * TargetEdgeLength is in mm; 0 (default) means 1.5 times the smallest voxel spacing.
 * A missing or empty model, or one that breaks its rules, raises an ExceptionObject.
 *
 * \sa OrthogonalContourModel, ScaleSpaceEdgeMeshRefinementFilter
 * \ingroup MeshExtraction
 */
template <typename TOutputMesh = QuadEdgeMesh<double, 3>>
class ITK_TEMPLATE_EXPORT OrthogonalContourModelToMeshFilter : public MeshSource<TOutputMesh>
{
public:
  ITK_DISALLOW_COPY_AND_MOVE(OrthogonalContourModelToMeshFilter);

  using Self = OrthogonalContourModelToMeshFilter;
  using Superclass = MeshSource<TOutputMesh>;
  using Pointer = SmartPointer<Self>;
  using ConstPointer = SmartPointer<const Self>;

  itkNewMacro(Self);
  itkOverrideGetNameOfClassMacro(OrthogonalContourModelToMeshFilter);

  using OutputMeshType = TOutputMesh;
  using ModelType = OrthogonalContourModel;

  static_assert(OutputMeshType::PointDimension == 3, "OrthogonalContourModelToMeshFilter makes 3-D surface meshes");

  /** The model. */
  using Superclass::SetInput;
  virtual void
  SetInput(const ModelType * model);
  const ModelType *
  GetInput() const;

  /** The length of the triangles' edges, mm, >= 0 (0: 1.5 times the smallest spacing). */
  itkSetMacro(TargetEdgeLength, double);
  itkGetConstMacro(TargetEdgeLength, double);

protected:
  OrthogonalContourModelToMeshFilter();
  ~OrthogonalContourModelToMeshFilter() override = default;
  void
  PrintSelf(std::ostream & os, Indent indent) const override;

  void
  GenerateData() override;

private:
  double m_TargetEdgeLength{ 0.0 };
};
} // namespace itk

#ifndef ITK_MANUAL_INSTANTIATION
#  include "itkOrthogonalContourModelToMeshFilter.hxx"
#endif

#endif
