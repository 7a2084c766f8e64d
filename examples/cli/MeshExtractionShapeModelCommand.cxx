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

#include "MeshExtractionCLI.h"

#include "itkLandmarkFreeShapeModelEstimator.h"
#include "itkMeshExtractionPLY.h"

#include <filesystem>
#include <iomanip>
#include <iostream>

namespace MeshExtractionCLI
{
namespace
{
using Estimator = itk::LandmarkFreeShapeModelEstimator<IOMeshType>;
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

/** Corresponded mesh i, named after its input, into `directory` (PLY or VTK after the input). */
void
WriteCorresponded(const Estimator & estimator, const std::vector<std::string> & inputs, const std::string & directory)
{
  std::filesystem::create_directories(directory);
  for (unsigned int i = 0; i < inputs.size(); ++i)
  {
    const std::filesystem::path input(inputs[i]);
    const bool                  ply = input.extension() == ".ply";
    const std::string           path =
      (std::filesystem::path(directory) / (input.stem().string() + (ply ? ".ply" : ".vtk"))).string();
    const auto mesh = estimator.GetCorrespondedMesh(i);
    if (ply)
    {
      WriteWhole(
        path, [&mesh](const std::string & partial) { ME::WritePLYFile(partial, ME::MakeIndexedTriangleMesh(*mesh)); });
    }
    else
    {
      WriteMeshFile(mesh.GetPointer(), path);
    }
  }
  std::cout << "corresponded meshes written to " << directory << '\n';
}

void
PrintModel(const Estimator & estimator, double seconds)
{
  const auto & variances = estimator.GetVariances();
  std::cout << "model built in " << std::fixed << std::setprecision(1) << seconds << " s: pivot input "
            << estimator.GetPivotIndex() << ", " << estimator.GetNumberOfPasses() << " template passes, "
            << estimator.GetNumberOfModes() << " modes\ncumulative variance (%):";
  double sum = 0.0;
  for (std::size_t k = 0; k < variances.size(); ++k)
  {
    sum += variances[k];
    std::cout << ' ' << k + 1 << ':' << 100.0 * sum / estimator.GetTotalVariance();
  }
  std::cout << std::defaultfloat << '\n';
}

int
RunShapeModel(const Arguments & args)
{
  auto                             estimator = Estimator::New();
  std::vector<IOMeshType::Pointer> meshes;
  for (const std::string & path : args.positional)
  {
    meshes.push_back(ReadTrainingMesh(path));
    estimator->AddInputMesh(meshes.back());
  }
  estimator->SetCorrespondence(
    ChooseOption(args, "correspondence", CorrespondenceNames(), Correspondence::PointToSurface));
  estimator->SetNonRigidCorrespondence(!args.Has("thesis"));
  estimator->SetVarianceFraction(args.GetDouble("variance-fraction", 0.95));
  estimator->SetMaximumNumberOfPasses(static_cast<unsigned int>(args.GetInteger("passes", 2)));
  Stopwatch watch;
  estimator->Update();
  PrintModel(*estimator, watch.Seconds());
  WriteWhole(args.Get("output"), [&estimator](const std::string & partial) { estimator->WriteModel(partial); });
  std::cout << "model written to " << args.Get("output") << '\n';
  if (args.Has("corresponded"))
  {
    WriteCorresponded(*estimator, args.positional, args.Get("corresponded"));
  }
  return 0;
}
} // namespace

Command
MakeShapeModelCommand()
{
  Command c;
  c.name = "shape-model";
  c.summary = "build a landmark-free statistical shape model of closed meshes (ch. 7)";
  c.usage = "MESH MESH [MESH...] --output MODEL.h5 [options]";
  c.description = "Builds the shape model of the meshes (PLY, or any format ITK reads) with\n"
                  "LandmarkFreeShapeModelEstimator: the symmetric similarity ICP of every mesh to a template (the\n"
                  "mesh with most vertices, then the mean), a non-rigid correspondence stage (off with --thesis:\n"
                  "the thesis' closest points), Procrustes analysis and PCA. Writes the model as a statismo HDF5\n"
                  "file and, with --corresponded, each input on the model's topology in its own frame.";
  c.options = {
    { "output", "FILE", "the model (statismo HDF5)", "" },
    { "corresponded", "DIR", "write each input's corresponded mesh here, named after the input", "" },
    { "correspondence", "surface|point", "closest points on the triangles or the nearest vertices", "surface" },
    { "thesis", "", "no non-rigid stage: the thesis' closest-point correspondence", "" },
    { "variance-fraction", "F", "keep the modes that explain this fraction of the variance", "0.95" },
    { "passes", "N", "at most this many template passes", "2" },
  };
  c.minimumPositional = 2;
  c.run = [](const Arguments & args) {
    if (!args.Has("output"))
    {
      throw UsageError("--output MODEL.h5 is required");
    }
    return RunShapeModel(args);
  };
  return c;
}

} // namespace MeshExtractionCLI
