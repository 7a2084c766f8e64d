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
#include "itkBoxImplicitSurface.h"
#include "itkNarrowCleftImplicitSurface.h"
#include "itkPlaneImplicitSurface.h"
#include "itkSphereImplicitSurface.h"
#include "itkSphereUnionImplicitSurface.h"
#include "itkMeshExtractionPhantoms.h"
#include "itkImplicitSurfaceTestHelpers.h"
#include "itkImageRegionConstIteratorWithIndex.h"

#include <cmath>
#include <sstream>

using namespace ImplicitSurfaceTest;

namespace
{
using FloatImage = itk::Image<float, 3>;
using DoubleImage = itk::Image<double, 3>;
using PhantomImage = itk::MeshExtractionEnums::PhantomImage;
} // namespace

TEST(MeshExtractionPhantoms, NamesRoundTripAndUnknownNamesListTheValidOnes)
{
  using namespace itk::MeshExtraction;
  const std::vector<std::string> expected = { "plane",           "sphere",     "two-spheres",
                                              "chapter4-sphere", "ellipsoid",  "indented-sphere",
                                              "torus",           "thin-plate", "narrow-cleft" };
  const auto                     shapes = AllPhantomShapes();
  ASSERT_EQ(shapes.size(), expected.size());
  for (size_t i = 0; i < shapes.size(); ++i)
  {
    EXPECT_EQ(PhantomShapeName(shapes[i]), expected[i]);
    EXPECT_EQ(PhantomShapeFromName(expected[i]), shapes[i]);
    std::ostringstream os;
    os << shapes[i];
    EXPECT_EQ(os.str(), expected[i]);
  }
  try
  {
    PhantomShapeFromName("cube");
    ADD_FAILURE() << "no exception for an unknown name";
  }
  catch (const itk::ExceptionObject & e)
  {
    const std::string message = e.GetDescription();
    EXPECT_NE(message.find("cube"), std::string::npos);
    for (const auto & name : expected)
    {
      EXPECT_NE(message.find(name), std::string::npos) << name;
    }
  }
}

TEST(MeshExtractionPhantoms, DefaultGridsAndImageModesFollowTheThesis)
{
  using namespace itk::MeshExtraction;
  for (const auto shape : AllPhantomShapes())
  {
    const PhantomGrid grid = DefaultPhantomGrid(shape);
    const unsigned    n = shape == PhantomShape::Chapter4Sphere ? 100 : 64;
    for (unsigned int k = 0; k < 3; ++k)
    {
      EXPECT_EQ(grid.size[k], n) << shape;
      EXPECT_EQ(grid.spacing[k], 1.0) << shape;
    }
    const auto parameters = DefaultPhantomImageParameters(shape);
    EXPECT_EQ(DefaultPhantomImageMode(shape), parameters.mode);
    if (shape == PhantomShape::Chapter4Sphere)
    {
      EXPECT_EQ(parameters.mode, itk::MeshExtractionEnums::PhantomImage::BlurredStep);
      EXPECT_EQ(parameters.insideValue, 100.0);
      EXPECT_EQ(parameters.outsideValue, 0.0);
      EXPECT_EQ(parameters.edgeWidth, 1.0);
    }
    else
    {
      EXPECT_EQ(parameters.mode, itk::MeshExtractionEnums::PhantomImage::DistanceMap) << shape;
    }
  }
}

TEST(MeshExtractionPhantoms, ShapesAreCentredInsideTheGridAndSizedByItsSmallestExtent)
{
  using namespace itk::MeshExtraction;
  PhantomGrid grid;
  grid.size[0] = 80;
  grid.size[1] = 60;
  grid.size[2] = 50;
  grid.spacing[0] = 0.8;
  grid.spacing[1] = 1.0;
  grid.spacing[2] = 1.5;
  grid.origin = P(-10, 5, 20);
  grid.direction = Rotation(0.3, 0.2, -0.4);
  const PointType center = PhantomGridCenter(grid);
  const double    extent = PhantomGridSmallestExtent(grid);
  EXPECT_DOUBLE_EQ(extent, 60.0);
  for (const auto shape : AllPhantomShapes())
  {
    const auto surface = MakePhantomSurface(shape, grid);
    if (shape != PhantomShape::Plane)
    {
      // Closed shapes: the centre is inside (or, for the cleft, under the slot) and
      // the surface lies within the grid's field of view.
      PointType lower, upper;
      surface->GetBounds(lower, upper);
      for (unsigned int i = 0; i < 3; ++i)
      {
        EXPECT_NEAR(0.5 * (lower[i] + upper[i]), center[i], 0.2 * extent) << shape;
      }
      for (const PointType & p : RandomPoints(lower, upper, 0.0, 500, 101))
      {
        const PointType  q = surface->ClosestSurfacePoint(p);
        const VectorType local = MatrixType(grid.direction.GetTranspose()) * (q - grid.origin);
        for (unsigned int k = 0; k < 3; ++k)
        {
          EXPECT_GT(local[k] / grid.spacing[k], -0.5) << shape;
          EXPECT_LT(local[k] / grid.spacing[k], grid.size[k] - 0.5) << shape;
        }
      }
    }
    else
    {
      EXPECT_NEAR(std::abs(surface->Evaluate(center)), 0.5 / std::sqrt(14.0) * 0.8, 1e-12);
    }
  }
}

TEST(MeshExtractionPhantoms, DefaultShapesHaveTheDocumentedSizes)
{
  using namespace itk::MeshExtraction;
  const auto chapter4 =
    MakePhantomSurface(PhantomShape::Chapter4Sphere, DefaultPhantomGrid(PhantomShape::Chapter4Sphere));
  const auto sphere4 = dynamic_cast<const itk::SphereImplicitSurface *>(chapter4.GetPointer());
  ASSERT_NE(sphere4, nullptr);
  EXPECT_DOUBLE_EQ(sphere4->GetRadius(), 25.0);
  ITK_EXPECT_VECTOR_NEAR(sphere4->GetCenter(), P(49.5, 49.5, 49.5), 1e-12);

  const auto two = MakePhantomSurface(PhantomShape::TwoSpheres, DefaultPhantomGrid(PhantomShape::TwoSpheres));
  const auto union2 = dynamic_cast<const itk::SphereUnionImplicitSurface *>(two.GetPointer());
  ASSERT_NE(union2, nullptr);
  ASSERT_EQ(union2->GetNumberOfSpheres(), 2u);
  EXPECT_NEAR(
    union2->GetSphereCenter(0).EuclideanDistanceTo(union2->GetSphereCenter(1)), union2->GetSphereRadius(0), 1e-12);

  // The default plane is tilted to every grid axis.
  const auto plane = MakePhantomSurface(PhantomShape::Plane, DefaultPhantomGrid(PhantomShape::Plane));
  const auto plane3 = dynamic_cast<const itk::PlaneImplicitSurface *>(plane.GetPointer());
  ASSERT_NE(plane3, nullptr);
  for (unsigned int k = 0; k < 3; ++k)
  {
    EXPECT_GT(std::abs(plane3->GetNormal()[k]), 0.2);
    EXPECT_LT(std::abs(plane3->GetNormal()[k]), 0.9);
  }

  const auto cleft = MakePhantomSurface(PhantomShape::NarrowCleft, DefaultPhantomGrid(PhantomShape::NarrowCleft));
  const auto cleft3 = dynamic_cast<const itk::NarrowCleftImplicitSurface *>(cleft.GetPointer());
  ASSERT_NE(cleft3, nullptr);
  EXPECT_DOUBLE_EQ(cleft3->GetSlotWidth(), 1.5);

  const auto plate = MakePhantomSurface(PhantomShape::ThinPlate, DefaultPhantomGrid(PhantomShape::ThinPlate));
  const auto plate3 = dynamic_cast<const itk::BoxImplicitSurface *>(plate.GetPointer());
  ASSERT_NE(plate3, nullptr);
  EXPECT_DOUBLE_EQ(2.0 * plate3->GetHalfSizes()[2], 2.0); // 2 voxels thick
}

TEST(MeshExtractionPhantoms, InvalidGridThrows)
{
  using namespace itk::MeshExtraction;
  PhantomGrid grid;
  grid.spacing[1] = 0.0;
  ExpectThrowsMentioning([&] { MakePhantomSurface(PhantomShape::Sphere, grid); }, "spacing");
  grid = PhantomGrid();
  grid.direction(0, 1) = 0.5;
  ExpectThrowsMentioning([&] { MakePhantomSurface(PhantomShape::Sphere, grid); }, "direction");
  grid = PhantomGrid();
  grid.size[2] = 0;
  ExpectThrowsMentioning([&] { MakePhantomSurface(PhantomShape::Sphere, grid); }, "size");
}

TEST(MeshExtractionPhantoms, DefaultPhantomImagesHaveTheGridGeometryAndNoVoxelExactlyOnTheSurface)
{
  using namespace itk::MeshExtraction;
  for (const auto shape : AllPhantomShapes())
  {
    const PhantomGrid      grid = DefaultPhantomGrid(shape);
    PhantomImageParameters distance = DefaultPhantomImageParameters(shape);
    distance.mode = PhantomImage::DistanceMap;
    auto source = MakePhantomImageSource<DoubleImage>(shape, grid, distance);
    source->Update();
    const DoubleImage * image = source->GetOutput();
    EXPECT_EQ(image->GetLargestPossibleRegion().GetSize(), grid.size) << shape;
    EXPECT_EQ(image->GetSpacing(), grid.spacing) << shape;
    unsigned int                                        onSurface = 0, inside = 0;
    itk::ImageRegionConstIteratorWithIndex<DoubleImage> it(image, image->GetLargestPossibleRegion());
    for (; !it.IsAtEnd(); ++it)
    {
      onSurface += it.Get() == 0.0 ? 1 : 0;
      inside += it.Get() < 0.0 ? 1 : 0;
    }
    EXPECT_EQ(onSurface, 0u) << shape;
    EXPECT_GT(inside, 0u) << shape;
    EXPECT_LT(inside, image->GetLargestPossibleRegion().GetNumberOfPixels()) << shape;
  }
}

TEST(MeshExtractionPhantoms, Chapter4SphereDefaultImageIsABlurredStepFrom0To100)
{
  using namespace itk::MeshExtraction;
  using UCharImage = itk::Image<unsigned char, 3>;
  const auto shape = PhantomShape::Chapter4Sphere;
  auto       source = MakePhantomImageSource<UCharImage>(shape, DefaultPhantomGrid(shape));
  EXPECT_EQ(source->GetImageMode(), PhantomImage::BlurredStep);
  source->Update();
  const UCharImage * image = source->GetOutput();
  EXPECT_EQ(image->GetLargestPossibleRegion().GetSize()[0], 100u);
  EXPECT_EQ(image->GetPixel({ { 50, 50, 50 } }), 100);
  EXPECT_EQ(image->GetPixel({ { 0, 0, 0 } }), 0);
  // Voxel (74, 49, 49) is at x = 74 - 49.5 = 24.5, y = z = -0.5 from the centre:
  // d = sqrt(24.5^2 + 0.5) - 25.
  const double d = std::sqrt(24.5 * 24.5 + 0.5) - 25.0;
  EXPECT_EQ(image->GetPixel({ { 74, 49, 49 } }), std::round(100.0 * 0.5 * std::erfc(d / std::sqrt(2.0))));
}

TEST(MeshExtractionPhantoms, PhantomImageDoesNotDependOnTheGridDirection)
{
  using namespace itk::MeshExtraction;
  for (const auto shape : { PhantomShape::Plane, PhantomShape::Ellipsoid, PhantomShape::NarrowCleft })
  {
    PhantomGrid grid;
    grid.size.Fill(24);
    auto straight = MakePhantomImageSource<FloatImage>(shape, grid);
    straight->Update();
    grid.direction = TiltedDirection();
    auto tilted = MakePhantomImageSource<FloatImage>(shape, grid);
    tilted->Update();
    itk::ImageRegionConstIteratorWithIndex<FloatImage> it(straight->GetOutput(),
                                                          straight->GetOutput()->GetLargestPossibleRegion());
    double                                             worst = 0.0;
    for (; !it.IsAtEnd(); ++it)
    {
      worst = std::max(worst, std::abs(double(it.Get()) - tilted->GetOutput()->GetPixel(it.GetIndex())));
    }
    EXPECT_LT(worst, 1e-4) << shape;
  }
}
