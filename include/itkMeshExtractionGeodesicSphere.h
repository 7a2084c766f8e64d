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
#ifndef itkMeshExtractionGeodesicSphere_h
#define itkMeshExtractionGeodesicSphere_h

#include "itkMeshExtractionIndexedTriangleMesh.h"

#include <cmath>
#include <cstdint>
#include <map>
#include <random>
#include <utility>
#include <vector>

namespace itk
{
namespace MeshExtraction
{
/** \file
 * \brief Coarse spheres as initial meshes for scale-space edge refinement (thesis
 * section 4.3 starts its sphere test from such a mesh: 720 vertices, 1436 triangles,
 * mean radius 24.78, radius variance 0.471).
 * \ingroup MeshExtraction
 */

/** Icosahedron subdivided `subdivisions` times (10 * 4^s + 2 vertices, 20 * 4^s
 * triangles: 642 and 1280 for s = 3), its vertices projected onto the sphere
 * (center, radius); triangles counter-clockwise seen from outside. */
inline IndexedTriangleMesh
MakeGeodesicSphere(unsigned int subdivisions, const Vec3 & center, double radius)
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
  for (unsigned int level = 0; level < subdivisions; ++level)
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
  for (auto & p : m.points)
  {
    p = center + p * radius;
  }
  return m;
}

/** A geodesic sphere made irregular, like the initial mesh of thesis Table 4.1:
 * 0. `edgeFlips` random edges are flipped (each flip keeps every valence >= 4 and is
 *    made only where the two new triangles keep the orientation of the old ones), so
 *    that the valences are irregular as on a mesh from another extraction method;
 * 1. every vertex moves tangentially by a random vector of length up to
 *    `tangentialJitter` times the length of its shortest edge (the move is halved
 *    until no incident triangle turns by 90 degrees or more, so the mesh stays
 *    valid);
 * 2. every vertex gets the radius meanRadius + N(0, 1) noise, standardised so that
 *    the vertices' radii have exactly that mean and population variance
 *    `radiusVariance`.
 * The random numbers come from std::mt19937_64 with `seed` through Box-Muller, so
 * the mesh is the same on every platform. */
inline IndexedTriangleMesh
MakePerturbedGeodesicSphere(unsigned int  subdivisions,
                            const Vec3 &  center,
                            double        meanRadius,
                            double        radiusVariance,
                            double        tangentialJitter,
                            std::size_t   edgeFlips = 0,
                            std::uint64_t seed = 4)
{
  IndexedTriangleMesh m = MakeGeodesicSphere(subdivisions, MakeVec3(0.0, 0.0, 0.0), 1.0);
  const std::size_t   n = m.points.size();
  std::mt19937_64     random(seed);
  auto uniform = [&random]() { return static_cast<double>(random() >> 11) * (1.0 / 9007199254740992.0); };

  // Random edge flips. Directed edge (a, b) -> the triangle that runs it.
  {
    using Key = std::pair<std::uint32_t, std::uint32_t>;
    std::map<Key, std::uint32_t> owner;
    std::vector<unsigned int>    valence(n, 0);
    for (std::uint32_t f = 0; f < m.triangles.size(); ++f)
    {
      for (unsigned int k = 0; k < 3; ++k)
      {
        owner[Key(m.triangles[f][k], m.triangles[f][(k + 1) % 3])] = f;
        ++valence[m.triangles[f][k]];
      }
    }
    auto apex = [&m](std::uint32_t f, std::uint32_t a, std::uint32_t b) {
      for (const auto v : m.triangles[f])
      {
        if (v != a && v != b)
        {
          return v;
        }
      }
      return a;
    };
    std::size_t flips = 0;
    for (std::size_t attempt = 0; flips < edgeFlips && attempt < 100 * (edgeFlips + 1); ++attempt)
    {
      const auto          f1 = static_cast<std::uint32_t>(uniform() * static_cast<double>(m.triangles.size()));
      const unsigned int  k = static_cast<unsigned int>(uniform() * 3.0) % 3;
      const std::uint32_t a = m.triangles[f1][k];
      const std::uint32_t b = m.triangles[f1][(k + 1) % 3];
      const auto          other = owner.find(Key(b, a));
      if (other == owner.end())
      {
        continue;
      }
      const std::uint32_t f2 = other->second;
      const std::uint32_t c = apex(f1, a, b);
      const std::uint32_t d = apex(f2, b, a);
      if (c == d || owner.count(Key(c, d)) > 0 || owner.count(Key(d, c)) > 0 || valence[a] <= 4 || valence[b] <= 4)
      {
        continue;
      }
      // (a, b, c) and (b, a, d) become (a, d, c) and (d, b, c).
      const Vec3 n1 = TriangleNormal(m.points[a], m.points[b], m.points[c]);
      const Vec3 n2 = TriangleNormal(m.points[b], m.points[a], m.points[d]);
      const Vec3 m1 = TriangleNormal(m.points[a], m.points[d], m.points[c]);
      const Vec3 m2 = TriangleNormal(m.points[d], m.points[b], m.points[c]);
      if (!(Dot(n1, m1) > 0.0 && Dot(n1, m2) > 0.0 && Dot(n2, m1) > 0.0 && Dot(n2, m2) > 0.0))
      {
        continue;
      }
      for (const auto f : { f1, f2 })
      {
        for (unsigned int j = 0; j < 3; ++j)
        {
          owner.erase(Key(m.triangles[f][j], m.triangles[f][(j + 1) % 3]));
        }
      }
      m.triangles[f1] = { a, d, c };
      m.triangles[f2] = { d, b, c };
      for (const auto f : { f1, f2 })
      {
        for (unsigned int j = 0; j < 3; ++j)
        {
          owner[Key(m.triangles[f][j], m.triangles[f][(j + 1) % 3])] = f;
        }
      }
      --valence[a];
      --valence[b];
      ++valence[c];
      ++valence[d];
      ++flips;
    }
  }
  auto normal = [&uniform]() {
    const double u = 1.0 - uniform(); // (0, 1]
    const double v = uniform();
    return std::sqrt(-2.0 * std::log(u)) * std::cos(2.0 * itk::Math::pi * v);
  };

  // Incident triangles and shortest edges on the unit sphere.
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
    const double angle = 2.0 * itk::Math::pi * uniform();
    const double length = tangentialJitter * shortest[v] * std::sqrt(uniform());
    Vec3         move = (u * std::cos(angle) + w * std::sin(angle)) * length;
    for (unsigned int attempt = 0; attempt < 8; ++attempt, move *= 0.5)
    {
      Vec3 candidate = m.points[v] + move;
      candidate *= 1.0 / Norm(candidate);
      bool valid = true;
      for (const auto f : incident[v])
      {
        const auto & t = m.triangles[f];
        Vec3         now[3];
        Vec3         moved[3];
        for (unsigned int k = 0; k < 3; ++k)
        {
          now[k] = original[t[k]];
          moved[k] = t[k] == v ? candidate : m.points[t[k]];
        }
        valid =
          valid && Dot(TriangleNormal(now[0], now[1], now[2]), TriangleNormal(moved[0], moved[1], moved[2])) > 0.0;
      }
      if (valid)
      {
        m.points[v] = candidate;
        break;
      }
    }
  }
  std::vector<double> z(n);
  double              mean = 0.0;
  for (auto & x : z)
  {
    x = normal();
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
  return m;
}

} // namespace MeshExtraction
} // namespace itk

#endif
