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
#include "itkImplicitSurfaceImageSource.h"
#include "itkBoxImplicitSurface.h"
#include "itkImplicitSurfaceTestHelpers.h"
#include "itkMeshExtractionPhantoms.h"
#include "itkPlaneImplicitSurface.h"
#include "itkSphereImplicitSurface.h"
#include "itkTorusImplicitSurface.h"
#include "itkImage.h"
#include "itkImageRegionConstIteratorWithIndex.h"
#include "itkMultiThreaderBase.h"
#include "itkGTest.h"

#include <cmath>
#include <limits>
#include <sstream>
#include <string>

namespace
{
using FloatImage = itk::Image<float, 3>;
using DoubleImage = itk::Image<double, 3>;
using PointType = itk::ImplicitSurfaceFunction::InputType;
using VectorType = itk::ImplicitSurfaceFunction::VectorType;
using PhantomImage = itk::MeshExtractionEnums::PhantomImage;
using ImplicitSurfaceTest::TiltedDirection;

PointType
P(double x, double y, double z)
{
  PointType p;
  p[0] = x;
  p[1] = y;
  p[2] = z;
  return p;
}

VectorType
V(double x, double y, double z)
{
  VectorType v;
  v[0] = x;
  v[1] = y;
  v[2] = z;
  return v;
}

itk::SphereImplicitSurface::Pointer
MakeSphere(const PointType & center, double radius)
{
  auto sphere = itk::SphereImplicitSurface::New();
  sphere->SetCenter(center);
  sphere->SetRadius(radius);
  return sphere;
}


template <typename TImage>
typename itk::ImplicitSurfaceImageSource<TImage>::Pointer
MakeSource(const itk::ImplicitSurfaceFunction * surface, unsigned int size = 24)
{
  auto source = itk::ImplicitSurfaceImageSource<TImage>::New();
  source->SetSurface(surface);
  typename TImage::SizeType s;
  s.Fill(size);
  source->SetSize(s);
  return source;
}

/** Every voxel of `image` compared with `expected(distance at its physical point)`,
 * exactly or within `tolerance`. */
template <typename TImage, typename TExpected>
void
ExpectVoxels(const TImage *                       image,
             const itk::ImplicitSurfaceFunction & surface,
             TExpected                            expected,
             double                               tolerance = 0.0)
{
  itk::ImageRegionConstIteratorWithIndex<TImage> it(image, image->GetLargestPossibleRegion());
  unsigned int                                   failures = 0;
  for (; !it.IsAtEnd() && failures < 10; ++it)
  {
    PointType p;
    image->TransformIndexToPhysicalPoint(it.GetIndex(), p);
    const auto want = expected(surface.Evaluate(p));
    const bool equal = tolerance > 0.0 ? std::abs(double(it.Get()) - double(want)) <= tolerance : it.Get() == want;
    if (!equal)
    {
      ++failures;
      ADD_FAILURE() << "voxel " << it.GetIndex() << " at " << p << ": " << +it.Get() << " != " << +want;
    }
  }
}

template <typename TImage>
bool
SameVoxels(const TImage * a, const TImage * b)
{
  itk::ImageRegionConstIteratorWithIndex<TImage> it(a, a->GetLargestPossibleRegion());
  for (; !it.IsAtEnd(); ++it)
  {
    if (!(it.Get() == b->GetPixel(it.GetIndex())))
    {
      return false;
    }
  }
  return true;
}
} // namespace

TEST(ImplicitSurfaceImageSource, DistanceMapVoxelIsTheSignedDistanceAtItsPhysicalPoint)
{
  const auto sphere = MakeSphere(P(11, 12, 10.5), 7.3);
  auto       source = MakeSource<FloatImage>(sphere);
  source->Update();
  const FloatImage * image = source->GetOutput();
  ExpectVoxels(image, *sphere, [](double d) { return static_cast<float>(d); });
  EXPECT_FLOAT_EQ(image->GetPixel({ { 11, 12, 10 } }), static_cast<float>(0.5 - 7.3));
  EXPECT_FLOAT_EQ(image->GetPixel({ { 0, 0, 0 } }), static_cast<float>(std::sqrt(121.0 + 144.0 + 110.25) - 7.3));
}

TEST(ImplicitSurfaceImageSource, DistanceScaleMultipliesTheDistance)
{
  const auto sphere = MakeSphere(P(10, 10, 10), 6);
  auto       source = MakeSource<DoubleImage>(sphere, 20);
  source->SetDistanceScale(-2.5);
  source->Update();
  ExpectVoxels(source->GetOutput(), *sphere, [](double d) { return -2.5 * d; });
}

TEST(ImplicitSurfaceImageSource, AnisotropicSpacingRotatedDirectionAndOriginAreHonoured)
{
  auto torus = itk::TorusImplicitSurface::New();
  torus->SetCenter(P(-3, 8, 15));
  torus->SetAxis(V(1, -2, 2));
  torus->SetRadii(6, 2);
  auto                  source = MakeSource<DoubleImage>(torus, 0);
  DoubleImage::SizeType size = { { 30, 20, 12 } };
  source->SetSize(size);
  DoubleImage::SpacingType spacing;
  spacing[0] = 0.6;
  spacing[1] = 0.9;
  spacing[2] = 2.0;
  source->SetSpacing(spacing);
  source->SetOrigin(P(-12, 0, 5));
  source->SetDirection(TiltedDirection());
  source->Update();
  const DoubleImage * image = source->GetOutput();
  EXPECT_EQ(image->GetSpacing(), spacing);
  EXPECT_EQ(image->GetDirection(), TiltedDirection());
  ExpectVoxels(image, *torus, [](double d) { return d; });
  // One voxel by hand: x = origin + D (spacing .* index).
  const DoubleImage::IndexType index = { { 17, 3, 9 } };
  const VectorType             scaled = V(17 * 0.6, 3 * 0.9, 9 * 2.0);
  const PointType              x = P(-12, 0, 5) + TiltedDirection() * scaled;
  EXPECT_NEAR(image->GetPixel(index), torus->Evaluate(x), 1e-12);
}

TEST(ImplicitSurfaceImageSource, BinaryMaskIsTheInsideTest)
{
  auto box = itk::BoxImplicitSurface::New();
  box->SetCenter(P(12, 11, 12));
  box->SetHalfSizes(V(6, 3.5, 8));
  using MaskImage = itk::Image<unsigned char, 3>;
  auto source = MakeSource<MaskImage>(box);
  source->SetImageMode(PhantomImage::BinaryMask);
  source->SetInsideValue(200);
  source->SetOutsideValue(7);
  source->Update();
  ExpectVoxels(source->GetOutput(), *box, [](double d) { return static_cast<unsigned char>(d <= 0.0 ? 200 : 7); });
  EXPECT_EQ(source->GetOutput()->GetPixel({ { 6, 11, 12 } }), 200); // on the face x = 6: inside
}

TEST(ImplicitSurfaceImageSource, BlurredStepIsHalfwayOnTheSurfaceAndMonotoneAcrossIt)
{
  // A plane through the voxel centres x = 10, normal +x: voxel (i, j, k) has d = i - 10.
  auto plane = itk::PlaneImplicitSurface::New();
  plane->SetPoint(P(10, 0, 0));
  plane->SetNormal(V(1, 0, 0));
  auto source = MakeSource<DoubleImage>(plane, 24);
  source->SetImageMode(PhantomImage::BlurredStep);
  source->SetInsideValue(100);
  source->SetOutsideValue(20);
  source->SetEdgeWidth(2.0);
  source->Update();
  const DoubleImage * image = source->GetOutput();
  EXPECT_DOUBLE_EQ(image->GetPixel({ { 10, 5, 5 } }), 60.0); // (inside + outside) / 2
  // One edge width out: 20 + 80 * Phi(-1).
  EXPECT_NEAR(image->GetPixel({ { 12, 5, 5 } }), 20.0 + 80.0 * 0.5 * std::erfc(1.0 / std::sqrt(2.0)), 1e-12);
  EXPECT_NEAR(image->GetPixel({ { 8, 5, 5 } }), 100.0 - 80.0 * 0.5 * std::erfc(1.0 / std::sqrt(2.0)), 1e-12);
  for (unsigned int i = 1; i < 24; ++i)
  {
    const double previous = image->GetPixel({ { i - 1, 3, 7 } });
    const double current = image->GetPixel({ { i, 3, 7 } });
    EXPECT_LE(current, previous) << i;
    if (i > 4 && i < 17)
    {
      EXPECT_LT(current, previous) << i; // strictly, where the blur has not saturated
    }
  }
  // Five edge widths away the step has reached its plateau to within 80 * Phi(-5) = 2.3e-5.
  EXPECT_NEAR(image->GetPixel({ { 0, 0, 0 } }), 100.0, 3e-5);
  EXPECT_NEAR(image->GetPixel({ { 23, 0, 0 } }), 20.0, 1e-6);
  ExpectVoxels(
    image, *plane, [](double d) { return 20.0 + 80.0 * 0.5 * std::erfc(d / (2.0 * std::sqrt(2.0))); }, 1e-12);
}

TEST(ImplicitSurfaceImageSource, IntegerPixelTypesAreRoundedAndClamped)
{
  const auto sphere = MakeSphere(P(12, 12, 12), 8.3);
  {
    using ShortImage = itk::Image<short, 3>;
    auto source = MakeSource<ShortImage>(sphere);
    source->SetDistanceScale(10.0);
    source->Update();
    ExpectVoxels(source->GetOutput(), *sphere, [](double d) { return static_cast<short>(std::round(10.0 * d)); });
  }
  {
    using UCharImage = itk::Image<unsigned char, 3>;
    auto source = MakeSource<UCharImage>(sphere);
    source->SetDistanceScale(25.0); // -207.5 .. 312: both ends clamp
    source->Update();
    ExpectVoxels(source->GetOutput(), *sphere, [](double d) {
      return static_cast<unsigned char>(std::min(255.0, std::max(0.0, std::round(25.0 * d))));
    });
    EXPECT_EQ(source->GetOutput()->GetPixel({ { 12, 12, 12 } }), 0);
    EXPECT_EQ(source->GetOutput()->GetPixel({ { 0, 0, 0 } }), 255);

    source->SetImageMode(PhantomImage::BlurredStep);
    source->SetInsideValue(100);
    source->SetOutsideValue(0);
    source->Update();
    ExpectVoxels(
      source->GetOutput(),
      *sphere,
      [](double d) { return static_cast<unsigned char>(std::round(100.0 * 0.5 * std::erfc(d / std::sqrt(2.0)))); },
      1.0); // rounding of values within an ulp of n + 1/2 may differ
  }
}

TEST(ImplicitSurfaceImageSource, NoiseIsIdenticalForAnyNumberOfThreadsAndWorkUnits)
{
  const auto sphere = MakeSphere(P(16, 15, 14), 9);
  const auto render = [&](unsigned int globalThreads, unsigned int workUnits) {
    const unsigned int saved = itk::MultiThreaderBase::GetGlobalDefaultNumberOfThreads();
    itk::MultiThreaderBase::SetGlobalDefaultNumberOfThreads(globalThreads);
    auto source = MakeSource<FloatImage>(sphere, 32);
    source->SetImageMode(PhantomImage::BlurredStep);
    source->SetInsideValue(100);
    source->SetNoiseStandardDeviation(2.0);
    source->SetNoiseSeed(1234);
    source->SetNumberOfWorkUnits(workUnits);
    source->Update();
    itk::MultiThreaderBase::SetGlobalDefaultNumberOfThreads(saved);
    FloatImage::Pointer image = source->GetOutput();
    image->DisconnectPipeline();
    return image;
  };
  const auto one = render(1, 1);
  EXPECT_TRUE(SameVoxels(one.GetPointer(), render(4, 4).GetPointer()));
  EXPECT_TRUE(SameVoxels(one.GetPointer(), render(1, 7).GetPointer()));
  EXPECT_TRUE(SameVoxels(one.GetPointer(), render(4, 1).GetPointer()));
}

TEST(ImplicitSurfaceImageSource, NoiseOfARequestedRegionEqualsTheSameVoxelsOfTheWholeImage)
{
  const auto sphere = MakeSphere(P(10, 10, 10), 5);
  auto       whole = MakeSource<FloatImage>(sphere, 20);
  whole->SetNoiseStandardDeviation(1.0);
  whole->SetNoiseSeed(99);
  whole->Update();
  auto part = MakeSource<FloatImage>(sphere, 20);
  part->SetNoiseStandardDeviation(1.0);
  part->SetNoiseSeed(99);
  FloatImage::RegionType region({ { 3, 5, 7 } }, { { 9, 4, 6 } });
  part->GetOutput()->SetRequestedRegion(region);
  part->GetOutput()->Update();
  ASSERT_EQ(part->GetOutput()->GetBufferedRegion(), region);
  itk::ImageRegionConstIteratorWithIndex<FloatImage> it(part->GetOutput(), region);
  for (; !it.IsAtEnd(); ++it)
  {
    ASSERT_EQ(it.Get(), whole->GetOutput()->GetPixel(it.GetIndex())) << it.GetIndex();
  }
}

TEST(ImplicitSurfaceImageSource, NoiseHasTheRequestedStandardDeviationAndZeroMean)
{
  // A mask with every voxel outside, so that the image is pure noise.
  const auto far = MakeSphere(P(1000, 1000, 1000), 1);
  for (const double sigma : { 0.5, 2.0 })
  {
    auto source = MakeSource<DoubleImage>(far, 64);
    source->SetImageMode(PhantomImage::BinaryMask);
    source->SetOutsideValue(10.0);
    source->SetNoiseStandardDeviation(sigma);
    source->SetNoiseSeed(7);
    source->Update();
    double                                              sum = 0.0, sumSquares = 0.0;
    itk::ImageRegionConstIteratorWithIndex<DoubleImage> it(source->GetOutput(),
                                                           source->GetOutput()->GetLargestPossibleRegion());
    double                                              n = 0.0;
    for (; !it.IsAtEnd(); ++it)
    {
      const double v = it.Get() - 10.0;
      sum += v;
      sumSquares += v * v;
      n += 1.0;
    }
    const double mean = sum / n;
    const double sd = std::sqrt(sumSquares / n - mean * mean);
    EXPECT_NEAR(sd, sigma, 0.03 * sigma);
    EXPECT_NEAR(mean, 0.0, 5.0 * sigma / std::sqrt(n));
  }
  // Different seeds give different noise; the deviate is a pure function.
  EXPECT_NE(itk::ImplicitSurfaceImageSource<FloatImage>::NormalDeviate(1, 5),
            itk::ImplicitSurfaceImageSource<FloatImage>::NormalDeviate(2, 5));
  EXPECT_EQ(itk::ImplicitSurfaceImageSource<FloatImage>::NormalDeviate(1, 5),
            itk::ImplicitSurfaceImageSource<FloatImage>::NormalDeviate(1, 5));
}

TEST(ImplicitSurfaceImageSource, ChangingTheSurfaceReexecutesTheSource)
{
  auto sphere = MakeSphere(P(8, 8, 8), 3);
  auto source = MakeSource<FloatImage>(sphere, 16);
  source->Update();
  EXPECT_FLOAT_EQ(source->GetOutput()->GetPixel({ { 8, 8, 8 } }), -3.0f);
  sphere->SetRadius(5);
  source->Update();
  EXPECT_FLOAT_EQ(source->GetOutput()->GetPixel({ { 8, 8, 8 } }), -5.0f);
}

TEST(ImplicitSurfaceImageSource, MissingSurfaceOrBadParametersThrow)
{
  const auto expectThrow = [](itk::ProcessObject * source, const std::string & word) {
    try
    {
      source->Update();
      ADD_FAILURE() << "expected an exception mentioning " << word;
    }
    catch (const itk::ExceptionObject & e)
    {
      EXPECT_NE(std::string(e.GetDescription()).find(word), std::string::npos) << e.GetDescription();
    }
  };
  {
    auto source = itk::ImplicitSurfaceImageSource<FloatImage>::New();
    expectThrow(source, "surface");
  }
  {
    auto source = MakeSource<FloatImage>(MakeSphere(P(5, 5, 5), 2), 10);
    source->SetImageMode(PhantomImage::BlurredStep);
    source->SetEdgeWidth(0.0);
    expectThrow(source, "EdgeWidth");
  }
  {
    auto source = MakeSource<FloatImage>(MakeSphere(P(5, 5, 5), 2), 10);
    source->SetNoiseStandardDeviation(-1.0);
    expectThrow(source, "NoiseStandardDeviation");
  }
  {
    auto torus = itk::TorusImplicitSurface::New();
    torus->SetMinorRadius(3.0); // not below the major radius 2
    auto source = MakeSource<FloatImage>(torus, 10);
    expectThrow(source, "MinorRadius");
  }
}

TEST(ImplicitSurfaceImageSource, PrintSelfShowsTheSettings)
{
  auto source = MakeSource<FloatImage>(MakeSphere(P(5, 5, 5), 2), 10);
  source->SetImageMode(PhantomImage::BlurredStep);
  std::ostringstream os;
  source->Print(os);
  EXPECT_NE(os.str().find("SphereImplicitSurface"), std::string::npos);
  EXPECT_NE(os.str().find("BlurredStep"), std::string::npos);
  EXPECT_NE(os.str().find("EdgeWidth: 1"), std::string::npos);
}
