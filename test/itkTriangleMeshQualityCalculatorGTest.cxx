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
#include "itkTriangleMeshQualityCalculator.h"
#include "itkMeshExtractionJSON.h"
#include "itkMeshExtractionTestHelpers.h"
#include "itkQuadrilateralCell.h"
#include "itkPolygonCell.h"

#include "gtest/gtest.h"

#include <limits>
#include <numeric>
#include <sstream>

using namespace MeshExtractionTest;
using itk::MeshExtraction::TriangleMeshQualityReport;

namespace
{
template <typename TMesh = MeshType>
TriangleMeshQualityReport
Analyze(const IndexedTriangleMesh & m, const IndexedTriangleMesh * reference = nullptr)
{
  auto calculator = itk::TriangleMeshQualityCalculator<TMesh>::New();
  auto mesh = ToITKMesh<TMesh>(m);
  calculator->SetMesh(mesh);
  typename TMesh::Pointer referenceMesh;
  if (reference)
  {
    referenceMesh = ToITKMesh<TMesh>(*reference);
    calculator->SetReferenceMesh(referenceMesh);
  }
  calculator->Compute();
  return calculator->GetReport();
}

void
ExpectClean(const TriangleMeshQualityReport & r)
{
  EXPECT_EQ(r.degenerateTriangles, 0);
  EXPECT_EQ(r.nonManifoldEdges, 0);
  EXPECT_EQ(r.nonManifoldVertices, 0);
  EXPECT_EQ(r.boundaryEdges, 0);
  EXPECT_EQ(r.boundaryLoops, 0);
  EXPECT_EQ(r.inconsistentlyOrientedEdges, 0);
  EXPECT_EQ(r.invertedTrianglesVersusOutward, 0);
  EXPECT_EQ(r.undeterminedOrientationTriangles, 0);
  EXPECT_EQ(r.selfIntersectingPairs, 0);
  EXPECT_EQ(r.unreferencedPoints, 0);
  EXPECT_TRUE(r.IsValidClosedSurface());
}

IndexedTriangleMesh
Flipped(IndexedTriangleMesh m, std::size_t triangle)
{
  std::swap(m.triangles[triangle][1], m.triangles[triangle][2]);
  return m;
}

/** Two closed meshes as one. */
IndexedTriangleMesh
Union(const IndexedTriangleMesh & a, const IndexedTriangleMesh & b)
{
  IndexedTriangleMesh m = a;
  const auto          offset = static_cast<std::uint32_t>(a.points.size());
  m.points.insert(m.points.end(), b.points.begin(), b.points.end());
  for (auto t : b.triangles)
  {
    m.triangles.push_back({ t[0] + offset, t[1] + offset, t[2] + offset });
  }
  return m;
}
} // namespace

TEST(TriangleMeshQualityCalculator, SphereMeshIsAValidClosedSurfaceWithEulerCharacteristicTwo)
{
  const IndexedTriangleMesh sphere = MakeIcosphere(3, 10.0);
  for (const auto & r : { Analyze<MeshType>(sphere), Analyze<QEMeshType>(sphere) })
  {
    ExpectClean(r);
    EXPECT_EQ(r.numberOfTriangles, 1280u);
    EXPECT_EQ(r.eulerCharacteristic, 2);
    EXPECT_EQ(r.genus, 0);
    EXPECT_EQ(r.connectedComponents, 1);
    EXPECT_NEAR(r.enclosedVolume, 4.0 / 3.0 * itk::Math::pi * 1000.0, 0.02 * 4188.8);
    EXPECT_LT(r.enclosedVolume, 4.0 / 3.0 * itk::Math::pi * 1000.0); // inscribed polyhedron
    EXPECT_GT(r.qArea.mean, 0.9);
    EXPECT_EQ(r.valenceHistogram[5], 12u); // the icosahedron's vertices
    EXPECT_EQ(r.valenceHistogram[6], r.numberOfReferencedPoints - 12);
    EXPECT_LT(r.meanSmoothness, 0.05);
  }
}

TEST(TriangleMeshQualityCalculator, TorusHasEulerCharacteristicZeroAndGenusOne)
{
  const auto r = Analyze(MakeTorus(32, 16, 10.0, 3.0));
  ExpectClean(r);
  EXPECT_EQ(r.eulerCharacteristic, 0);
  EXPECT_EQ(r.genus, 1);
}

TEST(TriangleMeshQualityCalculator, QuadEdgeMeshAndMeshGiveTheSameMeasures)
{
  const IndexedTriangleMesh torus = MakeTorus(20, 10, 5.0, 2.0);
  const auto                a = Analyze<MeshType>(torus);
  const auto                b = Analyze<QEMeshType>(torus);
  EXPECT_DOUBLE_EQ(a.qArea.mean, b.qArea.mean);
  EXPECT_DOUBLE_EQ(a.qAngle.mean, b.qAngle.mean);
  EXPECT_DOUBLE_EQ(a.meanSmoothness, b.meanSmoothness);
  EXPECT_EQ(a.numberOfEdges, b.numberOfEdges);
  EXPECT_EQ(b.numberOfTriangles, 400u);
}

TEST(TriangleMeshQualityCalculator, HolesAreCountedAsBoundaryLoops)
{
  IndexedTriangleMesh sphere = MakeIcosphere(2);
  sphere.triangles.erase(sphere.triangles.begin());
  auto r = Analyze(sphere);
  EXPECT_EQ(r.boundaryEdges, 3);
  EXPECT_EQ(r.boundaryLoops, 1);
  EXPECT_FALSE(r.IsClosed());
  EXPECT_EQ(r.invertedTrianglesVersusOutward, -1); // undefined for an open surface
  EXPECT_EQ(r.genus, 0);                           // a disc
  EXPECT_FALSE(r.IsValidClosedSurface());
  // A second hole far from the first.
  sphere.triangles.erase(sphere.triangles.begin() + 150);
  r = Analyze(sphere);
  EXPECT_EQ(r.boundaryEdges, 6);
  EXPECT_EQ(r.boundaryLoops, 2);
  EXPECT_EQ(r.eulerCharacteristic, 0); // an annulus
}

TEST(TriangleMeshQualityCalculator, OpenGridHasOneBoundaryLoopAndFlatInteriorVertices)
{
  const auto r = Analyze(MakeGrid(10));
  EXPECT_EQ(r.boundaryEdges, 40);
  EXPECT_EQ(r.boundaryLoops, 1);
  EXPECT_EQ(r.eulerCharacteristic, 1);
  EXPECT_EQ(r.numberOfInteriorVertices, 81u);
  EXPECT_NEAR(r.meanSmoothness, 0.0, 1e-12);
  EXPECT_NEAR(r.totalArea, 100.0, 1e-9);
}

TEST(TriangleMeshQualityCalculator, NonManifoldEdgeIsDetected)
{
  IndexedTriangleMesh sphere = MakeIcosphere(1);
  const auto          t = sphere.triangles[0];
  sphere.points.push_back(MakeVec3(3, 3, 3));
  sphere.triangles.push_back({ t[0], t[1], static_cast<std::uint32_t>(sphere.points.size() - 1) }); // a fin
  const auto r = Analyze(sphere);
  EXPECT_EQ(r.nonManifoldEdges, 1);
  EXPECT_FALSE(r.IsManifold());
  EXPECT_EQ(r.genus, -1);
  EXPECT_FALSE(r.IsValidClosedSurface());
}

TEST(TriangleMeshQualityCalculator, QuadEdgeMeshRefusesANonManifoldEdgeLoudly)
{
  IndexedTriangleMesh sphere = MakeIcosphere(1);
  const auto          t = sphere.triangles[0];
  sphere.points.push_back(MakeVec3(3, 3, 3));
  sphere.triangles.push_back({ t[0], t[1], static_cast<std::uint32_t>(sphere.points.size() - 1) });
  auto mesh = QEMeshType::New();
  EXPECT_THROW(itk::MeshExtraction::FillMesh(sphere, *mesh), itk::ExceptionObject);
}

TEST(TriangleMeshQualityCalculator, BowTieVertexIsNonManifold)
{
  IndexedTriangleMesh a = MakeTetrahedron();
  IndexedTriangleMesh b = MakeTetrahedron();
  for (auto & p : b.points)
  {
    p = MakeVec3(2, 2, 2) - p + MakeVec3(0, 0, 0); // point-mirrored through (1,1,1): vertex 0 stays
  }
  for (auto & t : b.triangles)
  {
    std::swap(t[1], t[2]); // mirroring flips orientation; restore outward
  }
  IndexedTriangleMesh m = Union(a, b);
  // Merge b's copy of vertex 0 (at (1,1,1)) into a's vertex 0.
  for (auto & t : m.triangles)
  {
    for (auto & v : t)
    {
      v = v == 4 ? 0 : v;
    }
  }
  const auto r = Analyze(m);
  EXPECT_EQ(r.nonManifoldVertices, 1);
  EXPECT_EQ(r.nonManifoldEdges, 0);
  EXPECT_EQ(r.connectedComponents, 2);
  EXPECT_EQ(r.unreferencedPoints, 1);
  EXPECT_EQ(r.selfIntersectingPairs, 0);
  EXPECT_FALSE(r.IsValidClosedSurface());
}

TEST(TriangleMeshQualityCalculator, FlippedTriangleIsInconsistentAndInverted)
{
  const auto r = Analyze(Flipped(MakeIcosphere(2), 17));
  EXPECT_EQ(r.inconsistentlyOrientedEdges, 3);
  EXPECT_EQ(r.invertedTrianglesVersusOutward, 1);
  EXPECT_EQ(r.genus, -1);
  EXPECT_FALSE(r.IsValidClosedSurface());
}

TEST(TriangleMeshQualityCalculator, InsideOutSphereHasEveryTriangleInverted)
{
  IndexedTriangleMesh sphere = MakeIcosphere(2);
  for (std::size_t f = 0; f < sphere.triangles.size(); ++f)
  {
    sphere = Flipped(sphere, f);
  }
  const auto r = Analyze(sphere);
  EXPECT_EQ(r.inconsistentlyOrientedEdges, 0);
  EXPECT_EQ(r.invertedTrianglesVersusOutward, static_cast<std::int64_t>(sphere.triangles.size()));
  EXPECT_LT(r.enclosedVolume, 0.0);
  EXPECT_FALSE(r.IsValidClosedSurface());
}

TEST(TriangleMeshQualityCalculator, NestedShellsAreOrientedByEnclosedMaterial)
{
  // A hollow ball: outer sphere outward, inner sphere facing the cavity.
  IndexedTriangleMesh inner = MakeIcosphere(2, 0.5);
  for (auto & t : inner.triangles)
  {
    std::swap(t[1], t[2]);
  }
  auto r = Analyze(Union(MakeIcosphere(2, 1.0), inner));
  ExpectClean(r);
  EXPECT_EQ(r.connectedComponents, 2);
  EXPECT_EQ(r.eulerCharacteristic, 4);
  // The same inner sphere facing outward is inverted relative to the material.
  r = Analyze(Union(MakeIcosphere(2, 1.0), MakeIcosphere(2, 0.5)));
  EXPECT_EQ(r.invertedTrianglesVersusOutward, 320);
}

TEST(TriangleMeshQualityCalculator, InvertedTrianglesAgainstAReferenceMesh)
{
  const IndexedTriangleMesh reference = MakeGrid(4);
  IndexedTriangleMesh       moved = reference;
  moved.points[6] = MakeVec3(2.6, 2.4, 0.0); // vertex (1,1) pushed across its neighbours
  const auto r = Analyze(moved, &reference);
  EXPECT_GT(r.invertedTrianglesVersusReference, 0);
  const auto clean = Analyze(reference, &reference);
  EXPECT_EQ(clean.invertedTrianglesVersusReference, 0);
  // A reference with different connectivity is refused.
  const IndexedTriangleMesh other = MakeGrid(3);
  EXPECT_THROW(Analyze(moved, &other), itk::ExceptionObject);
}

TEST(TriangleMeshQualityCalculator, DegenerateTrianglesAreCounted)
{
  IndexedTriangleMesh sphere = MakeIcosphere(2);
  const auto          t = sphere.triangles[5];
  sphere.points[t[0]] = sphere.points[t[1]]; // collapse an edge geometrically
  const auto r = Analyze(sphere);
  EXPECT_EQ(r.degenerateTriangles, 2);
  EXPECT_FALSE(r.IsValidClosedSurface());
}

TEST(TriangleMeshQualityCalculator, SelfIntersectionsAreFound)
{
  // Two overlapping spheres as one mesh.
  const auto r = Analyze(Union(MakeIcosphere(2, 1.0), MakeIcosphere(2, 1.0, MakeVec3(1.0, 0.2, 0.1))));
  EXPECT_GT(r.selfIntersectingPairs, 10);
  EXPECT_FALSE(r.IsValidClosedSurface());
  // A vertex pushed through the opposite side of a sphere.
  IndexedTriangleMesh dent = MakeIcosphere(2, 1.0);
  dent.points[0] = -dent.points[0] * 1.5;
  const auto d = Analyze(dent);
  EXPECT_GT(d.selfIntersectingPairs, 0);
  // Two disjoint spheres do not intersect.
  const auto apart = Analyze(Union(MakeIcosphere(2, 1.0), MakeIcosphere(2, 1.0, MakeVec3(2.5, 0, 0))));
  EXPECT_EQ(apart.selfIntersectingPairs, 0);
}

TEST(TriangleMeshQualityCalculator, QuadsAreMeasuredAfterSplittingAndOtherPolygonsRefused)
{
  using CellType = MeshType::CellType;
  auto mesh = MeshType::New();
  // Unit cube with 6 outward quads.
  const double corners[8][3] = { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 },
                                 { 0, 0, 1 }, { 1, 0, 1 }, { 1, 1, 1 }, { 0, 1, 1 } };
  for (unsigned int i = 0; i < 8; ++i)
  {
    MeshType::PointType p;
    p[0] = corners[i][0];
    p[1] = corners[i][1];
    p[2] = corners[i][2];
    mesh->SetPoint(i, p);
  }
  const unsigned int faces[6][4] = { { 0, 3, 2, 1 }, { 4, 5, 6, 7 }, { 0, 1, 5, 4 },
                                     { 2, 3, 7, 6 }, { 1, 2, 6, 5 }, { 0, 4, 7, 3 } };
  for (unsigned int f = 0; f < 6; ++f)
  {
    CellType::CellAutoPointer cell;
    cell.TakeOwnership(new itk::QuadrilateralCell<CellType>);
    for (unsigned int k = 0; k < 4; ++k)
    {
      cell->SetPointId(k, faces[f][k]);
    }
    mesh->SetCell(f, cell);
  }
  auto calculator = itk::TriangleMeshQualityCalculator<MeshType>::New();
  calculator->SetMesh(mesh);
  calculator->Compute();
  const auto & r = calculator->GetReport();
  EXPECT_EQ(r.numberOfSplitQuads, 6u);
  EXPECT_EQ(r.numberOfTriangles, 12u);
  EXPECT_EQ(r.eulerCharacteristic, 2);
  EXPECT_NEAR(r.enclosedVolume, 1.0, 1e-12);
  EXPECT_TRUE(r.IsValidClosedSurface());

  CellType::CellAutoPointer pentagon;
  pentagon.TakeOwnership(new itk::PolygonCell<CellType>);
  for (unsigned int k = 0; k < 5; ++k)
  {
    pentagon->SetPointId(k, k);
  }
  mesh->SetCell(6, pentagon);
  calculator->SetMesh(mesh);
  try
  {
    calculator->Compute();
    FAIL() << "a pentagon must be refused";
  }
  catch (const itk::ExceptionObject & e)
  {
    EXPECT_NE(std::string(e.GetDescription()).find("5 points"), std::string::npos) << e.GetDescription();
  }
}

TEST(TriangleMeshQualityCalculator, MissingMeshAndMissingPointsThrow)
{
  auto calculator = itk::TriangleMeshQualityCalculator<MeshType>::New();
  EXPECT_THROW(calculator->Compute(), itk::ExceptionObject);
  IndexedTriangleMesh                 m = MakeTetrahedron();
  auto                                mesh = ToITKMesh<MeshType>(m);
  MeshType::CellType::CellAutoPointer cell;
  cell.TakeOwnership(new itk::TriangleCell<MeshType::CellType>);
  cell->SetPointId(0, 0);
  cell->SetPointId(1, 1);
  cell->SetPointId(2, 99);
  mesh->SetCell(4, cell);
  calculator->SetMesh(mesh);
  EXPECT_THROW(calculator->Compute(), itk::ExceptionObject);
}

TEST(TriangleMeshQualityCalculator, ReportsPrintAsTextAndJSON)
{
  auto       calculator = itk::TriangleMeshQualityCalculator<MeshType>::New();
  const auto mesh = ToITKMesh<MeshType>(MakeIcosphere(1));
  calculator->SetMesh(mesh);
  calculator->Compute();
  const auto &       r = calculator->GetReport();
  std::ostringstream text;
  r.Print(text, "sphere");
  EXPECT_NE(text.str().find("q_area"), std::string::npos);
  EXPECT_NE(text.str().find("valid closed surface: yes"), std::string::npos);
  std::ostringstream json;
  r.PrintJSON(json);
  EXPECT_EQ(json.str().front(), '{');
  EXPECT_EQ(json.str().back(), '}');
  EXPECT_NE(json.str().find("\"euler_characteristic\": 2"), std::string::npos);
  // Python reads the report through GetReportAsJSON(): the same object.
  EXPECT_EQ(calculator->GetReportAsJSON(), json.str());
  EXPECT_NE(json.str().find("\"triangles\": 80,"), std::string::npos);
  EXPECT_NE(json.str().find("\"valid_closed_surface\": true}"), std::string::npos);
  // Per-triangle values as plain arrays (for Python), in measure order.
  const auto & measures = calculator->GetTriangleMeasures();
  const auto   qArea = calculator->GetTriangleQAreas();
  const auto   qAngle = calculator->GetTriangleQAngles();
  const auto   qLength = calculator->GetTriangleQLengths();
  ASSERT_EQ(measures.size(), 80u);
  ASSERT_EQ(qArea.size(), 80u);
  ASSERT_EQ(qAngle.size(), 80u);
  ASSERT_EQ(qLength.size(), 80u);
  for (std::size_t f = 0; f < measures.size(); ++f)
  {
    EXPECT_EQ(qArea[f], measures[f].qArea);
    EXPECT_EQ(qAngle[f], measures[f].qAngle);
    EXPECT_EQ(qLength[f], measures[f].qLength);
  }
  EXPECT_NEAR(std::accumulate(qArea.begin(), qArea.end(), 0.0) / 80.0, calculator->GetMeanQArea(), 1e-12);
}

TEST(TriangleMeshQualityCalculator, JSONReportOfAMeshWithANaNPointStaysValidJSON)
{
  // A NaN point gives NaN measures; JSON has no NaN, so they are written as null.
  IndexedTriangleMesh m = MakeIcosphere(1);
  m.points[0][0] = std::numeric_limits<double>::quiet_NaN();
  auto       calculator = itk::TriangleMeshQualityCalculator<MeshType>::New();
  const auto mesh = ToITKMesh<MeshType>(m);
  calculator->SetMesh(mesh);
  calculator->Compute();
  const std::string json = calculator->GetReportAsJSON();
  EXPECT_EQ(json.find("nan"), std::string::npos) << json;
  EXPECT_EQ(json.find("inf"), std::string::npos) << json;
  EXPECT_NE(json.find("null"), std::string::npos) << json;
  EXPECT_NE(json.find("\"valid_closed_surface\": false}"), std::string::npos) << json;

  std::ostringstream text;
  text << itk::MeshExtraction::detail::JSONString{ std::string("a\"b\\c\n") } << ' '
       << itk::MeshExtraction::detail::JSONNumber{ -std::numeric_limits<double>::infinity() } << ' '
       << itk::MeshExtraction::detail::JSONNumber{ 0.25 };
  EXPECT_EQ(text.str(), "\"a\\\"b\\\\c\\u000a\" null 0.25");
}
