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
// Object File Format (.off), ASCII: "OFF", the counts, a line per vertex and a line
// per face (a count, then the vertex numbers); colours and normals after them are
// skipped.

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
constexpr char Format[] = "OFF";

/** The words of the next line that has any (comments after '#' removed). */
std::vector<std::string>
NextWords(Cursor & cursor, const std::string & what)
{
  while (!cursor.AtEnd())
  {
    std::string_view line = cursor.NextLine();
    line = line.substr(0, line.find('#'));
    std::istringstream       in{ std::string(line) };
    std::vector<std::string> words;
    for (std::string w; in >> w;)
    {
      words.push_back(w);
    }
    if (!words.empty())
    {
      return words;
    }
  }
  cursor.Fail("the file ends where " + what + " should follow (a truncated file?)");
}

/** The header keyword (OFF, COFF, NOFF, CNOFF, STOFF...) and the three counts, which
 * may follow on the same line. */
void
ReadCounts(Cursor & cursor, std::int64_t counts[3])
{
  std::vector<std::string> words = NextWords(cursor, "the OFF header");
  const std::string        keyword = words[0];
  if (keyword.size() < 3 || keyword.compare(keyword.size() - 3, 3, "OFF") != 0 ||
      keyword.find_first_of("n4") != std::string::npos)
  {
    cursor.Fail("it does not start with OFF (or COFF, NOFF, STOFF), but with '" + keyword.substr(0, 40) + "'");
  }
  if (words.size() > 1 && Lower(words[1]) == "binary")
  {
    cursor.Fail("binary OFF is not read (only ASCII OFF)");
  }
  words.erase(words.begin());
  if (words.empty())
  {
    words = NextWords(cursor, "the numbers of vertices, faces and edges");
  }
  for (unsigned int k = 0; k < 2; ++k)
  {
    if (words.size() <= k || !ParseInteger(words[k], counts[k]) || counts[k] < 0)
    {
      cursor.Fail("the header does not give the numbers of vertices and faces");
    }
  }
  counts[2] = 0;
}
} // namespace

PolygonMesh
ReadOFFFile(const std::string & fileName)
{
  const std::string data = ReadWholeFile(Format, fileName);
  Cursor            cursor(data, Format, fileName);
  std::int64_t      counts[3];
  ReadCounts(cursor, counts);
  const auto vertices = static_cast<std::uint64_t>(counts[0]);
  const auto faces = static_cast<std::uint64_t>(counts[1]);
  RequirePointCount(cursor, vertices);
  RequireCountFits(cursor, vertices, 6, "the vertices");
  PolygonMesh mesh;
  mesh.points.reserve(static_cast<std::size_t>(vertices));
  for (std::uint64_t v = 0; v < vertices; ++v)
  {
    const std::vector<std::string> words = NextWords(cursor, "vertex " + std::to_string(v));
    double                         xyz[3];
    for (unsigned int k = 0; k < 3; ++k)
    {
      if (words.size() <= k || !ParseDouble(words[k], xyz[k]))
      {
        cursor.Fail("vertex " + std::to_string(v) + " does not have three numbers");
      }
    }
    mesh.points.push_back(CheckedPoint(cursor, xyz[0], xyz[1], xyz[2], v));
  }
  RequireCountFits(cursor, faces, 2, "the faces");
  std::vector<std::uint32_t> corners;
  for (std::uint64_t f = 0; f < faces; ++f)
  {
    const std::vector<std::string> words = NextWords(cursor, "face " + std::to_string(f));
    std::int64_t                   n = -1;
    if (!ParseInteger(words[0], n) || n < 0 || static_cast<std::uint64_t>(n) >= words.size())
    {
      cursor.Fail("face " + std::to_string(f) +
                  " does not start with its number of corners followed by as many "
                  "vertex numbers");
    }
    corners.resize(static_cast<std::size_t>(n));
    for (std::size_t k = 0; k < corners.size(); ++k)
    {
      std::int64_t index = -1;
      if (!ParseInteger(words[k + 1], index))
      {
        cursor.Fail("face " + std::to_string(f) + " has '" + words[k + 1].substr(0, 40) + "' for a vertex number");
      }
      corners[k] = CheckedIndex(cursor, index, mesh.points.size(), "face " + std::to_string(f));
    }
    if (corners.size() < 3)
    {
      cursor.Fail("face " + std::to_string(f) + " has " + std::to_string(corners.size()) +
                  " vertices; a face needs at least 3");
    }
    mesh.AddPolygon(corners.data(), corners.size());
  }
  return mesh;
}

void
WriteOFFFile(const std::string & fileName, const PolygonMesh & mesh, const MeshFileWriteOptions & options)
{
  if (options.encoding == MeshFileWriteOptions::Encoding::Binary)
  {
    FailToWrite(Format, fileName, "binary OFF is not written (only ASCII OFF)");
  }
  std::ofstream          out = OpenForWriting(Format, fileName);
  NumberToString<double> text;
  out << "OFF\n" << mesh.points.size() << ' ' << mesh.NumberOfPolygons() << " 0\n";
  for (const Vec3 & p : mesh.points)
  {
    out << text(p[0]) << ' ' << text(p[1]) << ' ' << text(p[2]) << '\n';
  }
  for (std::size_t f = 0; f < mesh.NumberOfPolygons(); ++f)
  {
    out << mesh.PolygonSize(f);
    for (std::size_t k = 0; k < mesh.PolygonSize(f); ++k)
    {
      out << ' ' << mesh.Polygon(f)[k];
    }
    out << '\n';
  }
  FinishWriting(out, Format, fileName);
}
} // namespace detail
} // namespace MeshExtraction
} // namespace itk
