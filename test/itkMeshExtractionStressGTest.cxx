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
// The stress runs: every filter on the SurfaceNets meshes of many smooth random volumes.
// Disabled by default (minutes); see each test for how to run it.

#include "itkEdgeSwapQuadEdgeMeshFilter.h"
#include "itkLaplacianSmoothingQuadEdgeMeshFilter.h"
#include "itkScaleSpaceEdgeMeshRefinementFilter.h"
#include "itkSurfaceNetsImageToMeshFilter.h"
#include "itkTaubinSmoothingQuadEdgeMeshFilter.h"
#include "itkTriangleMeshQualityCalculator.h"
#include "itkMeshExtractionRandomSurfaces.h"
#include "itkMeshExtractionScaleSpaceTestHelpers.h"
#include "itkMeshExtractionTestHelpers.h"

#include "gtest/gtest.h"

#include <iostream>
#include <map>
#include <string>

using namespace MeshExtractionTest;

namespace
{
using SwapType = itk::EdgeSwapQuadEdgeMeshFilter<QEMeshType>;
using LaplacianType = itk::LaplacianSmoothingQuadEdgeMeshFilter<QEMeshType>;
using Criterion = itk::MeshExtractionEnums::EdgeSwapCriterion;
using MeshExtractionScaleSpaceTest::RandomVolumeRefinement;

itk::MeshExtraction::TriangleMeshQualityReport
Analyze(const QEMeshType * mesh)
{
  auto calculator = itk::TriangleMeshQualityCalculator<QEMeshType>::New();
  calculator->SetMesh(mesh);
  calculator->Compute();
  return calculator->GetReport();
}
} // namespace

// ------------------------------------------------------------------------------
// Stress runs (not run by default: minutes). Seeds from the environment:
//   MESHEXTRACTION_STRESS_SEEDS=0,300 build/test/MeshExtractionGTestDriver
//     --gtest_also_run_disabled_tests --gtest_filter='StressRuns.*'
// ------------------------------------------------------------------------------
TEST(StressRuns, DISABLED_RandomSmoothVolumes)
{
  unsigned int first = 0;
  unsigned int last = 100;
  StressSeeds(first, last);
  std::map<std::string, int> failures;
  std::map<std::string, int> runs;
  auto                       check = [&](const std::string & what, bool ok, unsigned int seed) {
    ++runs[what];
    if (!ok)
    {
      ++failures[what];
      std::cout << what << ": seed " << seed << '\n';
    }
  };
  for (unsigned int seed = first; seed < last; ++seed)
  {
    const QEMeshType::Pointer input = RandomSurfaceNetsMesh(seed);
    if (!input)
    {
      continue;
    }
    const auto before = Analyze(input);
    check("SurfaceNets valid", before.IsValidClosedSurface(), seed);
    double     iso = 0.0;
    const auto image = MakeRandomSmoothVolume(seed, iso);
    auto       high = itk::SurfaceNetsImageToMeshFilter<itk::Image<float, 3>, QEMeshType>::New();
    high->SetInput(image);
    high->SetIsoValue(iso);
    high->SetHighQuality(true);
    high->Update();
    const auto hq = Analyze(high->GetOutput());
    check("high quality valid, topology kept",
          hq.IsValidClosedSurface() && hq.eulerCharacteristic == before.eulerCharacteristic &&
            hq.connectedComponents == before.connectedComponents,
          seed);
    high->SetHighQualityRemeshing(true);
    high->Update();
    const auto remeshed = Analyze(high->GetOutput());
    check("high quality remeshed valid, topology kept",
          remeshed.IsValidClosedSurface() && remeshed.eulerCharacteristic == before.eulerCharacteristic &&
            remeshed.connectedComponents == before.connectedComponents,
          seed);

    auto swap = SwapType::New();
    swap->SetInput(input);
    swap->SetCriterion(static_cast<Criterion>(seed % 3));
    swap->Update();
    const auto swapped = Analyze(swap->GetOutput());
    check("edge swap valid, topology kept",
          swapped.IsValidClosedSurface() && swapped.eulerCharacteristic == before.eulerCharacteristic,
          seed);

    auto laplacian = LaplacianType::New();
    laplacian->SetInput(input);
    laplacian->SetWeights(static_cast<itk::MeshExtractionEnums::SmoothingWeights>(seed % 5));
    laplacian->SetUpdateMode(static_cast<itk::MeshExtractionEnums::SmoothingUpdate>((seed / 5) % 2));
    laplacian->SetMovementConstraint(static_cast<itk::MeshExtractionEnums::MovementConstraint>((seed / 10) % 3));
    laplacian->SetNumberOfIterations(10);
    laplacian->Update();
    const auto smoothed = Analyze(laplacian->GetOutput());
    check("Laplacian x10 no self-intersection", smoothed.selfIntersectingPairs == 0, seed);
    check("Laplacian x10 valid", smoothed.IsValidClosedSurface(), seed);

    auto taubin = itk::TaubinSmoothingQuadEdgeMeshFilter<QEMeshType>::New();
    taubin->SetInput(input);
    taubin->Update();
    const auto taubinReport = Analyze(taubin->GetOutput());
    check("Taubin x10 no self-intersection", taubinReport.selfIntersectingPairs == 0, seed);
    check("Taubin x10 valid", taubinReport.IsValidClosedSurface(), seed);
  }
  for (const auto & r : runs)
  {
    std::cout << r.first << ": " << failures[r.first] << " failures in " << r.second << '\n';
  }
  for (const std::string what : { "SurfaceNets valid",
                                  "high quality valid, topology kept",
                                  "high quality remeshed valid, topology kept",
                                  "edge swap valid, topology kept",
                                  "Laplacian x10 no self-intersection",
                                  "Laplacian x10 valid",
                                  "Taubin x10 no self-intersection",
                                  "Taubin x10 valid" })
  {
    EXPECT_EQ(failures[what], 0) << what;
  }
}

// ------------------------------------------------------------------------------
// Stress runs (not run by default: minutes): the refinement of the SurfaceNets meshes
// of smooth random volumes (RandomSurfaceNetsMesh; many small components and pinches)
// against their own images, every third seed. Seeds from the environment:
//   MESHEXTRACTION_STRESS_SEEDS=0,300 build/test/MeshExtractionGTestDriver
//     --gtest_also_run_disabled_tests --gtest_filter='StressRuns.*'
// ------------------------------------------------------------------------------
TEST(StressRuns, DISABLED_RefinedRandomSmoothVolumes)
{
  unsigned int first = 0;
  unsigned int last = 300;
  MeshExtractionTest::StressSeeds(first, last);
  unsigned int runs = 0;
  unsigned int failures = 0;
  for (unsigned int seed = first + (3 - first % 3) % 3; seed < last; seed += 3)
  {
    const auto input = MeshExtractionTest::RandomSurfaceNetsMesh(seed);
    if (!input)
    {
      continue;
    }
    const auto filter = RandomVolumeRefinement(seed, input);
    ++runs;
    try
    {
      filter->Update();
    }
    catch (const itk::ExceptionObject & e)
    {
      ++failures;
      std::cout << "seed " << seed << ": " << e.GetDescription() << '\n';
      continue;
    }
    const auto report = Analyze(filter->GetOutput());
    if (!report.IsValidClosedSurface())
    {
      ++failures;
      std::cout << "seed " << seed << ": invalid: inverted (outward) " << report.invertedTrianglesVersusOutward
                << ", self-intersecting pairs " << report.selfIntersectingPairs << ", degenerate "
                << report.degenerateTriangles << '\n';
    }
  }
  std::cout << "refinement valid: " << failures << " failures in " << runs << '\n';
  EXPECT_EQ(failures, 0u);
}
