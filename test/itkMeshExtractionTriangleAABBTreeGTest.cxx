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
// The bounding-volume hierarchy of itkMeshExtractionTriangleAABBTree.h (internal): nearest
// triangle, refit, overlapping pairs.

#include "itkMeshExtractionSelfIntersections.h"
#include "itkMeshExtractionTriangleAABBTree.h"
#include "itkMeshExtractionTestHelpers.h"

#include "gtest/gtest.h"

#include <algorithm>
#include <limits>
#include <numeric>
#include <random>

using namespace itk::MeshExtraction;
using namespace itk::MeshExtraction::detail;
using MeshExtractionTest::MakeIcosphere;

TEST(TriangleAABBTree, NearestTriangleMatchesBruteForce)
{
  const IndexedTriangleMesh mesh = MakeIcosphere(3, 5.0);
  TriangleAABBTree          tree;
  tree.Build(mesh);
  std::mt19937                           rng(3);
  std::uniform_real_distribution<double> u(-8.0, 8.0);
  for (int trial = 0; trial < 500; ++trial)
  {
    const Vec3 p = MakeVec3(u(rng), u(rng), u(rng));
    double     best = std::numeric_limits<double>::max();
    for (const auto & t : mesh.triangles)
    {
      best = std::min(best, SquaredDistancePointTriangle(p, mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]]));
    }
    EXPECT_DOUBLE_EQ(tree.FindNearest(p).squaredDistance, best);
  }
}

TEST(TriangleAABBTree, RefitAfterMovesAndSwapsAnswersLikeAFreshBuild)
{
  // A tree built once, then refitted after the vertices moved and triangles changed
  // vertices (as edge swaps do): overlapping-box pairs and nearest points are those of
  // a tree built from scratch, and the self-intersections those of the full search.
  IndexedTriangleMesh mesh = MakeIcosphere(3, 5.0);
  TriangleAABBTree    refitted;
  auto                boxesOf = [](const IndexedTriangleMesh & m) {
    AxisAlignedBoxArray boxes(m.triangles.size());
    for (std::uint32_t f = 0; f < m.triangles.size(); ++f)
    {
      boxes[f] = TriangleBox(m, f);
    }
    return boxes;
  };
  refitted.Build(mesh, nullptr, nullptr);
  std::mt19937                           rng(9);
  std::uniform_real_distribution<double> jitter(-0.4, 0.4);
  for (int round = 0; round < 4; ++round)
  {
    SCOPED_TRACE(round);
    for (auto & p : mesh.points)
    {
      p += MakeVec3(jitter(rng), jitter(rng), jitter(rng));
    }
    // Exchange vertices between some triangles (the sets need not stay a mesh here).
    for (std::size_t f = 0; f + 7 < mesh.triangles.size(); f += 37)
    {
      std::swap(mesh.triangles[f][0], mesh.triangles[f + 7][1]);
    }
    const auto boxes = boxesOf(mesh);
    refitted.Refit(mesh, boxes);
    TriangleAABBTree fresh;
    fresh.Build(mesh, nullptr, &boxes);
    auto pairsOf = [](const TriangleAABBTree & tree) {
      std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
      for (const auto & start : tree.SplitOverlappingPairs(64))
      {
        tree.VisitOverlappingPairs(
          start, [&](std::uint32_t a, std::uint32_t b) { pairs.emplace_back(std::min(a, b), std::max(a, b)); });
      }
      std::sort(pairs.begin(), pairs.end());
      return pairs;
    };
    const auto pairs = pairsOf(refitted);
    ASSERT_EQ(pairs, pairsOf(fresh));
    ASSERT_FALSE(pairs.empty());
    std::vector<std::uint32_t> all(mesh.triangles.size());
    std::iota(all.begin(), all.end(), 0u);
    EXPECT_EQ(FindSelfIntersections(mesh, all, refitted), FindSelfIntersections(mesh));
    std::uniform_real_distribution<double> u(-8.0, 8.0);
    for (int trial = 0; trial < 100; ++trial)
    {
      const Vec3 p = MakeVec3(u(rng), u(rng), u(rng));
      EXPECT_DOUBLE_EQ(refitted.FindNearest(p).squaredDistance, fresh.FindNearest(p).squaredDistance);
    }
  }
  // A tree over part of the triangles cannot be refitted to all of them.
  TriangleAABBTree           part;
  std::vector<std::uint32_t> half(mesh.triangles.size() / 2);
  std::iota(half.begin(), half.end(), 0u);
  part.Build(mesh, &half);
  EXPECT_THROW(part.Refit(mesh, boxesOf(mesh)), itk::ExceptionObject);
}
