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
// meshextraction-compare: one input, every extraction method, one side-by-side table.
//
//   meshextraction-compare [--phantom NAME] [--size N] [--spacing S] [options]
//   meshextraction-compare IMAGE --iso V [--inside above|below] [options]
//
// The methods (the MeshExtractionVTKPeers library, peers/) are VTK's marching cubes and
// flying edges (plain and with 3D Slicer's windowed-sinc smoothing), ITK's
// BinaryMask3DMeshSource and this module's SurfaceNets (SNA, SNERT). Every mesh is
// brought into ITK physical space and measured by the module's own calculators
// (TriangleMeshQualityCalculator, MeshSurfaceDistanceCalculator).

#include "MeshExtractionCLI.h"
#include "MeshExtractionVTKPeersRunner.h"

#include "itksys/SystemTools.hxx"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>

using namespace MeshExtractionCompare;
namespace CLI = MeshExtractionCLI;

namespace
{
const char * const kProgram = "meshextraction-compare";
// The defaults the help prints and the options fall back to.
const char * const kDefaultPhantom = "sphere";
const char * const kDefaultGridSize = "128"; // this tool's default grid: 128^3
constexpr long     kDefaultRepeat = 3;

/** The keys of the methods run when --methods is not given, comma-separated. */
std::string
DefaultMethodKeys()
{
  std::string keys;
  for (const Method & m : Methods())
  {
    if (m.byDefault)
    {
      keys += (keys.empty() ? "" : ",") + m.key;
    }
  }
  return keys;
}

/** The input and everything the table's header says about it. */
struct Input
{
  ExtractionInput                       extraction;
  std::string                           description;
  ImageType::Pointer                    image;
  itk::ImplicitSurfaceFunction::Pointer exactSurface; ///< phantoms only
};

/** One row: a method's runs and their measurements. */
struct Row
{
  Method            method;
  RunRecord         run;
  CLI::MeasuredMesh measured;
};

CLI::Command
MakeCommand()
{
  CLI::Command c;
  c.name = kProgram;
  c.usage = "[IMAGE] [options]";
  c.description = "Extracts the iso-surface of one input with every method and prints a side-by-side table:\n"
                  "triangles, mean q_angle and q_area, share of triangles with q_angle < 0.3, smoothness, mean\n"
                  "and max distance of vertices and face centroids to a reference, integrity (valid closed\n"
                  "surface, non-manifold edges, boundary edges, self-intersecting pairs), wall time (best of\n"
                  "--repeat runs) and peak memory (each method in a forked child: its peak resident set minus\n"
                  "the resident set with the input loaded).\n\n"
                  "Input: a phantom (--phantom NAME, default sphere on a 128^3 grid; distance maps are\n"
                  "extracted at iso 0 with the inside below) or an IMAGE (any format ITK reads, or a DICOM\n"
                  "directory; read as float) with --iso and --inside. All methods see the same float image.\n"
                  "Reference for distances: the phantom's exact surface (default for phantoms), a mesh file\n"
                  "(--reference-mesh), the plain marching-cubes iso-surface (--reference marching-cubes), or\n"
                  "none (default for images).";
  c.options = {
    { "phantom", "NAME", "phantom input: " + ME::PhantomShapeNameList(), kDefaultPhantom },
    { "iso", "V", "iso-value (phantoms: 0 for distance maps)", "" },
    { "inside", "above|below", "which side of the iso-value is the object", "above; below for distance maps" },
    { "reference", "exact|marching-cubes|none", "reference surface for the distances", "exact / none" },
    { "reference-mesh", "FILE", "measure distances to this mesh", "" },
    { "methods", "LIST", "comma-separated method keys, or 'all' (see --list-methods)", DefaultMethodKeys() },
    { "list-methods", "", "list the methods and exit", "" },
    { "repeat", "N", "runs per method; the best wall time is reported", CLI::DefaultText(kDefaultRepeat) },
    { "threads", "N", "ITK work units and VTK SMP threads (0: all cores)", "0" },
    { "no-fork", "", "run the methods in this process (no peak-memory figures)", "" },
    { "no-self-intersections", "", "skip the self-intersection test (large meshes)", "" },
    { "csv", "FILE", "write the table (with more columns) as CSV", "" },
    { "markdown", "FILE", "write the table and its notes as Markdown", "" },
    { "write-meshes", "DIR", "write every method's mesh as DIR/<key>.vtk", "" },
  };
  for (auto o : CLI::GridOptions())
  {
    o.help += " (phantoms)";
    o.defaultValue = o.name == "size" ? kDefaultGridSize : o.defaultValue;
    c.options.push_back(o);
  }
  c.minimumPositional = 0;
  c.maximumPositional = 1;
  return c;
}

void
PrintHelp(const CLI::Command & c, std::ostream & os)
{
  os << "usage: " << kProgram << " [--phantom NAME] [--size N] [options]\n"
     << "       " << kProgram << " IMAGE --iso V [--inside above|below] [options]\n\n"
     << c.description << "\n\noptions:\n";
  for (const auto & o : c.options)
  {
    const std::string left = "  --" + o.name + (o.valueName.empty() ? "" : " " + o.valueName);
    os << std::left << std::setw(38) << left << ' ' << o.help;
    if (!o.defaultValue.empty())
    {
      os << " (default: " << o.defaultValue << ")";
    }
    os << '\n';
  }
  os << "  --help                                 show this help\n";
}

void
ListMethods(std::ostream & os)
{
  for (const Method & m : Methods())
  {
    os << std::left << std::setw(9) << m.key << std::setw(30) << m.name << (m.byDefault ? "" : "[not default] ")
       << m.description << '\n';
  }
}

// ------------------------------------------------------------------------------
// Options
// ------------------------------------------------------------------------------
std::vector<Method>
SelectMethods(const CLI::Arguments & args)
{
  std::vector<Method> selected;
  const std::string   list = args.Get("methods", "default");
  if (list == "default" || list == "all")
  {
    for (const Method & m : Methods())
    {
      if (list == "all" || m.byDefault)
      {
        selected.push_back(m);
      }
    }
    return selected;
  }
  std::stringstream in(list);
  std::string       key;
  while (std::getline(in, key, ','))
  {
    if (key.empty())
    {
      continue;
    }
    try
    {
      selected.push_back(FindMethod(key));
    }
    catch (const itk::ExceptionObject & e)
    {
      throw CLI::UsageError(CLI::Describe(e));
    }
  }
  if (selected.empty())
  {
    throw CLI::UsageError("--methods names no method");
  }
  return selected;
}

/** How the methods run. */
struct RunSettings
{
  unsigned int        repeat{ 1 };
  unsigned int        threads{ 0 };
  std::vector<Method> methods;
  bool                forked{ false };
};

RunSettings
ReadRunSettings(const CLI::Arguments & args)
{
  const long repeat = args.GetInteger("repeat", kDefaultRepeat);
  if (repeat < 1)
  {
    throw CLI::UsageError("--repeat must be >= 1");
  }
  const long threads = args.GetInteger("threads", 0);
  if (threads < 0)
  {
    throw CLI::UsageError("--threads must be >= 0");
  }
  RunSettings s;
  s.repeat = static_cast<unsigned int>(repeat);
  s.threads = static_cast<unsigned int>(threads);
  s.methods = SelectMethods(args);
  s.forked = !args.Has("no-fork") && CanMeasurePeakMemory();
  return s;
}

// ------------------------------------------------------------------------------
// The input
// ------------------------------------------------------------------------------
std::string
GridText(const ImageType & image)
{
  const auto         size = image.GetBufferedRegion().GetSize();
  const auto         spacing = image.GetSpacing();
  std::ostringstream os;
  os << size[0] << 'x' << size[1] << 'x' << size[2] << " voxels of " << spacing[0] << 'x' << spacing[1] << 'x'
     << spacing[2] << " mm";
  const auto & d = image.GetDirection();
  bool         identity = true;
  for (unsigned int r = 0; r < 3; ++r)
  {
    for (unsigned int c = 0; c < 3; ++c)
    {
      identity = identity && std::abs(d[r][c] - (r == c ? 1.0 : 0.0)) < 1e-12;
    }
  }
  if (!identity)
  {
    os << ", direction [";
    for (unsigned int r = 0; r < 3; ++r)
    {
      os << (r ? "; " : "") << d[r][0] << ' ' << d[r][1] << ' ' << d[r][2];
    }
    os << ']';
  }
  return os.str();
}

/** IMAGE with --iso (the inside above unless --inside says otherwise). */
void
LoadImageInput(const CLI::Arguments & args, Input & input)
{
  if (args.Has("phantom"))
  {
    throw CLI::UsageError("give either an IMAGE or --phantom, not both");
  }
  for (const char * option : { "size", "spacing", "origin", "direction" })
  {
    if (args.Has(option))
    {
      throw CLI::UsageError(std::string("--") + option + " applies to phantoms only");
    }
  }
  if (!args.Has("iso"))
  {
    throw CLI::UsageError("an IMAGE needs --iso V");
  }
  const std::string path = args.positional.front();
  input.image = CLI::ReadImageFile<ImageType>(path);
  input.extraction.isoValue = args.GetDouble("iso", 0.0);
  input.extraction.insideIsAboveIsoValue = true;
  input.description = path;
}

/** --phantom on this tool's default grid (or the grid options), at the iso-value its
 * image needs unless --iso is given, and its exact surface. */
void
LoadPhantomInput(const CLI::Arguments & args, Input & input)
{
  const ME::PhantomShape shape = CLI::ShapeFromName(args.Get("phantom", kDefaultPhantom));
  CLI::Arguments         gridArguments = args;
  if (!args.Has("size"))
  {
    gridArguments.Set("size", kDefaultGridSize);
  }
  const ME::PhantomGrid            grid = CLI::GridFromArguments(shape, gridArguments);
  const ME::PhantomImageParameters parameters = ME::DefaultPhantomImageParameters(shape);
  auto                             source = ME::MakePhantomImageSource<ImageType>(shape, grid, parameters);
  source->Update();
  input.image = source->GetOutput();
  input.image->DisconnectPipeline();
  input.exactSurface = ME::MakePhantomSurface(shape, grid);
  if (parameters.mode == itk::MeshExtractionEnums::PhantomImage::DistanceMap)
  {
    input.extraction.isoValue = 0.0;
    input.extraction.insideIsAboveIsoValue = parameters.distanceScale < 0.0;
  }
  else
  {
    input.extraction.isoValue = 0.5 * (parameters.insideValue + parameters.outsideValue);
    input.extraction.insideIsAboveIsoValue = parameters.insideValue > parameters.outsideValue;
  }
  input.extraction.isoValue = args.GetDouble("iso", input.extraction.isoValue);
  input.description = "phantom " + ME::PhantomShapeName(shape);
}

Input
LoadInput(const CLI::Arguments & args)
{
  Input input;
  if (!args.positional.empty())
  {
    LoadImageInput(args, input);
  }
  else
  {
    LoadPhantomInput(args, input);
  }
  if (args.Has("inside"))
  {
    const std::string side = args.Get("inside");
    if (side != "above" && side != "below")
    {
      throw CLI::UsageError("--inside must be above or below, got '" + side + "'");
    }
    input.extraction.insideIsAboveIsoValue = side == "above";
  }
  input.extraction.image = input.image;
  input.description += " (" + GridText(*input.image) + "), iso " + std::to_string(input.extraction.isoValue) +
                       ", inside " + (input.extraction.insideIsAboveIsoValue ? "above" : "below");
  return input;
}

// ------------------------------------------------------------------------------
// The reference for the distances
// ------------------------------------------------------------------------------
struct Reference
{
  std::string       kind; ///< exact, marching-cubes, mesh or none
  MeshType::Pointer mesh; ///< for mesh and marching-cubes
  std::string       text{ "none" };
};

Reference
ChooseReference(const CLI::Arguments & args, const Input & input)
{
  Reference reference;
  reference.kind = args.Get("reference", input.exactSurface ? "exact" : "none");
  if (args.Has("reference-mesh"))
  {
    if (args.Has("reference"))
    {
      throw CLI::UsageError("give either --reference or --reference-mesh, not both");
    }
    reference.kind = "mesh";
  }
  const std::string & kind = reference.kind;
  if (kind != "exact" && kind != "marching-cubes" && kind != "none" && kind != "mesh")
  {
    throw CLI::UsageError("--reference must be exact, marching-cubes or none, got '" + kind + "'");
  }
  if (kind == "exact" && !input.exactSurface)
  {
    throw CLI::UsageError("--reference exact needs a phantom; for an image use --reference-mesh FILE or "
                          "--reference marching-cubes");
  }
  if (kind == "mesh")
  {
    reference.mesh = CLI::ReadMeshFile(args.Get("reference-mesh"));
    reference.text = "the mesh " + args.Get("reference-mesh");
  }
  else if (kind == "exact")
  {
    reference.text = "the phantom's exact surface";
  }
  return reference;
}

/** --reference marching-cubes: the mesh of the "mc" row, or of a run of its own. */
void
UseMarchingCubesReference(const std::vector<Row> & rows,
                          const Input &            input,
                          const RunSettings &      settings,
                          Reference &              reference)
{
  const Row * mc = nullptr;
  for (const Row & row : rows)
  {
    mc = (row.method.key == "mc" && row.run.ok) ? &row : mc;
  }
  RunRecord computed;
  if (mc == nullptr)
  {
    computed = RunInProcess(FindMethod("mc"), input.extraction, 1, settings.threads, false);
    if (!computed.ok)
    {
      itkGenericExceptionMacro("the marching-cubes reference failed: " << computed.error);
    }
  }
  reference.mesh = MeshType::New();
  ME::FillMesh(mc != nullptr ? mc->run.mesh : computed.mesh, *reference.mesh);
  reference.text =
    "the plain vtkMarchingCubes iso-surface (" + std::to_string(reference.mesh->GetNumberOfCells()) + " triangles)";
}

// ------------------------------------------------------------------------------
// Running and measuring
// ------------------------------------------------------------------------------
std::vector<Row>
RunMethods(const Input & input, const RunSettings & settings)
{
  std::vector<Row> rows;
  for (const Method & method : settings.methods)
  {
    std::cerr << "running " << method.name << " (" << settings.repeat << "x"
              << (settings.forked ? ", in a child process" : "") << ")\n";
    Row row;
    row.method = method;
    row.run = settings.forked ? RunInChildProcess(method, input.extraction, settings.repeat, settings.threads)
                              : RunInProcess(method, input.extraction, settings.repeat, settings.threads, false);
    if (row.run.ok)
    {
      std::cerr << "  " << row.run.mesh.triangles.size() << " triangles, best " << std::fixed << std::setprecision(3)
                << row.run.BestSeconds() << " s" << std::defaultfloat << '\n';
    }
    else
    {
      std::cerr << "  failed: " << row.run.error << '\n';
    }
    rows.push_back(std::move(row));
  }
  return rows;
}

/** Measure every successful row with the module's calculators. */
void
MeasureRows(std::vector<Row> &                   rows,
            const MeshType *                     referenceMesh,
            const itk::ImplicitSurfaceFunction * referenceSurface,
            bool                                 selfIntersections)
{
  CLI::MeasureSettings settings;
  settings.referenceMesh = referenceMesh;
  settings.referenceSurface = referenceSurface;
  settings.selfIntersections = selfIntersections;
  for (Row & row : rows)
  {
    if (!row.run.ok)
    {
      continue;
    }
    CLI::Stopwatch watch;
    auto           mesh = MeshType::New();
    ME::FillMesh(row.run.mesh, *mesh);
    row.measured = CLI::MeasureMesh(mesh, row.method.name, settings);
    std::cerr << "  measured " << row.method.name << " in " << std::fixed << std::setprecision(2) << watch.Seconds()
              << " s\n"
              << std::defaultfloat;
  }
}

/** --write-meshes: every method's mesh as DIR/<key>.vtk. */
void
WriteMeshes(const std::vector<Row> & rows, const std::string & directory)
{
  itksys::SystemTools::MakeDirectory(directory);
  for (const Row & row : rows)
  {
    if (row.run.ok)
    {
      auto mesh = MeshType::New();
      ME::FillMesh(row.run.mesh, *mesh);
      CLI::WriteMeshFile(mesh.GetPointer(), directory + "/" + row.method.key + ".vtk");
    }
  }
}

// ------------------------------------------------------------------------------
// Output
// ------------------------------------------------------------------------------
std::string
Fixed(double value, int precision)
{
  std::ostringstream os;
  os << std::fixed << std::setprecision(precision) << value;
  return os.str();
}

std::string
Count(std::int64_t value)
{
  return value < 0 ? "-" : std::to_string(value);
}

/** The cells of one row, in the order of Columns(). */
struct Column
{
  std::string header;
  int         width;
};

const std::vector<Column> &
Columns()
{
  static const std::vector<Column> columns = {
    { "method", 28 },    { "triangles", 10 }, { "q_angle", 8 },    { "q_area", 8 },
    { "<0.3 %", 7 },     { "smooth", 8 },     { "vert mean", 10 }, { "vert max", 9 },
    { "face mean", 10 }, { "face max", 9 },   { "valid", 6 },      { "nm-edges", 9 },
    { "bnd-edges", 10 }, { "self-x", 7 },     { "time s", 8 },     { "peak MiB", 9 },
  };
  return columns;
}

std::vector<std::string>
Cells(const Row & row)
{
  std::vector<std::string> cells{ row.method.name };
  if (!row.run.ok)
  {
    cells.push_back("failed: " + row.run.error);
    return cells;
  }
  const auto & q = row.measured.quality;
  cells.push_back(std::to_string(q.numberOfTriangles));
  cells.push_back(Fixed(q.qAngle.mean, 4));
  cells.push_back(Fixed(q.qArea.mean, 4));
  cells.push_back(Fixed(100.0 * q.fractionQAngleBelow03, 2));
  cells.push_back(Fixed(q.meanSmoothness, 4));
  if (row.measured.hasDistance)
  {
    const auto & d = row.measured.distance;
    cells.push_back(Fixed(d.vertices.mean, 4));
    cells.push_back(Fixed(d.vertices.maximum, 3));
    cells.push_back(Fixed(d.faceCentroids.mean, 4));
    cells.push_back(Fixed(d.faceCentroids.maximum, 3));
  }
  else
  {
    cells.insert(cells.end(), 4, "-");
  }
  cells.push_back(q.IsValidClosedSurface() ? "yes" : "no");
  cells.push_back(Count(q.nonManifoldEdges));
  cells.push_back(Count(q.boundaryEdges));
  cells.push_back(Count(q.selfIntersectingPairs));
  cells.push_back(Fixed(row.run.BestSeconds(), 3));
  const double mib = row.run.ExtraPeakMiB();
  cells.push_back(mib < 0 ? "-" : Fixed(mib, 1));
  return cells;
}

/** The note on peak memory: how it is measured, or that it is not. */
std::string
MemoryNote(const std::vector<Row> & rows, bool forked)
{
  if (!forked)
  {
    return "peak MiB: not measured (--no-fork, or not Linux).";
  }
  std::string baseline;
  for (const Row & row : rows)
  {
    if (row.run.baselineKB >= 0)
    {
      baseline = Fixed(row.run.baselineKB / 1024.0, 1);
      break;
    }
  }
  return "peak MiB: extra resident memory of one run -- each method runs in a forked child process whose "
         "getrusage(RUSAGE_SELF).ru_maxrss (peak reset at the child's start via /proc/self/clear_refs) "
         "minus its resident set at the start (the input loaded, shared with the parent: " +
         baseline + " MiB). Counts the method's transient buffers and its output, not the input image.";
}

/** The notes on the methods: the threads, and each method's description and remarks. */
void
AddMethodNotes(const std::vector<Row> & rows, std::vector<std::string> & notes)
{
  for (const Row & row : rows)
  {
    if (row.run.ok && !row.run.threads.empty())
    {
      notes.push_back("threads: " + row.run.threads +
                      "; vtkMarchingCubes, vtkWindowedSincPolyDataFilter and BinaryMask3DMeshSource are serial.");
      break;
    }
  }
  for (const Row & row : rows)
  {
    std::string line = row.method.name + ": " + row.method.description;
    std::string remarks = row.run.ok ? row.run.notes : std::string();
    if (row.run.ok && row.run.droppedPoints > 0)
    {
      remarks += (remarks.empty() ? "" : "; ") + std::to_string(row.run.droppedPoints) +
                 " unreferenced points left out of the measurements";
    }
    if (!remarks.empty())
    {
      line += " [" + remarks + "]";
    }
    notes.push_back(line + ".");
  }
}

std::vector<std::string>
Notes(const Input &            input,
      const std::vector<Row> & rows,
      const std::string &      reference,
      unsigned int             repeat,
      bool                     forked)
{
  std::vector<std::string> notes;
  notes.push_back("input: " + input.description + ".");
  notes.push_back("quality: q_angle = smallest/largest angle, q_area = 4 sqrt(3) A / (sum of squared edges), means "
                  "over triangles; '<0.3 %' = share of triangles with q_angle < 0.3; smooth = mean |2 pi - sum of "
                  "angles| (radians) over interior vertices. Measured by TriangleMeshQualityCalculator on "
                  "itk::Mesh<double,3>, the same for every method.");
  notes.push_back("distances (mm) of the vertices and of the face centroids to the reference: " + reference +
                  " (MeshSurfaceDistanceCalculator).");
  notes.push_back("integrity: valid = closed, 2-manifold, consistently and outward oriented, no degenerate, inverted "
                  "or self-intersecting triangles; nm-edges = non-manifold edges; bnd-edges = boundary edges; "
                  "self-x = self-intersecting triangle pairs ('-' = not checked).");
  notes.push_back("time: wall-clock seconds, best of " + std::to_string(repeat) +
                  " runs, from the image in memory to the mesh in ITK physical space (VTK: the points mapped "
                  "through the ITK direction and origin), conversions for measurement excluded.");
  notes.push_back(MemoryNote(rows, forked));
  AddMethodNotes(rows, notes);
  return notes;
}

void
PrintTable(const std::vector<Row> & rows, const std::vector<std::string> & notes, std::ostream & os)
{
  const auto & columns = Columns();
  for (std::size_t c = 0; c < columns.size(); ++c)
  {
    os << (c == 0 ? std::left : std::right) << std::setw(columns[c].width) << columns[c].header;
  }
  os << '\n';
  for (const Row & row : rows)
  {
    const auto cells = Cells(row);
    for (std::size_t c = 0; c < cells.size(); ++c)
    {
      os << (c == 0 ? std::left : std::right) << std::setw(c < columns.size() ? columns[c].width : 0) << cells[c];
    }
    os << '\n';
  }
  os << std::right << '\n';
  for (const auto & note : notes)
  {
    os << "- " << note << '\n';
  }
}

void
WriteMarkdown(const std::vector<Row> & rows, const std::vector<std::string> & notes, const std::string & path)
{
  std::ofstream out(path);
  if (!out)
  {
    itkGenericExceptionMacro("cannot write '" << path << "'");
  }
  const auto & columns = Columns();
  out << '|';
  for (const auto & c : columns)
  {
    out << ' ' << c.header << " |";
  }
  out << "\n|";
  for (std::size_t c = 0; c < columns.size(); ++c)
  {
    out << (c == 0 ? "---|" : "---:|");
  }
  out << '\n';
  for (const Row & row : rows)
  {
    auto cells = Cells(row);
    cells.resize(columns.size());
    out << '|';
    for (const auto & cell : cells)
    {
      out << ' ' << cell << " |";
    }
    out << '\n';
  }
  out << '\n';
  for (const auto & note : notes)
  {
    out << "- " << note << '\n';
  }
}

std::string
CSVQuote(const std::string & text)
{
  std::string quoted = "\"";
  for (char c : text)
  {
    quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  }
  return quoted + '"';
}

/** The measured columns of a successful row in the CSV. */
void
WriteCSVMeasures(std::ostream & out, const Row & row)
{
  const auto & q = row.measured.quality;
  const auto & d = row.measured.distance;
  out << q.numberOfTriangles << ',' << q.numberOfReferencedPoints << ',' << q.qAngle.mean << ',' << q.qArea.mean << ','
      << q.qAngle.minimum << ',' << 100.0 * q.fractionQAngleBelow03 << ',' << q.meanSmoothness << ','
      << q.fractionValence6 << ',';
  if (row.measured.hasDistance)
  {
    out << d.vertices.mean << ',' << d.vertices.rms << ',' << d.vertices.maximum << ',' << d.vertices.signedMean << ','
        << d.faceCentroids.mean << ',' << d.faceCentroids.maximum << ',' << d.hausdorff << ',';
  }
  else
  {
    out << ",,,,,,,";
  }
  out << (q.IsValidClosedSurface() ? 1 : 0) << ',' << q.nonManifoldEdges << ',' << q.nonManifoldVertices << ','
      << q.boundaryEdges << ',' << q.selfIntersectingPairs << ',' << q.degenerateTriangles << ','
      << q.invertedTrianglesVersusOutward << ',' << q.inconsistentlyOrientedEdges << ',' << q.connectedComponents << ','
      << q.eulerCharacteristic << ',';
}

/** The timing, memory and remark columns of a successful row in the CSV. */
void
WriteCSVRun(std::ostream & out, const RunRecord & run)
{
  out << run.BestSeconds() << ',';
  std::string times;
  for (double s : run.seconds)
  {
    times += (times.empty() ? "" : " ") + Fixed(s, 4);
  }
  out << times << ',';
  const double mib = run.ExtraPeakMiB();
  if (mib >= 0)
  {
    out << mib << ',' << run.baselineKB / 1024.0;
  }
  else
  {
    out << ',';
  }
  out << ',' << run.droppedPoints << ',' << CSVQuote(run.threads) << ',' << CSVQuote(run.notes) << ",\n";
}

void
WriteCSV(const std::vector<Row> & rows, const std::string & path)
{
  std::ofstream out(path);
  if (!out)
  {
    itkGenericExceptionMacro("cannot write '" << path << "'");
  }
  out << "key,method,ok,triangles,points,mean_q_angle,mean_q_area,min_q_angle,percent_q_angle_below_0.3,"
         "mean_smoothness,fraction_valence6,vertex_distance_mean,vertex_distance_rms,vertex_distance_max,"
         "vertex_signed_mean,face_distance_mean,face_distance_max,hausdorff,valid_closed_surface,"
         "non_manifold_edges,non_manifold_vertices,boundary_edges,self_intersecting_pairs,degenerate_triangles,"
         "inverted_vs_outward,inconsistent_edges,components,euler_characteristic,time_best_s,times_s,"
         "peak_extra_mib,baseline_mib,unreferenced_points_dropped,threads,notes,error\n";
  out << std::setprecision(9);
  for (const Row & row : rows)
  {
    out << row.method.key << ',' << CSVQuote(row.method.name) << ',' << (row.run.ok ? 1 : 0) << ',';
    if (row.run.ok)
    {
      WriteCSVMeasures(out, row);
      WriteCSVRun(out, row.run);
    }
    else
    {
      out << std::string(32, ',') << CSVQuote(row.run.error) << '\n';
    }
  }
}

/** The table on stdout, and --markdown and --csv. */
void
WriteTables(const CLI::Arguments & args, const std::vector<Row> & rows, const std::vector<std::string> & notes)
{
  PrintTable(rows, notes, std::cout);
  if (args.Has("markdown"))
  {
    WriteMarkdown(rows, notes, args.Get("markdown"));
  }
  if (args.Has("csv"))
  {
    WriteCSV(rows, args.Get("csv"));
  }
}

int
Run(const CLI::Arguments & args)
{
  if (args.Has("list-methods"))
  {
    ListMethods(std::cout);
    return 0;
  }
  const RunSettings settings = ReadRunSettings(args);
  Input             input = LoadInput(args);
  std::cerr << kProgram << ": " << input.description << '\n';
  Reference reference = ChooseReference(args, input);

  std::vector<Row> rows = RunMethods(input, settings);
  if (reference.kind == "marching-cubes")
  {
    UseMarchingCubesReference(rows, input, settings, reference);
  }
  std::cerr << "measuring\n";
  MeasureRows(rows,
              reference.mesh.GetPointer(),
              reference.kind == "exact" ? input.exactSurface.GetPointer() : nullptr,
              !args.Has("no-self-intersections"));
  if (args.Has("write-meshes"))
  {
    WriteMeshes(rows, args.Get("write-meshes"));
  }
  WriteTables(args, rows, Notes(input, rows, reference.text, settings.repeat, settings.forked));
  for (const Row & row : rows)
  {
    if (!row.run.ok)
    {
      return 1;
    }
  }
  return 0;
}
} // namespace

int
main(int argc, char * argv[])
{
  const CLI::Command command = MakeCommand();
  for (int i = 1; i < argc; ++i)
  {
    if (std::string(argv[i]) == "--help" || std::string(argv[i]) == "-h")
    {
      PrintHelp(command, std::cout);
      return 0;
    }
  }
  try
  {
    return Run(command.Parse(argc - 1, argv + 1));
  }
  catch (const CLI::UsageError & e)
  {
    std::cerr << kProgram << ": " << e.what() << "\n\n";
    PrintHelp(command, std::cerr);
    return 2;
  }
  catch (const itk::ExceptionObject & e)
  {
    std::cerr << kProgram << ": error: " << CLI::Describe(e) << '\n';
    return 1;
  }
  catch (const std::exception & e)
  {
    std::cerr << kProgram << ": error: " << e.what() << '\n';
    return 1;
  }
}
