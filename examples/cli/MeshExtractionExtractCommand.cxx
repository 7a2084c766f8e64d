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
// meshextraction extract: a surface mesh from an image (or a phantom) with SurfaceNets.

#include "MeshExtractionCLI.h"

#include "itkImageRegionConstIterator.h"
#include "itkImageRegionIterator.h"
#include "itkImplicitSurfaceImageSource.h"
#include "itkMultiLabelSurfaceNetsImageToMeshFilter.h"
#include "itkSurfaceNetsImageToMeshFilter.h"

#include <cctype>
#include <cmath>
#include <fstream>
#include <map>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <limits>

namespace MeshExtractionCLI
{
namespace
{
using SurfaceNetsEnums = itk::SurfaceNetsImageToMeshFilterEnums;
// The tool only writes the mesh: itk::Mesh is faster to fill than QuadEdgeMesh.
using ExtractMeshType = IOMeshType;

/** The parts of the extract options that do not depend on the pixel type. The
 * filter's own settings start as the filter's defaults (ExtractDefaults), so that the
 * options and their help text cannot drift from the filter. */
struct ExtractSettings
{
  // The tool's own.
  bool         byLabel{ false };
  std::string  labelImage;
  unsigned int threads{ 0 };                  // 0: the filter's default number of work units
  double       minimumComponentVoxels{ 0.0 }; // --min-component-voxels: in the input's voxel volumes
  // The filter's (ExtractDefaults sets them).
  double                          isoValue{};
  bool                            insideAbove{};
  double                          label{};
  SurfaceNetsEnums::Relaxation    relaxation{};
  unsigned int                    iterations{};
  SurfaceNetsEnums::Triangulation triangulation{};
  SurfaceNetsEnums::Gradient      gradient{};
  double                          sigma{};
  bool                            highQuality{};
  unsigned int                    rounds{};
  double                          convergedSwaps{};
  double                          cellDilation{};
  double                          labelSigma{};
  bool                            sliverRemoval{};
  bool                            remeshing{};
  double                          targetEdgeLength{};
  unsigned int                    remeshingIterations{};
  bool                            isotropic{};
  double                          minimumComponentVolume{};
};

/** The settings of a default-constructed SurfaceNetsImageToMeshFilter (the pixel type
 * does not change them). */
ExtractSettings
ExtractDefaults()
{
  const auto      filter = itk::SurfaceNetsImageToMeshFilter<itk::Image<float, 3>, ExtractMeshType>::New();
  ExtractSettings s;
  s.isoValue = filter->GetIsoValue();
  s.insideAbove = filter->GetInsideIsAboveIsoValue();
  s.label = filter->GetLabelValue();
  s.relaxation = filter->GetRelaxation();
  s.iterations = filter->GetMaximumNumberOfIterations();
  s.triangulation = filter->GetTriangulation();
  s.gradient = filter->GetGradientMethod();
  s.sigma = filter->GetGradientSigma();
  s.highQuality = filter->GetHighQuality();
  s.rounds = filter->GetNumberOfHighQualityRounds();
  s.convergedSwaps = filter->GetConvergedSwapFraction();
  s.cellDilation = filter->GetHighQualityCellDilation();
  s.labelSigma = filter->GetLabelSurfaceSigma();
  s.sliverRemoval = filter->GetHighQualitySliverRemoval();
  s.remeshing = filter->GetHighQualityRemeshing();
  s.targetEdgeLength = filter->GetHighQualityTargetEdgeLength();
  s.remeshingIterations = filter->GetHighQualityRemeshingIterations();
  s.isotropic = filter->GetResampleToIsotropicVoxels();
  s.minimumComponentVolume = filter->GetMinimumComponentVolume();
  return s;
}

/** The names --triangulation takes, with the filter's setting each names. */
const OptionNames<SurfaceNetsEnums::Triangulation> &
TriangulationNames()
{
  static const OptionNames<SurfaceNetsEnums::Triangulation> table = {
    { "shortest", SurfaceNetsEnums::Triangulation::ShortestDiagonal },
    { "delaunay", SurfaceNetsEnums::Triangulation::Delaunay },
    { "quads", SurfaceNetsEnums::Triangulation::Quadrilaterals },
  };
  return table;
}

SurfaceNetsEnums::Relaxation
RelaxationFromName(const std::string & name)
{
  if (name == "auto")
  {
    return SurfaceNetsEnums::Relaxation::Automatic;
  }
  if (name == "none")
  {
    return SurfaceNetsEnums::Relaxation::None;
  }
  if (name == "sna" || name == "averaging")
  {
    return SurfaceNetsEnums::Relaxation::Averaging;
  }
  if (name == "gradient")
  {
    return SurfaceNetsEnums::Relaxation::Gradient;
  }
  if (name == "snert" || name == "combined")
  {
    return SurfaceNetsEnums::Relaxation::Combined;
  }
  throw UsageError("--relaxation must be auto, none, sna, gradient or snert, got '" + name + "'");
}

// ------------------------------------------------------------------------------
// Running SurfaceNets
// ------------------------------------------------------------------------------
template <typename TFilter>
void
ConfigureFilter(TFilter * filter, const ExtractSettings & s)
{
  filter->SetIsoValue(s.isoValue);
  filter->SetInsideIsAboveIsoValue(s.insideAbove);
  filter->SetClassifyByLabel(s.byLabel && s.labelImage.empty());
  filter->SetLabelValue(s.label);
  filter->SetRelaxation(s.relaxation);
  filter->SetMaximumNumberOfIterations(s.iterations);
  filter->SetTriangulation(s.triangulation);
  filter->SetGradientMethod(s.gradient);
  filter->SetGradientSigma(s.sigma);
  filter->SetHighQuality(s.highQuality);
  filter->SetNumberOfHighQualityRounds(s.rounds);
  filter->SetConvergedSwapFraction(s.convergedSwaps);
  filter->SetHighQualityCellDilation(s.cellDilation);
  filter->SetLabelSurfaceSigma(s.labelSigma);
  filter->SetHighQualitySliverRemoval(s.sliverRemoval);
  filter->SetHighQualityRemeshing(s.remeshing);
  filter->SetHighQualityTargetEdgeLength(s.targetEdgeLength);
  filter->SetHighQualityRemeshingIterations(s.remeshingIterations);
  filter->SetResampleToIsotropicVoxels(s.isotropic);
  double minimumVolume = s.minimumComponentVolume;
  if (s.minimumComponentVoxels > 0.0)
  {
    const auto spacing = filter->GetInput()->GetSpacing();
    minimumVolume = s.minimumComponentVoxels * spacing[0] * spacing[1] * spacing[2];
  }
  filter->SetMinimumComponentVolume(minimumVolume);
  if (s.threads > 0)
  {
    filter->SetNumberOfWorkUnits(s.threads);
  }
}

/** With --isotropic: whether, and to what spacing, the image is resampled. */
template <typename TFilter, typename TImage>
void
PrintResampling(const TImage * image)
{
  if (const double spacing = TFilter::IsotropicResamplingSpacing(image))
  {
    std::cerr << "  resampling to cubic voxels of " << spacing << " mm (from " << image->GetSpacing() << ")\n";
  }
  else
  {
    std::cerr << "  the voxels are cubic already: not resampled\n";
  }
}

/** The line that sums up what the filter did. */
template <typename TFilter>
void
PrintFilterSummary(const TFilter * filter, const ExtractSettings & s, const Stopwatch & watch)
{
  std::cerr << "  " << filter->GetNumberOfNodes() << " nodes (" << filter->GetNumberOfSplitCells() << " split cells), "
            << filter->GetNumberOfIterations() << " relaxation iterations (last largest move "
            << filter->GetLastMaximumRelocation() << " voxel), " << filter->GetNumberOfNodesMovedBack()
            << " nodes moved back";
  if (s.highQuality)
  {
    std::cerr << ", " << filter->GetNumberOfSwaps() << " swaps in " << filter->GetNumberOfRoundsPerformed()
              << " rounds";
    if (s.remeshing)
    {
      std::cerr << ", remeshing: " << filter->GetNumberOfSplits() << " splits, "
                << filter->GetNumberOfRemeshingCollapses() << " collapses, " << filter->GetNumberOfRemeshingSwaps()
                << " swaps in " << filter->GetNumberOfRemeshingRounds() << " rounds (at most "
                << 2 * s.remeshingIterations << ")";
    }
    if (s.sliverRemoval)
    {
      std::cerr << ", slivers: " << filter->GetNumberOfCollapses() << " collapses, " << filter->GetNumberOfSliverSwaps()
                << " swaps, " << filter->GetNumberOfSliverMoves() << " moves";
    }
  }
  if (filter->GetMinimumComponentVolume() > 0.0)
  {
    std::cerr << ", " << filter->GetNumberOfComponentsRemoved() << " components below "
              << filter->GetMinimumComponentVolume() << " mm^3 removed (" << filter->GetNumberOfFacesRemoved()
              << " faces)";
  }
  std::cerr << ", " << std::fixed << std::setprecision(3) << watch.Seconds() << " s\n" << std::defaultfloat;
}

/** Reads the --labels file into the filter's label pixel type, refusing labels that
 * type cannot hold (a cast would turn 257 into 1) and a --label it cannot name. */
template <typename TLabelImage>
typename TLabelImage::Pointer
ReadLabelImage(const std::string & path, double label)
{
  using PixelType = typename TLabelImage::PixelType;
  const double lowest = static_cast<double>(std::numeric_limits<PixelType>::lowest());
  const double highest = static_cast<double>(std::numeric_limits<PixelType>::max());
  if (!(label >= lowest && label <= highest && label == std::floor(label)))
  {
    throw UsageError("--label " + std::to_string(label) + " with --labels must be an integer in [" +
                     std::to_string(lowest) + ", " + std::to_string(highest) + "]");
  }
  ReadScalarVolumeInformation(path, "--labels");
  const auto wide = ReadImageFile<itk::Image<double, 3>>(path);
  const auto region = wide->GetBufferedRegion();
  auto       labels = TLabelImage::New();
  labels->CopyInformation(wide);
  labels->SetRegions(region);
  labels->Allocate();
  const double *    in = wide->GetBufferPointer();
  PixelType *       out = labels->GetBufferPointer();
  const std::size_t count = region.GetNumberOfPixels();
  for (std::size_t i = 0; i < count; ++i)
  {
    if (!(in[i] >= lowest && in[i] <= highest && in[i] == std::floor(in[i])))
    {
      itkGenericExceptionMacro("'" << path << "' has the label " << in[i] << " (voxel " << i
                                   << " of the buffer): --labels takes integer labels in [" << lowest << ", " << highest
                                   << "]");
    }
    out[i] = static_cast<PixelType>(in[i]);
  }
  return labels;
}

template <typename TImage>
ExtractMeshType::Pointer
RunSurfaceNets(const TImage * image, const ExtractSettings & s)
{
  // --labels files hold labels of up to 32 bits (FreeSurfer's, TotalSegmentator's, ITK-SNAP's).
  using FilterType = itk::SurfaceNetsImageToMeshFilter<TImage, ExtractMeshType, itk::Image<unsigned int, 3>>;
  auto filter = FilterType::New();
  filter->SetInput(image);
  ConfigureFilter(filter.GetPointer(), s);
  typename FilterType::LabelImageType::Pointer labels;
  if (!s.labelImage.empty())
  {
    labels = ReadLabelImage<typename FilterType::LabelImageType>(s.labelImage, s.label);
    filter->SetLabelImage(labels);
  }
  if (s.isotropic)
  {
    PrintResampling<FilterType>(image);
  }
  ReportProgress(filter.GetPointer(), "SurfaceNets");
  Stopwatch watch;
  filter->Update();
  PrintFilterSummary(filter.GetPointer(), s, watch);
  ExtractMeshType::Pointer mesh = filter->GetOutput();
  mesh->DisconnectPipeline();
  return mesh;
}

/** Reads INPUT with its own pixel type and extracts. */
ExtractMeshType::Pointer
ExtractFromFile(const std::string & path, const ExtractSettings & s)
{
  auto io = ReadScalarVolumeInformation(path, "SurfaceNets");
  using IOComponent = itk::IOComponentEnum;
  switch (io->GetComponentType())
  {
    case IOComponent::UCHAR:
      return RunSurfaceNets(ReadImageFile<itk::Image<unsigned char, 3>>(path).GetPointer(), s);
    case IOComponent::CHAR:
      return RunSurfaceNets(ReadImageFile<itk::Image<signed char, 3>>(path).GetPointer(), s);
    case IOComponent::USHORT:
      return RunSurfaceNets(ReadImageFile<itk::Image<unsigned short, 3>>(path).GetPointer(), s);
    case IOComponent::SHORT:
      return RunSurfaceNets(ReadImageFile<itk::Image<short, 3>>(path).GetPointer(), s);
    case IOComponent::UINT:
    case IOComponent::INT:
    case IOComponent::ULONG:
    case IOComponent::LONG:
    case IOComponent::ULONGLONG:
    case IOComponent::LONGLONG:
    case IOComponent::DOUBLE:
      return RunSurfaceNets(ReadImageFile<itk::Image<double, 3>>(path).GetPointer(), s);
    default:
      return RunSurfaceNets(ReadImageFile<itk::Image<float, 3>>(path).GetPointer(), s);
  }
}

/** Extracts from --phantom (the iso-value its image needs, unless --iso is given); the
 * phantom's exact surface goes to `exact`. */
ExtractMeshType::Pointer
ExtractFromPhantom(const Arguments & args, ExtractSettings & s, itk::ImplicitSurfaceFunction::Pointer & exact)
{
  const ME::PhantomShape shape = ShapeFromName(args.Get("phantom"));
  const ME::PhantomGrid  grid = GridFromArguments(shape, args);
  const auto             parameters = ME::DefaultPhantomImageParameters(shape);
  if (!args.Has("iso"))
  {
    // Distance maps: the zero level, inside negative; blurred steps: half-way.
    const bool step = parameters.mode == itk::MeshExtractionEnums::PhantomImage::BlurredStep;
    s.isoValue = step ? 0.5 * (parameters.insideValue + parameters.outsideValue) : 0.0;
    s.insideAbove = step;
  }
  std::cerr << "extract: phantom " << ME::PhantomShapeName(shape) << " (" << grid.size << " voxels)\n";
  auto source = ME::MakePhantomImageSource<itk::Image<float, 3>>(shape, grid, parameters);
  source->Update();
  ExtractMeshType::Pointer mesh = RunSurfaceNets(source->GetOutput(), s);
  exact = ME::MakePhantomSurface(shape, grid);
  return mesh;
}

// ------------------------------------------------------------------------------
// Options
// ------------------------------------------------------------------------------
/** A count option that must not be negative. */
unsigned int
NonNegative(const Arguments & args, const std::string & name, unsigned int fallback)
{
  const long value = args.GetInteger(name, static_cast<long>(fallback));
  if (value < 0)
  {
    throw UsageError("--" + name + " must be >= 0");
  }
  return static_cast<unsigned int>(value);
}

/** What the object is: --iso and --inside, --label, --labels. */
void
ReadObjectOptions(const Arguments & args, bool fromPhantom, ExtractSettings & s)
{
  s.byLabel = args.Has("label");
  s.label = args.GetDouble("label", s.label);
  s.labelImage = args.Get("labels");
  if (!fromPhantom && !args.Has("iso") && !s.byLabel)
  {
    throw UsageError("give the iso-value (--iso V) or the object's label (--label L)");
  }
  if (args.Has("labels") && !args.Has("iso"))
  {
    throw UsageError("--labels relaxes a segmentation toward the iso-surface of INPUT: give --iso too");
  }
  s.isoValue = args.GetDouble("iso", s.isoValue);
  const std::string inside = args.Get("inside", s.insideAbove ? "above" : "below");
  if (inside != "above" && inside != "below")
  {
    throw UsageError("--inside must be above or below, got '" + inside + "'");
  }
  s.insideAbove = inside == "above";
}

/** How the net is relaxed and triangulated, the high-quality mode, the threads. */
void
ReadMeshingOptions(const Arguments & args, ExtractSettings & s)
{
  if (args.Has("relaxation"))
  {
    s.relaxation = RelaxationFromName(args.Get("relaxation"));
  }
  s.iterations = NonNegative(args, "iterations", s.iterations);
  s.triangulation = ChooseOption(args, "triangulation", TriangulationNames(), s.triangulation);
  if (args.Has("sigma"))
  {
    s.gradient = SurfaceNetsEnums::Gradient::GaussianDerivative;
    s.sigma = args.GetDouble("sigma", s.sigma);
  }
  const std::string qualityMode = args.Get("quality", s.highQuality ? "high" : "standard");
  if (qualityMode != "standard" && qualityMode != "high")
  {
    throw UsageError("--quality must be standard or high, got '" + qualityMode + "'");
  }
  s.highQuality = qualityMode == "high";
  s.rounds = NonNegative(args, "rounds", s.rounds);
  s.convergedSwaps = args.GetDouble("converged-swaps", s.convergedSwaps); // the filter checks the range
  s.cellDilation = args.GetDouble("cell-dilation", s.cellDilation);       // so does this one
  s.labelSigma = args.GetDouble("label-sigma", s.labelSigma);             // and this one
  const std::string sliverMode = args.Get("sliver-removal", s.sliverRemoval ? "on" : "off");
  if (sliverMode != "on" && sliverMode != "off")
  {
    throw UsageError("--sliver-removal must be on or off, got '" + sliverMode + "'");
  }
  s.sliverRemoval = sliverMode == "on";
  const std::string remeshMode = args.Get("remeshing", s.remeshing ? "on" : "off");
  if (remeshMode != "on" && remeshMode != "off")
  {
    throw UsageError("--remeshing must be on or off, got '" + remeshMode + "'");
  }
  s.remeshing = remeshMode == "on";
  s.targetEdgeLength = args.GetDouble("target-edge-length", s.targetEdgeLength); // the filter checks it
  s.remeshingIterations = NonNegative(args, "remeshing-iterations", s.remeshingIterations);
  s.isotropic = s.isotropic || args.Has("isotropic");
  s.threads = NonNegative(args, "threads", 0);
  SetDicomSeries(args.Get("series"));
  if (args.Has("min-component-volume") && args.Has("min-component-voxels"))
  {
    throw UsageError("give --min-component-volume or --min-component-voxels, not both");
  }
  s.minimumComponentVolume = args.GetDouble("min-component-volume", s.minimumComponentVolume); // the filter checks it
  s.minimumComponentVoxels = args.GetDouble("min-component-voxels", 0.0);
  if (!(s.minimumComponentVoxels >= 0.0 && std::isfinite(s.minimumComponentVoxels)))
  {
    throw UsageError("--min-component-voxels must be a number >= 0");
  }
}

/** --report and --report-json: the quality (and distances to a phantom's exact surface). */
void
ReportOnMesh(const Arguments &                    args,
             const ExtractMeshType *              mesh,
             const itk::ImplicitSurfaceFunction * exact,
             const std::string &                  output)
{
  MeasureSettings settings;
  settings.referenceSurface = exact;
  const MeasuredMesh measured = MeasureMesh(mesh, output, settings);
  if (args.Has("report"))
  {
    PrintMeasuredMesh(measured, output, std::cout);
  }
  if (args.Has("report-json"))
  {
    WriteJSON({ measured }, args.Get("report-json"));
  }
}

// ------------------------------------------------------------------------------
// Every label of a label map (--all-labels, --label-list)
// ------------------------------------------------------------------------------
/** A label's voxels: how many, and their bounding box (buffer indices). */
struct LabelExtent
{
  std::size_t  voxels{ 0 };
  std::int64_t lower[3]{ std::numeric_limits<std::int64_t>::max(),
                         std::numeric_limits<std::int64_t>::max(),
                         std::numeric_limits<std::int64_t>::max() };
  std::int64_t upper[3]{ -1, -1, -1 };
};

using LabelMapType = itk::Image<unsigned int, 3>;
using MaskType = itk::Image<unsigned char, 3>;

/** Every non-zero label's voxels and bounding box, in one pass. */
std::map<unsigned int, LabelExtent>
MeasureLabels(const LabelMapType * labels)
{
  std::map<unsigned int, LabelExtent> extents;
  const auto                          size = labels->GetBufferedRegion().GetSize();
  const unsigned int *                buffer = labels->GetBufferPointer();
  LabelExtent *                       last = nullptr;
  unsigned int                        lastLabel = 0;
  std::size_t                         i = 0;
  for (std::int64_t z = 0; z < static_cast<std::int64_t>(size[2]); ++z)
  {
    for (std::int64_t y = 0; y < static_cast<std::int64_t>(size[1]); ++y)
    {
      for (std::int64_t x = 0; x < static_cast<std::int64_t>(size[0]); ++x, ++i)
      {
        const unsigned int label = buffer[i];
        if (label == 0)
        {
          continue;
        }
        if (last == nullptr || label != lastLabel)
        {
          last = &extents[label];
          lastLabel = label;
        }
        ++last->voxels;
        const std::int64_t at[3] = { x, y, z };
        for (unsigned int d = 0; d < 3; ++d)
        {
          last->lower[d] = std::min(last->lower[d], at[d]);
          last->upper[d] = std::max(last->upper[d], at[d]);
        }
      }
    }
  }
  return extents;
}

/** The label's voxels (1) in its bounding box and one voxel around it, clipped to the
 * image, in physical space where the label map has them: its surface is the one the
 * whole image gives, for far less work when the label is small. */
MaskType::Pointer
CropLabelMask(const LabelMapType * labels, unsigned int label, const LabelExtent & extent)
{
  const auto               size = labels->GetBufferedRegion().GetSize();
  const auto               first = labels->GetBufferedRegion().GetIndex();
  LabelMapType::RegionType region;
  for (unsigned int d = 0; d < 3; ++d)
  {
    const std::int64_t lower = std::max<std::int64_t>(0, extent.lower[d] - 1);
    const std::int64_t upper = std::min<std::int64_t>(static_cast<std::int64_t>(size[d]) - 1, extent.upper[d] + 1);
    region.SetIndex(d, first[d] + lower);
    region.SetSize(d, static_cast<itk::SizeValueType>(upper - lower + 1));
  }
  auto mask = MaskType::New();
  mask->SetRegions(region);
  mask->SetSpacing(labels->GetSpacing());
  mask->SetOrigin(labels->GetOrigin());
  mask->SetDirection(labels->GetDirection());
  mask->Allocate();
  itk::ImageRegionConstIterator<LabelMapType> in(labels, region);
  itk::ImageRegionIterator<MaskType>          out(mask, region);
  for (; !in.IsAtEnd(); ++in, ++out)
  {
    out.Set(in.Get() == label ? 1 : 0);
  }
  return mask;
}

/** Label names from a colour table: 3D Slicer's (.ctbl, .txt: "index name r g b a") or
 * ITK-SNAP's label description ("index r g b a visible mesh \"name\""); '#' starts a
 * comment. A line that names no integer index is refused with its number. */
std::map<unsigned int, std::string>
ReadLabelNames(const std::string & path)
{
  std::ifstream in(path);
  if (!in)
  {
    itkGenericExceptionMacro("cannot read the label names '" << path << "'");
  }
  std::map<unsigned int, std::string> names;
  std::string                         line;
  for (unsigned int number = 1; std::getline(in, line); ++number)
  {
    const auto start = line.find_first_not_of(" \t\r");
    if (start == std::string::npos || line[start] == '#')
    {
      continue;
    }
    std::istringstream fields(line);
    long               index = -1;
    if (!(fields >> index) || index < 0 || index > std::numeric_limits<unsigned int>::max())
    {
      itkGenericExceptionMacro("'" << path << "', line " << number << ": no label index (a non-negative integer)");
    }
    std::string name;
    const auto  quote = line.find('"');
    if (quote != std::string::npos)
    {
      const auto end = line.find('"', quote + 1);
      name = line.substr(quote + 1, end == std::string::npos ? std::string::npos : end - quote - 1);
    }
    else
    {
      fields >> name;
    }
    names[static_cast<unsigned int>(index)] = name;
  }
  return names;
}

/** OUTPUT with the label (and its name, letters, digits, '-' and '_' kept) before the
 * extension: out.vtk -> out-3-liver.vtk. */
std::string
LabelOutputName(const std::string & output, unsigned int label, const std::string & name)
{
  std::string tag = std::to_string(label);
  if (!name.empty())
  {
    tag += '-';
    for (char c : name)
    {
      tag += (std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_') ? c : '_';
    }
  }
  const auto dot = output.find_last_of('.');
  const auto slash = output.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash))
  {
    return output + '-' + tag;
  }
  return output.substr(0, dot) + '-' + tag + output.substr(dot);
}

/** The labels --label-list names, or every label of the map (--all-labels). */
std::vector<unsigned int>
ChosenLabels(const Arguments & args, const std::map<unsigned int, LabelExtent> & extents)
{
  std::vector<unsigned int> chosen;
  if (!args.Has("label-list"))
  {
    for (const auto & entry : extents)
    {
      chosen.push_back(entry.first);
    }
    return chosen;
  }
  std::string text = args.Get("label-list");
  for (char & c : text)
  {
    c = c == ',' ? ' ' : c;
  }
  std::istringstream in(text);
  std::string        token;
  while (in >> token)
  {
    const double v = Arguments::ParseDouble("label-list", token);
    if (!(v >= 1.0 && v <= std::numeric_limits<unsigned int>::max() && v == std::floor(v)))
    {
      throw UsageError("--label-list takes labels >= 1 (integers), got '" + token + "'");
    }
    if (extents.count(static_cast<unsigned int>(v)) == 0)
    {
      itkGenericExceptionMacro("the label map has no voxel with the label " << token);
    }
    chosen.push_back(static_cast<unsigned int>(v));
  }
  if (chosen.empty())
  {
    throw UsageError("--label-list names no label");
  }
  return chosen;
}

/** The name of label `label`'s file, and its name ("" without a colour table). */
std::string
LabelFileName(const std::string &                         output,
              unsigned int                                label,
              const std::map<unsigned int, std::string> & names,
              std::string &                               name)
{
  const auto found = names.find(label);
  name = found != names.end() ? found->second : std::string();
  return LabelOutputName(output, label, name);
}

/** --separate-labels (and --quality high): each label from its own crop of the map, as
 * a single-label extraction; neighbours' boundaries are made twice. */
int
RunSeparateLabels(const Arguments &                           args,
                  ExtractSettings                             s,
                  const MeshWriteSettings &                   writeSettings,
                  const LabelMapType *                        labels,
                  const std::map<unsigned int, LabelExtent> & extents,
                  const std::map<unsigned int, std::string> & names,
                  const std::vector<unsigned int> &           chosen)
{
  const std::string input = args.positional[0];
  const std::string output = args.positional[1];
  s.byLabel = true;
  s.label = 1.0; // of each label's crop, a mask
  std::ostringstream table;
  table << std::setw(10) << "label" << std::setw(12) << "voxels" << std::setw(10) << "points" << std::setw(10)
        << "faces"
        << "  file\n";
  for (const unsigned int label : chosen)
  {
    std::string       name;
    const std::string path = LabelFileName(output, label, names, name);
    std::cerr << "label " << label << (name.empty() ? "" : " (" + name + ")") << ": " << extents.at(label).voxels
              << " voxels\n";
    const auto mask = CropLabelMask(labels, label, extents.at(label));
    const auto mesh = RunSurfaceNets(mask.GetPointer(), s);
    WriteMeshFile(mesh.GetPointer(), path, writeSettings);
    table << std::setw(10) << label << std::setw(12) << extents.at(label).voxels << std::setw(10)
          << mesh->GetNumberOfPoints() << std::setw(10) << mesh->GetNumberOfCells() << "  " << path << '\n';
    if (args.Has("report"))
    {
      ReportOnMesh(args, mesh, nullptr, path);
    }
  }
  std::cout << chosen.size() << " labels of " << extents.size() << " in " << input << ", each on its own:\n"
            << table.str();
  return 0;
}

/** --label-thresholds T1,T2,...: a label map of a greyscale image, label k the voxels in
 * [T_k, T_k+1) (the last: from T_K up), 0 below T1; e.g. soft tissue and bone of a CT. */
LabelMapType::Pointer
ThresholdLabels(const std::string & path, const std::string & list)
{
  std::vector<double> thresholds;
  std::string         text = list;
  for (char & c : text)
  {
    c = c == ',' ? ' ' : c;
  }
  std::istringstream in(text);
  std::string        token;
  while (in >> token)
  {
    thresholds.push_back(Arguments::ParseDouble("label-thresholds", token));
    if (thresholds.size() > 1 && !(thresholds.back() > thresholds[thresholds.size() - 2]))
    {
      throw UsageError("--label-thresholds must increase, got '" + list + "'");
    }
  }
  if (thresholds.empty())
  {
    throw UsageError("--label-thresholds names no threshold");
  }
  ReadScalarVolumeInformation(path, "INPUT");
  const auto image = ReadImageFile<itk::Image<float, 3>>(path);
  auto       labels = LabelMapType::New();
  labels->CopyInformation(image);
  labels->SetRegions(image->GetBufferedRegion());
  labels->Allocate();
  const float *     v = image->GetBufferPointer();
  unsigned int *    out = labels->GetBufferPointer();
  const std::size_t count = image->GetBufferedRegion().GetNumberOfPixels();
  for (std::size_t i = 0; i < count; ++i)
  {
    if (std::isnan(v[i]))
    {
      itkGenericExceptionMacro("'" << path << "' has a NaN voxel (voxel " << i << " of the buffer)");
    }
    out[i] =
      static_cast<unsigned int>(std::upper_bound(thresholds.begin(), thresholds.end(), v[i]) - thresholds.begin());
  }
  return labels;
}

/** extract LABELS OUTPUT --all-labels: every label's closed surface in one pass, the
 * faces between neighbours shared (MultiLabelSurfaceNetsImageToMeshFilter), written as
 * OUTPUT-<label>[-<name>].<ext>; with --combined FILE also every face once, with the
 * two labels of each face (.vtk, .vtp: the cell array "labels"). */
int
RunAllLabels(const Arguments & args, ExtractSettings s, const MeshWriteSettings & writeSettings)
{
  const std::string input = args.positional[0];
  const std::string output = args.positional[1];
  std::cerr << "extract: " << input << ", every label\n";
  const auto labels = args.Has("label-thresholds") ? ThresholdLabels(input, args.Get("label-thresholds"))
                                                   : ReadLabelImage<LabelMapType>(input, 1.0);
  const auto extents = MeasureLabels(labels);
  if (extents.empty())
  {
    itkGenericExceptionMacro("'" << input << "' has no voxel with a label other than 0: there is no surface");
  }
  const auto names =
    args.Has("label-names") ? ReadLabelNames(args.Get("label-names")) : std::map<unsigned int, std::string>();
  const auto chosen = ChosenLabels(args, extents);
  if (s.highQuality || args.Has("separate-labels"))
  {
    if (args.Has("combined"))
    {
      throw UsageError("--combined needs the labels' shared faces: not with --separate-labels or --quality high");
    }
    return RunSeparateLabels(args, s, writeSettings, labels, extents, names, chosen);
  }
  using Filter = itk::MultiLabelSurfaceNetsImageToMeshFilter<LabelMapType, ExtractMeshType>;
  if (s.relaxation == SurfaceNetsEnums::Relaxation::Gradient || s.relaxation == SurfaceNetsEnums::Relaxation::Combined)
  {
    throw UsageError("--all-labels relaxes by averaging (sna) or not at all (none)");
  }
  if (s.triangulation == SurfaceNetsEnums::Triangulation::Quadrilaterals)
  {
    throw UsageError("--all-labels makes triangles: --triangulation shortest or delaunay");
  }
  auto filter = Filter::New();
  filter->SetInput(labels);
  filter->SetLabels(Filter::LabelListType(chosen.begin(), chosen.end()));
  filter->SetMaximumNumberOfIterations(s.relaxation == SurfaceNetsEnums::Relaxation::None ? 0 : s.iterations);
  filter->SetTriangulation(s.triangulation);
  if (s.threads > 0)
  {
    filter->SetNumberOfWorkUnits(s.threads);
  }
  ReportProgress(filter.GetPointer(), "SurfaceNets of every label");
  Stopwatch watch;
  filter->Update();
  std::cerr << "every label in one pass: " << std::fixed << std::setprecision(3) << watch.Seconds() << " s\n"
            << std::defaultfloat;
  const auto &                        faceLabels = filter->GetFaceLabels();
  std::map<unsigned int, std::size_t> sharedFaces;
  for (const auto & pair : faceLabels)
  {
    if (pair[0] != 0)
    {
      ++sharedFaces[pair[0]];
      ++sharedFaces[pair[1]];
    }
  }
  std::ostringstream table;
  table << std::setw(10) << "label" << std::setw(12) << "voxels" << std::setw(10) << "points" << std::setw(10)
        << "faces" << std::setw(10) << "shared"
        << "  file\n";
  for (const unsigned int label : chosen)
  {
    std::string       name;
    const std::string path = LabelFileName(output, label, names, name);
    const auto        mesh = filter->GetLabelSurface(label);
    WriteMeshFile(mesh.GetPointer(), path, writeSettings);
    table << std::setw(10) << label << std::setw(12) << extents.at(label).voxels << std::setw(10)
          << mesh->GetNumberOfPoints() << std::setw(10) << mesh->GetNumberOfCells() << std::setw(10)
          << sharedFaces[label] << "  " << path << '\n';
    if (args.Has("report"))
    {
      ReportOnMesh(args, mesh, nullptr, path);
    }
  }
  if (args.Has("combined"))
  {
    ME::PolygonMesh            combined = ME::MakePolygonMeshFromMesh(*filter->GetOutput());
    ME::PolygonMesh::CellArray pairs;
    pairs.name = "labels";
    pairs.components = 2;
    for (const auto & pair : faceLabels)
    {
      pairs.values.push_back(pair[0]);
      pairs.values.push_back(pair[1]);
    }
    combined.cellArrays.push_back(std::move(pairs));
    ME::WritePolygonMeshFile(args.Get("combined"), combined, writeSettings.options);
  }
  std::cout << chosen.size() << " labels of " << extents.size() << " in " << input
            << ", in one pass: " << faceLabels.size() << " faces, " << filter->GetOutput()->GetNumberOfPoints()
            << " nodes (" << filter->GetNumberOfJunctionNodes() << " on junctions of 3 or more labels, "
            << filter->GetNumberOfPinchedNodes() << " where a label touches itself, "
            << filter->GetNumberOfNodesMovedBack() << " moved back), " << filter->GetNumberOfIterations()
            << " iterations\n"
            << table.str();
  if (args.Has("combined"))
  {
    std::cout << "every face once, with its two labels: " << args.Get("combined") << '\n';
  }
  return 0;
}

int
RunExtract(const Arguments & args)
{
  ExtractSettings s = ExtractDefaults();
  const bool      fromPhantom = args.Has("phantom");
  if (fromPhantom == (args.positional.size() == 2))
  {
    throw UsageError(fromPhantom ? "with --phantom give only OUTPUT" : "'extract' expects INPUT and OUTPUT");
  }
  const std::string              output = args.positional.back();
  const std::vector<std::string> inputs{ fromPhantom ? std::string() : args.positional[0], args.Get("labels") };
  RequireNotAnInput(output, inputs, "OUTPUT");
  const MeshWriteSettings writeSettings = ReadMeshWriteSettings(args);
  RequireNotAnInput(args.Get("report-json"), inputs, "--report-json");
  RequireNotAnInput(args.Get("combined"), inputs, "--combined");
  if (args.Has("all-labels") || args.Has("label-list") || args.Has("label-thresholds"))
  {
    if (fromPhantom || args.Has("labels") || args.Has("label") || args.Has("iso") || args.Has("report-json"))
    {
      throw UsageError("--all-labels and --label-list take a label map as INPUT, without --phantom, --labels, "
                       "--label, --iso or --report-json");
    }
    ReadMeshingOptions(args, s);
    return RunAllLabels(args, s, writeSettings);
  }
  if (args.Has("label-names") || args.Has("combined") || args.Has("separate-labels"))
  {
    throw UsageError("--label-names, --combined and --separate-labels go with --all-labels or --label-list");
  }
  ReadObjectOptions(args, fromPhantom, s);
  ReadMeshingOptions(args, s);

  ExtractMeshType::Pointer              mesh;
  itk::ImplicitSurfaceFunction::Pointer exact;
  if (fromPhantom)
  {
    mesh = ExtractFromPhantom(args, s, exact);
  }
  else
  {
    std::cerr << "extract: " << args.positional[0] << '\n';
    mesh = ExtractFromFile(args.positional[0], s);
  }
  WriteMeshFile(mesh.GetPointer(), output, writeSettings);
  std::cerr << "  wrote " << output << " (" << mesh->GetNumberOfPoints() << " points, " << mesh->GetNumberOfCells()
            << " faces)\n";
  if (args.Has("report") || args.Has("report-json"))
  {
    ReportOnMesh(args, mesh, exact, output);
  }
  return 0;
}
} // namespace

/** The 3D Slicer Execution Model description of extract: the options a Slicer user
 * sets, with the filter's defaults. Slicer passes every parameter, so the label mode
 * (whose option switches the mode by being present) is not among them: a label map is
 * extracted with --iso 0.5 --inside above. */
std::string
ExtractSlicerXML()
{
  const ExtractSettings d = ExtractDefaults();
  std::ostringstream    x;
  x << "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n<executable>\n"
    << "  <category>Surface Models</category>\n  <title>MeshExtraction SurfaceNets</title>\n"
    << "  <description><![CDATA[A closed, 2-manifold, outward-oriented surface mesh of the voxels above (or below) "
       "an iso-value, by SurfaceNets with SNERT relaxation (P.W. de Bruin, thesis, TU Delft 2004); the high-quality "
       "mode gives near-equilateral triangles.]]></description>\n"
    << "  <version>" << MeshExtractionVersion() << "</version>\n  <license>Apache 2.0</license>\n"
    << "  <contributor>ITK MeshExtraction</contributor>\n"
    << "  <parameters>\n    <label>Input and output</label>\n"
    << "    <image><name>input</name><label>Input volume</label><channel>input</channel><index>0</index>"
       "<description>A 3-D scalar image</description></image>\n"
    << "    <geometry fileExtensions=\".vtk\"><name>output</name><label>Output model</label><channel>output</channel>"
       "<index>1</index><description>The surface mesh</description></geometry>\n  </parameters>\n"
    << "  <parameters>\n    <label>Object</label>\n"
    << "    <double><name>iso</name><longflag>iso</longflag><label>Iso-value</label><default>" << d.isoValue
    << "</default><description>The boundary between object and background</description></double>\n"
    << "    <string-enumeration><name>inside</name><longflag>inside</longflag><label>Object is</label><default>"
    << (d.insideAbove ? "above" : "below") << "</default><element>above</element><element>below</element>"
    << "<description>Which side of the iso-value is the object</description></string-enumeration>\n"
    << "    <double><name>minComponentVolume</name><longflag>min-component-volume</longflag><label>Smallest "
       "component (mm^3)</label><default>"
    << d.minimumComponentVolume
    << "</default><description>Drop closed components that enclose less (0: keep all)</description></double>\n"
    << "  </parameters>\n  <parameters>\n    <label>Meshing</label>\n"
    << "    <string-enumeration><name>quality</name><longflag>quality</longflag><label>Quality</label><default>"
    << (d.highQuality ? "high" : "standard") << "</default><element>standard</element><element>high</element>"
    << "<description>high: regularity edge swaps alternating with SNERT</description></string-enumeration>\n"
    << "    <string-enumeration><name>relaxation</name><longflag>relaxation</longflag><label>Relaxation</label>"
       "<default>auto</default><element>auto</element><element>none</element><element>sna</element>"
       "<element>gradient</element><element>snert</element><description>auto: SNERT</description>"
       "</string-enumeration>\n"
    << "    <integer><name>iterations</name><longflag>iterations</longflag><label>Iterations</label><default>"
    << d.iterations << "</default><description>Largest number of relaxation iterations</description></integer>\n"
    << "    <boolean><name>isotropic</name><longflag>isotropic</longflag><label>Resample to cubic voxels</label>"
       "<default>false</default><description>Better shaped triangles on anisotropic voxels</description>"
       "</boolean>\n"
    << "  </parameters>\n</executable>\n";
  return x.str();
}

Command
MakeExtractCommand()
{
  const ExtractSettings defaults = ExtractDefaults();
  Command               c;
  c.name = "extract";
  c.summary = "extract a surface mesh with SurfaceNets (SNA, SNERT)";
  c.usage = "INPUT OUTPUT [options]   |   meshextraction extract --phantom NAME OUTPUT [options]";
  c.description = "Extracts a closed, 2-manifold, outward-oriented triangle mesh from a 3-D image (any format ITK\n"
                  "reads, or a DICOM series directory) with SurfaceNets (thesis chapter 3) and writes it in the\n"
                  "format OUTPUT's extension names (.vtk, .vtp, .ply, .stl, .obj, .off, .gii, .byu). The object\n"
                  "is the voxels above (or below) --iso; or the voxels equal to --label in a label image; or a\n"
                  "segmentation (--labels FILE, voxels equal to --label) relaxed toward INPUT's --iso surface.\n"
                  "SNERT (the default for greyscale input) puts the nodes on the trilinear iso-surface and spaces\n"
                  "them out; SNA only averages. Coordinates are physical (spacing, origin, direction).";
  c.options = {
    { "iso", "V", "iso-value of the object's boundary", "0 for a phantom", OptionRange::Any() },
    { "inside", "above|below", "which side of --iso is the object", defaults.insideAbove ? "above" : "below" },
    { "label",
      "L",
      "the object is the voxels equal to L (INPUT or --labels is a label image)",
      DefaultText(defaults.label),
      OptionRange::Any() },
    { "labels",
      "FILE",
      "segmentation (integer labels, 0 to 2^32 - 1) whose --label voxels give the net, relaxed toward INPUT's "
      "iso-surface",
      "" },
    { "all-labels",
      "",
      "INPUT is a label map: one closed surface per non-zero label, written as OUTPUT-<label>[-<name>].<ext>, "
      "in one pass: neighbours share the faces of their boundary (SNA; --quality high: each label on its own)",
      "" },
    { "combined",
      "FILE",
      "with --all-labels: also every face once, with its two labels (lower first; the normal points out of the "
      "lower, 0 the outside) as the cell array 'labels' in .vtk and .vtp",
      "" },
    { "separate-labels", "", "with --all-labels: each label from its own voxels, as --label would", "" },
    { "label-list", "L,L,...", "--all-labels for these labels only", "", OptionRange::Between(1, 4294967295.0) },
    { "label-thresholds",
      "T,T,...",
      "--all-labels of INPUT's voxels by value: label k in [T_k, T_k+1), the last from T_K up, 0 below T_1 "
      "(e.g. -300,300: soft tissue and bone of a CT)",
      "",
      OptionRange::Any() },
    { "label-names",
      "FILE",
      "names for the files from a colour table (3D Slicer .ctbl, or an ITK-SNAP label description)",
      "" },
    { "phantom", "NAME", "extract from a built-in phantom instead of INPUT (see 'phantom list')", "" },
    { "relaxation", "MODE", "auto, none, sna, gradient or snert", "auto: snert, or sna for labels" },
    { "iterations",
      "N",
      "maximum relaxation iterations",
      DefaultText(defaults.iterations),
      OptionRange::Between(0, 10000) },
    { "triangulation",
      "MODE",
      OptionChoices(TriangulationNames()),
      OptionName(TriangulationNames(), defaults.triangulation) },
    { "sigma",
      "MM",
      "Gaussian-derivative gradients of this scale instead of central differences",
      "",
      OptionRange::AboveUpTo(0, 100) },
    { "quality",
      "standard|high",
      "high: alternate regularity edge swaps with SNERT on the triangles",
      defaults.highQuality ? "high" : "standard" },
    { "rounds",
      "N",
      "rounds of swaps and relaxation for --quality high",
      DefaultText(defaults.rounds),
      OptionRange::Between(0, 1000) },
    { "converged-swaps",
      "F",
      "--quality high stops its rounds when one swaps fewer than this fraction of the triangles (0: none)",
      DefaultText(defaults.convergedSwaps),
      OptionRange::Between(0, 1) },
    { "cell-dilation",
      "V",
      "--quality high lets a node leave its cell by up to V voxels (0: stay in the cell)",
      DefaultText(defaults.cellDilation),
      OptionRange::Between(0, 0.5) },
    { "label-sigma",
      "V",
      "--quality high on a label image: fit the surface to the voxels' smoothed signed distance at this scale in "
      "voxels (0: average only, which shrinks it)",
      DefaultText(defaults.labelSigma),
      OptionRange::Between(0, 16) },
    { "sliver-removal",
      "on|off",
      "--quality high: collapse, swap or move around the triangles with q_angle below 0.3 that the rounds leave",
      defaults.sliverRemoval ? "on" : "off" },
    { "remeshing",
      "on|off",
      "--quality high: isotropic remeshing (splits, collapses, valence swaps, relaxation onto the iso-surface) "
      "to --target-edge-length: near-equilateral triangles on anisotropic voxels without resampling",
      defaults.remeshing ? "on" : "off" },
    { "target-edge-length",
      "MM",
      "--remeshing on: the edge length it aims at (0: the mean voxel spacing)",
      DefaultText(defaults.targetEdgeLength),
      OptionRange::Between(0, 1e6) },
    { "remeshing-iterations",
      "N",
      "--remeshing on: rounds of splits, collapses and swaps, each with a relaxation, then as many of quality "
      "swaps and relaxation",
      DefaultText(defaults.remeshingIterations),
      OptionRange::Between(0, 1000) },
    { "isotropic",
      "",
      "resample to cubic voxels of the smallest spacing first: better shaped, more triangles on anisotropic voxels",
      "" },
    { "min-component-volume",
      "MM3",
      "drop closed components (islands, and cavities) enclosing less than this volume (0: keep all)",
      DefaultText(defaults.minimumComponentVolume),
      OptionRange::Between(0, 1e18) },
    { "min-component-voxels",
      "N",
      "the same, in voxels of INPUT (N x the voxel volume)",
      "0",
      OptionRange::Between(0, 1e18) },
    { "series", "UID", "the DICOM series to read when INPUT is a directory (default: the first; all are listed)", "" },
    { "threads", "N", "work units (0: all cores)", "0", OptionRange::Between(0, 1024) },
    { "report", "", "print the quality report (and distances to a phantom's exact surface)", "" },
    { "report-json", "FILE", "write the report as JSON", "" },
  };
  for (const auto & o : GridOptions())
  {
    c.options.push_back(o);
  }
  for (const auto & o : MeshWriteOptions())
  {
    c.options.push_back(o);
  }
  c.minimumPositional = 1;
  c.maximumPositional = 2;
  c.run = RunExtract;
  c.slicerXML = ExtractSlicerXML;
  return c;
}

} // namespace MeshExtractionCLI
