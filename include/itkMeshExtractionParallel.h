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
#ifndef itkMeshExtractionParallel_h
#define itkMeshExtractionParallel_h

#include "MeshExtractionExport.h"
#include "itkMultiThreaderBase.h"

#include <algorithm>
#include <cstddef>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
/** The number of work units ParallelForBlocks uses when given 0, for the calling
 * thread: 0 (ITK's global default) unless a ScopedNumberOfWorkUnits is alive. */
MeshExtraction_EXPORT unsigned int &
ThreadNumberOfWorkUnits();

/** While alive, ParallelForBlocks calls from this thread that pass no number of work
 * units use `numberOfWorkUnits`: a filter sets it from its own NumberOfWorkUnits at the
 * start of GenerateData, so every stage (including the free functions it calls)
 * honours SetNumberOfWorkUnits(). \ingroup MeshExtraction */
class MeshExtraction_EXPORT ScopedNumberOfWorkUnits
{
public:
  explicit ScopedNumberOfWorkUnits(unsigned int numberOfWorkUnits);
  ~ScopedNumberOfWorkUnits();
  ScopedNumberOfWorkUnits(const ScopedNumberOfWorkUnits &) = delete;
  ScopedNumberOfWorkUnits &
  operator=(const ScopedNumberOfWorkUnits &) = delete;

private:
  unsigned int m_Previous;
};

/** Run f(begin, end, block) over [0, n) cut into blocks of `blockSize`, the
 * blocks spread over ITK's multithreader (numberOfWorkUnits = 0: the calling
 * thread's ScopedNumberOfWorkUnits, else ITK's global default). Block boundaries
 * depend only on n and blockSize, never on the number of threads, so per-block
 * results combined in block order are deterministic.
 * f must not throw. \ingroup MeshExtraction */
template <typename TFunction>
void
ParallelForBlocks(std::size_t n, std::size_t blockSize, TFunction && f, unsigned int numberOfWorkUnits = 0)
{
  if (n == 0)
  {
    return;
  }
  blockSize = std::max<std::size_t>(blockSize, 1);
  const std::size_t blocks = (n + blockSize - 1) / blockSize;
  if (blocks == 1)
  {
    f(std::size_t{ 0 }, n, std::size_t{ 0 });
    return;
  }
  if (numberOfWorkUnits == 0)
  {
    numberOfWorkUnits = ThreadNumberOfWorkUnits();
  }
  MultiThreaderBase::Pointer threader = MultiThreaderBase::New();
  if (numberOfWorkUnits > 0)
  {
    // TBB (PyPI's itk's default threader) bounds its threads by MaximumNumberOfThreads,
    // not by the number of work units: both are set, so every threader honours it.
    threader->SetMaximumNumberOfThreads(numberOfWorkUnits);
    threader->SetNumberOfWorkUnits(numberOfWorkUnits);
  }
  threader->ParallelizeArray(
    0,
    static_cast<SizeValueType>(blocks),
    [&](SizeValueType b) {
      const std::size_t begin = static_cast<std::size_t>(b) * blockSize;
      f(begin, std::min(n, begin + blockSize), static_cast<std::size_t>(b));
    },
    nullptr);
}

} // namespace detail
} // namespace MeshExtraction
} // namespace itk

#endif
