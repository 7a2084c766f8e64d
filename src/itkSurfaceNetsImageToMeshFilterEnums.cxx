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
#include "itkSurfaceNetsImageToMeshFilterEnums.h"

#include <ostream>

namespace itk
{
std::ostream &
operator<<(std::ostream & out, SurfaceNetsImageToMeshFilterEnums::Relaxation value)
{
  switch (value)
  {
    case SurfaceNetsImageToMeshFilterEnums::Relaxation::Automatic:
      return out << "Automatic";
    case SurfaceNetsImageToMeshFilterEnums::Relaxation::None:
      return out << "None";
    case SurfaceNetsImageToMeshFilterEnums::Relaxation::Averaging:
      return out << "Averaging";
    case SurfaceNetsImageToMeshFilterEnums::Relaxation::Gradient:
      return out << "Gradient";
    case SurfaceNetsImageToMeshFilterEnums::Relaxation::Combined:
      return out << "Combined";
  }
  return out << "INVALID Relaxation";
}

std::ostream &
operator<<(std::ostream & out, SurfaceNetsImageToMeshFilterEnums::Triangulation value)
{
  switch (value)
  {
    case SurfaceNetsImageToMeshFilterEnums::Triangulation::ShortestDiagonal:
      return out << "ShortestDiagonal";
    case SurfaceNetsImageToMeshFilterEnums::Triangulation::Delaunay:
      return out << "Delaunay";
    case SurfaceNetsImageToMeshFilterEnums::Triangulation::Quadrilaterals:
      return out << "Quadrilaterals";
  }
  return out << "INVALID Triangulation";
}

std::ostream &
operator<<(std::ostream & out, SurfaceNetsImageToMeshFilterEnums::Gradient value)
{
  switch (value)
  {
    case SurfaceNetsImageToMeshFilterEnums::Gradient::CentralDifference:
      return out << "CentralDifference";
    case SurfaceNetsImageToMeshFilterEnums::Gradient::GaussianDerivative:
      return out << "GaussianDerivative";
  }
  return out << "INVALID Gradient";
}
} // namespace itk
