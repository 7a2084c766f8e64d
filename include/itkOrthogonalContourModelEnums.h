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
#ifndef itkOrthogonalContourModelEnums_h
#define itkOrthogonalContourModelEnums_h

#include "MeshExtractionExport.h"

#include <cstdint>
#include <iosfwd>

namespace itk
{
/** \class OrthogonalContourModelEnums
 * \brief The enumerations of OrthogonalContourModel, each printable with operator<<.
 * \ingroup MeshExtraction
 */
class OrthogonalContourModelEnums
{
public:
  /** How a contour runs between its control points (thesis section 5.2.2). */
  enum class Interpolation : std::uint8_t
  {
    /** Straight lines: the control polygon itself, the fastest to evaluate. */
    Linear = 0,
    /** Centripetal Catmull-Rom splines: through the control points, C1 there, and
     * (being centripetal) without cusps or loops inside a segment. */
    CatmullRom
  };
};

/** Writes "itk::OrthogonalContourModelEnums::Interpolation::Linear" and so on. */
MeshExtraction_EXPORT std::ostream &
                      operator<<(std::ostream & out, OrthogonalContourModelEnums::Interpolation value);
} // namespace itk

#endif
