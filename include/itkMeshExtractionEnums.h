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
};

MeshExtraction_EXPORT std::ostream &
operator<<(std::ostream & out, MeshExtractionEnums::PhantomImage value);

} // namespace itk

#endif
