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
#ifndef itkMeshExtractionSurfaceNetsRelaxation_h
#define itkMeshExtractionSurfaceNetsRelaxation_h

#include "itkMeshExtractionGaussianScaleSpace.h"
#include "itkMeshExtractionLargeBlockVector.h"
#include "itkMeshExtractionMacros.h"
#include "itkMeshExtractionParallel.h"
#include "itkMeshExtractionSurfaceNets.h"
#include "itkSurfaceNetsImageToMeshFilterEnums.h"
#include "itkImage.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <type_traits>
#if defined(__SSE2__)
#  include <emmintrin.h>
#  include <xmmintrin.h>
#endif

namespace itk
{
namespace MeshExtraction
{
namespace detail
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
    this->CollectCornerVoxels();
    m_Gradients.resize(m_Keys.size());
    const Kernels kernels(image, sigma);
    ParallelForBlocks(m_Keys.size(), 4096, [&](std::size_t begin, std::size_t end, std::size_t) {
      std::vector<std::int64_t> xs(kernels.smooth[0].size());
      for (std::size_t i = begin; i < end; ++i)
      {
        this->ComputeGradient(image, kernels, i, xs);
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
  /** Per axis d, the derivative kernel along d and the Gaussian (both centred, the
   * shorter padded with zeros to the longer's size), and their radius. */
  struct Kernels
  {
    std::vector<float> smooth[3];
    std::vector<float> derivative[3];
    int                radius[3];

    Kernels(const TImage * image, double sigma)
    {
      for (unsigned int d = 0; d < 3; ++d)
      {
        smooth[d] = GaussianKernel(sigma, image->GetSpacing()[d], 0);
        derivative[d] = GaussianKernel(sigma, image->GetSpacing()[d], 1);
        auto &            shorter = smooth[d].size() < derivative[d].size() ? smooth[d] : derivative[d];
        const std::size_t pad = (std::max(smooth[d].size(), derivative[d].size()) - shorter.size()) / 2;
        shorter.insert(shorter.begin(), pad, 0.0f);
        shorter.insert(shorter.end(), pad, 0.0f);
        radius[d] = static_cast<int>(smooth[d].size() / 2);
      }
    }
  };

  /** The corner voxels of every surface cell, once each, as sorted keys. */
  void
  CollectCornerVoxels()
  {
    m_Keys.reserve(m_Net.cells.size() * 2);
    for (const auto & c : m_Net.cells)
    {
      for (unsigned int k = 0; k < 8; ++k)
      {
        const auto v = CornerVoxel(c, k);
        m_Keys.push_back(Key(v[0], v[1], v[2]));
      }
    }
    std::sort(m_Keys.begin(), m_Keys.end());
    m_Keys.erase(std::unique(m_Keys.begin(), m_Keys.end()), m_Keys.end());
  }

  /** The gradient at corner voxel i: per axis d, the derivative kernel along d and the
   * Gaussian along the other two, applied in one pass over the voxel's neighbourhood;
   * voxels beyond the image take the value of the nearest image voxel (zero flux, as
   * ITK's neighbourhood functions do). `xs`: room for the kernel's x indices. */
  void
  ComputeGradient(const TImage * image, const Kernels & kernels, std::size_t i, std::vector<std::int64_t> & xs)
  {
    const auto *       buffer = image->GetBufferPointer();
    const std::int64_t sx = m_Size[0];
    const std::int64_t sxy = m_Size[0] * m_Size[1];
    auto               at = [](std::int64_t v, std::int64_t size) { return std::clamp<std::int64_t>(v, 0, size - 1); };
    const int *        radius = kernels.radius;
    std::int64_t       xyz[3];
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
          rowSmooth += kernels.smooth[0][a] * value;
          rowDerivative += kernels.derivative[0][a] * value;
        }
        const auto kb = static_cast<std::size_t>(b + radius[1]);
        gradient[0] += kernels.smooth[1][kb] * kernels.smooth[2][kc] * rowDerivative;
        gradient[1] += kernels.derivative[1][kb] * kernels.smooth[2][kc] * rowSmooth;
        gradient[2] += kernels.smooth[1][kb] * kernels.derivative[2][kc] * rowSmooth;
      }
    }
    for (unsigned int d = 0; d < 3; ++d)
    {
      // Per millimetre along the image axis -> per voxel.
      m_Gradients[i][d] = gradient[d] * image->GetSpacing()[d];
    }
  }

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

/** \brief Stage 3 of SurfaceNets, the relaxation of the nodes (thesis 3.2), as its
 * steps: the cell sampling, the cell cache, one SNERT step (eq. 3.5-3.6), the move of
 * one node, and the iterations until convergence. RelaxSurfaceNet runs it.
 *
 * The updates are batch (Jacobi) updates: every node moves from the positions of the
 * previous iteration, until the largest relocation falls below the threshold or the
 * iteration limit is reached. Vectors are built in physical space (the projection on
 * the plane perpendicular to the gradient needs true angles), constrained in index
 * space (where a cell is a unit cube). `gradient(p, node)` returns dI/d(index).
 * Deterministic for any number of threads.
 *
 * The per-node steps run millions of times an iteration: those marked
 * MESHEXTRACTION_ALWAYS_INLINE are inlined into the loop even where GCC would keep
 * them as calls, which pass their vectors through memory.
 * \ingroup MeshExtraction */
template <typename TSampler, typename TGradient>
class SurfaceNetsRelaxer
{
public:
  /** `sampler` may be null for Averaging only; `cellCache`: see SurfaceNetsCellCache. */
  SurfaceNetsRelaxer(SurfaceNet &                            net,
                     const TSampler *                        sampler,
                     TGradient &                             gradient,
                     const SurfaceNetsRelaxationParameters & parameters,
                     SurfaceNetsCellCache *                  cellCache)
      : m_Net(net)
      , m_Sampler(sampler)
      , m_Gradient(gradient)
      , m_Parameters(parameters)
      , m_UseGradient(parameters.kind != SurfaceNetsImageToMeshFilterEnums::Relaxation::Averaging)
      , m_UseAveraging(parameters.kind != SurfaceNetsImageToMeshFilterEnums::Relaxation::Gradient)
      , m_Inverse(parameters.indexToPhysical.GetInverse())
      , m_M(parameters.indexToPhysical)
      , m_Minv(m_Inverse)
      , m_MinvT(Matrix<double, 3, 3>(m_Inverse.GetTranspose()))
      , m_W(m_Inverse * Matrix<double, 3, 3>(m_Inverse.GetTranspose()))
      , m_NumberOfNodes(net.positions.size())
      , m_Next(m_NumberOfNodes)
      , m_NumberOfBlocks((m_NumberOfNodes + BlockSize - 1) / BlockSize)
      , m_BlockMaximum(m_NumberOfBlocks)
      , m_CellCache(cellCache)
      , m_Cache(cellCache != nullptr ? cellCache->entries : m_LocalCache)
      , m_Size(sampler != nullptr ? sampler->GetSize() : nullptr)
      , m_Sy(m_Size != nullptr ? m_Size[0] : 0)
      , m_Sz(m_Size != nullptr ? m_Size[0] * m_Size[1] : 0)
  {
    double smallestSpacing = std::numeric_limits<double>::max();
    m_CellDiagonal = 0.0;
    for (unsigned int c = 0; c < 3; ++c)
    {
      const double length = std::sqrt(m_M(0, c) * m_M(0, c) + m_M(1, c) * m_M(1, c) + m_M(2, c) * m_M(2, c));
      smallestSpacing = std::min(smallestSpacing, length);
      m_CellDiagonal += length * length;
    }
    m_CellDiagonal = std::sqrt(m_CellDiagonal);
    m_H = 0.5 * smallestSpacing;
  }
  SurfaceNetsRelaxer(const SurfaceNetsRelaxer &) = delete;
  SurfaceNetsRelaxer &
  operator=(const SurfaceNetsRelaxer &) = delete;

  /** The iterations: each moves every node once, until none moved more than the
   * convergence threshold or the iteration limit is reached. `progress` gets the
   * fraction of the limit done. */
  SurfaceNetsRelaxationResult
  Run(const std::function<void(double)> & progress)
  {
    SurfaceNetsRelaxationResult result;
    this->PrepareCellCache();
    // A node that has left its own cell (the high-quality mode lets it, by a fraction
    // of a voxel) takes the cell it is in now: see FollowNode. Central differences
    // only (the Gaussian gradients are known at the corners of the net's own cells).
    m_FollowCell = m_Sampler != nullptr && m_UseGradient && m_Parameters.centralDifferences && !m_Cache.empty();
    for (unsigned int iteration = 0; iteration < m_Parameters.maximumNumberOfIterations; ++iteration)
    {
      result.iterations = iteration + 1;
      result.lastMaximumRelocation = this->Iterate();
      if (progress)
      {
        progress(static_cast<double>(iteration + 1) / m_Parameters.maximumNumberOfIterations);
      }
      if (result.lastMaximumRelocation < m_Parameters.convergenceThreshold)
      {
        break;
      }
    }
    return result;
  }

private:
  using Entry = SurfaceNetsCellCache::Entry;
  using PixelType = typename TSampler::PixelType;
  static constexpr std::size_t BlockSize = 2048;

  /** A 3x3 matrix whose products the compiler inlines (itk::Matrix's are calls). */
  struct Matrix3
  {
    double m[3][3];
    explicit Matrix3(const Matrix<double, 3, 3> & A)
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

  // ---------------------------------------------------------------------------------
  // The iterations and the move of one node.

  /** One iteration, in parallel over blocks of nodes, each moved from the previous
   * positions; returns the largest relocation (voxels). */
  double
  Iterate()
  {
    ParallelForBlocks(
      m_NumberOfNodes,
      BlockSize,
      [this](std::size_t begin, std::size_t end, std::size_t block) {
        double largest = 0.0;
        for (std::size_t i = begin; i < end; ++i)
        {
          const Vec3 moved = this->MoveNode(i);
          largest = std::max(largest, SquaredNorm(moved - m_Net.positions[i]));
          m_Next[i] = moved;
        }
        m_BlockMaximum[block] = std::sqrt(largest);
      },
      m_Parameters.numberOfWorkUnits);
    m_Net.positions.swap(m_Next);
    return m_NumberOfBlocks ? *std::max_element(m_BlockMaximum.begin(), m_BlockMaximum.end()) : 0.0;
  }

  /** Node i's new position: SNA's averaging step (eq. 3.1-3.2), or the SNERT step from
   * the cache where the node is inside its entry's cell, or else the general step. */
  MESHEXTRACTION_ALWAYS_INLINE Vec3
  MoveNode(std::size_t i)
  {
    const Vec3 & p = m_Net.positions[i];
    const Vec3   a = this->AveragingVector(i);
    Vec3         moved = p;
    if (!m_UseGradient)
    {
      moved += ConstrainToBox(p, a * m_Parameters.smoothingWeight, m_Net.boxLower[i], m_Net.boxUpper[i]);
    }
    else if (Vec3 step;
             !m_Parameters.sequential && (this->CachedStep(p, i, a, step) ||
                                          (m_FollowCell && this->FollowNode(p, i) && this->CachedStep(p, i, a, step))))
    {
      moved += ConstrainToBox(p, step, m_Cache[i].lower, m_Cache[i].upper);
    }
    else
    {
      this->GeneralStep(p, i, a, moved);
    }
    return moved;
  }

  /** a_p: from node i to the average of its linked nodes (eq. 3.1). */
  MESHEXTRACTION_ALWAYS_INLINE Vec3
  AveragingVector(std::size_t i) const
  {
    const Vec3 & p = m_Net.positions[i];
    Vec3         average = MakeVec3(0, 0, 0);
    const auto   first = m_Net.neighborStart[i];
    const auto   last = m_Net.neighborStart[i + 1];
    for (auto k = first; k < last; ++k)
    {
      average += m_Net.positions[m_Net.neighbors[k]];
    }
    return (last > first) ? average * (1.0 / (last - first)) - p : MakeVec3(0, 0, 0);
  }

  // ---------------------------------------------------------------------------------
  // One SNERT step (eq. 3.5-3.6).

  /** The combined step (eq. 3.5-3.6) of a node inside its entry's cell, from the cache,
   * without normalising the gradient. With n = g/|g|, the projection on the tangent
   * plane is M^-1 (M a - n n.(M a)) = a - t (G.a)/|g|^2, since n.(M a) = (M^T g).a/|g|
   * = G.a/|g|; and the step to the iso-surface, M^-1 (n d) with d = (iso - I)/slope and
   * slope = dI.(M^-1 n) = dI.t/|g|, is t (iso - I)/(dI.t). The same vectors as
   * GeneralStep, with no square root and two divisions. False (d not set) where the
   * node is not in its entry's cell. */
  MESHEXTRACTION_ALWAYS_INLINE bool
  CachedStep(const Vec3 & p, std::size_t node, const Vec3 & a, Vec3 & d) const
  {
    CellSample sample;
    if (!this->SampleCell(p, node, sample))
    {
      return false;
    }
    const Vec3 & G = sample.G;
    const Vec3   t = m_W * G;
    const double g2 = Dot(G, t);
    d = m_UseAveraging ? a * m_Parameters.smoothingWeight : MakeVec3(0, 0, 0);
    if (!(g2 > 0.0))
    {
      return true; // no gradient: no projection, no step (as n = 0 in GeneralStep)
    }
    double       coefficient = m_UseAveraging ? -Dot(G, a) / g2 * m_Parameters.smoothingWeight : 0.0;
    const double slope = Dot(sample.dI, t); // |g| times the slope along n
    if (std::abs(slope) > 1e-3 * g2)
    {
      double q = (m_Parameters.isoValue - sample.value) / slope; // the distance is q |g|
      if (q * q * g2 > m_CellDiagonal * m_CellDiagonal)
      {
        q = std::copysign(m_CellDiagonal / std::sqrt(g2), q);
      }
      coefficient += q * m_Parameters.projectionWeight;
    }
    d += t * coefficient;
    return true;
  }

  /** The general step, from the gradient of any method and the image: the averaging
   * vector projected on the plane perpendicular to the gradient (eq. 3.5) plus the
   * step along the gradient to the iso-surface (eq. 3.6); or, sequential (3.2.4),
   * first the one and then the other from where it ended. Adds the constrained steps
   * to `moved`. */
  MESHEXTRACTION_ALWAYS_INLINE void
  GeneralStep(const Vec3 & p, std::size_t i, const Vec3 & a, Vec3 & moved) const
  {
    Vec3         n;
    const double distance = this->DistanceToIsoSurface(p, static_cast<std::uint32_t>(i), n);
    const Vec3   tangential = m_UseAveraging ? this->TangentialAveraging(a, n) : MakeVec3(0, 0, 0);
    if (m_Parameters.sequential)
    {
      moved += ConstrainToBox(moved, tangential, m_Net.boxLower[i], m_Net.boxUpper[i]);
      Vec3         n2;
      const double d2 = this->DistanceToIsoSurface(moved, static_cast<std::uint32_t>(i), n2);
      moved += ConstrainToBox(
        moved, m_Minv * (n2 * (d2 * m_Parameters.projectionWeight)), m_Net.boxLower[i], m_Net.boxUpper[i]);
    }
    else
    {
      const Vec3 d = tangential + m_Minv * (n * (distance * m_Parameters.projectionWeight)); // eq. 3.6
      moved += ConstrainToBox(p, d, m_Net.boxLower[i], m_Net.boxUpper[i]);
    }
  }

  /** Eq. 3.5: the averaging vector a (index space) without its component along the
   * unit physical gradient n, weighted. */
  MESHEXTRACTION_ALWAYS_INLINE Vec3
  TangentialAveraging(const Vec3 & a, const Vec3 & n) const
  {
    const Vec3 aPhysical = m_M * a;
    return m_Minv * (aPhysical - n * Dot(n, aPhysical)) * m_Parameters.smoothingWeight;
  }

  /** The signed distance (mm) from p along the unit physical gradient n to the
   * iso-surface, from a linear model of the image along n (thesis 3.2.3), clamped to
   * a cell's diagonal; n is set (zero where there is no gradient). From the cache
   * where p is in the node's entry's cell, else from the gradient and the image. */
  double
  DistanceToIsoSurface(const Vec3 & p, std::uint32_t node, Vec3 & n) const
  {
    if (CellSample sample; this->SampleCell(p, node, sample))
    {
      const Vec3   g = m_MinvT * sample.G;
      const double magnitude = Norm(g);
      if (!(magnitude > 0.0))
      {
        n.Fill(0.0);
        return 0.0;
      }
      n = g * (1.0 / magnitude);
      // The exact derivative of the trilinear field along n (M^-1 n: index displacement per mm).
      const double slope = Dot(sample.dI, m_Minv * n);
      if (!(std::abs(slope) > 1e-3 * magnitude))
      {
        return 0.0;
      }
      return std::clamp((m_Parameters.isoValue - sample.value) / slope, -m_CellDiagonal, m_CellDiagonal);
    }
    const Vec3   g = m_MinvT * m_Gradient(p, node);
    const double magnitude = Norm(g);
    if (!(magnitude > 0.0))
    {
      n.Fill(0.0);
      return 0.0;
    }
    n = g * (1.0 / magnitude);
    const Vec3   step = m_Minv * (n * m_H);
    const double value = m_Sampler->Interpolate(p);
    // The image's own slope along n (a smoothed gradient may disagree with it).
    const double slope = (m_Sampler->Interpolate(p + step) - m_Sampler->Interpolate(p - step)) / (2.0 * m_H);
    if (!(std::abs(slope) > 1e-3 * magnitude))
    {
      return 0.0; // flat along n: no reliable step
    }
    return std::clamp((m_Parameters.isoValue - value) / slope, -m_CellDiagonal, m_CellDiagonal);
  }

  // ---------------------------------------------------------------------------------
  // The cell sampling: a node's value, gradient and slope from its cell's 8 corners.
  //
  // Each node's cell: the 8 corner values and (central differences) corner gradients,
  // read once. Inside its cell a node's value, gradient and slope are then plain
  // arithmetic on these (trilinear interpolation, and the trilinear field's exact
  // derivative along n), not 9 interpolations from the image per iteration. Stored as
  // the trilinear fields' coefficients, f(u, v, w) = c0 + c1 u + c2 v + c3 w + c4 uv
  // + c5 uw + c6 vw + c7 uvw in the cell's local coordinates: a value and its three
  // partial derivatives then cost 16 multiply-adds.

  /** A node's value I, gradient G = dI/d(index) and the trilinear field's exact
   * derivative dI at a point. */
  struct CellSample
  {
    double value;
    Vec3   G;
    Vec3   dI;
  };

  /** The sample at p from node's cache entry; false (nothing computed) without a
   * cache or when p is outside the entry's cell. */
  MESHEXTRACTION_ALWAYS_INLINE bool
  SampleCell(const Vec3 & p, std::size_t node, CellSample & sample) const
  {
    if (m_Cache.empty())
    {
      return false;
    }
    const Entry & cc = m_Cache[node];
    const double  u = p[0] - cc.corner[0];
    const double  v = p[1] - cc.corner[1];
    const double  w = p[2] - cc.corner[2];
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
    sample.G = m_Parameters.centralDifferences ? MakeVec3(sum[1], sum[2], sum[3])
                                               : m_Gradient(p, static_cast<std::uint32_t>(node));
#else
    auto field = [&](const float * k) {
      return k[0] + k[1] * u + k[2] * v + k[3] * w + k[4] * uv + k[5] * uw + k[6] * vw + k[7] * uvw;
    };
    sample.value = field(f);
    sample.G = m_Parameters.centralDifferences
                 ? MakeVec3(field(cc.gradient[0]), field(cc.gradient[1]), field(cc.gradient[2]))
                 : m_Gradient(p, static_cast<std::uint32_t>(node));
#endif
    sample.dI = MakeVec3(f[1] + f[4] * v + f[5] * w + f[7] * vw,
                         f[2] + f[4] * u + f[6] * w + f[7] * uw,
                         f[3] + f[5] * u + f[6] * v + f[7] * uv);
    return true;
  }

  /** The trilinear field through 8 corner values (corner k at offset (k & 1,
   * (k >> 1) & 1, (k >> 2) & 1)) as the coefficients c0 .. c7. */
  static void
  ToCoefficients(const double f[8], float c[8])
  {
    c[0] = static_cast<float>(f[0]);
    c[1] = static_cast<float>(f[1] - f[0]);
    c[2] = static_cast<float>(f[2] - f[0]);
    c[3] = static_cast<float>(f[4] - f[0]);
    c[4] = static_cast<float>(f[3] - f[2] - f[1] + f[0]);
    c[5] = static_cast<float>(f[5] - f[4] - f[1] + f[0]);
    c[6] = static_cast<float>(f[6] - f[4] - f[2] + f[0]);
    c[7] = static_cast<float>(f[7] - f[6] - f[5] + f[4] - f[3] + f[2] + f[1] - f[0]);
  }

  /** An entry's fields for cell c: the coefficients of its value and (central
   * differences) gradient fields, and its corner (its box is left as it is). */
  void
  FillEntry(const SurfaceCell & c, Entry & entry) const
  {
    double corner[8];
    double cornerGradient[3][8] = {};
    if (this->IsInterior(c))
    {
      this->ReadInteriorCorners(
        m_Sampler->GetBufferPointer() + (c.z * m_Sz + c.y * m_Sy + c.x), corner, cornerGradient);
    }
    else
    {
      this->ReadCornersBeyondTheBorder(c, corner, cornerGradient);
    }
    entry.corner[0] = c.x;
    entry.corner[1] = c.y;
    entry.corner[2] = c.z;
    ToCoefficients(corner, entry.value);
    for (unsigned int d = 0; d < 3; ++d)
    {
      ToCoefficients(cornerGradient[d], entry.gradient[d]);
    }
  }

  /** Whether the 4x4x4 voxels around a cell (its corners and their central-difference
   * neighbours) are all inside the image: then they are read straight from the buffer. */
  bool
  IsInterior(const SurfaceCell & c) const
  {
    return c.x >= 1 && c.y >= 1 && c.z >= 1 && c.x + 2 < m_Size[0] && c.y + 2 < m_Size[1] && c.z + 2 < m_Size[2];
  }

  /** The corner values and central differences of an interior cell whose first corner
   * is at b, straight from the buffer. */
  void
  ReadInteriorCorners(const PixelType * b, double corner[8], double cornerGradient[3][8]) const
  {
#if defined(__SSE2__)
    if constexpr (std::is_same<PixelType, float>::value)
    {
      this->ReadInteriorCornerPairs(b, corner, cornerGradient);
      return;
    }
#endif
    const std::int64_t sy = m_Sy;
    const std::int64_t sz = m_Sz;
    for (unsigned int k = 0; k < 8; ++k)
    {
      const auto * v = b + ((k >> 2) & 1) * sz + ((k >> 1) & 1) * sy + (k & 1);
      corner[k] = static_cast<double>(v[0]);
      if (m_Parameters.centralDifferences)
      {
        cornerGradient[0][k] = 0.5 * (static_cast<double>(v[1]) - static_cast<double>(v[-1]));
        cornerGradient[1][k] = 0.5 * (static_cast<double>(v[sy]) - static_cast<double>(v[-sy]));
        cornerGradient[2][k] = 0.5 * (static_cast<double>(v[sz]) - static_cast<double>(v[-sz]));
      }
    }
  }

#if defined(__SSE2__)
  /** ReadInteriorCorners of a float image: two corners (x and x + 1) at a time, in
   * double precision as the scalar loop, so the same values, from four loads of two
   * voxels per corner row. */
  void
  ReadInteriorCornerPairs(const float * b, double corner[8], double cornerGradient[3][8]) const
  {
    const std::int64_t sy = m_Sy;
    const std::int64_t sz = m_Sz;
    auto               pair = [](const float * v) {
      return _mm_cvtps_pd(_mm_castsi128_ps(_mm_loadl_epi64(reinterpret_cast<const __m128i *>(v))));
    };
    const __m128d half = _mm_set1_pd(0.5);
    for (unsigned int k = 0; k < 8; k += 2)
    {
      const float * v = b + ((k >> 2) & 1) * sz + ((k >> 1) & 1) * sy;
      _mm_storeu_pd(corner + k, pair(v));
      if (m_Parameters.centralDifferences)
      {
        _mm_storeu_pd(cornerGradient[0] + k, _mm_mul_pd(half, _mm_sub_pd(pair(v + 1), pair(v - 1))));
        _mm_storeu_pd(cornerGradient[1] + k, _mm_mul_pd(half, _mm_sub_pd(pair(v + sy), pair(v - sy))));
        _mm_storeu_pd(cornerGradient[2] + k, _mm_mul_pd(half, _mm_sub_pd(pair(v + sz), pair(v - sz))));
      }
    }
  }
#endif

  /** The corner values and central differences of a cell at the image's border,
   * through the sampler (which extends the image beyond it). */
  void
  ReadCornersBeyondTheBorder(const SurfaceCell & c, double corner[8], double cornerGradient[3][8]) const
  {
    for (unsigned int k = 0; k < 8; ++k)
    {
      const auto [x, y, z] = CornerVoxel(c, k);
      corner[k] = m_Sampler->Value(x, y, z);
      if (m_Parameters.centralDifferences)
      {
        cornerGradient[0][k] = 0.5 * (m_Sampler->Value(x + 1, y, z) - m_Sampler->Value(x - 1, y, z));
        cornerGradient[1][k] = 0.5 * (m_Sampler->Value(x, y + 1, z) - m_Sampler->Value(x, y - 1, z));
        cornerGradient[2][k] = 0.5 * (m_Sampler->Value(x, y, z + 1) - m_Sampler->Value(x, y, z - 1));
      }
    }
  }

  // ---------------------------------------------------------------------------------
  // The cell cache: one entry per node (its cell's fields, its corner and the node's
  // box), so that an iteration reads one record per node (besides the positions)
  // instead of several arrays.

  /** With a gradient step: the entries of a `cellCache` made by an earlier call on
   * the same net get the nodes' boxes anew; otherwise every entry is filled. */
  void
  PrepareCellCache()
  {
    if (m_Sampler == nullptr || !m_UseGradient)
    {
      return;
    }
    if (m_CellCache != nullptr && m_Cache.size() == m_NumberOfNodes &&
        m_CellCache->centralDifferences == m_Parameters.centralDifferences)
    {
      this->RefreshBoxes();
      return;
    }
    // 200 bytes a node, all written by FillCellCache.
    m_Cache.Allocate(m_NumberOfNodes);
    if (m_CellCache != nullptr)
    {
      m_CellCache->centralDifferences = m_Parameters.centralDifferences;
    }
    this->FillCellCache();
  }

  void
  RefreshBoxes()
  {
    for (std::size_t i = 0; i < m_NumberOfNodes; ++i)
    {
      m_Cache[i].lower = m_Net.boxLower[i];
      m_Cache[i].upper = m_Net.boxUpper[i];
    }
  }

  /** Every node's entry for its own cell, in parallel. The voxels of the cell
   * PrefetchAhead nodes on are requested from memory meanwhile: the nodes come in
   * cell order, in a pattern of 16 short rows that the hardware's own prefetching
   * does not foresee, so without the request the fill waits on memory. */
  void
  FillCellCache()
  {
    ParallelForBlocks(
      m_NumberOfNodes,
      BlockSize,
      [this](std::size_t begin, std::size_t end, std::size_t) {
        constexpr std::size_t PrefetchAhead = 16;
        for (std::size_t i = begin; i < end; ++i)
        {
          if (i + PrefetchAhead < end)
          {
            this->PrefetchCell(m_Net.cells[m_Net.nodeCell[i + PrefetchAhead]]);
          }
          this->FillEntry(m_Net.cells[m_Net.nodeCell[i]], m_Cache[i]);
          m_Cache[i].lower = m_Net.boxLower[i];
          m_Cache[i].upper = m_Net.boxUpper[i];
        }
      },
      m_Parameters.numberOfWorkUnits);
  }

  /** Requests the 4x4x4 voxels FillEntry reads of an interior cell. */
  void
  PrefetchCell(const SurfaceCell & c) const
  {
    if (!this->IsInterior(c))
    {
      return;
    }
    const auto * b = m_Sampler->GetBufferPointer() + (c.z * m_Sz + c.y * m_Sy + c.x);
    for (std::int64_t dz = -1; dz <= 2; ++dz)
    {
      for (std::int64_t dy = -1; dy <= 2; ++dy)
      {
        PrefetchForReading(reinterpret_cast<std::uintptr_t>(b + dz * m_Sz + dy * m_Sy - 1), 4 * sizeof(*b));
      }
    }
  }

  /** A node that has left its entry's cell takes the cell it is in now: its entry is
   * refilled for that cell (its box kept), and its steps stay the cached arithmetic
   * instead of nine interpolations from the image. False for a point too far out to
   * name a cell. */
  bool
  FollowNode(const Vec3 & p, std::size_t node)
  {
    constexpr double limit = 1 << 30;
    if (!(std::abs(p[0]) < limit && std::abs(p[1]) < limit && std::abs(p[2]) < limit))
    {
      return false;
    }
    SurfaceCell c{};
    c.x = static_cast<std::int32_t>(std::floor(p[0]));
    c.y = static_cast<std::int32_t>(std::floor(p[1]));
    c.z = static_cast<std::int32_t>(std::floor(p[2]));
    this->FillEntry(c, m_Cache[node]);
    return true;
  }

  SurfaceNet &                            m_Net;
  const TSampler *                        m_Sampler;
  TGradient &                             m_Gradient;
  const SurfaceNetsRelaxationParameters & m_Parameters;
  const bool                              m_UseGradient;
  const bool                              m_UseAveraging;
  bool                                    m_FollowCell{ false };

  // Geometry: M = indexToPhysical, its inverse and inverse transpose, and W = M^-1 M^-T,
  // which maps an index-space gradient G to t = M^-1 g, the index displacement along
  // the physical gradient g = M^-T G, with |g|^2 = G.t.
  const Matrix<double, 3, 3> m_Inverse;
  const Matrix3              m_M;
  const Matrix3              m_Minv;
  const Matrix3              m_MinvT;
  const Matrix3              m_W;
  double                     m_CellDiagonal; ///< mm: the longest step to the iso-surface
  double                     m_H;            ///< mm: finite-difference step along the gradient

  const std::size_t      m_NumberOfNodes;
  LargeBlockVector<Vec3> m_Next; ///< the positions an iteration makes
  const std::size_t      m_NumberOfBlocks;
  std::vector<double>    m_BlockMaximum; ///< each block's largest relocation

  SurfaceNetsCellCache *      m_CellCache;
  UninitializedArray<Entry>   m_LocalCache; ///< the cache without a `cellCache`
  UninitializedArray<Entry> & m_Cache;
  const std::int64_t *        m_Size; ///< the image's size (voxels), null without a sampler
  const std::int64_t          m_Sy;   ///< buffer offset of one step along y
  const std::int64_t          m_Sz;   ///< buffer offset of one step along z
};

/** Stage 3 of SurfaceNets: relax the nodes (see SurfaceNetsRelaxer).
 * `cellCache`: see SurfaceNetsCellCache. \ingroup MeshExtraction */
template <typename TSampler, typename TGradient>
SurfaceNetsRelaxationResult
RelaxSurfaceNet(SurfaceNet &                            net,
                const TSampler *                        sampler,
                TGradient &&                            gradient,
                const SurfaceNetsRelaxationParameters & parameters,
                const std::function<void(double)> &     progress = nullptr,
                SurfaceNetsCellCache *                  cellCache = nullptr)
{
  using RelaxationEnum = SurfaceNetsImageToMeshFilterEnums::Relaxation;
  if (parameters.kind == RelaxationEnum::None || parameters.kind == RelaxationEnum::Automatic ||
      parameters.maximumNumberOfIterations == 0)
  {
    return {};
  }
  if (parameters.kind != RelaxationEnum::Averaging && sampler == nullptr)
  {
    itkGenericExceptionMacro("SurfaceNets: gradient relaxation needs a greyscale image.");
  }
  SurfaceNetsRelaxer<TSampler, std::remove_reference_t<TGradient>> relaxer(
    net, sampler, gradient, parameters, cellCache);
  return relaxer.Run(progress);
}

} // namespace detail
} // namespace MeshExtraction
} // namespace itk

#endif
