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
#include "itkMeshExtractionEnums.h"

#include <ostream>

namespace itk
{
std::ostream &
operator<<(std::ostream & out, MeshExtractionEnums::PhantomImage value)
{
  switch (value)
  {
    case MeshExtractionEnums::PhantomImage::DistanceMap:
      return out << "itk::MeshExtractionEnums::PhantomImage::DistanceMap";
    case MeshExtractionEnums::PhantomImage::BinaryMask:
      return out << "itk::MeshExtractionEnums::PhantomImage::BinaryMask";
    case MeshExtractionEnums::PhantomImage::BlurredStep:
      return out << "itk::MeshExtractionEnums::PhantomImage::BlurredStep";
  }
  return out << "INVALID VALUE FOR itk::MeshExtractionEnums::PhantomImage";
}
} // namespace itk
