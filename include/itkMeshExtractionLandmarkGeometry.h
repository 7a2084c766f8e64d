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
#ifndef itkMeshExtractionLandmarkGeometry_h
#define itkMeshExtractionLandmarkGeometry_h

#include "MeshExtractionExport.h"
#include "itkMatrix.h"
#include "itkVector.h"

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
/** \file
 * The rotations ThreeLandmarkIncrementalTransformInitializer composes (thesis ch. 6). */

/** The rotation taking the unit vector `from` onto the unit vector `to` along the
 * shortest arc (about from x to); for opposite vectors a half turn about an axis
 * perpendicular to `from`. */
MeshExtraction_EXPORT Matrix<double, 3, 3>
                      ShortestArcRotation(const Vector<double, 3> & from, const Vector<double, 3> & to);
/** The rotation by `angle` (radians, right-handed) about the unit vector `axis`
 * (Rodrigues' formula). */
MeshExtraction_EXPORT Matrix<double, 3, 3>
                      AxisAngleRotation(const Vector<double, 3> & axis, double angle);
/** The part of v perpendicular to the unit vector u. */
MeshExtraction_EXPORT Vector<double, 3>
                      PerpendicularPart(const Vector<double, 3> & v, const Vector<double, 3> & u);
} // namespace detail
} // namespace MeshExtraction
} // namespace itk

#endif
