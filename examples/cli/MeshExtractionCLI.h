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
#ifndef MeshExtractionCLI_h
#define MeshExtractionCLI_h

// The meshextraction command-line tool: its commands and the helpers they share.
// Compiled once into the MeshExtractionCLI library (examples/CMakeLists.txt), which
// meshextraction and meshextraction-compare link:
//
//   MeshExtractionCLICommandLine.cxx   arguments, options, help of a command
//   MeshExtractionCLIHelpers.cxx       error text, phantom grid options, progress, timing
//   MeshExtractionCLIIO.cxx            images and meshes on disk, with errors that name the file
//   MeshExtractionCLIMeasurement.cxx   measuring meshes and writing the figures (table, JSON, CSV)
//   MeshExtractionCLIRender.cxx        the software renderer of `report`
//   MeshExtraction<Name>Command.cxx    one command each: phantom, extract, improve, refine,
//                                      quality, report

#include "itkImage.h"
#include "itkImageIOBase.h"
#include "itkImplicitSurfaceFunction.h"
#include "itkMesh.h"
#include "itkMeshExtractionIndexedTriangleMesh.h"
#include "itkMeshExtractionMeshFile.h"
#include "itkMeshExtractionMeshSurfaceDistanceReport.h"
#include "itkMeshExtractionPhantoms.h"
#include "itkMeshExtractionTriangleMeshQualityReport.h"
#include "itkProcessObject.h"
#include "itkQuadEdgeMesh.h"

#include <chrono>
#include <functional>
#include <iosfwd>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace MeshExtractionCLI
{
namespace ME = itk::MeshExtraction;

/** How meshes are read, written and measured: a plain itk::Mesh holds even broken meshes. */
using IOMeshType = itk::Mesh<double, 3>;
/** What `improve` and `refine` work on: a manifold, consistently oriented triangle mesh. */
using QuadEdgeMeshType = itk::QuadEdgeMesh<double, 3>;

// ------------------------------------------------------------------------------
// Command line (MeshExtractionCLICommandLine.cxx)
// ------------------------------------------------------------------------------

/** A mistake in how the tool was called: printed with the command's usage, exit 2. */
class UsageError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

/** The values a numeric option accepts (every number of a list option): printed by
 * --help and checked when the command line is parsed, so that a value out of range is
 * a usage error naming the range, never a setting a command quietly adjusts. */
struct OptionRange
{
  double minimum{ -std::numeric_limits<double>::infinity() };
  double maximum{ std::numeric_limits<double>::infinity() };
  bool   minimumExcluded{ false };
  bool   maximumExcluded{ false };

  /** [low, high] */
  static OptionRange
  Between(double low, double high);
  /** (low, high) */
  static OptionRange
  Inside(double low, double high);
  /** (low, high] */
  static OptionRange
  AboveUpTo(double low, double high);
  /** Every finite number. */
  static OptionRange
  Any();

  bool
  IsSet() const;
  bool
  Contains(double value) const;
  /** "[0, 1]", "(0, 1]", "any number" */
  std::string
  Text() const;
};

struct OptionSpec
{
  std::string name;      ///< without the leading "--"
  std::string valueName; ///< empty for a flag
  std::string help;
  std::string defaultValue;
  OptionRange range; ///< for numeric options

  OptionSpec() = default;
  OptionSpec(std::string optionName,
             std::string optionValueName,
             std::string optionHelp,
             std::string optionDefault,
             OptionRange optionRange = OptionRange())
      : name(std::move(optionName))
      , valueName(std::move(optionValueName))
      , help(std::move(optionHelp))
      , defaultValue(std::move(optionDefault))
      , range(optionRange)
  {}
};

/** A default value as an OptionSpec prints it (shortest form: 10, 0.001, -0.53), for
 * defaults taken from a filter rather than written out again. */
template <typename T>
std::string
DefaultText(T value)
{
  std::ostringstream os;
  os << value;
  return os.str();
}

/** Parsed arguments of one subcommand. */
class Arguments
{
public:
  std::vector<std::string> positional;

  bool
  Has(const std::string & name) const;
  std::string
  Get(const std::string & name, const std::string & fallback = std::string()) const;
  double
  GetDouble(const std::string & name, double fallback) const;
  long
  GetInteger(const std::string & name, long fallback) const;
  /** A list of numbers separated by 'x' or ','; a single number is repeated `count` times. */
  std::vector<double>
  GetNumbers(const std::string & name, unsigned int count) const;
  void
  Set(const std::string & name, const std::string & value);

  /** The number `text` of option --name; a UsageError if it is not a finite number. */
  static double
  ParseDouble(const std::string & name, const std::string & text);

private:
  std::map<std::string, std::string> m_Values;
};

/** A subcommand: its usage line, description, options and body. */
struct Command
{
  std::string                           name;
  std::string                           summary;
  std::string                           usage;       ///< after "meshextraction <name> "
  std::string                           description; ///< paragraphs shown by --help
  std::vector<OptionSpec>               options;
  std::function<int(const Arguments &)> run;
  unsigned int                          minimumPositional{ 0 };
  /** The 3D Slicer Execution Model description (`COMMAND --xml`), if it has one. */
  std::function<std::string()> slicerXML;
  unsigned int                 maximumPositional{ 1000 };

  void
  PrintHelp(std::ostream & os) const;
  /** The options (--name VALUE, --name=VALUE, --flag) and positional arguments; a
   * UsageError for an unknown option, a missing or unexpected value, or too few or too
   * many positional arguments. */
  Arguments
  Parse(int argc, char * argv[]) const;
};

/** The names an option accepts, each with its value. */
template <typename T>
using OptionNames = std::vector<std::pair<std::string, T>>;

/** The names of `table` joined as "a, b or c" (or "a|b|c" with `bars`). */
template <typename T>
std::string
OptionChoices(const OptionNames<T> & table, bool bars = false)
{
  std::string list;
  for (std::size_t i = 0; i < table.size(); ++i)
  {
    list += (i == 0 ? "" : (bars ? "|" : (i + 1 == table.size() ? " or " : ", "))) + table[i].first;
  }
  return list;
}

/** The name of `value` in `table`. */
template <typename T>
std::string
OptionName(const OptionNames<T> & table, T value)
{
  for (const auto & entry : table)
  {
    if (entry.second == value)
    {
      return entry.first;
    }
  }
  return "";
}

/** The value of `--name` in `table`, or `fallback`. */
template <typename T>
T
ChooseOption(const Arguments & args, const std::string & name, const OptionNames<T> & table, T fallback)
{
  if (!args.Has(name))
  {
    return fallback;
  }
  const std::string value = args.Get(name);
  for (const auto & entry : table)
  {
    if (entry.first == value)
    {
      return entry.second;
    }
  }
  throw UsageError("--" + name + " must be " + OptionChoices(table) + ", got '" + value + "'");
}

// ------------------------------------------------------------------------------
// Shared helpers (MeshExtractionCLIHelpers.cxx)
// ------------------------------------------------------------------------------

/** An ITK exception's description without ITK's "ITK ERROR: Class(0x...): " prefix. */
std::string
Describe(const itk::ExceptionObject & e);

/** A UsageError unless `output` (named `what` in the message, e.g. "OUTPUT" or
 * "--csv") is a file other than each of the `inputs` given (empty ones are skipped):
 * no command overwrites what it reads. */
void
RequireNotAnInput(const std::string & output, const std::vector<std::string> & inputs, const std::string & what);

/** --size, --spacing, --origin and --direction: the grid of a phantom. */
std::vector<OptionSpec>
GridOptions();

/** The phantom's default grid, changed by the grid options given; a UsageError for a
 * size below 2 voxels, a spacing that is not positive or a direction that is not
 * orthonormal. */
ME::PhantomGrid
GridFromArguments(ME::PhantomShape shape, const Arguments & args);

/** The phantom shape of that name; a UsageError naming the shapes otherwise. */
ME::PhantomShape
ShapeFromName(const std::string & name);

/** Prints "label: 42%" on stderr as `process` progresses, every 10%. */
void
ReportProgress(itk::ProcessObject * process, const std::string & label);

/** Wall-clock timer for messages on stderr. */
class Stopwatch
{
public:
  double
  Seconds() const;

private:
  std::chrono::steady_clock::time_point m_Start{ std::chrono::steady_clock::now() };
};

// ------------------------------------------------------------------------------
// Images and meshes on disk (MeshExtractionCLIIO.cxx). Every failure is an
// itk::ExceptionObject that names the file and the problem.
// ------------------------------------------------------------------------------

/** Reads a 3-D image from a file (any format ITK reads) or a DICOM series directory.
 * Provided for itk::Image<T, 3> with T = unsigned char, signed char, unsigned short,
 * short, float and double. */
template <typename TImage>
typename TImage::Pointer
ReadImageFile(const std::string & path);

/** Header information of an image file or DICOM directory: component type and dimension. */
itk::ImageIOBase::Pointer
ReadImageInformation(const std::string & path);

/** The DICOM series a directory is read as (SeriesInstanceUID, from --series); empty:
 * the first, with the others listed. */
void
SetDicomSeries(const std::string & uid);

/** The module's version (pyproject.toml's). */
std::string
MeshExtractionVersion();

/** ReadImageInformation of a 3-D image with one component per voxel; otherwise an
 * exception that names `path` and says what `purpose` (e.g. "SurfaceNets") needs. */
itk::ImageIOBase::Pointer
ReadScalarVolumeInformation(const std::string & path, const std::string & purpose);

/** An exception naming `path` if `image` has a voxel that is NaN or infinite, or
 * holds one value everywhere (it has no edge and no iso-surface). */
void
CheckVoxelValues(const itk::Image<float, 3> * image, const std::string & path);

/** The voxel grid (size, spacing, origin, direction) of an image on disk. */
ME::PhantomGrid
ReadImageGrid(const std::string & path);

/** Writes an output whole or not at all: `write` writes a partial file beside `path`
 * (its name keeps the extension, which names the format), which then replaces `path` in
 * one rename; if `write` throws, the partial file is removed and `path` is left as it
 * was, and the exception names `path`. */
void
WriteWhole(const std::string & path, const std::function<void(const std::string & partial)> & write);

/** An exception naming `path` if it names an HDF5 file (.h5, .hdf5) that ITK's HDF5
 * writers could not write whole: under a file-size limit or on a disk with less than
 * 64 MB free. HDF5 crashes on a write that fails part-way. */
void
RequireRoomForHDF5(const std::string & path);

/** WriteWhole for text: `write` writes to a stream, which is checked after it is
 * flushed and closed (a full disk or a size limit is an error, not a short file). */
void
WriteTextWhole(const std::string & path, const std::function<void(std::ostream & out)> & write);

/** \brief A folder of outputs (a report: a page and its pictures) made whole or not at all.
 *
 * The files are written into Path(), a hidden folder inside the target that the
 * constructor makes (with the target, if need be); Commit() moves them into the target,
 * `last` (the page that links to the others) after the rest. Without a commit (a failed
 * run) the destructor removes them, and the target keeps what it held. */
class StagedDirectory
{
public:
  explicit StagedDirectory(const std::string & directory);
  ~StagedDirectory();
  StagedDirectory(const StagedDirectory &) = delete;
  StagedDirectory &
  operator=(const StagedDirectory &) = delete;

  const std::string &
  Path() const
  {
    return m_Staging;
  }
  void
  Commit(const std::string & last = "index.html");

private:
  std::string m_Directory;
  std::string m_Staging;
};

/** Writes an image (compressed where the format allows) in the format the extension
 * names, whole or not at all (WriteWhole), except in formats whose header names a
 * separate data file (.mhd, .nhdr, .hdr), which are written in place. Provided for the
 * pixel types of ReadImageFile. */
template <typename TImage>
void
WriteImageFile(const TImage * image, const std::string & path);

/** Reads a mesh as a plain itk::Mesh, so that even broken meshes can be measured: VTK
 * legacy (4.2 and 5.1), VTP, PLY, STL, OBJ and OFF through the module's readers, which
 * refuse a truncated file, an index out of range or a coordinate that is not finite
 * with the problem; any other format ITK reads (GIFTI, BYU, FreeSurfer) through ITK. */
IOMeshType::Pointer
ReadMeshFile(const std::string & path);

/** Reads a mesh (as ReadMeshFile) into a triangle QuadEdgeMesh (quadrilaterals are
 * split along their shorter diagonal); a mesh the quad-edge structure cannot hold
 * (non-manifold edges or vertices, inconsistent orientation) is refused, before any
 * face is added, with an error that names its defects and says `command` needs one. */
QuadEdgeMeshType::Pointer
ReadManifoldMesh(const std::string & path, const std::string & command);

/** How a command writes its mesh: --mesh-encoding and --vtk-version (either one makes
 * the module, not ITK, write a .vtk file: in version 4.2 or 5.1, ASCII or binary). */
struct MeshWriteSettings
{
  ME::MeshFileWriteOptions options;
  bool                     moduleWritesVTK{ false };
};
std::vector<OptionSpec>
MeshWriteOptions();
MeshWriteSettings
ReadMeshWriteSettings(const Arguments & args);

/** Writes a mesh (a QuadEdgeMesh's edge cells are left out) in the format its
 * extension names: VTP, PLY, STL, OBJ and OFF by the module (its faces as they are,
 * except in STL, which holds only triangles), VTK legacy and the other formats by
 * ITK's mesh IO. */
void
WriteMeshFile(const IOMeshType * mesh, const std::string & path, const MeshWriteSettings & settings = {});
void
WriteMeshFile(const QuadEdgeMeshType * mesh, const std::string & path, const MeshWriteSettings & settings = {});

// ------------------------------------------------------------------------------
// Measuring meshes (MeshExtractionCLIMeasurement.cxx)
// ------------------------------------------------------------------------------

/** A mesh's quality report and, when measured against a reference, its distances. */
struct MeasuredMesh
{
  std::string                   name;
  ME::TriangleMeshQualityReport quality;
  bool                          hasDistance{ false };
  ME::MeshSurfaceDistanceReport distance;
};

/** What a measurement compares a mesh with; everything else keeps the calculators'
 * defaults. */
struct MeasureSettings
{
  /** Distances to this exact surface; else to `referenceMesh`; else none. */
  const itk::ImplicitSurfaceFunction * referenceSurface{ nullptr };
  const IOMeshType *                   referenceMesh{ nullptr };
  /** Count the triangles flipped against this mesh (same connectivity). */
  const IOMeshType * inversionReference{ nullptr };
  bool               selfIntersections{ true };
  bool               outwardOrientation{ true };
  /** Subdivisions per triangle edge for the Hausdorff samples. */
  unsigned int samplingLevel{ 2 };
};

/** Measures `mesh` with TriangleMeshQualityCalculator and, given a reference,
 * MeshSurfaceDistanceCalculator. `triangleQArea`, if given, receives each triangle's
 * q_area in the order of ME::MakeIndexedTriangleMesh. */
MeasuredMesh
MeasureMesh(const IOMeshType *      mesh,
            const std::string &     name,
            const MeasureSettings & settings = MeasureSettings(),
            std::vector<double> *   triangleQArea = nullptr);
/** The same for a QuadEdgeMesh, with distances to an exact surface only. */
MeasuredMesh
MeasureMesh(const QuadEdgeMeshType *             mesh,
            const std::string &                  name,
            const itk::ImplicitSurfaceFunction * referenceSurface = nullptr);

/** Prints the quality report (and the distances, if measured) of one mesh. */
void
PrintMeasuredMesh(const MeasuredMesh & mesh, const std::string & title, std::ostream & os);

/** A side-by-side table of several meshes. */
void
PrintComparison(const std::vector<MeasuredMesh> & meshes, std::ostream & os);

/** The reports as a JSON array. */
void
WriteJSON(const std::vector<MeasuredMesh> & meshes, const std::string & path);

/** The quality histograms (q_area, q_angle, q_length, angles, valences) as CSV. */
void
WriteHistogramsCSV(const std::vector<MeasuredMesh> & meshes, const std::string & path);

/** Text with the characters HTML gives a meaning (< > & ' ") escaped. */
std::string
HtmlEscape(const std::string & text);

// ------------------------------------------------------------------------------
// Rendering (MeshExtractionCLIRender.cxx): orthographic, z-buffered, flat-shaded
// triangles, written as PNG through ITK, without a display or OpenGL.
// ------------------------------------------------------------------------------

struct RenderOptions
{
  unsigned int width{ 640 };
  unsigned int height{ 480 };
  double       azimuthDegrees{ 35.0 };
  double       elevationDegrees{ 25.0 };
  double       zoom{ 1.0 }; ///< >1 magnifies the centre of the view
  bool         outlineTriangles{ false };
  /** Per-triangle value in [0, 1] mapped to colour (empty: grey). */
  const std::vector<double> * triangleValues{ nullptr };
};

/** Renders the mesh and writes a PNG (or any 2-D RGB format ITK writes). */
void
RenderMesh(const ME::IndexedTriangleMesh & mesh, const RenderOptions & options, const std::string & path);

// ------------------------------------------------------------------------------
// The commands (MeshExtraction<Name>Command.cxx)
// ------------------------------------------------------------------------------
Command
MakePhantomCommand();
Command
MakeMatchCommand();
Command
MakeExtractCommand();
Command
MakeImproveCommand();
Command
MakeRefineCommand();
Command
MakeQualityCommand();
Command
MakeReportCommand();
Command
MakeShapeModelCommand();

} // namespace MeshExtractionCLI

#endif
