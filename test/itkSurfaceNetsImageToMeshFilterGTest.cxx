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
#include "itkSurfaceNetsImageToMeshFilter.h"
#include "itkBinaryMask3DMeshSource.h"
#include "itkDefaultDynamicMeshTraits.h"
#include "itkImageRegionIteratorWithIndex.h"
#include "itkMeshExtractionCellBlock.h"
#include "itkMeshExtractionPhantoms.h"
#include "itkMeshExtractionQualityAnalysis.h"
#include "itkMeshExtractionSurfaceNetsClassification.h"
#include "itkMeshExtractionSurfaceNetsRelaxation.h"
#include "itkMeshExtractionTestHelpers.h"
#include "itkMeshSurfaceDistanceCalculator.h"
#include "itkTriangleMeshQualityCalculator.h"

#include "gtest/gtest.h"

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <fstream>
#include <numeric>
#include <random>
#include <sstream>
#include <stdexcept>

using namespace MeshExtractionTest;
namespace ME = itk::MeshExtraction;

namespace
{
using FloatImage = itk::Image<float, 3>;
using MaskImage = itk::Image<unsigned char, 3>;
using Enums = itk::SurfaceNetsImageToMeshFilterEnums;

template <typename TImage>
typename TImage::Pointer
MakeImage(unsigned int nx, unsigned int ny, unsigned int nz, typename TImage::PixelType value = 0)
{
  auto                      image = TImage::New();
  typename TImage::SizeType size = { { nx, ny, nz } };
  image->SetRegions(size);
  image->Allocate();
  image->FillBuffer(value);
  return image;
}

template <typename TMesh = QEMeshType>
ME::TriangleMeshQualityReport
Measure(const TMesh * mesh)
{
  auto calculator = itk::TriangleMeshQualityCalculator<TMesh>::New();
  calculator->SetMesh(mesh);
  calculator->Compute();
  return calculator->GetReport();
}

ME::MeshSurfaceDistanceReport
Distance(const QEMeshType * mesh, const itk::ImplicitSurfaceFunction * surface)
{
  auto calculator = itk::MeshSurfaceDistanceCalculator<QEMeshType>::New();
  calculator->SetMesh(mesh);
  calculator->SetReferenceSurface(surface);
  calculator->SetSamplingLevel(1);
  calculator->Compute();
  return calculator->GetReport();
}

std::string
Text(const ME::TriangleMeshQualityReport & r)
{
  std::ostringstream os;
  r.Print(os);
  return os.str();
}

/** Number of 6-connected components of the voxels equal to 1. */
std::size_t
CountComponents(const MaskImage * mask)
{
  const auto        size = mask->GetBufferedRegion().GetSize();
  const long        n[3] = { static_cast<long>(size[0]), static_cast<long>(size[1]), static_cast<long>(size[2]) };
  std::vector<int>  seen(n[0] * n[1] * n[2], 0);
  const auto *      buffer = mask->GetBufferPointer();
  std::size_t       components = 0;
  std::vector<long> stack;
  for (long start = 0; start < n[0] * n[1] * n[2]; ++start)
  {
    if (buffer[start] != 1 || seen[start])
    {
      continue;
    }
    ++components;
    stack.push_back(start);
    seen[start] = 1;
    while (!stack.empty())
    {
      const long v = stack.back();
      stack.pop_back();
      const long x = v % n[0];
      const long y = (v / n[0]) % n[1];
      const long z = v / (n[0] * n[1]);
      const long neighbours[6][3] = { { x - 1, y, z }, { x + 1, y, z }, { x, y - 1, z },
                                      { x, y + 1, z }, { x, y, z - 1 }, { x, y, z + 1 } };
      for (const auto & q : neighbours)
      {
        if (q[0] < 0 || q[1] < 0 || q[2] < 0 || q[0] >= n[0] || q[1] >= n[1] || q[2] >= n[2])
        {
          continue;
        }
        const long w = (q[2] * n[1] + q[1]) * n[0] + q[0];
        if (buffer[w] == 1 && !seen[w])
        {
          seen[w] = 1;
          stack.push_back(w);
        }
      }
    }
  }
  return components;
}

template <typename TImage, typename TMesh = QEMeshType>
typename TMesh::Pointer
Extract(const TImage * image, double iso, bool insideAbove, Enums::Relaxation relaxation = Enums::Relaxation::Automatic)
{
  auto filter = itk::SurfaceNetsImageToMeshFilter<TImage, TMesh>::New();
  filter->SetInput(image);
  filter->SetIsoValue(iso);
  filter->SetInsideIsAboveIsoValue(insideAbove);
  filter->SetRelaxation(relaxation);
  filter->Update();
  return filter->GetOutput();
}

QEMeshType::Pointer
ExtractLabels(const MaskImage * mask, Enums::Relaxation relaxation)
{
  auto filter = itk::SurfaceNetsImageToMeshFilter<MaskImage>::New();
  filter->SetInput(mask);
  filter->SetClassifyByLabel(true);
  filter->SetLabelValue(1);
  filter->SetRelaxation(relaxation);
  filter->Update();
  return filter->GetOutput();
}

/** A phantom's distance map (inside negative) and its exact surface. */
struct Phantom
{
  FloatImage::Pointer                   image;
  itk::ImplicitSurfaceFunction::Pointer surface;
  ME::PhantomGrid                       grid;
};

Phantom
MakePhantom(ME::PhantomShape shape, const ME::PhantomGrid & grid)
{
  Phantom p;
  p.grid = grid;
  auto source = ME::MakePhantomImageSource<FloatImage>(shape, grid);
  source->Update();
  p.image = source->GetOutput();
  p.surface = ME::MakePhantomSurface(shape, grid);
  return p;
}

Phantom
MakePhantom(ME::PhantomShape shape)
{
  return MakePhantom(shape, ME::DefaultPhantomGrid(shape));
}

/** SurfaceNets of the phantom's distance map (the inside below 0), the filter set up
 * further by `configure(filter)`. */
template <typename TConfigure>
QEMeshType::Pointer
ExtractPhantom(const Phantom & p, TConfigure && configure)
{
  auto filter = itk::SurfaceNetsImageToMeshFilter<FloatImage>::New();
  filter->SetInput(p.image);
  filter->SetInsideIsAboveIsoValue(false);
  configure(filter.GetPointer());
  filter->Update();
  return filter->GetOutput();
}

/** The phantom's mask (1 inside), on its grid. */
MaskImage::Pointer
PhantomMask(const Phantom & p)
{
  auto mask = MakeImage<MaskImage>(1, 1, 1);
  mask->SetRegions(p.image->GetBufferedRegion());
  mask->CopyInformation(p.image);
  mask->Allocate();
  for (std::size_t i = 0; i < p.image->GetBufferedRegion().GetNumberOfPixels(); ++i)
  {
    mask->GetBufferPointer()[i] = p.image->GetBufferPointer()[i] <= 0.0f ? 1 : 0;
  }
  return mask;
}

/** Marching cubes (ITK's BinaryMask3DMeshSource) on the phantom's mask. */
QEMeshType::Pointer
MarchingCubes(const Phantom & p)
{
  auto mc = itk::BinaryMask3DMeshSource<MaskImage, QEMeshType>::New();
  mc->SetInput(PhantomMask(p));
  mc->SetObjectValue(1);
  mc->Update();
  return mc->GetOutput();
}
} // namespace

TEST(SurfaceNetsImageToMeshFilter, EveryCellConfigurationGivesAValidClosedSurfacePerComponent)
{
  for (unsigned int configuration = 1; configuration < 256; ++configuration)
  {
    for (unsigned int border = 0; border < 2; ++border)
    {
      // The 2x2x2 block inside a margin of background, or filling the whole image.
      const unsigned int n = border ? 2 : 4;
      const unsigned int o = border ? 0 : 1;
      auto               mask = MakeImage<MaskImage>(n, n, n);
      auto               grey = MakeImage<FloatImage>(n, n, n);
      for (unsigned int k = 0; k < 8; ++k)
      {
        if ((configuration >> k) & 1u)
        {
          MaskImage::IndexType index = { { o + (k & 1), o + ((k >> 1) & 1), o + ((k >> 2) & 1) } };
          mask->SetPixel(index, 1);
          grey->SetPixel(index, 1.0f);
        }
      }
      const auto expectedChi = static_cast<std::int64_t>(2 * CountComponents(mask));
      for (auto relaxation : { Enums::Relaxation::None, Enums::Relaxation::Averaging })
      {
        const auto r = Measure(ExtractLabels(mask, relaxation).GetPointer());
        ASSERT_TRUE(r.IsValidClosedSurface()) << "configuration " << configuration << " border " << border;
        ASSERT_EQ(r.eulerCharacteristic, expectedChi) << "configuration " << configuration;
      }
      if (configuration == 255 && border)
      {
        // A constant image has no iso-surface (the label image above is fine).
        EXPECT_THROW(Extract(grey.GetPointer(), 0.5, true), itk::ExceptionObject);
        continue;
      }
      const auto r = Measure(Extract(grey.GetPointer(), 0.5, true, Enums::Relaxation::Combined).GetPointer());
      ASSERT_TRUE(r.IsValidClosedSurface())
        << "greyscale configuration " << configuration << " border " << border << '\n'
        << Text(r);
      ASSERT_EQ(r.eulerCharacteristic, expectedChi) << "greyscale configuration " << configuration;
    }
  }
}

TEST(SurfaceNetsImageToMeshFilter, RandomVolumesGiveValidClosedSurfaces)
{
  std::mt19937                           rng(2024);
  std::uniform_real_distribution<float>  value(0.0f, 1.0f);
  std::uniform_real_distribution<double> density(0.2, 0.8);
  for (int trial = 0; trial < 250; ++trial)
  {
    SCOPED_TRACE(trial);
    const unsigned int n = 5 + trial % 3;
    auto               grey = MakeImage<FloatImage>(n, n, n);
    auto               mask = MakeImage<MaskImage>(n, n, n);
    const double       d = density(rng);
    for (std::size_t i = 0; i < grey->GetBufferedRegion().GetNumberOfPixels(); ++i)
    {
      const float v = value(rng);
      grey->GetBufferPointer()[i] = v;
      mask->GetBufferPointer()[i] = v < d ? 1 : 0;
    }
    if (CountComponents(mask) == 0)
    {
      continue;
    }
    const auto sna = Measure(ExtractLabels(mask, Enums::Relaxation::Averaging).GetPointer());
    ASSERT_TRUE(sna.IsValidClosedSurface()) << "binary trial " << trial << '\n' << Text(sna);
    const auto snert = Measure(Extract(grey.GetPointer(), d, false).GetPointer());
    ASSERT_TRUE(snert.IsValidClosedSurface()) << "greyscale trial " << trial << '\n' << Text(snert);
    ASSERT_EQ(snert.eulerCharacteristic, sna.eulerCharacteristic) << "greyscale trial " << trial;
    if (trial % 3 == 0)
    {
      // The high-quality mode on the same noise: swaps and moves are undone where
      // they would break the mesh.
      auto filter = itk::SurfaceNetsImageToMeshFilter<FloatImage>::New();
      filter->SetInput(grey);
      filter->SetIsoValue(d);
      filter->SetInsideIsAboveIsoValue(false);
      filter->SetHighQuality(true);
      filter->Update();
      const auto high = Measure(filter->GetOutput());
      ASSERT_TRUE(high.IsValidClosedSurface()) << "high-quality trial " << trial << '\n' << Text(high);
      ASSERT_EQ(high.eulerCharacteristic, sna.eulerCharacteristic) << "high-quality trial " << trial;
    }
  }
}

TEST(SurfaceNetsImageToMeshFilter, HighQualityKeepsSmoothRandomVolumesValidWithTheirTopology)
{
  // Blobs, sheets and tubes with noise (MakeRandomSmoothVolume), some on anisotropic
  // or rotated grids: many small components, thin parts, pinches. The high-quality
  // mode must give a valid closed surface with the components and Euler
  // characteristic of plain SNERT. Seeds 61, 90 and 100 failed before folds were
  // kept from closing, 8226 and 8278 before components kept their volume (11 of
  // 12,000 seeds from 8000): each time the 12 triangles of a single voxel's
  // component came out inside out by the ray test.
  std::vector<unsigned int> seeds(40);
  std::iota(seeds.begin(), seeds.end(), 0u);
  seeds.insert(seeds.end(), { 61u, 90u, 100u, 8226u, 8278u });
  std::size_t tested = 0;
  for (unsigned int seed : seeds)
  {
    SCOPED_TRACE(seed);
    double     iso = 0.0;
    const auto image = MakeRandomSmoothVolume(seed, iso);
    const auto min = std::min_element(image->GetBufferPointer(),
                                      image->GetBufferPointer() + image->GetBufferedRegion().GetNumberOfPixels());
    const auto max = std::max_element(image->GetBufferPointer(),
                                      image->GetBufferPointer() + image->GetBufferedRegion().GetNumberOfPixels());
    if (!(*min < iso && *max >= iso))
    {
      continue; // nothing inside, or nothing outside
    }
    ++tested;
    const auto snert = Measure(Extract(image.GetPointer(), iso, true).GetPointer());
    ASSERT_TRUE(snert.IsValidClosedSurface()) << "SNERT, seed " << seed << '\n' << Text(snert);
    auto filter = itk::SurfaceNetsImageToMeshFilter<FloatImage>::New();
    filter->SetInput(image);
    filter->SetIsoValue(iso);
    filter->SetHighQuality(true);
    filter->Update();
    const auto high = Measure(filter->GetOutput());
    ASSERT_TRUE(high.IsValidClosedSurface()) << "high quality, seed " << seed << '\n' << Text(high);
    EXPECT_EQ(high.connectedComponents, snert.connectedComponents);
    EXPECT_EQ(high.eulerCharacteristic, snert.eulerCharacteristic);
  }
  EXPECT_GE(tested, 35u);
}

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

TEST(SurfaceNetsImageToMeshFilter, StructuredSelfIntersectionSearchFindsExactlyWhatTheTreeFinds)
{
  // Nets of random volumes with every node thrown anywhere in its constraint box (far
  // more crossings than a relaxation makes), on axis-aligned and on rotated,
  // anisotropic grids: the search over the quads of each cell finds exactly the pairs
  // the tree over all faces finds, for all faces and for a changed subset.
  std::mt19937                           rng(5);
  std::uniform_real_distribution<float>  value(0.0f, 1.0f);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  itk::Matrix<double, 3, 3>              rotated;
  {
    const double a = 0.4;
    const double b = 0.3;
    const double R[3][3] = { { std::cos(a), -std::sin(a) * std::cos(b), std::sin(a) * std::sin(b) },
                             { std::sin(a), std::cos(a) * std::cos(b), -std::cos(a) * std::sin(b) },
                             { 0.0, std::sin(b), std::cos(b) } };
    const double spacing[3] = { 0.7, 1.1, 2.5 };
    for (unsigned int r = 0; r < 3; ++r)
    {
      for (unsigned int c = 0; c < 3; ++c)
      {
        rotated[r][c] = R[r][c] * spacing[c];
      }
    }
  }
  itk::Matrix<double, 3, 3> identity;
  identity.SetIdentity();
  std::size_t intersecting = 0;
  for (int trial = 0; trial < 40; ++trial)
  {
    SCOPED_TRACE(trial);
    const unsigned int n = 6 + trial % 4;
    auto               image = MakeImage<FloatImage>(n, n, n);
    const double       density = 0.3 + 0.4 * value(rng);
    for (std::size_t i = 0; i < image->GetBufferedRegion().GetNumberOfPixels(); ++i)
    {
      image->GetBufferPointer()[i] = value(rng);
    }
    ME::SurfaceNet net;
    ME::detail::ClassifySurfaceCells(
      image.GetPointer(), ME::detail::SurfaceNetsVoxelRange<float>::FromIsoValue(density, false), net, 1);
    if (net.cells.empty())
    {
      continue;
    }
    ME::detail::BuildSurfaceNet(net, 0.01, 1);
    for (std::size_t i = 0; i < net.positions.size(); ++i)
    {
      for (unsigned int k = 0; k < 3; ++k)
      {
        net.positions[i][k] = net.boxLower[i][k] + unit(rng) * (net.boxUpper[i][k] - net.boxLower[i][k]);
      }
    }
    const bool                        rotate = trial % 2 == 1;
    const itk::Matrix<double, 3, 3> & M = rotate ? rotated : identity;
    const ME::Vec3                    origin = rotate ? ME::MakeVec3(-12.5, 30.0, 7.25) : ME::MakeVec3(0, 0, 0);
    std::vector<ME::Vec3>             points;
    ME::LargeBlockVector<std::array<std::uint32_t, 4>> polygons;
    unsigned int                                       polygonSize = 3;
    ME::detail::MakeSurfaceNetFaces(
      net, origin, M, ME::detail::QuadSplit::ShortestDiagonal, points, polygons, polygonSize);
    ME::IndexedTriangleMesh mesh;
    mesh.points = ME::detail::ToPhysical(net.positions, origin, M, rotate);
    for (const auto & p : polygons)
    {
      mesh.triangles.push_back({ p[0], p[1], p[2] });
    }
    const auto                                           expected = ME::detail::FindSelfIntersections(mesh);
    std::vector<std::pair<std::uint32_t, std::uint32_t>> found;
    ASSERT_TRUE(ME::detail::FindSurfaceNetSelfIntersections(net, mesh, origin, M, rotate, nullptr, found));
    ASSERT_EQ(found, expected);
    intersecting += expected.size();
    std::vector<std::uint32_t> changed;
    for (std::uint32_t f = 0; f < mesh.triangles.size(); ++f)
    {
      if (unit(rng) < 0.2)
      {
        changed.push_back(f);
      }
    }
    ASSERT_TRUE(ME::detail::FindSurfaceNetSelfIntersections(net, mesh, origin, M, rotate, &changed, found));
    ASSERT_EQ(found, ME::detail::FindSelfIntersections(mesh, &changed));
    // A node on a face of its cell: the argument fails, and the search says so.
    net.positions[0][0] = std::floor(net.positions[0][0]);
    ASSERT_FALSE(ME::detail::FindSurfaceNetSelfIntersections(net, mesh, origin, M, rotate, nullptr, found));
    EXPECT_TRUE(found.empty());
  }
  EXPECT_GT(intersecting, 100u) << "the random nets should cross themselves often";
}

TEST(SurfaceNetsImageToMeshFilter, SelfIntersectionRemovalHandsOutTheFacesOfTheFinalNet)
{
  // Nets with nodes thrown anywhere in their boxes cross themselves; after the removal
  // the faces it hands out (which the filter writes instead of making them again) are
  // exactly the faces of the final net, and they do not intersect.
  std::mt19937                           rng(9);
  std::uniform_real_distribution<float>  value(0.0f, 1.0f);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  itk::Matrix<double, 3, 3>              M;
  M.SetIdentity();
  M[0][0] = 0.8;
  M[2][2] = 1.7;
  const ME::Vec3 origin = ME::MakeVec3(3.0, -2.0, 0.5);
  std::size_t    movedBack = 0;
  for (int trial = 0; trial < 24; ++trial)
  {
    SCOPED_TRACE(trial);
    const unsigned int n = 6 + trial % 3;
    auto               image = MakeImage<FloatImage>(n, n, n);
    for (std::size_t i = 0; i < image->GetBufferedRegion().GetNumberOfPixels(); ++i)
    {
      image->GetBufferPointer()[i] = value(rng);
    }
    ME::SurfaceNet net;
    ME::detail::ClassifySurfaceCells(
      image.GetPointer(), ME::detail::SurfaceNetsVoxelRange<float>::FromIsoValue(0.5, false), net, 1);
    if (net.cells.empty())
    {
      continue;
    }
    ME::detail::BuildSurfaceNet(net, 0.01, 1);
    const ME::LargeBlockVector<ME::Vec3> initial = net.positions;
    for (std::size_t i = 0; i < net.positions.size(); ++i)
    {
      for (unsigned int k = 0; k < 3; ++k)
      {
        net.positions[i][k] = net.boxLower[i][k] + unit(rng) * (net.boxUpper[i][k] - net.boxLower[i][k]);
      }
    }
    const bool                  roundToFloat = trial % 2 == 1;
    const ME::detail::QuadSplit split =
      trial % 4 < 2 ? ME::detail::QuadSplit::ShortestDiagonal : ME::detail::QuadSplit::Delaunay;
    ME::LargeBlockVector<std::array<std::uint32_t, 4>> faces;
    movedBack += ME::detail::RemoveSurfaceNetSelfIntersections(net, initial, origin, M, split, roundToFloat, &faces);
    std::vector<ME::Vec3>                              points;
    ME::LargeBlockVector<std::array<std::uint32_t, 4>> expected;
    unsigned int                                       polygonSize = 0;
    ME::detail::MakeSurfaceNetFaces(net, origin, M, split, points, expected, polygonSize);
    ASSERT_EQ(polygonSize, 3u);
    ASSERT_EQ(faces, expected);
    ME::IndexedTriangleMesh mesh;
    mesh.points = ME::detail::ToPhysical(net.positions, origin, M, roundToFloat);
    for (const auto & f : faces)
    {
      mesh.triangles.push_back({ f[0], f[1], f[2] });
    }
    EXPECT_TRUE(ME::detail::FindSelfIntersections(mesh).empty());
    // Quads are not what the check tests: nothing is handed out.
    ME::detail::RemoveSurfaceNetSelfIntersections(
      net, initial, origin, M, ME::detail::QuadSplit::KeepQuads, roundToFloat, &faces);
    EXPECT_TRUE(faces.empty());
  }
  EXPECT_GT(movedBack, 20u) << "the random nets should need nodes moved back";
}

TEST(SurfaceNetsImageToMeshFilter, SnertSphereHasSlicerQualityAtAFiftiethOfAVoxel)
{
  // Thesis Table 3.1, sphere distance map: radius 19.2 voxels (> 15).
  const Phantom p = MakePhantom(ME::PhantomShape::Sphere);
  auto          snert = Extract(p.image.GetPointer(), 0.0, false);
  const auto    q = Measure(snert.GetPointer());
  EXPECT_TRUE(q.IsValidClosedSurface()) << Text(q);
  EXPECT_EQ(q.eulerCharacteristic, 2);
  EXPECT_GE(q.qAngle.mean, 0.60);
  EXPECT_GE(q.qArea.mean, 0.90);
  EXPECT_EQ(q.fractionQAngleBelow03, 0.0);
  const auto d = Distance(snert.GetPointer(), p.surface);
  EXPECT_LE(d.vertices.mean, 0.02); // voxels (1 mm spacing)
  EXPECT_LE(d.faceCentroids.mean, 0.03);

  // SNA ignores the greyscale values: it shrinks the sphere and is less accurate.
  auto       sna = Extract(p.image.GetPointer(), 0.0, false, Enums::Relaxation::Averaging);
  const auto ds = Distance(sna.GetPointer(), p.surface);
  EXPECT_GT(ds.vertices.mean, 3 * d.vertices.mean);
  EXPECT_LT(ds.vertices.signedMean, -0.05); // inside the sphere
  EXPECT_TRUE(Measure(sna.GetPointer()).IsValidClosedSurface());

  // (Greyscale marching cubes is compared in the VTK test suite.)
}

TEST(SurfaceNetsImageToMeshFilter, SnertClosesAnObjectCutByTheImageBorderHalfAVoxelOutside)
{
  // A slab x <= 3.5 (distance map, inside below 0) cut by the image's x = 0 face: the
  // voxels outside the image count as background mirrored about the iso-value, so
  // the closing face lies halfway between voxel 0 and the virtual voxel -1, at
  // x = -0.5. (A cell at x = -1 once read its outside corners from the far side of
  // the image, x = 15, and put that face at about x = -0.23.)
  auto image = MakeImage<FloatImage>(16, 12, 12);
  for (itk::ImageRegionIteratorWithIndex<FloatImage> it(image, image->GetBufferedRegion()); !it.IsAtEnd(); ++it)
  {
    // Far from the object (x >= 12) the field slopes along y instead, so that reading
    // the far side of the image for the border cells shows in their gradients too.
    const auto & index = it.GetIndex();
    it.Set(index[0] < 12 ? static_cast<float>(index[0]) - 3.5f : 8.5f + 2.0f * static_cast<float>(index[1]));
  }
  for (const bool gaussian : { false, true })
  {
    SCOPED_TRACE(gaussian ? "Gaussian-derivative gradients" : "central differences");
    auto filter = itk::SurfaceNetsImageToMeshFilter<FloatImage, QEMeshType>::New();
    filter->SetInput(image);
    filter->SetIsoValue(0.0);
    filter->SetInsideIsAboveIsoValue(false);
    filter->SetRelaxation(Enums::Relaxation::Combined);
    if (gaussian)
    {
      filter->SetGradientMethod(Enums::Gradient::GaussianDerivative);
    }
    filter->Update();
    auto mesh = filter->GetOutput();
    ASSERT_TRUE(Measure(mesh).IsValidClosedSurface());
    std::size_t onTheBorderFace = 0;
    for (auto it = mesh->GetPoints()->Begin(); it != mesh->GetPoints()->End(); ++it)
    {
      const auto & point = it.Value();
      // Nodes of the border face away from its rim (y and z inside the image).
      if (point[0] < 0.0 && point[1] > 1.0 && point[1] < 10.0 && point[2] > 1.0 && point[2] < 10.0)
      {
        EXPECT_NEAR(point[0], -0.5, 0.02) << "node at " << point;
        ++onTheBorderFace;
      }
    }
    EXPECT_GE(onTheBorderFace, 64u);
  }
}

TEST(SurfaceNetsImageToMeshFilter, SnertPlaneIsExactAndAsFlatAsMarchingCubes)
{
  const Phantom p = MakePhantom(ME::PhantomShape::Plane);
  auto          mesh = Extract(p.image.GetPointer(), 0.0, false);
  auto          calculator = itk::TriangleMeshQualityCalculator<QEMeshType>::New();
  calculator->SetMesh(mesh);
  calculator->Compute();
  EXPECT_TRUE(calculator->GetReport().IsValidClosedSurface());
  // Away from the image border (where the half-space is closed), nodes lie on the
  // plane: the distance map is linear, so trilinear interpolation is exact.
  const auto & smoothness = calculator->GetVertexSmoothness();
  double       largestDistance = 0.0;
  double       sumSmoothness = 0.0;
  std::size_t  interior = 0;
  std::size_t  index = 0;
  for (auto it = mesh->GetPoints()->Begin(); it != mesh->GetPoints()->End(); ++it, ++index)
  {
    const auto & point = it.Value();
    bool         nearBorder = false;
    for (unsigned int d = 0; d < 3; ++d)
    {
      nearBorder = nearBorder || point[d] < 2.0 || point[d] > 61.0;
    }
    if (nearBorder)
    {
      continue;
    }
    itk::ImplicitSurfaceFunction::InputType x;
    for (unsigned int d = 0; d < 3; ++d)
    {
      x[d] = point[d];
    }
    largestDistance = std::max(largestDistance, std::abs(p.surface->Evaluate(x)));
    sumSmoothness += smoothness[index];
    ++interior;
  }
  ASSERT_GT(interior, 1000u);
  EXPECT_LT(largestDistance, 1e-4);
  const double meanSmoothness = sumSmoothness / interior;
  EXPECT_LT(meanSmoothness, 1e-3);
  // Marching cubes on the binary mask (ITK's BinaryMask3DMeshSource) terraces the tilted plane.
  EXPECT_LT(meanSmoothness, Measure(MarchingCubes(p).GetPointer()).meanSmoothness);
}

TEST(SurfaceNetsImageToMeshFilter, OverlappingSpheresTorusAndEllipsoidKeepTheirTopology)
{
  for (auto shape : { ME::PhantomShape::TwoSpheres,
                      ME::PhantomShape::Torus,
                      ME::PhantomShape::Ellipsoid,
                      ME::PhantomShape::IndentedSphere })
  {
    SCOPED_TRACE(ME::PhantomShapeName(shape));
    const Phantom p = MakePhantom(shape);
    auto          mesh = Extract(p.image.GetPointer(), 0.0, false);
    const auto    q = Measure(mesh.GetPointer());
    EXPECT_TRUE(q.IsValidClosedSurface()) << Text(q);
    EXPECT_EQ(q.connectedComponents, 1);
    EXPECT_EQ(q.eulerCharacteristic, shape == ME::PhantomShape::Torus ? 0 : 2);
    EXPECT_GE(q.qAngle.mean, 0.58);
    const auto d = Distance(mesh.GetPointer(), p.surface);
    EXPECT_LE(d.vertices.mean, 0.025);
  }
}

TEST(SurfaceNetsImageToMeshFilter, ThinPlateAndNarrowCleftRetainTheirDetail)
{
  for (auto shape : { ME::PhantomShape::ThinPlate, ME::PhantomShape::NarrowCleft })
  {
    SCOPED_TRACE(ME::PhantomShapeName(shape));
    const Phantom p = MakePhantom(shape);
    auto          mesh = Extract(p.image.GetPointer(), 0.0, false);
    const auto    q = Measure(mesh.GetPointer());
    EXPECT_TRUE(q.IsValidClosedSurface()) << Text(q);
    EXPECT_EQ(q.connectedComponents, 1);
    EXPECT_EQ(q.eulerCharacteristic, 2);
    // A bridged cleft or a plate with holes would leave parts of the exact surface
    // far from the mesh: the symmetric Hausdorff distance stays below a voxel.
    const auto d = Distance(mesh.GetPointer(), p.surface);
    EXPECT_LT(d.hausdorff, 1.0);
    EXPECT_LE(d.vertices.mean, 0.03);
  }
}

TEST(SurfaceNetsImageToMeshFilter, AnisotropicRotatedGridGivesTheSamePhysicalSurface)
{
  ME::PhantomGrid grid = ME::DefaultPhantomGrid(ME::PhantomShape::Sphere);
  grid.size[0] = 80;
  grid.size[1] = 64;
  grid.size[2] = 44;
  grid.spacing[0] = 0.8;
  grid.spacing[1] = 1.0;
  grid.spacing[2] = 1.45;
  const double angle = 0.5;
  grid.direction.SetIdentity();
  grid.direction[0][0] = std::cos(angle);
  grid.direction[0][1] = -std::sin(angle);
  grid.direction[1][0] = std::sin(angle);
  grid.direction[1][1] = std::cos(angle);
  grid.origin[0] = -20.0;
  grid.origin[1] = 7.0;
  grid.origin[2] = 3.0;
  const Phantom anisotropic = MakePhantom(ME::PhantomShape::Sphere, grid);
  auto          mesh = Extract(anisotropic.image.GetPointer(), 0.0, false);
  const auto    q = Measure(mesh.GetPointer());
  EXPECT_TRUE(q.IsValidClosedSurface()) << Text(q);
  const auto d = Distance(mesh.GetPointer(), anisotropic.surface);
  EXPECT_LE(d.vertices.mean, 0.03); // mm
  EXPECT_LT(d.hausdorff, 0.5);      // mm

  // The same sphere (same physical radius) on the default isotropic grid.
  const Phantom isotropic = MakePhantom(ME::PhantomShape::Sphere);
  auto          sphere = itk::SphereImplicitSurface::New();
  const auto *  s1 = dynamic_cast<const itk::SphereImplicitSurface *>(anisotropic.surface.GetPointer());
  const auto *  s2 = dynamic_cast<const itk::SphereImplicitSurface *>(isotropic.surface.GetPointer());
  ASSERT_NE(s1, nullptr);
  ASSERT_NE(s2, nullptr);
  const double radius = s1->GetRadius();
  EXPECT_NEAR(q.enclosedVolume, 4.0 / 3.0 * itk::Math::pi * radius * radius * radius, 0.01 * q.enclosedVolume);
  const auto   qi = Measure(Extract(isotropic.image.GetPointer(), 0.0, false).GetPointer());
  const double ri = s2->GetRadius();
  EXPECT_NEAR(qi.enclosedVolume / (ri * ri * ri), q.enclosedVolume / (radius * radius * radius), 0.01);
}

TEST(SurfaceNetsImageToMeshFilter, MeshIsIdenticalForOneAndManyThreads)
{
  const Phantom p = MakePhantom(ME::PhantomShape::TwoSpheres);
  auto          run = [&p](unsigned int workUnits) {
    auto filter = itk::SurfaceNetsImageToMeshFilter<FloatImage, MeshType>::New();
    filter->SetInput(p.image);
    filter->SetInsideIsAboveIsoValue(false);
    filter->SetNumberOfWorkUnits(workUnits);
    filter->Update();
    return ME::MakeIndexedTriangleMesh(*filter->GetOutput());
  };
  const auto one = run(1);
  const auto many = run(7);
  ASSERT_EQ(one.points.size(), many.points.size());
  EXPECT_EQ(one.triangles, many.triangles);
  for (std::size_t i = 0; i < one.points.size(); ++i)
  {
    ASSERT_EQ(one.points[i], many.points[i]) << "point " << i;
  }
}

TEST(SurfaceNetsImageToMeshFilter, EveryScalarPixelTypeGivesTheSurface)
{
  // A blurred-step sphere (inside 100, outside 0), iso-value 50, in five pixel types.
  ME::PhantomGrid grid;
  grid.size.Fill(40);
  auto surface = ME::MakePhantomSurface(ME::PhantomShape::Sphere, grid);
  auto check = [&surface](auto image) {
    auto mesh = Extract(image.GetPointer(), 50.0, true);
    EXPECT_TRUE(Measure(mesh.GetPointer()).IsValidClosedSurface());
    EXPECT_LE(Distance(mesh.GetPointer(), surface).vertices.mean, 0.05);
  };
  ME::PhantomImageParameters step;
  step.mode = itk::MeshExtractionEnums::PhantomImage::BlurredStep;
  step.insideValue = 100;
  step.outsideValue = 0;
  step.edgeWidth = 1.0;
  auto render = [&](auto * typeTag) {
    using ImageType = std::remove_pointer_t<decltype(typeTag)>;
    auto source = itk::ImplicitSurfaceImageSource<ImageType>::New();
    source->SetSurface(surface);
    source->SetSize(grid.size);
    source->SetImageMode(step.mode);
    source->SetInsideValue(100);
    source->SetOutsideValue(0);
    source->SetEdgeWidth(1.0);
    source->Update();
    return typename ImageType::Pointer(source->GetOutput());
  };
  check(render(static_cast<itk::Image<unsigned char, 3> *>(nullptr)));
  check(render(static_cast<itk::Image<short, 3> *>(nullptr)));
  check(render(static_cast<itk::Image<unsigned short, 3> *>(nullptr)));
  check(render(static_cast<itk::Image<float, 3> *>(nullptr)));
  check(render(static_cast<itk::Image<double, 3> *>(nullptr)));
}

TEST(SurfaceNetsImageToMeshFilter, MeshOutputTriangulationsAndQuadsAgree)
{
  const Phantom p = MakePhantom(ME::PhantomShape::Ellipsoid);
  auto          filter = itk::SurfaceNetsImageToMeshFilter<FloatImage, MeshType>::New();
  filter->SetInput(p.image);
  filter->SetInsideIsAboveIsoValue(false);
  filter->Update();
  const auto shortest = Measure<MeshType>(filter->GetOutput());
  EXPECT_TRUE(shortest.IsValidClosedSurface());
  filter->SetTriangulation(Enums::Triangulation::Delaunay);
  filter->Update();
  const auto delaunay = Measure<MeshType>(filter->GetOutput());
  EXPECT_TRUE(delaunay.IsValidClosedSurface());
  // Max-min per quad: the smallest angle of the mesh can only grow.
  EXPECT_GE(delaunay.minimumAngle.minimum, shortest.minimumAngle.minimum - 1e-9);
  filter->SetTriangulation(Enums::Triangulation::Quadrilaterals);
  filter->Update();
  const auto quads = Measure<MeshType>(filter->GetOutput());
  EXPECT_EQ(quads.numberOfSplitQuads, shortest.numberOfTriangles / 2);
  EXPECT_EQ(filter->GetOutput()->GetNumberOfCells(), shortest.numberOfTriangles / 2);
  EXPECT_EQ(quads.eulerCharacteristic, 2);
  // The QuadEdgeMesh output holds the same quads as faces.
  auto qe = itk::SurfaceNetsImageToMeshFilter<FloatImage>::New();
  qe->SetInput(p.image);
  qe->SetInsideIsAboveIsoValue(false);
  qe->SetTriangulation(Enums::Triangulation::Quadrilaterals);
  qe->Update();
  EXPECT_EQ(qe->GetOutput()->GetNumberOfFaces(), shortest.numberOfTriangles / 2);
}

TEST(SurfaceNetsImageToMeshFilter, DynamicMeshTraitsGetTheSameCells)
{
  // A mesh whose cells container is not a VectorContainer (map-based dynamic traits)
  // takes the filter's other output branch: one heap cell per face through SetCell.
  using DynamicMesh = itk::Mesh<double, 3, itk::DefaultDynamicMeshTraits<double, 3, 3>>;
  const Phantom p = MakePhantom(ME::PhantomShape::Ellipsoid);
  auto          vectorFilter = itk::SurfaceNetsImageToMeshFilter<FloatImage, MeshType>::New();
  auto          mapFilter = itk::SurfaceNetsImageToMeshFilter<FloatImage, DynamicMesh>::New();
  vectorFilter->SetInput(p.image);
  mapFilter->SetInput(p.image);
  vectorFilter->SetInsideIsAboveIsoValue(false);
  mapFilter->SetInsideIsAboveIsoValue(false);
  vectorFilter->Update();
  mapFilter->Update();
  const MeshType *    a = vectorFilter->GetOutput();
  const DynamicMesh * b = mapFilter->GetOutput();
  ASSERT_GT(a->GetNumberOfCells(), 0u);
  ASSERT_EQ(b->GetNumberOfCells(), a->GetNumberOfCells());
  ASSERT_EQ(b->GetNumberOfPoints(), a->GetNumberOfPoints());
  for (MeshType::CellIdentifier c = 0; c < a->GetNumberOfCells(); ++c)
  {
    MeshType::CellAutoPointer    u;
    DynamicMesh::CellAutoPointer v;
    ASSERT_TRUE(a->GetCell(c, u));
    ASSERT_TRUE(b->GetCell(c, v));
    ASSERT_EQ(v->GetType(), itk::CellGeometryEnum::TRIANGLE_CELL);
    ASSERT_EQ(v->GetNumberOfPoints(), 3u);
    for (unsigned int k = 0; k < 3; ++k)
    {
      ASSERT_EQ(v->GetPointIds()[k], u->GetPointIds()[k]) << "cell " << c;
    }
  }
  EXPECT_TRUE(Measure<DynamicMesh>(b).IsValidClosedSurface());
}

TEST(SurfaceNetsImageToMeshFilter, MeshCellsShareOneBlockThatGoesWithTheLastCell)
{
  using CellType = MeshType::CellType;
  using Triangle = ME::detail::BlockAllocatedCell<itk::TriangleCell<CellType>>;
  using Quad = ME::detail::BlockAllocatedCell<itk::QuadrilateralCell<CellType>>;
  const std::size_t trianglesBefore = Triangle::GetNumberOfBlocks();
  const std::size_t quadsBefore = Quad::GetNumberOfBlocks();
  const Phantom     p = MakePhantom(ME::PhantomShape::Ellipsoid);
  auto              filter = itk::SurfaceNetsImageToMeshFilter<FloatImage, MeshType>::New();
  filter->SetInput(p.image);
  filter->SetInsideIsAboveIsoValue(false);
  filter->Update();
  MeshType::Pointer mesh = filter->GetOutput();
  mesh->DisconnectPipeline();
  filter = nullptr;
  ASSERT_GT(mesh->GetNumberOfCells(), 1000u);
  EXPECT_EQ(Triangle::GetNumberOfBlocks(), trianglesBefore + 1);
  // Ordinary triangle cells to the mesh and its users, and independent copies.
  const CellType * first = mesh->GetCells()->ElementAt(0);
  EXPECT_EQ(first->GetType(), itk::CellGeometryEnum::TRIANGLE_CELL);
  EXPECT_NE(dynamic_cast<const itk::TriangleCell<CellType> *>(first), nullptr);
  CellType::CellAutoPointer copy;
  first->MakeCopy(copy);
  const std::vector<MeshType::PointIdentifier> firstIds(first->PointIdsBegin(), first->PointIdsEnd());
  // A cell replaced by the user is deleted by the mesh as any other; the block stays
  // while any of its cells does.
  CellType::CellAutoPointer replacement;
  replacement.TakeOwnership(new itk::TriangleCell<CellType>);
  replacement->SetPointIds(first->PointIdsBegin());
  CellType * replaced = mesh->GetCells()->ElementAt(1);
  mesh->GetCells()->InsertElement(1, replacement.ReleaseOwnership());
  delete replaced;
  EXPECT_EQ(Triangle::GetNumberOfBlocks(), trianglesBefore + 1);
  mesh = nullptr; // deletes every cell: the block goes with the last
  EXPECT_EQ(Triangle::GetNumberOfBlocks(), trianglesBefore);
  EXPECT_TRUE(std::equal(firstIds.begin(), firstIds.end(), copy->PointIdsBegin()));

  // Made in a block of many or alone, deleted in any order.
  std::vector<CellType *> cells(1000);
  Quad::MakeCells(cells.size(), cells.begin());
  EXPECT_EQ(Quad::GetNumberOfBlocks(), quadsBefore + 1);
  CellType * alone = new Quad;
  EXPECT_EQ(Quad::GetNumberOfBlocks(), quadsBefore + 2);
  std::mt19937 random(7);
  std::shuffle(cells.begin(), cells.end(), random);
  for (std::size_t i = 0; i + 1 < cells.size(); ++i)
  {
    cells[i]->SetPointId(3, i);
    EXPECT_EQ(cells[i]->GetNumberOfPoints(), 4u);
    delete cells[i];
  }
  EXPECT_EQ(Quad::GetNumberOfBlocks(), quadsBefore + 2);
  delete alone;
  EXPECT_EQ(Quad::GetNumberOfBlocks(), quadsBefore + 1);
  delete cells.back();
  EXPECT_EQ(Quad::GetNumberOfBlocks(), quadsBefore);
}

namespace
{
/** A triangle cell whose constructor throws on its `throwAt`-th call, as an
 * allocating constructor (ITK 5.2's) may. */
class ThrowingTriangle : public itk::TriangleCell<MeshType::CellType>
{
public:
  ThrowingTriangle()
  {
    if (++constructed == throwAt)
    {
      throw std::runtime_error("cell constructor failed");
    }
    ++alive;
  }
  ~ThrowingTriangle() override
  {
    --alive;
  }
  static std::atomic<std::size_t> constructed;
  static std::atomic<std::size_t> alive;
  static std::size_t              throwAt;
};
std::atomic<std::size_t> ThrowingTriangle::constructed{ 0 };
std::atomic<std::size_t> ThrowingTriangle::alive{ 0 };
std::size_t              ThrowingTriangle::throwAt = 0;
} // namespace

TEST(SurfaceNetsImageToMeshFilter, CellBlockLeavesNothingWhenAConstructorThrows)
{
  using Cell = ME::detail::BlockAllocatedCell<ThrowingTriangle>;
  const std::size_t                 blocksBefore = Cell::GetNumberOfBlocks();
  std::vector<MeshType::CellType *> cells(50000, nullptr);

  // Each cell in its slot: the addresses rise by one slot a cell.
  ThrowingTriangle::throwAt = 0;
  Cell::MakeCells(cells.size(), cells.begin());
  EXPECT_EQ(ThrowingTriangle::alive.load(), cells.size());
  EXPECT_EQ(Cell::GetNumberOfBlocks(), blocksBefore + 1);
  const auto slot = reinterpret_cast<std::uintptr_t>(cells[1]) - reinterpret_cast<std::uintptr_t>(cells[0]);
  for (std::size_t i = 1; i < cells.size(); ++i)
  {
    ASSERT_EQ(reinterpret_cast<std::uintptr_t>(cells[i]) - reinterpret_cast<std::uintptr_t>(cells[i - 1]), slot);
  }
  for (auto *& cell : cells)
  {
    delete cell;
    cell = nullptr;
  }
  EXPECT_EQ(ThrowingTriangle::alive.load(), 0u);
  EXPECT_EQ(Cell::GetNumberOfBlocks(), blocksBefore);

  // A constructor that throws part-way (the 20,000th of 50,000): the exception reaches
  // the caller, and no cell, block or address is left.
  ThrowingTriangle::constructed = 0;
  ThrowingTriangle::throwAt = 20000;
  EXPECT_THROW(Cell::MakeCells(cells.size(), cells.begin()), std::runtime_error);
  EXPECT_EQ(ThrowingTriangle::constructed.load(), ThrowingTriangle::throwAt);
  EXPECT_EQ(ThrowingTriangle::alive.load(), 0u);
  EXPECT_EQ(Cell::GetNumberOfBlocks(), blocksBefore);
  EXPECT_TRUE(std::all_of(cells.begin(), cells.end(), [](const MeshType::CellType * c) { return c == nullptr; }));
  ThrowingTriangle::throwAt = 0;
}

TEST(SurfaceNetsImageToMeshFilter, SegmentationRelaxedTowardTheGreyscaleIsoSurface)
{
  // The net from a mask of the sphere, relaxed toward the distance map's iso-surface,
  // lands where the greyscale-only SNERT does.
  const Phantom p = MakePhantom(ME::PhantomShape::Sphere);
  const auto    mask = PhantomMask(p);
  auto          filter = itk::SurfaceNetsImageToMeshFilter<FloatImage>::New();
  filter->SetInput(p.image);
  filter->SetLabelImage(mask);
  filter->SetInsideIsAboveIsoValue(false);
  filter->Update();
  EXPECT_TRUE(Measure(filter->GetOutput()).IsValidClosedSurface());
  EXPECT_LE(Distance(filter->GetOutput(), p.surface).vertices.mean, 0.02);
  // A label image of another size is refused.
  filter->SetLabelImage(MakeImage<MaskImage>(8, 8, 8, 1));
  EXPECT_THROW(filter->Update(), itk::ExceptionObject);
}

TEST(SurfaceNetsImageToMeshFilter, GaussianDerivativeGradientsHandleNoise)
{
  ME::PhantomGrid grid;
  grid.size.Fill(48);
  ME::PhantomImageParameters parameters = ME::DefaultPhantomImageParameters(ME::PhantomShape::Chapter4Sphere);
  parameters.noiseStandardDeviation = 2.0;
  auto source = ME::MakePhantomImageSource<FloatImage>(ME::PhantomShape::Sphere, grid, parameters);
  source->Update();
  auto filter = itk::SurfaceNetsImageToMeshFilter<FloatImage>::New();
  filter->SetInput(source->GetOutput());
  filter->SetIsoValue(50.0);
  filter->SetGradientMethod(Enums::Gradient::GaussianDerivative);
  filter->SetGradientSigma(1.0);
  filter->Update();
  const auto q = Measure(filter->GetOutput());
  EXPECT_TRUE(q.IsValidClosedSurface()) << Text(q);
  EXPECT_EQ(q.connectedComponents, 1);
  EXPECT_LE(Distance(filter->GetOutput(), ME::MakePhantomSurface(ME::PhantomShape::Sphere, grid)).vertices.mean, 0.15);
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

TEST(SurfaceNetsImageToMeshFilter, BadInputRaisesClearExceptions)
{
  auto expectMessage = [](auto & filter, const std::string & words) {
    try
    {
      filter->Update();
      FAIL() << "expected an exception mentioning '" << words << "'";
    }
    catch (const itk::ExceptionObject & e)
    {
      EXPECT_NE(std::string(e.GetDescription()).find(words), std::string::npos) << e.GetDescription();
    }
  };
  auto filter = itk::SurfaceNetsImageToMeshFilter<FloatImage>::New();
  EXPECT_THROW(filter->Update(), itk::ExceptionObject); // no input

  auto constant = MakeImage<FloatImage>(6, 6, 6, 3.0f);
  filter->SetInput(constant);
  expectMessage(filter, "constant (every voxel is 3)"); // every voxel inside (>= 0)
  filter->SetIsoValue(5.0);                             // and none
  expectMessage(filter, "constant (every voxel is 3)");
  filter->SetIsoValue(0.0);

  auto image = MakeImage<FloatImage>(6, 6, 6, 0.0f);
  image->SetPixel({ { 2, 2, 2 } }, 10.0f);
  filter->SetInput(image);
  filter->SetIsoValue(20.0);
  expectMessage(filter, "No voxel is inside: the image ranges over [0, 10]");

  filter->SetIsoValue(5.0);
  image->SetPixel({ { 4, 1, 3 } }, std::numeric_limits<float>::quiet_NaN());
  image->Modified();
  expectMessage(filter, "NaN voxel at index [4, 1, 3]");

  image->SetPixel({ { 4, 1, 3 } }, 0.0f);
  image->Modified();
  filter->SetCellMargin(0.6);
  expectMessage(filter, "CellMargin");
  filter->SetCellMargin(0.01);
  filter->SetSmoothingWeight(-1.0);
  expectMessage(filter, "SmoothingWeight");
  filter->SetSmoothingWeight(1.0);
  filter->Update(); // a single bright voxel: fine
  EXPECT_TRUE(Measure(filter->GetOutput()).IsValidClosedSurface());

  auto labels = itk::SurfaceNetsImageToMeshFilter<MaskImage>::New();
  labels->SetInput(MakeImage<MaskImage>(5, 5, 5, 0));
  labels->SetClassifyByLabel(true);
  labels->SetLabelValue(3);
  expectMessage(labels, "No voxel has the label 3");
  auto mask = MakeImage<MaskImage>(5, 5, 5, 0);
  mask->SetPixel({ { 1, 1, 1 } }, 3);
  labels->SetInput(mask);
  labels->SetRelaxation(Enums::Relaxation::Combined);
  expectMessage(labels, "label image");
  labels->SetRelaxation(Enums::Relaxation::Automatic);
  labels->Update();
  EXPECT_TRUE(Measure(labels->GetOutput()).IsValidClosedSurface());
}

namespace
{
QEMeshType::Pointer
ExtractHighQuality(const FloatImage * image, itk::SizeValueType * swaps = nullptr)
{
  auto filter = itk::SurfaceNetsImageToMeshFilter<FloatImage>::New();
  filter->SetInput(image);
  filter->SetInsideIsAboveIsoValue(false);
  filter->SetHighQuality(true);
  filter->Update();
  if (swaps)
  {
    *swaps = filter->GetNumberOfSwaps();
  }
  return filter->GetOutput();
}
} // namespace

TEST(SurfaceNetsImageToMeshFilter, FloatOutputMeshIsValidAsWrittenAndMatchesTheDoubleMesh)
{
  // With float coordinates the filter checks the points as they will be written
  // (rounded to float), so the float mesh is itself closed, manifold, outward and free
  // of self-intersections, and its points are the double mesh's, rounded.
  using FloatMesh = itk::Mesh<float, 3>;
  using DoubleMesh = itk::Mesh<double, 3>;
  for (const auto shape : { ME::PhantomShape::Sphere, ME::PhantomShape::TwoSpheres })
  {
    const Phantom p = MakePhantom(shape);
    for (const bool high : { false, true })
    {
      SCOPED_TRACE(std::string(ME::PhantomShapeName(shape)) + (high ? ", high quality" : ", SNERT"));
      auto single = itk::SurfaceNetsImageToMeshFilter<FloatImage, FloatMesh>::New();
      auto twice = itk::SurfaceNetsImageToMeshFilter<FloatImage, DoubleMesh>::New();
      single->SetInput(p.image);
      twice->SetInput(p.image);
      single->SetInsideIsAboveIsoValue(false);
      twice->SetInsideIsAboveIsoValue(false);
      single->SetHighQuality(high);
      twice->SetHighQuality(high);
      single->Update();
      twice->Update();
      const FloatMesh *  f = single->GetOutput();
      const DoubleMesh * d = twice->GetOutput();
      const auto         q = Measure(f);
      EXPECT_TRUE(q.IsValidClosedSurface()) << Text(q);
      EXPECT_EQ(q.selfIntersectingPairs, 0); // checked, and none
      ASSERT_EQ(f->GetNumberOfPoints(), d->GetNumberOfPoints());
      ASSERT_EQ(f->GetNumberOfCells(), d->GetNumberOfCells());
      std::size_t same = 0;
      for (itk::IdentifierType i = 0; i < f->GetNumberOfPoints(); ++i)
      {
        const auto a = f->GetPoint(i);
        const auto b = d->GetPoint(i);
        double     largest = 0.0;
        for (unsigned int k = 0; k < 3; ++k)
        {
          largest = std::max(largest, std::abs(static_cast<double>(a[k]) - b[k]));
        }
        same += largest <= 1e-5 ? 1 : 0; // float rounding at 40 mm: 4e-6 mm
      }
      // A node the checks pulled back in one mesh and not the other may differ.
      EXPECT_GE(static_cast<double>(same), 0.999 * static_cast<double>(f->GetNumberOfPoints()));
    }
  }
}

TEST(SurfaceNetsImageToMeshFilter, HighQualitySphereIsNearlyEquilateralAndStillAccurate)
{
  const Phantom      p = MakePhantom(ME::PhantomShape::Sphere); // radius 19.2 voxels
  itk::SizeValueType swaps = 0;
  auto               mesh = ExtractHighQuality(p.image.GetPointer(), &swaps);
  const auto         q = Measure(mesh.GetPointer());
  EXPECT_TRUE(q.IsValidClosedSurface()) << Text(q);
  EXPECT_EQ(q.eulerCharacteristic, 2);
  EXPECT_GT(swaps, 0u);
  EXPECT_GE(q.qArea.mean, 0.97);
  EXPECT_GE(q.qAngle.mean, 0.80);
  EXPECT_LE(q.fractionQAngleBelow03, 1e-4); // the issue allows 0.1 %; measured: none
  EXPECT_GE(q.fractionValence6, 0.90);
  const auto d = Distance(mesh.GetPointer(), p.surface);
  EXPECT_LE(d.vertices.mean, 0.02);
  EXPECT_LT(d.vertices.maximum, 0.05);
}

TEST(SurfaceNetsImageToMeshFilter, HighQualityBeatsSnertOnCreasesAndHandlesKeepingTopology)
{
  for (auto shape : { ME::PhantomShape::TwoSpheres, ME::PhantomShape::Torus })
  {
    SCOPED_TRACE(ME::PhantomShapeName(shape));
    const Phantom p = MakePhantom(shape);
    const auto    plain = Measure(Extract(p.image.GetPointer(), 0.0, false).GetPointer());
    auto          mesh = ExtractHighQuality(p.image.GetPointer());
    const auto    q = Measure(mesh.GetPointer());
    EXPECT_TRUE(q.IsValidClosedSurface()) << Text(q);
    EXPECT_EQ(q.eulerCharacteristic, plain.eulerCharacteristic);
    EXPECT_EQ(q.connectedComponents, plain.connectedComponents);
    EXPECT_GT(q.qAngle.mean, plain.qAngle.mean + 0.12);
    EXPECT_GT(q.qArea.mean, plain.qArea.mean + 0.04);
    EXPECT_LT(q.fractionQAngleBelow03, plain.fractionQAngleBelow03 + 1e-12);
    // Every node, crease nodes included, is still on the surface.
    const auto d = Distance(mesh.GetPointer(), p.surface);
    EXPECT_LE(d.vertices.mean, 0.02);
    EXPECT_LT(d.vertices.maximum, 0.35);
  }
}

TEST(SurfaceNetsImageToMeshFilter, HighQualityLetsNodesLeaveTheirCellsByHalfAVoxelForFewerSlivers)
{
  // The default HighQualityCellDilation (0.5 voxel) against 0.25 and 0 on the narrow
  // cleft, where the surfaces of the cleft's two sides pin nodes near their cells'
  // faces. Measured: mean q_angle 0.6596, 0.6289 and lower; triangles below q_angle 0.3
  // none, 0.0125 %; mean vertex distance to the exact surface 0.0103, 0.0105 mm.
  const Phantom p = MakePhantom(ME::PhantomShape::NarrowCleft);
  auto          run = [&p](double dilation) {
    return ExtractPhantom(p, [dilation](auto * filter) {
      filter->SetHighQuality(true);
      if (dilation >= 0.0)
      {
        filter->SetHighQualityCellDilation(dilation);
      }
    });
  };
  EXPECT_EQ(itk::SurfaceNetsImageToMeshFilter<FloatImage>::New()->GetHighQualityCellDilation(), 0.5);
  const auto byDefault = run(-1.0);
  const auto q = Measure(byDefault.GetPointer());
  const auto quarter = Measure(run(0.25).GetPointer());
  const auto inCell = Measure(run(0.0).GetPointer());
  for (const auto * r : { &q, &quarter, &inCell })
  {
    EXPECT_TRUE(r->IsValidClosedSurface()) << Text(*r);
    EXPECT_EQ(r->eulerCharacteristic, 2); // the cleft stays open
  }
  EXPECT_GT(q.qAngle.mean, quarter.qAngle.mean + 0.02);
  EXPECT_GT(quarter.qAngle.mean, inCell.qAngle.mean);
  EXPECT_EQ(q.fractionQAngleBelow03, 0.0);
  EXPECT_GT(quarter.fractionQAngleBelow03, 0.0);
  EXPECT_LE(Distance(byDefault.GetPointer(), p.surface).vertices.mean, 0.0125); // voxels (1 mm)
}

TEST(SurfaceNetsImageToMeshFilter, HighQualityDoesNotLetAFoldCloseOntoItself)
{
  // A 5^3 patch of smoothed noise (from a random volume on which the high-quality
  // mode once failed) in a background of -1. The voxel (4, 4, 4) is the only inside
  // voxel of its 6-neighbourhood; its 12 triangles form a double cone: two nodes
  // share the same 1-ring, and the mesh folds (normals more than 120 degrees apart)
  // at the ring's edges. SNERT keeps the two nodes in their own cells; with cells
  // dilated, the relaxation on the triangles pulled both to one point and the
  // component closed onto itself: no volume, its 12 triangles inside out by the ray
  // test, though no pair of triangles crossed. A fold may open, not close further.
  struct Voxel
  {
    int   x, y, z;
    float value;
  };
  const Voxel patch[] = {
    { 2, 2, 0, 0.499894887f },   { 3, 2, 0, 0.243303835f },   { 2, 3, 0, -0.306714207f }, { 3, 3, 0, -0.163112268f },
    { 1, 1, 1, 0.662257612f },   { 2, 1, 1, -0.429558992f },  { 3, 1, 1, 0.219578579f },  { 1, 2, 1, -0.326408207f },
    { 2, 2, 1, -0.0885649025f }, { 3, 2, 1, -0.456804037f },  { 4, 2, 1, 0.17164351f },   { 1, 3, 1, -0.179137766f },
    { 2, 3, 1, 0.0557733104f },  { 3, 3, 1, -0.269171566f },  { 2, 4, 1, -0.526567817f }, { 3, 4, 1, 0.298573285f },
    { 1, 0, 2, 0.394890577f },   { 0, 1, 2, 0.0882567689f },  { 1, 1, 2, 0.0484136902f }, { 2, 1, 2, -0.276257545f },
    { 3, 1, 2, -0.0409125686f }, { 1, 2, 2, -0.124542743f },  { 2, 2, 2, 0.245963544f },  { 3, 2, 2, 0.0826785788f },
    { 4, 2, 2, -0.235532939f },  { 1, 3, 2, 0.28932938f },    { 2, 3, 2, -0.14629595f },  { 3, 3, 2, -0.156968966f },
    { 4, 3, 2, -0.480757296f },  { 2, 4, 2, 0.362022996f },   { 3, 4, 2, -0.371320367f }, { 1, 0, 3, 0.384943694f },
    { 2, 0, 3, 0.106634721f },   { 0, 1, 3, 0.382190347f },   { 1, 1, 3, 0.15387471f },   { 2, 1, 3, -0.263362437f },
    { 3, 1, 3, 0.0586259812f },  { 0, 2, 3, -0.0945089236f }, { 1, 2, 3, -0.419652075f }, { 2, 2, 3, 0.0796070099f },
    { 3, 2, 3, 0.313506067f },   { 2, 3, 3, -0.315533161f },  { 3, 3, 3, 0.251280755f },  { 1, 0, 4, -0.365097493f },
    { 1, 1, 4, 0.269346446f },   { 2, 1, 4, 0.62721318f },    { 2, 2, 4, -0.155629173f }, { 4, 2, 4, -0.649866164f },
  };
  auto image = MakeImage<FloatImage>(9, 9, 9, -1.0f);
  for (const auto & v : patch)
  {
    image->SetPixel({ { v.x + 2, v.y + 2, v.z + 2 } }, v.value);
  }
  constexpr double iso = 0.203541;
  const auto       snert = Measure(Extract(image.GetPointer(), iso, true).GetPointer());
  ASSERT_TRUE(snert.IsValidClosedSurface()) << Text(snert);
  for (unsigned int threads : { 1u, 2u })
  {
    auto filter = itk::SurfaceNetsImageToMeshFilter<FloatImage>::New();
    filter->SetInput(image);
    filter->SetIsoValue(iso);
    filter->SetHighQuality(true);
    filter->SetNumberOfWorkUnits(threads);
    filter->Update();
    const auto high = Measure(filter->GetOutput());
    EXPECT_TRUE(high.IsValidClosedSurface()) << threads << " threads\n" << Text(high);
    EXPECT_EQ(high.invertedTrianglesVersusOutward, 0);
    EXPECT_EQ(high.connectedComponents, snert.connectedComponents);
    EXPECT_EQ(high.eulerCharacteristic, snert.eulerCharacteristic);
  }
}

TEST(SurfaceNetsImageToMeshFilter, HighQualityRoundsEndWhenTheSwapsHaveConverged)
{
  // Two spheres: the rounds swap 345, 59 and 3 edges of 14,544 triangles. By default
  // (fewer than 0.1 % of the triangles) the third round ends them; with a fraction
  // of 0 only a round without a swap does, one round later. Both meshes are valid and
  // of high quality.
  const Phantom p = MakePhantom(ME::PhantomShape::TwoSpheres);
  auto          run = [&p](double fraction, unsigned int & rounds) {
    auto filter = itk::SurfaceNetsImageToMeshFilter<FloatImage>::New();
    filter->SetInput(p.image);
    filter->SetInsideIsAboveIsoValue(false);
    filter->SetHighQuality(true);
    if (fraction >= 0.0)
    {
      filter->SetConvergedSwapFraction(fraction);
    }
    filter->Update();
    rounds = filter->GetNumberOfRoundsPerformed();
    return Measure(filter->GetOutput());
  };
  unsigned int byDefault = 0;
  unsigned int untilNoSwap = 0;
  const auto   converged = run(-1.0, byDefault);
  const auto   all = run(0.0, untilNoSwap);
  EXPECT_EQ(byDefault, 2u);
  EXPECT_EQ(untilNoSwap, 3u);
  for (const auto & q : { converged, all })
  {
    EXPECT_TRUE(q.IsValidClosedSurface()) << Text(q);
    EXPECT_GE(q.qArea.mean, 0.98);
    EXPECT_GE(q.qAngle.mean, 0.85);
  }

  auto filter = itk::SurfaceNetsImageToMeshFilter<FloatImage>::New();
  EXPECT_DOUBLE_EQ(filter->GetConvergedSwapFraction(), 0.001);
  filter->SetInput(p.image);
  filter->SetHighQuality(true);
  for (const double bad : { -0.1, 1.5, std::numeric_limits<double>::quiet_NaN() })
  {
    filter->SetConvergedSwapFraction(bad);
    const std::string message = ExceptionDescription([&] { filter->Update(); });
    EXPECT_NE(message.find("ConvergedSwapFraction must be in [0, 1]"), std::string::npos)
      << "ConvergedSwapFraction " << bad << ": " << message;
  }
}

TEST(SurfaceNetsImageToMeshFilter, HighQualityHoldsInPhysicalSpaceOnAnisotropicVoxels)
{
  ME::PhantomGrid grid = ME::DefaultPhantomGrid(ME::PhantomShape::Sphere);
  // Anisotropy of 1.1/0.9; beyond about 1.2 one node per cell cannot be spaced
  // evenly in physical space (documented in the filter).
  grid.size[0] = 72;
  grid.size[1] = 64;
  grid.size[2] = 58;
  grid.spacing[0] = 0.9;
  grid.spacing[1] = 1.0;
  grid.spacing[2] = 1.1;
  const Phantom p = MakePhantom(ME::PhantomShape::Sphere, grid);
  auto          mesh = ExtractHighQuality(p.image.GetPointer());
  const auto    q = Measure(mesh.GetPointer());
  EXPECT_TRUE(q.IsValidClosedSurface()) << Text(q);
  EXPECT_GE(q.qArea.mean, 0.97);
  EXPECT_GE(q.qAngle.mean, 0.80);
  EXPECT_LE(q.fractionQAngleBelow03, 0.001);
  EXPECT_LE(Distance(mesh.GetPointer(), p.surface).vertices.mean, 0.02); // mm
}

namespace
{
/** The sphere phantom on 1 x 1 x 2 mm voxels (the default grid's extent). */
Phantom
SphereOnAnisotropicVoxels()
{
  ME::PhantomGrid grid = ME::DefaultPhantomGrid(ME::PhantomShape::Sphere);
  grid.size[2] /= 2;
  grid.spacing[2] = 2.0;
  return MakePhantom(ME::PhantomShape::Sphere, grid);
}
} // namespace

TEST(SurfaceNetsImageToMeshFilter, ResamplingToIsotropicVoxelsGivesAnisotropicImagesTheIsotropicFigures)
{
  // One node per cell spaces the nodes as the voxels: on 1 x 1 x 2 mm voxels the
  // high-quality mode's triangles are stretched along z (measured q_angle 0.726).
  // Resampled to 1 mm cubes first, the mesh meets the isotropic sphere's figures
  // (measured q_area 0.989, q_angle 0.856, none below 0.3, 0.017 mm).
  const Phantom p = SphereOnAnisotropicVoxels();
  auto          run = [&p](bool resample, bool high) {
    return ExtractPhantom(p, [=](auto * filter) {
      filter->SetHighQuality(high);
      filter->SetResampleToIsotropicVoxels(resample);
    });
  };
  const auto stretched = run(false, true);
  const auto cubic = run(true, true);
  const auto s = Measure(stretched.GetPointer());
  const auto q = Measure(cubic.GetPointer());
  EXPECT_TRUE(s.IsValidClosedSurface()) << Text(s);
  EXPECT_LT(s.qAngle.mean, 0.80);
  EXPECT_TRUE(q.IsValidClosedSurface()) << Text(q);
  EXPECT_EQ(q.eulerCharacteristic, 2);
  EXPECT_GE(q.qArea.mean, 0.97);
  EXPECT_GE(q.qAngle.mean, 0.80);
  EXPECT_LE(q.fractionQAngleBelow03, 0.001);
  // Half the cell height along z: 1.50 times the triangles (measured; none more where
  // the surface faces along z, twice where it faces sideways).
  EXPECT_GT(q.numberOfTriangles, 1.4 * s.numberOfTriangles);
  EXPECT_LE(Distance(cubic.GetPointer(), p.surface).vertices.mean, 0.02); // mm = voxels of the new grid
  // Plain SNERT on the resampled grid is as accurate.
  const auto snert = run(true, false);
  EXPECT_TRUE(Measure(snert.GetPointer()).IsValidClosedSurface());
  EXPECT_LE(Distance(snert.GetPointer(), p.surface).vertices.mean, 0.03);
}

TEST(SurfaceNetsImageToMeshFilter, ResamplingToIsotropicVoxelsTakesLabelImagesByNearestNeighbour)
{
  const Phantom p = SphereOnAnisotropicVoxels();
  const auto    mask = PhantomMask(p);
  // A label image as the input (Gibson's binary net, SNA).
  auto labels = itk::SurfaceNetsImageToMeshFilter<MaskImage>::New();
  labels->SetInput(mask);
  labels->SetClassifyByLabel(true);
  labels->SetResampleToIsotropicVoxels(true);
  labels->Update();
  const auto l = Measure(labels->GetOutput());
  EXPECT_TRUE(l.IsValidClosedSurface()) << Text(l);
  EXPECT_EQ(l.eulerCharacteristic, 2);
  EXPECT_LE(Distance(labels->GetOutput(), p.surface).vertices.mean, 0.5); // the mask's staircase
  // A segmentation relaxed toward the greyscale iso-surface, both resampled.
  auto both = itk::SurfaceNetsImageToMeshFilter<FloatImage>::New();
  both->SetInput(p.image);
  both->SetLabelImage(mask);
  both->SetInsideIsAboveIsoValue(false);
  both->SetResampleToIsotropicVoxels(true);
  both->SetHighQuality(true);
  both->Update();
  const auto b = Measure(both->GetOutput());
  EXPECT_TRUE(b.IsValidClosedSurface()) << Text(b);
  EXPECT_GE(b.qAngle.mean, 0.80);
  EXPECT_LE(Distance(both->GetOutput(), p.surface).vertices.mean, 0.03);
  // A label image of another grid is refused before either image is resampled.
  both->SetLabelImage(MakeImage<MaskImage>(8, 8, 8, 1));
  const std::string message = ExceptionDescription([&] { both->Update(); });
  EXPECT_NE(message.find("LabelImage must have the input's grid"), std::string::npos) << message;
}

TEST(SurfaceNetsImageToMeshFilter, ResamplingToIsotropicVoxelsLeavesCubicVoxelsAlone)
{
  const Phantom p = MakePhantom(ME::PhantomShape::Ellipsoid);
  auto          run = [&p](bool resample) {
    return ME::MakeIndexedTriangleMesh(
      *ExtractPhantom(p, [resample](auto * filter) { filter->SetResampleToIsotropicVoxels(resample); }));
  };
  const auto off = run(false);
  const auto on = run(true);
  EXPECT_EQ(off.triangles, on.triangles);
  EXPECT_EQ(off.points, on.points);
}

TEST(SurfaceNetsImageToMeshFilter, ResamplingToIsotropicVoxelsNamesTheInputsOwnNaNVoxel)
{
  // Interpolation would spread the NaN over its neighbours in the resampled grid: the
  // error names the voxel of the input.
  Phantom               p = SphereOnAnisotropicVoxels();
  FloatImage::IndexType nan = { { 5, 6, 7 } };
  p.image->SetPixel(nan, std::numeric_limits<float>::quiet_NaN());
  const std::string message = ExceptionDescription(
    [&p] { ExtractPhantom(p, [](auto * filter) { filter->SetResampleToIsotropicVoxels(true); }); });
  EXPECT_NE(message.find("NaN voxel at index [5, 6, 7]"), std::string::npos) << message;
}

TEST(SurfaceNetsImageToMeshFilter, HighQualityIsIdenticalForOneAndManyThreads)
{
  const Phantom p = MakePhantom(ME::PhantomShape::Ellipsoid);
  auto          run = [&p](unsigned int workUnits) {
    auto filter = itk::SurfaceNetsImageToMeshFilter<FloatImage, MeshType>::New();
    filter->SetInput(p.image);
    filter->SetInsideIsAboveIsoValue(false);
    filter->SetHighQuality(true);
    filter->SetNumberOfWorkUnits(workUnits);
    filter->Update();
    return ME::MakeIndexedTriangleMesh(*filter->GetOutput());
  };
  const auto one = run(1);
  const auto many = run(5);
  EXPECT_EQ(one.triangles, many.triangles);
  EXPECT_EQ(one.points, many.points);
}

// Real data, when ../shared/data (next to the project, never part of it) is present:
// the small VTK head CT, read from its raw file (its NRRD header gives both 'space:'
// and 'spacings:', which ITK's NRRD reader refuses). Bone above 1150 (HU + 1024).
TEST(SurfaceNetsImageToMeshFilter, RealHeadCTGivesValidSurfacesAndHighQualityBeatsSnert)
{
  std::string where;
  const auto  image = MeshExtractionTest::ReadSharedHeadCT(where);
  if (image.IsNull())
  {
    GTEST_SKIP() << "../shared/data/ct_headsq is not next to the project (" << where << "): real-data test skipped";
  }
  using ShortImage = itk::Image<short, 3>;

  auto snert = itk::SurfaceNetsImageToMeshFilter<ShortImage>::New();
  snert->SetInput(image);
  snert->SetIsoValue(1150);
  snert->Update();
  const auto plain = Measure(snert->GetOutput());
  EXPECT_TRUE(plain.IsValidClosedSurface()) << Text(plain);
  EXPECT_EQ(plain.selfIntersectingPairs, 0);
  EXPECT_GT(plain.numberOfTriangles, 50000);

  auto high = itk::SurfaceNetsImageToMeshFilter<ShortImage>::New();
  high->SetInput(image);
  high->SetIsoValue(1150);
  high->SetHighQuality(true);
  high->Update();
  const auto q = Measure(high->GetOutput());
  EXPECT_TRUE(q.IsValidClosedSurface()) << Text(q);
  EXPECT_EQ(q.selfIntersectingPairs, 0);
  EXPECT_EQ(q.eulerCharacteristic, plain.eulerCharacteristic);
  EXPECT_GT(q.qArea.mean, plain.qArea.mean + 0.05);  // measured 0.886 vs 0.796
  EXPECT_GT(q.qAngle.mean, plain.qAngle.mean + 0.1); // measured 0.563 vs 0.424
  EXPECT_LT(q.fractionQAngleBelow03, 0.5 * plain.fractionQAngleBelow03);
}
