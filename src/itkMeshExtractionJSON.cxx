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
#include "itkMeshExtractionJSON.h"

#include <cmath>
#include <cstdio>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
std::ostream &
operator<<(std::ostream & os, const JSONNumber & number)
{
  if (std::isfinite(number.value))
  {
    return os << number.value;
  }
  return os << "null";
}

std::ostream &
operator<<(std::ostream & os, const JSONString & text)
{
  os << '"';
  for (const char c : text.value)
  {
    if (c == '"' || c == '\\')
    {
      os << '\\' << c;
    }
    else if (static_cast<unsigned char>(c) < 0x20)
    {
      char escaped[8];
      std::snprintf(escaped, sizeof(escaped), "\\u%04x", static_cast<unsigned int>(c));
      os << escaped;
    }
    else
    {
      os << c;
    }
  }
  return os << '"';
}
} // namespace detail
} // namespace MeshExtraction
} // namespace itk
