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
#ifndef MeshExtractionCommandHelpers_h
#define MeshExtractionCommandHelpers_h

// Helpers shared by the meshextraction subcommands: error text, option name tables,
// phantom grids.

#include "MeshExtractionCommandLine.h"
#include "MeshExtractionIO.h"
#include "itkMeshExtractionPhantoms.h"

#include <string>
#include <utility>
#include <vector>

namespace MeshExtractionCLI
{
namespace ME = itk::MeshExtraction;

/** The names an option accepts, each with its value. */
template <typename T>
using OptionNames = std::vector<std::pair<std::string, T>>;

/** The names of `table` joined as "a, b or c" (or "a|b|c" with `bars`). */
template <typename T>
std::string
OptionChoices(const OptionNames<T> & table, bool bars = false)
{
  std::string list;
  for (std::size_t i = 0; i < table.size(); ++i)
  {
    list += (i == 0 ? "" : (bars ? "|" : (i + 1 == table.size() ? " or " : ", "))) + table[i].first;
  }
  return list;
}

/** The name of `value` in `table`. */
template <typename T>
std::string
OptionName(const OptionNames<T> & table, T value)
{
  for (const auto & entry : table)
  {
    if (entry.second == value)
    {
      return entry.first;
    }
  }
  return "";
}

/** The value of `--name` in `table`, or `fallback`. */
template <typename T>
T
ChooseOption(const Arguments & args, const std::string & name, const OptionNames<T> & table, T fallback)
{
  if (!args.Has(name))
  {
    return fallback;
  }
  const std::string value = args.Get(name);
  for (const auto & entry : table)
  {
    if (entry.first == value)
    {
      return entry.second;
    }
  }
  throw UsageError("--" + name + " must be " + OptionChoices(table) + ", got '" + value + "'");
}


/** An ITK exception's description without ITK's "ITK ERROR: Class(0x...): " prefix. */
inline std::string
Describe(const itk::ExceptionObject & e)
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

// ------------------------------------------------------------------------------
// Shared option groups
// ------------------------------------------------------------------------------
inline std::vector<OptionSpec>
GridOptions()
{
  return { { "size", "N|NxNxN", "phantom grid size in voxels", "per phantom, e.g. 64" },
           { "spacing", "S|SxSxS", "voxel spacing in mm", "1" },
           { "origin", "X,Y,Z", "physical position of voxel (0,0,0)", "0,0,0" },
           { "direction", "9 NUMBERS", "direction cosine matrix, row by row", "identity" } };
}

inline ME::PhantomGrid
GridFromArguments(ME::PhantomShape shape, const Arguments & args)
{
  ME::PhantomGrid grid = ME::DefaultPhantomGrid(shape);
  if (args.Has("size"))
  {
    const auto size = args.GetNumbers("size", 3);
    for (unsigned int d = 0; d < 3; ++d)
    {
      if (size[d] < 2 || size[d] != std::floor(size[d]))
      {
        throw UsageError("--size needs whole numbers >= 2, got '" + args.Get("size") + "'");
      }
      grid.size[d] = static_cast<itk::SizeValueType>(size[d]);
    }
  }
  if (args.Has("spacing"))
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
  return grid;
}

inline ME::PhantomShape
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

} // namespace MeshExtractionCLI

#endif
