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
#include "itkMeshExtractionScaleSpaceRefinementSteps.h"

#include <cmath>
#include <iomanip>
#include <ostream>
#include <sstream>

namespace itk
{
namespace MeshExtraction
{
std::string
RefinementOperationAbbreviation(MeshExtractionEnums::RefinementOperation operation)
{
  switch (operation)
  {
    case MeshExtractionEnums::RefinementOperation::Initial:
      return "Org";
    case MeshExtractionEnums::RefinementOperation::EdgeDetection:
      return "ED";
    case MeshExtractionEnums::RefinementOperation::EdgeSwap:
      return "ES";
    case MeshExtractionEnums::RefinementOperation::Smoothing:
      return "S";
  }
  return "?";
}

namespace
{
std::string
Fixed(double value, int precision)
{
  if (!std::isfinite(value))
  {
    return "";
  }
  std::ostringstream s;
  s << std::fixed << std::setprecision(precision) << value;
  return s.str();
}

std::string
Count(std::int64_t value)
{
  return value < 0 ? "" : std::to_string(value);
}
} // namespace

void
PrintScaleSpaceRefinementTable(std::ostream &                                os,
                               const std::vector<ScaleSpaceRefinementStep> & steps,
                               double                                        referenceRadius)
{
  const bool radius = std::isfinite(referenceRadius);
  os << std::left << std::setw(5) << "Op" << std::right << std::setw(6) << "cycle" << std::setw(10) << "min.angle"
     << std::setw(9) << "quality" << std::setw(11) << "inaccuracy" << std::setw(12)
     << (radius ? "mean radius" : "mean dist.") << std::setw(10) << "variance" << std::setw(9) << "changes"
     << std::setw(9) << "rejected" << std::setw(8) << "mean mv" << std::setw(8) << "max mv" << std::setw(7) << "degen"
     << std::setw(7) << "nonman" << std::setw(7) << "invert" << std::setw(9) << "seconds" << '\n';
  for (const auto & s : steps)
  {
    const double distance = radius ? referenceRadius + s.referenceDistanceMean : s.referenceDistanceMean;
    os << std::left << std::setw(5) << RefinementOperationAbbreviation(s.operation) << std::right << std::setw(6)
       << s.cycle << std::setw(10) << Fixed(s.meanMinimumAngle, 2) << std::setw(9) << Fixed(s.meanQArea, 3)
       << std::setw(11) << Fixed(s.inaccuracy, 3) << std::setw(12) << Fixed(distance, 3) << std::setw(10)
       << Fixed(s.referenceDistanceVariance, 4) << std::setw(9) << Count(s.changes) << std::setw(9)
       << Count(s.rejectedMoves) << std::setw(8) << Fixed(s.meanTravel, 3) << std::setw(8) << Fixed(s.maximumTravel, 3)
       << std::setw(7) << Count(s.degenerateTriangles) << std::setw(7) << Count(s.nonManifold) << std::setw(7)
       << Count(s.invertedTriangles) << std::setw(9) << Fixed(s.seconds, 3) << '\n';
  }
}

void
WriteScaleSpaceRefinementCSV(std::ostream & os, const std::vector<ScaleSpaceRefinementStep> & steps)
{
  os << "operation,cycle,points,triangles,mean_min_angle_deg,mean_q_area,min_q_area,inaccuracy_mm,"
        "mean_signed_distance_mm,distance_variance_mm2,changes,rejected_moves,mean_travel_mm,max_travel_mm,degenerate,"
        "non_manifold,inverted,seconds\n";
  for (const auto & s : steps)
  {
    os << RefinementOperationAbbreviation(s.operation) << ',' << s.cycle << ',' << s.numberOfPoints << ','
       << s.numberOfTriangles << ',' << Fixed(s.meanMinimumAngle, 4) << ',' << Fixed(s.meanQArea, 5) << ','
       << Fixed(s.minimumQArea, 5) << ',' << Fixed(s.inaccuracy, 5) << ',' << Fixed(s.referenceDistanceMean, 5) << ','
       << Fixed(s.referenceDistanceVariance, 6) << ',' << Count(s.changes) << ',' << Count(s.rejectedMoves) << ','
       << Fixed(s.meanTravel, 5) << ',' << Fixed(s.maximumTravel, 5) << ',' << Count(s.degenerateTriangles) << ','
       << Count(s.nonManifold) << ',' << Count(s.invertedTriangles) << ',' << Fixed(s.seconds, 4) << '\n';
  }
}

} // namespace MeshExtraction
} // namespace itk
