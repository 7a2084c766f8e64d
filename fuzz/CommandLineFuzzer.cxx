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
// libFuzzer harness for the command-line tool's options: the first byte chooses the
// command, the rest, split at NUL bytes, are its arguments, parsed and run as
// `meshextraction COMMAND ARGS...` runs them. The runs happen in a scratch directory that
// holds a small mesh (m.obj, m.vtk), an image (s.nrrd), shape-model states (st*.json)
// and a broken model (bad.h5) for arguments to name. A command
// may refuse its arguments (UsageError: exit 2) or fail on its inputs
// (itk::ExceptionObject: exit 1, a message naming the file or option); any other
// exception is a finding (a library's message such as "stol" names neither), and so is a
// crash, a sanitizer report or a hang. Arguments that name a path outside the scratch
// directory (a '/', '..' or '~') are skipped, so that no run writes elsewhere, and so are
// arguments asking for more work than fuzzing can afford (a number above 40 after an
// option that counts voxels, iterations, rounds, cycles, modes or subdivisions).

#include "MeshExtractionCLI.h"
#include "itkMeshExtractionPhantoms.h"

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace
{
using namespace MeshExtractionCLI;

std::vector<Command> &
Commands()
{
  static std::vector<Command> commands{ MakePhantomCommand(), MakeExtractCommand(),   MakeImproveCommand(),
                                        MakeRefineCommand(),  MakeQualityCommand(),   MakeReportCommand(),
                                        MakeMatchCommand(),   MakeShapeModelCommand() };
  return commands;
}

/** Whether the arguments ask for more work than a fuzzing run can afford. */
bool
TooMuchWork(const std::vector<std::string> & arguments)
{
  static const std::set<std::string> counts{ "--size",           "--iterations",           "--rounds", "--cycles",
                                             "--modes",          "--sampling-level",       "--repeat", "--trials",
                                             "--max-iterations", "--min-component-voxels", "--width",  "--height" };
  for (std::size_t i = 0; i + 1 < arguments.size(); ++i)
  {
    std::string option = arguments[i];
    std::string value = arguments[i + 1];
    const auto  equals = option.find('=');
    if (equals != std::string::npos)
    {
      value = option.substr(equals + 1);
      option = option.substr(0, equals);
    }
    if (counts.count(option) == 0)
    {
      continue;
    }
    for (char & c : value)
    {
      c = (c == 'x' || c == ',') ? ' ' : c;
    }
    std::istringstream in(value);
    double             v = 0.0;
    while (in >> v)
    {
      if (!(v <= 40.0))
      {
        return true;
      }
    }
  }
  return false;
}

/** The inputs LLVMFuzzerInitialize writes into the scratch directory. */
const std::set<std::string> &
Inputs()
{
  static const std::set<std::string> inputs{ "m.obj",         "m.vtk", "s.nrrd", "st.json", "st-rotation.json",
                                             "st-scale.json", "bad.h5" };
  return inputs;
}

/** Removes what the runs wrote into the scratch directory, keeping the inputs. */
void
RemoveOutputs()
{
  namespace fs = std::filesystem;
  std::error_code error;
  for (const auto & entry : fs::directory_iterator(fs::current_path(), error))
  {
    const std::string name = entry.path().filename().string();
    if (Inputs().count(name) == 0)
    {
      fs::remove_all(entry.path(), error);
    }
  }
}

struct NullBuffer : std::streambuf
{
  int
  overflow(int c) override
  {
    return c;
  }
};
} // namespace

extern "C" int
LLVMFuzzerInitialize(int *, char ***)
{
  char scratch[] = "/tmp/meshextraction-cli-fuzz-XXXXXX";
  if (mkdtemp(scratch) == nullptr || chdir(scratch) != 0)
  {
    std::abort();
  }
  std::ofstream("m.obj") << "v 1 0 0\nv -1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nv 0 0 -1\n"
                            "f 1 3 5\nf 3 2 5\nf 2 4 5\nf 4 1 5\nf 3 1 6\nf 2 3 6\nf 4 2 6\nf 1 4 6\n";
  std::ofstream("m.vtk") << "# vtk DataFile Version 4.2\nm\nASCII\nDATASET POLYDATA\nPOINTS 4 float\n"
                            "0 0 0 1 0 0 0 1 0 0 0 1\nPOLYGONS 4 16\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  // Shape-model step states (renew, match --initial): a proper one, one whose rotation
  // is no rotation, one of scale 0; and a model file that is not HDF5.
  const char * states[][2] = { { "st.json", "[1, 0, 0, 0, 1, 0, 0, 0, 1], \"scale\": 1" },
                               { "st-rotation.json", "[1e308, 0, 0, 0, 1, 0, 0, 0, 1], \"scale\": 1" },
                               { "st-scale.json", "[1, 0, 0, 0, 1, 0, 0, 0, 1], \"scale\": 0" } };
  for (const auto & state : states)
  {
    std::ofstream(state[0]) << "{\"e2\": 1, \"corresponded\": \"m.obj\", \"template_to_mesh\": {\"rotation\": "
                            << state[1] << ", \"translation\": [0, 0, 0]}}\n";
  }
  std::ofstream("bad.h5") << "\x89HDF\r\n\x1a\n not a model";
  itk::MeshExtraction::PhantomGrid grid =
    itk::MeshExtraction::DefaultPhantomGrid(itk::MeshExtraction::PhantomShape::Sphere);
  grid.size.Fill(16);
  auto source =
    itk::MeshExtraction::MakePhantomImageSource<itk::Image<float, 3>>(itk::MeshExtraction::PhantomShape::Sphere, grid);
  source->Update();
  WriteImageFile(source->GetOutput(), "s.nrrd");
  static NullBuffer quiet;
  std::cout.rdbuf(&quiet);
  std::cerr.rdbuf(&quiet);
  return 0;
}

extern "C" int
LLVMFuzzerTestOneInput(const std::uint8_t * data, std::size_t size)
{
  if (size < 1)
  {
    return 0;
  }
  const Command &          command = Commands()[data[0] % Commands().size()];
  std::vector<std::string> arguments;
  std::string              current;
  for (std::size_t i = 1; i < size && arguments.size() < 32; ++i)
  {
    if (data[i] == 0)
    {
      arguments.push_back(current);
      current.clear();
    }
    else
    {
      current.push_back(static_cast<char>(data[i]));
    }
  }
  if (!current.empty() && arguments.size() < 32)
  {
    arguments.push_back(current);
  }
  // Files only in the scratch directory: no argument names a path elsewhere.
  for (const auto & a : arguments)
  {
    if (a.find('/') != std::string::npos || a.find("..") != std::string::npos || a.find('~') != std::string::npos)
    {
      return 0;
    }
  }
  if (TooMuchWork(arguments))
  {
    return 0;
  }
  static unsigned int runs = 0;
  if (++runs % 200 == 0)
  {
    RemoveOutputs();
  }
  std::vector<char *> argv;
  for (auto & a : arguments)
  {
    argv.push_back(a.data());
  }
  try
  {
    const Arguments parsed = command.Parse(static_cast<int>(argv.size()), argv.data());
    command.run(parsed);
  }
  catch (const UsageError &)
  {}
  catch (const itk::ExceptionObject &)
  {}
  catch (const std::bad_alloc &)
  {}
  catch (const std::exception & e)
  {
    std::fprintf(
      stderr, "meshextraction %s: an exception that names no option or file: %s\n", command.name.c_str(), e.what());
    std::abort();
  }
  return 0;
}
