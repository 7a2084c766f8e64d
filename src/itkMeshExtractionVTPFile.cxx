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
// VTK XML PolyData files (.vtp) without VTK: the tags are scanned (no general XML
// parser is needed for VTK's fixed layout), and the data arrays decoded from ascii,
// binary (base64) or appended (raw or base64) data, zlib-compressed or not.

#include "itkMeshExtractionMeshFileParsing.h"
#include "itkNumberToString.h"
#include "itk_zlib.h"

#include <map>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
namespace
{
constexpr char Format[] = "VTK XML PolyData";

// ------------------------------------------------------------------------------
// Tags
// ------------------------------------------------------------------------------
struct Tag
{
  std::string                        name;
  bool                               closing{ false };
  bool                               selfClosing{ false };
  std::map<std::string, std::string> attributes;

  std::string
  Attribute(const std::string & key, const std::string & fallback = std::string()) const
  {
    const auto found = attributes.find(key);
    return found == attributes.end() ? fallback : found->second;
  }
};

/** The attributes of a tag's text (between its name and its '>'). */
void
ParseAttributes(Cursor & cursor, std::string_view text, Tag & tag)
{
  std::size_t at = 0;
  while (at < text.size())
  {
    const std::size_t nameStart = text.find_first_not_of(" \t\r\n/", at);
    if (nameStart == std::string_view::npos)
    {
      return;
    }
    const std::size_t equals = text.find('=', nameStart);
    const std::size_t quote = equals == std::string_view::npos ? equals : text.find_first_of("\"'", equals);
    const std::size_t close = quote == std::string_view::npos ? quote : text.find(text[quote], quote + 1);
    if (close == std::string_view::npos)
    {
      cursor.Fail("the <" + tag.name + "> tag has a malformed attribute");
    }
    std::string_view name = text.substr(nameStart, equals - nameStart);
    name = name.substr(0, name.find_last_not_of(" \t\r\n") + 1);
    tag.attributes[std::string(name)] = std::string(text.substr(quote + 1, close - quote - 1));
    at = close + 1;
  }
}

/** The next tag (comments and <?xml ...?> skipped); an empty name at the end. */
Tag
NextTag(Cursor & cursor)
{
  const std::string & data = cursor.Data();
  for (;;)
  {
    const std::size_t open = data.find('<', cursor.Position());
    if (open == std::string::npos)
    {
      cursor.SetPosition(data.size());
      return Tag();
    }
    const bool        comment = data.compare(open, 4, "<!--") == 0;
    const std::size_t close = comment ? data.find("-->", open) : data.find('>', open);
    if (close == std::string::npos)
    {
      cursor.Fail("a tag is not closed (a truncated file?)");
    }
    cursor.SetPosition(close + (comment ? 3 : 1));
    if (comment || data[open + 1] == '?' || data[open + 1] == '!')
    {
      continue;
    }
    Tag              tag;
    std::string_view text = std::string_view(data).substr(open + 1, close - open - 1);
    tag.closing = !text.empty() && text.front() == '/';
    tag.selfClosing = !text.empty() && text.back() == '/';
    text.remove_prefix(tag.closing ? 1 : 0);
    const std::size_t nameEnd = std::min(text.find_first_of(" \t\r\n/"), text.size());
    tag.name = std::string(text.substr(0, nameEnd));
    ParseAttributes(cursor, text.substr(nameEnd), tag);
    return tag;
  }
}

// ------------------------------------------------------------------------------
// Data arrays
// ------------------------------------------------------------------------------

const DataType *
FindDataType(const std::string & name)
{
  static const DataType types[] = { { "Int8", 1, true, true },     { "UInt8", 1, true, false },
                                    { "Int16", 2, true, true },    { "UInt16", 2, true, false },
                                    { "Int32", 4, true, true },    { "UInt32", 4, true, false },
                                    { "Int64", 8, true, true },    { "UInt64", 8, true, false },
                                    { "Float32", 4, false, true }, { "Float64", 8, false, true } };
  for (const DataType & type : types)
  {
    if (name == type.name)
    {
      return &type;
    }
  }
  return nullptr;
}

/** A data array the mesh needs: where its values are and how they are stored. */
struct ArrayInfo
{
  const DataType * type{ nullptr };
  std::string      format;     ///< ascii, binary or appended
  std::size_t      begin{ 0 }; ///< ascii and binary: the text between the tags
  std::size_t      end{ 0 };
  std::uint64_t    offset{ 0 }; ///< appended: from the first byte after '_'
  bool             present{ false };
};

struct PieceInfo
{
  std::uint64_t numberOfPoints{ 0 };
  std::uint64_t numberOfCells[4]{ 0, 0, 0, 0 }; ///< Verts, Lines, Strips, Polys
  ArrayInfo     points;
  ArrayInfo     connectivity[2]; ///< Strips, Polys
  ArrayInfo     offsets[2];
};

/** The whole file's layout: its header attributes, pieces, appended data. */
struct Layout
{
  bool                   littleEndian{ true };
  unsigned int           headerSize{ 4 };
  bool                   compressed{ false };
  bool                   appendedIsRaw{ false };
  std::size_t            appendedStart{ std::string::npos };
  std::vector<PieceInfo> pieces;
};

/** Reads bytes from raw appended data or from base64 text, in streams: a compressed
 * array's header and its data are separate base64 streams, each padded to whole
 * four-character groups. */
class ByteSource
{
public:
  ByteSource(Cursor & cursor, std::string_view text, bool base64)
      : m_Cursor(cursor)
      , m_Text(text)
      , m_Base64(base64)
  {}

  std::vector<unsigned char>
  Read(std::size_t n, const std::string & what)
  {
    if (!m_Base64)
    {
      if (n > m_Text.size() - m_Position)
      {
        m_Cursor.Fail("the data of " + what + " end early (a truncated file?)");
      }
      std::vector<unsigned char> out(m_Text.begin() + m_Position, m_Text.begin() + m_Position + n);
      m_Position += n;
      return out;
    }
    while (m_Buffer.size() < n)
    {
      DecodeGroup(what);
    }
    std::vector<unsigned char> out(m_Buffer.begin(), m_Buffer.begin() + n);
    m_Buffer.erase(m_Buffer.begin(), m_Buffer.begin() + n);
    return out;
  }

  /** Ends a base64 stream: the rest of its last group is padding. */
  void
  EndStream()
  {
    m_Buffer.clear();
  }

private:
  void
  DecodeGroup(const std::string & what)
  {
    unsigned int value = 0;
    unsigned int bytes = 3;
    for (unsigned int k = 0; k < 4; ++k)
    {
      while (m_Position < m_Text.size() && std::isspace(static_cast<unsigned char>(m_Text[m_Position])))
      {
        ++m_Position;
      }
      if (m_Position >= m_Text.size())
      {
        m_Cursor.Fail("the base64 data of " + what + " end early (a truncated file?)");
      }
      const char c = m_Text[m_Position++];
      const int  digit = Digit(c);
      if (digit < 0 && c != '=')
      {
        m_Cursor.Fail("the base64 data of " + what + " hold the character '" + std::string(1, c) + "'");
      }
      bytes -= (c == '=' && k >= 2) ? 1 : 0;
      value = (value << 6) | static_cast<unsigned int>(digit < 0 ? 0 : digit);
    }
    for (unsigned int k = 0; k < bytes; ++k)
    {
      m_Buffer.push_back(static_cast<unsigned char>((value >> (16 - 8 * k)) & 0xff));
    }
  }

  static int
  Digit(char c)
  {
    if (c >= 'A' && c <= 'Z')
      return c - 'A';
    if (c >= 'a' && c <= 'z')
      return c - 'a' + 26;
    if (c >= '0' && c <= '9')
      return c - '0' + 52;
    return c == '+' ? 62 : (c == '/' ? 63 : -1);
  }

  Cursor &                   m_Cursor;
  std::string_view           m_Text;
  bool                       m_Base64;
  std::size_t                m_Position{ 0 };
  std::vector<unsigned char> m_Buffer;
};

/** An unsigned integer of `size` bytes in the file's byte order. */
std::uint64_t
DecodeUnsigned(const unsigned char * bytes, unsigned int size, bool littleEndian)
{
  std::uint64_t value = 0;
  for (unsigned int k = 0; k < size; ++k)
  {
    value |= static_cast<std::uint64_t>(bytes[littleEndian ? k : size - 1 - k]) << (8 * k);
  }
  return value;
}

/** The bytes of a binary or appended array: the header (the size, or the compression
 * blocks) and the data, decompressed. `expected` is the number of bytes the piece's
 * counts call for; anything else is an error. */
std::vector<unsigned char>
ReadPayload(Cursor & cursor, const Layout & layout, ByteSource & source, std::size_t expected, const std::string & what)
{
  const unsigned int h = layout.headerSize;
  if (!layout.compressed)
  {
    const std::uint64_t size = DecodeUnsigned(source.Read(h, what).data(), h, layout.littleEndian);
    if (size != expected)
    {
      cursor.Fail(what + " holds " + std::to_string(size) + " bytes, but the piece's counts call for " +
                  std::to_string(expected));
    }
    return source.Read(expected, what);
  }
  const std::vector<unsigned char> first = source.Read(3 * h, what);
  const std::uint64_t              blocks = DecodeUnsigned(first.data(), h, layout.littleEndian);
  const std::uint64_t              blockSize = DecodeUnsigned(first.data() + h, h, layout.littleEndian);
  const std::uint64_t              lastSize = DecodeUnsigned(first.data() + 2 * h, h, layout.littleEndian);
  const std::uint64_t total = blocks == 0 ? 0 : (blocks - 1) * blockSize + (lastSize == 0 ? blockSize : lastSize);
  if (blocks > cursor.Data().size() || blockSize > (std::uint64_t(1) << 32) || total != expected)
  {
    cursor.Fail(what + " is compressed into " + std::to_string(blocks) + " blocks holding " + std::to_string(total) +
                " bytes, but the piece's counts call for " + std::to_string(expected));
  }
  const std::vector<unsigned char> sizes = source.Read(static_cast<std::size_t>(blocks) * h, what);
  source.EndStream();
  std::vector<unsigned char> out(expected);
  std::size_t                at = 0;
  for (std::uint64_t b = 0; b < blocks; ++b)
  {
    const std::uint64_t compressedSize = DecodeUnsigned(sizes.data() + b * h, h, layout.littleEndian);
    if (compressedSize > cursor.Data().size())
    {
      cursor.Fail(what + " has a compressed block larger than the file");
    }
    const std::vector<unsigned char> packed = source.Read(static_cast<std::size_t>(compressedSize), what);
    uLongf       length = static_cast<uLongf>(b + 1 == blocks && lastSize != 0 ? lastSize : blockSize);
    const uLongf wanted = length;
    if (uncompress(out.data() + at, &length, packed.data(), static_cast<uLong>(packed.size())) != Z_OK ||
        length != wanted)
    {
      cursor.Fail("block " + std::to_string(b) + " of " + what + " does not decompress (corrupt zlib data)");
    }
    at += length;
  }
  return out;
}

/** One value of `type` from `bytes` as a double. */
double
DecodeValue(const DataType & type, const unsigned char * bytes, bool littleEndian)
{
  return DecodeBinaryValue(type, bytes, littleEndian);
}

/** The `count` values of an array, in whichever format it is stored. */
std::vector<double>
ReadArray(Cursor &            cursor,
          const Layout &      layout,
          const ArrayInfo &   array,
          std::uint64_t       count,
          const std::string & what)
{
  if (!array.present)
  {
    cursor.Fail("it has no " + what + " array");
  }
  const DataType &       type = *array.type;
  const std::string_view data(cursor.Data());
  if (count > data.size() * (layout.compressed ? 1100 : 1) / type.size + 16)
  {
    cursor.Fail("the piece's counts call for " + std::to_string(count) + " values of " + what +
                ", more than the file can hold");
  }
  std::vector<double> values(static_cast<std::size_t>(count));
  if (array.format == "ascii")
  {
    const std::string text(data.substr(array.begin, array.end - array.begin));
    Cursor            words(text, Format, "");
    for (double & v : values)
    {
      const std::string_view word = words.NextToken();
      std::int64_t           integer = 0;
      const bool             ok = type.isInteger ? ParseInteger(word, integer) : ParseDouble(word, v);
      if (!ok)
      {
        cursor.Fail("the ascii data of " + what + " end early or hold a word that is not a number");
      }
      v = type.isInteger ? static_cast<double>(integer) : v;
    }
    return values;
  }
  const bool       appended = array.format == "appended";
  std::string_view text;
  if (appended)
  {
    if (layout.appendedStart == std::string::npos || array.offset > data.size() - layout.appendedStart)
    {
      cursor.Fail("the appended data of " + what + " are missing (a truncated file?)");
    }
    text = data.substr(layout.appendedStart + static_cast<std::size_t>(array.offset));
  }
  else
  {
    text = data.substr(array.begin, array.end - array.begin);
  }
  ByteSource                       source(cursor, text, !(appended && layout.appendedIsRaw));
  const std::vector<unsigned char> bytes =
    ReadPayload(cursor, layout, source, values.size() * type.size, "the " + what + " array");
  for (std::size_t i = 0; i < values.size(); ++i)
  {
    values[i] = DecodeValue(type, bytes.data() + i * type.size, layout.littleEndian);
  }
  return values;
}

// ------------------------------------------------------------------------------
// The layout of the file
// ------------------------------------------------------------------------------

/** <VTKFile type="PolyData" byte_order=... header_type=... compressor=...>. */
void
ReadFileTag(Cursor & cursor, const Tag & tag, Layout & layout)
{
  if (tag.Attribute("type") != "PolyData")
  {
    cursor.Fail("it holds VTK XML data of type '" + tag.Attribute("type") +
                "'; only PolyData (surface meshes) are read");
  }
  layout.littleEndian = tag.Attribute("byte_order", "LittleEndian") != "BigEndian";
  const std::string header = tag.Attribute("header_type", "UInt32");
  if (header != "UInt32" && header != "UInt64")
  {
    cursor.Fail("its header_type '" + header + "' is neither UInt32 nor UInt64");
  }
  layout.headerSize = header == "UInt64" ? 8 : 4;
  const std::string compressor = tag.Attribute("compressor");
  if (!compressor.empty() && compressor != "vtkZLibDataCompressor")
  {
    cursor.Fail("its data are compressed with " + compressor +
                ", which is not read (only vtkZLibDataCompressor, VTK's default, and no compression)");
  }
  layout.compressed = !compressor.empty();
}

/** <DataArray ...>: its type, format and where its data are. */
ArrayInfo
ReadArrayTag(Cursor & cursor, const Tag & tag)
{
  ArrayInfo array;
  array.present = true;
  array.type = FindDataType(tag.Attribute("type"));
  if (array.type == nullptr)
  {
    cursor.Fail("the data array '" + tag.Attribute("Name") + "' has the unknown type '" + tag.Attribute("type") + "'");
  }
  array.format = tag.Attribute("format", "ascii");
  if (array.format == "appended")
  {
    std::int64_t offset = -1;
    if (!ParseInteger(tag.Attribute("offset"), offset) || offset < 0)
    {
      cursor.Fail("the appended data array '" + tag.Attribute("Name") + "' has no valid offset");
    }
    array.offset = static_cast<std::uint64_t>(offset);
    return array;
  }
  if (array.format != "ascii" && array.format != "binary")
  {
    cursor.Fail("the data array '" + tag.Attribute("Name") + "' has the unknown format '" + array.format + "'");
  }
  array.begin = cursor.Position();
  const std::size_t end = tag.selfClosing ? array.begin : cursor.Data().find("</DataArray>", array.begin);
  if (end == std::string::npos)
  {
    cursor.Fail("the data array '" + tag.Attribute("Name") + "' is not closed (a truncated file?)");
  }
  array.end = end;
  return array;
}

std::uint64_t
CountAttribute(Cursor & cursor, const Tag & tag, const char * name)
{
  std::int64_t value = 0;
  const auto   text = tag.Attribute(name, "0");
  if (!ParseInteger(text, value) || value < 0)
  {
    cursor.Fail("the piece's " + std::string(name) + " is '" + text + "'");
  }
  return static_cast<std::uint64_t>(value);
}

/** Records a data array in the piece, by the section it is in. */
void
RecordArray(Cursor & cursor, const Tag & tag, const std::string & section, PieceInfo & piece)
{
  const int cells = section == "Strips" ? 0 : (section == "Polys" ? 1 : -1);
  if (section == "Points")
  {
    piece.points = ReadArrayTag(cursor, tag);
    if (tag.Attribute("NumberOfComponents", "1") != "3")
    {
      cursor.Fail("its points have " + tag.Attribute("NumberOfComponents", "1") + " components, not 3");
    }
  }
  else if (cells >= 0 && tag.Attribute("Name") == "connectivity")
  {
    piece.connectivity[cells] = ReadArrayTag(cursor, tag);
  }
  else if (cells >= 0 && tag.Attribute("Name") == "offsets")
  {
    piece.offsets[cells] = ReadArrayTag(cursor, tag);
  }
}

Layout
ReadLayout(Cursor & cursor)
{
  Layout      layout;
  bool        haveFile = false;
  std::string section;
  for (Tag tag = NextTag(cursor); !tag.name.empty(); tag = NextTag(cursor))
  {
    if (tag.name == "VTKFile" && !tag.closing)
    {
      ReadFileTag(cursor, tag, layout);
      haveFile = true;
    }
    else if (tag.name == "Piece" && !tag.closing)
    {
      PieceInfo    piece;
      const char * names[4] = { "NumberOfVerts", "NumberOfLines", "NumberOfStrips", "NumberOfPolys" };
      piece.numberOfPoints = CountAttribute(cursor, tag, "NumberOfPoints");
      for (int k = 0; k < 4; ++k)
      {
        piece.numberOfCells[k] = CountAttribute(cursor, tag, names[k]);
      }
      layout.pieces.push_back(piece);
    }
    else if (tag.name == "DataArray" && !tag.closing && !layout.pieces.empty())
    {
      RecordArray(cursor, tag, section, layout.pieces.back());
    }
    else if (tag.name == "AppendedData" && !tag.closing)
    {
      layout.appendedIsRaw = tag.Attribute("encoding") == "raw";
      const std::size_t underscore = cursor.Data().find('_', cursor.Position());
      layout.appendedStart = underscore == std::string::npos ? underscore : underscore + 1;
      break; // raw data may hold any byte: no tags after this one are looked for
    }
    else if (tag.name != "DataArray")
    {
      section = tag.closing || tag.selfClosing ? std::string() : tag.name;
    }
  }
  if (!haveFile)
  {
    cursor.Fail("it has no <VTKFile> tag (not a VTK XML file)");
  }
  return layout;
}

/** The cells of one kind (strips or polygons) of a piece, into the mesh. */
void
AddCells(Cursor &          cursor,
         const Layout &    layout,
         const PieceInfo & piece,
         int               kind,
         std::uint32_t     first,
         PolygonMesh &     mesh)
{
  const std::uint64_t n = piece.numberOfCells[2 + kind];
  if (n == 0)
  {
    return;
  }
  const char *              name = kind == 0 ? "strip" : "polygon";
  const std::vector<double> offsets = ReadArray(cursor, layout, piece.offsets[kind], n, std::string(name) + " offsets");
  const double              size = offsets.back();
  if (!(size >= 0.0 && size <= static_cast<double>(cursor.Data().size()) * 1100.0))
  {
    cursor.Fail("the " + std::string(name) + " offsets end at " + std::to_string(size));
  }
  const std::vector<double> connectivity = ReadArray(
    cursor, layout, piece.connectivity[kind], static_cast<std::uint64_t>(size), std::string(name) + " connectivity");
  std::vector<std::uint32_t> corners;
  double                     start = 0.0;
  for (std::uint64_t c = 0; c < n; ++c)
  {
    if (!(offsets[c] >= start && offsets[c] <= size))
    {
      cursor.Fail("the " + std::string(name) + " offsets decrease at cell " + std::to_string(c));
    }
    corners.clear();
    for (auto k = static_cast<std::size_t>(start); k < static_cast<std::size_t>(offsets[c]); ++k)
    {
      const double v = connectivity[k];
      const auto   index = std::abs(v) < 9e18 ? static_cast<std::int64_t>(v) : std::int64_t{ -1 };
      corners.push_back(first +
                        CheckedIndex(cursor, index, piece.numberOfPoints, std::string(name) + ' ' + std::to_string(c)));
    }
    start = offsets[c];
    if (corners.size() < 3)
    {
      // Verts and Lines are the format's points and lines; a polygon or strip of fewer
      // than three corners is a broken surface.
      cursor.Fail(std::string(name) + ' ' + std::to_string(c) + " has " + std::to_string(corners.size()) +
                  " vertices; it needs at least 3");
    }
    for (std::size_t i = 0; kind == 0 && i + 2 < corners.size(); ++i)
    {
      const std::uint32_t t[3] = { corners[i + (i % 2)], corners[i + 1 - (i % 2)], corners[i + 2] };
      if (t[0] != t[1] && t[1] != t[2] && t[2] != t[0])
      {
        mesh.AddPolygon(t, 3);
      }
    }
    if (kind == 1)
    {
      mesh.AddPolygon(corners.data(), corners.size());
    }
  }
}

// ------------------------------------------------------------------------------
// Writing
// ------------------------------------------------------------------------------
std::string
Base64(const std::vector<unsigned char> & bytes)
{
  static const char digits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string       out;
  out.reserve(4 * ((bytes.size() + 2) / 3));
  for (std::size_t i = 0; i < bytes.size(); i += 3)
  {
    const unsigned int n = std::min<std::size_t>(3, bytes.size() - i);
    unsigned int       value = static_cast<unsigned int>(bytes[i]) << 16;
    value |= n > 1 ? static_cast<unsigned int>(bytes[i + 1]) << 8 : 0u;
    value |= n > 2 ? static_cast<unsigned int>(bytes[i + 2]) : 0u;
    for (unsigned int k = 0; k < 4; ++k)
    {
      out += k <= n ? digits[(value >> (18 - 6 * k)) & 0x3f] : '=';
    }
  }
  return out;
}

/** A DataArray element: ascii numbers, or base64 of a UInt64 byte count and the
 * values in the machine's byte order. */
template <typename T, typename TSource>
void
WriteArray(std::ostream & out, const char * type, const char * name, int components, const TSource & values, bool ascii)
{
  out << "        <DataArray type=\"" << type << "\" Name=\"" << name << "\"";
  if (components > 1)
  {
    out << " NumberOfComponents=\"" << components << "\"";
  }
  out << " format=\"" << (ascii ? "ascii" : "binary") << "\">\n          ";
  if (ascii)
  {
    NumberToString<double> text;
    for (std::size_t i = 0; i < values.size(); ++i)
    {
      out << (std::is_floating_point<T>::value ? text(static_cast<double>(values[i])) : std::to_string(values[i]))
          << ((i + 1) % 9 == 0 ? "\n          " : " ");
    }
  }
  else
  {
    const std::uint64_t        size = values.size() * sizeof(T);
    std::vector<unsigned char> bytes(sizeof(size) + size);
    std::memcpy(bytes.data(), &size, sizeof(size));
    for (std::size_t i = 0; i < values.size(); ++i)
    {
      const T value = static_cast<T>(values[i]);
      std::memcpy(bytes.data() + sizeof(size) + i * sizeof(T), &value, sizeof(T));
    }
    out << Base64(bytes);
  }
  out << "\n        </DataArray>\n";
}
} // namespace

PolygonMesh
ReadVTKXMLPolyDataFile(const std::string & fileName)
{
  const std::string data = ReadWholeFile(Format, fileName);
  Cursor            cursor(data, Format, fileName);
  const Layout      layout = ReadLayout(cursor);
  PolygonMesh       mesh;
  for (const PieceInfo & piece : layout.pieces)
  {
    const auto first = static_cast<std::uint32_t>(mesh.points.size());
    RequirePointCount(cursor, mesh.points.size() + piece.numberOfPoints);
    if (piece.numberOfPoints > 0)
    {
      const std::vector<double> xyz = ReadArray(cursor, layout, piece.points, 3 * piece.numberOfPoints, "point");
      for (std::size_t i = 0; i < piece.numberOfPoints; ++i)
      {
        mesh.points.push_back(CheckedPoint(cursor, xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2], first + i));
      }
    }
    mesh.numberOfIgnoredCells += piece.numberOfCells[0] + piece.numberOfCells[1];
    AddCells(cursor, layout, piece, 0, first, mesh);
    AddCells(cursor, layout, piece, 1, first, mesh);
  }
  if (layout.pieces.empty())
  {
    cursor.Fail("it has no <Piece>");
  }
  return mesh;
}

void
WriteVTKXMLPolyDataFile(const std::string & fileName, const PolygonMesh & mesh, const MeshFileWriteOptions & options)
{
  const bool          ascii = options.encoding == MeshFileWriteOptions::Encoding::ASCII;
  std::ofstream       out = OpenForWriting(Format, fileName);
  std::vector<double> xyz;
  xyz.reserve(3 * mesh.points.size());
  for (const Vec3 & p : mesh.points)
  {
    xyz.insert(xyz.end(), { p[0], p[1], p[2] });
  }
  const std::vector<std::uint32_t> offsets(mesh.polygonOffsets.begin() + 1, mesh.polygonOffsets.end());
  out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\""
      << (IsLittleEndian() ? "LittleEndian" : "BigEndian") << "\" header_type=\"UInt64\">\n  <PolyData>\n"
      << "    <Piece NumberOfPoints=\"" << mesh.points.size() << "\" NumberOfVerts=\"0\" NumberOfLines=\"0\" "
      << "NumberOfStrips=\"0\" NumberOfPolys=\"" << mesh.NumberOfPolygons() << "\">\n      <Points>\n";
  WriteArray<double>(out, "Float64", "Points", 3, xyz, ascii);
  out << "      </Points>\n      <Polys>\n";
  WriteArray<std::int64_t>(out, "Int64", "connectivity", 1, mesh.polygonIndices, ascii);
  WriteArray<std::int64_t>(out, "Int64", "offsets", 1, offsets, ascii);
  out << "      </Polys>\n";
  if (!mesh.cellArrays.empty())
  {
    out << "      <CellData>\n";
    for (const auto & array : mesh.cellArrays)
    {
      WriteArray<std::uint32_t>(
        out, "UInt32", array.name.c_str(), static_cast<int>(array.components), array.values, ascii);
    }
    out << "      </CellData>\n";
  }
  out << "    </Piece>\n  </PolyData>\n</VTKFile>\n";
  FinishWriting(out, Format, fileName);
}
} // namespace detail
} // namespace MeshExtraction
} // namespace itk
