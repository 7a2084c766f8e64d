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
#ifndef itkMultiLabelSurfaceNetsImageToMeshFilter_hxx
#define itkMultiLabelSurfaceNetsImageToMeshFilter_hxx

#include "itkMeshExtractionIndexedTriangleMesh.h"
#include "itkMeshExtractionParallel.h"

#include <algorithm>
#include <limits>
#include <unordered_set>

namespace itk
{
template <typename TLabelImage, typename TOutputMesh>
MultiLabelSurfaceNetsImageToMeshFilter<TLabelImage, TOutputMesh>::MultiLabelSurfaceNetsImageToMeshFilter()
{
  static_assert(!MeshExtraction::detail::IsQuadEdgeMesh<TOutputMesh>::value,
                "The output holds the faces of three or more labels on one edge: an itk::Mesh, not a QuadEdgeMesh "
                "(GetLabelSurface() gives each label's 2-manifold surface).");
}

template <typename TLabelImage, typename TOutputMesh>
void
MultiLabelSurfaceNetsImageToMeshFilter<TLabelImage, TOutputMesh>::SetLabels(const LabelListType & labels)
{
  if (labels != m_Labels)
  {
    m_Labels = labels;
    this->Modified();
  }
}

template <typename TLabelImage, typename TOutputMesh>
std::uint32_t
MultiLabelSurfaceNetsImageToMeshFilter<TLabelImage, TOutputMesh>::IndexOfLabel(LabelPixelType label) const
{
  const auto found = std::lower_bound(m_ExtractedLabels.begin(), m_ExtractedLabels.end(), label);
  if (found == m_ExtractedLabels.end() || *found != label)
  {
    return 0;
  }
  return static_cast<std::uint32_t>(found - m_ExtractedLabels.begin()) + 1;
}

template <typename TLabelImage, typename TOutputMesh>
std::vector<std::uint32_t>
MultiLabelSurfaceNetsImageToMeshFilter<TLabelImage, TOutputMesh>::IndexLabels(const LabelImageType * input)
{
  const std::size_t      n = input->GetBufferedRegion().GetNumberOfPixels();
  const LabelPixelType * buffer = input->GetBufferPointer();
  m_ExtractedLabels = m_Labels;
  if (m_ExtractedLabels.empty())
  {
    std::unordered_set<LabelPixelType> seen;
    LabelPixelType                     last = m_BackgroundValue;
    for (std::size_t i = 0; i < n; ++i)
    {
      if (buffer[i] != last)
      {
        last = buffer[i];
        if (last != m_BackgroundValue)
        {
          seen.insert(last);
        }
      }
    }
    m_ExtractedLabels.assign(seen.begin(), seen.end());
    if (m_ExtractedLabels.empty())
    {
      itkExceptionMacro("The label image has no voxel other than the background value "
                        << static_cast<double>(m_BackgroundValue) << ": there is no surface.");
    }
  }
  std::sort(m_ExtractedLabels.begin(), m_ExtractedLabels.end());
  m_ExtractedLabels.erase(std::unique(m_ExtractedLabels.begin(), m_ExtractedLabels.end()), m_ExtractedLabels.end());
  if (std::binary_search(m_ExtractedLabels.begin(), m_ExtractedLabels.end(), m_BackgroundValue))
  {
    itkExceptionMacro("The label " << static_cast<double>(m_BackgroundValue)
                                   << " is the background value; it has no surface of its own.");
  }
  std::vector<std::uint32_t> indices(n);
  std::vector<std::size_t>   counts(m_ExtractedLabels.size() + 1, 0);
  LabelPixelType             last = m_BackgroundValue;
  std::uint32_t              lastIndex = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    if (buffer[i] != last)
    {
      last = buffer[i];
      lastIndex = last == m_BackgroundValue ? 0 : this->IndexOfLabel(last);
    }
    indices[i] = lastIndex;
    ++counts[lastIndex];
  }
  for (std::size_t k = 0; k < m_ExtractedLabels.size(); ++k)
  {
    if (counts[k + 1] == 0)
    {
      itkExceptionMacro("No voxel has the label " << static_cast<double>(m_ExtractedLabels[k]) << '.');
    }
  }
  return indices;
}

template <typename TLabelImage, typename TOutputMesh>
void
MultiLabelSurfaceNetsImageToMeshFilter<TLabelImage, TOutputMesh>::GenerateData()
{
  namespace ME = MeshExtraction;
  const LabelImageType * input = this->GetInput();
  if (input == nullptr)
  {
    itkExceptionMacro("No input image: call SetInput() first.");
  }
  const auto region = input->GetBufferedRegion();
  if (region.GetNumberOfPixels() == 0)
  {
    itkExceptionMacro("The input image has no voxels (its size is " << region.GetSize() << ").");
  }
  if (!(m_CellMargin >= 0.0 && m_CellMargin < 0.5))
  {
    itkExceptionMacro("CellMargin must be in [0, 0.5), got " << m_CellMargin << '.');
  }
  if (!(m_ConvergenceThreshold >= 0.0))
  {
    itkExceptionMacro("ConvergenceThreshold must be >= 0, got " << m_ConvergenceThreshold << '.');
  }
  if (m_Triangulation == TriangulationEnum::Quadrilaterals)
  {
    itkExceptionMacro("Triangulation Quadrilaterals is not supported here: ShortestDiagonal or Delaunay.");
  }
  const ME::detail::ScopedNumberOfWorkUnits workUnits(this->GetNumberOfWorkUnits());
  this->UpdateProgress(0.0f);
  const std::vector<std::uint32_t> indices = this->IndexLabels(input);
  this->UpdateProgress(0.1f);

  ME::detail::MultiLabelSurfaceNetParameters p;
  p.maximumNumberOfIterations = m_MaximumNumberOfIterations;
  p.convergenceThreshold = m_ConvergenceThreshold;
  p.cellMargin = m_CellMargin;
  p.split = m_Triangulation == TriangulationEnum::Delaunay ? ME::detail::QuadSplit::Delaunay
                                                           : ME::detail::QuadSplit::ShortestDiagonal;
  using CoordinateType = typename OutputMeshType::PointType::ValueType;
  p.roundToFloat = std::is_same<CoordinateType, float>::value;
  p.numberOfWorkUnits = this->GetNumberOfWorkUnits();
  typename LabelImageType::PointType first;
  input->TransformIndexToPhysicalPoint(region.GetIndex(), first);
  p.origin = ME::MakeVec3(first[0], first[1], first[2]);
  for (unsigned int r = 0; r < 3; ++r)
  {
    for (unsigned int c = 0; c < 3; ++c)
    {
      p.indexToPhysical[r][c] = input->GetDirection()[r][c] * input->GetSpacing()[c];
    }
  }
  const std::array<std::int64_t, 3> size{ { static_cast<std::int64_t>(region.GetSize(0)),
                                            static_cast<std::int64_t>(region.GetSize(1)),
                                            static_cast<std::int64_t>(region.GetSize(2)) } };
  m_Net =
    ME::detail::MakeMultiLabelSurfaceNet(indices.data(), size, static_cast<std::uint32_t>(m_ExtractedLabels.size()), p);
  this->UpdateProgress(0.9f);

  m_NumberOfJunctionNodes = m_Net.numberOfJunctionNodes;
  m_NumberOfFixedNodes = m_Net.numberOfFixedNodes;
  m_NumberOfPinchedNodes = m_Net.numberOfPinchedNodes;
  m_NumberOfNodesMovedBack = m_Net.numberOfNodesMovedBack;
  m_NumberOfIterations = m_Net.iterations;
  m_FaceLabels.resize(m_Net.faceLabels.size());
  for (std::size_t f = 0; f < m_FaceLabels.size(); ++f)
  {
    for (unsigned int s = 0; s < 2; ++s)
    {
      const std::uint32_t k = m_Net.faceLabels[f][s];
      m_FaceLabels[f][s] = k == 0 ? m_BackgroundValue : m_ExtractedLabels[k - 1];
    }
  }
  ME::IndexedTriangleMesh all;
  all.points = m_Net.points;
  all.triangles = m_Net.triangles;
  OutputMeshType * output = this->GetOutput();
  output->Initialize();
  ME::FillMesh(all, *output);
  this->UpdateProgress(1.0f);
}

template <typename TLabelImage, typename TOutputMesh>
auto
MultiLabelSurfaceNetsImageToMeshFilter<TLabelImage, TOutputMesh>::GetFaceLabel(IdentifierType face,
                                                                               unsigned int   side) const
  -> LabelPixelType
{
  if (face >= m_FaceLabels.size() || side > 1)
  {
    itkExceptionMacro("No face " << face << " side " << side << " (the output has " << m_FaceLabels.size()
                                 << " faces, sides 0 and 1).");
  }
  return m_FaceLabels[face][side];
}

template <typename TLabelImage, typename TOutputMesh>
auto
MultiLabelSurfaceNetsImageToMeshFilter<TLabelImage, TOutputMesh>::GetLabelSurface(LabelPixelType label) const
  -> OutputMeshPointer
{
  const std::uint32_t k = this->IndexOfLabel(label);
  if (k == 0 || k > m_Net.numberOfLabels)
  {
    itkExceptionMacro("The label " << static_cast<double>(label)
                                   << " was not extracted (call Update() first; GetExtractedLabels() lists them).");
  }
  MeshExtraction::IndexedTriangleMesh surface;
  m_Net.LabelSurface(k, surface.points, surface.triangles);
  auto mesh = OutputMeshType::New();
  MeshExtraction::FillMesh(surface, *mesh);
  return mesh;
}

template <typename TLabelImage, typename TOutputMesh>
void
MultiLabelSurfaceNetsImageToMeshFilter<TLabelImage, TOutputMesh>::PrintSelf(std::ostream & os, Indent indent) const
{
  Superclass::PrintSelf(os, indent);
  os << indent << "Labels: " << m_Labels.size() << (m_Labels.empty() ? " (every label)" : "") << '\n';
  os << indent << "BackgroundValue: " << static_cast<double>(m_BackgroundValue) << '\n';
  os << indent << "MaximumNumberOfIterations: " << m_MaximumNumberOfIterations << '\n';
  os << indent << "ConvergenceThreshold: " << m_ConvergenceThreshold << '\n';
  os << indent << "CellMargin: " << m_CellMargin << '\n';
  os << indent << "Triangulation: " << m_Triangulation << '\n';
  os << indent << "NumberOfJunctionNodes: " << m_NumberOfJunctionNodes << '\n';
  os << indent << "NumberOfPinchedNodes: " << m_NumberOfPinchedNodes << '\n';
  os << indent << "NumberOfNodesMovedBack: " << m_NumberOfNodesMovedBack << '\n';
}
} // namespace itk

#endif
