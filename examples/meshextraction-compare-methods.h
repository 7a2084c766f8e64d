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
#ifndef meshextraction_compare_methods_h
#define meshextraction_compare_methods_h

// The surface-extraction methods that meshextraction-compare puts side by side, as a
// table of name -> function, shared with the VTK comparison tests and the benchmarks.
//
// Every method takes the same ExtractionInput (an ITK float image with an iso-value and
// the side that is inside) and returns its result in its native form (vtkPolyData or
// itk::Mesh), kept alive by a closure that converts it on demand into flat arrays
// (IndexedTriangleMesh) in ITK physical space, triangles oriented outward. So the
// module's calculators measure every method the same way.
//
// Physical space. VTK's image filters work in VTK image coordinates: spacing and
// origin, no direction. The image is handed to VTK with origin 0 and the ITK spacing
// (zero-copy: the vtkFloatArray points at the ITK buffer), and the output points are
// then mapped, inside the timed part, through p = P0 + D x, where P0 is the ITK
// physical point of the buffer's first voxel and D the ITK direction. A direction with
// determinant -1 mirrors the mesh, so the triangles' winding is reversed for it.
// ITK's filters (BinaryMask3DMeshSource, SurfaceNets) map through the direction
// themselves.
//
// To add a method, append an entry to Methods() below.

#include "itkBinaryMask3DMeshSource.h"
#include "itkImage.h"
#include "itkMesh.h"
#include "itkMeshExtractionIndexedTriangleMesh.h"
#include "itkSurfaceNetsImageToMeshFilter.h"
#include "vnl/vnl_det.h"

#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkDiscreteFlyingEdges3D.h>
#include <vtkFlyingEdges3D.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkMarchingCubes.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSMPTools.h>
#include <vtkSmartPointer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkWindowedSincPolyDataFilter.h>

#include <functional>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace MeshExtractionCompare
{
namespace ME = itk::MeshExtraction;
using ImageType = itk::Image<float, 3>;
using MaskImageType = itk::Image<unsigned char, 3>;
using MeshType = itk::Mesh<double, 3>;

/** One extraction problem: a 3-D image and the iso-surface to extract from it. */
struct ExtractionInput
{
  ImageType::ConstPointer image;
  double                  isoValue{ 0.0 };
  /** True: voxels >= isoValue are the object (CT bone). False: voxels <= isoValue are
   * (a signed distance map, negative inside). */
  bool insideIsAboveIsoValue{ true };
  /** Work units of ITK's multithreaded filters; 0 keeps ITK's default (all cores).
   * VTK's SMP threads are set by the caller (vtkSMPTools::Initialize). */
  unsigned int numberOfWorkUnits{ 0 };
};

/** What one run of a method produced, in its native form (kept alive by the closure). */
struct MethodOutput
{
  /** The mesh as flat arrays in ITK physical space, triangles oriented outward
   * (for VTK's filters, whose winding does not know which side is inside). */
  std::function<ME::IndexedTriangleMesh()> toIndexedMesh;
  /** Optional remarks about this run (iterations, ...). */
  std::string notes;
};

/** A row of the comparison. */
struct Method
{
  std::string                                          key;         ///< command-line name: "mc", "snert", ...
  std::string                                          name;        ///< table name
  std::string                                          description; ///< what exactly runs (parameters)
  bool                                                 byDefault{ true };
  std::function<MethodOutput(const ExtractionInput &)> run;
};

// ------------------------------------------------------------------------------
// Geometry shared by the VTK methods
// ------------------------------------------------------------------------------

/** Index-to-physical mapping of an image's buffer. */
struct BufferGeometry
{
  itk::Point<double, 3>     first;     ///< physical point of the buffer's first voxel
  itk::Matrix<double, 3, 3> direction; ///< ITK direction cosines
  itk::Vector<double, 3>    spacing;
  itk::Size<3>              size;

  bool
  IsMirrored() const
  {
    return vnl_det(direction.GetVnlMatrix()) < 0.0;
  }
};

inline BufferGeometry
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

/** A vtkImageData that shares the ITK image's buffer (no copy): dimensions of the
 * buffer, origin 0, and the ITK spacing (or unit spacing for `indexSpace`). */
inline vtkSmartPointer<vtkImageData>
WrapAsVTKImage(const ImageType & image, bool indexSpace = false)
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

/** Map points from VTK image coordinates (origin 0; ITK spacing, or unit spacing if
 * `indexSpace`) to ITK physical space, in place: p = first + D (S .* x or x). */
inline void
MapToPhysicalSpace(vtkPoints * points, const BufferGeometry & g, bool indexSpace = false)
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

/** Whether the triangles of VTK's iso-surface filters (vtkMarchingCubes,
 * vtkFlyingEdges3D, vtkDiscreteFlyingEdges3D) must be reversed to face out of the
 * object. Their winding makes the normals point toward decreasing scalars: an object
 * above the iso-value (CT bone, a label) comes out facing outward, a signed distance
 * map's object (inside below) facing inward. A mirroring direction (determinant -1)
 * reverses the winding once more. (Checked by the VTK comparison tests on both
 * conventions and on a mirrored grid.) */
inline bool
VTKTrianglesNeedReversal(bool insideIsAboveIsoValue, const BufferGeometry & g)
{
  return insideIsAboveIsoValue == g.IsMirrored();
}

/** Points and triangles of a vtkPolyData (polygons must be triangles); every
 * triangle reversed if `reverse`. */
inline ME::IndexedTriangleMesh
PolyDataToIndexedMesh(vtkPolyData * polyData, bool reverse)
{
  ME::IndexedTriangleMesh out;
  if (polyData == nullptr || polyData->GetPoints() == nullptr)
  {
    return out;
  }
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
  vtkCellArray * polys = polyData->GetPolys();
  if (polys == nullptr)
  {
    return out;
  }
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
  return out;
}

/** A MethodOutput around a vtkPolyData that is already in ITK physical space. */
inline MethodOutput
MakeVTKOutput(vtkSmartPointer<vtkPolyData> polyData, bool reverse)
{
  MethodOutput out;
  out.toIndexedMesh = [polyData, reverse]() { return PolyDataToIndexedMesh(polyData, reverse); };
  return out;
}

/** A MethodOutput around an ITK mesh (already in physical space, oriented by its filter). */
inline MethodOutput
MakeITKOutput(MeshType::Pointer mesh)
{
  MethodOutput out;
  out.toIndexedMesh = [mesh]() { return ME::MakeIndexedTriangleMesh(*mesh); };
  return out;
}

/** Drop the points no triangle uses (vtkMarchingCubes leaves some where it removes a
 * degenerate triangle at an exact tie with the iso-value): they are not vertices of the
 * surface and would count in the vertex distances. Returns how many were dropped. */
inline std::size_t
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

/** The mesh of a run as the comparison measures it: flat arrays in ITK physical space,
 * outward, without unreferenced points (their number goes to `dropped`). */
inline ME::IndexedTriangleMesh
MeshForMeasurement(const MethodOutput & output, std::size_t * dropped = nullptr)
{
  ME::IndexedTriangleMesh mesh = output.toIndexedMesh();
  const std::size_t       n = DropUnreferencedPoints(mesh);
  if (dropped != nullptr)
  {
    *dropped = n;
  }
  return mesh;
}

// ------------------------------------------------------------------------------
// The methods
// ------------------------------------------------------------------------------

/** vtkMarchingCubes on the greyscale image; normals, gradients and scalars off. */
inline MethodOutput
RunVTKMarchingCubes(const ExtractionInput & in)
{
  const BufferGeometry     g = GetBufferGeometry(*in.image);
  vtkNew<vtkMarchingCubes> mc;
  mc->SetInputData(WrapAsVTKImage(*in.image));
  mc->SetValue(0, in.isoValue);
  mc->ComputeNormalsOff();
  mc->ComputeGradientsOff();
  mc->ComputeScalarsOff();
  mc->Update();
  vtkSmartPointer<vtkPolyData> out = mc->GetOutput();
  MapToPhysicalSpace(out->GetPoints(), g);
  return MakeVTKOutput(out, VTKTrianglesNeedReversal(in.insideIsAboveIsoValue, g));
}

/** vtkFlyingEdges3D on the greyscale image; normals, gradients and scalars off. */
inline vtkSmartPointer<vtkPolyData>
FlyingEdgesInVTKImageCoordinates(const ExtractionInput & in)
{
  vtkNew<vtkFlyingEdges3D> fe;
  fe->SetInputData(WrapAsVTKImage(*in.image));
  fe->SetValue(0, in.isoValue);
  fe->ComputeNormalsOff();
  fe->ComputeGradientsOff();
  fe->ComputeScalarsOff();
  fe->Update();
  return fe->GetOutput();
}

inline MethodOutput
RunVTKFlyingEdges(const ExtractionInput & in)
{
  const BufferGeometry         g = GetBufferGeometry(*in.image);
  vtkSmartPointer<vtkPolyData> out = FlyingEdgesInVTKImageCoordinates(in);
  MapToPhysicalSpace(out->GetPoints(), g);
  return MakeVTKOutput(out, VTKTrianglesNeedReversal(in.insideIsAboveIsoValue, g));
}

/** The windowed-sinc settings of 3D Slicer's closed-surface conversion
 * (vtkBinaryLabelmapToClosedSurfaceConversionRule): 20 iterations, boundary and
 * feature-edge smoothing off, non-manifold smoothing and coordinate normalisation on. */
inline vtkSmartPointer<vtkPolyData>
SlicerWindowedSinc(vtkPolyData * input, double passBand)
{
  vtkNew<vtkWindowedSincPolyDataFilter> smoother;
  smoother->SetInputData(input);
  smoother->SetNumberOfIterations(20);
  smoother->SetPassBand(passBand);
  smoother->BoundarySmoothingOff();
  smoother->FeatureEdgeSmoothingOff();
  smoother->NonManifoldSmoothingOn();
  smoother->NormalizeCoordinatesOn();
  smoother->Update();
  return smoother->GetOutput();
}

/** vtkFlyingEdges3D + vtkWindowedSincPolyDataFilter (20 iterations, pass band 0.1). */
inline MethodOutput
RunVTKFlyingEdgesWindowedSinc(const ExtractionInput & in)
{
  const BufferGeometry         g = GetBufferGeometry(*in.image);
  vtkSmartPointer<vtkPolyData> out = SlicerWindowedSinc(FlyingEdgesInVTKImageCoordinates(in), 0.1);
  MapToPhysicalSpace(out->GetPoints(), g);
  return MakeVTKOutput(out, VTKTrianglesNeedReversal(in.insideIsAboveIsoValue, g));
}

/** 1 where the voxel is inside (the SurfaceNets filter's classification), else 0. */
inline bool
IsInside(float value, const ExtractionInput & in)
{
  return in.insideIsAboveIsoValue ? value >= in.isoValue : value <= in.isoValue;
}

/** 3D Slicer's own default pipeline on the thresholded labelmap, in index space as
 * Slicer does: vtkDiscreteFlyingEdges3D, then windowed sinc with the pass band of its
 * default smoothing factor 0.5 (10^(-4 * 0.5) = 0.01), then the index-to-physical map.
 * (Slicer also pads a labelmap that touches the border; not done here.) */
inline MethodOutput
RunSlicerLabelmapPipeline(const ExtractionInput & in)
{
  const BufferGeometry g = GetBufferGeometry(*in.image);
  auto                 labels = vtkSmartPointer<vtkImageData>::New();
  labels->SetDimensions(static_cast<int>(g.size[0]), static_cast<int>(g.size[1]), static_cast<int>(g.size[2]));
  labels->SetOrigin(0.0, 0.0, 0.0);
  labels->SetSpacing(1.0, 1.0, 1.0);
  auto              mask = vtkSmartPointer<vtkUnsignedCharArray>::New();
  const std::size_t n = in.image->GetBufferedRegion().GetNumberOfPixels();
  mask->SetNumberOfValues(static_cast<vtkIdType>(n));
  const float * buffer = in.image->GetBufferPointer();
  for (std::size_t i = 0; i < n; ++i)
  {
    mask->SetValue(static_cast<vtkIdType>(i), IsInside(buffer[i], in) ? 1 : 0);
  }
  labels->GetPointData()->SetScalars(mask);
  vtkNew<vtkDiscreteFlyingEdges3D> dfe;
  dfe->SetInputData(labels);
  dfe->SetValue(0, 1);
  dfe->ComputeNormalsOff();
  dfe->ComputeGradientsOff();
  dfe->ComputeScalarsOff();
  dfe->Update();
  vtkSmartPointer<vtkPolyData> out = SlicerWindowedSinc(dfe->GetOutput(), 0.01);
  MapToPhysicalSpace(out->GetPoints(), g, true);
  // The label (1) is above the background (0): the object is "above".
  return MakeVTKOutput(out, VTKTrianglesNeedReversal(true, g));
}

/** ITK's BinaryMask3DMeshSource (marching cubes on a binary mask) on the thresholded
 * image; the thresholding is part of the timed run. */
inline MethodOutput
RunITKBinaryMask3DMeshSource(const ExtractionInput & in)
{
  auto mask = MaskImageType::New();
  mask->SetRegions(in.image->GetBufferedRegion());
  mask->CopyInformation(in.image);
  mask->Allocate();
  const std::size_t n = in.image->GetBufferedRegion().GetNumberOfPixels();
  const float *     buffer = in.image->GetBufferPointer();
  unsigned char *   labels = mask->GetBufferPointer();
  for (std::size_t i = 0; i < n; ++i)
  {
    labels[i] = IsInside(buffer[i], in) ? 1 : 0;
  }
  auto source = itk::BinaryMask3DMeshSource<MaskImageType, MeshType>::New();
  source->SetInput(mask);
  source->SetObjectValue(1);
  source->Update();
  return MakeITKOutput(source->GetOutput());
}

using SurfaceNetsFilterType = itk::SurfaceNetsImageToMeshFilter<ImageType, MeshType>;

/** This module's SurfaceNets with the given relaxation (other settings default),
 * itk::Mesh<double,3> output. `configure` may change further settings. */
inline MethodOutput
RunSurfaceNets(const ExtractionInput &                              in,
               itk::SurfaceNetsImageToMeshFilterEnums::Relaxation   relaxation,
               const std::function<void(SurfaceNetsFilterType *)> & configure = {})
{
  auto filter = SurfaceNetsFilterType::New();
  filter->SetInput(in.image);
  filter->SetIsoValue(in.isoValue);
  filter->SetInsideIsAboveIsoValue(in.insideIsAboveIsoValue);
  filter->SetRelaxation(relaxation);
  if (in.numberOfWorkUnits > 0)
  {
    filter->SetNumberOfWorkUnits(in.numberOfWorkUnits);
  }
  if (configure)
  {
    configure(filter);
  }
  filter->Update();
  MethodOutput       out = MakeITKOutput(filter->GetOutput());
  std::ostringstream notes;
  notes << filter->GetNumberOfIterations() << " iterations, " << filter->GetNumberOfSplitCells() << " split cells, "
        << filter->GetNumberOfNodesMovedBack() << " nodes moved back";
  if (filter->GetHighQuality())
  {
    notes << ", " << filter->GetNumberOfRoundsPerformed() << " rounds, " << filter->GetNumberOfSwaps() << " swaps";
  }
  out.notes = notes.str();
  return out;
}

/** The comparison's rows, in table order. Add a method here. */
inline std::vector<Method>
Methods()
{
  using Relaxation = itk::SurfaceNetsImageToMeshFilterEnums::Relaxation;
  return {
    { "mc",
      "vtkMarchingCubes",
      "vtkMarchingCubes on the greyscale image (normals/gradients/scalars off, point merging on)",
      true,
      RunVTKMarchingCubes },
    { "fe",
      "vtkFlyingEdges3D",
      "vtkFlyingEdges3D on the greyscale image (normals/gradients/scalars off; VTK SMP threads)",
      true,
      RunVTKFlyingEdges },
    { "fe-sinc",
      "FlyingEdges3D+WindowedSinc",
      "vtkFlyingEdges3D + vtkWindowedSincPolyDataFilter: 20 iterations, pass band 0.1, NormalizeCoordinates on, "
      "FeatureEdgeSmoothing off, BoundarySmoothing off, NonManifoldSmoothing on (3D Slicer's settings at "
      "smoothing factor 0.25; Slicer's default 0.5 means pass band 0.01 on a labelmap: method 'slicer'), in VTK "
      "image coordinates",
      true,
      RunVTKFlyingEdgesWindowedSinc },
    { "bmms",
      "itkBinaryMask3DMeshSource",
      "ITK's BinaryMask3DMeshSource (marching cubes on the binary mask) on the thresholded image; "
      "thresholding included in the time",
      true,
      RunITKBinaryMask3DMeshSource },
    { "sna",
      "SurfaceNets SNA",
      "SurfaceNetsImageToMeshFilter, Relaxation::Averaging (SNA), defaults otherwise, itk::Mesh<double,3> output",
      true,
      [](const ExtractionInput & in) { return RunSurfaceNets(in, Relaxation::Averaging); } },
    { "snert",
      "SurfaceNets SNERT",
      "SurfaceNetsImageToMeshFilter, Relaxation::Combined (SNERT), defaults otherwise, itk::Mesh<double,3> output",
      true,
      [](const ExtractionInput & in) { return RunSurfaceNets(in, Relaxation::Combined); } },
    // Not in the default set:
    { "slicer",
      "Slicer labelmap DFE+Sinc0.01",
      "3D Slicer's default closed-surface conversion: thresholded labelmap, vtkDiscreteFlyingEdges3D in index "
      "space, windowed sinc 20 iterations pass band 0.01 (smoothing factor 0.5), no border padding",
      false,
      RunSlicerLabelmapPipeline },
    { "sn-hq",
      "SurfaceNets HQ",
      "SurfaceNetsImageToMeshFilter, SNERT + HighQuality (regularity swaps and SNERT rounds), defaults otherwise",
      false,
      [](const ExtractionInput & in) {
        return RunSurfaceNets(in, Relaxation::Combined, [](SurfaceNetsFilterType * f) { f->SetHighQuality(true); });
      } },
    { "sn-hq-iso",
      "SurfaceNets HQ isotropic",
      "as sn-hq, on the image resampled to cubic voxels of its smallest spacing (ResampleToIsotropicVoxels; "
      "the same as sn-hq on cubic voxels)",
      false,
      [](const ExtractionInput & in) {
        return RunSurfaceNets(in, Relaxation::Combined, [](SurfaceNetsFilterType * f) {
          f->SetHighQuality(true);
          f->SetResampleToIsotropicVoxels(true);
        });
      } },
  };
}

/** The method with that key; throws an itk::ExceptionObject listing the keys otherwise. */
inline Method
FindMethod(const std::string & key)
{
  std::string keys;
  for (const Method & m : Methods())
  {
    if (m.key == key)
    {
      return m;
    }
    keys += (keys.empty() ? "" : ", ") + m.key;
  }
  itkGenericExceptionMacro("unknown method '" << key << "'; the methods are: " << keys);
}

} // namespace MeshExtractionCompare

#endif
