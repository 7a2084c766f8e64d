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

// The landmark-free shape model: a synthetic population with one known mode, the model
// file (statismo's HDF5 layout, read back and checked by h5dump), bad input, and the
// L1 vertebrae of ../shared/data (skipped where they are absent).

#include "itkLandmarkFreeShapeModelEstimator.h"
#include "itkMeshExtractionGeodesicSphere.h"
#include "itkMeshExtractionIndexedTriangleMesh.h"
#include "itkMeshExtractionLandmarkFile.h"
#include "itkMeshExtractionPLY.h"
#include "itkMeshExtractionSelfIntersections.h"
#include "itkMeshExtractionShapeModelBuilder.h"
#include "itkMeshExtractionShapeModelEvaluation.h"
#include "itkQuadEdgeMesh.h"
#include "itkSymmetricEigenAnalysis.h"
#include "vnl/algo/vnl_svd.h"
#include "vnl/vnl_matrix.h"
#include "vnl/vnl_vector.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace
{
using MeshType = itk::QuadEdgeMesh<double, 3>;
using Estimator = itk::LandmarkFreeShapeModelEstimator<MeshType>;
using itk::MeshExtraction::IndexedTriangleMesh;
using itk::MeshExtraction::Vec3;

constexpr double shortAxis = 15.0;
constexpr double middleAxis = 20.0;

MeshType::Pointer
ToMesh(const IndexedTriangleMesh & indexed)
{
  auto mesh = MeshType::New();
  itk::MeshExtraction::FillMesh(indexed, *mesh);
  return mesh;
}

/** An ellipsoid with semi-axes (a, b, shortAxis), a geodesic sphere of the given
 * subdivisions scaled, under a random similarity (rotation, scale 0.8 to 1.25, a
 * translation of up to 300 mm). */
IndexedTriangleMesh
PosedEllipsoid(double a, double b, unsigned int subdivisions, std::mt19937_64 & random)
{
  IndexedTriangleMesh mesh =
    itk::MeshExtraction::MakeGeodesicSphere(subdivisions, itk::MeshExtraction::MakeVec3(0, 0, 0), 1.0);
  std::normal_distribution<double>       normal;
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  itk::Versor<double>                    versor;
  double                                 q[4];
  double                                 norm = 0.0;
  for (double & x : q)
  {
    x = normal(random);
    norm += x * x;
  }
  norm = std::sqrt(norm);
  versor.Set(q[0] / norm, q[1] / norm, q[2] / norm, q[3] / norm);
  const auto   rotation = versor.GetMatrix();
  const double scale = std::exp(0.22 * uniform(random));
  const Vec3 shift = itk::MeshExtraction::MakeVec3(300 * uniform(random), 300 * uniform(random), 300 * uniform(random));
  for (Vec3 & p : mesh.points)
  {
    const Vec3 axes = itk::MeshExtraction::MakeVec3(a * p[0], b * p[1], shortAxis * p[2]);
    p = scale * (rotation * axes) + shift;
  }
  return mesh;
}

/** The long semi-axis of ellipsoid i of n: evenly from 26 to 34 mm. */
double
LongAxis(unsigned int i, unsigned int n)
{
  return 26.0 + 8.0 * i / (n - 1.0);
}

/** The half-extents of a mesh along its principal axes (largest first). */
std::array<double, 3>
PrincipalExtents(const MeshType * mesh)
{
  const IndexedTriangleMesh indexed = itk::MeshExtraction::MakeIndexedTriangleMesh(*mesh);
  Vec3                      centre = itk::MeshExtraction::MakeVec3(0, 0, 0);
  for (const Vec3 & p : indexed.points)
  {
    centre += p / static_cast<double>(indexed.points.size());
  }
  itk::Matrix<double, 3, 3> moment;
  moment.Fill(0.0);
  for (const Vec3 & p : indexed.points)
  {
    for (unsigned int r = 0; r < 3; ++r)
    {
      for (unsigned int c = 0; c < 3; ++c)
      {
        moment[r][c] += (p[r] - centre[r]) * (p[c] - centre[c]);
      }
    }
  }
  itk::Matrix<double, 3, 3>                                                                                 vectors;
  itk::Vector<double, 3>                                                                                    values;
  itk::SymmetricEigenAnalysis<itk::Matrix<double, 3, 3>, itk::Vector<double, 3>, itk::Matrix<double, 3, 3>> eigen(3);
  eigen.SetOrderEigenMagnitudes(true);
  eigen.ComputeEigenValuesAndVectors(moment, values, vectors);
  std::array<double, 3> extents{ 0, 0, 0 };
  for (const Vec3 & p : indexed.points)
  {
    for (unsigned int k = 0; k < 3; ++k)
    {
      double projection = 0.0;
      for (unsigned int d = 0; d < 3; ++d)
      {
        projection += vectors[2 - k][d] * (p[d] - centre[d]);
      }
      extents[k] = std::max(extents[k], std::abs(projection));
    }
  }
  return extents;
}

/** Problems of a surface: boundary or non-manifold edges, inconsistent orientation, an
 * enclosed volume that is not positive (facing inward). 0 for a closed, 2-manifold,
 * outward surface. */
std::size_t
TopologyProblems(const IndexedTriangleMesh & indexed)
{
  const auto topology = itk::MeshExtraction::BuildMeshTopology(indexed);
  double     volume = 0.0;
  for (const auto & t : indexed.triangles)
  {
    volume += itk::MeshExtraction::Dot(indexed.points[t[0]],
                                       itk::MeshExtraction::Cross(indexed.points[t[1]], indexed.points[t[2]]));
  }
  return topology.numberOfBoundaryEdges + topology.numberOfNonManifoldEdges + topology.numberOfInconsistentEdges +
         (volume > 0.0 ? 0 : 1);
}

/** TopologyProblems and the self-intersecting triangle pairs of a mesh the model emits. */
std::size_t
SurfaceProblems(const MeshType * mesh)
{
  const IndexedTriangleMesh indexed = itk::MeshExtraction::MakeIndexedTriangleMesh(*mesh);
  return TopologyProblems(indexed) + itk::MeshExtraction::detail::FindSelfIntersections(indexed).size();
}

/** Eight posed ellipsoids, long axis from 26 to 34 mm, at two resolutions. */
Estimator::Pointer
EllipsoidModel(unsigned int n = 8)
{
  std::mt19937_64                random(29);
  std::vector<MeshType::Pointer> meshes;
  auto                           estimator = Estimator::New();
  for (unsigned int i = 0; i < n; ++i)
  {
    meshes.push_back(ToMesh(PosedEllipsoid(LongAxis(i, n), middleAxis, i % 2 == 0 ? 3 : 4, random)));
    estimator->AddInputMesh(meshes.back());
  }
  estimator->Update();
  return estimator;
}

std::string
TemporaryFile(const std::string & name)
{
  return ::testing::TempDir() + "/" + name;
}
} // namespace

TEST(LandmarkFreeShapeModelEstimator, EllipsoidsOfOneVaryingAxisGiveOneMode)
{
  const Estimator::Pointer estimator = EllipsoidModel();
  ASSERT_GE(estimator->GetNumberOfModes(), 1u);
  EXPECT_EQ(estimator->GetPivotIndex(), 1u); // the first of the finer meshes
  EXPECT_GT(estimator->GetVariances()[0] / estimator->GetTotalVariance(), 0.95);

  // The mean is the ellipsoid of the mean long axis (its aspect ratios; Procrustes sets its size).
  const auto mean = PrincipalExtents(estimator->GetMeanMesh());
  EXPECT_NEAR(mean[0] / mean[2], 30.0 / shortAxis, 0.02 * 30.0 / shortAxis);
  EXPECT_NEAR(mean[1] / mean[2], middleAxis / shortAxis, 0.02 * middleAxis / shortAxis);

  // Mode 1 is the long axis: at +-2 standard deviations it changes the long aspect ratio
  // and hardly the other.
  const auto   plus = PrincipalExtents(estimator->Synthesize({ 2.0 }));
  const auto   minus = PrincipalExtents(estimator->Synthesize({ -2.0 }));
  const double longChange = std::abs(plus[0] / plus[2] - minus[0] / minus[2]);
  const double middleChange = std::abs(plus[1] / plus[2] - minus[1] / minus[2]);
  EXPECT_GT(longChange, 0.3);
  EXPECT_LT(middleChange, 0.2 * longChange);

  // The meshes the model emits are closed, 2-manifold and outward.
  EXPECT_EQ(SurfaceProblems(estimator->GetMeanMesh()), 0u);
  EXPECT_EQ(SurfaceProblems(estimator->Synthesize({ 2.0 })), 0u);
  for (unsigned int i = 0; i < 8; ++i)
  {
    EXPECT_EQ(SurfaceProblems(estimator->GetCorrespondedMesh(i)), 0u) << "corresponded mesh " << i;
  }

  // A corresponded training mesh projects onto mode 1 in order of its long axis.
  const auto first = estimator->Project(estimator->GetCorrespondedMesh(0));
  const auto last = estimator->Project(estimator->GetCorrespondedMesh(7));
  EXPECT_GT(std::abs(first[0] - last[0]), 2.0);

  // A new subject, the long axis of the last one in another pose and resolution: matched
  // to the model, it projects near the last training mesh on mode 1.
  std::mt19937_64         random(101);
  const MeshType::Pointer subject = ToMesh(PosedEllipsoid(LongAxis(7, 8), middleAxis, 3, random));
  const auto              matched = estimator->MatchToModel(subject);
  EXPECT_EQ(matched->GetNumberOfPoints(), estimator->GetMeanMesh()->GetNumberOfPoints());
  const auto b = estimator->Project(matched);
  EXPECT_NEAR(b[0], last[0], 0.1 * std::abs(first[0] - last[0]));
  EXPECT_THROW(estimator->MatchToModel(nullptr), itk::ExceptionObject);
}

// The steps a distributed build runs (prepare, match per mesh and pass, renew, finish),
// each from what the previous steps wrote to files, give BuildShapeModel's model exactly.
TEST(LandmarkFreeShapeModelEstimator, StepsThroughFilesGiveTheModelOfOneBuild)
{
  namespace detail = itk::MeshExtraction::detail;
  std::mt19937_64                  random(35);
  std::vector<IndexedTriangleMesh> meshes;
  for (unsigned int i = 0; i < 5; ++i)
  {
    meshes.push_back(detail::PrepareTrainingMesh(PosedEllipsoid(LongAxis(i, 5), middleAxis, 2 + i % 2, random), "m"));
  }
  detail::ShapeModelSettings settings;
  settings.maximumNumberOfPasses = 2;
  const detail::ShapeModelBuildResult one = detail::BuildShapeModel(meshes, settings);

  // Points through double-precision PLY files, as the command's steps pass them.
  const auto throughFile = [](const IndexedTriangleMesh & mesh) {
    const std::string path = TemporaryFile("step.ply");
    itk::MeshExtraction::WritePLYFile(path, mesh, true);
    return itk::MeshExtraction::ReadPLYFile(path);
  };
  const std::size_t pivot = detail::ChoosePivot(meshes);
  ASSERT_EQ(pivot, one.pivot);
  IndexedTriangleMesh                templateMesh = throughFile(meshes[pivot]);
  std::vector<detail::TemplateMatch> matches(meshes.size());
  detail::SimilarityParameters       gauge;
  std::vector<double>                changes;
  for (unsigned int pass = 0; pass < settings.maximumNumberOfPasses; ++pass)
  {
    for (std::size_t i = 0; i < meshes.size(); ++i)
    {
      const detail::SimilarityParameters initial = detail::Compose(matches[i].templateToMesh, gauge.Inverse());
      matches[i] = detail::MatchTemplate(templateMesh, throughFile(meshes[i]), settings, pass > 0 ? &initial : nullptr);
      IndexedTriangleMesh corresponded = templateMesh;
      corresponded.points = matches[i].corresponded;
      matches[i].corresponded = throughFile(corresponded).points;
    }
    const detail::RenewedTemplate renewed = detail::RenewTemplate(templateMesh, matches, settings);
    changes.push_back(renewed.change);
    gauge = renewed.gauge;
    if (pass + 1 < settings.maximumNumberOfPasses)
    {
      templateMesh.points = renewed.points;
      templateMesh = throughFile(templateMesh);
    }
  }
  EXPECT_EQ(changes, one.templateChanges);
  detail::ShapeModelBuildResult steps;
  for (const detail::TemplateMatch & match : matches)
  {
    steps.corresponded.push_back(match.corresponded);
  }
  detail::FinishShapeModel(steps, settings.varianceFraction);
  EXPECT_EQ(steps.allVariances, one.allVariances);
  ASSERT_EQ(steps.corresponded.size(), one.corresponded.size());
  for (std::size_t i = 0; i < steps.corresponded.size(); ++i)
  {
    EXPECT_TRUE(steps.corresponded[i] == one.corresponded[i]) << "corresponded mesh " << i;
  }
  EXPECT_GT(one.allVariances.front(), 0.0);

  // A renewal without matches, or with a match of another template, is refused.
  EXPECT_THROW(detail::RenewTemplate(templateMesh, {}, settings), itk::ExceptionObject);
  std::vector<detail::TemplateMatch> foreign(1);
  foreign[0].corresponded.assign(templateMesh.points.size() + 1, itk::MeshExtraction::MakeVec3(0, 0, 0));
  EXPECT_THROW(detail::RenewTemplate(templateMesh, foreign, settings), itk::ExceptionObject);
}

TEST(LandmarkFreeShapeModelEstimator, TwoIndependentAxesGiveTwoModes)
{
  // A 3 x 3 grid of long and middle semi-axes: the first two modes explain the population
  // and the coefficients of every training mesh are a linear function of its two axes.
  std::mt19937_64                random(7);
  std::vector<MeshType::Pointer> meshes;
  std::vector<double>            longAxes, middleAxes;
  auto                           estimator = Estimator::New();
  for (unsigned int i = 0; i < 9; ++i)
  {
    longAxes.push_back(26.0 + 4.0 * (i % 3));
    middleAxes.push_back(18.0 + 2.0 * (i / 3));
    meshes.push_back(ToMesh(PosedEllipsoid(longAxes.back(), middleAxes.back(), i % 2 == 0 ? 3 : 4, random)));
    estimator->AddInputMesh(meshes.back());
  }
  estimator->Update();
  ASSERT_GE(estimator->GetNumberOfModes(), 2u);
  const auto & variances = estimator->GetVariances();
  EXPECT_GT((variances[0] + variances[1]) / estimator->GetTotalVariance(), 0.95);

  // Least squares of each coefficient on (1, long, middle): the residual is small.
  for (unsigned int mode = 0; mode < 2; ++mode)
  {
    vnl_matrix<double> design(9, 3);
    vnl_vector<double> coefficient(9);
    for (unsigned int i = 0; i < 9; ++i)
    {
      design(i, 0) = 1.0;
      design(i, 1) = longAxes[i];
      design(i, 2) = middleAxes[i];
      coefficient[i] = estimator->Project(estimator->GetCorrespondedMesh(i))[mode];
    }
    const vnl_vector<double> fit = vnl_svd<double>(design).solve(coefficient);
    const double             residual = (design * fit - coefficient).rms();
    EXPECT_LT(residual, 0.1 * coefficient.rms()) << "mode " << mode + 1;
  }

  // The modes' directions against the analytic ones: on the mean (centred, principal axes
  // e1 long, e2 middle), a change of the long axis moves vertex p by (p.e1) e1 and one of
  // the middle axis by (p.e2) e2, and Procrustes takes out some uniform scaling p. Along
  // the mean's vertex normals, where a shape change does not depend on how the points
  // slide, each of the first two modes lies within 0.1 rad of the span of these three.
  const IndexedTriangleMesh mean = itk::MeshExtraction::MakeIndexedTriangleMesh(*estimator->GetMeanMesh());
  const std::size_t         n = mean.points.size();
  Vec3                      centre = itk::MeshExtraction::MakeVec3(0, 0, 0);
  for (const Vec3 & p : mean.points)
  {
    centre += p / static_cast<double>(n);
  }
  itk::Matrix<double, 3, 3> scatter;
  scatter.Fill(0.0);
  for (const Vec3 & p : mean.points)
  {
    for (unsigned int r = 0; r < 3; ++r)
    {
      for (unsigned int c = 0; c < 3; ++c)
      {
        scatter[r][c] += (p - centre)[r] * (p - centre)[c];
      }
    }
  }
  itk::SymmetricEigenAnalysis<itk::Matrix<double, 3, 3>, itk::FixedArray<double, 3>, itk::Matrix<double, 3, 3>>
                             eigen(3);
  itk::FixedArray<double, 3> eigenvalues;
  itk::Matrix<double, 3, 3>  eigenvectors; // rows, by ascending eigenvalue
  eigen.SetOrderEigenValues(true);
  eigen.ComputeEigenValuesAndVectors(scatter, eigenvalues, eigenvectors);
  std::vector<Vec3> normals(n, itk::MeshExtraction::MakeVec3(0, 0, 0));
  for (const auto & t : mean.triangles)
  {
    const Vec3 area =
      itk::MeshExtraction::Cross(mean.points[t[1]] - mean.points[t[0]], mean.points[t[2]] - mean.points[t[0]]);
    for (unsigned int k = 0; k < 3; ++k)
    {
      normals[t[k]] += area;
    }
  }
  const auto alongNormals = [&](const std::vector<Vec3> & displacement) {
    vnl_vector<double> v(n);
    for (std::size_t k = 0; k < n; ++k)
    {
      v[k] = itk::MeshExtraction::Dot(displacement[k], normals[k]) / itk::MeshExtraction::Norm(normals[k]);
    }
    return v;
  };
  vnl_matrix<double> analytic(n, 3);
  std::vector<Vec3>  scaling(n);
  for (unsigned int axis = 0; axis < 2; ++axis)
  {
    const Vec3 e =
      itk::MeshExtraction::MakeVec3(eigenvectors[2 - axis][0], eigenvectors[2 - axis][1], eigenvectors[2 - axis][2]);
    std::vector<Vec3> stretch(n);
    for (std::size_t k = 0; k < n; ++k)
    {
      stretch[k] = itk::MeshExtraction::Dot(mean.points[k] - centre, e) * e;
      scaling[k] = mean.points[k] - centre;
    }
    analytic.set_column(axis, alongNormals(stretch));
  }
  analytic.set_column(2, alongNormals(scaling));
  const vnl_matrix<double> basis = vnl_svd<double>(analytic).U().extract(n, 3);
  for (unsigned int mode = 0; mode < 2; ++mode)
  {
    std::vector<double> b(mode + 1, 0.0);
    b[mode] = 1.0;
    const IndexedTriangleMesh shifted = itk::MeshExtraction::MakeIndexedTriangleMesh(*estimator->Synthesize(b));
    std::vector<Vec3>         move(n);
    for (std::size_t k = 0; k < n; ++k)
    {
      move[k] = shifted.points[k] - mean.points[k];
    }
    const vnl_vector<double> m = alongNormals(move);
    const double angle = std::acos(std::min(1.0, (basis.transpose() * m).magnitude() / m.magnitude()));
    EXPECT_LT(angle, 0.1) << "mode " << mode + 1 << " is " << angle << " rad from the analytic directions";
  }
}

TEST(LandmarkFreeShapeModelEstimator, TwoClustersSeparateOnModeOne)
{
  std::mt19937_64                random(11);
  std::vector<MeshType::Pointer> meshes;
  auto                           estimator = Estimator::New();
  const double                   axes[] = { 25.0, 25.5, 26.0, 26.5, 33.0, 33.5, 34.0, 34.5 };
  for (unsigned int i = 0; i < 8; ++i)
  {
    meshes.push_back(ToMesh(PosedEllipsoid(axes[i], middleAxis, i % 2 == 0 ? 3 : 4, random)));
    estimator->AddInputMesh(meshes.back());
  }
  estimator->Update();
  std::vector<double> first;
  for (unsigned int i = 0; i < 8; ++i)
  {
    first.push_back(estimator->Project(estimator->GetCorrespondedMesh(i))[0]);
  }
  const double sign = first[0] < 0.0 ? -1.0 : 1.0;
  for (unsigned int i = 0; i < 8; ++i)
  {
    EXPECT_GT((i < 4 ? sign : -sign) * first[i], 0.5) << "mesh " << i;
  }
}

TEST(LandmarkFreeShapeModelEstimator, PointToSurfaceMatchesCloserThanPointToPoint)
{
  // The thesis' Table 7.1: with meshes of different resolutions, pairing points with
  // the nearest point on the triangles leaves a smaller E^2 than pairing them with the
  // nearest vertex.
  double e2[2];
  for (unsigned int k = 0; k < 2; ++k)
  {
    std::mt19937_64                random(5);
    std::vector<MeshType::Pointer> meshes;
    auto                           estimator = Estimator::New();
    estimator->NonRigidCorrespondenceOff();
    estimator->SetCorrespondence(k == 0 ? itk::MeshExtractionEnums::Correspondence::PointToSurface
                                        : itk::MeshExtractionEnums::Correspondence::PointToPoint);
    for (unsigned int i = 0; i < 6; ++i)
    {
      meshes.push_back(ToMesh(PosedEllipsoid(LongAxis(i, 6), middleAxis, i % 2 == 0 ? 2 : 4, random)));
      estimator->AddInputMesh(meshes.back());
    }
    estimator->Update();
    e2[k] = estimator->GetMeanSquaredDistancePerPass().back();
  }
  EXPECT_LT(e2[0], e2[1]);
}

TEST(LandmarkFreeShapeModelEstimator, ModelFileRoundTripAndLayout)
{
  const Estimator::Pointer estimator = EllipsoidModel(4);
  const std::string        fileName = TemporaryFile("LandmarkFreeShapeModel.h5");
  estimator->WriteModel(fileName);

  std::vector<itk::MeshExtraction::TriangleIndices> triangles;
  const auto model = itk::MeshExtraction::detail::ReadStatismoModel(fileName, triangles);
  const auto mean = itk::MeshExtraction::MakeIndexedTriangleMesh(*estimator->GetMeanMesh());
  ASSERT_EQ(model.mean.size(), 3 * mean.points.size());
  EXPECT_EQ(triangles, mean.triangles);
  for (std::size_t k = 0; k < mean.points.size(); ++k)
  {
    for (unsigned int d = 0; d < 3; ++d)
    {
      EXPECT_NEAR(model.mean[3 * k + d], mean.points[k][d], 1e-4);
    }
  }
  ASSERT_EQ(model.NumberOfModes(), estimator->GetNumberOfModes());
  for (std::size_t i = 0; i < model.NumberOfModes(); ++i)
  {
    EXPECT_NEAR(model.variances[i], estimator->GetVariances()[i], 1e-5 * estimator->GetVariances()[i]);
    double norm = 0.0;
    for (double x : model.basis[i])
    {
      norm += x * x;
    }
    EXPECT_NEAR(norm, 1.0, 1e-5);
  }

  if (std::system("command -v h5dump > /dev/null 2>&1") != 0)
  {
    GTEST_SKIP() << "h5dump (Debian hdf5-tools) is not installed: the layout check is skipped";
  }
  const std::string dump = TemporaryFile("LandmarkFreeShapeModel.h5dump.txt");
  ASSERT_EQ(std::system(("h5dump -H " + fileName + " > " + dump).c_str()), 0);
  std::ifstream     in(dump);
  std::stringstream text;
  text << in.rdbuf();
  for (const char * expected : { "GROUP \"model\"",
                                 "DATASET \"mean\"",
                                 "DATASET \"pcaBasis\"",
                                 "DATASET \"pcaVariance\"",
                                 "DATASET \"noiseVariance\"",
                                 "GROUP \"representer\"",
                                 "DATASET \"points\"",
                                 "DATASET \"cells\"",
                                 "GROUP \"modelinfo\"",
                                 "GROUP \"version\"" })
  {
    EXPECT_NE(text.str().find(expected), std::string::npos) << expected << " missing in\n" << text.str();
  }
  const std::string k = std::to_string(estimator->GetNumberOfModes());
  const std::string n = std::to_string(mean.points.size());
  EXPECT_NE(text.str().find("( " + std::to_string(3 * mean.points.size()) + ", " + k + " )"), std::string::npos)
    << "pcaBasis is not 3n x k";
  EXPECT_NE(text.str().find("( 3, " + n + " )"), std::string::npos) << "representer points are not 3 x n";
  std::remove(dump.c_str());
  std::remove(fileName.c_str());
}

TEST(LandmarkFreeShapeModelEstimator, CorruptModelFilesAreRefusedWithAnITKException)
{
  // Issue 48, case 10: a bit-flipped model gave only "std::bad_alloc". Every byte of a
  // model flipped in turn (up to some 1,500 of them): each file reads, or is refused with
  // an itk::ExceptionObject naming it; nothing else escapes.
  const Estimator::Pointer estimator = EllipsoidModel(3);
  const std::string        fileName = TemporaryFile("LandmarkFreeShapeModel-corrupt.h5");
  estimator->WriteModel(fileName);
  std::ifstream           in(fileName, std::ios::binary);
  const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(bytes.size(), 1000u);
  const std::size_t stride = std::max<std::size_t>(1, bytes.size() / 1500);
  std::size_t       refused = 0;
  for (std::size_t i = 0; i < bytes.size(); i += stride)
  {
    std::vector<char> corrupt = bytes;
    corrupt[i] = static_cast<char>(corrupt[i] ^ 0x5a);
    std::ofstream(fileName, std::ios::binary | std::ios::trunc).write(corrupt.data(), corrupt.size());
    std::vector<itk::MeshExtraction::TriangleIndices> triangles;
    try
    {
      itk::MeshExtraction::detail::ReadStatismoModel(fileName, triangles);
    }
    catch (const itk::ExceptionObject & e)
    {
      ++refused;
      EXPECT_NE(std::string(e.GetDescription()).find(fileName), std::string::npos) << e.GetDescription();
    }
    catch (const std::exception & e)
    {
      ADD_FAILURE() << "byte " << i << " flipped: " << e.what();
    }
  }
  EXPECT_GT(refused, 0u);
  std::remove(fileName.c_str());
}

TEST(LandmarkFreeShapeModelEstimator, BadInputThrows)
{
  std::mt19937_64 random(3);
  const auto      good = ToMesh(PosedEllipsoid(30, middleAxis, 2, random));

  auto one = Estimator::New();
  one->AddInputMesh(good);
  EXPECT_THROW(one->Update(), itk::ExceptionObject);

  IndexedTriangleMesh openIndexed = PosedEllipsoid(30, middleAxis, 2, random);
  openIndexed.triangles.pop_back();
  IndexedTriangleMesh nanIndexed = PosedEllipsoid(30, middleAxis, 2, random);
  nanIndexed.points[5][1] = std::numeric_limits<double>::quiet_NaN();
  const std::vector<std::pair<MeshType::Pointer, std::string>> cases = { { ToMesh(openIndexed), "open" },
                                                                         { MeshType::New(), "empty" },
                                                                         { ToMesh(nanIndexed), "not finite" } };
  for (const auto & bad : cases)
  {
    auto estimator = Estimator::New();
    estimator->AddInputMesh(good);
    estimator->AddInputMesh(bad.first);
    try
    {
      estimator->Update();
      ADD_FAILURE() << "no exception for a mesh that is " << bad.second;
    }
    catch (const itk::ExceptionObject & e)
    {
      const std::string message = e.GetDescription();
      EXPECT_NE(message.find("input mesh 1"), std::string::npos) << message;
      EXPECT_NE(message.find(bad.second), std::string::npos) << message;
    }
  }
  EXPECT_THROW(Estimator::New()->GetMeanMesh(), itk::ExceptionObject); // not built
}

// The ten L1 vertebrae of ../shared/data (never part of the project): the model with the
// non-rigid stage, leave-one-out generalisation, specificity and landmark transfer
// against the bounds of issue 29 (or, where the prototype did not reach them, against
// bounds a little above what the prototype reached).
TEST(LandmarkFreeShapeModelEstimator, VertebraeL1)
{
  const std::string directory = std::string(MESHEXTRACTION_SOURCE_DIR) + "/../shared/data/vertebrae_L1/";
  const char *      names[] = { "010", "013", "016", "018", "022", "023", "024", "026", "030", "041" };
  if (!std::ifstream(directory + "sub-verse010_segment_20.ply"))
  {
    GTEST_SKIP() << "../shared/data/vertebrae_L1 is not next to the project (" << directory
                 << "): the L1 shape-model test is skipped";
  }
  namespace detail = itk::MeshExtraction::detail;
  auto                               estimator = Estimator::New();
  std::vector<MeshType::Pointer>     meshes;
  std::vector<IndexedTriangleMesh>   originals;
  std::vector<detail::MeshLandmarks> landmarks;
  for (const char * name : names)
  {
    const std::string stem = directory + "sub-verse" + name + "_segment_20";
    const auto        indexed = itk::MeshExtraction::ReadPLYFile(stem + ".ply");
    originals.push_back(detail::PrepareTrainingMesh(indexed, stem));
    meshes.push_back(ToMesh(indexed));
    estimator->AddInputMesh(meshes.back());
    detail::MeshLandmarks l;
    for (const auto & landmark : itk::MeshExtraction::ReadLandmarkFile(stem + ".json"))
    {
      l.ids.push_back(landmark.id);
      l.points.push_back(itk::MeshExtraction::MakeVec3(landmark.point[0], landmark.point[1], landmark.point[2]));
    }
    landmarks.push_back(l);
  }
  estimator->Update();
  std::vector<detail::Shape> corresponded;
  for (unsigned int i = 0; i < meshes.size(); ++i)
  {
    corresponded.push_back(itk::MeshExtraction::MakeIndexedTriangleMesh(*estimator->GetCorrespondedMesh(i)).points);
  }
  const auto triangles = itk::MeshExtraction::MakeIndexedTriangleMesh(*estimator->GetMeanMesh()).triangles;

  // Closed, 2-manifold and outward, and (the non-rigid stage undoes moves that fold or
  // cross the template) free of self-intersections. The mean of the model is reported.
  std::cout
    << "self-intersecting triangle pairs: pivot input "
    << detail::FindSelfIntersections(originals[estimator->GetPivotIndex()]).size() << ", mean "
    << detail::FindSelfIntersections(itk::MeshExtraction::MakeIndexedTriangleMesh(*estimator->GetMeanMesh())).size()
    << ", corresponded:";
  for (unsigned int i = 0; i < meshes.size(); ++i)
  {
    const auto emitted = itk::MeshExtraction::MakeIndexedTriangleMesh(*estimator->GetCorrespondedMesh(i));
    EXPECT_EQ(TopologyProblems(emitted), 0u) << "corresponded mesh " << names[i];
    const std::size_t crossing = detail::FindSelfIntersections(emitted).size();
    EXPECT_EQ(crossing, 0u) << "corresponded mesh " << names[i];
    std::cout << ' ' << crossing;
  }
  std::cout << std::endl;

  const auto loo = detail::LeaveOneOutGeneralization(corresponded, originals, 3);
  EXPECT_LE(loo.meanVertexToVertex, 1.8);
  std::vector<detail::SimilarityParameters> toModel;
  const auto                                aligned = detail::GeneralizedProcrustes(corresponded, true, &toModel);
  detail::SpecificitySettings               specificitySettings;
  const auto specificity = detail::Specificity(aligned, toModel, originals, specificitySettings);
  EXPECT_LE(specificity.vertexToSurface, 1.0);
  EXPECT_LE(specificity.vertexToVertex, 1.6);
  const auto transfer = detail::TransferLandmarks(corresponded, triangles, landmarks);
  EXPECT_EQ(transfer.count, 900u);
  EXPECT_LE(transfer.mean, 3.1);
  double inThree = 0.0;
  for (unsigned int i = 0; i < 3 && i < estimator->GetNumberOfModes(); ++i)
  {
    inThree += estimator->GetVariances()[i] / estimator->GetTotalVariance();
  }
  EXPECT_GE(inThree, 0.65);
  std::cout << "L1 model: LOO v2v " << loo.meanVertexToVertex << " mm, specificity v2v " << specificity.vertexToVertex
            << " mm, v2s " << specificity.vertexToSurface << " mm, transfer mean " << transfer.mean << " mm, median "
            << transfer.median << " mm, 3 modes " << inThree << std::endl;
}
