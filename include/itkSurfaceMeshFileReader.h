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
#ifndef itkSurfaceMeshFileReader_h
#define itkSurfaceMeshFileReader_h

#include "itkMeshExtractionMacros.h"
#include "itkMeshSource.h"
#include "itkQuadEdgeMesh.h"

#include <string>

namespace itk
{
/** \class SurfaceMeshFileReader
 * \brief Reads a surface mesh file the module parses itself: VTK legacy (4.2 and 5.1,
 * ASCII and binary), VTK XML PolyData (.vtp), PLY, STL, OBJ and OFF, named by the
 * file's extension (see MeshExtraction::MeshFileFormat).
 *
 * Into an itk::Mesh the polygons come as they are (triangle, quadrilateral and polygon
 * cells; point i and cell p get identifiers i and p). Into an itk::QuadEdgeMesh they
 * are triangulated (quadrilaterals along their shorter diagonal) and refused, before
 * any face is added, unless they make a manifold, consistently oriented surface:
 * ITK's MeshFileReader cannot make a QuadEdgeMesh, and ITK's QuadEdgeMesh would drop
 * such faces without a word. Vertex and line cells of the file are not part of the
 * surface; they are counted (GetNumberOfIgnoredCells).
 *
 * A missing file name, an unknown extension, an unreadable, truncated or malformed
 * file (an index out of range, a coordinate that is not finite) raises an
 * ExceptionObject naming the file and the problem.
 *
 * \sa SurfaceMeshFileWriter
 * \ingroup MeshExtraction
 */
template <typename TOutputMesh = QuadEdgeMesh<double, 3>>
class ITK_TEMPLATE_EXPORT SurfaceMeshFileReader : public MeshSource<TOutputMesh>
{
public:
  ITK_DISALLOW_COPY_AND_MOVE(SurfaceMeshFileReader);

  using Self = SurfaceMeshFileReader;
  using Superclass = MeshSource<TOutputMesh>;
  using Pointer = SmartPointer<Self>;
  using ConstPointer = SmartPointer<const Self>;

  itkNewMacro(Self);
  itkOverrideGetNameOfClassMacro(SurfaceMeshFileReader);

  using OutputMeshType = TOutputMesh;
  static_assert(OutputMeshType::PointDimension == 3, "SurfaceMeshFileReader reads 3-D surface meshes");

  /** The file to read; its extension names the format. */
  itkSetStringMacro(FileName);
  itkGetStringMacro(FileName);

  /** The vertex and line cells of the last file read, which are not part of a surface. */
  itkGetConstMacro(NumberOfIgnoredCells, SizeValueType);

protected:
  SurfaceMeshFileReader() = default;
  ~SurfaceMeshFileReader() override = default;
  void
  PrintSelf(std::ostream & os, Indent indent) const override;

  void
  GenerateData() override;

private:
  std::string   m_FileName;
  SizeValueType m_NumberOfIgnoredCells{ 0 };
};
} // namespace itk

#ifndef ITK_MANUAL_INSTANTIATION
#  include "itkSurfaceMeshFileReader.hxx"
#endif

#endif
