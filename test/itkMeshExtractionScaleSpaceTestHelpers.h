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
#ifndef itkMeshExtractionScaleSpaceTestHelpers_h
#define itkMeshExtractionScaleSpaceTestHelpers_h

// The images and initial meshes of the scale-space tests (thesis chapter 4), shared
// by the edge-detection and refinement tests, the Gaussian scale space's, the stress
// runs and the real-data tests.

#include "itkImage.h"
#include "itkMeshExtractionGeodesicSphere.h"
#include "itkMeshExtractionIndexedTriangleMesh.h"
#include "itkMeshExtractionPhantoms.h"
#include "itkMeshExtractionTestHelpers.h"
#include "itkQuadEdgeMesh.h"
#include "itkScaleSpaceEdgeMeshRefinementFilter.h"

namespace MeshExtractionScaleSpaceTest
{
namespace ME = itk::MeshExtraction;
using ME::Vec3;
using MeshType = itk::QuadEdgeMesh<double, 3>;
using ImageType = itk::Image<float, 3>;
using RefinementFilterType = itk::ScaleSpaceEdgeMeshRefinementFilter<MeshType, ImageType>;

inline MeshType::Pointer
ToMesh(const ME::IndexedTriangleMesh & m)
{
  auto mesh = MeshType::New();
  ME::FillMesh(m, *mesh);
  return mesh;
}

/** The chapter-4 sphere phantom on `grid` (default: thesis section 4.3, 100^3 voxels
 * of 1 mm, radius 25 mm, a step 0 -> 100 blurred by 1 mm), with optional noise. */
inline ImageType::Pointer
SphereImage(const ME::PhantomGrid & grid, double noise)
{
  const auto shape = ME::PhantomShape::Chapter4Sphere;
  auto       parameters = ME::DefaultPhantomImageParameters(shape);
  parameters.noiseStandardDeviation = noise;
  parameters.noiseSeed = 11;
  auto source = ME::MakePhantomImageSource<ImageType>(shape, grid, parameters);
  source->Update();
  return source->GetOutput();
}

inline ImageType::Pointer
Chapter4SphereImage(double noise = 0.0)
{
  return SphereImage(ME::DefaultPhantomGrid(ME::PhantomShape::Chapter4Sphere), noise);
}

inline Vec3
Chapter4SphereCenter()
{
  const auto c = ME::PhantomGridCenter(ME::DefaultPhantomGrid(ME::PhantomShape::Chapter4Sphere));
  return ME::MakeVec3(c[0], c[1], c[2]);
}

/** Like the initial mesh of thesis Table 4.1 (720 vertices, 1436 triangles, mean
 * radius 24.78, variance 0.471, mean q_area 0.76, mean minimum angle 35.4): a
 * geodesic sphere of 642 vertices and 1280 triangles with 100 random edge flips,
 * tangential jitter and radial noise, mean radius 24.78, variance 0.471. */
inline ME::IndexedTriangleMesh
InitialSphere()
{
  return ME::MakePerturbedGeodesicSphere(3, Chapter4SphereCenter(), 24.78, 0.471, 0.53, 100);
}

/** A smaller chapter-4 sphere for the tests that need no Table 4.1 numbers: size^3
 * voxels of 1 mm, and a perturbed geodesic start mesh of mean radius `radius`
 * (variance 0.2) about the grid's centre. */
struct SmallSphere
{
  unsigned int size;
  double       radius;

  ME::PhantomGrid
  Grid() const
  {
    ME::PhantomGrid grid;
    grid.size.Fill(size);
    return grid;
  }
  ImageType::Pointer
  Image(double noise = 0.0) const
  {
    return SphereImage(this->Grid(), noise);
  }
  ME::IndexedTriangleMesh
  InitialMesh() const
  {
    const auto c = ME::PhantomGridCenter(this->Grid());
    return ME::MakePerturbedGeodesicSphere(3, ME::MakeVec3(c[0], c[1], c[2]), radius, 0.2, 0.53, 100);
  }
};

/** The refinement of `input` (RandomSurfaceNetsMesh(seed)) against its own image:
 * maximum deviation 2, at most 3 cycles; not yet updated. */
inline RefinementFilterType::Pointer
RandomVolumeRefinement(unsigned int seed, const MeshType * input)
{
  double     iso = 0.0;
  const auto image = MeshExtractionTest::MakeRandomSmoothVolume(seed, iso);
  auto       filter = RefinementFilterType::New();
  filter->SetInput(input);
  filter->SetInputImage(image);
  filter->SetMaximumDeviation(2.0);
  filter->SetMaximumNumberOfCycles(3);
  return filter;
}
} // namespace MeshExtractionScaleSpaceTest

#endif
