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
// The SurfaceNets relaxation of itkMeshExtractionSurfaceNetsRelaxation.h (internal): a
// node's step along the trilinear field, the Gaussian-derivative gradients.

#include "itkMeshExtractionSurfaceNetsRelaxation.h"
#include "itkMeshExtractionSurfaceNets.h"
#include "itkImageRegionIteratorWithIndex.h"
#include "itkSurfaceNetsImageToMeshFilterEnums.h"
#include "itkMeshExtractionTestHelpers.h"

#include "gtest/gtest.h"

#include <array>
#include <cstdint>

using namespace MeshExtractionTest;
namespace ME = itk::MeshExtraction;

namespace
{
using FloatImage = itk::Image<float, 3>;
} // namespace

TEST(SurfaceNets, ToPhysicalRoundsEveryCoordinateToFloatForAnyNumberOfPoints)
{
  // Every coordinate, for one point as for many: g++ 12 once rounded only the last
  // coordinate of a point when it was given few points.
  namespace ME = itk::MeshExtraction;
  itk::Matrix<double, 3, 3> M;
  M.SetIdentity();
  M[0][0] = 0.857412;
  M[1][1] = 1.0471;
  M[2][2] = 1.3085;
  M[0][1] = 0.01;
  ME::Vec3 origin;
  origin[0] = 0.1;
  origin[1] = -0.2;
  origin[2] = 0.3;
  for (std::size_t n : { 1u, 2u, 3u, 4u, 5u, 17u })
  {
    std::vector<ME::Vec3> index(n);
    for (std::size_t i = 0; i < n; ++i)
    {
      index[i][0] = 2.99 + 0.1234567 * static_cast<double>(i);
      index[i][1] = 3.7520303932506032 - 0.3 * static_cast<double>(i);
      index[i][2] = -0.31102377518801833 + 0.7 * static_cast<double>(i);
    }
    std::vector<ME::Vec3> exact(n);
    std::vector<ME::Vec3> rounded(n);
    ME::detail::ToPhysical(index.data(), n, origin, M, false, exact.data());
    ME::detail::ToPhysical(index.data(), n, origin, M, true, rounded.data());
    for (std::size_t i = 0; i < n; ++i)
    {
      for (unsigned int r = 0; r < 3; ++r)
      {
        EXPECT_EQ(rounded[i][r], static_cast<double>(static_cast<float>(exact[i][r])))
          << n << " points, point " << i << " coordinate " << r;
      }
    }
  }
}

TEST(SurfaceNetsRelaxation, ANodeOutsideItsCellStepsAlongTheTrilinearFieldOfTheCellItIsIn)
{
  // I = x^2. One node of the cell x in [1, 2], allowed to move in x over [1, 3] (as
  // the high-quality mode lets nodes leave their cells), at x = 2.3: the trilinear
  // field of the cell [2, 3] it is in (4 + 5 (x - 2)) reaches the iso-value 6.25 at
  // x = 2.45, where one gradient step lands it; the own cell's field extrapolated, or
  // the image's finite-difference slope over +-0.5 voxel (which would land at 2.463),
  // would miss it. The same with a cache kept from an earlier call, which then
  // describes the cell the node is in.
  auto image = MakeImage<FloatImage>(8, 4, 4);
  for (itk::ImageRegionIteratorWithIndex<FloatImage> it(image, image->GetBufferedRegion()); !it.IsAtEnd(); ++it)
  {
    const double x = it.GetIndex()[0];
    it.Set(static_cast<float>(x * x));
  }
  ME::SurfaceNet net;
  net.size = { { 8, 4, 4 } };
  ME::SurfaceCell cell{};
  cell.x = 1;
  cell.y = 1;
  cell.z = 1;
  net.cells.push_back(cell);
  net.nodeCell.push_back(0);
  net.positions.push_back(ME::MakeVec3(2.3, 1.5, 1.5));
  net.boxLower.push_back(ME::MakeVec3(1.0, 1.0, 1.0));
  net.boxUpper.push_back(ME::MakeVec3(3.0, 2.0, 2.0));
  net.neighborStart.assign(2, 0);
  const ME::detail::SurfaceNetsSampler<FloatImage> sampler(image.GetPointer(), 6.25, -1.0);
  ME::detail::SurfaceNetsRelaxationParameters      parameters;
  parameters.kind = itk::SurfaceNetsImageToMeshFilterEnums::Relaxation::Gradient;
  parameters.maximumNumberOfIterations = 1;
  parameters.centralDifferences = true;
  parameters.isoValue = 6.25;
  parameters.indexToPhysical.SetIdentity();
  parameters.numberOfWorkUnits = 1;
  auto gradient = [&sampler](const ME::Vec3 & q, std::uint32_t) { return sampler.Gradient(q); };
  for (const bool keptCache : { false, true })
  {
    SCOPED_TRACE(keptCache);
    ME::detail::SurfaceNetsCellCache cache;
    if (keptCache)
    {
      // A cache made by an earlier call, with the node inside its own cell.
      net.positions[0] = ME::MakeVec3(1.5, 1.5, 1.5);
      ME::detail::RelaxSurfaceNet(net, &sampler, gradient, parameters, nullptr, &cache);
      ASSERT_EQ(cache.entries.size(), 1u);
      EXPECT_EQ(cache.entries[0].corner[0], 1.0);
      net.positions[0] = ME::MakeVec3(2.3, 1.5, 1.5);
    }
    ME::detail::RelaxSurfaceNet(net, &sampler, gradient, parameters, nullptr, &cache);
    EXPECT_NEAR(net.positions[0][0], 2.45, 1e-5);
    EXPECT_EQ(net.positions[0][1], 1.5);
    EXPECT_EQ(net.positions[0][2], 1.5);
    ASSERT_EQ(cache.entries.size(), 1u);
    EXPECT_EQ(cache.entries[0].corner[0], 2.0);
    net.positions[0] = ME::MakeVec3(2.3, 1.5, 1.5);
  }
}

TEST(SurfaceNetsImageToMeshFilter, GaussianDerivativeGradientsAreExactOnQuadratics)
{
  // I = x^2 / 2 + 2 y - z^2 / 4 (x, y, z voxel indices), on anisotropic voxels: the
  // Gaussian derivative of a quadratic is its derivative, so away from the border the
  // gradient per voxel index is (x, 2, -z / 2), at cell corners and, trilinearly, inside.
  auto         image = MakeImage<FloatImage>(36, 40, 30);
  const double spacing[3] = { 0.5, 1.0, 2.0 };
  image->SetSpacing(spacing);
  for (itk::ImageRegionIteratorWithIndex<FloatImage> it(image, image->GetBufferedRegion()); !it.IsAtEnd(); ++it)
  {
    const auto & i = it.GetIndex();
    it.Set(static_cast<float>(0.5 * i[0] * i[0] + 2.0 * i[1] - 0.25 * i[2] * i[2]));
  }
  ME::SurfaceNet net;
  for (const auto & c : { std::array<int, 3>{ 15, 17, 12 }, std::array<int, 3>{ 20, 22, 16 } })
  {
    ME::SurfaceCell cell{};
    cell.x = c[0];
    cell.y = c[1];
    cell.z = c[2];
    net.cells.push_back(cell);
  }
  const ME::detail::SurfaceNetsGaussianGradient<FloatImage> gaussian(image, net, 1.5);
  for (std::uint32_t k = 0; k < net.cells.size(); ++k)
  {
    const auto & c = net.cells[k];
    for (const double t : { 0.0, 0.5, 1.0 })
    {
      const ME::Vec3 p = ME::MakeVec3(c.x + t, c.y + t, c.z + t);
      const ME::Vec3 g = gaussian.Gradient(p, k);
      EXPECT_NEAR(g[0], p[0], 1e-4 * p[0]) << k << ' ' << t;
      EXPECT_NEAR(g[1], 2.0, 1e-4);
      EXPECT_NEAR(g[2], -0.5 * p[2], 1e-4 * p[2]);
    }
  }
}
