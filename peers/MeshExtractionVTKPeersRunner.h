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
#ifndef MeshExtractionVTKPeersRunner_h
#define MeshExtractionVTKPeersRunner_h

// Runs one method of the comparison --repeat times: the best run is its wall time, the
// first run also gives its peak memory.
//
// Peak memory (Linux): the method runs in a forked child process. The child
// resets its resident-set high-water mark (writing 5 to /proc/self/clear_refs),
// reads its resident set size (/proc/self/statm) as the baseline -- the parent's
// pages after the input was loaded, shared copy-on-write --, runs the method once and
// reads its own peak, getrusage(RUSAGE_SELF).ru_maxrss. Peak minus baseline is the
// memory the method needed on top of the loaded input: its transient buffers and its
// output. The child then runs the remaining repetitions for the timing, converts the
// last output to flat arrays and sends everything back through a pipe. Running every
// method in its own child also keeps one method's freed-but-cached heap from hiding
// another's, and keeps VTK's TBB thread pool out of the parent (TBB is not fork-safe).
// Elsewhere the methods run in-process, without memory figures.

#include "MeshExtractionVTKPeers.h"

#include <cstdint>
#include <string>
#include <vector>

namespace MeshExtractionCompare
{
/** Everything one method's runs produced. */
struct RunRecord
{
  bool                    ok{ false };
  std::string             error;
  std::vector<double>     seconds;          ///< wall time of each run
  std::int64_t            baselineKB{ -1 }; ///< resident set before the run (-1: not measured)
  std::int64_t            peakKB{ -1 };     ///< peak resident set during the first run (-1: not measured)
  std::string             notes;
  std::string             threads;            ///< the parallelism the run had
  std::uint64_t           droppedPoints{ 0 }; ///< unreferenced points left out of `mesh`
  ME::IndexedTriangleMesh mesh;               ///< the last run's mesh, ITK physical space, outward

  /** The shortest run. */
  double
  BestSeconds() const;
  /** Peak minus baseline, in MiB; negative if not measured. */
  double
  ExtraPeakMiB() const;
};

/** Whether peak memory is measured (forked children, Linux's /proc and ru_maxrss in KiB). */
bool
CanMeasurePeakMemory();

/** Run `method` `repeat` times in this process, with `threads` ITK work units and VTK
 * SMP threads (0: all cores). With `measureMemory`, the high-water mark is reset and
 * the baseline read just before, and the peak of the first run is read. */
RunRecord
RunInProcess(const Method &  method,
             ExtractionInput input,
             unsigned int    repeat,
             unsigned int    threads,
             bool            measureMemory);

/** Run `method` in a forked child (see the top of this file for what is measured);
 * without fork(), in this process without memory figures. */
RunRecord
RunInChildProcess(const Method & method, const ExtractionInput & input, unsigned int repeat, unsigned int threads);

} // namespace MeshExtractionCompare

#endif
