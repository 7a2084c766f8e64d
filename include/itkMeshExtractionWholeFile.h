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
#ifndef itkMeshExtractionWholeFile_h
#define itkMeshExtractionWholeFile_h

#include "MeshExtractionExport.h"

#include <functional>
#include <string>

namespace itk
{
class ExceptionObject;

namespace MeshExtraction
{
/** The description of an exception without ITK's "ITK ERROR: Class(0x...): " prefix:
 * the reason alone, for messages that name the file or the step themselves. */
MeshExtraction_EXPORT std::string
ExceptionReason(const ExceptionObject & e);

/** A name beside `path`, with its extension (which names the format), for the file
 * being written: it replaces `path` only once it is whole. */
MeshExtraction_EXPORT std::string
PartialFileName(const std::string & path);

/** Writes an output whole or not at all: `write` writes a partial file beside `path`
 * (PartialFileName), which then replaces `path` in one rename; if `write` throws, the
 * partial file is removed, `path` is left as it was, and the itk::ExceptionObject
 * names `path` and the reason. A `path` that exists and is not a regular file is
 * refused before anything is written. */
MeshExtraction_EXPORT void
WriteWhole(const std::string & path, const std::function<void(const std::string & partial)> & write);

} // namespace MeshExtraction
} // namespace itk

#endif
