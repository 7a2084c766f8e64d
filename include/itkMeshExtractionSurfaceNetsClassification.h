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
// Internal to MeshExtraction (namespace detail): not part of the public API.
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
namespace detail
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
 * waiting on memory; a request a few pages ahead, one cache line per 16 voxels, keeps
 * the float row pass fed (a whole row's request at its start did less well for it).
 * Rows of other pixel types, which the compiler vectorises, get that whole-row
 * prefetch. */
constexpr std::size_t SurfaceNetsPrefetchDistance = 4096;

#if defined(__SSE2__)
/** The float row pass of ClassifySurfaceNetsRow in blocks of 16 voxels: flags, inside
 * count, extremes (TExtremes) and NaN lanes, with `inRange` the inside test on four
 * floats (a mask). The accumulators `lo`, `hi` (two each) and `nan` are updated;
 * returns the number of voxels done (a multiple of 16). */
template <bool TExtremes, typename TInRange>
std::int64_t
ClassifySurfaceNetsFloatRowBlocks(const float *  row,
                                  std::int64_t   n,
                                  TInRange       inRange,
                                  std::uint8_t * flags,
                                  std::size_t &  insideCount,
                                  __m128 (&lo)[2],
                                  __m128 (&hi)[2],
                                  __m128 & nan)
{
  const __m128i one = _mm_set1_epi8(1);
  // Locals, not references, so that the stores to the flags cannot alias them.
  std::int64_t         i = 0;
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
  lo[0] = lo0;
  lo[1] = lo1;
  hi[0] = hi0;
  hi[1] = hi1;
  nan = na;
  return i;
}

/** The SSE2 part of ClassifySurfaceNetsRow for a float row: whole blocks of 16
 * voxels, with the inside test of one comparison where the range has one finite
 * bound (an iso-value), and the extremes reduced across lanes. Two accumulators each
 * for the minimum and maximum, so that their chains do not wait on every load (the
 * compiler may not reorder floating-point reductions itself). Returns the number of
 * voxels done. */
template <bool TExtremes>
std::int64_t
ClassifySurfaceNetsFloatRow(const float *                        row,
                            std::int64_t                         n,
                            const SurfaceNetsVoxelRange<float> & inside,
                            std::uint8_t *                       flags,
                            std::size_t &                        insideCount,
                            float &                              lowest,
                            float &                              highest,
                            bool &                               hasNaN)
{
  const __m128 low = _mm_set1_ps(inside.low);
  const __m128 high = _mm_set1_ps(inside.high);
  __m128       lo[2] = { _mm_set1_ps(lowest), _mm_set1_ps(lowest) };
  __m128       hi[2] = { _mm_set1_ps(highest), _mm_set1_ps(highest) };
  __m128       nan = _mm_setzero_ps();
  // An iso-value has one finite bound: one comparison (false for NaN) suffices.
  const int bounds = (inside.low > -std::numeric_limits<float>::infinity() ? 1 : 0) |
                     (inside.high < std::numeric_limits<float>::infinity() ? 2 : 0);
  std::int64_t done = 0;
  if (bounds == 1)
  {
    done = ClassifySurfaceNetsFloatRowBlocks<TExtremes>(
      row, n, [low](__m128 v) { return _mm_cmpge_ps(v, low); }, flags, insideCount, lo, hi, nan);
  }
  else if (bounds == 2)
  {
    done = ClassifySurfaceNetsFloatRowBlocks<TExtremes>(
      row, n, [high](__m128 v) { return _mm_cmple_ps(v, high); }, flags, insideCount, lo, hi, nan);
  }
  else
  {
    done = ClassifySurfaceNetsFloatRowBlocks<TExtremes>(
      row,
      n,
      [low, high](__m128 v) { return _mm_and_ps(_mm_cmpge_ps(v, low), _mm_cmple_ps(v, high)); },
      flags,
      insideCount,
      lo,
      hi,
      nan);
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
  return done;
}
#endif

/** ClassifySurfaceNetsRow from voxel x on: branch-free loops the compiler vectorizes.
 * A row that starts here (x = 0) has the part of the image SurfaceNetsPrefetchDistance
 * ahead, a row's length of it, requested at once. */
template <bool TExtremes, typename TPixel, typename TInside>
void
ClassifySurfaceNetsRowRemainder(const TPixel * row,
                                std::int64_t   x,
                                std::int64_t   n,
                                TInside        inside,
                                std::uint8_t * flags,
                                std::size_t &  insideCount,
                                TPixel &       lowest,
                                TPixel &       highest,
                                bool &         hasNaN)
{
  if (x == 0)
  {
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

/** The integer row pass of ClassifySurfaceNetsRow in blocks of 32 voxels: flags,
 * inside count and extremes. The blocks have a fixed length and the row and flags do
 * not alias (restrict), so that the compiler vectorizes them at -O2 too (GCC's cheap
 * cost model there declines loops of unknown length and loops whose pointers may
 * alias, and a byte-sized pixel may alias the byte-sized flags). Returns the number
 * of voxels done (a multiple of 32). */
template <bool TExtremes, typename TPixel, typename TInside>
std::int64_t
ClassifySurfaceNetsIntegerRowBlocks(const TPixel * __restrict row,
                                    std::int64_t n,
                                    TInside      inside,
                                    std::uint8_t * __restrict flags,
                                    std::size_t & insideCount,
                                    TPixel &      lowest,
                                    TPixel &      highest)
{
  constexpr std::int64_t block = 32;
  std::int64_t           x = 0;
  std::size_t            count = 0;
  TPixel                 lo = lowest;
  TPixel                 hi = highest;
  for (; x + block <= n; x += block)
  {
    const TPixel * __restrict r = row + x;
    std::uint8_t * __restrict f = flags + x;
    unsigned int blockCount = 0;
    for (std::int64_t k = 0; k < block; ++k)
    {
      const auto in = static_cast<std::uint8_t>(inside(r[k]));
      f[k] = in;
      blockCount += in;
    }
    count += blockCount;
    if constexpr (TExtremes)
    {
      for (std::int64_t k = 0; k < block; ++k)
      {
        lo = r[k] < lo ? r[k] : lo;
        hi = r[k] > hi ? r[k] : hi;
      }
    }
  }
  insideCount += count;
  lowest = lo;
  highest = hi;
  return x;
}

/** One voxel row of the classification: flags[x] = inside(row[x]) (NaN never
 * inside), the number of inside voxels (added to `insideCount`), the row's
 * extremes ignoring NaN (unchanged when every voxel is NaN), and whether it holds
 * a NaN. Branch-free loops the compiler vectorizes for integer pixels; float rows
 * use SSE2 where the compiler offers it, since the compiler may not reorder
 * floating-point minimum/maximum reductions itself. */
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
    x = ClassifySurfaceNetsFloatRow<TExtremes>(row, n, inside, flags, insideCount, lowest, highest, hasNaN);
  }
#endif
  if constexpr (std::is_integral<TPixel>::value)
  {
    x = ClassifySurfaceNetsIntegerRowBlocks<TExtremes>(row, n, inside, flags, insideCount, lowest, highest);
  }
  ClassifySurfaceNetsRowRemainder<TExtremes>(row, x, n, inside, flags, insideCount, lowest, highest, hasNaN);
}

/** \brief Stage 1 of SurfaceNets, the classification of the cells, as its steps:
 * the voxel rows of a slice (ClassifySurfaceNetsRow), the surface cells of a row of
 * cells, a slab of cell layers per task, and the slabs' cells joined in order.
 *
 * A cell is the cube between 8 neighbouring voxel centres; cells run from -1 to
 * N-1 along each axis, so that voxels outside the image count as outside and
 * objects touching the image border are closed. `inside(pixel)` classifies a voxel
 * (a NaN voxel is never inside, and reported). The image is read one slab of cell
 * layers per task, one slice at a time, in row passes without branches; a row of
 * cells is only visited between the first and last inside voxel of its four voxel
 * rows (found 8 flags at a time), each cell from the 4-bit codes of its two voxel
 * columns. Memory beyond the image is two slices of flags per task plus the surface
 * cells. Cells come out sorted by (z, y, x) whatever the number of threads.
 * \ingroup MeshExtraction */
template <typename TImage, typename TInside>
class SurfaceNetsCellClassifier
{
public:
  using PixelType = typename TImage::PixelType;
  static_assert(TImage::ImageDimension == 3, "SurfaceNets works on 3-D images");

  SurfaceNetsCellClassifier(const TImage * image,
                            TInside        inside,
                            SurfaceNet &   net,
                            unsigned int   numberOfWorkUnits,
                            bool           extremes)
      : m_Buffer(image->GetBufferPointer())
      , m_Inside(inside)
      , m_Net(net)
      , m_NumberOfWorkUnits(numberOfWorkUnits)
      , m_Extremes(extremes)
      , m_Nx(static_cast<std::int64_t>(image->GetBufferedRegion().GetSize(0)))
      , m_Ny(static_cast<std::int64_t>(image->GetBufferedRegion().GetSize(1)))
      , m_Nz(static_cast<std::int64_t>(image->GetBufferedRegion().GetSize(2)))
      // Rows of flags are padded: one zero byte before x = 0 and enough after nx - 1 for
      // 8-byte reads, so that cells x = -1 .. nx-1 read columns x and x + 1 without tests.
      , m_Stride(((m_Nx + 2 + 7) / 8 + 1) * 8)
      , m_NumberOfLayers(static_cast<std::size_t>(m_Nz + 1)) // cell layers z = -1 .. nz-1
  {
    m_Net.size = { { m_Nx, m_Ny, m_Nz } };
    // Spread a column of 4 inside bits (y0z0, y1z0, y0z1, y1z1) onto corner bits 0, 2, 4, 6.
    for (unsigned int c = 0; c < 16; ++c)
    {
      m_Spread[c] = static_cast<std::uint8_t>((c & 1u) | ((c & 2u) << 1) | ((c & 4u) << 2) | ((c & 8u) << 3));
    }
    // A few slabs per work unit: each slab reads the slice below its first layer
    // again and sets up its own two slices of flags.
    unsigned int workUnits = numberOfWorkUnits != 0 ? numberOfWorkUnits : ThreadNumberOfWorkUnits();
    if (workUnits == 0)
    {
      workUnits = MultiThreaderBase::GetGlobalDefaultNumberOfThreads();
    }
    m_LayersPerSlab = std::max<std::size_t>(1, m_NumberOfLayers / (4 * std::size_t{ workUnits }));
    m_NumberOfSlabs = (m_NumberOfLayers + m_LayersPerSlab - 1) / m_LayersPerSlab;
  }

  /** Classifies every slab in parallel, then joins their cells into the net. */
  SurfaceNetsClassificationStatistics
  Run()
  {
    m_Found.assign(m_NumberOfSlabs, {});
    m_Statistics.assign(m_NumberOfSlabs, {});
    ParallelForBlocks(
      m_NumberOfLayers,
      m_LayersPerSlab,
      [this](std::size_t begin, std::size_t end, std::size_t slab) { this->ClassifySlab(begin, end, slab); },
      m_NumberOfWorkUnits);
    return this->JoinSlabs();
  }

private:
  /** A slice of inside flags and, per voxel row, the first and last inside x
   * (last < first: no inside voxel) and whether every voxel between them is inside
   * (one run). Row y of a slice starts at flags + (y+1) * stride + 1: rows y = -1 and
   * y = ny are all zero, as are slices beyond the image. */
  struct Slice
  {
    std::int64_t              z{ std::numeric_limits<std::int64_t>::min() };
    std::vector<std::uint8_t> flags;
    std::vector<std::int64_t> first;
    std::vector<std::int64_t> last;
    std::vector<std::uint8_t> oneRun;
  };

  /** The surface cells and statistics of cell layers [begin, end) (layer l is the
   * cells at z = l - 1, between slices z and z + 1), in order. */
  void
  ClassifySlab(std::size_t begin, std::size_t end, std::size_t slab)
  {
    SurfaceNetsClassificationStatistics & stats = m_Statistics[slab];
    Slice                                 slices[2];
    for (auto & s : slices)
    {
      s.flags.assign(static_cast<std::size_t>((m_Ny + 2) * m_Stride), 0);
      s.first.assign(static_cast<std::size_t>(m_Ny + 2), 0);
      s.last.assign(static_cast<std::size_t>(m_Ny + 2), -1);
      s.oneRun.assign(static_cast<std::size_t>(m_Ny + 2), 1);
    }
    // Each slice is read by the layers below and above it; count it once, in the
    // layer whose upper slice it is.
    const std::int64_t        firstCountedSlice = static_cast<std::int64_t>(begin);
    std::vector<SurfaceCell>  cells = std::move(m_Found[slab]);
    std::vector<std::uint8_t> columns(static_cast<std::size_t>(m_Stride), 0);
    for (std::size_t layer = begin; layer < end; ++layer)
    {
      const std::int64_t z = static_cast<std::int64_t>(layer) - 1; // cell layer between slices z and z+1
      Slice *            lower = slices[0].z == z ? &slices[0] : (slices[1].z == z ? &slices[1] : nullptr);
      if (lower == nullptr)
      {
        this->ClassifySlice(slices[0], z, firstCountedSlice, stats);
        lower = &slices[0];
      }
      Slice * upper = lower == &slices[0] ? &slices[1] : &slices[0];
      this->ClassifySlice(*upper, z + 1, firstCountedSlice, stats);
      for (std::int64_t y = -1; y < m_Ny; ++y)
      {
        this->FindCellsOfRow(*lower, *upper, y, z, columns.data() + 1, cells);
      }
    }
    m_Found[slab] = std::move(cells);
  }

  /** Slice z's flags and row runs (all outside beyond the image); its inside voxels
   * and extremes counted in `stats` from slice `firstCountedSlice` on. */
  void
  ClassifySlice(Slice &                               s,
                std::int64_t                          z,
                std::int64_t                          firstCountedSlice,
                SurfaceNetsClassificationStatistics & stats) const
  {
    const bool wasEmpty = s.z < 0 || s.z >= m_Nz;
    s.z = z;
    if (z < 0 || z >= m_Nz)
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
    const bool count = firstCountedSlice - 1 < z;
    for (std::int64_t y = 0; y < m_Ny; ++y)
    {
      this->ClassifyVoxelRow(s, y, z, count, stats);
    }
  }

  /** Voxel row (y, z) into slice s: its flags (NaN voxels outside, the first one
   * recorded), the first and last inside voxel and whether they are one run; with
   * `count`, its inside voxels and extremes into `stats`. */
  void
  ClassifyVoxelRow(Slice & s, std::int64_t y, std::int64_t z, bool count, SurfaceNetsClassificationStatistics & stats)
    const
  {
    const std::int64_t nx = m_Nx;
    const PixelType *  row = m_Buffer + (z * m_Ny + y) * nx;
    std::uint8_t *     flags = s.flags.data() + (y + 1) * m_Stride + 1;
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
    if (m_Extremes)
    {
      ClassifySurfaceNetsRow<true>(row, nx, m_Inside, flags, insideInRow, lowest, highest, hasNaN);
    }
    else
    {
      ClassifySurfaceNetsRow<false>(row, nx, m_Inside, flags, insideInRow, lowest, highest, hasNaN);
    }
    if (m_Extremes && start < nx && count)
    {
      stats.minimum = std::min(stats.minimum, static_cast<double>(lowest));
      stats.maximum = std::max(stats.maximum, static_cast<double>(highest));
    }
    if (hasNaN)
    {
      insideInRow = ClearNaNVoxels(row, y, z, flags, stats);
    }
    std::int64_t first = 0;
    std::int64_t last = -1;
    this->FindInsideRange(flags, insideInRow, first, last);
    s.first[y + 1] = first;
    s.last[y + 1] = last;
    s.oneRun[y + 1] = static_cast<std::uint8_t>(static_cast<std::int64_t>(insideInRow) == last - first + 1);
    if (count)
    {
      stats.insideVoxels += insideInRow;
    }
  }

  /** Marks the NaN voxels of row (y, z) outside, records the first NaN voxel in
   * `stats`, and returns the row's inside voxels. */
  std::size_t
  ClearNaNVoxels(const PixelType *                     row,
                 std::int64_t                          y,
                 std::int64_t                          z,
                 std::uint8_t *                        flags,
                 SurfaceNetsClassificationStatistics & stats) const
  {
    for (std::int64_t x = 0; x < m_Nx; ++x)
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
    return static_cast<std::size_t>(std::count(flags, flags + m_Nx, std::uint8_t{ 1 }));
  }

  /** The first and last inside voxel of a row of flags with `insideInRow` inside
   * voxels, 8 flags at a time (the padding is zero); nothing to search in an empty or
   * a full row. Unchanged (first 0, last -1) for an empty row. */
  void
  FindInsideRange(const std::uint8_t * flags, std::size_t insideInRow, std::int64_t & first, std::int64_t & last) const
  {
    const std::int64_t nx = m_Nx;
    if (insideInRow == static_cast<std::size_t>(nx))
    {
      last = nx - 1;
      return;
    }
    if (insideInRow == 0)
    {
      return;
    }
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

  /** The surface cells of the row of cells (y, z), between the slices `lower` (z)
   * and `upper` (z + 1), appended to `cells` in order. `code` holds the column codes
   * (code[x], x >= -1). */
  void
  FindCellsOfRow(const Slice &              lower,
                 const Slice &              upper,
                 std::int64_t               y,
                 std::int64_t               z,
                 std::uint8_t *             code,
                 std::vector<SurfaceCell> & cells) const
  {
    // The four voxel rows (y, z), (y+1, z), (y, z+1), (y+1, z+1), padded rows of
    // zeros beyond the image.
    const Slice *        slicesOfRow[4] = { &lower, &lower, &upper, &upper };
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
      rows[r] = s.flags.data() + (ys[r] + 1) * m_Stride + 1;
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
      return; // no inside voxel: no surface cell in this row
    }
    if (runs && allFirst < allLast)
    {
      // Cells allFirst .. allLast-1 have all 8 corners inside: only the two ends of
      // the row can hold surface cells.
      this->ScanCells(rows, xFirst - 1, allFirst - 1, y, z, code, cells);
      this->ScanCells(rows, allLast, xLast, y, z, code, cells);
    }
    else
    {
      this->ScanCells(rows, xFirst - 1, xLast, y, z, code, cells);
    }
  }

  /** The surface cells among cells x0 .. x1 of row (y, z), in order: the column codes
   * of voxel columns x0 .. x1+1 (4 bits: the four voxel rows), then every cell whose
   * two columns are not both all inside or all outside. */
  void
  ScanCells(const std::uint8_t * const (&rows)[4],
            std::int64_t               x0,
            std::int64_t               x1,
            std::int64_t               y,
            std::int64_t               z,
            std::uint8_t *             code,
            std::vector<SurfaceCell> & cells) const
  {
    ColumnCodes(rows, x0, x1 + 1, code);
    std::int64_t x = x0;
#if defined(__SSE2__)
    // 16 cells at a time: runs of cells inside the object (columns 15) or outside it
    // (0) are skipped with one comparison each.
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
          this->AddCell(code, x + CountTrailingZeros(mixed), y, z, cells);
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
        this->AddCell(code, x, y, z, cells);
      }
    }
  }

  /** code[x] for voxel columns x0 .. x1: bit r set where voxel row r is inside. */
  static void
  ColumnCodes(const std::uint8_t * const (&rows)[4], std::int64_t x0, std::int64_t x1, std::uint8_t * code)
  {
    std::int64_t column = x0;
#if defined(__SSE2__)
    for (; column + 16 <= x1 + 1; column += 16)
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
    for (; column <= x1; ++column)
    {
      code[column] = static_cast<std::uint8_t>(rows[0][column] | (rows[1][column] << 1) | (rows[2][column] << 2) |
                                               (rows[3][column] << 3));
    }
  }

  /** Cell x of row (y, z), of columns x and x+1, with its configuration. */
  void
  AddCell(const std::uint8_t * code, std::int64_t x, std::int64_t y, std::int64_t z, std::vector<SurfaceCell> & cells)
    const
  {
    const unsigned int a = code[x];
    const unsigned int b = code[x + 1];
    cells.push_back({ static_cast<std::int32_t>(x),
                      static_cast<std::int32_t>(y),
                      static_cast<std::int32_t>(z),
                      static_cast<std::uint8_t>(m_Spread[a] | (m_Spread[b] << 1)),
                      0 });
  }

  /** The slabs' statistics summed (the first NaN voxel of the first slab that has
   * one), and their cells into the net in slab order: counted, allocated once, filled. */
  SurfaceNetsClassificationStatistics
  JoinSlabs()
  {
    SurfaceNetsClassificationStatistics total;
    std::size_t                         count = 0;
    for (std::size_t b = 0; b < m_NumberOfSlabs; ++b)
    {
      count += m_Found[b].size();
      total.minimum = std::min(total.minimum, m_Statistics[b].minimum);
      total.maximum = std::max(total.maximum, m_Statistics[b].maximum);
      total.insideVoxels += m_Statistics[b].insideVoxels;
      if (m_Statistics[b].foundNaN && !total.foundNaN)
      {
        total.foundNaN = true;
        std::copy(m_Statistics[b].nanVoxel, m_Statistics[b].nanVoxel + 3, total.nanVoxel);
      }
    }
    m_Net.cells.clear();
    m_Net.cells.reserve(count);
    for (auto & f : m_Found)
    {
      m_Net.cells.insert(m_Net.cells.end(), f.begin(), f.end());
      std::vector<SurfaceCell>().swap(f);
    }
    return total;
  }

  const PixelType *  m_Buffer;
  const TInside      m_Inside;
  SurfaceNet &       m_Net;
  const unsigned int m_NumberOfWorkUnits;
  const bool         m_Extremes;
  const std::int64_t m_Nx;
  const std::int64_t m_Ny;
  const std::int64_t m_Nz;
  const std::int64_t m_Stride; ///< bytes from one row of flags to the next
  const std::size_t  m_NumberOfLayers;
  std::uint8_t       m_Spread[16];
  std::size_t        m_LayersPerSlab{ 1 };
  std::size_t        m_NumberOfSlabs{ 0 };

  std::vector<std::vector<SurfaceCell>>            m_Found;      ///< each slab's cells
  std::vector<SurfaceNetsClassificationStatistics> m_Statistics; ///< each slab's statistics
};

/** Stage 1 of SurfaceNets: find the surface cells of an image (see
 * SurfaceNetsCellClassifier). Without `extremes` the statistics' minimum and maximum
 * are not computed (left at their initial values), which saves a quarter of the float
 * row pass: a caller that needs them only when there is no surface asks again then.
 * \ingroup MeshExtraction */
template <typename TImage, typename TInside>
SurfaceNetsClassificationStatistics
ClassifySurfaceCells(const TImage * image,
                     TInside        inside,
                     SurfaceNet &   net,
                     unsigned int   numberOfWorkUnits = 0,
                     bool           extremes = true)
{
  return SurfaceNetsCellClassifier<TImage, TInside>(image, inside, net, numberOfWorkUnits, extremes).Run();
}

} // namespace detail
} // namespace MeshExtraction
} // namespace itk

#endif
