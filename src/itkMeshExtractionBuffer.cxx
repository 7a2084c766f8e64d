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
#include "itkMeshExtractionBuffer.h"

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <new>
#if defined(_WIN32)
#  include <malloc.h>
#endif
#if defined(__linux__)
#  include <sys/mman.h>
#endif

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
namespace
{
constexpr std::size_t HugePage = std::size_t{ 2 } << 20;
constexpr std::size_t Alignment = 64; // a cache line, for the small blocks

bool
IsLarge(std::size_t bytes)
{
  return bytes >= HugePage / 2;
}

std::size_t
RoundedSize(std::size_t bytes)
{
  return (std::max<std::size_t>(bytes, 1) + Alignment - 1) / Alignment * Alignment;
}
} // namespace

void *
AllocateLargeBlock(std::size_t bytes)
{
  void * block = nullptr;
  if (IsLarge(bytes))
  {
    // Whole 2 MiB pages at a 2 MiB boundary inside one heap block (not
    // posix_memalign, which would split the heap around each large block); the
    // heap block's address sits just before the aligned one.
    const std::size_t pages = (bytes + HugePage - 1) / HugePage * HugePage;
    void *            raw = std::malloc(pages + HugePage);
    if (raw == nullptr)
    {
      throw std::bad_alloc();
    }
    const auto start = reinterpret_cast<std::uintptr_t>(raw) + sizeof(void *);
    block = reinterpret_cast<void *>((start + HugePage - 1) / HugePage * HugePage);
    static_cast<void **>(block)[-1] = raw;
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    madvise(block, pages, MADV_HUGEPAGE); // advice only: ignored where unsupported
#endif
    return block;
  }
#if defined(_WIN32)
  block = _aligned_malloc(RoundedSize(bytes), Alignment);
#else
  if (posix_memalign(&block, Alignment, RoundedSize(bytes)) != 0)
  {
    block = nullptr;
  }
#endif
  if (block == nullptr)
  {
    throw std::bad_alloc();
  }
  return block;
}

void
ReleaseLargeBlock(void * block, std::size_t bytes) noexcept
{
  if (block == nullptr)
  {
    return;
  }
  if (IsLarge(bytes))
  {
    std::free(static_cast<void **>(block)[-1]);
    return;
  }
#if defined(_WIN32)
  _aligned_free(block);
#else
  std::free(block);
#endif
}

} // namespace detail
} // namespace MeshExtraction
} // namespace itk
