"""Extract a sphere with SurfaceNets from Python, measure it, write it."""
import sys

import itk
import numpy as np

# A signed distance map of a sphere of radius 12 voxels (negative inside).
size = 40
grid = np.indices((size, size, size), dtype=np.float32) - (size - 1) / 2.0
distance = np.sqrt((grid**2).sum(axis=0)) - 12.0
image = itk.image_from_array(distance.astype(np.float32))

mesh = itk.surface_nets_image_to_mesh_filter(
    image, iso_value=0.0, inside_is_above_iso_value=False, high_quality=True,
    ttype=(type(image), itk.Mesh[itk.D, 3]))

calculator = itk.TriangleMeshQualityCalculator[itk.Mesh[itk.D, 3]].New()
calculator.SetMesh(mesh)
calculator.Compute()
assert calculator.GetMeanQArea() > 0.95, calculator.GetMeanQArea()
assert calculator.GetMeanQAngle() > 0.75, calculator.GetMeanQAngle()

itk.meshwrite(mesh, sys.argv[1])
