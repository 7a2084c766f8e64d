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
#ifndef MeshExtractionQualityCommand_h
#define MeshExtractionQualityCommand_h

#include "MeshExtractionCommandHelpers.h"
#include "itkMeshExtractionJSON.h"
#include "itkMeshSurfaceDistanceCalculator.h"
#include "itkTriangleMeshQualityCalculator.h"

#include <fstream>

namespace MeshExtractionCLI
{
// ------------------------------------------------------------------------------
// quality
// ------------------------------------------------------------------------------
struct MeasuredMesh
{
  std::string                   name;
  ME::TriangleMeshQualityReport quality;
  bool                          hasDistance{ false };
  ME::MeshSurfaceDistanceReport distance;
};

inline void
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

inline void
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
    out << "  {\"mesh\": " << itk::MeshExtraction::JSONString{ meshes[i].name } << ", \"quality\": ";
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

inline void
PrintComparison(const std::vector<MeasuredMesh> & meshes, std::ostream & os)
{
  os << std::left << std::setw(28) << "mesh" << std::right << std::setw(10) << "triangles" << std::setw(9) << "q_area"
     << std::setw(9) << "q_angle" << std::setw(9) << "<0.3 %" << std::setw(11) << "smooth" << std::setw(9) << "val6 %"
     << std::setw(12) << "d_vert" << std::setw(12) << "d_face" << std::setw(12) << "hausdorff" << std::setw(7)
     << "valid" << '\n';
  for (const auto & m : meshes)
  {
    std::string name = m.name.size() > 27 ? "..." + m.name.substr(m.name.size() - 24) : m.name;
    os << std::left << std::setw(28) << name << std::right << std::setw(10) << m.quality.numberOfTriangles << std::fixed
       << std::setprecision(4) << std::setw(9) << m.quality.qArea.mean << std::setw(9) << m.quality.qAngle.mean
       << std::setprecision(2) << std::setw(9) << 100 * m.quality.fractionQAngleBelow03 << std::setprecision(5)
       << std::setw(11) << m.quality.meanSmoothness << std::setprecision(1) << std::setw(9)
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

inline int
RunQuality(const Arguments & args)
{
  // The reference for distances: a mesh file or a phantom's exact surface.
  IOMeshType::Pointer                   referenceMesh;
  itk::ImplicitSurfaceFunction::Pointer referenceSurface;
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

inline Command
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
  return c;
}
} // namespace MeshExtractionCLI

#endif
