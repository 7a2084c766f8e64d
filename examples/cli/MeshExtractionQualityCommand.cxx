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
// meshextraction quality: triangle quality, integrity and accuracy of meshes.

#include "MeshExtractionCLI.h"

#include <iomanip>
#include <iostream>

namespace MeshExtractionCLI
{
namespace
{
/** What the meshes are compared with, kept alive for the measurements. */
struct QualityReferences
{
  IOMeshType::Pointer                   referenceMesh;
  itk::ImplicitSurfaceFunction::Pointer referenceSurface;
  IOMeshType::Pointer                   inversionReference;
};

/** The reference for distances (a mesh file or a phantom's exact surface) and the
 * reference for inverted triangles. */
QualityReferences
ReadReferences(const Arguments & args)
{
  QualityReferences references;
  if (args.Has("reference-mesh") && args.Has("phantom"))
  {
    throw UsageError("give either --reference-mesh or --phantom, not both");
  }
  if (args.Has("reference-mesh"))
  {
    references.referenceMesh = ReadMeshFile(args.Get("reference-mesh"));
  }
  if (args.Has("phantom"))
  {
    const ME::PhantomShape shape = ShapeFromName(args.Get("phantom"));
    const ME::PhantomGrid  grid = args.Has("image") ? ReadImageGrid(args.Get("image")) : GridFromArguments(shape, args);
    references.referenceSurface = ME::MakePhantomSurface(shape, grid);
  }
  else if (args.Has("image"))
  {
    throw UsageError("--image gives the grid of a --phantom reference; --phantom is missing");
  }
  if (args.Has("inversion-reference"))
  {
    references.inversionReference = ReadMeshFile(args.Get("inversion-reference"));
  }
  return references;
}

/** Reads, measures and prints one mesh. */
MeasuredMesh
MeasureFile(const std::string & path, const Arguments & args, const QualityReferences & references)
{
  Stopwatch watch;
  std::cerr << "measuring " << path << '\n';
  IOMeshType::Pointer mesh = ReadMeshFile(path);
  MeasureSettings     settings;
  settings.referenceSurface = references.referenceSurface;
  settings.referenceMesh = references.referenceMesh;
  settings.inversionReference = references.inversionReference;
  settings.selfIntersections = !args.Has("no-self-intersections");
  settings.outwardOrientation = !args.Has("no-orientation");
  if (references.referenceMesh || references.referenceSurface)
  {
    // Each triangle gets (N + 1)(N + 2) / 2 samples: 64 is finer than any use needs and
    // keeps the samples of a large mesh in memory.
    const long level = args.GetInteger("sampling-level", 2);
    if (level < 0 || level > 64)
    {
      throw UsageError("--sampling-level must be in [0, 64], got " + std::to_string(level));
    }
    settings.samplingLevel = static_cast<unsigned int>(level);
  }
  const MeasuredMesh measured = MeasureMesh(mesh, path, settings);
  PrintMeasuredMesh(measured, path, std::cout);
  std::cout << '\n';
  std::cerr << "  done in " << std::fixed << std::setprecision(2) << watch.Seconds() << " s\n" << std::defaultfloat;
  return measured;
}

/** With --require-valid: 1 (and a message) if a mesh is not a valid closed surface. */
int
ExitStatus(const std::vector<MeasuredMesh> & results, const Arguments & args)
{
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

int
RunQuality(const Arguments & args)
{
  for (const char * option : { "json", "csv" })
  {
    RequireNotAnInput(args.Get(option), args.positional, std::string("--") + option);
  }
  const QualityReferences   references = ReadReferences(args);
  std::vector<MeasuredMesh> results;
  for (const std::string & path : args.positional)
  {
    results.push_back(MeasureFile(path, args, references));
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
  return ExitStatus(results, args);
}
} // namespace

Command
MakeQualityCommand()
{
  Command c;
  c.name = "quality";
  c.summary = "measure triangle quality, integrity and accuracy of meshes";
  c.usage = "MESH [MESH...] [options]";
  c.description = "Measures each mesh (any format ITK reads) with TriangleMeshQualityCalculator: q_area, q_angle,\n"
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
    { "sampling-level",
      "N",
      "subdivisions per triangle edge for the Hausdorff samples",
      "2",
      OptionRange::Between(0, 64) },
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
  return c;
}

} // namespace MeshExtractionCLI
