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
#ifndef itkImplicitSurfaceImageSource_h
#define itkImplicitSurfaceImageSource_h

#include "itkGenerateImageSource.h"
#include "itkImplicitSurfaceFunction.h"
#include "itkMeshExtractionEnums.h"
#include "itkMeshExtractionMacros.h"

#include <cstdint>

namespace itk
{
/** \class ImplicitSurfaceImageSource
 * \brief Renders an ImplicitSurfaceFunction into a 3-D image: a phantom with a
 * known, exact surface.
 *
 * Every voxel is sampled at its physical point (TransformIndexToPhysicalPoint, so
 * spacing, origin and direction are honoured), where d is the surface's signed
 * distance (mm, negative inside). The ImageMode selects the value:
 *
 * - DistanceMap (default): d * DistanceScale.
 * - BinaryMask: InsideValue where d <= 0, OutsideValue elsewhere.
 * - BlurredStep: a step edge blurred by a Gaussian of standard deviation
 *   EdgeWidth (mm): Outside + (Inside - Outside) * 0.5 * erfc(d / (EdgeWidth sqrt 2)),
 *   i.e. exactly (Inside + Outside) / 2 on the surface. This is the image of a
 *   planar edge seen through a Gaussian point-spread function.
 *
 * NoiseStandardDeviation > 0 adds Gaussian noise in every mode. Each voxel's
 * deviate is a pure function of (NoiseSeed, the voxel's linear index in the largest
 * possible region) — a counter-based SplitMix64 hash fed to Box-Muller — so the
 * image is the same for any number of threads or work units, and any requested
 * region holds the same values as the whole image.
 *
 * For integer pixel types the value is rounded to the nearest integer (halves away
 * from zero) and clamped to the pixel type's range; floating-point pixel types get
 * the value as is.
 *
 * Size, Spacing, Origin, Direction and StartIndex are those of
 * GenerateImageSource (default 64^3 voxels of 1 mm at the origin).
 *
 * \ingroup MeshExtraction
 */
template <typename TOutputImage>
class ITK_TEMPLATE_EXPORT ImplicitSurfaceImageSource : public GenerateImageSource<TOutputImage>
{
public:
  ITK_DISALLOW_COPY_AND_MOVE(ImplicitSurfaceImageSource);

  using Self = ImplicitSurfaceImageSource;
  using Superclass = GenerateImageSource<TOutputImage>;
  using Pointer = SmartPointer<Self>;
  using ConstPointer = SmartPointer<const Self>;

  itkOverrideGetNameOfClassMacro(ImplicitSurfaceImageSource);
  itkNewMacro(Self);

  using OutputImageType = TOutputImage;
  using OutputImageRegionType = typename OutputImageType::RegionType;
  using OutputPixelType = typename OutputImageType::PixelType;
  using SurfaceType = ImplicitSurfaceFunction;
  using PhantomImageEnum = MeshExtractionEnums::PhantomImage;

  static constexpr unsigned int ImageDimension = TOutputImage::ImageDimension;
  static_assert(ImageDimension == 3, "ImplicitSurfaceImageSource renders 3-D surfaces into 3-D images");

  /** The surface to render (required). */
  itkSetConstObjectMacro(Surface, SurfaceType);
  itkGetConstObjectMacro(Surface, SurfaceType);

  /** DistanceMap (default), BinaryMask or BlurredStep. */
  itkSetEnumMacro(ImageMode, PhantomImageEnum);
  itkGetEnumMacro(ImageMode, PhantomImageEnum);

  /** DistanceMap mode: the value is the signed distance times this (default 1). */
  itkSetMacro(DistanceScale, double);
  itkGetConstMacro(DistanceScale, double);

  /** BinaryMask and BlurredStep: value inside (default 1) and outside (default 0). */
  itkSetMacro(InsideValue, OutputPixelType);
  itkGetConstMacro(InsideValue, OutputPixelType);
  itkSetMacro(OutsideValue, OutputPixelType);
  itkGetConstMacro(OutsideValue, OutputPixelType);

  /** BlurredStep: standard deviation (mm) of the Gaussian blur, > 0 (default 1). */
  itkSetMacro(EdgeWidth, double);
  itkGetConstMacro(EdgeWidth, double);

  /** Standard deviation of the additive Gaussian noise, >= 0 (default 0: none). */
  itkSetMacro(NoiseStandardDeviation, double);
  itkGetConstMacro(NoiseStandardDeviation, double);

  /** Seed of the noise (default 0). */
  itkSetMacro(NoiseSeed, std::uint64_t);
  itkGetConstMacro(NoiseSeed, std::uint64_t);

  /** The standard normal deviate used for the voxel with linear index `index`:
   * Box-Muller on two uniforms that are SplitMix64 outputs number 2 index and
   * 2 index + 1 of the stream keyed by `seed`. Deterministic and thread-free. */
  static double
  NormalDeviate(std::uint64_t seed, std::uint64_t index);

  /** Includes the surface's modification time. */
  ModifiedTimeType
  GetMTime() const override;

protected:
  ImplicitSurfaceImageSource();
  ~ImplicitSurfaceImageSource() override = default;
  void
  PrintSelf(std::ostream & os, Indent indent) const override;

  /** Checks the surface and the parameters (in the calling thread). */
  void
  BeforeThreadedGenerateData() override;

  void
  DynamicThreadedGenerateData(const OutputImageRegionType & outputRegionForThread) override;

private:
  static OutputPixelType
  ToPixel(double value);

  typename SurfaceType::ConstPointer m_Surface;
  PhantomImageEnum                   m_ImageMode{ PhantomImageEnum::DistanceMap };
  double                             m_DistanceScale{ 1.0 };
  OutputPixelType                    m_InsideValue;
  OutputPixelType                    m_OutsideValue;
  double                             m_EdgeWidth{ 1.0 };
  double                             m_NoiseStandardDeviation{ 0.0 };
  std::uint64_t                      m_NoiseSeed{ 0 };
};
} // namespace itk

#ifndef ITK_MANUAL_INSTANTIATION
#  include "itkImplicitSurfaceImageSource.hxx"
#endif

#endif
