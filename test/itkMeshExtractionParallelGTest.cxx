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
// The work-unit helpers of itkMeshExtractionParallel.h (internal).

#include "itkMeshExtractionParallel.h"
#include "itkMultiThreaderBase.h"

#include "gtest/gtest.h"

#include <chrono>
#include <mutex>
#include <set>
#include <thread>

using namespace itk::MeshExtraction::detail;

TEST(ParallelForBlocks, ScopedNumberOfWorkUnitsBoundsTheThreadsAndIsRestored)
{
  // A filter's SetNumberOfWorkUnits(1) must reach the free functions it calls.
  auto threadsUsed = []() {
    std::mutex                mutex;
    std::set<std::thread::id> ids;
    std::vector<std::size_t>  covered(4096, 0);
    ParallelForBlocks(covered.size(), 16, [&](std::size_t begin, std::size_t end, std::size_t) {
      for (std::size_t i = begin; i < end; ++i)
      {
        ++covered[i];
      }
      // Long enough that a second thread, if there is one, takes some blocks.
      std::this_thread::sleep_for(std::chrono::microseconds(200));
      std::lock_guard<std::mutex> lock(mutex);
      ids.insert(std::this_thread::get_id());
    });
    EXPECT_EQ(std::count(covered.begin(), covered.end(), 1u), static_cast<std::ptrdiff_t>(covered.size()));
    return ids.size();
  };
  EXPECT_EQ(ThreadNumberOfWorkUnits(), 0u);
  {
    const ScopedNumberOfWorkUnits one(1);
    EXPECT_EQ(ThreadNumberOfWorkUnits(), 1u);
    EXPECT_EQ(threadsUsed(), 1u);
    {
      const ScopedNumberOfWorkUnits two(2);
      EXPECT_EQ(ThreadNumberOfWorkUnits(), 2u);
      if (itk::MultiThreaderBase::GetGlobalDefaultNumberOfThreads() > 1)
      {
        EXPECT_GT(threadsUsed(), 1u);
      }
    }
    EXPECT_EQ(ThreadNumberOfWorkUnits(), 1u);
  }
  EXPECT_EQ(ThreadNumberOfWorkUnits(), 0u);
}
