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
#ifndef itkMeshExtractionTestHelpers_h
#define itkMeshExtractionTestHelpers_h

#include "itkMeshExtractionGeodesicSphere.h"
#include "itkMeshExtractionIndexedTriangleMesh.h"
#include "itkMeshExtractionPhantoms.h"
#include "itkImage.h"
#include "itkMacro.h"
#include "itkMesh.h"
#include "itkQuadEdgeMesh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>
#include <map>
#include <random>
#include <vector>

/** Fixtures shared by the GoogleTest suites: small closed and open meshes built
 * in code, in the module's flat form, and converted to ITK meshes. */
namespace MeshExtractionTest
{
/** The description of the itk::ExceptionObject that `run()` throws; a test failure
 * and "" when it throws none. */
template <typename TFunction>
std::string
ExceptionDescription(TFunction && run)
{
  try
  {
    run();
  }
  catch (const itk::ExceptionObject & e)
  {
    return e.GetDescription();
  }
  ADD_FAILURE() << "no itk::ExceptionObject was thrown";
  return std::string();
}

using itk::MeshExtraction::IndexedTriangleMesh;
using itk::MeshExtraction::MakeVec3;
using itk::MeshExtraction::Vec3;
using QEMeshType = itk::QuadEdgeMesh<double, 3>;
using MeshType = itk::Mesh<double, 3>;
/** A QuadEdgeMesh with double coordinates, for tests that need 1e-9 precision. */
using QEMeshTraitsD = itk::QuadEdgeMeshTraits<double, 3, bool, bool, double, double>;
using QEMeshDType = itk::QuadEdgeMesh<double, 3, QEMeshTraitsD>;

/** Icosahedron subdivided `level` times, vertices projected on the sphere
 * (center, radius); outward counter-clockwise triangles (the module's
 * MakeGeodesicSphere). */
inline IndexedTriangleMesh
MakeIcosphere(unsigned int level, double radius = 1.0, const Vec3 & center = MakeVec3(0, 0, 0))
{
  return itk::MeshExtraction::MakeGeodesicSphere(level, center, radius);
}

/** Torus (major radius R about the z axis, minor radius r), nu x nv quads split
 * into outward triangles. */
inline IndexedTriangleMesh
MakeTorus(unsigned int nu, unsigned int nv, double R, double r)
{
  IndexedTriangleMesh m;
  for (unsigned int i = 0; i < nu; ++i)
  {
    const double u = 2.0 * itk::Math::pi * i / nu;
    for (unsigned int j = 0; j < nv; ++j)
    {
      const double v = 2.0 * itk::Math::pi * j / nv;
      m.points.push_back(
        MakeVec3((R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v)));
    }
  }
  auto id = [nu, nv](unsigned int i, unsigned int j) { return static_cast<std::uint32_t>((i % nu) * nv + (j % nv)); };
  for (unsigned int i = 0; i < nu; ++i)
  {
    for (unsigned int j = 0; j < nv; ++j)
    {
      m.triangles.push_back({ id(i, j), id(i + 1, j), id(i + 1, j + 1) });
      m.triangles.push_back({ id(i, j), id(i + 1, j + 1), id(i, j + 1) });
    }
  }
  return m;
}

/** Flat n x n grid of unit squares in z = 0, each split into two triangles
 * (normals +z); an open sheet with one boundary loop. */
inline IndexedTriangleMesh
MakeGrid(unsigned int n, double step = 1.0)
{
  IndexedTriangleMesh m;
  for (unsigned int j = 0; j <= n; ++j)
  {
    for (unsigned int i = 0; i <= n; ++i)
    {
      m.points.push_back(MakeVec3(i * step, j * step, 0.0));
    }
  }
  auto id = [n](unsigned int i, unsigned int j) { return static_cast<std::uint32_t>(j * (n + 1) + i); };
  for (unsigned int j = 0; j < n; ++j)
  {
    for (unsigned int i = 0; i < n; ++i)
    {
      m.triangles.push_back({ id(i, j), id(i + 1, j), id(i + 1, j + 1) });
      m.triangles.push_back({ id(i, j), id(i + 1, j + 1), id(i, j + 1) });
    }
  }
  return m;
}

/** Regular tetrahedron, outward oriented. */
inline IndexedTriangleMesh
MakeTetrahedron()
{
  IndexedTriangleMesh m;
  m.points = { MakeVec3(1, 1, 1), MakeVec3(1, -1, -1), MakeVec3(-1, 1, -1), MakeVec3(-1, -1, 1) };
  m.triangles = { { 0, 1, 2 }, { 0, 3, 1 }, { 0, 2, 3 }, { 1, 3, 2 } };
  return m;
}

template <typename TMesh>
typename TMesh::Pointer
ToITKMesh(const IndexedTriangleMesh & in)
{
  auto mesh = TMesh::New();
  itk::MeshExtraction::FillMesh(in, *mesh);
  return mesh;
}


/** `mesh` with the triangles and points of `other` appended. */
inline void
Append(IndexedTriangleMesh & mesh, const IndexedTriangleMesh & other)
{
  const auto offset = static_cast<std::uint32_t>(mesh.points.size());
  mesh.points.insert(mesh.points.end(), other.points.begin(), other.points.end());
  for (auto t : other.triangles)
  {
    for (auto & v : t)
    {
      v += offset;
    }
    mesh.triangles.push_back(t);
  }
}

/** An image of nx x ny x nz voxels of 1 mm at the origin, filled with `value`. */
template <typename TImage>
typename TImage::Pointer
MakeImage(unsigned int nx, unsigned int ny, unsigned int nz, typename TImage::PixelType value = 0)
{
  auto                      image = TImage::New();
  typename TImage::SizeType size = { { nx, ny, nz } };
  image->SetRegions(size);
  image->Allocate();
  image->FillBuffer(value);
  return image;
}

/** A phantom's distance map (inside negative) and its exact surface. */
struct Phantom
{
  itk::Image<float, 3>::Pointer         image;
  itk::ImplicitSurfaceFunction::Pointer surface;
  itk::MeshExtraction::PhantomGrid      grid;
};

/** The phantom `shape` on `grid`. */
inline Phantom
MakePhantom(itk::MeshExtraction::PhantomShape shape, const itk::MeshExtraction::PhantomGrid & grid)
{
  Phantom p;
  p.grid = grid;
  auto source = itk::MeshExtraction::MakePhantomImageSource<itk::Image<float, 3>>(shape, grid);
  source->Update();
  p.image = source->GetOutput();
  p.surface = itk::MeshExtraction::MakePhantomSurface(shape, grid);
  return p;
}

/** The phantom `shape` on its default grid. */
inline Phantom
MakePhantom(itk::MeshExtraction::PhantomShape shape)
{
  return MakePhantom(shape, itk::MeshExtraction::DefaultPhantomGrid(shape));
}

/** The small VTK head CT of ../shared/data/ct_headsq (64 x 64 x 93 voxels of
 * 3.2 x 3.2 x 1.5 mm, HU + 1024, bone above ~1150), read from its raw file: its NRRD
 * header gives both 'space:' and 'spacings:', which ITK's NRRD reader refuses. That
 * folder lies next to the project and is never part of it: returns null (and where
 * it looked in `path`) when it is absent, so that tests can skip. */
inline itk::Image<short, 3>::Pointer
ReadSharedHeadCT(std::string & path)
{
  path = std::string(MESHEXTRACTION_SOURCE_DIR) + "/../shared/data/ct_headsq/headsq_quarter.raw";
  std::ifstream file(path, std::ios::binary);
  if (!file)
  {
    return nullptr;
  }
  using ImageType = itk::Image<short, 3>;
  auto                image = ImageType::New();
  ImageType::SizeType size;
  size[0] = 64;
  size[1] = 64;
  size[2] = 93;
  image->SetRegions(size);
  image->Allocate();
  const double spacing[3] = { 3.2, 3.2, 1.5 };
  image->SetSpacing(spacing);
  const std::size_t voxels = 64 * 64 * 93;
  std::vector<char> bytes(2 * voxels);
  if (!file.read(bytes.data(), static_cast<std::streamsize>(bytes.size())))
  {
    itkGenericExceptionMacro(<< path << " is shorter than 64 x 64 x 93 voxels of 2 bytes");
  }
  short * buffer = image->GetBufferPointer();
  for (std::size_t i = 0; i < voxels; ++i) // little endian, 15-bit values
  {
    buffer[i] = static_cast<short>(
      (static_cast<unsigned char>(bytes[2 * i]) | (static_cast<unsigned char>(bytes[2 * i + 1]) << 8)) & 0x7fff);
  }
  return image;
}

/** A smooth random volume for stress tests: the sum of 1 to 8 Gaussian blobs, sheets
 * and tubes of random width, sign, position and direction, with noise on about half
 * of them, on a grid of 10 to 31 voxels a side. Seeds 2 and 3 modulo 4 get anisotropic
 * spacing (0.6 to 1.4 mm), seeds 3 modulo 4 a rotated direction too. `iso` receives an
 * iso-value between 0.2 and 0.7 (the object is above it). Only std::mt19937's raw
 * output is used, so every standard library gives the same volume (up to libm's
 * exp, log and cos in the last bits). */
inline itk::Image<float, 3>::Pointer
MakeRandomSmoothVolume(unsigned int seed, double & iso)
{
  using ImageType = itk::Image<float, 3>;
  std::mt19937 rng(seed);
  auto         uniform = [&rng]() { return static_cast<double>(rng() >> 5) * (1.0 / 134217728.0); }; // [0, 1)
  const double pi = 3.14159265358979323846;
  unsigned int n[3];
  for (auto & side : n)
  {
    side = 10u + static_cast<unsigned int>(uniform() * 22);
  }
  auto                     image = ImageType::New();
  ImageType::SizeType      size = { { n[0], n[1], n[2] } };
  ImageType::SpacingType   spacing(1.0);
  ImageType::DirectionType direction;
  direction.SetIdentity();
  if (seed % 4 >= 2)
  {
    for (unsigned int d = 0; d < 3; ++d)
    {
      spacing[d] = 0.6 + 0.8 * uniform();
    }
  }
  if (seed % 4 == 3)
  {
    // Rotations about z, y and x by random angles.
    const double             a = 3 * uniform(), b = 3 * uniform(), c = 3 * uniform();
    ImageType::DirectionType rz, ry, rx;
    rz.SetIdentity();
    ry.SetIdentity();
    rx.SetIdentity();
    rz(0, 0) = std::cos(a), rz(0, 1) = -std::sin(a), rz(1, 0) = std::sin(a), rz(1, 1) = std::cos(a);
    ry(0, 0) = std::cos(b), ry(0, 2) = std::sin(b), ry(2, 0) = -std::sin(b), ry(2, 2) = std::cos(b);
    rx(1, 1) = std::cos(c), rx(1, 2) = -std::sin(c), rx(2, 1) = std::sin(c), rx(2, 2) = std::cos(c);
    direction = rz * ry * rx;
  }
  image->SetRegions(size);
  image->SetSpacing(spacing);
  image->SetDirection(direction);
  image->Allocate();
  struct Shape
  {
    double center[3];
    double width;
    double weight;
    int    kind; // 0 blob, 1 sheet, 2 tube
    double axis[3];
  };
  std::vector<Shape> shapes(1 + static_cast<std::size_t>(uniform() * 8));
  for (auto & s : shapes)
  {
    for (unsigned int d = 0; d < 3; ++d)
    {
      s.center[d] = uniform() * n[d];
    }
    s.width = 0.7 + 5.0 * uniform();
    s.weight = (uniform() < 0.75 ? 1.0 : -1.0) * (0.5 + uniform());
    s.kind = static_cast<int>(uniform() * 3);
    double length = 1e-9;
    for (auto & a : s.axis)
    {
      a = uniform() - 0.5;
      length += a * a;
    }
    for (auto & a : s.axis)
    {
      a /= std::sqrt(length);
    }
  }
  const double noise = uniform() < 0.5 ? 0.0 : 0.3 * uniform();
  float *      voxel = image->GetBufferPointer();
  for (unsigned int z = 0; z < n[2]; ++z)
  {
    for (unsigned int y = 0; y < n[1]; ++y)
    {
      for (unsigned int x = 0; x < n[0]; ++x)
      {
        const double p[3] = { static_cast<double>(x), static_cast<double>(y), static_cast<double>(z) };
        double       v = 0.0;
        for (const auto & s : shapes)
        {
          double along = 0.0;
          double r2 = 0.0;
          for (unsigned int d = 0; d < 3; ++d)
          {
            along += (p[d] - s.center[d]) * s.axis[d];
            r2 += (p[d] - s.center[d]) * (p[d] - s.center[d]);
          }
          const double d2 = s.kind == 0 ? r2 : s.kind == 1 ? 4.0 * along * along : r2 - along * along;
          v += s.weight * std::exp(-d2 / (2.0 * s.width * s.width));
        }
        if (noise > 0.0)
        {
          // Box-Muller.
          const double u = 1.0 - uniform();
          v += noise * std::sqrt(-2.0 * std::log(u)) * std::cos(2.0 * pi * uniform());
        }
        *voxel++ = static_cast<float>(v);
      }
    }
  }
  iso = 0.2 + 0.5 * uniform();
  return image;
}

} // namespace MeshExtractionTest

#endif
