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
#ifndef itkSurfaceNetsImageToMeshFilterEnums_h
#define itkSurfaceNetsImageToMeshFilterEnums_h

#include "MeshExtractionExport.h"

#include <cstdint>
#include <iosfwd>

namespace itk
{
/** \class SurfaceNetsImageToMeshFilterEnums
 * \brief Options of SurfaceNetsImageToMeshFilter.
 * \ingroup MeshExtraction */
class SurfaceNetsImageToMeshFilterEnums
{
public:
  /** How the nodes of the net are relaxed (thesis section 3.2). */
  enum class Relaxation : std::uint8_t
  {
    /** Combined (SNERT) when a greyscale image is available, Averaging (SNA) for a label image alone. */
    Automatic = 0,
    /** Nodes stay at their cell centres. */
    None,
    /** SNA: each node moves to the average of its linked nodes (eq. 3.1-3.2). */
    Averaging,
    /** Each node steps along the gradient to the iso-surface (eq. 3.3-3.4). */
    Gradient,
    /** SNERT: averaging within the iso-surface plus the step to it (eq. 3.5-3.6). */
    Combined
  };
  /** How quadrilaterals become faces (thesis section 3.2.5). */
  enum class Triangulation : std::uint8_t
  {
    /** Split along the shorter diagonal. */
    ShortestDiagonal = 0,
    /** Split along the diagonal that maximises the smallest angle. */
    Delaunay,
    /** Keep the quadrilaterals. */
    Quadrilaterals
  };
  /** How the image gradient is estimated. */
  enum class Gradient : std::uint8_t
  {
    /** Central differences of the trilinearly interpolated image. */
    CentralDifference = 0,
    /** ITK's Gaussian derivatives of scale GradientSigma (mm) at the cell corners, interpolated. */
    GaussianDerivative
  };
};
MeshExtraction_EXPORT std::ostream &
                      operator<<(std::ostream & out, SurfaceNetsImageToMeshFilterEnums::Relaxation value);
MeshExtraction_EXPORT std::ostream &
                      operator<<(std::ostream & out, SurfaceNetsImageToMeshFilterEnums::Triangulation value);
MeshExtraction_EXPORT std::ostream &
                      operator<<(std::ostream & out, SurfaceNetsImageToMeshFilterEnums::Gradient value);

} // namespace itk

#endif
