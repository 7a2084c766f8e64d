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
#ifndef itkMeshExtractionBuffer_h
#define itkMeshExtractionBuffer_h

#include "MeshExtractionExport.h"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <type_traits>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
/** Memory for `bytes`, not initialised, released with ReleaseLargeBlock(block,
 * bytes). Small blocks are aligned to a cache line. Large blocks (1 MiB and more)
 * are whole 2 MiB pages at a 2 MiB boundary inside one C-heap block (malloc of the
 * pages plus 2 MiB: not posix_memalign, whose split-off remainders fragment the
 * heap the rest of the program uses), advised on Linux as transparent huge pages,
 * so that the first touch costs one page fault per 2 MiB instead of one per 4 KiB,
 * which matters where a loop does little work per element it touches. Throws
 * std::bad_alloc. */
MeshExtraction_EXPORT void *
AllocateLargeBlock(std::size_t bytes);

/** Releases a block of AllocateLargeBlock(bytes), given the same `bytes`. */
MeshExtraction_EXPORT void
ReleaseLargeBlock(void * block, std::size_t bytes) noexcept;

/** Asks the processor to bring the cache lines that hold [address, address + bytes)
 * toward its caches: prefetch instructions, which change no result and fault at no
 * address (integer arithmetic, so the range may run past an array's end). For
 * memory read soon in a pattern the hardware's own prefetching does not foresee or
 * foresees too late. */
inline void
PrefetchForReading(std::uintptr_t address, std::size_t bytes)
{
#if defined(__GNUC__) || defined(__clang__)
  constexpr std::uintptr_t Line = 64;
  for (std::uintptr_t line = address & ~(Line - 1); line < address + bytes; line += Line)
  {
    __builtin_prefetch(reinterpret_cast<const void *>(line), 0, 3);
  }
#else
  (void)address;
  (void)bytes;
#endif
}

/** \brief A fixed-size array of trivial elements that are not zero-filled: for
 * the large per-node and per-face work arrays whose every element is written
 * before it is read. Unlike std::vector it does not touch the memory when
 * allocated, so the pages are first touched by the (parallel) loop that fills
 * them, and large arrays get huge pages (AllocateLargeBlock).
 * \ingroup MeshExtraction */
template <typename T>
class UninitializedArray
{
  static_assert(std::is_trivially_default_constructible<T>::value && std::is_trivially_destructible<T>::value,
                "UninitializedArray holds trivial elements only");

public:
  UninitializedArray() = default;
  explicit UninitializedArray(std::size_t n)
  {
    this->Allocate(n);
  }

  /** n elements with unspecified values; the previous contents are released. */
  void
  Allocate(std::size_t n)
  {
    m_Data = std::unique_ptr<T, Release>(n > 0 ? static_cast<T *>(AllocateLargeBlock(n * sizeof(T))) : nullptr,
                                         Release{ n * sizeof(T) });
    m_Size = n;
  }

  T *
  data() noexcept
  {
    return m_Data.get();
  }
  const T *
  data() const noexcept
  {
    return m_Data.get();
  }
  std::size_t
  size() const noexcept
  {
    return m_Size;
  }
  bool
  empty() const noexcept
  {
    return m_Size == 0;
  }
  T &
  operator[](std::size_t i) noexcept
  {
    return m_Data.get()[i];
  }
  const T &
  operator[](std::size_t i) const noexcept
  {
    return m_Data.get()[i];
  }

private:
  struct Release
  {
    std::size_t bytes{ 0 };
    void
    operator()(T * p) const noexcept
    {
      ReleaseLargeBlock(p, bytes);
    }
  };
  std::unique_ptr<T, Release> m_Data;
  std::size_t                 m_Size{ 0 };
};

} // namespace detail
} // namespace MeshExtraction
} // namespace itk

#endif
