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

// meshextraction shape-model evaluate: the landmark-free shape model (thesis chapter 7)
// of a set of meshes and the figures the field judges it by: the variance in the first
// modes (compactness), eigenvector stability against subset size (Table 7.2),
// leave-one-out generalisation, specificity, the fit of the corresponded meshes, and,
// where each mesh has a landmark file (same name, .json), the subject-to-subject landmark
// transfer error.

#include "MeshExtractionShapeModelCLI.h"

#include "itkMeshExtractionLandmarkFile.h"
#include "itkMeshExtractionSelfIntersections.h"
#include "itkMeshExtractionShapeModelEvaluation.h"

#include <algorithm>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <string>
#include <vector>

namespace MeshExtractionCLI
{
namespace
{
using Estimator = ShapeModelEstimator;
namespace detail = itk::MeshExtraction::detail;

/** The training set: meshes, prepared originals and landmarks (empty without a file). */
struct TrainingSet
{
  std::vector<std::string>                              names;
  std::vector<IOMeshType::Pointer>                      meshes;
  std::vector<itk::MeshExtraction::IndexedTriangleMesh> originals;
  std::vector<detail::MeshLandmarks>                    landmarks;
  bool                                                  allLandmarks{ true };
};

/** The meshes: the files given, or every *.ply of the one folder given but ref_* (the
 * vertebra data's template), in name order. */
std::vector<std::filesystem::path>
TrainingFiles(const std::vector<std::string> & inputs)
{
  std::vector<std::filesystem::path> files;
  if (inputs.size() == 1 && std::filesystem::is_directory(inputs.front()))
  {
    for (const auto & entry : std::filesystem::directory_iterator(inputs.front()))
    {
      const auto name = entry.path().filename().string();
      if (entry.path().extension() == ".ply" && name.rfind("ref_", 0) != 0)
      {
        files.push_back(entry.path());
      }
    }
    std::sort(files.begin(), files.end());
    return files;
  }
  return { inputs.begin(), inputs.end() };
}

TrainingSet
ReadTrainingSet(const std::vector<std::string> & inputs)
{
  TrainingSet set;
  for (const auto & file : TrainingFiles(inputs))
  {
    set.meshes.push_back(ReadMeshFile(file.string()));
    const auto indexed = itk::MeshExtraction::MakeIndexedTriangleMesh(*set.meshes.back());
    set.names.push_back(file.stem().string());
    set.originals.push_back(detail::PrepareTrainingMesh(indexed, file.string()));
    detail::MeshLandmarks landmarks;
    auto                  json = file;
    json.replace_extension(".json");
    if (std::filesystem::exists(json))
    {
      for (const auto & landmark : itk::MeshExtraction::ReadLandmarkFile(json.string()))
      {
        landmarks.ids.push_back(landmark.id);
        landmarks.points.push_back(
          itk::MeshExtraction::MakeVec3(landmark.point[0], landmark.point[1], landmark.point[2]));
      }
    }
    set.allLandmarks = set.allLandmarks && !landmarks.ids.empty();
    set.landmarks.push_back(landmarks);
  }
  return set;
}

void
PrintCompactness(const Estimator & estimator, const detail::PrincipalComponentModel & all)
{
  const auto cumulative = detail::CumulativeVarianceFractions(all.variances);
  std::cout << "compactness (cumulative variance, % per number of modes):";
  for (std::size_t k = 0; k < cumulative.size(); ++k)
  {
    std::cout << ' ' << k + 1 << ':' << std::fixed << std::setprecision(1) << 100.0 * cumulative[k];
  }
  std::cout << std::setprecision(3);
  std::cout << "\nmodes kept (variance fraction " << estimator.GetVarianceFraction()
            << "): " << estimator.GetNumberOfModes() << '\n';
}

void
PrintPasses(const Estimator & estimator)
{
  std::cout << std::fixed << std::setprecision(3)
            << "per template pass: mean E^2 of eq. 7.3 (mm^2) / template move (mm):";
  for (std::size_t p = 0; p < estimator.GetNumberOfPasses(); ++p)
  {
    std::cout << ' ' << estimator.GetMeanSquaredDistancePerPass()[p] << " / "
              << estimator.GetTemplateChangePerPass()[p];
  }
  std::cout << '\n';
}

/** Thesis Table 7.2: the angles of the first modes of subsets to those of all meshes. */
void
PrintStability(const std::vector<detail::Shape> & aligned, unsigned int modes)
{
  std::vector<std::size_t> sizes;
  for (std::size_t s = std::min<std::size_t>(aligned.size(), 4); s < aligned.size(); ++s)
  {
    sizes.push_back(s);
  }
  const auto angles = detail::EigenvectorStability(aligned, sizes, modes);
  std::cout << "eigenvector stability (angle to the mode of all meshes, rad), per subset size:";
  for (std::size_t s = 0; s < sizes.size(); ++s)
  {
    std::cout << "\n  " << sizes[s] << ':';
    for (double angle : angles[s])
    {
      std::cout << ' ' << angle;
    }
  }
  std::cout << '\n';
}

void
PrintEvaluation(const TrainingSet & set, const Estimator & estimator, unsigned int modes)
{
  std::vector<detail::Shape> corresponded;
  for (unsigned int i = 0; i < set.meshes.size(); ++i)
  {
    corresponded.push_back(itk::MeshExtraction::MakeIndexedTriangleMesh(*estimator.GetCorrespondedMesh(i)).points);
  }
  const auto triangles = itk::MeshExtraction::MakeIndexedTriangleMesh(*estimator.GetMeanMesh()).triangles;
  std::vector<detail::SimilarityParameters> toModel;
  const auto                                aligned = detail::GeneralizedProcrustes(corresponded, true, &toModel);
  PrintCompactness(estimator, detail::BuildPrincipalComponents(aligned, 1.0));
  std::cout << std::setprecision(3);
  PrintStability(aligned, modes);
  const auto loo = detail::LeaveOneOutGeneralization(corresponded, set.originals, modes);
  std::cout << "leave-one-out generalisation, " << modes << " modes (mm): vertex-to-vertex " << loo.meanVertexToVertex
            << ", vertex-to-surface " << loo.meanVertexToSurface << '\n';
  detail::SpecificitySettings settings;
  settings.modes = modes;
  const auto specificity = detail::Specificity(aligned, toModel, set.originals, settings);
  std::cout << "specificity, " << modes << " modes (mm): vertex-to-vertex " << specificity.vertexToVertex << " (sd "
            << specificity.vertexToVertexDeviation << "), vertex-to-surface " << specificity.vertexToSurface << '\n';
  const auto fit = detail::MeasureSurfaceFit(corresponded, triangles, set.originals);
  std::cout << "fit (mm): corresponded to original " << fit.forward << ", original to corresponded " << fit.backward
            << '\n';
  std::cout << "self-intersecting triangle pairs of the corresponded meshes:";
  for (const auto & shape : corresponded)
  {
    itk::MeshExtraction::IndexedTriangleMesh mesh;
    mesh.points = shape;
    mesh.triangles = triangles;
    std::cout << ' ' << detail::FindSelfIntersections(mesh).size();
  }
  std::cout << '\n';
  if (!set.allLandmarks)
  {
    std::cout << "landmark transfer: not measured (a mesh has no landmark file)\n";
    return;
  }
  const auto transfer = detail::TransferLandmarks(corresponded, triangles, set.landmarks);
  std::cout << "landmark transfer, " << transfer.count << " landmarks over the ordered pairs (mm): mean "
            << transfer.mean << ", median " << transfer.median << "\n  per landmark:";
  for (std::size_t l = 0; l < transfer.ids.size(); ++l)
  {
    std::cout << ' ' << transfer.ids[l] << ':' << transfer.meanPerLandmark[l];
  }
  std::cout << '\n';
}
} // namespace

int
EvaluateShapeModel(const Arguments & args, const std::vector<std::string> & inputs)
{
  const TrainingSet set = ReadTrainingSet(inputs);
  detail::CheckNumberOfTrainingMeshes(set.meshes.size());
  auto estimator = Estimator::New();
  for (const auto & mesh : set.meshes)
  {
    estimator->AddInputMesh(mesh);
  }
  ConfigureShapeModelEstimator(*estimator, args);
  const bool pointToPoint =
    estimator->GetCorrespondence() == itk::MeshExtractionEnums::Correspondence::PointToPoint;
  std::cout << set.meshes.size() << " meshes; "
            << (estimator->GetNonRigidCorrespondence() ? "non-rigid stage" : "thesis (closest points)") << ", "
            << (pointToPoint ? "point-to-point" : "point-to-surface") << '\n';
  Stopwatch watch;
  estimator->Update();
  std::cout << "model built in " << std::setprecision(3) << watch.Seconds() << " s: pivot "
            << set.names[estimator->GetPivotIndex()] << ", " << estimator->GetNumberOfPasses() << " template passes\n";
  PrintPasses(*estimator);
  PrintEvaluation(set, *estimator, static_cast<unsigned int>(args.GetInteger("modes", 3)));
  if (args.Has("output"))
  {
    WriteWhole(args.Get("output"), [&estimator](const std::string & partial) { estimator->WriteModel(partial); });
    std::cout << "model written to " << args.Get("output") << '\n';
  }
  return 0;
}
} // namespace MeshExtractionCLI
