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
// VTK legacy files (.vtk), DATASET POLYDATA: versions up to 4.2 (each cell its count
// and indices) and 5.x (OFFSETS and CONNECTIVITY arrays), ASCII and BINARY (big-endian).

#include "itkMeshExtractionMeshFileParsing.h"
#include "itkNumberToString.h"

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
namespace
{
constexpr char Format[] = "VTK legacy";


const DataType *
FindDataType(std::string_view name)
{
  static const DataType types[] = { { "bit", 0, true, false },
                                    { "unsigned_char", 1, true, false },
                                    { "char", 1, true, true },
                                    { "unsigned_short", 2, true, false },
                                    { "short", 2, true, true },
                                    { "unsigned_int", 4, true, false },
                                    { "int", 4, true, true },
                                    { "unsigned_long", 8, true, false },
                                    { "long", 8, true, true },
                                    { "float", 4, false, true },
                                    { "double", 8, false, true },
                                    { "vtktypeint8", 1, true, true },
                                    { "vtktypeuint8", 1, true, false },
                                    { "vtktypeint16", 2, true, true },
                                    { "vtktypeuint16", 2, true, false },
                                    { "vtktypeint32", 4, true, true },
                                    { "vtktypeuint32", 4, true, false },
                                    { "vtktypeint64", 8, true, true },
                                    { "vtktypeuint64", 8, true, false },
                                    { "vtkidtype", 4, true, true },
                                    { "vtktypefloat32", 4, false, true },
                                    { "vtktypefloat64", 8, false, true } };
  const std::string     lower = Lower(name);
  for (const DataType & type : types)
  {
    if (lower == type.name && type.size > 0)
    {
      return &type;
    }
  }
  return nullptr;
}

/** One big-endian binary value of `type` as a double (the legacy format's binary data
 * are big-endian). */
double
DecodeBigEndian(const DataType & type, const unsigned char * bytes)
{
  return DecodeBinaryValue(type, bytes, false);
}

/** The reader's state: the data, where it is, what it has read. */
struct LegacyReader
{
  LegacyReader(const std::string & data, const std::string & fileName)
      : cursor(data, Format, fileName)
  {}
  Cursor      cursor;
  bool        binary{ false };
  int         majorVersion{ 0 };
  bool        havePoints{ false };
  PolygonMesh mesh;

  /** The next keyword line's words, after skipping blank lines. */
  std::vector<std::string>
  KeywordLine()
  {
    cursor.SkipWhitespace();
    std::istringstream       words{ std::string(cursor.NextLine()) };
    std::vector<std::string> out;
    for (std::string w; words >> w;)
    {
      out.push_back(w);
    }
    return out;
  }

  /** `count` values of `type` (ASCII words or big-endian binary) as doubles; a float
   * type is parsed in single precision, as VTK and ITK store it. */
  std::vector<double>
  ReadValues(const DataType & type, std::uint64_t count, const std::string & what)
  {
    RequireCountFits(cursor, count, binary ? type.size : 2, what);
    std::vector<double> values(static_cast<std::size_t>(count));
    if (binary)
    {
      const unsigned char * bytes = cursor.RequireBytes(type.size * values.size(), what);
      for (std::size_t i = 0; i < values.size(); ++i)
      {
        values[i] = DecodeBigEndian(type, bytes + i * type.size);
      }
      return values;
    }
    for (double & value : values)
    {
      if (type.isInteger)
      {
        value = static_cast<double>(cursor.RequireInteger(what));
      }
      else
      {
        value = type.size == 4 ? static_cast<double>(cursor.RequireFloat(what)) : cursor.RequireDouble(what);
      }
    }
    return values;
  }

  const DataType &
  RequireDataType(const std::string & name, const std::string & where)
  {
    const DataType * type = FindDataType(name);
    if (type == nullptr)
    {
      cursor.Fail(where + " has the data type '" + name + "', which is not one of VTK's numeric types");
    }
    return *type;
  }

  std::uint64_t
  RequireCount(const std::vector<std::string> & words, std::size_t k, const std::string & what)
  {
    std::int64_t count = -1;
    if (words.size() <= k || !ParseInteger(words[k], count) || count < 0)
    {
      cursor.Fail("the line '" + Join(words) + "' does not give " + what);
    }
    return static_cast<std::uint64_t>(count);
  }

  static std::string
  Join(const std::vector<std::string> & words)
  {
    std::string text;
    for (const auto & w : words)
    {
      text += (text.empty() ? "" : " ") + w;
    }
    return text;
  }
};

// ------------------------------------------------------------------------------
// Reading
// ------------------------------------------------------------------------------

/** Lines 1-4: "# vtk DataFile Version x.y", a title, ASCII or BINARY, DATASET POLYDATA. */
void
ReadHeader(LegacyReader & r)
{
  const std::string first(r.cursor.NextLine());
  const std::string tag = "# vtk DataFile Version";
  if (first.compare(0, tag.size(), tag) != 0)
  {
    r.cursor.Fail("it does not start with '# vtk DataFile Version' (not a VTK legacy file)");
  }
  std::int64_t       major = 0;
  std::istringstream version(first.substr(tag.size()));
  std::string        number;
  version >> number;
  if (!ParseInteger(std::string_view(number).substr(0, number.find('.')), major))
  {
    r.cursor.Fail("its version line '" + first + "' has no version number");
  }
  r.majorVersion = static_cast<int>(major);
  r.cursor.NextLine(); // the title
  const std::string encoding = Lower(std::string(r.cursor.NextToken()));
  if (encoding != "ascii" && encoding != "binary")
  {
    r.cursor.Fail("its third line must say ASCII or BINARY, not '" + encoding + "'");
  }
  r.binary = encoding == "binary";
  const std::vector<std::string> dataset = r.KeywordLine();
  if (dataset.size() < 2 || Lower(dataset[0]) != "dataset")
  {
    r.cursor.Fail("its fourth line must be 'DATASET POLYDATA', not '" + LegacyReader::Join(dataset) + "'");
  }
  if (Lower(dataset[1]) != "polydata")
  {
    r.cursor.Fail("it holds a DATASET " + dataset[1] + "; only POLYDATA (surface meshes) are read");
  }
}

/** POINTS n type, then 3n coordinates. */
void
ReadPoints(LegacyReader & r, const std::vector<std::string> & words)
{
  if (r.havePoints)
  {
    r.cursor.Fail("it has two POINTS sections");
  }
  const std::uint64_t n = r.RequireCount(words, 1, "the number of points");
  RequirePointCount(r.cursor, n);
  const DataType &          type = r.RequireDataType(words.size() > 2 ? words[2] : "", "POINTS");
  const std::vector<double> xyz = r.ReadValues(type, 3 * n, "the coordinates of the " + std::to_string(n) + " points");
  r.mesh.points.resize(static_cast<std::size_t>(n));
  for (std::size_t i = 0; i < r.mesh.points.size(); ++i)
  {
    r.mesh.points[i] = CheckedPoint(r.cursor, xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2], i);
  }
  r.havePoints = true;
}

/** What a cell section becomes. */
enum class CellKind
{
  Ignored,  ///< VERTICES, LINES
  Polygons, ///< POLYGONS
  Strips    ///< TRIANGLE_STRIPS
};

/** Adds one cell of the section to the mesh (checking its indices). */
void
AddCell(LegacyReader & r, CellKind kind, const double * values, std::size_t n, std::uint64_t cell)
{
  std::vector<std::uint32_t> corners(n);
  for (std::size_t k = 0; k < n; ++k)
  {
    const double v = values[k];
    const auto   index = std::abs(v) < 9e18 ? static_cast<std::int64_t>(v) : std::int64_t{ -1 };
    corners[k] = CheckedIndex(r.cursor, index, r.mesh.points.size(), "cell " + std::to_string(cell));
  }
  if (kind == CellKind::Ignored)
  {
    ++r.mesh.numberOfIgnoredCells;
    return;
  }
  if (n < 3)
  {
    // VERTICES and LINES are the format's points and lines; a polygon or strip of
    // fewer than three corners is a broken surface.
    r.cursor.Fail(std::string(kind == CellKind::Polygons ? "polygon " : "strip ") + std::to_string(cell) + " has " +
                  std::to_string(n) + " vertices; it needs at least 3");
  }
  if (kind == CellKind::Polygons)
  {
    r.mesh.AddPolygon(corners.data(), n);
    return;
  }
  // A strip's triangles alternate orientation; triangles repeating a corner (how
  // strips are joined) are left out.
  for (std::size_t i = 0; i + 2 < n; ++i)
  {
    const std::uint32_t t[3] = { corners[i + (i % 2)], corners[i + 1 - (i % 2)], corners[i + 2] };
    if (t[0] != t[1] && t[1] != t[2] && t[2] != t[0])
    {
      r.mesh.AddPolygon(t, 3);
    }
  }
}

/** Versions up to 4.2: "KEYWORD n size", then each cell as its count and indices. */
void
ReadCountedCells(LegacyReader & r, CellKind kind, const std::vector<std::string> & words)
{
  const std::uint64_t       n = r.RequireCount(words, 1, "the number of cells");
  const std::uint64_t       size = r.RequireCount(words, 2, "the size of the cell list");
  static const DataType     int32 = { "int", 4, true, true };
  const std::vector<double> values = r.ReadValues(int32, size, "the " + words[0] + " list");
  std::size_t               at = 0;
  for (std::uint64_t cell = 0; cell < n; ++cell)
  {
    const double count = at < values.size() ? values[at] : -1.0;
    if (!(count >= 0.0 && count <= static_cast<double>(values.size() - at - 1)))
    {
      r.cursor.Fail(words[0] + " promises " + std::to_string(n) + " cells in " + std::to_string(size) +
                    " numbers, but cell " + std::to_string(cell) + " does not fit (its count is " +
                    (at < values.size() ? std::to_string(static_cast<std::int64_t>(count)) : "missing") + ")");
    }
    AddCell(r, kind, values.data() + at + 1, static_cast<std::size_t>(count), cell);
    at += 1 + static_cast<std::size_t>(count);
  }
  if (at != values.size())
  {
    r.cursor.Fail(words[0] + " says its " + std::to_string(n) + " cells take " + std::to_string(size) +
                  " numbers, but they take " + std::to_string(at));
  }
}

/** Version 5: "KEYWORD offsets connectivity", then OFFSETS type and CONNECTIVITY type. */
void
ReadOffsetCells(LegacyReader & r, CellKind kind, const std::vector<std::string> & words)
{
  const std::uint64_t numberOfOffsets = r.RequireCount(words, 1, "the number of offsets");
  const std::uint64_t size = r.RequireCount(words, 2, "the size of the connectivity");
  std::vector<double> arrays[2];
  const char *        names[2] = { "OFFSETS", "CONNECTIVITY" };
  for (int a = 0; a < 2; ++a)
  {
    const std::vector<std::string> line = r.KeywordLine();
    if (line.size() < 2 || Lower(line[0]) != Lower(names[a]))
    {
      r.cursor.Fail(words[0] + " must be followed by " + names[a] + " TYPE, not '" + LegacyReader::Join(line) + "'");
    }
    arrays[a] = r.ReadValues(r.RequireDataType(line[1], names[a]),
                             a == 0 ? numberOfOffsets : size,
                             std::string("the ") + names[a] + " of " + words[0]);
  }
  const std::vector<double> & offsets = arrays[0];
  if (offsets.empty() && size > 0)
  {
    r.cursor.Fail(words[0] + " has a connectivity of " + std::to_string(size) + " indices but no offsets");
  }
  if (!offsets.empty() && (offsets.front() != 0.0 || offsets.back() != static_cast<double>(size)))
  {
    r.cursor.Fail(words[0] + " has offsets from " + std::to_string(offsets.front()) + " to " +
                  std::to_string(offsets.back()) + ", not from 0 to its connectivity size " + std::to_string(size));
  }
  for (std::size_t cell = 0; cell + 1 < offsets.size(); ++cell)
  {
    if (!(offsets[cell + 1] >= offsets[cell]))
    {
      r.cursor.Fail(words[0] + " has decreasing offsets at cell " + std::to_string(cell));
    }
    AddCell(r,
            kind,
            arrays[1].data() + static_cast<std::size_t>(offsets[cell]),
            static_cast<std::size_t>(offsets[cell + 1] - offsets[cell]),
            cell);
  }
}

/** METADATA: blocks of lines up to an empty line. */
void
SkipMetadata(LegacyReader & r)
{
  while (!r.cursor.AtEnd())
  {
    const std::string_view line = r.cursor.NextLine();
    if (line.find_first_not_of(" \t") == std::string_view::npos)
    {
      return;
    }
  }
}

/** FIELD name n, then n arrays "name components tuples type" with their values. */
void
SkipFieldData(LegacyReader & r, const std::vector<std::string> & words)
{
  const std::uint64_t arrays = r.RequireCount(words, 2, "the number of field arrays");
  for (std::uint64_t a = 0; a < arrays; ++a)
  {
    const std::vector<std::string> line = r.KeywordLine();
    const std::uint64_t            components = r.RequireCount(line, 1, "a field array's number of components");
    const std::uint64_t            tuples = r.RequireCount(line, 2, "a field array's number of tuples");
    if (components > 0 && tuples > std::numeric_limits<std::uint64_t>::max() / components)
    {
      r.cursor.Fail("field array '" + line[0] + "' is too large");
    }
    r.ReadValues(r.RequireDataType(line.size() > 3 ? line[3] : "", "field array '" + line[0] + "'"),
                 components * tuples,
                 "field array '" + line[0] + "'");
  }
}

/** The sections after the header, up to POINT_DATA or CELL_DATA (attributes, not read). */
void
ReadSections(LegacyReader & r)
{
  for (;;)
  {
    r.cursor.SkipWhitespace();
    if (r.cursor.AtEnd())
    {
      return;
    }
    const std::vector<std::string> words = r.KeywordLine();
    const std::string              keyword = Lower(words.front());
    const CellKind                 kind = keyword == "polygons"          ? CellKind::Polygons
                                          : keyword == "triangle_strips" ? CellKind::Strips
                                                                         : CellKind::Ignored;
    if (keyword == "points")
    {
      ReadPoints(r, words);
    }
    else if (keyword == "polygons" || keyword == "triangle_strips" || keyword == "vertices" || keyword == "lines")
    {
      if (!r.havePoints)
      {
        r.cursor.Fail("its " + words.front() + " come before its POINTS");
      }
      (r.majorVersion >= 5 ? ReadOffsetCells : ReadCountedCells)(r, kind, words);
    }
    else if (keyword == "metadata")
    {
      SkipMetadata(r);
    }
    else if (keyword == "field")
    {
      SkipFieldData(r, words);
    }
    else if (keyword == "point_data" || keyword == "cell_data")
    {
      return;
    }
    else
    {
      r.cursor.Fail("unexpected section '" + LegacyReader::Join(words).substr(0, 60) + "'");
    }
  }
}

// ------------------------------------------------------------------------------
// Writing
// ------------------------------------------------------------------------------

/** Writes `values` as big-endian binary of T, then a line break. */
template <typename T, typename TSource>
void
WriteBigEndian(std::ostream & out, const std::vector<TSource> & values)
{
  std::vector<unsigned char> bytes(values.size() * sizeof(T));
  for (std::size_t i = 0; i < values.size(); ++i)
  {
    const T value = static_cast<T>(values[i]);
    std::memcpy(bytes.data() + i * sizeof(T), &value, sizeof(T));
  }
  if (IsLittleEndian())
  {
    SwapBytes(bytes.data(), sizeof(T), values.size());
  }
  out.write(reinterpret_cast<const char *>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  out << '\n';
}

void
WritePoints(std::ostream & out, const PolygonMesh & mesh, bool binary)
{
  out << "POINTS " << mesh.points.size() << " double\n";
  if (binary)
  {
    std::vector<double> xyz;
    xyz.reserve(3 * mesh.points.size());
    for (const Vec3 & p : mesh.points)
    {
      xyz.insert(xyz.end(), { p[0], p[1], p[2] });
    }
    WriteBigEndian<double>(out, xyz);
    return;
  }
  NumberToString<double> text;
  for (const Vec3 & p : mesh.points)
  {
    out << text(p[0]) << ' ' << text(p[1]) << ' ' << text(p[2]) << '\n';
  }
}

/** POLYGONS n size with each cell's count and indices (version 4.2). */
void
WriteCountedPolygons(std::ostream & out, const PolygonMesh & mesh, bool binary)
{
  out << "POLYGONS " << mesh.NumberOfPolygons() << ' ' << mesh.NumberOfPolygons() + mesh.polygonIndices.size() << '\n';
  std::vector<std::uint32_t> list;
  list.reserve(mesh.NumberOfPolygons() + mesh.polygonIndices.size());
  for (std::size_t p = 0; p < mesh.NumberOfPolygons(); ++p)
  {
    list.push_back(static_cast<std::uint32_t>(mesh.PolygonSize(p)));
    list.insert(list.end(), mesh.Polygon(p), mesh.Polygon(p) + mesh.PolygonSize(p));
    if (!binary)
    {
      for (std::size_t k = list.size() - mesh.PolygonSize(p) - 1; k < list.size(); ++k)
      {
        out << list[k] << (k + 1 < list.size() ? ' ' : '\n');
      }
    }
  }
  if (binary)
  {
    WriteBigEndian<std::int32_t>(out, list);
  }
}

/** POLYGONS with OFFSETS and CONNECTIVITY arrays (version 5.1). */
void
WriteOffsetPolygons(std::ostream & out, const PolygonMesh & mesh, bool binary)
{
  out << "POLYGONS " << mesh.polygonOffsets.size() << ' ' << mesh.polygonIndices.size() << '\n';
  const std::vector<std::uint32_t> * arrays[2] = { &mesh.polygonOffsets, &mesh.polygonIndices };
  const char *                       names[2] = { "OFFSETS", "CONNECTIVITY" };
  for (int a = 0; a < 2; ++a)
  {
    out << names[a] << " vtktypeint64\n";
    if (binary)
    {
      WriteBigEndian<std::int64_t>(out, *arrays[a]);
      continue;
    }
    for (std::size_t i = 0; i < arrays[a]->size(); ++i)
    {
      out << (*arrays[a])[i] << ((i + 1) % 9 == 0 || i + 1 == arrays[a]->size() ? '\n' : ' ');
    }
  }
}
} // namespace

PolygonMesh
ReadVTKLegacyFile(const std::string & fileName)
{
  const std::string data = ReadWholeFile(Format, fileName);
  LegacyReader      reader(data, fileName);
  ReadHeader(reader);
  ReadSections(reader);
  if (!reader.havePoints)
  {
    reader.cursor.Fail("it has no POINTS");
  }
  return std::move(reader.mesh);
}

void
WriteVTKLegacyFile(const std::string & fileName, const PolygonMesh & mesh, const MeshFileWriteOptions & options)
{
  using Options = MeshFileWriteOptions;
  const bool    binary = options.encoding == Options::Encoding::Binary;
  const bool    version5 = options.vtkLegacyVersion == Options::VTKLegacyVersion::V5_1;
  std::ofstream out = OpenForWriting(Format, fileName);
  out << "# vtk DataFile Version " << (version5 ? "5.1" : "4.2") << "\nMeshExtraction surface mesh\n"
      << (binary ? "BINARY" : "ASCII") << "\nDATASET POLYDATA\n";
  WritePoints(out, mesh, binary);
  if (mesh.NumberOfPolygons() > 0)
  {
    (version5 ? WriteOffsetPolygons : WriteCountedPolygons)(out, mesh, binary);
  }
  if (!mesh.cellArrays.empty())
  {
    out << "CELL_DATA " << mesh.NumberOfPolygons() << "\nFIELD FieldData " << mesh.cellArrays.size() << '\n';
    for (const auto & array : mesh.cellArrays)
    {
      out << array.name << ' ' << array.components << ' ' << mesh.NumberOfPolygons() << " unsigned_int\n";
      if (binary)
      {
        WriteBigEndian<std::uint32_t>(out, array.values);
        continue;
      }
      for (std::size_t i = 0; i < array.values.size(); ++i)
      {
        out << array.values[i] << ((i + 1) % array.components == 0 ? '\n' : ' ');
      }
    }
  }
  FinishWriting(out, Format, fileName);
}
} // namespace detail
} // namespace MeshExtraction
} // namespace itk
