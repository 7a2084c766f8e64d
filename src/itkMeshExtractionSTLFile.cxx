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
// STL files (.stl), binary and ASCII. STL stores each facet's own three corners; the
// reader joins corners with equal coordinates into shared vertices, so that a closed
// surface comes back closed.

#include "itkMeshExtractionMeshFileParsing.h"
#include "itkNumberToString.h"

#include <unordered_map>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
namespace
{
constexpr char        Format[] = "STL";
constexpr std::size_t HeaderBytes = 84;
constexpr std::size_t FacetBytes = 50;

/** Joins corners with equal coordinates (0 and -0 are equal) into one vertex. */
class VertexJoiner
{
public:
  explicit VertexJoiner(PolygonMesh & mesh)
      : m_Mesh(mesh)
  {}

  std::uint32_t
  Add(const Cursor & cursor, double x, double y, double z)
  {
    const Vec3 p = CheckedPoint(cursor, x + 0.0, y + 0.0, z + 0.0, m_Mesh.points.size());
    const Key  key{ p[0], p[1], p[2] };
    const auto found = m_Index.find(key);
    if (found != m_Index.end())
    {
      return found->second;
    }
    RequirePointCount(cursor, m_Mesh.points.size() + 1);
    const auto index = static_cast<std::uint32_t>(m_Mesh.points.size());
    m_Mesh.points.push_back(p);
    m_Index.emplace(key, index);
    return index;
  }

private:
  struct Key
  {
    double x, y, z;
    bool
    operator==(const Key & other) const
    {
      return x == other.x && y == other.y && z == other.z;
    }
  };
  struct KeyHash
  {
    std::size_t
    operator()(const Key & k) const
    {
      const std::hash<double> h;
      std::size_t             seed = h(k.x);
      seed ^= h(k.y) + 0x9e3779b97f4a7c15ull + (seed << 6) + (seed >> 2);
      seed ^= h(k.z) + 0x9e3779b97f4a7c15ull + (seed << 6) + (seed >> 2);
      return seed;
    }
  };
  PolygonMesh &                                   m_Mesh;
  std::unordered_map<Key, std::uint32_t, KeyHash> m_Index;
};

float
LittleEndianFloat(const unsigned char * bytes)
{
  unsigned char b[4];
  std::memcpy(b, bytes, 4);
  if (!IsLittleEndian())
  {
    std::reverse(b, b + 4);
  }
  float value;
  std::memcpy(&value, b, 4);
  return value;
}

std::uint32_t
LittleEndianUInt32(const unsigned char * bytes)
{
  return static_cast<std::uint32_t>(bytes[0]) | (static_cast<std::uint32_t>(bytes[1]) << 8) |
         (static_cast<std::uint32_t>(bytes[2]) << 16) | (static_cast<std::uint32_t>(bytes[3]) << 24);
}

/** Binary: an 80-byte header, the number of facets, then 50 bytes per facet (normal,
 * three corners, an attribute word). */
PolygonMesh
ReadBinary(Cursor & cursor, std::uint64_t numberOfFacets)
{
  PolygonMesh  mesh;
  VertexJoiner joiner(mesh);
  cursor.SetPosition(HeaderBytes);
  mesh.polygonIndices.reserve(3 * numberOfFacets);
  for (std::uint64_t f = 0; f < numberOfFacets; ++f)
  {
    const unsigned char * facet = cursor.RequireBytes(FacetBytes, "facet " + std::to_string(f));
    std::uint32_t         corners[3];
    for (unsigned int k = 0; k < 3; ++k)
    {
      const unsigned char * xyz = facet + 12 * (k + 1);
      corners[k] = joiner.Add(cursor, LittleEndianFloat(xyz), LittleEndianFloat(xyz + 4), LittleEndianFloat(xyz + 8));
    }
    mesh.AddPolygon(corners, 3);
  }
  return mesh;
}

/** Requires the word `expected` next. */
void
Expect(Cursor & cursor, const char * expected, const std::string & where)
{
  const std::string_view word = cursor.RequireToken(std::string("'") + expected + "'");
  if (Lower(word) != expected)
  {
    cursor.Fail("expected '" + std::string(expected) + "' " + where + ", found '" + std::string(word.substr(0, 40)) +
                "'");
  }
}

/** One "facet normal ... outer loop vertex ... endloop endfacet" (after "facet"). */
void
ReadASCIIFacet(Cursor & cursor, VertexJoiner & joiner, PolygonMesh & mesh, std::size_t f)
{
  const std::string where = "in facet " + std::to_string(f);
  Expect(cursor, "normal", where);
  for (int k = 0; k < 3; ++k)
  {
    cursor.RequireDouble("the normal of facet " + std::to_string(f));
  }
  Expect(cursor, "outer", where);
  Expect(cursor, "loop", where);
  std::vector<std::uint32_t> corners;
  for (;;)
  {
    const std::string word = Lower(cursor.RequireToken("'vertex' or 'endloop' " + where));
    if (word == "endloop")
    {
      break;
    }
    if (word != "vertex")
    {
      cursor.Fail("expected 'vertex' or 'endloop' " + where + ", found '" + word.substr(0, 40) + "'");
    }
    double xyz[3];
    for (double & c : xyz)
    {
      c = cursor.RequireDouble("a vertex coordinate " + where);
    }
    corners.push_back(joiner.Add(cursor, xyz[0], xyz[1], xyz[2]));
  }
  Expect(cursor, "endfacet", where);
  if (corners.size() < 3)
  {
    cursor.Fail("facet " + std::to_string(f) + " has " + std::to_string(corners.size()) + " corners");
  }
  mesh.AddPolygon(corners.data(), corners.size());
}

/** ASCII: "solid name", facets, "endsolid name" (possibly several solids). */
PolygonMesh
ReadASCII(Cursor & cursor)
{
  PolygonMesh  mesh;
  VertexJoiner joiner(mesh);
  bool         inSolid = false;
  for (std::string_view word = cursor.NextToken(); !word.empty(); word = cursor.NextToken())
  {
    const std::string w = Lower(word);
    if (w == "solid" && !inSolid)
    {
      cursor.NextLine(); // the solid's name
      inSolid = true;
    }
    else if (w == "facet" && inSolid)
    {
      ReadASCIIFacet(cursor, joiner, mesh, mesh.NumberOfPolygons());
    }
    else if (w.compare(0, 8, "endsolid") == 0 && inSolid)
    {
      cursor.NextLine();
      inSolid = false;
    }
    else
    {
      cursor.Fail("unexpected word '" + w.substr(0, 40) + "' (expected " +
                  (inSolid ? "'facet' or 'endsolid'" : "'solid'") + ")");
    }
  }
  if (inSolid)
  {
    cursor.Fail("the file ends without 'endsolid' (a truncated file?)");
  }
  return mesh;
}

void
PutLittleEndian(std::ostream & out, const void * value, std::size_t size)
{
  unsigned char b[4];
  std::memcpy(b, value, size);
  if (!IsLittleEndian())
  {
    std::reverse(b, b + size);
  }
  out.write(reinterpret_cast<const char *>(b), static_cast<std::streamsize>(size));
}

/** The unit normal of a triangle by the right-hand rule (zero if degenerate). */
Vec3
UnitNormal(const Vec3 & a, const Vec3 & b, const Vec3 & c)
{
  const Vec3   n = Cross(b - a, c - a);
  const double length = std::sqrt(Dot(n, n));
  return length > 0.0 ? n / length : MakeVec3(0, 0, 0);
}

void
WriteBinary(std::ostream & out, const IndexedTriangleMesh & mesh)
{
  std::string header = "MeshExtraction binary STL";
  header.resize(80, ' ');
  out.write(header.data(), 80);
  const auto count = static_cast<std::uint32_t>(mesh.triangles.size());
  PutLittleEndian(out, &count, 4);
  for (const TriangleIndices & t : mesh.triangles)
  {
    const Vec3 n = UnitNormal(mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]]);
    for (unsigned int k = 0; k < 12; ++k)
    {
      const float value = static_cast<float>(k < 3 ? n[k] : mesh.points[t[k / 3 - 1]][k % 3]);
      PutLittleEndian(out, &value, 4);
    }
    const std::uint16_t attribute = 0;
    PutLittleEndian(out, &attribute, 2);
  }
}

void
WriteASCII(std::ostream & out, const IndexedTriangleMesh & mesh)
{
  NumberToString<double> text;
  out << "solid MeshExtraction\n";
  for (const TriangleIndices & t : mesh.triangles)
  {
    const Vec3 n = UnitNormal(mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]]);
    out << "  facet normal " << text(n[0]) << ' ' << text(n[1]) << ' ' << text(n[2]) << "\n    outer loop\n";
    for (unsigned int k = 0; k < 3; ++k)
    {
      const Vec3 & p = mesh.points[t[k]];
      out << "      vertex " << text(p[0]) << ' ' << text(p[1]) << ' ' << text(p[2]) << '\n';
    }
    out << "    endloop\n  endfacet\n";
  }
  out << "endsolid MeshExtraction\n";
}
} // namespace

PolygonMesh
ReadSTLFile(const std::string & fileName)
{
  const std::string data = ReadWholeFile(Format, fileName);
  Cursor            cursor(data, Format, fileName);
  // A binary file's size follows from its facet count; an ASCII file starts with
  // "solid" (and so do some binary headers, hence the size test first).
  const std::uint64_t facets =
    data.size() >= HeaderBytes ? LittleEndianUInt32(reinterpret_cast<const unsigned char *>(data.data()) + 80) : 0;
  if (data.size() >= HeaderBytes && data.size() == HeaderBytes + FacetBytes * facets)
  {
    return ReadBinary(cursor, facets);
  }
  cursor.SkipWhitespace();
  if (Lower(std::string_view(data).substr(cursor.Position(), 5)) == "solid")
  {
    return ReadASCII(cursor);
  }
  if (data.size() < HeaderBytes)
  {
    cursor.Fail("it is neither ASCII STL (no 'solid') nor binary STL (shorter than the 84-byte header)");
  }
  cursor.Fail("it is not ASCII STL (no 'solid'), and as binary STL its header promises " + std::to_string(facets) +
              " facets, " + std::to_string(HeaderBytes + FacetBytes * facets) + " bytes, but the file has " +
              std::to_string(data.size()) + " bytes");
}

void
WriteSTLFile(const std::string & fileName, const PolygonMesh & mesh, const MeshFileWriteOptions & options)
{
  const IndexedTriangleMesh triangles = TriangulatePolygonMesh(mesh);
  if (triangles.triangles.size() > std::numeric_limits<std::uint32_t>::max())
  {
    FailToWrite(Format, fileName, "binary STL holds at most 2^32 - 1 triangles");
  }
  std::ofstream out = OpenForWriting(Format, fileName);
  if (options.encoding == MeshFileWriteOptions::Encoding::ASCII)
  {
    WriteASCII(out, triangles);
  }
  else
  {
    WriteBinary(out, triangles);
  }
  FinishWriting(out, Format, fileName);
}
} // namespace detail
} // namespace MeshExtraction
} // namespace itk
