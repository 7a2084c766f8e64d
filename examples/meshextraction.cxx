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
// meshextraction: the MeshExtraction module's command-line tool.
//
//   meshextraction phantom NAME OUT.nrrd [options]   write a phantom image
//   meshextraction quality MESH... [options]         measure meshes
//
// Run `meshextraction COMMAND --help` for the options of each command.

#include "MeshExtractionCommandLine.h"
#include "MeshExtractionIO.h"

#include "itkImplicitSurfaceImageSource.h"
#include "itkMeshExtractionPhantoms.h"
#include "itkMeshSurfaceDistanceCalculator.h"
#include "itkTriangleMeshQualityCalculator.h"

#include <fstream>

using namespace MeshExtractionCLI;
namespace ME = itk::MeshExtraction;

namespace
{
/** An ITK exception's description without ITK's "ITK ERROR: Class(0x...): " prefix. */
std::string
Describe(const itk::ExceptionObject & e)
{
  std::string text = e.GetDescription();
  const std::string prefix = "ITK ERROR: ";
  if (text.compare(0, prefix.size(), prefix) == 0)
  {
    text = text.substr(prefix.size());
  }
  const auto open = text.find("(0x");
  const auto close = text.find("): ");
  if (open != std::string::npos && close != std::string::npos && open < close && text.find(' ') > open)
  {
    text = text.substr(close + 3);
  }
  return text;
}

// ------------------------------------------------------------------------------
// Shared option groups
// ------------------------------------------------------------------------------
std::vector<OptionSpec>
GridOptions()
{
  return { { "size", "N|NxNxN", "phantom grid size in voxels", "per phantom, e.g. 64" },
           { "spacing", "S|SxSxS", "voxel spacing in mm", "1" },
           { "origin", "X,Y,Z", "physical position of voxel (0,0,0)", "0,0,0" },
           { "direction", "9 NUMBERS", "direction cosine matrix, row by row", "identity" } };
}

ME::PhantomGrid
GridFromArguments(ME::PhantomShape shape, const Arguments & args)
{
  ME::PhantomGrid grid = ME::DefaultPhantomGrid(shape);
  if (args.Has("size"))
  {
    const auto size = args.GetNumbers("size", 3);
    for (unsigned int d = 0; d < 3; ++d)
    {
      if (size[d] < 2 || size[d] != std::floor(size[d]))
      {
        throw UsageError("--size needs whole numbers >= 2, got '" + args.Get("size") + "'");
      }
      grid.size[d] = static_cast<itk::SizeValueType>(size[d]);
    }
  }
  if (args.Has("spacing"))
  {
    const auto spacing = args.GetNumbers("spacing", 3);
    for (unsigned int d = 0; d < 3; ++d)
    {
      if (!(spacing[d] > 0.0))
      {
        throw UsageError("--spacing must be positive, got '" + args.Get("spacing") + "'");
      }
      grid.spacing[d] = spacing[d];
    }
  }
  if (args.Has("origin"))
  {
    const auto origin = args.GetNumbers("origin", 3);
    for (unsigned int d = 0; d < 3; ++d)
    {
      grid.origin[d] = origin[d];
    }
  }
  if (args.Has("direction"))
  {
    const auto m = args.GetNumbers("direction", 9);
    for (unsigned int r = 0; r < 3; ++r)
    {
      for (unsigned int c = 0; c < 3; ++c)
      {
        grid.direction[r][c] = m[3 * r + c];
      }
    }
    const vnl_matrix_fixed<double, 3, 3> product = grid.direction.GetVnlMatrix() * grid.direction.GetTranspose();
    for (unsigned int r = 0; r < 3; ++r)
    {
      for (unsigned int c = 0; c < 3; ++c)
      {
        if (std::abs(product[r][c] - (r == c ? 1.0 : 0.0)) > 1e-6)
        {
          throw UsageError("--direction must be an orthonormal matrix");
        }
      }
    }
  }
  return grid;
}

ME::PhantomShape
ShapeFromName(const std::string & name)
{
  try
  {
    return ME::PhantomShapeFromName(name);
  }
  catch (const itk::ExceptionObject & e)
  {
    throw UsageError(Describe(e));
  }
}

// ------------------------------------------------------------------------------
// phantom
// ------------------------------------------------------------------------------
template <typename TPixel>
void
WritePhantom(ME::PhantomShape                    shape,
             const ME::PhantomGrid &             grid,
             const ME::PhantomImageParameters &  parameters,
             const std::string &                 output)
{
  using ImageType = itk::Image<TPixel, 3>;
  auto source = ME::MakePhantomImageSource<ImageType>(shape, grid, parameters);
  ReportProgress(source.GetPointer(), "rendering " + ME::PhantomShapeName(shape));
  source->Update();
  WriteImageFile(source->GetOutput(), output);
}

int
RunPhantom(const Arguments & args)
{
  if (args.positional[0] == "list")
  {
    for (auto shape : ME::AllPhantomShapes())
    {
      std::cout << ME::PhantomShapeName(shape) << '\n';
    }
    return 0;
  }
  if (args.positional.size() != 2)
  {
    throw UsageError("'phantom' expects NAME and OUTPUT (or 'list')");
  }
  const ME::PhantomShape  shape = ShapeFromName(args.positional[0]);
  const ME::PhantomGrid   grid = GridFromArguments(shape, args);
  ME::PhantomImageParameters p = ME::DefaultPhantomImageParameters(shape);
  if (args.Has("image-mode"))
  {
    const std::string mode = args.Get("image-mode");
    if (mode == "distance")
    {
      p.mode = itk::MeshExtractionEnums::PhantomImage::DistanceMap;
    }
    else if (mode == "mask")
    {
      p.mode = itk::MeshExtractionEnums::PhantomImage::BinaryMask;
    }
    else if (mode == "step")
    {
      p.mode = itk::MeshExtractionEnums::PhantomImage::BlurredStep;
    }
    else
    {
      throw UsageError("--image-mode must be distance, mask or step, got '" + mode + "'");
    }
    if (p.mode == itk::MeshExtractionEnums::PhantomImage::BinaryMask && !args.Has("inside"))
    {
      p.insideValue = 1.0;
      p.outsideValue = 0.0;
    }
  }
  p.distanceScale = args.GetDouble("distance-scale", p.distanceScale);
  p.insideValue = args.GetDouble("inside", p.insideValue);
  p.outsideValue = args.GetDouble("outside", p.outsideValue);
  p.edgeWidth = args.GetDouble("edge-width", p.edgeWidth);
  p.noiseStandardDeviation = args.GetDouble("noise", p.noiseStandardDeviation);
  p.noiseSeed = static_cast<std::uint64_t>(args.GetInteger("seed", static_cast<long>(p.noiseSeed)));
  const std::string defaultType =
    p.mode == itk::MeshExtractionEnums::PhantomImage::BinaryMask ? "uchar" : "float";
  const std::string type = args.Get("pixel-type", defaultType);
  const std::string & output = args.positional[1];
  std::cerr << "phantom " << ME::PhantomShapeName(shape) << ": " << grid.size << " voxels of " << grid.spacing
            << " mm, " << p.mode << ", " << type << " -> " << output << '\n';
  if (type == "float")
  {
    WritePhantom<float>(shape, grid, p, output);
  }
  else if (type == "double")
  {
    WritePhantom<double>(shape, grid, p, output);
  }
  else if (type == "uchar")
  {
    WritePhantom<unsigned char>(shape, grid, p, output);
  }
  else if (type == "short")
  {
    WritePhantom<short>(shape, grid, p, output);
  }
  else if (type == "ushort")
  {
    WritePhantom<unsigned short>(shape, grid, p, output);
  }
  else
  {
    throw UsageError("--pixel-type must be uchar, short, ushort, float or double, got '" + type + "'");
  }
  return 0;
}

// ------------------------------------------------------------------------------
// quality
// ------------------------------------------------------------------------------
struct MeasuredMesh
{
  std::string                               name;
  ME::TriangleMeshQualityReport             quality;
  bool                                      hasDistance{ false };
  ME::MeshSurfaceDistanceReport             distance;
};

void
WriteHistogramsCSV(const std::vector<MeasuredMesh> & meshes, const std::string & path)
{
  std::ofstream out(path);
  if (!out)
  {
    itkGenericExceptionMacro("cannot write '" << path << "'");
  }
  out << "mesh,measure,bin_lower,bin_upper,count\n";
  for (const auto & m : meshes)
  {
    const std::pair<const char *, const ME::ValueStatistics *> measures[] = {
      { "q_area", &m.quality.qArea },
      { "q_angle", &m.quality.qAngle },
      { "q_length", &m.quality.qLength },
      { "min_angle_deg", &m.quality.minimumAngle },
      { "max_angle_deg", &m.quality.maximumAngle },
    };
    for (const auto & measure : measures)
    {
      const auto & s = *measure.second;
      const double width = (s.histogramUpper - s.histogramLower) / s.histogram.size();
      for (std::size_t b = 0; b < s.histogram.size(); ++b)
      {
        out << m.name << ',' << measure.first << ',' << s.histogramLower + b * width << ','
            << s.histogramLower + (b + 1) * width << ',' << s.histogram[b] << '\n';
      }
    }
    for (std::size_t d = 0; d < m.quality.valenceHistogram.size(); ++d)
    {
      out << m.name << ",valence," << d << ',' << d + 1 << ',' << m.quality.valenceHistogram[d] << '\n';
    }
  }
}

void
WriteJSON(const std::vector<MeasuredMesh> & meshes, const std::string & path)
{
  std::ofstream out(path);
  if (!out)
  {
    itkGenericExceptionMacro("cannot write '" << path << "'");
  }
  out << "[\n";
  for (std::size_t i = 0; i < meshes.size(); ++i)
  {
    out << "  {\"mesh\": \"" << meshes[i].name << "\", \"quality\": ";
    meshes[i].quality.PrintJSON(out);
    if (meshes[i].hasDistance)
    {
      out << ", \"distance\": ";
      meshes[i].distance.PrintJSON(out);
    }
    out << '}' << (i + 1 < meshes.size() ? "," : "") << '\n';
  }
  out << "]\n";
}

void
PrintComparison(const std::vector<MeasuredMesh> & meshes, std::ostream & os)
{
  os << std::left << std::setw(28) << "mesh" << std::right << std::setw(10) << "triangles" << std::setw(9)
     << "q_area" << std::setw(9) << "q_angle" << std::setw(9) << "<0.3 %" << std::setw(11) << "smooth" << std::setw(9)
     << "val6 %" << std::setw(12) << "d_vert" << std::setw(12) << "d_face" << std::setw(12) << "hausdorff"
     << std::setw(7) << "valid" << '\n';
  for (const auto & m : meshes)
  {
    std::string name = m.name.size() > 27 ? "..." + m.name.substr(m.name.size() - 24) : m.name;
    os << std::left << std::setw(28) << name << std::right << std::setw(10) << m.quality.numberOfTriangles
       << std::fixed << std::setprecision(4) << std::setw(9) << m.quality.qArea.mean << std::setw(9)
       << m.quality.qAngle.mean << std::setprecision(2) << std::setw(9) << 100 * m.quality.fractionQAngleBelow03
       << std::setprecision(5) << std::setw(11) << m.quality.meanSmoothness << std::setprecision(1) << std::setw(9)
       << 100 * m.quality.fractionValence6;
    if (m.hasDistance)
    {
      os << std::scientific << std::setprecision(3) << std::setw(12) << m.distance.vertices.mean << std::setw(12)
         << m.distance.faceCentroids.mean << std::setw(12) << m.distance.hausdorff;
    }
    else
    {
      os << std::setw(12) << "-" << std::setw(12) << "-" << std::setw(12) << "-";
    }
    os << std::setw(7) << (m.quality.IsValidClosedSurface() ? "yes" : "NO") << std::defaultfloat << '\n';
  }
}

int
RunQuality(const Arguments & args)
{
  // The reference for distances: a mesh file or a phantom's exact surface.
  IOMeshType::Pointer                     referenceMesh;
  itk::ImplicitSurfaceFunction::Pointer   referenceSurface;
  if (args.Has("reference-mesh") && args.Has("phantom"))
  {
    throw UsageError("give either --reference-mesh or --phantom, not both");
  }
  if (args.Has("reference-mesh"))
  {
    referenceMesh = ReadMeshFile(args.Get("reference-mesh"));
  }
  if (args.Has("phantom"))
  {
    const ME::PhantomShape shape = ShapeFromName(args.Get("phantom"));
    const ME::PhantomGrid  grid = args.Has("image") ? ReadImageGrid(args.Get("image")) : GridFromArguments(shape, args);
    referenceSurface = ME::MakePhantomSurface(shape, grid);
  }
  else if (args.Has("image"))
  {
    throw UsageError("--image gives the grid of a --phantom reference; --phantom is missing");
  }
  IOMeshType::Pointer inversionReference;
  if (args.Has("inversion-reference"))
  {
    inversionReference = ReadMeshFile(args.Get("inversion-reference"));
  }

  std::vector<MeasuredMesh> results;
  for (const std::string & path : args.positional)
  {
    Stopwatch watch;
    std::cerr << "measuring " << path << '\n';
    IOMeshType::Pointer mesh = ReadMeshFile(path);
    auto                quality = itk::TriangleMeshQualityCalculator<IOMeshType>::New();
    quality->SetMesh(mesh);
    quality->SetReferenceMesh(inversionReference);
    quality->SetComputeSelfIntersections(!args.Has("no-self-intersections"));
    quality->SetComputeOutwardOrientation(!args.Has("no-orientation"));
    quality->Compute();
    MeasuredMesh measured;
    measured.name = path;
    measured.quality = quality->GetReport();
    if (referenceMesh || referenceSurface)
    {
      auto distance = itk::MeshSurfaceDistanceCalculator<IOMeshType>::New();
      distance->SetMesh(mesh);
      if (referenceMesh)
      {
        distance->SetReferenceMesh(referenceMesh);
      }
      else
      {
        distance->SetReferenceSurface(referenceSurface);
      }
      distance->SetSamplingLevel(static_cast<unsigned int>(args.GetInteger("sampling-level", 2)));
      distance->Compute();
      measured.hasDistance = true;
      measured.distance = distance->GetReport();
    }
    measured.quality.Print(std::cout, path);
    if (measured.hasDistance)
    {
      measured.distance.Print(std::cout);
    }
    std::cout << '\n';
    std::cerr << "  done in " << std::fixed << std::setprecision(2) << watch.Seconds() << " s\n" << std::defaultfloat;
    results.push_back(measured);
  }
  if (results.size() > 1)
  {
    PrintComparison(results, std::cout);
  }
  if (args.Has("json"))
  {
    WriteJSON(results, args.Get("json"));
  }
  if (args.Has("csv"))
  {
    WriteHistogramsCSV(results, args.Get("csv"));
  }
  if (args.Has("require-valid"))
  {
    for (const auto & r : results)
    {
      if (!r.quality.IsValidClosedSurface())
      {
        std::cerr << "meshextraction: " << r.name << " is not a valid closed surface\n";
        return 1;
      }
    }
  }
  return 0;
}

// ------------------------------------------------------------------------------
// The commands
// ------------------------------------------------------------------------------
std::vector<Command>
Commands()
{
  std::vector<Command> commands;
  {
    Command c;
    c.name = "phantom";
    c.summary = "write a phantom image (plane, sphere, two spheres, ellipsoid, torus, ...)";
    c.usage = "NAME OUTPUT [options]   |   meshextraction phantom list";
    c.description =
      "Renders one of the module's analytic phantoms into an image (any format ITK writes, by the\n"
      "extension of OUTPUT). The surface is exact: `quality --phantom NAME --image OUTPUT` measures\n"
      "meshes against it. Distance maps hold the signed distance in mm (negative inside, iso-value 0);\n"
      "masks hold --inside / --outside; the chapter4-sphere is a blurred step edge (inside 100,\n"
      "outside 0) to which --noise adds Gaussian noise. `phantom list` prints the names.";
    c.options = GridOptions();
    c.options.push_back({ "image-mode", "distance|mask|step", "what the voxels hold", "per phantom" });
    c.options.push_back({ "pixel-type", "TYPE", "uchar, short, ushort, float or double", "float; uchar for masks" });
    c.options.push_back({ "distance-scale", "S", "distance map value per mm", "1" });
    c.options.push_back({ "inside", "V", "mask/step value inside", "1 (mask), 100 (step)" });
    c.options.push_back({ "outside", "V", "mask/step value outside", "0" });
    c.options.push_back({ "edge-width", "MM", "standard deviation of the blurred step", "1" });
    c.options.push_back({ "noise", "SIGMA", "additive Gaussian noise", "0" });
    c.options.push_back({ "seed", "N", "noise seed", "0" });
    c.minimumPositional = 1;
    c.maximumPositional = 2;
    c.run = RunPhantom;
    commands.push_back(c);
  }
  {
    Command c;
    c.name = "quality";
    c.summary = "measure triangle quality, integrity and accuracy of meshes";
    c.usage = "MESH [MESH...] [options]";
    c.description =
      "Measures each mesh (any format ITK reads) with TriangleMeshQualityCalculator: q_area, q_angle,\n"
      "q_length, angles, smoothness, valences, and integrity (degenerate, inverted, non-manifold,\n"
      "holes, orientation, components, Euler characteristic, genus, self-intersections). With\n"
      "--reference-mesh or --phantom it also measures distances with MeshSurfaceDistanceCalculator:\n"
      "mean (thesis eq. 3.7), RMS, maximum, symmetric Hausdorff. Several meshes get a side-by-side\n"
      "table. Exit status 1 with --require-valid if a mesh is not a valid closed surface.";
    c.options = {
      { "reference-mesh", "FILE", "measure distances to this mesh", "" },
      { "phantom", "NAME", "measure distances to this phantom's exact surface", "" },
      { "image", "FILE", "take the phantom's grid from this image (else the grid options)", "" },
      { "inversion-reference", "FILE", "count triangles flipped against this mesh (same connectivity)", "" },
      { "sampling-level", "N", "subdivisions per triangle edge for the Hausdorff samples", "2" },
      { "no-self-intersections", "", "skip the self-intersection test", "" },
      { "no-orientation", "", "skip the outward-orientation test", "" },
      { "json", "FILE", "write the reports as JSON", "" },
      { "csv", "FILE", "write the histograms as CSV", "" },
      { "require-valid", "", "exit 1 unless every mesh is a valid closed surface", "" },
    };
    for (const auto & o : GridOptions())
    {
      c.options.push_back(o);
    }
    c.minimumPositional = 1;
    c.run = RunQuality;
    commands.push_back(c);
  }
  return commands;
}

void
PrintUsage(std::ostream & os, const std::vector<Command> & commands)
{
  os << "usage: meshextraction COMMAND [arguments] [--help]\n\n"
        "Accurate, well-formed surface meshes from CT and MRI volumes (ITK MeshExtraction).\n\ncommands:\n";
  for (const auto & c : commands)
  {
    os << "  " << std::left << std::setw(10) << c.name << c.summary << '\n';
  }
  os << "\nRun 'meshextraction COMMAND --help' for the options of a command.\n";
}
} // namespace

int
main(int argc, char * argv[])
{
  const std::vector<Command> commands = Commands();
  if (argc < 2 || std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h" || std::string(argv[1]) == "help")
  {
    PrintUsage(argc < 2 ? std::cerr : std::cout, commands);
    return argc < 2 ? 2 : 0;
  }
  const std::string name = argv[1];
  const Command *   command = nullptr;
  for (const auto & c : commands)
  {
    command = c.name == name ? &c : command;
  }
  if (command == nullptr)
  {
    std::cerr << "meshextraction: unknown command '" << name << "'\n\n";
    PrintUsage(std::cerr, commands);
    return 2;
  }
  for (int i = 2; i < argc; ++i)
  {
    if (std::string(argv[i]) == "--help" || std::string(argv[i]) == "-h")
    {
      command->PrintHelp(std::cout);
      return 0;
    }
  }
  try
  {
    const Arguments args = command->Parse(argc - 2, argv + 2);
    return command->run(args);
  }
  catch (const UsageError & e)
  {
    std::cerr << "meshextraction " << name << ": " << e.what() << "\n\n";
    command->PrintHelp(std::cerr);
    return 2;
  }
  catch (const itk::ExceptionObject & e)
  {
    std::cerr << "meshextraction " << name << ": error: " << Describe(e) << '\n';
    return 1;
  }
  catch (const std::exception & e)
  {
    std::cerr << "meshextraction " << name << ": error: " << e.what() << '\n';
    return 1;
  }
}
