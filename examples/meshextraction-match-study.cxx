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

// meshextraction-match-study: the target registration error (TRE) of the three-landmark
// incremental match (thesis 6.2.4) against the least-squares fit of ITK's
// LandmarkBasedTransformInitializer, over random trials with unequal landmark noise.
//
// The object is a uterus-like ellipsoid (semi-axes 25 x 20 x 40 mm) with the thesis'
// landmarks: A the bending point between corpus and cervix (its lower pole), B the top
// (its upper pole), C the centre of a myoma 18 mm off the axis. Each trial moves it by a
// random rigid transform (optionally with a distension: 10 % longer along AB, 8 % thinner
// toward C), perturbs the moving landmarks by Gaussian noise of standard deviation
// sigma_A, sigma_B, sigma_C per coordinate, matches, and measures |T_est(p) - T(p)| at
// three sets of points: the myoma (a sphere of radius 8 mm about C), the whole surface,
// and the cervix (a sphere of radius 8 mm about A).

#include "itkAffineTransform.h"
#include "itkImage.h"
#include "itkLandmarkBasedTransformInitializer.h"
#include "itkThreeLandmarkIncrementalTransformInitializer.h"
#include "itkVersorRigid3DTransform.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace
{
using Point = itk::Point<double, 3>;
using Vector = itk::Vector<double, 3>;
using Landmarks = std::vector<Point>;
using Rigid = itk::VersorRigid3DTransform<double>;
using Affine = itk::AffineTransform<double, 3>;
using Image = itk::Image<float, 3>;

struct NoiseSetting
{
  double a, b, c;
};

struct Study
{
  unsigned int              trials{ 2000 };
  unsigned int              seed{ 1 };
  std::string               markdown;
  std::vector<NoiseSetting> noise{ { 0.5, 1, 2 },    { 0.5, 1, 4 }, { 0.5, 2, 8 },
                                   { 0.25, 0.5, 6 }, { 1, 1, 1 },   { 3, 3, 3 } };
};

Point
MakePoint(double x, double y, double z)
{
  Point p;
  p[0] = x;
  p[1] = y;
  p[2] = z;
  return p;
}

/** n points spread evenly over the unit sphere (a Fibonacci lattice). */
std::vector<Vector>
SphereDirections(unsigned int n)
{
  std::vector<Vector> out;
  const double        golden = itk::Math::pi * (3.0 - std::sqrt(5.0));
  for (unsigned int i = 0; i < n; ++i)
  {
    const double z = 1.0 - 2.0 * (i + 0.5) / n;
    const double r = std::sqrt(1.0 - z * z);
    Vector       v;
    v[0] = r * std::cos(golden * i);
    v[1] = r * std::sin(golden * i);
    v[2] = z;
    out.push_back(v);
  }
  return out;
}

struct Phantom
{
  Landmarks          landmarks;
  std::vector<Point> myoma, surface, cervix;
};

Phantom
MakePhantom()
{
  Phantom p;
  p.landmarks = { MakePoint(0, 0, -40), MakePoint(0, 0, 40), MakePoint(18, 0, 10) };
  for (const Vector & d : SphereDirections(2000))
  {
    p.surface.push_back(MakePoint(25 * d[0], 20 * d[1], 40 * d[2]));
  }
  for (const Vector & d : SphereDirections(400))
  {
    p.myoma.push_back(p.landmarks[2] + d * 8.0);
    p.cervix.push_back(p.landmarks[0] + d * 8.0);
  }
  return p;
}

/** A random rigid transform, possibly followed (in the fixed frame) by the distension. */
Affine::Pointer
RandomTruth(std::mt19937_64 & random, bool distended, const Landmarks & fixed)
{
  std::normal_distribution<double> n;
  Vector                           axis;
  for (unsigned int d = 0; d < 3; ++d)
  {
    axis[d] = n(random);
  }
  itk::Versor<double> versor;
  versor.Set(axis / axis.GetNorm(), std::uniform_real_distribution<double>(-itk::Math::pi, itk::Math::pi)(random));
  itk::Matrix<double, 3, 3> linear = versor.GetMatrix();
  if (distended)
  {
    // 1.1 along AB (z), 0.92 toward C (x), 1 across (y).
    itk::Matrix<double, 3, 3> s;
    s.Fill(0.0);
    s[0][0] = 0.92;
    s[1][1] = 1.0;
    s[2][2] = 1.1;
    linear = linear * s;
  }
  auto truth = Affine::New();
  truth->SetCenter(fixed[0]);
  truth->SetMatrix(linear);
  Vector t;
  for (unsigned int d = 0; d < 3; ++d)
  {
    t[d] = std::uniform_real_distribution<double>(-100, 100)(random);
  }
  truth->SetTranslation(t);
  return truth;
}

itk::Transform<double, 3, 3>::Pointer
MatchIncremental(const Landmarks & fixed, const Landmarks & moving, bool distension)
{
  using Base = itk::Transform<double, 3, 3>;
  auto          initializer = itk::ThreeLandmarkIncrementalTransformInitializer<Base>::New();
  Base::Pointer transform;
  if (distension)
  {
    transform = Affine::New().GetPointer();
    initializer->SetDistension(itk::MeshExtractionEnums::LandmarkDistension::AlongAxes);
  }
  else
  {
    transform = Rigid::New().GetPointer();
  }
  initializer->SetTransform(transform);
  initializer->SetFixedLandmarks(fixed);
  initializer->SetMovingLandmarks(moving);
  initializer->InitializeTransform();
  return transform;
}

itk::Transform<double, 3, 3>::Pointer
MatchLeastSquares(const Landmarks & fixed, const Landmarks & moving)
{
  auto rigid = Rigid::New();
  auto initializer = itk::LandmarkBasedTransformInitializer<Rigid, Image, Image>::New();
  initializer->SetTransform(rigid);
  initializer->SetFixedLandmarks(fixed);
  initializer->SetMovingLandmarks(moving);
  initializer->InitializeTransform();
  return rigid.GetPointer();
}

/** The errors of one method at one set of points, over all trials. */
struct Errors
{
  std::vector<double> values;
  void
  Add(const itk::Transform<double, 3, 3> * estimate, const Affine * truth, const std::vector<Point> & points)
  {
    for (const Point & p : points)
    {
      values.push_back(estimate->TransformPoint(p).EuclideanDistanceTo(truth->TransformPoint(p)));
    }
  }
  double
  Mean() const
  {
    double sum = 0.0;
    for (double v : values)
    {
      sum += v;
    }
    return values.empty() ? 0.0 : sum / values.size();
  }
  double
  Percentile95()
  {
    if (values.empty())
    {
      return 0.0;
    }
    const std::size_t k = static_cast<std::size_t>(0.95 * (values.size() - 1));
    std::nth_element(values.begin(), values.begin() + k, values.end());
    return values[k];
  }
};

struct MethodErrors
{
  std::string name;
  Errors      myoma, surface, cervix;
};

std::vector<MethodErrors>
RunSetting(const Study & study, const Phantom & phantom, const NoiseSetting & sigma, bool distended)
{
  std::vector<MethodErrors> methods{ { "incremental (rigid)", {}, {}, {} }, { "least squares (rigid)", {}, {}, {} } };
  if (distended)
  {
    methods.push_back({ "incremental + distension", {}, {}, {} });
  }
  std::mt19937_64                  random(study.seed);
  std::normal_distribution<double> unit;
  const double                     sigmas[3] = { sigma.a, sigma.b, sigma.c };
  for (unsigned int trial = 0; trial < study.trials; ++trial)
  {
    const auto truth = RandomTruth(random, distended, phantom.landmarks);
    Landmarks  moving;
    for (unsigned int i = 0; i < 3; ++i)
    {
      Point p = truth->TransformPoint(phantom.landmarks[i]);
      for (unsigned int d = 0; d < 3; ++d)
      {
        p[d] += sigmas[i] * unit(random);
      }
      moving.push_back(p);
    }
    std::vector<itk::Transform<double, 3, 3>::Pointer> estimates{ MatchIncremental(phantom.landmarks, moving, false),
                                                                  MatchLeastSquares(phantom.landmarks, moving) };
    if (distended)
    {
      estimates.push_back(MatchIncremental(phantom.landmarks, moving, true));
    }
    for (std::size_t m = 0; m < methods.size(); ++m)
    {
      methods[m].myoma.Add(estimates[m], truth, phantom.myoma);
      methods[m].surface.Add(estimates[m], truth, phantom.surface);
      methods[m].cervix.Add(estimates[m], truth, phantom.cervix);
    }
  }
  return methods;
}

/** "mean / 95th percentile", in bold where the mean is the smallest of the row group. */
std::string
Cell(Errors & e, bool best)
{
  std::ostringstream out;
  out << std::fixed << std::setprecision(2) << (best ? "**" : "") << e.Mean() << " / " << e.Percentile95()
      << (best ? "**" : "");
  return out.str();
}

void
PrintTable(std::ostream & out, const Study & study, const Phantom & phantom, bool distended)
{
  out << "| sigma A, B, C (mm) | truth | method | myoma TRE mean / 95% | surface TRE mean / 95% | "
         "cervix TRE mean / 95% |\n";
  out << "|---|---|---|---:|---:|---:|\n";
  for (const NoiseSetting & sigma : study.noise)
  {
    auto methods = RunSetting(study, phantom, sigma, distended);
    // The method with the smallest mean error in each region.
    auto best = [&methods](Errors MethodErrors::*region) {
      std::size_t b = 0;
      for (std::size_t m = 1; m < methods.size(); ++m)
      {
        if ((methods[m].*region).Mean() < (methods[b].*region).Mean())
        {
          b = m;
        }
      }
      return b;
    };
    const std::size_t bestMyoma = best(&MethodErrors::myoma);
    const std::size_t bestSurface = best(&MethodErrors::surface);
    const std::size_t bestCervix = best(&MethodErrors::cervix);
    for (std::size_t m = 0; m < methods.size(); ++m)
    {
      out << "| " << sigma.a << ", " << sigma.b << ", " << sigma.c << " | "
          << (distended ? "rigid + distension" : "rigid") << " | " << methods[m].name << " | "
          << Cell(methods[m].myoma, m == bestMyoma) << " | " << Cell(methods[m].surface, m == bestSurface) << " | "
          << Cell(methods[m].cervix, m == bestCervix) << " |\n";
    }
  }
}

[[noreturn]] void
Usage(int status)
{
  (status == 0 ? std::cout : std::cerr)
    << "usage: meshextraction-match-study [--trials N] [--seed S] [--markdown FILE]\n"
       "Target registration error of the three-landmark incremental match (thesis 6.2.4) against\n"
       "ITK's least-squares LandmarkBasedTransformInitializer on a uterus-like ellipsoid (25 x 20 x\n"
       "40 mm; A and B its poles, C a myoma 18 mm off the axis), over random rigid transforms (and\n"
       "rigid + distension) with per-landmark Gaussian noise. Prints markdown tables of the TRE's\n"
       "mean and 95th percentile (mm) at the myoma, the whole surface and the cervix.\n"
       "  --trials N      random transforms per noise setting (default 2000)\n"
       "  --seed S        random seed (default 1)\n"
       "  --markdown FILE also write the tables to FILE\n";
  std::exit(status);
}

Study
ParseArguments(int argc, char * argv[])
{
  Study study;
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    auto              value = [&]() -> std::string {
      if (i + 1 >= argc)
      {
        std::cerr << "meshextraction-match-study: " << a << " needs a value\n";
        Usage(2);
      }
      return argv[++i];
    };
    auto number = [&](const std::string & text) {
      char *     end = nullptr;
      const long n = std::strtol(text.c_str(), &end, 10);
      if (end == text.c_str() || *end != '\0' || n < 1 || n > 10000000)
      {
        std::cerr << "meshextraction-match-study: " << a << " needs a whole number from 1 to 10000000, got '" << text
                  << "'\n";
        std::exit(2);
      }
      return static_cast<unsigned int>(n);
    };
    if (a == "--help" || a == "-h")
    {
      Usage(0);
    }
    else if (a == "--trials")
    {
      study.trials = number(value());
    }
    else if (a == "--seed")
    {
      study.seed = number(value());
    }
    else if (a == "--markdown")
    {
      study.markdown = value();
    }
    else
    {
      std::cerr << "meshextraction-match-study: unknown argument '" << a << "'\n";
      Usage(2);
    }
  }
  return study;
}
} // namespace

int
main(int argc, char * argv[])
{
  const Study   study = ParseArguments(argc, argv);
  const Phantom phantom = MakePhantom();
  try
  {
    std::ostringstream out;
    out << "TRE in mm over " << study.trials << " random transforms per row (seed " << study.seed
        << "); noise per coordinate; bold: the smallest mean of each noise setting.\n\n";
    PrintTable(out, study, phantom, false);
    out << '\n';
    PrintTable(out, study, phantom, true);
    std::cout << out.str();
    if (!study.markdown.empty())
    {
      std::ofstream file(study.markdown);
      file << out.str();
      if (!file)
      {
        std::cerr << "meshextraction-match-study: cannot write " << study.markdown << '\n';
        return 1;
      }
    }
  }
  catch (const itk::ExceptionObject & e)
  {
    std::cerr << "meshextraction-match-study: " << e.GetDescription() << '\n';
    return 1;
  }
  return 0;
}
