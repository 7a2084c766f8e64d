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
// Helpers shared by the meshextraction commands: error text, the phantom grid
// options, progress output, timing.

#include "MeshExtractionCLI.h"

#include "itkCommand.h"
#include "itkMeshExtractionWholeFile.h"

#include <cmath>
#include <filesystem>
#include <iostream>

namespace MeshExtractionCLI
{
namespace
{
/** Whether two paths name one file: the same file where both exist (hard links
 * included), else the same absolute path with "." and ".." resolved. */
bool
SameFile(const std::string & a, const std::string & b)
{
  namespace fs = std::filesystem;
  std::error_code error;
  if (fs::exists(a, error) && fs::exists(b, error))
  {
    return fs::equivalent(a, b, error);
  }
  const fs::path canonicalA = fs::weakly_canonical(a, error);
  const fs::path canonicalB = fs::weakly_canonical(b, error);
  return !error && canonicalA == canonicalB;
}
} // namespace

void
RequireNotAnInput(const std::string & output, const std::vector<std::string> & inputs, const std::string & what)
{
  for (const std::string & input : inputs)
  {
    if (!input.empty() && !output.empty() && SameFile(output, input))
    {
      throw UsageError(what + " '" + output + "' is the input '" + input + "': refusing to overwrite an input");
    }
  }
}

std::string
Describe(const itk::ExceptionObject & e)
{
  return ME::ExceptionReason(e);
}

// ------------------------------------------------------------------------------
// Phantom grids
// ------------------------------------------------------------------------------
std::vector<OptionSpec>
GridOptions()
{
  return { { "size", "N|NxNxN", "phantom grid size in voxels", "per phantom, e.g. 64", OptionRange::Between(2, 65536) },
           { "spacing", "S|SxSxS", "voxel spacing in mm", "1", OptionRange::AboveUpTo(0, 1e6) },
           { "origin", "X,Y,Z", "physical position of voxel (0,0,0)", "0,0,0", OptionRange::Between(-1e9, 1e9) },
           { "direction",
             "A,B,C,D,E,F,G,H,I",
             "direction cosine matrix, nine numbers row by row",
             "identity",
             OptionRange::Between(-1, 1) } };
}

namespace
{
/** --size: whole numbers of 2 to 65536 voxels. */
void
ReadGridSize(const Arguments & args, ME::PhantomGrid & grid)
{
  const auto size = args.GetNumbers("size", 3);
  for (unsigned int d = 0; d < 3; ++d)
  {
    // The upper bound keeps the voxel count within what a size type and memory hold.
    if (size[d] < 2 || size[d] > 65536 || size[d] != std::floor(size[d]))
    {
      throw UsageError("--size needs whole numbers from 2 to 65536, got '" + args.Get("size") + "'");
    }
    grid.size[d] = static_cast<itk::SizeValueType>(size[d]);
  }
}

/** --spacing: positive. */
void
ReadGridSpacing(const Arguments & args, ME::PhantomGrid & grid)
{
  const auto spacing = args.GetNumbers("spacing", 3);
  for (unsigned int d = 0; d < 3; ++d)
  {
    if (!(spacing[d] > 0.0))
    {
      throw UsageError("--spacing must be positive, got '" + args.Get("spacing") + "'");
    }
    grid.spacing[d] = spacing[d];
  }
}

/** --direction: nine numbers, row by row, of an orthonormal matrix. */
void
ReadGridDirection(const Arguments & args, ME::PhantomGrid & grid)
{
  const auto m = args.GetNumbers("direction", 9);
  for (unsigned int r = 0; r < 3; ++r)
  {
    for (unsigned int c = 0; c < 3; ++c)
    {
      grid.direction[r][c] = m[3 * r + c];
    }
  }
  const vnl_matrix_fixed<double, 3, 3> product = grid.direction.GetVnlMatrix() * grid.direction.GetTranspose();
  for (unsigned int r = 0; r < 3; ++r)
  {
    for (unsigned int c = 0; c < 3; ++c)
    {
      if (std::abs(product[r][c] - (r == c ? 1.0 : 0.0)) > 1e-6)
      {
        throw UsageError("--direction must be an orthonormal matrix");
      }
    }
  }
}
} // namespace

ME::PhantomGrid
GridFromArguments(ME::PhantomShape shape, const Arguments & args)
{
  ME::PhantomGrid grid = ME::DefaultPhantomGrid(shape);
  if (args.Has("size"))
  {
    ReadGridSize(args, grid);
  }
  if (args.Has("spacing"))
  {
    ReadGridSpacing(args, grid);
  }
  if (args.Has("origin"))
  {
    const auto origin = args.GetNumbers("origin", 3);
    for (unsigned int d = 0; d < 3; ++d)
    {
      grid.origin[d] = origin[d];
    }
  }
  if (args.Has("direction"))
  {
    ReadGridDirection(args, grid);
  }
  return grid;
}

ME::PhantomShape
ShapeFromName(const std::string & name)
{
  try
  {
    return ME::PhantomShapeFromName(name);
  }
  catch (const itk::ExceptionObject & e)
  {
    throw UsageError(Describe(e));
  }
}

// ------------------------------------------------------------------------------
// Progress and timing
// ------------------------------------------------------------------------------
namespace
{
/** Prints "label: 42%" on stderr as an ITK filter progresses. */
class ProgressPrinter : public itk::Command
{
public:
  using Self = ProgressPrinter;
  using Pointer = itk::SmartPointer<Self>;
  itkNewMacro(Self);

  void
  SetLabel(const std::string & label)
  {
    m_Label = label;
  }
  void
  Execute(itk::Object * caller, const itk::EventObject & event) override
  {
    Execute(static_cast<const itk::Object *>(caller), event);
  }
  void
  Execute(const itk::Object * caller, const itk::EventObject & event) override
  {
    const auto * process = dynamic_cast<const itk::ProcessObject *>(caller);
    if (process == nullptr)
    {
      return;
    }
    if (itk::ProgressEvent().CheckEvent(&event))
    {
      const int percent = static_cast<int>(100.0f * process->GetProgress());
      if (percent >= m_Last + 10 || (percent == 100 && m_Last != 100))
      {
        m_Last = percent;
        std::cerr << "  " << m_Label << ": " << percent << "%\n";
      }
    }
  }

private:
  std::string m_Label{ "progress" };
  int         m_Last{ -10 };
};
} // namespace

void
ReportProgress(itk::ProcessObject * process, const std::string & label)
{
  auto printer = ProgressPrinter::New();
  printer->SetLabel(label);
  process->AddObserver(itk::ProgressEvent(), printer);
}

double
Stopwatch::Seconds() const
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - m_Start).count();
}

std::string
HtmlEscape(const std::string & text)
{
  std::string out;
  for (char c : text)
  {
    switch (c)
    {
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '&':
        out += "&amp;";
        break;
      case '\'':
        out += "&#39;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

} // namespace MeshExtractionCLI
