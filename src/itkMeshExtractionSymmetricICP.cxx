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
#include "itkMeshExtractionSymmetricICP.h"
#include "itkLevenbergMarquardtOptimizer.h"
#include "itkMeshExtractionParallel.h"
#include "itkPointSetToPointSetRegistrationMethod.h"
#include "itkPointsLocator.h"
#include "itkSymmetricPairedPointSetMetric.h"
#include "vnl/algo/vnl_svd.h"
#include "vnl/algo/vnl_symmetric_eigensystem.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
namespace
{
/** Points per mesh in the coarse stage and for choosing among the initial estimates. */
constexpr std::size_t CoarseSample = 2000;

using PointType = Point<double, 3>;
using PointSetType = PointSet<double, 3>;

PointType
ToPoint(const Vec3 & v)
{
  PointType p;
  for (unsigned int d = 0; d < 3; ++d)
  {
    p[d] = v[d];
  }
  return p;
}

Vec3
ToVec(const PointType & p)
{
  return MakeVec3(p[0], p[1], p[2]);
}

SimilarityTransform::Pointer
MakeSimilarity(const Versor<double> & rotation, double scale, const Vec3 & offset, const Vec3 & center)
{
  auto t = SimilarityTransform::New();
  t->SetCenter(ToPoint(center));
  t->SetRotation(rotation);
  t->SetScale(scale);
  SimilarityTransform::OutputVectorType o;
  for (unsigned int d = 0; d < 3; ++d)
  {
    o[d] = offset[d];
  }
  t->SetOffset(o);
  return t;
}

Vec3
OffsetOf(const SimilarityTransform & t)
{
  const auto o = t.GetOffset();
  return MakeVec3(o[0], o[1], o[2]);
}
} // namespace

// ---- closest points -----------------------------------------------------------------

void
BarycentricWeights(const Vec3 & p, const Vec3 & a, const Vec3 & b, const Vec3 & c, double w[3])
{
  const Vec3   v0 = b - a;
  const Vec3   v1 = c - a;
  const Vec3   v2 = p - a;
  const double d00 = Dot(v0, v0);
  const double d01 = Dot(v0, v1);
  const double d11 = Dot(v1, v1);
  const double d20 = Dot(v2, v0);
  const double d21 = Dot(v2, v1);
  const double denominator = d00 * d11 - d01 * d01;
  if (!(denominator > 0.0))
  {
    w[0] = 1.0; // a degenerate triangle: its first corner
    w[1] = w[2] = 0.0;
    return;
  }
  w[1] = (d11 * d20 - d01 * d21) / denominator;
  w[2] = (d00 * d21 - d01 * d20) / denominator;
  w[0] = 1.0 - w[1] - w[2];
}


struct ClosestPointQuery::VertexTree
{
  using Container = VectorContainer<IdentifierType, PointType>;
  using Locator = PointsLocator<Container>;
  Container::Pointer         points = Container::New();
  Locator::Pointer           locator = Locator::New();
  std::vector<std::uint32_t> vertex; ///< mesh vertex of each locator point
};

ClosestPointQuery::ClosestPointQuery(const IndexedTriangleMesh & mesh, CorrespondenceEnum correspondence)
    : m_Mesh(mesh)
    , m_Correspondence(correspondence)
{
  if (mesh.triangles.empty())
  {
    itkGenericExceptionMacro("A mesh without triangles has no surface to find closest points on.");
  }
  if (correspondence == CorrespondenceEnum::PointToSurface)
  {
    m_Triangles.Build(mesh);
    return;
  }
  // The vertices that are corners of triangles, each with one of its triangles.
  m_VertexTriangle.assign(mesh.points.size(), std::numeric_limits<std::uint32_t>::max());
  m_VertexCorner.assign(mesh.points.size(), 0);
  for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t)
  {
    for (std::uint8_t k = 0; k < 3; ++k)
    {
      if (m_VertexTriangle[mesh.triangles[t][k]] == std::numeric_limits<std::uint32_t>::max())
      {
        m_VertexTriangle[mesh.triangles[t][k]] = t;
        m_VertexCorner[mesh.triangles[t][k]] = k;
      }
    }
  }
  m_Vertices = std::make_unique<VertexTree>();
  for (std::uint32_t v = 0; v < mesh.points.size(); ++v)
  {
    if (m_VertexTriangle[v] != std::numeric_limits<std::uint32_t>::max())
    {
      m_Vertices->points->push_back(ToPoint(mesh.points[v]));
      m_Vertices->vertex.push_back(v);
    }
  }
  m_Vertices->locator->SetPoints(m_Vertices->points);
  m_Vertices->locator->Initialize();
}

ClosestPointQuery::~ClosestPointQuery() = default;

SurfacePoint
ClosestPointQuery::FindOne(const Vec3 & p, std::uint32_t hintTriangle) const
{
  SurfacePoint s;
  if (m_Correspondence == CorrespondenceEnum::PointToSurface)
  {
    const TriangleAABBTree::Nearest nearest = m_Triangles.FindNearest(p, hintTriangle);
    const TriangleIndices &         t = m_Mesh.triangles[nearest.triangle];
    s.triangle = nearest.triangle;
    s.point = nearest.point;
    BarycentricWeights(nearest.point, m_Mesh.points[t[0]], m_Mesh.points[t[1]], m_Mesh.points[t[2]], s.weights);
    return s;
  }
  const std::uint32_t v = m_Vertices->vertex[m_Vertices->locator->FindClosestPoint(ToPoint(p))];
  s.triangle = m_VertexTriangle[v];
  s.weights[0] = s.weights[1] = s.weights[2] = 0.0;
  s.weights[m_VertexCorner[v]] = 1.0;
  s.point = m_Mesh.points[v];
  return s;
}

std::vector<SurfacePoint>
ClosestPointQuery::Find(const std::vector<Vec3> & points, const std::vector<SurfacePoint> * hints) const
{
  std::vector<SurfacePoint> out(points.size());
  ParallelForBlocks(points.size(), 1024, [&](std::size_t begin, std::size_t end, std::size_t) {
    for (std::size_t i = begin; i < end; ++i)
    {
      out[i] = this->FindOne(points[i],
                             hints != nullptr && i < hints->size() ? (*hints)[i].triangle
                                                                   : std::numeric_limits<std::uint32_t>::max());
    }
  });
  return out;
}

// ---- similarity transforms ----------------------------------------------------------

SimilarityTransform::Pointer
HalfSimilarity(const SimilarityTransform & full, const Vec3 & center)
{
  // The versor's square root (the shorter way round): normalise (1 + w, x, y, z).
  Versor<double> q = full.GetVersor();
  double         w = q.GetW(), x = q.GetX(), y = q.GetY(), z = q.GetZ();
  if (w < 0.0)
  {
    w = -w, x = -x, y = -y, z = -z;
  }
  const double   norm = std::sqrt((1.0 + w) * (1.0 + w) + x * x + y * y + z * z);
  Versor<double> half;
  half.Set(x / norm, y / norm, z / norm, (1.0 + w) / norm);
  const double scale = std::sqrt(full.GetScale());
  // Q(x) = M x + o_q with M = scale R_half; Q(Q(x)) = M^2 x + (M + I) o_q, so o_q solves
  // (M + I) o_q = o of the full transform.
  Matrix<double, 3, 3> m = half.GetMatrix() * scale;
  for (unsigned int d = 0; d < 3; ++d)
  {
    m[d][d] += 1.0;
  }
  const Vec3 offset = Matrix<double, 3, 3>(m.GetInverse()) * OffsetOf(full);
  return MakeSimilarity(half, scale, offset, center);
}

SimilarityTransform::Pointer
ComposeWithItself(const SimilarityTransform & half)
{
  const Versor<double> q = half.GetVersor();
  const double         s = half.GetScale();
  const Vec3           o = OffsetOf(half);
  const Vec3           offset = (half.GetMatrix() * o) + o;
  const auto           c = half.GetCenter();
  return MakeSimilarity(q * q, s * s, offset, MakeVec3(c[0], c[1], c[2]));
}

SimilarityTransform::Pointer
FitSimilarity(const std::vector<Vec3> &   fixed,
              const std::vector<Vec3> &   moving,
              const std::vector<double> & weights,
              const Vec3 &                center,
              bool                        symmetricScale)
{
  double total = 0.0;
  Vec3   meanFixed = MakeVec3(0, 0, 0), meanMoving = MakeVec3(0, 0, 0);
  for (std::size_t k = 0; k < fixed.size(); ++k)
  {
    total += weights[k];
    meanFixed += fixed[k] * weights[k];
    meanMoving += moving[k] * weights[k];
  }
  meanFixed *= 1.0 / total;
  meanMoving *= 1.0 / total;
  vnl_matrix<double> covariance(3, 3, 0.0);
  double             variance = 0.0;
  double             movingVariance = 0.0;
  for (std::size_t k = 0; k < fixed.size(); ++k)
  {
    const Vec3 f = fixed[k] - meanFixed;
    const Vec3 m = moving[k] - meanMoving;
    variance += weights[k] * SquaredNorm(f);
    movingVariance += weights[k] * SquaredNorm(m);
    for (unsigned int r = 0; r < 3; ++r)
    {
      for (unsigned int c = 0; c < 3; ++c)
      {
        covariance(r, c) += weights[k] * m[r] * f[c];
      }
    }
  }
  // Umeyama: R = U S V^T with S making it a rotation, s = tr(D S) / var.
  vnl_svd<double>    svd(covariance);
  vnl_matrix<double> S(3, 3, 0.0);
  S(0, 0) = S(1, 1) = 1.0;
  S(2, 2) = vnl_determinant(svd.U()) * vnl_determinant(svd.V()) < 0.0 ? -1.0 : 1.0;
  const vnl_matrix<double> R = svd.U() * S * svd.V().transpose();
  double                   trace = 0.0;
  for (unsigned int k = 0; k < 3; ++k)
  {
    trace += svd.W(k) * S(k, k);
  }
  // Umeyama's scale minimises sum w |T(f) - m|^2; Horn's symmetric one, sqrt of the
  // ratio of the spreads, minimises eq. 7.3 (|Q(f) - Q^-1(m)| = |T(f) - m| / sqrt(s), so
  // E^2 = sum w |T(f) - m|^2 / s).
  const double scale =
    !(variance > 0.0) ? 1.0 : (symmetricScale ? std::sqrt(movingVariance / variance) : trace / variance);
  Matrix<double, 3, 3> rotation;
  for (unsigned int r = 0; r < 3; ++r)
  {
    for (unsigned int c = 0; c < 3; ++c)
    {
      rotation[r][c] = R(r, c);
    }
  }
  Versor<double> versor;
  versor.Set(rotation);
  const Vec3 offset = meanMoving - (rotation * meanFixed) * scale;
  return MakeSimilarity(versor, scale, offset, center);
}

SurfaceMoments
ComputeSurfaceMoments(const IndexedTriangleMesh & mesh)
{
  SurfaceMoments moments;
  Vec3           weighted = MakeVec3(0, 0, 0);
  for (const TriangleIndices & t : mesh.triangles)
  {
    const Vec3 & a = mesh.points[t[0]];
    const Vec3 & b = mesh.points[t[1]];
    const Vec3 & c = mesh.points[t[2]];
    const double area = TriangleArea(a, b, c);
    moments.area += area;
    weighted += TriangleCentroid(a, b, c) * area;
  }
  if (!(moments.area > 0.0))
  {
    itkGenericExceptionMacro("The mesh's triangles have no area: it has no surface to align.");
  }
  moments.centroid = weighted * (1.0 / moments.area);
  // The exact second moment of a triangle about the centroid, per unit area:
  // (sum_k q_k q_k^T + 9 g g^T) / 12, q_k its corners and g its centroid, all relative to
  // the centroid. A vertex's weight for the mean distance is a third of its triangles' area.
  vnl_matrix<double>  second(3, 3, 0.0);
  std::vector<double> vertexArea(mesh.points.size(), 0.0);
  for (const TriangleIndices & t : mesh.triangles)
  {
    const Vec3   q[3] = { mesh.points[t[0]] - moments.centroid,
                          mesh.points[t[1]] - moments.centroid,
                          mesh.points[t[2]] - moments.centroid };
    const Vec3   g = (q[0] + q[1] + q[2]) * (1.0 / 3.0);
    const double area = TriangleArea(mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]]);
    for (unsigned int r = 0; r < 3; ++r)
    {
      for (unsigned int c = 0; c < 3; ++c)
      {
        second(r, c) += area * (q[0][r] * q[0][c] + q[1][r] * q[1][c] + q[2][r] * q[2][c] + 9.0 * g[r] * g[c]) / 12.0;
      }
    }
    for (std::uint32_t v : t)
    {
      vertexArea[v] += area / 3.0;
    }
  }
  vnl_symmetric_eigensystem<double> eigen(second); // ascending eigenvalues
  for (unsigned int k = 0; k < 3; ++k)
  {
    for (unsigned int r = 0; r < 3; ++r)
    {
      moments.axes[r][k] = eigen.V(r, 2 - k);
    }
  }
  if (vnl_determinant(moments.axes.GetVnlMatrix().as_ref()) < 0.0)
  {
    for (unsigned int r = 0; r < 3; ++r)
    {
      moments.axes[r][2] = -moments.axes[r][2];
    }
  }
  double distance = 0.0;
  double weight = 0.0;
  for (std::size_t v = 0; v < mesh.points.size(); ++v)
  {
    distance += vertexArea[v] * Norm(mesh.points[v] - moments.centroid);
    weight += vertexArea[v];
  }
  moments.meanDistance = distance / weight;
  return moments;
}

std::vector<SimilarityTransform::Pointer>
PrincipalAxesCandidates(const SurfaceMoments & fixed, const SurfaceMoments & moving)
{
  const Vec3 &                              cf = fixed.centroid;
  const Vec3 &                              cm = moving.centroid;
  const double                              scale = moving.meanDistance / fixed.meanDistance;
  const double                              signs[4][3] = { { 1, 1, 1 }, { 1, -1, -1 }, { -1, 1, -1 }, { -1, -1, 1 } };
  std::vector<SimilarityTransform::Pointer> candidates;
  for (const auto & sign : signs)
  {
    Matrix<double, 3, 3> flip;
    flip.Fill(0.0);
    for (unsigned int k = 0; k < 3; ++k)
    {
      flip[k][k] = sign[k];
    }
    const Matrix<double, 3, 3> rotation = moving.axes * flip * Matrix<double, 3, 3>(fixed.axes.GetTranspose());
    Versor<double>             versor;
    versor.Set(rotation);
    // T(x) = s R (x - cf) + cm.
    candidates.push_back(MakeSimilarity(versor, scale, cm - (rotation * cf) * scale, cf));
  }
  return candidates;
}

std::vector<Vec3>
TransformPoints(const std::vector<Vec3> & points, const Transform<double, 3, 3> & transform)
{
  std::vector<Vec3> out(points.size());
  ParallelForBlocks(points.size(), 4096, [&](std::size_t begin, std::size_t end, std::size_t) {
    for (std::size_t i = begin; i < end; ++i)
    {
      out[i] = ToVec(transform.TransformPoint(ToPoint(points[i])));
    }
  });
  return out;
}

// ---- the iterations -----------------------------------------------------------------

namespace
{
/** The pairs of eq. 7.3 for the current Q o Q: (a_i, closest on B of T(a_i)) and
 * (closest on A of T^-1(b_j), b_j), with the weights 1/sqrt(n). */
struct Pairs
{
  std::vector<Vec3>         fixed, moving;
  std::vector<double>       weights;
  double                    meanDistance{ 0.0 };
  std::vector<SurfacePoint> onFixed, onMoving; ///< the closest points found, hints for the next pairs
};

/** Every k-th point, k chosen so that at most `limit` remain (all for limit 0). */
std::vector<Vec3>
Sample(const std::vector<Vec3> & points, std::size_t limit)
{
  if (limit == 0 || points.size() <= limit)
  {
    return points;
  }
  const std::size_t stride = (points.size() + limit - 1) / limit;
  std::vector<Vec3> out;
  for (std::size_t i = 0; i < points.size(); i += stride)
  {
    out.push_back(points[i]);
  }
  return out;
}

Pairs
MakePairs(const ClosestPointQuery &   A,
          const ClosestPointQuery &   B,
          const SimilarityTransform & full,
          std::size_t                 limit = 0,
          const Pairs *               previous = nullptr)
{
  const std::vector<Vec3> a = Sample(A.GetMesh().points, limit);
  const std::vector<Vec3> b = Sample(B.GetMesh().points, limit);
  const auto              forward = TransformPoints(a, full);
  const bool              hinted =
    previous != nullptr && previous->onMoving.size() == a.size() && previous->onFixed.size() == b.size();
  Pairs pairs;
  pairs.onMoving = B.Find(forward, hinted ? &previous->onMoving : nullptr);
  pairs.onFixed = A.Find(TransformPoints(b, *full.GetInverseTransform()), hinted ? &previous->onFixed : nullptr);
  const auto & onB = pairs.onMoving;
  const auto & onA = pairs.onFixed;
  const double wa = 1.0 / std::sqrt(static_cast<double>(a.size()));
  const double wb = 1.0 / std::sqrt(static_cast<double>(b.size()));
  double       distance = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i)
  {
    pairs.fixed.push_back(a[i]);
    pairs.moving.push_back(onB[i].point);
    pairs.weights.push_back(wa);
    distance += Norm(forward[i] - onB[i].point);
  }
  const auto onAForward = TransformPoints(
    [&onA]() {
      std::vector<Vec3> points;
      for (const auto & s : onA)
      {
        points.push_back(s.point);
      }
      return points;
    }(),
    full);
  for (std::size_t j = 0; j < b.size(); ++j)
  {
    pairs.fixed.push_back(onA[j].point);
    pairs.moving.push_back(b[j]);
    pairs.weights.push_back(wb);
    distance += Norm(onAForward[j] - b[j]);
  }
  pairs.meanDistance = distance / static_cast<double>(a.size() + b.size());
  return pairs;
}

/** E^2 (eq. 7.3) of the half transform Q over fixed pairs: sum w^2 |Q(f) - Q^-1(m)|^2. */
double
PairsE2(const Pairs & pairs, const SimilarityTransform & half)
{
  const auto inverse = half.GetInverseTransform();
  double     e2 = 0.0;
  for (std::size_t k = 0; k < pairs.fixed.size(); ++k)
  {
    const Vec3 forward = ToVec(half.TransformPoint(ToPoint(pairs.fixed[k])));
    const Vec3 backward = ToVec(inverse->TransformPoint(ToPoint(pairs.moving[k])));
    e2 += pairs.weights[k] * pairs.weights[k] * SquaredNorm(forward - backward);
  }
  return e2;
}

PointSetType::Pointer
MakePointSet(const std::vector<Vec3> & points)
{
  auto set = PointSetType::New();
  auto container = PointSetType::PointsContainer::New();
  container->Reserve(points.size());
  for (std::size_t k = 0; k < points.size(); ++k)
  {
    container->SetElement(k, ToPoint(points[k]));
  }
  set->SetPoints(container);
  return set;
}

/** Q minimising eq. 7.3 for fixed pairs, with ITK's registration method and
 * Levenberg-Marquardt, from `start`; returns E^2 there. */
double
MinimizeE2(const Pairs & pairs, SimilarityTransform & start, unsigned int iterations)
{
  using Metric = SymmetricPairedPointSetMetric<PointSetType>;
  auto metric = Metric::New();
  metric->SetWeights(pairs.weights);
  auto optimizer = LevenbergMarquardtOptimizer::New();
  optimizer->SetUseCostFunctionGradient(true); // the metric's exact Jacobian
  optimizer->SetNumberOfIterations(iterations);
  optimizer->SetValueTolerance(1e-10);
  optimizer->SetGradientTolerance(1e-10);
  optimizer->SetEpsilonFunction(1e-10);
  LevenbergMarquardtOptimizer::ScalesType scales(start.GetNumberOfParameters());
  scales.Fill(1.0);
  optimizer->SetScales(scales);
  auto registration = PointSetToPointSetRegistrationMethod<PointSetType, PointSetType>::New();
  registration->SetFixedPointSet(MakePointSet(pairs.fixed));
  registration->SetMovingPointSet(MakePointSet(pairs.moving));
  registration->SetMetric(metric);
  registration->SetOptimizer(optimizer);
  registration->SetTransform(&start);
  registration->SetInitialTransformParameters(start.GetParameters());
  registration->Update();
  start.SetParameters(registration->GetLastTransformParameters());
  return metric->GetValue(start.GetParameters()).squared_magnitude();
}
} // namespace

double
SymmetricE2(const ClosestPointQuery &   fixed,
            const ClosestPointQuery &   moving,
            const SimilarityTransform & half,
            std::size_t                 sampleLimit)
{
  return PairsE2(MakePairs(fixed, moving, *ComposeWithItself(half), sampleLimit), half);
}

namespace
{
/** Closed-form iterations of the start search at most (each candidate). */
constexpr unsigned int ProbeIterations = 8;

/** A random sample of a mesh's vertices (the same for the same mesh: a fixed seed) with
 * a nearest-vertex locator: the start search's cheap stand-in for the mesh. */
class VertexSample
{
public:
  VertexSample(const std::vector<Vec3> & points, std::size_t limit, std::uint32_t seed)
  {
    // A partial Fisher-Yates shuffle driven by mt19937's raw output, which the standard
    // fixes, so the sample is the same on every platform.
    std::vector<std::uint32_t> order(points.size());
    for (std::uint32_t i = 0; i < order.size(); ++i)
    {
      order[i] = i;
    }
    std::mt19937      random(seed);
    const std::size_t count = std::min(limit, points.size());
    for (std::size_t i = 0; i < count; ++i)
    {
      std::swap(order[i], order[i + random() % (points.size() - i)]);
      m_Points.push_back(points[order[i]]);
    }
    m_Container = Container::New();
    for (std::size_t k = 0; k < m_Points.size(); ++k)
    {
      m_Container->push_back(ToPoint(m_Points[k]));
    }
    m_Locator = Locator::New();
    m_Locator->SetPoints(m_Container);
    m_Locator->Initialize();
  }

  const std::vector<Vec3> &
  Points() const
  {
    return m_Points;
  }

  Vec3
  Nearest(const Vec3 & p) const
  {
    return m_Points[m_Locator->FindClosestPoint(ToPoint(p))];
  }

private:
  using Container = VectorContainer<IdentifierType, PointType>;
  using Locator = PointsLocator<Container>;
  std::vector<Vec3>  m_Points;
  Container::Pointer m_Container;
  Locator::Pointer   m_Locator;
};

/** The pairs of eq. 7.3 between two samples for Q o Q = `full`, nearest vertices. */
Pairs
SamplePairs(const VertexSample & A, const VertexSample & B, const SimilarityTransform & full)
{
  Pairs        pairs;
  const auto   forward = TransformPoints(A.Points(), full);
  const auto   backward = TransformPoints(B.Points(), *full.GetInverseTransform());
  const double wa = 1.0 / std::sqrt(static_cast<double>(A.Points().size()));
  const double wb = 1.0 / std::sqrt(static_cast<double>(B.Points().size()));
  for (std::size_t i = 0; i < forward.size(); ++i)
  {
    pairs.fixed.push_back(A.Points()[i]);
    pairs.moving.push_back(B.Nearest(forward[i]));
    pairs.weights.push_back(wa);
  }
  for (std::size_t j = 0; j < backward.size(); ++j)
  {
    pairs.fixed.push_back(A.Nearest(backward[j]));
    pairs.moving.push_back(B.Points()[j]);
    pairs.weights.push_back(wb);
  }
  return pairs;
}

/** A few closed-form ICP iterations on the samples from `half`, until E^2 settles:
 * the best Q met and its E^2. */
std::pair<SimilarityTransform::Pointer, double>
Probe(const VertexSample & A, const VertexSample & B, SimilarityTransform::Pointer half, const Vec3 & center)
{
  SimilarityTransform::Pointer best = half;
  double                       bestE2 = std::numeric_limits<double>::infinity();
  for (unsigned int iteration = 0; iteration < ProbeIterations; ++iteration)
  {
    const Pairs  pairs = SamplePairs(A, B, *ComposeWithItself(*half));
    const double e2 = PairsE2(pairs, *half);
    if (!(e2 < bestE2 * (1.0 - 1e-5)))
    {
      if (e2 < bestE2)
      {
        best = half, bestE2 = e2;
      }
      break;
    }
    best = half, bestE2 = e2;
    std::vector<double> squared(pairs.weights.size());
    for (std::size_t k = 0; k < squared.size(); ++k)
    {
      squared[k] = pairs.weights[k] * pairs.weights[k];
    }
    half = HalfSimilarity(*FitSimilarity(pairs.fixed, pairs.moving, squared, center, true), center);
  }
  return { best, bestE2 };
}

/** The start: the given transform, or the best of the principal-axes candidates after
 * a short probe of each on vertex samples. */
SimilarityTransform::Pointer
InitialHalf(const ClosestPointQuery &    A,
            const ClosestPointQuery &    B,
            const SymmetricICPSettings & settings,
            const SurfaceMoments &       momentsA,
            const SurfaceMoments &       momentsB)
{
  const Vec3 & center = momentsA.centroid;
  if (settings.initial != nullptr)
  {
    return HalfSimilarity(*settings.initial, center);
  }
  if (!settings.initialAlignment)
  {
    return HalfSimilarity(*SimilarityTransform::New(), center);
  }
  const VertexSample           sampleA(A.GetMesh().points, CoarseSample, 0);
  const VertexSample           sampleB(B.GetMesh().points, CoarseSample, 1);
  SimilarityTransform::Pointer best;
  double                       bestE2 = std::numeric_limits<double>::infinity();
  for (const auto & candidate : PrincipalAxesCandidates(momentsA, momentsB))
  {
    const auto [half, e2] = Probe(sampleA, sampleB, HalfSimilarity(*candidate, center), center);
    if (e2 < bestE2)
    {
      bestE2 = e2;
      best = half;
    }
  }
  return best;
}
} // namespace

namespace
{
/** One ICP iteration from `half`: the pairs of Q o Q, then the new Q (the half of their
 * least-squares similarity, refined by Levenberg-Marquardt on eq. 7.3 when `exact`) and
 * its E^2 for these pairs. */
std::pair<SimilarityTransform::Pointer, double>
Iterate(const ClosestPointQuery &   fixed,
        const ClosestPointQuery &   moving,
        const SimilarityTransform & half,
        const Vec3 &                center,
        std::size_t                 sampleLimit,
        bool                        exact,
        unsigned int                levenbergMarquardtIterations,
        Pairs &                     pairs)
{
  Pairs next = MakePairs(fixed, moving, *ComposeWithItself(half), sampleLimit, &pairs);
  pairs = std::move(next);
  std::vector<double> squared(pairs.weights.size());
  for (std::size_t k = 0; k < squared.size(); ++k)
  {
    squared[k] = pairs.weights[k] * pairs.weights[k];
  }
  auto candidate = HalfSimilarity(*FitSimilarity(pairs.fixed, pairs.moving, squared, center, true), center);
  if (exact)
  {
    const double e2 = MinimizeE2(pairs, *candidate, levenbergMarquardtIterations);
    return { candidate, e2 };
  }
  return { candidate, PairsE2(pairs, *candidate) };
}
} // namespace

SymmetricICPResult
RunSymmetricICP(const ClosestPointQuery &    fixed,
                const ClosestPointQuery &    moving,
                const SymmetricICPSettings & settings)
{
  const SurfaceMoments momentsFixed = ComputeSurfaceMoments(fixed.GetMesh());
  const Vec3 &         center = momentsFixed.centroid;
  SymmetricICPResult   result;
  result.half = InitialHalf(fixed, moving, settings, momentsFixed, ComputeSurfaceMoments(moving.GetMesh()));
  result.initialE2 =
    settings.measureInitialE2 ? SymmetricE2(fixed, moving, *result.half) : std::numeric_limits<double>::quiet_NaN();
  // Three stages, each until E^2 settles: a sample of the points with the closed-form
  // step (the half of the pairs' least-squares similarity, close to eq. 7.3's minimum),
  // all points with it, then all points with each step refined by Levenberg-Marquardt on
  // eq. 7.3 itself. The sample only speeds up the approach; the result is that of all
  // points.
  enum Stage
  {
    Coarse,
    Fine,
    Exact
  };
  int    stage = Coarse;
  double previous = SymmetricE2(fixed, moving, *result.half, CoarseSample);
  Pairs  pairs; // the last pairs, whose closest points start the next searches
  for (unsigned int iteration = 0; iteration < settings.maximumIterations; ++iteration)
  {
    auto [candidate, e2] = Iterate(fixed,
                                   moving,
                                   *result.half,
                                   center,
                                   stage == Coarse ? CoarseSample : 0,
                                   stage == Exact,
                                   settings.levenbergMarquardtIterations,
                                   pairs);
    result.iterations = iteration + 1;
    if (settings.progress)
    {
      settings.progress(static_cast<double>(iteration + 1) / settings.maximumIterations);
    }
    const bool improved = e2 < previous;
    const bool settled = !improved || previous - e2 < settings.relativeTolerance * previous;
    if (improved)
    {
      result.half = candidate;
    }
    previous = improved ? e2 : previous;
    if (settled)
    {
      if (stage == Exact)
      {
        break;
      }
      ++stage;
      // The next stage measures E^2 its own way: start its comparison afresh.
      previous = std::numeric_limits<double>::infinity();
    }
  }
  result.fixedToMoving = ComposeWithItself(*result.half);
  const Pairs last = MakePairs(fixed, moving, *result.fixedToMoving, 0, &pairs);
  result.meanDistance = last.meanDistance;
  result.e2 = PairsE2(last, *result.half);
  return result;
}
} // namespace detail
} // namespace MeshExtraction
} // namespace itk
