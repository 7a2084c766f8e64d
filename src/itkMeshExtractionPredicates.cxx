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
#include "itkMeshExtractionPredicates.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
namespace
{
// ---------------------------------------------------------------------------
// Exact sums of products with floating-point expansions (Shewchuk, "Adaptive
// precision floating-point arithmetic and fast robust geometric predicates",
// 1997: TWO-SUM, TWO-PRODUCT via fused multiply-add, GROW-EXPANSION). An
// expansion is a sum of non-overlapping doubles in increasing magnitude; its
// sign is the sign of its largest (last non-zero) component.
// ---------------------------------------------------------------------------
inline void
TwoSum(double a, double b, double & x, double & y)
{
  x = a + b;
  const double bv = x - a;
  const double av = x - bv;
  y = (a - av) + (b - bv);
}

inline void
TwoProduct(double a, double b, double & x, double & y)
{
  x = a * b;
  y = std::fma(a, b, -x);
}

class ExactSum
{
public:
  void
  Add(double b)
  {
    if (b == 0.0)
    {
      return;
    }
    double      q = b;
    std::size_t out = 0;
    for (std::size_t i = 0; i < m_Size; ++i)
    {
      double sum;
      double err;
      TwoSum(q, m_Components[i], sum, err);
      q = sum;
      if (err != 0.0)
      {
        m_Components[out++] = err;
      }
    }
    m_Size = out;
    if (q != 0.0)
    {
      m_Components[m_Size++] = q;
    }
  }

  /** Adds sign * x * y exactly. */
  void
  AddProduct(double sign, double x, double y)
  {
    double p;
    double e;
    TwoProduct(x, y, p, e);
    Add(sign * p);
    Add(sign * e);
  }

  /** Adds sign * x * y * z exactly. */
  void
  AddProduct(double sign, double x, double y, double z)
  {
    double p;
    double e;
    TwoProduct(x, y, p, e);
    double p1;
    double p2;
    double e1;
    double e2;
    TwoProduct(p, z, p1, p2);
    TwoProduct(e, z, e1, e2);
    Add(sign * p1);
    Add(sign * p2);
    Add(sign * e1);
    Add(sign * e2);
  }

  int
  Sign() const
  {
    if (m_Size == 0)
    {
      return 0;
    }
    return m_Components[m_Size - 1] > 0.0 ? 1 : -1;
  }

private:
  // A sum of n doubles needs at most n non-overlapping components; the largest
  // sums here have 96 terms.
  double      m_Components[128];
  std::size_t m_Size{ 0 };
};

/** x - y as an exact two-term expansion: x - y = d + t. */
inline void
TwoDiff(double x, double y, double & d, double & t)
{
  d = x - y;
  const double bv = x - d;
  const double av = d + bv;
  t = (x - av) + (bv - y);
}

constexpr double Epsilon = 1.1102230246251565e-16; // 2^-53
// Static filter bounds (Shewchuk's ccwerrboundA and o3derrboundA, rounded up).
constexpr double Orient2DBound = (3.0 + 16.0 * Epsilon) * Epsilon * 1.0000001;
constexpr double Orient3DBound = (7.0 + 56.0 * Epsilon) * Epsilon * 1.0000001;

inline int
SignOf(double v)
{
  return (v > 0.0) - (v < 0.0);
}

// det3 of the rows u, v, w, added exactly with the given sign.
void
AddDet3(ExactSum & s, double sign, const Vec3 & u, const Vec3 & v, const Vec3 & w)
{
  s.AddProduct(sign, u[0], v[1], w[2]);
  s.AddProduct(-sign, u[0], v[2], w[1]);
  s.AddProduct(-sign, u[1], v[0], w[2]);
  s.AddProduct(sign, u[1], v[2], w[0]);
  s.AddProduct(sign, u[2], v[0], w[1]);
  s.AddProduct(-sign, u[2], v[1], w[0]);
}

/** u x v with the magnitudes of its products, for the static filter of w . (u x v)
 * (Shewchuk's orient3d bound, which holds when u, v and w are rounded differences of
 * doubles, or exact). */
struct FilteredCross
{
  Vec3 cross;
  Vec3 magnitude;

  FilteredCross() = default;
  FilteredCross(const Vec3 & u, const Vec3 & v)
  {
    const double m0 = u[1] * v[2];
    const double m1 = u[2] * v[1];
    const double m2 = u[2] * v[0];
    const double m3 = u[0] * v[2];
    const double m4 = u[0] * v[1];
    const double m5 = u[1] * v[0];
    cross = MakeVec3(m0 - m1, m2 - m3, m4 - m5);
    magnitude = MakeVec3(std::abs(m0) + std::abs(m1), std::abs(m2) + std::abs(m3), std::abs(m4) + std::abs(m5));
  }

  /** The sign of w . (u x v) if the filter is certain of it, else 0. */
  int
  Sign(const Vec3 & w) const
  {
    const double det = w[0] * cross[0] + w[1] * cross[1] + w[2] * cross[2];
    const double bound =
      Orient3DBound * (std::abs(w[0]) * magnitude[0] + std::abs(w[1]) * magnitude[1] + std::abs(w[2]) * magnitude[2]);
    return det > bound ? 1 : (-det > bound ? -1 : 0);
  }
};

/** Orient3D(a, b, c, x) for several x: the products of (b - a) x (c - a), with their
 * magnitudes for the static filter, are computed once. Exact signs (x outside the
 * filter's certainty goes to the exact evaluation). */
class PlaneOrientation
{
public:
  PlaneOrientation(const Vec3 & a, const Vec3 & b, const Vec3 & c)
      : m_A(a)
      , m_B(b)
      , m_C(c)
      , m_Products(b - a, c - a)
  {}

  int
  operator()(const Vec3 & d) const
  {
    const int sign = m_Products.Sign(d - m_A);
    return sign != 0 ? sign : Orient3DUncertain(m_A, m_B, m_C, d);
  }

private:
  static int
  Orient3DUncertain(const Vec3 & a, const Vec3 & b, const Vec3 & c, const Vec3 & d);

  Vec3          m_A;
  Vec3          m_B;
  Vec3          m_C;
  FilteredCross m_Products;
};

int
PlaneOrientation::Orient3DUncertain(const Vec3 & a, const Vec3 & b, const Vec3 & c, const Vec3 & d)
{
  // When the differences are exact (common: points on a grid, or close to each
  // other), det[u, v, w] of those doubles is the exact value: 6 triple products.
  Vec3 uu;
  Vec3 vv;
  Vec3 ww;
  bool exactDifferences = true;
  for (unsigned int k = 0; k < 3 && exactDifferences; ++k)
  {
    double t0;
    double t1;
    double t2;
    TwoDiff(b[k], a[k], uu[k], t0);
    TwoDiff(c[k], a[k], vv[k], t1);
    TwoDiff(d[k], a[k], ww[k], t2);
    exactDifferences = t0 == 0.0 && t1 == 0.0 && t2 == 0.0;
  }
  if (exactDifferences)
  {
    ExactSum s;
    AddDet3(s, 1.0, uu, vv, ww);
    return s.Sign();
  }
  // det[b-a, c-a, d-a] = det[b,c,d] - det[a,c,d] - det[b,a,d] - det[b,c,a].
  return Orient3DExact(a, b, c, d);
}

// ---------------------------------------------------------------------------
// 2-D helpers on the projection of a plane onto a coordinate plane.
// ---------------------------------------------------------------------------
struct Projection
{
  unsigned int u;
  unsigned int v;
};

inline void
Project(const Vec3 & p, const Projection & pr, double out[2])
{
  out[0] = p[pr.u];
  out[1] = p[pr.v];
}

/** A coordinate plane onto which the non-degenerate triangle (a, b, c) projects
 * to a non-degenerate triangle. Returns false if none does (degenerate). */
bool
ChooseProjection(const Vec3 & a, const Vec3 & b, const Vec3 & c, Projection & pr)
{
  const Vec3   n = TriangleNormal(a, b, c);
  unsigned int order[3] = { 0, 1, 2 };
  std::sort(order, order + 3, [&n](unsigned i, unsigned j) { return std::abs(n[i]) > std::abs(n[j]); });
  for (unsigned int drop : order)
  {
    const Projection candidate{ (drop + 1) % 3, (drop + 2) % 3 };
    double           pa[2];
    double           pb[2];
    double           pc[2];
    Project(a, candidate, pa);
    Project(b, candidate, pb);
    Project(c, candidate, pc);
    if (Orient2D(pa, pb, pc) != 0)
    {
      pr = candidate;
      return true;
    }
  }
  return false;
}

bool
OnSegment2D(const double p[2], const double a[2], const double b[2])
{
  // p is known to be collinear with a and b.
  return std::min(a[0], b[0]) <= p[0] && p[0] <= std::max(a[0], b[0]) && std::min(a[1], b[1]) <= p[1] &&
         p[1] <= std::max(a[1], b[1]);
}

bool
SegmentsIntersect2D(const double a[2], const double b[2], const double c[2], const double d[2])
{
  const int o1 = Orient2D(a, b, c);
  const int o2 = Orient2D(a, b, d);
  const int o3 = Orient2D(c, d, a);
  const int o4 = Orient2D(c, d, b);
  if (o1 * o2 < 0 && o3 * o4 < 0)
  {
    return true;
  }
  return (o1 == 0 && OnSegment2D(c, a, b)) || (o2 == 0 && OnSegment2D(d, a, b)) || (o3 == 0 && OnSegment2D(a, c, d)) ||
         (o4 == 0 && OnSegment2D(b, c, d));
}

bool
PointInTriangle2D(const double p[2], const double a[2], const double b[2], const double c[2])
{
  const int s = Orient2D(a, b, c);
  return Orient2D(a, b, p) * s >= 0 && Orient2D(b, c, p) * s >= 0 && Orient2D(c, a, p) * s >= 0;
}

bool
SegmentIntersectsTriangle2D(const double a[2], const double b[2], const double t[3][2])
{
  return PointInTriangle2D(a, t[0], t[1], t[2]) || PointInTriangle2D(b, t[0], t[1], t[2]) ||
         SegmentsIntersect2D(a, b, t[0], t[1]) || SegmentsIntersect2D(a, b, t[1], t[2]) ||
         SegmentsIntersect2D(a, b, t[2], t[0]);
}

/** With `a` coplanar with the triangle (v, c, d): does the direction a - v point
 * into the closed angle of that triangle at v? (a != v, triangle non-degenerate.) */
bool
DirectionInWedge(const Vec3 & a, const Vec3 & v, const Vec3 & c, const Vec3 & d)
{
  Projection pr{};
  if (!ChooseProjection(v, c, d, pr))
  {
    return false;
  }
  double pv[2];
  double pc[2];
  double pd[2];
  double pa[2];
  Project(v, pr, pv);
  Project(c, pr, pc);
  Project(d, pr, pd);
  Project(a, pr, pa);
  const int s = Orient2D(pv, pc, pd);
  return Orient2D(pv, pc, pa) * s >= 0 && Orient2D(pv, pa, pd) * s >= 0;
}

/** Edge (v, a) of one face runs into the other face (v, c, d) beyond v. */
bool
EdgeEntersFaceAtSharedVertex(const Vec3 & v, const Vec3 & a, const Vec3 & c, const Vec3 & d)
{
  return Orient3D(v, c, d, a) == 0 && DirectionInWedge(a, v, c, d);
}
} // namespace

int
Orient2D(const double a[2], const double b[2], const double c[2])
{
  const double acx = a[0] - c[0];
  const double bcx = b[0] - c[0];
  const double acy = a[1] - c[1];
  const double bcy = b[1] - c[1];
  const double left = acx * bcy;
  const double right = acy * bcx;
  const double det = left - right;
  const double bound = Orient2DBound * (std::abs(left) + std::abs(right));
  if (det > bound || -det > bound)
  {
    return SignOf(det);
  }
  // det[b-a, c-a] = det[b,c] - det[a,c] - det[b,a] over the 2x2 rows.
  ExactSum s;
  s.AddProduct(1.0, b[0], c[1]);
  s.AddProduct(-1.0, b[1], c[0]);
  s.AddProduct(-1.0, a[0], c[1]);
  s.AddProduct(1.0, a[1], c[0]);
  s.AddProduct(-1.0, b[0], a[1]);
  s.AddProduct(1.0, b[1], a[0]);
  return s.Sign();
}

int
Orient3D(const Vec3 & a, const Vec3 & b, const Vec3 & c, const Vec3 & d)
{
  return PlaneOrientation(a, b, c)(d);
}

int
Orient3DExact(const Vec3 & a, const Vec3 & b, const Vec3 & c, const Vec3 & d)
{
  ExactSum s;
  AddDet3(s, 1.0, b, c, d);
  AddDet3(s, -1.0, a, c, d);
  AddDet3(s, -1.0, b, a, d);
  AddDet3(s, -1.0, b, c, a);
  return s.Sign();
}

bool
IsTriangleDegenerateExact(const Vec3 & a, const Vec3 & b, const Vec3 & c)
{
  Projection pr{};
  return !ChooseProjection(a, b, c, pr);
}

bool
SegmentIntersectsTriangle(const Vec3 & a, const Vec3 & b, const Vec3 & p, const Vec3 & q, const Vec3 & r)
{
  const PlaneOrientation plane(p, q, r);
  const int              oa = plane(a);
  const int              ob = plane(b);
  if (oa * ob > 0)
  {
    return false;
  }
  if (oa == 0 && ob == 0)
  {
    Projection pr{};
    if (!ChooseProjection(p, q, r, pr))
    {
      return false;
    }
    double pa[2];
    double pb[2];
    double t[3][2];
    Project(a, pr, pa);
    Project(b, pr, pb);
    Project(p, pr, t[0]);
    Project(q, pr, t[1]);
    Project(r, pr, t[2]);
    return SegmentIntersectsTriangle2D(pa, pb, t);
  }
  // The line through a and b crosses the plane at a point of the segment; it
  // meets the closed triangle iff the three signed volumes do not disagree.
  const int  s1 = Orient3D(a, b, p, q);
  const int  s2 = Orient3D(a, b, q, r);
  const int  s3 = Orient3D(a, b, r, p);
  const bool anyPositive = s1 > 0 || s2 > 0 || s3 > 0;
  const bool anyNegative = s1 < 0 || s2 < 0 || s3 < 0;
  return !(anyPositive && anyNegative);
}

bool
TrianglesIntersect(const Vec3 P[3], const Vec3 Q[3])
{
  // Separated by the plane of either triangle: no common point.
  for (unsigned int pass = 0; pass < 2; ++pass)
  {
    const Vec3 *           A = pass == 0 ? P : Q;
    const Vec3 *           B = pass == 0 ? Q : P;
    const PlaneOrientation plane(A[0], A[1], A[2]);
    const int              s0 = plane(B[0]);
    const int              s1 = plane(B[1]);
    const int              s2 = plane(B[2]);
    if ((s0 > 0 && s1 > 0 && s2 > 0) || (s0 < 0 && s1 < 0 && s2 < 0))
    {
      return false;
    }
  }
  // If two closed triangles meet, an end of their (convex) intersection lies on an
  // edge of one of them, so six segment tests decide it.
  for (unsigned int i = 0; i < 3; ++i)
  {
    if (SegmentIntersectsTriangle(P[i], P[(i + 1) % 3], Q[0], Q[1], Q[2]) ||
        SegmentIntersectsTriangle(Q[i], Q[(i + 1) % 3], P[0], P[1], P[2]))
    {
      return true;
    }
  }
  return false;
}

namespace
{
/** Faces P and Q with the common edge (v, w) of P's sides beyond corner pi (P's
 * corner pi is not shared): they overlap beyond the edge only if they are coplanar
 * with their third vertices on the same side of it. */
bool
FacesWithCommonEdgeIntersect(const Vec3           P[3],
                             const IdentifierType pid[3],
                             unsigned int         pi,
                             const Vec3           Q[3],
                             const IdentifierType qid[3])
{
  const Vec3 & v = P[(pi + 1) % 3];
  const Vec3 & w = P[(pi + 2) % 3];
  const Vec3 & a = P[pi];
  unsigned int qi = 0;
  while (qid[qi] == pid[(pi + 1) % 3] || qid[qi] == pid[(pi + 2) % 3])
  {
    ++qi;
  }
  const Vec3 & c = Q[qi];
  if (Orient3D(v, w, a, c) != 0)
  {
    return false;
  }
  Projection pr{};
  if (!ChooseProjection(v, w, a, pr))
  {
    return false;
  }
  double pv[2];
  double pw[2];
  double pa[2];
  double pc[2];
  Project(v, pr, pv);
  Project(w, pr, pw);
  Project(a, pr, pa);
  Project(c, pr, pc);
  return Orient2D(pv, pw, pa) * Orient2D(pv, pw, pc) > 0;
}

/** Faces P = (v, a, b) and Q = (v, c, d) with the one common vertex v. A point other
 * than v in both faces exists iff the far edge of one face meets the other face, or
 * an edge leaving v runs into the other face: walking from v through a common
 * point, the last common point lies on the boundary of one face away from v, i.e.
 * on its far edge or on one of its edges leaving v. */
bool
FacesWithCommonVertexIntersect(const Vec3 & v, const Vec3 & a, const Vec3 & b, const Vec3 & c, const Vec3 & d)
{
  // Either face strictly on one side of the other's plane (but for v): only v is common.
  const PlaneOrientation planeP(v, a, b);
  const int              oc = planeP(c);
  const int              od = planeP(d);
  if (oc != 0 && oc == od)
  {
    return false;
  }
  const PlaneOrientation planeQ(v, c, d);
  const int              oa = planeQ(a);
  const int              ob = planeQ(b);
  if (oa != 0 && oa == ob)
  {
    return false;
  }
  return SegmentIntersectsTriangle(a, b, v, c, d) || SegmentIntersectsTriangle(c, d, v, a, b) ||
         EdgeEntersFaceAtSharedVertex(v, a, c, d) || EdgeEntersFaceAtSharedVertex(v, b, c, d) ||
         EdgeEntersFaceAtSharedVertex(v, c, a, b) || EdgeEntersFaceAtSharedVertex(v, d, a, b);
}
} // namespace

bool
FacesIntersect(const Vec3 P[3], const IdentifierType pid[3], const Vec3 Q[3], const IdentifierType qid[3])
{
  int sharedP[3] = { -1, -1, -1 }; // index into Q of P's vertex i, or -1
  int shared = 0;
  for (unsigned int i = 0; i < 3; ++i)
  {
    for (unsigned int j = 0; j < 3; ++j)
    {
      if (pid[i] == qid[j])
      {
        sharedP[i] = static_cast<int>(j);
        ++shared;
      }
    }
  }
  if (shared == 0)
  {
    return TrianglesIntersect(P, Q);
  }
  if (shared >= 3)
  {
    return true;
  }
  if (shared == 2)
  {
    unsigned int pi = 0; // P's corner that is not shared
    while (sharedP[pi] >= 0)
    {
      ++pi;
    }
    return FacesWithCommonEdgeIntersect(P, pid, pi, Q, qid);
  }
  unsigned int pi = 0; // P's shared corner
  while (sharedP[pi] < 0)
  {
    ++pi;
  }
  const unsigned int qi = static_cast<unsigned int>(sharedP[pi]);
  return FacesWithCommonVertexIntersect(P[pi], P[(pi + 1) % 3], P[(pi + 2) % 3], Q[(qi + 1) % 3], Q[(qi + 2) % 3]);
}

bool
FanIsEmbeddedStar(const Vec3 & v, const Vec3 * ring, unsigned int k)
{
  constexpr unsigned int MaximumValence = 32;
  if (k < 3 || k > MaximumValence)
  {
    return false;
  }
  // det[N, a, b] = N . (a x b), decided by Orient3D's static filter: a and b are
  // rounded differences and N is exact.
  Vec3          spoke[MaximumValence];
  FilteredCross face[MaximumValence];
  for (unsigned int i = 0; i < k; ++i)
  {
    spoke[i] = ring[i] - v;
  }
  Vec3 N = MakeVec3(0.0, 0.0, 0.0);
  for (unsigned int i = 0; i < k; ++i)
  {
    face[i] = FilteredCross(spoke[i], spoke[(i + 1) % k]);
    N += face[i].cross;
  }
  // Every face turns counter-clockwise about N (so no face is degenerate or seen
  // edge-on, and each covers an angle below pi)...
  for (unsigned int i = 0; i < k; ++i)
  {
    if (face[i].Sign(N) != 1)
    {
      return false;
    }
  }
  // ... and the angles add up to 2 pi, not a multiple: the first spoke lies in no
  // closed angle of faces 2 .. k-2 (faces 1 and k-1 are next to it). Going around
  // twice would take the sweep across it.
  for (unsigned int i = 2; i + 1 < k; ++i)
  {
    if (FilteredCross(spoke[i], spoke[0]).Sign(N) != -1 && FilteredCross(spoke[0], spoke[i + 1]).Sign(N) != -1)
    {
      return false;
    }
  }
  return true;
}

bool
CertifyFan(const Vec3 * points, std::uint32_t v, const FanCorner * corners, std::size_t k, FanScratch & scratch)
{
  if (k == 0)
  {
    return false;
  }
  scratch.used.assign(k, 0);
  scratch.ring.clear();
  std::uint32_t at = corners[0].next;
  bool          closed = true;
  for (std::size_t step = 0; step < k && closed; ++step)
  {
    std::size_t e = 0;
    while (e < k && (scratch.used[e] || corners[e].next != at))
    {
      ++e;
    }
    closed = e < k && std::find(scratch.ring.begin(), scratch.ring.end(), at) == scratch.ring.end();
    if (closed)
    {
      scratch.used[e] = 1;
      scratch.ring.push_back(at);
      at = corners[e].last;
    }
  }
  if (!closed || at != scratch.ring.front())
  {
    return false;
  }
  scratch.ringPoints.resize(k);
  for (std::size_t i = 0; i < k; ++i)
  {
    scratch.ringPoints[i] = points[scratch.ring[i]];
  }
  return FanIsEmbeddedStar(points[v], scratch.ringPoints.data(), static_cast<unsigned int>(k));
}

} // namespace detail
} // namespace MeshExtraction
} // namespace itk
