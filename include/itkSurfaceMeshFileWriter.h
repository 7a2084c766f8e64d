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
#ifndef itkSurfaceMeshFileWriter_h
#define itkSurfaceMeshFileWriter_h

#include "itkMeshExtractionEnums.h"
#include "itkMeshExtractionMacros.h"
#include "itkProcessObject.h"
#include "itkQuadEdgeMesh.h"

#include <string>

namespace itk
{
/** \class SurfaceMeshFileWriter
 * \brief Writes the faces of an itk::Mesh or itk::QuadEdgeMesh (a QuadEdgeMesh's edge
 * cells left out) in a format the module writes itself: VTK legacy (.vtk, version 4.2
 * or 5.1), VTK XML PolyData (.vtp), PLY, STL, OBJ or OFF, named by the file's
 * extension. Coordinates are written in double precision (binary STL holds single
 * precision only); quadrilaterals and larger polygons stay as they are, except in STL,
 * which holds triangles only.
 *
 * The file is written whole or not at all: into a partial file beside it, which
 * replaces FileName in one rename once every byte is written, so a full disk or a
 * failing write never leaves a truncated file or destroys the file that was there.
 *
 * Encoding: Default (ASCII for VTK legacy, OBJ and OFF; binary for VTP, PLY and STL),
 * ASCII, or Binary (not for OBJ and OFF). VTKLegacyVersion: V4_2 (default, what every
 * VTK and ITK's mesh IO read) or V5_1 (VTK 9's default).
 *
 * No input, a missing file name, an unknown extension or an encoding the format does
 * not have raises an ExceptionObject naming the problem.
 *
 * \sa SurfaceMeshFileReader
 * \ingroup MeshExtraction
 */
template <typename TInputMesh>
class ITK_TEMPLATE_EXPORT SurfaceMeshFileWriter : public ProcessObject
{
public:
  ITK_DISALLOW_COPY_AND_MOVE(SurfaceMeshFileWriter);

  using Self = SurfaceMeshFileWriter;
  using Superclass = ProcessObject;
  using Pointer = SmartPointer<Self>;
  using ConstPointer = SmartPointer<const Self>;

  itkNewMacro(Self);
  itkOverrideGetNameOfClassMacro(SurfaceMeshFileWriter);

  using InputMeshType = TInputMesh;
  using MeshFileEncodingEnum = MeshExtractionEnums::MeshFileEncoding;
  using VTKLegacyVersionEnum = MeshExtractionEnums::VTKLegacyVersion;
  static_assert(InputMeshType::PointDimension == 3, "SurfaceMeshFileWriter writes 3-D surface meshes");

  /** The mesh to write. */
  using Superclass::SetInput;
  void
  SetInput(const InputMeshType * mesh);
  const InputMeshType *
  GetInput() const;

  /** The file to write; its extension names the format. */
  itkSetStringMacro(FileName);
  itkGetStringMacro(FileName);

  itkSetEnumMacro(Encoding, MeshFileEncodingEnum);
  itkGetEnumMacro(Encoding, MeshFileEncodingEnum);

  itkSetEnumMacro(VTKLegacyVersion, VTKLegacyVersionEnum);
  itkGetEnumMacro(VTKLegacyVersion, VTKLegacyVersionEnum);

  /** Brings the input up to date and writes it. */
  virtual void
  Write();

  /** The same as Write(), so that a writer ends a pipeline like ITK's writers (and
   * Python's snake_case function, which calls UpdateLargestPossibleRegion, writes). */
  void
  Update() override
  {
    this->Write();
  }
  void
  UpdateLargestPossibleRegion() override
  {
    this->Write();
  }

protected:
  SurfaceMeshFileWriter();
  ~SurfaceMeshFileWriter() override = default;
  void
  PrintSelf(std::ostream & os, Indent indent) const override;

  void
  GenerateData() override;

private:
  std::string          m_FileName;
  MeshFileEncodingEnum m_Encoding{ MeshFileEncodingEnum::Default };
  VTKLegacyVersionEnum m_VTKLegacyVersion{ VTKLegacyVersionEnum::V4_2 };
};
} // namespace itk

#ifndef ITK_MANUAL_INSTANTIATION
#  include "itkSurfaceMeshFileWriter.hxx"
#endif

#endif
