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
// The module's mesh files against VTK itself (built where VTK is found): every file
// VTK 9's writers make (legacy 4.2 and 5.1 in ASCII and binary; XML PolyData ascii,
// binary, appended raw and base64, compressed or not, either header type and byte
// order; STL; PLY; OBJ) reads as the mesh VTK wrote, and every file the module writes
// reads in VTK as the module's mesh.

#include "itkMeshExtractionMeshFile.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkCubeSource.h"
#include "vtkIdList.h"
#include "vtkNew.h"
#include "vtkOBJReader.h"
#include "vtkOBJWriter.h"
#include "vtkPLYReader.h"
#include "vtkPLYWriter.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataReader.h"
#include "vtkPolyDataWriter.h"
#include "vtkSTLReader.h"
#include "vtkSTLWriter.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"
#include "vtkXMLPolyDataReader.h"
#include "vtkXMLPolyDataWriter.h"

#include "gtest/gtest.h"

#include <filesystem>
#include <functional>

namespace ME = itk::MeshExtraction;

namespace
{
std::string
TemporaryPath(const std::string & name)
{
  const auto directory = std::filesystem::temp_directory_path() / "meshextraction-meshfile-vtk-gtest";
  std::filesystem::create_directories(directory);
  return (directory / name).string();
}

/** A sphere of triangles, or a cube of quadrilaterals. */
vtkSmartPointer<vtkPolyData>
MakePolyData(bool quads)
{
  if (quads)
  {
    vtkNew<vtkCubeSource> cube;
    cube->SetXLength(2.5);
    cube->SetCenter(10.125, -3.5, 7.0);
    cube->Update();
    // The cube source gives each face its own corners; the polygons are what matters.
    return cube->GetOutput();
  }
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(16);
  sphere->SetPhiResolution(12);
  sphere->SetRadius(37.25);
  sphere->SetCenter(101.5, -20.25, 63.0);
  sphere->Update();
  return sphere->GetOutput();
}

/** The polygons of a vtkPolyData. */
std::vector<std::vector<std::uint32_t>>
PolygonsOf(vtkPolyData * data)
{
  std::vector<std::vector<std::uint32_t>> polygons;
  vtkNew<vtkIdList>                       ids;
  vtkCellArray *                          polys = data->GetPolys();
  polys->InitTraversal();
  while (polys->GetNextCell(ids))
  {
    std::vector<std::uint32_t> polygon;
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
    {
      polygon.push_back(static_cast<std::uint32_t>(ids->GetId(k)));
    }
    polygons.push_back(polygon);
  }
  return polygons;
}

std::vector<std::vector<std::uint32_t>>
PolygonsOf(const ME::PolygonMesh & mesh)
{
  std::vector<std::vector<std::uint32_t>> polygons;
  for (std::size_t p = 0; p < mesh.NumberOfPolygons(); ++p)
  {
    polygons.emplace_back(mesh.Polygon(p), mesh.Polygon(p) + mesh.PolygonSize(p));
  }
  return polygons;
}

/** Same points (to a relative tolerance) and same polygons. */
void
ExpectSameMesh(vtkPolyData * vtk, const ME::PolygonMesh & mesh, double tolerance)
{
  ASSERT_EQ(static_cast<std::size_t>(vtk->GetNumberOfPoints()), mesh.points.size());
  for (vtkIdType i = 0; i < vtk->GetNumberOfPoints(); ++i)
  {
    double p[3];
    vtk->GetPoint(i, p);
    for (unsigned int d = 0; d < 3; ++d)
    {
      ASSERT_NEAR(p[d], mesh.points[i][d], tolerance * (1.0 + std::abs(p[d]))) << "point " << i;
    }
  }
  EXPECT_EQ(PolygonsOf(vtk), PolygonsOf(mesh));
}

/** STL keeps no shared vertices: the same triangles, corner by corner, in space. */
void
ExpectSameTriangles(vtkPolyData * vtk, const ME::PolygonMesh & mesh, double tolerance)
{
  const auto vtkPolygons = PolygonsOf(vtk);
  ASSERT_EQ(vtkPolygons.size(), mesh.NumberOfPolygons());
  for (std::size_t f = 0; f < vtkPolygons.size(); ++f)
  {
    ASSERT_EQ(vtkPolygons[f].size(), mesh.PolygonSize(f));
    for (std::size_t k = 0; k < vtkPolygons[f].size(); ++k)
    {
      double p[3];
      vtk->GetPoint(vtkPolygons[f][k], p);
      const ME::Vec3 & q = mesh.points[mesh.Polygon(f)[k]];
      for (unsigned int d = 0; d < 3; ++d)
      {
        ASSERT_NEAR(p[d], q[d], tolerance * (1.0 + std::abs(p[d])));
      }
    }
  }
}

ME::PolygonMesh
FromPolyData(vtkPolyData * vtk)
{
  ME::PolygonMesh mesh;
  for (vtkIdType i = 0; i < vtk->GetNumberOfPoints(); ++i)
  {
    double p[3];
    vtk->GetPoint(i, p);
    mesh.points.push_back(ME::MakeVec3(p[0], p[1], p[2]));
  }
  for (const auto & polygon : PolygonsOf(vtk))
  {
    mesh.AddPolygon(polygon.data(), polygon.size());
  }
  return mesh;
}
} // namespace

// ------------------------------------------------------------------------------
// VTK writes, the module reads
// ------------------------------------------------------------------------------
TEST(MeshFileVTK, ReadsVTKLegacyFilesOfVersions42And51)
{
  for (const bool quads : { false, true })
  {
    for (const int version : { 42, 51 })
    {
      for (const bool binary : { false, true })
      {
        SCOPED_TRACE(std::to_string(version) + (binary ? " binary" : " ascii") + (quads ? " cube" : " sphere"));
        const auto                polyData = MakePolyData(quads);
        const std::string         path = TemporaryPath("vtk" + std::to_string(version) + (binary ? "b" : "a") + ".vtk");
        vtkNew<vtkPolyDataWriter> writer;
        writer->SetInputData(polyData);
        writer->SetFileName(path.c_str());
        writer->SetFileVersion(version);
        binary ? writer->SetFileTypeToBinary() : writer->SetFileTypeToASCII();
        ASSERT_EQ(writer->Write(), 1);
        // VTK's ASCII legacy files hold six significant digits.
        ExpectSameMesh(polyData, ME::ReadPolygonMeshFile(path), binary ? 1e-7 : 1e-5);
      }
    }
  }
}

TEST(MeshFileVTK, ReadsVTKXMLPolyDataInEveryEncoding)
{
  using Configure = std::function<void(vtkXMLPolyDataWriter *)>;
  const std::pair<const char *, Configure> cases[] = {
    { "default", [](vtkXMLPolyDataWriter *) {} },
    { "ascii", [](vtkXMLPolyDataWriter * w) { w->SetDataModeToAscii(); } },
    { "binary", [](vtkXMLPolyDataWriter * w) { w->SetDataModeToBinary(); } },
    { "binary-uncompressed",
      [](vtkXMLPolyDataWriter * w) {
        w->SetDataModeToBinary();
        w->SetCompressorTypeToNone();
      } },
    { "raw",
      [](vtkXMLPolyDataWriter * w) {
        w->SetDataModeToAppended();
        w->EncodeAppendedDataOff();
      } },
    { "raw-uncompressed-uint64",
      [](vtkXMLPolyDataWriter * w) {
        w->EncodeAppendedDataOff();
        w->SetCompressorTypeToNone();
        w->SetHeaderTypeToUInt64();
      } },
    { "base64-big-endian-small-blocks",
      [](vtkXMLPolyDataWriter * w) {
        w->SetByteOrderToBigEndian();
        w->SetHeaderTypeToUInt64();
        w->SetBlockSize(96);
      } },
  };
  for (const bool quads : { false, true })
  {
    for (const auto & c : cases)
    {
      SCOPED_TRACE(std::string(c.first) + (quads ? " cube" : " sphere"));
      const auto                   polyData = MakePolyData(quads);
      const std::string            path = TemporaryPath(std::string(c.first) + ".vtp");
      vtkNew<vtkXMLPolyDataWriter> writer;
      writer->SetInputData(polyData);
      writer->SetFileName(path.c_str());
      c.second(writer);
      ASSERT_EQ(writer->Write(), 1);
      ExpectSameMesh(polyData, ME::ReadPolygonMeshFile(path), 1e-6);
    }
  }
}

TEST(MeshFileVTK, ReadsSTLPLYAndOBJ)
{
  const auto polyData = MakePolyData(false);
  for (const bool binary : { false, true })
  {
    SCOPED_TRACE(binary ? "binary" : "ascii");
    const std::string    stl = TemporaryPath(binary ? "b.stl" : "a.stl");
    vtkNew<vtkSTLWriter> stlWriter;
    stlWriter->SetInputData(polyData);
    stlWriter->SetFileName(stl.c_str());
    binary ? stlWriter->SetFileTypeToBinary() : stlWriter->SetFileTypeToASCII();
    ASSERT_EQ(stlWriter->Write(), 1);
    const ME::PolygonMesh fromSTL = ME::ReadPolygonMeshFile(stl);
    ExpectSameTriangles(polyData, fromSTL, 1e-6);
    EXPECT_EQ(fromSTL.points.size(), static_cast<std::size_t>(polyData->GetNumberOfPoints()));

    const std::string    ply = TemporaryPath(binary ? "b.ply" : "a.ply");
    vtkNew<vtkPLYWriter> plyWriter;
    plyWriter->SetInputData(polyData);
    plyWriter->SetFileName(ply.c_str());
    binary ? plyWriter->SetFileTypeToBinary() : plyWriter->SetFileTypeToASCII();
    ASSERT_EQ(plyWriter->Write(), 1);
    ExpectSameMesh(polyData, ME::ReadPolygonMeshFile(ply), 1e-6);
  }
  const std::string    obj = TemporaryPath("vtk.obj");
  vtkNew<vtkOBJWriter> objWriter;
  objWriter->SetInputData(polyData);
  objWriter->SetFileName(obj.c_str());
  ASSERT_EQ(objWriter->Write(), 1);
  ExpectSameMesh(polyData, ME::ReadPolygonMeshFile(obj), 1e-6);
}

// ------------------------------------------------------------------------------
// The module writes, VTK reads
// ------------------------------------------------------------------------------
namespace
{
template <typename TReader>
vtkSmartPointer<vtkPolyData>
ReadWithVTK(const std::string & path)
{
  vtkNew<TReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  return reader->GetOutput();
}
} // namespace

TEST(MeshFileVTK, VTKReadsWhatTheModuleWrites)
{
  using Options = ME::MeshFileWriteOptions;
  for (const bool quads : { false, true })
  {
    const ME::PolygonMesh mesh = FromPolyData(MakePolyData(quads));
    for (const auto encoding : { Options::Encoding::ASCII, Options::Encoding::Binary })
    {
      SCOPED_TRACE(std::string(encoding == Options::Encoding::ASCII ? "ascii" : "binary") +
                   (quads ? " cube" : " sphere"));
      for (const auto version : { Options::VTKLegacyVersion::V4_2, Options::VTKLegacyVersion::V5_1 })
      {
        const std::string path = TemporaryPath("me.vtk");
        ME::WritePolygonMeshFile(path, mesh, Options{ encoding, version });
        ExpectSameMesh(ReadWithVTK<vtkPolyDataReader>(path), mesh, 1e-15);
      }
      const std::string vtp = TemporaryPath("me.vtp");
      ME::WritePolygonMeshFile(vtp, mesh, Options{ encoding });
      ExpectSameMesh(ReadWithVTK<vtkXMLPolyDataReader>(vtp), mesh, 1e-15);
      const std::string ply = TemporaryPath("me.ply");
      ME::WritePolygonMeshFile(ply, mesh, Options{ encoding });
      ExpectSameMesh(ReadWithVTK<vtkPLYReader>(ply), mesh, 1e-7); // VTK keeps PLY points as float
      const std::string stl = TemporaryPath("me.stl");
      ME::WritePolygonMeshFile(stl, mesh, Options{ encoding });
      const ME::PolygonMesh triangles = ME::MakePolygonMesh(ME::TriangulatePolygonMesh(mesh));
      ExpectSameTriangles(ReadWithVTK<vtkSTLReader>(stl), triangles, 1e-7);
    }
    const std::string obj = TemporaryPath("me.obj");
    ME::WritePolygonMeshFile(obj, mesh);
    ExpectSameMesh(ReadWithVTK<vtkOBJReader>(obj), mesh, 1e-7);
  }
}

// Cell arrays (a multi-label surface's two labels per face): VTK reads them back from the
// legacy format (a FIELD of CELL_DATA, both versions and encodings) and from VTP.
TEST(MeshFileVTK, VTKReadsTheCellArraysTheModuleWrites)
{
  using Options = ME::MeshFileWriteOptions;
  ME::PolygonMesh            mesh = FromPolyData(MakePolyData(false));
  ME::PolygonMesh::CellArray labels;
  labels.name = "labels";
  labels.components = 2;
  for (std::size_t f = 0; f < mesh.NumberOfPolygons(); ++f)
  {
    labels.values.push_back(static_cast<std::uint32_t>(f % 3));
    labels.values.push_back(static_cast<std::uint32_t>(4000000000u + f));
  }
  mesh.cellArrays.push_back(labels);
  auto expectArray = [&](vtkPolyData * read) {
    ExpectSameMesh(read, mesh, 1e-15);
    vtkDataArray * array = read->GetCellData()->GetArray("labels");
    ASSERT_NE(array, nullptr);
    ASSERT_EQ(array->GetNumberOfComponents(), 2);
    ASSERT_EQ(static_cast<std::size_t>(array->GetNumberOfTuples()), mesh.NumberOfPolygons());
    for (std::size_t f = 0; f < mesh.NumberOfPolygons(); ++f)
    {
      ASSERT_EQ(array->GetComponent(static_cast<vtkIdType>(f), 0), static_cast<double>(labels.values[2 * f]));
      ASSERT_EQ(array->GetComponent(static_cast<vtkIdType>(f), 1), static_cast<double>(labels.values[2 * f + 1]));
    }
  };
  for (const auto encoding : { Options::Encoding::ASCII, Options::Encoding::Binary })
  {
    for (const auto version : { Options::VTKLegacyVersion::V4_2, Options::VTKLegacyVersion::V5_1 })
    {
      const std::string path = TemporaryPath("labels.vtk");
      ME::WritePolygonMeshFile(path, mesh, Options{ encoding, version });
      vtkNew<vtkPolyDataReader> reader;
      reader->SetFileName(path.c_str());
      reader->ReadAllFieldsOn();
      reader->Update();
      expectArray(reader->GetOutput());
    }
    const std::string vtp = TemporaryPath("labels.vtp");
    ME::WritePolygonMeshFile(vtp, mesh, Options{ encoding });
    expectArray(ReadWithVTK<vtkXMLPolyDataReader>(vtp));
  }
  // The module's own readers leave the array out and read the surface.
  const ME::PolygonMesh back = ME::ReadPolygonMeshFile(TemporaryPath("labels.vtk"));
  EXPECT_EQ(back.NumberOfPolygons(), mesh.NumberOfPolygons());
}
