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
#include "itkOrthogonalContourModel.h"
#include "itkEllipsoidImplicitSurface.h"
#include "MeshExtractionContourUser.h"
#include "itkSphereImplicitSurface.h"
#include "itkOrthogonalContourModelToMeshFilter.h"
#include "itkTriangleMeshQualityCalculator.h"
#include "itkImage.h"
#include "itkQuadEdgeMesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <random>
#include <set>
#include <string>

namespace
{
using ModelType = itk::OrthogonalContourModel;
using MeshType = itk::QuadEdgeMesh<double, 3>;
using FilterType = itk::OrthogonalContourModelToMeshFilter<MeshType>;

itk::Vector<double, 3>
Vec(double x, double y, double z)
{
  itk::Vector<double, 3> v;
  v[0] = x;
  v[1] = y;
  v[2] = z;
  return v;
}

itk::Point<double, 3>
Pt(double x, double y, double z)
{
  itk::Point<double, 3> p;
  p[0] = x;
  p[1] = y;
  p[2] = z;
  return p;
}

/** A model on an n^3 grid of 1 mm voxels with the template at its centre. */
ModelType::Pointer
MakeTemplate(unsigned int                 n,
             double                       radius,
             ModelType::InterpolationEnum interpolation = ModelType::InterpolationEnum::CatmullRom)
{
  auto                model = ModelType::New();
  ModelType::SizeType size;
  size.Fill(n);
  ModelType::SpacingType spacing;
  spacing.Fill(1.0);
  ModelType::PointType origin;
  origin.Fill(0.0);
  ModelType::DirectionType direction;
  direction.SetIdentity();
  model->SetGrid(size, spacing, origin, direction);
  model->SetInterpolation(interpolation);
  ModelType::IndexType center;
  center.Fill(static_cast<itk::IndexValueType>(n / 2));
  ModelType::RadiiType radii;
  radii.Fill(radius);
  model->InitializeTemplate(center, radii);
  return model;
}

/** The control point on the line along `axis` through (a, b) (the other two axes in
 * order) nearest `near` along the line. */
unsigned int
PointOnLine(const ModelType & model, unsigned int axis, double a, double b, double near)
{
  unsigned int best = model.GetNumberOfControlPoints();
  double       bestDistance = 1e300;
  for (unsigned int p = 0; p < model.GetNumberOfControlPoints(); ++p)
  {
    const auto x = model.GetControlPointIndex(p);
    if (model.GetControlPointLineAxis(p) == axis && x[(axis + 1) % 3] == (axis == 1 ? b : a) &&
        x[(axis + 2) % 3] == (axis == 1 ? a : b) && std::abs(x[axis] - near) < bestDistance)
    {
      best = p;
      bestDistance = std::abs(x[axis] - near);
    }
  }
  EXPECT_LT(best, model.GetNumberOfControlPoints()) << "no control point on that line";
  return best;
}

/** The quality report of the model's mesh. */
itk::MeshExtraction::TriangleMeshQualityReport
MeshReport(const ModelType * model, double edgeLength = 0.0)
{
  auto filter = FilterType::New();
  filter->SetInput(model);
  filter->SetTargetEdgeLength(edgeLength);
  filter->Update();
  auto calculator = itk::TriangleMeshQualityCalculator<MeshType>::New();
  calculator->SetMesh(filter->GetOutput());
  calculator->Compute();
  return calculator->GetReport();
}

void
ExpectValidMesh(const ModelType * model, const std::string & what)
{
  const auto report = MeshReport(model);
  EXPECT_TRUE(report.IsValidClosedSurface())
    << what << ": boundary " << report.boundaryEdges << ", non-manifold " << report.nonManifoldEdges
    << ", inconsistent " << report.inconsistentlyOrientedEdges << ", degenerate " << report.degenerateTriangles
    << ", inverted " << report.invertedTrianglesVersusOutward << ", self-intersecting " << report.selfIntersectingPairs
    << ", volume " << report.enclosedVolume;
  EXPECT_EQ(report.eulerCharacteristic, 2) << what;
  EXPECT_EQ(report.connectedComponents, 1) << what;
}

bool
FourNeighbours(const ModelType::IndexType & a, const ModelType::IndexType & b)
{
  return std::abs(a[0] - b[0]) + std::abs(a[1] - b[1]) + std::abs(a[2] - b[2]) == 1;
}
} // namespace

TEST(OrthogonalContourModel, TemplateHasThreeContoursSixPointsAndEightFaces)
{
  for (const auto interpolation : { ModelType::InterpolationEnum::Linear, ModelType::InterpolationEnum::CatmullRom })
  {
    const auto model = MakeTemplate(33, 10.0, interpolation);
    EXPECT_EQ(model->CheckInvariants(), "");
    EXPECT_EQ(model->GetNumberOfContours(), 3u);
    EXPECT_EQ(model->GetNumberOfControlPoints(), 6u);
    EXPECT_EQ(model->GetFaces().size(), 8u);
    for (unsigned int p = 0; p < 6; ++p)
    {
      const auto n = model->GetControlPointNeighbours(p);
      EXPECT_EQ(std::set<unsigned int>(n.begin(), n.end()).size(), 4u);
    }
    // Linear: the octahedron, volume 4/3 r^3, with planar faces; Catmull-Rom: rounder,
    // between the octahedron and the sphere through the six points (four points per
    // contour make a curve inside the circle through them).
    const double octahedron = 4.0 / 3.0 * 1000.0;
    const double sphere = 4.0 / 3.0 * 3.141592653589793 * 1000.0;
    if (interpolation == ModelType::InterpolationEnum::Linear)
    {
      EXPECT_NEAR(model->GetVolume(), octahedron, 1e-6 * octahedron);
    }
    else
    {
      EXPECT_GT(model->GetVolume(), 1.2 * octahedron);
      EXPECT_LT(model->GetVolume(), sphere);
    }
    ExpectValidMesh(model, "template");
  }
}

TEST(OrthogonalContourModel, ScanConversionIsFourConnectedWithOnePointPerVoxel)
{
  const auto model = MakeTemplate(40, 13.0);
  ASSERT_TRUE(model->AddContour(2, 24));
  ASSERT_TRUE(model->AddContour(0, 15));
  for (unsigned int c = 0; c < model->GetNumberOfContours(); ++c)
  {
    const auto voxels = model->GetScanConversion(c);
    ASSERT_GE(voxels.size(), 4u);
    std::set<std::array<itk::IndexValueType, 3>> seen;
    for (std::size_t i = 0; i < voxels.size(); ++i)
    {
      EXPECT_TRUE(FourNeighbours(voxels[i], voxels[(i + 1) % voxels.size()])) << "contour " << c << " at " << i;
      EXPECT_EQ(voxels[i][model->GetContourAxis(c)], model->GetContourPosition(c));
      const std::array<itk::IndexValueType, 3> v{ { voxels[i][0], voxels[i][1], voxels[i][2] } };
      EXPECT_TRUE(seen.insert(v).second) << "voxel twice";
    }
    for (const auto p : model->GetContourControlPoints(c))
    {
      const auto                               x = model->GetControlPointIndex(p);
      const std::array<itk::IndexValueType, 3> v{ { static_cast<itk::IndexValueType>(std::floor(x[0] + 0.5)),
                                                    static_cast<itk::IndexValueType>(std::floor(x[1] + 0.5)),
                                                    static_cast<itk::IndexValueType>(std::floor(x[2] + 0.5)) } };
      EXPECT_EQ(seen.count(v), 1u) << "the voxel of control point " << p << " is not on contour " << c;
    }
  }
}

TEST(OrthogonalContourModel, MovesStayOnTheLineAndShortOfTheNeighboursOnIt)
{
  const auto         model = MakeTemplate(33, 10.0);
  const unsigned int top = PointOnLine(*model, 2, 16, 16, 26);
  const unsigned int bottom = PointOnLine(*model, 2, 16, 16, 6);
  EXPECT_TRUE(model->MoveControlPoint(top, 29.25));
  EXPECT_EQ(model->GetRefusalReason(), "");
  EXPECT_DOUBLE_EQ(model->GetControlPointIndex(top)[2], 29.25);
  EXPECT_DOUBLE_EQ(model->GetControlPointIndex(top)[0], 16.0);
  // Past the bottom point, into its voxel, or out of the grid: refused, nothing changes.
  const std::string before = model->ToJSON();
  for (const double target : { 3.0, 6.2, 5.6, 32.5, -1.0 })
  {
    EXPECT_FALSE(model->MoveControlPoint(top, target)) << target;
    EXPECT_NE(model->GetRefusalReason().find("Fig. 5.4"), std::string::npos) << model->GetRefusalReason();
    EXPECT_EQ(model->ToJSON(), before);
  }
  // Into the plane of a contour: refused.
  EXPECT_FALSE(model->MoveControlPoint(top, 16.0));
  EXPECT_EQ(model->ToJSON(), before);
  const auto range = model->GetControlPointRange(top);
  EXPECT_DOUBLE_EQ(range[0], 6.5);
  EXPECT_DOUBLE_EQ(range[1], 32.0);
  EXPECT_DOUBLE_EQ(model->GetControlPointIndex(bottom)[2], 6.0);
}

TEST(OrthogonalContourModel, AddingAndRemovingContours)
{
  const auto model = MakeTemplate(33, 10.0);
  EXPECT_TRUE(model->AddContour(2, 20)) << model->GetRefusalReason();
  EXPECT_EQ(model->GetNumberOfContours(), 4u);
  EXPECT_EQ(model->GetNumberOfControlPoints(), 10u);
  EXPECT_EQ(model->GetContoursInPlane(2, 20).size(), 1u);
  EXPECT_EQ(model->GetControlPointsInPlane(2, 20).size(), 4u);
  EXPECT_EQ(model->CheckInvariants(), "");
  EXPECT_TRUE(model->AddContour(0, 11)) << model->GetRefusalReason();
  EXPECT_EQ(model->CheckInvariants(), "");
  ExpectValidMesh(model, "five contours");

  const std::string before = model->ToJSON();
  // An occupied plane, a plane through a control point, a plane missing the model, a
  // plane outside the grid: refused with the reason, the model unchanged.
  EXPECT_FALSE(model->AddContour(2, 20));
  EXPECT_NE(model->GetRefusalReason().find("already holds contours"), std::string::npos);
  EXPECT_FALSE(model->AddContour(2, 26));
  EXPECT_NE(model->GetRefusalReason().find("lies in it"), std::string::npos) << model->GetRefusalReason();
  EXPECT_FALSE(model->AddContour(1, 30));
  EXPECT_NE(model->GetRefusalReason().find("fewer than 4"), std::string::npos) << model->GetRefusalReason();
  EXPECT_FALSE(model->AddContour(1, 40));
  EXPECT_FALSE(model->AddContour(3, 4));
  EXPECT_EQ(model->ToJSON(), before);

  // The last plane of an axis cannot go; removing a plane takes its points away.
  EXPECT_FALSE(model->RemoveContourPlane(1, 16));
  EXPECT_NE(model->GetRefusalReason().find("last plane"), std::string::npos);
  EXPECT_FALSE(model->RemoveContourPlane(1, 17));
  EXPECT_EQ(model->ToJSON(), before);
  EXPECT_TRUE(model->RemoveContourPlane(2, 20)) << model->GetRefusalReason();
  EXPECT_EQ(model->GetNumberOfContours(), 4u);
  EXPECT_EQ(model->CheckInvariants(), "");
  EXPECT_TRUE(model->RemoveContour(model->GetContoursInPlane(0, 11)[0])) << model->GetRefusalReason();
  EXPECT_EQ(model->GetNumberOfContours(), 3u);
  EXPECT_EQ(model->GetNumberOfControlPoints(), 6u);
}

TEST(OrthogonalContourModel, PassingAPlaneWithANeighbourInItIsRefused)
{
  // Fig. 5.9: the top point's neighbours lie on the contour of the plane z = 20.
  const auto model = MakeTemplate(33, 10.0);
  ASSERT_TRUE(model->AddContour(2, 20));
  ASSERT_TRUE(model->AddContour(0, 12));
  const unsigned int top = PointOnLine(*model, 2, 16, 16, 26);
  const std::string  before = model->ToJSON();
  EXPECT_FALSE(model->MoveControlPoint(top, 18.5));
  EXPECT_NE(model->GetRefusalReason().find("Fig. 5.9"), std::string::npos) << model->GetRefusalReason();
  EXPECT_EQ(model->ToJSON(), before);
}

TEST(OrthogonalContourModel, AnIndentationMakesAndUnmakesAConcentricContour)
{
  // Fig. 5.8a: a point pushed in through the plane y = 31, its neighbours beyond it.
  const auto model = MakeTemplate(49, 12.0);
  for (const auto & plane :
       std::vector<std::pair<unsigned int, int>>{ { 0, 20 }, { 0, 28 }, { 2, 20 }, { 2, 28 }, { 1, 31 } })
  {
    ASSERT_TRUE(model->AddContour(plane.first, plane.second)) << model->GetRefusalReason();
  }
  const unsigned int contours = model->GetNumberOfContours();
  unsigned int       p = PointOnLine(*model, 1, 24, 24, 36);
  ASSERT_TRUE(model->MoveControlPoint(p, 26.5)) << model->GetRefusalReason();
  EXPECT_EQ(model->GetNumberOfContours(), contours + 1);
  EXPECT_EQ(model->GetContoursInPlane(1, 31).size(), 2u);
  EXPECT_EQ(model->CheckInvariants(), "");
  ExpectValidMesh(model, "indentation");

  // A plane through the dent cuts two concentric loops.
  ASSERT_TRUE(model->AddContour(1, 28)) << model->GetRefusalReason();
  EXPECT_EQ(model->GetContoursInPlane(1, 28).size(), 2u);
  ExpectValidMesh(model, "concentric loops");
  ASSERT_TRUE(model->RemoveContourPlane(1, 28)) << model->GetRefusalReason();

  // Back out: the contour around the point goes again.
  p = PointOnLine(*model, 1, 24, 24, 26.5);
  ASSERT_TRUE(model->MoveControlPoint(p, 35.0)) << model->GetRefusalReason();
  EXPECT_EQ(model->GetNumberOfContours(), contours);
  EXPECT_EQ(model->GetContoursInPlane(1, 31).size(), 1u);
  EXPECT_EQ(model->CheckInvariants(), "");
}

TEST(OrthogonalContourModel, TwoProtrusionsAreCutInDisjointLoops)
{
  // Fig. 5.5c: two points pulled up; the plane z = 26 cuts each protrusion.
  const auto model = MakeTemplate(33, 8.0);
  ASSERT_TRUE(model->AddContour(0, 12)) << model->GetRefusalReason();
  ASSERT_TRUE(model->AddContour(0, 20)) << model->GetRefusalReason();
  for (const double x : { 12.0, 20.0 })
  {
    const unsigned int p = PointOnLine(*model, 2, x, 16, 24);
    ASSERT_TRUE(model->MoveControlPoint(p, 30.0)) << model->GetRefusalReason();
  }
  ASSERT_TRUE(model->AddContour(2, 26)) << model->GetRefusalReason();
  EXPECT_EQ(model->GetContoursInPlane(2, 26).size(), 2u);
  EXPECT_EQ(model->CheckInvariants(), "");
  ExpectValidMesh(model, "disjoint loops");
}

TEST(OrthogonalContourModel, SaveAndLoadRoundTrip)
{
  const auto model = MakeTemplate(40, 12.0);
  ASSERT_TRUE(model->AddContour(2, 25));
  ASSERT_TRUE(model->AddContour(1, 14));
  ASSERT_TRUE(model->MoveControlPoint(0, 9.123456789012345));
  const std::string file = "orthogonal-contour-model-round-trip.json";
  model->Write(file);
  auto read = ModelType::New();
  read->Read(file);
  EXPECT_EQ(read->ToJSON(), model->ToJSON());
  EXPECT_EQ(read->GetNumberOfContours(), model->GetNumberOfContours());
  for (unsigned int p = 0; p < model->GetNumberOfControlPoints(); ++p)
  {
    for (unsigned int i = 0; i < 3; ++i)
    {
      EXPECT_EQ(read->GetControlPointIndex(p)[i], model->GetControlPointIndex(p)[i]);
    }
  }
  std::remove(file.c_str());
  // Broken files are refused with the problem.
  auto        other = ModelType::New();
  std::string text = model->ToJSON();
  text.replace(text.find("\"points\": ["), 11, "\"points\": [0, ");
  EXPECT_THROW(other->FromJSON(text), itk::ExceptionObject);
  EXPECT_THROW(other->FromJSON("{\"format\": \"something else\"}"), itk::ExceptionObject);
  EXPECT_THROW(other->Read("no-such-model.json"), itk::ExceptionObject);
}

TEST(OrthogonalContourModel, PhysicalCoordinatesFollowTheGrid)
{
  auto                             model = ModelType::New();
  auto                             image = itk::Image<float, 3>::New();
  itk::Image<float, 3>::RegionType region;
  region.SetSize({ { 30, 30, 20 } });
  image->SetRegions(region);
  image->SetSpacing(Vec(0.5, 0.5, 1.5));
  image->SetOrigin(Pt(-10.0, 4.0, 2.0));
  itk::Matrix<double, 3, 3> direction;
  direction.Fill(0.0);
  direction(0, 1) = 1.0;
  direction(1, 0) = 1.0;
  direction(2, 2) = -1.0;
  image->SetDirection(direction);
  model->SetGrid(image);
  ModelType::IndexType center = { { 15, 15, 10 } };
  model->InitializeTemplate(center, Vec(8.0, 6.0, 4.0));
  EXPECT_EQ(model->CheckInvariants(), "");
  for (unsigned int p = 0; p < model->GetNumberOfControlPoints(); ++p)
  {
    const auto                      index = model->GetControlPointIndex(p);
    itk::Image<float, 3>::PointType expected;
    image->TransformContinuousIndexToPhysicalPoint(index, expected);
    EXPECT_NEAR(model->GetControlPoint(p).EuclideanDistanceTo(expected), 0.0, 1e-12);
  }
  // The mirrored direction still gives an outward mesh, between the octahedron and the
  // ellipsoid through the six points (semi-axes 4, 3, 6 mm).
  const auto report = MeshReport(model);
  EXPECT_TRUE(report.IsValidClosedSurface());
  const double octahedron = 4.0 / 3.0 * 4.0 * 3.0 * 6.0;
  const double ellipsoid = 3.141592653589793 * octahedron;
  EXPECT_GT(report.enclosedVolume, 1.2 * octahedron);
  EXPECT_LT(report.enclosedVolume, ellipsoid);
}

TEST(OrthogonalContourModel, BadInputThrows)
{
  auto model = ModelType::New();
  EXPECT_NE(model->CheckInvariants(), "");
  EXPECT_FALSE(model->AddContour(0, 1));
  EXPECT_THROW(model->GetControlPoint(0), itk::ExceptionObject);
  ModelType::SizeType size;
  size.Fill(10);
  ModelType::DirectionType direction;
  direction.SetIdentity();
  EXPECT_THROW(model->SetGrid(size, Vec(1.0, 0.0, 1.0), Pt(0.0, 0.0, 0.0), direction), itk::ExceptionObject);
  model->SetGrid(size, Vec(1.0, 1.0, 1.0), Pt(0.0, 0.0, 0.0), direction);
  ModelType::IndexType center = { { 5, 5, 5 } };
  EXPECT_THROW(model->InitializeTemplate(center, Vec(6.0, 2.0, 2.0)), itk::ExceptionObject);
  EXPECT_THROW(model->InitializeTemplate(center, Vec(0.5, 2.0, 2.0)), itk::ExceptionObject);
  auto filter = FilterType::New();
  filter->SetInput(model);
  EXPECT_THROW(filter->Update(), itk::ExceptionObject);
}

namespace
{
/** One random operation on the model; returns whether it was accepted. */
bool
RandomOperation(ModelType & model, std::mt19937 & random)
{
  std::uniform_int_distribution<int> kind(0, 9);
  const int                          k = kind(random);
  if (k < 7)
  {
    const unsigned int p = std::uniform_int_distribution<unsigned int>(0, model.GetNumberOfControlPoints() - 1)(random);
    const auto         range = model.GetControlPointRange(p);
    const double       x = model.GetControlPointIndex(p)[model.GetControlPointLineAxis(p)];
    // Mostly moves within the allowed range, sometimes beyond it.
    const double lo = std::min(x - 6.0, range[0] - 1.0);
    const double hi = std::max(x + 6.0, range[1] + 1.0);
    const double target = std::uniform_real_distribution<double>(std::max(lo, x - 8.0), std::min(hi, x + 8.0))(random);
    return model.MoveControlPoint(p, target);
  }
  const unsigned int axis = std::uniform_int_distribution<unsigned int>(0, 2)(random);
  if (k < 9)
  {
    const int position = std::uniform_int_distribution<int>(4, 35)(random);
    return model.AddContour(axis, position);
  }
  const unsigned int c = std::uniform_int_distribution<unsigned int>(0, model.GetNumberOfContours() - 1)(random);
  return model.RemoveContour(c);
}
} // namespace

TEST(OrthogonalContourModel, EveryRuleHoldsAfterThousandsOfRandomOperations)
{
  for (const auto interpolation : { ModelType::InterpolationEnum::CatmullRom, ModelType::InterpolationEnum::Linear })
  {
    std::mt19937 random(20041 + static_cast<int>(interpolation));
    const auto   model = MakeTemplate(40, 12.0, interpolation);
    unsigned int accepted = 0;
    unsigned int meshes = 0;
    for (unsigned int i = 0; i < 2000; ++i)
    {
      const std::string before = model->ToJSON();
      const bool        ok = RandomOperation(*model, random);
      accepted += ok ? 1 : 0;
      ASSERT_EQ(model->CheckInvariants(), "") << "operation " << i << (ok ? " (accepted)" : " (refused)");
      if (!ok)
      {
        ASSERT_EQ(model->ToJSON(), before) << "a refused operation changed the model: " << model->GetRefusalReason();
        ASSERT_NE(model->GetRefusalReason(), "");
      }
      if (ok && i % 25 == 0)
      {
        ExpectValidMesh(model, "after operation " + std::to_string(i));
        ++meshes;
      }
      // Keep the model from growing without bound.
      while (model->GetNumberOfContours() > 24)
      {
        model->RemoveContour(std::uniform_int_distribution<unsigned int>(0, model->GetNumberOfContours() - 1)(random));
      }
    }
    EXPECT_GT(accepted, 500u);
    EXPECT_GT(meshes, 10u);
  }
}

TEST(OrthogonalContourModel, MeshFilterIsRepeatableAndReadyForRefinement)
{
  const auto model = MakeTemplate(40, 12.0);
  ASSERT_TRUE(model->AddContour(2, 26));
  ASSERT_TRUE(model->AddContour(0, 14));
  auto filter = FilterType::New();
  filter->SetInput(model);
  filter->SetTargetEdgeLength(1.0);
  filter->Update();
  const MeshType * mesh = filter->GetOutput();
  EXPECT_GT(mesh->GetNumberOfCells(), 1000u);
  // The first points are the control points (QuadEdgeMesh<double, 3> stores float
  // coordinates).
  for (unsigned int p = 0; p < model->GetNumberOfControlPoints(); ++p)
  {
    const auto point = mesh->GetPoint(p);
    const auto expected = model->GetControlPoint(p);
    for (unsigned int i = 0; i < 3; ++i)
    {
      EXPECT_NEAR(point[i], expected[i], 1e-5) << "control point " << p;
    }
  }
  const auto report = MeshReport(model, 1.0);
  EXPECT_TRUE(report.IsValidClosedSurface());
  EXPECT_GT(report.qArea.mean, 0.6);
  EXPECT_NEAR(report.enclosedVolume, model->GetVolume(), 0.03 * model->GetVolume());
}

namespace
{
/** The rules of thesis chapter 5, checked from the public interface: every contour in
 * its plane and closed (its scan conversion a 4-connected cycle through its control
 * points), every control point where two contours of different axes cross (on both
 * planes, with four distinct neighbours), the curve through its control points. */
void
ExpectChapterFiveInvariants(const ModelType & model)
{
  std::vector<unsigned int> membership(model.GetNumberOfControlPoints(), 0);
  for (unsigned int c = 0; c < model.GetNumberOfContours(); ++c)
  {
    const unsigned int axis = model.GetContourAxis(c);
    const auto         position = static_cast<double>(model.GetContourPosition(c));
    const auto         points = model.GetContourControlPoints(c);
    ASSERT_GE(points.size(), 4u) << "contour " << c;
    const auto samples = model.SampleContour(c, 4);
    ASSERT_EQ(samples.size(), 4 * points.size());
    for (std::size_t k = 0; k < points.size(); ++k)
    {
      ++membership[points[k]];
      EXPECT_EQ(model.GetControlPointIndex(points[k])[axis], position) << "control point off its contour's plane";
      for (unsigned int i = 0; i < 3; ++i)
      {
        EXPECT_NEAR(samples[4 * k][i], model.GetControlPointIndex(points[k])[i], 1e-9)
          << "the curve misses a control point";
      }
    }
    for (const auto & x : samples)
    {
      EXPECT_EQ(x[axis], position) << "contour " << c << " leaves its plane";
    }
    const auto voxels = model.GetScanConversion(c);
    for (std::size_t i = 0; i < voxels.size(); ++i)
    {
      EXPECT_TRUE(FourNeighbours(voxels[i], voxels[(i + 1) % voxels.size()])) << "contour " << c << " not closed";
    }
  }
  for (unsigned int p = 0; p < model.GetNumberOfControlPoints(); ++p)
  {
    EXPECT_EQ(membership[p], 2u) << "control point " << p << " is not on exactly two contours";
    const auto contours = model.GetControlPointContours(p);
    const auto x = model.GetControlPointIndex(p);
    EXPECT_NE(model.GetContourAxis(contours[0]), model.GetContourAxis(contours[1]));
    for (const auto c : contours)
    {
      EXPECT_EQ(x[model.GetContourAxis(c)], static_cast<double>(model.GetContourPosition(c)))
        << "control point " << p << " is not at the intersection of its contours";
    }
    const auto n = model.GetControlPointNeighbours(p);
    EXPECT_EQ(std::set<unsigned int>(n.begin(), n.end()).size(), 4u) << "control point " << p;
  }
}

/** A model fitted to `surface` by a user who knows it: the template, then contours in
 * the planes `planes` (axis, position), every control point put on the surface after
 * each step. */
ModelType::Pointer
FitModel(const itk::ImplicitSurfaceFunction &              surface,
         double                                            radius,
         const std::vector<std::pair<unsigned int, int>> & planes)
{
  const auto model = MakeTemplate(48, radius);
  MeshExtractionContourUser::SnapToSurface(*model, surface, 0.0);
  for (const auto & plane : planes)
  {
    EXPECT_TRUE(model->AddContour(plane.first, plane.second)) << model->GetRefusalReason();
    MeshExtractionContourUser::SnapToSurface(*model, surface, 0.0);
  }
  return model;
}

std::vector<std::pair<unsigned int, int>>
PlanesAround(int centre, int offset)
{
  std::vector<std::pair<unsigned int, int>> planes;
  for (unsigned int axis = 0; axis < 3; ++axis)
  {
    planes.push_back({ axis, centre - offset });
    planes.push_back({ axis, centre + offset });
  }
  return planes;
}

void
ExpectCloseValidMesh(const ModelType *                    model,
                     const itk::ImplicitSurfaceFunction * surface,
                     double                               meanTolerance,
                     double                               maximumTolerance)
{
  ExpectValidMesh(model, "fitted model");
  const auto distance = MeshExtractionContourUser::MeshDistance(model, surface);
  std::cout << "mesh to surface: vertices mean " << distance.vertices.mean << " max " << distance.vertices.maximum
            << ", Hausdorff " << distance.hausdorff << " (mm, 1 mm voxels, " << model->GetNumberOfContours()
            << " contours)" << std::endl;
  EXPECT_LT(distance.vertices.mean, meanTolerance);
  EXPECT_LT(distance.hausdorff, maximumTolerance);
}

/** The description of the exception `f` throws, or "" if it throws none. */
template <typename TFunction>
std::string
ThrownDescription(TFunction && f)
{
  try
  {
    f();
  }
  catch (const itk::ExceptionObject & e)
  {
    return e.GetDescription();
  }
  return std::string();
}

/** The model's JSON with the three coordinates of its first control point replaced. */
std::string
WithFirstPoint(const std::string & json, const std::string & coordinates)
{
  const std::size_t begin = json.find('[', json.find("\"control_points\": [") + 19) + 1;
  const std::size_t end = json.find(']', begin);
  return json.substr(0, begin) + coordinates + json.substr(end);
}
} // namespace

TEST(OrthogonalContourModel, FittedContoursKeepTheChapterFiveInvariants)
{
  auto sphere = itk::SphereImplicitSurface::New();
  sphere->SetCenter(Pt(24.0, 24.0, 24.0));
  sphere->SetRadius(14.0);
  const auto model = FitModel(*sphere, 10.0, PlanesAround(24, 7));
  EXPECT_EQ(model->GetNumberOfContours(), 9u);
  EXPECT_EQ(model->CheckInvariants(), "");
  ExpectChapterFiveInvariants(*model);
  // And after random edits.
  std::mt19937 random(5);
  for (unsigned int i = 0; i < 200; ++i)
  {
    const unsigned int p =
      std::uniform_int_distribution<unsigned int>(0, model->GetNumberOfControlPoints() - 1)(random);
    const auto range = model->GetControlPointRange(p);
    model->MoveControlPoint(p, std::uniform_real_distribution<double>(range[0], range[1])(random));
  }
  ExpectChapterFiveInvariants(*model);
}

TEST(OrthogonalContourModel, MeshOfContoursOnASphereIsCloseToIt)
{
  // Sphere of radius 14 mm in 1 mm voxels; the contours' points on it exactly.
  auto sphere = itk::SphereImplicitSurface::New();
  sphere->SetCenter(Pt(24.0, 24.0, 24.0));
  sphere->SetRadius(14.0);
  const auto model = FitModel(*sphere, 10.0, PlanesAround(24, 7));
  const auto contourError = MeshExtractionContourUser::MeasureContourError(*model, *sphere);
  std::cout << "sphere: contour error mean " << contourError.mean << " max " << contourError.maximum << std::endl;
  EXPECT_LT(contourError.mean, 0.5);
  ExpectCloseValidMesh(model, sphere, 0.5, 1.5);
}

TEST(OrthogonalContourModel, MeshOfContoursOnAnEllipsoidIsCloseToIt)
{
  auto ellipsoid = itk::EllipsoidImplicitSurface::New();
  ellipsoid->SetCenter(Pt(24.0, 24.0, 24.0));
  ellipsoid->SetSemiAxes(Vec(17.0, 12.0, 9.0));
  const auto model = FitModel(*ellipsoid, 8.0, { { 0, 15 }, { 0, 33 }, { 1, 18 }, { 1, 30 }, { 2, 20 }, { 2, 28 } });
  const auto contourError = MeshExtractionContourUser::MeasureContourError(*model, *ellipsoid);
  std::cout << "ellipsoid: contour error mean " << contourError.mean << " max " << contourError.maximum << std::endl;
  EXPECT_LT(contourError.mean, 0.5);
  ExpectCloseValidMesh(model, ellipsoid, 0.5, 2.0);
}

TEST(OrthogonalContourModel, BadInputIsRefusedNamingTheProblem)
{
  const auto        model = MakeTemplate(33, 10.0);
  const std::string json = model->ToJSON();
  auto              other = ModelType::New();
  // A contour that does not close through its points: one point taken out of it.
  std::string       open = json;
  const std::size_t points = open.find("\"points\": [") + 11;
  open.erase(points, open.find(',', points) - points + 2);
  std::string problem = ThrownDescription([&] { other->FromJSON(open, "open.json"); });
  EXPECT_NE(problem.find("open.json"), std::string::npos) << problem;
  EXPECT_NE(problem.find("contour"), std::string::npos) << problem;
  std::cout << "open contour: " << problem << std::endl;
  // Contours that do not meet: a control point off the planes of its contours.
  problem = ThrownDescription([&] { other->FromJSON(WithFirstPoint(json, "16.5, 16.5, 16.5"), "apart.json"); });
  EXPECT_NE(problem.find("apart.json"), std::string::npos) << problem;
  EXPECT_NE(problem.find("not in the plane"), std::string::npos) << problem;
  std::cout << "contours apart: " << problem << std::endl;
  // NaN: a coordinate that is not a number (JSON writes NaN as null).
  problem = ThrownDescription([&] { other->FromJSON(WithFirstPoint(json, "null, 16, 16"), "nan.json"); });
  EXPECT_NE(problem.find("nan.json"), std::string::npos) << problem;
  std::cout << "NaN coordinate: " << problem << std::endl;
  EXPECT_EQ(other->GetNumberOfContours(), 0u) << "a refused file changed the model";
  // NaN moves and grids.
  const std::string before = model->ToJSON();
  EXPECT_FALSE(model->MoveControlPoint(0, std::numeric_limits<double>::quiet_NaN()));
  EXPECT_NE(model->GetRefusalReason(), "");
  EXPECT_EQ(model->ToJSON(), before);
  ModelType::SizeType size;
  size.Fill(10);
  ModelType::DirectionType direction;
  direction.SetIdentity();
  problem = ThrownDescription([&] {
    other->SetGrid(size, Vec(1.0, std::numeric_limits<double>::quiet_NaN(), 1.0), Pt(0.0, 0.0, 0.0), direction);
  });
  EXPECT_NE(problem.find("spacing"), std::string::npos) << problem;
  // The mesh filter refuses a model without contours, naming it.
  auto filter = FilterType::New();
  filter->SetInput(other);
  problem = ThrownDescription([&] { filter->Update(); });
  EXPECT_NE(problem.find("not valid"), std::string::npos) << problem;
}
