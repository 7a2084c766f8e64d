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
#ifndef itkMeshExtractionPLY_h
#define itkMeshExtractionPLY_h

#include "MeshExtractionExport.h"
#include "itkMeshExtractionIndexedTriangleMesh.h"

#include <string>

namespace itk
{
namespace MeshExtraction
{
/** Reads a PLY polygon file (ASCII, binary little- or big-endian; the vertex
 * properties x, y, z of any numeric type, other vertex properties skipped; faces as a
 * list "vertex_indices" or "vertex_index", polygons fanned into triangles; other
 * elements skipped). Coordinates are taken as they are (the module's meshes are in
 * physical LPS millimetres). Throws itk::ExceptionObject naming the file and the
 * problem: unreadable, not PLY, an unknown format or type, truncated data, an index
 * out of range, a coordinate that is not finite. */
MeshExtraction_EXPORT IndexedTriangleMesh
ReadPLYFile(const std::string & fileName);

/** Writes triangles as binary little-endian PLY (float coordinates, or double where
 * the points must be read back exactly, int indices). */
MeshExtraction_EXPORT void
WritePLYFile(const std::string & fileName, const IndexedTriangleMesh & mesh, bool doubleCoordinates = false);
} // namespace MeshExtraction
} // namespace itk

#endif
