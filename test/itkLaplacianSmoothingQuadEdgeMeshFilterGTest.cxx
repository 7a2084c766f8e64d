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
#include "itkLaplacianSmoothingQuadEdgeMeshFilter.h"
#include "itkMeshExtractionRandomSurfaces.h"
#include "itkMeshExtractionTestHelpers.h"
#include "itkMeshSurfaceDistanceCalculator.h"
#include "itkSmoothingQuadEdgeMeshFilter.h"
#include "itkTaubinSmoothingQuadEdgeMeshFilter.h"
#include "itkTriangleMeshQualityCalculator.h"
#include "itkBinaryMask3DMeshSource.h"
#include "itkImplicitSurfaceImageSource.h"

#include "itkGTest.h"

#include <functional>
#include <numeric>
#include <random>
#include <sstream>

using namespace MeshExtractionTest;
using itk::MeshExtraction::TriangleMeshQualityReport;

namespace
{
using LaplacianType = itk::LaplacianSmoothingQuadEdgeMeshFilter<QEMeshType>;
using LaplacianDType = itk::LaplacianSmoothingQuadEdgeMeshFilter<QEMeshDType>;
using Weights = itk::MeshExtractionEnums::SmoothingWeights;
using Update = itk::MeshExtractionEnums::SmoothingUpdate;
using Constraint = itk::MeshExtractionEnums::MovementConstraint;

constexpr Weights AllWeights[] = { Weights::Uniform,
                                   Weights::InverseEdgeLength,
                                   Weights::Area,
                                   Weights::Cotangent,
                                   Weights::AngleBisector };

template <typename TMesh>
TriangleMeshQualityReport
Analyze(const TMesh * mesh, const TMesh * reference = nullptr, bool selfIntersections = true)
{
  auto calculator = itk::TriangleMeshQualityCalculator<TMesh>::New();
  calculator->SetMesh(mesh);
  calculator->SetReferenceMesh(reference);
  calculator->SetComputeSelfIntersections(selfIntersections);
  calculator->Compute();
  return calculator->GetReport();
}

/** The filter of the random-surface tests on `input`: weights, update mode and movement
 * constraint chosen by the seed, so that a run of seeds covers every combination. */
LaplacianType::Pointer
SeededLaplacian(const QEMeshType * input, unsigned int seed)
{
  auto filter = LaplacianType::New();
  filter->SetInput(input);
  filter->SetWeights(AllWeights[seed % 5]);
  filter->SetUpdateMode((seed / 5) % 2 ? Update::Immediate : Update::Batch);
  filter->SetMovementConstraint(static_cast<Constraint>((seed / 10) % 3));
  return filter;
}

template <typename TMesh>
Vec3
PointOf(const TMesh * mesh, typename TMesh::PointIdentifier id)
{
  return itk::MeshExtraction::ToVec3(mesh->GetPoint(id));
}

/** A planar fan: point 0 at `center`, points 1..n the ring, triangles (0, i, i+1). */
IndexedTriangleMesh
MakeFan(const Vec3 & center, const std::vector<Vec3> & ring)
{
  IndexedTriangleMesh m;
  m.points.push_back(center);
  for (const auto & p : ring)
  {
    m.points.push_back(p);
  }
  const auto n = static_cast<std::uint32_t>(ring.size());
  for (std::uint32_t i = 0; i < n; ++i)
  {
    m.triangles.push_back({ 0, 1 + i, 1 + (i + 1) % n });
  }
  return m;
}

/** Whether p lies strictly inside the polygon `ring` of the z = 0 plane
 * (even-odd rule). */
bool
InsidePolygon(const Vec3 & p, const std::vector<Vec3> & ring)
{
  bool inside = false;
  for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++)
  {
    const Vec3 & a = ring[i];
    const Vec3 & b = ring[j];
    if ((a[1] > p[1]) != (b[1] > p[1]) && p[0] < (b[0] - a[0]) * (p[1] - a[1]) / (b[1] - a[1]) + a[0])
    {
      inside = !inside;
    }
  }
  return inside;
}

/** Thesis Figure 2.15: a concave 1-ring (a notch at ring vertex 1) whose average
 * (1.4, 0) lies in the notch, outside the ring: triangles 1-2-0 and 5-1-0 invert. */
std::vector<Vec3>
ConcaveRingOfFigure2_15()
{
  return { MakeVec3(1, 0, 0), MakeVec3(4, 1, 0), MakeVec3(-1, 1, 0), MakeVec3(-1, -1, 0), MakeVec3(4, -1, 0) };
}

/** Thesis Figure 4.5(b): a ring whose inverse-edge-length weighted average (2.11, 0)
 * lies in the notch at (1, 0). */
std::vector<Vec3>
InverseEdgeLengthRingOfFigure4_5b()
{
  return {
    MakeVec3(1, 0, 0), MakeVec3(10, 0.5, 0), MakeVec3(-0.2, 10, 0), MakeVec3(-0.2, -10, 0), MakeVec3(10, -0.5, 0)
  };
}

/** Thesis Figure 4.5(a): a ring where angle-bisector smoothing (the average of the
 * projections of the centre onto the bisectors of the ring's angles) moves the
 * centre out of the ring's kernel, the region from which it sees every ring edge,
 * to (0.13, -0.22): triangle 4-5-0 inverts. The plain average stays in the kernel.
 * Found by a random search. */
std::vector<Vec3>
AngleBisectorRingOfFigure4_5a()
{
  return { MakeVec3(0.6, 0.3, 0),  MakeVec3(0.1, 3, 0),    MakeVec3(-0.7, 0.9, 0), MakeVec3(-2.7, 1.4, 0),
           MakeVec3(-0.4, 0.1, 0), MakeVec3(0.9, -2.8, 0), MakeVec3(2.5, -2, 0) };
}

/** Number of fan triangles (p, ring[i], ring[i+1]) that face -z: inverted when the
 * centre is at p. Zero exactly when p lies in the kernel of the ring. */
int
InvertedFanTriangles(const Vec3 & p, const std::vector<Vec3> & ring)
{
  int n = 0;
  for (std::size_t i = 0; i < ring.size(); ++i)
  {
    n += itk::MeshExtraction::TriangleNormal(p, ring[i], ring[(i + 1) % ring.size()])[2] <= 0.0;
  }
  return n;
}

struct FanResult
{
  Vec3                      center;
  TriangleMeshQualityReport report;
  itk::SizeValueType        shortened;
  itk::SizeValueType        rejected;
};

FanResult
SmoothFan(const std::vector<Vec3> & ring, Weights weights, bool guard)
{
  const auto input = ToITKMesh<QEMeshType>(MakeFan(MakeVec3(0, 0, 0), ring));
  auto       filter = LaplacianType::New();
  filter->SetInput(input);
  filter->SetWeights(weights);
  filter->SetPreventInversions(guard);
  filter->Update();
  FanResult r;
  r.center = PointOf(filter->GetOutput(), 0);
  r.report = Analyze<QEMeshType>(filter->GetOutput(), input);
  r.shortened = filter->GetNumberOfShortenedMoves();
  r.rejected = filter->GetNumberOfRejectedMoves();
  return r;
}

void
ExpectCounterexample(const std::vector<Vec3> & ring, Weights weights, bool leavesThePolygon)
{
  ASSERT_EQ(InvertedFanTriangles(MakeVec3(0, 0, 0), ring), 0);
  const FanResult unguarded = SmoothFan(ring, weights, false);
  EXPECT_GE(InvertedFanTriangles(unguarded.center, ring), 1) << weights << " moved the centre to " << unguarded.center;
  EXPECT_EQ(InsidePolygon(unguarded.center, ring), !leavesThePolygon) << weights;
  EXPECT_GE(unguarded.report.invertedTrianglesVersusReference, 1) << weights;

  const FanResult guarded = SmoothFan(ring, weights, true);
  EXPECT_EQ(InvertedFanTriangles(guarded.center, ring), 0) << weights << " guarded centre " << guarded.center;
  EXPECT_EQ(guarded.report.invertedTrianglesVersusReference, 0) << weights;
  EXPECT_EQ(guarded.report.degenerateTriangles, 0) << weights;
  EXPECT_EQ(guarded.shortened, 1u) << weights << ": the guard shortens rather than cancels";
  EXPECT_EQ(guarded.rejected, 0u) << weights;
}

/** A level-`level` icosphere of radius 10 whose vertices are displaced by up to
 * `tangential` edge lengths along the surface and `radial` edge lengths along the
 * radius (uniform random, fixed seed). */
IndexedTriangleMesh
PerturbedIcosphere(std::mt19937 & rng, unsigned int level, double tangential, double radial)
{
  IndexedTriangleMesh m = MakeIcosphere(level, 10.0);
  const double        edge = itk::MeshExtraction::Norm(m.points[m.triangles[0][0]] - m.points[m.triangles[0][1]]);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (auto & p : m.points)
  {
    const Vec3 n = p * (1.0 / itk::MeshExtraction::Norm(p));
    Vec3       t = MakeVec3(u(rng), u(rng), u(rng));
    t -= n * itk::MeshExtraction::Dot(t, n);
    p += t * (tangential * edge) + n * (radial * edge * u(rng));
  }
  return m;
}

/** A marching-cubes sphere: ITK's BinaryMask3DMeshSource on a mask of the sphere
 * of radius 15 voxels (1 mm) centred off the voxel grid. */
struct MarchingCubesSphere
{
  QEMeshType::Pointer                 mesh;
  itk::SphereImplicitSurface::Pointer sphere;
};

const MarchingCubesSphere &
GetMarchingCubesSphere()
{
  static MarchingCubesSphere fixture = [] {
    using ImageType = itk::Image<unsigned char, 3>;
    MarchingCubesSphere f;
    f.sphere = itk::SphereImplicitSurface::New();
    itk::Point<double, 3> center;
    center.Fill(18.8);
    f.sphere->SetCenter(center);
    f.sphere->SetRadius(15.0);
    auto source = itk::ImplicitSurfaceImageSource<ImageType>::New();
    source->SetSurface(f.sphere);
    ImageType::SizeType size;
    size.Fill(38);
    source->SetSize(size);
    source->SetImageMode(itk::MeshExtractionEnums::PhantomImage::BinaryMask);
    auto mc = itk::BinaryMask3DMeshSource<ImageType, QEMeshType>::New();
    mc->SetInput(source->GetOutput());
    mc->SetObjectValue(1);
    mc->Update();
    f.mesh = mc->GetOutput();
    f.mesh->DisconnectPipeline();
    return f;
  }();
  return fixture;
}

template <typename TMesh>
double
MaximumPointDifference(const TMesh * a, const TMesh * b)
{
  double d = 0.0;
  for (auto it = a->GetPoints()->Begin(); it != a->GetPoints()->End(); ++it)
  {
    d = std::max(d, itk::MeshExtraction::Norm(itk::MeshExtraction::ToVec3(it.Value()) - PointOf(b, it.Index())));
  }
  return d;
}
} // namespace

// ------------------------------------------------------------------------------
// The counterexamples of the thesis: unguarded smoothing inverts, guarded never.
// ------------------------------------------------------------------------------
TEST(LaplacianSmoothingQuadEdgeMeshFilter, ConcaveOneRingOfFigure2_15InvertsWithoutGuardAndNeverWithIt)
{
  ExpectCounterexample(ConcaveRingOfFigure2_15(), Weights::Uniform, true);
}

TEST(LaplacianSmoothingQuadEdgeMeshFilter, InverseEdgeLengthCounterexampleOfFigure4_5bInvertsWithoutGuardOnly)
{
  ExpectCounterexample(InverseEdgeLengthRingOfFigure4_5b(), Weights::InverseEdgeLength, true);
}

TEST(LaplacianSmoothingQuadEdgeMeshFilter, AngleBisectorCounterexampleOfFigure4_5aInvertsWithoutGuardOnly)
{
  const auto ring = AngleBisectorRingOfFigure4_5a();
  // The plain average stays in the kernel of this ring: the angle-based weights are to blame.
  EXPECT_EQ(InvertedFanTriangles(SmoothFan(ring, Weights::Uniform, false).center, ring), 0);
  ExpectCounterexample(ring, Weights::AngleBisector, false);
}

TEST(LaplacianSmoothingQuadEdgeMeshFilter, CentroidSmoothingOfTheConcaveRingStillNeedsTheGuard)
{
  // Figure 4.7: centroid smoothing does not prevent every inversion. On the ring of
  // Figure 4.5(b) even 2/3 of the uniform move ends in the notch.
  const auto ring = InverseEdgeLengthRingOfFigure4_5b();
  const auto input = ToITKMesh<QEMeshType>(MakeFan(MakeVec3(0, 0, 0), ring));
  for (bool guard : { false, true })
  {
    auto filter = LaplacianType::New();
    filter->SetInput(input);
    filter->SetMovementConstraint(Constraint::Centroid);
    filter->SetPreventInversions(guard);
    filter->Update();
    const auto report = Analyze<QEMeshType>(filter->GetOutput(), input);
    if (guard)
    {
      EXPECT_EQ(report.invertedTrianglesVersusReference, 0);
      EXPECT_EQ(filter->GetNumberOfShortenedMoves(), 1u);
    }
    else
    {
      EXPECT_GE(report.invertedTrianglesVersusReference, 1);
    }
  }
}

// ------------------------------------------------------------------------------
// The guarantee on many random meshes.
// ------------------------------------------------------------------------------
TEST(LaplacianSmoothingQuadEdgeMeshFilter, GuardedSmoothingOfAThousandPerturbedClosedMeshesNeverInvertsOrDegenerates)
{
  // 1000 coarse spheres (42 vertices) with strong random displacements, smoothed
  // for 3 iterations with every combination of weights, update, constraint and
  // volume preservation. Every iteration is checked against the mesh before it
  // (one-iteration filters in a chain do exactly what one filter with
  // NumberOfIterations = 3 does): no triangle turns by 90 degrees or more, none
  // degenerates, the surface stays closed and manifold, and wherever it does not
  // intersect itself no triangle faces into the volume.
  // The guard is local: it cannot see a vertex pass through a non-adjacent part of
  // the surface, and on these spiky meshes that happens a few times (counted).
  std::mt19937       rng(20240501);
  const int          meshes = 1000;
  int                tested = 0;
  int                selfIntersecting = 0;
  itk::SizeValueType guardInterventions = 0;
  int                unguardedDamaged = 0;
  for (int k = 0; k < meshes; ++k)
  {
    QEMeshType::Pointer mesh = ToITKMesh<QEMeshType>(PerturbedIcosphere(rng, 1, 0.45, 0.25));
    if (!Analyze<QEMeshType>(mesh).IsValidClosedSurface())
    {
      continue; // the perturbation itself folded the mesh
    }
    ++tested;
    const QEMeshType::Pointer input = mesh;
    const Weights             weights = AllWeights[k % 5];
    const Update              update = (k / 5) % 2 ? Update::Immediate : Update::Batch;
    const Constraint          constraint = static_cast<Constraint>((k / 10) % 3);
    const bool                volume = (k / 30) % 2 == 1;
    for (int iteration = 0; iteration < 3; ++iteration)
    {
      auto filter = LaplacianType::New();
      filter->SetInput(mesh);
      filter->SetWeights(weights);
      filter->SetUpdateMode(update);
      filter->SetMovementConstraint(constraint);
      filter->SetVolumePreservation(volume);
      filter->SetNumberOfWorkUnits(1);
      filter->Update();
      const auto report = Analyze<QEMeshType>(filter->GetOutput(), mesh);
      ASSERT_EQ(report.invertedTrianglesVersusReference, 0)
        << "mesh " << k << ", iteration " << iteration << ": " << weights << ' ' << update << ' ' << constraint;
      ASSERT_EQ(report.degenerateTriangles, 0) << "mesh " << k << ", iteration " << iteration;
      ASSERT_EQ(report.nonManifoldEdges + report.nonManifoldVertices + report.boundaryEdges, 0);
      if (report.selfIntersectingPairs == 0)
      {
        ASSERT_EQ(report.invertedTrianglesVersusOutward, 0) << "mesh " << k << ", iteration " << iteration;
      }
      else
      {
        ++selfIntersecting;
        break;
      }
      guardInterventions += filter->GetNumberOfShortenedMoves() + filter->GetNumberOfRejectedMoves();
      mesh = filter->GetOutput();
      mesh->DisconnectPipeline();
    }

    if (k % 10 == 0)
    {
      auto filter = LaplacianType::New();
      filter->SetInput(input);
      filter->SetWeights(weights);
      filter->SetUpdateMode(update);
      filter->SetMovementConstraint(constraint);
      filter->SetNumberOfIterations(3);
      filter->SetPreventInversions(false);
      filter->Update();
      const auto unguarded = Analyze<QEMeshType>(filter->GetOutput(), input);
      unguardedDamaged += !unguarded.IsValidClosedSurface() || unguarded.invertedTrianglesVersusReference > 0;
    }
  }
  EXPECT_GT(tested, meshes * 9 / 10);
  // The meshes are hard enough that the guard had to act, and that unguarded
  // smoothing damages some of them.
  EXPECT_GT(guardInterventions, 100u);
  EXPECT_GT(unguardedDamaged, 5);
  EXPECT_LE(selfIntersecting, tested / 200);
  std::cout << tested << " valid perturbed meshes; the guard shortened or rejected " << guardInterventions << " moves; "
            << selfIntersecting << " guarded results intersect themselves; without the guard " << unguardedDamaged
            << " of " << (meshes + 9) / 10 << " were damaged\n";
}

TEST(LaplacianSmoothingQuadEdgeMeshFilter, GuardHoldsOnSurfaceNetsMeshesStoredInFloatCoordinates)
{
  // SurfaceNets meshes of smooth random volumes (MakeRandomSmoothVolume), without
  // relaxation (nodes at cell centres: many right angles) or with SNERT, one
  // iteration in every mode. QuadEdgeMesh<double, 3> stores float coordinates, and
  // the guard must check the rounded positions the mesh keeps: when it checked the
  // unrounded ones (GCC 12 dropped the round trip to float), the Immediate update
  // of seeds 5, 65 and 125 left a triangle turned by just over 90 degrees.
  std::vector<unsigned int> seeds(70);
  std::iota(seeds.begin(), seeds.end(), 0u);
  seeds.push_back(125u);
  int tested = 0;
  for (unsigned int seed : seeds)
  {
    const QEMeshType::Pointer input = RandomSurfaceNetsMesh(seed);
    if (!input)
    {
      continue; // nothing inside or nothing outside
    }
    ++tested;
    auto filter = SeededLaplacian(input, seed);
    filter->Update();
    const auto report = Analyze<QEMeshType>(filter->GetOutput(), input, false);
    EXPECT_EQ(report.invertedTrianglesVersusReference, 0) << "seed " << seed;
    EXPECT_EQ(report.degenerateTriangles, 0) << "seed " << seed;
    EXPECT_TRUE(report.IsClosed() && report.IsManifold() && report.IsConsistentlyOriented()) << "seed " << seed;
  }
  EXPECT_GE(tested, 65);
}

TEST(LaplacianSmoothingQuadEdgeMeshFilter, TenIterationsKeepEverySmallComponentWholeAndFacingOut)
{
  // The seeds of the stress runs (StressRuns.DISABLED_RandomSmoothVolumes, 0-300) on
  // which ten iterations, each within the checks, left a one-voxel component shrunk to
  // a speck (70) or a cavity that a surface had moved past in one step, now outside the
  // object and facing inward (155, 206, 298). The components' reference volumes and
  // nesting (ComponentReference) undo those moves.
  for (const unsigned int seed : { 70u, 155u, 206u, 298u })
  {
    const QEMeshType::Pointer input = RandomSurfaceNetsMesh(seed);
    ASSERT_NE(input, nullptr);
    auto filter = SeededLaplacian(input, seed);
    filter->SetNumberOfIterations(10);
    filter->Update();
    const auto before = Analyze<QEMeshType>(input);
    const auto report = Analyze<QEMeshType>(filter->GetOutput());
    EXPECT_TRUE(report.IsValidClosedSurface())
      << "seed " << seed << ": inverted (outward) " << report.invertedTrianglesVersusOutward;
    EXPECT_EQ(report.connectedComponents, before.connectedComponents) << "seed " << seed;
    EXPECT_GT(filter->GetNumberOfUndoneMoves(), 0u) << "seed " << seed;
  }
}

TEST(LaplacianSmoothingQuadEdgeMeshFilter, TenIterationsKeepARandomSurfaceFreeOfSelfIntersections)
{
  // Ten iterations on SurfaceNets meshes of smooth random volumes (valid closed
  // surfaces with many small components): the vertex-by-vertex guard alone let 47 of
  // 100 cross themselves (a stress run; 13 of these 20 seeds), Taubin 2 of 100
  // (seeds 42, 72). PreventSelfIntersections (the default) undoes those moves.
  int tested = 0;
  int crossedWithoutPrevention = 0;
  for (unsigned int seed = 0; seed < 20; ++seed)
  {
    const QEMeshType::Pointer input = RandomSurfaceNetsMesh(seed);
    if (!input)
    {
      continue; // nothing inside or nothing outside
    }
    ++tested;
    for (const bool prevent : { true, false })
    {
      auto filter = SeededLaplacian(input, seed);
      filter->SetNumberOfIterations(10);
      filter->SetPreventSelfIntersections(prevent);
      filter->Update();
      const auto report = Analyze<QEMeshType>(filter->GetOutput());
      if (prevent)
      {
        EXPECT_EQ(report.selfIntersectingPairs, 0) << "seed " << seed;
        EXPECT_EQ(report.degenerateTriangles, 0) << "seed " << seed;
      }
      else
      {
        crossedWithoutPrevention += report.selfIntersectingPairs > 0 ? 1 : 0;
        EXPECT_EQ(filter->GetNumberOfUndoneMoves(), 0u);
      }
    }
  }
  EXPECT_GE(tested, 18);
  EXPECT_GE(crossedWithoutPrevention, 8);
  for (unsigned int seed : { 42u, 72u })
  {
    auto taubin = itk::TaubinSmoothingQuadEdgeMeshFilter<QEMeshType>::New();
    taubin->SetInput(RandomSurfaceNetsMesh(seed));
    taubin->Update();
    EXPECT_EQ(Analyze<QEMeshType>(taubin->GetOutput()).selfIntersectingPairs, 0) << "Taubin, seed " << seed;
    EXPECT_GT(taubin->GetNumberOfUndoneMoves(), 0u) << "Taubin, seed " << seed;
  }
}

// ------------------------------------------------------------------------------
// Volume, shrinkage and accuracy on spheres.
// ------------------------------------------------------------------------------
TEST(LaplacianSmoothingQuadEdgeMeshFilter, VolumePreservationKeepsSphereVolumeWithinOnePercentOver20Iterations)
{
  const auto & mc = GetMarchingCubesSphere();
  const double volume = Analyze<QEMeshType>(mc.mesh, nullptr, false).enclosedVolume;
  double       lossWithout = 0.0;
  for (bool preserve : { false, true })
  {
    for (Update update : { Update::Batch, Update::Immediate })
    {
      auto filter = LaplacianType::New();
      filter->SetInput(mc.mesh);
      filter->SetVolumePreservation(preserve);
      filter->SetUpdateMode(update);
      filter->SetNumberOfIterations(20);
      filter->Update();
      const auto   report = Analyze<QEMeshType>(filter->GetOutput(), mc.mesh.GetPointer(), false);
      const double change = (report.enclosedVolume - volume) / volume;
      EXPECT_TRUE(report.IsValidClosedSurface());
      EXPECT_EQ(report.invertedTrianglesVersusReference, 0);
      if (preserve)
      {
        EXPECT_LT(std::abs(change), 0.01) << update;
      }
      else
      {
        EXPECT_LT(change, -0.03) << "uniform Laplacian smoothing shrinks (" << update << ")";
        lossWithout = std::max(lossWithout, -change);
      }
    }
  }
  EXPECT_GT(lossWithout, 0.03);
}


TEST(LaplacianSmoothingQuadEdgeMeshFilter, SmoothingMarchingCubesSphereRaisesQAreaAndStaysWithinAQuarterVoxel)
{
  // Bound: after 10 iterations the vertices of centroid- and safe-smoothed meshes
  // are on average within 0.25 voxel of the exact sphere and nowhere farther than
  // the 0.5 voxel the marching-cubes vertices themselves may be off.
  const auto & mc = GetMarchingCubesSphere();
  const auto   before = Analyze<QEMeshType>(mc.mesh);
  ASSERT_TRUE(before.IsValidClosedSurface()); // BinaryMask3DMeshSource gives a clean sphere here
  for (Constraint constraint : { Constraint::Centroid, Constraint::Safe })
  {
    for (Weights weights : { constraint == Constraint::Centroid ? Weights::Uniform : Weights::Area })
    {
      auto filter = LaplacianType::New();
      filter->SetInput(mc.mesh);
      filter->SetMovementConstraint(constraint);
      filter->SetWeights(weights);
      filter->SetNumberOfIterations(10);
      filter->Update();
      const auto after = Analyze<QEMeshType>(filter->GetOutput(), mc.mesh.GetPointer());
      EXPECT_GT(after.qArea.mean, before.qArea.mean + 0.02) << constraint << ' ' << weights;
      EXPECT_TRUE(after.IsValidClosedSurface()) << constraint << ' ' << weights;
      EXPECT_EQ(after.invertedTrianglesVersusReference, 0);
      auto distance = itk::MeshSurfaceDistanceCalculator<QEMeshType>::New();
      distance->SetMesh(filter->GetOutput());
      distance->SetReferenceSurface(mc.sphere);
      distance->Compute();
      EXPECT_LT(distance->GetVertexDistance().mean, 0.25) << constraint << ' ' << weights;
      EXPECT_LT(distance->GetVertexDistance().maximum, 0.5) << constraint << ' ' << weights;
    }
  }
}

// ------------------------------------------------------------------------------
// The parts of a move.
// ------------------------------------------------------------------------------
TEST(LaplacianSmoothingQuadEdgeMeshFilter, CentroidConstraintMovesTwoThirdsOfTheLaplacianMove)
{
  std::mt19937 rng(7);
  const auto   input = ToITKMesh<QEMeshDType>(PerturbedIcosphere(rng, 2, 0.2, 0.1));
  auto         plain = LaplacianDType::New();
  plain->SetInput(input);
  plain->SetPreventInversions(false);
  plain->Update();
  auto centroid = LaplacianDType::New();
  centroid->SetInput(input);
  centroid->SetPreventInversions(false);
  centroid->SetMovementConstraint(Constraint::Centroid);
  centroid->Update();
  for (auto it = input->GetPoints()->Begin(); it != input->GetPoints()->End(); ++it)
  {
    const Vec3 v = itk::MeshExtraction::ToVec3(it.Value());
    const Vec3 sl = PointOf(plain->GetOutput(), it.Index());
    ITK_EXPECT_VECTOR_NEAR(PointOf(centroid->GetOutput(), it.Index()), v * (1.0 / 3.0) + sl * (2.0 / 3.0), 1e-12);
  }
}

TEST(LaplacianSmoothingQuadEdgeMeshFilter, SafeConstraintClipsEveryMoveToTheNearestNeighbourDistance)
{
  // Figure 4.8: a vertex close to one neighbour, far from the average of all.
  const std::vector<Vec3> ring = {
    MakeVec3(0.3, 0, 0), MakeVec3(4, 3, 0), MakeVec3(-4, 3, 0), MakeVec3(-4, -3, 0), MakeVec3(4, -3, 0)
  };
  const auto input = ToITKMesh<QEMeshDType>(MakeFan(MakeVec3(0, 0, 0), ring));
  auto       filter = LaplacianDType::New();
  filter->SetInput(input);
  filter->SetMovementConstraint(Constraint::Safe);
  filter->SetPreventInversions(false);
  filter->Update();
  // The average is (0.06, 0, 0)... of length 0.06 < 0.3: not clipped.
  ITK_EXPECT_VECTOR_NEAR(PointOf(filter->GetOutput(), 0), MakeVec3(0.06, 0, 0), 1e-12);

  const std::vector<Vec3> far = {
    MakeVec3(0.3, 0, 0), MakeVec3(6, 3, 0), MakeVec3(-1, 3, 0), MakeVec3(-1, -3, 0), MakeVec3(6, -3, 0)
  };
  filter->SetInput(ToITKMesh<QEMeshDType>(MakeFan(MakeVec3(0, 0, 0), far)));
  filter->Update();
  // The average (2.06, 0, 0) is clipped to the nearest neighbour distance 0.3.
  ITK_EXPECT_VECTOR_NEAR(PointOf(filter->GetOutput(), 0), MakeVec3(0.3, 0, 0), 1e-12);
}

TEST(LaplacianSmoothingQuadEdgeMeshFilter, RelaxationFactorScalesTheMove)
{
  const auto input = ToITKMesh<QEMeshDType>(MakeFan(MakeVec3(0.5, 0.25, 0), ConcaveRingOfFigure2_15()));
  auto       filter = LaplacianDType::New();
  filter->SetInput(input);
  filter->SetRelaxationFactor(0.25);
  filter->SetPreventInversions(false);
  filter->Update();
  // Average of the ring: (1.4, 0, 0).
  ITK_EXPECT_VECTOR_NEAR(PointOf(filter->GetOutput(), 0), MakeVec3(0.5 + 0.25 * 0.9, 0.25 - 0.25 * 0.25, 0), 1e-12);
}

// ------------------------------------------------------------------------------
// Reuse of ITK, determinism, boundaries.
// ------------------------------------------------------------------------------
TEST(LaplacianSmoothingQuadEdgeMeshFilter, UniformBatchStepEqualsITKSmoothingQuadEdgeMeshFilter)
{
  std::mt19937                             rng(11);
  const auto                               input = ToITKMesh<QEMeshDType>(PerturbedIcosphere(rng, 2, 0.2, 0.1));
  itk::OnesMatrixCoefficients<QEMeshDType> ones;
  auto                                     itkFilter = itk::SmoothingQuadEdgeMeshFilter<QEMeshDType>::New();
  itkFilter->SetInput(input);
  itkFilter->SetCoefficientsMethod(&ones);
  itkFilter->SetNumberOfIterations(1); // ITK reuses its buffer from the 2nd iteration on
  itkFilter->SetRelaxationFactor(0.7);
  itkFilter->Update();
  auto filter = LaplacianDType::New();
  filter->SetInput(input);
  filter->SetRelaxationFactor(0.7);
  filter->SetPreventInversions(false);
  filter->Update();
  EXPECT_LT(MaximumPointDifference(filter->GetOutput(), itkFilter->GetOutput()), 1e-12);
}

TEST(LaplacianSmoothingQuadEdgeMeshFilter, ITKMatrixCoefficientsReproduceTheBuiltInWeights)
{
  std::mt19937                             rng(12);
  const auto                               input = ToITKMesh<QEMeshDType>(PerturbedIcosphere(rng, 2, 0.2, 0.1));
  itk::OnesMatrixCoefficients<QEMeshDType> ones;
  itk::InverseEuclideanDistanceMatrixCoefficients<QEMeshDType>           inverse;
  itk::ConformalMatrixCoefficients<QEMeshDType>                          conformal;
  const std::pair<Weights, const itk::MatrixCoefficients<QEMeshDType> *> pairs[] = {
    { Weights::Uniform, &ones }, { Weights::InverseEdgeLength, &inverse }, { Weights::Cotangent, &conformal }
  };
  for (const auto & pair : pairs)
  {
    for (Update update : { Update::Batch, Update::Immediate })
    {
      auto builtIn = LaplacianDType::New();
      builtIn->SetInput(input);
      builtIn->SetWeights(pair.first);
      builtIn->SetUpdateMode(update);
      builtIn->SetNumberOfIterations(3);
      builtIn->Update();
      auto viaITK = LaplacianDType::New();
      viaITK->SetInput(input);
      viaITK->SetCoefficientsMethod(pair.second);
      viaITK->SetUpdateMode(update);
      viaITK->SetNumberOfIterations(3);
      viaITK->Update();
      EXPECT_LT(MaximumPointDifference(builtIn->GetOutput(), viaITK->GetOutput()), 1e-9) << pair.first << ' ' << update;
    }
  }
}

TEST(LaplacianSmoothingQuadEdgeMeshFilter, BatchResultDoesNotDependOnTheNumberOfThreads)
{
  const auto &        mc = GetMarchingCubesSphere();
  QEMeshType::Pointer outputs[2];
  const unsigned int  workUnits[2] = { 1, 4 };
  for (int i = 0; i < 2; ++i)
  {
    auto filter = LaplacianType::New();
    filter->SetInput(mc.mesh);
    filter->SetWeights(Weights::Cotangent);
    filter->SetNumberOfIterations(3);
    filter->SetNumberOfWorkUnits(workUnits[i]);
    filter->Update();
    outputs[i] = filter->GetOutput();
    outputs[i]->DisconnectPipeline();
  }
  EXPECT_EQ(MaximumPointDifference(outputs[0].GetPointer(), outputs[1].GetPointer()), 0.0);
}

TEST(LaplacianSmoothingQuadEdgeMeshFilter, ImmediateUpdateIsRepeatableAndDiffersFromBatch)
{
  std::mt19937 rng(13);
  const auto   input = ToITKMesh<QEMeshType>(PerturbedIcosphere(rng, 2, 0.2, 0.1));
  auto         run = [&](Update update) {
    auto filter = LaplacianType::New();
    filter->SetInput(input);
    filter->SetUpdateMode(update);
    filter->SetNumberOfIterations(2);
    filter->Update();
    QEMeshType::Pointer out = filter->GetOutput();
    out->DisconnectPipeline();
    return out;
  };
  const auto immediate1 = run(Update::Immediate);
  const auto immediate2 = run(Update::Immediate);
  const auto batch = run(Update::Batch);
  EXPECT_EQ(MaximumPointDifference(immediate1.GetPointer(), immediate2.GetPointer()), 0.0);
  EXPECT_GT(MaximumPointDifference(immediate1.GetPointer(), batch.GetPointer()), 1e-3);
}

TEST(LaplacianSmoothingQuadEdgeMeshFilter, BoundaryVerticesStayFixedByDefault)
{
  IndexedTriangleMesh                    grid = MakeGrid(6);
  std::mt19937                           rng(3);
  std::uniform_real_distribution<double> u(-0.2, 0.2);
  for (auto & p : grid.points)
  {
    p += MakeVec3(u(rng), u(rng), u(rng));
  }
  const auto input = ToITKMesh<QEMeshType>(grid);
  for (bool fix : { true, false })
  {
    auto filter = LaplacianType::New();
    filter->SetInput(input);
    filter->SetFixBoundary(fix);
    filter->SetNumberOfIterations(5);
    filter->Update();
    double boundaryMove = 0.0;
    for (unsigned int j = 0; j <= 6; ++j)
    {
      for (unsigned int i = 0; i <= 6; ++i)
      {
        if (i == 0 || j == 0 || i == 6 || j == 6)
        {
          const auto id = j * 7 + i;
          boundaryMove =
            std::max(boundaryMove,
                     itk::MeshExtraction::Norm(PointOf(filter->GetOutput(), id) - PointOf(input.GetPointer(), id)));
        }
      }
    }
    const auto report = Analyze<QEMeshType>(filter->GetOutput(), input.GetPointer());
    EXPECT_EQ(report.invertedTrianglesVersusReference, 0);
    EXPECT_EQ(report.degenerateTriangles, 0);
    if (fix)
    {
      EXPECT_EQ(boundaryMove, 0.0);
      EXPECT_EQ(filter->GetNumberOfMovableVertices(), 25u);
    }
    else
    {
      EXPECT_GT(boundaryMove, 0.01);
      EXPECT_EQ(filter->GetNumberOfMovableVertices(), 49u);
    }
  }
}

TEST(LaplacianSmoothingQuadEdgeMeshFilter, ZeroIterationsCopyTheInput)
{
  const auto input = ToITKMesh<QEMeshType>(MakeIcosphere(1));
  auto       filter = LaplacianType::New();
  filter->SetInput(input);
  filter->SetNumberOfIterations(0);
  filter->Update();
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), input->GetNumberOfPoints());
  EXPECT_EQ(filter->GetOutput()->GetNumberOfFaces(), input->GetNumberOfFaces());
  EXPECT_EQ(MaximumPointDifference(filter->GetOutput(), input.GetPointer()), 0.0);
}

// ------------------------------------------------------------------------------
// Bad input.
// ------------------------------------------------------------------------------
TEST(LaplacianSmoothingQuadEdgeMeshFilter, ThrowsWithoutInput)
{
  auto filter = LaplacianType::New();
  EXPECT_THROW(filter->Update(), itk::ExceptionObject);
}

TEST(LaplacianSmoothingQuadEdgeMeshFilter, ThrowsOnANonTriangleFace)
{
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
  auto filter = LaplacianType::New();
  filter->SetInput(mesh);
  try
  {
    filter->Update();
    FAIL() << "no exception for a quadrilateral face";
  }
  catch (const itk::ExceptionObject & e)
  {
    EXPECT_NE(std::string(e.GetDescription()).find("triangle mesh"), std::string::npos) << e.GetDescription();
  }
}

TEST(LaplacianSmoothingQuadEdgeMeshFilter, ThrowsOnParametersOutOfRange)
{
  const auto input = ToITKMesh<QEMeshType>(MakeIcosphere(1));
  auto       expectThrow = [&](const std::function<void(LaplacianType *)> & set, const char * what) {
    auto filter = LaplacianType::New();
    filter->SetInput(input);
    set(filter);
    try
    {
      filter->Update();
      ADD_FAILURE() << "no exception for " << what;
    }
    catch (const itk::ExceptionObject & e)
    {
      EXPECT_NE(std::string(e.GetDescription()).find(what), std::string::npos) << e.GetDescription();
    }
  };
  expectThrow([](LaplacianType * f) { f->SetNumberOfIterations(-1); }, "NumberOfIterations");
  expectThrow([](LaplacianType * f) { f->SetRelaxationFactor(0.0); }, "RelaxationFactor");
  expectThrow([](LaplacianType * f) { f->SetRelaxationFactor(1.5); }, "RelaxationFactor");
  expectThrow([](LaplacianType * f) { f->SetRelaxationFactor(std::nan("")); }, "RelaxationFactor");
  expectThrow([](LaplacianType * f) { f->SetDegenerateQAreaTolerance(-0.1); }, "DegenerateQAreaTolerance");
  expectThrow([](LaplacianType * f) { f->SetWeights(static_cast<Weights>(17)); }, "Weights");
}

TEST(LaplacianSmoothingQuadEdgeMeshFilter, PrintSelfNamesEveryParameter)
{
  auto filter = LaplacianType::New();
  EXPECT_STREQ(filter->GetNameOfClass(), "LaplacianSmoothingQuadEdgeMeshFilter");
  std::ostringstream os;
  filter->Print(os);
  for (const char * name : { "Weights",
                             "UpdateMode",
                             "MovementConstraint",
                             "RelaxationFactor",
                             "NumberOfIterations",
                             "VolumePreservation",
                             "PreventInversions",
                             "MaximumNumberOfShortenings",
                             "DegenerateQAreaTolerance",
                             "FixBoundary",
                             "NumberOfRejectedMoves" })
  {
    EXPECT_NE(os.str().find(name), std::string::npos) << name;
  }
}
