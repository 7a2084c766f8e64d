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
#ifndef itkMeshExtractionLargeBlockVector_h
#define itkMeshExtractionLargeBlockVector_h

#include "itkMeshExtractionBuffer.h"

#include <cstddef>
#include <vector>

namespace itk
{
namespace MeshExtraction
{
/** \brief A standard allocator on detail::AllocateLargeBlock: the vectors of per-node and
 * per-face data (SurfaceNet, the faces) get huge pages where they are large, and
 * are otherwise the same std::vector. \ingroup MeshExtraction */
template <typename T>
struct LargeBlockAllocator
{
  using value_type = T;

  LargeBlockAllocator() = default;
  template <typename U>
  LargeBlockAllocator(const LargeBlockAllocator<U> &) noexcept
  {}

  T *
  allocate(std::size_t n)
  {
    return static_cast<T *>(detail::AllocateLargeBlock(n * sizeof(T)));
  }
  void
  deallocate(T * p, std::size_t n) noexcept
  {
    detail::ReleaseLargeBlock(p, n * sizeof(T));
  }
  template <typename U>
  bool
  operator==(const LargeBlockAllocator<U> &) const noexcept
  {
    return true;
  }
  template <typename U>
  bool
  operator!=(const LargeBlockAllocator<U> &) const noexcept
  {
    return false;
  }
};

/** A std::vector whose large buffers get huge pages (LargeBlockAllocator). */
template <typename T>
using LargeBlockVector = std::vector<T, LargeBlockAllocator<T>>;

} // namespace MeshExtraction
} // namespace itk

#endif
