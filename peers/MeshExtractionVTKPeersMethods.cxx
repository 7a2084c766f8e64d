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
// The methods of the comparison and their table (see MeshExtractionVTKPeers.h).

#include "MeshExtractionVTKPeers.h"

#include "itkBinaryMask3DMeshSource.h"
#include "itkSurfaceNetsImageToMeshFilter.h"

#include <vtkDiscreteFlyingEdges3D.h>
#include <vtkFlyingEdges3D.h>
#include <vtkImageData.h>
#include <vtkMarchingCubes.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkUnsignedCharArray.h>
#include <vtkWindowedSincPolyDataFilter.h>

#include <sstream>

namespace MeshExtractionCompare
{
namespace
{
using MaskImageType = itk::Image<unsigned char, 3>;

/** A MethodOutput around a vtkPolyData that is already in ITK physical space. */
MethodOutput
MakeVTKOutput(vtkSmartPointer<vtkPolyData> polyData, bool reverse)
{
  MethodOutput out;
  out.toIndexedMesh = [polyData, reverse]() { return PolyDataToIndexedMesh(polyData, reverse); };
  return out;
}

/** A MethodOutput around an ITK mesh (already in physical space, oriented by its filter). */
MethodOutput
MakeITKOutput(MeshType::Pointer mesh)
{
  MethodOutput out;
  out.toIndexedMesh = [mesh]() { return ME::MakeIndexedTriangleMesh(*mesh); };
  return out;
}

// ------------------------------------------------------------------------------
// VTK and 3D Slicer
// ------------------------------------------------------------------------------

/** vtkMarchingCubes on the greyscale image; normals, gradients and scalars off. */
MethodOutput
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
vtkSmartPointer<vtkPolyData>
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

MethodOutput
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
vtkSmartPointer<vtkPolyData>
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
MethodOutput
RunVTKFlyingEdgesWindowedSinc(const ExtractionInput & in)
{
  const BufferGeometry         g = GetBufferGeometry(*in.image);
  vtkSmartPointer<vtkPolyData> out = SlicerWindowedSinc(FlyingEdgesInVTKImageCoordinates(in), 0.1);
  MapToPhysicalSpace(out->GetPoints(), g);
  return MakeVTKOutput(out, VTKTrianglesNeedReversal(in.insideIsAboveIsoValue, g));
}

/** 1 where the voxel is inside (the SurfaceNets filter's classification), else 0. */
bool
IsInside(float value, const ExtractionInput & in)
{
  return in.insideIsAboveIsoValue ? value >= in.isoValue : value <= in.isoValue;
}

/** The thresholded image as a VTK labelmap in index space (1 inside, 0 outside). */
vtkSmartPointer<vtkImageData>
ThresholdedLabelmap(const ExtractionInput & in, const BufferGeometry & g)
{
  auto labels = vtkSmartPointer<vtkImageData>::New();
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
  return labels;
}

/** 3D Slicer's own default pipeline on the thresholded labelmap, in index space as
 * Slicer does: vtkDiscreteFlyingEdges3D, then windowed sinc with the pass band of its
 * default smoothing factor 0.5 (10^(-4 * 0.5) = 0.01), then the index-to-physical map.
 * (Slicer also pads a labelmap that touches the border; not done here.) */
MethodOutput
RunSlicerLabelmapPipeline(const ExtractionInput & in)
{
  const BufferGeometry             g = GetBufferGeometry(*in.image);
  vtkNew<vtkDiscreteFlyingEdges3D> dfe;
  dfe->SetInputData(ThresholdedLabelmap(in, g));
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

// ------------------------------------------------------------------------------
// ITK and this module
// ------------------------------------------------------------------------------

/** ITK's BinaryMask3DMeshSource (marching cubes on a binary mask) on the thresholded
 * image; the thresholding is part of the timed run. */
MethodOutput
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
MethodOutput
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
} // namespace

// ------------------------------------------------------------------------------
// The table
// ------------------------------------------------------------------------------
std::vector<Method>
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
      "SurfaceNetsImageToMeshFilter, SNERT + HighQuality (regularity swaps and SNERT rounds, then the sliver removal), "
      "defaults otherwise",
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
    { "sn-hq-remesh",
      "SurfaceNets HQ remeshed",
      "as sn-hq, with HighQualityRemeshing (isotropic remeshing to the mean spacing on the iso-surface, before the "
      "sliver removal)",
      false,
      [](const ExtractionInput & in) {
        return RunSurfaceNets(in, Relaxation::Combined, [](SurfaceNetsFilterType * f) {
          f->SetHighQuality(true);
          f->SetHighQualityRemeshing(true);
        });
      } },
  };
}

Method
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
