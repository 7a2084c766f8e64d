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
#include "itkMeshExtractionPLY.h"
#include "itkMeshExtractionMeshFileParsing.h"
#include "itkMacro.h"
#include "itkNumberToString.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>
#include <vector>

namespace itk
{
namespace MeshExtraction
{
namespace
{
enum class PLYFormat
{
  ASCII,
  BinaryLittleEndian,
  BinaryBigEndian
};

enum class PLYType
{
  Int8,
  UInt8,
  Int16,
  UInt16,
  Int32,
  UInt32,
  Float32,
  Float64
};

struct PLYProperty
{
  std::string name;
  PLYType     type{ PLYType::Float32 };
  bool        isList{ false };
  PLYType     countType{ PLYType::UInt8 };
};

struct PLYElement
{
  std::string              name;
  std::uint64_t            count{ 0 };
  std::vector<PLYProperty> properties;
};

struct PLYHeader
{
  PLYFormat               format{ PLYFormat::ASCII };
  std::vector<PLYElement> elements;
};

[[noreturn]] void
Fail(const std::string & fileName, const std::string & problem)
{
  itkGenericExceptionMacro(<< "Cannot read the PLY file " << fileName << ": " << problem << '.');
}

PLYType
ParseType(const std::string & word, const std::string & fileName)
{
  static const std::pair<const char *, PLYType> names[] = {
    { "char", PLYType::Int8 },      { "int8", PLYType::Int8 },       { "uchar", PLYType::UInt8 },
    { "uint8", PLYType::UInt8 },    { "short", PLYType::Int16 },     { "int16", PLYType::Int16 },
    { "ushort", PLYType::UInt16 },  { "uint16", PLYType::UInt16 },   { "int", PLYType::Int32 },
    { "int32", PLYType::Int32 },    { "uint", PLYType::UInt32 },     { "uint32", PLYType::UInt32 },
    { "float", PLYType::Float32 },  { "float32", PLYType::Float32 }, { "double", PLYType::Float64 },
    { "float64", PLYType::Float64 }
  };
  for (const auto & n : names)
  {
    if (word == n.first)
    {
      return n.second;
    }
  }
  Fail(fileName, "unknown property type '" + word + "'");
}

std::size_t
SizeOf(PLYType type)
{
  switch (type)
  {
    case PLYType::Int8:
    case PLYType::UInt8:
      return 1;
    case PLYType::Int16:
    case PLYType::UInt16:
      return 2;
    case PLYType::Int32:
    case PLYType::UInt32:
    case PLYType::Float32:
      return 4;
    case PLYType::Float64:
      return 8;
  }
  return 0;
}

PLYHeader
ReadHeader(std::istream & in, const std::string & fileName)
{
  std::string line;
  if (!std::getline(in, line) || line.substr(0, 3) != "ply")
  {
    Fail(fileName, "it does not start with 'ply'");
  }
  PLYHeader header;
  bool      haveFormat = false;
  while (std::getline(in, line))
  {
    if (!line.empty() && line.back() == '\r')
    {
      line.pop_back();
    }
    std::istringstream words(line);
    std::string        keyword;
    words >> keyword;
    if (keyword == "end_header")
    {
      if (!haveFormat)
      {
        Fail(fileName, "the header has no format line");
      }
      return header;
    }
    if (keyword == "format")
    {
      std::string format;
      words >> format;
      haveFormat = true;
      if (format == "ascii")
      {
        header.format = PLYFormat::ASCII;
      }
      else if (format == "binary_little_endian")
      {
        header.format = PLYFormat::BinaryLittleEndian;
      }
      else if (format == "binary_big_endian")
      {
        header.format = PLYFormat::BinaryBigEndian;
      }
      else
      {
        Fail(fileName, "unknown format '" + format + "'");
      }
    }
    else if (keyword == "element")
    {
      PLYElement element;
      if (!(words >> element.name >> element.count))
      {
        Fail(fileName, "an element line without a name and a count: '" + line + "'");
      }
      header.elements.push_back(element);
    }
    else if (keyword == "property")
    {
      if (header.elements.empty())
      {
        Fail(fileName, "a property before any element");
      }
      PLYProperty property;
      std::string type;
      words >> type;
      if (type == "list")
      {
        std::string countType, itemType;
        words >> countType >> itemType;
        property.isList = true;
        property.countType = ParseType(countType, fileName);
        property.type = ParseType(itemType, fileName);
      }
      else
      {
        property.type = ParseType(type, fileName);
      }
      words >> property.name;
      header.elements.back().properties.push_back(property);
    }
    // comment, obj_info and unknown lines are skipped.
  }
  Fail(fileName, "the header has no end_header line");
}

/** Reads one value of `type` as a double, from ASCII or binary. */
class ValueReader
{
public:
  ValueReader(std::istream & in, PLYFormat format, const std::string & fileName)
      : m_In(in)
      , m_Format(format)
      , m_FileName(fileName)
  {}

  double
  Read(PLYType type)
  {
    if (m_Format == PLYFormat::ASCII)
    {
      double value = 0.0;
      if (!(m_In >> value))
      {
        Fail(m_FileName, "the data end early or hold a word that is not a number");
      }
      return value;
    }
    unsigned char     bytes[8];
    const std::size_t size = SizeOf(type);
    if (!m_In.read(reinterpret_cast<char *>(bytes), static_cast<std::streamsize>(size)))
    {
      Fail(m_FileName, "the data end before every element was read (truncated file)");
    }
    const bool swap = (m_Format == PLYFormat::BinaryBigEndian) == IsLittleEndian();
    if (swap)
    {
      for (std::size_t k = 0; k < size / 2; ++k)
      {
        std::swap(bytes[k], bytes[size - 1 - k]);
      }
    }
    return Decode(type, bytes);
  }

  /** A list's number of items: a whole number no larger than the bytes left. */
  std::size_t
  ReadCount(PLYType type)
  {
    const double count = Read(type);
    if (!(count >= 0.0 && count == std::floor(count)))
    {
      Fail(m_FileName, "a list has " + std::to_string(count) + " items");
    }
    // Only long lists need the (slower) look at the position.
    if (count > 1024.0)
    {
      const auto position = static_cast<std::size_t>(std::max<std::streamoff>(m_In.tellg(), 0));
      if (count > static_cast<double>(m_FileSize - std::min(position, m_FileSize)))
      {
        Fail(m_FileName, "a list has " + std::to_string(count) + " items, more than the file holds");
      }
    }
    return static_cast<std::size_t>(count);
  }

  void
  SetFileSize(std::size_t size)
  {
    m_FileSize = size;
  }

  /** The bytes of the file after the current position. */
  std::size_t
  RemainingBytes()
  {
    const auto position = static_cast<std::size_t>(std::max<std::streamoff>(m_In.tellg(), 0));
    return m_FileSize - std::min(position, m_FileSize);
  }

  const std::string &
  FileName() const
  {
    return m_FileName;
  }

private:
  static bool
  IsLittleEndian()
  {
    const std::uint16_t one = 1;
    unsigned char       first;
    std::memcpy(&first, &one, 1);
    return first == 1;
  }

  template <typename T>
  static double
  As(const unsigned char * bytes)
  {
    T value;
    std::memcpy(&value, bytes, sizeof(T));
    return static_cast<double>(value);
  }

  static double
  Decode(PLYType type, const unsigned char * b)
  {
    switch (type)
    {
      case PLYType::Int8:
        return As<std::int8_t>(b);
      case PLYType::UInt8:
        return As<std::uint8_t>(b);
      case PLYType::Int16:
        return As<std::int16_t>(b);
      case PLYType::UInt16:
        return As<std::uint16_t>(b);
      case PLYType::Int32:
        return As<std::int32_t>(b);
      case PLYType::UInt32:
        return As<std::uint32_t>(b);
      case PLYType::Float32:
        return As<float>(b);
      case PLYType::Float64:
        return As<double>(b);
    }
    return 0.0;
  }

  std::istream &      m_In;
  PLYFormat           m_Format;
  const std::string & m_FileName;
  std::size_t         m_FileSize{ std::numeric_limits<std::size_t>::max() };
};

void
ReadVertices(ValueReader & reader, const PLYElement & element, PolygonMesh & mesh, const std::string & fileName)
{
  int axis[3] = { -1, -1, -1 };
  for (std::size_t k = 0; k < element.properties.size(); ++k)
  {
    const std::string & name = element.properties[k].name;
    if (name == "x" || name == "y" || name == "z")
    {
      axis[name[0] - 'x'] = static_cast<int>(k);
    }
  }
  if (axis[0] < 0 || axis[1] < 0 || axis[2] < 0)
  {
    Fail(fileName, "its vertices have no x, y and z properties");
  }
  if (element.count >= std::numeric_limits<std::uint32_t>::max())
  {
    Fail(fileName, "it has " + std::to_string(element.count) + " vertices, more than the supported 2^32 - 1");
  }
  for (std::uint64_t v = 0; v < element.count; ++v)
  {
    Vec3 p = MakeVec3(0, 0, 0);
    for (std::size_t k = 0; k < element.properties.size(); ++k)
    {
      const PLYProperty & property = element.properties[k];
      const std::size_t   items = property.isList ? reader.ReadCount(property.countType) : 1;
      for (std::size_t i = 0; i < items; ++i)
      {
        const double value = reader.Read(property.type);
        for (unsigned int d = 0; d < 3; ++d)
        {
          if (axis[d] == static_cast<int>(k))
          {
            p[d] = value;
          }
        }
      }
    }
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
    {
      Fail(fileName, "vertex " + std::to_string(v) + " has a coordinate that is not finite");
    }
    mesh.points.push_back(p);
  }
}

/** The faces' vertex_indices (or vertex_index) lists as polygons; other properties
 * are read past. */
void
ReadFaces(ValueReader & reader, const PLYElement & element, PolygonMesh & mesh, const std::string & fileName)
{
  std::vector<std::uint32_t> corners;
  for (std::uint64_t f = 0; f < element.count; ++f)
  {
    for (const PLYProperty & property : element.properties)
    {
      const bool isIndices = property.isList && (property.name == "vertex_indices" || property.name == "vertex_index");
      const std::size_t items = property.isList ? reader.ReadCount(property.countType) : 1;
      corners.clear();
      for (std::size_t i = 0; i < items; ++i)
      {
        const double value = reader.Read(property.type);
        if (!isIndices)
        {
          continue;
        }
        if (!(value >= 0.0 && value < static_cast<double>(mesh.points.size())))
        {
          Fail(fileName,
               "face " + std::to_string(f) + " names the vertex " + std::to_string(value) + ", but there are " +
                 std::to_string(mesh.points.size()));
        }
        corners.push_back(static_cast<std::uint32_t>(value));
      }
      if (isIndices && corners.size() < 3)
      {
        // PLY's lines are an element of their own ("edge"); a face is a surface's.
        Fail(fileName,
             "face " + std::to_string(f) + " has " + std::to_string(corners.size()) +
               " vertices; a face needs at least 3");
      }
      if (isIndices)
      {
        mesh.AddPolygon(corners.data(), corners.size());
      }
    }
  }
}

void
SkipElement(ValueReader & reader, const PLYElement & element)
{
  // An element without properties holds no data, whatever its count; one with
  // properties takes at least a byte per entry, so a count beyond the file is a lie
  // (that would otherwise be skipped value by value for ever).
  if (element.properties.empty())
  {
    return;
  }
  if (element.count > reader.RemainingBytes())
  {
    Fail(reader.FileName(),
         "its element '" + element.name + "' declares " + std::to_string(element.count) +
           " entries, more than the file holds");
  }
  for (std::uint64_t e = 0; e < element.count; ++e)
  {
    for (const PLYProperty & property : element.properties)
    {
      const std::size_t items = property.isList ? reader.ReadCount(property.countType) : 1;
      for (std::size_t i = 0; i < items; ++i)
      {
        reader.Read(property.type);
      }
    }
  }
}

/** The vertices and faces of a PLY file. */
PolygonMesh
ReadPolygons(const std::string & fileName)
{
  std::ifstream in(fileName, std::ios::binary | std::ios::ate);
  if (!in)
  {
    Fail(fileName, "no such file, or not readable");
  }
  const std::streamoff size = in.tellg();
  in.seekg(0, std::ios::beg);
  const PLYHeader header = ReadHeader(in, fileName);
  if (header.format == PLYFormat::ASCII)
  {
    in.imbue(std::locale::classic());
  }
  ValueReader reader(in, header.format, fileName);
  reader.SetFileSize(size > 0 ? static_cast<std::size_t>(size) : 0);
  PolygonMesh mesh;
  bool        haveVertices = false;
  for (const PLYElement & element : header.elements)
  {
    if (element.name == "vertex")
    {
      ReadVertices(reader, element, mesh, fileName);
      haveVertices = true;
    }
    else if (element.name == "face")
    {
      if (!haveVertices)
      {
        Fail(fileName, "its faces come before its vertices");
      }
      ReadFaces(reader, element, mesh, fileName);
    }
    else
    {
      SkipElement(reader, element);
    }
  }
  if (!haveVertices)
  {
    Fail(fileName, "it has no vertex element");
  }
  return mesh;
}

} // namespace

IndexedTriangleMesh
ReadPLYFile(const std::string & fileName)
{
  const PolygonMesh   polygons = ReadPolygons(fileName);
  IndexedTriangleMesh mesh;
  mesh.points = polygons.points;
  for (std::size_t v = 0; v < mesh.points.size(); ++v)
  {
    mesh.pointIds.push_back(static_cast<IdentifierType>(v));
  }
  for (std::size_t f = 0; f < polygons.NumberOfPolygons(); ++f)
  {
    const std::uint32_t * corners = polygons.Polygon(f);
    for (std::size_t k = 1; k + 1 < polygons.PolygonSize(f); ++k)
    {
      mesh.triangles.push_back({ corners[0], corners[k], corners[k + 1] });
      mesh.cellIds.push_back(static_cast<IdentifierType>(f));
    }
  }
  return mesh;
}

void
WritePLYFile(const std::string & fileName, const IndexedTriangleMesh & mesh, bool doubleCoordinates)
{
  std::ofstream     out(fileName, std::ios::binary);
  const char *const type = doubleCoordinates ? "double" : "float";
  out << "ply\nformat binary_little_endian 1.0\ncomment MeshExtraction\nelement vertex " << mesh.points.size()
      << "\nproperty " << type << " x\nproperty " << type << " y\nproperty " << type << " z\nelement face "
      << mesh.triangles.size()
      << "\nproperty list uchar int vertex_indices\nend_header\n";
  auto put = [&out](auto value) {
    unsigned char bytes[sizeof(value)];
    std::memcpy(bytes, &value, sizeof(value));
    const std::uint16_t one = 1;
    unsigned char       first;
    std::memcpy(&first, &one, 1);
    if (first != 1) // a big-endian machine writes little-endian bytes
    {
      for (std::size_t k = 0; k < sizeof(value) / 2; ++k)
      {
        std::swap(bytes[k], bytes[sizeof(value) - 1 - k]);
      }
    }
    out.write(reinterpret_cast<const char *>(bytes), sizeof(value));
  };
  for (const Vec3 & p : mesh.points)
  {
    for (unsigned int d = 0; d < 3; ++d)
    {
      if (doubleCoordinates)
      {
        put(static_cast<double>(p[d]));
      }
      else
      {
        put(static_cast<float>(p[d]));
      }
    }
  }
  for (const TriangleIndices & t : mesh.triangles)
  {
    put(static_cast<std::uint8_t>(3));
    put(static_cast<std::int32_t>(t[0]));
    put(static_cast<std::int32_t>(t[1]));
    put(static_cast<std::int32_t>(t[2]));
  }
  out.close();
  if (!out)
  {
    itkGenericExceptionMacro(<< "Cannot write the PLY file " << fileName << '.');
  }
}
namespace detail
{
PolygonMesh
ReadPLYPolygonFile(const std::string & fileName)
{
  return ReadPolygons(fileName);
}

void
WritePLYPolygonFile(const std::string & fileName, const PolygonMesh & mesh, const MeshFileWriteOptions & options)
{
  const bool    ascii = options.encoding == MeshFileWriteOptions::Encoding::ASCII;
  std::ofstream out = OpenForWriting("PLY", fileName);
  out << "ply\nformat " << (ascii ? "ascii" : "binary_little_endian") << " 1.0\ncomment MeshExtraction\nelement vertex "
      << mesh.points.size() << "\nproperty double x\nproperty double y\nproperty double z\nelement face "
      << mesh.NumberOfPolygons() << "\nproperty list uchar int vertex_indices\nend_header\n";
  NumberToString<double> text;
  auto                   put = [&out](auto value) {
    unsigned char bytes[sizeof(value)];
    std::memcpy(bytes, &value, sizeof(value));
    if (!IsLittleEndian())
    {
      std::reverse(bytes, bytes + sizeof(value));
    }
    out.write(reinterpret_cast<const char *>(bytes), sizeof(value));
  };
  for (const Vec3 & p : mesh.points)
  {
    if (ascii)
    {
      out << text(p[0]) << ' ' << text(p[1]) << ' ' << text(p[2]) << '\n';
      continue;
    }
    put(p[0]);
    put(p[1]);
    put(p[2]);
  }
  for (std::size_t f = 0; f < mesh.NumberOfPolygons(); ++f)
  {
    if (mesh.PolygonSize(f) > 255)
    {
      FailToWrite("PLY", fileName, "polygon " + std::to_string(f) + " has more than 255 corners");
    }
    if (ascii)
    {
      out << mesh.PolygonSize(f);
    }
    else
    {
      put(static_cast<std::uint8_t>(mesh.PolygonSize(f)));
    }
    for (std::size_t k = 0; k < mesh.PolygonSize(f); ++k)
    {
      if (ascii)
      {
        out << ' ' << mesh.Polygon(f)[k];
      }
      else
      {
        put(static_cast<std::int32_t>(mesh.Polygon(f)[k]));
      }
    }
    if (ascii)
    {
      out << '\n';
    }
  }
  FinishWriting(out, "PLY", fileName);
}
} // namespace detail
} // namespace MeshExtraction
} // namespace itk
