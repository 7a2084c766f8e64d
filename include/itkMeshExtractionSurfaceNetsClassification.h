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

#include <algorithm>
#include <atomic>
#if defined(__SSE2__)
#  include <emmintrin.h>
#endif
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
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

/** \brief Which voxels are inside: low <= v <= high, compared in the pixel type.
 *
 * The bounds are the exact pixel-type equivalents of a double iso-value or label
 * (`static_cast<double>(v) >= iso` holds exactly when `v >= low` does), so the test
 * is one or two comparisons the compiler vectorizes, with no conversion per voxel.
 * A NaN voxel is never inside. \ingroup MeshExtraction */
template <typename TPixel>
struct SurfaceNetsVoxelRange
{
  TPixel low;
  TPixel high; ///< high < low: no voxel is inside (Never)

  bool
  operator()(TPixel v) const
  {
    return (v >= low) & (v <= high); // no branch: vectorizes
  }

  /** The voxels >= iso (aboveIsInside) or <= iso. */
  static SurfaceNetsVoxelRange
  FromIsoValue(double iso, bool aboveIsInside)
  {
    using Limits = std::numeric_limits<TPixel>;
    SurfaceNetsVoxelRange r{ Limits::lowest(), Limits::max() };
    if (std::isnan(iso))
    {
      return Never();
    }
    if constexpr (std::is_floating_point<TPixel>::value)
    {
      // The pixel-type value nearest to iso on the inside's side; infinities keep
      // every finite voxel on the correct side.
      TPixel t = static_cast<TPixel>(iso);
      if (aboveIsInside)
      {
        if (static_cast<double>(t) < iso)
        {
          t = std::nextafter(t, Limits::infinity());
        }
        r.low = t;
        r.high = Limits::infinity();
      }
      else
      {
        if (static_cast<double>(t) > iso)
        {
          t = std::nextafter(t, -Limits::infinity());
        }
        r.low = -Limits::infinity();
        r.high = t;
      }
    }
    else
    {
      const double lowest = static_cast<double>(Limits::lowest());
      const double highest = static_cast<double>(Limits::max());
      if (aboveIsInside)
      {
        const double t = std::ceil(iso);
        if (t > highest)
        {
          return Never();
        }
        r.low = t <= lowest ? Limits::lowest() : static_cast<TPixel>(t);
      }
      else
      {
        const double t = std::floor(iso);
        if (t < lowest)
        {
          return Never();
        }
        r.high = t >= highest ? Limits::max() : static_cast<TPixel>(t);
      }
    }
    return r;
  }

  /** The voxels equal to `label`. */
  static SurfaceNetsVoxelRange
  FromLabel(double label)
  {
    using Limits = std::numeric_limits<TPixel>;
    if (!(label >= static_cast<double>(Limits::lowest()) && label <= static_cast<double>(Limits::max())) ||
        static_cast<double>(static_cast<TPixel>(label)) != label)
    {
      return Never(); // no pixel value equals the label
    }
    return SurfaceNetsVoxelRange{ static_cast<TPixel>(label), static_cast<TPixel>(label) };
  }

  static SurfaceNetsVoxelRange
  Never()
  {
    using Limits = std::numeric_limits<TPixel>;
    return SurfaceNetsVoxelRange{ Limits::max(), Limits::lowest() };
  }
};

/** The index of the lowest set bit of a non-zero mask. */
inline unsigned int
CountTrailingZeros(unsigned int mask)
{
#if defined(__GNUC__) || defined(__clang__)
  return static_cast<unsigned int>(__builtin_ctz(mask));
#else
  unsigned int n = 0;
  while (!(mask & 1u))
  {
    mask >>= 1;
    ++n;
  }
  return n;
#endif
}

/** How far ahead of the voxels being classified the image is prefetched (bytes). The
 * image is read as one stream, yet the hardware's own prefetching leaves the row pass
 * waiting on memory: at 256^3 (float) on 1 thread the classification took 7.5-9.7 ms
 * without software prefetching and 4.8-5.9 ms with it 4 KiB ahead, one cache line per
 * 16 voxels (benchmark SurfaceNets/NetConstruction, counter classify_ms; a whole row's
 * prefetch at its start, 4, 8 or 16 KiB ahead, gave 5.5-8.3 ms). Rows of other pixel
 * types, which the compiler vectorises, get that whole-row prefetch. */
constexpr std::size_t SurfaceNetsPrefetchDistance = 4096;

/** One voxel row of the classification: flags[x] = inside(row[x]) (NaN never
 * inside), the number of inside voxels (added to `insideCount`), the row's
 * extremes ignoring NaN (unchanged when every voxel is NaN), and whether it holds
 * a NaN. Branch-free loops the compiler vectorizes for
 * integer pixels; float rows use SSE2 where the compiler offers it, since the
 * compiler may not reorder floating-point minimum/maximum reductions itself. */
template <bool TExtremes = true, typename TPixel, typename TInside>
void
ClassifySurfaceNetsRow(const TPixel * row,
                       std::int64_t   n,
                       TInside        inside,
                       std::uint8_t * flags,
                       std::size_t &  insideCount,
                       TPixel &       lowest,
                       TPixel &       highest,
                       bool &         hasNaN)
{
  std::int64_t x = 0;
#if defined(__SSE2__)
  if constexpr (std::is_same<TPixel, float>::value && std::is_same<TInside, SurfaceNetsVoxelRange<float>>::value)
  {
    const __m128  low = _mm_set1_ps(inside.low);
    const __m128  high = _mm_set1_ps(inside.high);
    const __m128i one = _mm_set1_epi8(1);
    // Two accumulators each, so that the minimum and maximum chains do not wait on
    // every load.
    __m128 lo[2] = { _mm_set1_ps(lowest), _mm_set1_ps(lowest) };
    __m128 hi[2] = { _mm_set1_ps(highest), _mm_set1_ps(highest) };
    __m128 nan = _mm_setzero_ps();
    // An iso-value has one finite bound: one comparison (false for NaN) suffices.
    const int bounds = (inside.low > -std::numeric_limits<float>::infinity() ? 1 : 0) |
                       (inside.high < std::numeric_limits<float>::infinity() ? 2 : 0);
    auto run = [&](auto inRange) {
      // Locals, not captured references, so that the stores to the flags cannot alias them.
      std::int64_t         i = x;
      const float * const  r = row;
      std::uint8_t * const f = flags;
      __m128               lo0 = lo[0], lo1 = lo[1], hi0 = hi[0], hi1 = hi[1], na = nan;
      __m128i              count = _mm_setzero_si128();
      for (; i + 16 <= n; i += 16)
      {
        PrefetchForReading(reinterpret_cast<std::uintptr_t>(r + i) + SurfaceNetsPrefetchDistance, 1);
        const __m128  v0 = _mm_loadu_ps(r + i);
        const __m128  v1 = _mm_loadu_ps(r + i + 4);
        const __m128  v2 = _mm_loadu_ps(r + i + 8);
        const __m128  v3 = _mm_loadu_ps(r + i + 12);
        const __m128i m0 = _mm_castps_si128(inRange(v0));
        const __m128i m1 = _mm_castps_si128(inRange(v1));
        const __m128i m2 = _mm_castps_si128(inRange(v2));
        const __m128i m3 = _mm_castps_si128(inRange(v3));
        if constexpr (TExtremes)
        {
          lo0 = _mm_min_ps(v0, lo0); // a NaN v leaves lo
          lo1 = _mm_min_ps(v1, lo1);
          lo0 = _mm_min_ps(v2, lo0);
          lo1 = _mm_min_ps(v3, lo1);
          hi0 = _mm_max_ps(v0, hi0);
          hi1 = _mm_max_ps(v1, hi1);
          hi0 = _mm_max_ps(v2, hi0);
          hi1 = _mm_max_ps(v3, hi1);
        }
        na = _mm_or_ps(_mm_or_ps(na, _mm_cmpunord_ps(v0, v1)), _mm_cmpunord_ps(v2, v3));
        const __m128i bytes = _mm_and_si128(_mm_packs_epi16(_mm_packs_epi32(m0, m1), _mm_packs_epi32(m2, m3)), one);
        _mm_storeu_si128(reinterpret_cast<__m128i *>(f + i), bytes);
        count = _mm_add_epi64(count, _mm_sad_epu8(bytes, _mm_setzero_si128()));
      }
      alignas(16) std::uint64_t counts[2];
      _mm_store_si128(reinterpret_cast<__m128i *>(counts), count);
      insideCount += static_cast<std::size_t>(counts[0] + counts[1]);
      x = i;
      lo[0] = lo0;
      lo[1] = lo1;
      hi[0] = hi0;
      hi[1] = hi1;
      nan = na;
    };
    if (bounds == 1)
    {
      run([low](__m128 v) { return _mm_cmpge_ps(v, low); });
    }
    else if (bounds == 2)
    {
      run([high](__m128 v) { return _mm_cmple_ps(v, high); });
    }
    else
    {
      run([low, high](__m128 v) { return _mm_and_ps(_mm_cmpge_ps(v, low), _mm_cmple_ps(v, high)); });
    }
    if constexpr (TExtremes)
    {
      alignas(16) float l[4];
      alignas(16) float h[4];
      _mm_store_ps(l, _mm_min_ps(lo[0], lo[1]));
      _mm_store_ps(h, _mm_max_ps(hi[0], hi[1]));
      for (unsigned int k = 0; k < 4; ++k)
      {
        lowest = l[k] < lowest ? l[k] : lowest;
        highest = h[k] > highest ? h[k] : highest;
      }
    }
    hasNaN = hasNaN || _mm_movemask_ps(nan) != 0;
  }
#endif
  if (x == 0)
  {
    // Rows the loops below classify alone (vectorised by the compiler): the part of
    // the image SurfaceNetsPrefetchDistance ahead, a row's length of it, at once.
    PrefetchForReading(reinterpret_cast<std::uintptr_t>(row) + SurfaceNetsPrefetchDistance,
                       static_cast<std::size_t>(n) * sizeof(TPixel));
  }
  std::size_t tail = 0;
  for (std::int64_t i = x; i < n; ++i)
  {
    flags[i] = static_cast<std::uint8_t>(inside(row[i]));
    tail += flags[i];
  }
  insideCount += tail;
  if constexpr (TExtremes)
  {
    for (std::int64_t i = x; i < n; ++i)
    {
      lowest = row[i] < lowest ? row[i] : lowest;
      highest = row[i] > highest ? row[i] : highest;
    }
  }
  if constexpr (std::is_floating_point<TPixel>::value)
  {
    int nan = 0;
    for (std::int64_t i = x; i < n; ++i)
    {
      nan |= (row[i] != row[i]) ? 1 : 0;
    }
    hasNaN = hasNaN || nan != 0;
  }
}

/** Stage 1 of SurfaceNets: find the surface cells of an image.
 *
 * A cell is the cube between 8 neighbouring voxel centres; cells run from -1 to
 * N-1 along each axis, so that voxels outside the image count as outside and
 * objects touching the image border are closed. `inside(pixel)` classifies a voxel
 * (a NaN voxel is never inside, and reported). The image is read one z-slab per
 * work unit, one slice at a time, in row passes without branches
 * (ClassifySurfaceNetsRow: vectorized by the compiler, or SSE2 for float rows); a
 * row of cells is only visited between the first and last inside voxel of its four
 * voxel rows (found 8 flags at a time), each cell from the 4-bit codes of its two
 * voxel columns. Memory beyond the image is two slices of flags per work unit plus
 * the surface cells. Cells come out sorted by (z, y, x) whatever the number of
 * threads. Without `extremes` the statistics' minimum and maximum are not computed
 * (left at their initial values), which saves a quarter of the float row pass: a
 * caller that needs them only when there is no surface asks again then.
 * \ingroup MeshExtraction */
template <typename TImage, typename TInside>
SurfaceNetsClassificationStatistics
ClassifySurfaceCells(const TImage * image,
                     TInside        inside,
                     SurfaceNet &   net,
                     unsigned int   numberOfWorkUnits = 0,
                     bool           extremes = true)
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

  // Rows of flags are padded: one zero byte before x = 0 and enough after nx - 1 for
  // 8-byte reads, so that cells x = -1 .. nx-1 read columns x and x + 1 without tests.
  const std::int64_t stride = ((nx + 2 + 7) / 8 + 1) * 8;
  const std::size_t  numberOfLayers = static_cast<std::size_t>(nz + 1); // cell layers z = -1 .. nz-1
  // A few blocks of layers per work unit: each block reads the slice below its first
  // layer again and sets up its own two slices of flags.
  unsigned int workUnits = numberOfWorkUnits != 0 ? numberOfWorkUnits : ThreadNumberOfWorkUnits();
  if (workUnits == 0)
  {
    workUnits = MultiThreaderBase::GetGlobalDefaultNumberOfThreads();
  }
  const std::size_t layersPerBlock = std::max<std::size_t>(1, numberOfLayers / (4 * std::size_t{ workUnits }));
  const std::size_t numberOfBlocks = (numberOfLayers + layersPerBlock - 1) / layersPerBlock;
  std::vector<std::vector<SurfaceCell>>            found(numberOfBlocks);
  std::vector<SurfaceNetsClassificationStatistics> statistics(numberOfBlocks);

  ParallelForBlocks(
    numberOfLayers,
    layersPerBlock,
    [&](std::size_t begin, std::size_t end, std::size_t block) {
      SurfaceNetsClassificationStatistics & stats = statistics[block];
      // A slice of inside flags and, per voxel row, the first and last inside x
      // (last < first: no inside voxel) and whether every voxel between them is
      // inside (one run). Row y of a slice starts at flags + (y+1) * stride + 1:
      // rows y = -1 and y = ny are all zero, as are slices beyond the image.
      struct Slice
      {
        std::int64_t              z{ std::numeric_limits<std::int64_t>::min() };
        std::vector<std::uint8_t> flags;
        std::vector<std::int64_t> first;
        std::vector<std::int64_t> last;
        std::vector<std::uint8_t> oneRun;
      };
      Slice slices[2];
      for (auto & s : slices)
      {
        s.flags.assign(static_cast<std::size_t>((ny + 2) * stride), 0);
        s.first.assign(static_cast<std::size_t>(ny + 2), 0);
        s.last.assign(static_cast<std::size_t>(ny + 2), -1);
        s.oneRun.assign(static_cast<std::size_t>(ny + 2), 1);
      }
      auto fill = [&](Slice & s, std::int64_t z) {
        const bool wasEmpty = s.z < 0 || s.z >= nz;
        s.z = z;
        if (z < 0 || z >= nz)
        {
          if (!wasEmpty)
          {
            std::fill(s.flags.begin(), s.flags.end(), std::uint8_t{ 0 });
            std::fill(s.first.begin(), s.first.end(), 0);
            std::fill(s.last.begin(), s.last.end(), -1);
            std::fill(s.oneRun.begin(), s.oneRun.end(), std::uint8_t{ 1 });
          }
          return;
        }
        // Each slice is read by the layers below and above it; count it once, in
        // the layer whose upper slice it is.
        const bool count = static_cast<std::int64_t>(begin) - 1 < z;
        for (std::int64_t y = 0; y < ny; ++y)
        {
          const PixelType * row = buffer + (z * ny + y) * nx;
          std::uint8_t *    flags = s.flags.data() + (y + 1) * stride + 1;
          // A row starting with NaN would poison the extremes: start from its first number.
          std::int64_t start = 0;
          if constexpr (std::is_floating_point<PixelType>::value)
          {
            while (start < nx && std::isnan(row[start]))
            {
              ++start;
            }
          }
          PixelType   lowest = row[std::min(start, nx - 1)];
          PixelType   highest = lowest;
          bool        hasNaN = false;
          std::size_t insideInRow = 0;
          if (extremes)
          {
            ClassifySurfaceNetsRow<true>(row, nx, inside, flags, insideInRow, lowest, highest, hasNaN);
          }
          else
          {
            ClassifySurfaceNetsRow<false>(row, nx, inside, flags, insideInRow, lowest, highest, hasNaN);
          }
          if (extremes && start < nx && count)
          {
            stats.minimum = std::min(stats.minimum, static_cast<double>(lowest));
            stats.maximum = std::max(stats.maximum, static_cast<double>(highest));
          }
          if (hasNaN)
          {
            for (std::int64_t x = 0; x < nx; ++x)
            {
              if (std::isnan(static_cast<double>(row[x])))
              {
                if (!stats.foundNaN)
                {
                  stats.foundNaN = true;
                  stats.nanVoxel[0] = x;
                  stats.nanVoxel[1] = y;
                  stats.nanVoxel[2] = z;
                }
                flags[x] = 0;
              }
            }
            insideInRow = static_cast<std::size_t>(std::count(flags, flags + nx, std::uint8_t{ 1 }));
          }
          // First and last inside voxel, 8 flags at a time (the padding is zero);
          // nothing to search in an empty or a full row.
          std::int64_t first = 0;
          std::int64_t last = -1;
          if (insideInRow == static_cast<std::size_t>(nx))
          {
            last = nx - 1;
          }
          else if (insideInRow > 0)
          {
            const std::int64_t words = (nx + 7) / 8;
            auto               word = [flags](std::int64_t w) {
              std::uint64_t value;
              std::memcpy(&value, flags + 8 * w, 8);
              return value;
            };
            std::int64_t w = 0;
            while (w < words && word(w) == 0)
            {
              ++w;
            }
            if (w < words)
            {
              first = 8 * w;
              while (flags[first] == 0)
              {
                ++first;
              }
              w = words - 1;
              while (word(w) == 0)
              {
                --w;
              }
              last = 8 * w + 7;
              while (flags[last] == 0)
              {
                --last;
              }
            }
          }
          s.first[y + 1] = first;
          s.last[y + 1] = last;
          s.oneRun[y + 1] = static_cast<std::uint8_t>(static_cast<std::int64_t>(insideInRow) == last - first + 1);
          if (count)
          {
            stats.insideVoxels += insideInRow;
          }
        }
      };
      std::vector<SurfaceCell>  cells = std::move(found[block]);
      std::vector<std::uint8_t> columns(static_cast<std::size_t>(stride), 0);
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
          // The four voxel rows (y, z), (y+1, z), (y, z+1), (y+1, z+1), padded rows
          // of zeros beyond the image.
          const Slice *        slicesOfRow[4] = { lower, lower, upper, upper };
          const std::int64_t   ys[4] = { y, y + 1, y, y + 1 };
          const std::uint8_t * rows[4];
          std::int64_t         xFirst = std::numeric_limits<std::int64_t>::max();
          std::int64_t         xLast = -1;
          // Where all four rows are one run each: the columns in all four runs,
          // [allFirst, allLast], whose cells between are inside the object.
          std::int64_t allFirst = -1;
          std::int64_t allLast = std::numeric_limits<std::int64_t>::max();
          bool         runs = true;
          for (unsigned int r = 0; r < 4; ++r)
          {
            const Slice &      s = *slicesOfRow[r];
            const std::int64_t first = s.first[ys[r] + 1];
            const std::int64_t last = s.last[ys[r] + 1];
            rows[r] = s.flags.data() + (ys[r] + 1) * stride + 1;
            if (last >= first)
            {
              xFirst = std::min(xFirst, first);
              xLast = std::max(xLast, last);
            }
            runs = runs && last >= first && s.oneRun[ys[r] + 1];
            allFirst = std::max(allFirst, first);
            allLast = std::min(allLast, last);
          }
          if (xLast < 0)
          {
            continue; // no inside voxel: no surface cell in this row
          }
          std::uint8_t * code = columns.data() + 1; // code[x], x >= -1
          // Cell x (columns x, x+1) is a surface cell unless its 8 corners agree.
          auto addCell = [&](std::int64_t x) {
            const unsigned int a = code[x];
            const unsigned int b = code[x + 1];
            cells.push_back({ static_cast<std::int32_t>(x),
                              static_cast<std::int32_t>(y),
                              static_cast<std::int32_t>(z),
                              static_cast<std::uint8_t>(spread[a] | (spread[b] << 1)),
                              0 });
          };
          // The surface cells among cells x0 .. x1, in order.
          auto scan = [&](std::int64_t x0, std::int64_t x1) {
            // Column codes (4 bits: the four rows) of voxel columns x0 .. x1+1.
            std::int64_t column = x0;
#if defined(__SSE2__)
            for (; column + 16 <= x1 + 2; column += 16)
            {
              auto load = [column](const std::uint8_t * r) {
                return _mm_loadu_si128(reinterpret_cast<const __m128i *>(r + column));
              };
              const __m128i r01 = _mm_or_si128(load(rows[0]), _mm_add_epi8(load(rows[1]), load(rows[1])));
              const __m128i r23 = _mm_or_si128(load(rows[2]), _mm_add_epi8(load(rows[3]), load(rows[3])));
              const __m128i c = _mm_or_si128(r01, _mm_slli_epi16(r23, 2)); // flags are 0 or 1: no carries
              _mm_storeu_si128(reinterpret_cast<__m128i *>(code + column), c);
            }
#endif
            for (; column <= x1 + 1; ++column)
            {
              code[column] = static_cast<std::uint8_t>(rows[0][column] | (rows[1][column] << 1) |
                                                       (rows[2][column] << 2) | (rows[3][column] << 3));
            }
            std::int64_t x = x0;
#if defined(__SSE2__)
            // 16 cells at a time: runs of cells inside the object (columns 15) or
            // outside it (0) are skipped with one comparison each.
            {
              const __m128i zero = _mm_setzero_si128();
              const __m128i full = _mm_set1_epi8(15);
              for (; x + 16 <= x1 + 1; x += 16)
              {
                const __m128i a = _mm_loadu_si128(reinterpret_cast<const __m128i *>(code + x));
                const __m128i b = _mm_loadu_si128(reinterpret_cast<const __m128i *>(code + x + 1));
                const __m128i uniform =
                  _mm_or_si128(_mm_cmpeq_epi8(_mm_or_si128(a, b), zero), _mm_cmpeq_epi8(_mm_and_si128(a, b), full));
                unsigned int mixed = ~static_cast<unsigned int>(_mm_movemask_epi8(uniform)) & 0xFFFFu;
                while (mixed != 0)
                {
                  addCell(x + CountTrailingZeros(mixed));
                  mixed &= mixed - 1;
                }
              }
            }
#endif
            for (; x <= x1; ++x)
            {
              const unsigned int a = code[x];
              const unsigned int b = code[x + 1];
              if ((a | b) != 0 && (a & b) != 15)
              {
                addCell(x);
              }
            }
          };
          if (runs && allFirst < allLast)
          {
            // Cells allFirst .. allLast-1 have all 8 corners inside: only the two ends
            // of the row can hold surface cells.
            scan(xFirst - 1, allFirst - 1);
            scan(allLast, xLast);
          }
          else
          {
            scan(xFirst - 1, xLast);
          }
        }
      }
      found[block] = std::move(cells);
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
