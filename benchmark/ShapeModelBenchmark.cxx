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

// The shape model's speed (issue 29): the symmetric similarity ICP of two meshes of about
// 20,000 vertices (with the model's tolerance), and the whole model of the ten L1 vertebrae with the non-rigid stage,
// on ../shared/data when it is next to the project (skipped otherwise). Peak memory:
// run under /usr/bin/time -v (benchmark/README.md).

#include "itkMeshExtractionGeodesicSphere.h"
#include "itkMeshExtractionPLY.h"
#include "itkMeshExtractionShapeModelBuilder.h"
#include "itkMeshExtractionSymmetricICP.h"

#include <benchmark/benchmark.h>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

namespace
{
namespace ME = itk::MeshExtraction;

std::string
VertebraPath(const char * name)
{
  return std::string(MESHEXTRACTION_SOURCE_DIR) + "/../shared/data/vertebrae_L1/sub-verse" + name + "_segment_20.ply";
}

/** True, after marking the benchmark skipped, where ../shared/data is not next to the project. */
bool
SkippedWithoutVertebrae(benchmark::State & state)
{
  if (std::ifstream(VertebraPath("010")))
  {
    return false;
  }
  state.SkipWithError("../shared/data/vertebrae_L1 is not next to the project");
  return true;
}

/** L1 vertebra sub-verse<name>, made ready as the shape model takes it. */
ME::IndexedTriangleMesh
Vertebra(const char * name)
{
  return ME::detail::PrepareTrainingMesh(ME::ReadPLYFile(VertebraPath(name)), VertebraPath(name));
}

/** An ellipsoid of semi-axes a, 20, 15 mm: a geodesic sphere of the given subdivisions,
 * turned by `angle` about z and moved by `shift`. */
ME::IndexedTriangleMesh
Ellipsoid(unsigned int subdivisions, double a, double angle, double shift)
{
  ME::IndexedTriangleMesh mesh = ME::MakeGeodesicSphere(subdivisions, ME::MakeVec3(0, 0, 0), 1.0);
  const double            c = std::cos(angle);
  const double            s = std::sin(angle);
  for (ME::Vec3 & p : mesh.points)
  {
    const ME::Vec3 q = ME::MakeVec3(a * p[0], 20 * p[1], 15 * p[2]);
    p = ME::MakeVec3(c * q[0] - s * q[1] + shift, s * q[0] + c * q[1], q[2]);
  }
  return mesh;
}

void
RunICP(benchmark::State & state, const ME::IndexedTriangleMesh & a, const ME::IndexedTriangleMesh & b)
{
  const ME::detail::ClosestPointQuery fixed(a, itk::MeshExtractionEnums::Correspondence::PointToSurface);
  const ME::detail::ClosestPointQuery moving(b, itk::MeshExtractionEnums::Correspondence::PointToSurface);
  ME::detail::SymmetricICPSettings    settings; // as the shape model's passes run it
  settings.relativeTolerance = ME::detail::ShapeModelSettings().icpRelativeTolerance;
  settings.measureInitialE2 = false;
  double       e2 = 0.0;
  unsigned int iterations = 0;
  for (auto _ : state)
  {
    const ME::detail::SymmetricICPResult result = ME::detail::RunSymmetricICP(fixed, moving, settings);
    e2 = result.e2;
    iterations = result.iterations;
  }
  state.counters["iterations"] = iterations;
  state.counters["vertices_a"] = static_cast<double>(a.points.size());
  state.counters["vertices_b"] = static_cast<double>(b.points.size());
  state.counters["E2_mm2"] = e2;
}

/** Two ellipsoids of 10,242 and 40,962 vertices (mean about 25,000) and long semi-axes of
 * 30 and 34 mm, 0.5 rad and 40 mm apart. */
void
SymmetricICPEllipsoids(benchmark::State & state)
{
  RunICP(state, Ellipsoid(5, 30.0, 0.0, 0.0), Ellipsoid(6, 34.0, 0.5, 40.0));
}
BENCHMARK(SymmetricICPEllipsoids)->Unit(benchmark::kMillisecond);

/** L1 vertebrae sub-verse010 and sub-verse041 (19,264 and 13,520 vertices), as scanned. */
void
SymmetricICPVertebrae(benchmark::State & state)
{
  if (!SkippedWithoutVertebrae(state))
  {
    RunICP(state, Vertebra("010"), Vertebra("041"));
  }
}
BENCHMARK(SymmetricICPVertebrae)->Unit(benchmark::kMillisecond);

/** The model of the ten L1 vertebrae, non-rigid stage on, two template passes. */
void
ShapeModelVertebrae(benchmark::State & state)
{
  if (SkippedWithoutVertebrae(state))
  {
    return;
  }
  std::vector<ME::IndexedTriangleMesh> meshes;
  std::size_t                          vertices = 0;
  for (const char * name : { "010", "013", "016", "018", "022", "023", "024", "026", "030", "041" })
  {
    meshes.push_back(Vertebra(name));
    vertices += meshes.back().points.size();
  }
  std::size_t modes = 0;
  for (auto _ : state)
  {
    modes = ME::detail::BuildShapeModel(meshes, ME::detail::ShapeModelSettings()).model.NumberOfModes();
  }
  state.counters["meshes"] = static_cast<double>(meshes.size());
  state.counters["vertices"] = static_cast<double>(vertices);
  state.counters["modes"] = static_cast<double>(modes);
}
BENCHMARK(ShapeModelVertebrae)->Unit(benchmark::kSecond)->Iterations(1);
} // namespace
