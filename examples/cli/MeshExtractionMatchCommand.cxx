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
// meshextraction match: the three-landmark incremental match (thesis chapter 6) of a
// moving image onto a fixed one, its transform, the resampled image, a carried mesh
// and a picture of the alignment.

#include "MeshExtractionCLI.h"

#include "itkAffineTransform.h"
#include "itkImageFileWriter.h"
#include "itkLandmarkBasedTransformInitializer.h"
#include "itkLinearInterpolateImageFunction.h"
#include "itkMeshExtractionLandmarkFile.h"
#include "itkResampleImageFilter.h"
#include "itkRGBPixel.h"
#include "itkSimilarity3DTransform.h"
#include "itkThreeLandmarkIncrementalTransformInitializer.h"
#include "itkTransformFileWriter.h"
#include "itkVersorRigid3DTransform.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>

namespace MeshExtractionCLI
{
namespace
{
using ImageType = itk::Image<float, 3>;
using TransformType = itk::Transform<double, 3, 3>;
using Distension = itk::MeshExtractionEnums::LandmarkDistension;
using LandmarkPoints = std::vector<itk::Point<double, 3>>;

const OptionNames<Distension> &
DistensionNames()
{
  static const OptionNames<Distension> names{ { "none", Distension::None },
                                              { "isotropic", Distension::Isotropic },
                                              { "axes", Distension::AlongAxes } };
  return names;
}

/** The landmark ids, in order of certainty: --landmarks A,B,C. */
std::vector<std::string>
LandmarkIds(const Arguments & args)
{
  const std::string        text = args.Get("landmarks", "A,B,C");
  std::vector<std::string> ids;
  std::string              id;
  for (char c : text + ",")
  {
    if (c == ',')
    {
      if (id.empty())
      {
        throw UsageError("--landmarks needs three ids separated by commas, got '" + text + "'");
      }
      ids.push_back(id);
      id.clear();
    }
    else
    {
      id += c;
    }
  }
  if (ids.size() != 3 || ids[0] == ids[1] || ids[0] == ids[2] || ids[1] == ids[2])
  {
    throw UsageError("--landmarks needs three different ids (A, B, C in order of certainty), got '" + text + "'");
  }
  return ids;
}

LandmarkPoints
ReadThreeLandmarks(const std::string & path, const std::vector<std::string> & ids)
{
  return ME::SelectLandmarks(ME::ReadLandmarkFile(path), ids, path);
}

/** The incremental match as the transform type its distension needs. */
TransformType::Pointer
MatchIncrementally(const LandmarkPoints & fixed, const LandmarkPoints & moving, Distension distension)
{
  TransformType::Pointer transform;
  switch (distension)
  {
    case Distension::None:
      transform = itk::VersorRigid3DTransform<double>::New().GetPointer();
      break;
    case Distension::Isotropic:
      transform = itk::Similarity3DTransform<double>::New().GetPointer();
      break;
    case Distension::AlongAxes:
      transform = itk::AffineTransform<double, 3>::New().GetPointer();
      break;
  }
  auto initializer = itk::ThreeLandmarkIncrementalTransformInitializer<TransformType>::New();
  initializer->SetTransform(transform);
  initializer->SetFixedLandmarks(fixed);
  initializer->SetMovingLandmarks(moving);
  initializer->SetDistension(distension);
  initializer->InitializeTransform();
  return transform;
}

/** ITK's least-squares rigid fit of the same landmarks, for comparison. */
TransformType::Pointer
MatchByLeastSquares(const LandmarkPoints & fixed, const LandmarkPoints & moving)
{
  using Rigid = itk::VersorRigid3DTransform<double>;
  auto rigid = Rigid::New();
  auto initializer = itk::LandmarkBasedTransformInitializer<Rigid, ImageType, ImageType>::New();
  initializer->SetTransform(rigid);
  initializer->SetFixedLandmarks(fixed);
  initializer->SetMovingLandmarks(moving);
  initializer->InitializeTransform();
  return rigid.GetPointer();
}

void
PrintResiduals(const std::string &              label,
               const TransformType *            transform,
               const LandmarkPoints &           fixed,
               const LandmarkPoints &           moving,
               const std::vector<std::string> & ids)
{
  std::cout << "  " << std::left << std::setw(26) << label << std::right;
  for (std::size_t i = 0; i < 3; ++i)
  {
    std::cout << "  " << ids[i] << ' ' << std::fixed << std::setprecision(3)
              << transform->TransformPoint(fixed[i]).EuclideanDistanceTo(moving[i]) << " mm";
  }
  std::cout << std::defaultfloat << '\n';
}

void
WriteTransform(const TransformType * transform, const std::string & path)
{
  RequireRoomForHDF5(path);
  WriteWhole(path, [transform](const std::string & partial) {
    auto writer = itk::TransformFileWriterTemplate<double>::New();
    writer->SetInput(transform);
    writer->SetFileName(partial);
    writer->Update();
  });
}

/** The moving image seen in the fixed image's grid (linear interpolation; 0 outside). */
ImageType::Pointer
ResampleMoving(const ImageType * fixed, const ImageType * moving, const TransformType * transform)
{
  auto resample = itk::ResampleImageFilter<ImageType, ImageType, double, double>::New();
  resample->SetInput(moving);
  resample->SetTransform(transform);
  resample->UseReferenceImageOn();
  resample->SetReferenceImage(fixed);
  resample->SetDefaultPixelValue(0.0f);
  resample->Update();
  return resample->GetOutput();
}

/** A mesh of the moving space carried into the fixed space: T maps fixed to moving, so
 * the mesh goes through T's inverse. */
void
CarryMesh(const TransformType * transform, const std::string & input, const std::string & output)
{
  auto inverse = transform->GetInverseTransform();
  if (inverse.IsNull())
  {
    itkGenericExceptionMacro("the transform has no inverse: the mesh cannot be carried");
  }
  auto mesh = ReadMeshFile(input);
  auto points = mesh->GetPoints();
  for (auto it = points->Begin(); it != points->End(); ++it)
  {
    it.Value() = inverse->TransformPoint(it.Value());
  }
  WriteMeshFile(mesh.GetPointer(), output);
}

// ---- the picture of the alignment -------------------------------------------------

using RGB = itk::RGBPixel<unsigned char>;
using PictureType = itk::Image<RGB, 2>;

/** The 1st and 99th percentiles of an image's values, for the grey scale. */
std::pair<double, double>
DisplayRange(const ImageType * image)
{
  const auto         n = image->GetBufferedRegion().GetNumberOfPixels();
  const float *      buffer = image->GetBufferPointer();
  std::vector<float> sample;
  const std::size_t  step = std::max<std::size_t>(1, n / 200000);
  for (std::size_t i = 0; i < n; i += step)
  {
    if (std::isfinite(buffer[i]))
    {
      sample.push_back(buffer[i]);
    }
  }
  if (sample.empty())
  {
    return { 0.0, 1.0 };
  }
  std::sort(sample.begin(), sample.end());
  const double low = sample[sample.size() / 100];
  const double high = sample[sample.size() - 1 - sample.size() / 100];
  return { low, high > low ? high : low + 1.0 };
}

/** One orthogonal slice of the fixed grid through `centre` (index space), as grey values
 * in [0, 255] of both images, at the smallest spacing of the slice's two axes. */
struct Slice
{
  unsigned int               width{ 0 }, height{ 0 };
  std::vector<unsigned char> fixed, moving;
};

Slice
MakeSlice(const ImageType *                 fixed,
          const ImageType *                 moving,
          unsigned int                      normal,
          const itk::Index<3> &             centre,
          const std::pair<double, double> & fixedRange,
          const std::pair<double, double> & movingRange)
{
  const unsigned int u = normal == 0 ? 1 : 0;
  const unsigned int v = normal == 2 ? 1 : 2;
  const auto         size = fixed->GetBufferedRegion().GetSize();
  const auto         spacing = fixed->GetSpacing();
  const double       pixel = std::min(spacing[u], spacing[v]);
  Slice              s;
  s.width = static_cast<unsigned int>(std::lround(size[u] * spacing[u] / pixel));
  s.height = static_cast<unsigned int>(std::lround(size[v] * spacing[v] / pixel));
  auto grey = [](double value, const std::pair<double, double> & range) {
    const double t = std::clamp((value - range.first) / (range.second - range.first), 0.0, 1.0);
    return static_cast<unsigned char>(std::lround(255.0 * t));
  };
  for (unsigned int y = 0; y < s.height; ++y)
  {
    for (unsigned int x = 0; x < s.width; ++x)
    {
      itk::Index<3> index = centre;
      index[u] = fixed->GetBufferedRegion().GetIndex(u) +
                 std::min<itk::IndexValueType>(size[u] - 1, static_cast<itk::IndexValueType>(x * pixel / spacing[u]));
      // Rows from the top: the last index of the second axis first (superior up).
      index[v] = fixed->GetBufferedRegion().GetIndex(v) +
                 std::min<itk::IndexValueType>(
                   size[v] - 1, static_cast<itk::IndexValueType>((s.height - 1 - y) * pixel / spacing[v]));
      s.fixed.push_back(grey(fixed->GetPixel(index), fixedRange));
      s.moving.push_back(grey(moving->GetPixel(index), movingRange));
    }
  }
  return s;
}

/** Three slices side by side: above, the fixed image in magenta and the moving in green
 * (aligned structures look grey); below, a checkerboard of the two. */
void
WriteAlignmentPicture(const ImageType *         fixed,
                      const ImageType *         resampled,
                      const ME::NamedLandmark & through,
                      const std::string &       path)
{
  itk::ContinuousIndex<double, 3> c;
  // A landmark outside the image is fine: the slices are clamped to it below.
  static_cast<void>(fixed->TransformPhysicalPointToContinuousIndex(through.point, c));
  itk::Index<3> centre;
  const auto &  region = fixed->GetBufferedRegion();
  for (unsigned int d = 0; d < 3; ++d)
  {
    const auto first = region.GetIndex(d);
    const auto last = first + static_cast<itk::IndexValueType>(region.GetSize(d)) - 1;
    centre[d] = std::clamp<itk::IndexValueType>(static_cast<itk::IndexValueType>(std::lround(c[d])), first, last);
  }
  const auto         fixedRange = DisplayRange(fixed);
  const auto         movingRange = DisplayRange(resampled);
  std::vector<Slice> slices;
  unsigned int       width = 0, height = 0;
  for (unsigned int normal : { 2u, 1u, 0u })
  {
    slices.push_back(MakeSlice(fixed, resampled, normal, centre, fixedRange, movingRange));
    width += slices.back().width;
    height = std::max(height, slices.back().height);
  }
  auto                  picture = PictureType::New();
  PictureType::SizeType size;
  size[0] = width;
  size[1] = 2 * height;
  picture->SetRegions(size);
  picture->Allocate(true);
  constexpr unsigned int Square = 16;
  unsigned int           left = 0;
  for (const Slice & s : slices)
  {
    for (unsigned int y = 0; y < s.height; ++y)
    {
      for (unsigned int x = 0; x < s.width; ++x)
      {
        const unsigned char f = s.fixed[y * s.width + x];
        const unsigned char m = s.moving[y * s.width + x];
        RGB                 overlay, board;
        overlay.Set(f, m, f);
        const unsigned char g = ((x / Square + y / Square) % 2 == 0) ? f : m;
        board.Set(g, g, g);
        picture->SetPixel({ { left + x, y } }, overlay);
        picture->SetPixel({ { left + x, height + y } }, board);
      }
    }
    left += s.width;
  }
  WriteWhole(path, [&picture](const std::string & partial) {
    auto writer = itk::ImageFileWriter<PictureType>::New();
    writer->SetInput(picture);
    writer->SetFileName(partial);
    writer->Update();
  });
}

// ---- the command -------------------------------------------------------------------

struct MatchOutputs
{
  std::string transform, resampled, png, meshIn, meshOut;
};

MatchOutputs
ReadOutputs(const Arguments & args)
{
  MatchOutputs o;
  o.transform = args.Get("transform");
  o.resampled = args.Get("resampled");
  o.png = args.Get("png");
  if (args.Has("mesh"))
  {
    const auto & p = args.positional;
    // --mesh IN OUT: the option takes IN, OUT is the next positional argument.
    if (p.size() != 3)
    {
      throw UsageError("--mesh needs two files, IN and OUT: 'match FIXED MOVING --mesh IN OUT'");
    }
    o.meshIn = args.Get("mesh");
    o.meshOut = p[2];
  }
  else if (args.positional.size() != 2)
  {
    throw UsageError("'match' expects FIXED and MOVING");
  }
  if (o.transform.empty() && o.resampled.empty() && o.png.empty() && o.meshOut.empty())
  {
    throw UsageError("nothing to write: give --transform, --resampled, --png or --mesh");
  }
  return o;
}

int
RunMatch(const Arguments & args)
{
  const MatchOutputs             outputs = ReadOutputs(args);
  const std::vector<std::string> ids = LandmarkIds(args);
  if (!args.Has("fixed-landmarks") || !args.Has("moving-landmarks"))
  {
    throw UsageError("give both --fixed-landmarks and --moving-landmarks");
  }
  const Distension     distension = ChooseOption(args, "distension", DistensionNames(), Distension::None);
  const auto           fixedNamed = ME::ReadLandmarkFile(args.Get("fixed-landmarks"));
  const LandmarkPoints fixedPoints = ME::SelectLandmarks(fixedNamed, ids, args.Get("fixed-landmarks"));
  const LandmarkPoints movingPoints = ReadThreeLandmarks(args.Get("moving-landmarks"), ids);

  const auto transform = MatchIncrementally(fixedPoints, movingPoints, distension);
  std::cout << "match: three-landmark incremental match (" << ids[0] << ' ' << ids[1] << ' ' << ids[2]
            << ", most certain first), distension " << OptionName(DistensionNames(), distension)
            << "\n  |T(fixed) - moving| at the landmarks:\n";
  PrintResiduals("incremental", transform, fixedPoints, movingPoints, ids);
  PrintResiduals(
    "least squares (ITK, rigid)", MatchByLeastSquares(fixedPoints, movingPoints), fixedPoints, movingPoints, ids);
  if (!outputs.transform.empty())
  {
    WriteTransform(transform, outputs.transform);
    std::cerr << "  wrote " << outputs.transform << " (fixed -> moving, as ITK's resampling uses it)\n";
  }
  if (!outputs.meshOut.empty())
  {
    CarryMesh(transform, outputs.meshIn, outputs.meshOut);
    std::cerr << "  wrote " << outputs.meshOut << " (" << outputs.meshIn << " carried into the fixed space)\n";
  }
  if (outputs.resampled.empty() && outputs.png.empty())
  {
    return 0;
  }
  const auto fixed = ReadImageFile<ImageType>(args.positional[0]);
  const auto moving = ReadImageFile<ImageType>(args.positional[1]);
  const auto resampled = ResampleMoving(fixed, moving, transform);
  if (!outputs.resampled.empty())
  {
    WriteImageFile(resampled.GetPointer(), outputs.resampled);
    std::cerr << "  wrote " << outputs.resampled << " (the moving image on the fixed grid)\n";
  }
  if (!outputs.png.empty())
  {
    ME::NamedLandmark through{ ids[2], fixedPoints[2] };
    WriteAlignmentPicture(fixed, resampled, through, outputs.png);
    std::cerr << "  wrote " << outputs.png << " (slices through fixed " << ids[2] << ")\n";
  }
  return 0;
}
} // namespace

Command
MakeMatchCommand()
{
  Command c;
  c.name = "match";
  c.summary = "match a moving image to a fixed one by three landmarks (thesis ch. 6)";
  c.usage = "FIXED MOVING --fixed-landmarks F.json --moving-landmarks M.json [options] [--mesh IN OUT]";
  c.description =
    "Matches three landmarks placed with unequal certainty incrementally (thesis 6.2.4): A (the most\n"
    "certain) by translation, B by a rotation about A, C by a rotation about the axis AB, so that\n"
    "the error of the least certain landmark is not spread over the others, as a least-squares fit\n"
    "spreads it (both are printed). Landmark files: the module's JSON ([{\"id\": \"A\", \"coordinates\":\n"
    "[x, y, z]}, ...], LPS mm) or 3D Slicer markups (.mrk.json, RAS or LPS). The transform maps\n"
    "fixed points to moving points, as ITK's registration and resampling use it; --resampled is the\n"
    "moving image on the fixed grid, --mesh carries a mesh of the moving space into the fixed\n"
    "space (through the inverse), --png shows three slices through the fixed image's C: the fixed\n"
    "image in magenta and the moving in green (aligned structures look grey), and a checkerboard.";
  c.options = {
    { "fixed-landmarks", "FILE", "landmarks in the fixed image (JSON or .mrk.json)", "" },
    { "moving-landmarks", "FILE", "landmarks in the moving image", "" },
    { "landmarks", "A,B,C", "the three landmark ids, most certain first", "A,B,C" },
    { "distension", "MODE", "none, isotropic (one scale: B on B) or axes (along AB and toward C)", "none" },
    { "transform", "FILE", "write the transform (ITK's .tfm, or .h5)", "" },
    { "resampled", "FILE", "write the moving image resampled onto the fixed grid", "" },
    { "mesh", "IN", "carry the mesh IN (moving space) into the fixed space; OUT follows IN", "" },
    { "png", "FILE", "write a picture of the alignment (three orthogonal slices)", "" },
  };
  c.minimumPositional = 2;
  c.maximumPositional = 3;
  c.run = RunMatch;
  return c;
}
} // namespace MeshExtractionCLI
