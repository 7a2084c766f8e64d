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
// meshextraction phantom: one of the module's analytic phantoms rendered into an image.

#include "MeshExtractionCLI.h"

#include "itkImplicitSurfaceImageSource.h"

#include <iostream>

namespace MeshExtractionCLI
{
namespace
{
using PhantomImage = itk::MeshExtractionEnums::PhantomImage;

template <typename TPixel>
void
WritePhantom(ME::PhantomShape                   shape,
             const ME::PhantomGrid &            grid,
             const ME::PhantomImageParameters & parameters,
             const std::string &                output)
{
  using ImageType = itk::Image<TPixel, 3>;
  auto source = ME::MakePhantomImageSource<ImageType>(shape, grid, parameters);
  ReportProgress(source.GetPointer(), "rendering " + ME::PhantomShapeName(shape));
  source->Update();
  WriteImageFile(source->GetOutput(), output);
}

/** --image-mode: what the voxels hold; a mask is 1 inside and 0 outside unless --inside says otherwise. */
void
ReadImageMode(const Arguments & args, ME::PhantomImageParameters & p)
{
  const std::string mode = args.Get("image-mode");
  if (mode == "distance")
  {
    p.mode = PhantomImage::DistanceMap;
  }
  else if (mode == "mask")
  {
    p.mode = PhantomImage::BinaryMask;
  }
  else if (mode == "step")
  {
    p.mode = PhantomImage::BlurredStep;
  }
  else
  {
    throw UsageError("--image-mode must be distance, mask or step, got '" + mode + "'");
  }
  if (p.mode == PhantomImage::BinaryMask && !args.Has("inside"))
  {
    p.insideValue = 1.0;
    p.outsideValue = 0.0;
  }
}

/** The phantom's default image parameters, changed by the options given. */
ME::PhantomImageParameters
ImageParametersFromArguments(ME::PhantomShape shape, const Arguments & args)
{
  ME::PhantomImageParameters p = ME::DefaultPhantomImageParameters(shape);
  if (args.Has("image-mode"))
  {
    ReadImageMode(args, p);
  }
  p.distanceScale = args.GetDouble("distance-scale", p.distanceScale);
  p.insideValue = args.GetDouble("inside", p.insideValue);
  p.outsideValue = args.GetDouble("outside", p.outsideValue);
  p.edgeWidth = args.GetDouble("edge-width", p.edgeWidth);
  p.noiseStandardDeviation = args.GetDouble("noise", p.noiseStandardDeviation);
  p.noiseSeed = static_cast<std::uint64_t>(args.GetInteger("seed", static_cast<long>(p.noiseSeed)));
  return p;
}

/** Writes the phantom with the pixel type named by --pixel-type. */
void
WritePhantomOfType(const std::string &                type,
                   ME::PhantomShape                   shape,
                   const ME::PhantomGrid &            grid,
                   const ME::PhantomImageParameters & p,
                   const std::string &                output)
{
  if (type == "float")
  {
    WritePhantom<float>(shape, grid, p, output);
  }
  else if (type == "double")
  {
    WritePhantom<double>(shape, grid, p, output);
  }
  else if (type == "uchar")
  {
    WritePhantom<unsigned char>(shape, grid, p, output);
  }
  else if (type == "short")
  {
    WritePhantom<short>(shape, grid, p, output);
  }
  else if (type == "ushort")
  {
    WritePhantom<unsigned short>(shape, grid, p, output);
  }
  else
  {
    throw UsageError("--pixel-type must be uchar, short, ushort, float or double, got '" + type + "'");
  }
}

int
RunPhantom(const Arguments & args)
{
  if (args.positional[0] == "list")
  {
    for (auto shape : ME::AllPhantomShapes())
    {
      std::cout << ME::PhantomShapeName(shape) << '\n';
    }
    return 0;
  }
  if (args.positional.size() != 2)
  {
    throw UsageError("'phantom' expects NAME and OUTPUT (or 'list')");
  }
  const ME::PhantomShape           shape = ShapeFromName(args.positional[0]);
  const ME::PhantomGrid            grid = GridFromArguments(shape, args);
  const ME::PhantomImageParameters p = ImageParametersFromArguments(shape, args);
  const std::string                defaultType = p.mode == PhantomImage::BinaryMask ? "uchar" : "float";
  const std::string                type = args.Get("pixel-type", defaultType);
  const std::string &              output = args.positional[1];
  if (p.mode == PhantomImage::DistanceMap && (type == "uchar" || type == "ushort"))
  {
    // The distances inside the object are negative: an unsigned pixel would clip them to 0.
    throw UsageError("a distance map is negative inside the object: --pixel-type " + type +
                     " cannot hold it (use short, float or double)");
  }
  std::cerr << "phantom " << ME::PhantomShapeName(shape) << ": " << grid.size << " voxels of " << grid.spacing
            << " mm, " << p.mode << ", " << type << " -> " << output << '\n';
  WritePhantomOfType(type, shape, grid, p, output);
  return 0;
}
} // namespace

Command
MakePhantomCommand()
{
  Command c;
  c.name = "phantom";
  c.summary = "write a phantom image (plane, sphere, two spheres, ellipsoid, torus, ...)";
  c.usage = "NAME OUTPUT [options]   |   meshextraction phantom list";
  c.description = "Renders one of the module's analytic phantoms into an image (any format ITK writes, by the\n"
                  "extension of OUTPUT). The surface is exact: `quality --phantom NAME --image OUTPUT` measures\n"
                  "meshes against it. Distance maps hold the signed distance in mm (negative inside, iso-value 0);\n"
                  "masks hold --inside / --outside; the chapter4-sphere is a blurred step edge (inside 100,\n"
                  "outside 0) to which --noise adds Gaussian noise. `phantom list` prints the names.";
  c.options = GridOptions();
  c.options.push_back({ "image-mode", "distance|mask|step", "what the voxels hold", "per phantom" });
  c.options.push_back({ "pixel-type", "TYPE", "uchar, short, ushort, float or double", "float; uchar for masks" });
  c.options.push_back({ "distance-scale", "S", "distance map value per mm", "1", OptionRange::AboveUpTo(0, 1e6) });
  c.options.push_back(
    { "inside", "V", "mask/step value inside", "1 (mask), 100 (step)", OptionRange::Between(-1e20, 1e20) });
  c.options.push_back({ "outside", "V", "mask/step value outside", "0", OptionRange::Between(-1e20, 1e20) });
  c.options.push_back(
    { "edge-width", "MM", "standard deviation of the blurred step", "1", OptionRange::AboveUpTo(0, 1e3) });
  c.options.push_back({ "noise", "SIGMA", "additive Gaussian noise", "0", OptionRange::Between(0, 1e20) });
  c.options.push_back({ "seed", "N", "noise seed", "0", OptionRange::Between(0, 2147483647) });
  c.minimumPositional = 1;
  c.maximumPositional = 2;
  c.run = RunPhantom;
  return c;
}

} // namespace MeshExtractionCLI
