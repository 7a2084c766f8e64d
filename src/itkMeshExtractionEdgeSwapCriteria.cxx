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
#include "itkMeshExtractionEdgeSwapCriteria.h"

#include <ostream>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
std::ostream &
operator<<(std::ostream & os, EdgeSwapVerdict v)
{
  switch (v)
  {
    case EdgeSwapVerdict::Swap:
      return os << "Swap";
    case EdgeSwapVerdict::NoImprovement:
      return os << "NoImprovement";
    case EdgeSwapVerdict::NotManifold:
      return os << "NotManifold";
    case EdgeSwapVerdict::ValenceTooLow:
      return os << "ValenceTooLow";
    case EdgeSwapVerdict::DegenerateTriangle:
      return os << "DegenerateTriangle";
    case EdgeSwapVerdict::NormalsDisagree:
      return os << "NormalsDisagree";
    case EdgeSwapVerdict::FeatureEdge:
      return os << "FeatureEdge";
    case EdgeSwapVerdict::LowerQuality:
      return os << "LowerQuality";
  }
  return os << "InvalidEdgeSwapVerdict";
}
} // namespace detail
} // namespace MeshExtraction
} // namespace itk
