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
#ifndef itkMeshExtractionSurfaceNetsClassification_h
#define itkMeshExtractionSurfaceNetsClassification_h

#include "itkMeshExtractionParallel.h"
#include "itkMeshExtractionSurfaceNets.h"
#include "itkImage.h"
#include "itkMath.h"

#include <atomic>
#include <cmath>
#include <limits>
#include <type_traits>

namespace itk
{
namespace MeshExtraction
{
/** What the classification pass saw of the image. */
struct SurfaceNetsClassificationStatistics
{
  double       minimum{ std::numeric_limits<double>::max() };
  double       maximum{ std::numeric_limits<double>::lowest() };
  std::size_t  insideVoxels{ 0 };
  bool         foundNaN{ false };
  std::int64_t nanVoxel[3]{ 0, 0, 0 };
};

/** Stage 1 of SurfaceNets: find the surface cells of an image.
 *
 * A cell is the cube between 8 neighbouring voxel centres; cells run from -1 to
 * N-1 along each axis, so that voxels outside the image count as outside and
 * objects touching the image border are closed. `inside(pixel)` classifies a voxel.
 * The image is read one z-slab per work unit, one pair of slices at a time, and a
 * row of cells is only visited between the first and last inside voxel of its four
 * voxel rows; memory beyond the image is two slices per work unit plus the surface
 * cells. Cells come out sorted by (z, y, x) whatever the number of threads.
 * \ingroup MeshExtraction */
template <typename TImage, typename TInside>
SurfaceNetsClassificationStatistics
ClassifySurfaceCells(const TImage * image, TInside inside, SurfaceNet & net, unsigned int numberOfWorkUnits = 0)
{
  static_assert(TImage::ImageDimension == 3, "SurfaceNets works on 3-D images");
  using PixelType = typename TImage::PixelType;
  const auto         region = image->GetBufferedRegion();
  const std::int64_t nx = static_cast<std::int64_t>(region.GetSize(0));
  const std::int64_t ny = static_cast<std::int64_t>(region.GetSize(1));
  const std::int64_t nz = static_cast<std::int64_t>(region.GetSize(2));
  net.size = { { nx, ny, nz } };
  const PixelType * buffer = image->GetBufferPointer();

  // Spread a column of 4 inside bits (y0z0, y1z0, y0z1, y1z1) onto corner bits 0, 2, 4, 6.
  std::uint8_t spread[16];
  for (unsigned int c = 0; c < 16; ++c)
  {
    spread[c] = static_cast<std::uint8_t>((c & 1u) | ((c & 2u) << 1) | ((c & 4u) << 2) | ((c & 8u) << 3));
  }

  const std::size_t                     numberOfLayers = static_cast<std::size_t>(nz + 1); // cell layers z = -1 .. nz-1
  const std::size_t                     layersPerBlock = std::max<std::size_t>(1, numberOfLayers / 64);
  const std::size_t                     numberOfBlocks = (numberOfLayers + layersPerBlock - 1) / layersPerBlock;
  std::vector<std::vector<SurfaceCell>> found(numberOfBlocks);
  std::vector<SurfaceNetsClassificationStatistics> statistics(numberOfBlocks);

  ParallelForBlocks(
    numberOfLayers,
    layersPerBlock,
    [&](std::size_t begin, std::size_t end, std::size_t block) {
      SurfaceNetsClassificationStatistics & stats = statistics[block];
      // A slice of inside flags and, per voxel row, the first and last inside x.
      struct Slice
      {
        std::int64_t              z{ std::numeric_limits<std::int64_t>::min() };
        std::vector<std::uint8_t> flags;
        std::vector<std::int64_t> first;
        std::vector<std::int64_t> last;
      };
      Slice slices[2];
      auto  fill = [&](Slice & s, std::int64_t z) {
        s.z = z;
        s.flags.assign(static_cast<std::size_t>(nx * ny), 0);
        s.first.assign(static_cast<std::size_t>(ny), -1);
        s.last.assign(static_cast<std::size_t>(ny), -2);
        if (z < 0 || z >= nz)
        {
          return;
        }
        // Each slice is read by the layers below and above it; count it once, in
        // the layer whose upper slice it is.
        const bool count = static_cast<std::int64_t>(begin) - 1 < z;
        for (std::int64_t y = 0; y < ny; ++y)
        {
          const PixelType * row = buffer + (z * ny + y) * nx;
          std::uint8_t *    flags = s.flags.data() + y * nx;
          // Branch-free passes the compiler vectorizes: the inside flags, then (floating
          // point) whether the row has a NaN, then the first and last inside voxel and
          // the statistics. A NaN voxel is never inside.
          std::int64_t inRow = 0;
          for (std::int64_t x = 0; x < nx; ++x)
          {
            const std::uint8_t in = inside(row[x]) ? 1 : 0;
            flags[x] = in;
            inRow += in;
          }
          if constexpr (std::is_floating_point<PixelType>::value)
          {
            int nan = 0;
            for (std::int64_t x = 0; x < nx; ++x)
            {
              nan |= (row[x] != row[x]) ? 1 : 0;
            }
            if (nan)
            {
              for (std::int64_t x = 0; x < nx; ++x)
              {
                if (std::isnan(row[x]))
                {
                  if (!stats.foundNaN)
                  {
                    stats.foundNaN = true;
                    stats.nanVoxel[0] = x;
                    stats.nanVoxel[1] = y;
                    stats.nanVoxel[2] = z;
                  }
                  inRow -= flags[x];
                  flags[x] = 0;
                }
              }
            }
          }
          if (inRow > 0)
          {
            std::int64_t first = 0;
            while (flags[first] == 0)
            {
              ++first;
            }
            std::int64_t last = nx - 1;
            while (flags[last] == 0)
            {
              --last;
            }
            s.first[y] = first;
            s.last[y] = last;
          }
          if (count)
          {
            // NaN compares false, so it changes neither extreme.
            PixelType lowest = row[0];
            PixelType highest = row[0];
            for (std::int64_t x = 0; x < nx; ++x)
            {
              lowest = row[x] < lowest ? row[x] : lowest;
              highest = row[x] > highest ? row[x] : highest;
            }
            if (!(lowest != lowest)) // a row that starts with NaN: fall back
            {
              stats.minimum = std::min(stats.minimum, static_cast<double>(lowest));
              stats.maximum = std::max(stats.maximum, static_cast<double>(highest));
            }
            else
            {
              for (std::int64_t x = 0; x < nx; ++x)
              {
                if (!(row[x] != row[x]))
                {
                  stats.minimum = std::min(stats.minimum, static_cast<double>(row[x]));
                  stats.maximum = std::max(stats.maximum, static_cast<double>(row[x]));
                }
              }
            }
            stats.insideVoxels += static_cast<std::size_t>(inRow);
          }
        }
      };
      std::vector<SurfaceCell> & cells = found[block];
      for (std::size_t layer = begin; layer < end; ++layer)
      {
        const std::int64_t z = static_cast<std::int64_t>(layer) - 1; // cell layer between slices z and z+1
        Slice *            lower = slices[0].z == z ? &slices[0] : (slices[1].z == z ? &slices[1] : nullptr);
        if (lower == nullptr)
        {
          fill(slices[0], z);
          lower = &slices[0];
        }
        Slice * upper = lower == &slices[0] ? &slices[1] : &slices[0];
        fill(*upper, z + 1);
        for (std::int64_t y = -1; y < ny; ++y)
        {
          // The four voxel rows (y, z), (y+1, z), (y, z+1), (y+1, z+1).
          const std::uint8_t * rows[4] = { nullptr, nullptr, nullptr, nullptr };
          std::int64_t         xFirst = std::numeric_limits<std::int64_t>::max();
          std::int64_t         xLast = -2;
          const Slice *        slicesOfRow[4] = { lower, lower, upper, upper };
          const std::int64_t   ys[4] = { y, y + 1, y, y + 1 };
          for (unsigned int r = 0; r < 4; ++r)
          {
            const Slice & s = *slicesOfRow[r];
            if (ys[r] < 0 || ys[r] >= ny || s.z < 0 || s.z >= nz || s.first[ys[r]] < 0)
            {
              continue;
            }
            rows[r] = s.flags.data() + ys[r] * nx;
            xFirst = std::min(xFirst, s.first[ys[r]]);
            xLast = std::max(xLast, s.last[ys[r]]);
          }
          if (xLast < 0)
          {
            continue; // no inside voxel: no surface cell in this row
          }
          auto column = [&](std::int64_t x) -> unsigned int {
            if (x < 0 || x >= nx)
            {
              return 0;
            }
            unsigned int c = 0;
            for (unsigned int r = 0; r < 4; ++r)
            {
              c |= (rows[r] != nullptr && rows[r][x]) ? (1u << r) : 0u;
            }
            return c;
          };
          unsigned int previous = column(xFirst - 1);
          for (std::int64_t x = xFirst - 1; x <= xLast; ++x)
          {
            const unsigned int next = column(x + 1);
            const auto         configuration = static_cast<std::uint8_t>(spread[previous] | (spread[next] << 1));
            if (configuration != 0 && configuration != 255)
            {
              cells.push_back({ static_cast<std::int32_t>(x),
                                static_cast<std::int32_t>(y),
                                static_cast<std::int32_t>(z),
                                configuration,
                                0 });
            }
            previous = next;
          }
        }
      }
    },
    numberOfWorkUnits);

  SurfaceNetsClassificationStatistics total;
  std::size_t                         count = 0;
  for (std::size_t b = 0; b < numberOfBlocks; ++b)
  {
    count += found[b].size();
    total.minimum = std::min(total.minimum, statistics[b].minimum);
    total.maximum = std::max(total.maximum, statistics[b].maximum);
    total.insideVoxels += statistics[b].insideVoxels;
    if (statistics[b].foundNaN && !total.foundNaN)
    {
      total.foundNaN = true;
      std::copy(statistics[b].nanVoxel, statistics[b].nanVoxel + 3, total.nanVoxel);
    }
  }
  net.cells.clear();
  net.cells.reserve(count);
  for (auto & f : found)
  {
    net.cells.insert(net.cells.end(), f.begin(), f.end());
    std::vector<SurfaceCell>().swap(f);
  }
  return total;
}

} // namespace MeshExtraction
} // namespace itk

#endif
