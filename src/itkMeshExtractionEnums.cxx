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
#include "itkMeshExtractionEnums.h"

#include <ostream>

namespace itk
{
std::ostream &
operator<<(std::ostream & out, MeshExtractionEnums::PhantomImage value)
{
  switch (value)
  {
    case MeshExtractionEnums::PhantomImage::DistanceMap:
      return out << "itk::MeshExtractionEnums::PhantomImage::DistanceMap";
    case MeshExtractionEnums::PhantomImage::BinaryMask:
      return out << "itk::MeshExtractionEnums::PhantomImage::BinaryMask";
    case MeshExtractionEnums::PhantomImage::BlurredStep:
      return out << "itk::MeshExtractionEnums::PhantomImage::BlurredStep";
  }
  return out << "INVALID VALUE FOR itk::MeshExtractionEnums::PhantomImage";
}

std::ostream &
operator<<(std::ostream & out, MeshExtractionEnums::SmoothingWeights value)
{
  switch (value)
  {
    case MeshExtractionEnums::SmoothingWeights::Uniform:
      return out << "itk::MeshExtractionEnums::SmoothingWeights::Uniform";
    case MeshExtractionEnums::SmoothingWeights::InverseEdgeLength:
      return out << "itk::MeshExtractionEnums::SmoothingWeights::InverseEdgeLength";
    case MeshExtractionEnums::SmoothingWeights::Area:
      return out << "itk::MeshExtractionEnums::SmoothingWeights::Area";
    case MeshExtractionEnums::SmoothingWeights::Cotangent:
      return out << "itk::MeshExtractionEnums::SmoothingWeights::Cotangent";
    case MeshExtractionEnums::SmoothingWeights::AngleBisector:
      return out << "itk::MeshExtractionEnums::SmoothingWeights::AngleBisector";
  }
  return out << "INVALID VALUE FOR itk::MeshExtractionEnums::SmoothingWeights";
}

std::ostream &
operator<<(std::ostream & out, MeshExtractionEnums::SmoothingUpdate value)
{
  switch (value)
  {
    case MeshExtractionEnums::SmoothingUpdate::Batch:
      return out << "itk::MeshExtractionEnums::SmoothingUpdate::Batch";
    case MeshExtractionEnums::SmoothingUpdate::Immediate:
      return out << "itk::MeshExtractionEnums::SmoothingUpdate::Immediate";
  }
  return out << "INVALID VALUE FOR itk::MeshExtractionEnums::SmoothingUpdate";
}

std::ostream &
operator<<(std::ostream & out, MeshExtractionEnums::MovementConstraint value)
{
  switch (value)
  {
    case MeshExtractionEnums::MovementConstraint::None:
      return out << "itk::MeshExtractionEnums::MovementConstraint::None";
    case MeshExtractionEnums::MovementConstraint::Centroid:
      return out << "itk::MeshExtractionEnums::MovementConstraint::Centroid";
    case MeshExtractionEnums::MovementConstraint::Safe:
      return out << "itk::MeshExtractionEnums::MovementConstraint::Safe";
  }
  return out << "INVALID VALUE FOR itk::MeshExtractionEnums::MovementConstraint";
}

std::ostream &
operator<<(std::ostream & out, MeshExtractionEnums::EdgeSwapCriterion value)
{
  switch (value)
  {
    case MeshExtractionEnums::EdgeSwapCriterion::Regularity:
      return out << "itk::MeshExtractionEnums::EdgeSwapCriterion::Regularity";
    case MeshExtractionEnums::EdgeSwapCriterion::Delaunay:
      return out << "itk::MeshExtractionEnums::EdgeSwapCriterion::Delaunay";
    case MeshExtractionEnums::EdgeSwapCriterion::ShortestEdge:
      return out << "itk::MeshExtractionEnums::EdgeSwapCriterion::ShortestEdge";
  }
  return out << "INVALID VALUE FOR itk::MeshExtractionEnums::EdgeSwapCriterion";
}

std::ostream &
operator<<(std::ostream & out, MeshExtractionEnums::EdgeSearchDirection value)
{
  switch (value)
  {
    case MeshExtractionEnums::EdgeSearchDirection::ImageGradient:
      return out << "itk::MeshExtractionEnums::EdgeSearchDirection::ImageGradient";
    case MeshExtractionEnums::EdgeSearchDirection::VertexNormal:
      return out << "itk::MeshExtractionEnums::EdgeSearchDirection::VertexNormal";
  }
  return out << "INVALID VALUE FOR itk::MeshExtractionEnums::EdgeSearchDirection";
}

std::ostream &
operator<<(std::ostream & out, MeshExtractionEnums::RefinementOperation value)
{
  switch (value)
  {
    case MeshExtractionEnums::RefinementOperation::Initial:
      return out << "itk::MeshExtractionEnums::RefinementOperation::Initial";
    case MeshExtractionEnums::RefinementOperation::EdgeDetection:
      return out << "itk::MeshExtractionEnums::RefinementOperation::EdgeDetection";
    case MeshExtractionEnums::RefinementOperation::EdgeSwap:
      return out << "itk::MeshExtractionEnums::RefinementOperation::EdgeSwap";
    case MeshExtractionEnums::RefinementOperation::Smoothing:
      return out << "itk::MeshExtractionEnums::RefinementOperation::Smoothing";
  }
  return out << "INVALID VALUE FOR itk::MeshExtractionEnums::RefinementOperation";
}
std::ostream &
operator<<(std::ostream & out, MeshExtractionEnums::LandmarkDistension value)
{
  switch (value)
  {
    case MeshExtractionEnums::LandmarkDistension::None:
      return out << "itk::MeshExtractionEnums::LandmarkDistension::None";
    case MeshExtractionEnums::LandmarkDistension::Isotropic:
      return out << "itk::MeshExtractionEnums::LandmarkDistension::Isotropic";
    case MeshExtractionEnums::LandmarkDistension::AlongAxes:
      return out << "itk::MeshExtractionEnums::LandmarkDistension::AlongAxes";
  }
  return out << "INVALID VALUE FOR itk::MeshExtractionEnums::LandmarkDistension";
}
std::ostream &
operator<<(std::ostream & out, MeshExtractionEnums::Correspondence value)
{
  switch (value)
  {
    case MeshExtractionEnums::Correspondence::PointToPoint:
      return out << "itk::MeshExtractionEnums::Correspondence::PointToPoint";
    case MeshExtractionEnums::Correspondence::PointToSurface:
      return out << "itk::MeshExtractionEnums::Correspondence::PointToSurface";
  }
  return out << "INVALID VALUE FOR itk::MeshExtractionEnums::Correspondence";
}

std::ostream &
operator<<(std::ostream & out, MeshExtractionEnums::MeshFileEncoding value)
{
  switch (value)
  {
    case MeshExtractionEnums::MeshFileEncoding::Default:
      return out << "itk::MeshExtractionEnums::MeshFileEncoding::Default";
    case MeshExtractionEnums::MeshFileEncoding::ASCII:
      return out << "itk::MeshExtractionEnums::MeshFileEncoding::ASCII";
    case MeshExtractionEnums::MeshFileEncoding::Binary:
      return out << "itk::MeshExtractionEnums::MeshFileEncoding::Binary";
  }
  return out << "INVALID VALUE FOR itk::MeshExtractionEnums::MeshFileEncoding";
}

std::ostream &
operator<<(std::ostream & out, MeshExtractionEnums::VTKLegacyVersion value)
{
  switch (value)
  {
    case MeshExtractionEnums::VTKLegacyVersion::V4_2:
      return out << "itk::MeshExtractionEnums::VTKLegacyVersion::V4_2";
    case MeshExtractionEnums::VTKLegacyVersion::V5_1:
      return out << "itk::MeshExtractionEnums::VTKLegacyVersion::V5_1";
  }
  return out << "INVALID VALUE FOR itk::MeshExtractionEnums::VTKLegacyVersion";
}
} // namespace itk
