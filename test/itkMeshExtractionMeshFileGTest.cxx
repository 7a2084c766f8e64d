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
// The module's mesh files (itkMeshExtractionMeshFile.h): every format and encoding
// round-trips; hand-written files (VTK legacy 4.2 and 5.1, OBJ, OFF, STL, PLY, VTP)
// read as written; and every corrupted variant (truncated at every byte, indices out
// of range, NaN and infinite coordinates, counts that lie) ends in an
// itk::ExceptionObject naming the file, never in a crash or a hang. The test of
// files written by VTK itself is itkMeshExtractionMeshFileVTKGTest.cxx.

#include "itkMeshExtractionMeshFile.h"
#include "itkMeshExtractionTestHelpers.h"
#include "itkQuadEdgeMesh.h"
#include "itkSurfaceNetsImageToMeshFilter.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace ME = itk::MeshExtraction;
using MeshExtractionTest::ExceptionDescription;

namespace
{
using Options = ME::MeshFileWriteOptions;

std::string
TemporaryPath(const std::string & name)
{
  const auto directory = std::filesystem::temp_directory_path() / "meshextraction-meshfile-gtest";
  std::filesystem::create_directories(directory);
  return (directory / name).string();
}

std::string
WriteText(const std::string & name, const std::string & text)
{
  const std::string path = TemporaryPath(name);
  std::ofstream     out(path, std::ios::binary);
  out << text;
  return path;
}

std::string
ReadBytes(const std::string & path)
{
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/** An octahedron with one quadrilateral and one pentagon among its faces. */
ME::PolygonMesh
MakeMixedMesh()
{
  ME::PolygonMesh mesh;
  mesh.points = { ME::MakeVec3(1.25, 0, 0),   ME::MakeVec3(-1, 0, 0),   ME::MakeVec3(0, 1.0 / 3.0, 0),
                  ME::MakeVec3(0, -1, 0),     ME::MakeVec3(0, 0, 1e-7), ME::MakeVec3(0, 0, -12345.678901234567),
                  ME::MakeVec3(0.5, 0.5, 0.5) };
  const std::vector<std::vector<std::uint32_t>> faces = { { 0, 2, 4 }, { 2, 1, 4 },    { 1, 3, 4 },      { 3, 0, 4 },
                                                          { 2, 0, 5 }, { 1, 2, 5, 6 }, { 3, 1, 5, 6, 0 } };
  for (const auto & f : faces)
  {
    mesh.AddPolygon(f.data(), f.size());
  }
  return mesh;
}

void
ExpectSamePolygons(const ME::PolygonMesh & a, const ME::PolygonMesh & b)
{
  EXPECT_EQ(a.polygonOffsets, b.polygonOffsets);
  EXPECT_EQ(a.polygonIndices, b.polygonIndices);
}

void
ExpectSamePoints(const ME::PolygonMesh & a, const ME::PolygonMesh & b, double tolerance)
{
  ASSERT_EQ(a.points.size(), b.points.size());
  for (std::size_t i = 0; i < a.points.size(); ++i)
  {
    for (unsigned int d = 0; d < 3; ++d)
    {
      EXPECT_NEAR(a.points[i][d], b.points[i][d], tolerance * (1.0 + std::abs(a.points[i][d]))) << "point " << i;
    }
  }
}

/** `read` on every proper prefix of `bytes` (and on bytes with one character
 * changed in the header) either succeeds or throws an itk::ExceptionObject naming
 * the file: no crash, no hang, no other exception. */
void
ExpectNoCrashOnAnyPrefix(const std::string & name, const std::string & bytes)
{
  const std::string path = TemporaryPath(name);
  std::size_t       refused = 0;
  for (std::size_t n = 0; n < bytes.size(); ++n)
  {
    {
      std::ofstream out(path, std::ios::binary);
      out.write(bytes.data(), static_cast<std::streamsize>(n));
    }
    try
    {
      ME::ReadPolygonMeshFile(path);
    }
    catch (const itk::ExceptionObject & e)
    {
      ++refused;
      EXPECT_NE(std::string(e.GetDescription()).find(path), std::string::npos) << e.GetDescription();
    }
  }
  // A prefix may be a valid smaller file (ASCII formats), but most are not.
  EXPECT_GT(refused, bytes.size() / 2) << name;
}
} // namespace

// ------------------------------------------------------------------------------
// Round trips: the module writes, the module reads the same mesh back
// ------------------------------------------------------------------------------
TEST(MeshFile, RoundTripsEveryFormatAndEncoding)
{
  const ME::PolygonMesh mesh = MakeMixedMesh();
  struct Case
  {
    const char *              name;
    Options::Encoding         encoding;
    Options::VTKLegacyVersion version;
  };
  const Case cases[] = {
    { "a42.vtk", Options::Encoding::ASCII, Options::VTKLegacyVersion::V4_2 },
    { "b42.vtk", Options::Encoding::Binary, Options::VTKLegacyVersion::V4_2 },
    { "a51.vtk", Options::Encoding::ASCII, Options::VTKLegacyVersion::V5_1 },
    { "b51.vtk", Options::Encoding::Binary, Options::VTKLegacyVersion::V5_1 },
    { "a.vtp", Options::Encoding::ASCII, Options::VTKLegacyVersion::V4_2 },
    { "b.vtp", Options::Encoding::Default, Options::VTKLegacyVersion::V4_2 },
    { "a.ply", Options::Encoding::ASCII, Options::VTKLegacyVersion::V4_2 },
    { "b.PLY", Options::Encoding::Binary, Options::VTKLegacyVersion::V4_2 },
    { "a.obj", Options::Encoding::Default, Options::VTKLegacyVersion::V4_2 },
    { "a.off", Options::Encoding::ASCII, Options::VTKLegacyVersion::V4_2 },
  };
  for (const Case & c : cases)
  {
    SCOPED_TRACE(c.name);
    Options options;
    options.encoding = c.encoding;
    options.vtkLegacyVersion = c.version;
    const std::string path = TemporaryPath(c.name);
    ME::WritePolygonMeshFile(path, mesh, options);
    const ME::PolygonMesh back = ME::ReadPolygonMeshFile(path);
    ExpectSamePoints(mesh, back, 0.0); // double precision, shortest round-trip text
    ExpectSamePolygons(mesh, back);
  }
}

TEST(MeshFile, RoundTripsSTLWithSharedVertices)
{
  const ME::IndexedTriangleMesh sphere = MeshExtractionTest::MakeIcosphere(2, 10.0);
  const ME::PolygonMesh         mesh = ME::MakePolygonMesh(sphere);
  for (const auto encoding : { Options::Encoding::Binary, Options::Encoding::ASCII })
  {
    Options options;
    options.encoding = encoding;
    const std::string path = TemporaryPath(encoding == Options::Encoding::ASCII ? "ascii.stl" : "binary.stl");
    ME::WritePolygonMeshFile(path, mesh, options);
    const ME::PolygonMesh back = ME::ReadPolygonMeshFile(path);
    // The corners are joined again: the same vertices (single precision in binary),
    // in the order of their first use.
    EXPECT_EQ(back.points.size(), mesh.points.size());
    EXPECT_EQ(back.NumberOfPolygons(), mesh.NumberOfPolygons());
    const ME::IndexedTriangleMesh triangles = ME::TriangulatePolygonMesh(back);
    EXPECT_FALSE(ME::FindTriangleMeshDefects(triangles).Any());
    for (std::size_t f = 0; f < back.NumberOfPolygons(); ++f)
    {
      for (unsigned int k = 0; k < 3; ++k)
      {
        const ME::Vec3 & expected = mesh.points[mesh.Polygon(f)[k]];
        const ME::Vec3 & found = back.points[back.Polygon(f)[k]];
        const double     tolerance = encoding == Options::Encoding::ASCII ? 0.0 : 1e-5;
        EXPECT_NEAR((expected - found).GetNorm(), 0.0, tolerance);
      }
    }
  }
}

TEST(MeshFile, RoundTripsSurfaceNetsMeshesInEveryFormat)
{
  // A mesh the module makes (SurfaceNets of the torus phantom, as triangles and as
  // quadrilaterals) written in every format and encoding and read back: the same points
  // and faces (STL: triangles only, single precision in binary), and, read into a
  // QuadEdgeMesh, a closed, consistently oriented surface again.
  using Triangulation = itk::SurfaceNetsImageToMeshFilterEnums::Triangulation;
  struct Case
  {
    const char *              name;
    Options::Encoding         encoding;
    Options::VTKLegacyVersion version;
  };
  const Case cases[] = {
    { "a42.vtk", Options::Encoding::ASCII, Options::VTKLegacyVersion::V4_2 },
    { "b51.vtk", Options::Encoding::Binary, Options::VTKLegacyVersion::V5_1 },
    { "b.vtp", Options::Encoding::Default, Options::VTKLegacyVersion::V4_2 },
    { "a.vtp", Options::Encoding::ASCII, Options::VTKLegacyVersion::V4_2 },
    { "b.ply", Options::Encoding::Binary, Options::VTKLegacyVersion::V4_2 },
    { "a.obj", Options::Encoding::Default, Options::VTKLegacyVersion::V4_2 },
    { "a.off", Options::Encoding::Default, Options::VTKLegacyVersion::V4_2 },
    { "b.stl", Options::Encoding::Binary, Options::VTKLegacyVersion::V4_2 },
    { "a.stl", Options::Encoding::ASCII, Options::VTKLegacyVersion::V4_2 },
  };
  const auto phantom = MeshExtractionTest::MakePhantom(ME::PhantomShape::Torus);
  for (const auto triangulation : { Triangulation::ShortestDiagonal, Triangulation::Quadrilaterals })
  {
    auto filter = itk::SurfaceNetsImageToMeshFilter<itk::Image<float, 3>>::New();
    filter->SetInput(phantom.image);
    filter->SetInsideIsAboveIsoValue(false);
    filter->SetTriangulation(triangulation);
    filter->Update();
    const ME::PolygonMesh mesh = ME::MakePolygonMeshFromMesh(*filter->GetOutput());
    const bool            quads = triangulation == Triangulation::Quadrilaterals;
    ASSERT_GT(mesh.NumberOfPolygons(), 100u);
    EXPECT_EQ(mesh.PolygonSize(0), quads ? 4u : 3u);
    const ME::IndexedTriangleMesh triangles = ME::TriangulatePolygonMesh(mesh);
    for (const Case & c : cases)
    {
      SCOPED_TRACE(std::string(c.name) + (quads ? " (quadrilaterals)" : " (triangles)"));
      Options options;
      options.encoding = c.encoding;
      options.vtkLegacyVersion = c.version;
      const std::string path = TemporaryPath(std::string(quads ? "surfacenets-q-" : "surfacenets-t-") + c.name);
      ME::WritePolygonMeshFile(path, mesh, options);
      const ME::PolygonMesh back = ME::ReadPolygonMeshFile(path);
      if (ME::MeshFileFormatFromFileName(path) != ME::MeshFileFormat::STL)
      {
        ExpectSamePoints(mesh, back, 0.0);
        ExpectSamePolygons(mesh, back);
      }
      else
      {
        ASSERT_EQ(back.NumberOfPolygons(), triangles.triangles.size());
        EXPECT_EQ(back.points.size(), mesh.points.size());
        const double tolerance = c.encoding == Options::Encoding::ASCII ? 0.0 : 1e-4;
        for (std::size_t f = 0; f < back.NumberOfPolygons(); ++f)
        {
          for (unsigned int k = 0; k < 3; ++k)
          {
            const ME::Vec3 d = triangles.points[triangles.triangles[f][k]] - back.points[back.Polygon(f)[k]];
            ASSERT_LE(d.GetNorm(), tolerance) << "triangle " << f;
          }
        }
      }
      const auto                    surface = ME::ReadSurfaceMeshFile<itk::QuadEdgeMesh<double, 3>>(path);
      const ME::IndexedTriangleMesh read = ME::MakeIndexedTriangleMesh(*surface);
      EXPECT_EQ(read.triangles.size(), triangles.triangles.size());
      EXPECT_FALSE(ME::FindTriangleMeshDefects(read).Any());
      EXPECT_EQ(ME::BuildMeshTopology(read).numberOfBoundaryEdges, 0u);
    }
  }
}

TEST(MeshFile, ReadsIntoITKMeshesAndWritesThem)
{
  const std::string path = TemporaryPath("mixed.vtk");
  ME::WritePolygonMeshFile(path, MakeMixedMesh());
  const auto mesh = ME::ReadSurfaceMeshFile<itk::Mesh<double, 3>>(path);
  EXPECT_EQ(mesh->GetNumberOfPoints(), 7u);
  ASSERT_EQ(mesh->GetNumberOfCells(), 7u);
  typename itk::Mesh<double, 3>::CellAutoPointer cell;
  ASSERT_TRUE(mesh->GetCell(5, cell));
  EXPECT_EQ(cell->GetType(), itk::CellGeometryEnum::QUADRILATERAL_CELL);
  ASSERT_TRUE(mesh->GetCell(6, cell));
  EXPECT_EQ(cell->GetType(), itk::CellGeometryEnum::POLYGON_CELL);
  EXPECT_EQ(cell->GetNumberOfPoints(), 5u);
  // Written back from the itk::Mesh: the quadrilateral and the pentagon as they are
  // (the coordinates in the mesh's single precision).
  const std::string again = TemporaryPath("mixed-again.ply");
  ME::WriteSurfaceMeshFile(*mesh, again);
  const ME::PolygonMesh mixed = ME::ReadPolygonMeshFile(again);
  ExpectSamePoints(MakeMixedMesh(), mixed, 1e-7);
  ExpectSamePolygons(MakeMixedMesh(), mixed);

  const std::string out = TemporaryPath("sphere.ply");
  auto              sphere = itk::QuadEdgeMesh<double, 3>::New();
  ME::FillMesh(MeshExtractionTest::MakeIcosphere(1), *sphere);
  ME::WriteSurfaceMeshFile(*sphere, out);
  const auto back = ME::ReadSurfaceMeshFile<itk::QuadEdgeMesh<double, 3>>(out);
  EXPECT_EQ(back->GetNumberOfPoints(), sphere->GetNumberOfPoints());
  EXPECT_EQ(back->GetNumberOfFaces(), sphere->GetNumberOfFaces());
}

TEST(MeshFile, NamesTheFormatsByExtension)
{
  EXPECT_EQ(ME::MeshFileFormatFromFileName("a/b.c/mesh.VTK"), ME::MeshFileFormat::VTKLegacy);
  EXPECT_EQ(ME::MeshFileFormatFromFileName("mesh.vtp"), ME::MeshFileFormat::VTKXMLPolyData);
  EXPECT_EQ(ME::MeshFileFormatFromFileName("mesh.Stl"), ME::MeshFileFormat::STL);
  EXPECT_EQ(ME::MeshFileFormatFromFileName("a.vtk/mesh"), ME::MeshFileFormat::Unknown);
  EXPECT_EQ(ME::MeshFileFormatFromFileName("mesh.gii"), ME::MeshFileFormat::Unknown);
  const std::string message = ExceptionDescription([] { ME::ReadPolygonMeshFile(TemporaryPath("mesh.gii")); });
  EXPECT_NE(message.find("mesh.gii"), std::string::npos);
  EXPECT_NE(message.find("no format MeshExtraction reads"), std::string::npos);
  EXPECT_NE(ExceptionDescription([] {
              ME::WritePolygonMeshFile(TemporaryPath("m.obj"), MakeMixedMesh(), Options{ Options::Encoding::Binary });
            }).find("OBJ has no binary form"),
            std::string::npos);
}

// ------------------------------------------------------------------------------
// Hand-written files
// ------------------------------------------------------------------------------
namespace
{
const char Tetrahedron42[] = "# vtk DataFile Version 4.2\ntetrahedron\nASCII\nDATASET POLYDATA\n"
                             "POINTS 4 float\n0 0 0 1 0 0\n0 1 0 0 0 1\n"
                             "POLYGONS 4 16\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n"
                             "POINT_DATA 4\nSCALARS s float 1\nLOOKUP_TABLE default\n1 2 3 4\n";
// As VTK 9's vtkPolyDataWriter writes it by default (version 5.1, offset arrays,
// METADATA after the points).
const char Tetrahedron51[] = "# vtk DataFile Version 5.1\nvtk output\nASCII\nDATASET POLYDATA\n"
                             "POINTS 4 float\n0 0 0 1 0 0 0 1 0 \n0 0 1 \n"
                             "METADATA\nINFORMATION 2\nNAME L2_NORM_RANGE LOCATION vtkDataArray\n"
                             "DATA 2 0 1 \nNAME L2_NORM_FINITE_RANGE LOCATION vtkDataArray\nDATA 2 0 1 \n\n"
                             "VERTICES 2 1\nOFFSETS vtktypeint64\n0 1 \nCONNECTIVITY vtktypeint64\n3 \n"
                             "POLYGONS 5 12\nOFFSETS vtktypeint64\n0 3 6 9 12 \n"
                             "CONNECTIVITY vtktypeint64\n0 2 1 0 1 3 0 3 2 \n1 2 3 \n"
                             "CELL_DATA 5\nFIELD FieldData 1\nids 1 5 int\n0 1 2 3 4\n";
} // namespace

TEST(MeshFile, ReadsVTKLegacy42And51)
{
  for (const char * text : { Tetrahedron42, Tetrahedron51 })
  {
    const ME::PolygonMesh mesh = ME::ReadPolygonMeshFile(WriteText("tetrahedron.vtk", text));
    ASSERT_EQ(mesh.points.size(), 4u);
    ASSERT_EQ(mesh.NumberOfPolygons(), 4u);
    EXPECT_EQ(mesh.Polygon(3)[0], 1u);
    EXPECT_EQ(mesh.Polygon(3)[2], 3u);
    EXPECT_EQ(mesh.points[3][2], 1.0);
    EXPECT_EQ(mesh.numberOfIgnoredCells, text == Tetrahedron51 ? 1u : 0u);
  }
}

TEST(MeshFile, ReadsVTKLegacyFloatsInSinglePrecision)
{
  // "POINTS n float" holds single-precision values: read as VTK and ITK read them.
  const ME::PolygonMesh mesh = ME::ReadPolygonMeshFile(
    WriteText("float.vtk",
              "# vtk DataFile Version 2.0\nx\nASCII\nDATASET POLYDATA\nPOINTS 3 float\n0.1 0 0\n0 1 0\n0 0 1\n"
              "POLYGONS 1 4\n3 0 1 2\n"));
  EXPECT_EQ(mesh.points[0][0], static_cast<double>(0.1f));
}

TEST(MeshFile, ReadsTriangleStripsAndSkipsLines)
{
  const ME::PolygonMesh mesh = ME::ReadPolygonMeshFile(
    WriteText("strip.vtk",
              "# vtk DataFile Version 3.0\nx\nASCII\nDATASET POLYDATA\nPOINTS 5 double\n0 0 0 1 0 0 0 1 0 1 1 0 "
              "2 1 0\nLINES 1 3\n2 0 1\nTRIANGLE_STRIPS 1 6\n5 0 1 2 3 4\n"));
  ASSERT_EQ(mesh.NumberOfPolygons(), 3u);
  EXPECT_EQ(mesh.numberOfIgnoredCells, 1u);
  // Alternate orientation: (0 1 2), (2 1 3), (2 3 4).
  EXPECT_EQ(mesh.Polygon(1)[0], 2u);
  EXPECT_EQ(mesh.Polygon(1)[1], 1u);
  EXPECT_EQ(mesh.Polygon(2)[0], 2u);
}

TEST(MeshFile, ReadsOBJAndOFFVariants)
{
  const ME::PolygonMesh obj = ME::ReadPolygonMeshFile(
    WriteText("variants.obj",
              "# comment\nmtllib x.mtl\nv 0 0 0 1\nv 1 0 0\nv 0 1 0\nv 0 0 1 0.5 0.5 0.5\n"
              "vn 0 0 1\nvt 0 0\ng group\nf 1/1/1 3//1 2\nf -4 -3 -1\nl 1 2\nf 1 4 \\\n 3\nf 2 3 4\n"));
  ASSERT_EQ(obj.points.size(), 4u);
  ASSERT_EQ(obj.NumberOfPolygons(), 4u);
  EXPECT_EQ(obj.Polygon(1)[2], 3u);
  EXPECT_EQ(obj.Polygon(2)[2], 2u);
  EXPECT_EQ(obj.numberOfIgnoredCells, 1u);

  const ME::PolygonMesh off =
    ME::ReadPolygonMeshFile(WriteText("variants.off",
                                      "COFF # colours\n\n4 4 6\n0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n0 1 0 1 1 1 1\n"
                                      "0 0 1 1 1 1 1\n3 0 2 1 255 0 0\n3 0 1 3\n3 0 3 2\n3 1 2 3\n"));
  ASSERT_EQ(off.NumberOfPolygons(), 4u);
  EXPECT_EQ(off.Polygon(0)[1], 2u);
}

// ------------------------------------------------------------------------------
// Malformed files: an error naming the file and the problem
// ------------------------------------------------------------------------------
namespace
{
std::string
ReadError(const std::string & name, const std::string & text)
{
  const std::string path = WriteText(name, text);
  const std::string message = ExceptionDescription([&path] { ME::ReadPolygonMeshFile(path); });
  EXPECT_NE(message.find(path), std::string::npos) << message;
  return message;
}
} // namespace

TEST(MeshFile, RefusesNonFiniteCoordinates)
{
  // Issue 32, cases 1 and 9: ITK's VTK reader hangs on these; its OBJ reader reads
  // garbage.
  std::string nan42 = Tetrahedron42;
  nan42.replace(nan42.find("0 0 0 1 0 0"), 5, "nan 0 0");
  EXPECT_NE(ReadError("nan.vtk", nan42).find("point 0 has a coordinate that is not a finite number"),
            std::string::npos);
  std::string inf51 = Tetrahedron51;
  inf51.replace(inf51.find("0 0 1 \n"), 5, "0 0 inf");
  EXPECT_NE(ReadError("inf.vtk", inf51).find("point 3 has a coordinate that is not a finite number"),
            std::string::npos);
  EXPECT_NE(ReadError("nan.obj", "v nan nan nan\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").find("not a finite number"),
            std::string::npos);
  EXPECT_NE(ReadError("huge.off", "OFF\n3 1 0\n1e999 0 0\n1 0 0\n0 1 0\n3 0 1 2\n").find("not a finite number"),
            std::string::npos);
  EXPECT_NE(ReadError("nan.stl",
                      "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex NaN 0 0\n"
                      "vertex 0 1 0\nendloop\nendfacet\nendsolid x\n")
              .find("not a finite number"),
            std::string::npos);
}

TEST(MeshFile, RefusesFacesOfFewerThanThreeVertices)
{
  // Issue 48, case 5: they were dropped without a word, and the rest called valid.
  const std::string octahedronPoints = "1 0 0\n-1 0 0\n0 1 0\n0 -1 0\n0 0 1\n0 0 -1\n";
  EXPECT_NE(ReadError("short.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2\n")
              .find("face 1 has 2 vertices; a face needs at least 3"),
            std::string::npos);
  EXPECT_NE(ReadError("empty-face.off", "OFF\n6 2 0\n" + octahedronPoints + "3 0 2 4\n0\n")
              .find("face 1 has 0 vertices; a face needs at least 3"),
            std::string::npos);
  EXPECT_NE(ReadError("short.ply",
                      "ply\nformat ascii 1.0\nelement vertex 6\nproperty float x\nproperty float y\n"
                      "property float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n" +
                        octahedronPoints + "1 3\n3 0 2 4\n")
              .find("face 0 has 1 vertices; a face needs at least 3"),
            std::string::npos);
  EXPECT_NE(ReadError("short.vtk",
                      "# vtk DataFile Version 4.2\nx\nASCII\nDATASET POLYDATA\nPOINTS 6 double\n" + octahedronPoints +
                        "POLYGONS 2 7\n3 0 2 4\n2 0 1\n")
              .find("polygon 1 has 2 vertices; it needs at least 3"),
            std::string::npos);
  const std::string vtp = "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" byte_order=\"LittleEndian\">\n"
                          "<PolyData>\n<Piece NumberOfPoints=\"3\" NumberOfPolys=\"2\">\n"
                          "<Points><DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">"
                          "0 0 0 1 0 0 0 1 0</DataArray></Points>\n<Polys>"
                          "<DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">0 1 2 0 1</DataArray>"
                          "<DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">3 5</DataArray></Polys>\n"
                          "</Piece>\n</PolyData>\n</VTKFile>\n";
  EXPECT_NE(ReadError("short.vtp", vtp).find("polygon 1 has 2 vertices; it needs at least 3"), std::string::npos);
  // The format's own points and lines are still counted, not refused.
  EXPECT_EQ(ME::ReadPolygonMeshFile(WriteText("lines.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nl 1 2\np 3\n"))
              .numberOfIgnoredCells,
            2u);
}

TEST(MeshFile, RefusesCoordinatesBeyondTheMeshCoordinateType)
{
  // Issue 48, case 1: x = 1e40 became an infinity in float points, and the rendering
  // crashed on it.
  const std::string path = WriteText("far.obj",
                                     "v 1e40 0 0\nv 0 1 0\nv 0 0 1\nv -1 -1 -1\n"
                                     "f 1 2 3\nf 1 4 2\nf 1 3 4\nf 2 4 3\n");
  using FloatMesh = itk::Mesh<double, 3, itk::DefaultStaticMeshTraits<double, 3, 3, float, float>>;
  using DoubleMesh = itk::Mesh<double, 3, itk::DefaultStaticMeshTraits<double, 3, 3, double, double>>;
  const std::string message = ExceptionDescription([&path] { ME::ReadSurfaceMeshFile<FloatMesh>(path); });
  EXPECT_NE(message.find("point 0 has the coordinate 1e+40, beyond the range of float coordinates"), std::string::npos)
    << message;
  EXPECT_NE(message.find(path), std::string::npos) << message;
  EXPECT_NE(ExceptionDescription([&path] {
              ME::ReadSurfaceMeshFile<itk::QuadEdgeMesh<double, 3>>(path);
            }).find("beyond the range of float coordinates"),
            std::string::npos);
  EXPECT_EQ(ME::ReadSurfaceMeshFile<DoubleMesh>(path)->GetPoint(0)[0], 1e40);
}

TEST(MeshFile, RefusesIndicesOutOfRange)
{
  std::string bad42 = Tetrahedron42;
  bad42.replace(bad42.find("3 1 2 3"), 7, "3 1 2 4");
  EXPECT_NE(ReadError("index.vtk", bad42).find("cell 3 names point 4, but there are 4 points"), std::string::npos);
  std::string bad51 = Tetrahedron51;
  bad51.replace(bad51.find("1 2 3 \nCELL"), 5, "1 -2 3");
  EXPECT_NE(ReadError("index51.vtk", bad51).find("names point -2"), std::string::npos);
  EXPECT_NE(ReadError("index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n").find("names vertex 4, but there are 3"),
            std::string::npos);
  EXPECT_NE(ReadError("zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n").find("'0' is not a vertex number"),
            std::string::npos);
  EXPECT_NE(ReadError("index.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n").find("face 0 names point 3"),
            std::string::npos);
}

TEST(MeshFile, RefusesHeadersThatLieAboutCounts)
{
  std::string more = Tetrahedron42;
  more.replace(more.find("POINTS 4"), 8, "POINTS 4000000000");
  EXPECT_NE(ReadError("points.vtk", more).find("more than the"), std::string::npos);
  std::string cells = Tetrahedron42;
  cells.replace(cells.find("POLYGONS 4 16"), 13, "POLYGONS 5 16");
  EXPECT_NE(ReadError("cells.vtk", cells).find("cell 4 does not fit"), std::string::npos);
  std::string size = Tetrahedron42;
  size.replace(size.find("POLYGONS 4 16"), 13, "POLYGONS 4 15");
  EXPECT_NE(ReadError("size.vtk", size).find("does not fit"), std::string::npos);
  std::string offsets = Tetrahedron51;
  offsets.replace(offsets.find("0 3 6 9 12"), 10, "0 3 9 6 12");
  EXPECT_NE(ReadError("offsets.vtk", offsets).find("decreasing offsets"), std::string::npos);
  EXPECT_NE(ReadError("faces.off", "OFF\n3 99999999 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n").find("more than the"),
            std::string::npos);
  EXPECT_NE(
    ReadError("other.vtk", "# vtk DataFile Version 4.2\nx\nASCII\nDATASET UNSTRUCTURED_GRID\n").find("only POLYDATA"),
    std::string::npos);
  EXPECT_NE(ReadError("none.vtk", "not a mesh\n").find("not a VTK legacy file"), std::string::npos);
  EXPECT_NE(ReadError("empty.obj", "").find("it is empty"), std::string::npos);
}

TEST(MeshFile, SkipsPLYElementsItDoesNotKnowWithoutTrustingTheirCounts)
{
  // Found by scripts/run-fuzzers.sh: an unknown element with a huge count and no
  // properties was skipped entry by entry, for hours. It holds no data: read the rest.
  const std::string header = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                             "property float z\nelement face 1\nproperty list uchar int vertex_indices\n";
  const std::string data = "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  EXPECT_EQ(
    ME::ReadPolygonMeshFile(WriteText("empty-element.ply", header + "element note 33333333333\nend_header\n" + data))
      .NumberOfPolygons(),
    1u);
  // With a property, each entry takes at least a byte: a count beyond the file is refused.
  EXPECT_NE(ReadError("lying-element.ply", header + "element note 33333333333\nproperty uchar n\nend_header\n" + data)
              .find("declares 33333333333 entries, more than the file holds"),
            std::string::npos);
}

TEST(MeshFile, RefusesHostileFilesOfEveryFormat)
{
  // Issue 32: a coordinate that is not finite, an index out of range or a count that
  // would allocate far more than the file holds, in each format: an error naming the
  // file and the problem, before any large allocation.
  const std::string ply = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                          "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                          "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  auto              edit = [](std::string text, const std::string & from, const std::string & to) {
    text.replace(text.find(from), from.size(), to);
    return text;
  };
  const std::string   vtp = "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" byte_order=\"LittleEndian\">\n"
                            "<PolyData>\n<Piece NumberOfPoints=\"3\" NumberOfPolys=\"1\">\n<Points><DataArray "
                            "type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">0 0 0 1 0 0 0 1 0</DataArray>"
                            "</Points>\n<Polys><DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">0 1 2"
                            "</DataArray><DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">3</DataArray>"
                            "</Polys>\n</Piece>\n</PolyData>\n</VTKFile>\n";
  std::string         binarySTL(80, ' ');
  const std::uint32_t facets = 0xFFFFFFF0u; // about 200 GB of facets in a 134-byte file
  binarySTL.append(reinterpret_cast<const char *>(&facets), 4);
  binarySTL.append(50, '\0');
  struct Case
  {
    const char * name;
    std::string  text;
    const char * problem;
  };
  const Case cases[] = {
    { "nan.ply", edit(ply, "1 0 0", "nan 0 0"), "" },
    { "index.ply", edit(ply, "3 0 1 2", "3 0 1 3"), "names the vertex 3" },
    { "vertices.ply", edit(ply, "vertex 3", "vertex 4294967295"), "more than the supported" },
    { "corners.ply", edit(ply, "3 0 1 2", "200000000 0 1 2"), "more than the file holds" },
    { "faces.ply", edit(ply, "face 1", "face 3000000000"), "" },
    { "nan.vtp", edit(vtp, "0 0 0 1 0 0", "0 0 0 1 nan 0"), "point 1 has a coordinate that is not a finite number" },
    { "index.vtp", edit(vtp, ">0 1 2<", ">0 1 7<"), "names point 7" },
    { "points.vtp", edit(vtp, "NumberOfPoints=\"3\"", "NumberOfPoints=\"3000000000\""), "more than the file can hold" },
    { "polys.vtp", edit(vtp, "NumberOfPolys=\"1\"", "NumberOfPolys=\"3000000000\""), "more than the file can hold" },
    { "facets.stl", binarySTL, "header promises 4294967280" },
    { "negative.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -4\n", "" },
    { "inf.obj", "v 0 0 0\nv 1 0 0\nv 0 inf 0\nf 1 2 3\n", "not a finite number" },
    { "vertices.off", "OFF\n4000000000 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "more than the" },
    { "corners.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2000000000 0 1 2\n", "" },
    { "nan.stl",
      "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 nan 0\n"
      "endloop\nendfacet\nendsolid x\n",
      "not a finite number" },
  };
  for (const Case & c : cases)
  {
    SCOPED_TRACE(c.name);
    const std::string message = ReadError(c.name, c.text);
    EXPECT_FALSE(message.empty());
    EXPECT_NE(message.find(c.problem), std::string::npos) << message;
  }
}

TEST(MeshFile, RefusesTruncatedFilesOfEveryFormat)
{
  // Issue 32, cases 2 and 5: a file cut anywhere gives an error naming it.
  const ME::PolygonMesh mesh = MakeMixedMesh();
  const char *          names[] = { "t42.vtk", "t51.vtk", "tb42.vtk", "tb51.vtk", "t.vtp", "ta.vtp",
                                    "t.ply",   "ta.ply",  "t.stl",    "ta.stl",   "t.obj", "t.off" };
  for (const char * name : names)
  {
    Options           options;
    const std::string n = name;
    options.encoding = n.find("tb") == 0 ? Options::Encoding::Binary
                                         : (n.find("ta") == 0 ? Options::Encoding::ASCII : Options::Encoding::Default);
    options.vtkLegacyVersion =
      n.find("51") != std::string::npos ? Options::VTKLegacyVersion::V5_1 : Options::VTKLegacyVersion::V4_2;
    const std::string path = TemporaryPath(std::string("whole-") + name);
    ME::WritePolygonMeshFile(path, mesh, options);
    SCOPED_TRACE(name);
    ExpectNoCrashOnAnyPrefix(name, ReadBytes(path));
  }
}

TEST(MeshFile, RefusesCorruptVTPData)
{
  const std::string head = "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" byte_order=\"LittleEndian\" "
                           "header_type=\"UInt32\"%C>\n<PolyData>\n<Piece NumberOfPoints=\"3\" NumberOfPolys=\"1\">\n"
                           "<Points><DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">"
                           "0 0 0 1 0 0 0 1 0</DataArray></Points>\n<Polys>"
                           "<DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">%I</DataArray>"
                           "<DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">3</DataArray></Polys>\n"
                           "</Piece>\n</PolyData>\n</VTKFile>\n";
  auto              make = [&head](const std::string & compressor, const std::string & indices) {
    std::string text = head;
    text.replace(text.find("%C"), 2, compressor);
    text.replace(text.find("%I"), 2, indices);
    return text;
  };
  EXPECT_EQ(ME::ReadPolygonMeshFile(WriteText("good.vtp", make("", "0 1 2"))).NumberOfPolygons(), 1u);
  EXPECT_NE(ReadError("index.vtp", make("", "0 1 3")).find("names point 3"), std::string::npos);
  EXPECT_NE(ReadError("short.vtp", make("", "0 1")).find("end early"), std::string::npos);
  EXPECT_NE(ReadError("lz4.vtp", make(" compressor=\"vtkLZ4DataCompressor\"", "0 1 2")).find("vtkLZ4DataCompressor"),
            std::string::npos);
  EXPECT_NE(ReadError("grid.vtp", "<VTKFile type=\"UnstructuredGrid\">").find("only PolyData"), std::string::npos);
  std::string base64 = make("", "0 1 2");
  base64.replace(base64.find("format=\"ascii\">0 0 0"), 29, "format=\"binary\">JAAAAAAAAAAAAA*AAAAAA");
  EXPECT_NE(ReadError("base64.vtp", base64).find("base64"), std::string::npos);
}

// ------------------------------------------------------------------------------
// Meshes a QuadEdgeMesh cannot hold: refused before any face is added
// ------------------------------------------------------------------------------
namespace
{
/** Two closed cubes (12 triangles each) sharing one corner: a non-manifold vertex
 * (issue 32, case 3: ITK's QuadEdgeMesh crashed on it). */
ME::IndexedTriangleMesh
MakeCubesSharingACorner()
{
  ME::IndexedTriangleMesh mesh;
  const unsigned int      quads[6][4] = { { 0, 1, 3, 2 }, { 4, 6, 7, 5 }, { 0, 4, 5, 1 },
                                          { 2, 3, 7, 6 }, { 0, 2, 6, 4 }, { 1, 5, 7, 3 } };
  for (int cube = 0; cube < 2; ++cube)
  {
    std::uint32_t index[8];
    for (unsigned int c = 0; c < 8; ++c)
    {
      // Corner 7 of the first cube is corner 0 of the second.
      if (cube == 1 && c == 0)
      {
        index[c] = 7;
        continue;
      }
      index[c] = static_cast<std::uint32_t>(mesh.points.size());
      mesh.points.push_back(ME::MakeVec3(cube + ((c >> 2) & 1), cube + ((c >> 1) & 1), cube + (c & 1)));
    }
    for (const auto & q : quads)
    {
      mesh.triangles.push_back({ index[q[0]], index[q[1]], index[q[2]] });
      mesh.triangles.push_back({ index[q[0]], index[q[2]], index[q[3]] });
    }
  }
  return mesh;
}
} // namespace

TEST(MeshValidation, FindsNonManifoldVerticesBeforeAQuadEdgeMeshIsBuilt)
{
  const ME::IndexedTriangleMesh cubes = MakeCubesSharingACorner();
  const ME::TriangleMeshDefects defects = ME::FindTriangleMeshDefects(cubes);
  EXPECT_EQ(defects.numberOfNonManifoldVertices, 1u);
  EXPECT_EQ(defects.firstNonManifoldVertex, 7u);
  EXPECT_EQ(defects.numberOfNonManifoldEdges + defects.numberOfInconsistentEdges, 0u);
  const std::string message =
    ExceptionDescription([&cubes] { ME::RequireQuadEdgeMeshTriangles(cubes, "'cubes.obj'"); });
  EXPECT_NE(message.find("'cubes.obj' is not a manifold, consistently oriented triangle mesh: 1 non-manifold vertex "
                         "(point 7 at [1, 1, 1]"),
            std::string::npos)
    << message;
}

TEST(MeshValidation, FillMeshRefusesANonManifoldVertexInsteadOfCrashing)
{
  // In the file's order the first cube is closed before the second arrives; other
  // orders join two open fans, which the QuadEdgeMesh survives: either way, no crash.
  ME::IndexedTriangleMesh cubes = MakeCubesSharingACorner();
  std::mt19937            random(5);
  for (int trial = 0; trial < 40; ++trial)
  {
    auto mesh = itk::QuadEdgeMesh<double, 3>::New();
    try
    {
      ME::FillMesh(cubes, *mesh);
    }
    catch (const itk::ExceptionObject & e)
    {
      EXPECT_NE(std::string(e.GetDescription()).find("non-manifold"), std::string::npos);
    }
    std::shuffle(cubes.triangles.begin(), cubes.triangles.end(), random);
  }
}

TEST(MeshValidation, DescribesEveryKindOfDefect)
{
  ME::IndexedTriangleMesh mesh = MeshExtractionTest::MakeIcosphere(1);
  mesh.points[3][1] = std::numeric_limits<double>::quiet_NaN();
  mesh.triangles.push_back(mesh.triangles[0]);           // a third triangle on three edges
  std::swap(mesh.triangles[5][0], mesh.triangles[5][1]); // flipped
  ME::TriangleMeshDefects defects = ME::FindTriangleMeshDefects(mesh);
  EXPECT_EQ(defects.numberOfNonFinitePoints, 1u);
  EXPECT_EQ(defects.numberOfNonManifoldEdges, 3u);
  EXPECT_GT(defects.numberOfInconsistentEdges, 0u);
  const std::string text = defects.Describe(mesh);
  EXPECT_NE(text.find("not a finite number"), std::string::npos) << text;
  EXPECT_NE(text.find("shared by more than two triangles"), std::string::npos) << text;
  EXPECT_NE(text.find("oriented oppositely"), std::string::npos) << text;

  mesh.triangles.push_back({ 0, 0, 1 });
  mesh.triangles.push_back({ 0, 1, 999 });
  defects = ME::FindTriangleMeshDefects(mesh);
  EXPECT_EQ(defects.numberOfRepeatedCorners, 1u);
  EXPECT_EQ(defects.numberOfIndicesOutOfRange, 1u);
  EXPECT_NE(defects.Describe(mesh).find("naming a point the mesh has not"), std::string::npos);
}
