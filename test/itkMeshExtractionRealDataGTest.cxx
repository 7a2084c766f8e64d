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
// Tests on real data: they read ../shared/data next to the project (never part of it)
// and are skipped where it is not present.

#include "itkMeshExtractionLandmarkFile.h"
#include "itkScaleSpaceEdgeMeshRefinementFilter.h"
#include "itkSurfaceNetsImageToMeshFilter.h"
#include "itkTriangleMeshQualityCalculator.h"
#include "itkMeshExtractionTestHelpers.h"
#include "itksys/SystemTools.hxx"

#include "gtest/gtest.h"

#include <sstream>
#include <string>
#include <vector>

namespace
{
namespace ME = itk::MeshExtraction;
using MeshType = itk::QuadEdgeMesh<double, 3>;
using Operation = itk::MeshExtractionEnums::RefinementOperation;

ME::TriangleMeshQualityReport
Analyze(const MeshType * mesh)
{
  auto calculator = itk::TriangleMeshQualityCalculator<MeshType>::New();
  calculator->SetMesh(mesh);
  calculator->Compute();
  return calculator->GetReport();
}

std::string
Describe(const ME::TriangleMeshQualityReport & report)
{
  std::ostringstream os;
  report.Print(os);
  return os.str();
}
} // namespace

// Real data, when ../shared/data (next to the project, never part of it) is present:
// the small VTK head CT, read from its raw file (its NRRD header gives both 'space:'
// and 'spacings:', which ITK's NRRD reader refuses). Bone above 1150 (HU + 1024).
TEST(SurfaceNetsImageToMeshFilter, RealHeadCTGivesValidSurfacesAndHighQualityBeatsSnert)
{
  std::string where;
  const auto  image = MeshExtractionTest::ReadSharedHeadCT(where);
  if (image.IsNull())
  {
    GTEST_SKIP() << "../shared/data/ct_headsq is not next to the project (" << where << "): real-data test skipped";
  }
  using ShortImage = itk::Image<short, 3>;

  auto snert = itk::SurfaceNetsImageToMeshFilter<ShortImage>::New();
  snert->SetInput(image);
  snert->SetIsoValue(1150);
  snert->Update();
  const auto plain = Analyze(snert->GetOutput());
  EXPECT_TRUE(plain.IsValidClosedSurface()) << Describe(plain);
  EXPECT_EQ(plain.selfIntersectingPairs, 0);
  EXPECT_GT(plain.numberOfTriangles, 50000);

  auto high = itk::SurfaceNetsImageToMeshFilter<ShortImage>::New();
  high->SetInput(image);
  high->SetIsoValue(1150);
  high->SetHighQuality(true);
  high->Update();
  const auto q = Analyze(high->GetOutput());
  EXPECT_TRUE(q.IsValidClosedSurface()) << Describe(q);
  EXPECT_EQ(q.selfIntersectingPairs, 0);
  EXPECT_EQ(q.eulerCharacteristic, plain.eulerCharacteristic);
  EXPECT_GT(q.qArea.mean, plain.qArea.mean + 0.05);  // measured 0.886 vs 0.796
  EXPECT_GT(q.qAngle.mean, plain.qAngle.mean + 0.1); // measured 0.563 vs 0.424
  EXPECT_LT(q.fractionQAngleBelow03, 0.5 * plain.fractionQAngleBelow03);

  // The sliver removal (on by default): on 3.2 x 3.2 x 1.5 mm voxels the rounds leave
  // many needles between nodes pinned near shared cell faces; the local remeshing takes
  // away most of them (measured 5.54 % -> 0.96 % below q_angle 0.3), keeping the
  // topology and the validity.
  auto without = itk::SurfaceNetsImageToMeshFilter<ShortImage>::New();
  without->SetInput(image);
  without->SetIsoValue(1150);
  without->SetHighQuality(true);
  without->SetHighQualitySliverRemoval(false);
  without->Update();
  const auto w = Analyze(without->GetOutput());
  EXPECT_TRUE(w.IsValidClosedSurface()) << Describe(w);
  EXPECT_GT(high->GetNumberOfCollapses(), 0u);
  EXPECT_EQ(q.connectedComponents, w.connectedComponents);
  EXPECT_LT(q.fractionQAngleBelow03, 0.25 * w.fractionQAngleBelow03);
  EXPECT_LE(q.fractionQAngleBelow03, 0.0105); // the target: 1 %
  EXPECT_GT(q.qAngle.mean, w.qAngle.mean + 0.01); // measured 0.594 vs 0.579
  EXPECT_GT(q.qAngle.minimum, w.qAngle.minimum);
}

// Real data, when ../shared/data is next to the project: the small VTK head CT (bone
// above 1150, 3.2 x 3.2 x 1.5 mm voxels), from the unrelaxed SurfaceNets mesh.
TEST(ScaleSpaceEdgeMeshRefinementFilter, RealHeadCTGetsMoreAccurateAndBetterShapedAndStaysValid)
{
  std::string where;
  const auto  image = MeshExtractionTest::ReadSharedHeadCT(where);
  if (image.IsNull())
  {
    GTEST_SKIP() << "../shared/data/ct_headsq is not next to the project (" << where << "): real-data test skipped";
  }
  using ShortImage = itk::Image<short, 3>;
  auto net = itk::SurfaceNetsImageToMeshFilter<ShortImage, MeshType>::New();
  net->SetInput(image);
  net->SetIsoValue(1150);
  net->SetRelaxation(itk::SurfaceNetsImageToMeshFilterEnums::Relaxation::None);
  net->Update();
  const auto before = Analyze(net->GetOutput());
  ASSERT_TRUE(before.IsValidClosedSurface()) << Describe(before);

  auto filter = itk::ScaleSpaceEdgeMeshRefinementFilter<MeshType, ShortImage>::New();
  filter->SetInput(net->GetOutput());
  filter->SetInputImage(image);
  filter->SetMaximumDeviation(3.0);
  filter->SetMaximumNumberOfCycles(2);
  filter->Update();
  std::vector<double> inaccuracy;
  for (const auto & s : filter->GetSteps())
  {
    EXPECT_EQ(s.degenerateTriangles, 0);
    EXPECT_EQ(s.nonManifold, 0);
    EXPECT_LE(s.invertedTriangles, 0);
    if (s.operation == Operation::EdgeDetection)
    {
      inaccuracy.push_back(s.inaccuracy);
    }
  }
  ASSERT_EQ(inaccuracy.size(), 3u);
  EXPECT_LT(inaccuracy.back(), 0.75 * inaccuracy.front()); // measured 0.687 -> 0.426 mm
  const auto after = Analyze(filter->GetOutput());
  EXPECT_TRUE(after.IsValidClosedSurface()) << Describe(after);
  EXPECT_EQ(after.selfIntersectingPairs, 0);
  EXPECT_EQ(after.eulerCharacteristic, before.eulerCharacteristic);
  EXPECT_GT(after.qArea.mean, before.qArea.mean + 0.03);   // measured 0.714 -> 0.764
  EXPECT_GT(after.qAngle.mean, before.qAngle.mean + 0.05); // measured 0.332 -> 0.41
}

TEST(LandmarkFile, ReadsTheVertebraLandmarks)
{
  const std::string path =
    std::string(MESHEXTRACTION_SOURCE_DIR) + "/../shared/data/vertebrae_L1/sub-verse010_segment_20.json";
  if (!itksys::SystemTools::FileExists(path))
  {
    GTEST_SKIP() << "../shared/data/vertebrae_L1 is not present next to the project";
  }
  const auto l = ME::ReadLandmarkFile(path);
  ASSERT_EQ(l.size(), 10u);
  EXPECT_EQ(l[0].id, "A");
  EXPECT_NEAR(l[0].point[1], 250.64239501953125, 1e-12);
}
