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
// The mesh-file formats by extension, the polygon mesh and its triangles, and the
// parsing helpers the formats share.

#include "itkMeshExtractionMeshFileParsing.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <charconv>
#include <cstdlib>

namespace itk
{
namespace MeshExtraction
{
// ------------------------------------------------------------------------------
// Formats
// ------------------------------------------------------------------------------
MeshFileFormat
MeshFileFormatFromFileName(const std::string & fileName)
{
  const auto dot = fileName.find_last_of('.');
  const auto slash = fileName.find_last_of("/\\");
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash))
  {
    return MeshFileFormat::Unknown;
  }
  const std::string extension = detail::Lower(std::string_view(fileName).substr(dot + 1));
  static const std::pair<const char *, MeshFileFormat> table[] = {
    { "vtk", MeshFileFormat::VTKLegacy }, { "vtp", MeshFileFormat::VTKXMLPolyData },
    { "ply", MeshFileFormat::PLY },       { "stl", MeshFileFormat::STL },
    { "obj", MeshFileFormat::OBJ },       { "off", MeshFileFormat::OFF }
  };
  for (const auto & entry : table)
  {
    if (extension == entry.first)
    {
      return entry.second;
    }
  }
  return MeshFileFormat::Unknown;
}

const char *
MeshFileFormatName(MeshFileFormat format)
{
  switch (format)
  {
    case MeshFileFormat::VTKLegacy:
      return "VTK legacy";
    case MeshFileFormat::VTKXMLPolyData:
      return "VTK XML PolyData";
    case MeshFileFormat::PLY:
      return "PLY";
    case MeshFileFormat::STL:
      return "STL";
    case MeshFileFormat::OBJ:
      return "OBJ";
    case MeshFileFormat::OFF:
      return "OFF";
    case MeshFileFormat::Unknown:
      break;
  }
  return "unknown";
}

PolygonMesh
ReadPolygonMeshFile(const std::string & fileName)
{
  return ReadPolygonMeshFile(fileName, MeshFileFormatFromFileName(fileName));
}

PolygonMesh
ReadPolygonMeshFile(const std::string & fileName, MeshFileFormat format)
{
  namespace P = detail;
  switch (format)
  {
    case MeshFileFormat::VTKLegacy:
      return P::ReadVTKLegacyFile(fileName);
    case MeshFileFormat::VTKXMLPolyData:
      return P::ReadVTKXMLPolyDataFile(fileName);
    case MeshFileFormat::PLY:
      return P::ReadPLYPolygonFile(fileName);
    case MeshFileFormat::STL:
      return P::ReadSTLFile(fileName);
    case MeshFileFormat::OBJ:
      return P::ReadOBJFile(fileName);
    case MeshFileFormat::OFF:
      return P::ReadOFFFile(fileName);
    case MeshFileFormat::Unknown:
      break;
  }
  itkGenericExceptionMacro(<< "Cannot read the mesh file '" << fileName
                           << "': its extension names no format MeshExtraction reads (.vtk, .vtp, .ply, .stl, "
                              ".obj, .off).");
}

void
WritePolygonMeshFile(const std::string & fileName, const PolygonMesh & mesh, const MeshFileWriteOptions & options)
{
  WritePolygonMeshFile(fileName, mesh, MeshFileFormatFromFileName(fileName), options);
}

void
WritePolygonMeshFile(const std::string &          fileName,
                     const PolygonMesh &          mesh,
                     MeshFileFormat               format,
                     const MeshFileWriteOptions & options)
{
  namespace P = detail;
  switch (format)
  {
    case MeshFileFormat::VTKLegacy:
      return P::WriteVTKLegacyFile(fileName, mesh, options);
    case MeshFileFormat::VTKXMLPolyData:
      return P::WriteVTKXMLPolyDataFile(fileName, mesh, options);
    case MeshFileFormat::PLY:
      return P::WritePLYPolygonFile(fileName, mesh, options);
    case MeshFileFormat::STL:
      return P::WriteSTLFile(fileName, mesh, options);
    case MeshFileFormat::OBJ:
      return P::WriteOBJFile(fileName, mesh, options);
    case MeshFileFormat::OFF:
      return P::WriteOFFFile(fileName, mesh, options);
    case MeshFileFormat::Unknown:
      break;
  }
  itkGenericExceptionMacro(<< "Cannot write the mesh file '" << fileName
                           << "': its extension names no format MeshExtraction writes (.vtk, .vtp, .ply, .stl, "
                              ".obj, .off).");
}

// ------------------------------------------------------------------------------
// Polygons and triangles
// ------------------------------------------------------------------------------
void
PolygonMesh::AddPolygon(const std::uint32_t * corners, std::size_t numberOfCorners)
{
  polygonIndices.insert(polygonIndices.end(), corners, corners + numberOfCorners);
  polygonOffsets.push_back(static_cast<std::uint32_t>(polygonIndices.size()));
}

void
RequireCoordinatesWithin(const PolygonMesh & polygons, double limit, const char * typeName, const std::string & what)
{
  for (std::size_t i = 0; i < polygons.points.size(); ++i)
  {
    for (unsigned int d = 0; d < 3; ++d)
    {
      const double value = polygons.points[i][d];
      if (!(std::abs(value) <= limit))
      {
        itkGenericExceptionMacro(<< what << ": point " << i << " has the coordinate " << value
                                 << ", beyond the range of " << typeName << " coordinates (+-" << limit << ")");
      }
    }
  }
}

IndexedTriangleMesh
TriangulatePolygonMesh(const PolygonMesh & mesh)
{
  IndexedTriangleMesh out;
  out.points = mesh.points;
  out.pointIds.resize(mesh.points.size());
  for (std::size_t i = 0; i < mesh.points.size(); ++i)
  {
    out.pointIds[i] = i;
  }
  out.numberOfIgnoredCells = mesh.numberOfIgnoredCells;
  out.triangles.reserve(mesh.polygonIndices.size() / 3);
  for (std::size_t p = 0; p < mesh.NumberOfPolygons(); ++p)
  {
    const std::size_t     n = mesh.PolygonSize(p);
    const std::uint32_t * c = mesh.Polygon(p);
    if (n < 3)
    {
      ++out.numberOfIgnoredCells;
      continue;
    }
    if (n == 4)
    {
      TriangleIndices t0;
      TriangleIndices t1;
      detail::SplitQuad(out, c, t0, t1);
      out.triangles.push_back(t0);
      out.triangles.push_back(t1);
      out.cellIds.insert(out.cellIds.end(), 2, p);
      ++out.numberOfSplitQuads;
      continue;
    }
    for (std::size_t k = 1; k + 1 < n; ++k)
    {
      out.triangles.push_back({ c[0], c[k], c[k + 1] });
      out.cellIds.push_back(p);
    }
  }
  return out;
}

PolygonMesh
MakePolygonMesh(const IndexedTriangleMesh & mesh)
{
  PolygonMesh out;
  out.points = mesh.points;
  out.polygonOffsets.reserve(mesh.triangles.size() + 1);
  out.polygonIndices.reserve(3 * mesh.triangles.size());
  for (const TriangleIndices & t : mesh.triangles)
  {
    out.AddPolygon(t.data(), 3);
  }
  return out;
}

// ------------------------------------------------------------------------------
// Parsing helpers
// ------------------------------------------------------------------------------
namespace detail
{
void
FailToRead(const char * format, const std::string & fileName, const std::string & problem)
{
  itkGenericExceptionMacro(<< "Cannot read the " << format << " file '" << fileName << "': " << problem << '.');
}

void
FailToWrite(const char * format, const std::string & fileName, const std::string & problem)
{
  itkGenericExceptionMacro(<< "Cannot write the " << format << " file '" << fileName << "': " << problem << '.');
}

std::string
ReadWholeFile(const char * format, const std::string & fileName)
{
  std::ifstream in(fileName, std::ios::binary);
  if (!in)
  {
    FailToRead(format, fileName, "no such file, or not readable");
  }
  std::string data;
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  if (size < 0)
  {
    FailToRead(format, fileName, "it cannot be read (a directory?)");
  }
  data.resize(static_cast<std::size_t>(size));
  in.seekg(0, std::ios::beg);
  if (!in.read(&data[0], static_cast<std::streamsize>(size)))
  {
    FailToRead(format, fileName, "reading it failed");
  }
  if (data.empty())
  {
    FailToRead(format, fileName, "it is empty");
  }
  return data;
}

std::ofstream
OpenForWriting(const char * format, const std::string & fileName)
{
  std::ofstream out(fileName, std::ios::binary);
  if (!out)
  {
    FailToWrite(format, fileName, "it cannot be opened for writing");
  }
  return out;
}

void
FinishWriting(std::ofstream & out, const char * format, const std::string & fileName)
{
  out.flush();
  const bool written = static_cast<bool>(out);
  out.close();
  if (!written || !out)
  {
    FailToWrite(format, fileName, "writing failed (a full disk?)");
  }
}

bool
ParseInteger(std::string_view text, std::int64_t & value)
{
  if (!text.empty() && text.front() == '+')
  {
    text.remove_prefix(1);
  }
  const auto result = std::from_chars(text.data(), text.data() + text.size(), value);
  return !text.empty() && result.ec == std::errc() && result.ptr == text.data() + text.size();
}

namespace
{
template <typename T>
bool
ParseReal(std::string_view text, T & value)
{
  if (!text.empty() && text.front() == '+')
  {
    text.remove_prefix(1);
  }
  const auto result = std::from_chars(text.data(), text.data() + text.size(), value);
  // A value too large or too small to represent: from_chars leaves `value` unchanged;
  // strtod or strtof (the program keeps the C locale) gives infinity or the underflowed value.
  if (result.ec == std::errc::result_out_of_range && result.ptr == text.data() + text.size())
  {
    const std::string copy(text);
    if constexpr (std::is_same_v<T, float>)
    {
      value = std::strtof(copy.c_str(), nullptr);
    }
    else
    {
      value = std::strtod(copy.c_str(), nullptr);
    }
    return true;
  }
  return !text.empty() && result.ec == std::errc() && result.ptr == text.data() + text.size();
}
} // namespace

bool
ParseDouble(std::string_view text, double & value)
{
  return ParseReal(text, value);
}

bool
ParseFloat(std::string_view text, float & value)
{
  return ParseReal(text, value);
}

bool
IsLittleEndian()
{
  const std::uint16_t one = 1;
  unsigned char       first;
  std::memcpy(&first, &one, 1);
  return first == 1;
}

void
SwapBytes(unsigned char * data, std::size_t size, std::size_t n)
{
  for (std::size_t i = 0; i < n; ++i)
  {
    std::reverse(data + i * size, data + (i + 1) * size);
  }
}

double
DecodeBinaryValue(const DataType & type, const unsigned char * bytes, bool littleEndian)
{
  unsigned char b[8];
  // type.size is 1, 2, 4 or 8; the bound tells GCC's -O3 too (it warned of an overflow).
  const std::size_t size = std::min<std::size_t>(type.size, sizeof(b));
  std::memcpy(b, bytes, size);
  if (littleEndian != IsLittleEndian())
  {
    std::reverse(b, b + size);
  }
  auto as = [&b](auto value) {
    std::memcpy(&value, b, sizeof(value));
    return static_cast<double>(value);
  };
  if (!type.isInteger)
  {
    return type.size == 4 ? as(float()) : as(double());
  }
  switch (type.size)
  {
    case 1:
      return type.isSigned ? as(std::int8_t()) : as(std::uint8_t());
    case 2:
      return type.isSigned ? as(std::int16_t()) : as(std::uint16_t());
    case 4:
      return type.isSigned ? as(std::int32_t()) : as(std::uint32_t());
    default:
      return type.isSigned ? as(std::int64_t()) : as(std::uint64_t());
  }
}

std::string
Lower(std::string_view text)
{
  std::string out(text);
  for (char & c : out)
  {
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  return out;
}

void
Cursor::SkipWhitespace()
{
  while (m_Position < m_Data.size() &&
         (m_Data[m_Position] == ' ' || m_Data[m_Position] == '\t' || m_Data[m_Position] == '\r' ||
          m_Data[m_Position] == '\n' || m_Data[m_Position] == '\f' || m_Data[m_Position] == '\v'))
  {
    ++m_Position;
  }
}

std::string_view
Cursor::NextToken()
{
  SkipWhitespace();
  const std::size_t start = m_Position;
  while (m_Position < m_Data.size() && !std::isspace(static_cast<unsigned char>(m_Data[m_Position])))
  {
    ++m_Position;
  }
  return std::string_view(m_Data).substr(start, m_Position - start);
}

std::string_view
Cursor::RequireToken(const std::string & what)
{
  const std::string_view token = NextToken();
  if (token.empty())
  {
    Fail("the file ends where " + what + " should follow (a truncated file?)");
  }
  return token;
}

std::string_view
Cursor::NextLine()
{
  const std::size_t start = m_Position;
  const std::size_t end = m_Data.find('\n', start);
  const std::size_t stop = end == std::string::npos ? m_Data.size() : end;
  m_Position = end == std::string::npos ? m_Data.size() : end + 1;
  std::string_view line = std::string_view(m_Data).substr(start, stop - start);
  if (!line.empty() && line.back() == '\r')
  {
    line.remove_suffix(1);
  }
  return line;
}

std::int64_t
Cursor::RequireInteger(const std::string & what)
{
  const std::string_view token = RequireToken(what);
  std::int64_t           value = 0;
  if (!ParseInteger(token, value))
  {
    Fail("expected " + what + " (a whole number), found '" + std::string(token.substr(0, 40)) + "'");
  }
  return value;
}

double
Cursor::RequireDouble(const std::string & what)
{
  const std::string_view token = RequireToken(what);
  double                 value = 0.0;
  if (!ParseDouble(token, value))
  {
    Fail("expected " + what + " (a number), found '" + std::string(token.substr(0, 40)) + "'");
  }
  return value;
}

float
Cursor::RequireFloat(const std::string & what)
{
  const std::string_view token = RequireToken(what);
  float                  value = 0.0f;
  if (!ParseFloat(token, value))
  {
    Fail("expected " + what + " (a number), found '" + std::string(token.substr(0, 40)) + "'");
  }
  return value;
}

const unsigned char *
Cursor::RequireBytes(std::size_t size, const std::string & what)
{
  if (size > Remaining())
  {
    Fail("the file ends inside " + what + " (" + std::to_string(Remaining()) + " of " + std::to_string(size) +
         " bytes; a truncated file?)");
  }
  const auto * bytes = reinterpret_cast<const unsigned char *>(m_Data.data() + m_Position);
  m_Position += size;
  return bytes;
}
} // namespace detail

} // namespace MeshExtraction
} // namespace itk
