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
#include "itkMeshExtractionContourNetwork.h"
#include "itkMeshExtractionJSON.h"
#include "itkMeshExtractionLandmarkFile.h"
#include "itkMacro.h"

#include <cmath>
#include <iomanip>
#include <sstream>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
namespace
{
const char * const AxisNames[3] = { "x", "y", "z" };
const char * const FormatName = "meshextraction-orthogonal-contours";

template <typename T>
void
WriteArray(std::ostream & os, const T & values)
{
  os << '[';
  for (std::size_t i = 0; i < values.size(); ++i)
  {
    os << (i ? ", " : "") << JSONNumber{ static_cast<double>(values[i]) };
  }
  os << ']';
}

/** Reads the JSON model file; every accessor names the member it wanted. */
class ContourFileReader
{
public:
  explicit ContourFileReader(std::string source)
      : m_Source(std::move(source))
  {}

  const JSONValue &
  Member(const JSONValue & object, const char * name) const
  {
    const JSONValue * value = object.Find(name);
    if (value == nullptr)
    {
      itkGenericExceptionMacro(<< m_Source << ": the model file has no \"" << name << "\"");
    }
    return *value;
  }

  double
  Number(const JSONValue & value, const char * what) const
  {
    if (value.kind != JSONValue::Kind::Number || !std::isfinite(value.number))
    {
      itkGenericExceptionMacro(<< m_Source << ": " << what << " is not a finite number");
    }
    return value.number;
  }

  std::int64_t
  WholeNumber(const JSONValue & value, const char * what) const
  {
    const double x = this->Number(value, what);
    if (x != std::floor(x) || std::abs(x) > 9.0e15)
    {
      itkGenericExceptionMacro(<< m_Source << ": " << what << " is not a whole number");
    }
    return static_cast<std::int64_t>(x);
  }

  std::vector<double>
  Numbers(const JSONValue & value, std::size_t count, const char * what) const
  {
    if (value.kind != JSONValue::Kind::Array || value.elements.size() != count)
    {
      itkGenericExceptionMacro(<< m_Source << ": " << what << " is not an array of " << count << " numbers");
    }
    std::vector<double> result;
    for (const auto & e : value.elements)
    {
      result.push_back(this->Number(e, what));
    }
    return result;
  }

  const std::vector<JSONValue> &
  Array(const JSONValue & value, const char * what) const
  {
    if (value.kind != JSONValue::Kind::Array)
    {
      itkGenericExceptionMacro(<< m_Source << ": " << what << " is not an array");
    }
    return value.elements;
  }

  ContourGrid
  Grid(const JSONValue & root) const
  {
    const JSONValue & grid = this->Member(root, "grid");
    ContourGrid       result;
    const auto        size = this->Numbers(this->Member(grid, "size"), 3, "grid.size");
    const auto        spacing = this->Numbers(this->Member(grid, "spacing"), 3, "grid.spacing");
    const auto        origin = this->Numbers(this->Member(grid, "origin"), 3, "grid.origin");
    const auto        direction = this->Numbers(this->Member(grid, "direction"), 9, "grid.direction");
    for (unsigned int a = 0; a < 3; ++a)
    {
      result.size[a] = static_cast<std::int64_t>(size[a]);
      result.spacing[a] = spacing[a];
      result.origin[a] = origin[a];
    }
    for (unsigned int i = 0; i < 9; ++i)
    {
      result.direction[i] = direction[i];
    }
    const std::string problem = DescribeInvalidGrid(result);
    if (!problem.empty())
    {
      itkGenericExceptionMacro(<< m_Source << ": " << problem);
    }
    return result;
  }

  Contour
  ReadContour(const JSONValue & value, std::size_t pointCount) const
  {
    Contour           contour;
    const JSONValue & axis = this->Member(value, "axis");
    contour.axis = 3;
    for (unsigned int a = 0; a < 3; ++a)
    {
      contour.axis = axis.kind == JSONValue::Kind::String && axis.text == AxisNames[a] ? a : contour.axis;
    }
    if (contour.axis > 2)
    {
      itkGenericExceptionMacro(<< m_Source << ": a contour's axis is not \"x\", \"y\" or \"z\"");
    }
    contour.position = this->WholeNumber(this->Member(value, "position"), "a contour's position");
    for (const auto & id : this->Array(this->Member(value, "points"), "a contour's points"))
    {
      const std::int64_t p = this->WholeNumber(id, "a contour's point");
      if (p < 0 || static_cast<std::size_t>(p) >= pointCount)
      {
        itkGenericExceptionMacro(<< m_Source << ": a contour lists control point " << p << ", which does not exist");
      }
      contour.points.push_back(static_cast<std::uint32_t>(p));
    }
    return contour;
  }

private:
  std::string m_Source;
};

/** The two contours of every point, from the contours' lists; throws for a point on
 * other than two contours. */
void
AssignContoursToPoints(ContourNetwork & network, const std::string & source)
{
  std::vector<std::vector<std::uint32_t>> owners(network.points.size());
  for (std::uint32_t c = 0; c < network.contours.size(); ++c)
  {
    for (const auto p : network.contours[c].points)
    {
      owners[p].push_back(c);
    }
  }
  for (std::size_t p = 0; p < owners.size(); ++p)
  {
    if (owners[p].size() != 2)
    {
      itkGenericExceptionMacro(<< source << ": control point " << p << " is on " << owners[p].size()
                               << " contours, not two");
    }
    const std::uint32_t a = owners[p][0];
    const std::uint32_t b = owners[p][1];
    network.points[p].contours = network.contours[a].axis <= network.contours[b].axis
                                   ? std::array<std::uint32_t, 2>{ { a, b } }
                                   : std::array<std::uint32_t, 2>{ { b, a } };
  }
}
} // namespace

std::string
ContourNetworkToJSON(const ContourNetwork & network)
{
  std::ostringstream os;
  os << std::setprecision(17);
  os << "{\"format\": " << JSONString{ std::string(FormatName) } << ", \"version\": 1,\n";
  os << " \"interpolation\": \"" << (network.interpolation == ContourInterpolation::Linear ? "linear" : "catmull-rom")
     << "\",\n";
  os << " \"grid\": {\"size\": ";
  WriteArray(os, network.grid.size);
  os << ", \"spacing\": ";
  WriteArray(os, network.grid.spacing);
  os << ", \"origin\": ";
  WriteArray(os, network.grid.origin);
  os << ",\n          \"direction\": ";
  WriteArray(os, network.grid.direction);
  os << "},\n \"control_points\": [";
  for (std::size_t p = 0; p < network.points.size(); ++p)
  {
    os << (p ? ",\n   " : "\n   ");
    WriteArray(os, network.points[p].x);
  }
  os << "],\n \"contours\": [";
  for (std::size_t c = 0; c < network.contours.size(); ++c)
  {
    const Contour & contour = network.contours[c];
    os << (c ? ",\n   " : "\n   ") << "{\"axis\": \"" << AxisNames[contour.axis]
       << "\", \"position\": " << contour.position << ", \"points\": ";
    WriteArray(os, contour.points);
    os << '}';
  }
  os << "]}\n";
  return os.str();
}

ContourNetwork
ContourNetworkFromJSON(const std::string & text, const std::string & source)
{
  const JSONValue         root = ParseJSON(text, source);
  const ContourFileReader reader(source);
  const JSONValue &       format = reader.Member(root, "format");
  if (format.kind != JSONValue::Kind::String || format.text != FormatName)
  {
    itkGenericExceptionMacro(<< source << ": not an orthogonal contour model (\"format\" is not \"" << FormatName
                             << "\")");
  }
  if (reader.WholeNumber(reader.Member(root, "version"), "version") != 1)
  {
    itkGenericExceptionMacro(<< source << ": version " << reader.Member(root, "version").number
                             << " of the model file is not known (1 is)");
  }
  ContourNetwork    network;
  const JSONValue & interpolation = reader.Member(root, "interpolation");
  if (interpolation.kind != JSONValue::Kind::String ||
      (interpolation.text != "linear" && interpolation.text != "catmull-rom"))
  {
    itkGenericExceptionMacro(<< source << ": \"interpolation\" is neither \"linear\" nor \"catmull-rom\"");
  }
  network.interpolation =
    interpolation.text == "linear" ? ContourInterpolation::Linear : ContourInterpolation::CatmullRom;
  network.grid = reader.Grid(root);
  for (const auto & point : reader.Array(reader.Member(root, "control_points"), "control_points"))
  {
    const auto x = reader.Numbers(point, 3, "a control point");
    network.points.push_back(ContourControlPoint{ MakeVec3(x[0], x[1], x[2]), { { 0, 0 } } });
  }
  for (const auto & contour : reader.Array(reader.Member(root, "contours"), "contours"))
  {
    network.contours.push_back(reader.ReadContour(contour, network.points.size()));
  }
  AssignContoursToPoints(network, source);
  const std::string problem = CheckContourNetwork(network);
  if (!problem.empty())
  {
    itkGenericExceptionMacro(<< source << ": the model breaks a rule: " << problem);
  }
  return network;
}
} // namespace detail
} // namespace MeshExtraction
} // namespace itk
