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
#include "itkBoxImplicitSurface.h"
#include "itkEllipsoidImplicitSurface.h"
#include "itkNarrowCleftImplicitSurface.h"
#include "itkPlaneImplicitSurface.h"
#include "itkSphereDifferenceImplicitSurface.h"
#include "itkSphereImplicitSurface.h"
#include "itkSphereUnionImplicitSurface.h"
#include "itkTorusImplicitSurface.h"
#include "itkMeshExtractionPhantoms.h"
#include "itkImplicitSurfaceTestHelpers.h"

#include <sstream>
#include <utility>

using namespace ImplicitSurfaceTest;

namespace
{
using NamedSurfaces = std::vector<std::pair<std::string, SurfaceType::Pointer>>;

/** The single shapes: plane, sphere, ellipsoids (with ties in the axis order), torus
 * and box, with rotations and offsets. */
NamedSurfaces
SingleShapeSurfaces()
{
  NamedSurfaces surfaces;
  {
    auto s = itk::PlaneImplicitSurface::New();
    s->SetPoint(P(1, -2, 0.5));
    s->SetNormal(V(1, 2, 3));
    surfaces.emplace_back("plane", s.GetPointer());
  }
  {
    auto s = itk::SphereImplicitSurface::New();
    s->SetCenter(P(1, 2, 3));
    s->SetRadius(2.5);
    surfaces.emplace_back("sphere", s.GetPointer());
  }
  {
    auto s = itk::EllipsoidImplicitSurface::New();
    s->SetCenter(P(-1, 0.5, 2));
    s->SetSemiAxes(V(2, 5, 3));
    s->SetRotation(Rotation(0.3, -0.7, 1.1));
    surfaces.emplace_back("ellipsoid", s.GetPointer());
  }
  {
    auto s = itk::EllipsoidImplicitSurface::New();
    s->SetSemiAxes(V(4, 4, 1.5)); // oblate spheroid: ties in the axis order
    surfaces.emplace_back("oblate spheroid", s.GetPointer());
  }
  {
    auto s = itk::EllipsoidImplicitSurface::New();
    s->SetSemiAxes(V(1.5, 4, 1.5)); // prolate spheroid
    surfaces.emplace_back("prolate spheroid", s.GetPointer());
  }
  {
    auto s = itk::TorusImplicitSurface::New();
    s->SetCenter(P(0.5, 0, -1));
    s->SetAxis(V(1, 1, 4));
    s->SetRadii(4, 1.5);
    surfaces.emplace_back("torus", s.GetPointer());
  }
  {
    auto s = itk::BoxImplicitSurface::New();
    s->SetCenter(P(2, 1, 0));
    s->SetHalfSizes(V(3, 2, 0.5));
    s->SetRotation(Rotation(0.2, 0.4, -0.3));
    surfaces.emplace_back("box", s.GetPointer());
  }
  return surfaces;
}

/** The composite shapes: unions and differences of balls and the narrow cleft. */
NamedSurfaces
CompositeSurfaces()
{
  NamedSurfaces surfaces;
  {
    auto s = itk::SphereUnionImplicitSurface::New();
    s->AddSphere(P(0, 0, 0), 2);
    s->AddSphere(P(2, 0, 0), 2);
    surfaces.emplace_back("two spheres", s.GetPointer());
  }
  {
    auto s = itk::SphereUnionImplicitSurface::New();
    s->AddSphere(P(0, 0, 0), 1.5);
    s->AddSphere(P(2, 0.3, 0), 1.2);
    s->AddSphere(P(1, 1.6, 0.4), 1.3);
    s->AddSphere(P(5, 0, 0), 0.7); // disjoint from the others
    surfaces.emplace_back("four spheres", s.GetPointer());
  }
  {
    auto s = itk::SphereDifferenceImplicitSurface::New();
    s->SetCenterA(P(0, 0, 0));
    s->SetRadiusA(3);
    s->SetCenterB(P(2, 1, -1));
    s->SetRadiusB(1.5);
    surfaces.emplace_back("indented sphere", s.GetPointer());
  }
  {
    auto s = itk::SphereDifferenceImplicitSurface::New();
    s->SetCenterA(P(0, 0, 0));
    s->SetRadiusA(3);
    s->SetCenterB(P(0.5, 0, 0));
    s->SetRadiusB(1);
    surfaces.emplace_back("hollow sphere", s.GetPointer());
  }
  {
    auto s = itk::NarrowCleftImplicitSurface::New();
    s->SetCenter(P(1, 2, 3));
    s->SetHalfSizes(V(5, 4, 3));
    s->SetSlotWidth(1.5);
    s->SetSlotDepth(4);
    s->SetRotation(Rotation(-0.4, 0.25, 0.6));
    surfaces.emplace_back("narrow cleft", s.GetPointer());
  }
  return surfaces;
}

/** Named surfaces covering every class, with rotations and offsets, and every
 * phantom. */
NamedSurfaces
AllSurfaces()
{
  NamedSurfaces surfaces = SingleShapeSurfaces();
  const auto    composite = CompositeSurfaces();
  surfaces.insert(surfaces.end(), composite.begin(), composite.end());
  for (const auto shape : itk::MeshExtraction::AllPhantomShapes())
  {
    std::ostringstream name;
    name << "phantom " << shape;
    const auto grid = itk::MeshExtraction::DefaultPhantomGrid(shape);
    surfaces.emplace_back(name.str(), itk::MeshExtraction::MakePhantomSurface(shape, grid));
  }
  return surfaces;
}
} // namespace

// ---------------------------------------------------------------------------------
// Properties shared by every surface
// ---------------------------------------------------------------------------------

TEST(ImplicitSurfaceFunction, DistanceEqualsDistanceToClosestPointWhichLiesOnTheSurface)
{
  for (const auto & entry : AllSurfaces())
  {
    for (const PointType & p : RandomPointsAround(*entry.second, 300, 11))
    {
      ExpectConsistentAt(*entry.second, p, entry.first);
    }
  }
}

TEST(ImplicitSurfaceFunction, IsOneLipschitzOnRandomPointPairs)
{
  for (const auto & entry : AllSurfaces())
  {
    const auto                       a = RandomPointsAround(*entry.second, 500, 21);
    const auto                       b = RandomPointsAround(*entry.second, 500, 22);
    std::mt19937_64                  generator(23);
    std::normal_distribution<double> normal(0.0, 0.05);
    for (size_t i = 0; i < a.size(); ++i)
    {
      // Far pairs and near pairs (where a wrong sign or a bound would show first).
      PointType near = a[i];
      for (unsigned int k = 0; k < 3; ++k)
      {
        near[k] += normal(generator);
      }
      for (const PointType & q : { b[i], near })
      {
        const double difference = std::abs(entry.second->Evaluate(a[i]) - entry.second->Evaluate(q));
        EXPECT_LE(difference, a[i].EuclideanDistanceTo(q) + Tolerance) << entry.first << " " << a[i] << " " << q;
      }
    }
  }
}

TEST(ImplicitSurfaceFunction, DistanceIsExactBecauseNoSurfacePointIsCloserThanTheClaimedDistance)
{
  // Along the segment from p to its closest point q the distance must fall linearly
  // (|d| decreases by exactly the step), which a bound or approximation violates.
  for (const auto & entry : AllSurfaces())
  {
    for (const PointType & p : RandomPointsAround(*entry.second, 100, 31))
    {
      const PointType q = entry.second->ClosestSurfacePoint(p);
      const double    d = entry.second->Evaluate(p);
      for (const double t : { 0.25, 0.5, 0.75 })
      {
        const PointType m = p + (q - p) * t;
        EXPECT_NEAR(entry.second->Evaluate(m), d * (1.0 - t), 1e-8) << entry.first << " at " << p;
      }
    }
  }
}

TEST(ImplicitSurfaceFunction, PrintSelfNamesTheClassAndParameters)
{
  for (const auto & entry : AllSurfaces())
  {
    std::ostringstream os;
    entry.second->Print(os);
    EXPECT_NE(os.str().find(entry.second->GetNameOfClass()), std::string::npos) << entry.first;
    EXPECT_NE(os.str().find("ParametersValid: true"), std::string::npos) << entry.first;
  }
}

TEST(ImplicitSurfaceFunction, SettingAParameterUpdatesTheModifiedTime)
{
  auto                        sphere = itk::SphereImplicitSurface::New();
  const itk::ModifiedTimeType before = sphere->GetMTime();
  sphere->SetRadius(3.0);
  EXPECT_GT(sphere->GetMTime(), before);
}
