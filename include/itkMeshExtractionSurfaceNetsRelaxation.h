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
#ifndef itkMeshExtractionSurfaceNetsRelaxation_h
#define itkMeshExtractionSurfaceNetsRelaxation_h

#include "itkMeshExtractionBuffer.h"
#include "itkMeshExtractionGaussianScaleSpace.h"
#include "itkMeshExtractionMacros.h"
#include "itkMeshExtractionParallel.h"
#include "itkMeshExtractionSurfaceNets.h"
#include "itkSurfaceNetsImageToMeshFilterEnums.h"
#include "itkImage.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <type_traits>
#if defined(__SSE2__)
#  include <emmintrin.h>
#  include <xmmintrin.h>
#endif

namespace itk
{
namespace MeshExtraction
{
/** \brief Trilinear interpolation and central-difference gradients of an image in
 * continuous index space (relative to the buffer's first voxel), extended beyond
 * the image so that everything outside it is outside the object.
 *
 * A voxel beyond the border reads as the nearest border voxel mirrored to the
 * outside of the iso-value: iso + max(|v - iso|, epsilon) on the outside side.
 * The iso-surface then closes an object that touches the border exactly half a
 * voxel beyond it, as a flat cap that meets the rest of the surface without a
 * spurious ridge. ITK's interpolators require points inside the buffer
 * (IsInsideBuffer), and the SurfaceNet reaches half a voxel beyond it, hence this
 * sampler. \ingroup MeshExtraction */
template <typename TImage>
class SurfaceNetsSampler
{
public:
  using PixelType = typename TImage::PixelType;

  /** `outsideSign` is +1 if the outside of the object is above the iso-value, -1 if below. */
  SurfaceNetsSampler(const TImage * image, double isoValue, double outsideSign)
      : m_Buffer(image->GetBufferPointer())
      , m_IsoValue(isoValue)
      , m_OutsideSign(outsideSign)
  {
    const auto region = image->GetBufferedRegion();
    for (unsigned int d = 0; d < 3; ++d)
    {
      m_Size[d] = static_cast<std::int64_t>(region.GetSize(d));
    }
  }

  double
  Value(std::int64_t x, std::int64_t y, std::int64_t z) const
  {
    if (x < 0 || y < 0 || z < 0 || x >= m_Size[0] || y >= m_Size[1] || z >= m_Size[2])
    {
      const std::int64_t cx = std::clamp<std::int64_t>(x, 0, m_Size[0] - 1);
      const std::int64_t cy = std::clamp<std::int64_t>(y, 0, m_Size[1] - 1);
      const std::int64_t cz = std::clamp<std::int64_t>(z, 0, m_Size[2] - 1);
      const double       v = static_cast<double>(m_Buffer[(cz * m_Size[1] + cy) * m_Size[0] + cx]);
      const double       epsilon = 1e-6 * (1.0 + std::abs(m_IsoValue));
      return m_IsoValue + m_OutsideSign * std::max(std::abs(v - m_IsoValue), epsilon);
    }
    return static_cast<double>(m_Buffer[(z * m_Size[1] + y) * m_Size[0] + x]);
  }

  double
  Interpolate(const Vec3 & p) const
  {
    const double       fx = std::floor(p[0]);
    const double       fy = std::floor(p[1]);
    const double       fz = std::floor(p[2]);
    const std::int64_t x = static_cast<std::int64_t>(fx);
    const std::int64_t y = static_cast<std::int64_t>(fy);
    const std::int64_t z = static_cast<std::int64_t>(fz);
    const double       u = p[0] - fx;
    const double       v = p[1] - fy;
    const double       w = p[2] - fz;
    double             c[8];
    if (x >= 0 && y >= 0 && z >= 0 && x + 1 < m_Size[0] && y + 1 < m_Size[1] && z + 1 < m_Size[2])
    {
      const PixelType *  b = m_Buffer + (z * m_Size[1] + y) * m_Size[0] + x;
      const std::int64_t sy = m_Size[0];
      const std::int64_t sz = m_Size[0] * m_Size[1];
      c[0] = b[0];
      c[1] = b[1];
      c[2] = b[sy];
      c[3] = b[sy + 1];
      c[4] = b[sz];
      c[5] = b[sz + 1];
      c[6] = b[sz + sy];
      c[7] = b[sz + sy + 1];
    }
    else
    {
      for (unsigned int k = 0; k < 8; ++k)
      {
        c[k] = Value(x + (k & 1), y + ((k >> 1) & 1), z + ((k >> 2) & 1));
      }
    }
    const double c00 = c[0] + u * (c[1] - c[0]);
    const double c10 = c[2] + u * (c[3] - c[2]);
    const double c01 = c[4] + u * (c[5] - c[4]);
    const double c11 = c[6] + u * (c[7] - c[6]);
    const double c0 = c00 + v * (c10 - c00);
    const double c1 = c01 + v * (c11 - c01);
    return c0 + w * (c1 - c0);
  }

  /** dI/d(index) by central differences of the interpolated image, one voxel apart. */
  Vec3
  Gradient(const Vec3 & p) const
  {
    Vec3 g;
    for (unsigned int d = 0; d < 3; ++d)
    {
      Vec3 plus = p;
      Vec3 minus = p;
      plus[d] += 1.0;
      minus[d] -= 1.0;
      g[d] = 0.5 * (Interpolate(plus) - Interpolate(minus));
    }
    return g;
  }

  const std::int64_t *
  GetSize() const
  {
    return m_Size;
  }

  const PixelType *
  GetBufferPointer() const
  {
    return m_Buffer;
  }

private:
  const PixelType * m_Buffer;
  double            m_IsoValue;
  double            m_OutsideSign;
  std::int64_t      m_Size[3];
};

/** \brief Gaussian-derivative gradients (the separable kernels of GaussianKernel, from
 * ITK's GaussianDerivativeOperator) at the corner voxels of every surface cell,
 * computed once, in parallel, and trilinearly interpolated inside a node's cell.
 *
 * (ITK 5.2's GaussianDerivativeImageFunction is not used: it applies a 1-D
 * derivative kernel without blurring across it, and returns the negated
 * derivative.) \ingroup MeshExtraction */
template <typename TImage>
class SurfaceNetsGaussianGradient
{
public:
  SurfaceNetsGaussianGradient(const TImage * image, const SurfaceNet & net, double sigma)
      : m_Net(net)
  {
    const auto region = image->GetBufferedRegion();
    for (unsigned int d = 0; d < 3; ++d)
    {
      m_Size[d] = static_cast<std::int64_t>(region.GetSize(d));
    }
    m_Keys.reserve(net.cells.size() * 2);
    for (const auto & c : net.cells)
    {
      for (unsigned int k = 0; k < 8; ++k)
      {
        const auto v = CornerVoxel(c, k);
        m_Keys.push_back(Key(v[0], v[1], v[2]));
      }
    }
    std::sort(m_Keys.begin(), m_Keys.end());
    m_Keys.erase(std::unique(m_Keys.begin(), m_Keys.end()), m_Keys.end());
    m_Gradients.resize(m_Keys.size());
    // Per axis d, the derivative kernel along d and the Gaussian along the other two,
    // applied at each corner voxel in one pass over its neighbourhood; voxels beyond
    // the image take the value of the nearest image voxel (zero flux, as ITK's
    // neighbourhood functions do).
    std::vector<float> smooth[3];
    std::vector<float> derivative[3];
    int                radius[3];
    for (unsigned int d = 0; d < 3; ++d)
    {
      smooth[d] = GaussianKernel(sigma, image->GetSpacing()[d], 0);
      derivative[d] = GaussianKernel(sigma, image->GetSpacing()[d], 1);
      // Both centred, the shorter padded with zeros to the longer's size.
      auto &            shorter = smooth[d].size() < derivative[d].size() ? smooth[d] : derivative[d];
      const std::size_t pad = (std::max(smooth[d].size(), derivative[d].size()) - shorter.size()) / 2;
      shorter.insert(shorter.begin(), pad, 0.0f);
      shorter.insert(shorter.end(), pad, 0.0f);
      radius[d] = static_cast<int>(smooth[d].size() / 2);
    }
    const auto *       buffer = image->GetBufferPointer();
    const std::int64_t sx = m_Size[0];
    const std::int64_t sxy = m_Size[0] * m_Size[1];
    auto               at = [](std::int64_t v, std::int64_t size) { return std::clamp<std::int64_t>(v, 0, size - 1); };
    ParallelForBlocks(m_Keys.size(), 4096, [&](std::size_t begin, std::size_t end, std::size_t) {
      std::vector<std::int64_t> xs(smooth[0].size());
      for (std::size_t i = begin; i < end; ++i)
      {
        std::int64_t xyz[3];
        Unkey(m_Keys[i], xyz);
        // Voxels beyond the image take the gradient of the nearest image voxel.
        for (unsigned int d = 0; d < 3; ++d)
        {
          xyz[d] = at(xyz[d], m_Size[d]);
        }
        for (int a = -radius[0]; a <= radius[0]; ++a)
        {
          xs[static_cast<std::size_t>(a + radius[0])] = at(xyz[0] + a, m_Size[0]);
        }
        double gradient[3] = { 0.0, 0.0, 0.0 };
        for (int c = -radius[2]; c <= radius[2]; ++c)
        {
          const std::int64_t z = at(xyz[2] + c, m_Size[2]);
          const auto         kc = static_cast<std::size_t>(c + radius[2]);
          for (int b = -radius[1]; b <= radius[1]; ++b)
          {
            const auto * row = buffer + z * sxy + at(xyz[1] + b, m_Size[1]) * sx;
            double       rowSmooth = 0.0;
            double       rowDerivative = 0.0;
            for (std::size_t a = 0; a < xs.size(); ++a)
            {
              const auto value = static_cast<double>(row[xs[a]]);
              rowSmooth += smooth[0][a] * value;
              rowDerivative += derivative[0][a] * value;
            }
            const auto kb = static_cast<std::size_t>(b + radius[1]);
            gradient[0] += smooth[1][kb] * smooth[2][kc] * rowDerivative;
            gradient[1] += derivative[1][kb] * smooth[2][kc] * rowSmooth;
            gradient[2] += smooth[1][kb] * derivative[2][kc] * rowSmooth;
          }
        }
        for (unsigned int d = 0; d < 3; ++d)
        {
          // Per millimetre along the image axis -> per voxel.
          m_Gradients[i][d] = gradient[d] * image->GetSpacing()[d];
        }
      }
    });
  }

  /** dI/d(index) at p, a point of the node's cell `cell`. */
  Vec3
  Gradient(const Vec3 & p, std::uint32_t cell) const
  {
    const SurfaceCell & c = m_Net.cells[cell];
    const double        u = std::clamp(p[0] - c.x, 0.0, 1.0);
    const double        v = std::clamp(p[1] - c.y, 0.0, 1.0);
    const double        w = std::clamp(p[2] - c.z, 0.0, 1.0);
    Vec3                corner[8];
    for (unsigned int k = 0; k < 8; ++k)
    {
      const auto [x, y, z] = CornerVoxel(c, k);
      const std::int64_t key = Key(x, y, z);
      corner[k] = m_Gradients[std::lower_bound(m_Keys.begin(), m_Keys.end(), key) - m_Keys.begin()];
    }
    const Vec3 c00 = corner[0] + (corner[1] - corner[0]) * u;
    const Vec3 c10 = corner[2] + (corner[3] - corner[2]) * u;
    const Vec3 c01 = corner[4] + (corner[5] - corner[4]) * u;
    const Vec3 c11 = corner[6] + (corner[7] - corner[6]) * u;
    const Vec3 c0 = c00 + (c10 - c00) * v;
    const Vec3 c1 = c01 + (c11 - c01) * v;
    return c0 + (c1 - c0) * w;
  }

private:
  std::int64_t
  Key(std::int64_t x, std::int64_t y, std::int64_t z) const
  {
    return ((z + 1) * (m_Size[1] + 2) + (y + 1)) * (m_Size[0] + 2) + (x + 1);
  }
  void
  Unkey(std::int64_t key, std::int64_t xyz[3]) const
  {
    xyz[0] = key % (m_Size[0] + 2) - 1;
    key /= (m_Size[0] + 2);
    xyz[1] = key % (m_Size[1] + 2) - 1;
    xyz[2] = key / (m_Size[1] + 2) - 1;
  }

  const SurfaceNet &        m_Net;
  std::int64_t              m_Size[3];
  std::vector<std::int64_t> m_Keys;
  std::vector<Vec3>         m_Gradients;
};

/** How RelaxSurfaceNet moves the nodes (thesis section 3.2). `kind` is the filter's
 * Relaxation: None (and Automatic, which the filter resolves before it relaxes) leaves
 * the nodes where the net put them; Averaging is SNA (eq. 3.1-3.2), Gradient the step
 * to the iso-surface (eq. 3.3-3.4), Combined SNERT (eq. 3.5-3.6). */
struct SurfaceNetsRelaxationParameters
{
  SurfaceNetsImageToMeshFilterEnums::Relaxation kind{ SurfaceNetsImageToMeshFilterEnums::Relaxation::Combined };
  unsigned int                                  maximumNumberOfIterations{ 20 };
  double convergenceThreshold{ 1e-3 }; ///< largest relocation (voxels) that ends the iterations
  double smoothingWeight{ 1.0 };       ///< weight of the averaging vector
  double projectionWeight{ 1.0 };      ///< weight of the step to the iso-surface
  bool   sequential{ false };          ///< average, then project, within each iteration (3.2.4)
  /** The gradient is the sampler's central differences: cache them, with the voxel
   * values, at the 8 corners of each node's cell (set by the filter). */
  bool                 centralDifferences{ true };
  double               isoValue{ 0.0 };
  Matrix<double, 3, 3> indexToPhysical; ///< direction * diag(spacing)
  unsigned int         numberOfWorkUnits{ 0 };
};

/** Scale d so that p + d stays in the box [lower, upper] (thesis eq. 3.2, the
 * function c: the relocation is shortened along its own direction, not clipped
 * per axis). p must be in the box. */
inline Vec3
ConstrainToBox(const Vec3 & p, const Vec3 & d, const Vec3 & lower, const Vec3 & upper)
{
  const Vec3 q = p + d;
  if (q[0] >= lower[0] && q[0] <= upper[0] && q[1] >= lower[1] && q[1] <= upper[1] && q[2] >= lower[2] &&
      q[2] <= upper[2])
  {
    return d; // the whole step stays in the box (the common case: no division)
  }
  double t = 1.0;
  for (unsigned int k = 0; k < 3; ++k)
  {
    if (d[k] > 0.0)
    {
      t = std::min(t, (upper[k] - p[k]) / d[k]);
    }
    else if (d[k] < 0.0)
    {
      t = std::min(t, (lower[k] - p[k]) / d[k]);
    }
  }
  return d * std::max(t, 0.0);
}

/** What RelaxSurfaceNet reads of each node in an iteration: the trilinear value and
 * (central differences) gradient fields of a cell as coefficients, that cell's
 * corner, and the node's box. The cell is the node's own, or with central
 * differences the one it was last found in when its box lets it leave its own.
 * Passed to several RelaxSurfaceNet calls on one net (the same nodes, cells, image
 * and gradient method, as in the high-quality mode's rounds), it is made once and
 * only the boxes are refreshed. \ingroup MeshExtraction */
struct SurfaceNetsCellCache
{
  struct Entry
  {
    float  value[8];
    float  gradient[3][8];
    Vec3   lower;
    Vec3   upper;
    double corner[3];
  };
  UninitializedArray<Entry> entries;
  bool                      centralDifferences{ false };
};

/** Stage 3 of SurfaceNets: relax the nodes with batch (Jacobi) updates until the
 * largest relocation falls below the threshold or the iteration limit is reached.
 * Vectors are built in physical space (the projection on the plane
 * perpendicular to the gradient needs true angles), constrained in index space
 * (where a cell is a unit cube). `gradient(p, node)` returns dI/d(index).
 * Deterministic for any number of threads. `cellCache`: see SurfaceNetsCellCache.
 * \ingroup MeshExtraction */
template <typename TSampler, typename TGradient>
SurfaceNetsRelaxationResult
RelaxSurfaceNet(SurfaceNet &                            net,
                const TSampler *                        sampler,
                TGradient &&                            gradient,
                const SurfaceNetsRelaxationParameters & parameters,
                const std::function<void(double)> &     progress = nullptr,
                SurfaceNetsCellCache *                  cellCache = nullptr)
{
  SurfaceNetsRelaxationResult result;
  using RelaxationEnum = SurfaceNetsImageToMeshFilterEnums::Relaxation;
  if (parameters.kind == RelaxationEnum::None || parameters.kind == RelaxationEnum::Automatic ||
      parameters.maximumNumberOfIterations == 0)
  {
    return result;
  }
  const bool useGradient = parameters.kind != RelaxationEnum::Averaging;
  const bool useAveraging = parameters.kind != RelaxationEnum::Gradient;
  if (useGradient && sampler == nullptr)
  {
    itkGenericExceptionMacro("SurfaceNets: gradient relaxation needs a greyscale image.");
  }
  // The matrices as plain 3x3 products the compiler inlines (itk::Matrix's are calls).
  struct Mat3
  {
    double m[3][3];
    explicit Mat3(const Matrix<double, 3, 3> & A)
    {
      for (unsigned int r = 0; r < 3; ++r)
      {
        for (unsigned int c = 0; c < 3; ++c)
        {
          m[r][c] = A[r][c];
        }
      }
    }
    Vec3
    operator*(const Vec3 & v) const
    {
      Vec3 out;
      out[0] = m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2];
      out[1] = m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2];
      out[2] = m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2];
      return out;
    }
    double
    operator()(unsigned int r, unsigned int c) const
    {
      return m[r][c];
    }
  };
  const Matrix<double, 3, 3> matrix = parameters.indexToPhysical;
  const Matrix<double, 3, 3> inverse(matrix.GetInverse());
  const Mat3                 M(matrix);
  const Mat3                 Minv(inverse);
  const Mat3                 MinvT(Matrix<double, 3, 3>(inverse.GetTranspose()));
  // W = M^-1 M^-T maps an index-space gradient G to t = M^-1 g, the index displacement
  // along the physical gradient g = M^-T G, with |g|^2 = G.t.
  const Mat3 W(inverse * Matrix<double, 3, 3>(inverse.GetTranspose()));
  double     smallestSpacing = std::numeric_limits<double>::max();
  double     cellDiagonal = 0.0;
  for (unsigned int c = 0; c < 3; ++c)
  {
    const double length = std::sqrt(M(0, c) * M(0, c) + M(1, c) * M(1, c) + M(2, c) * M(2, c));
    smallestSpacing = std::min(smallestSpacing, length);
    cellDiagonal += length * length;
  }
  cellDiagonal = std::sqrt(cellDiagonal);
  const double h = 0.5 * smallestSpacing; // finite-difference step along the gradient (mm)

  const std::size_t      numberOfNodes = net.positions.size();
  LargeBlockVector<Vec3> next(numberOfNodes);
  constexpr std::size_t  BlockSize = 2048;
  const std::size_t      numberOfBlocks = (numberOfNodes + BlockSize - 1) / BlockSize;
  std::vector<double>    blockMaximum(numberOfBlocks);

  // Each node's cell: the 8 corner values and (central differences) corner
  // gradients, read once. Inside its cell a node's value, gradient and slope are then
  // plain arithmetic on these (trilinear interpolation, and the trilinear field's
  // exact derivative along n), not 9 interpolations from the image per iteration.
  // Stored as the trilinear fields' coefficients, f(u, v, w) = c0 + c1 u + c2 v + c3 w
  // + c4 uv + c5 uw + c6 vw + c7 uvw in the cell's local coordinates: a value and its
  // three partial derivatives then cost 16 multiply-adds.
  // With the node's box and its cell's corner, so that an iteration reads one
  // record per node (besides the positions) instead of several arrays.
  auto toCoefficients = [](const double f[8], float c[8]) {
    c[0] = static_cast<float>(f[0]);
    c[1] = static_cast<float>(f[1] - f[0]);
    c[2] = static_cast<float>(f[2] - f[0]);
    c[3] = static_cast<float>(f[4] - f[0]);
    c[4] = static_cast<float>(f[3] - f[2] - f[1] + f[0]);
    c[5] = static_cast<float>(f[5] - f[4] - f[1] + f[0]);
    c[6] = static_cast<float>(f[6] - f[4] - f[2] + f[0]);
    c[7] = static_cast<float>(f[7] - f[6] - f[5] + f[4] - f[3] + f[2] + f[1] - f[0]);
  };
  // 200 bytes a node, all written below; kept in `cellCache` from an earlier call
  // on the same net, where only the boxes are refreshed.
  UninitializedArray<SurfaceNetsCellCache::Entry>   localCache;
  UninitializedArray<SurfaceNetsCellCache::Entry> & cache = cellCache != nullptr ? cellCache->entries : localCache;
  const std::int64_t *                              size = sampler != nullptr ? sampler->GetSize() : nullptr;
  const std::int64_t                                sy = size != nullptr ? size[0] : 0;
  const std::int64_t                                sz = size != nullptr ? size[0] * size[1] : 0;
  // The 4x4x4 voxels around a cell (its corners and their central-difference
  // neighbours) are read straight from the buffer when all are inside the image.
  auto isInterior = [size](const SurfaceCell & c) {
    return c.x >= 1 && c.y >= 1 && c.z >= 1 && c.x + 2 < size[0] && c.y + 2 < size[1] && c.z + 2 < size[2];
  };
  // An entry's fields for cell c (its box is left as it is).
  auto fillEntry = [&](const SurfaceCell & c, SurfaceNetsCellCache::Entry & entry) {
    const bool interior = isInterior(c);
    double     corner[8];
    double     cornerGradient[3][8] = {};
    // The corners and central differences inside the image, straight from the buffer.
    auto readInterior = [&](const auto * b) {
      for (unsigned int k = 0; k < 8; ++k)
      {
        const auto * v = b + ((k >> 2) & 1) * sz + ((k >> 1) & 1) * sy + (k & 1);
        corner[k] = static_cast<double>(v[0]);
        if (parameters.centralDifferences)
        {
          cornerGradient[0][k] = 0.5 * (static_cast<double>(v[1]) - static_cast<double>(v[-1]));
          cornerGradient[1][k] = 0.5 * (static_cast<double>(v[sy]) - static_cast<double>(v[-sy]));
          cornerGradient[2][k] = 0.5 * (static_cast<double>(v[sz]) - static_cast<double>(v[-sz]));
        }
      }
    };
#if defined(__SSE2__)
    // A float image: two corners (x and x + 1) at a time, in double precision as
    // readInterior, so the same values, from four loads of two voxels per corner row.
    auto readInteriorPairs = [&](const float * b) {
      auto pair = [](const float * v) {
        return _mm_cvtps_pd(_mm_castsi128_ps(_mm_loadl_epi64(reinterpret_cast<const __m128i *>(v))));
      };
      const __m128d half = _mm_set1_pd(0.5);
      for (unsigned int k = 0; k < 8; k += 2)
      {
        const float * v = b + ((k >> 2) & 1) * sz + ((k >> 1) & 1) * sy;
        _mm_storeu_pd(corner + k, pair(v));
        if (parameters.centralDifferences)
        {
          _mm_storeu_pd(cornerGradient[0] + k, _mm_mul_pd(half, _mm_sub_pd(pair(v + 1), pair(v - 1))));
          _mm_storeu_pd(cornerGradient[1] + k, _mm_mul_pd(half, _mm_sub_pd(pair(v + sy), pair(v - sy))));
          _mm_storeu_pd(cornerGradient[2] + k, _mm_mul_pd(half, _mm_sub_pd(pair(v + sz), pair(v - sz))));
        }
      }
    };
#endif
    if (interior)
    {
      const auto * b = sampler->GetBufferPointer() + (c.z * sz + c.y * sy + c.x);
#if defined(__SSE2__)
      if constexpr (std::is_same<std::remove_cv_t<std::remove_pointer_t<decltype(b)>>, float>::value)
      {
        readInteriorPairs(b);
      }
      else
      {
        readInterior(b);
      }
#else
      readInterior(b);
#endif
    }
    else
    {
      for (unsigned int k = 0; k < 8; ++k)
      {
        const auto [x, y, z] = CornerVoxel(c, k);
        corner[k] = sampler->Value(x, y, z);
        if (parameters.centralDifferences)
        {
          cornerGradient[0][k] = 0.5 * (sampler->Value(x + 1, y, z) - sampler->Value(x - 1, y, z));
          cornerGradient[1][k] = 0.5 * (sampler->Value(x, y + 1, z) - sampler->Value(x, y - 1, z));
          cornerGradient[2][k] = 0.5 * (sampler->Value(x, y, z + 1) - sampler->Value(x, y, z - 1));
        }
      }
    }
    entry.corner[0] = c.x;
    entry.corner[1] = c.y;
    entry.corner[2] = c.z;
    toCoefficients(corner, entry.value);
    for (unsigned int d = 0; d < 3; ++d)
    {
      toCoefficients(cornerGradient[d], entry.gradient[d]);
    }
  };
  if (sampler != nullptr && useGradient && cellCache != nullptr && cache.size() == numberOfNodes &&
      cellCache->centralDifferences == parameters.centralDifferences)
  {
    for (std::size_t i = 0; i < numberOfNodes; ++i)
    {
      cache[i].lower = net.boxLower[i];
      cache[i].upper = net.boxUpper[i];
    }
  }
  else if (sampler != nullptr && useGradient)
  {
    cache.Allocate(numberOfNodes);
    if (cellCache != nullptr)
    {
      cellCache->centralDifferences = parameters.centralDifferences;
    }
    ParallelForBlocks(
      numberOfNodes,
      BlockSize,
      [&](std::size_t begin, std::size_t end, std::size_t) {
        // Those of the cell PrefetchAhead nodes on are requested now: the nodes come
        // in cell order, in a pattern of 16 short rows that the hardware's own
        // prefetching does not foresee. SNERT at 256^3 (SurfaceNets/SNERT, three
        // alternating processes) took 95-101 ms on 1 thread and 57-58 on 2 without
        // this, 90-93 and 53-56.5 with it.
        constexpr std::size_t PrefetchAhead = 16;
        for (std::size_t i = begin; i < end; ++i)
        {
          if (i + PrefetchAhead < end)
          {
            const SurfaceCell & ahead = net.cells[net.nodeCell[i + PrefetchAhead]];
            if (isInterior(ahead))
            {
              const auto * b = sampler->GetBufferPointer() + (ahead.z * sz + ahead.y * sy + ahead.x);
              for (std::int64_t dz = -1; dz <= 2; ++dz)
              {
                for (std::int64_t dy = -1; dy <= 2; ++dy)
                {
                  PrefetchForReading(reinterpret_cast<std::uintptr_t>(b + dz * sz + dy * sy - 1), 4 * sizeof(*b));
                }
              }
            }
          }
          fillEntry(net.cells[net.nodeCell[i]], cache[i]);
          cache[i].lower = net.boxLower[i];
          cache[i].upper = net.boxUpper[i];
        }
      },
      parameters.numberOfWorkUnits);
  }
  // A node that has left its own cell (the high-quality mode lets it, by a fraction of
  // a voxel) takes the cell it is in now: its entry is refilled for that cell, and the
  // steps stay the cached arithmetic instead of nine interpolations from the image.
  // Central differences only (the Gaussian gradients are known at the corners of the
  // net's own cells).
  const bool followCell = sampler != nullptr && useGradient && parameters.centralDifferences && !cache.empty();
  auto       moveEntryTo = [&](const Vec3 & p, std::size_t node) -> bool {
    constexpr double limit = 1 << 30;
    if (!(std::abs(p[0]) < limit && std::abs(p[1]) < limit && std::abs(p[2]) < limit))
    {
      return false;
    }
    SurfaceCell c{};
    c.x = static_cast<std::int32_t>(std::floor(p[0]));
    c.y = static_cast<std::int32_t>(std::floor(p[1]));
    c.z = static_cast<std::int32_t>(std::floor(p[2]));
    fillEntry(c, cache[node]);
    return true;
  };

  // A node's value I, gradient G = dI/d(index) and the trilinear field's exact
  // derivative dI at p, from the node's cache entry; false (nothing computed)
  // without a cache or when p is outside the entry's cell.
  struct CellSample
  {
    double value;
    Vec3   G;
    Vec3   dI;
  };
  // (Both per-node steps below are forced inline: GCC 12 kept them as calls, which
  // pass their vectors through memory; inlined, SNERT gained 1-2 % at 256^3.)
  auto sampleCell = [&](const Vec3 & p, std::size_t node, CellSample & sample) MESHEXTRACTION_ALWAYS_INLINE -> bool {
    if (cache.empty())
    {
      return false;
    }
    const SurfaceNetsCellCache::Entry & cc = cache[node];
    const double                        u = p[0] - cc.corner[0];
    const double                        v = p[1] - cc.corner[1];
    const double                        w = p[2] - cc.corner[2];
    if (!(u >= 0.0 && u <= 1.0 && v >= 0.0 && v <= 1.0 && w >= 0.0 && w <= 1.0))
    {
      return false;
    }
    const double  uv = u * v;
    const double  uw = u * w;
    const double  vw = v * w;
    const double  uvw = uv * w;
    const float * f = cc.value;
#if defined(__SSE2__)
    // The value and the three gradient fields at once, in single precision (the
    // coefficients' own precision): four 8-term dot products with the basis
    // (1, u, v, w, uv, uw, vw, uvw), summed across lanes by a 4x4 transpose.
    const __m128 b0 = _mm_set_ps(static_cast<float>(w), static_cast<float>(v), static_cast<float>(u), 1.0f);
    const __m128 b1 =
      _mm_set_ps(static_cast<float>(uvw), static_cast<float>(vw), static_cast<float>(uw), static_cast<float>(uv));
    auto dot = [&](const float * k) {
      return _mm_add_ps(_mm_mul_ps(_mm_loadu_ps(k), b0), _mm_mul_ps(_mm_loadu_ps(k + 4), b1));
    };
    __m128 r0 = dot(cc.value);
    __m128 r1 = dot(cc.gradient[0]);
    __m128 r2 = dot(cc.gradient[1]);
    __m128 r3 = dot(cc.gradient[2]);
    _MM_TRANSPOSE4_PS(r0, r1, r2, r3);
    float sum[4];
    _mm_storeu_ps(sum, _mm_add_ps(_mm_add_ps(r0, r1), _mm_add_ps(r2, r3)));
    sample.value = sum[0];
    sample.G =
      parameters.centralDifferences ? MakeVec3(sum[1], sum[2], sum[3]) : gradient(p, static_cast<std::uint32_t>(node));
#else
    auto field = [&](const float * k) {
      return k[0] + k[1] * u + k[2] * v + k[3] * w + k[4] * uv + k[5] * uw + k[6] * vw + k[7] * uvw;
    };
    sample.value = field(f);
    sample.G = parameters.centralDifferences
                 ? MakeVec3(field(cc.gradient[0]), field(cc.gradient[1]), field(cc.gradient[2]))
                 : gradient(p, static_cast<std::uint32_t>(node));
#endif
    sample.dI = MakeVec3(f[1] + f[4] * v + f[5] * w + f[7] * vw,
                         f[2] + f[4] * u + f[6] * w + f[7] * uw,
                         f[3] + f[5] * u + f[6] * v + f[7] * uv);
    return true;
  };

  // The step to the iso-surface from p along the unit physical gradient n (mm),
  // from a linear model of the image along n (thesis 3.2.3).
  auto projection = [&](const Vec3 & p, std::uint32_t node, Vec3 & n) -> double {
    if (CellSample sample; sampleCell(p, node, sample))
    {
      const Vec3   g = MinvT * sample.G;
      const double magnitude = Norm(g);
      if (!(magnitude > 0.0))
      {
        n.Fill(0.0);
        return 0.0;
      }
      n = g * (1.0 / magnitude);
      // The exact derivative of the trilinear field along n (M^-1 n: index displacement per mm).
      const double slope = Dot(sample.dI, Minv * n);
      if (!(std::abs(slope) > 1e-3 * magnitude))
      {
        return 0.0;
      }
      return std::clamp((parameters.isoValue - sample.value) / slope, -cellDiagonal, cellDiagonal);
    }
    const Vec3   g = MinvT * gradient(p, node);
    const double magnitude = Norm(g);
    if (!(magnitude > 0.0))
    {
      n.Fill(0.0);
      return 0.0;
    }
    n = g * (1.0 / magnitude);
    const Vec3   step = Minv * (n * h);
    const double value = sampler->Interpolate(p);
    // The image's own slope along n (a smoothed gradient may disagree with it).
    const double slope = (sampler->Interpolate(p + step) - sampler->Interpolate(p - step)) / (2.0 * h);
    if (!(std::abs(slope) > 1e-3 * magnitude))
    {
      return 0.0; // flat along n: no reliable step
    }
    return std::clamp((parameters.isoValue - value) / slope, -cellDiagonal, cellDiagonal);
  };

  // The combined step (eq. 3.5-3.6) of a node inside its entry's cell, from the cache,
  // without normalising the gradient. With n = g/|g|, the projection on the tangent
  // plane is M^-1 (M a - n n.(M a)) = a - t (G.a)/|g|^2, since n.(M a) = (M^T g).a/|g|
  // = G.a/|g|; and the step to the iso-surface, M^-1 (n d) with d = (iso - I)/slope and
  // slope = dI.(M^-1 n) = dI.t/|g|, is t (iso - I)/(dI.t). The same vectors as the
  // general path below, with no square root and two divisions.
  auto cachedStep = [&](const Vec3 & p, std::size_t node, const Vec3 & a, Vec3 & d)
                      MESHEXTRACTION_ALWAYS_INLINE -> bool {
    CellSample sample;
    if (!sampleCell(p, node, sample))
    {
      return false;
    }
    const Vec3 & G = sample.G;
    const Vec3   t = W * G;
    const double g2 = Dot(G, t);
    d = useAveraging ? a * parameters.smoothingWeight : MakeVec3(0, 0, 0);
    if (!(g2 > 0.0))
    {
      return true; // no gradient: no projection, no step (as n = 0 below)
    }
    double       coefficient = useAveraging ? -Dot(G, a) / g2 * parameters.smoothingWeight : 0.0;
    const double slope = Dot(sample.dI, t); // |g| times the slope along n
    if (std::abs(slope) > 1e-3 * g2)
    {
      double q = (parameters.isoValue - sample.value) / slope; // the distance is q |g|
      if (q * q * g2 > cellDiagonal * cellDiagonal)
      {
        q = std::copysign(cellDiagonal / std::sqrt(g2), q);
      }
      coefficient += q * parameters.projectionWeight;
    }
    d += t * coefficient;
    return true;
  };

  for (unsigned int iteration = 0; iteration < parameters.maximumNumberOfIterations; ++iteration)
  {
    ParallelForBlocks(
      numberOfNodes,
      BlockSize,
      [&](std::size_t begin, std::size_t end, std::size_t block) {
        double largest = 0.0;
        for (std::size_t i = begin; i < end; ++i)
        {
          const Vec3 & p = net.positions[i];
          Vec3         average = MakeVec3(0, 0, 0);
          const auto   first = net.neighborStart[i];
          const auto   last = net.neighborStart[i + 1];
          for (auto k = first; k < last; ++k)
          {
            average += net.positions[net.neighbors[k]];
          }
          Vec3 a = (last > first) ? average * (1.0 / (last - first)) - p : MakeVec3(0, 0, 0);
          Vec3 moved = p;
          if (!useGradient)
          {
            moved += ConstrainToBox(p, a * parameters.smoothingWeight, net.boxLower[i], net.boxUpper[i]);
          }
          else if (Vec3 step;
                   !parameters.sequential &&
                   (cachedStep(p, i, a, step) || (followCell && moveEntryTo(p, i) && cachedStep(p, i, a, step))))
          {
            moved += ConstrainToBox(p, step, cache[i].lower, cache[i].upper);
          }
          else
          {
            Vec3         n;
            const double distance = projection(p, static_cast<std::uint32_t>(i), n);
            Vec3         tangential = MakeVec3(0, 0, 0);
            if (useAveraging)
            {
              const Vec3 aPhysical = M * a;
              tangential = Minv * (aPhysical - n * Dot(n, aPhysical)) * parameters.smoothingWeight; // eq. 3.5
            }
            if (parameters.sequential)
            {
              moved += ConstrainToBox(moved, tangential, net.boxLower[i], net.boxUpper[i]);
              Vec3         n2;
              const double d2 = projection(moved, static_cast<std::uint32_t>(i), n2);
              moved += ConstrainToBox(
                moved, Minv * (n2 * (d2 * parameters.projectionWeight)), net.boxLower[i], net.boxUpper[i]);
            }
            else
            {
              const Vec3 d = tangential + Minv * (n * (distance * parameters.projectionWeight)); // eq. 3.6
              moved += ConstrainToBox(p, d, net.boxLower[i], net.boxUpper[i]);
            }
          }
          largest = std::max(largest, SquaredNorm(moved - p));
          next[i] = moved;
        }
        blockMaximum[block] = std::sqrt(largest);
      },
      parameters.numberOfWorkUnits);
    net.positions.swap(next);
    result.iterations = iteration + 1;
    result.lastMaximumRelocation = numberOfBlocks ? *std::max_element(blockMaximum.begin(), blockMaximum.end()) : 0.0;
    if (progress)
    {
      progress(static_cast<double>(iteration + 1) / parameters.maximumNumberOfIterations);
    }
    if (result.lastMaximumRelocation < parameters.convergenceThreshold)
    {
      break;
    }
  }
  return result;
}

} // namespace MeshExtraction
} // namespace itk

#endif
