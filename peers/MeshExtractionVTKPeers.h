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
#ifndef MeshExtractionVTKPeers_h
#define MeshExtractionVTKPeers_h

// The surface-extraction methods SurfaceNets is compared with, as a table of name ->
// function: VTK's marching cubes and flying edges (plain and with 3D Slicer's
// windowed-sinc smoothing), 3D Slicer's labelmap pipeline, ITK's
// BinaryMask3DMeshSource and this module's own SurfaceNets modes. Used by
// meshextraction-compare, the VTK comparison test and the benchmarks (the
// MeshExtractionVTKPeers library, peers/MeshExtractionVTKPeers.cmake).
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
// To add a method, append an entry to Methods() (MeshExtractionVTKPeersMethods.cxx).

#include "itkImage.h"
#include "itkMesh.h"
#include "itkMeshExtractionIndexedTriangleMesh.h"

#include <vtkSmartPointer.h>

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

class vtkImageData;
class vtkPoints;
class vtkPolyData;

namespace MeshExtractionCompare
{
namespace ME = itk::MeshExtraction;
using ImageType = itk::Image<float, 3>;
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
// The methods (MeshExtractionVTKPeersMethods.cxx)
// ------------------------------------------------------------------------------

/** The comparison's rows, in table order. */
std::vector<Method>
Methods();

/** The method with that key; throws an itk::ExceptionObject listing the keys otherwise. */
Method
FindMethod(const std::string & key);

// ------------------------------------------------------------------------------
// Between ITK and VTK (MeshExtractionVTKPeersConversion.cxx)
// ------------------------------------------------------------------------------

/** Index-to-physical mapping of an image's buffer. */
struct BufferGeometry
{
  itk::Point<double, 3>     first;     ///< physical point of the buffer's first voxel
  itk::Matrix<double, 3, 3> direction; ///< ITK direction cosines
  itk::Vector<double, 3>    spacing;
  itk::Size<3>              size;

  /** Whether the direction has determinant -1. */
  bool
  IsMirrored() const;
};

BufferGeometry
GetBufferGeometry(const ImageType & image);

/** A vtkImageData that shares the ITK image's buffer (no copy): dimensions of the
 * buffer, origin 0, and the ITK spacing (or unit spacing for `indexSpace`). */
vtkSmartPointer<vtkImageData>
WrapAsVTKImage(const ImageType & image, bool indexSpace = false);

/** Map points from VTK image coordinates (origin 0; ITK spacing, or unit spacing if
 * `indexSpace`) to ITK physical space, in place: p = first + D (S .* x or x). */
void
MapToPhysicalSpace(vtkPoints * points, const BufferGeometry & g, bool indexSpace = false);

/** Whether the triangles of VTK's iso-surface filters (vtkMarchingCubes,
 * vtkFlyingEdges3D, vtkDiscreteFlyingEdges3D) must be reversed to face out of the
 * object. Their winding makes the normals point toward decreasing scalars: an object
 * above the iso-value (CT bone, a label) comes out facing outward, a signed distance
 * map's object (inside below) facing inward. A mirroring direction (determinant -1)
 * reverses the winding once more. (Checked by the VTK comparison tests on both
 * conventions and on a mirrored grid.) */
bool
VTKTrianglesNeedReversal(bool insideIsAboveIsoValue, const BufferGeometry & g);

/** Points and triangles of a vtkPolyData (polygons must be triangles); every
 * triangle reversed if `reverse`. */
ME::IndexedTriangleMesh
PolyDataToIndexedMesh(vtkPolyData * polyData, bool reverse);

/** Drop the points no triangle uses (vtkMarchingCubes leaves some where it removes a
 * degenerate triangle at an exact tie with the iso-value): they are not vertices of the
 * surface and would count in the vertex distances. Returns how many were dropped. */
std::size_t
DropUnreferencedPoints(ME::IndexedTriangleMesh & mesh);

/** The mesh of a run as the comparison measures it: flat arrays in ITK physical space,
 * outward, without unreferenced points (their number goes to `dropped`). */
ME::IndexedTriangleMesh
MeshForMeasurement(const MethodOutput & output, std::size_t * dropped = nullptr);

} // namespace MeshExtractionCompare

#endif
