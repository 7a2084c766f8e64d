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
// libFuzzer harness for the module's mesh-file readers: the first byte chooses the
// format, the rest is the file. A reader may refuse a file with an itk::ExceptionObject;
// it must not crash, hang or allocate without bound, and a mesh it accepts must pass
// through the checks that stand before a QuadEdgeMesh, and into one when they pass.

#include "itkMeshExtractionMeshFile.h"
#include "itkMeshExtractionMeshValidation.h"
#include "itkMesh.h"
#include "itkQuadEdgeMesh.h"

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>
#include <unistd.h>

namespace
{
/** A scratch file of this process, with the extension that names the format. */
std::string
ScratchFile(const char * extension)
{
  return "/tmp/meshextraction-fuzz-mesh-" + std::to_string(getpid()) + extension;
}
} // namespace

extern "C" int
LLVMFuzzerTestOneInput(const std::uint8_t * data, std::size_t size)
{
  if (size < 1)
  {
    return 0;
  }
  static const char * extensions[] = { ".vtk", ".vtp", ".ply", ".stl", ".obj", ".off" };
  const std::string   path = ScratchFile(extensions[data[0] % 6]);
  {
    std::ofstream file(path, std::ios::binary | std::ios::trunc);
    file.write(reinterpret_cast<const char *>(data + 1), static_cast<std::streamsize>(size - 1));
  }
  try
  {
    // Through the polygons, into a QuadEdgeMesh (after the manifold checks), and into an
    // itk::Mesh: the three ways the module reads a mesh.
    itk::MeshExtraction::ReadSurfaceMeshFile<itk::QuadEdgeMesh<double, 3>>(path);
  }
  catch (const itk::ExceptionObject &)
  {
    // a refusal, with its message: what a malformed file should get
  }
  try
  {
    itk::MeshExtraction::ReadSurfaceMeshFile<itk::Mesh<double, 3>>(path);
  }
  catch (const itk::ExceptionObject &)
  {}
  std::remove(path.c_str());
  return 0;
}
