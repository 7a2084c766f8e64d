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
#ifndef itkSurfaceMeshConvertFilter_h
#define itkSurfaceMeshConvertFilter_h

#include "itkMeshExtractionMacros.h"
#include "itkMeshSource.h"
#include "itkQuadEdgeMesh.h"

namespace itk
{
/** \class SurfaceMeshConvertFilter
 * \brief Copies the points and faces of a surface mesh into another mesh type:
 * itk::QuadEdgeMesh (what the module's mesh filters take) to itk::Mesh (what ITK's mesh
 * IO, itk.meshwrite and ITK's NumPy helpers take) and back.
 *
 * The points keep their order (compacted to identifiers 0..n-1 in the order of the
 * point container) and the faces their corners and orientation. Vertex and line cells
 * (a QuadEdgeMesh's edges) are not faces and are left out. Into an itk::Mesh, faces
 * come as they are (triangles, quadrilaterals, polygons); into an itk::QuadEdgeMesh they
 * are triangulated (quadrilaterals along their shorter diagonal), and a set of faces
 * that is not manifold or not consistently oriented is refused with the reasons,
 * before any face is added, instead of the faces ITK's QuadEdgeMesh would drop.
 *
 * No input, or a face naming a point the mesh has not, raises an ExceptionObject.
 *
 * \ingroup MeshExtraction
 */
template <typename TInputMesh, typename TOutputMesh = QuadEdgeMesh<double, 3>>
class ITK_TEMPLATE_EXPORT SurfaceMeshConvertFilter : public MeshSource<TOutputMesh>
{
public:
  ITK_DISALLOW_COPY_AND_MOVE(SurfaceMeshConvertFilter);

  using Self = SurfaceMeshConvertFilter;
  using Superclass = MeshSource<TOutputMesh>;
  using Pointer = SmartPointer<Self>;
  using ConstPointer = SmartPointer<const Self>;

  itkNewMacro(Self);
  itkOverrideGetNameOfClassMacro(SurfaceMeshConvertFilter);

  using InputMeshType = TInputMesh;
  using OutputMeshType = TOutputMesh;
  static_assert(InputMeshType::PointDimension == 3 && OutputMeshType::PointDimension == 3,
                "SurfaceMeshConvertFilter converts 3-D surface meshes");

  /** The mesh to convert. */
  using Superclass::SetInput;
  void
  SetInput(const InputMeshType * mesh);
  const InputMeshType *
  GetInput() const;

protected:
  SurfaceMeshConvertFilter();
  ~SurfaceMeshConvertFilter() override = default;

  /** The input is another mesh type, whose information PointSet::CopyInformation
   * cannot take: nothing to copy. */
  void
  GenerateOutputInformation() override
  {}

  void
  GenerateData() override;
};
} // namespace itk

#ifndef ITK_MANUAL_INSTANTIATION
#  include "itkSurfaceMeshConvertFilter.hxx"
#endif

#endif
