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
#include "itkMeshExtractionShapeModelBuilder.h"
#include "itkMeshExtractionParallel.h"
#include "itkMeshExtractionValidityGuard.h"
#include "itkMultiThreaderBase.h"

#include <atomic>
#include <cmath>
#include <exception>
#include <memory>
#include <numeric>
#include <sstream>
#include <thread>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
// ---- training meshes ------------------------------------------------------------------

namespace
{
/** The root of v's set, halving the path on the way. */
std::uint32_t
FindRoot(std::vector<std::uint32_t> & parent, std::uint32_t v)
{
  while (parent[v] != v)
  {
    parent[v] = parent[parent[v]];
    v = parent[v];
  }
  return v;
}

/** The triangles of the component with most vertices, its vertices renumbered in order. */
IndexedTriangleMesh
LargestComponent(const IndexedTriangleMesh & mesh, std::size_t & dropped)
{
  std::vector<std::uint32_t> parent(mesh.points.size());
  std::iota(parent.begin(), parent.end(), 0u);
  for (const TriangleIndices & t : mesh.triangles)
  {
    for (unsigned int k = 1; k < 3; ++k)
    {
      const std::uint32_t a = FindRoot(parent, t[0]);
      const std::uint32_t b = FindRoot(parent, t[k]);
      parent[std::max(a, b)] = std::min(a, b);
    }
  }
  std::vector<bool> used(mesh.points.size(), false);
  for (const TriangleIndices & t : mesh.triangles)
  {
    used[t[0]] = used[t[1]] = used[t[2]] = true;
  }
  std::vector<std::size_t> size(mesh.points.size(), 0);
  std::uint32_t            largest = 0;
  for (std::uint32_t v = 0; v < mesh.points.size(); ++v)
  {
    if (used[v] && ++size[FindRoot(parent, v)] > size[largest])
    {
      largest = FindRoot(parent, v);
    }
  }
  IndexedTriangleMesh        out;
  std::vector<std::uint32_t> index(mesh.points.size(), std::numeric_limits<std::uint32_t>::max());
  for (std::uint32_t v = 0; v < mesh.points.size(); ++v)
  {
    if (used[v] && FindRoot(parent, v) == largest)
    {
      index[v] = static_cast<std::uint32_t>(out.points.size());
      out.points.push_back(mesh.points[v]);
      out.pointIds.push_back(v < mesh.pointIds.size() ? mesh.pointIds[v] : v);
    }
  }
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f)
  {
    const TriangleIndices & t = mesh.triangles[f];
    if (index[t[0]] != std::numeric_limits<std::uint32_t>::max())
    {
      out.triangles.push_back({ index[t[0]], index[t[1]], index[t[2]] });
      out.cellIds.push_back(f < mesh.cellIds.size() ? mesh.cellIds[f] : f);
    }
  }
  dropped = mesh.points.size() - out.points.size();
  return out;
}

/** 6 x the signed volume a closed mesh encloses (negative if its triangles face inward). */
double
SixVolume(const IndexedTriangleMesh & mesh)
{
  const Vec3 & o = mesh.points.front();
  double       volume = 0.0;
  for (const TriangleIndices & t : mesh.triangles)
  {
    volume += Dot(mesh.points[t[0]] - o, Cross(mesh.points[t[1]] - o, mesh.points[t[2]] - o));
  }
  return volume;
}
} // namespace

IndexedTriangleMesh
PrepareTrainingMesh(const IndexedTriangleMesh & mesh, const std::string & name, std::size_t * droppedVertices)
{
  if (mesh.triangles.empty())
  {
    itkGenericExceptionMacro(<< name << " is empty: it has no triangles (" << mesh.points.size() << " points).");
  }
  for (std::size_t i = 0; i < mesh.points.size(); ++i)
  {
    for (unsigned int d = 0; d < 3; ++d)
    {
      if (!std::isfinite(mesh.points[i][d]))
      {
        itkGenericExceptionMacro(<< name << " has a coordinate that is not finite (point "
                                 << (i < mesh.pointIds.size() ? mesh.pointIds[i] : i) << ").");
      }
    }
  }
  std::size_t         dropped = 0;
  IndexedTriangleMesh out = LargestComponent(mesh, dropped);
  const MeshTopology  topology = BuildMeshTopology(out);
  if (topology.numberOfBoundaryEdges > 0)
  {
    itkGenericExceptionMacro(<< name << " is open: its largest component has " << topology.numberOfBoundaryEdges
                             << " boundary edges; the shape model needs closed surfaces.");
  }
  if (topology.numberOfNonManifoldEdges > 0 || topology.numberOfNonManifoldVertices > 0)
  {
    itkGenericExceptionMacro(<< name << " is not a manifold: " << topology.numberOfNonManifoldEdges
                             << " non-manifold edges, " << topology.numberOfNonManifoldVertices
                             << " non-manifold vertices.");
  }
  if (topology.numberOfInconsistentEdges > 0)
  {
    itkGenericExceptionMacro(<< name << " is inconsistently oriented: " << topology.numberOfInconsistentEdges
                             << " edges are run the same way by their two triangles.");
  }
  if (SixVolume(out) < 0.0)
  {
    for (TriangleIndices & t : out.triangles)
    {
      std::swap(t[1], t[2]);
    }
  }
  if (droppedVertices != nullptr)
  {
    *droppedVertices = dropped;
  }
  return out;
}

// ---- transforms ------------------------------------------------------------------------

SimilarityTransform::Pointer
ToSimilarityTransform(const SimilarityParameters & parameters)
{
  Matrix<double, 3, 3> rotation;
  for (unsigned int r = 0; r < 3; ++r)
  {
    for (unsigned int c = 0; c < 3; ++c)
    {
      rotation[r][c] = parameters.rotation[r][c];
    }
  }
  Versor<double> versor;
  versor.Set(rotation);
  auto transform = SimilarityTransform::New();
  transform->SetRotation(versor);
  transform->SetScale(parameters.scale);
  SimilarityTransform::OutputVectorType translation;
  for (unsigned int d = 0; d < 3; ++d)
  {
    translation[d] = parameters.translation[d];
  }
  transform->SetTranslation(translation);
  return transform;
}

SimilarityParameters
ToSimilarityParameters(const SimilarityTransform & transform)
{
  SimilarityParameters parameters;
  const auto           rotation = transform.GetVersor().GetMatrix();
  for (unsigned int r = 0; r < 3; ++r)
  {
    for (unsigned int c = 0; c < 3; ++c)
    {
      parameters.rotation[r][c] = rotation[r][c];
    }
  }
  parameters.scale = transform.GetScale();
  const auto offset = transform.GetOffset();
  parameters.translation = MakeVec3(offset[0], offset[1], offset[2]);
  return parameters;
}

// ---- the template passes ---------------------------------------------------------------

namespace
{
/** What every pass matches against: each training mesh with its closest-point queries
 * (the correspondence's, and point-to-surface for the non-rigid stage). */
struct TrainingMesh
{
  TrainingMesh(const IndexedTriangleMesh & mesh, const ShapeModelSettings & settings)
      : query(mesh, settings.correspondence)
  {
    if (settings.nonRigid)
    {
      if (settings.correspondence != MeshExtractionEnums::Correspondence::PointToSurface)
      {
        surface = std::make_unique<ClosestPointQuery>(mesh, MeshExtractionEnums::Correspondence::PointToSurface);
      }
      target = std::make_unique<NonRigidTarget>(surface ? *surface : query);
    }
  }
  ClosestPointQuery                  query;
  std::unique_ptr<ClosestPointQuery> surface;
  std::unique_ptr<NonRigidTarget>    target;
};

Shape
Mean(const std::vector<Shape> & shapes)
{
  Shape mean(shapes.front().size(), MakeVec3(0, 0, 0));
  for (const Shape & s : shapes)
  {
    for (std::size_t k = 0; k < mean.size(); ++k)
    {
      mean[k] += s[k];
    }
  }
  for (Vec3 & p : mean)
  {
    p *= 1.0 / static_cast<double>(shapes.size());
  }
  return mean;
}

double
RMSDistance(const Shape & a, const Shape & b)
{
  double sum = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k)
  {
    sum += SquaredNorm(a[k] - b[k]);
  }
  return std::sqrt(sum / static_cast<double>(a.size()));
}

/** One mesh matched to the template (thesis 7.2.2, one mesh of a pass): the symmetric
 * similarity ICP from `initial` (or the initial estimate), then the correspondence in
 * the mesh's frame: the non-rigid match from T(template), or T(template)'s closest
 * points. */
TemplateMatch
MatchOne(const ClosestPointQuery &           onTemplate,
         const std::vector<Vec3> &           templatePoints,
         const TrainingMesh &                training,
         const NonRigidTemplate *            nonRigid,
         const ShapeModelSettings &          settings,
         const SimilarityParameters *        initial,
         const std::function<void(double)> & progress)
{
  const double         icpShare = nonRigid ? 0.15 : 1.0;
  SymmetricICPSettings icp;
  icp.correspondence = settings.correspondence;
  const SimilarityTransform::Pointer start = initial ? ToSimilarityTransform(*initial) : nullptr;
  icp.initial = start.GetPointer();
  icp.relativeTolerance = settings.icpRelativeTolerance;
  icp.measureInitialE2 = false;
  const SymmetricICPResult match = RunSymmetricICP(onTemplate, training.query, icp);
  if (progress)
  {
    progress(icpShare);
  }
  TemplateMatch out;
  out.e2 = match.e2;
  out.templateToMesh = ToSimilarityParameters(*match.fixedToMoving);
  const std::vector<Vec3> moved = TransformPoints(templatePoints, *match.fixedToMoving);
  if (nonRigid)
  {
    out.corresponded = MatchNonRigid(*nonRigid, moved, *training.target, [&](double f) {
      if (progress)
      {
        progress(icpShare + (1.0 - icpShare) * f);
      }
    });
    return out;
  }
  const std::vector<SurfacePoint> closest = training.query.Find(moved);
  out.corresponded.resize(closest.size());
  for (std::size_t k = 0; k < closest.size(); ++k)
  {
    out.corresponded[k] = closest[k].point;
  }
  return out;
}

std::unique_ptr<NonRigidTemplate>
MakeNonRigidTemplate(const IndexedTriangleMesh & templateMesh, const ShapeModelSettings & settings)
{
  if (!settings.nonRigid)
  {
    return nullptr;
  }
  return std::make_unique<NonRigidTemplate>(
    templateMesh.triangles, templateMesh.points.size(), settings.nonRigidSettings);
}

/** The passes of thesis 7.2.2 as named steps: match and correspond every mesh, then
 * renew the template. */
class TemplatePasses
{
public:
  TemplatePasses(const std::vector<IndexedTriangleMesh> & meshes,
                 const ShapeModelSettings &               settings,
                 const std::function<void(double)> &      progress)
      : m_Meshes(meshes)
      , m_Settings(settings)
      , m_Progress(progress)
  {
    m_Pivot = ChoosePivot(meshes);
    m_Template.points = meshes[m_Pivot].points;
    m_Template.triangles = meshes[m_Pivot].triangles;
    for (const IndexedTriangleMesh & mesh : meshes)
    {
      m_Training.push_back(std::make_unique<TrainingMesh>(mesh, settings));
    }
    m_NonRigid = MakeNonRigidTemplate(m_Template, settings);
  }

  /** The passes until the template settles or their maximum; fills `result`. */
  void
  Run(ShapeModelBuildResult & result)
  {
    result.pivot = m_Pivot;
    result.triangles = m_Template.triangles;
    for (unsigned int pass = 0; pass < m_Settings.maximumNumberOfPasses; ++pass)
    {
      this->MatchAll(pass, result);
      const RenewedTemplate renewed = RenewTemplate(m_Template, m_Matches, m_Settings);
      m_Template.points = renewed.points;
      const SimilarityParameters inverse = renewed.gauge.Inverse();
      for (TemplateMatch & match : m_Matches)
      {
        match.templateToMesh = Compose(match.templateToMesh, inverse);
      }
      result.templateChanges.push_back(renewed.change);
      if (renewed.change < m_Settings.passTolerance)
      {
        break;
      }
    }
  }

private:
  /** Every mesh matched to the template and corresponded (from the second pass on, its
   * similarity of the previous pass, moved with the template, is the initial estimate). */
  void
  MatchAll(unsigned int pass, ShapeModelBuildResult & result)
  {
    const ClosestPointQuery onTemplate(m_Template, m_Settings.correspondence);
    const std::size_t       m = m_Meshes.size();
    m_Matches.resize(m);
    std::vector<std::exception_ptr> errors(m);
    std::atomic<std::size_t>        next{ 0 };
    std::atomic<std::size_t>        done{ 0 };
    // The meshes are matched side by side, each on one thread: the parallel loops inside
    // a match are short and leave cores idle, the matches are independent of each other,
    // and a match gives the same result on any number of threads. Only the calling
    // thread reports progress (observers need not be thread-safe).
    const auto work = [&](bool reports) {
      const ScopedNumberOfWorkUnits one(1);
      for (std::size_t i = next++; i < m; i = next++)
      {
        try
        {
          const SimilarityParameters previous = m_Matches[i].templateToMesh;
          m_Matches[i] = MatchOne(onTemplate,
                                  m_Template.points,
                                  *m_Training[i],
                                  m_NonRigid.get(),
                                  m_Settings,
                                  pass > 0 ? &previous : nullptr,
                                  {});
        }
        catch (...)
        {
          errors[i] = std::current_exception();
        }
        ++done;
        if (reports)
        {
          this->Report(static_cast<double>(pass * m + done) /
                       static_cast<double>(m_Settings.maximumNumberOfPasses * m));
        }
      }
    };
    const unsigned int given = ThreadNumberOfWorkUnits();
    const std::size_t  threads = std::min<std::size_t>(
      m, std::max(1u, given > 0 ? given : MultiThreaderBase::GetGlobalDefaultNumberOfThreads()));
    std::vector<std::thread> helpers;
    for (std::size_t t = 1; t < threads; ++t)
    {
      helpers.emplace_back(work, false);
    }
    work(true);
    for (std::thread & helper : helpers)
    {
      helper.join();
    }
    for (const std::exception_ptr & error : errors)
    {
      if (error)
      {
        std::rethrow_exception(error);
      }
    }
    result.corresponded.assign(m, Shape());
    result.e2.assign(m, 0.0);
    for (std::size_t i = 0; i < m; ++i)
    {
      result.e2[i] = m_Matches[i].e2;
      result.corresponded[i] = m_Matches[i].corresponded;
    }
    double sum = 0.0;
    for (double e : result.e2)
    {
      sum += e;
    }
    result.meanE2PerPass.push_back(sum / static_cast<double>(result.e2.size()));
  }

  void
  Report(double fraction) const
  {
    if (m_Progress)
    {
      m_Progress(fraction);
    }
  }

  const std::vector<IndexedTriangleMesh> &   m_Meshes;
  const ShapeModelSettings &                 m_Settings;
  const std::function<void(double)> &        m_Progress;
  std::size_t                                m_Pivot{ 0 };
  IndexedTriangleMesh                        m_Template;
  std::vector<std::unique_ptr<TrainingMesh>> m_Training;
  std::unique_ptr<NonRigidTemplate>          m_NonRigid;
  std::vector<TemplateMatch>                 m_Matches;
};
} // namespace

std::size_t
ChoosePivot(const std::vector<IndexedTriangleMesh> & meshes)
{
  std::size_t pivot = 0;
  for (std::size_t i = 0; i < meshes.size(); ++i)
  {
    pivot = meshes[i].points.size() > meshes[pivot].points.size() ? i : pivot;
  }
  return pivot;
}

TemplateMatch
MatchTemplate(const IndexedTriangleMesh &         templateMesh,
              const IndexedTriangleMesh &         mesh,
              const ShapeModelSettings &          settings,
              const SimilarityParameters *        initial,
              const std::function<void(double)> & progress)
{
  const ClosestPointQuery                 onTemplate(templateMesh, settings.correspondence);
  const TrainingMesh                      training(mesh, settings);
  const std::unique_ptr<NonRigidTemplate> nonRigid = MakeNonRigidTemplate(templateMesh, settings);
  return MatchOne(onTemplate, templateMesh.points, training, nonRigid.get(), settings, initial, progress);
}

void
CheckMatchOfTemplate(const IndexedTriangleMesh & templateMesh, const TemplateMatch & match)
{
  if (match.corresponded.size() != templateMesh.points.size())
  {
    itkGenericExceptionMacro("A corresponded mesh has " << match.corresponded.size() << " points, the template "
                                                        << templateMesh.points.size()
                                                        << ": it was not matched to this template.");
  }
}

RenewedTemplate
RenewTemplate(const IndexedTriangleMesh &        templateMesh,
              const std::vector<TemplateMatch> & matches,
              const ShapeModelSettings &         settings)
{
  if (matches.empty())
  {
    itkGenericExceptionMacro("A template is renewed from at least one match.");
  }
  std::vector<Shape> inTemplateFrame;
  for (const TemplateMatch & match : matches)
  {
    CheckMatchOfTemplate(templateMesh, match);
    inTemplateFrame.push_back(ApplySimilarity(match.templateToMesh.Inverse(), match.corresponded));
  }
  const Shape     mean = Mean(inTemplateFrame);
  RenewedTemplate out;
  out.gauge = AlignShape(mean, templateMesh.points, true);
  out.points = ApplySimilarity(out.gauge, mean);
  if (settings.nonRigid && settings.nonRigidSettings.preventFolds)
  {
    // The mean of surfaces free of self-intersections need not be: where it crosses or
    // folds, the old template's points stay.
    IndexedTriangleMesh renewed;
    renewed.points = out.points;
    renewed.triangles = templateMesh.triangles;
    UndoFoldingMoves(
      renewed, BuildMeshTopology(renewed), templateMesh.points, ValidityThresholds::DegenerateQAreaTolerance);
    out.points = renewed.points;
  }
  out.change = RMSDistance(out.points, templateMesh.points);
  return out;
}

void
FinishShapeModel(ShapeModelBuildResult & result, double varianceFraction)
{
  CheckNumberOfTrainingMeshes(result.corresponded.size());
  result.aligned = GeneralizedProcrustes(result.corresponded, true, &result.toModel);
  result.model = BuildPrincipalComponents(result.aligned, varianceFraction);
  result.allVariances = BuildPrincipalComponents(result.aligned, 1.0).variances;
}

ShapeModelBuildResult
BuildShapeModel(const std::vector<IndexedTriangleMesh> & meshes,
                const ShapeModelSettings &               settings,
                const std::function<void(double)> &      progress)
{
  CheckNumberOfTrainingMeshes(meshes.size());
  if (settings.maximumNumberOfPasses < 1)
  {
    itkGenericExceptionMacro("A shape model needs at least one template pass.");
  }
  ShapeModelBuildResult result;
  TemplatePasses(meshes, settings, progress).Run(result);
  FinishShapeModel(result, settings.varianceFraction);
  if (progress)
  {
    progress(1.0);
  }
  return result;
}
// ---- the model ---------------------------------------------------------------------------

std::string
TrainingMeshName(std::size_t i)
{
  return "input mesh " + std::to_string(i);
}

void
CheckNumberOfTrainingMeshes(std::size_t numberOfMeshes)
{
  if (numberOfMeshes < 2)
  {
    itkGenericExceptionMacro("A shape model needs at least two meshes, got " << numberOfMeshes << '.');
  }
}

IndexedTriangleMesh
ModelMesh(const ShapeModelBuildResult & result, const std::vector<double> & coordinates)
{
  IndexedTriangleMesh mesh;
  mesh.points.resize(coordinates.size() / 3);
  for (std::size_t k = 0; k < mesh.points.size(); ++k)
  {
    mesh.points[k] = MakeVec3(coordinates[3 * k], coordinates[3 * k + 1], coordinates[3 * k + 2]);
  }
  mesh.triangles = result.triangles;
  return mesh;
}

std::vector<double>
SynthesizeInStandardDeviations(const PrincipalComponentModel & model, const std::vector<double> & standardDeviations)
{
  if (standardDeviations.size() > model.NumberOfModes())
  {
    itkGenericExceptionMacro(<< standardDeviations.size() << " coefficients for a model of " << model.NumberOfModes()
                             << " modes.");
  }
  std::vector<double> x = model.mean;
  for (std::size_t i = 0; i < standardDeviations.size(); ++i)
  {
    const double b = standardDeviations[i] * std::sqrt(model.variances[i]);
    for (std::size_t k = 0; k < x.size(); ++k)
    {
      x[k] += b * model.basis[i][k];
    }
  }
  return x;
}

std::vector<double>
ProjectInStandardDeviations(const ShapeModelBuildResult & result, const Shape & shape)
{
  const PrincipalComponentModel & model = result.model;
  if (3 * shape.size() != model.mean.size())
  {
    itkGenericExceptionMacro("The mesh to project has " << shape.size() << " points; the model's topology has "
                                                        << model.mean.size() / 3 << '.');
  }
  Shape mean(shape.size());
  for (std::size_t k = 0; k < mean.size(); ++k)
  {
    mean[k] = MakeVec3(model.mean[3 * k], model.mean[3 * k + 1], model.mean[3 * k + 2]);
  }
  std::vector<double> b = model.Project(ApplySimilarity(AlignShape(shape, mean, true), shape));
  for (std::size_t i = 0; i < b.size(); ++i)
  {
    b[i] /= std::sqrt(model.variances[i]);
  }
  return b;
}

void
WriteShapeModel(const std::string & fileName, const ShapeModelBuildResult & result)
{
  std::ostringstream info;
  info << "itk::LandmarkFreeShapeModelEstimator (MeshExtraction): " << result.corresponded.size() << " meshes, pivot "
       << result.pivot << ", " << result.templateChanges.size()
       << " template passes, similarity Procrustes, PCA by thin SVD";
  WriteStatismoModel(fileName, result.model, result.triangles, info.str());
}

} // namespace detail
} // namespace MeshExtraction
} // namespace itk
