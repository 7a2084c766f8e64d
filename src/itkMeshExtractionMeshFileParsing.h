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
#ifndef itkMeshExtractionMeshFileParsing_h
#define itkMeshExtractionMeshFileParsing_h

// What the mesh-file readers and writers of src/ share (not installed): a file read
// whole into memory, a cursor over it that never reads past its end, number parsing
// that does not depend on the locale, and the errors that name the file.

#include "itkMeshExtractionMeshFile.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <string_view>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
/** Throws "Cannot read the <format> file '<fileName>': <problem>." */
[[noreturn]] void
FailToRead(const char * format, const std::string & fileName, const std::string & problem);

/** Throws "Cannot write the <format> file '<fileName>': <problem>." */
[[noreturn]] void
FailToWrite(const char * format, const std::string & fileName, const std::string & problem);

/** The bytes of a file; FailToRead if it cannot be read. */
std::string
ReadWholeFile(const char * format, const std::string & fileName);

/** Opens a file for writing in binary mode; FailToWrite if it cannot be. */
std::ofstream
OpenForWriting(const char * format, const std::string & fileName);

/** Closes a written file; FailToWrite if a write failed (a full disk, say). */
void
FinishWriting(std::ofstream & out, const char * format, const std::string & fileName);

/** Whether `text` is a whole number (an optional sign, then digits) that fits;
 * writes it to `value`. */
bool
ParseInteger(std::string_view text, std::int64_t & value);
/** Whether `text` is a whole decimal or floating-point number (nan and inf included:
 * the callers check finiteness and say so); writes it to `value`. */
bool
ParseDouble(std::string_view text, double & value);
/** The same for single precision, rounded once from the text as a float reader does. */
bool
ParseFloat(std::string_view text, float & value);

/** Whether the machine stores numbers little-endian. */
bool
IsLittleEndian();

/** Reverses the bytes of each `size`-byte value of `data` (n values). */
void
SwapBytes(unsigned char * data, std::size_t size, std::size_t n);

/** Lower-case copy (ASCII letters only). */
std::string
Lower(std::string_view text);

/** A binary number type of the VTK formats: its name in the file, its size in bytes,
 * whether it is integer and signed. */
struct DataType
{
  const char * name;
  unsigned int size;
  bool         isInteger;
  bool         isSigned;
};

/** One binary value of `type` at `bytes`, stored little- or big-endian, as a double
 * (integers up to 2^53 exactly). */
double
DecodeBinaryValue(const DataType & type, const unsigned char * bytes, bool littleEndian);

/** \brief A read position in a file's bytes, for text and binary sections.
 *
 * Every read is bounded by the end of the data: a truncated file ends in a
 * FailToRead, never in a read past the end or a loop without progress.
 */
class Cursor
{
public:
  Cursor(const std::string & data, const char * format, const std::string & fileName)
      : m_Data(data)
      , m_Format(format)
      , m_FileName(fileName)
  {}

  bool
  AtEnd() const
  {
    return m_Position >= m_Data.size();
  }
  std::size_t
  Position() const
  {
    return m_Position;
  }
  void
  SetPosition(std::size_t position)
  {
    m_Position = std::min(position, m_Data.size());
  }
  std::size_t
  Remaining() const
  {
    return m_Data.size() - m_Position;
  }
  const std::string &
  Data() const
  {
    return m_Data;
  }

  /** Skips spaces, tabs, carriage returns and newlines. */
  void
  SkipWhitespace();
  /** The next whitespace-separated word (empty at the end of the data). */
  std::string_view
  NextToken();
  /** The next word; FailToRead saying `what` was expected at the end of the data. */
  std::string_view
  RequireToken(const std::string & what);
  /** The rest of the current line without its line break (and the position after it). */
  std::string_view
  NextLine();
  /** The next word as a whole number; FailToRead naming `what` otherwise. */
  std::int64_t
  RequireInteger(const std::string & what);
  /** The next word as a number; FailToRead naming `what` otherwise (NaN and infinite
   * values are returned: the caller names them). */
  double
  RequireDouble(const std::string & what);
  float
  RequireFloat(const std::string & what);
  /** `size` bytes; FailToRead naming `what` if the data end first. */
  const unsigned char *
  RequireBytes(std::size_t size, const std::string & what);

  [[noreturn]] void
  Fail(const std::string & problem) const
  {
    FailToRead(m_Format, m_FileName, problem);
  }

private:
  const std::string & m_Data;
  const char *        m_Format;
  const std::string & m_FileName;
  std::size_t         m_Position{ 0 };
};

/** The largest count a section of `bytesPerItem` bytes (at least) per item can hold
 * in what is left of the data: a header that promises more lies about its counts. */
inline void
RequireCountFits(const Cursor & cursor, std::uint64_t count, std::size_t bytesPerItem, const std::string & what)
{
  // (+1: the last item of a text section may end the file without a separator)
  if (count > (cursor.Remaining() + 1) / std::max<std::size_t>(bytesPerItem, 1))
  {
    cursor.Fail(what + " (" + std::to_string(count) + " by the header) need more than the " +
                std::to_string(cursor.Remaining()) + " bytes left in the file (a truncated file?)");
  }
}

/** Point `index` after checking that it is one of `numberOfPoints`. */
inline std::uint32_t
CheckedIndex(const Cursor & cursor, std::int64_t index, std::size_t numberOfPoints, const std::string & where)
{
  if (index < 0 || static_cast<std::uint64_t>(index) >= numberOfPoints)
  {
    cursor.Fail(where + " names point " + std::to_string(index) + ", but there are " + std::to_string(numberOfPoints) +
                " points");
  }
  return static_cast<std::uint32_t>(index);
}

/** A point after checking that its coordinates are finite. */
inline Vec3
CheckedPoint(const Cursor & cursor, double x, double y, double z, std::size_t index)
{
  if (!(std::isfinite(x) && std::isfinite(y) && std::isfinite(z)))
  {
    std::ostringstream os;
    os << "point " << index << " has a coordinate that is not a finite number (" << x << ' ' << y << ' ' << z << ')';
    cursor.Fail(os.str());
  }
  return MakeVec3(x, y, z);
}

/** Refuses meshes whose points the 32-bit indices of PolygonMesh cannot number. */
inline void
RequirePointCount(const Cursor & cursor, std::uint64_t numberOfPoints)
{
  if (numberOfPoints >= std::numeric_limits<std::uint32_t>::max())
  {
    cursor.Fail("it has " + std::to_string(numberOfPoints) + " points, more than the supported 2^32 - 1");
  }
}

// The formats, one translation unit each.
PolygonMesh
ReadVTKLegacyFile(const std::string & fileName);
void
WriteVTKLegacyFile(const std::string & fileName, const PolygonMesh & mesh, const MeshFileWriteOptions & options);
PolygonMesh
ReadVTKXMLPolyDataFile(const std::string & fileName);
void
WriteVTKXMLPolyDataFile(const std::string & fileName, const PolygonMesh & mesh, const MeshFileWriteOptions & options);
PolygonMesh
ReadPLYPolygonFile(const std::string & fileName);
void
WritePLYPolygonFile(const std::string & fileName, const PolygonMesh & mesh, const MeshFileWriteOptions & options);
PolygonMesh
ReadSTLFile(const std::string & fileName);
void
WriteSTLFile(const std::string & fileName, const PolygonMesh & mesh, const MeshFileWriteOptions & options);
PolygonMesh
ReadOBJFile(const std::string & fileName);
void
WriteOBJFile(const std::string & fileName, const PolygonMesh & mesh, const MeshFileWriteOptions & options);
PolygonMesh
ReadOFFFile(const std::string & fileName);
void
WriteOFFFile(const std::string & fileName, const PolygonMesh & mesh, const MeshFileWriteOptions & options);
} // namespace detail
} // namespace MeshExtraction
} // namespace itk

#endif
