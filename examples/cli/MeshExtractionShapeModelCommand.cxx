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

// meshextraction shape-model: the landmark-free statistical shape model (thesis chapter
// 7) of closed meshes, written as a statismo HDF5 file, with every input's corresponded
// mesh on the model's topology.

#include "MeshExtractionShapeModelCLI.h"

#include "itkMeshExtractionJSON.h"
#include "itkMeshExtractionLandmarkFile.h"
#include "itkMeshExtractionPLY.h"
#include "itkMeshExtractionShapeModelEvaluation.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <random>
#include <sstream>

namespace MeshExtractionCLI
{
namespace
{
using Estimator = ShapeModelEstimator;
using Correspondence = itk::MeshExtractionEnums::Correspondence;

const OptionNames<Correspondence> &
CorrespondenceNames()
{
  static const OptionNames<Correspondence> names{ { "surface", Correspondence::PointToSurface },
                                                  { "point", Correspondence::PointToPoint } };
  return names;
}

/** A mesh file: PLY by the module's reader, any other format by ITK's. */
IOMeshType::Pointer
ReadTrainingMesh(const std::string & path)
{
  if (std::filesystem::path(path).extension() != ".ply")
  {
    return ReadMeshFile(path);
  }
  auto mesh = IOMeshType::New();
  ME::FillMesh(ME::ReadPLYFile(path), *mesh);
  return mesh;
}

/** A mesh on the model's topology: PLY by the module's writer, any other format by ITK's. */
void
WriteModelMesh(const std::string & path, const ME::IndexedTriangleMesh & mesh)
{
  if (std::filesystem::path(path).extension() == ".ply")
  {
    WriteWhole(path, [&mesh](const std::string & partial) { ME::WritePLYFile(partial, mesh); });
    return;
  }
  auto out = IOMeshType::New();
  ME::FillMesh(mesh, *out);
  WriteMeshFile(out.GetPointer(), path);
}

/** Corresponded mesh i, named after its input, into `directory` (PLY or VTK after the input). */
void
WriteCorresponded(const Estimator & estimator, const std::vector<std::string> & inputs, const std::string & directory)
{
  std::filesystem::create_directories(directory);
  for (unsigned int i = 0; i < inputs.size(); ++i)
  {
    const std::filesystem::path input(inputs[i]);
    const bool                  ply = input.extension() == ".ply";
    WriteModelMesh((std::filesystem::path(directory) / (input.stem().string() + (ply ? ".ply" : ".vtk"))).string(),
                   ME::MakeIndexedTriangleMesh(*estimator.GetCorrespondedMesh(i)));
  }
  std::cout << "corresponded meshes written to " << directory << '\n';
}

/** The model's summary (meshextraction shape-model build|finish --json): modes and
 * variances at full precision, so that builds can be compared exactly. */
struct ModelSummary
{
  std::vector<double> variances;    ///< of the kept modes
  std::vector<double> allVariances; ///< all m - 1
  double              totalVariance{ 0.0 };
  std::size_t         pivot{ 0 };
  std::size_t         passes{ 0 };
  std::size_t         meshes{ 0 };

  /** The cumulative fraction of the variance in the first k + 1 modes (all modes). */
  std::vector<double>
  Cumulative() const
  {
    return ME::detail::CumulativeVarianceFractions(allVariances);
  }
};

ModelSummary
Summarize(const ME::detail::ShapeModelBuildResult & result)
{
  return { result.model.variances, result.allVariances,           result.model.totalVariance,
           result.pivot,            result.templateChanges.size(), result.corresponded.size() };
}

void
PrintModel(const ModelSummary & summary, double seconds)
{
  std::cout << "model built in " << std::fixed << std::setprecision(1) << seconds << " s: pivot input "
            << summary.pivot << ", " << summary.passes << " template passes, " << summary.variances.size()
            << " modes\ncumulative variance (%):";
  const std::vector<double> cumulative = summary.Cumulative();
  for (std::size_t k = 0; k < summary.variances.size(); ++k)
  {
    std::cout << ' ' << k + 1 << ':' << 100.0 * cumulative[k];
  }
  std::cout << std::defaultfloat << '\n';
}

void
WriteNumbers(std::ostream & out, const std::vector<double> & values)
{
  out << '[';
  for (std::size_t k = 0; k < values.size(); ++k)
  {
    out << (k ? ", " : "") << ME::detail::JSONNumber{ values[k] };
  }
  out << ']';
}

void
WriteSummary(const ModelSummary & summary, const std::string & path)
{
  WriteTextWhole(path, [&summary](std::ostream & out) {
    out << std::setprecision(17) << "{\"modes\": " << summary.variances.size() << ", \"variances\": ";
    WriteNumbers(out, summary.variances);
    out << ", \"all_variances\": ";
    WriteNumbers(out, summary.allVariances);
    out << ", \"total_variance\": " << ME::detail::JSONNumber{ summary.totalVariance } << ", \"pivot\": " << summary.pivot
        << ", \"passes\": " << summary.passes << ", \"meshes\": " << summary.meshes << "}\n";
  });
}

/** The file names without folder and extensions (a.state.json: a), naming meshes in reports. */
std::vector<std::string>
Stems(const std::vector<std::string> & paths)
{
  std::vector<std::string> stems;
  for (const std::string & path : paths)
  {
    const std::string name = std::filesystem::path(path).filename().string();
    stems.push_back(name.substr(0, name.find('.')));
  }
  return stems;
}

/** The cumulative variance against the number of modes (thesis Fig. 7.2), as SVG; the
 * first `kept` modes marked. */
void
WriteCompactnessSVG(const std::vector<double> & cumulative, std::size_t kept, const std::string & path)
{
  WriteTextWhole(path, [&](std::ostream & out) {
    const double      width = 520, height = 300, left = 50, top = 30, plotWidth = 440, plotHeight = 220;
    const std::size_t n = cumulative.size();
    const auto        x = [&](double k) { return left + plotWidth * k / static_cast<double>(n); };
    const auto        y = [&](double fraction) { return top + plotHeight * (1.0 - fraction); };
    out << "<svg xmlns='http://www.w3.org/2000/svg' width='" << width << "' height='" << height
        << "' font-family='sans-serif' font-size='11'>\n<text x='" << left
        << "' y='18' font-size='13'>Cumulative variance (%) against the number of modes</text>\n"
        << "<rect x='" << left << "' y='" << top << "' width='" << plotWidth << "' height='" << plotHeight
        << "' fill='none' stroke='#999'/>\n";
    for (int percent = 0; percent <= 100; percent += 20)
    {
      out << "<text x='" << left - 6 << "' y='" << y(percent / 100.0) + 4 << "' text-anchor='end'>" << percent
          << "</text>\n";
    }
    out << "<polyline fill='none' stroke='#4e79a7' stroke-width='2' points='" << x(0) << ',' << y(0);
    for (std::size_t k = 0; k < n; ++k)
    {
      out << ' ' << x(k + 1) << ',' << y(cumulative[k]);
    }
    out << "'/>\n";
    for (std::size_t k = 0; k < n; ++k)
    {
      out << "<circle cx='" << x(k + 1) << "' cy='" << y(cumulative[k]) << "' r='3' fill='"
          << (k < kept ? "#4e79a7" : "#bbb") << "'/>\n<text x='" << x(k + 1) << "' y='" << top + plotHeight + 14
          << "' text-anchor='middle'>" << k + 1 << "</text>\n";
    }
    out << "</svg>\n";
  });
}

/** An HTML page of the model: compactness, the variance table, and renderings of the
 * mean and of the first modes at -2 and +2 standard deviations. */
void
WriteModelReport(const ModelSummary &                                                        summary,
                 const std::function<ME::IndexedTriangleMesh(const std::vector<double> &)> & synthesize,
                 const std::vector<double> &                                                 e2,
                 const std::vector<std::string> &                                            names,
                 const std::string &                                                         target)
{
  // Made in a staging folder and moved in when whole (an earlier report stays as it was
  // if this one fails).
  StagedDirectory           staged(target);
  const std::string         directory = staged.Path();
  const std::size_t         modes = summary.variances.size();
  const std::vector<double> cumulative = summary.Cumulative();
  WriteCompactnessSVG(cumulative, modes, directory + "/compactness.svg");
  RenderOptions view;
  view.width = 360;
  view.height = 300;
  const auto render = [&](const std::vector<double> & b, const std::string & file) {
    RenderMesh(synthesize(b), view, directory + "/" + file);
  };
  const ME::IndexedTriangleMesh mean = synthesize({});
  RenderMesh(mean, view, directory + "/mean.png");
  const std::size_t points = mean.points.size();
  const std::size_t shown = std::min<std::size_t>(3, modes);
  for (std::size_t mode = 0; mode < shown; ++mode)
  {
    for (const double s : { -2.0, 2.0 })
    {
      std::vector<double> b(mode + 1, 0.0);
      b[mode] = s;
      render(b, "mode" + std::to_string(mode + 1) + (s < 0 ? "-minus2.png" : "-plus2.png"));
    }
  }
  WriteTextWhole(directory + "/index.html", [&](std::ostream & out) {
    out << "<!DOCTYPE html>\n<html><head><meta charset='utf-8'><title>Shape model</title>\n"
        << "<style>body{font-family:sans-serif;margin:2em}table{border-collapse:collapse}"
        << "td,th{border:1px solid #ccc;padding:3px 8px;text-align:right}</style></head><body>\n"
        << "<h1>Shape model</h1>\n<p>" << summary.meshes << " meshes, pivot "
        << HtmlEscape(summary.pivot < names.size() ? names[summary.pivot] : std::to_string(summary.pivot)) << ", "
        << summary.passes << " template passes, " << points << " points, " << modes << " modes kept.</p>\n<h2>Compactness</h2>\n<img src='compactness.svg'>\n"
        << "<table><tr><th>mode</th><th>variance (mm&sup2;)</th><th>%</th><th>cumulative %</th></tr>\n";
    for (std::size_t k = 0; k < summary.allVariances.size(); ++k)
    {
      out << "<tr><td>" << k + 1 << (k < modes ? "" : " (not kept)") << "</td><td>" << std::setprecision(6)
          << summary.allVariances[k] << "</td><td>" << std::fixed << std::setprecision(1)
          << 100.0 * summary.allVariances[k] / summary.totalVariance << "</td><td>" << 100.0 * cumulative[k]
          << "</td></tr>\n"
          << std::defaultfloat;
    }
    out << "</table>\n<h2>The mean and the first modes at &minus;2 and +2 standard deviations</h2>\n"
        << "<p><img src='mean.png' title='mean'></p>\n";
    for (std::size_t mode = 0; mode < shown; ++mode)
    {
      out << "<p>mode " << mode + 1 << ": <img src='mode" << mode + 1 << "-minus2.png'> <img src='mode" << mode + 1
          << "-plus2.png'></p>\n";
    }
    if (!e2.empty())
    {
      out << "<h2>Similarity ICP of the last pass</h2>\n<table><tr><th>mesh</th><th>E&sup2; (mm&sup2;)</th></tr>\n";
      for (std::size_t i = 0; i < e2.size(); ++i)
      {
        out << "<tr><td>" << HtmlEscape(i < names.size() ? names[i] : std::to_string(i)) << "</td><td>"
            << std::setprecision(4) << e2[i] << "</td></tr>\n";
      }
      out << "</table>\n";
    }
    out << "</body></html>\n";
  });
  staged.Commit("index.html");
  std::cout << "report written to " << target << "/index.html\n";
}

int
RunShapeModel(const Arguments & args)
{
  auto                             estimator = Estimator::New();
  std::vector<IOMeshType::Pointer> meshes;
  const std::vector<std::string>   inputs(args.positional.begin() + 1, args.positional.end());
  for (const std::string & path : inputs)
  {
    meshes.push_back(ReadTrainingMesh(path));
    estimator->AddInputMesh(meshes.back());
  }
  ConfigureShapeModelEstimator(*estimator, args);
  Stopwatch watch;
  estimator->Update();
  ModelSummary summary;
  summary.variances = estimator->GetVariances();
  summary.pivot = estimator->GetPivotIndex();
  summary.passes = estimator->GetNumberOfPasses();
  summary.meshes = meshes.size();
  summary.allVariances = estimator->GetAllVariances();
  summary.totalVariance = estimator->GetTotalVariance();
  PrintModel(summary, watch.Seconds());
  if (args.Has("report"))
  {
    WriteModelReport(
      summary,
      [&estimator](const std::vector<double> & b) { return ME::MakeIndexedTriangleMesh(*estimator->Synthesize(b)); },
      {},
      Stems(inputs),
      args.Get("report"));
  }
  WriteWhole(args.Get("output"), [&estimator](const std::string & partial) { estimator->WriteModel(partial); });
  std::cout << "model written to " << args.Get("output") << '\n';
  if (args.Has("corresponded"))
  {
    WriteCorresponded(*estimator, inputs, args.Get("corresponded"));
  }
  if (args.Has("json"))
  {
    WriteSummary(summary, args.Get("json"));
  }
  return 0;
}
// ---- the steps of a build spread over processes (meshextraction-cohort shape-model) ----
// prepare, match (per mesh, per pass), renew (the pass's reduction), finish (Procrustes
// and PCA). Points travel between the steps as double-precision PLY and the similarities
// as JSON numbers of 17 digits, so the steps give the model `build` gives.

/** A mesh a step wrote (or any mesh): PLY read as it is, in double precision (the CLI's
 * itk::Mesh holds float coordinates, which would round what the steps pass on). */
ME::IndexedTriangleMesh
ReadStepMesh(const std::string & path)
{
  if (std::filesystem::path(path).extension() == ".ply")
  {
    return ME::ReadPLYFile(path);
  }
  return ME::MakeIndexedTriangleMesh(*ReadTrainingMesh(path));
}

/** A mesh made ready (PrepareTrainingMesh), named by its path in errors. */
ME::IndexedTriangleMesh
ReadPrepared(const std::string & path)
{
  return ME::detail::PrepareTrainingMesh(ReadStepMesh(path), "mesh " + path);
}

void
WritePoints(const std::string & path, const ME::IndexedTriangleMesh & topology, const ME::detail::Shape & points)
{
  ME::IndexedTriangleMesh mesh;
  mesh.points = points;
  mesh.triangles = topology.triangles;
  WriteWhole(path, [&mesh](const std::string & partial) { ME::WritePLYFile(partial, mesh, true); });
}

ME::JSONValue
ReadJSONFile(const std::string & path)
{
  std::ifstream in(path);
  if (!in)
  {
    itkGenericExceptionMacro(<< "Cannot read " << path << '.');
  }
  std::ostringstream text;
  text << in.rdbuf();
  return ME::ParseJSON(text.str(), path);
}

const ME::JSONValue &
Member(const ME::JSONValue & object, const std::string & name, const std::string & path)
{
  const ME::JSONValue * member = object.Find(name);
  if (member == nullptr)
  {
    itkGenericExceptionMacro(<< path << " has no member \"" << name << "\".");
  }
  return *member;
}

double
NumberOf(const ME::JSONValue & value, const std::string & what)
{
  if (value.kind != ME::JSONValue::Kind::Number || !std::isfinite(value.number))
  {
    itkGenericExceptionMacro(<< what << " must be a finite number.");
  }
  return value.number;
}

std::vector<double>
NumbersOf(const ME::JSONValue & value, std::size_t count, const std::string & what)
{
  if (value.kind != ME::JSONValue::Kind::Array || value.elements.size() != count)
  {
    itkGenericExceptionMacro(<< what << " must be an array of " << count << " numbers.");
  }
  std::vector<double> numbers;
  for (const ME::JSONValue & element : value.elements)
  {
    numbers.push_back(NumberOf(element, what));
  }
  return numbers;
}

/** An exception naming `what` unless the rotation is a proper rotation (orthonormal,
 * determinant +1, to the digits a state file holds) and the scale positive: what the
 * steps write, and what the next step's arithmetic needs. */
void
RequireSimilarity(const ME::detail::SimilarityParameters & t, const std::string & what)
{
  double largest = 0.0; // of R^T R - I
  for (unsigned int i = 0; i < 3; ++i)
  {
    for (unsigned int j = 0; j < 3; ++j)
    {
      double dot = 0.0;
      for (unsigned int k = 0; k < 3; ++k)
      {
        dot += t.rotation[k][i] * t.rotation[k][j];
      }
      largest = std::max(largest, std::abs(dot - (i == j ? 1.0 : 0.0)));
    }
  }
  const auto & r = t.rotation;
  const double determinant = r[0][0] * (r[1][1] * r[2][2] - r[1][2] * r[2][1]) -
                             r[0][1] * (r[1][0] * r[2][2] - r[1][2] * r[2][0]) +
                             r[0][2] * (r[1][0] * r[2][1] - r[1][1] * r[2][0]);
  if (!(largest <= 1e-6) || !(determinant > 0.0))
  {
    itkGenericExceptionMacro(<< what << ": the rotation is not a proper rotation (R^T R differs from I by " << largest
                             << ", det R = " << determinant << ").");
  }
  if (!(t.scale > 0.0))
  {
    itkGenericExceptionMacro(<< what << ": the scale is " << t.scale << "; it must be positive.");
  }
}

ME::detail::SimilarityParameters
ReadSimilarity(const std::string & path, const std::string & name)
{
  const ME::JSONValue      document = ReadJSONFile(path);
  const ME::JSONValue &    object = Member(document, name, path);
  ME::detail::SimilarityParameters t;
  const std::vector<double>        rotation = NumbersOf(Member(object, "rotation", path), 9, path + ": rotation");
  const std::vector<double>        translation =
    NumbersOf(Member(object, "translation", path), 3, path + ": translation");
  t.scale = NumberOf(Member(object, "scale", path), path + ": scale");
  for (unsigned int k = 0; k < 9; ++k)
  {
    t.rotation[k / 3][k % 3] = rotation[k];
  }
  t.translation = ME::MakeVec3(translation[0], translation[1], translation[2]);
  RequireSimilarity(t, path + ": \"" + name + "\"");
  return t;
}

void
WriteSimilarity(std::ostream & out, const ME::detail::SimilarityParameters & t)
{
  out << "{\"rotation\": [";
  for (unsigned int k = 0; k < 9; ++k)
  {
    out << (k ? ", " : "") << ME::detail::JSONNumber{ t.rotation[k / 3][k % 3] };
  }
  out << "], \"scale\": " << ME::detail::JSONNumber{ t.scale } << ", \"translation\": ["
      << ME::detail::JSONNumber{ t.translation[0] } << ", " << ME::detail::JSONNumber{ t.translation[1] } << ", "
      << ME::detail::JSONNumber{ t.translation[2] } << "]}";
}

/** A match's state file: its similarity, E^2 and the corresponded mesh (read back). */
ME::detail::TemplateMatch
ReadMatchState(const std::string & path)
{
  const ME::JSONValue document = ReadJSONFile(path);
  const ME::JSONValue & corresponded = Member(document, "corresponded", path);
  if (corresponded.kind != ME::JSONValue::Kind::String)
  {
    itkGenericExceptionMacro(<< path << ": \"corresponded\" must name the corresponded mesh.");
  }
  ME::detail::TemplateMatch match;
  match.templateToMesh = ReadSimilarity(path, "template_to_mesh");
  match.e2 = NumberOf(Member(document, "e2", path), path + ": e2");
  if (match.e2 < 0.0)
  {
    itkGenericExceptionMacro(<< path << ": e2 is " << match.e2 << "; a mean squared distance is not negative.");
  }
  match.corresponded = ReadStepMesh(corresponded.text).points;
  return match;
}

int
RunPrepare(const Arguments & args)
{
  std::size_t         dropped = 0;
  const std::string & input = args.positional[1];
  // Read as build reads its inputs, so that both start from the same points.
  const ME::IndexedTriangleMesh mesh =
    ME::detail::PrepareTrainingMesh(ME::MakeIndexedTriangleMesh(*ReadTrainingMesh(input)), "mesh " + input, &dropped);
  WritePoints(args.Get("output"), mesh, mesh.points);
  std::cout << input << ": " << mesh.points.size() << " points, " << mesh.triangles.size() << " triangles ("
            << dropped << " vertices of other components dropped)\n";
  if (args.Has("json"))
  {
    WriteTextWhole(args.Get("json"), [&](std::ostream & out) {
      out << "{\"points\": " << mesh.points.size() << ", \"triangles\": " << mesh.triangles.size()
          << ", \"dropped_vertices\": " << dropped << "}\n";
    });
  }
  return 0;
}

int
RunMatch(const Arguments & args)
{
  if (args.Has("gauge") != args.Has("initial"))
  {
    throw UsageError("--initial and --gauge go together (the previous pass's state and renewal)");
  }
  const ME::IndexedTriangleMesh    templateMesh = ReadPrepared(args.positional[1]);
  const ME::IndexedTriangleMesh    mesh = ReadPrepared(args.positional[2]);
  const auto                       settings = ShapeModelSettingsOf(args);
  ME::detail::SimilarityParameters initial;
  if (args.Has("initial"))
  {
    initial = ME::detail::Compose(ReadSimilarity(args.Get("initial"), "template_to_mesh"),
                                  ReadSimilarity(args.Get("gauge"), "gauge").Inverse());
  }
  Stopwatch                       watch;
  const ME::detail::TemplateMatch match =
    ME::detail::MatchTemplate(templateMesh, mesh, settings, args.Has("initial") ? &initial : nullptr);
  const std::string output = std::filesystem::absolute(args.Get("output")).string();
  WritePoints(output, templateMesh, match.corresponded);
  WriteTextWhole(args.Get("json"), [&](std::ostream & out) {
    out << std::setprecision(17) << "{\"e2\": " << ME::detail::JSONNumber{ match.e2 } << ", \"template_to_mesh\": ";
    WriteSimilarity(out, match.templateToMesh);
    out << ", \"corresponded\": " << ME::detail::JSONString{ output } << ", \"points\": " << match.corresponded.size()
        << "}\n";
  });
  std::cout << args.positional[2] << " matched in " << std::fixed << std::setprecision(1) << watch.Seconds()
            << " s: E^2 " << std::setprecision(4) << match.e2 << " mm^2\n";
  return 0;
}

std::vector<ME::detail::TemplateMatch>
ReadMatchStates(const Arguments & args)
{
  std::vector<ME::detail::TemplateMatch> matches;
  for (std::size_t k = 2; k < args.positional.size(); ++k)
  {
    matches.push_back(ReadMatchState(args.positional[k]));
  }
  return matches;
}

int
RunRenew(const Arguments & args)
{
  const ME::IndexedTriangleMesh     templateMesh = ReadPrepared(args.positional[1]);
  const ME::detail::RenewedTemplate renewed =
    ME::detail::RenewTemplate(templateMesh, ReadMatchStates(args), ShapeModelSettingsOf(args));
  WritePoints(args.Get("output"), templateMesh, renewed.points);
  WriteTextWhole(args.Get("json"), [&](std::ostream & out) {
    out << std::setprecision(17) << "{\"change\": " << ME::detail::JSONNumber{ renewed.change } << ", \"gauge\": ";
    WriteSimilarity(out, renewed.gauge);
    out << "}\n";
  });
  std::cout << "template renewed from " << args.positional.size() - 2 << " meshes: it moved " << std::setprecision(4)
            << renewed.change << " mm (RMS)\n";
  return 0;
}

int
RunFinish(const Arguments & args)
{
  const ME::IndexedTriangleMesh     templateMesh = ReadPrepared(args.positional[1]);
  ME::detail::ShapeModelBuildResult result;
  result.triangles = templateMesh.triangles;
  result.pivot = static_cast<std::size_t>(args.GetInteger("pivot", 0));
  for (const ME::detail::TemplateMatch & match : ReadMatchStates(args))
  {
    ME::detail::CheckMatchOfTemplate(templateMesh, match);
    result.corresponded.push_back(match.corresponded);
    result.e2.push_back(match.e2);
  }
  result.templateChanges.assign(static_cast<std::size_t>(args.GetInteger("passes", 2)), 0.0);
  Stopwatch watch;
  ME::detail::FinishShapeModel(result, ShapeModelSettingsOf(args).varianceFraction);
  const ModelSummary summary = Summarize(result);
  PrintModel(summary, watch.Seconds());
  if (args.Has("report"))
  {
    WriteModelReport(
      summary,
      [&result](const std::vector<double> & b) {
        return ME::detail::ModelMesh(result, ME::detail::SynthesizeInStandardDeviations(result.model, b));
      },
      result.e2,
      Stems({ args.positional.begin() + 2, args.positional.end() }),
      args.Get("report"));
  }
  WriteWhole(args.Get("output"),
             [&result](const std::string & partial) { ME::detail::WriteShapeModel(partial, result); });
  std::cout << "model written to " << args.Get("output") << '\n';
  if (args.Has("json"))
  {
    WriteSummary(summary, args.Get("json"));
  }
  return 0;
}

// ---- using a model: sample and project ---------------------------------------------------

/** A model file read back, as the builder's result (model and topology). */
ME::detail::ShapeModelBuildResult
ReadModel(const std::string & path)
{
  ME::detail::ShapeModelBuildResult result;
  result.model = ME::detail::ReadStatismoModel(path, result.triangles);
  return result;
}

/** Coefficients in standard deviations: --coefficients, or (--random-seed) drawn from the
 * standard normal and kept within +-2 (thesis: |b_i| <= 2 sqrt(lambda_i)). */
std::vector<double>
CoefficientsOf(const Arguments & args, std::size_t modes)
{
  if (args.Has("random-seed"))
  {
    std::mt19937_64                  random(static_cast<std::uint64_t>(args.GetInteger("random-seed", 0)));
    std::normal_distribution<double> normal;
    std::vector<double>              b(modes);
    for (double & x : b)
    {
      x = std::max(-2.0, std::min(2.0, normal(random)));
    }
    return b;
  }
  if (!args.Has("coefficients"))
  {
    return {};
  }
  const std::string text = args.Get("coefficients");
  return args.GetNumbers("coefficients", 1 + static_cast<unsigned int>(std::count(text.begin(), text.end(), ',')));
}

int
RunSample(const Arguments & args)
{
  if (args.Has("random-seed") && args.Has("coefficients"))
  {
    throw UsageError("give --coefficients or --random-seed, not both");
  }
  const ME::detail::ShapeModelBuildResult result = ReadModel(args.positional[1]);
  const std::vector<double>               b = CoefficientsOf(args, result.model.NumberOfModes());
  const ME::IndexedTriangleMesh           mesh =
    ME::detail::ModelMesh(result, ME::detail::SynthesizeInStandardDeviations(result.model, b));
  WriteModelMesh(args.Get("output"), mesh);
  std::cout << "sample of " << result.model.NumberOfModes() << " modes at (standard deviations):";
  for (double x : b)
  {
    std::cout << ' ' << x;
  }
  std::cout << (b.empty() ? " 0 (the mean)" : "") << "\nwritten to " << args.Get("output") << '\n';
  return 0;
}

/** A new mesh's coefficients: the model's mean matched to it (similarity ICP and the
 * correspondence of the build), aligned to the mean and projected; the residual is what
 * the modes do not explain (RMS over the vertices, mm in the model's frame). */
int
RunProject(const Arguments & args)
{
  const ME::detail::ShapeModelBuildResult result = ReadModel(args.positional[1]);
  ME::IndexedTriangleMesh                 mean = ME::detail::ModelMesh(result, result.model.mean);
  const ME::IndexedTriangleMesh           mesh = ReadPrepared(args.positional[2]);
  Stopwatch                               watch;
  const ME::detail::TemplateMatch match = ME::detail::MatchTemplate(mean, mesh, ShapeModelSettingsOf(args), nullptr);
  const std::vector<double>       b = ME::detail::ProjectInStandardDeviations(result, match.corresponded);
  const ME::detail::Shape         aligned =
    ME::detail::ApplySimilarity(ME::detail::AlignShape(match.corresponded, mean.points, true), match.corresponded);
  const std::vector<double> reconstruction = ME::detail::SynthesizeInStandardDeviations(result.model, b);
  double                    sum = 0.0;
  for (std::size_t k = 0; k < aligned.size(); ++k)
  {
    sum += ME::SquaredNorm(aligned[k] -
                           ME::MakeVec3(reconstruction[3 * k], reconstruction[3 * k + 1], reconstruction[3 * k + 2]));
  }
  const double residual = std::sqrt(sum / static_cast<double>(aligned.size()));
  std::cout << args.positional[2] << " projected in " << std::fixed << std::setprecision(1) << watch.Seconds()
            << " s: E^2 " << std::setprecision(4) << match.e2 << " mm^2, residual " << residual
            << " mm (RMS)\ncoefficients (standard deviations):";
  for (double x : b)
  {
    std::cout << ' ' << x;
  }
  std::cout << std::defaultfloat << '\n';
  if (args.Has("output"))
  {
    mean.points = match.corresponded;
    WritePoints(args.Get("output"), mean, mean.points);
  }
  if (args.Has("json"))
  {
    WriteTextWhole(args.Get("json"), [&](std::ostream & out) {
      out << std::setprecision(17) << "{\"coefficients\": ";
      WriteNumbers(out, b);
      out << ", \"residual\": " << ME::detail::JSONNumber{ residual } << ", \"e2\": "
          << ME::detail::JSONNumber{ match.e2 } << "}\n";
    });
  }
  return 0;
}

int
RunEvaluate(const Arguments & args)
{
  return EvaluateShapeModel(args, { args.positional.begin() + 1, args.positional.end() });
}

/** The verbs of shape-model and how many positional arguments each takes (its own
 * included); `build` is also the default, for the form without a verb. */
struct Verb
{
  const char * name;
  std::size_t  minimum;
  std::size_t  maximum;
  bool         needsJSON;
  bool         needsOutput;
  int (*run)(const Arguments &);
};

const std::vector<Verb> &
Verbs()
{
  static const std::vector<Verb> verbs{
    { "build", 3, 100000, false, true, RunShapeModel }, { "prepare", 2, 2, false, true, RunPrepare },
    { "match", 3, 3, true, true, RunMatch },            { "renew", 3, 100000, true, true, RunRenew },
    { "finish", 4, 100000, false, true, RunFinish },    { "sample", 2, 2, false, true, RunSample },
    { "project", 3, 3, false, false, RunProject },      { "evaluate", 2, 100000, false, false, RunEvaluate },
  };
  return verbs;
}

int
RunVerb(const Arguments & given)
{
  Arguments args = given;
  auto      verb = std::find_if(
    Verbs().begin(), Verbs().end(), [&args](const Verb & v) { return args.positional.front() == v.name; });
  if (verb == Verbs().end())
  {
    // The form without a verb: shape-model MESH MESH ... is build.
    args.positional.insert(args.positional.begin(), "build");
    verb = Verbs().begin();
  }
  if (args.positional.size() < verb->minimum || args.positional.size() > verb->maximum)
  {
    throw UsageError(std::string("shape-model ") + verb->name + " takes " +
                     (verb->minimum == verb->maximum ? std::to_string(verb->minimum - 1)
                                                     : "at least " + std::to_string(verb->minimum - 1)) +
                     " input files; see --help");
  }
  if (verb->needsOutput && !args.Has("output"))
  {
    throw UsageError(std::string("shape-model ") + verb->name + ": --output is required");
  }
  if (verb->needsJSON && !args.Has("json"))
  {
    throw UsageError(std::string("shape-model ") + verb->name + ": --json STATE.json is required");
  }
  return verb->run(args);
}
} // namespace

ME::detail::ShapeModelSettings
ShapeModelSettingsOf(const Arguments & args)
{
  ME::detail::ShapeModelSettings settings;
  settings.correspondence = ChooseOption(args, "correspondence", CorrespondenceNames(), Correspondence::PointToSurface);
  settings.nonRigid = !args.Has("thesis");
  settings.varianceFraction = args.GetDouble("variance-fraction", 0.95);
  settings.maximumNumberOfPasses = static_cast<unsigned int>(args.GetInteger("passes", 2));
  return settings;
}

void
ConfigureShapeModelEstimator(ShapeModelEstimator & estimator, const Arguments & args)
{
  const ME::detail::ShapeModelSettings settings = ShapeModelSettingsOf(args);
  estimator.SetCorrespondence(settings.correspondence);
  estimator.SetNonRigidCorrespondence(settings.nonRigid);
  estimator.SetVarianceFraction(settings.varianceFraction);
  estimator.SetMaximumNumberOfPasses(settings.maximumNumberOfPasses);
}

Command
MakeShapeModelCommand()
{
  Command c;
  c.name = "shape-model";
  c.summary = "build a landmark-free statistical shape model of closed meshes (ch. 7)";
  c.usage = "[build] MESH MESH [MESH...] --output MODEL.h5 [options]\n"
            "       meshextraction shape-model prepare MESH --output PREPARED.ply [--json INFO.json]\n"
            "       meshextraction shape-model match TEMPLATE MESH --output CORRESPONDED.ply --json STATE.json\n"
            "                                  [--initial STATE.json --gauge RENEWAL.json]\n"
            "       meshextraction shape-model renew TEMPLATE STATE.json... --output TEMPLATE.ply --json RENEWAL.json\n"
            "       meshextraction shape-model finish TEMPLATE STATE.json... --output MODEL.h5 [--pivot I --passes P]\n"
            "       meshextraction shape-model sample MODEL.h5 --output MESH [--coefficients S,S,... | --random-seed N]\n"
            "       meshextraction shape-model project MODEL.h5 MESH [--json B.json] [--output CORRESPONDED.ply]\n"
            "       meshextraction shape-model evaluate MESH MESH [MESH...] | FOLDER [--modes K] [--output MODEL.h5]";
  c.description =
    "build: the shape model of the meshes (PLY, or any format ITK reads) with\n"
    "LandmarkFreeShapeModelEstimator: the symmetric similarity ICP of every mesh to a template (the\n"
    "mesh with most vertices, then the mean), a non-rigid correspondence stage (off with --thesis:\n"
    "the thesis' closest points), Procrustes analysis and PCA. Writes the model as a statismo HDF5\n"
    "file and, with --corresponded, each input on the model's topology in its own frame.\n\n"
    "prepare, match, renew and finish are the steps of build, for builds spread over processes\n"
    "(meshextraction-cohort shape-model runs them on Dask and gives the model build gives):\n"
    "prepare makes a mesh ready (its largest component, outward); match matches TEMPLATE to one\n"
    "prepared mesh (the first pass's template is the prepared mesh with most points) and writes\n"
    "the template's points on it and its state (similarity, E^2); renew makes a pass's next\n"
    "template from its states, in input order; finish makes the model from the last pass's states.\n"
    "Points are written as double-precision PLY so that the steps lose nothing.\n\n"
    "sample writes the model's shape at the given coefficients (standard deviations of each mode;\n"
    "none: the mean), or at coefficients drawn from a standard normal within +-2. project matches\n"
    "the model's mean to a new mesh as build does, and prints its coefficients and the residual\n"
    "the modes leave (RMS, mm).\n\n"
    "evaluate builds the model of the meshes (or of a folder's *.ply but ref_*) and prints the\n"
    "figures of thesis section 7.3 and beyond: compactness, eigenvector stability against subset\n"
    "size, leave-one-out generalisation and specificity with K modes, the fit of the corresponded\n"
    "meshes, their self-intersections, and, where every mesh has a landmark file of its name\n"
    "(.json), the landmark transfer error over all ordered pairs.";
  c.options = {
    { "output", "FILE", "the model (statismo HDF5); of a step, its mesh", "" },
    { "json", "FILE", "build, finish: the model's summary; prepare, match, renew: the step's state", "" },
    { "corresponded", "DIR", "build: write each input's corresponded mesh here, named after the input", "" },
    { "report", "DIR", "build, finish: an HTML page of the model (compactness, the modes rendered)", "" },
    { "correspondence", "surface|point", "closest points on the triangles or the nearest vertices", "surface" },
    { "thesis", "", "no non-rigid stage: the thesis' closest-point correspondence", "" },
    { "variance-fraction",
      "F",
      "keep the modes that explain this fraction of the variance",
      "0.95",
      OptionRange::AboveUpTo(0, 1) },
    { "passes",
      "N",
      "build: at most this many template passes; finish: the passes run",
      "2",
      OptionRange::Between(1, 100) },
    { "initial", "STATE.json", "match: this mesh's state of the previous pass", "" },
    { "gauge", "RENEWAL.json", "match: the previous pass's renewal", "" },
    { "pivot", "I", "finish: the pivot's index, for the model's description", "0", OptionRange::Between(0, 1e6) },
    { "coefficients",
      "S,S,...",
      "sample: standard deviations of the first modes (--coefficients=-2,1)",
      "",
      OptionRange::Between(-10, 10) },
    { "random-seed",
      "N",
      "sample: coefficients drawn from a standard normal, within +-2",
      "",
      OptionRange::Between(0, 2147483647) },
    { "modes",
      "K",
      "evaluate: the modes of the generalisation, specificity and stability",
      "3",
      OptionRange::Between(1, 1000) },
  };
  c.minimumPositional = 2;
  c.run = RunVerb;
  return c;
}

} // namespace MeshExtractionCLI
