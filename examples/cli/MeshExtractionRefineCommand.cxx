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
// meshextraction refine: scale-space edge refinement of a rough mesh, the ED/ES/S
// protocol of thesis chapter 4.

#include "MeshExtractionCLI.h"

#include "itkMeshExtractionGeodesicSphere.h"
#include "itkScaleSpaceEdgeMeshRefinementFilter.h"
#include "itkSurfaceNetsImageToMeshFilter.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>

namespace MeshExtractionCLI
{
namespace
{
using RefineMeshType = QuadEdgeMeshType;
using RefineImageType = itk::Image<float, 3>;
using RefineFilterType = itk::ScaleSpaceEdgeMeshRefinementFilter<RefineMeshType, RefineImageType>;
using Direction = itk::MeshExtractionEnums::EdgeSearchDirection;

/** The defaults of the options that build the initial mesh (the command's own, not
 * a filter's; the help prints these). */
constexpr long RefineDefaultSubdivisions = 3;
constexpr char RefineDefaultInside[] = "above";
constexpr char RefineDefaultRelaxation[] = "none";

/** The name --search gives the filter's search direction. */
const char *
SearchDirectionName(Direction direction)
{
  return direction == Direction::ImageGradient ? "gradient" : "normal";
}

// ------------------------------------------------------------------------------
// The initial mesh
// ------------------------------------------------------------------------------

/** The physical centre of the image. */
ME::Vec3
ImageCentre(const RefineImageType * image)
{
  const auto                      region = image->GetLargestPossibleRegion();
  itk::ContinuousIndex<double, 3> middle;
  RefineImageType::PointType      p;
  for (unsigned int d = 0; d < 3; ++d)
  {
    middle[d] = static_cast<double>(region.GetIndex(d)) + 0.5 * (static_cast<double>(region.GetSize(d)) - 1.0);
  }
  image->TransformContinuousIndexToPhysicalPoint(middle, p);
  return ME::MakeVec3(p[0], p[1], p[2]);
}

/** --initial sphere: a geodesic sphere (--subdivisions, --radius, --center). */
RefineMeshType::Pointer
InitialSphereMesh(const Arguments & args, const RefineImageType * image)
{
  if (!args.Has("radius"))
  {
    throw UsageError("--initial sphere needs --radius MM");
  }
  const double radius = args.GetDouble("radius", 0.0);
  if (!(radius > 0.0))
  {
    throw UsageError("--radius must be > 0, got '" + args.Get("radius") + "'");
  }
  const long subdivisions = args.GetInteger("subdivisions", RefineDefaultSubdivisions);
  if (subdivisions < 0 || subdivisions > 7)
  {
    throw UsageError("--subdivisions must be in 0..7, got " + std::to_string(subdivisions));
  }
  ME::Vec3 center;
  if (args.Has("center"))
  {
    const auto c = args.GetNumbers("center", 3);
    center = ME::MakeVec3(c[0], c[1], c[2]);
  }
  else
  {
    center = ImageCentre(image);
  }
  auto mesh = RefineMeshType::New();
  ME::FillMesh(ME::MakeGeodesicSphere(static_cast<unsigned int>(subdivisions), center, radius), *mesh);
  std::cerr << "  initial mesh: geodesic sphere, " << subdivisions << " subdivisions, radius " << radius
            << " mm, centre " << center << '\n';
  return mesh;
}

/** --initial surfacenets: SurfaceNets of the threshold --iso (no relaxation, or
 * --relaxation sna). */
RefineMeshType::Pointer
InitialSurfaceNetsMesh(const Arguments & args, const RefineImageType * image)
{
  if (!args.Has("iso"))
  {
    throw UsageError("--initial surfacenets needs --iso V (the threshold of the rough segmentation)");
  }
  const std::string inside = args.Get("inside", RefineDefaultInside);
  if (inside != "above" && inside != "below")
  {
    throw UsageError("--inside must be above or below, got '" + inside + "'");
  }
  const std::string relaxation = args.Get("relaxation", RefineDefaultRelaxation);
  if (relaxation != "none" && relaxation != "sna")
  {
    throw UsageError("--relaxation must be none or sna, got '" + relaxation + "'");
  }
  using FilterType = itk::SurfaceNetsImageToMeshFilter<RefineImageType, RefineMeshType>;
  auto filter = FilterType::New();
  filter->SetInput(image);
  filter->SetIsoValue(args.GetDouble("iso", 0.0));
  filter->SetInsideIsAboveIsoValue(inside == "above");
  filter->SetRelaxation(relaxation == "none" ? itk::SurfaceNetsImageToMeshFilterEnums::Relaxation::None
                                             : itk::SurfaceNetsImageToMeshFilterEnums::Relaxation::Averaging);
  Stopwatch watch;
  filter->Update();
  RefineMeshType::Pointer mesh = filter->GetOutput();
  mesh->DisconnectPipeline();
  std::cerr << "  initial mesh: SurfaceNets (" << relaxation << ") of the voxels " << inside << ' ' << args.Get("iso")
            << ", " << mesh->GetNumberOfPoints() << " points, " << mesh->GetNumberOfFaces() << " triangles, "
            << std::fixed << std::setprecision(2) << watch.Seconds() << " s\n"
            << std::defaultfloat;
  return mesh;
}

/** The initial mesh: built (--initial) or read (MESH). */
RefineMeshType::Pointer
InitialMesh(const Arguments & args, const std::string & initial, const RefineImageType * image)
{
  if (initial == "sphere")
  {
    return InitialSphereMesh(args, image);
  }
  if (initial == "surfacenets")
  {
    return InitialSurfaceNetsMesh(args, image);
  }
  RefineMeshType::Pointer mesh = ReadManifoldMesh(args.positional[1], "refine");
  std::cerr << "  initial mesh: " << args.positional[1] << ", " << mesh->GetNumberOfPoints() << " points, "
            << mesh->GetNumberOfFaces() << " triangles\n";
  return mesh;
}

/** The largest connected component (by number of triangles) of a triangle mesh:
 * threshold meshes of real images carry small islands whose vertices smoothing moves
 * far, which would end every cycle after one smoothing step. */
RefineMeshType::Pointer
LargestComponent(const RefineMeshType * mesh)
{
  const ME::IndexedTriangleMesh in = ME::MakeIndexedTriangleMesh(*mesh);
  const ME::MeshTopology        topology = ME::BuildMeshTopology(in);
  std::vector<std::size_t>      size(topology.numberOfComponents, 0);
  for (const auto c : topology.triangleComponent)
  {
    ++size[c];
  }
  const auto largest = static_cast<std::uint32_t>(std::max_element(size.begin(), size.end()) - size.begin());
  ME::IndexedTriangleMesh    out;
  std::vector<std::uint32_t> index(in.points.size(), std::numeric_limits<std::uint32_t>::max());
  for (std::size_t t = 0; t < in.triangles.size(); ++t)
  {
    if (topology.triangleComponent[t] != largest)
    {
      continue;
    }
    ME::TriangleIndices triangle;
    for (unsigned int k = 0; k < 3; ++k)
    {
      const std::uint32_t v = in.triangles[t][k];
      if (index[v] == std::numeric_limits<std::uint32_t>::max())
      {
        index[v] = static_cast<std::uint32_t>(out.points.size());
        out.points.push_back(in.points[v]);
      }
      triangle[k] = index[v];
    }
    out.triangles.push_back(triangle);
  }
  auto result = RefineMeshType::New();
  ME::FillMesh(out, *result);
  std::cerr << "  largest component: " << result->GetNumberOfPoints() << " points, " << out.triangles.size()
            << " triangles (of " << topology.numberOfComponents << " components)\n";
  return result;
}

// ------------------------------------------------------------------------------
// Options
// ------------------------------------------------------------------------------

/** A UsageError for options of one way to build the initial mesh given with another. */
void
CheckInitialMeshOptions(const Arguments & args, const std::string & initial)
{
  const char * sphereOptions[] = { "radius", "center", "subdivisions" };
  for (const char * option : sphereOptions)
  {
    if (args.Has(option) && initial != "sphere")
    {
      throw UsageError(std::string("--") + option + " applies to --initial sphere");
    }
  }
  const char * netsOptions[] = { "iso", "inside", "relaxation" };
  for (const char * option : netsOptions)
  {
    if (args.Has(option) && initial != "surfacenets")
    {
      throw UsageError(std::string("--") + option + " applies to --initial surfacenets");
    }
  }
  if (initial == "sphere" && !args.Has("radius"))
  {
    throw UsageError("--initial sphere needs --radius MM");
  }
  if (initial == "surfacenets" && !args.Has("iso"))
  {
    throw UsageError("--initial surfacenets needs --iso V (the threshold of the rough segmentation)");
  }
}

/** --initial (empty: MESH is read), after checking the positional arguments and the
 * options that go with it. */
std::string
ReadInitialChoice(const Arguments & args)
{
  const bool hasInitial = args.Has("initial");
  if (hasInitial && args.positional.size() != 2)
  {
    throw UsageError("with --initial give IMAGE and OUT only");
  }
  if (!hasInitial && args.positional.size() != 3)
  {
    throw UsageError("'refine' expects IMAGE MESH OUT (or IMAGE OUT with --initial sphere|surfacenets)");
  }
  const std::string initial = args.Get("initial");
  if (hasInitial && initial != "sphere" && initial != "surfacenets")
  {
    throw UsageError("--initial must be sphere or surfacenets, got '" + initial + "'");
  }
  CheckInitialMeshOptions(args, initial);
  if (!args.Has("max-deviation"))
  {
    throw UsageError("give the largest distance between the initial mesh and the object's edge: --max-deviation MM");
  }
  return initial;
}

/** The refinement's settings; the options not given keep the filter's defaults. */
struct RefineSettings
{
  double      deviation{ 0.0 };
  double      target{ 0.0 };
  long        cycles{ 0 };
  long        smoothingSteps{ 0 };
  long        perOctave{ 0 };
  long        threads{ 0 };
  std::string search;
};

RefineSettings
ReadRefineSettings(const Arguments & args, const RefineFilterType * defaults)
{
  RefineSettings s;
  s.deviation = args.GetDouble("max-deviation", 0.0);
  s.target = args.GetDouble("target-quality", defaults->GetTargetQuality());
  s.cycles = args.GetInteger("cycles", defaults->GetMaximumNumberOfCycles());
  s.smoothingSteps = args.GetInteger("smoothing-steps", defaults->GetMaximumNumberOfSmoothingSteps());
  s.perOctave = args.GetInteger("scales-per-octave", defaults->GetNumberOfScalesPerOctave());
  s.threads = args.GetInteger("threads", 0);
  SetDicomSeries(args.Get("series"));
  if (s.cycles < 0 || s.smoothingSteps < 1 || s.perOctave < 1 || s.threads < 0)
  {
    throw UsageError("--cycles must be >= 0, --smoothing-steps and --scales-per-octave >= 1, --threads >= 0");
  }
  s.search = args.Get("search", SearchDirectionName(defaults->GetSearchDirection()));
  if (s.search != "gradient" && s.search != "normal")
  {
    throw UsageError("--search must be gradient or normal, got '" + s.search + "'");
  }
  return s;
}

/** --phantom: the phantom's exact surface on IMAGE's grid, and its radius if it is a
 * sphere (NaN otherwise). */
itk::ImplicitSurfaceFunction::Pointer
PhantomReference(const Arguments & args, const std::string & imagePath, double & radius)
{
  radius = std::numeric_limits<double>::quiet_NaN();
  if (!args.Has("phantom"))
  {
    return nullptr;
  }
  const ME::PhantomShape                shape = ShapeFromName(args.Get("phantom"));
  itk::ImplicitSurfaceFunction::Pointer reference = ME::MakePhantomSurface(shape, ReadImageGrid(imagePath));
  if (const auto * sphere = dynamic_cast<const itk::SphereImplicitSurface *>(reference.GetPointer()))
  {
    radius = sphere->GetRadius();
  }
  return reference;
}

// ------------------------------------------------------------------------------
// The refinement
// ------------------------------------------------------------------------------
void
ConfigureRefinement(RefineFilterType *                   filter,
                    const RefineSettings &               s,
                    const Arguments &                    args,
                    const itk::ImplicitSurfaceFunction * reference)
{
  filter->SetMaximumDeviation(s.deviation);
  filter->SetTargetQuality(s.target);
  filter->SetMaximumNumberOfCycles(static_cast<unsigned int>(s.cycles));
  filter->SetMaximumNumberOfSmoothingSteps(static_cast<unsigned int>(s.smoothingSteps));
  filter->SetNumberOfScalesPerOctave(static_cast<unsigned int>(s.perOctave));
  filter->SetMinimumScale(args.GetDouble("minimum-scale", filter->GetMinimumScale()));
  filter->SetSearchDirection(s.search == "gradient" ? Direction::ImageGradient : Direction::VertexNormal);
  filter->SetSubSampleRefinement(!args.Has("thesis-detector"));
  filter->SetComputeInaccuracy(!args.Has("no-inaccuracy"));
  filter->SetReferenceSurface(reference);
  if (s.threads > 0)
  {
    filter->SetNumberOfWorkUnits(static_cast<unsigned int>(s.threads));
  }
}

/** The scales, the step table (thesis Table 4.1) and the totals. */
void
PrintRefinement(const RefineFilterType * filter,
                const RefineSettings &   s,
                const RefineImageType *  image,
                double                   radius,
                double                   refineSeconds)
{
  const auto & steps = filter->GetSteps();
  const double minimumScale = ME::detail::ResolveMinimumScale(image->GetSpacing(), filter->GetMinimumScale());
  std::cout << "scale-space refinement (thesis 4.2.4): maximum deviation " << s.deviation << " mm, target quality "
            << s.target << ", scales "
            << ME::detail::ScaleSpaceScales(s.deviation, minimumScale, static_cast<unsigned int>(s.perOctave)).size()
            << " (" << s.deviation << " .. " << minimumScale << " mm)\n";
  filter->PrintSteps(std::cout, radius);
  double      edgeDetectionSeconds = 0.0;
  std::size_t edgeDetections = 0;
  for (const auto & step : steps)
  {
    if (step.operation == itk::MeshExtractionEnums::RefinementOperation::EdgeDetection)
    {
      edgeDetectionSeconds += step.seconds;
      ++edgeDetections;
    }
  }
  std::cout << filter->GetNumberOfCycles() << " cycles, target quality "
            << (filter->GetTargetQualityReached() ? "reached" : "NOT reached") << "; " << edgeDetections
            << " ED steps, " << std::fixed << std::setprecision(3) << edgeDetectionSeconds << " s in ED (the first "
            << (steps.size() > 1 ? steps[1].seconds : 0.0) << " s with the scale space), " << refineSeconds
            << " s in all\n"
            << std::defaultfloat;
}

/** --csv: the step table. */
void
WriteStepsCSV(const RefineFilterType * filter, const std::string & path)
{
  WriteTextWhole(path, [filter](std::ostream & out) { ME::WriteScaleSpaceRefinementCSV(out, filter->GetSteps()); });
}

/** --report: the quality (and phantom distances) before and after, side by side. */
void
PrintBeforeAndAfter(const MeasuredMesh & before, const MeasuredMesh & after, const std::string & outputPath)
{
  PrintMeasuredMesh(before, "before: initial mesh", std::cout);
  std::cout << '\n';
  PrintMeasuredMesh(after, "after: " + outputPath, std::cout);
  std::cout << '\n';
  PrintComparison({ before, after }, std::cout);
}

/** --max-deviation is a capture range inside the image: no larger than the image's
 * diagonal, or vertices would be sent far outside it. */
void
CheckDeviationWithinImage(double deviation, const RefineImageType * image)
{
  const auto size = image->GetLargestPossibleRegion().GetSize();
  double     diagonal = 0.0;
  for (unsigned int d = 0; d < 3; ++d)
  {
    const double extent = static_cast<double>(size[d]) * image->GetSpacing()[d];
    diagonal += extent * extent;
  }
  diagonal = std::sqrt(diagonal);
  if (deviation > diagonal)
  {
    throw UsageError("--max-deviation must be at most the image's diagonal (" + std::to_string(diagonal) +
                     " mm), got " + std::to_string(deviation));
  }
}

/** Reads IMAGE (a 3-D scalar image of finite, not constant values). */
RefineImageType::Pointer
ReadRefineImage(const std::string & imagePath)
{
  std::cerr << "refine: " << imagePath << '\n';
  ReadScalarVolumeInformation(imagePath, "the refinement");
  RefineImageType::Pointer image = ReadImageFile<RefineImageType>(imagePath);
  CheckVoxelValues(image.GetPointer(), imagePath);
  std::cerr << "  image " << image->GetLargestPossibleRegion().GetSize() << " voxels of " << image->GetSpacing()
            << " mm\n";
  return image;
}

int
RunRefine(const Arguments & args)
{
  const std::string    initial = ReadInitialChoice(args);
  auto                 filter = RefineFilterType::New();
  const RefineSettings s = ReadRefineSettings(args, filter);

  const std::string &            imagePath = args.positional[0];
  const std::string &            outputPath = args.positional.back();
  const std::vector<std::string> inputs(args.positional.begin(), args.positional.end() - 1);
  RequireNotAnInput(outputPath, inputs, "OUT");
  RequireNotAnInput(args.Get("csv"), args.positional, "--csv");
  const MeshWriteSettings        writeSettings = ReadMeshWriteSettings(args);
  Stopwatch                      watch;
  const RefineImageType::Pointer image = ReadRefineImage(imagePath);
  CheckDeviationWithinImage(s.deviation, image.GetPointer());
  RefineMeshType::Pointer mesh = InitialMesh(args, initial, image);
  if (args.Has("largest-component"))
  {
    mesh = LargestComponent(mesh);
  }
  double                                      radius;
  const itk::ImplicitSurfaceFunction::Pointer reference = PhantomReference(args, imagePath, radius);
  MeasuredMesh                                before;
  if (args.Has("report"))
  {
    before = MeasureMesh(mesh, "initial", reference);
  }

  filter->SetInput(mesh);
  filter->SetInputImage(image);
  ConfigureRefinement(filter, s, args, reference);
  ReportProgress(filter.GetPointer(), "refine");
  Stopwatch refineWatch;
  filter->Update();
  const double            refineSeconds = refineWatch.Seconds();
  RefineMeshType::Pointer output = filter->GetOutput();
  output->DisconnectPipeline();

  PrintRefinement(filter, s, image, radius, refineSeconds);
  if (args.Has("csv"))
  {
    WriteStepsCSV(filter, args.Get("csv"));
  }
  WriteMeshFile(output.GetPointer(), outputPath, writeSettings);
  std::cerr << "  wrote " << outputPath << " (" << output->GetNumberOfPoints() << " points, "
            << output->GetNumberOfFaces() << " triangles) in " << std::fixed << std::setprecision(2) << watch.Seconds()
            << " s\n"
            << std::defaultfloat;
  if (args.Has("report"))
  {
    PrintBeforeAndAfter(before, MeasureMesh(output, outputPath, reference), outputPath);
  }
  return 0;
}
} // namespace

Command
MakeRefineCommand()
{
  Command c;
  c.name = "refine";
  c.summary = "move a rough mesh onto the image's edges and improve it (scale-space ED/ES/S protocol)";
  c.usage = "IMAGE MESH OUT --max-deviation D [options]   |   meshextraction refine IMAGE OUT --initial "
            "sphere|surfacenets --max-deviation D [options]";
  c.description = "Thesis chapter 4 (ScaleSpaceEdgeMeshRefinementFilter): for data a threshold cannot segment (noise,\n"
                  "MRI bias fields). Starting from a rough mesh MESH (.vtk, .vtp, .ply, .stl, .obj, .off or another\n"
                  "format ITK reads), a geodesic sphere or a\n"
                  "SurfaceNets mesh of a threshold, it alternates scale-space edge detection (ED: every vertex moves\n"
                  "along the image gradient to the edge found coarse-to-fine from sigma = D down to the voxel\n"
                  "length), regularity edge swaps (ES) and centroid smoothing (S) until the mean q_area reaches\n"
                  "--target-quality, and ends with ED and ES. D is the largest distance between the initial mesh and\n"
                  "the object's edge, in mm. Prints the step table (thesis Table 4.1) and writes OUT (format from\n"
                  "its extension). Distances are physical (spacing, origin, direction).";
  const auto defaults = RefineFilterType::New();
  c.options = {
    { "max-deviation",
      "MM",
      "largest distance from the initial mesh to the edge (capture range)",
      "required",
      OptionRange::AboveUpTo(0, 1e4) },
    { "series", "UID", "the DICOM series to read when IMAGE is a directory (default: the first)", "" },
    { "target-quality",
      "Q",
      "mean q_area to reach",
      DefaultText(defaults->GetTargetQuality()),
      OptionRange::AboveUpTo(0, 1) },
    { "initial", "sphere|surfacenets", "build the initial mesh instead of reading MESH", "" },
    { "radius", "MM", "sphere: radius", "", OptionRange::AboveUpTo(0, 1e6) },
    { "center", "X,Y,Z", "sphere: centre", "the image's centre", OptionRange::Between(-1e9, 1e9) },
    { "subdivisions",
      "N",
      "sphere: icosahedron subdivisions (10*4^N+2 vertices)",
      DefaultText(RefineDefaultSubdivisions),
      OptionRange::Between(0, 8) },
    { "iso", "V", "surfacenets: threshold of the rough segmentation", "", OptionRange::Any() },
    { "inside", "above|below", "surfacenets: which side of --iso is the object", RefineDefaultInside },
    { "relaxation", "none|sna", "surfacenets: relaxation of the rough mesh", RefineDefaultRelaxation },
    { "largest-component", "", "keep only the initial mesh's largest connected component", "" },
    { "cycles",
      "N",
      "largest number of S...ED ES cycles after the first ED ES",
      DefaultText(defaults->GetMaximumNumberOfCycles()),
      OptionRange::Between(0, 1000) },
    { "smoothing-steps",
      "N",
      "largest number of smoothing steps per cycle",
      DefaultText(defaults->GetMaximumNumberOfSmoothingSteps()),
      OptionRange::Between(1, 10000) },
    { "scales-per-octave",
      "N",
      "scales per doubling of sigma",
      DefaultText(defaults->GetNumberOfScalesPerOctave()),
      OptionRange::Between(1, 16) },
    { "minimum-scale", "MM", "smallest scale", "the voxel length (smallest spacing)", OptionRange::AboveUpTo(0, 1e4) },
    { "search",
      "gradient|normal",
      "search line: image gradient or vertex normal",
      SearchDirectionName(defaults->GetSearchDirection()) },
    { "thesis-detector", "", "no sub-sample refinement of the edge (the thesis' 5 samples only)", "" },
    { "no-inaccuracy", "", "skip the inaccuracy measurement after each ED", "" },
    { "phantom", "NAME", "IMAGE is this phantom: add distances to its exact surface to the table", "" },
    { "csv", "FILE", "write the step table as CSV", "" },
    { "report", "", "print the quality (and phantom distances) before and after", "" },
    { "threads", "N", "work units (0: all cores)", "0", OptionRange::Between(0, 1024) },
  };
  for (const auto & o : MeshWriteOptions())
  {
    c.options.push_back(o);
  }
  c.minimumPositional = 2;
  c.maximumPositional = 3;
  c.run = RunRefine;
  return c;
}

} // namespace MeshExtractionCLI
