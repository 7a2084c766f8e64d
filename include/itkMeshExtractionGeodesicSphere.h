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

#include "MeshExtractionExport.h"
#include "itkMeshExtractionIndexedTriangleMesh.h"

#include <cstddef>
#include <cstdint>
#include <random> // the seed is that of a std::mt19937_64

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
MeshExtraction_EXPORT IndexedTriangleMesh
MakeGeodesicSphere(unsigned int subdivisions, const Vec3 & center, double radius);

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
MeshExtraction_EXPORT IndexedTriangleMesh
MakePerturbedGeodesicSphere(unsigned int  subdivisions,
                            const Vec3 &  center,
                            double        meanRadius,
                            double        radiusVariance,
                            double        tangentialJitter,
                            std::size_t   edgeFlips = 0,
                            std::uint64_t seed = 4);

} // namespace MeshExtraction
} // namespace itk

#endif
