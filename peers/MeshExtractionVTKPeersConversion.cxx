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
// Between ITK and VTK: an ITK image handed to VTK without a copy, VTK's points mapped
// into ITK physical space, VTK's triangles as the flat arrays the module measures.

#include "MeshExtractionVTKPeers.h"

#include "vnl/vnl_det.h"

#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <cstdint>
#include <limits>

namespace MeshExtractionCompare
{
bool
BufferGeometry::IsMirrored() const
{
  return vnl_det(direction.GetVnlMatrix()) < 0.0;
}

BufferGeometry
GetBufferGeometry(const ImageType & image)
{
  BufferGeometry g;
  const auto     region = image.GetBufferedRegion();
  image.TransformIndexToPhysicalPoint(region.GetIndex(), g.first);
  g.direction = image.GetDirection();
  g.spacing = image.GetSpacing();
  g.size = region.GetSize();
  return g;
}

vtkSmartPointer<vtkImageData>
WrapAsVTKImage(const ImageType & image, bool indexSpace)
{
  const BufferGeometry g = GetBufferGeometry(image);
  auto                 data = vtkSmartPointer<vtkImageData>::New();
  data->SetDimensions(static_cast<int>(g.size[0]), static_cast<int>(g.size[1]), static_cast<int>(g.size[2]));
  data->SetOrigin(0.0, 0.0, 0.0);
  if (indexSpace)
  {
    data->SetSpacing(1.0, 1.0, 1.0);
  }
  else
  {
    data->SetSpacing(g.spacing[0], g.spacing[1], g.spacing[2]);
  }
  auto scalars = vtkSmartPointer<vtkFloatArray>::New();
  scalars->SetName("ImageScalars");
  // save = 1: VTK never frees (or writes) the ITK buffer.
  scalars->SetArray(const_cast<float *>(image.GetBufferPointer()),
                    static_cast<vtkIdType>(image.GetBufferedRegion().GetNumberOfPixels()),
                    1);
  data->GetPointData()->SetScalars(scalars);
  return data;
}

void
MapToPhysicalSpace(vtkPoints * points, const BufferGeometry & g, bool indexSpace)
{
  if (points == nullptr)
  {
    return;
  }
  double m[3][3];
  for (unsigned int r = 0; r < 3; ++r)
  {
    for (unsigned int c = 0; c < 3; ++c)
    {
      m[r][c] = g.direction[r][c] * (indexSpace ? g.spacing[c] : 1.0);
    }
  }
  const vtkIdType n = points->GetNumberOfPoints();
  for (vtkIdType i = 0; i < n; ++i)
  {
    double x[3];
    points->GetPoint(i, x);
    double p[3];
    for (unsigned int r = 0; r < 3; ++r)
    {
      p[r] = g.first[r] + m[r][0] * x[0] + m[r][1] * x[1] + m[r][2] * x[2];
    }
    points->SetPoint(i, p);
  }
  points->Modified();
}

bool
VTKTrianglesNeedReversal(bool insideIsAboveIsoValue, const BufferGeometry & g)
{
  return insideIsAboveIsoValue == g.IsMirrored();
}

namespace
{
/** The points of a vtkPolyData, each its own id. */
void
CopyPoints(vtkPolyData * polyData, ME::IndexedTriangleMesh & out)
{
  const vtkIdType n = polyData->GetNumberOfPoints();
  if (static_cast<std::uint64_t>(n) >= std::numeric_limits<std::uint32_t>::max())
  {
    itkGenericExceptionMacro("meshextraction-compare: a VTK mesh with " << n << " points is too large");
  }
  out.points.resize(static_cast<std::size_t>(n));
  out.pointIds.resize(static_cast<std::size_t>(n));
  for (vtkIdType i = 0; i < n; ++i)
  {
    double x[3];
    polyData->GetPoint(i, x);
    out.points[i] = ME::MakeVec3(x[0], x[1], x[2]);
    out.pointIds[i] = static_cast<itk::IdentifierType>(i);
  }
}

/** The triangles of a vtkCellArray, each reversed if `reverse`. */
void
CopyTriangles(vtkCellArray * polys, bool reverse, ME::IndexedTriangleMesh & out)
{
  out.triangles.reserve(static_cast<std::size_t>(polys->GetNumberOfCells()));
  out.cellIds.reserve(static_cast<std::size_t>(polys->GetNumberOfCells()));
  auto                iterator = vtk::TakeSmartPointer(polys->NewIterator());
  itk::IdentifierType cell = 0;
  for (iterator->GoToFirstCell(); !iterator->IsDoneWithTraversal(); iterator->GoToNextCell(), ++cell)
  {
    vtkIdType         size = 0;
    const vtkIdType * ids = nullptr;
    iterator->GetCurrentCell(size, ids);
    if (size != 3)
    {
      itkGenericExceptionMacro("meshextraction-compare: VTK polygon " << cell << " has " << size
                                                                      << " points; triangles were expected");
    }
    const auto a = static_cast<std::uint32_t>(ids[0]);
    const auto b = static_cast<std::uint32_t>(ids[1]);
    const auto c = static_cast<std::uint32_t>(ids[2]);
    out.triangles.push_back(reverse ? ME::TriangleIndices{ a, c, b } : ME::TriangleIndices{ a, b, c });
    out.cellIds.push_back(cell);
  }
}
} // namespace

ME::IndexedTriangleMesh
PolyDataToIndexedMesh(vtkPolyData * polyData, bool reverse)
{
  ME::IndexedTriangleMesh out;
  if (polyData == nullptr || polyData->GetPoints() == nullptr)
  {
    return out;
  }
  CopyPoints(polyData, out);
  vtkCellArray * polys = polyData->GetPolys();
  if (polys != nullptr)
  {
    CopyTriangles(polys, reverse, out);
  }
  return out;
}

std::size_t
DropUnreferencedPoints(ME::IndexedTriangleMesh & mesh)
{
  constexpr std::uint32_t    unused = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> newIndex(mesh.points.size(), unused);
  for (const auto & t : mesh.triangles)
  {
    for (const std::uint32_t v : t)
    {
      newIndex[v] = 0;
    }
  }
  std::uint32_t kept = 0;
  for (std::size_t i = 0; i < newIndex.size(); ++i)
  {
    if (newIndex[i] != unused)
    {
      newIndex[i] = kept;
      mesh.points[kept] = mesh.points[i];
      mesh.pointIds[kept] = mesh.pointIds[i];
      ++kept;
    }
  }
  const std::size_t dropped = mesh.points.size() - kept;
  mesh.points.resize(kept);
  mesh.pointIds.resize(kept);
  for (auto & t : mesh.triangles)
  {
    for (std::uint32_t & v : t)
    {
      v = newIndex[v];
    }
  }
  return dropped;
}

ME::IndexedTriangleMesh
MeshForMeasurement(const MethodOutput & output, std::size_t * dropped)
{
  ME::IndexedTriangleMesh mesh = output.toIndexedMesh();
  const std::size_t       n = DropUnreferencedPoints(mesh);
  if (dropped != nullptr)
  {
    *dropped = n;
  }
  return mesh;
}

} // namespace MeshExtractionCompare
