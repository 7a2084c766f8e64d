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
// meshextraction improve: edge swaps, then Laplacian or Taubin smoothing that never
// inverts a triangle.

#include "MeshExtractionCLI.h"

#include "itkEdgeSwapQuadEdgeMeshFilter.h"
#include "itkLaplacianSmoothingQuadEdgeMeshFilter.h"
#include "itkMeshExtractionPredicates.h"
#include "itkTaubinSmoothingQuadEdgeMeshFilter.h"

#include <iomanip>
#include <iostream>

namespace MeshExtractionCLI
{
namespace
{
using ImproveMeshType = QuadEdgeMeshType;
using SwapFilterType = itk::EdgeSwapQuadEdgeMeshFilter<ImproveMeshType>;
using LaplacianFilterType = itk::LaplacianSmoothingQuadEdgeMeshFilter<ImproveMeshType>;
using TaubinFilterType = itk::TaubinSmoothingQuadEdgeMeshFilter<ImproveMeshType>;

using SmoothingWeights = itk::MeshExtractionEnums::SmoothingWeights;
using SmoothingUpdate = itk::MeshExtractionEnums::SmoothingUpdate;
using MovementConstraint = itk::MeshExtractionEnums::MovementConstraint;
using EdgeSwapCriterion = itk::MeshExtractionEnums::EdgeSwapCriterion;

const OptionNames<std::string> &
SmoothingNames()
{
  static const OptionNames<std::string> table = { { "laplacian", "laplacian" },
                                                  { "taubin", "taubin" },
                                                  { "none", "none" } };
  return table;
}

const OptionNames<SmoothingWeights> &
WeightNames()
{
  static const OptionNames<SmoothingWeights> table = { { "uniform", SmoothingWeights::Uniform },
                                                       { "inverse-edge-length", SmoothingWeights::InverseEdgeLength },
                                                       { "area", SmoothingWeights::Area },
                                                       { "cotangent", SmoothingWeights::Cotangent },
                                                       { "angle-bisector", SmoothingWeights::AngleBisector } };
  return table;
}

const OptionNames<SmoothingUpdate> &
UpdateNames()
{
  static const OptionNames<SmoothingUpdate> table = { { "batch", SmoothingUpdate::Batch },
                                                      { "immediate", SmoothingUpdate::Immediate } };
  return table;
}

const OptionNames<MovementConstraint> &
ConstraintNames()
{
  static const OptionNames<MovementConstraint> table = { { "none", MovementConstraint::None },
                                                         { "centroid", MovementConstraint::Centroid },
                                                         { "safe", MovementConstraint::Safe } };
  return table;
}

const OptionNames<EdgeSwapCriterion> &
SwapCriterionNames()
{
  static const OptionNames<EdgeSwapCriterion> table = { { "regularity", EdgeSwapCriterion::Regularity },
                                                        { "delaunay", EdgeSwapCriterion::Delaunay },
                                                        { "shortest-edge", EdgeSwapCriterion::ShortestEdge } };
  return table;
}

/** The tool's own defaults, where they are not the filters': regularity swaps, then
 * Taubin smoothing, 10 iterations: the combination that keeps the surface where it is
 * (Laplacian smoothing shrinks it, by a fraction of a voxel on a marching-cubes sphere)
 * while it evens the triangles out. With --smoothing laplacian, the moves are
 * restricted to the centroid of the neighbours (thesis 4.2.2; the filter itself
 * restricts nothing by default). */
struct ImproveDefaults
{
  static constexpr const char *       smoothing = "taubin";
  static constexpr MovementConstraint constraint = MovementConstraint::Centroid;
  static constexpr long               iterations = 10;
  static constexpr EdgeSwapCriterion  criterion = EdgeSwapCriterion::Regularity;
};

/** The choices of one `improve` run. The weights and the update mode start as the
 * filters' defaults (the Laplacian and Taubin filters share them). */
struct ImproveOptions
{
  std::string        smoothing;
  SmoothingWeights   weights{};
  SmoothingUpdate    update{};
  MovementConstraint constraint{};
  bool               swap{ false };
  EdgeSwapCriterion  criterion{};
  long               iterations{ 0 };
  long               swapIterations{ 0 };
};

/** A UsageError for each option given that the other choices make meaningless. */
void
CheckOptionCombinations(const Arguments & args, const std::string & smoothing, bool swap)
{
  const char * laplacianOnly[] = { "constraint", "relaxation", "volume-preservation" };
  for (const char * option : laplacianOnly)
  {
    if (args.Has(option) && smoothing != "laplacian")
    {
      throw UsageError(std::string("--") + option + " applies to --smoothing laplacian");
    }
  }
  const char * taubinOnly[] = { "lambda", "mu", "pass-band" };
  for (const char * option : taubinOnly)
  {
    if (args.Has(option) && smoothing != "taubin")
    {
      throw UsageError(std::string("--") + option + " applies to --smoothing taubin");
    }
  }
  if (args.Has("mu") && args.Has("pass-band"))
  {
    throw UsageError("give either --mu or --pass-band, not both");
  }
  const char * smoothingOptions[] = { "weights", "update", "iterations" };
  for (const char * option : smoothingOptions)
  {
    if (args.Has(option) && smoothing == "none")
    {
      throw UsageError(std::string("--") + option + " needs smoothing (--smoothing laplacian or taubin)");
    }
  }
  const char * swapOptions[] = { "swap-iterations", "feature-angle", "swap-quality" };
  for (const char * option : swapOptions)
  {
    if (args.Has(option) && !swap)
    {
      throw UsageError(std::string("--") + option + " needs swaps (not --swap none)");
    }
  }
}

ImproveOptions
ReadImproveOptions(const Arguments & args)
{
  const auto     laplacianDefaults = LaplacianFilterType::New();
  ImproveOptions o;
  o.smoothing = ChooseOption(args, "smoothing", SmoothingNames(), std::string(ImproveDefaults::smoothing));
  o.weights = ChooseOption(args, "weights", WeightNames(), laplacianDefaults->GetWeights());
  o.update = ChooseOption(args, "update", UpdateNames(), laplacianDefaults->GetUpdateMode());
  o.constraint = ChooseOption(args, "constraint", ConstraintNames(), ImproveDefaults::constraint);
  o.swap = args.Get("swap") != "none";
  o.criterion =
    o.swap ? ChooseOption(args, "swap", SwapCriterionNames(), ImproveDefaults::criterion) : ImproveDefaults::criterion;
  CheckOptionCombinations(args, o.smoothing, o.swap);
  o.iterations = args.GetInteger("iterations", ImproveDefaults::iterations);
  if (o.iterations < 0)
  {
    throw UsageError("--iterations must be >= 0, got " + std::to_string(o.iterations));
  }
  o.swapIterations = args.GetInteger("swap-iterations", SwapFilterType::New()->GetMaximumNumberOfIterations());
  if (o.swapIterations < 0)
  {
    throw UsageError("--swap-iterations must be >= 0, got " + std::to_string(o.swapIterations));
  }
  return o;
}

// ------------------------------------------------------------------------------
// The steps: swap, then smooth (thesis section 4.2.4: smoothing converges faster on
// the regularised mesh)
// ------------------------------------------------------------------------------

/** A line for the vertices the smoothing filters moved back where the surface would
 * have crossed itself (PreventSelfIntersections), if there were any. */
void
PrintUndoneMoves(itk::SizeValueType undone)
{
  if (undone > 0)
  {
    std::cout << "  " << undone
              << " vertex moves undone where the surface would have cut through itself, folded, or collapsed or passed "
                 "a component\n";
  }
}

ImproveMeshType::Pointer
SwapEdges(ImproveMeshType * mesh, const ImproveOptions & o, const Arguments & args)
{
  auto filter = SwapFilterType::New();
  filter->SetInput(mesh);
  filter->SetCriterion(o.criterion);
  filter->SetMaximumNumberOfIterations(static_cast<int>(o.swapIterations));
  filter->SetFeatureAngle(args.GetDouble("feature-angle", filter->GetFeatureAngle()));
  filter->SetMinimumQAreaRatio(args.GetDouble("swap-quality", filter->GetMinimumQAreaRatio()));
  ReportProgress(filter.GetPointer(), "edge swap");
  filter->Update();
  std::cout << "edge swap (" << OptionName(SwapCriterionNames(), o.criterion) << "): " << filter->GetNumberOfSwaps()
            << " swaps in " << filter->GetNumberOfIterations() << " passes, " << filter->GetNumberOfRefusedSwaps()
            << " improving swaps refused by the validity checks\n";
  if (filter->GetNumberOfCrossingTriangles() > 0)
  {
    std::cout << "  " << filter->GetNumberOfCrossingTriangles()
              << " new triangles cut through the surface: their corners were locked and the swaps made again ("
              << filter->GetNumberOfAttempts() << " attempts"
              << (filter->GetKeptInput() ? "; they still crossed, so the mesh was kept unswapped" : "") << ")\n";
  }
  ImproveMeshType::Pointer out = filter->GetOutput();
  out->DisconnectPipeline();
  return out;
}

ImproveMeshType::Pointer
SmoothLaplacian(ImproveMeshType * mesh, const ImproveOptions & o, const Arguments & args)
{
  auto filter = LaplacianFilterType::New();
  filter->SetInput(mesh);
  filter->SetWeights(o.weights);
  filter->SetUpdateMode(o.update);
  filter->SetMovementConstraint(o.constraint);
  filter->SetNumberOfIterations(static_cast<int>(o.iterations));
  filter->SetRelaxationFactor(args.GetDouble("relaxation", filter->GetRelaxationFactor()));
  filter->SetVolumePreservation(args.Has("volume-preservation"));
  ReportProgress(filter.GetPointer(), "laplacian smoothing");
  filter->Update();
  std::cout << "laplacian smoothing (" << OptionName(WeightNames(), o.weights) << ", "
            << OptionName(ConstraintNames(), o.constraint) << ", " << OptionName(UpdateNames(), o.update)
            << "): " << o.iterations << " iterations of " << filter->GetNumberOfMovableVertices()
            << " movable vertices, " << filter->GetNumberOfMoves() << " moves, " << filter->GetNumberOfShortenedMoves()
            << " shortened and " << filter->GetNumberOfRejectedMoves() << " rejected by the inversion guard\n";
  PrintUndoneMoves(filter->GetNumberOfUndoneMoves());
  ImproveMeshType::Pointer out = filter->GetOutput();
  out->DisconnectPipeline();
  return out;
}

ImproveMeshType::Pointer
SmoothTaubin(ImproveMeshType * mesh, const ImproveOptions & o, const Arguments & args)
{
  auto filter = TaubinFilterType::New();
  filter->SetInput(mesh);
  filter->SetWeights(o.weights);
  filter->SetUpdateMode(o.update);
  filter->SetNumberOfIterations(static_cast<int>(o.iterations));
  filter->SetLambda(args.GetDouble("lambda", filter->GetLambda()));
  filter->SetMu(args.GetDouble("mu", filter->GetMu()));
  filter->SetPassBandFrequency(args.GetDouble("pass-band", 0.0));
  ReportProgress(filter.GetPointer(), "taubin smoothing");
  filter->Update();
  std::cout << "taubin smoothing (lambda " << filter->GetLambda() << ", mu " << filter->GetEffectiveMu() << ", "
            << OptionName(WeightNames(), o.weights) << ", " << OptionName(UpdateNames(), o.update)
            << "): " << o.iterations << " iterations of " << filter->GetNumberOfMovableVertices()
            << " movable vertices, " << filter->GetNumberOfMoves() << " moves, " << filter->GetNumberOfShortenedMoves()
            << " shortened and " << filter->GetNumberOfRejectedMoves() << " rejected by the inversion guard\n";
  PrintUndoneMoves(filter->GetNumberOfUndoneMoves());
  ImproveMeshType::Pointer out = filter->GetOutput();
  out->DisconnectPipeline();
  return out;
}

/** The triangles whose corners are collinear or coincide (decided exactly). */
std::size_t
CountDegenerateTriangles(const ImproveMeshType * mesh)
{
  const ME::IndexedTriangleMesh flat = ME::MakeIndexedTriangleMesh(*mesh);
  std::size_t                   count = 0;
  for (const auto & t : flat.triangles)
  {
    count += ME::detail::IsTriangleDegenerateExact(flat.points[t[0]], flat.points[t[1]], flat.points[t[2]]) ? 1 : 0;
  }
  return count;
}

/** --report: the quality before and after, and the two side by side. */
void
PrintBeforeAndAfter(const MeasuredMesh & before, const MeasuredMesh & after)
{
  before.quality.Print(std::cout, before.name);
  std::cout << '\n';
  after.quality.Print(std::cout, after.name);
  std::cout << '\n';
  PrintComparison({ before, after }, std::cout);
}

int
RunImprove(const Arguments & args)
{
  const ImproveOptions o = ReadImproveOptions(args);
  const std::string &  inputPath = args.positional[0];
  const std::string &  outputPath = args.positional[1];
  RequireNotAnInput(outputPath, { inputPath }, "OUTPUT");
  const MeshWriteSettings  writeSettings = ReadMeshWriteSettings(args);
  Stopwatch                watch;
  ImproveMeshType::Pointer mesh = ReadManifoldMesh(inputPath, "improve");
  std::cerr << "improve " << inputPath << ": " << mesh->GetNumberOfPoints() << " points, " << mesh->GetNumberOfFaces()
            << " triangles\n";
  // Smoothing and swaps improve a surface; they cannot make one of triangles that have
  // no area (points that all coincide, say), and their guards keep every move from
  // making a triangle degenerate, so such an input would come out as it went in.
  const std::size_t degenerate = CountDegenerateTriangles(mesh);
  if (degenerate == mesh->GetNumberOfFaces())
  {
    itkGenericExceptionMacro("'" << inputPath << "' has no surface to improve: all " << degenerate
                                 << " triangles are degenerate (their corners coincide or are collinear)");
  }
  MeasuredMesh before;
  if (args.Has("report"))
  {
    before = MeasureMesh(mesh, "before: " + inputPath);
  }
  if (o.swap)
  {
    mesh = SwapEdges(mesh, o, args);
  }
  if (o.smoothing == "laplacian")
  {
    mesh = SmoothLaplacian(mesh, o, args);
  }
  else if (o.smoothing == "taubin")
  {
    mesh = SmoothTaubin(mesh, o, args);
  }
  if (const std::size_t left = CountDegenerateTriangles(mesh); left > 0)
  {
    std::cout << "  " << left << " degenerate triangles (corners collinear or coincident) remain of the input's "
              << degenerate << '\n';
  }
  WriteMeshFile(mesh.GetPointer(), outputPath, writeSettings);
  std::cerr << "  wrote " << outputPath << " in " << std::fixed << std::setprecision(2) << watch.Seconds() << " s\n"
            << std::defaultfloat;
  if (args.Has("report"))
  {
    PrintBeforeAndAfter(before, MeasureMesh(mesh, "after: " + outputPath));
  }
  return 0;
}
} // namespace

Command
MakeImproveCommand()
{
  // The filters' own defaults, for the help text.
  const auto swapDefaults = SwapFilterType::New();
  const auto laplacianDefaults = LaplacianFilterType::New();
  const auto taubinDefaults = TaubinFilterType::New();
  Command    c;
  c.name = "improve";
  c.summary = "improve a mesh: edge swaps, then Laplacian or Taubin smoothing that never inverts triangles";
  c.usage = "INPUT OUTPUT [options]";
  c.description = "Reads a triangle mesh (any format ITK reads; it must be manifold and consistently oriented),\n"
                  "optionally swaps edges (EdgeSwapQuadEdgeMeshFilter: regularity Eb = sum (d-6)^2, Delaunay or\n"
                  "shortest edge, with the validity checks of thesis 4.5.1), then smooths it\n"
                  "(LaplacianSmoothingQuadEdgeMeshFilter or TaubinSmoothingQuadEdgeMeshFilter, lambda|mu) and\n"
                  "writes OUTPUT (format from its extension). Every smoothing move passes a guard: a move that\n"
                  "would invert or degenerate a triangle is halved or rejected, and the counts are printed.\n"
                  "Boundary vertices of open meshes stay in place. --report prints the quality before and after.";
  c.options = {
    { "smoothing", OptionChoices(SmoothingNames(), true), "smoothing after the swaps", ImproveDefaults::smoothing },
    { "weights", "NAME", OptionChoices(WeightNames()), OptionName(WeightNames(), laplacianDefaults->GetWeights()) },
    { "constraint",
      OptionChoices(ConstraintNames(), true),
      "laplacian: move restriction (thesis 4.2.2, Fig. 4.8)",
      OptionName(ConstraintNames(), ImproveDefaults::constraint) },
    { "update",
      OptionChoices(UpdateNames(), true),
      "when new positions take effect",
      OptionName(UpdateNames(), laplacianDefaults->GetUpdateMode()) },
    { "iterations",
      "N",
      "smoothing iterations (taubin: lambda|mu pairs)",
      std::to_string(ImproveDefaults::iterations),
      OptionRange::Between(0, 1000) },
    { "relaxation",
      "F",
      "laplacian: relaxation factor",
      DefaultText(laplacianDefaults->GetRelaxationFactor()),
      OptionRange::AboveUpTo(0, 1) },
    { "lambda",
      "L",
      "taubin: positive step factor",
      DefaultText(taubinDefaults->GetLambda()),
      OptionRange::AboveUpTo(0, 1) },
    { "mu",
      "M",
      "taubin: negative step factor, < -lambda",
      DefaultText(taubinDefaults->GetMu()),
      OptionRange::Inside(-100, 0) },
    { "pass-band",
      "K",
      "taubin: pass-band frequency k_PB; mu from 1/lambda + 1/mu = K",
      "",
      OptionRange::Inside(0, 1) },
    { "volume-preservation", "", "laplacian: approximate volume preservation (thesis eq. 2.7-2.10)", "" },
    { "swap",
      OptionChoices(SwapCriterionNames(), true) + "|none",
      "swap edges first by this criterion (none: no swaps)",
      OptionName(SwapCriterionNames(), ImproveDefaults::criterion) },
    { "swap-iterations",
      "N",
      "largest number of passes over the edges",
      DefaultText(swapDefaults->GetMaximumNumberOfIterations()),
      OptionRange::Between(0, 1000) },
    { "feature-angle",
      "DEG",
      "no swap across or creating a crease sharper than this",
      DefaultText(swapDefaults->GetFeatureAngle()),
      OptionRange::Between(0, 180) },
    { "swap-quality",
      "RATIO",
      "a swap keeps its worst triangle's q_area >= RATIO x the old worst",
      DefaultText(swapDefaults->GetMinimumQAreaRatio()),
      OptionRange::Between(0, 1) },
    { "report", "", "print the quality before and after", "" },
  };
  for (const auto & o : MeshWriteOptions())
  {
    c.options.push_back(o);
  }
  c.minimumPositional = 2;
  c.maximumPositional = 2;
  c.run = RunImprove;
  return c;
}

} // namespace MeshExtractionCLI
