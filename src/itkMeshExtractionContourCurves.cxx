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

#include <algorithm>
#include <cmath>
#include <sstream>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
namespace
{
/** sqrt of the physical distance between two continuous indices: the knot spacing of
 * the centripetal Catmull-Rom spline (kept away from zero). */
double
CentripetalKnotSpacing(const ContourGrid & grid, const Vec3 & a, const Vec3 & b)
{
  double d2 = 0.0;
  for (unsigned int i = 0; i < 3; ++i)
  {
    const double d = (b[i] - a[i]) * grid.spacing[i];
    d2 += d * d;
  }
  return std::max(std::sqrt(std::sqrt(d2)), 1e-6);
}

Vec3
Blend(double wa, const Vec3 & a, double wb, const Vec3 & b)
{
  return a * wa + b * wb;
}

/** The centripetal Catmull-Rom segment from p1 to p2 (Barry and Goldman's pyramid). */
Vec3
CatmullRom(const ContourGrid & grid, const Vec3 & p0, const Vec3 & p1, const Vec3 & p2, const Vec3 & p3, double t)
{
  const double t0 = 0.0;
  const double t1 = t0 + CentripetalKnotSpacing(grid, p0, p1);
  const double t2 = t1 + CentripetalKnotSpacing(grid, p1, p2);
  const double t3 = t2 + CentripetalKnotSpacing(grid, p2, p3);
  const double u = t1 + t * (t2 - t1);
  const Vec3   a1 = Blend((t1 - u) / (t1 - t0), p0, (u - t0) / (t1 - t0), p1);
  const Vec3   a2 = Blend((t2 - u) / (t2 - t1), p1, (u - t1) / (t2 - t1), p2);
  const Vec3   a3 = Blend((t3 - u) / (t3 - t2), p2, (u - t2) / (t3 - t2), p3);
  const Vec3   b1 = Blend((t2 - u) / (t2 - t0), a1, (u - t0) / (t2 - t0), a2);
  const Vec3   b2 = Blend((t3 - u) / (t3 - t1), a2, (u - t1) / (t3 - t1), a3);
  return Blend((t2 - u) / (t2 - t1), b1, (u - t1) / (t2 - t1), b2);
}

bool
AreFourNeighbours(const ContourVoxel & a, const ContourVoxel & b)
{
  return std::abs(a[0] - b[0]) + std::abs(a[1] - b[1]) + std::abs(a[2] - b[2]) == 1;
}

double
SquaredDistanceToCentre(const ContourVoxel & v, const Vec3 & x)
{
  double d2 = 0.0;
  for (unsigned int i = 0; i < 3; ++i)
  {
    const double d = static_cast<double>(v[i]) - x[i];
    d2 += d * d;
  }
  return d2;
}

/** Appends the voxels of the curve after v0 up to v1 (scan conversion by subdivision,
 * thesis section 5.2.2): stops where consecutive voxels are 4-neighbours, and where
 * the subdivision cannot separate them (the curve through a voxel corner) steps one
 * axis at a time towards v1 through the voxel nearest the curve. */
template <typename TEvaluate>
void
SubdivideSegment(TEvaluate &&                evaluate,
                 double                      t0,
                 const ContourVoxel &        v0,
                 double                      t1,
                 const ContourVoxel &        v1,
                 unsigned int                depth,
                 std::vector<ContourVoxel> & out)
{
  if (v0 == v1)
  {
    return;
  }
  if (AreFourNeighbours(v0, v1))
  {
    out.push_back(v1);
    return;
  }
  const double tm = 0.5 * (t0 + t1);
  const Vec3   xm = evaluate(tm);
  if (depth == 0)
  {
    ContourVoxel v = v0;
    while (v != v1)
    {
      ContourVoxel best = v;
      double       bestDistance = 0.0;
      for (unsigned int a = 0; a < 3; ++a)
      {
        if (v[a] == v1[a])
        {
          continue;
        }
        ContourVoxel w = v;
        w[a] += v1[a] > v[a] ? 1 : -1;
        const double d = SquaredDistanceToCentre(w, xm);
        if (best == v || d < bestDistance)
        {
          best = w;
          bestDistance = d;
        }
      }
      v = best;
      out.push_back(v);
    }
    return;
  }
  const ContourVoxel vm = VoxelOf(xm);
  SubdivideSegment(evaluate, t0, v0, tm, vm, depth - 1, out);
  SubdivideSegment(evaluate, tm, vm, t1, v1, depth - 1, out);
}

/** Removes back-and-forth visits A B A of a voxel B (the curve grazing a voxel's face)
 * around the closed path, except at a control point's voxel. */
void
RemoveGrazingVisits(std::vector<ContourVoxel> & path, const std::vector<ContourVoxel> & keep)
{
  auto kept = [&](const ContourVoxel & v) { return std::find(keep.begin(), keep.end(), v) != keep.end(); };
  std::vector<ContourVoxel> stack;
  for (const auto & v : path)
  {
    if (stack.size() >= 2 && stack[stack.size() - 2] == v && !kept(stack.back()))
    {
      stack.pop_back();
      continue;
    }
    if (!stack.empty() && stack.back() == v)
    {
      continue;
    }
    stack.push_back(v);
  }
  // The same around the start of the closed path.
  bool changed = true;
  while (changed && stack.size() >= 3)
  {
    changed = false;
    const std::size_t n = stack.size();
    if (stack[n - 1] == stack[0])
    {
      stack.pop_back();
      changed = true;
    }
    else if (stack[n - 1] == stack[1] && !kept(stack[0]))
    {
      stack.erase(stack.begin());
      stack.pop_back();
      changed = true;
    }
    else if (stack[n - 2] == stack[0] && !kept(stack[n - 1]))
    {
      stack.pop_back();
      stack.pop_back();
      changed = true;
    }
  }
  path.swap(stack);
}
} // namespace

Vec3
EvaluateContourSegment(const ContourNetwork & network, std::uint32_t c, std::size_t k, double t)
{
  const auto &      list = network.contours[c].points;
  const std::size_t n = list.size();
  const Vec3 &      p1 = network.points[list[k % n]].x;
  const Vec3 &      p2 = network.points[list[(k + 1) % n]].x;
  if (network.interpolation == ContourInterpolation::Linear)
  {
    return Blend(1.0 - t, p1, t, p2);
  }
  const Vec3 & p0 = network.points[list[(k + n - 1) % n]].x;
  const Vec3 & p3 = network.points[list[(k + 2) % n]].x;
  Vec3         x = CatmullRom(network.grid, p0, p1, p2, p3, t);
  // The contour's own coordinate stays its plane's, exactly.
  x[network.contours[c].axis] = static_cast<double>(network.contours[c].position);
  return x;
}

std::vector<Vec3>
SampleContour(const ContourNetwork & network, std::uint32_t c, unsigned int samplesPerSegment)
{
  const std::size_t  n = network.contours[c].points.size();
  const unsigned int m = std::max(1u, samplesPerSegment);
  std::vector<Vec3>  samples;
  samples.reserve(n * m);
  for (std::size_t k = 0; k < n; ++k)
  {
    for (unsigned int i = 0; i < m; ++i)
    {
      samples.push_back(EvaluateContourSegment(network, c, k, static_cast<double>(i) / m));
    }
  }
  return samples;
}

std::vector<Vec3>
ContourPlaneIntersections(const ContourNetwork & network, unsigned int axis, double position)
{
  constexpr unsigned int steps = 16;
  std::vector<Vec3>      result;
  for (std::uint32_t c = 0; c < network.contours.size(); ++c)
  {
    if (network.contours[c].axis == axis)
    {
      continue;
    }
    for (std::size_t k = 0; k < network.contours[c].points.size(); ++k)
    {
      Vec3 a = EvaluateContourSegment(network, c, k, 0.0);
      if (a[axis] == position)
      {
        result.push_back(a);
      }
      for (unsigned int i = 1; i <= steps; ++i)
      {
        const Vec3   b = EvaluateContourSegment(network, c, k, static_cast<double>(i) / steps);
        const double da = a[axis] - position;
        const double db = b[axis] - position;
        if (da * db < 0.0)
        {
          Vec3 x = a + (b - a) * (da / (da - db));
          x[axis] = position;
          result.push_back(x);
        }
        a = b;
      }
    }
  }
  return result;
}

std::vector<ContourVoxel>
ScanConvertContour(const ContourNetwork & network, std::uint32_t c)
{
  const auto &              list = network.contours[c].points;
  std::vector<ContourVoxel> keep;
  for (const auto p : list)
  {
    keep.push_back(VoxelOf(network.points[p].x));
  }
  std::vector<ContourVoxel> path;
  path.push_back(keep.front());
  for (std::size_t k = 0; k < list.size(); ++k)
  {
    auto evaluate = [&](double t) { return EvaluateContourSegment(network, c, k, t); };
    SubdivideSegment(evaluate, 0.0, keep[k], 1.0, keep[(k + 1) % list.size()], 40, path);
  }
  if (path.size() > 1 && path.back() == path.front())
  {
    path.pop_back();
  }
  RemoveGrazingVisits(path, keep);
  return path;
}

std::string
DescribeInvalidScanConversion(const ContourNetwork & network, std::uint32_t c, const std::vector<ContourVoxel> & voxels)
{
  std::ostringstream s;
  s << "the scan conversion of contour " << c;
  const std::size_t n = voxels.size();
  if (n < 4)
  {
    s << " has " << n << " voxels, fewer than 4";
    return s.str();
  }
  const Contour & contour = network.contours[c];
  for (std::size_t i = 0; i < n; ++i)
  {
    const ContourVoxel & v = voxels[i];
    if (v[contour.axis] != contour.position)
    {
      s << " leaves its plane";
      return s.str();
    }
    if (!AreFourNeighbours(v, voxels[(i + 1) % n]))
    {
      s << " is not 4-connected at voxel (" << v[0] << ", " << v[1] << ", " << v[2] << ")";
      return s.str();
    }
  }
  std::vector<ContourVoxel> sorted = voxels;
  std::sort(sorted.begin(), sorted.end());
  const auto twice = std::adjacent_find(sorted.begin(), sorted.end());
  if (twice != sorted.end())
  {
    s << " passes voxel (" << (*twice)[0] << ", " << (*twice)[1] << ", " << (*twice)[2]
      << ") twice: the contour comes back within a voxel of itself";
    return s.str();
  }
  for (const auto p : contour.points)
  {
    if (!std::binary_search(sorted.begin(), sorted.end(), VoxelOf(network.points[p].x)))
    {
      s << " misses the voxel of control point " << p;
      return s.str();
    }
  }
  return std::string();
}
} // namespace detail
} // namespace MeshExtraction
} // namespace itk
