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
// A folder of outputs (a report) made whole or not at all: see StagedDirectory in
// MeshExtractionCLI.h.
#include "MeshExtractionCLI.h"

#include "itkMeshExtractionWholeFile.h"

#include <algorithm>
#include <filesystem>

namespace MeshExtractionCLI
{
namespace fs = std::filesystem;

StagedDirectory::StagedDirectory(const std::string & directory)
    : m_Directory(directory)
{
  std::error_code error;
  fs::create_directories(directory, error);
  if (!fs::is_directory(directory, error))
  {
    itkGenericExceptionMacro("cannot write into '" << directory << "': it is not a folder and cannot be made one");
  }
  // A hidden folder inside the target: the same file system, so the files move in by
  // renaming them.
  m_Staging = ME::PartialFileName((fs::path(directory) / "staging").string());
  fs::create_directory(m_Staging, error);
  if (error)
  {
    itkGenericExceptionMacro("cannot write into '" << directory << "': " << error.message());
  }
}

StagedDirectory::~StagedDirectory()
{
  std::error_code error;
  fs::remove_all(m_Staging, error); // empty after a commit; what a failed run made
}

void
StagedDirectory::Commit(const std::string & last)
{
  // Every file but `last` first: the page that links to them appears when they are all
  // in place.
  std::vector<fs::path> files;
  for (const auto & entry : fs::directory_iterator(m_Staging))
  {
    files.push_back(entry.path());
  }
  std::stable_partition(files.begin(), files.end(), [&last](const fs::path & p) { return p.filename() != last; });
  for (const fs::path & file : files)
  {
    std::error_code error;
    fs::rename(file, fs::path(m_Directory) / file.filename(), error);
    if (error)
    {
      itkGenericExceptionMacro("cannot move '" << file.filename().string() << "' into '" << m_Directory
                                               << "': " << error.message());
    }
  }
}
} // namespace MeshExtractionCLI
