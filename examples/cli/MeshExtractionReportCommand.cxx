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
// meshextraction report: an HTML page of meshes with a quality table, histograms and
// renderings.

#include "MeshExtractionCLI.h"

#include "itksys/SystemTools.hxx"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <iterator>

namespace MeshExtractionCLI
{
namespace
{
using HistogramMeasure = std::function<const ME::ValueStatistics &(const MeasuredMesh &)>;

/** The geometry of a histogram chart. */
struct Chart
{
  double width{ 680 };
  double height{ 300 };
  double left{ 50 };
  double bottom{ 40 };
  double top{ 30 };
  double plotWidth{ width - left - 20 };
  double plotHeight{ height - bottom - top };
};

/** The largest share of triangles in any bin of any mesh (at least 1e-9). */
double
LargestShare(const std::vector<MeasuredMesh> & meshes, const HistogramMeasure & measure)
{
  double largest = 0.0;
  for (const auto & m : meshes)
  {
    const auto & s = measure(m);
    for (auto count : s.histogram)
    {
      largest = std::max(largest, s.count ? static_cast<double>(count) / s.count : 0.0);
    }
  }
  return std::max(largest, 1e-9);
}

/** The title, the axes, the share ticks and the bin labels. */
void
WriteChartAxes(std::ostream &              out,
               const Chart &               chart,
               const std::string &         title,
               double                      largest,
               const ME::ValueStatistics & first)
{
  const auto   bins = first.histogram.size();
  const double group = chart.plotWidth / bins;
  out << "<text x='" << chart.left << "' y='18' font-size='13'>" << HtmlEscape(title) << "</text>\n";
  out << "<line x1='" << chart.left << "' y1='" << chart.top + chart.plotHeight << "' x2='"
      << chart.left + chart.plotWidth << "' y2='" << chart.top + chart.plotHeight << "' stroke='black'/>\n";
  for (int tick = 0; tick <= 4; ++tick)
  {
    const double fraction = largest * tick / 4.0;
    const double y = chart.top + chart.plotHeight * (1.0 - tick / 4.0);
    out << "<text x='" << chart.left - 6 << "' y='" << y + 4 << "' text-anchor='end'>" << std::fixed
        << std::setprecision(0) << 100.0 * fraction << "%</text>\n";
    out << "<line x1='" << chart.left << "' y1='" << y << "' x2='" << chart.left + chart.plotWidth << "' y2='" << y
        << "' stroke='#ddd'/>\n";
  }
  for (std::size_t b = 0; b <= bins; ++b)
  {
    const double v = first.histogramLower + (first.histogramUpper - first.histogramLower) * b / bins;
    out << "<text x='" << chart.left + group * b << "' y='" << chart.top + chart.plotHeight + 14
        << "' text-anchor='middle'>" << std::setprecision(1) << v << "</text>\n";
  }
}

/** Grouped bar chart of one histogram measure for every mesh, as SVG. */
void
WriteHistogramSVG(const std::vector<MeasuredMesh> & meshes,
                  const std::vector<std::string> &  names,
                  const HistogramMeasure &          measure,
                  const std::string &               title,
                  const std::string &               path)
{
  static const char * colours[] = { "#4e79a7", "#f28e2b", "#59a14f", "#e15759", "#76b7b2", "#edc948", "#b07aa1" };
  WriteTextWhole(path, [&](std::ostream & out) {
    const Chart  chart;
    const auto   bins = measure(meshes.front()).histogram.size();
    const double largest = LargestShare(meshes, measure);
    const double group = chart.plotWidth / bins;
    const double bar = 0.8 * group / meshes.size();
    out << "<svg xmlns='http://www.w3.org/2000/svg' width='" << chart.width << "' height='"
        << chart.height + 18 * meshes.size() << "' font-family='sans-serif' font-size='11'>\n";
    WriteChartAxes(out, chart, title, largest, measure(meshes.front()));
    for (std::size_t m = 0; m < meshes.size(); ++m)
    {
      const auto & s = measure(meshes[m]);
      for (std::size_t b = 0; b < s.histogram.size(); ++b)
      {
        const double fraction = s.count ? static_cast<double>(s.histogram[b]) / s.count : 0.0;
        const double h = chart.plotHeight * fraction / largest;
        out << "<rect x='" << chart.left + group * b + 0.1 * group + bar * m << "' y='"
            << chart.top + chart.plotHeight - h << "' width='" << bar << "' height='" << h << "' fill='"
            << colours[m % 7] << "'/>\n";
      }
      const double y = chart.height + 18 * m;
      out << "<rect x='" << chart.left << "' y='" << y - 10 << "' width='12' height='12' fill='" << colours[m % 7]
          << "'/><text x='" << chart.left + 18 << "' y='" << y << "'>" << HtmlEscape(names[m]) << " (mean "
          << std::setprecision(3) << s.mean << ")</text>\n";
    }
    out << "</svg>\n";
  });
}

/** The renderings of the mesh-th mesh are named by its position, never by its file
 * name: two inputs with the same name get their own pictures, and no file name ends
 * up in an HTML attribute. */
std::string
RenderingName(std::size_t mesh)
{
  return "mesh-" + std::to_string(mesh + 1);
}

/** Measures one mesh file and renders it twice: shaded, and coloured by q_area with
 * the triangles outlined (zoomed). */
MeasuredMesh
MeasureAndRender(const std::string &     path,
                 const std::string &     name,
                 const std::string &     directory,
                 const MeasureSettings & settings)
{
  std::cerr << "report: " << path << '\n';
  auto                          mesh = ReadMeshFile(path);
  std::vector<double>           qArea;
  const MeasuredMesh            measured = MeasureMesh(mesh, path, settings, &qArea);
  const ME::IndexedTriangleMesh flat = ME::MakeIndexedTriangleMesh(*mesh);
  RenderOptions                 view;
  RenderMesh(flat, view, directory + "/" + name + ".png");
  view.triangleValues = &qArea;
  view.outlineTriangles = true;
  view.zoom = std::max(1.0, std::sqrt(static_cast<double>(flat.triangles.size())) / 60.0);
  RenderMesh(flat, view, directory + "/" + name + "-q_area.png");
  return measured;
}

/** The page's head, title and the line that says what was measured. */
void
WriteHtmlHead(std::ostream & html, const std::string & title, const MeasureSettings & settings)
{
  html << "<!DOCTYPE html>\n<html><head><meta charset='utf-8'><title>" << HtmlEscape(title)
       << "</title>\n<style>body{font-family:sans-serif;margin:2em;max-width:1400px} "
          "table{border-collapse:collapse} td,th{border:1px solid #ccc;padding:3px 8px;text-align:right} "
          "th{background:#f3f3f3} td:first-child{text-align:left} .bad{color:#b00;font-weight:bold} "
          "figure{display:inline-block;margin:6px} figcaption{font-size:12px;text-align:center}</style>"
          "</head><body>\n<h1>"
       << HtmlEscape(title) << "</h1>\n";
  html << "<p>Measured with TriangleMeshQualityCalculator and MeshSurfaceDistanceCalculator (thesis "
          "sections 2.2.2, 3.3, 4.2.3). q_area and q_angle are 1 for an equilateral triangle. Distances are "
          "in mm"
       << (settings.referenceSurface != nullptr ? " to the phantom's exact surface"
           : settings.referenceMesh != nullptr  ? " to the reference mesh"
                                                : "")
       << ".</p>\n";
}

/** The table of the figures, one row per mesh. */
void
WriteHtmlTable(std::ostream & html, const std::vector<MeasuredMesh> & meshes, const std::vector<std::string> & names)
{
  html << "<table><tr><th>mesh</th><th>triangles</th><th>mean q_area</th><th>mean "
          "q_angle</th><th>q_angle&lt;0.3</th>"
          "<th>smoothness</th><th>valence 6</th><th>mean dist. vertices</th><th>mean dist. centroids</th>"
          "<th>Hausdorff</th><th>components</th><th>genus</th><th>closed, manifold, oriented, no defects</th></tr>\n";
  for (std::size_t m = 0; m < meshes.size(); ++m)
  {
    const auto & q = meshes[m].quality;
    html << "<tr><td>" << HtmlEscape(names[m]) << "</td><td>" << q.numberOfTriangles << "</td><td>" << std::fixed
         << std::setprecision(3) << q.qArea.mean << "</td><td>" << q.qAngle.mean << "</td><td>" << std::setprecision(2)
         << 100.0 * q.fractionQAngleBelow03 << " %</td><td>" << std::setprecision(4) << q.meanSmoothness << "</td><td>"
         << std::setprecision(1) << 100.0 * q.fractionValence6 << " %</td>";
    if (meshes[m].hasDistance)
    {
      const auto & d = meshes[m].distance;
      html << std::setprecision(4) << "<td>" << d.vertices.mean << "</td><td>" << d.faceCentroids.mean << "</td><td>"
           << d.hausdorff << "</td>";
    }
    else
    {
      html << "<td>-</td><td>-</td><td>-</td>";
    }
    html << "<td>" << q.connectedComponents << "</td><td>" << q.genus << "</td><td"
         << (q.IsValidClosedSurface() ? ">yes" : " class='bad'>NO") << "</td></tr>\n";
  }
  html << "</table>\n";
}

/** The histograms, the renderings and the --include file. */
void
WriteHtmlFigures(std::ostream & html, const std::vector<std::string> & names, const Arguments & args)
{
  html << "<h2>Triangle quality</h2>\n<img src='q_area.svg'> <img src='q_angle.svg'>\n<h2>Meshes</h2>\n";
  for (std::size_t m = 0; m < names.size(); ++m)
  {
    const std::string & name = names[m];
    html << "<figure><img src='" << RenderingName(m) << ".png' width='480'><figcaption>" << HtmlEscape(name)
         << "</figcaption></figure><figure><img src='" << RenderingName(m) << "-q_area.png' width='480'><figcaption>"
         << HtmlEscape(name) << ": q_area (red 0, blue 1), centre magnified</figcaption></figure><br>\n";
  }
  if (args.Has("include"))
  {
    std::ifstream extra(args.Get("include"));
    if (!extra)
    {
      itkGenericExceptionMacro("cannot read '" << args.Get("include") << "'");
    }
    html << "<h2>" << HtmlEscape(itksys::SystemTools::GetFilenameName(args.Get("include"))) << "</h2>\n<pre>"
         << HtmlEscape(std::string(std::istreambuf_iterator<char>(extra), std::istreambuf_iterator<char>()))
         << "</pre>\n";
  }
  html << "<p>Files: report.json (all measures), histograms.csv.</p></body></html>\n";
}

/** report.json, histograms.csv and the two histogram charts. */
void
WriteFigureFiles(const std::vector<MeasuredMesh> & meshes,
                 const std::vector<std::string> &  names,
                 const std::string &               directory)
{
  WriteJSON(meshes, directory + "/report.json");
  WriteHistogramsCSV(meshes, directory + "/histograms.csv");
  WriteHistogramSVG(
    meshes,
    names,
    [](const MeasuredMesh & m) -> const ME::ValueStatistics & { return m.quality.qArea; },
    "q_area = 4 sqrt(3) A / sum e^2 (share of triangles)",
    directory + "/q_area.svg");
  WriteHistogramSVG(
    meshes,
    names,
    [](const MeasuredMesh & m) -> const ME::ValueStatistics & { return m.quality.qAngle; },
    "q_angle = smallest / largest angle (share of triangles)",
    directory + "/q_angle.svg");
}

int
RunReport(const Arguments & args)
{
  // Made in a staging folder and moved in when whole: a failed run leaves an earlier
  // report in the folder as it was.
  StagedDirectory                       staged(args.positional.front());
  const std::string                     directory = staged.Path();
  itk::ImplicitSurfaceFunction::Pointer surface;
  IOMeshType::Pointer                   referenceMesh;
  if (args.Has("phantom"))
  {
    const ME::PhantomShape shape = ShapeFromName(args.Get("phantom"));
    surface = ME::MakePhantomSurface(
      shape, args.Has("image") ? ReadImageGrid(args.Get("image")) : GridFromArguments(shape, args));
  }
  if (args.Has("reference-mesh"))
  {
    referenceMesh = ReadMeshFile(args.Get("reference-mesh"));
  }
  MeasureSettings settings;
  settings.referenceSurface = surface;
  settings.referenceMesh = referenceMesh;
  std::vector<MeasuredMesh> meshes;
  std::vector<std::string>  names;
  for (std::size_t i = 1; i < args.positional.size(); ++i)
  {
    const std::string & path = args.positional[i];
    names.push_back(itksys::SystemTools::GetFilenameWithoutLastExtension(path));
    meshes.push_back(MeasureAndRender(path, RenderingName(i - 1), directory, settings));
  }
  WriteFigureFiles(meshes, names, directory);
  WriteTextWhole(directory + "/index.html", [&](std::ostream & html) {
    WriteHtmlHead(html, args.Get("title", "MeshExtraction report"), settings);
    WriteHtmlTable(html, meshes, names);
    WriteHtmlFigures(html, names, args);
  });
  staged.Commit("index.html");
  const std::string page = args.positional.front() + "/index.html";
  std::cout << "report: " << page << '\n';
  return 0;
}
} // namespace

Command
MakeReportCommand()
{
  Command c;
  c.name = "report";
  c.summary = "write an HTML report of meshes: quality table, histograms, renderings";
  c.usage = "OUTDIR MESH [MESH...] [options]";
  c.description = "Measures each mesh like 'quality' and writes OUTDIR/index.html with a table of the figures,\n"
                  "q_area and q_angle histograms (SVG) and two renderings per mesh (PNG, rendered in software:\n"
                  "shaded, and coloured by q_area with the triangles outlined), plus report.json and\n"
                  "histograms.csv. Distances are measured to --phantom's exact surface or --reference-mesh.";
  c.options = {
    { "phantom", "NAME", "measure distances to this phantom's exact surface", "" },
    { "image", "FILE", "the phantom's grid, from this image", "" },
    { "reference-mesh", "FILE", "measure distances to this mesh", "" },
    { "title", "TEXT", "title of the page", "MeshExtraction report" },
    { "include", "FILE", "append this text file (e.g. a comparison table) to the page", "" },
  };
  for (const auto & o : GridOptions())
  {
    c.options.push_back(o);
  }
  c.minimumPositional = 2;
  c.run = RunReport;
  return c;
}

} // namespace MeshExtractionCLI
