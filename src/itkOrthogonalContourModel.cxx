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
#include "itkOrthogonalContourModel.h"

#include <fstream>
#include <iterator>
#include <sstream>

namespace itk
{
namespace
{
const char * const AxisNames[3] = { "x", "y", "z" };
} // namespace

std::ostream &
operator<<(std::ostream & out, OrthogonalContourModelEnums::Interpolation value)
{
  switch (value)
  {
    case OrthogonalContourModelEnums::Interpolation::Linear:
      return out << "itk::OrthogonalContourModelEnums::Interpolation::Linear";
    case OrthogonalContourModelEnums::Interpolation::CatmullRom:
      return out << "itk::OrthogonalContourModelEnums::Interpolation::CatmullRom";
  }
  return out << "INVALID VALUE FOR itk::OrthogonalContourModelEnums::Interpolation";
}

void
OrthogonalContourModel::SetGrid(const ImageBase<3> * image)
{
  if (image == nullptr)
  {
    itkExceptionMacro(<< "SetGrid: the image is null");
  }
  const auto region = image->GetLargestPossibleRegion();
  for (unsigned int a = 0; a < 3; ++a)
  {
    if (region.GetIndex(a) != 0)
    {
      itkExceptionMacro(<< "SetGrid: the image's largest possible region starts at " << region.GetIndex()
                        << ", not at index 0");
    }
  }
  this->SetGrid(region.GetSize(), image->GetSpacing(), image->GetOrigin(), image->GetDirection());
}

void
OrthogonalContourModel::SetGrid(const SizeType &      size,
                                const SpacingType &   spacing,
                                const PointType &     origin,
                                const DirectionType & direction)
{
  MeshExtraction::detail::ContourGrid grid;
  for (unsigned int i = 0; i < 3; ++i)
  {
    grid.size[i] = static_cast<std::int64_t>(size[i]);
    grid.spacing[i] = spacing[i];
    grid.origin[i] = origin[i];
    for (unsigned int j = 0; j < 3; ++j)
    {
      grid.direction[3 * i + j] = direction(i, j);
    }
  }
  const std::string problem = MeshExtraction::detail::DescribeInvalidGrid(grid);
  if (!problem.empty())
  {
    itkExceptionMacro(<< "SetGrid: " << problem);
  }
  m_Network.grid = grid;
  m_Network.points.clear();
  m_Network.contours.clear();
  m_RefusalReason.clear();
  this->Modified();
}

OrthogonalContourModel::SizeType
OrthogonalContourModel::GetSize() const
{
  SizeType size;
  for (unsigned int i = 0; i < 3; ++i)
  {
    size[i] = static_cast<SizeValueType>(m_Network.grid.size[i]);
  }
  return size;
}

OrthogonalContourModel::SpacingType
OrthogonalContourModel::GetSpacing() const
{
  SpacingType spacing;
  for (unsigned int i = 0; i < 3; ++i)
  {
    spacing[i] = m_Network.grid.spacing[i];
  }
  return spacing;
}

OrthogonalContourModel::PointType
OrthogonalContourModel::GetOrigin() const
{
  PointType origin;
  for (unsigned int i = 0; i < 3; ++i)
  {
    origin[i] = m_Network.grid.origin[i];
  }
  return origin;
}

OrthogonalContourModel::DirectionType
OrthogonalContourModel::GetDirection() const
{
  DirectionType direction;
  for (unsigned int i = 0; i < 3; ++i)
  {
    for (unsigned int j = 0; j < 3; ++j)
    {
      direction(i, j) = m_Network.grid.direction[3 * i + j];
    }
  }
  return direction;
}

void
OrthogonalContourModel::InitializeTemplate(const IndexType & center, const RadiiType & radii)
{
  MeshExtraction::detail::ContourNetwork network;
  const std::string                      problem = MeshExtraction::detail::MakeTemplateNetwork(m_Network.grid,
                                                                          { { center[0], center[1], center[2] } },
                                                                          { { radii[0], radii[1], radii[2] } },
                                                                          m_Network.interpolation,
                                                                          network);
  if (!problem.empty())
  {
    itkExceptionMacro(<< "InitializeTemplate: " << problem);
  }
  m_Network = std::move(network);
  m_RefusalReason.clear();
  this->Modified();
}

bool
OrthogonalContourModel::SetInterpolation(InterpolationEnum interpolation)
{
  if (interpolation == m_Network.interpolation)
  {
    return this->Finish(std::string());
  }
  NetworkType candidate = m_Network;
  candidate.interpolation = interpolation;
  const std::string problem =
    candidate.points.empty() ? std::string() : MeshExtraction::detail::CheckContourNetwork(candidate);
  if (problem.empty())
  {
    m_Network = std::move(candidate);
  }
  return this->Finish(problem.empty() ? problem : "the interpolation cannot change: " + problem);
}

void
OrthogonalContourModel::CheckControlPoint(unsigned int p) const
{
  if (p >= m_Network.points.size())
  {
    itkExceptionMacro(<< "There is no control point " << p << " (the model has " << m_Network.points.size() << ")");
  }
}

void
OrthogonalContourModel::CheckContour(unsigned int c) const
{
  if (c >= m_Network.contours.size())
  {
    itkExceptionMacro(<< "There is no contour " << c << " (the model has " << m_Network.contours.size() << ")");
  }
}

unsigned int
OrthogonalContourModel::GetContourAxis(unsigned int c) const
{
  this->CheckContour(c);
  return m_Network.contours[c].axis;
}

IndexValueType
OrthogonalContourModel::GetContourPosition(unsigned int c) const
{
  this->CheckContour(c);
  return static_cast<IndexValueType>(m_Network.contours[c].position);
}

OrthogonalContourModel::IdentifierListType
OrthogonalContourModel::GetContourControlPoints(unsigned int c) const
{
  this->CheckContour(c);
  const auto & list = m_Network.contours[c].points;
  return IdentifierListType(list.begin(), list.end());
}

OrthogonalContourModel::ContinuousIndexType
OrthogonalContourModel::GetControlPointIndex(unsigned int p) const
{
  this->CheckControlPoint(p);
  ContinuousIndexType index;
  for (unsigned int i = 0; i < 3; ++i)
  {
    index[i] = m_Network.points[p].x[i];
  }
  return index;
}

OrthogonalContourModel::PointType
OrthogonalContourModel::GetControlPoint(unsigned int p) const
{
  this->CheckControlPoint(p);
  const MeshExtraction::Vec3 x = MeshExtraction::detail::GridToPhysical(m_Network.grid, m_Network.points[p].x);
  PointType                  point;
  for (unsigned int i = 0; i < 3; ++i)
  {
    point[i] = x[i];
  }
  return point;
}

unsigned int
OrthogonalContourModel::GetControlPointLineAxis(unsigned int p) const
{
  this->CheckControlPoint(p);
  return MeshExtraction::detail::LineAxis(m_Network, p);
}

FixedArray<unsigned int, 2>
OrthogonalContourModel::GetControlPointContours(unsigned int p) const
{
  this->CheckControlPoint(p);
  FixedArray<unsigned int, 2> contours;
  contours[0] = m_Network.points[p].contours[0];
  contours[1] = m_Network.points[p].contours[1];
  return contours;
}

FixedArray<unsigned int, 4>
OrthogonalContourModel::GetControlPointNeighbours(unsigned int p) const
{
  this->CheckControlPoint(p);
  MeshExtraction::detail::ContourAdjacency adjacency;
  MeshExtraction::detail::BuildContourAdjacency(m_Network, adjacency);
  const auto                  n = adjacency.Neighbours(m_Network, p);
  FixedArray<unsigned int, 4> result;
  for (unsigned int i = 0; i < 4; ++i)
  {
    result[i] = n[i];
  }
  return result;
}

FixedArray<double, 2>
OrthogonalContourModel::GetControlPointRange(unsigned int p) const
{
  this->CheckControlPoint(p);
  const auto            range = MeshExtraction::detail::ControlPointRange(m_Network, p);
  FixedArray<double, 2> result;
  result[0] = range[0];
  result[1] = range[1];
  return result;
}

OrthogonalContourModel::IdentifierListType
OrthogonalContourModel::GetContoursInPlane(unsigned int axis, IndexValueType position) const
{
  IdentifierListType result;
  for (unsigned int c = 0; c < m_Network.contours.size(); ++c)
  {
    if (m_Network.contours[c].axis == axis && m_Network.contours[c].position == position)
    {
      result.push_back(c);
    }
  }
  return result;
}

OrthogonalContourModel::IdentifierListType
OrthogonalContourModel::GetControlPointsInPlane(unsigned int axis, IndexValueType position) const
{
  IdentifierListType result;
  for (const auto c : this->GetContoursInPlane(axis, position))
  {
    const auto & list = m_Network.contours[c].points;
    result.insert(result.end(), list.begin(), list.end());
  }
  return result;
}

std::vector<OrthogonalContourModel::ContinuousIndexType>
OrthogonalContourModel::GetPlaneIntersections(unsigned int axis, double position) const
{
  std::vector<ContinuousIndexType> result;
  if (axis > 2 || m_Network.points.empty())
  {
    return result;
  }
  for (const auto & x : MeshExtraction::detail::ContourPlaneIntersections(m_Network, axis, position))
  {
    ContinuousIndexType index;
    for (unsigned int i = 0; i < 3; ++i)
    {
      index[i] = x[i];
    }
    result.push_back(index);
  }
  return result;
}

bool
OrthogonalContourModel::Finish(const std::string & refusal)
{
  m_RefusalReason = refusal;
  if (refusal.empty())
  {
    this->Modified();
  }
  return refusal.empty();
}

bool
OrthogonalContourModel::MoveControlPoint(unsigned int p, double coordinate)
{
  return this->Finish(MeshExtraction::detail::MoveContourControlPoint(m_Network, p, coordinate));
}

bool
OrthogonalContourModel::AddContour(unsigned int axis, IndexValueType position)
{
  if (m_Network.points.empty())
  {
    return this->Finish("no contour can be added: the model is empty (InitializeTemplate first)");
  }
  return this->Finish(MeshExtraction::detail::AddContourPlane(m_Network, axis, position));
}

bool
OrthogonalContourModel::RemoveContour(unsigned int c)
{
  if (c >= m_Network.contours.size())
  {
    std::ostringstream s;
    s << "contour " << c << " cannot be removed: there is no such contour";
    return this->Finish(s.str());
  }
  return this->RemoveContourPlane(m_Network.contours[c].axis, m_Network.contours[c].position);
}

bool
OrthogonalContourModel::RemoveContourPlane(unsigned int axis, IndexValueType position)
{
  return this->Finish(MeshExtraction::detail::RemoveContourPlane(m_Network, axis, position));
}

std::string
OrthogonalContourModel::CheckInvariants() const
{
  if (m_Network.points.empty() && m_Network.contours.empty())
  {
    return "the model is empty (InitializeTemplate first)";
  }
  return MeshExtraction::detail::CheckContourNetwork(m_Network);
}

std::vector<OrthogonalContourModel::IndexType>
OrthogonalContourModel::GetScanConversion(unsigned int c) const
{
  this->CheckContour(c);
  std::vector<IndexType> result;
  for (const auto & v : MeshExtraction::detail::ScanConvertContour(m_Network, c))
  {
    IndexType index;
    for (unsigned int i = 0; i < 3; ++i)
    {
      index[i] = static_cast<IndexValueType>(v[i]);
    }
    result.push_back(index);
  }
  return result;
}

std::vector<OrthogonalContourModel::ContinuousIndexType>
OrthogonalContourModel::SampleContour(unsigned int c, unsigned int samplesPerSegment) const
{
  this->CheckContour(c);
  std::vector<ContinuousIndexType> result;
  for (const auto & x : MeshExtraction::detail::SampleContour(m_Network, c, samplesPerSegment))
  {
    ContinuousIndexType index;
    for (unsigned int i = 0; i < 3; ++i)
    {
      index[i] = x[i];
    }
    result.push_back(index);
  }
  return result;
}

std::vector<OrthogonalContourModel::IdentifierListType>
OrthogonalContourModel::GetFaces() const
{
  std::vector<IdentifierListType> result;
  for (const auto & face : MeshExtraction::detail::ContourFaces(m_Network))
  {
    result.emplace_back(face.begin(), face.end());
  }
  return result;
}

double
OrthogonalContourModel::GetVolume() const
{
  return MeshExtraction::detail::SurfaceAreaAndVolume(
    MeshExtraction::detail::BuildContourSurface(m_Network, MeshExtraction::detail::ContourSurfaceParameters{}))[1];
}

double
OrthogonalContourModel::GetArea() const
{
  return MeshExtraction::detail::SurfaceAreaAndVolume(
    MeshExtraction::detail::BuildContourSurface(m_Network, MeshExtraction::detail::ContourSurfaceParameters{}))[0];
}

std::string
OrthogonalContourModel::ToJSON() const
{
  return MeshExtraction::detail::ContourNetworkToJSON(m_Network);
}

void
OrthogonalContourModel::FromJSON(const std::string & text, const std::string & source)
{
  m_Network = MeshExtraction::detail::ContourNetworkFromJSON(text, source);
  m_RefusalReason.clear();
  this->Modified();
}

void
OrthogonalContourModel::Write(const std::string & fileName) const
{
  const std::string temporary = fileName + ".tmp";
  {
    std::ofstream file(temporary, std::ios::binary);
    file << this->ToJSON();
    if (!file)
    {
      itkExceptionMacro(<< "Cannot write the model file " << fileName);
    }
  }
  if (std::rename(temporary.c_str(), fileName.c_str()) != 0)
  {
    std::remove(temporary.c_str());
    itkExceptionMacro(<< "Cannot write the model file " << fileName);
  }
}

void
OrthogonalContourModel::Read(const std::string & fileName)
{
  std::ifstream file(fileName, std::ios::binary);
  if (!file)
  {
    itkExceptionMacro(<< "Cannot read the model file " << fileName << " (no such file, or not readable)");
  }
  const std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  this->FromJSON(text, fileName);
}

void
OrthogonalContourModel::DeepCopy(const OrthogonalContourModel * other)
{
  if (other == nullptr || other == this)
  {
    return;
  }
  m_Network = other->m_Network;
  m_RefusalReason = other->m_RefusalReason;
  this->Modified();
}

void
OrthogonalContourModel::Graft(const DataObject * data)
{
  const auto * other = dynamic_cast<const OrthogonalContourModel *>(data);
  if (data != nullptr && other == nullptr)
  {
    itkExceptionMacro(<< "Graft: " << data->GetNameOfClass() << " is not an OrthogonalContourModel");
  }
  this->DeepCopy(other);
}

void
OrthogonalContourModel::Initialize()
{
  Superclass::Initialize();
  m_Network.points.clear();
  m_Network.contours.clear();
  m_RefusalReason.clear();
}

void
OrthogonalContourModel::PrintSelf(std::ostream & os, Indent indent) const
{
  Superclass::PrintSelf(os, indent);
  os << indent << "Size: " << this->GetSize() << '\n';
  os << indent << "Spacing: " << this->GetSpacing() << '\n';
  os << indent << "Origin: " << this->GetOrigin() << '\n';
  os << indent << "Interpolation: " << m_Network.interpolation << '\n';
  os << indent << "Contours: " << m_Network.contours.size() << '\n';
  for (std::size_t c = 0; c < m_Network.contours.size(); ++c)
  {
    os << indent.GetNextIndent() << c << ": " << AxisNames[m_Network.contours[c].axis] << " = "
       << m_Network.contours[c].position << ", " << m_Network.contours[c].points.size() << " control points\n";
  }
  os << indent << "ControlPoints: " << m_Network.points.size() << '\n';
  os << indent << "RefusalReason: " << m_RefusalReason << '\n';
}
} // namespace itk
