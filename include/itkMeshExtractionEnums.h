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
#ifndef itkMeshExtractionEnums_h
#define itkMeshExtractionEnums_h

#include "MeshExtractionExport.h"
#include <cstdint>
#include <iosfwd>

namespace itk
{
/** \class MeshExtractionEnums
 * \brief The enumerations of the MeshExtraction module, each printable with operator<<.
 * \ingroup MeshExtraction
 */
class MeshExtractionEnums
{
public:
  /** How ImplicitSurfaceImageSource renders a surface into voxels. */
  enum class PhantomImage : std::uint8_t
  {
    /** Signed Euclidean distance to the surface (negative inside), times DistanceScale. */
    DistanceMap = 0,
    /** InsideValue where the signed distance is <= 0, OutsideValue elsewhere. */
    BinaryMask,
    /** A step edge blurred by a Gaussian of standard deviation EdgeWidth:
     * Outside + (Inside - Outside) * Phi(-d / EdgeWidth), plus optional noise. */
    BlurredStep
  };

  /** The weights w_j of the Laplacian smoothing operator
   * S(v) = v + sum_j w_j (v_j - v) / sum_j w_j (thesis eq. 2.5-2.6, section 2.2.4). */
  enum class SmoothingWeights : std::uint8_t
  {
    /** w_j = 1: the average of the linked neighbours (standard Laplacian). */
    Uniform = 0,
    /** w_j = 1 / |v_j - v|. */
    InverseEdgeLength,
    /** The area-weighted average of the centroids of the incident triangles. */
    Area,
    /** w_j = cot(alpha_j) + cot(beta_j) (Desbrun), clamped at 0. */
    Cotangent,
    /** The average of the projections of v onto the bisectors of the 1-ring
     * polygon's angles (thesis Figure 2.16). */
    AngleBisector
  };

  /** When the new positions of a smoothing step take effect (thesis section 4.5.1). */
  enum class SmoothingUpdate : std::uint8_t
  {
    /** Every new position is computed from the mesh as it was at the start of the step. */
    Batch = 0,
    /** Vertices move one by one, in increasing point identifier order, each seeing
     * the moves made before it. */
    Immediate
  };

  /** Restriction of a smoothing move (thesis sections 4.2.2 and 4.5.1). */
  enum class MovementConstraint : std::uint8_t
  {
    /** The move goes to the smoothing target (times the relaxation factor). */
    None = 0,
    /** Centroid smoothing S_C = 1/3 v + 2/3 S(v). */
    Centroid,
    /** Safe smoothing: the move is clipped to the distance to the nearest neighbour
     * (thesis Figure 4.8). */
    Safe
  };

  /** When an edge is swapped (thesis sections 2.2.6 and 4.2.2). */
  enum class EdgeSwapCriterion : std::uint8_t
  {
    /** Lower relaxation index E_b = sum (d_i - 6)^2 over the four quad corners (eq. 2.16). */
    Regularity = 0,
    /** The angles opposite the edge sum to more than pi, i.e. the fourth vertex lies in
     * the circumcircle of the other three (thesis Figure 2.18). */
    Delaunay,
    /** The other diagonal of the quad is shorter. */
    ShortestEdge
  };

  /** The line along which scale-space edge detection searches for the edge from a
   * vertex (thesis section 4.2.1). */
  enum class EdgeSearchDirection : std::uint8_t
  {
    /** The image gradient at the vertex, a Gaussian derivative at the largest scale
     * (the thesis' choice); the vertex normal where the gradient vanishes. */
    ImageGradient = 0,
    /** The area-weighted vertex normal of the mesh. */
    VertexNormal
  };

  /** The operations of the scale-space refinement protocol (thesis section 4.2.4,
   * the rows of Table 4.1). */
  enum class RefinementOperation : std::uint8_t
  {
    /** The initial mesh ("Org"). */
    Initial = 0,
    /** A scale-space edge-detection step ("ED"). */
    EdgeDetection,
    /** Regularity edge swapping ("ES"). */
    EdgeSwap,
    /** One centroid smoothing step ("S"). */
    Smoothing
  };

  /** How a point finds its counterpart on another mesh (thesis section 7.3.1). */
  enum class Correspondence : std::uint8_t
  {
    /** The closest vertex. */
    PointToPoint = 0,
    /** The closest point on the triangles (barycentric interpolation of their corners). */
    PointToSurface
  };

  /** The distension that ThreeLandmarkIncrementalTransformInitializer adds to the
   * rigid incremental match (thesis section 6.2.2: "distention can be described by
   * scaling along these axes"). */
  enum class LandmarkDistension : std::uint8_t
  {
    /** Rigid: translation of A, rotation of B about A, rotation of C about AB. */
    None = 0,
    /** One scale factor, |A'B'| / |AB|, so that B lands on its counterpart
     * (a Similarity3DTransform or an AffineTransform). */
    Isotropic,
    /** A scale along AB (B lands on its counterpart) and one along the perpendicular
     * from AB through C (C's distance to the axis matches); none across the plane ABC
     * (an AffineTransform). */
    AlongAxes
  };

  /** How SurfaceMeshFileWriter encodes a file. */
  enum class MeshFileEncoding : std::uint8_t
  {
    /** The format's usual one: ASCII for VTK legacy, OBJ and OFF; binary for VTP, PLY
     * and STL. */
    Default = 0,
    ASCII,
    /** Not for OBJ and OFF, which are text formats. */
    Binary
  };

  /** The VTK legacy file version SurfaceMeshFileWriter writes. */
  enum class VTKLegacyVersion : std::uint8_t
  {
    /** POLYGONS with a count before each cell: read by every VTK and by ITK's mesh IO. */
    V4_2 = 0,
    /** OFFSETS and CONNECTIVITY arrays: VTK 9's default. */
    V5_1
  };
};

MeshExtraction_EXPORT std::ostream &
                      operator<<(std::ostream & out, MeshExtractionEnums::PhantomImage value);
MeshExtraction_EXPORT std::ostream &
                      operator<<(std::ostream & out, MeshExtractionEnums::SmoothingWeights value);
MeshExtraction_EXPORT std::ostream &
                      operator<<(std::ostream & out, MeshExtractionEnums::SmoothingUpdate value);
MeshExtraction_EXPORT std::ostream &
                      operator<<(std::ostream & out, MeshExtractionEnums::MovementConstraint value);
MeshExtraction_EXPORT std::ostream &
                      operator<<(std::ostream & out, MeshExtractionEnums::EdgeSwapCriterion value);
MeshExtraction_EXPORT std::ostream &
                      operator<<(std::ostream & out, MeshExtractionEnums::EdgeSearchDirection value);
MeshExtraction_EXPORT std::ostream &
                      operator<<(std::ostream & out, MeshExtractionEnums::RefinementOperation value);
MeshExtraction_EXPORT std::ostream &
                      operator<<(std::ostream & out, MeshExtractionEnums::LandmarkDistension value);
MeshExtraction_EXPORT std::ostream &
                      operator<<(std::ostream & out, MeshExtractionEnums::Correspondence value);
MeshExtraction_EXPORT std::ostream &
                      operator<<(std::ostream & out, MeshExtractionEnums::MeshFileEncoding value);
MeshExtraction_EXPORT std::ostream &
                      operator<<(std::ostream & out, MeshExtractionEnums::VTKLegacyVersion value);

} // namespace itk

#endif
