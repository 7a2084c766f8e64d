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
// The validity guard of itkMeshExtractionValidityGuard.h (internal): the component
// volumes, the undoing of folding moves, and the self-intersection search and removal
// of the SurfaceNets relaxation.

#include "itkMeshExtractionValidityGuard.h"
#include "itkMeshExtractionGeodesicSphere.h"
#include "itkMeshExtractionRayParity.h"
#include "itkMeshExtractionSelfIntersections.h"
#include "itkMeshExtractionSurfaceNets.h"
#include "itkMeshExtractionSurfaceNetsClassification.h"
#include "itkMeshExtractionTestHelpers.h"

#include "gtest/gtest.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <utility>
#include <vector>

using namespace MeshExtractionTest;
namespace ME = itk::MeshExtraction;
using itk::MeshExtraction::TriangleIndices;
using itk::MeshExtraction::detail::ComponentVolumes;

namespace
{
using FloatImage = itk::Image<float, 3>;
} // namespace

TEST(ComponentVolumes, FlagAComponentThatTurnsInsideOutOrFlattensAndNoOther)
{
  // Three components: a sphere, a small sphere inside it turned inward (a cavity:
  // negative volume), and a small sphere elsewhere.
  const IndexedTriangleMesh    outer = MakeIcosphere(2, 10.0);
  const IndexedTriangleMesh    inner = MakeIcosphere(1, 2.0, MakeVec3(1.0, 0.0, 0.0));
  const IndexedTriangleMesh    apart = MakeIcosphere(1, 1.0, MakeVec3(20.0, 0.0, 0.0));
  std::vector<Vec3>            points;
  std::vector<TriangleIndices> triangles;
  auto                         add = [&](const IndexedTriangleMesh & m, bool inward) {
    const auto first = static_cast<std::uint32_t>(points.size());
    points.insert(points.end(), m.points.begin(), m.points.end());
    for (auto t : m.triangles)
    {
      if (inward)
      {
        std::swap(t[1], t[2]);
      }
      triangles.push_back({ t[0] + first, t[1] + first, t[2] + first });
    }
  };
  add(outer, false);
  add(inner, true);
  add(apart, false);
  ComponentVolumes volumes;
  EXPECT_EQ(volumes.Collapsed(triangles, points), std::vector<bool>{}); // not initialised
  volumes.Initialize(triangles, points);
  ASSERT_EQ(volumes.reference.size(), 3u);
  EXPECT_GT(volumes.reference[0], 0.0);
  EXPECT_LT(volumes.reference[1], 0.0);
  EXPECT_GT(volumes.reference[2], 0.0);
  EXPECT_EQ(volumes.vertexComponent[outer.points.size()], 1u);
  EXPECT_EQ(volumes.Collapsed(triangles, points), std::vector<bool>(3, false));

  const std::size_t apartFirst = outer.points.size() + inner.points.size();
  auto              moved = [&](double scaleZ, double mirrorX) {
    std::vector<Vec3> p = points;
    for (std::size_t v = apartFirst; v < p.size(); ++v)
    {
      const Vec3 c = MakeVec3(20.0, 0.0, 0.0);
      Vec3       d = p[v] - c;
      d[0] *= mirrorX;
      d[2] *= scaleZ;
      p[v] = c + d;
    }
    return volumes.Collapsed(triangles, p);
  };
  const std::vector<bool> onlyApart{ false, false, true };
  EXPECT_EQ(moved(0.5, 1.0), std::vector<bool>(3, false)); // half its volume: kept
  EXPECT_EQ(moved(0.2, 1.0), onlyApart);                   // a fifth: flattened
  EXPECT_EQ(moved(0.0, 1.0), onlyApart);                   // no volume
  EXPECT_EQ(moved(1.0, -1.0), onlyApart);                  // mirrored: inside out
  // The cavity turned outward, and a NaN point.
  std::vector<Vec3> p = points;
  for (std::size_t v = outer.points.size(); v < apartFirst; ++v)
  {
    p[v] = MakeVec3(1.0, 0.0, 0.0) + (MakeVec3(1.0, 0.0, 0.0) - p[v]);
  }
  EXPECT_EQ(volumes.Collapsed(triangles, p), (std::vector<bool>{ false, true, false }));
  p = points;
  p[0][0] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(volumes.Collapsed(triangles, p), (std::vector<bool>{ true, false, false }));
}

// A small closed component can turn inside out as a whole although every triangle
// keeps its normal and none crosses another: here an icosahedron mirrored through its
// centre (the same surface, each triangle now facing inward). Found on the head CT,
// where one-voxel components collapsed through their centre during edge detection.
TEST(ScaleSpaceEdgeDetection, UndoFoldingMovesRestoresAComponentTurnedInsideOut)
{
  const Vec3              center = ME::MakeVec3(10.0, 10.0, 10.0);
  ME::IndexedTriangleMesh mesh = ME::MakeGeodesicSphere(0, center, 2.0);
  const std::size_t       n = mesh.points.size();
  // A second, untouched component, and a third that only moves outward.
  for (const double x : { 30.0, 50.0 })
  {
    Append(mesh, ME::MakeGeodesicSphere(1, ME::MakeVec3(x, 10.0, 10.0), 3.0));
  }
  const ME::MeshTopology  topology = ME::BuildMeshTopology(mesh);
  const std::vector<Vec3> start = mesh.points;
  ASSERT_EQ(topology.numberOfComponents, 3u);
  for (std::size_t i = 0; i < n; ++i)
  {
    mesh.points[i] = center * 2.0 - start[i]; // point reflection: orientation reversed
  }
  const Vec3 third = ME::MakeVec3(50.0, 10.0, 10.0);
  for (std::size_t i = mesh.points.size() - (mesh.points.size() - n) / 2; i < mesh.points.size(); ++i)
  {
    mesh.points[i] = third + (start[i] - third) * 1.1;
  }
  const std::vector<Vec3> moved = mesh.points;
  for (std::uint32_t f = 0; f < mesh.triangles.size(); ++f)
  {
    ASSERT_TRUE(ME::detail::IsValidTriangleAgainstStart(mesh, start, f, 1e-6)) << f; // no triangle flips
  }

  EXPECT_EQ(ME::detail::UndoFoldingMoves(mesh, topology, start, 1e-6), n);
  for (std::size_t i = 0; i < mesh.points.size(); ++i)
  {
    EXPECT_EQ(mesh.points[i], i < n ? start[i] : moved[i]) << i;
  }
}

// Found by the stress runs (seeds 155, 206 and 298 of StressRuns.DISABLED_RandomSmoothVolumes):
// a Laplacian step moved a surface past a one-voxel cavity in one step. No triangle
// crossed another at the end and none turned over, but the cavity was now outside the
// object, facing the wrong way. Here a sphere shrinks past a small sphere inside it.
TEST(ScaleSpaceEdgeDetection, UndoFoldingMovesRestoresASurfaceThatMovedPastASmallComponent)
{
  const Vec3              center = ME::MakeVec3(10.0, 10.0, 10.0);
  ME::IndexedTriangleMesh mesh = ME::MakeGeodesicSphere(3, center, 5.0);
  const std::size_t       n = mesh.points.size();
  Append(mesh, ME::MakeGeodesicSphere(1, center + ME::MakeVec3(4.5, 0.05, -0.03), 0.1));
  const ME::MeshTopology               topology = ME::BuildMeshTopology(mesh);
  const std::vector<Vec3>              start = mesh.points;
  const ME::detail::ComponentReference reference = ME::detail::MakeComponentReference(mesh, topology);
  const std::vector<std::int8_t>       expected{ 0, 1 };
  ASSERT_EQ(reference.nesting, expected);
  for (std::size_t i = 0; i < n; ++i)
  {
    mesh.points[i] = center + (start[i] - center) * 0.8; // radius 4: the small sphere is outside now
  }
  const std::vector<Vec3> moved = mesh.points;
  ASSERT_TRUE(ME::detail::FindSelfIntersections(mesh).empty());
  // The cheap filter that lets most steps skip the parity test names the small sphere.
  const std::vector<std::uint32_t> mayHavePassed = ME::detail::ComponentsAMoveMayHavePassed(mesh, topology, start);
  EXPECT_NE(std::find(mayHavePassed.begin(), mayHavePassed.end(), 1u), mayHavePassed.end());
  {
    // Only the far side moving: nothing can have passed the small sphere.
    ME::IndexedTriangleMesh farSide = mesh;
    for (std::size_t i = 0; i < farSide.points.size(); ++i)
    {
      farSide.points[i] = i < n && start[i][0] < center[0] ? moved[i] : start[i];
    }
    EXPECT_TRUE(ME::detail::ComponentsAMoveMayHavePassed(farSide, topology, start).empty());
  }

  // Without the reference, nothing seems wrong.
  EXPECT_EQ(ME::detail::UndoFoldingMoves(mesh, topology, start, 1e-6), 0u);
  EXPECT_NE(ME::detail::ComponentNestingParity(mesh, topology), expected);

  const std::size_t undone = ME::detail::UndoFoldingMoves(mesh, topology, start, 1e-6, &reference);
  EXPECT_GT(undone, 0u);
  EXPECT_EQ(ME::detail::ComponentNestingParity(mesh, topology), expected);
  EXPECT_TRUE(ME::detail::FindSelfIntersections(mesh).empty());
  // Only the part of the sphere near the small one went back.
  std::size_t stillMoved = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    stillMoved += mesh.points[i] == moved[i] ? 1 : 0;
  }
  EXPECT_GT(stillMoved, n * 9 / 10);
  EXPECT_LT(stillMoved, n);
}

// A component that steps within the per-step rules shrink to a speck goes back once it
// falls below CollapsedComponentVolumeFraction of its volume before the first step.
TEST(ScaleSpaceEdgeDetection, UndoFoldingMovesKeepsAComponentFromShrinkingToASpeck)
{
  const Vec3                           center = ME::MakeVec3(10.0, 10.0, 10.0);
  ME::IndexedTriangleMesh              mesh = ME::MakeGeodesicSphere(1, center, 1.0);
  const ME::MeshTopology               topology = ME::BuildMeshTopology(mesh);
  const ME::detail::ComponentReference reference = ME::detail::MakeComponentReference(mesh, topology);
  unsigned int                         steps = 0;
  for (; steps < 20; ++steps)
  {
    const std::vector<Vec3> start = mesh.points;
    for (auto & p : mesh.points)
    {
      p = center + (p - center) * 0.5; // each step keeps 1/8 of the volume
    }
    if (ME::detail::UndoFoldingMoves(mesh, topology, start, 1e-6, &reference) > 0)
    {
      EXPECT_EQ(mesh.points, start);
      break;
    }
  }
  EXPECT_EQ(steps, 3u); // 1/8, 1/64, 1/512 pass; 1/4096 < 1/1000 does not
}

TEST(SurfaceNetsImageToMeshFilter, StructuredSelfIntersectionSearchFindsExactlyWhatTheTreeFinds)
{
  // Nets of random volumes with every node thrown anywhere in its constraint box (far
  // more crossings than a relaxation makes), on axis-aligned and on rotated,
  // anisotropic grids: the search over the quads of each cell finds exactly the pairs
  // the tree over all faces finds, for all faces and for a changed subset.
  std::mt19937                           rng(5);
  std::uniform_real_distribution<float>  value(0.0f, 1.0f);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  itk::Matrix<double, 3, 3>              rotated;
  {
    const double a = 0.4;
    const double b = 0.3;
    const double R[3][3] = { { std::cos(a), -std::sin(a) * std::cos(b), std::sin(a) * std::sin(b) },
                             { std::sin(a), std::cos(a) * std::cos(b), -std::cos(a) * std::sin(b) },
                             { 0.0, std::sin(b), std::cos(b) } };
    const double spacing[3] = { 0.7, 1.1, 2.5 };
    for (unsigned int r = 0; r < 3; ++r)
    {
      for (unsigned int c = 0; c < 3; ++c)
      {
        rotated[r][c] = R[r][c] * spacing[c];
      }
    }
  }
  itk::Matrix<double, 3, 3> identity;
  identity.SetIdentity();
  std::size_t intersecting = 0;
  for (int trial = 0; trial < 40; ++trial)
  {
    SCOPED_TRACE(trial);
    const unsigned int n = 6 + trial % 4;
    auto               image = MakeImage<FloatImage>(n, n, n);
    const double       density = 0.3 + 0.4 * value(rng);
    for (std::size_t i = 0; i < image->GetBufferedRegion().GetNumberOfPixels(); ++i)
    {
      image->GetBufferPointer()[i] = value(rng);
    }
    ME::SurfaceNet net;
    ME::detail::ClassifySurfaceCells(
      image.GetPointer(), ME::detail::SurfaceNetsVoxelRange<float>::FromIsoValue(density, false), net, 1);
    if (net.cells.empty())
    {
      continue;
    }
    ME::detail::BuildSurfaceNet(net, 0.01, 1);
    for (std::size_t i = 0; i < net.positions.size(); ++i)
    {
      for (unsigned int k = 0; k < 3; ++k)
      {
        net.positions[i][k] = net.boxLower[i][k] + unit(rng) * (net.boxUpper[i][k] - net.boxLower[i][k]);
      }
    }
    const bool                        rotate = trial % 2 == 1;
    const itk::Matrix<double, 3, 3> & M = rotate ? rotated : identity;
    const ME::Vec3                    origin = rotate ? ME::MakeVec3(-12.5, 30.0, 7.25) : ME::MakeVec3(0, 0, 0);
    std::vector<ME::Vec3>             points;
    ME::LargeBlockVector<std::array<std::uint32_t, 4>> polygons;
    unsigned int                                       polygonSize = 3;
    ME::detail::MakeSurfaceNetFaces(
      net, origin, M, ME::detail::QuadSplit::ShortestDiagonal, points, polygons, polygonSize);
    ME::IndexedTriangleMesh mesh;
    mesh.points = ME::detail::ToPhysical(net.positions, origin, M, rotate);
    for (const auto & p : polygons)
    {
      mesh.triangles.push_back({ p[0], p[1], p[2] });
    }
    const auto                                           expected = ME::detail::FindSelfIntersections(mesh);
    std::vector<std::pair<std::uint32_t, std::uint32_t>> found;
    ASSERT_TRUE(ME::detail::FindSurfaceNetSelfIntersections(net, mesh, origin, M, rotate, nullptr, found));
    ASSERT_EQ(found, expected);
    intersecting += expected.size();
    std::vector<std::uint32_t> changed;
    for (std::uint32_t f = 0; f < mesh.triangles.size(); ++f)
    {
      if (unit(rng) < 0.2)
      {
        changed.push_back(f);
      }
    }
    ASSERT_TRUE(ME::detail::FindSurfaceNetSelfIntersections(net, mesh, origin, M, rotate, &changed, found));
    ASSERT_EQ(found, ME::detail::FindSelfIntersections(mesh, &changed));
    // A node on a face of its cell: the argument fails, and the search says so.
    net.positions[0][0] = std::floor(net.positions[0][0]);
    ASSERT_FALSE(ME::detail::FindSurfaceNetSelfIntersections(net, mesh, origin, M, rotate, nullptr, found));
    EXPECT_TRUE(found.empty());
  }
  EXPECT_GT(intersecting, 100u) << "the random nets should cross themselves often";
}

TEST(SurfaceNetsImageToMeshFilter, SelfIntersectionRemovalHandsOutTheFacesOfTheFinalNet)
{
  // Nets with nodes thrown anywhere in their boxes cross themselves; after the removal
  // the faces it hands out (which the filter writes instead of making them again) are
  // exactly the faces of the final net, and they do not intersect.
  std::mt19937                           rng(9);
  std::uniform_real_distribution<float>  value(0.0f, 1.0f);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  itk::Matrix<double, 3, 3>              M;
  M.SetIdentity();
  M[0][0] = 0.8;
  M[2][2] = 1.7;
  const ME::Vec3 origin = ME::MakeVec3(3.0, -2.0, 0.5);
  std::size_t    movedBack = 0;
  for (int trial = 0; trial < 24; ++trial)
  {
    SCOPED_TRACE(trial);
    const unsigned int n = 6 + trial % 3;
    auto               image = MakeImage<FloatImage>(n, n, n);
    for (std::size_t i = 0; i < image->GetBufferedRegion().GetNumberOfPixels(); ++i)
    {
      image->GetBufferPointer()[i] = value(rng);
    }
    ME::SurfaceNet net;
    ME::detail::ClassifySurfaceCells(
      image.GetPointer(), ME::detail::SurfaceNetsVoxelRange<float>::FromIsoValue(0.5, false), net, 1);
    if (net.cells.empty())
    {
      continue;
    }
    ME::detail::BuildSurfaceNet(net, 0.01, 1);
    const ME::LargeBlockVector<ME::Vec3> initial = net.positions;
    for (std::size_t i = 0; i < net.positions.size(); ++i)
    {
      for (unsigned int k = 0; k < 3; ++k)
      {
        net.positions[i][k] = net.boxLower[i][k] + unit(rng) * (net.boxUpper[i][k] - net.boxLower[i][k]);
      }
    }
    const bool                  roundToFloat = trial % 2 == 1;
    const ME::detail::QuadSplit split =
      trial % 4 < 2 ? ME::detail::QuadSplit::ShortestDiagonal : ME::detail::QuadSplit::Delaunay;
    ME::LargeBlockVector<std::array<std::uint32_t, 4>> faces;
    movedBack += ME::detail::RemoveSurfaceNetSelfIntersections(net, initial, origin, M, split, roundToFloat, &faces);
    std::vector<ME::Vec3>                              points;
    ME::LargeBlockVector<std::array<std::uint32_t, 4>> expected;
    unsigned int                                       polygonSize = 0;
    ME::detail::MakeSurfaceNetFaces(net, origin, M, split, points, expected, polygonSize);
    ASSERT_EQ(polygonSize, 3u);
    ASSERT_EQ(faces, expected);
    ME::IndexedTriangleMesh mesh;
    mesh.points = ME::detail::ToPhysical(net.positions, origin, M, roundToFloat);
    for (const auto & f : faces)
    {
      mesh.triangles.push_back({ f[0], f[1], f[2] });
    }
    EXPECT_TRUE(ME::detail::FindSelfIntersections(mesh).empty());
    // Quads are not what the check tests: nothing is handed out.
    ME::detail::RemoveSurfaceNetSelfIntersections(
      net, initial, origin, M, ME::detail::QuadSplit::KeepQuads, roundToFloat, &faces);
    EXPECT_TRUE(faces.empty());
  }
  EXPECT_GT(movedBack, 20u) << "the random nets should need nodes moved back";
}
