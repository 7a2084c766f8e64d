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
// The edge-swap criteria of itkMeshExtractionEdgeSwapCriteria.h (internal): the gains of
// the regularity, Delaunay and shortest-edge criteria and the checks that refuse a swap
// (thesis sections 2.2.6, 4.2.2 and 4.5.1).

#include "itkMeshExtractionEdgeSwapCriteria.h"
#include "itkMeshExtractionTestHelpers.h"

#include "gtest/gtest.h"

#include <cmath>

using namespace MeshExtractionTest;
using itk::MeshExtraction::detail::EdgeSwapDecision;
using itk::MeshExtraction::detail::EdgeSwapParameters;
using itk::MeshExtraction::detail::EdgeSwapQuad;
using itk::MeshExtraction::detail::EdgeSwapVerdict;

namespace
{
using Criterion = itk::MeshExtractionEnums::EdgeSwapCriterion;

/** A flat quad: the edge (a, b) = ((0,0), (1,0)) with c above and d below. */
EdgeSwapQuad
FlatQuad(const Vec3 & c, const Vec3 & d)
{
  EdgeSwapQuad q;
  q.a = MakeVec3(0, 0, 0);
  q.b = MakeVec3(1, 0, 0);
  q.c = c;
  q.d = d;
  return q;
}
} // namespace

// ------------------------------------------------------------------------------
// The decision (pure functions, shared with other mesh types).
// ------------------------------------------------------------------------------
TEST(EdgeSwapQuadEdgeMeshFilter, RegularityGainIsTheDropOfTheRelaxationIndexEb)
{
  EdgeSwapQuad q = FlatQuad(MakeVec3(0.5, 0.8, 0), MakeVec3(0.5, -0.8, 0));
  q.valenceA = 7;
  q.valenceB = 8;
  q.valenceC = 5;
  q.valenceD = 4;
  // E_b before: 1 + 4 + 1 + 4 = 10; after (6, 7, 6, 5): 0 + 1 + 0 + 1 = 2.
  EXPECT_DOUBLE_EQ(itk::MeshExtraction::detail::EdgeSwapGain(Criterion::Regularity, q), 8.0);
  EdgeSwapParameters p;
  EXPECT_EQ(itk::MeshExtraction::detail::EvaluateEdgeSwap(q, p).verdict, EdgeSwapVerdict::Swap);
  q.valenceA = q.valenceB = q.valenceC = q.valenceD = 6;
  EXPECT_DOUBLE_EQ(itk::MeshExtraction::detail::EdgeSwapGain(Criterion::Regularity, q), -4.0);
  EXPECT_EQ(itk::MeshExtraction::detail::EvaluateEdgeSwap(q, p).verdict, EdgeSwapVerdict::NoImprovement);
  // A boundary corner aims at valence 4.
  q.valenceC = 3;
  q.boundaryC = true;
  // Before (6, 6, 3, 6): 0 + 0 + 1 + 0; after (5, 5, 4, 7): 1 + 1 + 0 + 1.
  EXPECT_DOUBLE_EQ(itk::MeshExtraction::detail::EdgeSwapGain(Criterion::Regularity, q), -2.0);
}

TEST(EdgeSwapQuadEdgeMeshFilter, DelaunayGainAgreesWithTheCircumcircleTestOfFigure2_18)
{
  std::mt19937                           rng(4);
  std::uniform_real_distribution<double> x(-0.5, 1.5);
  std::uniform_real_distribution<double> y(0.05, 1.5);
  int                                    inside = 0;
  for (int k = 0; k < 2000; ++k)
  {
    const EdgeSwapQuad q = FlatQuad(MakeVec3(x(rng), y(rng), 0), MakeVec3(x(rng), -y(rng), 0));
    const double       gain = itk::MeshExtraction::detail::EdgeSwapGain(Criterion::Delaunay, q);
    if (std::abs(gain) < 1e-9)
    {
      continue;
    }
    const bool inCircle = itk::MeshExtraction::IsInsideCircumcircle(q.a, q.b, q.c, q.d);
    EXPECT_EQ(gain > 0.0, inCircle) << q.c << ' ' << q.d;
    inside += inCircle;
  }
  EXPECT_GT(inside, 100);
}

TEST(EdgeSwapQuadEdgeMeshFilter, DelaunayShortcutDecidesAsTheOppositeAngleSum)
{
  // EvaluateEdgeSwap (and EdgeSwapImproves) skips the arc tangents when neither opposite
  // angle is obtuse; the verdicts must be those of the exact gain, including right angles (a square, and
  // apexes on the circle over the edge) and folded quads.
  std::mt19937                           rng(11);
  std::uniform_real_distribution<double> x(-0.5, 1.5);
  std::uniform_real_distribution<double> y(0.05, 1.5);
  std::uniform_real_distribution<double> z(-1.0, 1.0);
  std::uniform_real_distribution<double> t(0.0, itk::Math::pi);
  EdgeSwapParameters                     p;
  p.criterion = Criterion::Delaunay;
  auto exactVerdict = [&p](const EdgeSwapQuad & q) {
    const double gain = itk::MeshExtraction::detail::EdgeSwapGain(Criterion::Delaunay, q);
    return itk::MeshExtraction::detail::IsEdgeSwapImprovement(Criterion::Delaunay, q, gain)
             ? itk::MeshExtraction::detail::CheckEdgeSwap(q, p)
             : EdgeSwapVerdict::NoImprovement;
  };
  int shortcuts = 0;
  int swaps = 0;
  for (int k = 0; k < 6000; ++k)
  {
    EdgeSwapQuad q;
    if (k % 3 == 0)
    {
      // Apexes on the circle with diameter (a, b): both opposite angles are right.
      const double s = t(rng);
      const double r = t(rng);
      q = FlatQuad(MakeVec3(0.5 + 0.5 * std::cos(s), 0.5 * std::sin(s), 0),
                   MakeVec3(0.5 + 0.5 * std::cos(r), -0.5 * std::sin(r), 0));
    }
    else
    {
      q = FlatQuad(MakeVec3(x(rng), y(rng), 0), MakeVec3(x(rng), -y(rng), 0));
      if (k % 3 == 2)
      {
        q.c[2] = z(rng);
        q.d[2] = z(rng);
      }
    }
    shortcuts += itk::MeshExtraction::detail::NeitherOppositeAngleIsObtuse(q) ? 1 : 0;
    const EdgeSwapDecision decision = itk::MeshExtraction::detail::EvaluateEdgeSwap(q, p);
    const EdgeSwapVerdict  verdict = decision.verdict;
    swaps += verdict == EdgeSwapVerdict::Swap ? 1 : 0;
    EXPECT_EQ(verdict, exactVerdict(q)) << q.c << ' ' << q.d;
    // The criterion's half alone (as SwapEdges asks it) agrees, gain included.
    double gain = -1.0;
    EXPECT_EQ(itk::MeshExtraction::detail::EdgeSwapImproves(q, p, gain), verdict != EdgeSwapVerdict::NoImprovement);
    EXPECT_EQ(gain, decision.gain);
  }
  EXPECT_GT(shortcuts, 1000);
  EXPECT_GT(swaps, 100);
  // A square with (a, b) as its diagonal: right angles, no gain, no swap either way.
  const EdgeSwapQuad square = FlatQuad(MakeVec3(0.5, 0.5, 0), MakeVec3(0.5, -0.5, 0));
  EXPECT_TRUE(itk::MeshExtraction::detail::NeitherOppositeAngleIsObtuse(square));
  EXPECT_EQ(itk::MeshExtraction::detail::EvaluateEdgeSwap(square, p).verdict, EdgeSwapVerdict::NoImprovement);
  EXPECT_EQ(exactVerdict(square), EdgeSwapVerdict::NoImprovement);
}

TEST(EdgeSwapQuadEdgeMeshFilter, ConcaveQuadIsNeverSwapped)
{
  // d sits so far to the right that the segment c-d passes outside the quad.
  EdgeSwapQuad q = FlatQuad(MakeVec3(0.5, 0.1, 0), MakeVec3(3.0, -0.1, 0));
  q.valenceA = q.valenceB = 8;
  q.valenceC = q.valenceD = 4;
  EdgeSwapParameters p;
  EXPECT_GT(itk::MeshExtraction::detail::EdgeSwapGain(Criterion::Regularity, q), 0.0);
  EXPECT_EQ(itk::MeshExtraction::detail::EvaluateEdgeSwap(q, p).verdict, EdgeSwapVerdict::NormalsDisagree);
  p.criterion = Criterion::ShortestEdge;
  EXPECT_EQ(itk::MeshExtraction::detail::EvaluateEdgeSwap(q, p).verdict, EdgeSwapVerdict::NoImprovement);
}

TEST(EdgeSwapQuadEdgeMeshFilter, SwapThatLeavesAVertexWithTwoEdgesIsRefused)
{
  // c-d (0.4) is shorter than a-b (1), but a has only three edges.
  EdgeSwapQuad q = FlatQuad(MakeVec3(0.5, 0.2, 0), MakeVec3(0.5, -0.2, 0));
  q.valenceA = 3;
  q.valenceB = 7;
  q.valenceC = q.valenceD = 4;
  EdgeSwapParameters p;
  p.criterion = Criterion::ShortestEdge;
  EXPECT_EQ(itk::MeshExtraction::detail::EvaluateEdgeSwap(q, p).verdict, EdgeSwapVerdict::ValenceTooLow);
  q.valenceA = 4;
  EXPECT_EQ(itk::MeshExtraction::detail::EvaluateEdgeSwap(q, p).verdict, EdgeSwapVerdict::Swap);
}

TEST(EdgeSwapQuadEdgeMeshFilter, ExistingOppositeEdgeIsNeverDuplicated)
{
  EdgeSwapQuad       q = FlatQuad(MakeVec3(0.5, 0.2, 0), MakeVec3(0.5, -0.2, 0));
  EdgeSwapParameters p;
  p.criterion = Criterion::ShortestEdge;
  q.oppositeEdgeExists = true;
  EXPECT_EQ(itk::MeshExtraction::detail::EvaluateEdgeSwap(q, p).verdict, EdgeSwapVerdict::NotManifold);
  q.oppositeEdgeExists = false;
  q.sameApex = true;
  EXPECT_EQ(itk::MeshExtraction::detail::EvaluateEdgeSwap(q, p).verdict, EdgeSwapVerdict::NotManifold);
}

TEST(EdgeSwapQuadEdgeMeshFilter, FeatureEdgesAreNeitherCutNorCreated)
{
  // The normals of the two triangles are 80 degrees apart: a crease along (a, b).
  const double       angle = 80.0 * itk::Math::pi / 180.0;
  EdgeSwapQuad       q = FlatQuad(MakeVec3(0.5, 0.2, 0), MakeVec3(0.5, -0.2 * std::cos(angle), 0.2 * std::sin(angle)));
  EdgeSwapParameters p;
  p.criterion = Criterion::ShortestEdge;
  p.featureAngle = 60.0 * itk::Math::pi / 180.0;
  EXPECT_GT(itk::MeshExtraction::detail::EdgeSwapGain(p.criterion, q), 0.0);
  EXPECT_EQ(itk::MeshExtraction::detail::EvaluateEdgeSwap(q, p).verdict, EdgeSwapVerdict::FeatureEdge);
  p.featureAngle = itk::Math::pi;
  EXPECT_EQ(itk::MeshExtraction::detail::EvaluateEdgeSwap(q, p).verdict, EdgeSwapVerdict::Swap);
}

TEST(EdgeSwapQuadEdgeMeshFilter, SwapCreatingADegenerateTriangleIsRefused)
{
  // c, d and a are collinear: the new triangle (a, d, c) has no area, although the
  // new edge (0.8) is shorter than the old one (1).
  EdgeSwapQuad       q = FlatQuad(MakeVec3(0.0, 0.4, 0), MakeVec3(0.0, -0.4, 0));
  EdgeSwapParameters p;
  p.criterion = Criterion::ShortestEdge;
  p.featureAngle = itk::Math::pi;
  EXPECT_EQ(itk::MeshExtraction::detail::EvaluateEdgeSwap(q, p).verdict, EdgeSwapVerdict::DegenerateTriangle);
}
