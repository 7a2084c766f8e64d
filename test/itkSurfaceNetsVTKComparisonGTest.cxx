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
// SurfaceNets against VTK's extractors (thesis Table 3.1, issue 5): the methods of
// meshextraction-compare, measured by the module's calculators in ITK physical space.
// Phantoms on their default grids (64^3 voxels of 1 mm: distances in mm are voxels),
// distance maps extracted at iso 0 with the inside below.

#include "MeshExtractionVTKPeers.h"

#include "itkMeshExtractionPhantoms.h"
#include "itkMeshSurfaceDistanceCalculator.h"
#include "itkTriangleMeshQualityCalculator.h"

#include "gtest/gtest.h"

#include <cmath>
#include <sstream>

namespace MC = MeshExtractionCompare;
namespace ME = itk::MeshExtraction;

namespace
{
struct Phantom
{
  MC::ImageType::Pointer                image;
  itk::ImplicitSurfaceFunction::Pointer surface;
};

Phantom
MakePhantom(ME::PhantomShape shape, const ME::PhantomGrid & grid)
{
  auto source = ME::MakePhantomImageSource<MC::ImageType>(shape, grid);
  source->Update();
  Phantom p;
  p.image = source->GetOutput();
  p.image->DisconnectPipeline();
  p.surface = ME::MakePhantomSurface(shape, grid);
  return p;
}

Phantom
MakePhantom(ME::PhantomShape shape)
{
  return MakePhantom(shape, ME::DefaultPhantomGrid(shape));
}

/** The phantom's distance map times -1: the same surface with the inside above. */
MC::ImageType::Pointer
Negated(const MC::ImageType * image)
{
  auto out = MC::ImageType::New();
  out->SetRegions(image->GetBufferedRegion());
  out->CopyInformation(image);
  out->Allocate();
  const std::size_t n = image->GetBufferedRegion().GetNumberOfPixels();
  for (std::size_t i = 0; i < n; ++i)
  {
    out->GetBufferPointer()[i] = -image->GetBufferPointer()[i];
  }
  return out;
}

/** One method's mesh, measured as meshextraction-compare measures it. */
struct Measured
{
  std::string                   key;
  ME::TriangleMeshQualityReport quality;
  ME::MeshSurfaceDistanceReport distance;

  std::string
  Text() const
  {
    std::ostringstream os;
    os << key << ": " << quality.numberOfTriangles << " triangles, q_angle " << quality.qAngle.mean << ", q_area "
       << quality.qArea.mean << ", vertex distance " << distance.vertices.mean << " (max " << distance.vertices.maximum
       << "), face-centroid distance " << distance.faceCentroids.mean << ", valid " << quality.IsValidClosedSurface()
       << ", inverted " << quality.invertedTrianglesVersusOutward;
    return os.str();
  }
};

Measured
ExtractAndMeasure(const std::string &                  key,
                  const MC::ImageType *                image,
                  const itk::ImplicitSurfaceFunction * surface,
                  bool                                 insideIsAbove = false)
{
  MC::ExtractionInput input;
  input.image = image;
  input.isoValue = 0.0;
  input.insideIsAboveIsoValue = insideIsAbove;
  const ME::IndexedTriangleMesh triangles = MC::MeshForMeasurement(MC::FindMethod(key).run(input));
  auto                          mesh = MC::MeshType::New();
  ME::FillMesh(triangles, *mesh);

  Measured m;
  m.key = key;
  auto quality = itk::TriangleMeshQualityCalculator<MC::MeshType>::New();
  quality->SetMesh(mesh);
  quality->Compute();
  m.quality = quality->GetReport();
  auto distance = itk::MeshSurfaceDistanceCalculator<MC::MeshType>::New();
  distance->SetMesh(mesh);
  distance->SetReferenceSurface(surface);
  distance->SetSymmetric(false);
  distance->Compute();
  m.distance = distance->GetReport();
  return m;
}
} // namespace

TEST(SurfaceNetsVTKComparison, SnertHasHigherMeanQAngleThanVTKMarchingCubesOnPlaneSphereAndTwoSpheres)
{
  for (const auto shape : { ME::PhantomShape::Plane, ME::PhantomShape::Sphere, ME::PhantomShape::TwoSpheres })
  {
    const Phantom  p = MakePhantom(shape);
    const Measured mc = ExtractAndMeasure("mc", p.image, p.surface);
    const Measured snert = ExtractAndMeasure("snert", p.image, p.surface);
    EXPECT_GT(snert.quality.qAngle.mean, mc.quality.qAngle.mean) << ME::PhantomShapeName(shape) << "\n"
                                                                 << mc.Text() << "\n"
                                                                 << snert.Text();
    EXPECT_TRUE(snert.quality.IsValidClosedSurface()) << ME::PhantomShapeName(shape) << "\n" << snert.Text();
  }
}

TEST(SurfaceNetsVTKComparison, SnertSphereVerticesWithinAFiftiethOfAVoxelAndFacesAsAccurateAsMarchingCubes)
{
  const Phantom     p = MakePhantom(ME::PhantomShape::Sphere);
  const Measured    mc = ExtractAndMeasure("mc", p.image, p.surface);
  const Measured    snert = ExtractAndMeasure("snert", p.image, p.surface);
  const std::string both = mc.Text() + "\n" + snert.Text();
  EXPECT_LE(snert.distance.vertices.mean, 0.02) << both;
  // Marching cubes' vertices lie on voxel edges, where linear interpolation of the
  // distance map is nearly exact; its face centroids are what a mesh's surface is. "As
  // accurate" here: SNERT's face centroids stay within twice marching cubes' distance
  // and a few hundredths of a voxel (the Slicer pipeline's is ~0.035).
  EXPECT_LE(snert.distance.faceCentroids.mean, 2.0 * mc.distance.faceCentroids.mean) << both;
  EXPECT_LE(snert.distance.faceCentroids.mean, 0.03) << both;
}

TEST(SurfaceNetsVTKComparison, SlicerPipelineIsMeasurablyLessAccurateThanSnertOnTheSphere)
{
  const Phantom     p = MakePhantom(ME::PhantomShape::Sphere);
  const Measured    slicer = ExtractAndMeasure("fe-sinc", p.image, p.surface);
  const Measured    snert = ExtractAndMeasure("snert", p.image, p.surface);
  const std::string both = slicer.Text() + "\n" + snert.Text();
  // Windowed sinc smooths toward the centre of curvature, off the iso-surface.
  EXPECT_GE(slicer.distance.vertices.mean, 1.5 * snert.distance.vertices.mean) << both;
  EXPECT_GE(slicer.distance.vertices.mean - snert.distance.vertices.mean, 0.005) << both;
  EXPECT_GT(slicer.distance.faceCentroids.mean, snert.distance.faceCentroids.mean) << both;
  EXPECT_LT(slicer.distance.vertices.signedMean, -0.01) << both; // the sphere shrinks
}

TEST(SurfaceNetsVTKComparison, EveryMethodGivesAnOutwardClosedSphereForEitherInsideConvention)
{
  const Phantom                p = MakePhantom(ME::PhantomShape::Sphere);
  const MC::ImageType::Pointer negated = Negated(p.image);
  for (const MC::Method & method : MC::Methods())
  {
    if (!method.byDefault)
    {
      continue;
    }
    for (const bool insideIsAbove : { false, true })
    {
      const Measured m = ExtractAndMeasure(
        method.key, insideIsAbove ? negated.GetPointer() : p.image.GetPointer(), p.surface, insideIsAbove);
      EXPECT_TRUE(m.quality.IsValidClosedSurface()) << "inside above " << insideIsAbove << ": " << m.Text();
      EXPECT_EQ(m.quality.eulerCharacteristic, 2) << m.Text();
      EXPECT_LT(m.distance.vertices.mean, 0.3) << m.Text();
    }
  }
}

TEST(SurfaceNetsVTKComparison, VTKMeshesAreMappedIntoITKPhysicalSpaceOnRotatedAndMirroredGrids)
{
  // VTK's filters know spacing and origin only; the comparison maps their points
  // through the ITK direction. On a rotated, anisotropic, shifted grid, and on a
  // mirrored one, the VTK meshes must still lie on the phantom's exact surface and face
  // outward.
  const double              a = 30.0 * itk::Math::pi / 180.0;
  const double              b = 20.0 * itk::Math::pi / 180.0;
  itk::Matrix<double, 3, 3> rz;
  rz.SetIdentity();
  rz[0][0] = std::cos(a);
  rz[0][1] = -std::sin(a);
  rz[1][0] = std::sin(a);
  rz[1][1] = std::cos(a);
  itk::Matrix<double, 3, 3> rx;
  rx.SetIdentity();
  rx[1][1] = std::cos(b);
  rx[1][2] = -std::sin(b);
  rx[2][1] = std::sin(b);
  rx[2][2] = std::cos(b);
  itk::Matrix<double, 3, 3> mirror;
  mirror.SetIdentity();
  mirror[2][2] = -1.0;

  ME::PhantomGrid rotated = ME::DefaultPhantomGrid(ME::PhantomShape::TwoSpheres);
  rotated.spacing[1] = 1.3;
  rotated.spacing[2] = 0.8;
  rotated.origin[0] = 10.0;
  rotated.origin[1] = -20.0;
  rotated.origin[2] = 5.0;
  rotated.direction = rz * rx;
  ME::PhantomGrid mirrored = rotated;
  mirrored.direction = rz * mirror;

  // Bounds per method (mm; the grid's spacing is up to 1.3 mm): linear interpolation
  // is nearly exact on a distance map except at the crease where the spheres meet;
  // windowed sinc shrinks; Slicer's labelmap pipeline starts from a binary staircase.
  struct Bound
  {
    const char * key;
    double       mean;
    double       maximum;
  };
  const Bound bounds[] = {
    { "mc", 0.01, 0.25 }, { "fe", 0.01, 0.25 }, { "fe-sinc", 0.1, 0.5 }, { "slicer", 0.15, 1.0 }
  };
  for (const ME::PhantomGrid & grid : { rotated, mirrored })
  {
    const Phantom p = MakePhantom(ME::PhantomShape::TwoSpheres, grid);
    for (const Bound & bound : bounds)
    {
      const Measured m = ExtractAndMeasure(bound.key, p.image, p.surface);
      EXPECT_TRUE(m.quality.IsValidClosedSurface()) << m.Text();
      EXPECT_EQ(m.quality.invertedTrianglesVersusOutward, 0) << m.Text();
      // Ignoring the direction would put the meshes millimetres away.
      EXPECT_LT(m.distance.vertices.mean, bound.mean) << m.Text();
      EXPECT_LT(m.distance.vertices.maximum, bound.maximum) << m.Text();
    }
  }
}
