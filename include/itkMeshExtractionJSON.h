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
#ifndef itkMeshExtractionJSON_h
#define itkMeshExtractionJSON_h

#include "MeshExtractionExport.h"

#include <ostream>
#include <sstream>
#include <string>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
/** A double as a JSON value: `os << JSONNumber{ x }` writes a finite x as a number and
 * NaN or an infinity, which JSON cannot hold, as null (a mesh with a NaN point has NaN
 * measures; Python's json.loads refuses "nan"). \ingroup MeshExtraction */
struct JSONNumber
{
  double value;
};

MeshExtraction_EXPORT std::ostream &
                      operator<<(std::ostream & os, const JSONNumber & number);

/** A string as a JSON string, quoted, with quotes, backslashes and control characters
 * escaped: `os << JSONString{ name }`. \ingroup MeshExtraction */
struct JSONString
{
  const std::string & value;
};

MeshExtraction_EXPORT std::ostream &
                      operator<<(std::ostream & os, const JSONString & text);

/** What `printable.PrintJSON(os)` writes, as a string (the calculators' GetReportAsJSON()). */
template <typename TPrintable>
std::string
JSONText(const TPrintable & printable)
{
  std::ostringstream os;
  printable.PrintJSON(os);
  return os.str();
}
} // namespace detail
} // namespace MeshExtraction
} // namespace itk

#endif
