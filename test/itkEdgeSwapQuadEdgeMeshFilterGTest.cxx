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
#include "itkEdgeSwapQuadEdgeMeshFilter.h"
#include "itkLaplacianSmoothingQuadEdgeMeshFilter.h"
#include "itkMeshSurfaceDistanceCalculator.h"
#include "itkTaubinSmoothingQuadEdgeMeshFilter.h"
#include "itkMeshExtractionEdgeSwapCriteria.h"
#include "itkMeshExtractionEdgeSwapPasses.h"
#include "itkMeshExtractionRandomSurfaces.h"
#include "itkMeshExtractionTestHelpers.h"
#include "itkTriangleMeshQualityCalculator.h"
#include "itkBinaryMask3DMeshSource.h"
#include "itkImplicitSurfaceImageSource.h"

#include "itkGTest.h"
#include "itkQuadEdgeMeshEulerOperatorFlipEdgeFunction.h"
#include <algorithm>
#include <cstdlib>
#include <array>

#include <functional>
#include <iomanip>
#include <map>
#include <random>
#include <set>
#include <sstream>

using namespace MeshExtractionTest;
using itk::MeshExtraction::TriangleMeshQualityReport;
using itk::MeshExtraction::detail::EdgeSwapParameters;
using itk::MeshExtraction::detail::EdgeSwapQuad;

namespace
{
using SwapType = itk::EdgeSwapQuadEdgeMeshFilter<QEMeshType>;
using LaplacianType = itk::LaplacianSmoothingQuadEdgeMeshFilter<QEMeshType>;
using Criterion = itk::MeshExtractionEnums::EdgeSwapCriterion;

TriangleMeshQualityReport
Analyze(const QEMeshType * mesh, bool selfIntersections = true)
{
  auto calculator = itk::TriangleMeshQualityCalculator<QEMeshType>::New();
  calculator->SetMesh(mesh);
  calculator->SetComputeSelfIntersections(selfIntersections);
  calculator->Compute();
  return calculator->GetReport();
}

/** The triangles of a mesh as point-identifier triples, each rotated to start at
 * its smallest identifier (orientation kept), in a set. */
template <typename TMesh>
std::set<std::array<itk::IdentifierType, 3>>
TriangleSetOf(const TMesh * mesh)
{
  const IndexedTriangleMesh                    m = itk::MeshExtraction::MakeIndexedTriangleMesh(*mesh);
  std::set<std::array<itk::IdentifierType, 3>> triangles;
  for (const auto & t : m.triangles)
  {
    std::array<itk::IdentifierType, 3> ids = { m.pointIds[t[0]], m.pointIds[t[1]], m.pointIds[t[2]] };
    std::rotate(ids.begin(), std::min_element(ids.begin(), ids.end()), ids.end());
    triangles.insert(ids);
  }
  return triangles;
}

std::set<std::array<itk::IdentifierType, 3>>
TriangleSet(const QEMeshType * mesh)
{
  return TriangleSetOf(mesh);
}

/** The internal edges of an indexed mesh with their quads: (a, b, c, d) where
 * (a, b, c) and (b, a, d) are the triangles on either side. */
std::vector<std::array<std::uint32_t, 4>>
InternalEdgeQuads(const IndexedTriangleMesh & m)
{
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> apex; // directed edge -> opposite vertex
  for (const auto & t : m.triangles)
  {
    for (unsigned int k = 0; k < 3; ++k)
    {
      apex[{ t[k], t[(k + 1) % 3] }] = t[(k + 2) % 3];
    }
  }
  std::vector<std::array<std::uint32_t, 4>> quads;
  for (const auto & e : apex)
  {
    const auto other = apex.find({ e.first.second, e.first.first });
    if (e.first.first < e.first.second && other != apex.end())
    {
      quads.push_back({ e.first.first, e.first.second, e.second, other->second });
    }
  }
  return quads;
}

/** The number of edges of `mesh` that the filter with these parameters would
 * still swap: zero once it has converged. */
template <typename TMesh>
unsigned int
RemainingSwaps(const TMesh * mesh, const EdgeSwapParameters & parameters)
{
  const IndexedTriangleMesh m = itk::MeshExtraction::MakeIndexedTriangleMesh(*mesh);
  unsigned int              remaining = 0;
  for (const auto & quad : InternalEdgeQuads(m))
  {
    EdgeSwapQuad   q;
    Vec3 *         corners[4] = { &q.a, &q.b, &q.c, &q.d };
    unsigned int * valences[4] = { &q.valenceA, &q.valenceB, &q.valenceC, &q.valenceD };
    bool *         boundaries[4] = { &q.boundaryA, &q.boundaryB, &q.boundaryC, &q.boundaryD };
    for (unsigned int k = 0; k < 4; ++k)
    {
      const auto & point = mesh->GetPoints()->ElementAt(m.pointIds[quad[k]]);
      *corners[k] = m.points[quad[k]];
      *valences[k] = static_cast<unsigned int>(point.GetValence());
      *boundaries[k] = !point.IsInternal();
    }
    q.sameApex = quad[2] == quad[3];
    q.oppositeEdgeExists = mesh->FindEdge(m.pointIds[quad[2]], m.pointIds[quad[3]]) != nullptr;
    remaining += itk::MeshExtraction::detail::EvaluateEdgeSwap(q, parameters).Swap();
  }
  return remaining;
}

/** ITK's BinaryMask3DMeshSource on a mask of the sphere of the given radius (in
 * voxels of 1 mm), centred off the grid at 3.8 + radius in every coordinate. */
QEMeshType::Pointer
MakeMarchingCubesSphere(double radius)
{
  using ImageType = itk::Image<unsigned char, 3>;
  auto                  sphere = itk::SphereImplicitSurface::New();
  itk::Point<double, 3> center;
  center.Fill(3.8 + radius);
  sphere->SetCenter(center);
  sphere->SetRadius(radius);
  auto source = itk::ImplicitSurfaceImageSource<ImageType>::New();
  source->SetSurface(sphere);
  ImageType::SizeType size;
  size.Fill(static_cast<itk::SizeValueType>(2 * radius + 8));
  source->SetSize(size);
  source->SetImageMode(itk::MeshExtractionEnums::PhantomImage::BinaryMask);
  auto mc = itk::BinaryMask3DMeshSource<ImageType, QEMeshType>::New();
  mc->SetInput(source->GetOutput());
  mc->SetObjectValue(1);
  mc->Update();
  QEMeshType::Pointer m = mc->GetOutput();
  m->DisconnectPipeline();
  return m;
}

/** The marching-cubes sphere of radius 15 voxels. */
const QEMeshType *
MarchingCubesSphere()
{
  static QEMeshType::Pointer mesh = MakeMarchingCubesSphere(15.0);
  return mesh.GetPointer();
}

QEMeshType::Pointer
Swap(const QEMeshType * input, Criterion criterion, double minimumQAreaRatio = 0.0)
{
  auto filter = SwapType::New();
  filter->SetInput(input);
  filter->SetCriterion(criterion);
  filter->SetMinimumQAreaRatio(minimumQAreaRatio);
  filter->Update();
  QEMeshType::Pointer out = filter->GetOutput();
  out->DisconnectPipeline();
  return out;
}

QEMeshType::Pointer
Smooth(const QEMeshType * input, int iterations)
{
  auto filter = LaplacianType::New();
  filter->SetInput(input);
  filter->SetMovementConstraint(itk::MeshExtractionEnums::MovementConstraint::Centroid);
  filter->SetNumberOfIterations(iterations);
  filter->Update();
  QEMeshType::Pointer out = filter->GetOutput();
  out->DisconnectPipeline();
  return out;
}

} // namespace


// ------------------------------------------------------------------------------
// The filter.
// ------------------------------------------------------------------------------
TEST(EdgeSwapQuadEdgeMeshFilter, RegularitySwapsRaiseTheValence6ShareOfAMarchingCubesSphere)
{
  const QEMeshType * input = MarchingCubesSphere();
  const auto         before = Analyze(input);
  ASSERT_TRUE(before.IsValidClosedSurface());
  auto filter = SwapType::New();
  filter->SetInput(input);
  filter->Update();
  const auto after = Analyze(filter->GetOutput());
  EXPECT_GT(filter->GetNumberOfSwaps(), 1000u);
  EXPECT_LT(filter->GetNumberOfIterations(), 20); // converged
  EXPECT_LT(before.fractionValence6, 0.4);
  EXPECT_GT(after.fractionValence6, 0.75);
  EXPECT_TRUE(after.IsValidClosedSurface());
  EXPECT_EQ(after.eulerCharacteristic, 2);
  EXPECT_EQ(after.numberOfTriangles, before.numberOfTriangles);
  EXPECT_EQ(after.numberOfPoints, before.numberOfPoints);
  EXPECT_NEAR(after.enclosedVolume, before.enclosedVolume, 1e-3 * before.enclosedVolume);
  EXPECT_EQ(RemainingSwaps(filter->GetOutput(), EdgeSwapParameters()), 0u);
}

TEST(EdgeSwapQuadEdgeMeshFilter, NoEdgeIsSwappedAroundLockedPoints)
{
  const QEMeshType * input = MarchingCubesSphere();
  // Lock the points of the lower half (z below the centre): the triangles around them
  // keep their corners, and the upper half still gets its swaps.
  double zMin = 1e300;
  double zMax = -1e300;
  for (auto it = input->GetPoints()->Begin(); it != input->GetPoints()->End(); ++it)
  {
    zMin = std::min(zMin, static_cast<double>(it.Value()[2]));
    zMax = std::max(zMax, static_cast<double>(it.Value()[2]));
  }
  std::vector<QEMeshType::PointIdentifier> locked;
  for (auto it = input->GetPoints()->Begin(); it != input->GetPoints()->End(); ++it)
  {
    if (it.Value()[2] < 0.5 * (zMin + zMax))
    {
      locked.push_back(it.Index());
    }
  }
  auto triangleSet = [](const QEMeshType * mesh, const std::vector<QEMeshType::PointIdentifier> & around) {
    std::set<std::array<QEMeshType::PointIdentifier, 3>> triangles;
    const auto                                           indexed = itk::MeshExtraction::MakeIndexedTriangleMesh(*mesh);
    for (const auto & corners : indexed.triangles)
    {
      std::array<QEMeshType::PointIdentifier, 3> t;
      for (unsigned int k = 0; k < 3; ++k)
      {
        t[k] = indexed.pointIds[corners[k]];
      }
      if (std::any_of(t.begin(), t.end(), [&](QEMeshType::PointIdentifier p) {
            return std::binary_search(around.begin(), around.end(), p);
          }))
      {
        std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
        triangles.insert(t);
      }
    }
    return triangles;
  };
  auto filter = SwapType::New();
  filter->SetInput(input);
  filter->SetLockedPoints(locked);
  filter->Update();
  const auto free = SwapType::New();
  free->SetInput(input);
  free->Update();
  EXPECT_GT(filter->GetNumberOfSwaps(), 200u);
  EXPECT_LT(filter->GetNumberOfSwaps(), free->GetNumberOfSwaps());
  EXPECT_EQ(triangleSet(filter->GetOutput(), locked), triangleSet(input, locked));
  EXPECT_NE(triangleSet(free->GetOutput(), locked), triangleSet(input, locked)); // the lock made the difference
  EXPECT_TRUE(Analyze(filter->GetOutput()).IsValidClosedSurface());

  filter->SetLockedPoints({});
  filter->Update();
  EXPECT_EQ(filter->GetNumberOfSwaps(), free->GetNumberOfSwaps());
}

TEST(EdgeSwapQuadEdgeMeshFilter, SwapsNeverMakeTheSurfaceCrossItself)
{
  // SurfaceNets meshes of smooth random volumes with noise (MakeRandomSmoothVolume):
  // valid closed surfaces with many small components and pinches, on which the local
  // checks of 4.5.1 let some swaps cut through a nearby part of the surface (seeds
  // 144-198 of a stress run: 3 to 88 crossing pairs, some triangles then facing
  // inward). With PreventSelfIntersections (the default) the output is as valid as
  // the input, and the retries only lock what crossed.
  int                tested = 0;
  int                crossedWithoutPrevention = 0;
  int                retried = 0;
  itk::SizeValueType swaps = 0;
  for (unsigned int seed : { 144u, 150u, 162u, 176u, 186u, 188u, 198u, 0u, 1u, 2u, 3u })
  {
    const QEMeshType::Pointer input = RandomSurfaceNetsMesh(seed);
    if (!input)
    {
      continue; // nothing inside or nothing outside
    }
    const auto before = Analyze(input);
    ASSERT_TRUE(before.IsValidClosedSurface()) << "seed " << seed;
    ++tested;
    for (const bool prevent : { true, false })
    {
      auto filter = SwapType::New();
      filter->SetInput(input);
      filter->SetCriterion(static_cast<Criterion>(seed % 3));
      filter->SetPreventSelfIntersections(prevent);
      filter->Update();
      const auto after = Analyze(filter->GetOutput());
      if (prevent)
      {
        std::ostringstream text;
        after.Print(text);
        EXPECT_TRUE(after.IsValidClosedSurface()) << "seed " << seed << '\n' << text.str();
        EXPECT_EQ(after.eulerCharacteristic, before.eulerCharacteristic) << "seed " << seed;
        swaps += filter->GetNumberOfSwaps();
        EXPECT_FALSE(filter->GetKeptInput()) << "seed " << seed;
        retried += filter->GetNumberOfAttempts() > 1 ? 1 : 0;
        EXPECT_EQ(filter->GetNumberOfAttempts() > 1, filter->GetNumberOfCrossingTriangles() > 0);
      }
      else
      {
        crossedWithoutPrevention += after.selfIntersectingPairs > 0 ? 1 : 0;
        EXPECT_EQ(filter->GetNumberOfAttempts(), 1u);
      }
    }
  }
  EXPECT_GE(tested, 10);
  EXPECT_GE(crossedWithoutPrevention, 5); // the test can fail: the local checks alone let them cross
  EXPECT_GE(retried, 5);
  EXPECT_GT(swaps, 1000u);
}

TEST(EdgeSwapQuadEdgeMeshFilter, RegularitySwapsThenSmoothingReachAHigherQAreaThanSmoothingAlone)
{
  // Thesis 4.2.4: smoothing converges faster after an edge swap. On the
  // marching-cubes sphere the swaps alone trade some q_area for regularity; with
  // MinimumQAreaRatio = 1 they keep every quad's worst triangle and so never lower
  // the mean q_area, and still make most vertices regular.
  const QEMeshType * input = MarchingCubesSphere();
  const double       smoothedOnly = Analyze(Smooth(input, 5), false).qArea.mean;
  const double       swappedThenSmoothed = Analyze(Smooth(Swap(input, Criterion::Regularity), 5), false).qArea.mean;
  EXPECT_GT(swappedThenSmoothed, smoothedOnly + 0.01) << smoothedOnly << " vs " << swappedThenSmoothed;

  const auto before = Analyze(input, false);
  const auto careful = Analyze(Swap(input, Criterion::Regularity, 1.0), false);
  EXPECT_GE(careful.qArea.mean, before.qArea.mean - 1e-12);
  EXPECT_GT(careful.fractionValence6, 0.75);
}

TEST(EdgeSwapQuadEdgeMeshFilter, DelaunaySwapsLeaveADelaunayMeshUnchanged)
{
  const auto icosphere = ToITKMesh<QEMeshType>(MakeIcosphere(3, 10.0));
  for (const QEMeshType * input : { static_cast<const QEMeshType *>(icosphere.GetPointer()), MarchingCubesSphere() })
  {
    auto filter = SwapType::New();
    filter->SetInput(input);
    filter->SetCriterion(Criterion::Delaunay);
    filter->Update();
    EXPECT_EQ(filter->GetNumberOfSwaps(), 0u);
    EXPECT_EQ(filter->GetNumberOfIterations(), 1);
    EXPECT_EQ(TriangleSet(filter->GetOutput()), TriangleSet(input));
  }
}

TEST(EdgeSwapQuadEdgeMeshFilter, DelaunaySwapsMakeAJitteredPlanarGridDelaunay)
{
  IndexedTriangleMesh                    grid = MakeGrid(10);
  std::mt19937                           rng(8);
  std::uniform_real_distribution<double> u(-0.35, 0.35);
  for (auto & p : grid.points)
  {
    const bool boundary = p[0] == 0 || p[1] == 0 || p[0] == 10 || p[1] == 10;
    if (!boundary)
    {
      p += MakeVec3(u(rng), u(rng), 0);
    }
  }
  const auto input = ToITKMesh<QEMeshDType>(grid);
  auto       filter = itk::EdgeSwapQuadEdgeMeshFilter<QEMeshDType>::New();
  filter->SetInput(input);
  filter->SetCriterion(Criterion::Delaunay);
  filter->Update();
  EXPECT_GT(filter->GetNumberOfSwaps(), 10u);
  const IndexedTriangleMesh out = itk::MeshExtraction::MakeIndexedTriangleMesh(*filter->GetOutput());
  for (const auto & t : out.triangles)
  {
    EXPECT_GT(itk::MeshExtraction::TriangleNormal(out.points[t[0]], out.points[t[1]], out.points[t[2]])[2], 0.0);
  }
  for (const auto & q : InternalEdgeQuads(out))
  {
    EXPECT_LE(
      itk::MeshExtraction::OppositeAngleSum(out.points[q[0]], out.points[q[1]], out.points[q[2]], out.points[q[3]]),
      itk::Math::pi + 1e-9);
    EXPECT_FALSE(itk::MeshExtraction::IsInsideCircumcircle(
      out.points[q[0]], out.points[q[1]], out.points[q[2]], out.points[q[3]]));
  }
  EXPECT_EQ(out.triangles.size(), grid.triangles.size());
  EdgeSwapParameters parameters;
  parameters.criterion = Criterion::Delaunay;
  EXPECT_EQ(RemainingSwaps(filter->GetOutput(), parameters), 0u);
}

TEST(EdgeSwapQuadEdgeMeshFilter, ShortestEdgeSwapsShortenTheTotalEdgeLength)
{
  // A jittered grid: in about half of the squares the other diagonal is shorter.
  IndexedTriangleMesh                    grid = MakeGrid(10);
  std::mt19937                           rng(21);
  std::uniform_real_distribution<double> u(-0.3, 0.3);
  for (auto & p : grid.points)
  {
    if (p[0] > 0 && p[1] > 0 && p[0] < 10 && p[1] < 10)
    {
      p += MakeVec3(u(rng), u(rng), 0);
    }
  }
  const auto input = ToITKMesh<QEMeshType>(grid);
  const auto before = Analyze(input);
  auto       filter = SwapType::New();
  filter->SetInput(input);
  filter->SetCriterion(Criterion::ShortestEdge);
  filter->Update();
  const auto after = Analyze(filter->GetOutput());
  EXPECT_GT(filter->GetNumberOfSwaps(), 20u);
  EXPECT_LT(after.edgeLength.mean * after.numberOfEdges, before.edgeLength.mean * before.numberOfEdges - 1.0);
  EXPECT_EQ(after.degenerateTriangles, 0);
  EXPECT_EQ(after.boundaryEdges, before.boundaryEdges);
  const IndexedTriangleMesh out = itk::MeshExtraction::MakeIndexedTriangleMesh(*filter->GetOutput());
  for (const auto & t : out.triangles)
  {
    EXPECT_GT(itk::MeshExtraction::TriangleNormal(out.points[t[0]], out.points[t[1]], out.points[t[2]])[2], 0.0);
  }
  // No edge is left whose swap would shorten it and pass the checks.
  EdgeSwapParameters parameters;
  parameters.criterion = Criterion::ShortestEdge;
  EXPECT_EQ(RemainingSwaps(filter->GetOutput(), parameters), 0u);
}

TEST(EdgeSwapQuadEdgeMeshFilter, SwapAndSmoothingSequencesKeepHundredsOfPerturbedClosedMeshesValid)
{
  // Swap, smooth, swap on 700 randomly perturbed coarse spheres, each criterion in
  // turn: every result stays a valid closed surface (closed, manifold, outward,
  // no degenerate triangles) with the same numbers of points, faces and Euler
  // characteristic.
  std::mt19937       rng(31337);
  int                tested = 0;
  int                selfIntersecting = 0;
  itk::SizeValueType swaps = 0;
  itk::SizeValueType refused = 0;
  const Criterion    criteria[] = { Criterion::Regularity, Criterion::Delaunay, Criterion::ShortestEdge };
  for (int k = 0; k < 700; ++k)
  {
    IndexedTriangleMesh                    m = MakeIcosphere(1, 10.0);
    std::uniform_real_distribution<double> u(-1.6, 1.6);
    for (auto & p : m.points)
    {
      p += MakeVec3(u(rng), u(rng), u(rng));
    }
    QEMeshType::Pointer mesh = ToITKMesh<QEMeshType>(m);
    if (!Analyze(mesh).IsValidClosedSurface())
    {
      continue;
    }
    ++tested;
    for (int stage = 0; stage < 3; ++stage)
    {
      if (stage == 1)
      {
        mesh = Smooth(mesh, 1);
      }
      else
      {
        auto filter = SwapType::New();
        filter->SetInput(mesh);
        filter->SetCriterion(criteria[(k + stage) % 3]);
        filter->SetFeatureAngle(k % 2 ? 60.0 : 150.0);
        filter->Update();
        swaps += filter->GetNumberOfSwaps();
        refused += filter->GetNumberOfRefusedSwaps();
        mesh = filter->GetOutput();
        mesh->DisconnectPipeline();
      }
      const auto report = Analyze(mesh);
      ASSERT_EQ(report.degenerateTriangles, 0) << "mesh " << k << ", stage " << stage;
      ASSERT_EQ(report.nonManifoldEdges + report.nonManifoldVertices + report.boundaryEdges, 0)
        << "mesh " << k << ", stage " << stage;
      ASSERT_EQ(report.inconsistentlyOrientedEdges, 0) << "mesh " << k << ", stage " << stage;
      ASSERT_EQ(report.eulerCharacteristic, 2) << "mesh " << k << ", stage " << stage;
      ASSERT_EQ(report.numberOfTriangles, 80u) << "mesh " << k << ", stage " << stage;
      if (report.selfIntersectingPairs == 0)
      {
        ASSERT_EQ(report.invertedTrianglesVersusOutward, 0) << "mesh " << k << ", stage " << stage;
      }
      else
      {
        ++selfIntersecting;
        break;
      }
    }
  }
  EXPECT_GT(tested, 600);
  EXPECT_GT(swaps, 1000u);
  EXPECT_GT(refused, 20u); // the checks had work to do
  EXPECT_LE(selfIntersecting, tested / 200);
  std::cout << tested << " valid perturbed meshes; " << swaps << " swaps made, " << refused
            << " improving swaps refused by the checks; " << selfIntersecting << " results intersect themselves\n";
}

TEST(EdgeSwapQuadEdgeMeshFilter, BoundaryEdgesAreNeverSwapped)
{
  IndexedTriangleMesh                    grid = MakeGrid(6);
  std::mt19937                           rng(2);
  std::uniform_real_distribution<double> u(-0.3, 0.3);
  for (auto & p : grid.points)
  {
    p[2] += u(rng) * 0.2;
  }
  const auto input = ToITKMesh<QEMeshType>(grid);
  const auto before = Analyze(input);
  for (Criterion c : { Criterion::Regularity, Criterion::Delaunay, Criterion::ShortestEdge })
  {
    auto filter = SwapType::New();
    filter->SetInput(input);
    filter->SetCriterion(c);
    filter->Update();
    const auto after = Analyze(filter->GetOutput());
    EXPECT_EQ(after.boundaryEdges, before.boundaryEdges) << c;
    EXPECT_EQ(after.boundaryLoops, 1) << c;
    EXPECT_EQ(after.degenerateTriangles, 0) << c;
    // The boundary edges are the same ones.
    for (unsigned int i = 0; i < 6; ++i)
    {
      EXPECT_NE(filter->GetOutput()->FindEdge(i, i + 1), nullptr);
    }
  }
}

/** The filter's passes as they were made on the QuadEdgeMesh itself with ITK's Euler
 * operator (QuadEdgeMeshEulerOperatorFlipEdgeFunction), before they moved to flat
 * arrays: the oracle that the array passes must agree with, swap for swap. */
template <typename TMesh>
itk::SizeValueType
EulerOperatorPasses(TMesh * mesh, const EdgeSwapParameters & parameters, int maximumPasses)
{
  using PointIdentifier = typename TMesh::PointIdentifier;
  itk::SizeValueType total = 0;
  auto               flip = itk::QuadEdgeMeshEulerOperatorFlipEdgeFunction<TMesh, typename TMesh::QEType>::New();
  flip->SetInput(mesh);
  for (int pass = 0; pass < maximumPasses; ++pass)
  {
    std::vector<std::pair<PointIdentifier, PointIdentifier>> edges;
    for (auto it = mesh->GetEdgeCells()->Begin(); it != mesh->GetEdgeCells()->End(); ++it)
    {
      auto p = it.Value()->PointIdsBegin();
      edges.emplace_back(std::min(p[0], p[1]), std::max(p[0], p[1]));
    }
    std::sort(edges.begin(), edges.end());
    std::map<PointIdentifier, int>  valence;
    std::map<PointIdentifier, bool> boundary;
    for (auto it = mesh->GetPoints()->Begin(); it != mesh->GetPoints()->End(); ++it)
    {
      valence[it.Index()] = it.Value().GetValence();
      boundary[it.Index()] = !it.Value().IsInternal();
    }
    itk::SizeValueType swaps = 0;
    for (const auto & ab : edges)
    {
      auto * e = mesh->FindEdge(ab.first, ab.second);
      if (e == nullptr || !e->IsInternal() || !e->IsLnextOfTriangle() || !e->GetSym()->IsLnextOfTriangle())
      {
        continue;
      }
      const PointIdentifier q[4] = { e->GetOrigin(), e->GetDestination(), e->GetLnext()->GetDestination(),
                                     e->GetSym()->GetLnext()->GetDestination() };
      EdgeSwapQuad          quad;
      Vec3 *                corners[4] = { &quad.a, &quad.b, &quad.c, &quad.d };
      unsigned int *        valences[4] = { &quad.valenceA, &quad.valenceB, &quad.valenceC, &quad.valenceD };
      bool *                boundaries[4] = { &quad.boundaryA, &quad.boundaryB, &quad.boundaryC, &quad.boundaryD };
      for (unsigned int k = 0; k < 4; ++k)
      {
        const auto & point = mesh->GetPoint(q[k]);
        *corners[k] = MakeVec3(point[0], point[1], point[2]);
        *valences[k] = static_cast<unsigned int>(valence[q[k]]);
        *boundaries[k] = boundary[q[k]];
      }
      quad.sameApex = q[2] == q[3];
      quad.oppositeEdgeExists = !quad.sameApex && mesh->FindEdge(q[2], q[3]) != nullptr;
      if (!itk::MeshExtraction::detail::EvaluateEdgeSwap(quad, parameters).Swap() || flip->Evaluate(e) == nullptr)
      {
        continue;
      }
      --valence[q[0]];
      --valence[q[1]];
      ++valence[q[2]];
      ++valence[q[3]];
      ++swaps;
    }
    total += swaps;
    if (swaps == 0)
    {
      break;
    }
  }
  return total;
}

TEST(EdgeSwapQuadEdgeMeshFilter, ArrayPassesSwapAsITKsEulerOperatorDid)
{
  // Marching-cubes spheres, closed and with a cap cut off, perturbed spheres and open
  // grids, every criterion: the filter's triangles and swap count equal those of the
  // Euler operator's passes.
  const IndexedTriangleMesh mc = itk::MeshExtraction::MakeIndexedTriangleMesh(*MarchingCubesSphere());
  IndexedTriangleMesh       cut = mc;
  cut.triangles.clear();
  for (const auto & t : mc.triangles)
  {
    if (!(mc.points[t[0]][2] > 28 && mc.points[t[1]][2] > 28 && mc.points[t[2]][2] > 28))
    {
      cut.triangles.push_back(t);
    }
  }
  ASSERT_LT(cut.triangles.size(), mc.triangles.size());
  std::mt19937                     rng(4242);
  std::vector<IndexedTriangleMesh> meshes = { mc, cut };
  for (int k = 0; k < 16; ++k)
  {
    IndexedTriangleMesh m = k % 2 == 0 ? MakeIcosphere(2, 10.0) : MakeGrid(12);
    std::uniform_real_distribution<double> u(-0.6, 0.6);
    for (auto & p : m.points)
    {
      p += MakeVec3(u(rng), u(rng), k % 2 == 0 ? u(rng) : 0.2 * u(rng));
    }
    meshes.push_back(m);
  }
  std::map<Criterion, itk::SizeValueType> swapsByCriterion;
  for (std::size_t k = 0; k < meshes.size(); ++k)
  {
    for (Criterion c : { Criterion::Regularity, Criterion::Delaunay, Criterion::ShortestEdge })
    {
      const auto input = ToITKMesh<QEMeshDType>(meshes[k]);
      auto       filter = itk::EdgeSwapQuadEdgeMeshFilter<QEMeshDType>::New();
      filter->SetInput(input);
      filter->SetCriterion(c);
      filter->SetPreventSelfIntersections(false);
      filter->Update();
      EdgeSwapParameters parameters;
      parameters.criterion = c;
      parameters.featureAngle = filter->GetFeatureAngle() * itk::Math::pi / 180.0;
      const auto reference = ToITKMesh<QEMeshDType>(meshes[k]);
      const auto swaps =
        EulerOperatorPasses(reference.GetPointer(), parameters, filter->GetMaximumNumberOfIterations());
      EXPECT_EQ(filter->GetNumberOfSwaps(), swaps) << "mesh " << k << ", " << c;
      EXPECT_EQ(TriangleSetOf(filter->GetOutput()), TriangleSetOf(reference.GetPointer())) << "mesh " << k << ", " << c;
      swapsByCriterion[c] += swaps;
    }
  }
  EXPECT_GT(swapsByCriterion[Criterion::Regularity], 1000u);
  EXPECT_GT(swapsByCriterion[Criterion::Delaunay], 100u);
  EXPECT_GT(swapsByCriterion[Criterion::ShortestEdge], 100u);
}

TEST(EdgeSwapQuadEdgeMeshFilter, SwapsKeepPointDataAndWireEdges)
{
  IndexedTriangleMesh                    grid = MakeGrid(6);
  std::mt19937                           rng(5);
  std::uniform_real_distribution<double> u(-0.3, 0.3);
  for (auto & p : grid.points)
  {
    p += MakeVec3(u(rng), u(rng), 0.1 * u(rng));
  }
  const auto input = ToITKMesh<QEMeshType>(grid);
  // An extra point joined to a corner of the grid by an edge without faces.
  QEMeshType::PointType extra;
  extra[0] = -3.0;
  extra[1] = -3.0;
  extra[2] = 0.0;
  const QEMeshType::PointIdentifier extraId = input->GetNumberOfPoints();
  input->SetPoint(extraId, extra);
  ASSERT_NE(input->AddEdge(0, extraId), nullptr);
  for (QEMeshType::PointIdentifier i = 0; i <= extraId; ++i)
  {
    input->SetPointData(i, static_cast<QEMeshType::PixelType>(i) * 0.5);
  }
  auto filter = SwapType::New();
  filter->SetInput(input);
  filter->SetCriterion(Criterion::Delaunay);
  filter->Update();
  ASSERT_GT(filter->GetNumberOfSwaps(), 0u);
  const QEMeshType * out = filter->GetOutput();
  EXPECT_EQ(out->GetNumberOfPoints(), input->GetNumberOfPoints());
  EXPECT_EQ(out->GetNumberOfFaces(), input->GetNumberOfFaces());
  EXPECT_NE(out->FindEdge(0, extraId), nullptr);
  for (QEMeshType::PointIdentifier i = 0; i <= extraId; ++i)
  {
    QEMeshType::PixelType value = -1;
    ASSERT_TRUE(out->GetPointData(i, &value));
    EXPECT_EQ(value, static_cast<QEMeshType::PixelType>(i) * 0.5);
    EXPECT_EQ(out->GetPoint(i), input->GetPoint(i));
  }
}

TEST(EdgeSwapQuadEdgeMeshFilter, ArrayPassesRefuseAnEdgeOfThreeTriangles)
{
  IndexedTriangleMesh m;
  m.points = { MakeVec3(0, 0, 0), MakeVec3(1, 0, 0), MakeVec3(0, 1, 0), MakeVec3(0, -1, 0), MakeVec3(0, 0, 1) };
  m.pointIds = { 0, 1, 2, 3, 4 };
  m.triangles = { { 0, 1, 2 }, { 1, 0, 3 }, { 0, 1, 4 } };
  try
  {
    itk::MeshExtraction::detail::SwapEdgesInPasses(m, EdgeSwapParameters(), {}, 20);
    FAIL() << "no exception";
  }
  catch (const itk::ExceptionObject & e)
  {
    EXPECT_NE(std::string(e.GetDescription()).find("edge (0, 1) has 3 triangles"), std::string::npos)
      << e.GetDescription();
  }
  m.triangles = { { 0, 1, 2 }, { 0, 1, 3 } };
  EXPECT_THROW(itk::MeshExtraction::detail::SwapEdgesInPasses(m, EdgeSwapParameters(), {}, 20),
               itk::ExceptionObject); // both run (0, 1) the same way
  m.triangles = { { 0, 1, 2 }, { 1, 0, 3 } };
  EXPECT_THROW(itk::MeshExtraction::detail::SwapEdgesInPasses(m, EdgeSwapParameters(), { 0, 0 }, 20),
               itk::ExceptionObject); // two lock flags for five points
}

TEST(EdgeSwapQuadEdgeMeshFilter, RegularMeshesHaveNothingToSwap)
{
  // Tetrahedron (valence 3) and icosahedron (valence 5): no swap lowers E_b; a
  // tetrahedron's other diagonals are edges already, and the icosahedron is
  // Delaunay with equal edges.
  for (const IndexedTriangleMesh & m : { MakeTetrahedron(), MakeIcosphere(0) })
  {
    const auto input = ToITKMesh<QEMeshType>(m);
    for (Criterion c : { Criterion::Regularity, Criterion::Delaunay, Criterion::ShortestEdge })
    {
      auto filter = SwapType::New();
      filter->SetInput(input);
      filter->SetCriterion(c);
      filter->Update();
      EXPECT_EQ(filter->GetNumberOfSwaps(), 0u) << c;
      EXPECT_EQ(TriangleSet(filter->GetOutput()), TriangleSet(input)) << c;
    }
  }
}

TEST(EdgeSwapQuadEdgeMeshFilter, SwapsAreDeterministic)
{
  const auto input = MakeMarchingCubesSphere(6.0);
  for (Criterion c : { Criterion::Regularity, Criterion::ShortestEdge })
  {
    const auto first = Swap(input, c, 0.0);
    const auto second = Swap(input, c, 0.0);
    if (c == Criterion::Regularity)
    {
      EXPECT_NE(TriangleSet(first), TriangleSet(input)) << c;
    }
    EXPECT_EQ(TriangleSet(first), TriangleSet(second)) << c;
  }
}

TEST(EdgeSwapQuadEdgeMeshFilter, ZeroIterationsCopyTheInput)
{
  const auto input = ToITKMesh<QEMeshType>(MakeIcosphere(1));
  auto       filter = SwapType::New();
  filter->SetInput(input);
  filter->SetMaximumNumberOfIterations(0);
  filter->Update();
  EXPECT_EQ(filter->GetNumberOfSwaps(), 0u);
  EXPECT_EQ(TriangleSet(filter->GetOutput()), TriangleSet(input));
}

TEST(EdgeSwapQuadEdgeMeshFilter, ThrowsOnBadInput)
{
  auto filter = SwapType::New();
  EXPECT_THROW(filter->Update(), itk::ExceptionObject);

  auto mesh = QEMeshType::New();
  for (unsigned int i = 0; i < 4; ++i)
  {
    QEMeshType::PointType p;
    p[0] = i % 2;
    p[1] = i / 2;
    p[2] = 0;
    mesh->SetPoint(i, p);
  }
  QEMeshType::PointIdList quad = { 0, 1, 3, 2 };
  ASSERT_NE(mesh->AddFace(quad), nullptr);
  filter->SetInput(mesh);
  EXPECT_THROW(filter->Update(), itk::ExceptionObject);

  const auto input = ToITKMesh<QEMeshType>(MakeIcosphere(1));
  auto       expectThrow = [&](const std::function<void(SwapType *)> & set, const char * what) {
    auto f = SwapType::New();
    f->SetInput(input);
    set(f);
    try
    {
      f->Update();
      ADD_FAILURE() << "no exception for " << what;
    }
    catch (const itk::ExceptionObject & e)
    {
      EXPECT_NE(std::string(e.GetDescription()).find(what), std::string::npos) << e.GetDescription();
    }
  };
  expectThrow([](SwapType * f) { f->SetMaximumNumberOfIterations(-1); }, "MaximumNumberOfIterations");
  expectThrow([](SwapType * f) { f->SetFeatureAngle(0.0); }, "FeatureAngle");
  expectThrow([](SwapType * f) { f->SetFeatureAngle(200.0); }, "FeatureAngle");
  expectThrow([](SwapType * f) { f->SetDegenerateQAreaTolerance(-1.0); }, "DegenerateQAreaTolerance");
  expectThrow([](SwapType * f) { f->SetMinimumQAreaRatio(-0.5); }, "MinimumQAreaRatio");
  expectThrow([](SwapType * f) { f->SetCriterion(static_cast<Criterion>(9)); }, "Criterion");
}

TEST(EdgeSwapQuadEdgeMeshFilter, PrintSelfNamesEveryParameter)
{
  auto filter = SwapType::New();
  EXPECT_STREQ(filter->GetNameOfClass(), "EdgeSwapQuadEdgeMeshFilter");
  std::ostringstream os;
  filter->Print(os);
  for (const char * name : { "Criterion",
                             "MaximumNumberOfIterations",
                             "FeatureAngle",
                             "DegenerateQAreaTolerance",
                             "MinimumQAreaRatio",
                             "NumberOfSwaps",
                             "NumberOfRefusedSwaps" })
  {
    EXPECT_NE(os.str().find(name), std::string::npos) << name;
  }
}

// ------------------------------------------------------------------------------
// The before/after table of the three filters on a marching-cubes sphere. Disabled
// by default (a few seconds); run it with
//   MeshExtractionGTestDriver --gtest_also_run_disabled_tests --gtest_filter='MeshImprovementTable.*'
// ------------------------------------------------------------------------------
TEST(MeshImprovementTable, DISABLED_PrintsBeforeAndAfterOnAMarchingCubesSphereOfRadius15)
{
  using Weights = itk::MeshExtractionEnums::SmoothingWeights;
  using Constraint = itk::MeshExtractionEnums::MovementConstraint;
  auto                  sphere = itk::SphereImplicitSurface::New();
  itk::Point<double, 3> center;
  center.Fill(18.8);
  sphere->SetCenter(center);
  sphere->SetRadius(15.0);
  const QEMeshType * input = MarchingCubesSphere();

  std::cout
    << "Marching-cubes sphere (ITK BinaryMask3DMeshSource), radius 15 voxels of 1 mm, centre (18.8, 18.8, 18.8);\n"
       "distances of the vertices to the exact sphere in voxels.\n\n";
  std::cout << std::left << std::setw(48) << "mesh" << std::right << std::setw(8) << "q_area" << std::setw(9)
            << "q_angle" << std::setw(8) << "val6 %" << std::setw(9) << "d mean" << std::setw(8) << "d max"
            << std::setw(10) << "shortened" << std::setw(9) << "rejected" << std::setw(7) << "swaps" << std::setw(10)
            << "inverted" << std::setw(7) << "valid" << '\n';
  auto row = [&](const std::string & name,
                 const QEMeshType *  mesh,
                 const std::string & shortened,
                 const std::string & rejected,
                 const std::string & swaps,
                 const QEMeshType *  reference = nullptr,
                 bool                expectValid = true) {
    auto calculator = itk::TriangleMeshQualityCalculator<QEMeshType>::New();
    calculator->SetMesh(mesh);
    calculator->SetReferenceMesh(reference);
    calculator->Compute();
    const auto & report = calculator->GetReport();
    auto         distance = itk::MeshSurfaceDistanceCalculator<QEMeshType>::New();
    distance->SetMesh(mesh);
    distance->SetReferenceSurface(sphere);
    distance->SetSymmetric(false);
    distance->Compute();
    std::cout << std::left << std::setw(48) << name << std::right << std::fixed << std::setprecision(4) << std::setw(8)
              << report.qArea.mean << std::setw(9) << report.qAngle.mean << std::setprecision(1) << std::setw(8)
              << 100.0 * report.fractionValence6 << std::setprecision(3) << std::setw(9)
              << distance->GetVertexDistance().mean << std::setw(8) << distance->GetVertexDistance().maximum
              << std::setw(10) << shortened << std::setw(9) << rejected << std::setw(7) << swaps << std::setw(10)
              << (reference ? std::to_string(report.invertedTrianglesVersusReference) : std::string("-"))
              << std::setw(7) << (report.IsValidClosedSurface() ? "yes" : "NO") << std::defaultfloat << '\n';
    if (expectValid)
    {
      EXPECT_TRUE(report.IsValidClosedSurface()) << name;
      EXPECT_LE(report.invertedTrianglesVersusReference, 0) << name;
    }
  };
  row("marching cubes (input)", input, "-", "-", "-");

  struct LaplacianRow
  {
    const char * name;
    Weights      weights;
    Constraint   constraint;
    bool         volume;
  };
  const LaplacianRow laplacianRows[] = {
    { "Laplacian uniform, 10 it", Weights::Uniform, Constraint::None, false },
    { "Laplacian uniform centroid, 10 it", Weights::Uniform, Constraint::Centroid, false },
    { "Laplacian uniform safe, 10 it", Weights::Uniform, Constraint::Safe, false },
    { "Laplacian uniform volume-preserving, 10 it", Weights::Uniform, Constraint::None, true },
    { "Laplacian inverse edge length, 10 it", Weights::InverseEdgeLength, Constraint::None, false },
    { "Laplacian area, 10 it", Weights::Area, Constraint::None, false },
    { "Laplacian cotangent, 10 it", Weights::Cotangent, Constraint::None, false },
    { "Laplacian angle bisector, 10 it", Weights::AngleBisector, Constraint::None, false },
  };
  for (const auto & r : laplacianRows)
  {
    auto filter = LaplacianType::New();
    filter->SetInput(input);
    filter->SetWeights(r.weights);
    filter->SetMovementConstraint(r.constraint);
    filter->SetVolumePreservation(r.volume);
    filter->SetNumberOfIterations(10);
    filter->Update();
    row(r.name,
        filter->GetOutput(),
        std::to_string(filter->GetNumberOfShortenedMoves()),
        std::to_string(filter->GetNumberOfRejectedMoves()),
        "-",
        input);
  }
  for (int iterations : { 10, 50 })
  {
    auto filter = itk::TaubinSmoothingQuadEdgeMeshFilter<QEMeshType>::New();
    filter->SetInput(input);
    filter->SetNumberOfIterations(iterations);
    filter->Update();
    row("Taubin 0.5|-0.53, " + std::to_string(iterations) + " it",
        filter->GetOutput(),
        std::to_string(filter->GetNumberOfShortenedMoves()),
        std::to_string(filter->GetNumberOfRejectedMoves()),
        "-",
        input);
  }
  struct SwapRow
  {
    const char * name;
    Criterion    criterion;
    double       ratio;
  };
  const SwapRow swapRows[] = { { "edge swap regularity", Criterion::Regularity, 0.0 },
                               { "edge swap regularity, MinimumQAreaRatio 1", Criterion::Regularity, 1.0 },
                               { "edge swap Delaunay", Criterion::Delaunay, 0.0 },
                               { "edge swap shortest edge", Criterion::ShortestEdge, 0.0 } };
  for (const auto & r : swapRows)
  {
    auto filter = SwapType::New();
    filter->SetInput(input);
    filter->SetCriterion(r.criterion);
    filter->SetMinimumQAreaRatio(r.ratio);
    filter->Update();
    row(r.name, filter->GetOutput(), "-", "-", std::to_string(filter->GetNumberOfSwaps()));
  }
  // The thesis protocol's ES + S steps: regularity swaps, then centroid smoothing.
  auto swap = SwapType::New();
  swap->SetInput(input);
  swap->Update();
  auto smooth = LaplacianType::New();
  smooth->SetInput(swap->GetOutput());
  smooth->SetMovementConstraint(Constraint::Centroid);
  smooth->SetNumberOfIterations(10);
  smooth->Update();
  row("regularity swap + Laplacian centroid, 10 it",
      smooth->GetOutput(),
      std::to_string(smooth->GetNumberOfShortenedMoves()),
      std::to_string(smooth->GetNumberOfRejectedMoves()),
      std::to_string(swap->GetNumberOfSwaps()));

  // The same sphere with every vertex displaced by up to 0.25 voxel along each axis
  // (uniform, seed 1): the guard now has work to do. Unguarded rows show what it
  // prevents; "inverted" counts triangles turned by 90 degrees or more against the
  // jittered input.
  IndexedTriangleMesh                    jittered = itk::MeshExtraction::MakeIndexedTriangleMesh(*input);
  std::mt19937                           rng(1);
  std::uniform_real_distribution<double> u(-0.25, 0.25);
  for (auto & p : jittered.points)
  {
    p += MakeVec3(u(rng), u(rng), u(rng));
  }
  const auto noisy = ToITKMesh<QEMeshType>(jittered);
  std::cout << '\n';
  row("jittered marching cubes (input)", noisy, "-", "-", "-", nullptr, false);
  for (Weights weights : { Weights::Uniform, Weights::InverseEdgeLength, Weights::AngleBisector })
  {
    for (bool guard : { true, false })
    {
      auto filter = LaplacianType::New();
      filter->SetInput(noisy);
      filter->SetWeights(weights);
      filter->SetPreventInversions(guard);
      filter->SetNumberOfIterations(1);
      filter->Update();
      std::ostringstream name;
      name << "  Laplacian "
           << (weights == Weights::Uniform             ? "uniform"
               : weights == Weights::InverseEdgeLength ? "inverse edge length"
                                                       : "angle bisector")
           << ", 1 it" << (guard ? "" : ", NO guard");
      row(name.str(),
          filter->GetOutput(),
          std::to_string(filter->GetNumberOfShortenedMoves()),
          std::to_string(filter->GetNumberOfRejectedMoves()),
          "-",
          noisy,
          guard);
    }
  }
  auto taubin = itk::TaubinSmoothingQuadEdgeMeshFilter<QEMeshType>::New();
  taubin->SetInput(noisy);
  taubin->SetNumberOfIterations(1);
  taubin->Update();
  row("  Taubin 0.5|-0.53, 1 it",
      taubin->GetOutput(),
      std::to_string(taubin->GetNumberOfShortenedMoves()),
      std::to_string(taubin->GetNumberOfRejectedMoves()),
      "-",
      noisy);
  auto noisySwap = SwapType::New();
  noisySwap->SetInput(noisy);
  noisySwap->Update();
  row("  edge swap regularity",
      noisySwap->GetOutput(),
      "-",
      "-",
      std::to_string(noisySwap->GetNumberOfSwaps()),
      nullptr,
      false);
}
