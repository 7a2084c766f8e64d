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
#ifndef itkMeshExtractionRandomSurfaces_h
#define itkMeshExtractionRandomSurfaces_h

#include "itkMeshExtractionTestHelpers.h"
#include "itkSurfaceNetsImageToMeshFilter.h"

#include <cstdlib>
#include <sstream>

namespace MeshExtractionTest
{
/** The SurfaceNets mesh of MakeRandomSmoothVolume(seed), a valid closed surface with
 * many small components and pinches: without relaxation for odd seeds (nodes at cell
 * centres, many right angles), with SNERT for even ones. Null if the volume has
 * nothing inside or nothing outside. */
inline QEMeshType::Pointer
RandomSurfaceNetsMesh(unsigned int seed)
{
  double     iso = 0.0;
  const auto image = MakeRandomSmoothVolume(seed, iso);
  auto       extract = itk::SurfaceNetsImageToMeshFilter<itk::Image<float, 3>, QEMeshType>::New();
  extract->SetInput(image);
  extract->SetIsoValue(iso);
  extract->SetRelaxation(seed % 2 ? itk::SurfaceNetsImageToMeshFilterEnums::Relaxation::None
                                  : itk::SurfaceNetsImageToMeshFilterEnums::Relaxation::Combined);
  try
  {
    extract->Update();
  }
  catch (const itk::ExceptionObject &)
  {
    return nullptr;
  }
  return extract->GetOutput();
}
/** The seed range [first, last) of the stress runs: MESHEXTRACTION_STRESS_SEEDS=A,B
 * if set, else the defaults given. */
inline void
StressSeeds(unsigned int & first, unsigned int & last)
{
  if (const char * seeds = std::getenv("MESHEXTRACTION_STRESS_SEEDS"))
  {
    std::istringstream in(seeds);
    char               comma = 0;
    in >> first >> comma >> last;
  }
}
} // namespace MeshExtractionTest

#endif
