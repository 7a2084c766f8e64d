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
// The SurfaceNets cell classification of itkMeshExtractionSurfaceNetsClassification.h
// (internal): the voxel ranges and the surface cells.

#include "itkMeshExtractionSurfaceNetsClassification.h"
#include "itkMeshExtractionTestHelpers.h"

#include "gtest/gtest.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

using namespace MeshExtractionTest;
namespace ME = itk::MeshExtraction;

namespace
{
using FloatImage = itk::Image<float, 3>;
} // namespace

template <typename TPixel>
void
CheckVoxelRange(const std::vector<double> & isoValues, const std::vector<TPixel> & voxels)
{
  using Range = ME::detail::SurfaceNetsVoxelRange<TPixel>;
  for (double iso : isoValues)
  {
    const Range above = Range::FromIsoValue(iso, true);
    const Range below = Range::FromIsoValue(iso, false);
    const Range label = Range::FromLabel(iso);
    for (TPixel v : voxels)
    {
      const double d = static_cast<double>(v);
      ASSERT_EQ(above(v), d >= iso) << "v " << d << " >= iso " << iso;
      ASSERT_EQ(below(v), d <= iso) << "v " << d << " <= iso " << iso;
      ASSERT_EQ(label(v), d == iso) << "v " << d << " == label " << iso;
    }
  }
}

TEST(SurfaceNetsImageToMeshFilter, VoxelRangeAgreesExactlyWithTheDoubleComparison)
{
  // The classification compares voxels in their own type; the bounds must give
  // exactly the comparison with the double iso-value or label, at every edge.
  std::vector<double> isoValues = { 0.0,     -0.0,    0.1,    -0.1,   0.5,         1.0,    2.5,     255.0,
                                    255.5,   256.0,   -0.5,   -1.0,   -128.5,      127.5,  300.0,   300.5,
                                    -1024.,  1e-40,   -1e-40, 1e-300, 1e300,       -1e300, 32767.5, -32768.5,
                                    65535.0, 65535.5, 3.4e38, 1e39,   std::nan("") };
  std::mt19937        rng(7);
  {
    std::vector<float> voxels = { 0.0f,
                                  -0.0f,
                                  1.0f,
                                  -1.0f,
                                  255.0f,
                                  300.0f,
                                  1e-40f,
                                  -1e-40f,
                                  3.4e38f,
                                  -3.4e38f,
                                  std::numeric_limits<float>::infinity(),
                                  -std::numeric_limits<float>::infinity(),
                                  std::numeric_limits<float>::quiet_NaN() };
    for (double iso : isoValues)
    {
      const float f = static_cast<float>(iso);
      voxels.insert(voxels.end(),
                    { f,
                      std::nextafter(f, std::numeric_limits<float>::infinity()),
                      std::nextafter(f, -std::numeric_limits<float>::infinity()) });
    }
    std::uniform_real_distribution<float> u(-400.0f, 400.0f);
    for (int i = 0; i < 200; ++i)
    {
      voxels.push_back(u(rng));
    }
    CheckVoxelRange<float>(isoValues, voxels);
    std::vector<double> doubles(voxels.begin(), voxels.end());
    doubles.insert(doubles.end(), isoValues.begin(), isoValues.end());
    CheckVoxelRange<double>(isoValues, doubles);
  }
  std::vector<short> shorts = { -32768, -32767, -1025, -1024, -129, -128, -1,  0,    1,
                                2,      127,    255,   256,   299,  300,  301, 32767 };
  CheckVoxelRange<short>(isoValues, shorts);
  std::vector<unsigned char> bytes;
  for (int v = 0; v < 256; ++v)
  {
    bytes.push_back(static_cast<unsigned char>(v));
  }
  CheckVoxelRange<unsigned char>(isoValues, bytes);
  std::vector<unsigned short> words = { 0, 1, 2, 255, 256, 299, 300, 301, 32767, 32768, 65534, 65535 };
  CheckVoxelRange<unsigned short>(isoValues, words);
}

TEST(SurfaceNetsImageToMeshFilter, ClassificationFindsExactlyTheMixedCells)
{
  // Every cell (x, y, z in -1 .. N-1, voxels beyond the image outside) whose 8
  // corners disagree, with its configuration, in (z, y, x) order; and the
  // statistics, on random volumes of awkward sizes (rows shorter and longer than
  // the 16-voxel vector step, with NaN voxels in some), and on distance maps whose
  // inside is a ball, its outside or a shell (voxel rows of one run, two runs, full
  // or empty, where the classification skips the cells inside all four runs).
  std::mt19937                          rng(11);
  std::uniform_real_distribution<float> value(0.0f, 1.0f);
  const unsigned int                    sizes[][3] = { { 1, 1, 1 },  { 3, 2, 1 },  { 7, 5, 4 },  { 16, 3, 3 },
                                                       { 17, 4, 2 }, { 33, 3, 5 }, { 40, 1, 3 }, { 5, 9, 8 } };
  for (int trial = 0; trial < 64; ++trial)
  {
    SCOPED_TRACE(trial);
    const unsigned int solidSizes[][3] = { { 40, 9, 8 }, { 17, 12, 10 }, { 64, 5, 6 }, { 33, 16, 3 } };
    const bool         solid = trial % 4 == 1;
    const auto &       size = solid ? solidSizes[(trial / 4) % 4] : sizes[trial % 8];
    auto               image = MakeImage<FloatImage>(size[0], size[1], size[2]);
    const double       density = 0.1 + 0.8 * value(rng);
    const bool         withNaN = trial % 5 == 4;
    const auto         n = image->GetBufferedRegion().GetNumberOfPixels();
    float *            buffer = image->GetBufferPointer();
    // A solid trial: the distance to a random centre, over the longest side.
    const float centre[3] = { (1.4f * value(rng) - 0.2f) * size[0],
                              (1.4f * value(rng) - 0.2f) * size[1],
                              (1.4f * value(rng) - 0.2f) * size[2] };
    const float longest = static_cast<float>(std::max({ size[0], size[1], size[2] }));
    for (std::size_t i = 0; i < n; ++i)
    {
      buffer[i] = value(rng);
      if (solid)
      {
        const float d[3] = { static_cast<float>(i % size[0]) - centre[0],
                             static_cast<float>((i / size[0]) % size[1]) - centre[1],
                             static_cast<float>(i / (size[0] * size[1])) - centre[2] };
        buffer[i] = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) / longest;
      }
      if (withNaN && value(rng) < 0.05f)
      {
        buffer[i] = std::numeric_limits<float>::quiet_NaN();
      }
    }
    // Inside below or above an iso-value (one bound), or in a band (two bounds, as a label).
    const bool                               below = trial % 2 == 0;
    const bool                               band = trial % 3 == 2;
    ME::detail::SurfaceNetsVoxelRange<float> range =
      ME::detail::SurfaceNetsVoxelRange<float>::FromIsoValue(density, !below);
    if (band)
    {
      range = { static_cast<float>(density) - 0.25f, static_cast<float>(density) + 0.125f };
    }
    ME::SurfaceNet net;
    const auto     stats = ME::detail::ClassifySurfaceCells(image.GetPointer(), range, net, 1 + trial % 3);
    auto           insideValue = [&](float v) {
      if (band)
      {
        return v >= range.low && v <= range.high;
      }
      return below ? static_cast<double>(v) <= density : static_cast<double>(v) >= density;
    };
    auto inside = [&](std::int64_t x, std::int64_t y, std::int64_t z) {
      if (x < 0 || y < 0 || z < 0 || x >= size[0] || y >= size[1] || z >= size[2])
      {
        return false;
      }
      return insideValue(buffer[(z * size[1] + y) * size[0] + x]);
    };
    std::vector<ME::SurfaceCell> expected;
    for (std::int64_t z = -1; z < size[2]; ++z)
    {
      for (std::int64_t y = -1; y < size[1]; ++y)
      {
        for (std::int64_t x = -1; x < size[0]; ++x)
        {
          unsigned int configuration = 0;
          for (unsigned int k = 0; k < 8; ++k)
          {
            configuration |= inside(x + (k & 1), y + ((k >> 1) & 1), z + ((k >> 2) & 1)) ? (1u << k) : 0u;
          }
          if (configuration != 0 && configuration != 255)
          {
            expected.push_back({ static_cast<std::int32_t>(x),
                                 static_cast<std::int32_t>(y),
                                 static_cast<std::int32_t>(z),
                                 static_cast<std::uint8_t>(configuration) });
          }
        }
      }
    }
    ASSERT_EQ(net.cells.size(), expected.size());
    for (std::size_t i = 0; i < expected.size(); ++i)
    {
      ASSERT_EQ(net.cells[i].x, expected[i].x) << "cell " << i;
      ASSERT_EQ(net.cells[i].y, expected[i].y) << "cell " << i;
      ASSERT_EQ(net.cells[i].z, expected[i].z) << "cell " << i;
      ASSERT_EQ(int{ net.cells[i].configuration }, int{ expected[i].configuration }) << "cell " << i;
    }
    double       minimum = std::numeric_limits<double>::max();
    double       maximum = std::numeric_limits<double>::lowest();
    std::size_t  insideVoxels = 0;
    std::int64_t firstNaN = -1;
    for (std::size_t i = 0; i < n; ++i)
    {
      if (std::isnan(buffer[i]))
      {
        firstNaN = firstNaN < 0 ? static_cast<std::int64_t>(i) : firstNaN;
        continue;
      }
      minimum = std::min(minimum, static_cast<double>(buffer[i]));
      maximum = std::max(maximum, static_cast<double>(buffer[i]));
      insideVoxels += insideValue(buffer[i]) ? 1 : 0;
    }
    EXPECT_EQ(stats.minimum, minimum);
    EXPECT_EQ(stats.maximum, maximum);
    EXPECT_EQ(stats.insideVoxels, insideVoxels);
    ASSERT_EQ(stats.foundNaN, firstNaN >= 0);
    // Without the extremes: the same cells, count and NaN, extremes left unset.
    ME::SurfaceNet plain;
    const auto     lean = ME::detail::ClassifySurfaceCells(image.GetPointer(), range, plain, 1 + trial % 3, false);
    ASSERT_EQ(plain.cells.size(), net.cells.size());
    for (std::size_t i = 0; i < net.cells.size(); ++i)
    {
      ASSERT_TRUE(plain.cells[i].x == net.cells[i].x && plain.cells[i].y == net.cells[i].y &&
                  plain.cells[i].z == net.cells[i].z && plain.cells[i].configuration == net.cells[i].configuration)
        << "cell " << i;
    }
    EXPECT_EQ(lean.insideVoxels, insideVoxels);
    EXPECT_EQ(lean.foundNaN, stats.foundNaN);
    EXPECT_EQ(lean.minimum, ME::detail::SurfaceNetsClassificationStatistics{}.minimum);
    EXPECT_EQ(lean.maximum, ME::detail::SurfaceNetsClassificationStatistics{}.maximum);
    if (firstNaN >= 0)
    {
      const std::int64_t index = (stats.nanVoxel[2] * size[1] + stats.nanVoxel[1]) * size[0] + stats.nanVoxel[0];
      EXPECT_TRUE(std::isnan(buffer[index]));
    }
  }
}
