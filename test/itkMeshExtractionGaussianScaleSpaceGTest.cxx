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
// The Gaussian scale space of itkMeshExtractionGaussianScaleSpace.h (internal): the
// scales, the search along a line, the derivative kernels and the gradient images
// (thesis section 4.2.1).

#include "itkMeshExtractionGaussianScaleSpace.h"
#include "itkScaleSpaceEdgeDetectionMeshFilter.h"
#if __has_include("itkDiscreteGradientMagnitudeGaussianImageFunction.h")
#  include "itkDiscreteGradientMagnitudeGaussianImageFunction.h" // ITKReview: not a dependency
#  define MESHEXTRACTION_HAVE_ITK_REVIEW
#endif
#include "itkEuler3DTransform.h"
#include "itkImageRegionIteratorWithIndex.h"

#include "itkMeshExtractionScaleSpaceTestHelpers.h"

#include "itkGTest.h"

#include <chrono>
#include <cmath>
#include <iomanip>
#include <vector>

namespace
{
namespace ME = itk::MeshExtraction;
using ME::Vec3;
using ImageType = itk::Image<float, 3>;
using ScaleSpaceType = ME::detail::GaussianGradientMagnitudeScaleSpace<ImageType>;
} // namespace

TEST(ScaleSpaceEdgeDetection, ScalesAreLogarithmicFromMaximumToMinimum)
{
  const std::vector<double> scales = ME::detail::ScaleSpaceScales(3.0, 1.0, 4);
  ASSERT_EQ(scales.size(), 8u); // ceil(4 log2 3) = 7 steps
  EXPECT_DOUBLE_EQ(scales.front(), 3.0);
  EXPECT_DOUBLE_EQ(scales.back(), 1.0);
  for (std::size_t i = 1; i < scales.size(); ++i)
  {
    EXPECT_NEAR(scales[i - 1] / scales[i], std::pow(3.0, 1.0 / 7.0), 1e-12);
    EXPECT_LE(scales[i - 1] / scales[i], std::pow(2.0, 1.0 / 4.0) + 1e-12);
  }
  // Exactly n per octave when the ratio is a power of two: 2^(i/n).
  const std::vector<double> octaves = ME::detail::ScaleSpaceScales(4.0, 1.0, 2);
  ASSERT_EQ(octaves.size(), 5u);
  for (std::size_t i = 0; i < octaves.size(); ++i)
  {
    EXPECT_NEAR(octaves[i], std::pow(2.0, (4.0 - static_cast<double>(i)) / 2.0), 1e-12);
  }
  EXPECT_EQ(ME::detail::ScaleSpaceScales(0.5, 1.0, 4), std::vector<double>{ 0.5 });
  EXPECT_TRUE(ME::detail::ScaleSpaceScales(0.0, 1.0, 4).empty());
  EXPECT_TRUE(ME::detail::ScaleSpaceScales(3.0, 1.0, 0).empty());
}

TEST(ScaleSpaceEdgeDetection, SearchFindsTheMaximumWithinHalfAStep)
{
  const std::vector<double> scales = ME::detail::ScaleSpaceScales(4.0, 1.0, 4);
  for (const double edge : { -3.1, -1.37, 0.0, 0.22, 1.3, 2.71, 3.9 })
  {
    // The gradient magnitude of a step at `edge` blurred by the scale (plus 1 mm).
    auto profile = [&](std::size_t k, double t) {
      const double s2 = scales[k] * scales[k] + 1.0;
      return std::exp(-0.5 * (t - edge) * (t - edge) / s2) / std::sqrt(s2);
    };
    const double thesis = ME::detail::SearchEdgeAlongLine(scales, 4.0, profile, false);
    EXPECT_LE(std::abs(thesis - edge), 0.25 + 1e-12) << edge; // half a step of the finest scale
    const double refined = ME::detail::SearchEdgeAlongLine(scales, 4.0, profile, true);
    EXPECT_LE(std::abs(refined - edge), 0.02) << edge;
  }
  // An edge beyond the capture range: the windows stay inside it.
  auto far = [](std::size_t, double t) { return std::exp(-0.5 * (t - 7.0) * (t - 7.0)); };
  EXPECT_DOUBLE_EQ(ME::detail::SearchEdgeAlongLine(scales, 4.0, far, false), 4.0);
  EXPECT_LE(ME::detail::SearchEdgeAlongLine(scales, 4.0, far, true), 4.0);
  // A flat profile keeps the vertex where it is (ties prefer the window's centre).
  auto flat = [](std::size_t, double) { return 1.0; };
  EXPECT_EQ(ME::detail::SearchEdgeAlongLine(scales, 4.0, flat, true), 0.0);
  // One step: the window is translated back inside the capture range.
  std::vector<double> seen;
  const double        best = ME::detail::EdgeSearchStep(3.5, 1.0, 4.0, [&](double t) {
    seen.push_back(t);
    return t;
  });
  EXPECT_DOUBLE_EQ(best, 4.0);
  EXPECT_EQ(seen, (std::vector<double>{ 3.0, 2.5, 3.5, 2.0, 4.0 }));
  EXPECT_NEAR(ME::detail::ParabolicPeakOffset(0.0, 0.0, -2.0, 1.0), -0.5, 1e-12); // y = -(x + 0.5)^2 + 0.25
  EXPECT_NEAR(ME::detail::ParabolicPeakOffset(0.75, 1.0, 0.75, 1.0), 0.0, 1e-12);
  EXPECT_EQ(ME::detail::ParabolicPeakOffset(1.0, 0.0, 1.0, 1.0), 0.0); // not a maximum
}

TEST(ScaleSpaceEdgeDetection, GaussianDerivativeKernels)
{
  for (const double spacing : { 0.5, 1.0, 2.5 })
  {
    for (const double sigma : { 0.4, 1.0, 3.0 })
    {
      const std::vector<float> g = ME::detail::GaussianKernel(sigma, spacing, 0);
      const std::vector<float> d = ME::detail::GaussianKernel(sigma, spacing, 1);
      double                   sum = 0.0;
      double                   slope = 0.0;
      const int                r = static_cast<int>(d.size() / 2);
      for (const float v : g)
      {
        sum += v;
      }
      for (int i = 0; i < static_cast<int>(d.size()); ++i)
      {
        slope += d[static_cast<std::size_t>(i)] * (i - r) * spacing;
      }
      EXPECT_NEAR(sum, 1.0, 1e-5) << sigma << ' ' << spacing;
      EXPECT_NEAR(slope, 1.0, 1e-6) << sigma << ' ' << spacing; // per millimetre, positive
      EXPECT_GE(static_cast<double>(g.size() / 2) * spacing, 3.0 * sigma - spacing) << sigma << ' ' << spacing;
    }
  }
}

TEST(ScaleSpaceEdgeDetection, GradientOfARampInPhysicalSpace)
{
  // A linear ramp on anisotropic, rotated voxels: the Gaussian gradient of a ramp is
  // the ramp's physical gradient at every scale.
  auto                image = ImageType::New();
  ImageType::SizeType size;
  size[0] = 30;
  size[1] = 26;
  size[2] = 14;
  image->SetRegions(size);
  ImageType::SpacingType spacing;
  spacing[0] = 0.8;
  spacing[1] = 1.1;
  spacing[2] = 2.5;
  image->SetSpacing(spacing);
  auto rotation = itk::Euler3DTransform<double>::New();
  rotation->SetRotation(0.4, 0.2, -0.6);
  image->SetDirection(rotation->GetMatrix());
  ImageType::PointType origin;
  origin[0] = 4.0;
  origin[1] = -7.0;
  origin[2] = 1.5;
  image->SetOrigin(origin);
  image->Allocate();
  const Vec3                                   a = ME::MakeVec3(0.3, -0.5, 0.8);
  itk::ImageRegionIteratorWithIndex<ImageType> it(image, image->GetLargestPossibleRegion());
  for (; !it.IsAtEnd(); ++it)
  {
    ImageType::PointType p;
    image->TransformIndexToPhysicalPoint(it.GetIndex(), p);
    it.Set(static_cast<float>(a[0] * p[0] + a[1] * p[1] + a[2] * p[2]));
  }
  ScaleSpaceType       scaleSpace;
  ImageType::IndexType centreIndex;
  centreIndex[0] = 15;
  centreIndex[1] = 13;
  centreIndex[2] = 7;
  ImageType::PointType centre;
  image->TransformIndexToPhysicalPoint(centreIndex, centre);
  const Vec3 c = ME::MakeVec3(centre[0], centre[1], centre[2]);
  const Vec3 lower = ME::MakeVec3(15, 13, 7);
  EXPECT_TRUE(scaleSpace.Prepare(image, { 2.0, 1.0 }, lower, lower));
  EXPECT_FALSE(scaleSpace.Prepare(image, { 2.0, 1.0 }, lower, lower)); // kept
  const Vec3 index = scaleSpace.ToRegionIndex(c + ME::MakeVec3(0.3, 0.2, -0.4));
  ITK_EXPECT_VECTOR_NEAR(scaleSpace.GradientAt(index), a, 1e-3);
  for (std::size_t k = 0; k < 2; ++k)
  {
    EXPECT_NEAR(scaleSpace.GradientMagnitude(k, index), ME::Norm(a), 1e-3);
  }
  image->Modified();
  EXPECT_TRUE(scaleSpace.Prepare(image, { 2.0, 1.0 }, lower, lower)); // a changed image is recomputed
  EXPECT_TRUE(scaleSpace.Prepare(image, { 3.0, 1.0 }, lower, lower)); // and so are other scales
}

#ifdef MESHEXTRACTION_HAVE_ITK_REVIEW // where ITK has its Review module
namespace
{
using MeshType = itk::QuadEdgeMesh<double, 3>;
using FilterType = itk::ScaleSpaceEdgeDetectionMeshFilter<MeshType, ImageType>;
using MeshExtractionScaleSpaceTest::Chapter4SphereCenter;
using MeshExtractionScaleSpaceTest::Chapter4SphereImage;
using MeshExtractionScaleSpaceTest::InitialSphere;
using MeshExtractionScaleSpaceTest::ToMesh;
} // namespace

/** Which Gaussian machinery: ITK's DiscreteGradientMagnitudeGaussianImageFunction
 * evaluated at the search samples, one instance per scale built serially, versus the
 * separable gradient-magnitude images of the mesh's region used by the filter, on
 * the thesis' sphere test (642 vertices, 8 scales, vertices + centroids). Prints a
 * table; run with --gtest_also_run_disabled_tests. */
TEST(ScaleSpaceEdgeDetectionMeshFilter, DISABLED_BenchmarkGaussianMachinery)
{
  const ImageType::Pointer      image = Chapter4SphereImage();
  const ME::IndexedTriangleMesh initial = InitialSphere();
  const std::vector<double>     scales = ME::detail::ScaleSpaceScales(3.0, 1.0, 4);
  using Clock = std::chrono::steady_clock;

  // The filter (scale-space build + searches + inaccuracy).
  auto filter = FilterType::New();
  filter->SetInput(ToMesh(initial));
  filter->SetInputImage(image);
  filter->SetMaximumDeviation(3.0);
  const auto t0 = Clock::now();
  filter->Update();
  const double separable = std::chrono::duration<double>(Clock::now() - t0).count();

  // The image functions: the same searches from the vertices only, along the normal.
  using FunctionType = itk::DiscreteGradientMagnitudeGaussianImageFunction<ImageType, double>;
  std::vector<FunctionType::Pointer> functions;
  const auto                         t1 = Clock::now();
  for (const double s : scales)
  {
    auto f = FunctionType::New();
    f->SetInputImage(image);
    f->SetSigma(s);
    f->SetUseImageSpacing(true);
    f->SetMaximumKernelWidth(1000);
    f->SetMaximumError(1e-3);
    f->SetInterpolationMode(itk::GaussianDerivativeOperatorEnums::InterpolationMode::LinearInterpolation);
    f->Initialize();
    functions.push_back(f);
  }
  const double initialize = std::chrono::duration<double>(Clock::now() - t1).count();
  const Vec3   center = Chapter4SphereCenter();
  const auto   t2 = Clock::now();
  double       radius = 0.0;
  for (const auto & p : initial.points)
  {
    const Vec3   d = (p - center) * (1.0 / ME::Norm(p - center));
    const double t = ME::detail::SearchEdgeAlongLine(scales, 3.0, [&](std::size_t k, double offset) {
      ImageType::PointType q;
      for (unsigned int i = 0; i < 3; ++i)
      {
        q[i] = p[i] + offset * d[i];
      }
      return functions[k]->Evaluate(q);
    });
    radius += ME::Norm(p + d * t - center);
  }
  const double evaluate = std::chrono::duration<double>(Clock::now() - t2).count();
  std::cout << std::fixed << std::setprecision(3) << "Gaussian machinery on the chapter-4 sphere (642 vertices, "
            << scales.size() << " scales 3..1 mm):\n"
            << "  separable images of the region + searches from vertices and centroids: " << separable << " s\n"
            << "  DiscreteGradientMagnitudeGaussianImageFunction: Initialize " << initialize
            << " s, searches from the vertices only " << evaluate << " s (mean radius "
            << radius / static_cast<double>(initial.points.size()) << ")\n";
}
#endif
