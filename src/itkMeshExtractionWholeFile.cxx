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
#include "itkMeshExtractionWholeFile.h"

#include "itkMacro.h"

#include <chrono>
#include <filesystem>

namespace itk
{
namespace MeshExtraction
{
std::string
PartialFileName(const std::string & path)
{
  const std::filesystem::path p(path);
  const auto                  tag = std::chrono::steady_clock::now().time_since_epoch().count();
  return (p.parent_path() / ("." + p.stem().string() + ".partial-" + std::to_string(tag) + p.extension().string()))
    .string();
}

std::string
ExceptionReason(const ExceptionObject & e)
{
  std::string       text = e.GetDescription();
  const std::string prefix = "ITK ERROR: ";
  if (text.compare(0, prefix.size(), prefix) == 0)
  {
    text = text.substr(prefix.size());
  }
  const auto open = text.find("(0x");
  const auto close = text.find("): ");
  if (open != std::string::npos && close != std::string::npos && open < close && text.find(' ') > open)
  {
    text = text.substr(close + 3);
  }
  return text;
}

void
WriteWhole(const std::string & path, const std::function<void(const std::string & partial)> & write)
{
  namespace fs = std::filesystem;
  std::error_code error;
  if (fs::exists(path, error) && !fs::is_regular_file(path, error))
  {
    itkGenericExceptionMacro("cannot write '" << path << "': it exists and is not a regular file");
  }
  const std::string partial = PartialFileName(path);
  try
  {
    write(partial);
    fs::rename(partial, path, error);
    if (error)
    {
      itkGenericExceptionMacro("cannot rename the written file to it: " << error.message());
    }
  }
  catch (const ExceptionObject & e)
  {
    fs::remove(partial, error);
    itkGenericExceptionMacro("cannot write '" << path << "': " << ExceptionReason(e));
  }
}

} // namespace MeshExtraction
} // namespace itk
