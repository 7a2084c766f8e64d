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
#include "itkMeshExtractionMeshSurfaceDistanceReport.h"
#include "itkMeshExtractionJSON.h"

#include <iomanip>
#include <ostream>

namespace itk
{
namespace MeshExtraction
{
using detail::JSONNumber;
using detail::JSONString;

void
MeshSurfaceDistanceReport::Print(std::ostream & os, const std::string & title) const
{
  const auto flags = os.flags();
  const auto precision = os.precision();
  if (!title.empty())
  {
    os << title << '\n';
  }
  os << "  distance to " << referenceDescription << '\n';
  os << "  " << std::left << std::setw(24) << "from" << std::right << std::setw(10) << "count" << std::setw(14)
     << "mean" << std::setw(14) << "rms" << std::setw(14) << "max" << std::setw(14) << "signed mean" << '\n';
  auto row = [&os](const char * name, const DistanceStatistics & s) {
    os << "  " << std::left << std::setw(24) << name << std::right << std::setw(10) << s.count << std::scientific
       << std::setprecision(4) << std::setw(14) << s.mean << std::setw(14) << s.rms << std::setw(14) << s.maximum
       << std::setw(14) << s.signedMean << std::defaultfloat << '\n';
  };
  row("vertices", vertices);
  row("face centroids", faceCentroids);
  row("mesh samples", meshSamples);
  if (symmetric)
  {
    row("reference samples", referenceSamples);
  }
  os << "  " << (symmetric ? "symmetric" : "one-sided") << " Hausdorff distance " << std::setprecision(6) << hausdorff
     << '\n';
  os.flags(flags);
  os.precision(precision);
}

void
MeshSurfaceDistanceReport::PrintJSON(std::ostream & os) const
{
  const auto precision = os.precision();
  os << std::setprecision(10);
  auto stats = [&os](const DistanceStatistics & s) {
    os << "{\"count\": " << s.count << ", \"mean\": " << JSONNumber{ s.mean } << ", \"rms\": " << JSONNumber{ s.rms }
       << ", \"max\": " << JSONNumber{ s.maximum } << ", \"signed_mean\": " << JSONNumber{ s.signedMean } << "}";
  };
  os << "{\"reference\": " << JSONString{ referenceDescription } << ", \"vertices\": ";
  stats(vertices);
  os << ", \"face_centroids\": ";
  stats(faceCentroids);
  os << ", \"mesh_samples\": ";
  stats(meshSamples);
  os << ", \"reference_samples\": ";
  stats(referenceSamples);
  os << ", \"hausdorff\": " << JSONNumber{ hausdorff } << ", \"symmetric\": " << (symmetric ? "true" : "false") << "}";
  os.precision(precision);
}

} // namespace MeshExtraction
} // namespace itk
