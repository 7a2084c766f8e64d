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
#ifndef itkMultiLabelSurfaceNetsImageToMeshFilter_h
#define itkMultiLabelSurfaceNetsImageToMeshFilter_h

#include "itkImage.h"
#include "itkImageToMeshFilter.h"
#include "itkMesh.h"
#include "itkMeshExtractionMacros.h"
#include "itkMeshExtractionMultiLabelSurfaceNet.h"
#include "itkSurfaceNetsImageToMeshFilterEnums.h"

#include <array>
#include <type_traits>
#include <vector>

namespace itk
{
/** \class MultiLabelSurfaceNetsImageToMeshFilter
 * \brief The surfaces of every label of a label map in one pass, neighbours sharing
 * their boundary: one copy of each face between two labels (SurfaceNets with SNA,
 * thesis 3.2, extended to many labels).
 *
 * The input is a label image of an integer pixel type. The labels are those given
 * with SetLabels(), or every value but BackgroundValue; voxels of other values count
 * as background, as does everything outside the image.
 *
 * Each label has the topology of its own binary SurfaceNet, so GetLabelSurface(label)
 * is a closed, oriented (outward) 2-manifold, as SurfaceNetsImageToMeshFilter's
 * surface of that label alone, with one difference: where two of a label's voxels meet
 * only across a face diagonal and the other diagonal holds two different labels (or a
 * label and the background), the label is joined across the face (alone it is not:
 * 6-connected objects); in a checkerboard of two labels on a face the lower label
 * joins. Where the sheets of two labels share a crossing voxel
 * edge in a cell they share the node, so the face between two labels is the same
 * triangles in both surfaces: neighbours are watertight against each other by
 * construction, without gaps or overlaps. Nodes are relaxed as by SNA (each to the
 * average of its neighbours, in its cell shrunk by CellMargin); a node on a voxel
 * edge of three or more labels (a junction) averages only its neighbours on the same
 * junction line, and stays where junction lines meet or end; a cell with several
 * nodes keeps them at the centres of their crossing edges. Faces that would cross
 * after the relaxation have their nodes moved back, as in the single-label filter.
 *
 * The output is one mesh with every face once; it is not a 2-manifold where three or
 * more labels meet (an edge of a junction line has a face to each pair of them).
 * GetFaceLabels() gives each face's two labels, the lower first, and the face's
 * normal points out of the lower label into the higher; the background counts as the
 * lowest. Where a label still touches itself (the higher label of a checkerboard of
 * two: its two sheets share a node), its own surface has two vertices there, moved a
 * fiftieth of the way from the node toward their sheets, so that it stays a valid
 * 2-manifold; the faces at such a node differ from the neighbour's copies by that
 * much (GetNumberOfPinchedNodes() counts these nodes; the output has one copy).
 *
 * Points are in physical coordinates (origin, spacing and direction of the input).
 * An empty image, an image with no label voxel, a listed label with no voxel, or a
 * listed label equal to the background is an itk::ExceptionObject.
 * \ingroup MeshExtraction
 */
template <typename TLabelImage, typename TOutputMesh = Mesh<double, TLabelImage::ImageDimension>>
class ITK_TEMPLATE_EXPORT MultiLabelSurfaceNetsImageToMeshFilter : public ImageToMeshFilter<TLabelImage, TOutputMesh>
{
public:
  ITK_DISALLOW_COPY_AND_MOVE(MultiLabelSurfaceNetsImageToMeshFilter);

  using Self = MultiLabelSurfaceNetsImageToMeshFilter;
  using Superclass = ImageToMeshFilter<TLabelImage, TOutputMesh>;
  using Pointer = SmartPointer<Self>;
  using ConstPointer = SmartPointer<const Self>;

  itkNewMacro(Self);
  itkOverrideGetNameOfClassMacro(MultiLabelSurfaceNetsImageToMeshFilter);

  static constexpr unsigned int ImageDimension = TLabelImage::ImageDimension;
  static_assert(ImageDimension == 3, "MultiLabelSurfaceNetsImageToMeshFilter extracts surfaces from 3-D images.");

  using LabelImageType = TLabelImage;
  using LabelPixelType = typename LabelImageType::PixelType;
  static_assert(std::is_integral<LabelPixelType>::value, "The label image must have an integer pixel type.");
  using OutputMeshType = TOutputMesh;
  using OutputMeshPointer = typename OutputMeshType::Pointer;
  using LabelListType = std::vector<LabelPixelType>;
  using FaceLabelsType = std::array<LabelPixelType, 2>;
  using TriangulationEnum = SurfaceNetsImageToMeshFilterEnums::Triangulation;

  /** The labels to extract; empty (the default): every value but BackgroundValue. */
  void
  SetLabels(const LabelListType & labels);
  const LabelListType &
  GetLabels() const
  {
    return m_Labels;
  }
  /** The background value (default 0). */
  itkSetMacro(BackgroundValue, LabelPixelType);
  itkGetConstMacro(BackgroundValue, LabelPixelType);
  /** SNA iterations (default 10, as SurfaceNetsImageToMeshFilter); 0 leaves the nodes
   * at their cell centres. */
  itkSetMacro(MaximumNumberOfIterations, unsigned int);
  itkGetConstMacro(MaximumNumberOfIterations, unsigned int);
  /** The largest relocation (voxels) that ends the iterations (default 1e-3). */
  itkSetMacro(ConvergenceThreshold, double);
  itkGetConstMacro(ConvergenceThreshold, double);
  /** How far (voxels, in [0, 0.5)) a node keeps from its cell's faces (default 0.01). */
  itkSetMacro(CellMargin, double);
  itkGetConstMacro(CellMargin, double);
  /** How quads become triangles: ShortestDiagonal (default) or Delaunay. */
  itkSetEnumMacro(Triangulation, TriangulationEnum);
  itkGetEnumMacro(Triangulation, TriangulationEnum);

  /** After Update(): the labels extracted, in increasing order. */
  const LabelListType &
  GetExtractedLabels() const
  {
    return m_ExtractedLabels;
  }
  /** After Update(): the two labels of every face of the output (lower first; the
   * background value for the outside of a label). */
  const std::vector<FaceLabelsType> &
  GetFaceLabels() const
  {
    return m_FaceLabels;
  }
  /** The same for one face: side 0 the lower label, 1 the higher. */
  LabelPixelType
  GetFaceLabel(IdentifierType face, unsigned int side) const;
  /** After Update(): the closed surface of one of the extracted labels, outward, in a
   * new mesh. */
  OutputMeshPointer
  GetLabelSurface(LabelPixelType label) const;

  /** After Update(): what the pass did. */
  itkGetConstMacro(NumberOfJunctionNodes, SizeValueType);
  itkGetConstMacro(NumberOfFixedNodes, SizeValueType);
  itkGetConstMacro(NumberOfPinchedNodes, SizeValueType);
  itkGetConstMacro(NumberOfNodesMovedBack, SizeValueType);
  itkGetConstMacro(NumberOfIterations, unsigned int);

protected:
  MultiLabelSurfaceNetsImageToMeshFilter();
  ~MultiLabelSurfaceNetsImageToMeshFilter() override = default;

  void
  GenerateData() override;
  void
  GenerateOutputInformation() override
  {}
  void
  PrintSelf(std::ostream & os, Indent indent) const override;

private:
  /** The index of each voxel's label (0 for the background) and the labels. */
  std::vector<std::uint32_t>
  IndexLabels(const LabelImageType * input);
  std::uint32_t
  IndexOfLabel(LabelPixelType label) const;

  LabelListType     m_Labels;
  LabelPixelType    m_BackgroundValue{ 0 };
  unsigned int      m_MaximumNumberOfIterations{ 10 };
  double            m_ConvergenceThreshold{ 1e-3 };
  double            m_CellMargin{ 0.01 };
  TriangulationEnum m_Triangulation{ TriangulationEnum::ShortestDiagonal };

  LabelListType                        m_ExtractedLabels;
  std::vector<FaceLabelsType>          m_FaceLabels;
  MeshExtraction::MultiLabelSurfaceNet m_Net;
  SizeValueType                        m_NumberOfJunctionNodes{ 0 };
  SizeValueType                        m_NumberOfFixedNodes{ 0 };
  SizeValueType                        m_NumberOfPinchedNodes{ 0 };
  SizeValueType                        m_NumberOfNodesMovedBack{ 0 };
  unsigned int                         m_NumberOfIterations{ 0 };
};
} // namespace itk

#ifndef ITK_MANUAL_INSTANTIATION
#  include "itkMultiLabelSurfaceNetsImageToMeshFilter.hxx"
#endif

#endif
