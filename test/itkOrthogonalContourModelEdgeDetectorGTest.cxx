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
#include "itkOrthogonalContourModelEdgeDetector.h"
#include "itkEllipsoidImplicitSurface.h"
#include "itkImage.h"
#include "itkImplicitSurfaceImageSource.h"
#include "MeshExtractionContourUser.h"
#include "itkSphereDifferenceImplicitSurface.h"
#include "itkScaleSpaceEdgeMeshRefinementFilter.h"
#include "itkSphereImplicitSurface.h"
#include "itkTriangleMeshQualityCalculator.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>
#include <iostream>
#include <string>

namespace
{
using namespace MeshExtractionContourUser;
using ImageType = itk::Image<float, 3>;
using DetectorType = itk::OrthogonalContourModelEdgeDetector<ImageType>;

itk::Point<double, 3>
Centre()
{
  itk::Point<double, 3> p;
  p.Fill(24.0);
  return p;
}

/** A 48^3 image of 1 mm voxels: the surface as a step from 100 inside to 0 outside,
 * blurred by a Gaussian of 1 mm. */
ImageType::Pointer
Phantom(const itk::ImplicitSurfaceFunction * surface)
{
  auto source = itk::ImplicitSurfaceImageSource<ImageType>::New();
  source->SetSurface(surface);
  ImageType::SizeType size;
  size.Fill(48);
  source->SetSize(size);
  source->SetImageMode(itk::MeshExtractionEnums::PhantomImage::BlurredStep);
  source->SetInsideValue(100.0f);
  source->SetOutsideValue(0.0f);
  source->SetEdgeWidth(1.0);
  source->Update();
  return source->GetOutput();
}

ModelType::Pointer
Template(const ImageType * image, double radius)
{
  auto model = ModelType::New();
  model->SetGrid(image);
  ModelType::IndexType centre;
  centre.Fill(24);
  ModelType::RadiiType radii;
  radii.Fill(radius);
  model->InitializeTemplate(centre, radii);
  return model;
}

DetectorType::Pointer
Detector(const ImageType * image, ModelType * model, double capture)
{
  auto detector = DetectorType::New();
  detector->SetImage(image);
  detector->SetModel(model);
  detector->SetCaptureRange(capture);
  return detector;
}

void
Print(const std::string &                  what,
      const UserRun &                      run,
      const ModelType *                    model,
      const itk::ImplicitSurfaceFunction * surface)
{
  const auto distance = MeshDistance(model, surface);
  std::cout << what << ": " << model->GetNumberOfContours() << " contours (" << run.contoursAdded << " added), "
            << run.relocations << " relocations over " << run.voxelsTravelled << " voxels, " << run.edgeDetectionRuns
            << " EDEMS runs over " << run.voxelsTravelledByEdgeDetection << " voxels; contour error mean "
            << run.error.mean << " max " << run.error.maximum << " voxels; mesh to surface mean "
            << distance.vertices.mean << " max " << distance.vertices.maximum << " mm" << std::endl;
}
} // namespace

TEST(OrthogonalContourModelEdgeDetector, ControlPointsSnapToTheSphereEdge)
{
  auto sphere = itk::SphereImplicitSurface::New();
  sphere->SetCenter(Centre());
  sphere->SetRadius(13.0);
  const auto image = Phantom(sphere);
  const auto model = Template(image, 10.0);
  const auto detector = Detector(image, model, 5.0);
  // One point: its edge is 3 voxels out along its line.
  const double edge = detector->FindEdge(0);
  const auto   x = model->GetControlPointIndex(0);
  EXPECT_NEAR(std::abs(edge - 24.0), 13.0, 0.25) << "point at " << x;
  EXPECT_EQ(detector->MoveAllControlPoints(), 6u);
  EXPECT_EQ(detector->GetNumberOfRefusedMoves(), 0u);
  EXPECT_NEAR(detector->GetDistanceTravelled(), 18.0, 1.5);
  for (unsigned int p = 0; p < model->GetNumberOfControlPoints(); ++p)
  {
    EXPECT_LT(std::abs(sphere->Evaluate(model->GetControlPoint(p))), 0.25) << "control point " << p;
  }
  EXPECT_EQ(model->CheckInvariants(), "");
}

TEST(OrthogonalContourModelEdgeDetector, OnlyThePointsOfTheActiveViewMove)
{
  auto sphere = itk::SphereImplicitSurface::New();
  sphere->SetCenter(Centre());
  sphere->SetRadius(13.0);
  const auto image = Phantom(sphere);
  const auto model = Template(image, 10.0);
  const auto inPlane = model->GetControlPointsInPlane(2, 24);
  ASSERT_EQ(inPlane.size(), 4u);
  std::vector<ModelType::ContinuousIndexType> before;
  for (unsigned int p = 0; p < model->GetNumberOfControlPoints(); ++p)
  {
    before.push_back(model->GetControlPointIndex(p));
  }
  const auto detector = Detector(image, model, 5.0);
  EXPECT_EQ(detector->MoveControlPointsInPlane(2, 24), 4u);
  for (unsigned int p = 0; p < model->GetNumberOfControlPoints(); ++p)
  {
    const bool moved = model->GetControlPointIndex(p) != before[p];
    EXPECT_EQ(moved, std::find(inPlane.begin(), inPlane.end(), p) != inPlane.end()) << "control point " << p;
  }
}

TEST(OrthogonalContourModelEdgeDetector, BadInputThrows)
{
  auto sphere = itk::SphereImplicitSurface::New();
  sphere->SetCenter(Centre());
  sphere->SetRadius(13.0);
  const auto image = Phantom(sphere);
  const auto model = Template(image, 10.0);
  auto       detector = DetectorType::New();
  EXPECT_THROW(detector->MoveAllControlPoints(), itk::ExceptionObject);
  detector->SetImage(image);
  detector->SetModel(model);
  EXPECT_THROW(detector->MoveAllControlPoints(), itk::ExceptionObject) << "no capture range";
  detector->SetCaptureRange(std::numeric_limits<double>::quiet_NaN());
  EXPECT_THROW(detector->MoveAllControlPoints(), itk::ExceptionObject);
  detector->SetCaptureRange(4.0);
  // A model on another grid.
  auto                other = ModelType::New();
  ModelType::SizeType size;
  size.Fill(40);
  ModelType::SpacingType spacing;
  spacing.Fill(1.0);
  ModelType::DirectionType direction;
  direction.SetIdentity();
  other->SetGrid(size, spacing, Centre(), direction);
  ModelType::IndexType centre;
  centre.Fill(20);
  ModelType::RadiiType radii;
  radii.Fill(5.0);
  other->InitializeTemplate(centre, radii);
  detector->SetModel(other);
  try
  {
    detector->MoveAllControlPoints();
    ADD_FAILURE() << "no exception for a model on another grid";
  }
  catch (const itk::ExceptionObject & e)
  {
    EXPECT_NE(std::string(e.GetDescription()).find("grid"), std::string::npos) << e.GetDescription();
  }
}

TEST(OrthogonalContourModelEdgeDetector, SimulatedUserReachesTheEllipsoidWithFewerRelocationsWithEdges)
{
  // Issue 31's simulated user on an ellipsoid phantom (semi-axes 17, 12, 9 voxels), from
  // the template of radius 10 voxels, with and without EDEMS (thesis Table 5.1).
  auto ellipsoid = itk::EllipsoidImplicitSurface::New();
  ellipsoid->SetCenter(Centre());
  itk::Vector<double, 3> axes;
  axes[0] = 17.0;
  axes[1] = 12.0;
  axes[2] = 9.0;
  ellipsoid->SetSemiAxes(axes);
  const auto image = Phantom(ellipsoid);

  const auto manualModel = Template(image, 10.0);
  const auto manual = SimulateUser<DetectorType>(*manualModel, *ellipsoid, nullptr, 0.5, 12);
  Print("ellipsoid, manual", manual, manualModel, ellipsoid);

  const auto assistedModel = Template(image, 10.0);
  const auto detector = Detector(image, assistedModel, 4.0);
  const auto assisted = SimulateUser(*assistedModel, *ellipsoid, detector.GetPointer(), 0.5, 12);
  Print("ellipsoid, with EDEMS", assisted, assistedModel, ellipsoid);

  for (const auto * model : { manualModel.GetPointer(), assistedModel.GetPointer() })
  {
    EXPECT_EQ(model->CheckInvariants(), "");
    EXPECT_LE(model->GetNumberOfContours(), 12u);
  }
  EXPECT_LE(manual.error.mean, 0.5);
  EXPECT_LE(assisted.error.mean, 0.5);
  EXPECT_LT(assisted.relocations, manual.relocations);
}

TEST(OrthogonalContourModelEdgeDetector, SimulatedUserReachesTheIndentedSphereWithFewerRelocationsWithEdges)
{
  // The indented sphere of thesis Table 5.1: a sphere of radius 14 voxels with a dent
  // 4 voxels deep cut by a sphere of radius 8 on its top.
  auto indented = itk::SphereDifferenceImplicitSurface::New();
  indented->SetCenterA(Centre());
  indented->SetRadiusA(14.0);
  auto top = Centre();
  top[2] += 18.0;
  indented->SetCenterB(top);
  indented->SetRadiusB(8.0);
  const auto image = Phantom(indented);

  const auto manualModel = Template(image, 10.0);
  const auto manual = SimulateUser<DetectorType>(*manualModel, *indented, nullptr, 0.5, 12);
  Print("indented sphere, manual", manual, manualModel, indented);

  const auto assistedModel = Template(image, 10.0);
  const auto detector = Detector(image, assistedModel, 4.0);
  const auto assisted = SimulateUser(*assistedModel, *indented, detector.GetPointer(), 0.5, 12);
  Print("indented sphere, with EDEMS", assisted, assistedModel, indented);

  for (const auto * model : { manualModel.GetPointer(), assistedModel.GetPointer() })
  {
    EXPECT_EQ(model->CheckInvariants(), "");
    EXPECT_LE(model->GetNumberOfContours(), 12u);
  }
  EXPECT_LE(manual.error.mean, 0.5);
  EXPECT_LE(assisted.error.mean, 0.5);
  EXPECT_LT(assisted.relocations, manual.relocations);
}

TEST(OrthogonalContourModelEdgeDetector, ContourMeshRefinedByChapterFourFitsTheEllipsoid)
{
  // The model the simulated user makes with EDEMS, meshed and refined by the chapter-4
  // protocol on the phantom: the initial mesh chapter 5 is for.
  auto ellipsoid = itk::EllipsoidImplicitSurface::New();
  ellipsoid->SetCenter(Centre());
  itk::Vector<double, 3> axes;
  axes[0] = 17.0;
  axes[1] = 12.0;
  axes[2] = 9.0;
  ellipsoid->SetSemiAxes(axes);
  const auto image = Phantom(ellipsoid);
  const auto model = Template(image, 10.0);
  SimulateUser(*model, *ellipsoid, Detector(image, model, 4.0).GetPointer(), 0.5, 12);

  auto mesher = itk::OrthogonalContourModelToMeshFilter<MeshType>::New();
  mesher->SetInput(model);
  auto refinement = itk::ScaleSpaceEdgeMeshRefinementFilter<MeshType, ImageType>::New();
  refinement->SetInput(mesher->GetOutput());
  refinement->SetInputImage(image);
  refinement->SetMaximumDeviation(3.0);
  refinement->SetTargetQuality(0.9);
  refinement->Update();

  auto quality = itk::TriangleMeshQualityCalculator<MeshType>::New();
  quality->SetMesh(refinement->GetOutput());
  quality->Compute();
  const auto & report = quality->GetReport();
  auto         distance = itk::MeshSurfaceDistanceCalculator<MeshType>::New();
  distance->SetMesh(refinement->GetOutput());
  distance->SetReferenceSurface(ellipsoid);
  distance->Compute();
  const auto before = MeshDistance(model, ellipsoid);
  std::cout << "ellipsoid, EDEMS model refined by chapter 4: mesh to surface mean " << before.vertices.mean << " -> "
            << distance->GetReport().vertices.mean << " mm, max " << before.vertices.maximum << " -> "
            << distance->GetReport().vertices.maximum << " mm, mean q_area " << report.qArea.mean << ", "
            << refinement->GetNumberOfCycles() << " cycles" << std::endl;
  EXPECT_TRUE(report.IsValidClosedSurface());
  EXPECT_LT(distance->GetReport().vertices.mean, before.vertices.mean);
  // Issue 31 asks for a mean distance of at most 0.1 voxel and a mean q_area of at
  // least 0.9 after refinement; the test allows some slack around them.
  EXPECT_LT(distance->GetReport().vertices.mean, 0.15);
  EXPECT_GT(report.qArea.mean, 0.85);
}
