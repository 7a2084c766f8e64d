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
// The indexed swap engine of itkMeshExtractionClosedSurfaceEdgeSwap.h (internal):
// SurfaceNetTriangles' connectivity and SwapEdges.

#include "itkMeshExtractionClosedSurfaceEdgeSwap.h"
#include "itkMeshExtractionTestHelpers.h"

#include "gtest/gtest.h"

#include <random>

using namespace itk::MeshExtraction;
using namespace itk::MeshExtraction::detail;
using MeshExtractionTest::MakeIcosphere;

TEST(SurfaceNetTriangles, BuildConnectivityPairsEveryHalfEdgeWithItsReverse)
{
  const IndexedTriangleMesh sphere = MakeIcosphere(2, 1.0);
  SurfaceNetTriangles       mesh;
  mesh.triangles = sphere.triangles;
  mesh.BuildConnectivity(sphere.points.size());
  ASSERT_EQ(mesh.twin.size(), 3 * mesh.triangles.size());
  std::vector<std::uint32_t> facesAt(sphere.points.size(), 0);
  for (std::uint32_t h = 0; h < mesh.twin.size(); ++h)
  {
    const std::uint32_t t = mesh.twin[h];
    ASSERT_LT(t, mesh.twin.size());
    EXPECT_NE(t / 3, h / 3);
    EXPECT_EQ(mesh.twin[t], h);
    // h runs u -> v, its twin v -> u.
    EXPECT_EQ(mesh.triangles[h / 3][h % 3], mesh.triangles[t / 3][(t % 3 + 1) % 3]);
    EXPECT_EQ(mesh.triangles[h / 3][(h % 3 + 1) % 3], mesh.triangles[t / 3][t % 3]);
    ++facesAt[mesh.triangles[h / 3][h % 3]];
  }
  EXPECT_EQ(mesh.valence, facesAt);

  SurfaceNetTriangles open = mesh; // a hole: edges with one half-edge
  open.triangles.pop_back();
  EXPECT_THROW(open.BuildConnectivity(sphere.points.size()), itk::ExceptionObject);
  SurfaceNetTriangles fin = mesh; // a third face on an edge
  fin.triangles.push_back(
    { mesh.triangles[0][0], mesh.triangles[0][1], static_cast<std::uint32_t>(sphere.points.size()) });
  EXPECT_THROW(fin.BuildConnectivity(sphere.points.size() + 1), itk::ExceptionObject);
  EXPECT_THROW(mesh.BuildConnectivity(sphere.points.size() - 1), itk::ExceptionObject); // a node out of range
}

TEST(SurfaceNetTriangles, ReplaceTrianglesGivesTheConnectivityOfABuildFromScratch)
{
  // Swap edges of a perturbed sphere (to the shorter diagonal), then undo every other
  // swap, and then all of them, locally: twins and valences must be those that
  // BuildConnectivity gives the same triangles.
  IndexedTriangleMesh              sphere = MakeIcosphere(3, 1.0);
  std::mt19937                     rng(5);
  std::normal_distribution<double> jitter(0.0, 0.04);
  for (auto & p : sphere.points)
  {
    p += MakeVec3(jitter(rng), jitter(rng), jitter(rng));
  }
  SurfaceNetTriangles mesh;
  mesh.triangles = sphere.triangles;
  mesh.BuildConnectivity(sphere.points.size());
  EdgeSwapParameters shortest;
  shortest.criterion = itk::MeshExtractionEnums::EdgeSwapCriterion::ShortestEdge;
  const auto swaps = SwapEdges(sphere.points, mesh, shortest);
  ASSERT_GT(swaps.size(), 20u);
  std::vector<std::pair<std::uint32_t, itk::MeshExtraction::TriangleIndices>> undo;
  for (std::size_t i = 0; i < swaps.size(); i += 2)
  {
    undo.emplace_back(swaps[i].first, swaps[i].oldFirst);
    undo.emplace_back(swaps[i].second, swaps[i].oldSecond);
  }
  SurfaceNetTriangles local = mesh;
  local.ReplaceTriangles(undo);
  SurfaceNetTriangles scratch = local;
  scratch.BuildConnectivity(sphere.points.size());
  EXPECT_EQ(local.triangles, scratch.triangles);
  EXPECT_EQ(local.twin, scratch.twin);
  EXPECT_EQ(local.valence, scratch.valence);
  EXPECT_NE(local.triangles, mesh.triangles);
  // Undoing every swap (neighbouring quads among them) gives back the sphere's own.
  SurfaceNetTriangles                                                         back = mesh;
  std::vector<std::pair<std::uint32_t, itk::MeshExtraction::TriangleIndices>> all;
  for (const auto & s : swaps)
  {
    all.emplace_back(s.first, s.oldFirst);
    all.emplace_back(s.second, s.oldSecond);
  }
  back.ReplaceTriangles(all);
  SurfaceNetTriangles original;
  original.triangles = sphere.triangles;
  original.BuildConnectivity(sphere.points.size());
  EXPECT_EQ(back.triangles, original.triangles);
  EXPECT_EQ(back.twin, original.twin);
  EXPECT_EQ(back.valence, original.valence);

  // Corners that do not cover the same part (those of a face elsewhere): the rest no
  // longer closes up.
  const std::uint32_t                                                               face = undo[0].first;
  const std::vector<std::pair<std::uint32_t, itk::MeshExtraction::TriangleIndices>> wrong{
    { face, local.triangles[(face + local.triangles.size() / 2) % local.triangles.size()] }
  };
  EXPECT_THROW(local.ReplaceTriangles(wrong), itk::ExceptionObject);
}
