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
#ifndef itkMeshExtractionContourNetwork_h
#define itkMeshExtractionContourNetwork_h

#include "MeshExtractionExport.h"
#include "itkMeshExtractionIndexedTriangleMesh.h"
#include "itkMeshExtractionTriangleGeometry.h"
#include "itkOrthogonalContourModelEnums.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
/** \file
 * \brief The data and the algorithms of itk::OrthogonalContourModel (thesis chapter 5):
 * a network of planar contours in the three orthogonal planes of a voxel grid, joined
 * at control points.
 *
 * Everything here works in the continuous index space of the grid (voxel units, a
 * contour plane at a whole index); GridToPhysical maps to millimetres at the end.
 *
 * The network's topology and its rules are those of the control polygon (straight
 * segments between control points); the interpolation (linear or centripetal
 * Catmull-Rom) shapes the curves between the control points for the scan conversion,
 * the surface and the measures.
 *
 * \ingroup MeshExtraction
 */

using ContourInterpolation = OrthogonalContourModelEnums::Interpolation;

/** The voxel grid of a model: the image's size, spacing, origin and direction
 * (row-major, direction[3 * i + j] = D(i, j)). */
struct ContourGrid
{
  std::array<std::int64_t, 3> size{ { 1, 1, 1 } };
  std::array<double, 3>       spacing{ { 1.0, 1.0, 1.0 } };
  std::array<double, 3>       origin{ { 0.0, 0.0, 0.0 } };
  std::array<double, 9>       direction{ { 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0 } };
};

/** origin + D (spacing .* index). */
MeshExtraction_EXPORT Vec3
GridToPhysical(const ContourGrid & grid, const Vec3 & index);

/** The inverse of GridToPhysical (D is orthonormal). */
MeshExtraction_EXPORT Vec3
PhysicalToGrid(const ContourGrid & grid, const Vec3 & physical);

/** What is wrong with a grid (empty if nothing): a size below 1, a spacing that is not
 * positive and finite, a non-finite origin, a direction that is not orthonormal. */
MeshExtraction_EXPORT std::string
                      DescribeInvalidGrid(const ContourGrid & grid);

/** A control point: its position (continuous index; the coordinates along the axes of
 * its two contours are their planes' positions, the third, along its line, is free)
 * and its two contours, the one whose plane has the smaller axis first. */
struct ContourControlPoint
{
  Vec3                         x;
  std::array<std::uint32_t, 2> contours{ { 0, 0 } };
};

/** A closed planar contour: the plane index[axis] = position and its control points
 * in order around it. */
struct Contour
{
  unsigned int               axis{ 0 };
  std::int64_t               position{ 0 };
  std::vector<std::uint32_t> points;
};

/** The whole model. Identifiers are indices into `points` and `contours`; an operation
 * that adds or removes contours renumbers both, keeping the order of what stays. */
struct ContourNetwork
{
  ContourGrid                      grid;
  ContourInterpolation             interpolation{ ContourInterpolation::CatmullRom };
  std::vector<ContourControlPoint> points;
  std::vector<Contour>             contours;
};

/** A voxel: whole indices. */
using ContourVoxel = std::array<std::int64_t, 3>;

/** The voxel holding a continuous index (round half up). */
MeshExtraction_EXPORT ContourVoxel
VoxelOf(const Vec3 & x);

/** The axis of the line along which control point p moves: the one that is neither of
 * its contours' axes. */
MeshExtraction_EXPORT unsigned int
LineAxis(const ContourNetwork & network, std::uint32_t p);

// ------------------------------------------------------------------------------------
// Structure: where each point sits in its contours, its lines, the planes in use.
// ------------------------------------------------------------------------------------

/** The place of every control point in its two contours; BuildContourAdjacency fills it. */
struct ContourAdjacency
{
  std::vector<std::array<std::uint32_t, 2>> slot; ///< index of point p in the list of contours[s]

  /** The neighbour of p before (step -1) or after (step +1) it on its contour s. */
  std::uint32_t
  Neighbour(const ContourNetwork & network, std::uint32_t p, unsigned int s, int step) const;
  /** The four neighbours: before and after on contour 0, before and after on contour 1. */
  std::array<std::uint32_t, 4>
  Neighbours(const ContourNetwork & network, std::uint32_t p) const;
};

/** Fills `adjacency`; returns what is wrong with the membership of the points in the
 * contours (empty if nothing): a point on a contour that it does not name, a point
 * twice on one contour or on no contour, two contours of one axis. */
MeshExtraction_EXPORT std::string
                      BuildContourAdjacency(const ContourNetwork & network, ContourAdjacency & adjacency);

/** The lines that hold control points (the intersection lines of two planes in use),
 * each the list of its points sorted by their coordinate along the line, and the rank
 * of every point on its line. */
struct ContourLines
{
  std::vector<std::vector<std::uint32_t>> lines;
  std::vector<std::uint32_t>              lineOf;
  std::vector<std::uint32_t>              rank;
};

MeshExtraction_EXPORT ContourLines
BuildContourLines(const ContourNetwork & network);

/** The positions of the planes that hold contours, per axis, sorted and unique. */
using OccupiedContourPlanes = std::array<std::vector<std::int64_t>, 3>;

MeshExtraction_EXPORT OccupiedContourPlanes
OccupiedPlanes(const ContourNetwork & network);

MeshExtraction_EXPORT bool
IsOccupied(const OccupiedContourPlanes & planes, unsigned int axis, double position);

/** The four neighbours of every control point in counter-clockwise order seen from
 * outside the surface. Outside is read from the point's rank on its line: a line
 * enters the object at its first control point, leaves at the second, and so on. */
MeshExtraction_EXPORT std::vector<std::array<std::uint32_t, 4>>
ContourRotations(const ContourNetwork & network, const ContourAdjacency & adjacency, const ContourLines & lines);

/** The faces of the network (the polygons enclosed by contour segments), each the
 * list of its corners counter-clockwise seen from outside, traced from the rotations:
 * the face left of the directed segment u -> v continues at v with the neighbour that
 * precedes u in v's counter-clockwise order. */
MeshExtraction_EXPORT std::vector<std::vector<std::uint32_t>>
                      TraceContourFaces(const std::vector<std::array<std::uint32_t, 4>> & rotations);

/** Faces of the network in one call (adjacency, lines, rotations, faces); an empty
 * list if the membership is broken. */
MeshExtraction_EXPORT std::vector<std::vector<std::uint32_t>>
                      ContourFaces(const ContourNetwork & network);

// ------------------------------------------------------------------------------------
// The rules (thesis sections 5.2.2-5.2.5), checked one by one.
// ------------------------------------------------------------------------------------

/** What rule of the model the network breaks (empty if none), in this order:
 * 1. at least one contour per axis, each in a plane of the grid with at least four
 *    control points, no point twice;
 * 2. every control point on exactly two contours of different axes, at their planes,
 *    its coordinate along its line finite, in the grid and not in a plane in use;
 * 3. at every control point each contour crosses the other's plane: its two
 *    neighbours lie strictly on either side;
 * 4. no segment crosses a plane in use between its control points (every intersection
 *    of contours is a control point);
 * 5. the control points on one line lie in different voxels (none passes another,
 *    Fig. 5.4), and so do the control points of one contour;
 * 6. the contours of a plane are simple polygons that do not meet;
 * 7. the faces traced from the rotations close a sphere (V - E + F = 2) facing outward;
 * 8. the scan conversion of every contour is a closed 4-connected path through its
 *    control points' voxels with one point per voxel, and contours in one plane share
 *    no voxel. */
MeshExtraction_EXPORT std::string
                      CheckContourNetwork(const ContourNetwork & network);

// ------------------------------------------------------------------------------------
// Operations. Each works on the network it is given and returns why it refused (empty
// on success); on refusal the network is unchanged.
// ------------------------------------------------------------------------------------

/** The three-contour template (Fig. 5.3a): the planes through `center` (whole indices)
 * and six control points at center +/- radii[a] along each axis a. Returns the problem
 * (a plane or point outside the grid, a radius below one voxel) or an empty string. */
MeshExtraction_EXPORT std::string
                      MakeTemplateNetwork(const ContourGrid &                 grid,
                                          const std::array<std::int64_t, 3> & center,
                                          const std::array<double, 3> &       radii,
                                          ContourInterpolation                interpolation,
                                          ContourNetwork &                    network);

/** The interval of coordinates along its line that control point p may take: the grid,
 * and short of the voxels of its neighbours on the line (Fig. 5.4). */
MeshExtraction_EXPORT std::array<double, 2>
                      ControlPointRange(const ContourNetwork & network, std::uint32_t p);

/** Moves control point p along its line to `coordinate` (Figs. 5.4, 5.8, 5.9). Passing
 * a plane in use makes a new contour there around p when all four neighbours are on
 * p's side of it (an indentation or a protrusion), takes away the four-point contour
 * around p when all four are in it (the reverse), and is refused otherwise (a
 * neighbour on a contour of that plane: add a contour between them first). */
MeshExtraction_EXPORT std::string
                      MoveContourControlPoint(ContourNetwork & network, std::uint32_t p, double coordinate);

/** Adds the contours of the plane index[axis] = position (Figs. 5.5-5.7): the plane
 * must be free of contours and control points and cut the model in at least four
 * points; the crossings are linked through the faces they cut into one or more loops
 * (one contour, or concentric or disjoint ones). */
MeshExtraction_EXPORT std::string
                      AddContourPlane(ContourNetwork & network, unsigned int axis, std::int64_t position);

/** Removes every contour of the plane index[axis] = position and their control points
 * from the contours they cross (section 5.2.4): another plane of that axis must stay,
 * and every contour left must keep four control points. */
MeshExtraction_EXPORT std::string
                      RemoveContourPlane(ContourNetwork & network, unsigned int axis, std::int64_t position);

// ------------------------------------------------------------------------------------
// Curves and scan conversion.
// ------------------------------------------------------------------------------------

/** The point at parameter t in [0, 1] of segment k of contour c (from its k-th control
 * point to the next), continuous index. */
MeshExtraction_EXPORT Vec3
EvaluateContourSegment(const ContourNetwork & network, std::uint32_t c, std::size_t k, double t);

/** Points along the whole closed contour c, at least `samplesPerSegment` intervals per
 * segment, starting at its first control point (not repeated at the end). */
MeshExtraction_EXPORT std::vector<Vec3>
                      SampleContour(const ContourNetwork & network, std::uint32_t c, unsigned int samplesPerSegment);

/** The scan conversion of contour c (thesis section 5.2.2): the voxels the curve passes
 * through, found by recursive subdivision of each segment until consecutive voxels are
 * 4-neighbours, in order around the contour, with repeats and back-and-forth visits of
 * a voxel removed; one voxel per visit. */
MeshExtraction_EXPORT std::vector<ContourVoxel>
                      ScanConvertContour(const ContourNetwork & network, std::uint32_t c);

/** What is wrong with the scan conversion `voxels` of contour c (empty if nothing):
 * not closed or not 4-connected, a voxel twice, a control point's voxel missing. */
MeshExtraction_EXPORT std::string
                      DescribeInvalidScanConversion(const ContourNetwork &            network,
                                                    std::uint32_t                     c,
                                                    const std::vector<ContourVoxel> & voxels);

/** Where the curves of the contours cross the plane index[axis] = position (control
 * points in the plane included), continuous index: the intersections of the model with
 * a plane (section 5.2.6). */
MeshExtraction_EXPORT std::vector<Vec3>
                      ContourPlaneIntersections(const ContourNetwork & network, unsigned int axis, double position);

// ------------------------------------------------------------------------------------
// The surface.
// ------------------------------------------------------------------------------------

/** How the surface of the model is triangulated. */
struct ContourSurfaceParameters
{
  /** The length of the pieces the contour segments are cut into, and the spacing of
   * the points filling the faces, mm; 0 (default): 1.5 times the smallest spacing. */
  double targetEdgeLength{ 0.0 };
  /** With Catmull-Rom contours, fair the patches inside the faces (least squares of
   * the uniform Laplacian, smooth across the contours) instead of leaving the mean
   * value patches, which sag between curved contours; a faired mesh that is not a
   * valid closed surface is dropped for the unfaired one. */
  bool fairInterior{ true };
};

/** The closed surface enclosed by the contours, in physical coordinates: every contour
 * segment cut into pieces of about the target length (shared by its two faces), every
 * face filled with rings of points placed by mean value coordinates of its boundary
 * mapped to a circle (a smooth patch through the boundary), and the rings zipped into
 * triangles, counter-clockwise seen from outside; then faired (see fairInterior). The
 * first points are the control points, in order. Empty if the network's faces do not
 * close a sphere or the mesh would not be a valid closed surface (closed, 2-manifold,
 * outward, no degenerate or intersecting triangles): no invalid mesh is returned. */
MeshExtraction_EXPORT IndexedTriangleMesh
BuildContourSurface(const ContourNetwork & network, const ContourSurfaceParameters & parameters);

/** Area (mm^2) and enclosed volume (mm^3) of a closed triangle mesh. */
MeshExtraction_EXPORT std::array<double, 2>
                      SurfaceAreaAndVolume(const IndexedTriangleMesh & mesh);

// ------------------------------------------------------------------------------------
// The model file (JSON).
// ------------------------------------------------------------------------------------

/** The network as the model file's JSON text:
 * {"format": "meshextraction-orthogonal-contours", "version": 1,
 *  "interpolation": "catmull-rom" | "linear",
 *  "grid": {"size": [..3], "spacing": [..3], "origin": [..3], "direction": [..9]},
 *  "control_points": [[i, j, k], ...],            (continuous indices)
 *  "contours": [{"axis": "x" | "y" | "z", "position": n, "points": [ids]}, ...]} */
MeshExtraction_EXPORT std::string
                      ContourNetworkToJSON(const ContourNetwork & network);

/** Reads the model file's JSON text; throws itk::ExceptionObject naming `source` and
 * the problem (not JSON, a member missing or of the wrong type, a rule broken). */
MeshExtraction_EXPORT ContourNetwork
ContourNetworkFromJSON(const std::string & text, const std::string & source);
} // namespace detail
} // namespace MeshExtraction
} // namespace itk

#endif
