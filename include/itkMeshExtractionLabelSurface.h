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
// Internal to MeshExtraction (namespace detail): not part of the public API.
#ifndef itkMeshExtractionLabelSurface_h
#define itkMeshExtractionLabelSurface_h

#include "MeshExtractionExport.h"
#include "itkImage.h"

#include <cstdint>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
/** \brief The smooth surface a label image's voxels stand for: the implicit function
 * the high-quality mode relaxes a label surface toward (SurfaceNetsImageToMeshFilter's
 * LabelSurfaceSigma), so that it keeps the surface where the segmentation puts it.
 *
 * The object's boundary in a mask is the staircase of voxel faces between inside and
 * outside voxels. Its signed distance at the voxel centres (index units, negative
 * inside: half a voxel less than the exact Euclidean distance from an inside voxel to
 * the nearest outside one, or from an outside voxel to the nearest inside one) is
 * smoothed by a Gaussian of `sigma` voxels, which rounds the stairs off. Smoothing a
 * signed distance moves its zero level inward by sigma^2/2 times its Laplacian (the
 * sum of the principal curvatures): that first-order shift is added back, from the
 * Laplacian of the same Gaussian, so that convex and thin parts do not shrink:
 * f = G * phi - sigma^2/2 * Laplacian(G * phi). Where f contradicts the mask at a voxel
 * centre (parts thinner than the Gaussian), that voxel and its neighbours keep phi.
 *
 * `mask` holds 1 inside and 0 outside over a region that extends some voxels beyond
 * the object (and beyond the image, as outside: the net closes objects at the image
 * border half a voxel beyond it, and so does f); `function` gets f on the mask's grid
 * (index space). Separable passes (distance transforms, then the Gaussian and its
 * second derivative along each axis), each in parallel on `numberOfWorkUnits` (0: the
 * calling thread's ParallelForBlocks default). */
MeshExtraction_EXPORT void
MakeLabelSurfaceFunction(const Image<std::uint8_t, 3> * mask,
                         double                         sigma,
                         Image<float, 3> *              function,
                         unsigned int                   numberOfWorkUnits);

/** The margin, in voxels, a mask needs around the object for MakeLabelSurfaceFunction
 * at `sigma`: the Gaussian's support, its central differences and a dilated cell. */
MeshExtraction_EXPORT std::int64_t
                      LabelSurfaceMargin(double sigma);
} // namespace detail
} // namespace MeshExtraction
} // namespace itk

#endif
