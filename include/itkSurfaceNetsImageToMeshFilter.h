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
#ifndef itkSurfaceNetsImageToMeshFilter_h
#define itkSurfaceNetsImageToMeshFilter_h

#include "MeshExtractionExport.h"
#include "itkImage.h"
#include "itkImageToMeshFilter.h"
#include "itkMeshExtractionMacros.h"
#include "itkMeshExtractionIndexedTriangleMesh.h"
#include "itkMeshExtractionSurfaceNet.h"
#include "itkMeshExtractionSurfaceNets.h"
#include "itkQuadEdgeMesh.h"
#include "itkSurfaceNetsImageToMeshFilterEnums.h"

#include <array>
#include <cstdint>
#include <type_traits>
#include <vector>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
struct SurfaceNetsCellCache;
struct SurfaceNetsClassificationStatistics;
} // namespace detail
} // namespace MeshExtraction

/** \class SurfaceNetsImageToMeshFilter
 * \brief Extracts a closed, 2-manifold, outward-oriented triangle (or quad) mesh
 * from a 3-D image with the SurfaceNets of Gibson, extended with greyscale
 * relaxation (SNERT) as in P.W. de Bruin's thesis, chapter 3.
 *
 * Inputs: a greyscale image and an IsoValue (InsideIsAboveIsoValue says which side
 * is the object); or a label image (ClassifyByLabel on, LabelValue the object's
 * label: Gibson's binary SurfaceNet); or both, a greyscale input plus a LabelImage:
 * the net is built from the segmentation and relaxed toward the greyscale
 * iso-surface. Voxels outside the image count as outside, so objects touching the
 * border are closed.
 *
 * GenerateData checks the input and the parameters and, with
 * ResampleToIsotropicVoxels, resamples the inputs to cubic voxels (PrepareInputs);
 * then it runs the stages, one line each, each in its own unit:
 * 1. classify cells (cubes between 8 voxel centres) — ClassifyCells,
 *    ClassifySurfaceCells;
 * 2. build the net: one node per surface sheet of a cell, the quadrilateral of
 *    every voxel edge crossing the surface, the links — BuildNet, BuildSurfaceNet;
 * 3. relax the nodes, each constrained to its cell — RelaxNodes, RelaxSurfaceNet;
 * 4. keep faces from crossing (PreventSelfIntersections): move the nodes of relaxed
 *    faces that cross back toward their start — RemoveSelfIntersections,
 *    RemoveSurfaceNetSelfIntersections;
 * 5. form faces in physical space (unless stage 4 made them of the final nodes) —
 *    FormFaces, MakeSurfaceNetFaces;
 * 6. the high-quality mode (HighQuality): rounds of edge swaps and relaxation on the
 *    triangles — RunHighQualityStage, RunHighQualityMode, MeshExtraction::detail::SurfaceNetsHighQuality;
 * 7. drop small components (MinimumComponentVolume, off by default) —
 *    RemoveSmallComponents;
 * 8. the output mesh — MakeOutputMesh.
 *
 * Guarantees: the output is closed, 2-manifold and consistently oriented with
 * normals pointing out of the object, for every configuration. A cell where the
 * object touches itself at an edge or a corner, or a checkerboard face, gets one
 * node per sheet (manifold dual contouring) instead of a non-manifold vertex. Nodes
 * stay a margin (CellMargin, default 0.01 voxel) inside their cell, and each
 * quadrilateral is split along a diagonal that keeps both triangles facing along
 * the quad's voxel edge, so no triangle is degenerate or inverted. Spacing, origin
 * and direction are honoured (the cell constraint is applied in index space, the
 * relaxation vectors are built in physical space). Classification, net building
 * and relaxation run on ITK's multithreader; the mesh is identical for any number
 * of threads. Memory beyond the input image is proportional to the surface.
 *
 * Bad input raises an itk::ExceptionObject: no input, NaN voxels (the first one is
 * named), a constant image, no voxel inside, a label image of another geometry,
 * gradient relaxation without a greyscale image, out-of-range parameters.
 *
 * \ingroup MeshExtraction
 */
template <typename TInputImage,
          typename TOutputMesh = QuadEdgeMesh<double, TInputImage::ImageDimension>,
          typename TLabelImage = Image<unsigned char, TInputImage::ImageDimension>>
class ITK_TEMPLATE_EXPORT SurfaceNetsImageToMeshFilter : public ImageToMeshFilter<TInputImage, TOutputMesh>
{
public:
  ITK_DISALLOW_COPY_AND_MOVE(SurfaceNetsImageToMeshFilter);

  using Self = SurfaceNetsImageToMeshFilter;
  using Superclass = ImageToMeshFilter<TInputImage, TOutputMesh>;
  using Pointer = SmartPointer<Self>;
  using ConstPointer = SmartPointer<const Self>;

  itkNewMacro(Self);
  itkOverrideGetNameOfClassMacro(SurfaceNetsImageToMeshFilter);

  static constexpr unsigned int ImageDimension = TInputImage::ImageDimension;
  static_assert(ImageDimension == 3, "SurfaceNetsImageToMeshFilter extracts surfaces from 3-D images.");

  using InputImageType = TInputImage;
  using InputPixelType = typename InputImageType::PixelType;
  using LabelImageType = TLabelImage;
  using OutputMeshType = TOutputMesh;

  using RelaxationEnum = SurfaceNetsImageToMeshFilterEnums::Relaxation;
  using TriangulationEnum = SurfaceNetsImageToMeshFilterEnums::Triangulation;
  using GradientEnum = SurfaceNetsImageToMeshFilterEnums::Gradient;

  /** Optional segmentation: the net is built from LabelImage == LabelValue and
   * relaxed toward the greyscale input's iso-surface. Same grid as the input. */
  itkSetInputMacro(LabelImage, LabelImageType);
  itkGetInputMacro(LabelImage, LabelImageType);

  /** The iso-value of the greyscale input (default 0). */
  itkSetMacro(IsoValue, double);
  itkGetConstMacro(IsoValue, double);
  /** True (default): voxels >= IsoValue are the object (CT bone, a bright organ).
   * False: voxels <= IsoValue are (a signed distance map, negative inside). */
  itkSetMacro(InsideIsAboveIsoValue, bool);
  itkGetConstMacro(InsideIsAboveIsoValue, bool);
  itkBooleanMacro(InsideIsAboveIsoValue);
  /** The input itself is a label image; the object is its LabelValue voxels. */
  itkSetMacro(ClassifyByLabel, bool);
  itkGetConstMacro(ClassifyByLabel, bool);
  itkBooleanMacro(ClassifyByLabel);
  /** The object's label in the label image (default 1). */
  itkSetMacro(LabelValue, double);
  itkGetConstMacro(LabelValue, double);

  /** Relaxation (default Automatic: SNERT with a greyscale image, SNA without). */
  itkSetEnumMacro(Relaxation, RelaxationEnum);
  itkGetEnumMacro(Relaxation, RelaxationEnum);
  /** Iteration limit of the relaxation (default 10: enough for the nodes to settle;
   * more iterations change neither quality nor accuracy much). */
  itkSetMacro(MaximumNumberOfIterations, unsigned int);
  itkGetConstMacro(MaximumNumberOfIterations, unsigned int);
  /** The relaxation stops when no node moved more than this (voxels, default 1e-3). */
  itkSetMacro(ConvergenceThreshold, double);
  itkGetConstMacro(ConvergenceThreshold, double);
  /** Weight of the averaging vector a_p of eq. 3.5 (default 1, the thesis' SNERT). */
  itkSetMacro(SmoothingWeight, double);
  itkGetConstMacro(SmoothingWeight, double);
  /** Weight of the step to the iso-surface (default 1). */
  itkSetMacro(ProjectionWeight, double);
  itkGetConstMacro(ProjectionWeight, double);
  /** Average, then project, within each iteration, ending with the iso-surface
   * (thesis 3.2.4); default off: both in one step (eq. 3.6). */
  itkSetMacro(SequentialRelaxation, bool);
  itkGetConstMacro(SequentialRelaxation, bool);
  itkBooleanMacro(SequentialRelaxation);
  /** Gradient estimate (default central differences) and the Gaussian's scale in mm. */
  itkSetEnumMacro(GradientMethod, GradientEnum);
  itkGetEnumMacro(GradientMethod, GradientEnum);
  itkSetMacro(GradientSigma, double);
  itkGetConstMacro(GradientSigma, double);

  /** Faces (default shortest diagonal). */
  itkSetEnumMacro(Triangulation, TriangulationEnum);
  itkGetEnumMacro(Triangulation, TriangulationEnum);
  /** High-quality mode (default off; thesis 2.3 and 4.2.4 applied to SurfaceNets):
   * after the SNERT relaxation, rounds of regularity edge swaps (the decision of
   * EdgeSwapQuadEdgeMeshFilter) followed by SNERT relaxation on the triangle mesh's
   * 1-rings, every node on the iso-surface and near its own cell (see
   * HighQualityCellDilation); MeshExtraction::detail::SurfaceNetsHighQuality. Swaps and moves
   * that would flip, degenerate or cross a triangle, or collapse a component, are
   * undone (the validity guard, itkMeshExtractionValidityGuard.h), so the output keeps
   * every guarantee of plain SurfaceNets. Needs triangles. On strongly anisotropic
   * voxels one node per cell cannot be spaced evenly in physical space: quality stays
   * below that on cubic voxels unless the image is resampled first
   * (ResampleToIsotropicVoxels). */
  itkSetMacro(HighQuality, bool);
  itkGetConstMacro(HighQuality, bool);
  itkBooleanMacro(HighQuality);
  /** Rounds of swaps and relaxation in high-quality mode (default 8); a round whose
   * swaps are fewer than ConvergedSwapFraction of the triangles (after the first) ends
   * them early. Then Delaunay swap sweeps and a last relaxation, which also gets the
   * iterations of the round that ended them early. */
  itkSetMacro(NumberOfHighQualityRounds, unsigned int);
  itkGetConstMacro(NumberOfHighQualityRounds, unsigned int);
  /** The rounds of the high-quality mode have converged when a round's regularity swaps
   * are fewer than this fraction of the triangles (default 0.001; 0: only a round
   * without any swap ends them). The swaps fall off quickly from round to round, and
   * once they are this few the mesh hardly changes any more: the remaining rounds would
   * cost time and give nothing. */
  itkSetMacro(ConvergedSwapFraction, double);
  itkGetConstMacro(ConvergedSwapFraction, double);
  /** SNERT iterations per round in high-quality mode (default 4). */
  itkSetMacro(HighQualityIterations, unsigned int);
  itkGetConstMacro(HighQualityIterations, unsigned int);
  /** In high-quality mode a node may leave its cell by this much (voxels, default
   * 0.5, the most allowed): the swaps and the validity checks, not the cells, then keep
   * the mesh valid. 0 keeps every node in its cell (plain SurfaceNets' constraint). A
   * node that may leave its cell reaches the iso-surface near the cell's corners and
   * spaces out more evenly, so a larger dilation gives better angles, fewer slivers and
   * a smaller largest vertex error, while the mean distance to the surface stays
   * about the same. */
  itkSetMacro(HighQualityCellDilation, double);
  itkGetConstMacro(HighQualityCellDilation, double);
#if !defined(ITK_LEGACY_REMOVE)
  /** \deprecated The high-quality settings' earlier names: use
   * Set/GetNumberOfHighQualityRounds, Set/GetHighQualityIterations and
   * Set/GetHighQualityCellDilation. */
  [[deprecated("use SetNumberOfHighQualityRounds")]] void
  SetNumberOfImprovementRounds(unsigned int rounds)
  {
    this->SetNumberOfHighQualityRounds(rounds);
  }
  [[deprecated("use GetNumberOfHighQualityRounds")]] unsigned int
  GetNumberOfImprovementRounds() const
  {
    return this->GetNumberOfHighQualityRounds();
  }
  [[deprecated("use SetHighQualityIterations")]] void
  SetImprovementIterations(unsigned int iterations)
  {
    this->SetHighQualityIterations(iterations);
  }
  [[deprecated("use GetHighQualityIterations")]] unsigned int
  GetImprovementIterations() const
  {
    return this->GetHighQualityIterations();
  }
  [[deprecated("use SetHighQualityCellDilation")]] void
  SetImprovementCellDilation(double dilation)
  {
    this->SetHighQualityCellDilation(dilation);
  }
  [[deprecated("use GetHighQualityCellDilation")]] double
  GetImprovementCellDilation() const
  {
    return this->GetHighQualityCellDilation();
  }
#endif
  /** The scale (voxels, default 2) of the smooth surface the high-quality mode fits to
   * a label image (ClassifyByLabel): the signed distance of the object's voxels, smoothed
   * by a Gaussian of this standard deviation with its shrinkage corrected to first
   * order (the mean curvature), so that the surface stays where the segmentation puts
   * it; the relaxation is then SNERT toward it (central differences). Larger values
   * round the voxel stairs off more and follow features of a few voxels less. 0: the
   * high-quality mode only averages the label surface (SNA), as before this option,
   * which moves every node inward on convex parts. Unused for greyscale input. */
  itkSetMacro(LabelSurfaceSigma, double);
  itkGetConstMacro(LabelSurfaceSigma, double);
  /** In the high-quality mode, remesh locally around the slivers the rounds leave
   * (default on): one node per cell cannot mend a needle between two nodes pinned near
   * a shared cell face, nor the thin triangles around a node of valence 3. Around each
   * triangle whose q_angle is below 0.3 one edge collapse (onto an end or onto the
   * midpoint projected onto the iso-surface), edge swap or node move onto the
   * iso-surface is made, the one that raises the smallest q_angle there the most, under
   * the same guards as the rounds (2-manifold and closed, no fold, no turned or
   * degenerate triangle, no crossing, no collapsed component). The output then has
   * fewer nodes than the net (GetSurfaceNet()). See GetNumberOfCollapses. */
  itkSetMacro(HighQualitySliverRemoval, bool);
  itkGetConstMacro(HighQualitySliverRemoval, bool);
  itkBooleanMacro(HighQualitySliverRemoval);
  /** In the high-quality mode, remesh isotropically before the sliver removal (default
   * off): edges longer than 4/3 of HighQualityTargetEdgeLength are split, edges
   * shorter than 4/5 of it collapsed, edges swapped toward valence 6, and the nodes
   * relaxed along the surface and projected onto the iso-surface (Botsch and Kobbelt's
   * isotropic remeshing), each change under the sliver removal's guards. One node per
   * cell spaces the nodes as the voxels are spaced; this gives anisotropic voxels
   * near-equilateral triangles without resampling the image. Needs a surface to project
   * onto: a greyscale input, or a label input with LabelSurfaceSigma > 0 (otherwise it
   * is skipped). The output then has other nodes than the net (GetSurfaceNet()). See
   * GetNumberOfSplits. */
  itkSetMacro(HighQualityRemeshing, bool);
  itkGetConstMacro(HighQualityRemeshing, bool);
  itkBooleanMacro(HighQualityRemeshing);
  /** The target edge length (mm) of HighQualityRemeshing; 0 (the default) means the
   * mean of the input's spacings. Lengths below MinimumTargetEdgeLengthInVoxels of the
   * smallest spacing are an exception at Update(). */
  itkSetMacro(HighQualityTargetEdgeLength, double);
  itkGetConstMacro(HighQualityTargetEdgeLength, double);
  /** HighQualityRemeshing's rounds of splits, collapses, swaps and relaxation
   * (default 8), at most: they stop at a round that changes nothing
   * (GetNumberOfRemeshingRounds). */
  itkSetMacro(HighQualityRemeshingIterations, unsigned int);
  itkGetConstMacro(HighQualityRemeshingIterations, unsigned int);
  /** Undo relaxation where faces would cross (default on): nodes of crossing
   * faces move back toward their cell centres until the mesh is free of
   * self-intersections (see GetNumberOfNodesMovedBack). */
  itkSetMacro(PreventSelfIntersections, bool);
  itkGetConstMacro(PreventSelfIntersections, bool);
  itkBooleanMacro(PreventSelfIntersections);
  /** Drop every closed component whose enclosed volume (mm^3, in magnitude) is below
   * this: the noise islands of a real scan, and likewise small cavities inside the
   * object. 0 (the default) keeps every component. Components are measured on the
   * final surface, so the rest of the mesh is exactly what it is without the option.
   * See GetNumberOfComponentsRemoved. */
  itkSetMacro(MinimumComponentVolume, double);
  itkGetConstMacro(MinimumComponentVolume, double);
  /** Distance (voxels) nodes keep from their cell's faces (default 0.01). */
  itkSetMacro(CellMargin, double);
  itkGetConstMacro(CellMargin, double);
  /** Resample the input (and LabelImage) to cubic voxels of its smallest spacing before
   * extracting (default off; nothing happens when the voxels are already cubic). One
   * node per cell spaces the nodes as the voxels are spaced, so on anisotropic voxels
   * the triangles are stretched along the longest spacing; this gives them the
   * isotropic figures at the cost of more triangles. Greyscale values are interpolated
   * linearly (ITK's ResampleImageFilter; integer pixels are truncated to the pixel
   * type), label images by nearest neighbour. The grid starts at the buffered region's
   * first voxel, with the input's direction, and ends at or before its last voxel. The
   * linear interpolation moves the iso-surface by a fraction of a voxel, and can remove
   * or join features of about one voxel. On anisotropic voxels the triangles come out
   * markedly more regular (with --quality high, too), with more of them.
   * GetSurfaceNet() is then in the resampled grid's indices. */
  itkSetMacro(ResampleToIsotropicVoxels, bool);
  itkGetConstMacro(ResampleToIsotropicVoxels, bool);
  itkBooleanMacro(ResampleToIsotropicVoxels);
  /** The spacing ResampleToIsotropicVoxels gives `image`: its smallest spacing, or 0
   * when its voxels are cubic already (within 1e-6) and it is not resampled. */
  static double
  IsotropicResamplingSpacing(const InputImageType * image);
  // The multithreaded stages use ProcessObject's NumberOfWorkUnits.

  /** After Update(): relaxation iterations run, the last largest relocation (voxels),
   * the number of nodes, of cells split into several nodes, and of nodes moved
   * back to keep faces from crossing. */
  itkGetConstMacro(NumberOfIterations, unsigned int);
  itkGetConstMacro(LastMaximumRelocation, double);
  itkGetConstMacro(NumberOfNodes, SizeValueType);
  itkGetConstMacro(NumberOfSplitCells, SizeValueType);
  itkGetConstMacro(NumberOfNodesMovedBack, SizeValueType);
  /** After Update(): components and faces dropped by MinimumComponentVolume. */
  itkGetConstMacro(NumberOfComponentsRemoved, SizeValueType);
  itkGetConstMacro(NumberOfFacesRemoved, SizeValueType);
  /** After Update() in high-quality mode: swaps kept, and high-quality rounds run
   * (those that swapped and relaxed; the last relaxation not counted). */
  itkGetConstMacro(NumberOfSwaps, SizeValueType);
  itkGetConstMacro(NumberOfRoundsPerformed, unsigned int);
  /** After Update() with HighQualitySliverRemoval: edges collapsed, edges swapped and
   * nodes moved around slivers (kept after the checks). */
  itkGetConstMacro(NumberOfCollapses, SizeValueType);
  itkGetConstMacro(NumberOfSliverSwaps, SizeValueType);
  itkGetConstMacro(NumberOfSliverMoves, SizeValueType);
  /** After Update() with HighQualityRemeshing: edges split, collapsed and swapped by the
   * remeshing (kept after the checks; those of the sliver removal are above). */
  itkGetConstMacro(NumberOfSplits, SizeValueType);
  itkGetConstMacro(NumberOfRemeshingCollapses, SizeValueType);
  itkGetConstMacro(NumberOfRemeshingSwaps, SizeValueType);
  /** Rounds the remeshing ran (both kinds, at most twice HighQualityRemeshingIterations):
   * each kind stops at the first round that changes nothing. */
  itkGetConstMacro(NumberOfRemeshingRounds, unsigned int);

  /** The smallest HighQualityTargetEdgeLength, as a fraction of the smallest voxel
   * spacing: shorter edges would resolve nothing more of the image. */
  static constexpr double MinimumTargetEdgeLengthInVoxels = 0.25;

  /** After Update(): the net itself (nodes in continuous index space, quads, links). */
  const MeshExtraction::SurfaceNet &
  GetSurfaceNet() const
  {
    return m_Net;
  }

protected:
  SurfaceNetsImageToMeshFilter();
  ~SurfaceNetsImageToMeshFilter() override = default;

  void
  GenerateData() override;
  void
  GenerateOutputInformation() override
  {}
  void
  PrintSelf(std::ostream & os, Indent indent) const override;

  /** Stage 1: surface cells of the input (or the label image). */
  void
  ClassifyCells();
  /** Relax the net along its links (at most `iterations` times): stage 3, and the
   * relaxation of the high-quality rounds. With `cellCache`, the nodes' cells are read
   * once for every call on this net. */
  MeshExtraction::detail::SurfaceNetsRelaxationResult
  RelaxNet(RelaxationEnum                                 relaxation,
           unsigned int                                   iterations,
           MeshExtraction::detail::SurfaceNetsCellCache * cellCache = nullptr);
  /** Stage 6's rounds (MeshExtraction::detail::SurfaceNetsHighQuality): swaps
   * and relaxation (RelaxNet) on the triangles, every change checked by the validity
   * guard. */
  void
  RunHighQualityMode(std::vector<MeshExtraction::TriangleIndices> & triangles,
                     MeshExtraction::detail::SurfaceNetsCellCache * cellCache);
  /** Stage 6's end (HighQualitySliverRemoval): local remeshing around the slivers
   * (MeshExtraction::detail::RemoveSlivers), onto the surface the relaxation fits. */
  void
  RemoveSlivers(std::vector<MeshExtraction::TriangleIndices> & triangles);
  /** Stage 8: the faces (node indices) with the nodes in physical space, into the
   * output mesh. `points`: the nodes' physical points if already made (the face
   * split made them), else null. `keptPoints`: the nodes the faces use, new index ->
   * old, when stage 7 removed some (the faces are numbered on them), else null. */
  void
  MakeOutputMesh(const MeshExtraction::LargeBlockVector<std::array<std::uint32_t, 4>> & polygons,
                 unsigned int                                                           polygonSize,
                 const MeshExtraction::Vec3 *                                           points,
                 const std::vector<std::uint32_t> *                                     keptPoints = nullptr);
  /** The index-to-physical matrix (direction * spacing), the physical point of the
   * buffer's first voxel, and the face split of the Triangulation setting. */
  void
  GetGeometry(Matrix<double, 3, 3> & indexToPhysical, MeshExtraction::Vec3 & first) const;
  MeshExtraction::detail::QuadSplit
  GetQuadSplit() const;
  /** The images the stages read: the input and LabelImage, or their resampled copies
   * (ResampleToIsotropicVoxels). */
  const InputImageType *
  GetSampledInput() const;
  const LabelImageType *
  GetSampledLabelImage() const;

private:
  /** The faces the stages hand on: node indices (triangles, or quads), and the nodes'
   * physical points they were made with, by stage 4 or 5, while they are those of the
   * final positions. */
  struct Faces
  {
    MeshExtraction::LargeBlockVector<std::array<std::uint32_t, 4>> polygons;
    unsigned int                                                   polygonSize{ 3 };
    std::vector<MeshExtraction::Vec3>                              checkedPoints; ///< stage 4's
    MeshExtraction::LargeBlockVector<MeshExtraction::Vec3>         points;        ///< stage 5's
    bool movedNodes{ false };              ///< the high-quality stage moved the nodes after the faces were made
    bool removedNodes{ false };            ///< the sliver removal left nodes in no face
    std::vector<std::uint32_t> keptPoints; ///< stage 7's: the nodes left (new -> old), empty if all are

    /** The points of the final positions, or null where none were made. */
    const MeshExtraction::Vec3 *
    PhysicalPoints() const
    {
      if (movedNodes)
      {
        return nullptr;
      }
      return !checkedPoints.empty() ? checkedPoints.data() : (!points.empty() ? points.data() : nullptr);
    }
  };
  /** Output points rounded to float: what the self-intersection check must see. */
  static constexpr bool RoundsToFloat = std::is_same<typename TOutputMesh::PointType::ValueType, float>::value;

  /** Before the stages: the input and parameters checked, the inputs resampled
   * (ResampleToIsotropicVoxels); returns the Relaxation with Automatic resolved. */
  RelaxationEnum
  PrepareInputs();
  /** Stage 1's two ways: by label (the input or LabelImage), or by iso-value. Each
   * returns what it saw of the greyscale input (its NaN voxel). */
  MeshExtraction::detail::SurfaceNetsClassificationStatistics
  ClassifyCellsByLabel();
  MeshExtraction::detail::SurfaceNetsClassificationStatistics
  ClassifyCellsByIsoValue();
  /** The image index of a voxel given relative to the buffer's first voxel. */
  template <typename TImage>
  static typename TImage::IndexType
  BufferIndex(const TImage * image, const std::int64_t * local);
  /** Stage 2: the net of the surface cells. */
  void
  BuildNet();
  /** Before stage 3, in the high-quality mode on a label image (LabelSurfaceSigma > 0):
   * the smooth surface of the label's voxels (MakeLabelSurfaceFunction) on the input's
   * grid, computed near the surface cells; returns the relaxation toward it (Combined),
   * or `relaxation` unchanged where there is none. */
  RelaxationEnum
  MakeLabelSurface(RelaxationEnum relaxation);

  /** Stage 3: relax the nodes (MaximumNumberOfIterations); returns their start
   * positions where stage 4 runs (else empty). `cellCache` is kept for stage 6. */
  MeshExtraction::LargeBlockVector<MeshExtraction::Vec3>
  RelaxNodes(RelaxationEnum relaxation, MeshExtraction::detail::SurfaceNetsCellCache & cellCache);
  /** Whether stage 4 runs: PreventSelfIntersections, and the nodes were relaxed. */
  bool
  PreventsSelfIntersections(RelaxationEnum relaxation) const
  {
    return m_PreventSelfIntersections && relaxation != RelaxationEnum::None;
  }
  /** Stage 4: nodes of crossing faces moved back toward `initial`; makes the faces of
   * the final positions. */
  void
  RemoveSelfIntersections(RelaxationEnum                                                 relaxation,
                          const MeshExtraction::LargeBlockVector<MeshExtraction::Vec3> & initial,
                          Faces &                                                        faces);
  /** Stage 5: the faces by the Triangulation setting, unless stage 4 made them. */
  void
  FormFaces(Faces & faces);
  /** Stage 6 (HighQuality): the high-quality rounds on the triangles. */
  void
  RunHighQualityStage(Faces & faces, MeshExtraction::detail::SurfaceNetsCellCache & cellCache);
  /** Stage 7 (MinimumComponentVolume): small components out of the faces. */
  void
  RemoveSmallComponents(Faces & faces);
  /** After stage 7: where the sliver removal left nodes in no face and stage 7 did not
   * renumber the faces, the faces renumbered onto the nodes they use (keptPoints). */
  void
  DropUnusedNodes(Faces & faces);
  /** Stage 8's parts: the points, and the cells of an itk::Mesh. */
  void
  MakeOutputPoints(const MeshExtraction::Vec3 * points, const std::vector<std::uint32_t> * keptPoints);
  void
  MakeOutputCells(const MeshExtraction::LargeBlockVector<std::array<std::uint32_t, 4>> & polygons,
                  unsigned int                                                           polygonSize);
  /** The cells of a cells container that is a vector, made in one block (`cellType`: a
   * null pointer to the cell type). */
  template <typename TCell, typename TCellVector>
  void
  MakeBlockAllocatedCells(TCell *                                                                cellType,
                          const MeshExtraction::LargeBlockVector<std::array<std::uint32_t, 4>> & polygons,
                          TCellVector &                                                          vector);
  /** After the stages: the resampled copies of the inputs released. */
  void
  ReleaseResampledInputs();

  void
  VerifyParameters() const;
  /** Throws unless `labels` has the grid of `input` (size, spacing, origin, direction). */
  void
  VerifyLabelImageGrid(const InputImageType * input, const LabelImageType * labels) const;
  /** Makes the resampled copies of the input and LabelImage when
   * ResampleToIsotropicVoxels asks for them (and the voxels are not cubic). */
  void
  ResampleInputs();

  double            m_IsoValue{ 0.0 };
  bool              m_InsideIsAboveIsoValue{ true };
  bool              m_ClassifyByLabel{ false };
  double            m_LabelValue{ 1.0 };
  RelaxationEnum    m_Relaxation{ RelaxationEnum::Automatic };
  unsigned int      m_MaximumNumberOfIterations{ 10 };
  double            m_ConvergenceThreshold{ 1e-3 };
  double            m_SmoothingWeight{ 1.0 };
  double            m_ProjectionWeight{ 1.0 };
  bool              m_SequentialRelaxation{ false };
  GradientEnum      m_GradientMethod{ GradientEnum::CentralDifference };
  double            m_GradientSigma{ 1.0 };
  TriangulationEnum m_Triangulation{ TriangulationEnum::ShortestDiagonal };
  double            m_CellMargin{ 0.01 };
  bool              m_PreventSelfIntersections{ true };
  bool              m_HighQuality{ false };
  unsigned int      m_NumberOfHighQualityRounds{ 8 };
  double            m_ConvergedSwapFraction{ 0.001 };
  unsigned int      m_HighQualityIterations{ 4 };
  double            m_HighQualityCellDilation{ 0.5 };
  double            m_MinimumComponentVolume{ 0.0 };
  bool              m_ResampleToIsotropicVoxels{ false };
  double            m_LabelSurfaceSigma{ 2.0 };
  bool              m_HighQualitySliverRemoval{ true };
  bool              m_HighQualityRemeshing{ false };
  double            m_HighQualityTargetEdgeLength{ 0.0 };
  unsigned int      m_HighQualityRemeshingIterations{ 8 };

  using LabelSurfaceImageType = Image<float, 3>;
  LabelSurfaceImageType::Pointer m_LabelSurface; // while GenerateData runs (MakeLabelSurface)

  typename InputImageType::ConstPointer m_SampledInput;      // while GenerateData runs
  typename LabelImageType::ConstPointer m_SampledLabelImage; // idem

  unsigned int  m_NumberOfIterations{ 0 };
  double        m_LastMaximumRelocation{ 0.0 };
  SizeValueType m_NumberOfNodes{ 0 };
  SizeValueType m_NumberOfSplitCells{ 0 };
  SizeValueType m_NumberOfNodesMovedBack{ 0 };
  SizeValueType m_NumberOfComponentsRemoved{ 0 };
  SizeValueType m_NumberOfFacesRemoved{ 0 };
  SizeValueType m_NumberOfSwaps{ 0 };
  unsigned int  m_NumberOfRoundsPerformed{ 0 };
  SizeValueType m_NumberOfCollapses{ 0 };
  SizeValueType m_NumberOfSliverSwaps{ 0 };
  SizeValueType m_NumberOfSliverMoves{ 0 };
  SizeValueType m_NumberOfSplits{ 0 };
  SizeValueType m_NumberOfRemeshingCollapses{ 0 };
  SizeValueType m_NumberOfRemeshingSwaps{ 0 };
  unsigned int  m_NumberOfRemeshingRounds{ 0 };

  MeshExtraction::SurfaceNet m_Net;
};
} // namespace itk

#ifndef ITK_MANUAL_INSTANTIATION
#  include "itkSurfaceNetsImageToMeshFilter.hxx"
#endif

#endif
