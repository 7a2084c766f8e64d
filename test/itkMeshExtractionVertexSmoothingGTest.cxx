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
// One smoothing move of one vertex, itkMeshExtractionVertexSmoothing.h (internal): the
// Laplacian targets of every weight and the volume-preserving displacement (thesis
// sections 2.2.3-2.2.4).

#include "itkMeshExtractionVertexSmoothing.h"
#include "itkMeshExtractionTestHelpers.h"

#include "itkGTest.h"

#include <cmath>
#include <vector>

using namespace MeshExtractionTest;

namespace
{
using Weights = itk::MeshExtractionEnums::SmoothingWeights;

constexpr Weights AllWeights[] = { Weights::Uniform,
                                   Weights::InverseEdgeLength,
                                   Weights::Area,
                                   Weights::Cotangent,
                                   Weights::AngleBisector };
} // namespace

TEST(LaplacianSmoothingQuadEdgeMeshFilter, VolumePreservingMoveKeepsTheConeVolumeOfItsRing)
{
  // eq. 2.7-2.10: the cone volume sum_f v.N_f does not change when v moves.
  const std::vector<Vec3>                    ring = { MakeVec3(1, 0, 0.3),
                                                      MakeVec3(0.2, 1.1, -0.2),
                                                      MakeVec3(-1, 0.3, 0.4),
                                                      MakeVec3(-0.6, -0.9, 0.1),
                                                      MakeVec3(0.7, -0.8, -0.3) };
  itk::MeshExtraction::detail::VertexOneRing r;
  r.center = MakeVec3(0.1, -0.05, 0.6);
  r.ring = ring.data();
  r.size = ring.size();
  r.closed = true;
  auto coneVolume = [&](const Vec3 & v) {
    double sum = 0.0;
    for (std::size_t t = 0; t < ring.size(); ++t)
    {
      sum += itk::MeshExtraction::Dot(v, itk::MeshExtraction::TriangleNormal(v, r.First(t), r.Second(t)));
    }
    return sum;
  };
  itk::MeshExtraction::detail::VertexSmoothingParameters p;
  p.volumePreservation = true;
  for (Weights w : AllWeights)
  {
    const Vec3 target = itk::MeshExtraction::detail::LaplacianTarget(w, r);
    const Vec3 d = itk::MeshExtraction::detail::SmoothingDisplacement(p, r, target);
    EXPECT_GT(itk::MeshExtraction::Norm(d), 0.01) << w;
    EXPECT_NEAR(coneVolume(r.center + d), coneVolume(r.center), 1e-12) << w;
    EXPECT_NEAR(itk::MeshExtraction::Dot(d, itk::MeshExtraction::detail::OneRingNormal(r)), 0.0, 1e-12) << w;
  }
}

TEST(LaplacianSmoothingQuadEdgeMeshFilter, EveryWeightKeepsTheCentreOfARegularPlanarRing)
{
  std::vector<Vec3> ring;
  for (int i = 0; i < 6; ++i)
  {
    ring.push_back(MakeVec3(std::cos(i * itk::Math::pi / 3), std::sin(i * itk::Math::pi / 3), 0));
  }
  itk::MeshExtraction::detail::VertexOneRing r;
  r.center = MakeVec3(0, 0, 0);
  r.ring = ring.data();
  r.size = ring.size();
  for (Weights w : AllWeights)
  {
    ITK_EXPECT_VECTOR_NEAR(itk::MeshExtraction::detail::LaplacianTarget(w, r), MakeVec3(0, 0, 0), 1e-12);
  }
}
