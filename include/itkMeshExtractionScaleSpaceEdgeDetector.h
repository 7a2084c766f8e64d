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
#ifndef itkMeshExtractionScaleSpaceEdgeDetector_h
#define itkMeshExtractionScaleSpaceEdgeDetector_h

#include "itkMeshExtractionEnums.h"
#include "itkMeshExtractionGaussianScaleSpace.h"
#include "itkMeshExtractionIndexedTriangleMesh.h"
#include "itkMeshExtractionParallel.h"
#include "itkMeshExtractionQualityAnalysis.h"
#include "itkMeshExtractionQuadEdgeMeshVertexSmoother.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace itk
{
namespace MeshExtraction
{
/** The parameters of one scale-space edge-detection step (thesis section 4.2.1);
 * distances in millimetres. \ingroup MeshExtraction */
struct ScaleSpaceEdgeDetectionParameters
{
  /** The largest distance between the mesh and the object's edge: the capture range
   * (each vertex searches [-d, d] along its line) and the largest scale. Required, > 0. */
  double maximumDeviation{ 0.0 };
  /** The smallest scale; 0 (default) = the voxel length, the smallest voxel spacing. */
  double minimumScale{ 0.0 };
  /** n of sigma_i = 2^(i/n), scales per doubling, >= 1. */
  unsigned int                             scalesPerOctave{ 4 };
  MeshExtractionEnums::EdgeSearchDirection searchDirection{ MeshExtractionEnums::EdgeSearchDirection::ImageGradient };
  /** Refine the finest scale's maximum to the vertex of a parabola (beyond the thesis,
   * whose five samples leave an uncertainty of 0.25 sigma_min). */
  bool subSampleRefinement{ true };
  /** Halve, and at last reject, a move that would turn an incident triangle over or
   * make it degenerate. */
  bool         preventInversions{ true };
  unsigned int maximumShortenings{ 5 };
  double       degenerateQAreaTolerance{ 1e-4 };
  /** Also search from every triangle centroid after the step: the inaccuracy of
   * thesis section 4.2.3. */
  bool         computeInaccuracy{ true };
  unsigned int numberOfWorkUnits{ 0 };
};

/** What one step did. \ingroup MeshExtraction */
struct ScaleSpaceEdgeDetectionResult
{
  std::vector<double> scales; ///< coarse to fine, mm
  std::size_t         numberOfVertices{ 0 };
  std::size_t         movedVertices{ 0 };      ///< vertices whose position changed
  std::size_t         shortenedMoves{ 0 };     ///< moves the guard shortened
  std::size_t         rejectedMoves{ 0 };      ///< moves the guard cancelled
  std::size_t         undoneMoves{ 0 };        ///< moves undone because they folded the surface
  std::size_t         normalFallbacks{ 0 };    ///< searches along the normal for want of a gradient
  double              meanDisplacement{ 0.0 }; ///< mm, over all vertices
  double              maximumDisplacement{ 0.0 };
  /** Mean and largest distance from the triangle centroids to the edge the detector
   * finds from them (NaN when not computed). */
  double inaccuracy{ std::numeric_limits<double>::quiet_NaN() };
  double maximumInaccuracy{ std::numeric_limits<double>::quiet_NaN() };
  bool   scaleSpaceBuilt{ false }; ///< the scale space was (re)computed for this step
  double scaleSpaceSeconds{ 0.0 }; ///< time of that computation
  double searchSeconds{ 0.0 };     ///< searches from the vertices
  double applySeconds{ 0.0 };      ///< the guarded moves and the fold check
  double inaccuracySeconds{ 0.0 }; ///< searches from the centroids
  double seconds{ 0.0 };           ///< time of the whole step
};

/** The smallest scale used for `requested`: `requested` if > 0, else the voxel length
 * of thesis section 4.2.1, taken as the smallest spacing, the finest detail the image
 * resolves (on 1 x 1 x 2.5 mm voxels the largest spacing as the finest scale would
 * dislocate curved edges by sigma^2 times the curvature: 0.4 mm instead of 0.1 mm on
 * the ellipsoid of the tests). */
template <typename TSpacing>
double
ResolveMinimumScale(const TSpacing & spacing, double requested)
{
  if (requested > 0.0)
  {
    return requested;
  }
  return std::min(
    { static_cast<double>(spacing[0]), static_cast<double>(spacing[1]), static_cast<double>(spacing[2]) });
}

/** \class ScaleSpaceEdgeDetector
 * \brief One scale-space edge-detection step on a triangle QuadEdgeMesh, in place:
 * the engine of ScaleSpaceEdgeDetectionMeshFilter and
 * ScaleSpaceEdgeMeshRefinementFilter (thesis sections 4.2.1 and 4.2.3).
 *
 * For every vertex, a line through it along the image gradient at the largest scale
 * (or the vertex normal); the coarse-to-fine five-sample search of
 * SearchEdgeAlongLine() over the scales ScaleSpaceScales(d, minimum scale, n) within
 * the capture range [-d, d]; the vertex moves to the edge found. The searches run on
 * ITK's multithreader, one result per vertex, and the moves are then applied one by
 * one in point order, each through the no-inversion guard of the smoothing filters
 * (against the neighbours' current positions and the orientation at the start of the
 * step), so the result does not depend on the number of threads. The gradient
 * magnitudes come from a GaussianGradientMagnitudeScaleSpace kept between steps.
 *
 * \ingroup MeshExtraction
 */
template <typename TMesh, typename TImage>
class ScaleSpaceEdgeDetector
{
public:
  using MeshType = TMesh;
  using ImageType = TImage;
  using ScaleSpaceType = GaussianGradientMagnitudeScaleSpace<ImageType>;
  using CoordinateType = typename MeshType::PointType::ValueType;
  using ParametersType = ScaleSpaceEdgeDetectionParameters;
  using ResultType = ScaleSpaceEdgeDetectionResult;

  /** What is wrong with the parameters (empty if nothing). */
  static std::string
  CheckParameters(const ParametersType & p)
  {
    std::ostringstream s;
    if (!(p.maximumDeviation > 0.0) || !std::isfinite(p.maximumDeviation))
    {
      s << "MaximumDeviation must be a positive, finite distance in mm (the capture range of the edge detector), got "
        << p.maximumDeviation;
    }
    else if (!(p.minimumScale >= 0.0) || !std::isfinite(p.minimumScale))
    {
      s << "MinimumScale must be >= 0 mm (0: the voxel length), got " << p.minimumScale;
    }
    else if (p.scalesPerOctave == 0)
    {
      s << "NumberOfScalesPerOctave must be >= 1, got 0";
    }
    else if (!(p.degenerateQAreaTolerance >= 0.0 && p.degenerateQAreaTolerance < 1.0))
    {
      s << "DegenerateQAreaTolerance must be in [0, 1), got " << p.degenerateQAreaTolerance;
    }
    else if (p.searchDirection != MeshExtractionEnums::EdgeSearchDirection::ImageGradient &&
             p.searchDirection != MeshExtractionEnums::EdgeSearchDirection::VertexNormal)
    {
      s << "Unknown SearchDirection " << static_cast<int>(p.searchDirection);
    }
    return s.str();
  }

  /** How far, in voxels, a vertex may lie beyond the image's faces: SurfaceNets closes
   * an object that touches the image border with nodes up to a voxel outside. */
  static constexpr double OutsideMargin = 1.0;

  /** What is wrong with the inputs (empty if nothing): a missing image or one that is
   * not buffered, an empty mesh, a mesh without triangles, a face that is not a
   * triangle, or a vertex more than OutsideMargin voxels outside the image. */
  static std::string
  CheckInputs(const MeshType * mesh, const ImageType * image)
  {
    std::ostringstream s;
    if (image == nullptr)
    {
      return "No input image: call SetInputImage() before Update()";
    }
    const auto region = image->GetLargestPossibleRegion();
    if (region.GetNumberOfPixels() == 0 || !image->GetBufferedRegion().IsInside(region) ||
        image->GetBufferPointer() == nullptr)
    {
      s << "The input image is empty or not buffered (largest possible region " << region << ")";
      return s.str();
    }
    if (mesh == nullptr)
    {
      return "No input mesh: call SetInput() before Update()";
    }
    if (mesh->GetPoints() == nullptr || mesh->GetNumberOfPoints() == 0)
    {
      return "The input mesh is empty: it has no points";
    }
    const std::string nonTriangle = QuadEdgeMeshVertexSmoother<MeshType>::DescribeNonTriangleFace(*mesh);
    if (!nonTriangle.empty())
    {
      return nonTriangle;
    }
    std::size_t triangles = 0;
    if (mesh->GetCells() != nullptr)
    {
      for (auto it = mesh->GetCells()->Begin(); it != mesh->GetCells()->End(); ++it)
      {
        triangles += it.Value() != nullptr && it.Value()->GetNumberOfPoints() == 3 ? 1 : 0;
      }
    }
    if (triangles == 0)
    {
      s << "The input mesh is empty: it has " << mesh->GetNumberOfPoints() << " points but no triangles";
      return s.str();
    }
    std::size_t                outside = 0;
    IdentifierType             firstId = 0;
    Vec3                       first(0.0);
    ContinuousIndex<double, 3> firstIndex;
    firstIndex.Fill(0.0);
    for (auto it = mesh->GetPoints()->Begin(); it != mesh->GetPoints()->End(); ++it)
    {
      typename ImageType::PointType p;
      for (unsigned int d = 0; d < 3; ++d)
      {
        p[d] = static_cast<double>(it.Value()[d]);
      }
      const auto ci = image->template TransformPhysicalPointToContinuousIndex<double>(p);
      bool       inside = true;
      for (unsigned int d = 0; d < 3; ++d)
      {
        // The image's extent (voxel centres +- half a voxel) and one voxel beyond it,
        // where SurfaceNets closes objects that touch the border (nodes up to a
        // voxel outside); the scale space is clamped at the image's faces.
        const double lo = static_cast<double>(region.GetIndex(d)) - 0.5 - OutsideMargin;
        const double hi = lo + static_cast<double>(region.GetSize(d)) + 2.0 * OutsideMargin;
        inside = inside && ci[d] >= lo && ci[d] <= hi;
      }
      if (!inside)
      {
        if (outside == 0)
        {
          firstId = it.Index();
          first = ToVec3(it.Value());
          firstIndex = ci;
        }
        ++outside;
      }
    }
    if (outside > 0)
    {
      s << outside << " of " << mesh->GetNumberOfPoints() << " mesh vertices lie outside the image, e.g. vertex "
        << firstId << " at physical point " << first << " (continuous index " << firstIndex << ", image region "
        << region.GetIndex() << " + " << region.GetSize()
        << "): the mesh must lie in the image (or within one voxel of its faces), in the same physical "
           "coordinates (origin, spacing, direction)";
    }
    return s.str();
  }

  /** One step on `mesh`, in place; call CheckParameters and CheckInputs first. */
  ResultType
  Run(MeshType & mesh, const ImageType & image, const ParametersType & p)
  {
    const auto          start = std::chrono::steady_clock::now();
    ResultType          result;
    IndexedTriangleMesh indexed = MakeIndexedTriangleMesh(mesh);
    const MeshTopology  topology = BuildMeshTopology(indexed);
    const std::size_t   n = indexed.points.size();
    result.numberOfVertices = n;
    // No move may take a surface past another component (see UndoFoldingMoves).
    const ComponentReference componentsAtStart =
      p.preventInversions ? MakeComponentReference(indexed, topology) : ComponentReference{};
    const double capture = p.maximumDeviation;
    result.scales =
      ScaleSpaceScales(capture, ResolveMinimumScale(image.GetSpacing(), p.minimumScale), p.scalesPerOctave);

    // The scale space covers the vertices' box plus the capture range.
    Vec3 lower(std::numeric_limits<double>::infinity());
    Vec3 upper(-std::numeric_limits<double>::infinity());
    for (const Vec3 & x : indexed.points)
    {
      typename ImageType::PointType q;
      for (unsigned int d = 0; d < 3; ++d)
      {
        q[d] = x[d];
      }
      const auto ci = image.template TransformPhysicalPointToContinuousIndex<double>(q);
      for (unsigned int d = 0; d < 3; ++d)
      {
        lower[d] = std::min(lower[d], ci[d] - capture / image.GetSpacing()[d]);
        upper[d] = std::max(upper[d], ci[d] + capture / image.GetSpacing()[d]);
      }
    }
    result.scaleSpaceBuilt = m_ScaleSpace.Prepare(&image, result.scales, lower, upper, p.numberOfWorkUnits);
    result.scaleSpaceSeconds = result.scaleSpaceBuilt ? m_ScaleSpace.GetBuildSeconds() : 0.0;

    // Search from every vertex.
    std::vector<Vec3> normals(n, Vec3(0.0));
    for (const auto & t : indexed.triangles)
    {
      const Vec3 normal = TriangleNormal(indexed.points[t[0]], indexed.points[t[1]], indexed.points[t[2]]);
      for (const auto v : t)
      {
        normals[v] += normal;
      }
    }
    std::vector<Vec3>   directions;
    std::vector<double> offsets;
    auto                lap = std::chrono::steady_clock::now();
    auto                seconds = [&lap]() {
      const auto   now = std::chrono::steady_clock::now();
      const double s = std::chrono::duration<double>(now - lap).count();
      lap = now;
      return s;
    };
    seconds();
    result.normalFallbacks += this->Search(indexed.points, normals, p, directions, offsets);
    result.searchSeconds = seconds();

    // Apply the moves one by one, in point order, through the guard.
    const std::vector<Vec3> startPositions = indexed.points;
    std::vector<Vec3> &     positions = indexed.points;
    for (std::size_t v = 0; v < n; ++v)
    {
      const Vec3 displacement = directions[v] * offsets[v];
      if (!(SquaredNorm(displacement) > 0.0))
      {
        continue;
      }
      if (p.preventInversions)
      {
        double fraction = 1.0;
        bool   moved = false;
        for (unsigned int s = 0; s <= p.maximumShortenings; ++s, fraction *= 0.5)
        {
          const Vec3 candidate = Round(positions[v] + displacement * fraction);
          if (candidate == positions[v])
          {
            break;
          }
          if (IsValidMove(indexed, topology, startPositions, v, candidate, p.degenerateQAreaTolerance))
          {
            positions[v] = candidate;
            moved = true;
            result.shortenedMoves += s > 0 ? 1 : 0;
            break;
          }
        }
        result.rejectedMoves += moved ? 0 : 1;
      }
      else
      {
        positions[v] = Round(positions[v] + displacement);
      }
    }
    if (p.preventInversions)
    {
      result.undoneMoves =
        UndoFoldingMoves(indexed, topology, startPositions, p.degenerateQAreaTolerance, &componentsAtStart);
    }

    // Write the new positions.
    auto * meshPoints = mesh.GetPoints();
    double sumDisplacement = 0.0;
    for (std::size_t v = 0; v < n; ++v)
    {
      if (positions[v] == startPositions[v])
      {
        continue;
      }
      auto & point = meshPoints->ElementAt(static_cast<typename MeshType::PointIdentifier>(indexed.pointIds[v]));
      for (unsigned int d = 0; d < 3; ++d)
      {
        point[d] = static_cast<CoordinateType>(positions[v][d]);
      }
      ++result.movedVertices;
      const double l = Norm(positions[v] - startPositions[v]);
      sumDisplacement += l;
      result.maximumDisplacement = std::max(result.maximumDisplacement, l);
    }
    result.meanDisplacement = n > 0 ? sumDisplacement / static_cast<double>(n) : 0.0;
    meshPoints->Modified();
    mesh.Modified();
    result.applySeconds = seconds();

    // The inaccuracy: the detector run from the triangle centroids of the result.
    if (p.computeInaccuracy && !indexed.triangles.empty())
    {
      std::vector<Vec3> centroids;
      std::vector<Vec3> faceNormals;
      centroids.reserve(indexed.triangles.size());
      faceNormals.reserve(indexed.triangles.size());
      for (const auto & t : indexed.triangles)
      {
        centroids.push_back(TriangleCentroid(positions[t[0]], positions[t[1]], positions[t[2]]));
        faceNormals.push_back(TriangleNormal(positions[t[0]], positions[t[1]], positions[t[2]]));
      }
      std::vector<Vec3>   centroidDirections;
      std::vector<double> centroidOffsets;
      result.normalFallbacks += this->Search(centroids, faceNormals, p, centroidDirections, centroidOffsets);
      double sum = 0.0;
      double maximum = 0.0;
      for (const double o : centroidOffsets)
      {
        sum += std::abs(o);
        maximum = std::max(maximum, std::abs(o));
      }
      result.inaccuracy = sum / static_cast<double>(centroidOffsets.size());
      result.maximumInaccuracy = maximum;
      result.inaccuracySeconds = seconds();
    }
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
  }

  /** The edge offsets along the search lines from `points` (scale space prepared):
   * the unit direction of every line (the gradient at the largest scale, or the
   * normalised `normals[i]`, which also stand in where the gradient vanishes; a zero
   * direction where neither exists) and the offset of the edge along it. Returns the
   * number of lines that fell back to the normal. */
  std::size_t
  Search(const std::vector<Vec3> & points,
         const std::vector<Vec3> & normals,
         const ParametersType &    p,
         std::vector<Vec3> &       directions,
         std::vector<double> &     offsets) const
  {
    const std::size_t n = points.size();
    directions.assign(n, Vec3(0.0));
    offsets.assign(n, 0.0);
    std::vector<std::uint8_t> fallback(n, 0);
    const double              capture = p.maximumDeviation;
    const double              noGradient = 1e-6 * m_ScaleSpace.GetMaximumTopGradientMagnitude();
    const bool useGradient = p.searchDirection == MeshExtractionEnums::EdgeSearchDirection::ImageGradient;
    const std::vector<double> & scales = m_ScaleSpace.GetScales();
    ParallelForBlocks(
      n,
      256,
      [&](std::size_t begin, std::size_t end, std::size_t) {
        for (std::size_t i = begin; i < end; ++i)
        {
          const Vec3 origin = m_ScaleSpace.ToRegionIndex(points[i]);
          Vec3       d(0.0);
          if (useGradient)
          {
            const Vec3   g = m_ScaleSpace.GradientAt(origin);
            const double l = Norm(g);
            if (l > noGradient && std::isfinite(l))
            {
              d = g * (1.0 / l);
            }
          }
          if (!(SquaredNorm(d) > 0.0))
          {
            const double l = Norm(normals[i]);
            if (l > 0.0 && std::isfinite(l))
            {
              d = normals[i] * (1.0 / l);
              fallback[i] = useGradient ? 1 : 0;
            }
          }
          directions[i] = d;
          if (!(SquaredNorm(d) > 0.0))
          {
            continue;
          }
          const Vec3 step = m_ScaleSpace.ToRegionIndexDirection(d);
          offsets[i] = SearchEdgeAlongLine(
            scales,
            capture,
            [&](std::size_t k, double t) { return m_ScaleSpace.GradientMagnitude(k, origin + step * t); },
            p.subSampleRefinement);
        }
      },
      p.numberOfWorkUnits);
    std::size_t count = 0;
    for (const auto f : fallback)
    {
      count += f;
    }
    return count;
  }

  const ScaleSpaceType &
  GetScaleSpace() const
  {
    return m_ScaleSpace;
  }
  /** Frees the scale space (the next step recomputes it). */
  void
  ReleaseScaleSpace()
  {
    m_ScaleSpace.Clear();
  }

private:
  static Vec3
  Round(const Vec3 & x)
  {
    return RoundToCoordinateType<CoordinateType>(x);
  }

  /** The checks of IsValidVertexMove() on the incident triangles of vertex v moved to
   * `candidate`: no triangle turns by 90 degrees or more against its orientation now
   * or at the start of the step, none becomes degenerate (or, if already degenerate,
   * worse). */
  static bool
  IsValidMove(const IndexedTriangleMesh & mesh,
              const MeshTopology &        topology,
              const std::vector<Vec3> &   startPositions,
              std::size_t                 v,
              const Vec3 &                candidate,
              double                      tolerance)
  {
    const auto & x = mesh.points;
    for (std::uint32_t k = topology.vertexTriangleOffsets[v]; k < topology.vertexTriangleOffsets[v + 1]; ++k)
    {
      const auto & t = mesh.triangles[topology.vertexTriangles[k]];
      Vec3         now[3];
      Vec3         moved[3];
      Vec3         then[3];
      for (unsigned int c = 0; c < 3; ++c)
      {
        now[c] = x[t[c]];
        moved[c] = t[c] == v ? candidate : x[t[c]];
        then[c] = startPositions[t[c]];
      }
      const Vec3   oldNormal = TriangleNormal(now[0], now[1], now[2]);
      const Vec3   newNormal = TriangleNormal(moved[0], moved[1], moved[2]);
      const double oldQ = TriangleQArea(now[0], now[1], now[2]);
      const double newQ = TriangleQArea(moved[0], moved[1], moved[2]);
      if (oldQ > 0.0 && !(Dot(oldNormal, newNormal) > 0.0))
      {
        return false;
      }
      if (oldQ > tolerance ? !(newQ > tolerance) : !(newQ >= oldQ))
      {
        return false;
      }
      if (TriangleQArea(then[0], then[1], then[2]) > 0.0 &&
          !(Dot(TriangleNormal(then[0], then[1], then[2]), newNormal) > 0.0))
      {
        return false;
      }
    }
    return true;
  }

  ScaleSpaceType m_ScaleSpace;
};

} // namespace MeshExtraction
} // namespace itk

#endif
