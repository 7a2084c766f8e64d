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
#include "itkSymmetricSimilarityICPRegistration.h"
#include "itkImplicitSurfaceImageSource.h"
#include "itkMeshExtractionIndexedTriangleMesh.h"
#include "itkMeshExtractionSymmetricICP.h"
#include "itkSphereUnionImplicitSurface.h"
#include "itkSurfaceNetsImageToMeshFilter.h"
#include "itkSymmetricPairedPointSetMetric.h"

#include <gtest/gtest.h>

#include <cmath>

namespace
{
using MeshType = itk::QuadEdgeMesh<double, 3>;
using Registration = itk::SymmetricSimilarityICPRegistration<MeshType>;
using Similarity = itk::Similarity3DTransform<double>;
using Point = itk::Point<double, 3>;

/** Three balls of different radii on a scalene triangle: no rotation maps the shape
 * onto itself, so a similarity between two copies is unique. Extracted by SurfaceNets
 * (SNERT) on a grid of the given spacing. */
MeshType::Pointer
AsymmetricShape(double spacing)
{
  auto  surface = itk::SphereUnionImplicitSurface::New();
  Point c;
  c[0] = 0, c[1] = 0, c[2] = 0;
  surface->AddSphere(c, 10.0);
  c[0] = 13, c[1] = 2, c[2] = 1;
  surface->AddSphere(c, 7.0);
  c[0] = 3, c[1] = 12, c[2] = -2;
  surface->AddSphere(c, 5.0);
  using ImageType = itk::Image<float, 3>;
  auto                 source = itk::ImplicitSurfaceImageSource<ImageType>::New();
  ImageType::SizeType  size;
  ImageType::PointType origin;
  const double         low[3] = { -13, -13, -13 };
  const double         high[3] = { 23, 20, 13 };
  for (unsigned int d = 0; d < 3; ++d)
  {
    size[d] = static_cast<itk::SizeValueType>(std::ceil((high[d] - low[d]) / spacing)) + 1;
    origin[d] = low[d];
  }
  ImageType::SpacingType s;
  s.Fill(spacing);
  source->SetSurface(surface);
  source->SetSize(size);
  source->SetSpacing(s);
  source->SetOrigin(origin);
  auto extract = itk::SurfaceNetsImageToMeshFilter<ImageType, MeshType>::New();
  extract->SetInput(source->GetOutput());
  extract->SetInsideIsAboveIsoValue(false);
  extract->Update();
  MeshType::Pointer mesh = extract->GetOutput();
  mesh->DisconnectPipeline();
  return mesh;
}

/** A copy of `mesh` moved by `transform`. */
MeshType::Pointer
Moved(const MeshType * mesh, const itk::Transform<double, 3, 3> & transform)
{
  itk::MeshExtraction::IndexedTriangleMesh indexed = itk::MeshExtraction::MakeIndexedTriangleMesh(*mesh);
  for (auto & v : indexed.points)
  {
    Point p;
    p[0] = v[0], p[1] = v[1], p[2] = v[2];
    const Point q = transform.TransformPoint(p);
    v = itk::MeshExtraction::MakeVec3(q[0], q[1], q[2]);
  }
  auto moved = MeshType::New();
  itk::MeshExtraction::FillMesh(indexed, *moved);
  return moved;
}

Similarity::Pointer
KnownSimilarity()
{
  auto                   t = Similarity::New();
  itk::Vector<double, 3> axis;
  axis[0] = 0.3, axis[1] = -0.8, axis[2] = 0.5;
  itk::Versor<double> versor;
  versor.Set(axis / axis.GetNorm(), 1.3); // 75 degrees
  Point center;
  center[0] = 5, center[1] = 4, center[2] = 0;
  t->SetCenter(center);
  t->SetRotation(versor);
  t->SetScale(1.3);
  Similarity::OutputVectorType translation;
  translation[0] = 112, translation[1] = -40, translation[2] = 600; // far from the origin, as real scans lie
  t->SetTranslation(translation);
  return t;
}

double
LargestDifference(const itk::Transform<double, 3, 3> & a, const itk::Transform<double, 3, 3> & b)
{
  double largest = 0.0;
  for (double x = -15; x <= 25; x += 10)
  {
    for (double y = -15; y <= 20; y += 10)
    {
      for (double z = -15; z <= 15; z += 10)
      {
        Point p;
        p[0] = x, p[1] = y, p[2] = z;
        largest = std::max(largest, a.TransformPoint(p).EuclideanDistanceTo(b.TransformPoint(p)));
      }
    }
  }
  return largest;
}

Registration::Pointer
Register(const MeshType * fixed, const MeshType * moving, itk::MeshExtractionEnums::Correspondence mode)
{
  auto registration = Registration::New();
  registration->SetFixedMesh(fixed);
  registration->SetMovingMesh(moving);
  registration->SetCorrespondence(mode);
  registration->Update();
  return registration;
}
} // namespace

TEST(SymmetricSimilarityICPRegistration, RecoversAKnownSimilarityAndIsSymmetric)
{
  const auto shape = AsymmetricShape(1.0);
  const auto truth = KnownSimilarity();
  const auto moved = Moved(shape, *truth);
  for (auto mode : { itk::MeshExtractionEnums::Correspondence::PointToPoint,
                     itk::MeshExtractionEnums::Correspondence::PointToSurface })
  {
    const auto forward = Register(shape, moved, mode);
    EXPECT_LT(LargestDifference(*forward->GetTransform(), *truth), 1e-3) << mode;
    EXPECT_NEAR(forward->GetTransform()->GetScale(), 1.3, 1e-6) << mode;
    EXPECT_LT(forward->GetMeanSquaredDistance(), 1e-8) << mode; // float coordinates
    // B to A is the inverse of A to B.
    const auto backward = Register(moved, shape, mode);
    auto       inverse = Similarity::New();
    ASSERT_TRUE(forward->GetTransform()->GetInverse(inverse));
    Point p;
    p.Fill(3.0);
    EXPECT_LT(backward->GetTransform()->TransformPoint(truth->TransformPoint(p)).EuclideanDistanceTo(p), 1e-3);
  }
}

TEST(SymmetricSimilarityICPRegistration, PointToSurfaceFitsBetterThanPointToPointAcrossResolutions)
{
  // The same shape at two resolutions: the vertices do not correspond, the surfaces do.
  const auto coarse = AsymmetricShape(1.5);
  const auto fine = Moved(AsymmetricShape(0.7), *KnownSimilarity());
  const auto p2p = Register(coarse, fine, itk::MeshExtractionEnums::Correspondence::PointToPoint);
  const auto p2s = Register(coarse, fine, itk::MeshExtractionEnums::Correspondence::PointToSurface);
  EXPECT_LT(p2s->GetMeanSquaredDistance(), 0.5 * p2p->GetMeanSquaredDistance());
  EXPECT_LT(LargestDifference(*p2s->GetTransform(), *KnownSimilarity()), 0.3);
  EXPECT_LT(p2s->GetMeanSquaredDistance(), p2s->GetInitialMeanSquaredDistance());
}

TEST(SymmetricSimilarityICPRegistration, LevenbergMarquardtOnTheMetricFindsTheClosedFormMinimum)
{
  // Eq. 7.3 for fixed pairs: the half of the pairs' similarity with Horn's symmetric
  // scale is its minimum; ITK's registration method with the metric stays there.
  using namespace itk::MeshExtraction;
  std::vector<Vec3>   fixed, moving;
  std::vector<double> weights;
  const auto          truth = KnownSimilarity();
  for (int k = 0; k < 200; ++k)
  {
    const Vec3 p = MakeVec3(std::sin(k * 1.1) * 20, std::cos(k * 0.7) * 15, std::sin(k * 0.3 + 1) * 10);
    Point      q;
    q[0] = p[0], q[1] = p[1], q[2] = p[2];
    const auto t = truth->TransformPoint(q);
    fixed.push_back(p);
    moving.push_back(MakeVec3(t[0] + std::sin(k * 2.3), t[1] + std::cos(k * 1.9), t[2] + std::sin(k * 0.9)));
    weights.push_back(1.0);
  }
  const Vec3 center = MakeVec3(1, 2, 3);
  auto       half = detail::HalfSimilarity(*detail::FitSimilarity(fixed, moving, weights, center, true), center);
  using PointSet = itk::PointSet<double, 3>;
  auto makeSet = [](const std::vector<Vec3> & points) {
    auto set = PointSet::New();
    for (std::size_t k = 0; k < points.size(); ++k)
    {
      Point p;
      p[0] = points[k][0], p[1] = points[k][1], p[2] = points[k][2];
      set->SetPoint(k, p);
    }
    return set;
  };
  auto metric = itk::SymmetricPairedPointSetMetric<PointSet>::New();
  metric->SetFixedPointSet(makeSet(fixed));
  metric->SetMovingPointSet(makeSet(moving));
  metric->SetTransform(half);
  metric->Initialize();
  // (GetValue sets the transform's parameters: keep the minimum's own copy.)
  const auto   minimum = half->GetParameters();
  const double closedForm = metric->GetValue(minimum).squared_magnitude();
  // Every nearby parameter vector is worse.
  for (unsigned int j = 0; j < half->GetNumberOfParameters(); ++j)
  {
    for (double step : { -1e-4, 1e-4 })
    {
      auto p = minimum;
      p[j] += step;
      EXPECT_GT(metric->GetValue(p).squared_magnitude(), closedForm) << "parameter " << j;
    }
  }
  // The derivative is the finite difference of the values.
  itk::SymmetricPairedPointSetMetric<PointSet>::DerivativeType derivative;
  metric->GetDerivative(minimum, derivative);
  for (unsigned int j = 0; j < half->GetNumberOfParameters(); ++j)
  {
    auto plus = minimum, minus = minimum;
    plus[j] += 1e-6;
    minus[j] -= 1e-6;
    const auto high = metric->GetValue(plus);
    const auto low = metric->GetValue(minus);
    for (unsigned int v = 0; v < 12; ++v)
    {
      const double difference = (high[v] - low[v]) / 2e-6;
      EXPECT_NEAR(derivative[j][v], difference, 1e-5 * (1.0 + std::abs(difference)))
        << "parameter " << j << " value " << v;
    }
  }
}

TEST(SymmetricSimilarityICPRegistration, RefusesBadMeshesWithAMessage)
{
  auto expectError = [](const MeshType * fixed, const MeshType * moving, const std::string & text) {
    auto registration = Registration::New();
    registration->SetFixedMesh(fixed);
    registration->SetMovingMesh(moving);
    try
    {
      registration->Update();
      ADD_FAILURE() << "no exception; expected: " << text;
    }
    catch (const itk::ExceptionObject & e)
    {
      EXPECT_NE(std::string(e.GetDescription()).find(text), std::string::npos) << e.GetDescription();
    }
  };
  const auto shape = AsymmetricShape(1.5);
  expectError(nullptr, shape, "No fixed mesh");
  expectError(shape, MeshType::New(), "The moving mesh has no triangles");
  auto                broken = Moved(shape, *Similarity::New());
  MeshType::PointType nan = broken->GetPoint(7);
  nan[1] = std::nan("");
  broken->SetPoint(7, nan);
  expectError(broken, shape, "The fixed mesh's point 7 has a coordinate that is not finite");
}
