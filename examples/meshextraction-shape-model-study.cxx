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

// meshextraction-shape-model-study: `meshextraction shape-model evaluate` under the name
// and options earlier notes and doc/history.md quote: the model of the meshes of one
// folder (default ../shared/data/vertebrae_L1: every *.ply but ref_*) and its figures.
// Options: --thesis (no non-rigid stage: the thesis' closest points), --p2p
// (point-to-point correspondence), --modes k (default 3), --passes N (at most N template
// passes, default 2), --write FILE (the model as statismo HDF5).

#include "MeshExtractionShapeModelCLI.h"

#include <cstdlib>
#include <exception>
#include <iostream>
#include <string>

int
main(int argc, char * argv[])
{
  MeshExtractionCLI::Arguments args;
  std::string                  folder = "../shared/data/vertebrae_L1";
  for (int i = 1; i < argc; ++i)
  {
    const std::string argument = argv[i];
    const bool        valued = i + 1 < argc;
    if (argument == "--thesis")
    {
      args.Set("thesis", "");
    }
    else if (argument == "--p2p")
    {
      args.Set("correspondence", "point");
    }
    else if ((argument == "--modes" || argument == "--passes") && valued)
    {
      args.Set(argument.substr(2), argv[++i]);
    }
    else if (argument == "--write" && valued)
    {
      args.Set("output", argv[++i]);
    }
    else
    {
      folder = argument;
    }
  }
  try
  {
    return MeshExtractionCLI::EvaluateShapeModel(args, { folder });
  }
  catch (const std::exception & e)
  {
    std::cerr << "meshextraction-shape-model-study: " << e.what() << '\n';
    return EXIT_FAILURE;
  }
}
