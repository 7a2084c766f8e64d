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
#include "itkMeshExtractionTriangleMeshQualityReport.h"
#include "itkMeshExtractionJSON.h"

#include <iomanip>
#include <ostream>
#include <sstream>

namespace itk
{
namespace MeshExtraction
{
namespace
{
using detail::JSONNumber;

void
PrintStatistics(std::ostream & os, const char * name, const ValueStatistics & s)
{
  os << "  " << std::left << std::setw(16) << name << std::right << std::fixed << std::setprecision(4) << std::setw(10)
     << s.mean << std::setw(10) << s.minimum << std::setw(10) << s.percentile05 << std::setw(10) << s.median
     << std::setw(10) << s.maximum << '\n';
}

void
PrintStatisticsJSON(std::ostream & os, const ValueStatistics & s)
{
  os << "{\"count\": " << s.count << ", \"mean\": " << JSONNumber{ s.mean } << ", \"min\": " << JSONNumber{ s.minimum }
     << ", \"max\": " << JSONNumber{ s.maximum } << ", \"p01\": " << JSONNumber{ s.percentile01 }
     << ", \"p05\": " << JSONNumber{ s.percentile05 } << ", \"median\": " << JSONNumber{ s.median }
     << ", \"p95\": " << JSONNumber{ s.percentile95 } << ", \"histogram_range\": [" << JSONNumber{ s.histogramLower }
     << ", " << JSONNumber{ s.histogramUpper } << "], \"histogram\": [";
  for (std::size_t i = 0; i < s.histogram.size(); ++i)
  {
    os << (i ? ", " : "") << s.histogram[i];
  }
  os << "]}";
}
} // namespace

bool
TriangleMeshQualityReport::IsClosed() const
{
  return boundaryEdges == 0 && numberOfTriangles > 0;
}

bool
TriangleMeshQualityReport::IsManifold() const
{
  return nonManifoldEdges == 0 && nonManifoldVertices == 0;
}

bool
TriangleMeshQualityReport::IsConsistentlyOriented() const
{
  return inconsistentlyOrientedEdges == 0;
}

bool
TriangleMeshQualityReport::IsValidClosedSurface() const
{
  return IsClosed() && IsManifold() && IsConsistentlyOriented() && degenerateTriangles == 0 &&
         invertedTrianglesVersusOutward <= 0 && invertedTrianglesVersusReference <= 0 && selfIntersectingPairs <= 0 &&
         enclosedVolume > 0.0;
}

void
TriangleMeshQualityReport::Print(std::ostream & os, const std::string & title) const
{
  const auto flags = os.flags();
  const auto precision = os.precision();
  if (!title.empty())
  {
    os << title << '\n';
  }
  os << "  points " << numberOfPoints << " (" << numberOfReferencedPoints << " in triangles), triangles "
     << numberOfTriangles;
  if (numberOfSplitQuads)
  {
    os << " (" << numberOfSplitQuads << " quads split)";
  }
  os << ", edges " << numberOfEdges << '\n';
  os << "  " << std::left << std::setw(16) << "measure" << std::right << std::setw(10) << "mean" << std::setw(10)
     << "min" << std::setw(10) << "p05" << std::setw(10) << "median" << std::setw(10) << "max" << '\n';
  PrintStatistics(os, "q_area", qArea);
  PrintStatistics(os, "q_angle", qAngle);
  PrintStatistics(os, "q_length", qLength);
  PrintStatistics(os, "min angle (deg)", minimumAngle);
  PrintStatistics(os, "max angle (deg)", maximumAngle);
  PrintStatistics(os, "edge length", edgeLength);
  os << std::setprecision(4) << "  q_angle < 0.3: " << 100.0 * fractionQAngleBelow03
     << " %   smoothness |2pi-sum|: " << std::setprecision(6) << meanSmoothness
     << "   valence 6: " << std::setprecision(2) << 100.0 * fractionValence6 << " %\n";
  os << "  valence histogram:";
  for (std::size_t d = 0; d < valenceHistogram.size(); ++d)
  {
    if (valenceHistogram[d])
    {
      os << ' ' << d << ':' << valenceHistogram[d];
    }
  }
  os << '\n';
  auto count = [](std::int64_t v) {
    std::ostringstream s;
    if (v < 0)
    {
      s << "n/a";
    }
    else
    {
      s << v;
    }
    return s.str();
  };
  os << "  integrity: degenerate " << degenerateTriangles << ", inverted (outward) "
     << count(invertedTrianglesVersusOutward) << ", inverted (reference) " << count(invertedTrianglesVersusReference)
     << ", self-intersecting pairs " << count(selfIntersectingPairs) << '\n';
  os << "             non-manifold edges " << nonManifoldEdges << ", non-manifold vertices " << nonManifoldVertices
     << ", boundary edges " << boundaryEdges << " in " << boundaryLoops << " loops, inconsistent edges "
     << inconsistentlyOrientedEdges << '\n';
  os << "  topology: components " << connectedComponents << ", Euler characteristic " << eulerCharacteristic
     << ", genus " << count(genus) << ", unreferenced points " << unreferencedPoints << '\n';
  os << std::setprecision(6) << "  area " << totalArea << ", enclosed volume " << enclosedVolume << '\n';
  os << "  valid closed surface: " << (IsValidClosedSurface() ? "yes" : "NO") << '\n';
  os.flags(flags);
  os.precision(precision);
}

void
TriangleMeshQualityReport::PrintJSON(std::ostream & os) const
{
  const auto precision = os.precision();
  os << std::setprecision(10);
  os << "{\"points\": " << numberOfPoints << ", \"referenced_points\": " << numberOfReferencedPoints
     << ", \"triangles\": " << numberOfTriangles << ", \"split_quads\": " << numberOfSplitQuads
     << ", \"edges\": " << numberOfEdges;
  os << ", \"q_area\": ";
  PrintStatisticsJSON(os, qArea);
  os << ", \"q_angle\": ";
  PrintStatisticsJSON(os, qAngle);
  os << ", \"q_length\": ";
  PrintStatisticsJSON(os, qLength);
  os << ", \"min_angle_deg\": ";
  PrintStatisticsJSON(os, minimumAngle);
  os << ", \"max_angle_deg\": ";
  PrintStatisticsJSON(os, maximumAngle);
  os << ", \"edge_length\": ";
  PrintStatisticsJSON(os, edgeLength);
  os << ", \"fraction_q_angle_below_0_3\": " << JSONNumber{ fractionQAngleBelow03 }
     << ", \"mean_smoothness\": " << JSONNumber{ meanSmoothness }
     << ", \"interior_vertices\": " << numberOfInteriorVertices
     << ", \"fraction_valence_6\": " << JSONNumber{ fractionValence6 } << ", \"valence_histogram\": [";
  for (std::size_t d = 0; d < valenceHistogram.size(); ++d)
  {
    os << (d ? ", " : "") << valenceHistogram[d];
  }
  os << "], \"degenerate_triangles\": " << degenerateTriangles
     << ", \"inverted_triangles_vs_reference\": " << invertedTrianglesVersusReference
     << ", \"inverted_triangles_vs_outward\": " << invertedTrianglesVersusOutward
     << ", \"undetermined_orientation_triangles\": " << undeterminedOrientationTriangles
     << ", \"non_manifold_edges\": " << nonManifoldEdges << ", \"non_manifold_vertices\": " << nonManifoldVertices
     << ", \"boundary_edges\": " << boundaryEdges << ", \"boundary_loops\": " << boundaryLoops
     << ", \"inconsistently_oriented_edges\": " << inconsistentlyOrientedEdges
     << ", \"unreferenced_points\": " << unreferencedPoints << ", \"connected_components\": " << connectedComponents
     << ", \"euler_characteristic\": " << eulerCharacteristic << ", \"genus\": " << genus
     << ", \"self_intersecting_pairs\": " << selfIntersectingPairs
     << ", \"self_intersecting_triangles\": " << selfIntersectingTriangles
     << ", \"total_area\": " << JSONNumber{ totalArea } << ", \"enclosed_volume\": " << JSONNumber{ enclosedVolume }
     << ", \"valid_closed_surface\": " << (IsValidClosedSurface() ? "true" : "false") << "}";
  os.precision(precision);
}

} // namespace MeshExtraction
} // namespace itk
