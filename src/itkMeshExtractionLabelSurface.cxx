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
#include "itkMeshExtractionLabelSurface.h"

#include "itkImageRegionConstIterator.h"
#include "itkImageRegionIterator.h"
#include "itkLaplacianRecursiveGaussianImageFilter.h"
#include "itkSignedMaurerDistanceMapImageFilter.h"
#include "itkSmoothingRecursiveGaussianImageFilter.h"

#include <cmath>
#include <vector>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
std::int64_t
LabelSurfaceMargin(double sigma)
{
  // Four standard deviations of the Gaussian, the central differences of the
  // relaxation (one voxel) and a node up to half a voxel outside its cell.
  return static_cast<std::int64_t>(std::ceil(4.0 * sigma)) + 3;
}

namespace
{
/** Where the smooth function contradicts the mask at a voxel centre (an inside voxel at
 * or above 0, an outside one below), and at the six neighbours of such a voxel, the
 * function becomes the unsmoothed signed distance `phi` again. On parts thinner than
 * about the Gaussian's width (a plate or a vessel of a voxel or two) smoothing lifts
 * the whole part above 0 and the surface would collapse into it; there the staircase
 * is kept instead. Elsewhere the smooth surface crosses a voxel centre only now and
 * then, where it rounds a stair off, and those few voxels keep the staircase. */
void
KeepThinPartsOfTheMask(const Image<std::uint8_t, 3> * mask, const Image<float, 3> * phi, Image<float, 3> * function)
{
  const auto                size = mask->GetBufferedRegion().GetSize();
  const std::int64_t        nx = static_cast<std::int64_t>(size[0]);
  const std::int64_t        ny = static_cast<std::int64_t>(size[1]);
  const std::int64_t        nz = static_cast<std::int64_t>(size[2]);
  const std::uint8_t *      m = mask->GetBufferPointer();
  const float *             p = phi->GetBufferPointer();
  float *                   f = function->GetBufferPointer();
  const std::size_t         n = static_cast<std::size_t>(nx * ny * nz);
  std::vector<std::uint8_t> contradicts(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    contradicts[i] = static_cast<std::uint8_t>(m[i] != 0 ? f[i] >= 0.0f : f[i] < 0.0f);
  }
  for (std::int64_t z = 0; z < nz; ++z)
  {
    for (std::int64_t y = 0; y < ny; ++y)
    {
      for (std::int64_t x = 0; x < nx; ++x)
      {
        const std::int64_t i = (z * ny + y) * nx + x;
        const bool near = contradicts[i] || (x > 0 && contradicts[i - 1]) || (x + 1 < nx && contradicts[i + 1]) ||
                          (y > 0 && contradicts[i - nx]) || (y + 1 < ny && contradicts[i + nx]) ||
                          (z > 0 && contradicts[i - nx * ny]) || (z + 1 < nz && contradicts[i + nx * ny]);
        if (near)
        {
          f[i] = p[i];
        }
      }
    }
  }
}
} // namespace

void
MakeLabelSurfaceFunction(const Image<std::uint8_t, 3> * mask,
                         double                         sigma,
                         Image<float, 3> *              function,
                         unsigned int                   numberOfWorkUnits)
{
  using MaskType = Image<std::uint8_t, 3>;
  using FloatImageType = Image<float, 3>;
  // Distances between voxel centres: of an outside voxel to the nearest inside one (the
  // mask's map) and of an inside voxel to the nearest outside one (the complement's
  // map). SignedMaurerDistanceMapImageFilter measures to the object's contour voxels,
  // which are the nearest voxels of the object, so each map is right on the side
  // where it is read; one map alone puts inside voxels that touch the outside only
  // diagonally at distance 0 and the surface too far in.
  auto distanceTo = [numberOfWorkUnits](const MaskType * object) {
    auto distance = SignedMaurerDistanceMapImageFilter<MaskType, FloatImageType>::New();
    distance->SetInput(object);
    distance->SetBackgroundValue(0);
    distance->SetInsideIsPositive(false);
    distance->SetSquaredDistance(false);
    distance->SetUseImageSpacing(false);
    if (numberOfWorkUnits > 0)
    {
      distance->SetNumberOfWorkUnits(numberOfWorkUnits);
    }
    distance->Update();
    FloatImageType::Pointer map = distance->GetOutput();
    map->DisconnectPipeline();
    return map;
  };
  auto complement = MaskType::New();
  complement->CopyInformation(mask);
  complement->SetRegions(mask->GetBufferedRegion());
  complement->Allocate();
  const std::size_t    n = mask->GetBufferedRegion().GetNumberOfPixels();
  const std::uint8_t * in = mask->GetBufferPointer();
  std::uint8_t *       out = complement->GetBufferPointer();
  for (std::size_t i = 0; i < n; ++i)
  {
    out[i] = static_cast<std::uint8_t>(in[i] == 0);
  }
  FloatImageType::Pointer phi = distanceTo(mask);
  {
    const FloatImageType::Pointer toOutside = distanceTo(complement);
    complement = nullptr;
    // phi: the signed distance to the voxel faces between inside and outside, which
    // lie half a voxel from the centres, negative inside.
    float *       p = phi->GetBufferPointer();
    const float * o = toOutside->GetBufferPointer();
    for (std::size_t i = 0; i < n; ++i)
    {
      p[i] = in[i] != 0 ? 0.5f - o[i] : p[i] - 0.5f;
    }
  }

  auto smooth = SmoothingRecursiveGaussianImageFilter<FloatImageType, FloatImageType>::New();
  smooth->SetInput(phi);
  smooth->SetSigma(sigma);
  smooth->SetNormalizeAcrossScale(false);
  auto laplacian = LaplacianRecursiveGaussianImageFilter<FloatImageType, FloatImageType>::New();
  laplacian->SetInput(phi);
  laplacian->SetSigma(sigma);
  laplacian->SetNormalizeAcrossScale(false);
  if (numberOfWorkUnits > 0)
  {
    smooth->SetNumberOfWorkUnits(numberOfWorkUnits);
    laplacian->SetNumberOfWorkUnits(numberOfWorkUnits);
  }
  smooth->Update();
  laplacian->Update();

  const double                             correction = 0.5 * sigma * sigma;
  ImageRegionConstIterator<FloatImageType> s(smooth->GetOutput(), mask->GetBufferedRegion());
  ImageRegionConstIterator<FloatImageType> l(laplacian->GetOutput(), mask->GetBufferedRegion());
  ImageRegionIterator<FloatImageType>      f(function, mask->GetBufferedRegion());
  for (; !f.IsAtEnd(); ++s, ++l, ++f)
  {
    f.Set(static_cast<float>(static_cast<double>(s.Get()) - correction * static_cast<double>(l.Get())));
  }
  KeepThinPartsOfTheMask(mask, phi, function);
}
} // namespace detail
} // namespace MeshExtraction
} // namespace itk
