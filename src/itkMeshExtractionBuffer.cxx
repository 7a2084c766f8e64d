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
namespace
{
constexpr std::size_t HugePage = std::size_t{ 2 } << 20;
constexpr std::size_t Alignment = 64; // a cache line, for the small blocks
} // namespace

void *
AllocateLargeBlock(std::size_t bytes)
{
  if (bytes == 0)
  {
    bytes = 1;
  }
  const bool large = bytes >= 2 * HugePage;
  const auto alignment = large ? HugePage : Alignment;
  const auto rounded = (bytes + alignment - 1) / alignment * alignment;
  void *     block = nullptr;
#if defined(_WIN32)
  block = _aligned_malloc(rounded, alignment);
#else
  if (posix_memalign(&block, alignment, rounded) != 0)
  {
    block = nullptr;
  }
#endif
  if (block == nullptr)
  {
    throw std::bad_alloc();
  }
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  if (large)
  {
    madvise(block, rounded, MADV_HUGEPAGE); // advice only: ignored where unsupported
  }
#endif
  return block;
}

void
ReleaseLargeBlock(void * block) noexcept
{
#if defined(_WIN32)
  _aligned_free(block);
#else
  std::free(block);
#endif
}

} // namespace MeshExtraction
} // namespace itk
