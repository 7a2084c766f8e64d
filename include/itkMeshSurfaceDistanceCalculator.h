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
#ifndef itkMeshSurfaceDistanceCalculator_h
#define itkMeshSurfaceDistanceCalculator_h

#include "itkImplicitSurfaceFunction.h"
#include "itkMeshExtractionJSON.h"
#include "itkMeshExtractionMacros.h"
#include "itkMeshExtractionMeshSurfaceDistanceReport.h"
#include "itkObject.h"
#include "itkObjectFactory.h"

#include <string>

namespace itk
{
/** \class MeshSurfaceDistanceCalculator
 * \brief Distances from a mesh to a reference surface: a triangle mesh or an
 * exact implicit surface (ImplicitSurfaceFunction).
 *
 * Reports, for the mesh's vertices and for its face centroids, the mean distance
 * (the unidirected modified Hausdorff distance of thesis eq. 3.7), the RMS and the
 * maximum; and the symmetric Hausdorff distance, the larger of
 * - the largest distance of the mesh's samples (vertices, centroids and a
 *   barycentric lattice of SamplingLevel subdivisions per triangle) to the
 *   reference, and
 * - the largest distance of the reference's samples to the mesh (a reference
 *   mesh is sampled the same way; an implicit surface at ImplicitSampleSpacing,
 *   default half the mesh's mean edge length).
 * The Hausdorff distance is therefore exact up to the sampling density.
 *
 * Point-to-triangle distances are exact (closest point by Voronoi regions) and
 * found with an AABB tree; queries run on ITK's multithreader. Distances to an
 * implicit surface are signed (negative inside), which GetSignedMean reports.
 * All values are in the mesh's physical units.
 *
 * \ingroup MeshExtraction
 */
template <typename TMesh, typename TReferenceMesh = TMesh>
class ITK_TEMPLATE_EXPORT MeshSurfaceDistanceCalculator : public Object
{
public:
  ITK_DISALLOW_COPY_AND_MOVE(MeshSurfaceDistanceCalculator);

  using Self = MeshSurfaceDistanceCalculator;
  using Superclass = Object;
  using Pointer = SmartPointer<Self>;
  using ConstPointer = SmartPointer<const Self>;

  itkNewMacro(Self);
  itkOverrideGetNameOfClassMacro(MeshSurfaceDistanceCalculator);

  using MeshType = TMesh;
  using ReferenceMeshType = TReferenceMesh;
  using ReportType = MeshExtraction::MeshSurfaceDistanceReport;
  using StatisticsType = MeshExtraction::DistanceStatistics;

  itkSetConstObjectMacro(Mesh, MeshType);
  itkGetConstObjectMacro(Mesh, MeshType);

  /** The reference: a triangle mesh, or an implicit surface. Setting one clears the other. */
  void
  SetReferenceMesh(const ReferenceMeshType * reference);
  itkGetConstObjectMacro(ReferenceMesh, ReferenceMeshType);
  void
  SetReferenceSurface(const ImplicitSurfaceFunction * surface);
  itkGetConstObjectMacro(ReferenceSurface, ImplicitSurfaceFunction);

  /** Subdivisions per triangle edge of the sampling lattice (default 2). */
  itkSetMacro(SamplingLevel, unsigned int);
  itkGetConstMacro(SamplingLevel, unsigned int);
  /** Measure the reverse direction for the symmetric Hausdorff distance (default on). */
  itkSetMacro(Symmetric, bool);
  itkGetConstMacro(Symmetric, bool);
  itkBooleanMacro(Symmetric);
  /** Sample spacing on an implicit reference (0: half the mean edge length). */
  itkSetMacro(ImplicitSampleSpacing, double);
  itkGetConstMacro(ImplicitSampleSpacing, double);
  itkSetMacro(NumberOfWorkUnits, unsigned int);
  itkGetConstMacro(NumberOfWorkUnits, unsigned int);

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
  const StatisticsType &
  GetVertexDistance() const
  {
    return m_Report.vertices;
  }
  const StatisticsType &
  GetFaceCentroidDistance() const
  {
    return m_Report.faceCentroids;
  }
  double
  GetHausdorffDistance() const
  {
    return m_Report.hausdorff;
  }
  /** Distance of every point (signed for an implicit reference), in point-container order. */
  const std::vector<double> &
  GetVertexDistances() const
  {
    return m_VertexDistances;
  }
  /** Distance of every triangle's centroid (signed for an implicit reference), in cell order. */
  const std::vector<double> &
  GetFaceCentroidDistances() const
  {
    return m_FaceCentroidDistances;
  }

protected:
  MeshSurfaceDistanceCalculator() = default;
  ~MeshSurfaceDistanceCalculator() override = default;
  void
  PrintSelf(std::ostream & os, Indent indent) const override;

private:
  typename MeshType::ConstPointer          m_Mesh;
  typename ReferenceMeshType::ConstPointer m_ReferenceMesh;
  ImplicitSurfaceFunction::ConstPointer    m_ReferenceSurface;
  unsigned int                             m_SamplingLevel{ 2 };
  bool                                     m_Symmetric{ true };
  double                                   m_ImplicitSampleSpacing{ 0.0 };
  unsigned int                             m_NumberOfWorkUnits{ 0 };
  ReportType                               m_Report;
  std::vector<double>                      m_VertexDistances;
  std::vector<double>                      m_FaceCentroidDistances;
};
} // namespace itk

#ifndef ITK_MANUAL_INSTANTIATION
#  include "itkMeshSurfaceDistanceCalculator.hxx"
#endif

#endif
