"""Extract a sphere with SurfaceNets from Python, measure it, write it."""
import json
import sys

import itk
import numpy as np

# A signed distance map of a sphere of radius 12 voxels (negative inside), with
# 0.8 mm voxels: the surface is a sphere of radius 9.6 mm about the image centre.
size = 40
spacing = 0.8
radius = 12.0 * spacing
grid = np.indices((size, size, size), dtype=np.float32) - (size - 1) / 2.0
distance = np.sqrt((grid**2).sum(axis=0)) * spacing - radius
image = itk.image_from_array(distance.astype(np.float32))
image.SetSpacing([spacing] * 3)
centre = [(size - 1) / 2.0 * spacing] * 3

MeshType = itk.Mesh[itk.D, 3]
mesh = itk.surface_nets_image_to_mesh_filter(
    image, iso_value=0.0, inside_is_above_iso_value=False, high_quality=True,
    ttype=(type(image), MeshType))

calculator = itk.TriangleMeshQualityCalculator[MeshType].New()
calculator.SetMesh(mesh)
calculator.Compute()
assert calculator.GetMeanQArea() > 0.95, calculator.GetMeanQArea()
assert calculator.GetMeanQAngle() > 0.75, calculator.GetMeanQAngle()
# The report structure is not wrapped; its JSON form carries every figure.
report = json.loads(calculator.GetReportAsJSON())
assert report["valid_closed_surface"], report
assert report["euler_characteristic"] == 2, report
assert report["triangles"] == mesh.GetNumberOfCells(), report
assert abs(report["q_area"]["mean"] - calculator.GetMeanQArea()) < 1e-9, report

# Distances to the exact sphere, in physical units.
sphere = itk.SphereImplicitSurface.New()
sphere.SetCenter(centre)
sphere.SetRadius(radius)
distances = itk.MeshSurfaceDistanceCalculator[MeshType, MeshType].New()
distances.SetMesh(mesh)
distances.SetReferenceSurface(sphere)
distances.Compute()
vertex_mean = json.loads(distances.GetReportAsJSON())["vertices"]["mean"]
assert vertex_mean < 0.02 * spacing, vertex_mean

# The QuadEdgeMesh output (what the mesh filters of the module take).
QEMeshType = itk.QuadEdgeMesh[itk.D, 3]
qe = itk.SurfaceNetsImageToMeshFilter[type(image), QEMeshType].New(
    image, IsoValue=0.0, InsideIsAboveIsoValue=False)
qe.Update()
surface = qe.GetOutput()
euler = surface.GetNumberOfPoints() - surface.GetNumberOfEdges() + surface.GetNumberOfFaces()
assert euler == 2, euler

itk.meshwrite(mesh, sys.argv[1])
print("triangles %d, q_area %.4f, q_angle %.4f, mean vertex distance %.5f mm" % (
    report["triangles"], calculator.GetMeanQArea(), calculator.GetMeanQAngle(), vertex_mean))
