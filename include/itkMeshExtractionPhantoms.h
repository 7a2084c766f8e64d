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
#ifndef itkMeshExtractionPhantoms_h
#define itkMeshExtractionPhantoms_h

#include "itkImplicitSurfaceFunction.h"
#include "itkImplicitSurfaceImageSource.h"
#include "itkMeshExtractionEnums.h"
#include "itkMatrix.h"
#include "itkPoint.h"
#include "itkSize.h"
#include "itkVector.h"
#include "MeshExtractionExport.h"

#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

namespace itk
{
namespace MeshExtraction
{
/** \file
 * \brief Named test objects ("phantoms") with exact surfaces, placed in an image grid.
 *
 * Every phantom is an ImplicitSurfaceFunction (exact signed distance) built by
 * MakePhantomSurface() for a PhantomGrid, and rendered by ImplicitSurfaceImageSource
 * (MakePhantomImageSource() does both with the phantom's default image settings).
 *
 * Placement rules, for every shape:
 * - C is the physical centre of the grid (the midpoint of the first and last voxel
 *   centres, PhantomGridCenter()).
 * - E is the smallest physical extent of the grid, min_k size[k] * spacing[k]
 *   (PhantomGridSmallestExtent()); sizes are fractions of E, so a phantom fits any
 *   grid and keeps its proportions.
 * - Orientations are given in the grid's frame: a direction v below means
 *   Direction * v in physical space. The voxel values of a phantom therefore do not
 *   depend on the grid's direction matrix (for a given size, spacing).
 * - Default positions avoid voxel centres lying exactly on the surface (exact zeros
 *   of the distance map are ties for iso-surface extraction).
 *
 * The shapes (E = 64 mm in the default 64^3 1 mm grid, C = (31.5, 31.5, 31.5)):
 * - Plane ("plane"): the plane with normal (1,2,3)/sqrt(14), tilted to every grid
 *   axis, through C shifted along the normal by 0.5/sqrt(14) times the smallest
 *   spacing, so that on an isotropic grid no voxel centre lies on it (the signed
 *   distances of voxel centres are (m - 1/2) spacing / sqrt(14), m integer). One of
 *   the thesis' two distance maps (chapter 3, Table 3.1).
 * - Sphere ("sphere"): centre C, radius 0.3 E (19.2 mm). The thesis' other distance
 *   map (chapter 3, Table 3.1).
 * - TwoSpheres ("two-spheres"): the union of two balls of radius 0.25 E (16 mm)
 *   whose centres are one radius apart, at C -/+ (0.125 E) (1,1,1)/sqrt(3)
 *   (thesis Figure 3.6, "two spheres partly overlapping").
 * - Chapter4Sphere ("chapter4-sphere"): centre C, radius 0.25 E, i.e. 25 mm in its
 *   default 100^3 grid of 1 mm voxels: the sphere of thesis section 4.3 / Table 4.1
 *   (the text says "diameter 25" but Table 4.1 reports mean radii of 24.8-25.0, so
 *   the radius is 25). Its default image is a blurred step (see
 *   DefaultPhantomImageParameters); the thesis' noisy variant adds noise of
 *   standard deviation 2.
 * - Ellipsoid ("ellipsoid"): centre C, semi-axes (0.35, 0.25, 0.15) E
 *   (22.4, 16, 9.6 mm), axes rotated by Rz(30 deg) Rx(20 deg) (thesis chapter 5
 *   test objects).
 * - IndentedSphere ("indented-sphere"): ball A (centre C, radius 0.3 E) minus ball B
 *   of radius 0.15 E centred on A's surface at C + 0.3 E (1,1,1)/sqrt(3): a dent
 *   0.15 E deep whose rim is a crease circle (thesis chapter 5, "a sphere with an
 *   indentation").
 * - Torus ("torus"): centre C, axis (1,1,4)/sqrt(18), major radius 0.25 E (16 mm),
 *   minor radius 0.1 E (6.4 mm): genus one.
 * - ThinPlate ("thin-plate"): a box 2 voxels thick (half-thickness = the smallest
 *   spacing) and 0.7 E wide and long, centre C, its normal tilted to
 *   (1,2,10)/sqrt(105) (about 12.6 degrees from the grid's third axis), its first
 *   edge along the grid's first axis projected onto the plate.
 * - NarrowCleft ("narrow-cleft"): a block with half-sizes (0.3, 0.3, 0.2) E
 *   (19.2, 19.2, 12.8 mm), centre C, aligned with the grid, with a slot 1.5 voxels
 *   wide (1.5 * spacing[0] across the grid's first axis) cut from its top (+third
 *   axis) through its whole second-axis extent, 0.24 E deep (60% of the block's
 *   height; 15.36 mm).
 *
 * \ingroup MeshExtraction
 */

/** The named phantoms. */
enum class PhantomShape : std::uint8_t
{
  Plane = 0,
  Sphere,
  TwoSpheres,
  Chapter4Sphere,
  Ellipsoid,
  IndentedSphere,
  Torus,
  ThinPlate,
  NarrowCleft
};

/** Writes the command-line name of the shape ("two-spheres", ...). */
MeshExtraction_EXPORT std::ostream &
                      operator<<(std::ostream & out, PhantomShape shape);

/** The command-line name: "plane", "sphere", "two-spheres", "chapter4-sphere",
 * "ellipsoid", "indented-sphere", "torus", "thin-plate", "narrow-cleft". */
MeshExtraction_EXPORT std::string
                      PhantomShapeName(PhantomShape shape);

/** The shape with that command-line name; throws an itk::ExceptionObject that lists
 * the valid names otherwise. */
MeshExtraction_EXPORT PhantomShape
PhantomShapeFromName(const std::string & name);

/** Every shape, in declaration order. */
MeshExtraction_EXPORT std::vector<PhantomShape>
                      AllPhantomShapes();

/** The valid names separated by ", " (for usage messages). */
MeshExtraction_EXPORT std::string
                      PhantomShapeNameList();

/** The image grid a phantom is placed in (the geometry of the image it is rendered
 * into). Default: 64^3 voxels of 1 mm, origin (0,0,0), identity direction. */
struct MeshExtraction_EXPORT PhantomGrid
{
  Size<3>              size;
  Vector<double, 3>    spacing;
  Point<double, 3>     origin;
  Matrix<double, 3, 3> direction;

  PhantomGrid();
};

/** 64^3 voxels of 1 mm at the origin for every shape, except Chapter4Sphere:
 * 100^3 voxels of 1 mm (thesis section 4.3). */
MeshExtraction_EXPORT PhantomGrid
DefaultPhantomGrid(PhantomShape shape);

/** The physical centre of the grid: origin + direction * (spacing .* (size - 1) / 2). */
MeshExtraction_EXPORT Point<double, 3>
                      PhantomGridCenter(const PhantomGrid & grid);

/** min_k size[k] * spacing[k]. */
MeshExtraction_EXPORT double
PhantomGridSmallestExtent(const PhantomGrid & grid);

/** The shape placed and sized for `grid` as documented above. Throws for an invalid
 * grid (zero size, non-positive spacing, non-finite origin, or a direction that is
 * not orthogonal within 1e-4). */
MeshExtraction_EXPORT ImplicitSurfaceFunction::Pointer
                      MakePhantomSurface(PhantomShape shape, const PhantomGrid & grid);

/** How a phantom is rendered by default (the settings of ImplicitSurfaceImageSource). */
struct MeshExtraction_EXPORT PhantomImageParameters
{
  MeshExtractionEnums::PhantomImage mode{ MeshExtractionEnums::PhantomImage::DistanceMap };
  double                            distanceScale{ 1.0 };
  double                            insideValue{ 1.0 };
  double                            outsideValue{ 0.0 };
  double                            edgeWidth{ 1.0 };
  double                            noiseStandardDeviation{ 0.0 };
  std::uint64_t                     noiseSeed{ 0 };
};

/** DistanceMap (scale 1) for every shape except Chapter4Sphere, which is a
 * BlurredStep with InsideValue 100, OutsideValue 0 and EdgeWidth 1 mm. No noise. */
MeshExtraction_EXPORT PhantomImageParameters
DefaultPhantomImageParameters(PhantomShape shape);

/** DefaultPhantomImageParameters(shape).mode. */
MeshExtraction_EXPORT MeshExtractionEnums::PhantomImage
                      DefaultPhantomImageMode(PhantomShape shape);

/** An ImplicitSurfaceImageSource for the phantom: grid geometry, surface and image
 * settings set, not yet updated. */
template <typename TImage>
typename ImplicitSurfaceImageSource<TImage>::Pointer
MakePhantomImageSource(PhantomShape shape, const PhantomGrid & grid, const PhantomImageParameters & parameters)
{
  using SourceType = ImplicitSurfaceImageSource<TImage>;
  using PixelType = typename SourceType::OutputPixelType;
  auto source = SourceType::New();
  source->SetSurface(MakePhantomSurface(shape, grid));
  source->SetSize(grid.size);
  source->SetSpacing(grid.spacing);
  source->SetOrigin(grid.origin);
  source->SetDirection(grid.direction);
  source->SetImageMode(parameters.mode);
  source->SetDistanceScale(parameters.distanceScale);
  source->SetInsideValue(static_cast<PixelType>(parameters.insideValue));
  source->SetOutsideValue(static_cast<PixelType>(parameters.outsideValue));
  source->SetEdgeWidth(parameters.edgeWidth);
  source->SetNoiseStandardDeviation(parameters.noiseStandardDeviation);
  source->SetNoiseSeed(parameters.noiseSeed);
  return source;
}

/** MakePhantomImageSource with DefaultPhantomImageParameters(shape). */
template <typename TImage>
typename ImplicitSurfaceImageSource<TImage>::Pointer
MakePhantomImageSource(PhantomShape shape, const PhantomGrid & grid)
{
  return MakePhantomImageSource<TImage>(shape, grid, DefaultPhantomImageParameters(shape));
}

} // namespace MeshExtraction
} // namespace itk

#endif
