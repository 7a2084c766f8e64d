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

#include "itkMeshExtractionBuffer.h"
#include "itkMeshExtractionParallel.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
namespace
{
/** The grid of a mask's region: sizes and strides, the voxels in x-fastest order. */
struct Grid
{
  std::int64_t n[3];
  std::int64_t stride[3];
  std::size_t  count;

  explicit Grid(const Image<std::uint8_t, 3> * mask)
  {
    const auto size = mask->GetBufferedRegion().GetSize();
    for (unsigned int d = 0; d < 3; ++d)
    {
      n[d] = static_cast<std::int64_t>(size[d]);
    }
    stride[0] = 1;
    stride[1] = n[0];
    stride[2] = n[0] * n[1];
    count = static_cast<std::size_t>(n[0] * n[1] * n[2]);
  }
};

constexpr float Far = std::numeric_limits<float>::max();

/** The 1-D squared distance transform of sampled function f (Felzenszwalb and
 * Huttenlocher's lower envelope of parabolas): d[q] = min_p (q - p)^2 + f[p], Far
 * where every f is Far. `v` and `z` are scratch of n and n + 1 entries. */
void
SquaredDistance1D(const float * f, float * d, std::int64_t n, std::vector<std::int64_t> & v, std::vector<double> & z)
{
  std::int64_t k = -1;
  for (std::int64_t q = 0; q < n; ++q)
  {
    if (f[q] >= Far)
    {
      continue;
    }
    if (k < 0)
    {
      k = 0;
      v[0] = q;
      z[0] = -std::numeric_limits<double>::infinity();
      z[1] = std::numeric_limits<double>::infinity();
      continue;
    }
    double s = 0.0;
    for (;;)
    {
      const std::int64_t p = v[k];
      s =
        ((f[q] + static_cast<double>(q * q)) - (f[p] + static_cast<double>(p * p))) / static_cast<double>(2 * (q - p));
      if (s > z[k])
      {
        break;
      }
      --k; // z[0] is -infinity: k stays >= 0
    }
    ++k;
    v[k] = q;
    z[k] = s;
    z[k + 1] = std::numeric_limits<double>::infinity();
  }
  if (k < 0)
  {
    std::fill(d, d + n, Far);
    return;
  }
  k = 0;
  for (std::int64_t q = 0; q < n; ++q)
  {
    while (z[k + 1] < static_cast<double>(q))
    {
      ++k;
    }
    const std::int64_t p = v[k];
    d[q] = static_cast<float>(static_cast<double>((q - p) * (q - p)) + f[p]);
  }
}

/** Squared distances (voxels) of every voxel to the nearest voxel whose mask value is
 * `feature`, in place in `d`: one pass of SquaredDistance1D per axis, the lines of
 * each pass in parallel. */
void
SquaredDistanceToFeature(const Grid & g, const std::uint8_t * mask, std::uint8_t feature, float * d)
{
  for (std::size_t i = 0; i < g.count; ++i)
  {
    d[i] = mask[i] == feature ? 0.0f : Far;
  }
  for (unsigned int axis = 0; axis < 3; ++axis)
  {
    const unsigned int a = (axis + 1) % 3;
    const unsigned int b = (axis + 2) % 3;
    const std::int64_t n = g.n[axis];
    const std::int64_t lines = g.n[a] * g.n[b];
    ParallelForBlocks(static_cast<std::size_t>(lines), 256, [&](std::size_t begin, std::size_t end, std::size_t) {
      std::vector<float>        in(n);
      std::vector<float>        out(n);
      std::vector<std::int64_t> v(n);
      std::vector<double>       z(n + 1);
      for (std::size_t line = begin; line < end; ++line)
      {
        const std::int64_t ia = static_cast<std::int64_t>(line) % g.n[a];
        const std::int64_t ib = static_cast<std::int64_t>(line) / g.n[a];
        float *            base = d + ia * g.stride[a] + ib * g.stride[b];
        for (std::int64_t q = 0; q < n; ++q)
        {
          in[q] = base[q * g.stride[axis]];
        }
        SquaredDistance1D(in.data(), out.data(), n, v, z);
        for (std::int64_t q = 0; q < n; ++q)
        {
          base[q * g.stride[axis]] = out[q];
        }
      }
    });
  }
}

/** The sampled Gaussian of `sigma` voxels (sum 1) and its second derivative (sum 0,
 * second moment 2: exact on quadratics), over [-radius, radius]. */
void
GaussianKernels(double sigma, std::int64_t radius, std::vector<float> & smooth, std::vector<float> & second)
{
  std::vector<double> g(2 * radius + 1);
  std::vector<double> h(2 * radius + 1);
  double              sum = 0.0;
  for (std::int64_t k = -radius; k <= radius; ++k)
  {
    g[k + radius] = std::exp(-0.5 * static_cast<double>(k * k) / (sigma * sigma));
    sum += g[k + radius];
  }
  double mean = 0.0;
  for (std::int64_t k = -radius; k <= radius; ++k)
  {
    g[k + radius] /= sum;
    h[k + radius] = g[k + radius] * (static_cast<double>(k * k) / (sigma * sigma) - 1.0) / (sigma * sigma);
    mean += h[k + radius];
  }
  mean /= static_cast<double>(h.size());
  double moment = 0.0;
  for (std::int64_t k = -radius; k <= radius; ++k)
  {
    h[k + radius] -= mean;
    moment += static_cast<double>(k * k) * h[k + radius];
  }
  smooth.assign(g.begin(), g.end());
  second.resize(h.size());
  for (std::size_t i = 0; i < h.size(); ++i)
  {
    second[i] = static_cast<float>(2.0 * h[i] / moment);
  }
}

/** out = kernel (along `axis`) * in, for any number of kernels at once (each with its
 * own input and output), the image's border voxels repeated beyond it. Whole rows at a
 * time, in parallel over the slices. */
struct Convolution
{
  const float * in;
  float *       out;
  const float * kernel;
};

void
Convolve(const Grid & g, unsigned int axis, std::int64_t radius, const std::vector<Convolution> & convolutions)
{
  const std::int64_t nx = g.n[0];
  ParallelForBlocks(static_cast<std::size_t>(g.n[2]), 1, [&](std::size_t begin, std::size_t end, std::size_t) {
    std::vector<float> padded(nx + 2 * radius);
    for (std::int64_t z = static_cast<std::int64_t>(begin); z < static_cast<std::int64_t>(end); ++z)
    {
      for (std::int64_t y = 0; y < g.n[1]; ++y)
      {
        const std::int64_t row = z * g.stride[2] + y * g.stride[1];
        for (const Convolution & c : convolutions)
        {
          float * out = c.out + row;
          if (axis == 0)
          {
            const float * in = c.in + row;
            std::fill(padded.begin(), padded.begin() + radius, in[0]);
            std::copy(in, in + nx, padded.begin() + radius);
            std::fill(padded.begin() + radius + nx, padded.end(), in[nx - 1]);
            for (std::int64_t x = 0; x < nx; ++x)
            {
              float sum = 0.0f;
              for (std::int64_t k = 0; k <= 2 * radius; ++k)
              {
                sum += c.kernel[k] * padded[x + k];
              }
              out[x] = sum;
            }
            continue;
          }
          const std::int64_t at = axis == 1 ? y : z;
          std::fill(out, out + nx, 0.0f);
          for (std::int64_t k = -radius; k <= radius; ++k)
          {
            const std::int64_t source = std::clamp<std::int64_t>(at + k, 0, g.n[axis] - 1);
            const float *      in = c.in + row + (source - at) * g.stride[axis];
            const float        w = c.kernel[k + radius];
            for (std::int64_t x = 0; x < nx; ++x)
            {
              out[x] += w * in[x];
            }
          }
        }
      }
    }
  });
}

/** Where the smooth function contradicts the mask at a voxel centre (an inside voxel at
 * or above 0, an outside one below), and at the six neighbours of such a voxel, the
 * function becomes the unsmoothed signed distance `phi` again. On parts thinner than
 * about the Gaussian's width (a plate or a vessel of a voxel or two) smoothing lifts
 * the whole part above 0 and the surface would collapse into it; there the staircase
 * is kept instead. Elsewhere the smooth surface crosses a voxel centre only now and
 * then, where it rounds a stair off, and those few voxels keep the staircase. */
void
KeepThinPartsOfTheMask(const Grid & g, const std::uint8_t * m, const float * p, float * f)
{
  std::vector<std::uint8_t> contradicts(g.count);
  for (std::size_t i = 0; i < g.count; ++i)
  {
    contradicts[i] = static_cast<std::uint8_t>(m[i] != 0 ? f[i] >= 0.0f : f[i] < 0.0f);
  }
  const std::int64_t nx = g.n[0];
  const std::int64_t ny = g.n[1];
  const std::int64_t nz = g.n[2];
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

std::int64_t
LabelSurfaceMargin(double sigma)
{
  // Four standard deviations of the Gaussian, the central differences of the
  // relaxation (one voxel) and a node up to half a voxel outside its cell.
  return static_cast<std::int64_t>(std::ceil(4.0 * sigma)) + 3;
}

void
MakeLabelSurfaceFunction(const Image<std::uint8_t, 3> * mask,
                         double                         sigma,
                         Image<float, 3> *              function,
                         unsigned int                   numberOfWorkUnits)
{
  const ScopedNumberOfWorkUnits workUnits(numberOfWorkUnits > 0 ? numberOfWorkUnits : ThreadNumberOfWorkUnits());
  const Grid                    g(mask);
  const std::uint8_t *          m = mask->GetBufferPointer();
  // phi, the signed distance to the voxel faces between inside and outside (half a
  // voxel from the centres), negative inside: from the distances between voxel centres
  // of an inside voxel to the nearest outside one and of an outside voxel to the
  // nearest inside one (exact Euclidean distance transforms).
  // Five region-sized scratch arrays, reused from pass to pass: fresh memory costs the
  // system's page clearing on first touch.
  UninitializedArray<float> phi(g.count);
  UninitializedArray<float> t1(g.count);
  UninitializedArray<float> t2(g.count);
  UninitializedArray<float> t3(g.count);
  UninitializedArray<float> t4(g.count);
  SquaredDistanceToFeature(g, m, 0, phi.data());
  SquaredDistanceToFeature(g, m, 1, t1.data());
  for (std::size_t i = 0; i < g.count; ++i)
  {
    phi[i] = m[i] != 0 ? 0.5f - std::sqrt(phi[i]) : std::sqrt(t1[i]) - 0.5f;
  }
  // f = G * phi - sigma^2 / 2 * Laplacian(G * phi), separably: along x the Gaussian (A,
  // in t1) and its second derivative (B, t2); along y, AA = G A (t3) and
  // E = AA - c (G'' A + G B) (t4, with G'' A in f meanwhile); along z,
  // f = G E - c G'' AA (G'' AA in t1).
  const std::int64_t radius = static_cast<std::int64_t>(std::ceil(4.0 * sigma));
  std::vector<float> smooth;
  std::vector<float> second;
  GaussianKernels(sigma, radius, smooth, second);
  const float c = static_cast<float>(0.5 * sigma * sigma);
  float *     f = function->GetBufferPointer();
  Convolve(g, 0, radius, { { phi.data(), t1.data(), smooth.data() }, { phi.data(), t2.data(), second.data() } });
  Convolve(g,
           1,
           radius,
           { { t1.data(), t3.data(), smooth.data() },
             { t1.data(), f, second.data() },
             { t2.data(), t4.data(), smooth.data() } });
  for (std::size_t i = 0; i < g.count; ++i)
  {
    t4[i] = t3[i] - c * (f[i] + t4[i]);
  }
  Convolve(g, 2, radius, { { t4.data(), f, smooth.data() }, { t3.data(), t1.data(), second.data() } });
  for (std::size_t i = 0; i < g.count; ++i)
  {
    f[i] -= c * t1[i];
  }
  KeepThinPartsOfTheMask(g, m, phi.data(), f);
}
} // namespace detail
} // namespace MeshExtraction
} // namespace itk
