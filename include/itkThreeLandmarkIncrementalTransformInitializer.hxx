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
#ifndef itkThreeLandmarkIncrementalTransformInitializer_hxx
#define itkThreeLandmarkIncrementalTransformInitializer_hxx

#include "itkThreeLandmarkIncrementalTransformInitializer.h"
#include "itkAffineTransform.h"
#include "itkMeshExtractionLandmarkGeometry.h"
#include "itkSimilarity3DTransform.h"

#include <cmath>
#include <type_traits>

namespace itk
{

template <typename TTransform>
void
ThreeLandmarkIncrementalTransformInitializer<TTransform>::VerifyConfiguration(const LandmarkPointContainer & l,
                                                                              const char * space) const
{
  if (l.size() != 3)
  {
    itkExceptionMacro("Three " << space << " landmarks (A, B, C) are needed, got " << l.size() << '.');
  }
  const char * names = "ABC";
  for (unsigned int i = 0; i < 3; ++i)
  {
    for (unsigned int d = 0; d < 3; ++d)
    {
      if (!std::isfinite(l[i][d]))
      {
        itkExceptionMacro("The " << space << " landmark " << names[i]
                                 << " has a coordinate that is not finite: " << l[i] << '.');
      }
    }
  }
  const VectorType ab = l[1] - l[0];
  const VectorType ac = l[2] - l[0];
  const double     extent = std::max({ ab.GetNorm(), ac.GetNorm(), (l[2] - l[1]).GetNorm() });
  if (!(ab.GetNorm() > m_DegeneracyTolerance * extent) || !(extent > 0.0))
  {
    itkExceptionMacro("The " << space << " landmarks A " << l[0] << " and B " << l[1]
                             << " are at the same place: they define no axis.");
  }
  const VectorType perpendicular = MeshExtraction::detail::PerpendicularPart(ac, ab / ab.GetNorm());
  if (!(perpendicular.GetNorm() > m_DegeneracyTolerance * extent))
  {
    itkExceptionMacro("The " << space << " landmark C " << l[2] << " lies on the line through A " << l[0] << " and B "
                             << l[1] << ": the three landmarks define no plane.");
  }
}

template <typename TTransform>
void
ThreeLandmarkIncrementalTransformInitializer<TTransform>::VerifyLandmarks() const
{
  if (m_Transform.IsNull())
  {
    itkExceptionMacro("No transform: call SetTransform() first.");
  }
  if (!(m_DegeneracyTolerance >= 0.0 && m_DegeneracyTolerance < 1.0))
  {
    itkExceptionMacro("DegeneracyTolerance must be in [0, 1), got " << m_DegeneracyTolerance << '.');
  }
  this->VerifyConfiguration(m_FixedLandmarks, "fixed");
  this->VerifyConfiguration(m_MovingLandmarks, "moving");
  using Scalar = typename TransformType::ScalarType;
  TransformBase * transform = m_Transform.GetPointer();
  const bool      similarity = dynamic_cast<Similarity3DTransform<Scalar> *>(transform) != nullptr;
  const bool      affine = dynamic_cast<AffineTransform<Scalar, 3> *>(transform) != nullptr;
  if (!similarity && dynamic_cast<VersorRigid3DTransform<Scalar> *>(transform) == nullptr &&
      dynamic_cast<MatrixOffsetTransformBase<Scalar, 3, 3> *>(transform) == nullptr)
  {
    itkExceptionMacro("A " << transform->GetNameOfClass()
                           << " cannot hold the match: give a VersorRigid3DTransform, Similarity3DTransform, "
                              "Euler3DTransform, AffineTransform or another MatrixOffsetTransformBase.");
  }
  if (m_Distension == DistensionEnum::Isotropic && !similarity && !affine)
  {
    itkExceptionMacro("Distension " << m_Distension << " scales: it needs a Similarity3DTransform or an "
                                    << "AffineTransform, not a " << transform->GetNameOfClass() << '.');
  }
  if (m_Distension == DistensionEnum::AlongAxes && !affine)
  {
    itkExceptionMacro("Distension " << m_Distension << " scales along two axes: it needs an AffineTransform, not a "
                                    << transform->GetNameOfClass() << '.');
  }
}

template <typename TTransform>
void
ThreeLandmarkIncrementalTransformInitializer<TTransform>::ComputeDistension(const VectorType & axisFixed,
                                                                            MatrixType &       scaling)
{
  const LandmarkPointContainer & f = m_FixedLandmarks;
  const LandmarkPointContainer & m = m_MovingLandmarks;
  const double                   alongAxis = (m[1] - m[0]).GetNorm() / (f[1] - f[0]).GetNorm();
  const VectorType               perpendicularFixed = MeshExtraction::detail::PerpendicularPart(f[2] - f[0], axisFixed);
  const VectorType               perpendicularMoving =
    MeshExtraction::detail::PerpendicularPart(m[2] - m[0], (m[1] - m[0]) / (m[1] - m[0]).GetNorm());
  m_Scales.Fill(1.0);
  if (m_Distension == DistensionEnum::Isotropic)
  {
    m_Scales.Fill(alongAxis);
  }
  else if (m_Distension == DistensionEnum::AlongAxes)
  {
    m_Scales[0] = alongAxis;
    m_Scales[1] = perpendicularMoving.GetNorm() / perpendicularFixed.GetNorm();
  }
  // S = sum_k s_k e_k e_k^T in the frame e_1 = AB, e_2 = toward C, e_3 = e_1 x e_2.
  const VectorType e2 = perpendicularFixed / perpendicularFixed.GetNorm();
  const VectorType e3 = CrossProduct(axisFixed, e2);
  const VectorType frame[3] = { axisFixed, e2, e3 };
  scaling.Fill(0.0);
  for (unsigned int k = 0; k < 3; ++k)
  {
    for (unsigned int r = 0; r < 3; ++r)
    {
      for (unsigned int c = 0; c < 3; ++c)
      {
        scaling[r][c] += m_Scales[k] * frame[k][r] * frame[k][c];
      }
    }
  }
}

template <typename TTransform>
void
ThreeLandmarkIncrementalTransformInitializer<TTransform>::SetTransformParameters(const MatrixType & linear)
{
  using Scalar = typename TransformType::ScalarType;
  Point<Scalar, 3>  center;
  Vector<Scalar, 3> translation;
  for (unsigned int d = 0; d < 3; ++d)
  {
    center[d] = static_cast<Scalar>(m_FixedLandmarks[0][d]);
    translation[d] = static_cast<Scalar>(m_MovingLandmarks[0][d] - m_FixedLandmarks[0][d]);
  }
  auto toScalar = [](const MatrixType & in) {
    Matrix<Scalar, 3, 3> out;
    for (unsigned int r = 0; r < 3; ++r)
    {
      for (unsigned int c = 0; c < 3; ++c)
      {
        out[r][c] = static_cast<Scalar>(in[r][c]);
      }
    }
    return out;
  };
  TransformBase * transform = m_Transform.GetPointer();
  if (auto * rigid = dynamic_cast<VersorRigid3DTransform<Scalar> *>(transform))
  {
    // The versor of the rotation (a similarity's scale is set on its own): the
    // transform's matrix is recomputed from it, orthogonal to rounding.
    typename VersorRigid3DTransform<Scalar>::VersorType versor;
    versor.Set(toScalar(m_Rotation));
    rigid->SetIdentity();
    rigid->SetCenter(center);
    rigid->SetRotation(versor);
    if (auto * similarity = dynamic_cast<Similarity3DTransform<Scalar> *>(transform))
    {
      similarity->SetScale(static_cast<Scalar>(m_Scales[0]));
    }
    rigid->SetTranslation(translation);
  }
  else
  {
    auto * matrixOffset = dynamic_cast<MatrixOffsetTransformBase<Scalar, 3, 3> *>(transform);
    matrixOffset->SetIdentity();
    matrixOffset->SetCenter(center);
    matrixOffset->SetMatrix(toScalar(linear));
    matrixOffset->SetTranslation(translation);
  }
}

template <typename TTransform>
void
ThreeLandmarkIncrementalTransformInitializer<TTransform>::InitializeTransform()
{
  this->VerifyLandmarks();
  const LandmarkPointContainer & f = m_FixedLandmarks;
  const LandmarkPointContainer & m = m_MovingLandmarks;
  // Step 1, A by translation, is the transform's centre and translation (below).
  // Step 2: B by the shortest-arc rotation about A.
  const VectorType axisFixed = (f[1] - f[0]) / (f[1] - f[0]).GetNorm();
  const VectorType axisMoving = (m[1] - m[0]) / (m[1] - m[0]).GetNorm();
  const MatrixType first = MeshExtraction::detail::ShortestArcRotation(axisFixed, axisMoving);
  // Step 3: C by the rotation about the axis AB (now the moving axis) through the
  // signed angle between the perpendicular parts of C's directions.
  const VectorType rotatedC = MeshExtraction::detail::PerpendicularPart(first * (f[2] - f[0]), axisMoving);
  const VectorType targetC = MeshExtraction::detail::PerpendicularPart(m[2] - m[0], axisMoving);
  const double     angle = std::atan2(axisMoving * CrossProduct(rotatedC, targetC), rotatedC * targetC);
  m_Rotation = MeshExtraction::detail::AxisAngleRotation(axisMoving, angle) * first;

  MatrixType scaling;
  this->ComputeDistension(axisFixed, scaling);
  this->SetTransformParameters(m_Rotation * scaling);
  for (unsigned int i = 0; i < 3; ++i)
  {
    typename TransformType::InputPointType p;
    for (unsigned int d = 0; d < 3; ++d)
    {
      p[d] = static_cast<typename TransformType::ScalarType>(f[i][d]);
    }
    const auto mapped = m_Transform->TransformPoint(p);
    double     squared = 0.0;
    for (unsigned int d = 0; d < 3; ++d)
    {
      squared += (mapped[d] - m[i][d]) * (mapped[d] - m[i][d]);
    }
    m_LandmarkResiduals[i] = std::sqrt(squared);
  }
}

template <typename TTransform>
void
ThreeLandmarkIncrementalTransformInitializer<TTransform>::PrintSelf(std::ostream & os, Indent indent) const
{
  Superclass::PrintSelf(os, indent);
  os << indent << "Transform: " << m_Transform.GetPointer() << '\n';
  os << indent << "Distension: " << m_Distension << '\n';
  os << indent << "DegeneracyTolerance: " << m_DegeneracyTolerance << '\n';
  os << indent << "FixedLandmarks:";
  for (const auto & p : m_FixedLandmarks)
  {
    os << ' ' << p;
  }
  os << '\n' << indent << "MovingLandmarks:";
  for (const auto & p : m_MovingLandmarks)
  {
    os << ' ' << p;
  }
  os << '\n' << indent << "Scales: " << m_Scales[0] << ' ' << m_Scales[1] << ' ' << m_Scales[2] << '\n';
}
} // namespace itk

#endif
