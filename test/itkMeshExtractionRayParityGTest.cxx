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
// The ray-parity tests of itkMeshExtractionRayParity.h (internal): the nesting of
// closed components.

#include "itkMeshExtractionRayParity.h"
#include "itkMeshExtractionGeodesicSphere.h"
#include "itkMeshExtractionTestHelpers.h"

#include "gtest/gtest.h"

namespace
{
namespace ME = itk::MeshExtraction;
using ME::Vec3;
using MeshExtractionTest::Append;
} // namespace

TEST(ScaleSpaceEdgeDetection, ComponentNestingParityCountsTheSurfacesAroundEachComponent)
{
  const Vec3              center = ME::MakeVec3(10.0, 10.0, 10.0);
  ME::IndexedTriangleMesh mesh = ME::MakeGeodesicSphere(2, center, 8.0);
  EXPECT_TRUE(ME::detail::ComponentNestingParity(mesh, ME::BuildMeshTopology(mesh)).empty()); // one component
  Append(mesh, ME::MakeGeodesicSphere(2, center, 4.0));                                       // inside the first
  Append(mesh, ME::MakeGeodesicSphere(1, center + ME::MakeVec3(1, 0.5, 0.25), 1.0));          // inside both
  Append(mesh, ME::MakeGeodesicSphere(1, center + ME::MakeVec3(20, 0, 0), 2.0));              // apart
  ME::IndexedTriangleMesh open = ME::MakeGeodesicSphere(1, center + ME::MakeVec3(0, 20, 0), 2.0);
  open.triangles.pop_back(); // a hole
  Append(mesh, open);
  const ME::MeshTopology topology = ME::BuildMeshTopology(mesh);
  ASSERT_EQ(topology.numberOfComponents, 5u);
  const std::vector<std::int8_t> parity = ME::detail::ComponentNestingParity(mesh, topology);
  ASSERT_EQ(parity.size(), 5u);
  const std::vector<std::int8_t> expected{ 0, 1, 0, 0, -1 }; // components in triangle order
  EXPECT_EQ(parity, expected);
}
