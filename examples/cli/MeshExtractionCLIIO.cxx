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
// Reading and writing images and meshes for the meshextraction tool, with errors
// that name the file and the problem.

#include "MeshExtractionCLI.h"

#include "itkGDCMImageIO.h"
#include "itkGDCMSeriesFileNames.h"
#include "itkImageFileReader.h"
#include "itkImageFileWriter.h"
#include "itkImageIOFactory.h"
#include "itkImageSeriesReader.h"
#include "itkMeshExtractionMeshFile.h"
#include "itkMeshExtractionWholeFile.h"
#include "itkMeshFileReader.h"
#include "itkMeshIOFactory.h"
#include "itkMeshFileWriter.h"
#include "itk_zlib.h"
#include "itksys/SystemTools.hxx"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <optional>
#include <sstream>
#include <type_traits>
#include <vector>

#include <sys/resource.h>
#include <sys/statvfs.h>

namespace MeshExtractionCLI
{
namespace
{
bool
IsDirectory(const std::string & path)
{
  return itksys::SystemTools::FileIsDirectory(path);
}

void
RequireReadable(const std::string & path)
{
  if (!itksys::SystemTools::FileExists(path))
  {
    itkGenericExceptionMacro("cannot read '" << path << "': no such file or directory");
  }
}

/** --series: the SeriesInstanceUID to read from a DICOM directory (empty: the first). */
std::string &
DicomSeriesChoice()
{
  static std::string choice;
  return choice;
}

/** The files of the first DICOM series in a directory, in slice order. */
std::vector<std::string>
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
  const std::string & chosen = DicomSeriesChoice();
  if (chosen.empty())
  {
    if (series.size() > 1)
    {
      std::cerr << "  '" << directory << "' holds " << series.size() << " DICOM series; reading the first (choose one "
                << "with --series UID):\n";
      for (const auto & uid : series)
      {
        std::cerr << "    " << uid << " (" << names->GetFileNames(uid).size() << " files)\n";
      }
    }
    return names->GetFileNames(series.front());
  }
  if (std::find(series.begin(), series.end(), chosen) == series.end())
  {
    std::ostringstream found;
    for (const auto & uid : series)
    {
      found << "\n  " << uid << " (" << names->GetFileNames(uid).size() << " files)";
    }
    itkGenericExceptionMacro("'" << directory << "' has no DICOM series " << chosen << "; it has:" << found.str());
  }
  return names->GetFileNames(chosen);
}

/** The grid of an image. */
template <typename TImage>
ME::PhantomGrid
GridOf(const TImage * image)
{
  ME::PhantomGrid grid;
  grid.size = image->GetLargestPossibleRegion().GetSize();
  grid.spacing = image->GetSpacing();
  grid.origin = image->GetOrigin();
  grid.direction = image->GetDirection();
  return grid;
}
} // namespace

// ------------------------------------------------------------------------------
// Images
// ------------------------------------------------------------------------------
namespace
{
/** Whether ITK's reader for `path` leaves the last bytes of a buffer prefilled with
 * `fill` as they were: what it does when the file ends before the voxel data its
 * header describes. Null if ITK has no reader for it (the reader reports that). */
std::optional<bool>
LeavesTheTailUnwritten(const std::string & path, unsigned char fill)
{
  auto io = itk::ImageIOFactory::CreateImageIO(path.c_str(), itk::ImageIOFactory::IOFileModeEnum::ReadMode);
  if (io.IsNull())
  {
    return std::nullopt;
  }
  io->SetFileName(path);
  io->ReadImageInformation();
  const std::size_t bytes = io->GetImageSizeInBytes();
  if (bytes == 0)
  {
    return std::nullopt;
  }
  itk::ImageIORegion region(io->GetNumberOfDimensions());
  for (unsigned int d = 0; d < io->GetNumberOfDimensions(); ++d)
  {
    region.SetIndex(d, 0);
    region.SetSize(d, io->GetDimensions(d));
  }
  io->SetIORegion(region);
  std::vector<unsigned char> buffer(bytes, fill);
  io->Read(buffer.data());
  const std::size_t tail = std::min<std::size_t>(bytes, 4096);
  return std::all_of(buffer.end() - tail, buffer.end(), [fill](unsigned char b) { return b == fill; });
}

/** Several of ITK's readers (MetaImage, NIfTI, NRRD, compressed or not) read a file
 * that ends before its voxel data does without an error, and leave the rest of the
 * image as the memory was. Reading the file into a buffer filled with a pattern, and
 * again with another, tells: a tail that keeps both patterns was never read. The
 * extra read costs a second pass over the file, which is what certainty costs
 * without a reader that reports it. */
/** The bytes a NIfTI-1 file (.nii or .nii.gz) holds after its header's vox_offset: the
 * file's size for an uncompressed file, counted through zlib for a compressed one; null
 * if it is not a NIfTI-1 single file. */
std::optional<std::uint64_t>
NiftiBytesAfterOffset(const std::string & path)
{
  gzFile file = gzopen(path.c_str(), "rb");
  if (file == nullptr)
  {
    return std::nullopt;
  }
  std::array<unsigned char, 348> header{};
  std::optional<std::uint64_t>   result;
  if (gzread(file, header.data(), 348) == 348 && std::memcmp(header.data() + 344, "n+1", 4) == 0)
  {
    std::int32_t sizeofHeader;
    float        voxOffset;
    std::memcpy(&sizeofHeader, header.data(), 4);
    if (sizeofHeader != 348) // the other byte order
    {
      std::reverse(header.begin() + 108, header.begin() + 112);
    }
    std::memcpy(&voxOffset, header.data() + 108, 4);
    std::uint64_t total = 348;
    int           got = 0;
    if (gzdirect(file))
    {
      total = itksys::SystemTools::FileLength(path);
    }
    else
    {
      std::vector<char> chunk(1 << 16);
      while ((got = gzread(file, chunk.data(), static_cast<unsigned int>(chunk.size()))) > 0)
      {
        total += static_cast<std::uint64_t>(got);
      }
    }
    if (got == 0 && voxOffset >= 348.0f)
    {
      const auto offset = static_cast<std::uint64_t>(voxOffset);
      result = total > offset ? total - offset : 0;
    }
  }
  gzclose(file);
  return result;
}

void
CheckImageDataComplete(const std::string & path)
{
  using itksys::SystemTools;
  const std::string lower = SystemTools::LowerCase(path);
  if (SystemTools::StringEndsWith(lower, ".nrrd") || SystemTools::StringEndsWith(lower, ".nhdr"))
  {
    return; // teem's reader refuses data shorter than the header says, raw or compressed
  }
  if (SystemTools::StringEndsWith(lower, ".nii") || SystemTools::StringEndsWith(lower, ".nii.gz"))
  {
    // The NIfTI reader copies whatever its library read over the whole buffer: count instead.
    auto io = itk::ImageIOFactory::CreateImageIO(path.c_str(), itk::ImageIOFactory::IOFileModeEnum::ReadMode);
    if (io.IsNull())
    {
      return;
    }
    io->SetFileName(path);
    io->ReadImageInformation();
    const std::optional<std::uint64_t> held = NiftiBytesAfterOffset(path);
    if (held && *held < static_cast<std::uint64_t>(io->GetImageSizeInBytes()))
    {
      itkGenericExceptionMacro("'" << path << "' ends before its voxel data does (a truncated or corrupt file: "
                                   << *held << " of " << io->GetImageSizeInBytes() << " bytes)");
    }
    return;
  }
  if (LeavesTheTailUnwritten(path, 0xA5).value_or(false) && LeavesTheTailUnwritten(path, 0x5A).value_or(false))
  {
    itkGenericExceptionMacro("'" << path << "' ends before its voxel data does (a truncated or corrupt file)");
  }
}
} // namespace

void
SetDicomSeries(const std::string & uid)
{
  DicomSeriesChoice() = uid;
}

std::string
MeshExtractionVersion()
{
  return MESHEXTRACTION_VERSION;
}

namespace
{
/** An exception naming what is wrong where an image's numbers are too large to
 * compute with (the extraction interpolates and differences in float; a mesh made
 * from them would hold infinities): an origin beyond +-1e9 mm, a spacing outside
 * [1e-6, 1e6] mm, a voxel of a floating-point image beyond +-1e30. */
template <typename TImage>
void
CheckImageNumbers(const TImage * image)
{
  for (unsigned int d = 0; d < 3; ++d)
  {
    if (!(std::abs(image->GetOrigin()[d]) <= 1e9))
    {
      itkGenericExceptionMacro("its origin " << image->GetOrigin() << " is beyond +-1e9 mm: too far to compute with");
    }
    if (!(image->GetSpacing()[d] >= 1e-6 && image->GetSpacing()[d] <= 1e6))
    {
      itkGenericExceptionMacro("its spacing " << image->GetSpacing() << " is outside [1e-6, 1e6] mm");
    }
  }
  using PixelType = typename TImage::PixelType;
  if constexpr (std::is_floating_point_v<PixelType>)
  {
    const PixelType * voxels = image->GetBufferPointer();
    const std::size_t count = image->GetBufferedRegion().GetNumberOfPixels();
    for (std::size_t i = 0; i < count; ++i)
    {
      if (std::isfinite(voxels[i]) && !(std::abs(static_cast<double>(voxels[i])) <= 1e30))
      {
        itkGenericExceptionMacro("voxel " << i << " of the buffer holds " << voxels[i]
                                          << ", beyond +-1e30: too large to interpolate and difference in float");
      }
    }
  }
}
} // namespace

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
      CheckImageNumbers(reader->GetOutput());
      return reader->GetOutput();
    }
    CheckImageDataComplete(path);
    auto reader = itk::ImageFileReader<TImage>::New();
    reader->SetFileName(path);
    reader->Update();
    CheckImageNumbers(reader->GetOutput());
    return reader->GetOutput();
  }
  catch (const itk::ExceptionObject & e)
  {
    itkGenericExceptionMacro("cannot read image '" << path << "': " << e.GetDescription());
  }
}

itk::ImageIOBase::Pointer
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

itk::ImageIOBase::Pointer
ReadScalarVolumeInformation(const std::string & path, const std::string & purpose)
{
  auto io = ReadImageInformation(path);
  if (io->GetNumberOfDimensions() != 3)
  {
    itkGenericExceptionMacro("'" << path << "' is a " << io->GetNumberOfDimensions() << "-D image; " << purpose
                                 << " needs a 3-D image");
  }
  if (io->GetNumberOfComponents() != 1)
  {
    itkGenericExceptionMacro("'" << path << "' has " << io->GetNumberOfComponents() << " components per voxel; "
                                 << purpose << " needs a scalar image");
  }
  for (unsigned int d = 0; d < 3; ++d)
  {
    if (io->GetDimensions(d) == 0)
    {
      itkGenericExceptionMacro("'" << path << "' has no voxels (its size is " << io->GetDimensions(0) << " x "
                                   << io->GetDimensions(1) << " x " << io->GetDimensions(2) << ")");
    }
    if (io->GetDimensions(d) == 1)
    {
      // NIfTI's reader turns a dimension of 0 or less in the header into 1.
      itkGenericExceptionMacro("'" << path << "' is one voxel thick (its size is " << io->GetDimensions(0) << " x "
                                   << io->GetDimensions(1) << " x " << io->GetDimensions(2) << "; a NIfTI header with "
                                   << "a dimension of 0 or less reads so): " << purpose
                                   << " needs at least 2 voxels along each axis");
    }
  }
  return io;
}

void
CheckVoxelValues(const itk::Image<float, 3> * image, const std::string & path)
{
  const float *     voxels = image->GetBufferPointer();
  const std::size_t count = image->GetBufferedRegion().GetNumberOfPixels();
  float             lowest = std::numeric_limits<float>::infinity();
  float             highest = -lowest;
  for (std::size_t i = 0; i < count; ++i)
  {
    if (!std::isfinite(voxels[i]))
    {
      itkGenericExceptionMacro("'" << path << "' has a voxel that is " << voxels[i] << " (voxel " << i
                                   << " of the buffer): the image must hold finite values");
    }
    lowest = std::min(lowest, voxels[i]);
    highest = std::max(highest, voxels[i]);
  }
  if (count > 0 && !(lowest < highest))
  {
    itkGenericExceptionMacro("'" << path << "' holds " << lowest << " in every voxel: a constant image has no edge");
  }
}

ME::PhantomGrid
ReadImageGrid(const std::string & path)
{
  using ImageType = itk::Image<float, 3>;
  auto reader = itk::ImageFileReader<ImageType>::New();
  if (IsDirectory(path))
  {
    auto image = ReadImageFile<ImageType>(path);
    return GridOf(image.GetPointer());
  }
  RequireReadable(path);
  ReadScalarVolumeInformation(path, "a phantom's grid");
  reader->SetFileName(path);
  try
  {
    reader->UpdateOutputInformation();
  }
  catch (const itk::ExceptionObject & e)
  {
    itkGenericExceptionMacro("cannot read image '" << path << "': " << e.GetDescription());
  }
  return GridOf(reader->GetOutput());
}

void
RequireRoomForHDF5(const std::string & path)
{
  const std::string extension = itksys::SystemTools::LowerCase(itksys::SystemTools::GetFilenameLastExtension(path));
  if (extension != ".h5" && extension != ".hdf5" && extension != ".hdf" && extension != ".he5")
  {
    return;
  }
  // HDF5 does not survive a write that fails part-way (it crashes when the file is closed
  // or at exit), so ITK's HDF5 writers get a file only where one can be written whole.
  constexpr std::uint64_t room = std::uint64_t{ 64 } << 20;
  rlimit                  limit{};
  if (getrlimit(RLIMIT_FSIZE, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY && limit.rlim_cur < room)
  {
    itkGenericExceptionMacro("cannot write '" << path << "': a file size limit of " << limit.rlim_cur
                                              << " bytes is in force, and HDF5 cannot fail a write safely (it needs "
                                              << (room >> 20) << " MB; or write another format)");
  }
  const std::string folder = itksys::SystemTools::GetFilenamePath(itksys::SystemTools::CollapseFullPath(path));
  struct statvfs    disk{};
  if (statvfs(folder.c_str(), &disk) == 0 && static_cast<std::uint64_t>(disk.f_bavail) * disk.f_frsize < room)
  {
    itkGenericExceptionMacro("cannot write '" << path << "': less than " << (room >> 20) << " MB free in '" << folder
                                              << "', and HDF5 cannot fail a write safely");
  }
}

template <typename TImage>
void
WriteImageFile(const TImage * image, const std::string & path)
{
  RequireRoomForHDF5(path);
  auto write = [image](const std::string & file) {
    auto writer = itk::ImageFileWriter<TImage>::New();
    writer->SetFileName(file);
    writer->SetInput(image);
    writer->SetUseCompression(true);
    writer->Update();
  };
  const std::string extension = itksys::SystemTools::LowerCase(itksys::SystemTools::GetFilenameLastExtension(path));
  if (extension == ".mhd" || extension == ".nhdr" || extension == ".hdr")
  {
    // The header names its data file by the name written: a renamed header would point
    // at a partial data file.
    try
    {
      write(path);
    }
    catch (const itk::ExceptionObject & e)
    {
      itkGenericExceptionMacro("cannot write image '" << path << "': " << e.GetDescription());
    }
    return;
  }
  // ITK's image writers do not all report a failed write (a full disk, a size limit):
  // the partial file is read back, with the reader's own checks, before it replaces path.
  WriteWhole(path, [&write](const std::string & partial) {
    write(partial);
    try
    {
      ReadImageFile<TImage>(partial);
    }
    catch (const itk::ExceptionObject & e)
    {
      itkGenericExceptionMacro(
        "the file written does not read back whole (disk full or a file size limit?): " << Describe(e));
    }
  });
}

// The pixel types the commands read and write.
#define MESHEXTRACTION_CLI_IMAGE_IO(TPixel)                                                                            \
  template itk::Image<TPixel, 3>::Pointer ReadImageFile<itk::Image<TPixel, 3>>(const std::string & path);              \
  template void WriteImageFile<itk::Image<TPixel, 3>>(const itk::Image<TPixel, 3> * image, const std::string & path)
MESHEXTRACTION_CLI_IMAGE_IO(unsigned char);
MESHEXTRACTION_CLI_IMAGE_IO(signed char);
MESHEXTRACTION_CLI_IMAGE_IO(unsigned short);
MESHEXTRACTION_CLI_IMAGE_IO(short);
MESHEXTRACTION_CLI_IMAGE_IO(float);
MESHEXTRACTION_CLI_IMAGE_IO(double);
#undef MESHEXTRACTION_CLI_IMAGE_IO

// ------------------------------------------------------------------------------
// Meshes
// ------------------------------------------------------------------------------
namespace
{
/** Whether the module reads and writes the format the extension names itself (VTK
 * legacy 4.2 and 5.1, VTP, PLY, STL, OBJ, OFF), checking every count, index and
 * coordinate; other formats (GIFTI, BYU, FreeSurfer) go through ITK's mesh IO. */
bool
IsModuleFormat(const std::string & path)
{
  return ME::MeshFileFormatFromFileName(path) != ME::MeshFileFormat::Unknown;
}

/** An error naming the formats there are, unless ITK's mesh IO has one for `path`
 * (which it picks by the extension or, to read, by the file's contents). */
void
RequireITKMeshIO(const std::string & path, itk::IOFileModeEnum mode)
{
  if (itk::MeshIOFactory::CreateMeshIO(path.c_str(), mode).IsNull())
  {
    itkGenericExceptionMacro("no mesh format MeshExtraction or ITK "
                             << (mode == itk::IOFileModeEnum::ReadMode ? "reads" : "writes")
                             << " goes by its name (the module: .vtk, .vtp, .ply, .stl, .obj, .off; ITK's mesh IO "
                                "also .gii, .byu, .fsa, .fsb)");
  }
}

IOMeshType::Pointer
ReadWithITK(const std::string & path)
{
  RequireITKMeshIO(path, itk::IOFileModeEnum::ReadMode);
  auto reader = itk::MeshFileReader<IOMeshType>::New();
  reader->SetFileName(path);
  reader->Update();
  return reader->GetOutput();
}
} // namespace

IOMeshType::Pointer
ReadMeshFile(const std::string & path)
{
  RequireReadable(path);
  IOMeshType::Pointer mesh;
  try
  {
    mesh = IsModuleFormat(path) ? ME::ReadSurfaceMeshFile<IOMeshType>(path) : ReadWithITK(path);
  }
  catch (const itk::ExceptionObject & e)
  {
    itkGenericExceptionMacro("cannot read mesh '" << path << "': " << Describe(e));
  }
  // ITK's mesh IO turns a coordinate beyond float range into an infinity (the module's
  // readers refuse it themselves).
  for (auto it = mesh->GetPoints()->Begin(); it != mesh->GetPoints()->End(); ++it)
  {
    const auto & p = it.Value();
    if (!(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2])))
    {
      itkGenericExceptionMacro("cannot read mesh '" << path << "': point " << it.Index()
                                                    << " has a coordinate that is not a finite float (" << p << ")");
    }
  }
  if (mesh->GetNumberOfPoints() == 0 || mesh->GetNumberOfCells() == 0)
  {
    itkGenericExceptionMacro("cannot read mesh '" << path << "': it has " << mesh->GetNumberOfPoints() << " points and "
                                                  << mesh->GetNumberOfCells() << " cells");
  }
  return mesh;
}

QuadEdgeMeshType::Pointer
ReadManifoldMesh(const std::string & path, const std::string & command)
{
  const IOMeshType::Pointer     mesh = ReadMeshFile(path);
  const ME::IndexedTriangleMesh triangles = ME::MakeIndexedTriangleMesh(*mesh);
  // Found before any face is added: ITK's QuadEdgeMesh crashes on some non-manifold
  // vertices and drops other faces.
  const ME::TriangleMeshDefects defects = ME::FindTriangleMeshDefects(triangles);
  std::string                   problem = defects.Any() ? defects.Describe(triangles) : std::string();
  auto                          out = QuadEdgeMeshType::New();
  if (problem.empty())
  {
    try
    {
      ME::FillMesh(triangles, *out);
    }
    catch (const itk::ExceptionObject & e)
    {
      problem = Describe(e);
    }
  }
  if (!problem.empty())
  {
    itkGenericExceptionMacro("'" << path << "' is not a manifold, consistently oriented triangle mesh, which '"
                                 << command << "' needs: " << problem);
  }
  return out;
}

namespace
{
/** Writes faces (quadrilaterals as they are, not split: those of --triangulation quads)
 * through a plain itk::Mesh and ITK's mesh IO. */
void
WriteWithITK(const ME::PolygonMesh & faces, const std::string & path)
{
  RequireITKMeshIO(path, itk::IOFileModeEnum::WriteMode);
  auto out = IOMeshType::New();
  ME::FillMeshWithPolygons(faces, *out);
  auto writer = itk::MeshFileWriter<IOMeshType>::New();
  writer->SetFileName(path);
  writer->SetInput(out);
  writer->Update();
}

/** Reads a file ITK's writer wrote back where the module reads its format: ITK does not
 * report a failed write, and a disk that filled up or a size limit leaves fewer points
 * or faces than were written. (The module's own writers check every write.) */
void
RequireWrittenWhole(const ME::PolygonMesh & faces, const std::string & written)
{
  if (!IsModuleFormat(written))
  {
    return;
  }
  ME::PolygonMesh back;
  try
  {
    back = ME::ReadPolygonMeshFile(written);
  }
  catch (const itk::ExceptionObject & e)
  {
    itkGenericExceptionMacro(
      "the file written does not read back whole (a full disk or a size limit?): " << Describe(e));
  }
  // STL holds triangles only, and joins its corners by their coordinates.
  const bool  stl = ME::MeshFileFormatFromFileName(written) == ME::MeshFileFormat::STL;
  std::size_t expectedFaces = faces.NumberOfPolygons();
  if (stl)
  {
    expectedFaces = 0;
    for (std::size_t f = 0; f < faces.NumberOfPolygons(); ++f)
    {
      expectedFaces += faces.PolygonSize(f) >= 3 ? faces.PolygonSize(f) - 2 : 0;
    }
  }
  if ((!stl && back.points.size() != faces.points.size()) || back.NumberOfPolygons() != expectedFaces)
  {
    itkGenericExceptionMacro("the file written holds " << back.points.size() << " points and "
                                                       << back.NumberOfPolygons() << " faces, not "
                                                       << faces.points.size() << " and " << expectedFaces);
  }
}

} // namespace

void
WriteWhole(const std::string & path, const std::function<void(const std::string & partial)> & write)
{
  ME::WriteWhole(path, write);
}

void
WriteTextWhole(const std::string & path, const std::function<void(std::ostream & out)> & write)
{
  WriteWhole(path, [&write](const std::string & partial) {
    std::ofstream out(partial);
    if (!out)
    {
      itkGenericExceptionMacro("cannot open '" << partial << "' for writing");
    }
    write(out);
    out.close();
    if (!out)
    {
      itkGenericExceptionMacro("the write failed (disk full or a file size limit?)");
    }
  });
}

namespace
{
/** Writes to a partial file beside `path`, checks it, then renames it to `path`: a
 * failed write never replaces an existing file. */
void
WriteFaces(const ME::PolygonMesh & faces, const std::string & path, const MeshWriteSettings & settings)
{
  // Said before writing: otherwise the check that the file reads back whole would
  // blame the disk.
  for (std::size_t i = 0; i < faces.points.size(); ++i)
  {
    const ME::Vec3 & p = faces.points[i];
    if (!(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2])))
    {
      itkGenericExceptionMacro("cannot write '" << path << "': point " << i << " of the mesh is (" << p[0] << ", "
                                                << p[1] << ", " << p[2]
                                                << "): the computation overflowed on numbers of the input too large "
                                                   "to compute with");
    }
  }
  ME::WriteWhole(path, [&](const std::string & partial) {
    // VTK legacy files stay ITK's, as every earlier version of the tool wrote them.
    const bool vtk = ME::MeshFileFormatFromFileName(path) == ME::MeshFileFormat::VTKLegacy;
    if (IsModuleFormat(path) && (!vtk || settings.moduleWritesVTK))
    {
      ME::WritePolygonMeshFile(partial, faces, settings.options); // fails on a failed write
    }
    else
    {
      WriteWithITK(faces, partial);
      RequireWrittenWhole(faces, partial);
    }
  });
}
} // namespace

void
WriteMeshFile(const IOMeshType * mesh, const std::string & path, const MeshWriteSettings & settings)
{
  WriteFaces(ME::MakePolygonMeshFromMesh(*mesh), path, settings);
}

void
WriteMeshFile(const QuadEdgeMeshType * mesh, const std::string & path, const MeshWriteSettings & settings)
{
  WriteFaces(ME::MakePolygonMeshFromMesh(*mesh), path, settings);
}

std::vector<OptionSpec>
MeshWriteOptions()
{
  return {
    { "mesh-encoding",
      "ascii|binary",
      "encoding of a .vtk, .vtp, .ply or .stl OUTPUT",
      "binary for .vtp, .ply, .stl; ascii for .vtk" },
    { "vtk-version", "4.2|5.1", "write a .vtk OUTPUT in this version of the legacy format (5.1: VTK 9's)", "" }
  };
}

MeshWriteSettings
ReadMeshWriteSettings(const Arguments & args)
{
  using Options = ME::MeshFileWriteOptions;
  MeshWriteSettings s;
  s.options.encoding =
    ChooseOption<Options::Encoding>(args,
                                    "mesh-encoding",
                                    { { "ascii", Options::Encoding::ASCII }, { "binary", Options::Encoding::Binary } },
                                    Options::Encoding::Default);
  s.options.vtkLegacyVersion = ChooseOption<Options::VTKLegacyVersion>(
    args,
    "vtk-version",
    { { "4.2", Options::VTKLegacyVersion::V4_2 }, { "5.1", Options::VTKLegacyVersion::V5_1 } },
    Options::VTKLegacyVersion::V4_2);
  s.moduleWritesVTK = args.Has("mesh-encoding") || args.Has("vtk-version");
  return s;
}

} // namespace MeshExtractionCLI
