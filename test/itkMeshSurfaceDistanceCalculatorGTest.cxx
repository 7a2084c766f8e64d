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
#include "itkMeshSurfaceDistanceCalculator.h"
#include "itkMeshExtractionTestHelpers.h"

#include "gtest/gtest.h"

#include <random>

using namespace MeshExtractionTest;
using itk::MeshExtraction::Norm;
using itk::MeshExtraction::TriangleCentroid;

namespace
{
using CalculatorType = itk::MeshSurfaceDistanceCalculator<QEMeshDType>;

itk::SphereImplicitSurface::Pointer
MakeSphere(double radius)
{
  auto sphere = itk::SphereImplicitSurface::New();
  sphere->SetRadius(radius);
  return sphere;
}
} // namespace

TEST(MeshSurfaceDistanceCalculator, DistancesToAnAnalyticSphereAreExact)
{
  const double              radius = 10.0;
  const IndexedTriangleMesh m = MakeIcosphere(4, radius);
  auto                      mesh = ToITKMesh<QEMeshDType>(m);
  auto                      sphere = MakeSphere(radius);
  auto                      calculator = CalculatorType::New();
  calculator->SetMesh(mesh);
  calculator->SetReferenceSurface(sphere);
  calculator->Compute();
  // Vertices lie on the sphere; centroids at radius - |centroid| inside it.
  EXPECT_LT(calculator->GetVertexDistance().maximum, 1e-9);
  const auto & centroidDistances = calculator->GetFaceCentroidDistances();
  ASSERT_EQ(centroidDistances.size(), m.triangles.size());
  double expectedMean = 0.0;
  for (std::size_t f = 0; f < m.triangles.size(); ++f)
  {
    const auto & t = m.triangles[f];
    const double expected = Norm(TriangleCentroid(m.points[t[0]], m.points[t[1]], m.points[t[2]])) - radius;
    EXPECT_NEAR(centroidDistances[f], expected, 1e-6);
    expectedMean += std::abs(expected);
  }
  expectedMean /= m.triangles.size();
  EXPECT_NEAR(calculator->GetFaceCentroidDistance().mean, expectedMean, 1e-6);
  EXPECT_LT(calculator->GetFaceCentroidDistance().signedMean, 0.0); // centroids are inside
  // The largest gap between a chord triangle and the sphere is the sagitta at a face centre.
  EXPECT_TRUE(calculator->GetReport().symmetric);
  EXPECT_GE(calculator->GetHausdorffDistance(), calculator->GetFaceCentroidDistance().maximum - 1e-12);
  EXPECT_LT(calculator->GetHausdorffDistance(), 0.1);
  // Python reads the report through GetReportAsJSON().
  const std::string json = calculator->GetReportAsJSON();
  EXPECT_EQ(json.rfind("{\"reference\": \"implicit surface (SphereImplicitSurface)", 0), 0u) << json;
  EXPECT_NE(json.find("\"vertices\": {\"count\": " + std::to_string(m.points.size()) + ","), std::string::npos);
  EXPECT_NE(json.find("\"symmetric\": true}"), std::string::npos);
}

TEST(MeshSurfaceDistanceCalculator, DistancesToAnAnalyticPlaneAreExact)
{
  IndexedTriangleMesh m = MakeGrid(8, 0.5);
  for (auto & p : m.points)
  {
    p[2] = 0.3;
  }
  auto mesh = ToITKMesh<QEMeshDType>(m);
  auto plane = itk::PlaneImplicitSurface::New();
  auto calculator = CalculatorType::New();
  calculator->SetMesh(mesh);
  calculator->SetReferenceSurface(plane);
  calculator->Compute();
  const auto & r = calculator->GetReport();
  EXPECT_NEAR(r.vertices.mean, 0.3, 1e-6);
  EXPECT_NEAR(r.vertices.rms, 0.3, 1e-6);
  EXPECT_NEAR(r.vertices.maximum, 0.3, 1e-6);
  EXPECT_NEAR(r.vertices.signedMean, 0.3, 1e-6);
  EXPECT_NEAR(r.faceCentroids.mean, 0.3, 1e-6);
  EXPECT_NEAR(r.hausdorff, 0.3, 1e-6);
  for (double d : calculator->GetVertexDistances())
  {
    EXPECT_NEAR(d, 0.3, 1e-6);
  }
}

TEST(MeshSurfaceDistanceCalculator, DistancesToAReferenceMeshAreExactAndSymmetric)
{
  const IndexedTriangleMesh flat = MakeGrid(10, 1.0);
  IndexedTriangleMesh       lifted = flat;
  for (auto & p : lifted.points)
  {
    p[2] = 0.25;
  }
  auto calculator = CalculatorType::New();
  calculator->SetMesh(ToITKMesh<QEMeshDType>(lifted));
  calculator->SetReferenceMesh(ToITKMesh<QEMeshDType>(flat));
  calculator->Compute();
  EXPECT_NEAR(calculator->GetVertexDistance().mean, 0.25, 1e-12);
  EXPECT_NEAR(calculator->GetFaceCentroidDistance().maximum, 0.25, 1e-12);
  EXPECT_NEAR(calculator->GetHausdorffDistance(), 0.25, 1e-12);

  // A stray triangle floating 3 mm above the reference is seen only from the
  // reference side: the one-sided distance stays 0, the symmetric Hausdorff
  // distance reports it.
  IndexedTriangleMesh stray = flat;
  const auto          first = static_cast<std::uint32_t>(stray.points.size());
  stray.points.push_back(MakeVec3(4, 4, 3));
  stray.points.push_back(MakeVec3(5, 4, 3));
  stray.points.push_back(MakeVec3(4, 5, 3));
  stray.triangles.push_back({ first, first + 1, first + 2 });
  calculator->SetMesh(ToITKMesh<QEMeshDType>(flat));
  calculator->SetReferenceMesh(ToITKMesh<QEMeshDType>(stray));
  calculator->SetSymmetric(false);
  calculator->Compute();
  EXPECT_NEAR(calculator->GetVertexDistance().maximum, 0.0, 1e-12);
  const double oneSided = calculator->GetHausdorffDistance();
  EXPECT_NEAR(oneSided, 0.0, 1e-12);
  calculator->SetSymmetric(true);
  calculator->Compute();
  EXPECT_NEAR(calculator->GetHausdorffDistance(), 3.0, 1e-12);
}

TEST(MeshSurfaceDistanceCalculator, MeshDistancesMatchBruteForceForAnyThreadCount)
{
  const IndexedTriangleMesh        reference = MakeTorus(24, 12, 4.0, 1.5);
  IndexedTriangleMesh              query = MakeIcosphere(2, 5.0);
  std::mt19937                     rng(5);
  std::normal_distribution<double> noise(0.0, 0.3);
  for (auto & p : query.points)
  {
    p += MakeVec3(noise(rng), noise(rng), noise(rng));
  }
  auto calculator = CalculatorType::New();
  calculator->SetMesh(ToITKMesh<QEMeshDType>(query));
  calculator->SetReferenceMesh(ToITKMesh<QEMeshDType>(reference));
  calculator->SetNumberOfWorkUnits(1);
  calculator->Compute();
  const std::vector<double> single = calculator->GetVertexDistances();
  calculator->SetNumberOfWorkUnits(4);
  calculator->Compute();
  EXPECT_EQ(single, calculator->GetVertexDistances());
  for (std::size_t i = 0; i < query.points.size(); ++i)
  {
    double best = std::numeric_limits<double>::max();
    for (const auto & t : reference.triangles)
    {
      best = std::min(best,
                      itk::MeshExtraction::SquaredDistancePointTriangle(
                        query.points[i], reference.points[t[0]], reference.points[t[1]], reference.points[t[2]]));
    }
    EXPECT_NEAR(single[i], std::sqrt(best), 1e-12);
  }
}

TEST(MeshSurfaceDistanceCalculator, MissingInputsThrowClearly)
{
  auto calculator = CalculatorType::New();
  EXPECT_THROW(calculator->Compute(), itk::ExceptionObject);
  calculator->SetMesh(ToITKMesh<QEMeshDType>(MakeIcosphere(1)));
  try
  {
    calculator->Compute();
    FAIL() << "no reference must throw";
  }
  catch (const itk::ExceptionObject & e)
  {
    EXPECT_NE(std::string(e.GetDescription()).find("reference"), std::string::npos);
  }
  calculator->SetReferenceMesh(QEMeshDType::New()); // empty
  EXPECT_THROW(calculator->Compute(), itk::ExceptionObject);
  calculator->SetMesh(QEMeshDType::New());
  calculator->SetReferenceSurface(MakeSphere(1.0));
  EXPECT_THROW(calculator->Compute(), itk::ExceptionObject);
}
