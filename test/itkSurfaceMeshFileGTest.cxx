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
// The public classes around the module's mesh files: SurfaceMeshFileReader and
// SurfaceMeshFileWriter (itk::Mesh and QuadEdgeMesh, every format) and
// SurfaceMeshConvertFilter (itk::Mesh <-> QuadEdgeMesh).

#include "itkMeshExtractionTestHelpers.h"
#include "itkSurfaceMeshConvertFilter.h"
#include "itkSurfaceMeshFileReader.h"
#include "itkSurfaceMeshFileWriter.h"
#include "itkTriangleMeshQualityCalculator.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace ME = itk::MeshExtraction;
using MeshExtractionTest::ExceptionDescription;
using MeshExtractionTest::MeshType;
using MeshExtractionTest::QEMeshType;
using Enums = itk::MeshExtractionEnums;

namespace
{
std::filesystem::path
TemporaryDirectory()
{
  const auto directory = std::filesystem::temp_directory_path() / "meshextraction-surfacemeshfile-gtest";
  std::filesystem::remove_all(directory);
  std::filesystem::create_directories(directory);
  return directory;
}

template <typename TMesh>
typename TMesh::Pointer
Read(const std::filesystem::path & path)
{
  auto reader = itk::SurfaceMeshFileReader<TMesh>::New();
  reader->SetFileName(path.string());
  reader->Update();
  return reader->GetOutput();
}

template <typename TMesh>
void
Write(const TMesh *                 mesh,
      const std::filesystem::path & path,
      Enums::MeshFileEncoding       encoding = Enums::MeshFileEncoding::Default,
      Enums::VTKLegacyVersion       version = Enums::VTKLegacyVersion::V4_2)
{
  auto writer = itk::SurfaceMeshFileWriter<TMesh>::New();
  writer->SetInput(mesh);
  writer->SetFileName(path.string());
  writer->SetEncoding(encoding);
  writer->SetVTKLegacyVersion(version);
  writer->Update();
}

template <typename TMesh>
bool
IsValidClosedSurface(const TMesh * mesh)
{
  auto quality = itk::TriangleMeshQualityCalculator<TMesh>::New();
  quality->SetMesh(mesh);
  quality->Compute();
  return quality->GetReport().IsValidClosedSurface();
}

/** The points and faces of a mesh as the module's polygons, for exact comparison. */
template <typename TMesh>
ME::PolygonMesh
Faces(const TMesh * mesh)
{
  return ME::MakePolygonMeshFromMesh(*mesh);
}
} // namespace

TEST(SurfaceMeshFileReaderWriter, EveryFormatRoundTripsBothMeshTypes)
{
  const auto dir = TemporaryDirectory();
  const auto qe = MeshExtractionTest::ToITKMesh<QEMeshType>(MeshExtractionTest::MakeIcosphere(2, 5.0));
  const auto expected = Faces(qe.GetPointer());
  const struct
  {
    const char *            name;
    Enums::MeshFileEncoding encoding;
    Enums::VTKLegacyVersion version;
  } cases[] = { { "a.vtk", Enums::MeshFileEncoding::ASCII, Enums::VTKLegacyVersion::V4_2 },
                { "b.vtk", Enums::MeshFileEncoding::Binary, Enums::VTKLegacyVersion::V5_1 },
                { "c.vtp", Enums::MeshFileEncoding::Default, Enums::VTKLegacyVersion::V4_2 },
                { "d.ply", Enums::MeshFileEncoding::ASCII, Enums::VTKLegacyVersion::V4_2 },
                { "e.stl", Enums::MeshFileEncoding::Binary, Enums::VTKLegacyVersion::V4_2 },
                { "f.obj", Enums::MeshFileEncoding::Default, Enums::VTKLegacyVersion::V4_2 },
                { "g.off", Enums::MeshFileEncoding::Default, Enums::VTKLegacyVersion::V4_2 } };
  for (const auto & c : cases)
  {
    SCOPED_TRACE(c.name);
    Write(qe.GetPointer(), dir / c.name, c.encoding, c.version);
    const auto asMesh = Read<MeshType>(dir / c.name);
    const auto asQE = Read<QEMeshType>(dir / c.name);
    EXPECT_EQ(asMesh->GetNumberOfCells(), expected.NumberOfPolygons());
    EXPECT_EQ(asQE->GetNumberOfFaces(), expected.NumberOfPolygons());
    EXPECT_TRUE(IsValidClosedSurface(asMesh.GetPointer()));
    EXPECT_TRUE(IsValidClosedSurface(asQE.GetPointer()));
    if (std::string(c.name) != "e.stl") // STL joins corners by their coordinates
    {
      const auto back = Faces(asQE.GetPointer());
      EXPECT_EQ(back.points, expected.points);
      EXPECT_EQ(back.polygonIndices, expected.polygonIndices);
    }
  }
  // An itk::Mesh written and read again, through the module's VTK 5.1 file.
  const auto plain = Read<MeshType>(dir / "b.vtk");
  Write(plain.GetPointer(), dir / "h.vtk", Enums::MeshFileEncoding::ASCII, Enums::VTKLegacyVersion::V5_1);
  EXPECT_EQ(Faces(Read<MeshType>(dir / "h.vtk").GetPointer()).polygonIndices, Faces(plain.GetPointer()).polygonIndices);
}

TEST(SurfaceMeshFileReaderWriter, AFailedWriteLeavesTheOldFileAndNoPartialFile)
{
  const auto dir = TemporaryDirectory();
  const auto qe = MeshExtractionTest::ToITKMesh<QEMeshType>(MeshExtractionTest::MakeTetrahedron());
  Write(qe.GetPointer(), dir / "t.obj");
  std::ifstream     in(dir / "t.obj");
  const std::string before((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string what =
    ExceptionDescription([&] { Write(qe.GetPointer(), dir / "t.obj", Enums::MeshFileEncoding::Binary); });
  EXPECT_NE(what.find("t.obj"), std::string::npos) << what;
  std::ifstream     again(dir / "t.obj");
  const std::string after((std::istreambuf_iterator<char>(again)), std::istreambuf_iterator<char>());
  EXPECT_EQ(after, before);
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator()), 1);
}

TEST(SurfaceMeshFileReaderWriter, BadInputIsNamed)
{
  const auto dir = TemporaryDirectory();
  auto       reader = itk::SurfaceMeshFileReader<QEMeshType>::New();
  EXPECT_NE(ExceptionDescription([&] { reader->Update(); }).find("no file name"), std::string::npos);
  reader->SetFileName((dir / "missing.ply").string());
  EXPECT_NE(ExceptionDescription([&] { reader->Update(); }).find("missing.ply"), std::string::npos);
  auto writer = itk::SurfaceMeshFileWriter<QEMeshType>::New();
  EXPECT_NE(ExceptionDescription([&] { writer->Update(); }).find("no input mesh"), std::string::npos);
  writer->SetInput(MeshExtractionTest::ToITKMesh<QEMeshType>(MeshExtractionTest::MakeTetrahedron()));
  EXPECT_NE(ExceptionDescription([&] { writer->Update(); }).find("no file name"), std::string::npos);
  writer->SetFileName((dir / "t.xyz").string());
  EXPECT_NE(ExceptionDescription([&] { writer->Update(); }).find("names no format"), std::string::npos);
  // Three faces on one edge: an itk::Mesh holds them, a QuadEdgeMesh is refused.
  std::ofstream((dir / "fin.obj").string()) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\n"
                                               "f 1 2 3\nf 2 1 4\nf 1 2 5\n";
  EXPECT_EQ(Read<MeshType>(dir / "fin.obj")->GetNumberOfCells(), 3u);
  const std::string what = ExceptionDescription([&] { Read<QEMeshType>(dir / "fin.obj"); });
  EXPECT_NE(what.find("fin.obj"), std::string::npos) << what;
}

TEST(SurfaceMeshFileReaderWriter, VertexAndLineCellsAreCountedNotHidden)
{
  const auto dir = TemporaryDirectory();
  std::ofstream((dir / "mixed.vtk").string()) << "# vtk DataFile Version 4.2\nmixed\nASCII\nDATASET POLYDATA\n"
                                                 "POINTS 4 double\n1 1 1\n1 -1 -1\n-1 1 -1\n-1 -1 1\n"
                                                 "VERTICES 1 2\n1 0\nLINES 1 3\n2 0 1\n"
                                                 "POLYGONS 4 16\n3 0 1 2\n3 0 3 1\n3 0 2 3\n3 1 3 2\n";
  auto reader = itk::SurfaceMeshFileReader<MeshType>::New();
  reader->SetFileName((dir / "mixed.vtk").string());
  reader->Update();
  EXPECT_EQ(reader->GetOutput()->GetNumberOfCells(), 4u);
  EXPECT_EQ(reader->GetNumberOfIgnoredCells(), 2u);
}

TEST(SurfaceMeshConvertFilter, QuadEdgeMeshToMeshAndBackKeepsPointsAndFaces)
{
  const auto qe = MeshExtractionTest::ToITKMesh<QEMeshType>(MeshExtractionTest::MakeTorus(12, 8, 5.0, 1.5));
  auto       toMesh = itk::SurfaceMeshConvertFilter<QEMeshType, MeshType>::New();
  toMesh->SetInput(qe);
  toMesh->Update();
  const MeshType * mesh = toMesh->GetOutput();
  EXPECT_EQ(mesh->GetNumberOfCells(), qe->GetNumberOfFaces()); // the edges are not faces
  EXPECT_EQ(mesh->GetNumberOfPoints(), qe->GetNumberOfPoints());
  auto toQE = itk::SurfaceMeshConvertFilter<MeshType, QEMeshType>::New();
  toQE->SetInput(mesh);
  toQE->Update();
  EXPECT_EQ(Faces(toQE->GetOutput()).polygonIndices, Faces(qe.GetPointer()).polygonIndices);
  EXPECT_EQ(Faces(toQE->GetOutput()).points, Faces(qe.GetPointer()).points);
  EXPECT_EQ(toQE->GetOutput()->GetNumberOfEdges(), qe->GetNumberOfEdges());
  EXPECT_TRUE(IsValidClosedSurface(toQE->GetOutput()));
  // Run again after a change of input: the output is replaced, not appended to.
  toQE->SetInput(toMesh->GetOutput());
  toQE->Modified();
  toQE->Update();
  EXPECT_EQ(toQE->GetOutput()->GetNumberOfFaces(), qe->GetNumberOfFaces());
}

TEST(SurfaceMeshConvertFilter, FacesAQuadEdgeMeshCannotHoldAreRefused)
{
  auto     mesh = MeshType::New();
  ME::PolygonMesh fin;
  fin.points = { ME::MakeVec3(0, 0, 0), ME::MakeVec3(1, 0, 0), ME::MakeVec3(0, 1, 0), ME::MakeVec3(0, -1, 0),
                 ME::MakeVec3(0, 0, 1) };
  const std::uint32_t faces[3][3] = { { 0, 1, 2 }, { 1, 0, 3 }, { 0, 1, 4 } };
  for (const auto & f : faces)
  {
    fin.AddPolygon(f, 3);
  }
  ME::FillMeshWithPolygons(fin, *mesh);
  auto filter = itk::SurfaceMeshConvertFilter<MeshType, QEMeshType>::New();
  filter->SetInput(mesh);
  const std::string what = ExceptionDescription([&] { filter->Update(); });
  EXPECT_NE(what.find("the input mesh"), std::string::npos) << what;
  auto empty = itk::SurfaceMeshConvertFilter<MeshType, QEMeshType>::New();
  // ITK names the missing input before GenerateData runs.
  EXPECT_NE(ExceptionDescription([&] { empty->Update(); }).find("required"), std::string::npos);
}
