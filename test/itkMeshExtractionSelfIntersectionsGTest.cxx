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
// The self-intersection search of itkMeshExtractionSelfIntersections.h (internal) and its
// cache.

#include "itkMeshExtractionSelfIntersections.h"
#include "itkMeshExtractionTriangleAABBTree.h"
#include "itkMeshExtractionTestHelpers.h"

#include "gtest/gtest.h"

#include <numeric>
#include <random>

using namespace itk::MeshExtraction;
using namespace itk::MeshExtraction::detail;
using MeshExtractionTest::MakeIcosphere;

TEST(SelfIntersectionCache, FindsThePairsOfTheFullSearchAfterSmallAndLargeMoves)
{
  // Two spheres with a gap of a tenth of an edge between them, moved in small steps
  // (no face "moves" for the cache: the near pairs across the gap must catch the
  // spheres meeting), with single vertices thrown far (queries of moved faces) and
  // faces exchanging vertices (as swaps do). Every search must equal the full one.
  IndexedTriangleMesh       mesh = MakeIcosphere(3, 5.0);
  const IndexedTriangleMesh second = MakeIcosphere(3, 5.0);
  const double edge = std::sqrt(SquaredNorm(mesh.points[mesh.triangles[0][0]] - mesh.points[mesh.triangles[0][1]]));
  const auto   offset = static_cast<std::uint32_t>(mesh.points.size());
  for (const auto & p : second.points)
  {
    mesh.points.push_back(p + MakeVec3(10.0 + 0.1 * edge, 0.0, 0.0));
  }
  for (const auto & t : second.triangles)
  {
    mesh.triangles.push_back({ t[0] + offset, t[1] + offset, t[2] + offset });
  }
  SelfIntersectionCache cache;
  cache.margin = 0.5 * edge;
  TriangleAABBTree           tree;
  std::vector<std::uint32_t> all(mesh.triangles.size());
  std::iota(all.begin(), all.end(), 0u);
  std::mt19937                           rng(3);
  std::uniform_real_distribution<double> jitter(-0.05 * edge, 0.05 * edge);
  std::size_t                            incrementalWithPairs = 0;
  for (int round = 0; round < 12; ++round)
  {
    SCOPED_TRACE(round);
    if (round > 0)
    {
      for (auto & p : mesh.points)
      {
        p += MakeVec3(jitter(rng), jitter(rng), jitter(rng));
      }
    }
    if (round >= 3 && round <= 6)
    {
      // The second sphere closes the gap and goes 0.1 edge into the first per round
      // (0.1 edge since the last rebuild at most: no face moved for the cache).
      for (std::size_t v = offset; v < mesh.points.size(); ++v)
      {
        mesh.points[v][0] -= 0.1 * edge;
      }
    }
    if (round == 8)
    {
      mesh.points[7] = -mesh.points[7]; // through the sphere: its faces moved
    }
    if (round == 10)
    {
      std::swap(mesh.triangles[5][0], mesh.triangles[40][1]);
    }
    AxisAlignedBoxArray boxes(mesh.triangles.size());
    for (std::uint32_t f = 0; f < mesh.triangles.size(); ++f)
    {
      boxes[f] = TriangleBox(mesh, f);
      for (unsigned int d = 0; d < 3; ++d)
      {
        boxes[f].lower[d] -= 0.5 * cache.margin;
        boxes[f].upper[d] += 0.5 * cache.margin;
      }
    }
    tree.Build(mesh, nullptr, &boxes);
    const std::size_t incremental = cache.numberOfIncrementalSearches;
    const auto        pairs = FindSelfIntersections(mesh, all, tree, &cache);
    ASSERT_EQ(pairs, FindSelfIntersections(mesh));
    if (cache.numberOfIncrementalSearches > incremental && !pairs.empty())
    {
      ++incrementalWithPairs;
    }
  }
  EXPECT_GE(cache.numberOfRebuilds, 1u);
  EXPECT_GE(cache.numberOfIncrementalSearches, 6u);
  EXPECT_GE(incrementalWithPairs, 3u); // the spheres meeting, the thrown vertex, the swap
}
