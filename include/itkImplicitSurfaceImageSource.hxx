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
#ifndef itkImplicitSurfaceImageSource_hxx
#define itkImplicitSurfaceImageSource_hxx

#include "itkImplicitSurfaceImageSource.h"
#include "itkImageRegionIteratorWithIndex.h"
#include "itkMath.h"
#include "itkNumericTraits.h"
#include "itkTotalProgressReporter.h"

#include <algorithm>
#include <cmath>
#include <type_traits>

namespace itk
{
template <typename TOutputImage>
ImplicitSurfaceImageSource<TOutputImage>::ImplicitSurfaceImageSource()
    : m_InsideValue(NumericTraits<OutputPixelType>::OneValue())
    , m_OutsideValue(NumericTraits<OutputPixelType>::ZeroValue())
{
  this->DynamicMultiThreadingOn();
}

template <typename TOutputImage>
ModifiedTimeType
ImplicitSurfaceImageSource<TOutputImage>::GetMTime() const
{
  ModifiedTimeType t = Superclass::GetMTime();
  if (m_Surface)
  {
    t = std::max(t, m_Surface->GetMTime());
  }
  return t;
}

template <typename TOutputImage>
double
ImplicitSurfaceImageSource<TOutputImage>::NormalDeviate(std::uint64_t seed, std::uint64_t index)
{
  // SplitMix64 (Steele, Lea & Flood 2014) used as a counter-based generator:
  // output n of the stream keyed by `key` is Mix(key + (n + 1) * golden).
  constexpr std::uint64_t golden = 0x9E3779B97F4A7C15ULL;
  const auto              mix = [](std::uint64_t z) {
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  };
  const std::uint64_t key = mix(seed + golden);
  const std::uint64_t a = mix(key + (2 * index + 1) * golden);
  const std::uint64_t b = mix(key + (2 * index + 2) * golden);
  constexpr double    scale = 1.0 / 9007199254740992.0;                  // 2^-53
  const double        u1 = (static_cast<double>(a >> 11) + 1.0) * scale; // (0, 1]
  const double        u2 = static_cast<double>(b >> 11) * scale;         // [0, 1)
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * itk::Math::pi * u2);
}

template <typename TOutputImage>
auto
ImplicitSurfaceImageSource<TOutputImage>::ToPixel(double value) -> OutputPixelType
{
  if constexpr (std::is_integral<OutputPixelType>::value)
  {
    if (std::isnan(value))
    {
      return NumericTraits<OutputPixelType>::ZeroValue();
    }
    const double rounded = std::round(value);
    if (rounded <= static_cast<double>(NumericTraits<OutputPixelType>::NonpositiveMin()))
    {
      return NumericTraits<OutputPixelType>::NonpositiveMin();
    }
    if (rounded >= static_cast<double>(NumericTraits<OutputPixelType>::max()))
    {
      return NumericTraits<OutputPixelType>::max();
    }
    return static_cast<OutputPixelType>(rounded);
  }
  else
  {
    return static_cast<OutputPixelType>(value);
  }
}

template <typename TOutputImage>
void
ImplicitSurfaceImageSource<TOutputImage>::BeforeThreadedGenerateData()
{
  if (!m_Surface)
  {
    itkExceptionMacro(<< "No surface: call SetSurface() with an ImplicitSurfaceFunction before Update()");
  }
  m_Surface->VerifyParameters();
  if (m_ImageMode == PhantomImageEnum::BlurredStep && !(m_EdgeWidth > 0.0 && std::isfinite(m_EdgeWidth)))
  {
    itkExceptionMacro(<< "EdgeWidth must be a finite number > 0 in BlurredStep mode, got " << m_EdgeWidth);
  }
  if (!(m_NoiseStandardDeviation >= 0.0 && std::isfinite(m_NoiseStandardDeviation)))
  {
    itkExceptionMacro(<< "NoiseStandardDeviation must be a finite number >= 0, got " << m_NoiseStandardDeviation);
  }
  if (!std::isfinite(m_DistanceScale))
  {
    itkExceptionMacro(<< "DistanceScale must be finite, got " << m_DistanceScale);
  }
  if (m_ImageMode != PhantomImageEnum::DistanceMap && m_ImageMode != PhantomImageEnum::BinaryMask &&
      m_ImageMode != PhantomImageEnum::BlurredStep)
  {
    itkExceptionMacro(<< "Unknown ImageMode " << static_cast<int>(m_ImageMode));
  }
}

template <typename TOutputImage>
void
ImplicitSurfaceImageSource<TOutputImage>::DynamicThreadedGenerateData(
  const OutputImageRegionType & outputRegionForThread)
{
  OutputImageType * output = this->GetOutput();

  const auto & largest = output->GetLargestPossibleRegion();
  const auto   start = largest.GetIndex();
  const auto   size = largest.GetSize();

  const double inside = static_cast<double>(m_InsideValue);
  const double outside = static_cast<double>(m_OutsideValue);
  const double edgeScale = 1.0 / (m_EdgeWidth * std::sqrt(2.0));
  const bool   addNoise = m_NoiseStandardDeviation > 0.0;

  TotalProgressReporter progress(this, output->GetRequestedRegion().GetNumberOfPixels());

  typename SurfaceType::InputType               point;
  ImageRegionIteratorWithIndex<OutputImageType> it(output, outputRegionForThread);
  for (it.GoToBegin(); !it.IsAtEnd(); ++it)
  {
    const auto & index = it.GetIndex();
    output->TransformIndexToPhysicalPoint(index, point);
    const double distance = m_Surface->Evaluate(point);

    double value = 0.0;
    switch (m_ImageMode)
    {
      case PhantomImageEnum::DistanceMap:
        value = distance * m_DistanceScale;
        break;
      case PhantomImageEnum::BinaryMask:
        value = distance <= 0.0 ? inside : outside;
        break;
      case PhantomImageEnum::BlurredStep:
        value = outside + (inside - outside) * 0.5 * std::erfc(distance * edgeScale);
        break;
    }
    if (addNoise)
    {
      const std::uint64_t linear =
        static_cast<std::uint64_t>(index[0] - start[0]) +
        static_cast<std::uint64_t>(size[0]) *
          (static_cast<std::uint64_t>(index[1] - start[1]) +
           static_cast<std::uint64_t>(size[1]) * static_cast<std::uint64_t>(index[2] - start[2]));
      value += m_NoiseStandardDeviation * NormalDeviate(m_NoiseSeed, linear);
    }
    it.Set(ToPixel(value));
    progress.CompletedPixel();
  }
}

template <typename TOutputImage>
void
ImplicitSurfaceImageSource<TOutputImage>::PrintSelf(std::ostream & os, Indent indent) const
{
  Superclass::PrintSelf(os, indent);
  os << indent << "Surface: ";
  if (m_Surface)
  {
    os << m_Surface->GetNameOfClass() << " (" << m_Surface.GetPointer() << ")" << std::endl;
  }
  else
  {
    os << "(none)" << std::endl;
  }
  os << indent << "ImageMode: " << m_ImageMode << std::endl;
  os << indent << "DistanceScale: " << m_DistanceScale << std::endl;
  os << indent << "InsideValue: " << static_cast<typename NumericTraits<OutputPixelType>::PrintType>(m_InsideValue)
     << std::endl;
  os << indent << "OutsideValue: " << static_cast<typename NumericTraits<OutputPixelType>::PrintType>(m_OutsideValue)
     << std::endl;
  os << indent << "EdgeWidth: " << m_EdgeWidth << std::endl;
  os << indent << "NoiseStandardDeviation: " << m_NoiseStandardDeviation << std::endl;
  os << indent << "NoiseSeed: " << m_NoiseSeed << std::endl;
}
} // namespace itk

#endif
