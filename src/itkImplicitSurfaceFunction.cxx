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
#include "itkImplicitSurfaceFunction.h"
#include "itkMeshExtractionClosedFormGeometry.h"

#include <cmath>
#include <sstream>

namespace itk
{
namespace
{
using MeshExtraction::MakeVec3;
using MeshExtraction::Norm;
using MeshExtraction::Vec3;
} // namespace

ImplicitSurfaceFunction::OutputType
ImplicitSurfaceFunction::EvaluateWithClosestPoint(const InputType & point, InputType & closest) const
{
  closest = this->ClosestSurfacePoint(point);
  return this->Evaluate(point);
}

void
ImplicitSurfaceFunction::VerifyParameters() const
{
  if (!m_ParameterError.empty())
  {
    itkExceptionMacro(<< "Invalid parameters: " << m_ParameterError);
  }
}

void
ImplicitSurfaceFunction::ParametersChanged()
{
  m_ParameterError = this->CheckParameterConsistency();
  this->Modified();
}

void
ImplicitSurfaceFunction::RequirePositive(const char * parameterName, double value) const
{
  if (!(std::isfinite(value) && value > 0.0))
  {
    itkExceptionMacro(<< parameterName << " must be a finite number > 0, got " << value);
  }
}

void
ImplicitSurfaceFunction::RequirePositive(const char * parameterName, const VectorType & value) const
{
  for (unsigned int i = 0; i < 3; ++i)
  {
    if (!(std::isfinite(value[i]) && value[i] > 0.0))
    {
      itkExceptionMacro(<< parameterName << " must have finite components > 0, got " << value << " (component " << i
                        << " is " << value[i] << ")");
    }
  }
}

void
ImplicitSurfaceFunction::RequireFinite(const char * parameterName, const InputType & value) const
{
  for (unsigned int i = 0; i < 3; ++i)
  {
    if (!std::isfinite(value[i]))
    {
      itkExceptionMacro(<< parameterName << " must have finite coordinates, got " << value);
    }
  }
}

ImplicitSurfaceFunction::VectorType
ImplicitSurfaceFunction::RequireDirection(const char * parameterName, const VectorType & value) const
{
  const Vec3   v = MakeVec3(value[0], value[1], value[2]);
  const double l = Norm(v);
  if (!(std::isfinite(l) && l > 0.0))
  {
    itkExceptionMacro(<< parameterName << " must be a finite, non-zero vector, got " << value);
  }
  return v / l;
}

ImplicitSurfaceFunction::MatrixType
ImplicitSurfaceFunction::RequireRotation(const char * parameterName, const MatrixType & value) const
{
  const double maximumError = MeshExtraction::detail::OrthogonalityError(value);
  if (!(maximumError <= 1e-6))
  {
    itkExceptionMacro(<< parameterName << " must be an orthogonal matrix (orthonormal columns within 1e-6), got "
                      << value << "with max |R^T R - I| = " << maximumError);
  }
  // Gram-Schmidt on the columns, so that R^T R = I to rounding and distances
  // computed in the local frame are distances in physical space.
  return MeshExtraction::detail::OrthonormalizeColumns(value);
}

void
ImplicitSurfaceFunction::PrintSelf(std::ostream & os, Indent indent) const
{
  Superclass::PrintSelf(os, indent);
  os << indent << "ParametersValid: " << (m_ParameterError.empty() ? "true" : "false") << std::endl;
  if (!m_ParameterError.empty())
  {
    os << indent << "ParameterError: " << m_ParameterError << std::endl;
  }
}

namespace
{
template <typename TValue>
std::string
ToText(const TValue & value)
{
  std::ostringstream s;
  s.precision(17);
  s << value;
  return s.str();
}
} // namespace

std::string
ImplicitSurfaceFunction::ParameterText(double value)
{
  return ToText(value);
}

std::string
ImplicitSurfaceFunction::ParameterText(const InputType & value)
{
  return ToText(value);
}

std::string
ImplicitSurfaceFunction::ParameterText(const VectorType & value)
{
  return ToText(value);
}

} // namespace itk
