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
#ifndef itkMeshExtractionLandmarkFile_h
#define itkMeshExtractionLandmarkFile_h

#include "MeshExtractionExport.h"
#include "itkPoint.h"

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace itk
{
namespace MeshExtraction
{
/** \brief A parsed JSON value (RFC 8259): what the module reads of landmark and
 * markup files. Objects keep their members in file order.
 * \ingroup MeshExtraction */
struct MeshExtraction_EXPORT JSONValue
{
  enum class Kind
  {
    Null,
    Boolean,
    Number,
    String,
    Array,
    Object
  };
  Kind                                           kind{ Kind::Null };
  bool                                           boolean{ false };
  double                                         number{ 0.0 };
  std::string                                    text;
  std::vector<JSONValue>                         elements;
  std::vector<std::pair<std::string, JSONValue>> members;

  /** The member `name` of an object, or null if there is none (or this is no object). */
  const JSONValue *
  Find(const std::string & name) const;
};

/** Parses JSON text; throws itk::ExceptionObject naming `source` (a file name, for
 * the message), the line and the problem when the text is not valid JSON. */
MeshExtraction_EXPORT JSONValue
ParseJSON(const std::string & text, const std::string & source = "JSON text");

/** \brief Named landmarks in physical (LPS, ITK) coordinates, in file order. */
struct MeshExtraction_EXPORT NamedLandmark
{
  std::string      id;
  Point<double, 3> point;
};

/** Reads a landmark file in either of two formats, detected from the content:
 * - the module's (and the vertebra data's): a JSON array of objects
 *   {"id": "A", "coordinates": [x, y, z]} in LPS millimetres (other members ignored);
 * - a 3D Slicer markups file (.mrk.json): {"markups": [{"coordinateSystem": "LPS" or
 *   "RAS", "controlPoints": [{"label": "A", "position": [x, y, z]}, ...]}]}; RAS
 *   points are turned into LPS (x and y negated). Control points whose
 *   positionStatus is "missing" are skipped.
 * Throws itk::ExceptionObject naming the file and the problem: unreadable, not JSON,
 * neither format, a point without three finite coordinates, an id given twice. */
MeshExtraction_EXPORT std::vector<NamedLandmark>
                      ReadLandmarkFile(const std::string & fileName);

/** Writes landmarks in the module's format (readable by ReadLandmarkFile). */
MeshExtraction_EXPORT void
WriteLandmarkFile(const std::string & fileName, const std::vector<NamedLandmark> & landmarks);

/** The points of `landmarks` with the given ids, in the order of `ids`; throws
 * naming `fileName` and the ids that are missing. */
MeshExtraction_EXPORT std::vector<Point<double, 3>>
                      SelectLandmarks(const std::vector<NamedLandmark> & landmarks,
                                      const std::vector<std::string> &   ids,
                                      const std::string &                fileName);
} // namespace MeshExtraction
} // namespace itk

#endif
