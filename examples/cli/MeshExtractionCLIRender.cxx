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
// A small software renderer for reports: orthographic, z-buffered, flat-shaded
// triangles, optionally coloured by a per-triangle value and outlined, written as
// PNG through ITK. It needs no display or OpenGL, so reports render on a headless
// build machine.

#include "MeshExtractionCLI.h"

#include "itkImageFileWriter.h"
#include "itkRGBPixel.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace MeshExtractionCLI
{
namespace
{
using PixelType = itk::RGBPixel<unsigned char>;
using RGBImageType = itk::Image<PixelType, 2>;

/** Colour ramp for a value in [0, 1]: dark red (0, bad) - orange - yellow - green - blue (1, good). */
PixelType
QualityColour(double v)
{
  static const double stops[5][3] = {
    { 0.55, 0.0, 0.05 }, { 0.95, 0.45, 0.1 }, { 0.98, 0.85, 0.25 }, { 0.45, 0.8, 0.35 }, { 0.2, 0.45, 0.85 }
  };
  v = std::clamp(v, 0.0, 1.0) * 4.0;
  const int    i = std::min(3, static_cast<int>(v));
  const double t = v - i;
  PixelType    c;
  for (unsigned int k = 0; k < 3; ++k)
  {
    c[k] = static_cast<unsigned char>(255.0 * ((1 - t) * stops[i][k] + t * stops[i + 1][k]));
  }
  return c;
}

/** The mesh's points in screen coordinates: x to the right and y down, in pixels, the
 * mesh centred and filling the view; the third coordinate is the depth (smaller is
 * nearer). The view rotates about z (azimuth), then tilts (elevation), and looks
 * along -y'. */
std::vector<ME::Vec3>
ProjectToScreen(const ME::IndexedTriangleMesh & mesh, const RenderOptions & o)
{
  const double az = o.azimuthDegrees * itk::Math::pi / 180.0;
  const double el = o.elevationDegrees * itk::Math::pi / 180.0;
  auto         view = [&](const ME::Vec3 & p) {
    const double x = std::cos(az) * p[0] + std::sin(az) * p[1];
    const double y = -std::sin(az) * p[0] + std::cos(az) * p[1];
    const double z = p[2];
    // screen x, screen y (up), depth (smaller = nearer)
    return ME::MakeVec3(x, std::cos(el) * z - std::sin(el) * y, std::cos(el) * y + std::sin(el) * z);
  };
  std::vector<ME::Vec3> projected(mesh.points.size());
  double                lo[2] = { std::numeric_limits<double>::max(), std::numeric_limits<double>::max() };
  double                hi[2] = { std::numeric_limits<double>::lowest(), std::numeric_limits<double>::lowest() };
  for (std::size_t i = 0; i < mesh.points.size(); ++i)
  {
    projected[i] = view(mesh.points[i]);
    for (unsigned int k = 0; k < 2; ++k)
    {
      lo[k] = std::min(lo[k], projected[i][k]);
      hi[k] = std::max(hi[k], projected[i][k]);
    }
  }
  const double extent = std::max(hi[0] - lo[0], hi[1] - lo[1]) + 1e-12;
  const double scale = 0.92 * std::min(o.width, o.height) / extent * o.zoom;
  const double cx = 0.5 * (lo[0] + hi[0]);
  const double cy = 0.5 * (lo[1] + hi[1]);
  for (auto & p : projected)
  {
    p[0] = 0.5 * o.width + (p[0] - cx) * scale;
    p[1] = 0.5 * o.height - (p[1] - cy) * scale;
  }
  return projected;
}

/** The flat-shaded colour of triangle `f` (screen corners a, b, c): its value's
 * colour, or grey, lit from a fixed direction. */
PixelType
ShadedColour(const ME::Vec3 & a, const ME::Vec3 & b, const ME::Vec3 & c, std::size_t f, const RenderOptions & o)
{
  const ME::Vec3 light = ME::MakeVec3(-0.3, 0.5, -0.8) * (1.0 / std::sqrt(0.09 + 0.25 + 0.64));
  // Normal in view space (screen y points down: flip it back).
  ME::Vec3 n = ME::TriangleUnitNormal(
    ME::MakeVec3(a[0], -a[1], a[2]), ME::MakeVec3(b[0], -b[1], b[2]), ME::MakeVec3(c[0], -c[1], c[2]));
  const double shade = 0.25 + 0.75 * std::abs(ME::Dot(n, light));
  PixelType    base;
  if (o.triangleValues != nullptr)
  {
    base = QualityColour((*o.triangleValues)[f]);
  }
  else
  {
    base.Set(205, 200, 190);
  }
  PixelType colour;
  for (unsigned int k = 0; k < 3; ++k)
  {
    colour[k] = static_cast<unsigned char>(std::min(255.0, base[k] * shade));
  }
  return colour;
}

/** The image and its depth buffer. */
struct Canvas
{
  RGBImageType::Pointer image;
  std::vector<double>   depth;
};

/** Draws the pixels of the triangle a, b, c (screen coordinates) that are nearer than
 * what is drawn there already, darker near its edges if the triangles are outlined. */
void
RasteriseTriangle(const ME::Vec3 &      a,
                  const ME::Vec3 &      b,
                  const ME::Vec3 &      c,
                  const PixelType &     colour,
                  const RenderOptions & o,
                  Canvas &              canvas)
{
  const double area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
  if (std::abs(area) < 1e-12)
  {
    return;
  }
  PixelType * buffer = canvas.image->GetBufferPointer();
  const int   x0 = std::max(0, static_cast<int>(std::floor(std::min({ a[0], b[0], c[0] }))));
  const int   x1 = std::min(static_cast<int>(o.width) - 1, static_cast<int>(std::ceil(std::max({ a[0], b[0], c[0] }))));
  const int   y0 = std::max(0, static_cast<int>(std::floor(std::min({ a[1], b[1], c[1] }))));
  const int y1 = std::min(static_cast<int>(o.height) - 1, static_cast<int>(std::ceil(std::max({ a[1], b[1], c[1] }))));
  for (int y = y0; y <= y1; ++y)
  {
    for (int x = x0; x <= x1; ++x)
    {
      const double px = x + 0.5;
      const double py = y + 0.5;
      const double w0 = ((b[0] - px) * (c[1] - py) - (b[1] - py) * (c[0] - px)) / area;
      const double w1 = ((c[0] - px) * (a[1] - py) - (c[1] - py) * (a[0] - px)) / area;
      const double w2 = 1.0 - w0 - w1;
      if (w0 < 0 || w1 < 0 || w2 < 0)
      {
        continue;
      }
      const double      z = w0 * a[2] + w1 * b[2] + w2 * c[2];
      const std::size_t k = static_cast<std::size_t>(y) * o.width + x;
      if (z < canvas.depth[k])
      {
        canvas.depth[k] = z;
        const bool edge = o.outlineTriangles && std::min({ w0, w1, w2 }) * std::sqrt(std::abs(area)) < 0.6;
        buffer[k] = colour;
        if (edge)
        {
          buffer[k].Set(colour[0] / 3, colour[1] / 3, colour[2] / 3);
        }
      }
    }
  }
}

/** A blank canvas of the options' size. */
Canvas
BlankCanvas(const RenderOptions & o)
{
  Canvas                 canvas;
  RGBImageType::SizeType size = { { o.width, o.height } };
  canvas.image = RGBImageType::New();
  canvas.image->SetRegions(size);
  canvas.image->Allocate();
  PixelType background;
  background.Set(250, 250, 252);
  canvas.image->FillBuffer(background);
  canvas.depth.assign(static_cast<std::size_t>(o.width) * o.height, std::numeric_limits<double>::infinity());
  return canvas;
}

void
WriteRGBImage(const RGBImageType * image, const std::string & path)
{
  WriteWhole(path, [image](const std::string & partial) {
    auto writer = itk::ImageFileWriter<RGBImageType>::New();
    writer->SetInput(image);
    writer->SetFileName(partial);
    writer->Update();
  });
}
} // namespace

void
RenderMesh(const ME::IndexedTriangleMesh & mesh, const RenderOptions & options, const std::string & path)
{
  Canvas                      canvas = BlankCanvas(options);
  const std::vector<ME::Vec3> projected = ProjectToScreen(mesh, options);
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f)
  {
    const auto &     t = mesh.triangles[f];
    const ME::Vec3 & a = projected[t[0]];
    const ME::Vec3 & b = projected[t[1]];
    const ME::Vec3 & c = projected[t[2]];
    RasteriseTriangle(a, b, c, ShadedColour(a, b, c, f, options), options, canvas);
  }
  WriteRGBImage(canvas.image, path);
}

} // namespace MeshExtractionCLI
