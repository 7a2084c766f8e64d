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
// meshextraction-contours: the interactive editor of connected orthogonal contours
// (thesis chapter 5, section 5.2.6). Three orthogonal slice views and a 3-D view.
//
// Keys (in the view under the mouse): Up/Down scroll the slice; a add a contour in the
// slice's plane; d remove the contours of that plane; e EDEMS (the slice's control
// points to the nearest edge); u undo; s save the model and the mesh; r refine the mesh
// with chapter 4 (shown in the 3-D view); i list the slice's control points; q quit. Drag a control point with the left
// button along its line (its colour is that of its line's axis: x red, y yellow, z blue);
// contours are green; where a plane without contours cuts the model, purple points.
#include "MeshExtractionCLI.h"
#include "itkOrthogonalContourModel.h"
#include "itkOrthogonalContourModelEdgeDetector.h"
#include "itkOrthogonalContourModelToMeshFilter.h"
#include "itkScaleSpaceEdgeMeshRefinementFilter.h"

#include <vtkActor.h>
#include <vtkCallbackCommand.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkImageDifference.h>
#include <vtkImageProperty.h>
#include <vtkImageSlice.h>
#include <vtkImageSliceMapper.h>
#include <vtkInteractorEventRecorder.h>
#include <vtkInteractorStyleTrackballCamera.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>
#include <vtkPNGWriter.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkWindowToImageFilter.h>

#include <array>
#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace
{
using ImageType = itk::Image<float, 3>;
using ModelType = itk::OrthogonalContourModel;
using MeshType = itk::QuadEdgeMesh<double, 3>;

/** The colours of the planes and of the lines along their normals (section 5.2.6). */
const double AxisColours[3][3] = { { 1.0, 0.1, 0.1 }, { 1.0, 0.9, 0.1 }, { 0.2, 0.4, 1.0 } };
const double ContourColour[3] = { 0.1, 0.9, 0.2 };
const double IntersectionColour[3] = { 0.7, 0.2, 0.9 };

struct Options
{
  std::string image;
  std::string model;
  std::string outputModel{ "contours.json" };
  std::string outputMesh{ "contours.vtk" };
  std::string replay;
  std::string screenshot;
  std::string baseline;
  double      threshold{ 10.0 };
  double      capture{ 4.0 };
  int         windowSize{ 800 };
};

Options
ParseOptions(int argc, char * argv[])
{
  Options options;
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    auto              value = [&]() -> std::string {
      if (i + 1 >= argc)
      {
        throw std::runtime_error(arg + " needs a value");
      }
      return argv[++i];
    };
    if (arg == "--model")
      options.model = value();
    else if (arg == "--output-model")
      options.outputModel = value();
    else if (arg == "--output-mesh")
      options.outputMesh = value();
    else if (arg == "--replay")
      options.replay = value();
    else if (arg == "--screenshot")
      options.screenshot = value();
    else if (arg == "--baseline")
      options.baseline = value();
    else if (arg == "--threshold")
      options.threshold = std::stod(value());
    else if (arg == "--capture")
      options.capture = std::stod(value());
    else if (arg == "--window-size")
      options.windowSize = std::stoi(value());
    else if (!arg.empty() && arg[0] != '-' && options.image.empty())
      options.image = arg;
    else
      throw std::runtime_error("unknown argument " + arg);
  }
  if (options.image.empty())
  {
    throw std::runtime_error("usage: meshextraction-contours IMAGE [--model M.json] [--output-model M.json] "
                             "[--output-mesh MESH] [--capture MM] [--replay EVENTS --screenshot PNG [--baseline PNG "
                             "--threshold T]] [--window-size PIXELS]");
  }
  return options;
}

/** The image as vtkImageData in display coordinates (index times spacing). */
vtkSmartPointer<vtkImageData>
ToVTK(const ImageType * image)
{
  const auto size = image->GetLargestPossibleRegion().GetSize();
  auto       data = vtkSmartPointer<vtkImageData>::New();
  data->SetDimensions(static_cast<int>(size[0]), static_cast<int>(size[1]), static_cast<int>(size[2]));
  data->SetSpacing(image->GetSpacing()[0], image->GetSpacing()[1], image->GetSpacing()[2]);
  data->SetOrigin(0.0, 0.0, 0.0);
  data->AllocateScalars(VTK_FLOAT, 1);
  std::copy(image->GetBufferPointer(),
            image->GetBufferPointer() + image->GetLargestPossibleRegion().GetNumberOfPixels(),
            static_cast<float *>(data->GetScalarPointer()));
  return data;
}

/** A poly data of points and lines with per-point colours, and its actor. */
struct Overlay
{
  vtkNew<vtkPoints>            points;
  vtkNew<vtkCellArray>         lines;
  vtkNew<vtkCellArray>         vertices;
  vtkNew<vtkUnsignedCharArray> colours;
  vtkNew<vtkPolyData>          data;
  vtkNew<vtkPolyDataMapper>    mapper;
  vtkNew<vtkActor>             actor;

  Overlay()
  {
    colours->SetNumberOfComponents(3);
    data->SetPoints(points);
    data->SetLines(lines);
    data->SetVerts(vertices);
    data->GetPointData()->SetScalars(colours);
    mapper->SetInputData(data);
    actor->SetMapper(mapper);
    actor->GetProperty()->SetPointSize(9.0);
    actor->GetProperty()->SetLineWidth(2.0);
  }
  void
  Clear()
  {
    points->Reset();
    lines->Reset();
    vertices->Reset();
    colours->Reset();
  }
  vtkIdType
  Add(const std::array<double, 3> & x, const double colour[3])
  {
    colours->InsertNextTuple3(255.0 * colour[0], 255.0 * colour[1], 255.0 * colour[2]);
    return points->InsertNextPoint(x.data());
  }
  void
  Done()
  {
    points->Modified();
    lines->Modified();
    vertices->Modified();
    colours->Modified();
    data->Modified();
  }
};
} // namespace

namespace
{
/** The editor: the model, its undo stack, the four views and what they show. */
class ContourEditor
{
public:
  ContourEditor(ImageType::Pointer image, ModelType::Pointer model, const Options & options)
      : m_Image(std::move(image))
      , m_Model(std::move(model))
      , m_Options(options)
  {
    m_Detector = itk::OrthogonalContourModelEdgeDetector<ImageType>::New();
    m_Detector->SetImage(m_Image);
    m_Detector->SetModel(m_Model);
    m_Detector->SetCaptureRange(options.capture);
    for (unsigned int a = 0; a < 3; ++a)
    {
      m_Slice[a] = static_cast<int>(std::lround(m_Model->GetControlPointIndex(0)[a]));
      const auto in = m_Model->GetContoursInPlane(a, m_Slice[a]);
      for (unsigned int c = 0; c < m_Model->GetNumberOfContours() && in.empty(); ++c)
      {
        m_Slice[a] = m_Model->GetContourAxis(c) == a ? static_cast<int>(m_Model->GetContourPosition(c)) : m_Slice[a];
      }
    }
  }

  void
  Build(vtkRenderWindow * window)
  {
    const auto data = ToVTK(m_Image);
    double     range[2];
    data->GetScalarRange(range);
    const double viewports[4][4] = {
      { 0.0, 0.5, 0.5, 1.0 }, { 0.5, 0.5, 1.0, 1.0 }, { 0.0, 0.0, 0.5, 0.5 }, { 0.5, 0.0, 1.0, 0.5 }
    };
    for (unsigned int v = 0; v < 4; ++v)
    {
      m_Renderers[v]->SetViewport(viewports[v]);
      window->AddRenderer(m_Renderers[v]);
    }
    for (unsigned int a = 0; a < 3; ++a)
    {
      m_SliceMappers[a]->SetInputData(data);
      m_SliceMappers[a]->SetOrientation(static_cast<int>(a));
      m_Slices[a]->SetMapper(m_SliceMappers[a]);
      m_Slices[a]->GetProperty()->SetColorWindow(range[1] - range[0]);
      m_Slices[a]->GetProperty()->SetColorLevel(0.5 * (range[0] + range[1]));
      m_Renderers[a]->AddViewProp(m_Slices[a]);
      m_Renderers[a]->AddActor(m_Overlays[a].actor);
      this->SetUpCamera(a);
    }
    m_Renderers[3]->AddActor(m_Overlays[3].actor);
    m_MeshActor->SetMapper(m_MeshMapper);
    m_MeshActor->GetProperty()->SetColor(0.9, 0.8, 0.7);
    m_Renderers[3]->AddActor(m_MeshActor);
    this->Refresh();
    m_Renderers[3]->ResetCamera();
    m_Renderers[3]->GetActiveCamera()->Elevation(30.0);
    m_Renderers[3]->GetActiveCamera()->Azimuth(30.0);
  }

  /** Which view (0-2: the planes of axis x, y, z; 3: 3-D) holds the display point. */
  int
  ViewAt(int x, int y, vtkRenderWindow * window) const
  {
    const int * size = window->GetSize();
    const int   column = 2 * x >= size[0] ? 1 : 0;
    const int   row = 2 * y >= size[1] ? 0 : 1;
    return 2 * row + column;
  }

  /** A key in view `view`; false if it is not the editor's. */
  bool
  Key(const std::string & key, int view)
  {
    const bool inPlane = view >= 0 && view < 3;
    if ((key == "Up" || key == "Down") && inPlane)
    {
      m_Slice[view] += key == "Up" ? 1 : -1;
      m_Slice[view] = std::max(0, std::min(m_Slice[view], static_cast<int>(m_Model->GetSize()[view]) - 1));
    }
    else if (key == "a" && inPlane)
    {
      this->Apply("add contour", [&] { return m_Model->AddContour(view, m_Slice[view]); });
    }
    else if (key == "d" && inPlane)
    {
      this->Apply("remove contours", [&] { return m_Model->RemoveContourPlane(view, m_Slice[view]); });
    }
    else if (key == "e" && inPlane)
    {
      this->Apply("EDEMS", [&] { return m_Detector->MoveControlPointsInPlane(view, m_Slice[view]) > 0; });
    }
    else if (key == "u")
    {
      this->Undo();
    }
    else if (key == "s")
    {
      this->Save();
    }
    else if (key == "r")
    {
      this->Refine();
    }
    else if (key == "i" && inPlane)
    {
      this->PrintControlPoints(view);
    }
    else
    {
      return false;
    }
    this->Refresh();
    return true;
  }

  /** The left button went down at display (x, y) in view `view`: picks the nearest
   * control point of the slice within a few voxels. */
  bool
  Press(int view, int x, int y)
  {
    m_Dragged = -1;
    if (view < 0 || view > 2)
    {
      return false;
    }
    const auto   world = this->World(view, x, y);
    const auto & spacing = m_Image->GetSpacing();
    double       best = 3.0 * std::max({ spacing[0], spacing[1], spacing[2] });
    for (const auto p : m_Model->GetControlPointsInPlane(view, m_Slice[view]))
    {
      const auto q = m_Model->GetControlPointIndex(p);
      double     d2 = 0.0;
      for (unsigned int i = 0; i < 3; ++i)
      {
        d2 += i == static_cast<unsigned int>(view) ? 0.0 : std::pow(q[i] * spacing[i] - world[i], 2);
      }
      if (std::sqrt(d2) < best)
      {
        best = std::sqrt(d2);
        m_Dragged = static_cast<int>(p);
      }
    }
    m_DragView = view;
    return m_Dragged >= 0;
  }

  /** The button went up: the dragged point moves along its line to the mouse. */
  bool
  Release(int x, int y)
  {
    if (m_Dragged < 0)
    {
      return false;
    }
    const auto         p = static_cast<unsigned int>(m_Dragged);
    const unsigned int line = m_Model->GetControlPointLineAxis(p);
    const double       target = this->World(m_DragView, x, y)[line] / m_Image->GetSpacing()[line];
    this->Apply("move control point", [&] { return m_Model->MoveControlPoint(p, target); });
    m_Dragged = -1;
    this->Refresh();
    return true;
  }

  /** The model's state, one line of JSON. */
  std::string
  State() const
  {
    std::ostringstream os;
    os << "{\"contours\": " << m_Model->GetNumberOfContours()
       << ", \"control_points\": " << m_Model->GetNumberOfControlPoints() << ", \"undo\": " << m_Undo.size()
       << ", \"invariants\": \"" << (m_Model->CheckInvariants().empty() ? "ok" : "broken")
       << "\", \"volume\": " << m_Model->GetVolume() << "}";
    return os.str();
  }

private:
  /** The control points of the view's slice: identifier, line axis, continuous index
   * and display position (pixels), for scripting interactions. */
  void
  PrintControlPoints(int view) const
  {
    for (const auto p : m_Model->GetControlPointsInPlane(view, m_Slice[view]))
    {
      const auto x = m_Model->GetControlPointIndex(p);
      const auto w = this->Display(x, view);
      m_Renderers[view]->SetWorldPoint(w[0], w[1], w[2], 1.0);
      m_Renderers[view]->WorldToDisplay();
      const double * d = m_Renderers[view]->GetDisplayPoint();
      std::cout << "control point " << p << ": line "
                << "xyz"[m_Model->GetControlPointLineAxis(p)] << ", index " << x << ", display " << std::lround(d[0])
                << ' ' << std::lround(d[1]) << std::endl;
    }
  }

  template <typename TOperation>
  void
  Apply(const char * what, TOperation && operation)
  {
    const std::string before = m_Model->ToJSON();
    if (operation())
    {
      m_Undo.push_back(before);
      std::cout << what << ": " << this->State() << std::endl;
    }
    else
    {
      std::cout << what << ": refused: " << m_Model->GetRefusalReason() << std::endl;
    }
  }

  void
  Undo()
  {
    if (!m_Undo.empty())
    {
      m_Model->FromJSON(m_Undo.back(), "the undo stack");
      m_Undo.pop_back();
      std::cout << "undo: " << this->State() << std::endl;
    }
  }

  void
  Save()
  {
    m_Model->Write(m_Options.outputModel);
    MeshExtractionCLI::WriteMeshFile(this->CurrentMesh(), m_Options.outputMesh);
    std::cout << "saved " << m_Options.outputModel << " and " << m_Options.outputMesh << std::endl;
  }

  void
  Refine()
  {
    auto mesher = itk::OrthogonalContourModelToMeshFilter<MeshType>::New();
    mesher->SetInput(m_Model);
    auto refinement = itk::ScaleSpaceEdgeMeshRefinementFilter<MeshType, ImageType>::New();
    refinement->SetInput(mesher->GetOutput());
    refinement->SetInputImage(m_Image);
    refinement->SetMaximumDeviation(m_Options.capture);
    refinement->Update();
    m_Refined = refinement->GetOutput();
    m_Refined->DisconnectPipeline();
    m_RefinedTime = m_Model->GetMTime();
    std::cout << "refined: " << refinement->GetNumberOfCycles() << " cycles" << std::endl;
  }

  /** The refined mesh if the model has not changed since, else the model's mesh. */
  MeshType::Pointer
  CurrentMesh() const
  {
    if (m_Refined && m_RefinedTime == m_Model->GetMTime())
    {
      return m_Refined;
    }
    auto mesher = itk::OrthogonalContourModelToMeshFilter<MeshType>::New();
    mesher->SetInput(m_Model);
    mesher->Update();
    MeshType::Pointer mesh = mesher->GetOutput();
    mesh->DisconnectPipeline();
    return mesh;
  }

  std::array<double, 3>
  World(int view, int x, int y) const
  {
    vtkRenderer * renderer = m_Renderers[view];
    renderer->SetDisplayPoint(x, y, 0.0);
    renderer->DisplayToWorld();
    double w[4];
    renderer->GetWorldPoint(w);
    return { { w[0] / w[3], w[1] / w[3], w[2] / w[3] } };
  }

  void
  SetUpCamera(unsigned int a)
  {
    const auto & spacing = m_Image->GetSpacing();
    const auto   size = m_Image->GetLargestPossibleRegion().GetSize();
    double       centre[3];
    for (unsigned int i = 0; i < 3; ++i)
    {
      centre[i] = 0.5 * spacing[i] * static_cast<double>(size[i] - 1);
    }
    vtkCamera * camera = m_Renderers[a]->GetActiveCamera();
    camera->ParallelProjectionOn();
    camera->SetFocalPoint(centre);
    double position[3] = { centre[0], centre[1], centre[2] };
    position[a] += 1000.0;
    camera->SetPosition(position);
    camera->SetViewUp(a == 2 ? 0.0 : 0.0, a == 2 ? 1.0 : 0.0, a == 2 ? 0.0 : 1.0);
    m_Renderers[a]->ResetCamera();
  }

  /** The display point of continuous index x in view a (just in front of the slice). */
  std::array<double, 3>
  Display(const ModelType::ContinuousIndexType & x, int a) const
  {
    std::array<double, 3> p;
    for (unsigned int i = 0; i < 3; ++i)
    {
      p[i] = x[i] * m_Image->GetSpacing()[i];
    }
    if (a >= 0)
    {
      p[a] = (m_Slice[a] + 0.2) * m_Image->GetSpacing()[a];
    }
    return p;
  }

  void
  AddContourLines(Overlay & overlay, unsigned int c, int a)
  {
    const auto samples = m_Model->SampleContour(c, 8);
    const auto first = overlay.points->GetNumberOfPoints();
    for (const auto & x : samples)
    {
      overlay.Add(this->Display(x, a), ContourColour);
    }
    overlay.lines->InsertNextCell(static_cast<vtkIdType>(samples.size() + 1));
    for (std::size_t i = 0; i <= samples.size(); ++i)
    {
      overlay.lines->InsertCellPoint(first + static_cast<vtkIdType>(i % samples.size()));
    }
  }

  void
  AddCrossHair(Overlay & overlay, unsigned int a)
  {
    const auto size = m_Image->GetLargestPossibleRegion().GetSize();
    for (unsigned int b = 0; b < 3; ++b)
    {
      if (b == a)
      {
        continue;
      }
      const unsigned int             c = 3 - a - b;
      ModelType::ContinuousIndexType x;
      x[a] = m_Slice[a];
      x[b] = m_Slice[b];
      x[c] = 0.0;
      const vtkIdType from = overlay.Add(this->Display(x, static_cast<int>(a)), AxisColours[b]);
      x[c] = static_cast<double>(size[c] - 1);
      const vtkIdType to = overlay.Add(this->Display(x, static_cast<int>(a)), AxisColours[b]);
      const vtkIdType line[2] = { from, to };
      overlay.lines->InsertNextCell(2, line);
    }
  }

  void
  RefreshView(unsigned int a)
  {
    m_SliceMappers[a]->SetSliceNumber(m_Slice[a]);
    Overlay & overlay = m_Overlays[a];
    overlay.Clear();
    this->AddCrossHair(overlay, a);
    const auto contours = m_Model->GetContoursInPlane(a, m_Slice[a]);
    for (const auto c : contours)
    {
      this->AddContourLines(overlay, c, static_cast<int>(a));
    }
    for (const auto p : m_Model->GetControlPointsInPlane(a, m_Slice[a]))
    {
      overlay.vertices->InsertNextCell(1);
      overlay.vertices->InsertCellPoint(
        overlay.Add(this->Display(m_Model->GetControlPointIndex(p), static_cast<int>(a)),
                    AxisColours[m_Model->GetControlPointLineAxis(p)]));
    }
    if (contours.empty())
    {
      for (const auto & x : m_Model->GetPlaneIntersections(a, m_Slice[a]))
      {
        overlay.vertices->InsertNextCell(1);
        overlay.vertices->InsertCellPoint(overlay.Add(this->Display(x, static_cast<int>(a)), IntersectionColour));
      }
    }
    overlay.Done();
  }

  void
  RefreshMesh()
  {
    const MeshType::Pointer mesh = this->CurrentMesh();
    vtkNew<vtkPoints>       points;
    for (MeshType::PointIdentifier i = 0; i < mesh->GetNumberOfPoints(); ++i)
    {
      const auto p = mesh->GetPoint(i);
      // Display coordinates: the grid's index times spacing.
      itk::ContinuousIndex<double, 3> x =
        m_Image->TransformPhysicalPointToContinuousIndex<double, double>(itk::Point<double, 3>(p.GetDataPointer()));
      points->InsertNextPoint(
        x[0] * m_Image->GetSpacing()[0], x[1] * m_Image->GetSpacing()[1], x[2] * m_Image->GetSpacing()[2]);
    }
    vtkNew<vtkCellArray> triangles;
    for (auto it = mesh->GetCells()->Begin(); it != mesh->GetCells()->End(); ++it)
    {
      if (it.Value()->GetNumberOfPoints() == 3)
      {
        const auto *    ids = it.Value()->GetPointIds();
        const vtkIdType triangle[3] = { static_cast<vtkIdType>(ids[0]),
                                        static_cast<vtkIdType>(ids[1]),
                                        static_cast<vtkIdType>(ids[2]) };
        triangles->InsertNextCell(3, triangle);
      }
    }
    m_Mesh->SetPoints(points);
    m_Mesh->SetPolys(triangles);
    m_MeshMapper->SetInputData(m_Mesh);
  }

  void
  Refresh()
  {
    for (unsigned int a = 0; a < 3; ++a)
    {
      this->RefreshView(a);
    }
    Overlay & overlay = m_Overlays[3];
    overlay.Clear();
    for (unsigned int c = 0; c < m_Model->GetNumberOfContours(); ++c)
    {
      this->AddContourLines(overlay, c, -1);
    }
    overlay.Done();
    this->RefreshMesh();
  }

  ImageType::Pointer                                          m_Image;
  ModelType::Pointer                                          m_Model;
  Options                                                     m_Options;
  itk::OrthogonalContourModelEdgeDetector<ImageType>::Pointer m_Detector;
  std::array<int, 3>                                          m_Slice{ { 0, 0, 0 } };
  std::vector<std::string>                                    m_Undo;
  int                                                         m_Dragged{ -1 };
  int                                                         m_DragView{ 0 };
  MeshType::Pointer                                           m_Refined;
  itk::ModifiedTimeType                                       m_RefinedTime{ 0 };
  vtkNew<vtkRenderer>                                         m_Renderers[4];
  vtkNew<vtkImageSliceMapper>                                 m_SliceMappers[3];
  vtkNew<vtkImageSlice>                                       m_Slices[3];
  Overlay                                                     m_Overlays[4];
  vtkNew<vtkPolyData>                                         m_Mesh;
  vtkNew<vtkPolyDataMapper>                                   m_MeshMapper;
  vtkNew<vtkActor>                                            m_MeshActor;
};

/** What the interactor's observer needs. */
struct EventContext
{
  ContourEditor *             editor{ nullptr };
  vtkRenderWindowInteractor * interactor{ nullptr };
  vtkCallbackCommand *        command{ nullptr };
};

/** The editor's keys and mouse in the slice views; everything else (the 3-D view's
 * trackball) goes on to the interactor style. */
void
OnEvent(vtkObject *, unsigned long event, void * clientData, void *)
{
  auto &      context = *static_cast<EventContext *>(clientData);
  const int * position = context.interactor->GetEventPosition();
  const int   view = context.editor->ViewAt(position[0], position[1], context.interactor->GetRenderWindow());
  bool        handled = false;
  switch (event)
  {
    case vtkCommand::KeyPressEvent:
    {
      const char * keysym = context.interactor->GetKeySym();
      handled = keysym != nullptr && context.editor->Key(keysym, view);
      break;
    }
    case vtkCommand::CharEvent:
      // The style's own keys (e: exit, w: wireframe, ...) would clash: only q quits.
      handled = context.interactor->GetKeyCode() != 'q';
      break;
    case vtkCommand::LeftButtonPressEvent:
      context.editor->Press(view, position[0], position[1]);
      handled = view < 3;
      break;
    case vtkCommand::LeftButtonReleaseEvent:
      handled = context.editor->Release(position[0], position[1]) || view < 3;
      break;
    case vtkCommand::MouseMoveEvent:
      handled = view < 3;
      break;
    default:
      break;
  }
  if (handled)
  {
    context.command->SetAbortFlag(1);
    context.interactor->GetRenderWindow()->Render();
  }
}

ModelType::Pointer
MakeModel(const ImageType * image, const std::string & file)
{
  auto model = ModelType::New();
  model->SetGrid(image);
  if (!file.empty())
  {
    model->Read(file);
    return model;
  }
  const auto           size = image->GetLargestPossibleRegion().GetSize();
  ModelType::IndexType centre;
  ModelType::RadiiType radii;
  for (unsigned int a = 0; a < 3; ++a)
  {
    centre[a] = static_cast<itk::IndexValueType>(size[a] / 2);
    radii[a] = std::max(1.0, std::floor(static_cast<double>(std::min({ size[0], size[1], size[2] })) / 4.0));
  }
  model->InitializeTemplate(centre, radii);
  return model;
}

/** Replays the recorded events, writes the screenshot and compares it with the
 * baseline; returns the exit status. */
int
Replay(const Options &             options,
       vtkRenderWindow *           window,
       vtkRenderWindowInteractor * interactor,
       const ContourEditor &       editor)
{
  std::ifstream      in(options.replay);
  std::ostringstream events;
  events << in.rdbuf();
  if (!in)
  {
    std::cerr << "cannot read the events " << options.replay << std::endl;
    return 1;
  }
  vtkNew<vtkInteractorEventRecorder> recorder;
  recorder->SetInteractor(interactor);
  recorder->ReadFromInputStringOn();
  recorder->SetInputString(events.str().c_str());
  recorder->Play();
  window->Render();
  std::cout << "state: " << editor.State() << std::endl;
  if (options.screenshot.empty())
  {
    return 0;
  }
  vtkNew<vtkWindowToImageFilter> capture;
  capture->SetInput(window);
  capture->ReadFrontBufferOff();
  capture->Update();
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(options.screenshot.c_str());
  writer->SetInputConnection(capture->GetOutputPort());
  writer->Write();
  if (options.baseline.empty())
  {
    return 0;
  }
  vtkNew<vtkPNGReader> baseline;
  baseline->SetFileName(options.baseline.c_str());
  vtkNew<vtkImageDifference> difference;
  difference->SetInputConnection(capture->GetOutputPort());
  difference->SetImageConnection(baseline->GetOutputPort());
  difference->Update();
  const double error = difference->GetThresholdedError();
  std::cout << "screenshot difference from the baseline: " << error << " (threshold " << options.threshold << ")"
            << std::endl;
  return error <= options.threshold ? 0 : 1;
}
} // namespace

int
main(int argc, char * argv[])
{
  try
  {
    const Options options = ParseOptions(argc, argv);
    const auto    image = MeshExtractionCLI::ReadImageFile<ImageType>(options.image);
    const auto    model = MakeModel(image, options.model);
    ContourEditor editor(image, model, options);

    vtkNew<vtkRenderWindow> window;
    window->SetSize(options.windowSize, options.windowSize);
    window->SetWindowName("meshextraction-contours");
    vtkNew<vtkRenderWindowInteractor> interactor;
    interactor->SetRenderWindow(window);
    vtkNew<vtkInteractorStyleTrackballCamera> style;
    interactor->SetInteractorStyle(style);
    editor.Build(window);

    EventContext               context{ &editor, interactor, nullptr };
    vtkNew<vtkCallbackCommand> command;
    context.command = command;
    command->SetCallback(OnEvent);
    command->SetClientData(&context);
    for (const auto event : { vtkCommand::KeyPressEvent,
                              vtkCommand::CharEvent,
                              vtkCommand::LeftButtonPressEvent,
                              vtkCommand::LeftButtonReleaseEvent,
                              vtkCommand::MouseMoveEvent })
    {
      interactor->AddObserver(event, command, 10.0f);
    }
    interactor->Initialize();
    window->Render();
    if (!options.replay.empty())
    {
      return Replay(options, window, interactor, editor);
    }
    interactor->Start();
    return 0;
  }
  catch (const itk::ExceptionObject & e)
  {
    std::cerr << "meshextraction-contours: " << e.GetDescription() << std::endl;
    return 1;
  }
  catch (const std::exception & e)
  {
    std::cerr << "meshextraction-contours: " << e.what() << std::endl;
    return 2;
  }
}
