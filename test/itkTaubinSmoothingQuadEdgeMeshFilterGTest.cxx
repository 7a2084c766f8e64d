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
#include "itkTaubinSmoothingQuadEdgeMeshFilter.h"
#include "itkLaplacianSmoothingQuadEdgeMeshFilter.h"
#include "itkMeshExtractionTestHelpers.h"
#include "itkTriangleMeshQualityCalculator.h"
#include "itkBinaryMask3DMeshSource.h"
#include "itkImplicitSurfaceImageSource.h"

#include "itkGTest.h"

#include <functional>
#include <random>
#include <sstream>

using namespace MeshExtractionTest;
using itk::MeshExtraction::TriangleMeshQualityReport;

namespace
{
using TaubinType = itk::TaubinSmoothingQuadEdgeMeshFilter<QEMeshType>;
using LaplacianType = itk::LaplacianSmoothingQuadEdgeMeshFilter<QEMeshType>;
using Weights = itk::MeshExtractionEnums::SmoothingWeights;
using Update = itk::MeshExtractionEnums::SmoothingUpdate;

TriangleMeshQualityReport
Analyze(const QEMeshType * mesh, const QEMeshType * reference = nullptr, bool selfIntersections = true)
{
  auto calculator = itk::TriangleMeshQualityCalculator<QEMeshType>::New();
  calculator->SetMesh(mesh);
  calculator->SetReferenceMesh(reference);
  calculator->SetComputeSelfIntersections(selfIntersections);
  calculator->Compute();
  return calculator->GetReport();
}

/** Mean and standard deviation of the distances of the points to `center`. */
std::pair<double, double>
RadiusStatistics(const QEMeshType * mesh, const Vec3 & center)
{
  double sum = 0.0;
  double sumSq = 0.0;
  for (auto it = mesh->GetPoints()->Begin(); it != mesh->GetPoints()->End(); ++it)
  {
    const double r = itk::MeshExtraction::Norm(itk::MeshExtraction::ToVec3(it.Value()) - center);
    sum += r;
    sumSq += r * r;
  }
  const double n = static_cast<double>(mesh->GetNumberOfPoints());
  const double mean = sum / n;
  return { mean, std::sqrt(std::max(0.0, sumSq / n - mean * mean)) };
}

/** ITK's BinaryMask3DMeshSource on a mask of the sphere of radius 15 voxels centred
 * at (18.8, 18.8, 18.8). */
const QEMeshType *
MarchingCubesSphere()
{
  static QEMeshType::Pointer mesh = [] {
    using ImageType = itk::Image<unsigned char, 3>;
    auto                  sphere = itk::SphereImplicitSurface::New();
    itk::Point<double, 3> center;
    center.Fill(18.8);
    sphere->SetCenter(center);
    sphere->SetRadius(15.0);
    auto source = itk::ImplicitSurfaceImageSource<ImageType>::New();
    source->SetSurface(sphere);
    ImageType::SizeType size;
    size.Fill(38);
    source->SetSize(size);
    source->SetImageMode(itk::MeshExtractionEnums::PhantomImage::BinaryMask);
    auto mc = itk::BinaryMask3DMeshSource<ImageType, QEMeshType>::New();
    mc->SetInput(source->GetOutput());
    mc->SetObjectValue(1);
    mc->Update();
    QEMeshType::Pointer m = mc->GetOutput();
    m->DisconnectPipeline();
    return m;
  }();
  return mesh.GetPointer();
}

const Vec3 MarchingCubesCenter = MakeVec3(18.8, 18.8, 18.8);

/** Icosphere of radius 10 (642 vertices) with uniform radial noise of +-amplitude. */
QEMeshType::Pointer
NoisySphere(double amplitude, unsigned int seed)
{
  IndexedTriangleMesh                    m = MakeIcosphere(3, 10.0);
  std::mt19937                           rng(seed);
  std::uniform_real_distribution<double> u(-amplitude, amplitude);
  for (auto & p : m.points)
  {
    p *= (10.0 + u(rng)) / 10.0;
  }
  return ToITKMesh<QEMeshType>(m);
}
} // namespace

TEST(TaubinSmoothingQuadEdgeMeshFilter, KeepsTheMeanRadiusOfAMarchingCubesSphereWithinHalfAPercentOver50Iterations)
{
  const QEMeshType * input = MarchingCubesSphere();
  const double       before = RadiusStatistics(input, MarchingCubesCenter).first;
  auto               taubin = TaubinType::New();
  taubin->SetInput(input);
  taubin->SetNumberOfIterations(50);
  taubin->Update();
  const double after = RadiusStatistics(taubin->GetOutput(), MarchingCubesCenter).first;
  EXPECT_LT(std::abs(after - before) / before, 0.005) << before << " -> " << after;
  const auto report = Analyze(taubin->GetOutput(), input, false);
  EXPECT_TRUE(report.IsValidClosedSurface());
  EXPECT_GT(report.qArea.mean, Analyze(input, nullptr, false).qArea.mean);

  // Uniform Laplacian smoothing, by contrast, shrinks the sphere (thesis 2.2.3).
  auto laplacian = LaplacianType::New();
  laplacian->SetInput(input);
  laplacian->SetNumberOfIterations(50);
  laplacian->Update();
  const double shrunk = RadiusStatistics(laplacian->GetOutput(), MarchingCubesCenter).first;
  EXPECT_LT(shrunk, before * 0.97) << before << " -> " << shrunk;
}

TEST(TaubinSmoothingQuadEdgeMeshFilter, UniformLaplacianShrinksASphereEveryIterationAndTaubinDoesNot)
{
  // Thesis section 2.2.3: every vertex of a sphere moves to the average of its
  // neighbours, which is closer to the centre, so the sphere shrinks at every step.
  QEMeshType::Pointer mesh = ToITKMesh<QEMeshType>(MakeIcosphere(3, 10.0));
  const Vec3          origin = MakeVec3(0, 0, 0);
  double              previous = RadiusStatistics(mesh, origin).first;
  for (int iteration = 0; iteration < 10; ++iteration)
  {
    auto laplacian = LaplacianType::New();
    laplacian->SetInput(mesh);
    laplacian->Update();
    mesh = laplacian->GetOutput();
    mesh->DisconnectPipeline();
    const double radius = RadiusStatistics(mesh, origin).first;
    EXPECT_LT(radius, previous) << "iteration " << iteration;
    previous = radius;
  }
  EXPECT_LT(previous, 9.9);

  // Taubin's filter passes the sphere's low frequency with a gain slightly above one
  // (f(k) = (1 - lambda k)(1 - mu k) > 1 below the pass-band frequency): it does not
  // shrink; on this coarse sphere (edge 1.6, radius 10) it grows by about 1.5%.
  auto taubin = TaubinType::New();
  taubin->SetInput(ToITKMesh<QEMeshType>(MakeIcosphere(3, 10.0)));
  taubin->SetNumberOfIterations(50);
  taubin->Update();
  const double taubinRadius = RadiusStatistics(taubin->GetOutput(), origin).first;
  EXPECT_GE(taubinRadius, 10.0 - 1e-6);
  EXPECT_LT(taubinRadius, 10.2);
}

TEST(TaubinSmoothingQuadEdgeMeshFilter, RemovesNoiseFromASphereWithoutShrinkingIt)
{
  const auto input = NoisySphere(0.4, 5);
  const auto before = RadiusStatistics(input, MakeVec3(0, 0, 0));
  for (Weights weights : { Weights::Uniform, Weights::Cotangent })
  {
    auto taubin = TaubinType::New();
    taubin->SetInput(input);
    taubin->SetWeights(weights);
    taubin->SetNumberOfIterations(20);
    taubin->Update();
    const auto after = RadiusStatistics(taubin->GetOutput(), MakeVec3(0, 0, 0));
    EXPECT_LT(after.second, 0.5 * before.second)
      << weights << ": roughness " << before.second << " -> " << after.second;
    EXPECT_LT(std::abs(after.first - before.first) / before.first, 0.01) << weights;
    const auto report = Analyze(taubin->GetOutput(), input);
    EXPECT_TRUE(report.IsValidClosedSurface()) << weights;
    EXPECT_EQ(report.invertedTrianglesVersusReference, 0) << weights;
  }
  // The same smoothing with plain Laplacian steps shrinks the sphere.
  auto laplacian = LaplacianType::New();
  laplacian->SetInput(input);
  laplacian->SetNumberOfIterations(20);
  laplacian->SetRelaxationFactor(0.5);
  laplacian->Update();
  EXPECT_LT(RadiusStatistics(laplacian->GetOutput(), MakeVec3(0, 0, 0)).first, 0.98 * before.first);
}

TEST(TaubinSmoothingQuadEdgeMeshFilter, PassBandFrequencyGivesMuFromOneOverLambdaPlusOneOverMu)
{
  auto taubin = TaubinType::New();
  EXPECT_DOUBLE_EQ(taubin->GetEffectiveMu(), taubin->GetMu());
  taubin->SetLambda(0.5);
  taubin->SetPassBandFrequency(0.1);
  const double mu = taubin->GetEffectiveMu();
  EXPECT_NEAR(1.0 / 0.5 + 1.0 / mu, 0.1, 1e-12);
  EXPECT_LT(mu, -0.5);

  // The same filter given mu directly gives the same mesh.
  const auto input = NoisySphere(0.3, 6);
  taubin->SetInput(input);
  taubin->SetNumberOfIterations(5);
  taubin->Update();
  auto direct = TaubinType::New();
  direct->SetInput(input);
  direct->SetLambda(0.5);
  direct->SetMu(mu);
  direct->SetNumberOfIterations(5);
  direct->Update();
  double difference = 0.0;
  for (auto it = direct->GetOutput()->GetPoints()->Begin(); it != direct->GetOutput()->GetPoints()->End(); ++it)
  {
    difference = std::max(difference, it.Value().EuclideanDistanceTo(taubin->GetOutput()->GetPoint(it.Index())));
  }
  EXPECT_EQ(difference, 0.0);
}

TEST(TaubinSmoothingQuadEdgeMeshFilter, GuardedTaubinOfHundredsOfPerturbedMeshesNeverInvertsOrDegenerates)
{
  // Each lambda|mu iteration is checked against the mesh before it.
  std::mt19937 rng(99);
  int          tested = 0;
  for (int k = 0; k < 300; ++k)
  {
    IndexedTriangleMesh                    m = MakeIcosphere(1, 10.0);
    std::uniform_real_distribution<double> u(-1.5, 1.5);
    for (auto & p : m.points)
    {
      p += MakeVec3(u(rng), u(rng), u(rng));
    }
    QEMeshType::Pointer mesh = ToITKMesh<QEMeshType>(m);
    if (!Analyze(mesh).IsValidClosedSurface())
    {
      continue;
    }
    ++tested;
    for (int iteration = 0; iteration < 2; ++iteration)
    {
      auto taubin = TaubinType::New();
      taubin->SetInput(mesh);
      taubin->SetNumberOfIterations(1);
      taubin->SetWeights(k % 2 ? Weights::Uniform : Weights::InverseEdgeLength);
      taubin->SetUpdateMode(k % 3 ? Update::Batch : Update::Immediate);
      taubin->Update();
      const auto report = Analyze(taubin->GetOutput(), mesh, false);
      ASSERT_EQ(report.invertedTrianglesVersusReference, 0) << "mesh " << k << ", iteration " << iteration;
      ASSERT_EQ(report.degenerateTriangles, 0) << "mesh " << k << ", iteration " << iteration;
      ASSERT_TRUE(report.IsClosed() && report.IsManifold()) << "mesh " << k;
      mesh = taubin->GetOutput();
      mesh->DisconnectPipeline();
    }
  }
  EXPECT_GT(tested, 200);
}

TEST(TaubinSmoothingQuadEdgeMeshFilter, ResultDoesNotDependOnTheNumberOfThreads)
{
  QEMeshType::Pointer outputs[2];
  const unsigned int  workUnits[2] = { 1, 3 };
  for (int i = 0; i < 2; ++i)
  {
    auto taubin = TaubinType::New();
    taubin->SetInput(MarchingCubesSphere());
    taubin->SetNumberOfIterations(3);
    taubin->SetNumberOfWorkUnits(workUnits[i]);
    taubin->Update();
    outputs[i] = taubin->GetOutput();
    outputs[i]->DisconnectPipeline();
  }
  for (auto it = outputs[0]->GetPoints()->Begin(); it != outputs[0]->GetPoints()->End(); ++it)
  {
    ASSERT_EQ(it.Value().EuclideanDistanceTo(outputs[1]->GetPoint(it.Index())), 0.0);
  }
}

TEST(TaubinSmoothingQuadEdgeMeshFilter, ThrowsWithoutInputOrOnANonTriangleFace)
{
  auto taubin = TaubinType::New();
  EXPECT_THROW(taubin->Update(), itk::ExceptionObject);

  auto mesh = QEMeshType::New();
  for (unsigned int i = 0; i < 4; ++i)
  {
    QEMeshType::PointType p;
    p[0] = i % 2;
    p[1] = i / 2;
    p[2] = 0;
    mesh->SetPoint(i, p);
  }
  QEMeshType::PointIdList quad = { 0, 1, 3, 2 };
  ASSERT_NE(mesh->AddFace(quad), nullptr);
  taubin->SetInput(mesh);
  EXPECT_THROW(taubin->Update(), itk::ExceptionObject);
}

TEST(TaubinSmoothingQuadEdgeMeshFilter, ThrowsWhenMuIsNotBelowMinusLambdaOrOtherParametersAreOutOfRange)
{
  const auto input = ToITKMesh<QEMeshType>(MakeIcosphere(1));
  auto       expectThrow = [&](const std::function<void(TaubinType *)> & set, const char * what) {
    auto taubin = TaubinType::New();
    taubin->SetInput(input);
    set(taubin);
    try
    {
      taubin->Update();
      ADD_FAILURE() << "no exception for " << what;
    }
    catch (const itk::ExceptionObject & e)
    {
      EXPECT_NE(std::string(e.GetDescription()).find(what), std::string::npos) << e.GetDescription();
    }
  };
  expectThrow([](TaubinType * f) { f->SetMu(-0.5); }, "mu < -lambda"); // mu = -lambda
  expectThrow([](TaubinType * f) { f->SetMu(-0.3); }, "mu < -lambda"); // |mu| < lambda: shrinks
  expectThrow([](TaubinType * f) { f->SetMu(0.2); }, "mu < -lambda");  // positive
  expectThrow([](TaubinType * f) { f->SetLambda(0.0); }, "Lambda");
  expectThrow([](TaubinType * f) { f->SetLambda(1.2); }, "Lambda");
  expectThrow([](TaubinType * f) { f->SetPassBandFrequency(2.0); }, "PassBandFrequency"); // = 1/lambda
  expectThrow([](TaubinType * f) { f->SetPassBandFrequency(-0.1); }, "PassBandFrequency");
  expectThrow([](TaubinType * f) { f->SetNumberOfIterations(-2); }, "NumberOfIterations");
  expectThrow([](TaubinType * f) { f->SetDegenerateQAreaTolerance(1.0); }, "DegenerateQAreaTolerance");
}

TEST(TaubinSmoothingQuadEdgeMeshFilter, PrintSelfNamesEveryParameter)
{
  auto taubin = TaubinType::New();
  EXPECT_STREQ(taubin->GetNameOfClass(), "TaubinSmoothingQuadEdgeMeshFilter");
  std::ostringstream os;
  taubin->Print(os);
  for (const char * name : { "Lambda",
                             "Mu",
                             "PassBandFrequency",
                             "EffectiveMu",
                             "NumberOfIterations",
                             "Weights",
                             "UpdateMode",
                             "PreventInversions",
                             "FixBoundary",
                             "NumberOfShortenedMoves" })
  {
    EXPECT_NE(os.str().find(name), std::string::npos) << name;
  }
}
