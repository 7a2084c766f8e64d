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
// meshextraction: the MeshExtraction module's command-line tool.
//
//   meshextraction phantom NAME OUT.nrrd [options]   write a phantom image
//   meshextraction extract IN OUT.vtk [options]      extract a surface mesh
//   meshextraction improve IN OUT.vtk [options]      smooth and swap edges of a mesh
//   meshextraction refine IMAGE MESH OUT [options]   scale-space edge refinement (ch. 4)
//   meshextraction report DIR MESH... [options]      HTML report with plots and renderings
//   meshextraction quality MESH... [options]         measure meshes
//   meshextraction match FIXED MOVING [options]      three-landmark matching (ch. 6)
//   meshextraction shape-model MESH... [options]     landmark-free shape model (ch. 7)
//
// Run `meshextraction COMMAND --help` for the options of each command.

#include "MeshExtractionCLI.h"

#include "itkVersion.h"
#include "itksys/SystemTools.hxx"

#include <csignal>
#include <iomanip>
#include <iostream>

using namespace MeshExtractionCLI;

namespace
{
/** Every subcommand; each lives in its own cli/MeshExtraction<Name>Command.cxx. */
std::vector<Command>
Commands()
{
  return { MakePhantomCommand(), MakeExtractCommand(), MakeImproveCommand(), MakeRefineCommand(),
           MakeQualityCommand(), MakeReportCommand(),  MakeMatchCommand(),   MakeShapeModelCommand() };
}
void
PrintUsage(std::ostream & os, const std::vector<Command> & commands)
{
  os << "usage: meshextraction COMMAND [arguments] [--help]\n\n"
        "Accurate, well-formed surface meshes from CT and MRI volumes (ITK MeshExtraction).\n\ncommands:\n";
  for (const auto & c : commands)
  {
    os << "  " << std::left << std::setw(12) << c.name << c.summary << '\n';
  }
  os << "\nRun 'meshextraction COMMAND --help' for the options of a command; 'meshextraction --version'\n"
        "prints the versions. Installed as meshextraction-extract (a link), the tool runs 'extract' and\n"
        "'meshextraction-extract --xml' describes it to 3D Slicer as a CLI module.\n";
}

/** The command the program's own name implies: meshextraction-extract runs extract. */
std::string
CommandOfProgramName(const char * argv0)
{
  const std::string program = itksys::SystemTools::GetFilenameWithoutExtension(argv0);
  const std::string prefix = "meshextraction-";
  return program.compare(0, prefix.size(), prefix) == 0 ? program.substr(prefix.size()) : std::string();
}
} // namespace

int
main(int argc, char * argv[])
{
#ifdef SIGXFSZ
  // A write beyond the file-size limit then fails (and is reported, the partial file
  // removed) instead of ending the process with the output half written.
  std::signal(SIGXFSZ, SIG_IGN);
#endif
  const std::vector<Command> commands = Commands();
  // meshextraction-extract ARGS is meshextraction extract ARGS (3D Slicer calls a CLI
  // module's executable with the module's own arguments only).
  std::vector<char *> arguments(argv, argv + argc);
  const std::string   implied = CommandOfProgramName(argv[0]);
  std::string         impliedStorage = implied;
  if (!implied.empty())
  {
    arguments.insert(arguments.begin() + 1, impliedStorage.data());
    argc = static_cast<int>(arguments.size());
    argv = arguments.data();
  }
  if (argc >= 2 && std::string(argv[1]) == "--version")
  {
    std::cout << "meshextraction " << MeshExtractionVersion() << " (ITK " << itk::Version::GetITKVersion() << ")\n";
    return 0;
  }
  if (argc < 2 || std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h" || std::string(argv[1]) == "help")
  {
    PrintUsage(argc < 2 ? std::cerr : std::cout, commands);
    return argc < 2 ? 2 : 0;
  }
  const std::string name = argv[1];
  const Command *   command = nullptr;
  for (const auto & c : commands)
  {
    command = c.name == name ? &c : command;
  }
  if (command == nullptr)
  {
    std::cerr << "meshextraction: unknown command '" << name << "'\n\n";
    PrintUsage(std::cerr, commands);
    return 2;
  }
  for (int i = 2; i < argc; ++i)
  {
    if (std::string(argv[i]) == "--help" || std::string(argv[i]) == "-h")
    {
      command->PrintHelp(std::cout);
      return 0;
    }
  }
  if (argc == 3 && std::string(argv[2]) == "--xml" && command->slicerXML)
  {
    std::cout << command->slicerXML();
    return 0;
  }
  try
  {
    const Arguments args = command->Parse(argc - 2, argv + 2);
    return command->run(args);
  }
  catch (const UsageError & e)
  {
    std::cerr << "meshextraction " << name << ": " << e.what() << "\n\n";
    command->PrintHelp(std::cerr);
    return 2;
  }
  catch (const itk::ExceptionObject & e)
  {
    std::cerr << "meshextraction " << name << ": error: " << Describe(e) << '\n';
    return 1;
  }
  catch (const std::exception & e)
  {
    std::cerr << "meshextraction " << name << ": error: " << e.what() << '\n';
    return 1;
  }
}
