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
#ifndef itkMeshExtractionScaleSpaceEdgeDetector_h
#define itkMeshExtractionScaleSpaceEdgeDetector_h

#include "MeshExtractionExport.h"
#include "itkMeshExtractionEnums.h"
#include "itkMeshExtractionGaussianScaleSpace.h"
#include "itkMeshExtractionIndexedTriangleMesh.h"
#include "itkMeshExtractionParallel.h"
#include "itkMeshExtractionQualityAnalysis.h"
#include "itkMeshExtractionQuadEdgeMeshVertexSmoother.h"
#include "itkMeshExtractionScaleSpaceEdgeDetectionResult.h"

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
namespace detail
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

/** The smallest scale used for `requested`: `requested` if > 0, else the voxel length
 * of thesis section 4.2.1, taken as the smallest spacing, the finest detail the image
 * resolves (on anisotropic voxels the largest spacing as the finest scale would
 * dislocate curved edges by sigma^2 times the curvature, that is by the square of
 * the spacings' ratio more). */
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

/** The most scales (blurred images) one edge detection may use: with its capture range
 * and scales per octave, a bound on the minimum scale. */
constexpr unsigned int MaximumNumberOfEdgeDetectionScales = 128;

/** What is wrong with the parameters of a step (empty if nothing):
 * ScaleSpaceEdgeDetector::CheckParameters. */
MeshExtraction_EXPORT std::string
                      DescribeInvalidEdgeDetectionParameters(const ScaleSpaceEdgeDetectionParameters & p);

/** The sum of the un-normalised normals of the triangles at every point: the
 * direction a vertex's line takes where the image has no gradient. */
MeshExtraction_EXPORT std::vector<Vec3>
                      VertexNormalSums(const IndexedTriangleMesh & mesh);

/** The centroid and the un-normalised normal of every triangle of `triangles` over
 * `points`: the starts and fallback directions of the inaccuracy's searches. */
MeshExtraction_EXPORT void
TriangleCentroidsAndNormals(const std::vector<Vec3> &            points,
                            const std::vector<TriangleIndices> & triangles,
                            std::vector<Vec3> &                  centroids,
                            std::vector<Vec3> &                  normals);

/** The guard of an edge-detection move (the checks of IsValidVertexMove()) on the
 * triangles at vertex v of `mesh` moved to `candidate`: no triangle turns by 90
 * degrees or more against its orientation now or at `startPositions`, none becomes
 * degenerate (q_area <= tolerance) or, if already degenerate, worse. */
MeshExtraction_EXPORT bool
IsValidEdgeDetectionMove(const IndexedTriangleMesh & mesh,
                         const MeshTopology &        topology,
                         const std::vector<Vec3> &   startPositions,
                         std::size_t                 v,
                         const Vec3 &                candidate,
                         double                      tolerance);


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
    return DescribeInvalidEdgeDetectionParameters(p);
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
    std::string problem = CheckImage(image);
    if (problem.empty())
    {
      problem = CheckMesh(mesh);
    }
    if (problem.empty())
    {
      problem = DescribeVerticesOutside(*mesh, *image);
    }
    return problem;
  }

  /** One step on `mesh`, in place; call CheckParameters and CheckInputs first: the
   * scale space over the vertices' box, the searches from the vertices, the moves
   * through the guard and the fold check, the new positions written, and the
   * inaccuracy searched from the triangle centroids. */
  ResultType
  Run(MeshType & mesh, const ImageType & image, const ParametersType & p)
  {
    const auto          start = std::chrono::steady_clock::now();
    ResultType          result;
    IndexedTriangleMesh indexed = MakeIndexedTriangleMesh(mesh);
    const MeshTopology  topology = BuildMeshTopology(indexed);
    result.numberOfVertices = indexed.points.size();
    // No move may take a surface past another component (see UndoFoldingMoves).
    const ComponentReference componentsAtStart =
      p.preventInversions ? MakeComponentReference(indexed, topology) : ComponentReference{};
    result.scales =
      ScaleSpaceScales(p.maximumDeviation, ResolveMinimumScale(image.GetSpacing(), p.minimumScale), p.scalesPerOctave);
    this->PrepareScaleSpace(indexed.points, image, p, result);

    // Search from every vertex.
    const std::vector<Vec3> normals = VertexNormalSums(indexed);
    std::vector<Vec3>       directions;
    std::vector<double>     offsets;
    Stopwatch               lap;
    result.normalFallbacks += this->Search(indexed.points, normals, p, directions, offsets);
    result.searchSeconds = lap.Lap();

    // Apply the moves, undo those that fold the surface, write the positions.
    const std::vector<Vec3> startPositions = indexed.points;
    ApplyMoves(indexed, topology, startPositions, directions, offsets, p, result);
    if (p.preventInversions)
    {
      result.undoneMoves =
        UndoFoldingMoves(indexed, topology, startPositions, p.degenerateQAreaTolerance, &componentsAtStart);
    }
    WritePositions(mesh, indexed, startPositions, result);
    result.applySeconds = lap.Lap();

    // The inaccuracy: the detector run from the triangle centroids of the result.
    if (p.computeInaccuracy && !indexed.triangles.empty())
    {
      this->MeasureInaccuracy(indexed, p, result);
      result.inaccuracySeconds = lap.Lap();
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
  /** Seconds since construction or the last Lap(). */
  class Stopwatch
  {
  public:
    double
    Lap()
    {
      const auto   now = std::chrono::steady_clock::now();
      const double s = std::chrono::duration<double>(now - m_Last).count();
      m_Last = now;
      return s;
    }

  private:
    std::chrono::steady_clock::time_point m_Last{ std::chrono::steady_clock::now() };
  };

  static Vec3
  Round(const Vec3 & x)
  {
    return RoundToCoordinateType<CoordinateType>(x);
  }

  /** A missing image, or one that is empty or not buffered. */
  static std::string
  CheckImage(const ImageType * image)
  {
    if (image == nullptr)
    {
      return "No input image: call SetInputImage() before Update()";
    }
    const auto region = image->GetLargestPossibleRegion();
    if (region.GetNumberOfPixels() == 0 || !image->GetBufferedRegion().IsInside(region) ||
        image->GetBufferPointer() == nullptr)
    {
      std::ostringstream s;
      s << "The input image is empty or not buffered (largest possible region " << region << ")";
      return s.str();
    }
    return std::string();
  }

  /** A missing mesh, one without points or triangles, or a face that is not a triangle. */
  static std::string
  CheckMesh(const MeshType * mesh)
  {
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
      std::ostringstream s;
      s << "The input mesh is empty: it has " << mesh->GetNumberOfPoints() << " points but no triangles";
      return s.str();
    }
    return std::string();
  }

  /** The vertices more than OutsideMargin voxels outside the image, counted and the
   * first one described (empty if none). The image's extent is the voxel centres
   * +- half a voxel; SurfaceNets closes objects that touch the border with nodes up
   * to a voxel beyond it, and the scale space is clamped at the image's faces. */
  static std::string
  DescribeVerticesOutside(const MeshType & mesh, const ImageType & image)
  {
    const auto                 region = image.GetLargestPossibleRegion();
    std::size_t                outside = 0;
    IdentifierType             firstId = 0;
    Vec3                       first(0.0);
    ContinuousIndex<double, 3> firstIndex;
    firstIndex.Fill(0.0);
    for (auto it = mesh.GetPoints()->Begin(); it != mesh.GetPoints()->End(); ++it)
    {
      typename ImageType::PointType p;
      for (unsigned int d = 0; d < 3; ++d)
      {
        p[d] = static_cast<double>(it.Value()[d]);
      }
      const auto ci = image.template TransformPhysicalPointToContinuousIndex<double>(p);
      bool       inside = true;
      for (unsigned int d = 0; d < 3; ++d)
      {
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
    std::ostringstream s;
    if (outside > 0)
    {
      s << outside << " of " << mesh.GetNumberOfPoints() << " mesh vertices lie outside the image, e.g. vertex "
        << firstId << " at physical point " << first << " (continuous index " << firstIndex << ", image region "
        << region.GetIndex() << " + " << region.GetSize()
        << "): the mesh must lie in the image (or within one voxel of its faces), in the same physical "
           "coordinates (origin, spacing, direction)";
    }
    return s.str();
  }

  /** Makes the scale space cover the vertices' box plus the capture range (rebuilt
   * only if needed), and records whether it was rebuilt and the time it took. */
  void
  PrepareScaleSpace(const std::vector<Vec3> & points,
                    const ImageType &         image,
                    const ParametersType &    p,
                    ResultType &              result)
  {
    const double capture = p.maximumDeviation;
    Vec3         lower(std::numeric_limits<double>::infinity());
    Vec3         upper(-std::numeric_limits<double>::infinity());
    for (const Vec3 & x : points)
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
  }

  /** The moves (directions[v] offsets[v]) applied one by one, in point order, each
   * rounded to the mesh's coordinate type; with the guard, a move is halved up to
   * maximumShortenings times until IsValidEdgeDetectionMove accepts it, else rejected. */
  static void
  ApplyMoves(IndexedTriangleMesh &       indexed,
             const MeshTopology &        topology,
             const std::vector<Vec3> &   startPositions,
             const std::vector<Vec3> &   directions,
             const std::vector<double> & offsets,
             const ParametersType &      p,
             ResultType &                result)
  {
    std::vector<Vec3> & positions = indexed.points;
    for (std::size_t v = 0; v < positions.size(); ++v)
    {
      const Vec3 displacement = directions[v] * offsets[v];
      if (!(SquaredNorm(displacement) > 0.0))
      {
        continue;
      }
      if (!p.preventInversions)
      {
        positions[v] = Round(positions[v] + displacement);
        continue;
      }
      double fraction = 1.0;
      bool   moved = false;
      for (unsigned int s = 0; s <= p.maximumShortenings; ++s, fraction *= 0.5)
      {
        const Vec3 candidate = Round(positions[v] + displacement * fraction);
        if (candidate == positions[v])
        {
          break;
        }
        if (IsValidEdgeDetectionMove(indexed, topology, startPositions, v, candidate, p.degenerateQAreaTolerance))
        {
          positions[v] = candidate;
          moved = true;
          result.shortenedMoves += s > 0 ? 1 : 0;
          break;
        }
      }
      result.rejectedMoves += moved ? 0 : 1;
    }
  }

  /** Writes the positions that changed into `mesh`, counting the moved vertices and
   * measuring the mean (over all vertices) and largest displacement. */
  static void
  WritePositions(MeshType &                  mesh,
                 const IndexedTriangleMesh & indexed,
                 const std::vector<Vec3> &   startPositions,
                 ResultType &                result)
  {
    const std::vector<Vec3> & positions = indexed.points;
    const std::size_t         n = positions.size();
    auto *                    meshPoints = mesh.GetPoints();
    double                    sumDisplacement = 0.0;
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
  }

  /** The mean and largest distance from the triangle centroids to the edges the
   * detector finds from them (thesis section 4.2.3). */
  void
  MeasureInaccuracy(const IndexedTriangleMesh & indexed, const ParametersType & p, ResultType & result) const
  {
    std::vector<Vec3> centroids;
    std::vector<Vec3> faceNormals;
    TriangleCentroidsAndNormals(indexed.points, indexed.triangles, centroids, faceNormals);
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
  }

  ScaleSpaceType m_ScaleSpace;
};

} // namespace detail
} // namespace MeshExtraction
} // namespace itk

#endif
