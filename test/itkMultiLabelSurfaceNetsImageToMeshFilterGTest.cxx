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
#include "itkMultiLabelSurfaceNetsImageToMeshFilter.h"
#include "itkSurfaceNetsImageToMeshFilter.h"
#include "itkTriangleMeshQualityCalculator.h"
#include "itkMeshExtractionMeshValidation.h"
#include "itkMeshExtractionQualityAnalysis.h"
#include "itkMeshExtractionSelfIntersections.h"
#include "itkMeshExtractionTestHelpers.h"

#include "gtest/gtest.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <random>
#include <string>
#include <vector>

namespace ME = itk::MeshExtraction;
using namespace MeshExtractionTest;

namespace
{
using LabelImage = itk::Image<unsigned short, 3>;
using FilterType = itk::MultiLabelSurfaceNetsImageToMeshFilter<LabelImage, MeshType>;

ME::detail::MultiLabelSurfaceNetParameters
IndexSpaceParameters(unsigned int workUnits = 0)
{
  ME::detail::MultiLabelSurfaceNetParameters p;
  p.indexToPhysical.SetIdentity();
  p.numberOfWorkUnits = workUnits;
  return p;
}

/** Number of 6-connected components of the voxels with index `k` (0 outside). */
std::size_t
CountComponents(const std::vector<std::uint32_t> & labels, const std::array<std::int64_t, 3> & n, std::uint32_t k)
{
  std::vector<char>         seen(labels.size(), 0);
  std::size_t               components = 0;
  std::vector<std::int64_t> stack;
  for (std::int64_t start = 0; start < static_cast<std::int64_t>(labels.size()); ++start)
  {
    if (labels[start] != k || seen[start])
    {
      continue;
    }
    ++components;
    seen[start] = 1;
    stack.push_back(start);
    while (!stack.empty())
    {
      const std::int64_t v = stack.back();
      stack.pop_back();
      const std::int64_t at[3] = { v % n[0], (v / n[0]) % n[1], v / (n[0] * n[1]) };
      for (unsigned int d = 0; d < 3; ++d)
      {
        for (int s : { -1, 1 })
        {
          std::int64_t to[3] = { at[0], at[1], at[2] };
          to[d] += s;
          if (to[d] < 0 || to[d] >= n[d])
          {
            continue;
          }
          const std::int64_t w = (to[2] * n[1] + to[1]) * n[0] + to[0];
          if (labels[w] == k && !seen[w])
          {
            seen[w] = 1;
            stack.push_back(w);
          }
        }
      }
    }
  }
  return components;
}

/** A face as the coordinates of its corners, rotated so the smallest comes first (the
 * orientation kept). */
using FaceKey = std::array<double, 9>;
FaceKey
KeyOf(const std::vector<ME::Vec3> & points, const ME::TriangleIndices & t)
{
  std::array<ME::Vec3, 3> c = { points[t[0]], points[t[1]], points[t[2]] };
  auto                    less = [](const ME::Vec3 & a, const ME::Vec3 & b) {
    return std::lexicographical_compare(&a[0], &a[0] + 3, &b[0], &b[0] + 3);
  };
  while (less(c[1], c[0]) || less(c[2], c[0]))
  {
    std::rotate(c.begin(), c.begin() + 1, c.end());
  }
  FaceKey key;
  for (unsigned int i = 0; i < 3; ++i)
  {
    for (unsigned int d = 0; d < 3; ++d)
    {
      key[3 * i + d] = c[i][d];
    }
  }
  return key;
}

/** Everything the multi-label net promises:
 * - no two faces cross (faces of one label or of two);
 * - each label's surface is closed, a 2-manifold, consistently oriented, with a positive
 *   volume, and (where `labels` is given) has Euler characteristic 2 x its
 *   6-connected components, as the label's binary net;
 * - no two faces of a label's surface cross or touch;
 * - a face between two labels is in both their surfaces, on the same nodes (the same
 *   coordinates bit for bit, except within 0.02 voxel where a label touches itself) and
 *   with opposite orientations; a face with the background in one only. */
void
ExpectValidMultiLabelNet(const ME::MultiLabelSurfaceNet &    net,
                         const std::string &                 what,
                         const std::vector<std::uint32_t> *  labels = nullptr,
                         const std::array<std::int64_t, 3> * size = nullptr,
                         double                              maximumSpacing = 1.0)
{
  ME::IndexedTriangleMesh all;
  all.points = net.points;
  all.triangles = net.triangles;
  const auto crossings = ME::detail::FindSelfIntersections(all);
  ASSERT_TRUE(crossings.empty()) << what << ": faces " << crossings[0].first << " and " << crossings[0].second
                                 << " cross";
  std::map<FaceKey, int> faces; // +1 per oriented copy, -1 per reversed copy
  for (std::size_t f = 0; f < net.triangles.size(); ++f)
  {
    ASSERT_LT(net.faceLabels[f][0], net.faceLabels[f][1]) << what;
  }
  ME::detail::TriangleMeshQualityOptions options;
  options.computeOutwardOrientation = false;
  std::size_t sharedCopies = 0;
  for (std::uint32_t k = 1; k <= net.numberOfLabels; ++k)
  {
    ME::IndexedTriangleMesh    surface;
    std::vector<std::uint32_t> nodes;
    net.LabelSurface(k, surface.points, surface.triangles, &nodes);
    // Each vertex at its node, or, where the label touches itself, a little toward its
    // own sheet (a fiftieth of the way: below 0.02 voxel).
    for (std::size_t v = 0; v < nodes.size(); ++v)
    {
      const double d = std::sqrt(ME::SquaredNorm(surface.points[v] - net.points[nodes[v]]));
      if (d != 0.0)
      {
        ASSERT_GT(net.numberOfPinchedNodes, 0u) << what << ", label " << k << ", vertex " << v;
        ASSERT_LT(d, 0.02 * maximumSpacing) << what << ", label " << k << ", vertex " << v;
      }
    }
    const auto defects = ME::FindTriangleMeshDefects(surface);
    ASSERT_FALSE(defects.Any()) << what << ", label " << k << ": " << defects.Describe(surface);
    const auto r = ME::detail::AnalyzeTriangleMesh(surface, options);
    ASSERT_TRUE(r.IsClosed()) << what << ", label " << k;
    ASSERT_EQ(r.degenerateTriangles, 0) << what << ", label " << k;
    ASSERT_GT(r.enclosedVolume, 0.0) << what << ", label " << k;
    ASSERT_EQ(r.selfIntersectingPairs, 0) << what << ", label " << k;
    if (labels != nullptr)
    {
      // Spheres only (no handles in a few voxels): one per 6-connected component of the
      // label, or fewer where the label joins across a face diagonal.
      ASSERT_EQ(r.eulerCharacteristic, 2 * r.connectedComponents) << what << ", label " << k;
      ASSERT_LE(r.connectedComponents, static_cast<std::int64_t>(CountComponents(*labels, *size, k)))
        << what << ", label " << k;
    }
    for (const auto & t : surface.triangles)
    {
      ++faces[KeyOf(net.points, { { nodes[t[0]], nodes[t[1]], nodes[t[2]] } })];
    }
  }
  // Every face of the output, in its orientation (out of the lower label), and its
  // copies in the label surfaces: the lower label's has that orientation, the higher's
  // the other.
  for (std::size_t f = 0; f < net.triangles.size(); ++f)
  {
    const auto & t = net.triangles[f];
    const auto   key = KeyOf(net.points, t);
    const auto   reversed = KeyOf(net.points, { { t[0], t[2], t[1] } });
    if (net.faceLabels[f][0] != 0)
    {
      ASSERT_EQ(faces[key], 1) << what << ", face " << f;
      ++sharedCopies;
    }
    else
    {
      ASSERT_EQ(faces.count(key) ? faces[key] : 0, 0) << what << ", face " << f;
    }
    ASSERT_EQ(faces[reversed], 1) << what << ", face " << f;
  }
  std::size_t labelFaces = 0;
  for (const auto & entry : faces)
  {
    labelFaces += static_cast<std::size_t>(entry.second);
  }
  EXPECT_EQ(labelFaces, net.triangles.size() + sharedCopies) << what;
}

LabelImage::Pointer
ToImage(const std::vector<std::uint32_t> & labels, const std::array<std::int64_t, 3> & n)
{
  auto image = MakeImage<LabelImage>(
    static_cast<unsigned int>(n[0]), static_cast<unsigned int>(n[1]), static_cast<unsigned int>(n[2]));
  std::copy(labels.begin(), labels.end(), image->GetBufferPointer());
  return image;
}

/** A ball of radius r about (c, c, c) cut into `sectors` labels 1.. by the angle about
 * the z axis (one label: the whole ball). */
std::vector<std::uint32_t>
BallSectors(std::int64_t n, double r, unsigned int sectors, double shift = 0.0)
{
  std::vector<std::uint32_t> labels(n * n * n, 0);
  const double               c = 0.5 * (n - 1) + shift;
  for (std::int64_t z = 0; z < n; ++z)
  {
    for (std::int64_t y = 0; y < n; ++y)
    {
      for (std::int64_t x = 0; x < n; ++x)
      {
        const double dx = x - c;
        const double dy = y - c;
        const double dz = z - c;
        if (dx * dx + dy * dy + dz * dz <= r * r)
        {
          const double angle = std::atan2(dy, dx) + M_PI; // [0, 2 pi]
          labels[(z * n + y) * n + x] =
            1 + std::min<std::uint32_t>(sectors - 1, static_cast<std::uint32_t>(angle / (2 * M_PI) * sectors));
        }
      }
    }
  }
  return labels;
}

} // namespace

// Every 2 x 2 x 2 block of up to 8 labels (each partition of the corners into labels,
// with and without the background among them) in a background margin.
TEST(MultiLabelSurfaceNets, EveryCellOfUpToEightLabelsGivesValidSharedSurfaces)
{
  const std::array<std::int64_t, 3> n{ { 4, 4, 4 } };
  std::array<unsigned int, 8>       block{};
  std::size_t                       partitions = 0;
  std::size_t                       pinched = 0;
  // Restricted growth strings: block[0] = 0, block[i] <= 1 + max(block[0..i-1]).
  while (true)
  {
    ++partitions;
    const unsigned int blocks = *std::max_element(block.begin(), block.end()) + 1;
    for (unsigned int withBackground = 0; withBackground < 2; ++withBackground)
    {
      if (withBackground && blocks == 1)
      {
        continue; // an empty image
      }
      std::vector<std::uint32_t> labels(64, 0);
      for (unsigned int k = 0; k < 8; ++k)
      {
        labels[((1 + ((k >> 2) & 1)) * 4 + 1 + ((k >> 1) & 1)) * 4 + 1 + (k & 1)] = block[k] + (withBackground ? 0 : 1);
      }
      const std::uint32_t K = blocks - (withBackground ? 1 : 0);
      std::string         what = "blocks";
      for (unsigned int k = 0; k < 8; ++k)
      {
        what += ' ' + std::to_string(labels[((1 + ((k >> 2) & 1)) * 4 + 1 + ((k >> 1) & 1)) * 4 + 1 + (k & 1)]);
      }
      for (unsigned int iterations : { 0u, 10u })
      {
        auto p = IndexSpaceParameters(1);
        p.maximumNumberOfIterations = iterations;
        const auto net = ME::detail::MakeMultiLabelSurfaceNet(labels.data(), n, K, p);
        ExpectValidMultiLabelNet(net, what + " iterations " + std::to_string(iterations), &labels, &n);
        if (::testing::Test::HasFatalFailure())
        {
          return;
        }
        pinched += net.numberOfPinchedNodes > 0 ? 1 : 0;
      }
    }
    // Next restricted growth string.
    int i = 7;
    for (; i > 0; --i)
    {
      const unsigned int highest = *std::max_element(block.begin(), block.begin() + i);
      if (block[i] <= highest)
      {
        ++block[i];
        std::fill(block.begin() + i + 1, block.end(), 0u);
        break;
      }
    }
    if (i == 0)
    {
      break;
    }
  }
  EXPECT_EQ(partitions, 4140u); // Bell(8)
  EXPECT_GT(pinched, 0u);       // the cases where a label touches itself across another's diagonal are among them
}

// Seeded random label volumes, every voxel drawn on its own (the hardest case for
// topology): valid shared surfaces, and the same result on one and two work units.
TEST(MultiLabelSurfaceNets, RandomLabelVolumesGiveValidSharedSurfaces)
{
  unsigned int first = 0;
  unsigned int last = 1000;
  if (const char * seeds = std::getenv("MESHEXTRACTION_MULTILABEL_SEEDS"))
  {
    std::sscanf(seeds, "%u,%u", &first, &last);
  }
  for (unsigned int seed = first; seed < last; ++seed)
  {
    std::mt19937                            rng(seed);
    const std::int64_t                      side = 4 + static_cast<std::int64_t>(seed % 6);
    const std::array<std::int64_t, 3>       n{ { side, side, side } };
    const std::uint32_t                     K = 1 + seed % 5;
    std::uniform_int_distribution<unsigned> pick(0, K);
    std::vector<std::uint32_t>              labels(side * side * side);
    for (auto & v : labels)
    {
      v = pick(rng);
    }
    for (std::uint32_t k = 1; k <= K; ++k)
    {
      labels[k - 1] = k; // every label has a voxel
    }
    const auto one = ME::detail::MakeMultiLabelSurfaceNet(labels.data(), n, K, IndexSpaceParameters(1));
    ExpectValidMultiLabelNet(one, "seed " + std::to_string(seed)); // labels with tunnels: no Euler check
    if (::testing::Test::HasFatalFailure())
    {
      return;
    }
    if (seed % 10 == 0)
    {
      const auto two = ME::detail::MakeMultiLabelSurfaceNet(labels.data(), n, K, IndexSpaceParameters(2));
      ASSERT_EQ(one.points, two.points) << "seed " << seed;
      ASSERT_EQ(one.triangles, two.triangles) << "seed " << seed;
    }
  }
}

// One label alone: the same surface as SurfaceNetsImageToMeshFilter's SNA on its mask.
TEST(MultiLabelSurfaceNets, OneLabelIsTheSingleLabelSurface)
{
  const std::int64_t      N = 24;
  const auto              labels = BallSectors(N, 8.3, 1, 0.3);
  const auto              image = ToImage(labels, { { N, N, N } });
  LabelImage::SpacingType spacing;
  spacing[0] = 0.5;
  spacing[1] = 0.7;
  spacing[2] = 1.1;
  image->SetSpacing(spacing);
  auto filter = FilterType::New();
  filter->SetInput(image);
  filter->Update();
  const auto surface = filter->GetLabelSurface(1);

  auto single = itk::SurfaceNetsImageToMeshFilter<LabelImage, MeshType>::New();
  single->SetInput(image);
  single->SetClassifyByLabel(true);
  single->SetLabelValue(1);
  single->Update();
  ASSERT_EQ(filter->GetNumberOfNodesMovedBack(), 0u);
  ASSERT_EQ(single->GetNumberOfNodesMovedBack(), 0u);
  const MeshType * expected = single->GetOutput();
  ASSERT_EQ(surface->GetNumberOfPoints(), expected->GetNumberOfPoints());
  ASSERT_EQ(surface->GetNumberOfCells(), expected->GetNumberOfCells());
  auto sorted = [](const MeshType * mesh) {
    std::vector<std::array<double, 3>> points;
    for (auto it = mesh->GetPoints()->Begin(); it != mesh->GetPoints()->End(); ++it)
    {
      points.push_back({ { it.Value()[0], it.Value()[1], it.Value()[2] } });
    }
    std::sort(points.begin(), points.end());
    return points;
  };
  const auto a = sorted(surface.GetPointer());
  const auto b = sorted(expected);
  for (std::size_t i = 0; i < a.size(); ++i)
  {
    for (unsigned int d = 0; d < 3; ++d)
    {
      ASSERT_NEAR(a[i][d], b[i][d], 1e-9) << "point " << i;
    }
  }
  // Every face of the output is between the label and the background.
  for (const auto & pair : filter->GetFaceLabels())
  {
    ASSERT_EQ(pair[0], 0);
    ASSERT_EQ(pair[1], 1);
  }
}

// Two and three labels that touch (a ball cut into sectors): each label's surface is
// closed and valid, the shared faces are one set of triangles, the volumes follow the
// voxel counts, and the three-label ball has a junction line along its axis.
TEST(MultiLabelSurfaceNets, TouchingObjectsShareTheirBoundary)
{
  const std::int64_t                N = 40;
  const std::array<std::int64_t, 3> n{ { N, N, N } };
  for (unsigned int sectors : { 2u, 3u })
  {
    const auto              labels = BallSectors(N, 15.2, sectors, 0.25);
    auto                    image = ToImage(labels, n);
    LabelImage::SpacingType spacing;
    spacing.Fill(0.8);
    image->SetSpacing(spacing);
    auto filter = FilterType::New();
    filter->SetInput(image);
    filter->Update();
    ASSERT_EQ(filter->GetExtractedLabels().size(), sectors);

    auto p = IndexSpaceParameters();
    p.indexToPhysical(0, 0) = p.indexToPhysical(1, 1) = p.indexToPhysical(2, 2) = 0.8;
    const auto net = ME::detail::MakeMultiLabelSurfaceNet(labels.data(), n, sectors, p);
    ExpectValidMultiLabelNet(net, std::to_string(sectors) + " sectors", &labels, &n, 0.8);
    ASSERT_EQ(net.triangles.size(), filter->GetOutput()->GetNumberOfCells());
    if (sectors == 2)
    {
      EXPECT_EQ(net.numberOfPinchedNodes, 0u); // two half-balls: no label touches itself
    }
    if (sectors == 3)
    {
      EXPECT_GT(net.numberOfJunctionNodes, 0u);
    }
    // The ball as one label: the sectors together enclose its volume.
    std::vector<std::uint32_t> ball(labels.size());
    std::transform(labels.begin(), labels.end(), ball.begin(), [](std::uint32_t v) { return v != 0 ? 1u : 0u; });
    auto whole = itk::SurfaceNetsImageToMeshFilter<LabelImage, MeshType>::New();
    auto ballImage = ToImage(ball, n);
    ballImage->SetSpacing(image->GetSpacing());
    whole->SetInput(ballImage);
    whole->SetClassifyByLabel(true);
    whole->Update();
    double wholeVolume = 0.0;
    {
      auto calculator = itk::TriangleMeshQualityCalculator<MeshType>::New();
      calculator->SetMesh(whole->GetOutput());
      calculator->Compute();
      wholeVolume = calculator->GetReport().enclosedVolume;
    }
    double      sectorVolumes = 0.0;
    std::size_t shared = 0;
    for (const auto & pair : filter->GetFaceLabels())
    {
      shared += pair[0] != 0 ? 1 : 0;
    }
    EXPECT_GT(shared, 100u);
    for (std::uint32_t k = 1; k <= sectors; ++k)
    {
      const auto                    surface = filter->GetLabelSurface(static_cast<unsigned short>(k));
      ME::TriangleMeshQualityReport r;
      {
        auto calculator = itk::TriangleMeshQualityCalculator<MeshType>::New();
        calculator->SetMesh(surface);
        calculator->Compute();
        r = calculator->GetReport();
      }
      if (net.numberOfPinchedNodes == 0)
      {
        EXPECT_TRUE(r.IsValidClosedSurface()) << sectors << " sectors, label " << k;
      }
      const double voxels = static_cast<double>(std::count(labels.begin(), labels.end(), k)) * 0.8 * 0.8 * 0.8;
      // SNA rounds the ball's outer surface off (as for one label: a few per cent on a
      // ball of 15 voxels); the cuts between sectors stay where the voxels meet.
      EXPECT_NEAR(r.enclosedVolume / voxels, 1.0, 0.05) << sectors << " sectors, label " << k;
      sectorVolumes += r.enclosedVolume;
    }
    EXPECT_NEAR(sectorVolumes / wholeVolume, 1.0, 0.002) << sectors << " sectors";
  }
}

// A single slice (one voxel thick) of two labels side by side, and a label touching the
// image's border: closed slabs that share their faces.
TEST(MultiLabelSurfaceNets, OneSliceAndTheImageBorder)
{
  const std::array<std::int64_t, 3> n{ { 6, 5, 1 } };
  std::vector<std::uint32_t>        labels(30, 0);
  for (std::int64_t y = 0; y < 5; ++y)
  {
    for (std::int64_t x = 0; x < 6; ++x)
    {
      labels[y * 6 + x] = x < 3 ? 1 : (y > 0 ? 2 : 0);
    }
  }
  const auto net = ME::detail::MakeMultiLabelSurfaceNet(labels.data(), n, 2, IndexSpaceParameters());
  ExpectValidMultiLabelNet(net, "one slice", &labels, &n);
  std::size_t shared = 0;
  for (const auto & pair : net.faceLabels)
  {
    shared += pair[0] == 1 && pair[1] == 2 ? 1 : 0;
  }
  EXPECT_EQ(shared, 8u); // four voxel faces between the labels, two triangles each
}

TEST(MultiLabelSurfaceNets, BadInputIsRefusedWithAMessage)
{
  auto filter = FilterType::New();
  EXPECT_THROW(filter->Update(), itk::ExceptionObject); // no input
  auto background = MakeImage<LabelImage>(5, 5, 5);
  filter->SetInput(background);
  EXPECT_NE(ExceptionDescription([&] { filter->Update(); }).find("no voxel other than the background"),
            std::string::npos);
  background->SetPixel({ { 2, 2, 2 } }, 3);
  filter->SetLabels({ 3, 4 });
  EXPECT_NE(ExceptionDescription([&] { filter->Update(); }).find("No voxel has the label 4"), std::string::npos);
  filter->SetLabels({ 0, 3 });
  EXPECT_NE(ExceptionDescription([&] { filter->Update(); }).find("background value"), std::string::npos);
  filter->SetLabels({ 3 });
  filter->Update();
  EXPECT_EQ(filter->GetOutput()->GetNumberOfCells(), 12u); // one voxel: a cube of 6 quads
  EXPECT_NE(ExceptionDescription([&] { filter->GetLabelSurface(7); }).find("was not extracted"), std::string::npos);
  EXPECT_NE(ExceptionDescription([&] { filter->GetFaceLabel(12, 0); }).find("No face"), std::string::npos);
}
