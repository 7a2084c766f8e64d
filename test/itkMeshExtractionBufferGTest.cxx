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
// The buffers of itkMeshExtractionBuffer.h (internal).

#include "itkMeshExtractionBuffer.h"

#include "gtest/gtest.h"

#include <cstdint>

using namespace itk::MeshExtraction::detail;

TEST(UninitializedArray, HoldsWhatIsWrittenAlignedForCacheLinesAndHugePages)
{
  // Small arrays are aligned to a cache line, large ones (1 MiB and more) to a 2 MiB
  // page; every element keeps what was written; Allocate replaces the contents.
  UninitializedArray<std::uint32_t> empty;
  EXPECT_TRUE(empty.empty());
  EXPECT_EQ(empty.size(), 0u);
  EXPECT_EQ(empty.data(), nullptr);
  for (const std::size_t n : { std::size_t{ 1 }, std::size_t{ 1000 }, std::size_t{ 300000 }, std::size_t{ 3 } << 20 })
  {
    SCOPED_TRACE(n);
    UninitializedArray<std::uint32_t> a(n);
    ASSERT_EQ(a.size(), n);
    ASSERT_FALSE(a.empty());
    const auto address = reinterpret_cast<std::uintptr_t>(a.data());
    EXPECT_EQ(address % 64, 0u);
    if (n * sizeof(std::uint32_t) >= (std::size_t{ 1 } << 20))
    {
      EXPECT_EQ(address % (std::size_t{ 2 } << 20), 0u);
    }
    for (std::size_t i = 0; i < n; ++i)
    {
      a[i] = static_cast<std::uint32_t>(i * 2654435761u);
    }
    std::size_t  wrong = 0;
    const auto & constant = a;
    for (std::size_t i = 0; i < n; ++i)
    {
      wrong += constant[i] != static_cast<std::uint32_t>(i * 2654435761u) ? 1 : 0;
    }
    EXPECT_EQ(wrong, 0u);
    a.Allocate(7);
    EXPECT_EQ(a.size(), 7u);
    a.Allocate(0);
    EXPECT_TRUE(a.empty());
    EXPECT_EQ(a.data(), nullptr);
  }
}
