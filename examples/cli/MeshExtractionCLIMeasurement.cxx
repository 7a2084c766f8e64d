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
// Measuring meshes with the module's calculators, and the figures as a table, JSON
// and CSV.

#include "MeshExtractionCLI.h"

#include "itkMeshExtractionJSON.h"
#include "itkMeshSurfaceDistanceCalculator.h"
#include "itkTriangleMeshQualityCalculator.h"

#include <fstream>
#include <iomanip>
#include <iostream>

namespace MeshExtractionCLI
{
// ------------------------------------------------------------------------------
// Measuring
// ------------------------------------------------------------------------------
MeasuredMesh
MeasureMesh(const IOMeshType *      mesh,
            const std::string &     name,
            const MeasureSettings & settings,
            std::vector<double> *   triangleQArea)
{
  auto quality = itk::TriangleMeshQualityCalculator<IOMeshType>::New();
  quality->SetMesh(mesh);
  quality->SetReferenceMesh(settings.inversionReference);
  quality->SetComputeSelfIntersections(settings.selfIntersections);
  quality->SetComputeOutwardOrientation(settings.outwardOrientation);
  quality->Compute();
  MeasuredMesh measured;
  measured.name = name;
  measured.quality = quality->GetReport();
  if (triangleQArea != nullptr)
  {
    triangleQArea->clear();
    for (const auto & triangle : quality->GetTriangleMeasures())
    {
      triangleQArea->push_back(triangle.qArea);
    }
  }
  if (settings.referenceSurface != nullptr || settings.referenceMesh != nullptr)
  {
    auto distance = itk::MeshSurfaceDistanceCalculator<IOMeshType>::New();
    distance->SetMesh(mesh);
    if (settings.referenceSurface != nullptr)
    {
      distance->SetReferenceSurface(settings.referenceSurface);
    }
    else
    {
      distance->SetReferenceMesh(settings.referenceMesh);
    }
    distance->SetSamplingLevel(settings.samplingLevel);
    distance->Compute();
    measured.hasDistance = true;
    measured.distance = distance->GetReport();
  }
  return measured;
}

MeasuredMesh
MeasureMesh(const QuadEdgeMeshType *             mesh,
            const std::string &                  name,
            const itk::ImplicitSurfaceFunction * referenceSurface)
{
  auto calculator = itk::TriangleMeshQualityCalculator<QuadEdgeMeshType>::New();
  calculator->SetMesh(mesh);
  calculator->Compute();
  MeasuredMesh m;
  m.name = name;
  m.quality = calculator->GetReport();
  if (referenceSurface != nullptr)
  {
    auto distance = itk::MeshSurfaceDistanceCalculator<QuadEdgeMeshType>::New();
    distance->SetMesh(mesh);
    distance->SetReferenceSurface(referenceSurface);
    distance->Compute();
    m.hasDistance = true;
    m.distance = distance->GetReport();
  }
  return m;
}

// ------------------------------------------------------------------------------
// Printing and writing
// ------------------------------------------------------------------------------
void
PrintMeasuredMesh(const MeasuredMesh & mesh, const std::string & title, std::ostream & os)
{
  mesh.quality.Print(os, title);
  if (mesh.hasDistance)
  {
    mesh.distance.Print(os);
  }
}

void
PrintComparison(const std::vector<MeasuredMesh> & meshes, std::ostream & os)
{
  os << std::left << std::setw(28) << "mesh" << std::right << std::setw(10) << "triangles" << std::setw(9) << "q_area"
     << std::setw(9) << "q_angle" << std::setw(9) << "<0.3 %" << std::setw(11) << "smooth" << std::setw(9) << "val6 %"
     << std::setw(12) << "d_vert" << std::setw(12) << "d_face" << std::setw(12) << "hausdorff" << std::setw(7)
     << "valid" << '\n';
  for (const auto & m : meshes)
  {
    std::string name = m.name.size() > 27 ? "..." + m.name.substr(m.name.size() - 24) : m.name;
    os << std::left << std::setw(28) << name << std::right << std::setw(10) << m.quality.numberOfTriangles << std::fixed
       << std::setprecision(4) << std::setw(9) << m.quality.qArea.mean << std::setw(9) << m.quality.qAngle.mean
       << std::setprecision(2) << std::setw(9) << 100 * m.quality.fractionQAngleBelow03 << std::setprecision(5)
       << std::setw(11) << m.quality.meanSmoothness << std::setprecision(1) << std::setw(9)
       << 100 * m.quality.fractionValence6;
    if (m.hasDistance)
    {
      os << std::scientific << std::setprecision(3) << std::setw(12) << m.distance.vertices.mean << std::setw(12)
         << m.distance.faceCentroids.mean << std::setw(12) << m.distance.hausdorff;
    }
    else
    {
      os << std::setw(12) << "-" << std::setw(12) << "-" << std::setw(12) << "-";
    }
    os << std::setw(7) << (m.quality.IsValidClosedSurface() ? "yes" : "NO") << std::defaultfloat << '\n';
  }
}

void
WriteJSON(const std::vector<MeasuredMesh> & meshes, const std::string & path)
{
  WriteTextWhole(path, [&meshes](std::ostream & out) {
    out << "[\n";
    for (std::size_t i = 0; i < meshes.size(); ++i)
    {
      out << "  {\"mesh\": " << itk::MeshExtraction::detail::JSONString{ meshes[i].name } << ", \"quality\": ";
      meshes[i].quality.PrintJSON(out);
      if (meshes[i].hasDistance)
      {
        out << ", \"distance\": ";
        meshes[i].distance.PrintJSON(out);
      }
      out << '}' << (i + 1 < meshes.size() ? "," : "") << '\n';
    }
    out << "]\n";
  });
}

void
WriteHistogramsCSV(const std::vector<MeasuredMesh> & meshes, const std::string & path)
{
  WriteTextWhole(path, [&meshes](std::ostream & out) {
    out << "mesh,measure,bin_lower,bin_upper,count\n";
    for (const auto & m : meshes)
    {
      const std::pair<const char *, const ME::ValueStatistics *> measures[] = {
        { "q_area", &m.quality.qArea },
        { "q_angle", &m.quality.qAngle },
        { "q_length", &m.quality.qLength },
        { "min_angle_deg", &m.quality.minimumAngle },
        { "max_angle_deg", &m.quality.maximumAngle },
      };
      for (const auto & measure : measures)
      {
        const auto & s = *measure.second;
        const double width = (s.histogramUpper - s.histogramLower) / s.histogram.size();
        for (std::size_t b = 0; b < s.histogram.size(); ++b)
        {
          out << m.name << ',' << measure.first << ',' << s.histogramLower + b * width << ','
              << s.histogramLower + (b + 1) * width << ',' << s.histogram[b] << '\n';
        }
      }
      for (std::size_t d = 0; d < m.quality.valenceHistogram.size(); ++d)
      {
        out << m.name << ",valence," << d << ',' << d + 1 << ',' << m.quality.valenceHistogram[d] << '\n';
      }
    }
  });
}

} // namespace MeshExtractionCLI
