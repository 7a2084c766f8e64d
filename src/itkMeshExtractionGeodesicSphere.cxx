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
#include "itkMeshExtractionGeodesicSphere.h"

#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <utility>

namespace itk
{
namespace MeshExtraction
{
namespace
{
/** The regular icosahedron on the unit sphere, counter-clockwise seen from outside. */
IndexedTriangleMesh
UnitIcosahedron()
{
  IndexedTriangleMesh m;
  const double        t = (1.0 + std::sqrt(5.0)) / 2.0;
  const double base[12][3] = { { -1, t, 0 },  { 1, t, 0 },  { -1, -t, 0 }, { 1, -t, 0 }, { 0, -1, t },  { 0, 1, t },
                               { 0, -1, -t }, { 0, 1, -t }, { t, 0, -1 },  { t, 0, 1 },  { -t, 0, -1 }, { -t, 0, 1 } };
  for (const auto & b : base)
  {
    const Vec3 v = MakeVec3(b[0], b[1], b[2]);
    m.points.push_back(v * (1.0 / Norm(v)));
  }
  m.triangles = { { 0, 11, 5 },  { 0, 5, 1 },  { 0, 1, 7 },  { 0, 7, 10 }, { 0, 10, 11 }, { 1, 5, 9 }, { 5, 11, 4 },
                  { 11, 10, 2 }, { 10, 7, 6 }, { 7, 1, 8 },  { 3, 9, 4 },  { 3, 4, 2 },   { 3, 2, 6 }, { 3, 6, 8 },
                  { 3, 8, 9 },   { 4, 9, 5 },  { 2, 4, 11 }, { 6, 2, 10 }, { 8, 6, 7 },   { 9, 8, 1 } };
  return m;
}

/** Every triangle of a mesh on the unit sphere split into four at its edges'
 * midpoints, projected onto the sphere (one new point per edge). */
void
SubdivideOnUnitSphere(IndexedTriangleMesh & m)
{
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> midpoints;
  auto                                                             midpoint = [&](std::uint32_t a, std::uint32_t b) {
    const auto key = std::make_pair(std::min(a, b), std::max(a, b));
    const auto found = midpoints.find(key);
    if (found != midpoints.end())
    {
      return found->second;
    }
    const Vec3 v = (m.points[a] + m.points[b]) * 0.5;
    m.points.push_back(v * (1.0 / Norm(v)));
    const auto index = static_cast<std::uint32_t>(m.points.size() - 1);
    midpoints.emplace(key, index);
    return index;
  };
  std::vector<TriangleIndices> next;
  next.reserve(4 * m.triangles.size());
  for (const auto & tri : m.triangles)
  {
    const std::uint32_t ab = midpoint(tri[0], tri[1]);
    const std::uint32_t bc = midpoint(tri[1], tri[2]);
    const std::uint32_t ca = midpoint(tri[2], tri[0]);
    next.push_back({ tri[0], ab, ca });
    next.push_back({ tri[1], bc, ab });
    next.push_back({ tri[2], ca, bc });
    next.push_back({ ab, bc, ca });
  }
  m.triangles.swap(next);
}

/** The random numbers of MakePerturbedGeodesicSphere: uniform on [0, 1) from the top
 * 53 bits of std::mt19937_64, normal by Box-Muller, the same on every platform. */
class SphereRandom
{
public:
  explicit SphereRandom(std::uint64_t seed)
      : m_Engine(seed)
  {}

  double
  Uniform()
  {
    return static_cast<double>(m_Engine() >> 11) * (1.0 / 9007199254740992.0);
  }

  double
  Normal()
  {
    const double u = 1.0 - this->Uniform(); // (0, 1]
    const double v = this->Uniform();
    return std::sqrt(-2.0 * std::log(u)) * std::cos(2.0 * itk::Math::pi * v);
  }

private:
  std::mt19937_64 m_Engine;
};

/** Random edge flips on a closed mesh: the directed edges and the triangles that run
 * them, and the valences, kept up to date. */
class RandomEdgeFlipper
{
public:
  explicit RandomEdgeFlipper(IndexedTriangleMesh & m)
      : m_Mesh(m)
      , m_Valence(m.points.size(), 0)
  {
    for (std::uint32_t f = 0; f < m.triangles.size(); ++f)
    {
      this->AddOwner(f);
      for (unsigned int k = 0; k < 3; ++k)
      {
        ++m_Valence[m.triangles[f][k]];
      }
    }
  }

  /** Flips up to `edgeFlips` random edges (at most 100 attempts per flip wanted). */
  void
  Flip(std::size_t edgeFlips, SphereRandom & random)
  {
    std::size_t flips = 0;
    for (std::size_t attempt = 0; flips < edgeFlips && attempt < 100 * (edgeFlips + 1); ++attempt)
    {
      const auto f1 = static_cast<std::uint32_t>(random.Uniform() * static_cast<double>(m_Mesh.triangles.size()));
      const unsigned int k = static_cast<unsigned int>(random.Uniform() * 3.0) % 3;
      flips += this->TryFlip(f1, k) ? 1 : 0;
    }
  }

private:
  using Key = std::pair<std::uint32_t, std::uint32_t>;

  /** Flips side k of triangle f1, (a, b), with the triangle across it: (a, b, c) and
   * (b, a, d) become (a, d, c) and (d, b, c), unless (c, d) is an edge already, a or b
   * would drop below valence 4, or a new triangle would turn against an old one. */
  bool
  TryFlip(std::uint32_t f1, unsigned int k)
  {
    auto &              m = m_Mesh;
    const std::uint32_t a = m.triangles[f1][k];
    const std::uint32_t b = m.triangles[f1][(k + 1) % 3];
    const auto          other = m_Owner.find(Key(b, a));
    if (other == m_Owner.end())
    {
      return false;
    }
    const std::uint32_t f2 = other->second;
    const std::uint32_t c = this->Apex(f1, a, b);
    const std::uint32_t d = this->Apex(f2, b, a);
    if (c == d || m_Owner.count(Key(c, d)) > 0 || m_Owner.count(Key(d, c)) > 0 || m_Valence[a] <= 4 ||
        m_Valence[b] <= 4)
    {
      return false;
    }
    const Vec3 n1 = TriangleNormal(m.points[a], m.points[b], m.points[c]);
    const Vec3 n2 = TriangleNormal(m.points[b], m.points[a], m.points[d]);
    const Vec3 m1 = TriangleNormal(m.points[a], m.points[d], m.points[c]);
    const Vec3 m2 = TriangleNormal(m.points[d], m.points[b], m.points[c]);
    if (!(Dot(n1, m1) > 0.0 && Dot(n1, m2) > 0.0 && Dot(n2, m1) > 0.0 && Dot(n2, m2) > 0.0))
    {
      return false;
    }
    this->RemoveOwner(f1);
    this->RemoveOwner(f2);
    m.triangles[f1] = { a, d, c };
    m.triangles[f2] = { d, b, c };
    this->AddOwner(f1);
    this->AddOwner(f2);
    --m_Valence[a];
    --m_Valence[b];
    ++m_Valence[c];
    ++m_Valence[d];
    return true;
  }

  /** The vertex of triangle f that is neither a nor b. */
  std::uint32_t
  Apex(std::uint32_t f, std::uint32_t a, std::uint32_t b) const
  {
    for (const auto v : m_Mesh.triangles[f])
    {
      if (v != a && v != b)
      {
        return v;
      }
    }
    return a;
  }

  void
  AddOwner(std::uint32_t f)
  {
    for (unsigned int j = 0; j < 3; ++j)
    {
      m_Owner[Key(m_Mesh.triangles[f][j], m_Mesh.triangles[f][(j + 1) % 3])] = f;
    }
  }

  void
  RemoveOwner(std::uint32_t f)
  {
    for (unsigned int j = 0; j < 3; ++j)
    {
      m_Owner.erase(Key(m_Mesh.triangles[f][j], m_Mesh.triangles[f][(j + 1) % 3]));
    }
  }

  IndexedTriangleMesh &        m_Mesh;
  std::map<Key, std::uint32_t> m_Owner; ///< directed edge (a, b) -> the triangle that runs it
  std::vector<unsigned int>    m_Valence;
};

/** Whether moving vertex v of `m` to `candidate` turns none of its triangles by 90
 * degrees or more against their orientation at `original` positions. */
bool
MoveKeepsOrientation(const IndexedTriangleMesh &        m,
                     const std::vector<Vec3> &          original,
                     const std::vector<std::uint32_t> & incident,
                     std::size_t                        v,
                     const Vec3 &                       candidate)
{
  bool valid = true;
  for (const auto f : incident)
  {
    const auto & t = m.triangles[f];
    Vec3         now[3];
    Vec3         moved[3];
    for (unsigned int k = 0; k < 3; ++k)
    {
      now[k] = original[t[k]];
      moved[k] = t[k] == v ? candidate : m.points[t[k]];
    }
    valid = valid && Dot(TriangleNormal(now[0], now[1], now[2]), TriangleNormal(moved[0], moved[1], moved[2])) > 0.0;
  }
  return valid;
}

/** Moves every vertex of a mesh on the unit sphere tangentially by a random vector of
 * length up to `tangentialJitter` times its shortest edge, back onto the sphere; a
 * move is halved (up to 8 times) until it keeps the orientation of the incident
 * triangles (MoveKeepsOrientation). */
void
JitterTangentially(IndexedTriangleMesh & m, double tangentialJitter, SphereRandom & random)
{
  const std::size_t                       n = m.points.size();
  std::vector<std::vector<std::uint32_t>> incident(n);
  std::vector<double>                     shortest(n, std::numeric_limits<double>::infinity());
  for (std::uint32_t f = 0; f < m.triangles.size(); ++f)
  {
    const auto & t = m.triangles[f];
    for (unsigned int k = 0; k < 3; ++k)
    {
      incident[t[k]].push_back(f);
      const double l = Norm(m.points[t[k]] - m.points[t[(k + 1) % 3]]);
      shortest[t[k]] = std::min(shortest[t[k]], l);
      shortest[t[(k + 1) % 3]] = std::min(shortest[t[(k + 1) % 3]], l);
    }
  }
  const std::vector<Vec3> original = m.points;
  for (std::size_t v = 0; v < n; ++v)
  {
    const Vec3 radial = m.points[v] * (1.0 / Norm(m.points[v]));
    Vec3       u = Cross(radial, std::abs(radial[0]) < 0.9 ? MakeVec3(1, 0, 0) : MakeVec3(0, 1, 0));
    u *= 1.0 / Norm(u);
    const Vec3   w = Cross(radial, u);
    const double angle = 2.0 * itk::Math::pi * random.Uniform();
    const double length = tangentialJitter * shortest[v] * std::sqrt(random.Uniform());
    Vec3         move = (u * std::cos(angle) + w * std::sin(angle)) * length;
    for (unsigned int attempt = 0; attempt < 8; ++attempt, move *= 0.5)
    {
      Vec3 candidate = m.points[v] + move;
      candidate *= 1.0 / Norm(candidate);
      if (MoveKeepsOrientation(m, original, incident[v], v, candidate))
      {
        m.points[v] = candidate;
        break;
      }
    }
  }
}

/** Gives every vertex of a mesh around the origin the radius meanRadius + N(0, 1)
 * noise, standardised so that the radii have exactly that mean and population
 * variance `radiusVariance`, and moves the mesh to `center`. */
void
SetRandomRadii(IndexedTriangleMesh & m,
               const Vec3 &          center,
               double                meanRadius,
               double                radiusVariance,
               SphereRandom &        random)
{
  const std::size_t   n = m.points.size();
  std::vector<double> z(n);
  double              mean = 0.0;
  for (auto & x : z)
  {
    x = random.Normal();
    mean += x;
  }
  mean /= static_cast<double>(n);
  double variance = 0.0;
  for (const double x : z)
  {
    variance += (x - mean) * (x - mean);
  }
  variance /= static_cast<double>(n);
  const double scale = variance > 0.0 ? std::sqrt(radiusVariance / variance) : 0.0;
  for (std::size_t v = 0; v < n; ++v)
  {
    const double r = meanRadius + (z[v] - mean) * scale;
    m.points[v] = center + m.points[v] * (r / Norm(m.points[v]));
  }
}
} // namespace

IndexedTriangleMesh
MakeGeodesicSphere(unsigned int subdivisions, const Vec3 & center, double radius)
{
  IndexedTriangleMesh m = UnitIcosahedron();
  for (unsigned int level = 0; level < subdivisions; ++level)
  {
    SubdivideOnUnitSphere(m);
  }
  for (auto & p : m.points)
  {
    p = center + p * radius;
  }
  return m;
}

IndexedTriangleMesh
MakePerturbedGeodesicSphere(unsigned int  subdivisions,
                            const Vec3 &  center,
                            double        meanRadius,
                            double        radiusVariance,
                            double        tangentialJitter,
                            std::size_t   edgeFlips,
                            std::uint64_t seed)
{
  IndexedTriangleMesh m = MakeGeodesicSphere(subdivisions, MakeVec3(0.0, 0.0, 0.0), 1.0);
  SphereRandom        random(seed);
  RandomEdgeFlipper(m).Flip(edgeFlips, random);
  JitterTangentially(m, tangentialJitter, random);
  SetRandomRadii(m, center, meanRadius, radiusVariance, random);
  return m;
}

} // namespace MeshExtraction
} // namespace itk
