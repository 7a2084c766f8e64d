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
#ifndef MeshExtractionIO_h
#define MeshExtractionIO_h

// Reading and writing images and meshes for the meshextraction tool, with errors
// that name the file and the problem.

#include "itkMeshExtractionIndexedTriangleMesh.h"
#include "itkMeshExtractionPhantoms.h"

#include "itkGDCMImageIO.h"
#include "itkGDCMSeriesFileNames.h"
#include "itkImageFileReader.h"
#include "itkImageFileWriter.h"
#include "itkImageIOFactory.h"
#include "itkImageSeriesReader.h"
#include "itkMesh.h"
#include "itkMeshFileReader.h"
#include "itkMeshFileWriter.h"
#include "itksys/SystemTools.hxx"

#include <string>

namespace MeshExtractionCLI
{
using IOMeshType = itk::Mesh<double, 3>;

inline bool
IsDirectory(const std::string & path)
{
  return itksys::SystemTools::FileIsDirectory(path);
}

inline void
RequireReadable(const std::string & path)
{
  if (!itksys::SystemTools::FileExists(path))
  {
    itkGenericExceptionMacro("cannot read '" << path << "': no such file or directory");
  }
}

/** The files of the first DICOM series in a directory, in slice order. */
inline std::vector<std::string>
DicomSeriesFiles(const std::string & directory)
{
  auto names = itk::GDCMSeriesFileNames::New();
  names->SetUseSeriesDetails(true);
  names->SetDirectory(directory);
  const auto & series = names->GetSeriesUIDs();
  if (series.empty())
  {
    itkGenericExceptionMacro("'" << directory << "' is a directory without a DICOM series");
  }
  return names->GetFileNames(series.front());
}

/** Reads a 3-D image from a file (any format ITK reads) or a DICOM series directory. */
template <typename TImage>
typename TImage::Pointer
ReadImageFile(const std::string & path)
{
  RequireReadable(path);
  try
  {
    if (IsDirectory(path))
    {
      using ReaderType = itk::ImageSeriesReader<TImage>;
      auto reader = ReaderType::New();
      reader->SetImageIO(itk::GDCMImageIO::New());
      reader->SetFileNames(DicomSeriesFiles(path));
      reader->Update();
      return reader->GetOutput();
    }
    auto reader = itk::ImageFileReader<TImage>::New();
    reader->SetFileName(path);
    reader->Update();
    return reader->GetOutput();
  }
  catch (const itk::ExceptionObject & e)
  {
    itkGenericExceptionMacro("cannot read image '" << path << "': " << e.GetDescription());
  }
}

/** Header information of an image file or DICOM directory: component type and dimension. */
inline itk::ImageIOBase::Pointer
ReadImageInformation(const std::string & path)
{
  RequireReadable(path);
  const std::string file = IsDirectory(path) ? DicomSeriesFiles(path).front() : path;
  auto io = itk::ImageIOFactory::CreateImageIO(file.c_str(), itk::ImageIOFactory::IOFileModeEnum::ReadMode);
  if (io.IsNull())
  {
    itkGenericExceptionMacro("cannot read image '" << path << "': not a format ITK recognises (or a corrupt file)");
  }
  io->SetFileName(file);
  try
  {
    io->ReadImageInformation();
  }
  catch (const itk::ExceptionObject & e)
  {
    itkGenericExceptionMacro("cannot read image '" << path << "': " << e.GetDescription());
  }
  return io;
}

/** The voxel grid (size, spacing, origin, direction) of an image on disk. */
inline itk::MeshExtraction::PhantomGrid
ReadImageGrid(const std::string & path)
{
  using ImageType = itk::Image<float, 3>;
  auto                             reader = itk::ImageFileReader<ImageType>::New();
  itk::MeshExtraction::PhantomGrid grid;
  if (IsDirectory(path))
  {
    auto image = ReadImageFile<ImageType>(path);
    grid.size = image->GetLargestPossibleRegion().GetSize();
    grid.spacing = image->GetSpacing();
    grid.origin = image->GetOrigin();
    grid.direction = image->GetDirection();
    return grid;
  }
  RequireReadable(path);
  reader->SetFileName(path);
  try
  {
    reader->UpdateOutputInformation();
  }
  catch (const itk::ExceptionObject & e)
  {
    itkGenericExceptionMacro("cannot read image '" << path << "': " << e.GetDescription());
  }
  const ImageType * image = reader->GetOutput();
  grid.size = image->GetLargestPossibleRegion().GetSize();
  grid.spacing = image->GetSpacing();
  grid.origin = image->GetOrigin();
  grid.direction = image->GetDirection();
  return grid;
}

template <typename TImage>
void
WriteImageFile(const TImage * image, const std::string & path)
{
  auto writer = itk::ImageFileWriter<TImage>::New();
  writer->SetFileName(path);
  writer->SetInput(image);
  writer->SetUseCompression(true);
  try
  {
    writer->Update();
  }
  catch (const itk::ExceptionObject & e)
  {
    itkGenericExceptionMacro("cannot write image '" << path << "': " << e.GetDescription());
  }
}

/** Reads a mesh in any format ITK reads (VTK, OBJ, OFF, GIFTI, BYU, FreeSurfer) as
 * a plain itk::Mesh, so that even broken meshes can be measured. */
inline IOMeshType::Pointer
ReadMeshFile(const std::string & path)
{
  RequireReadable(path);
  auto reader = itk::MeshFileReader<IOMeshType>::New();
  reader->SetFileName(path);
  try
  {
    reader->Update();
  }
  catch (const itk::ExceptionObject & e)
  {
    itkGenericExceptionMacro("cannot read mesh '" << path << "': " << e.GetDescription());
  }
  IOMeshType::Pointer mesh = reader->GetOutput();
  if (mesh->GetNumberOfPoints() == 0 || mesh->GetNumberOfCells() == 0)
  {
    itkGenericExceptionMacro("cannot read mesh '" << path << "': it has " << mesh->GetNumberOfPoints() << " points and "
                                                  << mesh->GetNumberOfCells() << " cells");
  }
  return mesh;
}

/** Writes the triangles of any ITK mesh (a QuadEdgeMesh's edge cells are left out)
 * in the format its extension names. */
template <typename TMesh>
void
WriteMeshFile(const TMesh * mesh, const std::string & path)
{
  const itk::MeshExtraction::IndexedTriangleMesh triangles = itk::MeshExtraction::MakeIndexedTriangleMesh(*mesh);
  auto                                           out = IOMeshType::New();
  itk::MeshExtraction::FillMesh(triangles, *out);
  auto writer = itk::MeshFileWriter<IOMeshType>::New();
  writer->SetFileName(path);
  writer->SetInput(out);
  try
  {
    writer->Update();
  }
  catch (const itk::ExceptionObject & e)
  {
    itkGenericExceptionMacro("cannot write mesh '" << path << "': " << e.GetDescription());
  }
}

} // namespace MeshExtractionCLI

#endif
