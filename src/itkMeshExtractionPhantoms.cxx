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
#include "itkMeshExtractionPhantoms.h"
#include "itkBoxImplicitSurface.h"
#include "itkEllipsoidImplicitSurface.h"
#include "itkMeshExtractionClosedFormGeometry.h"
#include "itkNarrowCleftImplicitSurface.h"
#include "itkPlaneImplicitSurface.h"
#include "itkSphereDifferenceImplicitSurface.h"
#include "itkSphereImplicitSurface.h"
#include "itkSphereUnionImplicitSurface.h"
#include "itkTorusImplicitSurface.h"

#include <algorithm>
#include <cmath>
#include <ostream>
#include <sstream>

namespace itk
{
namespace MeshExtraction
{
namespace
{
using detail::FrameFromNormal;
using detail::Normalized;
using detail::OrthogonalityError;
using detail::OrthonormalizeColumns;
using detail::RotationAboutX;
using detail::RotationAboutZ;

struct ShapeName
{
  PhantomShape shape;
  const char * name;
};

constexpr ShapeName ShapeNames[] = {
  { PhantomShape::Plane, "plane" },
  { PhantomShape::Sphere, "sphere" },
  { PhantomShape::TwoSpheres, "two-spheres" },
  { PhantomShape::Chapter4Sphere, "chapter4-sphere" },
  { PhantomShape::Ellipsoid, "ellipsoid" },
  { PhantomShape::IndentedSphere, "indented-sphere" },
  { PhantomShape::Torus, "torus" },
  { PhantomShape::ThinPlate, "thin-plate" },
  { PhantomShape::NarrowCleft, "narrow-cleft" },
};

using PointType = ImplicitSurfaceFunction::InputType;
using VectorType = ImplicitSurfaceFunction::VectorType;
using MatrixType = ImplicitSurfaceFunction::MatrixType;

/** The grid's direction, checked orthogonal within 1e-4 and orthonormalised. */
MatrixType
GridFrame(const PhantomGrid & grid)
{
  const double maximumError = OrthogonalityError(grid.direction);
  if (!(maximumError <= 1e-4))
  {
    itkGenericExceptionMacro(<< "PhantomGrid direction must be orthogonal (max |D^T D - I| <= 1e-4), got\n"
                             << grid.direction << "with max |D^T D - I| = " << maximumError);
  }
  return OrthonormalizeColumns(grid.direction);
}

void
CheckGrid(const PhantomGrid & grid)
{
  for (unsigned int k = 0; k < 3; ++k)
  {
    if (grid.size[k] == 0)
    {
      itkGenericExceptionMacro(<< "PhantomGrid size must be > 0 along every axis, got " << grid.size);
    }
    if (!(std::isfinite(grid.spacing[k]) && grid.spacing[k] > 0.0))
    {
      itkGenericExceptionMacro(<< "PhantomGrid spacing must be finite and > 0 along every axis, got " << grid.spacing);
    }
    if (!std::isfinite(grid.origin[k]))
    {
      itkGenericExceptionMacro(<< "PhantomGrid origin must be finite, got " << grid.origin);
    }
  }
}

/** A direction given in the grid's frame, normalised, in physical space. */
Vec3
GridDirection(const MatrixType & frame, double x, double y, double z)
{
  return frame * Normalized(MakeVec3(x, y, z));
}
} // namespace

std::ostream &
operator<<(std::ostream & out, PhantomShape shape)
{
  return out << PhantomShapeName(shape);
}

std::string
PhantomShapeName(PhantomShape shape)
{
  for (const ShapeName & entry : ShapeNames)
  {
    if (entry.shape == shape)
    {
      return entry.name;
    }
  }
  return "INVALID PhantomShape " + std::to_string(static_cast<int>(shape));
}

PhantomShape
PhantomShapeFromName(const std::string & name)
{
  for (const ShapeName & entry : ShapeNames)
  {
    if (name == entry.name)
    {
      return entry.shape;
    }
  }
  itkGenericExceptionMacro(<< "Unknown phantom shape \"" << name << "\"; valid names are: " << PhantomShapeNameList());
}

std::vector<PhantomShape>
AllPhantomShapes()
{
  std::vector<PhantomShape> shapes;
  for (const ShapeName & entry : ShapeNames)
  {
    shapes.push_back(entry.shape);
  }
  return shapes;
}

std::string
PhantomShapeNameList()
{
  std::string list;
  for (const ShapeName & entry : ShapeNames)
  {
    if (!list.empty())
    {
      list += ", ";
    }
    list += entry.name;
  }
  return list;
}

PhantomGrid::PhantomGrid()
{
  size.Fill(64);
  spacing.Fill(1.0);
  origin.Fill(0.0);
  direction.SetIdentity();
}

PhantomGrid
DefaultPhantomGrid(PhantomShape shape)
{
  PhantomGrid grid;
  if (shape == PhantomShape::Chapter4Sphere)
  {
    grid.size.Fill(100);
  }
  return grid;
}

Point<double, 3>
PhantomGridCenter(const PhantomGrid & grid)
{
  VectorType halfDiagonal;
  for (unsigned int k = 0; k < 3; ++k)
  {
    halfDiagonal[k] = 0.5 * grid.spacing[k] * (static_cast<double>(grid.size[k]) - 1.0);
  }
  return grid.origin + grid.direction * halfDiagonal;
}

double
PhantomGridSmallestExtent(const PhantomGrid & grid)
{
  double extent = static_cast<double>(grid.size[0]) * grid.spacing[0];
  for (unsigned int k = 1; k < 3; ++k)
  {
    extent = std::min(extent, static_cast<double>(grid.size[k]) * grid.spacing[k]);
  }
  return extent;
}

namespace
{
/** Where a phantom goes and how large it is (the placement rules of the header). */
struct PhantomPlacement
{
  MatrixType frame;           // the grid's direction, orthonormalised
  PointType  center;          // C
  double     extent;          // E
  double     smallestSpacing; // of the three axes
  double     firstSpacing;    // along the grid's first axis
};

PhantomPlacement
PlaceInGrid(const PhantomGrid & grid)
{
  CheckGrid(grid);
  PhantomPlacement at;
  at.frame = GridFrame(grid);
  at.center = PhantomGridCenter(grid);
  at.extent = PhantomGridSmallestExtent(grid);
  at.smallestSpacing = std::min({ grid.spacing[0], grid.spacing[1], grid.spacing[2] });
  at.firstSpacing = grid.spacing[0];
  return at;
}

ImplicitSurfaceFunction::Pointer
MakePlanePhantom(const PhantomPlacement & at)
{
  const Vec3 normal = GridDirection(at.frame, 1.0, 2.0, 3.0);
  auto       plane = PlaneImplicitSurface::New();
  plane->SetNormal(normal);
  plane->SetPoint(at.center + normal * (0.5 / std::sqrt(14.0) * at.smallestSpacing));
  return plane.GetPointer();
}

/** Sphere (radius 0.3 E) and Chapter4Sphere (0.25 E). */
ImplicitSurfaceFunction::Pointer
MakeSpherePhantom(const PhantomPlacement & at, double radiusFraction)
{
  auto sphere = SphereImplicitSurface::New();
  sphere->SetCenter(at.center);
  sphere->SetRadius(radiusFraction * at.extent);
  return sphere.GetPointer();
}

ImplicitSurfaceFunction::Pointer
MakeTwoSpheresPhantom(const PhantomPlacement & at)
{
  const double radius = 0.25 * at.extent;
  const Vec3   axis = GridDirection(at.frame, 1.0, 1.0, 1.0);
  auto         spheres = SphereUnionImplicitSurface::New();
  spheres->AddSphere(at.center + axis * (-0.5 * radius), radius);
  spheres->AddSphere(at.center + axis * (0.5 * radius), radius);
  return spheres.GetPointer();
}

ImplicitSurfaceFunction::Pointer
MakeEllipsoidPhantom(const PhantomPlacement & at)
{
  auto ellipsoid = EllipsoidImplicitSurface::New();
  ellipsoid->SetCenter(at.center);
  ellipsoid->SetSemiAxes(MakeVec3(0.35 * at.extent, 0.25 * at.extent, 0.15 * at.extent));
  ellipsoid->SetRotation(at.frame * RotationAboutZ(30.0) * RotationAboutX(20.0));
  return ellipsoid.GetPointer();
}

ImplicitSurfaceFunction::Pointer
MakeIndentedSpherePhantom(const PhantomPlacement & at)
{
  const double radius = 0.3 * at.extent;
  const Vec3   axis = GridDirection(at.frame, 1.0, 1.0, 1.0);
  auto         indented = SphereDifferenceImplicitSurface::New();
  indented->SetCenterA(at.center);
  indented->SetRadiusA(radius);
  indented->SetCenterB(at.center + axis * radius);
  indented->SetRadiusB(0.5 * radius);
  return indented.GetPointer();
}

ImplicitSurfaceFunction::Pointer
MakeTorusPhantom(const PhantomPlacement & at)
{
  auto torus = TorusImplicitSurface::New();
  torus->SetCenter(at.center);
  torus->SetAxis(GridDirection(at.frame, 1.0, 1.0, 4.0));
  torus->SetRadii(0.25 * at.extent, 0.1 * at.extent);
  return torus.GetPointer();
}

ImplicitSurfaceFunction::Pointer
MakeThinPlatePhantom(const PhantomPlacement & at)
{
  // The plate's frame in grid coordinates: normal n, first edge along the grid's first
  // axis projected onto the plate.
  const MatrixType local = FrameFromNormal(Normalized(MakeVec3(1.0, 2.0, 10.0)), MakeVec3(1.0, 0.0, 0.0));
  auto             plate = BoxImplicitSurface::New();
  plate->SetCenter(at.center);
  plate->SetHalfSizes(MakeVec3(0.35 * at.extent, 0.35 * at.extent, at.smallestSpacing));
  plate->SetRotation(at.frame * local);
  return plate.GetPointer();
}

ImplicitSurfaceFunction::Pointer
MakeNarrowCleftPhantom(const PhantomPlacement & at)
{
  auto cleft = NarrowCleftImplicitSurface::New();
  cleft->SetCenter(at.center);
  cleft->SetRotation(at.frame);
  cleft->SetHalfSizes(MakeVec3(0.3 * at.extent, 0.3 * at.extent, 0.2 * at.extent));
  cleft->SetSlotWidth(1.5 * at.firstSpacing);
  cleft->SetSlotDepth(0.24 * at.extent);
  cleft->VerifyParameters();
  return cleft.GetPointer();
}
} // namespace

ImplicitSurfaceFunction::Pointer
MakePhantomSurface(PhantomShape shape, const PhantomGrid & grid)
{
  const PhantomPlacement at = PlaceInGrid(grid);
  switch (shape)
  {
    case PhantomShape::Plane:
      return MakePlanePhantom(at);
    case PhantomShape::Sphere:
      return MakeSpherePhantom(at, 0.3);
    case PhantomShape::TwoSpheres:
      return MakeTwoSpheresPhantom(at);
    case PhantomShape::Chapter4Sphere:
      return MakeSpherePhantom(at, 0.25);
    case PhantomShape::Ellipsoid:
      return MakeEllipsoidPhantom(at);
    case PhantomShape::IndentedSphere:
      return MakeIndentedSpherePhantom(at);
    case PhantomShape::Torus:
      return MakeTorusPhantom(at);
    case PhantomShape::ThinPlate:
      return MakeThinPlatePhantom(at);
    case PhantomShape::NarrowCleft:
      return MakeNarrowCleftPhantom(at);
  }
  itkGenericExceptionMacro(<< "Unknown PhantomShape " << static_cast<int>(shape)
                           << "; valid names are: " << PhantomShapeNameList());
}

PhantomImageParameters
DefaultPhantomImageParameters(PhantomShape shape)
{
  PhantomImageParameters parameters;
  if (shape == PhantomShape::Chapter4Sphere)
  {
    parameters.mode = MeshExtractionEnums::PhantomImage::BlurredStep;
    parameters.insideValue = 100.0;
    parameters.outsideValue = 0.0;
    parameters.edgeWidth = 1.0;
  }
  return parameters;
}

MeshExtractionEnums::PhantomImage
DefaultPhantomImageMode(PhantomShape shape)
{
  return DefaultPhantomImageParameters(shape).mode;
}

} // namespace MeshExtraction
} // namespace itk
