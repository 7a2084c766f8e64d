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
#ifndef itkTriangleMeshQualityCalculator_h
#define itkTriangleMeshQualityCalculator_h

#include "itkMeshExtractionJSON.h"
#include "itkMeshExtractionMacros.h"
#include "itkMeshExtractionTriangleGeometry.h"
#include "itkMeshExtractionTriangleMeshQualityReport.h"
#include "itkObject.h"
#include "itkObjectFactory.h"

#include <string>
#include <vector>

namespace itk
{
/** \class TriangleMeshQualityCalculator
 * \brief Measures the triangle quality and the integrity of a surface mesh.
 *
 * The measures are those of P.W. de Bruin's thesis (sections 2.2.2, 3.3 and 4.2.3):
 * - per triangle: q_length (shortest / longest edge), q_angle (smallest / largest
 *   angle), q_area = 4 sqrt(3) A / (e1^2 + e2^2 + e3^2), minimum and maximum angle;
 *   summarised as mean, minimum, percentiles and histograms (10 bins on [0, 1] for
 *   the q's; angles in degrees);
 * - per vertex: smoothness |2 pi - sum of incident angles| averaged over interior
 *   vertices, the valence histogram and the share of valence-6 vertices;
 * - integrity: degenerate triangles (q_area <= DegenerateQAreaTolerance), inverted
 *   triangles against a reference mesh with the same connectivity and, for closed
 *   meshes, against the outward direction (ray-crossing parity), non-manifold edges
 *   and vertices, boundary edges and loops (holes), inconsistently oriented edges,
 *   connected components, Euler characteristic and genus, self-intersections (exact
 *   predicates, accelerated by an AABB tree), total area and enclosed volume.
 *
 * Works on itk::Mesh and itk::QuadEdgeMesh. Quadrilaterals are measured after
 * being split along their shorter diagonal (the report counts them); other
 * polygons are refused with an itk::ExceptionObject. Vertex and line cells are
 * ignored. Computation is in double precision and multithreaded with ITK's
 * multithreader; results do not depend on the number of threads.
 *
 * \code
 * auto calculator = itk::TriangleMeshQualityCalculator<MeshType>::New();
 * calculator->SetMesh(mesh);
 * calculator->Compute();
 * std::cout << calculator->GetMeanQArea() << ' ' << calculator->GetReport().IsValidClosedSurface();
 * \endcode
 *
 * \ingroup MeshExtraction
 */
template <typename TMesh>
class ITK_TEMPLATE_EXPORT TriangleMeshQualityCalculator : public Object
{
public:
  ITK_DISALLOW_COPY_AND_MOVE(TriangleMeshQualityCalculator);

  using Self = TriangleMeshQualityCalculator;
  using Superclass = Object;
  using Pointer = SmartPointer<Self>;
  using ConstPointer = SmartPointer<const Self>;

  itkNewMacro(Self);
  itkOverrideGetNameOfClassMacro(TriangleMeshQualityCalculator);

  using MeshType = TMesh;
  using ReportType = MeshExtraction::TriangleMeshQualityReport;
  using TriangleMeasuresType = MeshExtraction::TriangleMeasures;

  itkSetConstObjectMacro(Mesh, MeshType);
  itkGetConstObjectMacro(Mesh, MeshType);

  /** Optional: a mesh with the same points and cells by identifier (e.g. the
   * input of a smoothing filter) to count triangles whose normal flipped. */
  itkSetConstObjectMacro(ReferenceMesh, MeshType);
  itkGetConstObjectMacro(ReferenceMesh, MeshType);

  itkSetMacro(DegenerateQAreaTolerance, double);
  itkGetConstMacro(DegenerateQAreaTolerance, double);
  itkSetMacro(ComputeSelfIntersections, bool);
  itkGetConstMacro(ComputeSelfIntersections, bool);
  itkBooleanMacro(ComputeSelfIntersections);
  itkSetMacro(ComputeOutwardOrientation, bool);
  itkGetConstMacro(ComputeOutwardOrientation, bool);
  itkBooleanMacro(ComputeOutwardOrientation);

  /** Measure the mesh. Throws if no mesh is set or it holds polygons other than
   * triangles and quadrilaterals. */
  void
  Compute();

  const ReportType &
  GetReport() const
  {
    return m_Report;
  }
  /** The report as one JSON object, as the CLI's `--report-json` writes it. For
   * Python, where the report structure is not wrapped: json.loads(c.GetReportAsJSON()). */
  std::string
  GetReportAsJSON() const
  {
    return MeshExtraction::detail::JSONText(m_Report);
  }
  double
  GetMeanQArea() const
  {
    return m_Report.qArea.mean;
  }
  double
  GetMeanQAngle() const
  {
    return m_Report.qAngle.mean;
  }
  double
  GetMeanQLength() const
  {
    return m_Report.qLength.mean;
  }
  double
  GetMeanSmoothness() const
  {
    return m_Report.meanSmoothness;
  }
  /** Measures of every triangle, in cell order (a split quad gives two). */
  const std::vector<TriangleMeasuresType> &
  GetTriangleMeasures() const
  {
    return m_TriangleMeasures;
  }
  /** q_area, q_angle and q_length of every measured triangle, in the order of
   * GetTriangleMeasures(): plain arrays, which Python reads as tuples (numpy.asarray). */
  std::vector<double>
  GetTriangleQAreas() const
  {
    return this->CollectTriangleMeasure(&TriangleMeasuresType::qArea);
  }
  std::vector<double>
  GetTriangleQAngles() const
  {
    return this->CollectTriangleMeasure(&TriangleMeasuresType::qAngle);
  }
  std::vector<double>
  GetTriangleQLengths() const
  {
    return this->CollectTriangleMeasure(&TriangleMeasuresType::qLength);
  }
  /** Cell identifier of every measured triangle. */
  const std::vector<IdentifierType> &
  GetTriangleCellIdentifiers() const
  {
    return m_TriangleCellIdentifiers;
  }
  /** |2 pi - sum of angles| of every point (0 for boundary and non-manifold ones), in point-container order. */
  const std::vector<double> &
  GetVertexSmoothness() const
  {
    return m_VertexSmoothness;
  }

protected:
  TriangleMeshQualityCalculator() = default;
  ~TriangleMeshQualityCalculator() override = default;
  void
  PrintSelf(std::ostream & os, Indent indent) const override;

private:
  std::vector<double>
  CollectTriangleMeasure(double TriangleMeasuresType::*measure) const
  {
    std::vector<double> values;
    values.reserve(m_TriangleMeasures.size());
    for (const auto & m : m_TriangleMeasures)
    {
      values.push_back(m.*measure);
    }
    return values;
  }

  typename MeshType::ConstPointer m_Mesh;
  typename MeshType::ConstPointer m_ReferenceMesh;
  double                          m_DegenerateQAreaTolerance{ 1e-6 };
  bool                            m_ComputeSelfIntersections{ true };
  bool                            m_ComputeOutwardOrientation{ true };

  ReportType                        m_Report;
  std::vector<TriangleMeasuresType> m_TriangleMeasures;
  std::vector<IdentifierType>       m_TriangleCellIdentifiers;
  std::vector<double>               m_VertexSmoothness;
};
} // namespace itk

#ifndef ITK_MANUAL_INSTANTIATION
#  include "itkTriangleMeshQualityCalculator.hxx"
#endif

#endif
