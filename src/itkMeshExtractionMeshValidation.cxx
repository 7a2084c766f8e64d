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
#include "itkMeshExtractionMeshValidation.h"

#include <cmath>
#include <sstream>

namespace itk
{
namespace MeshExtraction
{
namespace
{
/** 1. Coordinates that are not finite, corners that name no point or one point twice. */
void
FindElementDefects(const IndexedTriangleMesh & mesh, TriangleMeshDefects & d)
{
  for (std::size_t i = 0; i < mesh.points.size(); ++i)
  {
    const Vec3 & p = mesh.points[i];
    if (!(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2])))
    {
      d.firstNonFinitePoint = d.numberOfNonFinitePoints++ == 0 ? i : d.firstNonFinitePoint;
    }
  }
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f)
  {
    const TriangleIndices & t = mesh.triangles[f];
    if (t[0] >= mesh.points.size() || t[1] >= mesh.points.size() || t[2] >= mesh.points.size())
    {
      d.firstTriangleOutOfRange = d.numberOfIndicesOutOfRange++ == 0 ? f : d.firstTriangleOutOfRange;
    }
    else if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0])
    {
      d.firstRepeatedCorner = d.numberOfRepeatedCorners++ == 0 ? f : d.firstRepeatedCorner;
    }
  }
}

/** 2. Non-manifold and inconsistently oriented edges, non-manifold vertices. */
void
FindTopologicalDefects(const IndexedTriangleMesh & mesh, TriangleMeshDefects & d)
{
  const MeshTopology topology = BuildMeshTopology(mesh);
  for (const MeshTopology::Edge & e : topology.edges)
  {
    if (e.numberOfIncidences > 2)
    {
      if (d.numberOfNonManifoldEdges++ == 0)
      {
        d.firstNonManifoldEdge[0] = e.a;
        d.firstNonManifoldEdge[1] = e.b;
      }
    }
    else if (e.numberOfIncidences == 2 &&
             topology.incidences[e.firstIncidence].forward == topology.incidences[e.firstIncidence + 1].forward)
    {
      if (d.numberOfInconsistentEdges++ == 0)
      {
        d.firstInconsistentEdge[0] = e.a;
        d.firstInconsistentEdge[1] = e.b;
      }
    }
  }
  d.numberOfNonManifoldVertices = topology.numberOfNonManifoldVertices;
  for (std::size_t v = 0; v < topology.vertexIsNonManifold.size() && d.firstNonManifoldVertex == d.None; ++v)
  {
    d.firstNonManifoldVertex = topology.vertexIsNonManifold[v] ? v : d.None;
  }
}

/** "1 thing" or "3 things". */
std::string
Count(std::size_t n, const char * singular, const char * plural)
{
  return std::to_string(n) + ' ' + (n == 1 ? singular : plural);
}

std::string
PointText(const IndexedTriangleMesh & mesh, std::uint64_t v)
{
  std::ostringstream os;
  os << "point " << v << " at [" << mesh.points[v][0] << ", " << mesh.points[v][1] << ", " << mesh.points[v][2] << ']';
  return os.str();
}
} // namespace

bool
TriangleMeshDefects::Any() const
{
  return numberOfNonFinitePoints + numberOfIndicesOutOfRange + numberOfRepeatedCorners + numberOfNonManifoldEdges +
           numberOfInconsistentEdges + numberOfNonManifoldVertices >
         0;
}

std::string
TriangleMeshDefects::Describe(const IndexedTriangleMesh & mesh) const
{
  std::vector<std::string> parts;
  if (numberOfNonFinitePoints > 0)
  {
    parts.push_back(Count(numberOfNonFinitePoints, "point", "points") +
                    " with a coordinate that is not a finite number (NaN or infinite; the first is point " +
                    std::to_string(firstNonFinitePoint) + ")");
  }
  if (numberOfIndicesOutOfRange > 0)
  {
    parts.push_back(Count(numberOfIndicesOutOfRange, "triangle", "triangles") +
                    " naming a point the mesh has not (of " + std::to_string(mesh.points.size()) +
                    "; the first is triangle " + std::to_string(firstTriangleOutOfRange) + ")");
  }
  if (numberOfRepeatedCorners > 0)
  {
    parts.push_back(Count(numberOfRepeatedCorners, "triangle", "triangles") +
                    " naming one point twice (the first is triangle " + std::to_string(firstRepeatedCorner) + ")");
  }
  if (numberOfNonManifoldEdges > 0)
  {
    parts.push_back(Count(numberOfNonManifoldEdges, "non-manifold edge", "non-manifold edges") +
                    " shared by more than two triangles (the first joins points " +
                    std::to_string(firstNonManifoldEdge[0]) + " and " + std::to_string(firstNonManifoldEdge[1]) + ")");
  }
  if (numberOfInconsistentEdges > 0)
  {
    parts.push_back(Count(numberOfInconsistentEdges, "edge", "edges") +
                    " whose two triangles are oriented oppositely (the first joins points " +
                    std::to_string(firstInconsistentEdge[0]) + " and " + std::to_string(firstInconsistentEdge[1]) +
                    ")");
  }
  if (numberOfNonManifoldVertices > 0)
  {
    parts.push_back(Count(numberOfNonManifoldVertices, "non-manifold vertex", "non-manifold vertices") + " (" +
                    PointText(mesh, firstNonManifoldVertex) +
                    ": its triangles form separate fans that meet only there)");
  }
  std::string text;
  for (std::size_t i = 0; i < parts.size(); ++i)
  {
    text += (i == 0 ? "" : "; ") + parts[i];
  }
  return text;
}

TriangleMeshDefects
FindTriangleMeshDefects(const IndexedTriangleMesh & mesh)
{
  TriangleMeshDefects defects;
  FindElementDefects(mesh, defects);
  if (defects.numberOfIndicesOutOfRange == 0 && defects.numberOfRepeatedCorners == 0)
  {
    FindTopologicalDefects(mesh, defects);
  }
  return defects;
}

void
RequireQuadEdgeMeshTriangles(const IndexedTriangleMesh & mesh, const std::string & what)
{
  const TriangleMeshDefects defects = FindTriangleMeshDefects(mesh);
  if (defects.Any())
  {
    itkGenericExceptionMacro(<< what
                             << " is not a manifold, consistently oriented triangle mesh: " << defects.Describe(mesh));
  }
}

} // namespace MeshExtraction
} // namespace itk
