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
// Timing and peak memory of the comparison's methods (see MeshExtractionVTKPeersRunner.h).

#include "MeshExtractionVTKPeersRunner.h"

#include "itkMultiThreaderBase.h"

#include <vtkSMPTools.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <sstream>

#if defined(__linux__)
#  define MESHEXTRACTION_COMPARE_FORK 1
#  include <malloc.h>
#  include <string.h> // strsignal
#  include <sys/resource.h>
#  include <sys/types.h>
#  include <sys/wait.h>
#  include <unistd.h>
#else
#  define MESHEXTRACTION_COMPARE_FORK 0 // elsewhere the methods run in-process, without memory figures
#endif

namespace MeshExtractionCompare
{
double
RunRecord::BestSeconds() const
{
  double best = seconds.empty() ? 0.0 : seconds.front();
  for (double s : seconds)
  {
    best = std::min(best, s);
  }
  return best;
}

double
RunRecord::ExtraPeakMiB() const
{
  return (peakKB < 0 || baselineKB < 0) ? -1.0 : std::max<std::int64_t>(0, peakKB - baselineKB) / 1024.0;
}

bool
CanMeasurePeakMemory()
{
  return MESHEXTRACTION_COMPARE_FORK != 0;
}

namespace
{
// ------------------------------------------------------------------------------
// Resident memory
// ------------------------------------------------------------------------------
#if MESHEXTRACTION_COMPARE_FORK
/** Resident set size of this process in KiB (from /proc/self/statm), -1 if unknown. */
std::int64_t
CurrentResidentKB()
{
  std::ifstream statm("/proc/self/statm");
  long long     size = 0;
  long long     resident = 0;
  if (!(statm >> size >> resident))
  {
    return -1;
  }
  return resident * (static_cast<std::int64_t>(sysconf(_SC_PAGESIZE)) / 1024);
}

/** getrusage(RUSAGE_SELF).ru_maxrss, in KiB on Linux. */
std::int64_t
PeakResidentKB()
{
  struct rusage usage;
  std::memset(&usage, 0, sizeof(usage));
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<std::int64_t>(usage.ru_maxrss);
}

/** Reset the resident-set high-water mark (Linux >= 4.0); false if not possible. */
bool
ResetPeakResident()
{
  FILE * f = std::fopen("/proc/self/clear_refs", "w");
  if (f == nullptr)
  {
    return false;
  }
  const bool ok = std::fputs("5", f) >= 0;
  return std::fclose(f) == 0 && ok;
}
#else
std::int64_t
CurrentResidentKB()
{
  return -1;
}
std::int64_t
PeakResidentKB()
{
  return -1;
}
bool
ResetPeakResident()
{
  return false;
}
#endif

/** Thread settings for a run: ITK work units and VTK SMP threads (0: all cores). */
std::string
ApplyThreadSettings(ExtractionInput & input, unsigned int threads)
{
  if (threads > 0)
  {
    itk::MultiThreaderBase::SetGlobalDefaultNumberOfThreads(threads);
    input.numberOfWorkUnits = threads;
    vtkSMPTools::Initialize(static_cast<int>(threads));
  }
  else
  {
    vtkSMPTools::Initialize();
  }
  std::ostringstream os;
  os << "ITK " << (threads > 0 ? threads : itk::MultiThreaderBase::GetGlobalDefaultNumberOfThreads())
     << " work units; VTK SMP (" << vtkSMPTools::GetBackend() << ") " << vtkSMPTools::GetEstimatedNumberOfThreads()
     << " threads";
  return os.str();
}

/** The timed runs; the last one's mesh, as the comparison measures it, goes into `record`. */
void
TimeRuns(const Method &          method,
         const ExtractionInput & input,
         unsigned int            repeat,
         bool                    measureMemory,
         RunRecord &             record)
{
  MethodOutput last;
  for (unsigned int r = 0; r < std::max(1u, repeat); ++r)
  {
    last = MethodOutput{}; // the previous output is freed before the next run
    const auto start = std::chrono::steady_clock::now();
    last = method.run(input);
    record.seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    if (r == 0 && measureMemory)
    {
      record.peakKB = PeakResidentKB();
    }
  }
  record.notes = last.notes;
  std::size_t dropped = 0;
  record.mesh = MeshForMeasurement(last, &dropped);
  record.droppedPoints = dropped;
}
} // namespace

RunRecord
RunInProcess(const Method &  method,
             ExtractionInput input,
             unsigned int    repeat,
             unsigned int    threads,
             bool            measureMemory)
{
  RunRecord record;
  record.threads = ApplyThreadSettings(input, threads);
  if (measureMemory)
  {
    ResetPeakResident();
    record.baselineKB = CurrentResidentKB();
  }
  try
  {
    TimeRuns(method, input, repeat, measureMemory, record);
    record.ok = true;
  }
  catch (const itk::ExceptionObject & e)
  {
    record.error = e.GetDescription();
  }
  catch (const std::exception & e)
  {
    record.error = e.what();
  }
  return record;
}

// ------------------------------------------------------------------------------
// A RunRecord through the pipe (only with fork())
// ------------------------------------------------------------------------------
#if MESHEXTRACTION_COMPARE_FORK
namespace
{
void
Put(std::string & buffer, const void * data, std::size_t bytes)
{
  buffer.append(static_cast<const char *>(data), bytes);
}
template <typename T>
void
PutValue(std::string & buffer, const T & value)
{
  Put(buffer, &value, sizeof(T));
}
void
PutString(std::string & buffer, const std::string & s)
{
  PutValue<std::uint64_t>(buffer, s.size());
  Put(buffer, s.data(), s.size());
}

class Reader
{
public:
  explicit Reader(const std::string & buffer)
      : m_Buffer(buffer)
  {}
  void
  Get(void * data, std::size_t bytes)
  {
    if (m_Offset + bytes > m_Buffer.size())
    {
      itkGenericExceptionMacro("meshextraction-compare: truncated result from the child process");
    }
    std::memcpy(data, m_Buffer.data() + m_Offset, bytes);
    m_Offset += bytes;
  }
  template <typename T>
  T
  GetValue()
  {
    T value;
    Get(&value, sizeof(T));
    return value;
  }
  std::string
  GetString()
  {
    const auto  n = GetValue<std::uint64_t>();
    std::string s(n, '\0');
    Get(s.data(), n);
    return s;
  }

private:
  const std::string & m_Buffer;
  std::size_t         m_Offset{ 0 };
};

constexpr std::uint32_t kMagic = 0x4d454331; // "MEC1"

/** The mesh of a record: its points, then its triangles. */
void
PutMesh(std::string & b, const ME::IndexedTriangleMesh & mesh)
{
  PutValue<std::uint64_t>(b, mesh.points.size());
  for (const auto & p : mesh.points)
  {
    const double xyz[3] = { p[0], p[1], p[2] };
    Put(b, xyz, sizeof(xyz));
  }
  PutValue<std::uint64_t>(b, mesh.triangles.size());
  Put(b, mesh.triangles.data(), mesh.triangles.size() * sizeof(ME::TriangleIndices));
}

ME::IndexedTriangleMesh
GetMesh(Reader & in)
{
  ME::IndexedTriangleMesh mesh;
  const auto              numberOfPoints = in.GetValue<std::uint64_t>();
  mesh.points.resize(numberOfPoints);
  mesh.pointIds.resize(numberOfPoints);
  for (std::uint64_t i = 0; i < numberOfPoints; ++i)
  {
    double xyz[3];
    in.Get(xyz, sizeof(xyz));
    mesh.points[i] = ME::MakeVec3(xyz[0], xyz[1], xyz[2]);
    mesh.pointIds[i] = static_cast<itk::IdentifierType>(i);
  }
  const auto numberOfTriangles = in.GetValue<std::uint64_t>();
  mesh.triangles.resize(numberOfTriangles);
  in.Get(mesh.triangles.data(), numberOfTriangles * sizeof(ME::TriangleIndices));
  mesh.cellIds.resize(numberOfTriangles);
  for (std::uint64_t i = 0; i < numberOfTriangles; ++i)
  {
    mesh.cellIds[i] = static_cast<itk::IdentifierType>(i);
  }
  return mesh;
}

std::string
SerializeRecord(const RunRecord & r)
{
  std::string b;
  PutValue(b, kMagic);
  PutValue<std::uint8_t>(b, r.ok ? 1 : 0);
  PutString(b, r.error);
  PutValue<std::uint64_t>(b, r.seconds.size());
  Put(b, r.seconds.data(), r.seconds.size() * sizeof(double));
  PutValue(b, r.baselineKB);
  PutValue(b, r.peakKB);
  PutString(b, r.notes);
  PutString(b, r.threads);
  PutValue(b, r.droppedPoints);
  PutMesh(b, r.mesh);
  return b;
}

RunRecord
DeserializeRecord(const std::string & buffer)
{
  Reader in(buffer);
  if (in.GetValue<std::uint32_t>() != kMagic)
  {
    itkGenericExceptionMacro("meshextraction-compare: unexpected data from the child process");
  }
  RunRecord r;
  r.ok = in.GetValue<std::uint8_t>() != 0;
  r.error = in.GetString();
  r.seconds.resize(in.GetValue<std::uint64_t>());
  in.Get(r.seconds.data(), r.seconds.size() * sizeof(double));
  r.baselineKB = in.GetValue<std::int64_t>();
  r.peakKB = in.GetValue<std::int64_t>();
  r.notes = in.GetString();
  r.threads = in.GetString();
  r.droppedPoints = in.GetValue<std::uint64_t>();
  r.mesh = GetMesh(in);
  return r;
}
} // namespace

// ------------------------------------------------------------------------------
// The child process
// ------------------------------------------------------------------------------
namespace
{
bool
WriteAll(int fd, const std::string & data)
{
  std::size_t written = 0;
  while (written < data.size())
  {
    const ssize_t n = ::write(fd, data.data() + written, data.size() - written);
    if (n < 0 && errno == EINTR)
    {
      continue;
    }
    if (n <= 0)
    {
      return false;
    }
    written += static_cast<std::size_t>(n);
  }
  return true;
}

/** Everything the child sent until it closed the pipe. */
std::string
ReadAll(int fd)
{
  std::string buffer;
  char        chunk[1 << 16];
  for (;;)
  {
    const ssize_t n = ::read(fd, chunk, sizeof(chunk));
    if (n < 0 && errno == EINTR)
    {
      continue;
    }
    if (n <= 0)
    {
      break;
    }
    buffer.append(chunk, static_cast<std::size_t>(n));
  }
  return buffer;
}

/** The child's part: run, send the record through `fd`, and leave without running
 * static destructors (TBB, ITK). */
[[noreturn]] void
RunChild(const Method & method, const ExtractionInput & input, unsigned int repeat, unsigned int threads, int fd)
{
  const RunRecord record = RunInProcess(method, input, repeat, threads, true);
  const bool      ok = WriteAll(fd, SerializeRecord(record));
  ::close(fd);
  std::cerr.flush();
  ::_exit(ok ? 0 : 3);
}

/** The record the child sent, or a failed one that says how the child ended. */
RunRecord
RecordFromChild(int status, const std::string & buffer)
{
  if (WIFSIGNALED(status))
  {
    RunRecord failed;
    failed.error = "the child process running it was killed by signal " + std::to_string(WTERMSIG(status)) + " (" +
                   strsignal(WTERMSIG(status)) + ")";
    return failed;
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || buffer.empty())
  {
    RunRecord failed;
    failed.error = "the child process running it failed (exit status " +
                   std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) + ")";
    return failed;
  }
  return DeserializeRecord(buffer);
}
} // namespace

RunRecord
RunInChildProcess(const Method & method, const ExtractionInput & input, unsigned int repeat, unsigned int threads)
{
  int fds[2];
  if (::pipe(fds) != 0)
  {
    itkGenericExceptionMacro("meshextraction-compare: pipe() failed: " << std::strerror(errno));
  }
  std::cout.flush();
  std::cerr.flush();
  malloc_trim(0); // give freed heap back, so the child starts from the input's own pages
  const pid_t pid = ::fork();
  if (pid < 0)
  {
    ::close(fds[0]);
    ::close(fds[1]);
    itkGenericExceptionMacro("meshextraction-compare: fork() failed: " << std::strerror(errno));
  }
  if (pid == 0)
  {
    ::close(fds[0]);
    RunChild(method, input, repeat, threads, fds[1]);
  }
  ::close(fds[1]);
  const std::string buffer = ReadAll(fds[0]);
  ::close(fds[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR)
  {}
  return RecordFromChild(status, buffer);
}
#else
RunRecord
RunInChildProcess(const Method & method, const ExtractionInput & input, unsigned int repeat, unsigned int threads)
{
  return RunInProcess(method, input, repeat, threads, false);
}
#endif

} // namespace MeshExtractionCompare
