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
#include "itkMeshExtractionContourNetwork.h"
#include "itkMeshExtractionQualityAnalysis.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
namespace
{
constexpr double TwoPi = 6.283185307179586;

/** A ring of points of a face's disk: mesh point identifiers and their angles. */
struct FaceRing
{
  std::vector<std::uint32_t> ids;
  std::vector<double>        angles;
};

/** The pieces of every contour segment: the identifiers of the points inside it (its
 * ends are the control points), in order from the smaller control point identifier to
 * the larger. */
std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::uint32_t>>
CutSegments(const ContourNetwork & network, double h, IndexedTriangleMesh & mesh)
{
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::uint32_t>> segments;
  for (std::uint32_t c = 0; c < network.contours.size(); ++c)
  {
    const auto &      list = network.contours[c].points;
    const std::size_t n = list.size();
    for (std::size_t k = 0; k < n; ++k)
    {
      // The length of the curve, from a few points along it.
      constexpr unsigned int probes = 8;
      double                 length = 0.0;
      Vec3                   last = GridToPhysical(network.grid, network.points[list[k]].x);
      for (unsigned int i = 1; i <= probes; ++i)
      {
        const Vec3 x =
          GridToPhysical(network.grid, EvaluateContourSegment(network, c, k, static_cast<double>(i) / probes));
        length += (x - last).GetNorm();
        last = x;
      }
      const auto                 pieces = static_cast<unsigned int>(std::max(1.0, std::ceil(length / h)));
      std::vector<std::uint32_t> ids;
      for (unsigned int i = 1; i < pieces; ++i)
      {
        ids.push_back(static_cast<std::uint32_t>(mesh.points.size()));
        mesh.points.push_back(
          GridToPhysical(network.grid, EvaluateContourSegment(network, c, k, static_cast<double>(i) / pieces)));
      }
      const std::uint32_t u = list[k];
      const std::uint32_t v = list[(k + 1) % n];
      if (v < u)
      {
        std::reverse(ids.begin(), ids.end());
      }
      segments[{ std::min(u, v), std::max(u, v) }] = std::move(ids);
    }
  }
  return segments;
}

/** The boundary of a face: its corners and the pieces of its segments, in its order;
 * `corner[i]` is the index in the boundary of the face's i-th corner. */
std::vector<std::uint32_t>
FaceBoundary(const std::vector<std::uint32_t> &                                                    face,
             const std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::uint32_t>> & segments,
             std::vector<std::size_t> &                                                            corner)
{
  std::vector<std::uint32_t> boundary;
  corner.clear();
  for (std::size_t i = 0; i < face.size(); ++i)
  {
    const std::uint32_t u = face[i];
    const std::uint32_t v = face[(i + 1) % face.size()];
    corner.push_back(boundary.size());
    boundary.push_back(u);
    const auto & ids = segments.at({ std::min(u, v), std::max(u, v) });
    if (u < v)
    {
      boundary.insert(boundary.end(), ids.begin(), ids.end());
    }
    else
    {
      boundary.insert(boundary.end(), ids.rbegin(), ids.rend());
    }
  }
  return boundary;
}

/** Mean value coordinates (Floater) of the point (x, y) inside the convex polygon
 * `polygon`, applied to the boundary points: a smooth interpolation of the boundary
 * that reproduces it exactly where the boundary is an affine image of the polygon. */
Vec3
MeanValuePoint(const std::vector<std::array<double, 2>> & polygon,
               const std::vector<Vec3> &                  boundary,
               double                                     x,
               double                                     y)
{
  const std::size_t   m = polygon.size();
  std::vector<double> tanHalf(m);
  std::vector<double> length(m);
  for (std::size_t i = 0; i < m; ++i)
  {
    const double ux = polygon[i][0] - x;
    const double uy = polygon[i][1] - y;
    const double vx = polygon[(i + 1) % m][0] - x;
    const double vy = polygon[(i + 1) % m][1] - y;
    const double lu = std::sqrt(ux * ux + uy * uy);
    const double lv = std::sqrt(vx * vx + vy * vy);
    length[i] = lu;
    tanHalf[i] = std::abs(ux * vy - uy * vx) / (lu * lv + ux * vx + uy * vy);
  }
  Vec3   sum(0.0);
  double total = 0.0;
  for (std::size_t i = 0; i < m; ++i)
  {
    const double w = (tanHalf[(i + m - 1) % m] + tanHalf[i]) / length[i];
    sum += boundary[i] * w;
    total += w;
  }
  return sum / total;
}

/** Triangles between two rings around the same centre, counter-clockwise, walking
 * both by angle. */
void
ZipRings(const FaceRing & outer, const FaceRing & inner, std::vector<TriangleIndices> & triangles)
{
  const std::size_t no = outer.ids.size();
  const std::size_t ni = inner.ids.size();
  std::size_t       i = 0;
  std::size_t       j = 0;
  while (i < no || j < ni)
  {
    const double nextOuter = i + 1 < no ? outer.angles[i + 1] : TwoPi + outer.angles[0];
    const double nextInner = j + 1 < ni ? inner.angles[j + 1] : TwoPi + inner.angles[0];
    if (j >= ni || (i < no && nextOuter <= nextInner))
    {
      triangles.push_back({ { outer.ids[i % no], outer.ids[(i + 1) % no], inner.ids[j % ni] } });
      ++i;
    }
    else
    {
      triangles.push_back({ { outer.ids[i % no], inner.ids[(j + 1) % ni], inner.ids[j % ni] } });
      ++j;
    }
  }
}

/** Area of a closed polygon of points, fanned from its centroid. */
double
PolygonArea(const std::vector<Vec3> & points)
{
  Vec3 centre(0.0);
  for (const auto & p : points)
  {
    centre += p;
  }
  centre /= static_cast<double>(points.size());
  double area = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    area += TriangleArea(centre, points[i], points[(i + 1) % points.size()]);
  }
  return area;
}

/** The face's parameter polygon: its n corners at those of a regular n-gon inscribed in
 * the unit circle, the boundary points between two corners at their fraction of the
 * side's length (so a planar polygon's boundary is an affine image of it, side by side). */
std::vector<std::array<double, 2>>
ParameterPolygon(const std::vector<Vec3> & boundary, const std::vector<std::size_t> & corner)
{
  const std::size_t                  m = boundary.size();
  const std::size_t                  n = corner.size();
  std::vector<std::array<double, 2>> polygon(m);
  for (std::size_t side = 0; side < n; ++side)
  {
    const std::size_t   begin = corner[side];
    const std::size_t   end = side + 1 < n ? corner[side + 1] : m;
    const double        a0 = TwoPi * static_cast<double>(side) / static_cast<double>(n);
    const double        a1 = TwoPi * static_cast<double>(side + 1) / static_cast<double>(n);
    std::vector<double> along(end - begin + 1, 0.0);
    for (std::size_t i = begin + 1; i <= end; ++i)
    {
      along[i - begin] = along[i - 1 - begin] + (boundary[i % m] - boundary[i - 1]).GetNorm();
    }
    for (std::size_t i = begin; i < end; ++i)
    {
      const double s = along.back() > 0.0 ? along[i - begin] / along.back() : 0.0;
      polygon[i] = { { (1.0 - s) * std::cos(a0) + s * std::cos(a1), (1.0 - s) * std::sin(a0) + s * std::sin(a1) } };
    }
  }
  return polygon;
}

/** Fills a face (its boundary counter-clockwise from outside): concentric copies of
 * its parameter polygon shrunk towards the centre, about h apart, each with points
 * about h apart placed by mean value coordinates, a centre point, and the rings zipped
 * into triangles. */
void
FillFace(const std::vector<std::uint32_t> & boundaryIds,
         const std::vector<std::size_t> &   corner,
         double                             h,
         IndexedTriangleMesh &              mesh)
{
  const std::size_t m = boundaryIds.size();
  std::vector<Vec3> boundary(m);
  for (std::size_t i = 0; i < m; ++i)
  {
    boundary[i] = mesh.points[boundaryIds[i]];
  }
  const std::vector<std::array<double, 2>> polygon = ParameterPolygon(boundary, corner);
  FaceRing                                 ring{ boundaryIds, std::vector<double>(m, 0.0) };
  for (std::size_t i = 0; i < m; ++i)
  {
    ring.angles[i] = std::atan2(polygon[i][1], polygon[i][0]);
    ring.angles[i] += ring.angles[i] < 0.0 ? TwoPi : 0.0;
  }
  const auto rings =
    static_cast<std::size_t>(std::max(1.0, std::round(std::sqrt(PolygonArea(boundary) / 3.14159265358979) / h)));
  for (std::size_t k = 1; k < rings; ++k)
  {
    const double r = 1.0 - static_cast<double>(k) / static_cast<double>(rings);
    const auto   count = static_cast<std::size_t>(std::max(3.0, std::round(static_cast<double>(m) * r)));
    FaceRing     inner;
    for (std::size_t j = 0; j < count; ++j)
    {
      // Evenly along the shrunk polygon's perimeter, starting half a step on at odd rings.
      const double t = (static_cast<double>(j) + 0.5 * static_cast<double>(k % 2)) / static_cast<double>(count);
      const double sides = t * static_cast<double>(corner.size());
      const auto   side = static_cast<std::size_t>(std::floor(sides)) % corner.size();
      const double s = sides - std::floor(sides);
      const double a0 = TwoPi * static_cast<double>(side) / static_cast<double>(corner.size());
      const double a1 = TwoPi * static_cast<double>(side + 1) / static_cast<double>(corner.size());
      const double x = r * ((1.0 - s) * std::cos(a0) + s * std::cos(a1));
      const double y = r * ((1.0 - s) * std::sin(a0) + s * std::sin(a1));
      double       angle = std::atan2(y, x);
      angle += angle < 0.0 ? TwoPi : 0.0;
      inner.ids.push_back(static_cast<std::uint32_t>(mesh.points.size()));
      inner.angles.push_back(angle);
      mesh.points.push_back(MeanValuePoint(polygon, boundary, x, y));
    }
    ZipRings(ring, inner, mesh.triangles);
    ring = std::move(inner);
  }
  const auto centre = static_cast<std::uint32_t>(mesh.points.size());
  mesh.points.push_back(MeanValuePoint(polygon, boundary, 0.0, 0.0));
  for (std::size_t i = 0; i < ring.ids.size(); ++i)
  {
    mesh.triangles.push_back({ { ring.ids[i], ring.ids[(i + 1) % ring.ids.size()], centre } });
  }
}

/** The vertex neighbours of a triangle mesh (compressed rows, sorted, unique). */
void
VertexNeighbours(const IndexedTriangleMesh &  mesh,
                 std::vector<std::uint32_t> & offsets,
                 std::vector<std::uint32_t> & neighbours)
{
  std::vector<std::vector<std::uint32_t>> lists(mesh.points.size());
  for (const auto & t : mesh.triangles)
  {
    for (unsigned int k = 0; k < 3; ++k)
    {
      lists[t[k]].push_back(t[(k + 1) % 3]);
      lists[t[k]].push_back(t[(k + 2) % 3]);
    }
  }
  offsets.assign(1, 0);
  neighbours.clear();
  for (auto & list : lists)
  {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
    neighbours.insert(neighbours.end(), list.begin(), list.end());
    offsets.push_back(static_cast<std::uint32_t>(neighbours.size()));
  }
}

/** out = L x, the uniform graph Laplacian: (mean of the neighbours) - x. */
void
ApplyLaplacian(const std::vector<std::uint32_t> & offsets,
               const std::vector<std::uint32_t> & neighbours,
               const std::vector<Vec3> &          x,
               std::vector<Vec3> &                out)
{
  for (std::size_t v = 0; v + 1 < offsets.size(); ++v)
  {
    Vec3 sum(0.0);
    for (std::uint32_t k = offsets[v]; k < offsets[v + 1]; ++k)
    {
      sum += x[neighbours[k]];
    }
    out[v] = sum / static_cast<double>(offsets[v + 1] - offsets[v]) - x[v];
  }
}

/** Fairs the points from `first` on, the others fixed: the least squares solution of
 * the uniform Laplacian L x = 0 at every vertex (the discrete thin plate, smooth across
 * the contours), by conjugate gradients on the normal equations. A patch between
 * contours then curves as the contours around it do instead of sagging. */
void
FairInterior(IndexedTriangleMesh & mesh, std::size_t first)
{
  const std::size_t n = mesh.points.size();
  if (first >= n)
  {
    return;
  }
  std::vector<std::uint32_t> offsets;
  std::vector<std::uint32_t> neighbours;
  VertexNeighbours(mesh, offsets, neighbours);
  // L is not symmetric with uniform weights; A = L^T L restricted to the free points.
  std::vector<Vec3> lx(n);
  auto              normalProduct = [&](const std::vector<Vec3> & x, std::vector<Vec3> & out) {
    ApplyLaplacian(offsets, neighbours, x, lx);
    // out = L^T lx: vertex v gets -lx[v] plus lx[u] / deg(u) for each neighbour u.
    std::fill(out.begin(), out.end(), Vec3(0.0));
    for (std::size_t u = 0; u < n; ++u)
    {
      out[u] -= lx[u];
      const double w = 1.0 / static_cast<double>(offsets[u + 1] - offsets[u]);
      for (std::uint32_t k = offsets[u]; k < offsets[u + 1]; ++k)
      {
        out[neighbours[k]] += lx[u] * w;
      }
    }
  };
  // r = -A x over the free points (the residual of A x = 0 with the fixed points in x).
  std::vector<Vec3> r(n, Vec3(0.0));
  normalProduct(mesh.points, r);
  for (std::size_t v = 0; v < n; ++v)
  {
    r[v] = v < first ? Vec3(0.0) : -r[v];
  }
  std::vector<Vec3> d = r;
  std::vector<Vec3> ad(n);
  auto              dot = [&](const std::vector<Vec3> & a, const std::vector<Vec3> & b) {
    double s = 0.0;
    for (std::size_t v = first; v < n; ++v)
    {
      s += Dot(a[v], b[v]);
    }
    return s;
  };
  double            rr = dot(r, r);
  const double      stop = 1e-20 * std::max(1.0, rr);
  std::vector<Vec3> dFree(n, Vec3(0.0));
  for (unsigned int iteration = 0; iteration < 1000 && rr > stop; ++iteration)
  {
    for (std::size_t v = first; v < n; ++v)
    {
      dFree[v] = d[v];
    }
    normalProduct(dFree, ad);
    const double dad = dot(d, ad);
    if (!(dad > 0.0))
    {
      break;
    }
    const double alpha = rr / dad;
    for (std::size_t v = first; v < n; ++v)
    {
      mesh.points[v] += d[v] * alpha;
      r[v] -= ad[v] * alpha;
    }
    const double next = dot(r, r);
    for (std::size_t v = first; v < n; ++v)
    {
      d[v] = r[v] + d[v] * (next / rr);
    }
    rr = next;
  }
}

double
Determinant(const std::array<double, 9> & d)
{
  return d[0] * (d[4] * d[8] - d[5] * d[7]) - d[1] * (d[3] * d[8] - d[5] * d[6]) + d[2] * (d[3] * d[7] - d[4] * d[6]);
}

/** The mesh of the faces filled one by one (the patches meet the contours but are
 * not yet faired), in physical coordinates; `curvePoints` receives the number of
 * points on the contour curves (the control points and the pieces of the segments). */
IndexedTriangleMesh
FilledFaces(const ContourNetwork &                          network,
            const std::vector<std::vector<std::uint32_t>> & faces,
            double                                          h,
            std::size_t &                                   curvePoints)
{
  IndexedTriangleMesh mesh;
  for (const auto & p : network.points)
  {
    mesh.points.push_back(GridToPhysical(network.grid, p.x));
  }
  const auto segments = CutSegments(network, h, mesh);
  curvePoints = mesh.points.size();
  std::vector<std::size_t> corner;
  for (const auto & face : faces)
  {
    const std::vector<std::uint32_t> boundary = FaceBoundary(face, segments, corner);
    FillFace(boundary, corner, h, mesh);
  }
  // A direction matrix that mirrors turns counter-clockwise into clockwise.
  if (Determinant(network.grid.direction) < 0.0)
  {
    for (auto & t : mesh.triangles)
    {
      std::swap(t[1], t[2]);
    }
  }
  mesh.pointIds.resize(mesh.points.size());
  for (std::size_t i = 0; i < mesh.points.size(); ++i)
  {
    mesh.pointIds[i] = i;
  }
  mesh.cellIds.resize(mesh.triangles.size());
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i)
  {
    mesh.cellIds[i] = i;
  }
  return mesh;
}

bool
IsValidClosedSurface(const IndexedTriangleMesh & mesh)
{
  return AnalyzeTriangleMesh(mesh, TriangleMeshQualityOptions()).IsValidClosedSurface();
}
} // namespace

IndexedTriangleMesh
BuildContourSurface(const ContourNetwork & network, const ContourSurfaceParameters & parameters)
{
  const auto faces = ContourFaces(network);
  if (faces.size() != network.points.size() + 2)
  {
    return IndexedTriangleMesh();
  }
  const double smallest = std::min({ network.grid.spacing[0], network.grid.spacing[1], network.grid.spacing[2] });
  const double h = parameters.targetEdgeLength > 0.0 ? parameters.targetEdgeLength : 1.5 * smallest;
  std::size_t  curvePoints = 0;
  IndexedTriangleMesh mesh = FilledFaces(network, faces, h, curvePoints);
  // Straight contours keep their planar faces; curved ones get faired patches, unless
  // fairing folds the surface somewhere (a sharp indentation), where the unfaired
  // patches stay.
  if (parameters.fairInterior && network.interpolation == ContourInterpolation::CatmullRom)
  {
    IndexedTriangleMesh faired = mesh;
    FairInterior(faired, curvePoints);
    if (IsValidClosedSurface(faired))
    {
      return faired;
    }
  }
  return IsValidClosedSurface(mesh) ? mesh : IndexedTriangleMesh();
}

std::array<double, 2>
SurfaceAreaAndVolume(const IndexedTriangleMesh & mesh)
{
  double area = 0.0;
  double sixVolume = 0.0;
  if (mesh.points.empty())
  {
    return { { 0.0, 0.0 } };
  }
  const Vec3 & o = mesh.points[0];
  for (const auto & t : mesh.triangles)
  {
    const Vec3 & a = mesh.points[t[0]];
    const Vec3 & b = mesh.points[t[1]];
    const Vec3 & c = mesh.points[t[2]];
    area += TriangleArea(a, b, c);
    sixVolume += Dot(a - o, Cross(b - o, c - o));
  }
  return { { area, sixVolume / 6.0 } };
}
} // namespace detail
} // namespace MeshExtraction
} // namespace itk
