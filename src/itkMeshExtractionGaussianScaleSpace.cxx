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
#include "itkMeshExtractionGaussianScaleSpace.h"
#include "itkGaussianDerivativeOperator.h"

#include <algorithm>
#include <cmath>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
std::vector<double>
ScaleSpaceScales(double maximumScale, double minimumScale, unsigned int scalesPerOctave)
{
  std::vector<double> scales;
  if (!(maximumScale > 0.0) || !(minimumScale > 0.0) || !std::isfinite(maximumScale) || !std::isfinite(minimumScale) ||
      scalesPerOctave == 0)
  {
    return scales;
  }
  if (maximumScale <= minimumScale * (1.0 + 1e-9))
  {
    scales.push_back(maximumScale);
    return scales;
  }
  const double       octaves = std::log2(maximumScale / minimumScale);
  const unsigned int steps = std::max(1u, static_cast<unsigned int>(std::ceil(scalesPerOctave * octaves - 1e-9)));
  scales.reserve(steps + 1);
  for (unsigned int i = 0; i <= steps; ++i)
  {
    scales.push_back(maximumScale * std::pow(minimumScale / maximumScale, static_cast<double>(i) / steps));
  }
  scales.back() = minimumScale;
  return scales;
}

double
ParabolicPeakOffset(double below, double centre, double above, double h)
{
  const double curvature = below - 2.0 * centre + above;
  if (!(curvature < 0.0))
  {
    return 0.0;
  }
  return std::clamp(0.5 * h * (below - above) / curvature, -0.5 * h, 0.5 * h);
}

std::vector<float>
GaussianKernel(double sigma, double spacing, unsigned int order)
{
  GaussianDerivativeOperator<double, 1> op;
  op.SetDirection(0);
  op.SetSpacing(spacing);
  op.SetVariance(sigma * sigma);
  op.SetOrder(order);
  op.SetNormalizeAcrossScale(false);
  op.SetMaximumError(GaussianKernelMaximumError);
  op.SetMaximumKernelWidth(100000);
  op.CreateDirectional();
  const unsigned int  n = static_cast<unsigned int>(op.GetSize()[0]);
  const int           r = static_cast<int>(n / 2);
  std::vector<double> k(n);
  Offset<1>           o;
  o.Fill(0);
  for (unsigned int i = 0; i < n; ++i)
  {
    o[0] = static_cast<OffsetValueType>(static_cast<int>(i) - r);
    k[i] = op[op.GetNeighborhoodIndex(o)];
  }
  if (order == 1)
  {
    // On in[x] = x * spacing this must give exactly +1 (the truncated, clamped kernel
    // gives only about 1, with the sign of ITK's convention): a ramp's gradient is
    // then exact.
    double slope = 0.0;
    for (unsigned int i = 0; i < n; ++i)
    {
      slope += k[i] * (static_cast<double>(i) - r) * spacing;
    }
    if (slope != 0.0)
    {
      for (auto & v : k)
      {
        v /= slope;
      }
    }
  }
  return std::vector<float>(k.begin(), k.end());
}

} // namespace detail
} // namespace MeshExtraction
} // namespace itk
