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
#include "itkImage.h"
#include "itkMesh.h"
#include "itkQuadEdgeMesh.h"

#include <cmath>
#include <fstream>
#include <string>
#include <map>
#include <random>

/** Fixtures shared by the GoogleTest suites: small closed and open meshes built
 * in code, in the module's flat form, and converted to ITK meshes. */
namespace MeshExtractionTest
{
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

} // namespace MeshExtractionTest

#endif
