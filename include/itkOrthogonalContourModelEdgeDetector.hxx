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
#ifndef itkOrthogonalContourModelEdgeDetector_hxx
#define itkOrthogonalContourModelEdgeDetector_hxx

#include <algorithm>
#include <cmath>
#include <limits>

namespace itk
{
template <typename TImage>
void
OrthogonalContourModelEdgeDetector<TImage>::CheckInputs() const
{
  if (m_Image.IsNull() || m_Model.IsNull())
  {
    itkExceptionMacro(<< "Both an image (SetImage) and a model (SetModel) are needed");
  }
  if (!(m_CaptureRange > 0.0) || !std::isfinite(m_CaptureRange) || !(m_MinimumScale >= 0.0) || m_ScalesPerOctave < 1)
  {
    itkExceptionMacro(<< "CaptureRange must be > 0 mm (got " << m_CaptureRange << "), MinimumScale >= 0 (got "
                      << m_MinimumScale << ") and ScalesPerOctave >= 1 (got " << m_ScalesPerOctave << ")");
  }
  if (m_Image->GetBufferedRegion() != m_Image->GetLargestPossibleRegion() ||
      m_Image->GetLargestPossibleRegion().GetIndex() != typename ImageType::IndexType{ { 0, 0, 0 } })
  {
    itkExceptionMacro(<< "The image must be buffered whole, starting at index 0 (call Update() on its source)");
  }
  constexpr double tolerance = 1e-6;
  bool             same = m_Image->GetLargestPossibleRegion().GetSize() == m_Model->GetSize();
  for (unsigned int i = 0; i < 3; ++i)
  {
    same =
      same && std::abs(m_Image->GetSpacing()[i] - m_Model->GetSpacing()[i]) <= tolerance * m_Image->GetSpacing()[i];
    same = same && std::abs(m_Image->GetOrigin()[i] - m_Model->GetOrigin()[i]) <=
                     tolerance * (1.0 + std::abs(m_Image->GetOrigin()[i]));
    for (unsigned int j = 0; j < 3; ++j)
    {
      same = same && std::abs(m_Image->GetDirection()(i, j) - m_Model->GetDirection()(i, j)) <= tolerance;
    }
  }
  if (!same)
  {
    itkExceptionMacro(<< "The model's grid is not the image's (size, spacing, origin and direction must match): call "
                         "SetGrid(image) on the model");
  }
}

template <typename TImage>
void
OrthogonalContourModelEdgeDetector<TImage>::PrepareScaleSpace(const IdentifierListType & points)
{
  this->CheckInputs();
  const auto & spacing = m_Image->GetSpacing();
  const double smallest = std::min({ spacing[0], spacing[1], spacing[2] });
  m_Scales = MeshExtraction::detail::ScaleSpaceScales(
    m_CaptureRange, m_MinimumScale > 0.0 ? m_MinimumScale : smallest, m_ScalesPerOctave);
  MeshExtraction::Vec3 lower(std::numeric_limits<double>::infinity());
  MeshExtraction::Vec3 upper(-std::numeric_limits<double>::infinity());
  for (const auto p : points)
  {
    const auto x = m_Model->GetControlPointIndex(p);
    for (unsigned int d = 0; d < 3; ++d)
    {
      lower[d] = std::min(lower[d], x[d] - m_CaptureRange / spacing[d]);
      upper[d] = std::max(upper[d], x[d] + m_CaptureRange / spacing[d]);
    }
  }
  if (!points.empty())
  {
    m_ScaleSpace.Prepare(m_Image.GetPointer(), m_Scales, lower, upper);
  }
}

template <typename TImage>
double
OrthogonalContourModelEdgeDetector<TImage>::SearchEdge(unsigned int p) const
{
  const unsigned int   axis = m_Model->GetControlPointLineAxis(p);
  const auto           x = m_Model->GetControlPointIndex(p);
  const auto           point = m_Model->GetControlPoint(p);
  MeshExtraction::Vec3 physical;
  MeshExtraction::Vec3 direction;
  for (unsigned int i = 0; i < 3; ++i)
  {
    physical[i] = point[i];
    direction[i] = m_Image->GetDirection()(i, axis);
  }
  const MeshExtraction::Vec3 origin = m_ScaleSpace.ToRegionIndex(physical);
  const MeshExtraction::Vec3 step = m_ScaleSpace.ToRegionIndexDirection(direction);
  const double               offset = MeshExtraction::detail::SearchEdgeAlongLine(
    m_Scales,
    m_CaptureRange,
    [&](std::size_t k, double t) { return m_ScaleSpace.GradientMagnitude(k, origin + step * t); },
    true);
  const auto range = m_Model->GetControlPointRange(p);
  return std::clamp(x[axis] + offset / m_Image->GetSpacing()[axis], range[0], range[1]);
}

template <typename TImage>
double
OrthogonalContourModelEdgeDetector<TImage>::FindEdge(unsigned int p)
{
  this->PrepareScaleSpace({ p });
  return this->SearchEdge(p);
}

template <typename TImage>
unsigned int
OrthogonalContourModelEdgeDetector<TImage>::MoveControlPoints(const IdentifierListType & points)
{
  this->PrepareScaleSpace(points);
  // All targets first; a move that adds or removes a contour renumbers the points, so
  // each is found again by its position (no two control points share one).
  std::vector<typename ModelType::ContinuousIndexType> starts;
  std::vector<double>                                  targets;
  for (const auto p : points)
  {
    starts.push_back(m_Model->GetControlPointIndex(p));
    targets.push_back(this->SearchEdge(p));
  }
  m_NumberOfRefusedMoves = 0;
  m_DistanceTravelled = 0.0;
  unsigned int moved = 0;
  for (std::size_t i = 0; i < starts.size(); ++i)
  {
    for (unsigned int p = 0; p < m_Model->GetNumberOfControlPoints(); ++p)
    {
      if (m_Model->GetControlPointIndex(p) != starts[i])
      {
        continue;
      }
      const double from = starts[i][m_Model->GetControlPointLineAxis(p)];
      if (targets[i] != from)
      {
        const bool accepted = m_Model->MoveControlPoint(p, targets[i]);
        moved += accepted ? 1 : 0;
        m_NumberOfRefusedMoves += accepted ? 0 : 1;
        m_DistanceTravelled += accepted ? std::abs(targets[i] - from) : 0.0;
      }
      break;
    }
  }
  return moved;
}

template <typename TImage>
unsigned int
OrthogonalContourModelEdgeDetector<TImage>::MoveControlPointsInPlane(unsigned int axis, IndexValueType position)
{
  this->CheckInputs();
  return this->MoveControlPoints(m_Model->GetControlPointsInPlane(axis, position));
}

template <typename TImage>
unsigned int
OrthogonalContourModelEdgeDetector<TImage>::MoveAllControlPoints()
{
  this->CheckInputs();
  IdentifierListType points(m_Model->GetNumberOfControlPoints());
  for (unsigned int p = 0; p < points.size(); ++p)
  {
    points[p] = p;
  }
  return this->MoveControlPoints(points);
}

template <typename TImage>
void
OrthogonalContourModelEdgeDetector<TImage>::PrintSelf(std::ostream & os, Indent indent) const
{
  Superclass::PrintSelf(os, indent);
  os << indent << "CaptureRange: " << m_CaptureRange << '\n';
  os << indent << "MinimumScale: " << m_MinimumScale << '\n';
  os << indent << "ScalesPerOctave: " << m_ScalesPerOctave << '\n';
  os << indent << "NumberOfRefusedMoves: " << m_NumberOfRefusedMoves << '\n';
  os << indent << "DistanceTravelled: " << m_DistanceTravelled << '\n';
}
} // namespace itk

#endif
