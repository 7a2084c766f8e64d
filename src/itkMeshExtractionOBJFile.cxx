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
// Wavefront OBJ files (.obj): the v and f lines of a polygon mesh.

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
constexpr char Format[] = "OBJ";

/** The words of a line, without its comment. */
std::vector<std::string_view>
Words(std::string_view line)
{
  line = line.substr(0, line.find('#'));
  std::vector<std::string_view> words;
  std::size_t                   at = 0;
  while (at < line.size())
  {
    const std::size_t start = line.find_first_not_of(" \t\r\f\v", at);
    if (start == std::string_view::npos)
    {
      break;
    }
    const std::size_t end = std::min(line.find_first_of(" \t\r\f\v", start), line.size());
    words.push_back(line.substr(start, end - start));
    at = end;
  }
  return words;
}

/** The next line, joined with the following ones while it ends in a backslash. */
std::string
LogicalLine(Cursor & cursor)
{
  std::string line(cursor.NextLine());
  while (!line.empty() && line.back() == '\\' && !cursor.AtEnd())
  {
    line.pop_back();
    line += ' ';
    line += cursor.NextLine();
  }
  return line;
}

/** "v x y z [w]": the first three numbers. */
void
ReadVertex(Cursor & cursor, const std::vector<std::string_view> & words, PolygonMesh & mesh, std::size_t lineNumber)
{
  double xyz[3];
  for (unsigned int k = 0; k < 3; ++k)
  {
    if (k + 1 >= words.size() || !ParseDouble(words[k + 1], xyz[k]))
    {
      cursor.Fail("line " + std::to_string(lineNumber) + ": a 'v' line needs three numbers");
    }
  }
  RequirePointCount(cursor, mesh.points.size() + 1);
  mesh.points.push_back(CheckedPoint(cursor, xyz[0], xyz[1], xyz[2], mesh.points.size()));
}

/** "f a b c ...": each corner's vertex (before any '/'), 1-based or negative
 * (relative to the vertices so far); checked against the number of vertices later. */
void
ReadFace(Cursor &                              cursor,
         const std::vector<std::string_view> & words,
         PolygonMesh &                         mesh,
         std::vector<std::int64_t> &           corners,
         std::size_t                           lineNumber)
{
  corners.clear();
  for (std::size_t k = 1; k < words.size(); ++k)
  {
    std::int64_t index = 0;
    if (!ParseInteger(words[k].substr(0, words[k].find('/')), index) || index == 0)
    {
      cursor.Fail("line " + std::to_string(lineNumber) + ": '" + std::string(words[k].substr(0, 40)) +
                  "' is not a vertex number");
    }
    corners.push_back(index > 0 ? index - 1 : static_cast<std::int64_t>(mesh.points.size()) + index);
  }
  std::vector<std::uint32_t> polygon;
  for (const std::int64_t c : corners)
  {
    // Indices past the vertices so far are checked at the end (a face may name a
    // vertex that follows it); negative ones must name an earlier vertex.
    if (c < 0 || c >= static_cast<std::int64_t>(std::numeric_limits<std::uint32_t>::max()))
    {
      cursor.Fail("line " + std::to_string(lineNumber) + ": a face names vertex " + std::to_string(c + 1) +
                  ", which does not exist");
    }
    polygon.push_back(static_cast<std::uint32_t>(c));
  }
  if (polygon.size() < 3)
  {
    // A face of fewer than three corners is no surface ('l' and 'p' lines are the
    // format's lines and points).
    cursor.Fail("line " + std::to_string(lineNumber) + ": face " + std::to_string(mesh.NumberOfPolygons()) + " has " +
                std::to_string(polygon.size()) + " vertices; a face needs at least 3");
  }
  mesh.AddPolygon(polygon.data(), polygon.size());
}
} // namespace

PolygonMesh
ReadOBJFile(const std::string & fileName)
{
  const std::string         data = ReadWholeFile(Format, fileName);
  Cursor                    cursor(data, Format, fileName);
  PolygonMesh               mesh;
  std::vector<std::int64_t> corners;
  for (std::size_t lineNumber = 1; !cursor.AtEnd(); ++lineNumber)
  {
    const std::string                   line = LogicalLine(cursor);
    const std::vector<std::string_view> words = Words(line);
    if (words.empty())
    {
      continue;
    }
    if (words[0] == "v")
    {
      ReadVertex(cursor, words, mesh, lineNumber);
    }
    else if (words[0] == "f")
    {
      ReadFace(cursor, words, mesh, corners, lineNumber);
    }
    else if (words[0] == "l" || words[0] == "p")
    {
      ++mesh.numberOfIgnoredCells;
    }
    // vn, vt, g, o, s, usemtl, mtllib and the rest describe no geometry here.
  }
  for (std::size_t i = 0; i < mesh.polygonIndices.size(); ++i)
  {
    if (mesh.polygonIndices[i] >= mesh.points.size())
    {
      cursor.Fail("a face names vertex " + std::to_string(mesh.polygonIndices[i] + 1) + ", but there are " +
                  std::to_string(mesh.points.size()) + " vertices");
    }
  }
  if (mesh.points.empty())
  {
    cursor.Fail("it has no 'v' lines");
  }
  return mesh;
}

void
WriteOBJFile(const std::string & fileName, const PolygonMesh & mesh, const MeshFileWriteOptions & options)
{
  if (options.encoding == MeshFileWriteOptions::Encoding::Binary)
  {
    FailToWrite(Format, fileName, "OBJ has no binary form");
  }
  std::ofstream          out = OpenForWriting(Format, fileName);
  NumberToString<double> text;
  out << "# MeshExtraction surface mesh: " << mesh.points.size() << " vertices, " << mesh.NumberOfPolygons()
      << " faces\n";
  for (const Vec3 & p : mesh.points)
  {
    out << "v " << text(p[0]) << ' ' << text(p[1]) << ' ' << text(p[2]) << '\n';
  }
  for (std::size_t f = 0; f < mesh.NumberOfPolygons(); ++f)
  {
    out << 'f';
    for (std::size_t k = 0; k < mesh.PolygonSize(f); ++k)
    {
      out << ' ' << mesh.Polygon(f)[k] + 1;
    }
    out << '\n';
  }
  FinishWriting(out, Format, fileName);
}
} // namespace detail
} // namespace MeshExtraction
} // namespace itk
