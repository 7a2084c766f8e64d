"""Extract a sphere with SurfaceNets from Python, measure it, write it."""
import csv
import io
import json
import sys

import itk

# The module's own phantom: the signed distance (mm, negative inside) of a sphere of
# radius 9.6 mm, sampled on 40^3 voxels of 0.8 mm (no NumPy bridge needed).
size = 40
spacing = 0.8
radius = 9.6
centre = [(size - 1) / 2.0 * spacing] * 3
sphere = itk.SphereImplicitSurface.New()
sphere.SetCenter(centre)
sphere.SetRadius(radius)
ImageType = itk.Image[itk.F, 3]
source = itk.ImplicitSurfaceImageSource[ImageType].New()
source.SetSurface(sphere)
source.SetSize([size] * 3)
source.SetSpacing([spacing] * 3)
source.Update()
image = source.GetOutput()

MeshType = itk.Mesh[itk.D, 3]
mesh = itk.surface_nets_image_to_mesh_filter(
    image, iso_value=0.0, inside_is_above_iso_value=False, high_quality=True,
    ttype=(ImageType, MeshType))

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
# Per-triangle values as plain tuples.
q_angles = calculator.GetTriangleQAngles()
assert len(q_angles) == mesh.GetNumberOfCells(), len(q_angles)
assert all(0.0 <= q <= 1.0 for q in q_angles), (min(q_angles), max(q_angles))
assert abs(sum(calculator.GetTriangleQAreas()) / len(q_angles) - calculator.GetMeanQArea()) < 1e-9

# Distances to the exact sphere, in physical units.
distances = itk.MeshSurfaceDistanceCalculator[MeshType, MeshType].New()
distances.SetMesh(mesh)
distances.SetReferenceSurface(sphere)
distances.Compute()
vertex_mean = json.loads(distances.GetReportAsJSON())["vertices"]["mean"]
assert vertex_mean < 0.02 * spacing, vertex_mean

# The QuadEdgeMesh output (what the mesh filters of the module take).
QEMeshType = itk.QuadEdgeMesh[itk.D, 3]
qe = itk.SurfaceNetsImageToMeshFilter[ImageType, QEMeshType].New(
    image, IsoValue=0.0, InsideIsAboveIsoValue=False)
qe.Update()
surface = qe.GetOutput()
euler = surface.GetNumberOfPoints() - surface.GetNumberOfEdges() + surface.GetNumberOfFaces()
assert euler == 2, euler

# A label image (Gibson's binary SurfaceNet), and that segmentation relaxed toward the
# greyscale iso-surface.
LabelType = itk.Image[itk.UC, 3]
mask = itk.ImplicitSurfaceImageSource[LabelType].New(Surface=sphere, Size=[size] * 3, Spacing=[spacing] * 3)
mask.SetImageMode(itk.MeshExtractionEnums.PhantomImage_BinaryMask)
mask.SetInsideValue(1)
mask.SetOutsideValue(0)
mask.Update()
labelled = itk.SurfaceNetsImageToMeshFilter[LabelType, MeshType].New(
    mask.GetOutput(), ClassifyByLabel=True, LabelValue=1)
labelled.Update()
label_quality = itk.TriangleMeshQualityCalculator[MeshType].New(Mesh=labelled.GetOutput())
label_quality.Compute()
assert json.loads(label_quality.GetReportAsJSON())["valid_closed_surface"]
segmented = itk.SurfaceNetsImageToMeshFilter[ImageType, MeshType].New(
    image, IsoValue=0.0, InsideIsAboveIsoValue=False, LabelImage=mask.GetOutput(), LabelValue=1)
segmented.Update()
segmented_distance = itk.MeshSurfaceDistanceCalculator[MeshType, MeshType].New(
    Mesh=segmented.GetOutput(), ReferenceSurface=sphere)
segmented_distance.Compute()
segmented_mean = json.loads(segmented_distance.GetReportAsJSON())["vertices"]["mean"]
assert segmented_mean < 0.05 * spacing, segmented_mean

# Scale-space edge refinement (thesis chapter 4) of that mesh, on a blurred-step
# image of the same sphere; its step table comes as CSV (the structure is not wrapped).
source.SetImageMode(itk.MeshExtractionEnums.PhantomImage_BlurredStep)
source.SetInsideValue(100.0)
source.SetOutsideValue(0.0)
source.SetEdgeWidth(1.0)
source.Update()
refine = itk.ScaleSpaceEdgeMeshRefinementFilter[QEMeshType, ImageType].New()
refine.SetInput(surface)
refine.SetInputImage(source.GetOutput())
refine.SetMaximumDeviation(2.0)
refine.SetMaximumNumberOfCycles(1)
refine.Update()
steps = list(csv.DictReader(io.StringIO(refine.GetStepsAsCSV())))
assert [s["operation"] for s in steps[:3]] == ["Org", "ED", "ES"], steps
assert int(steps[-1]["degenerate"]) == 0 and int(steps[-1]["non_manifold"]) == 0, steps[-1]

itk.meshwrite(mesh, sys.argv[1])
print("high quality: triangles %d, q_area %.4f, q_angle %.4f, mean vertex distance %.5f mm" % (
    report["triangles"], calculator.GetMeanQArea(), calculator.GetMeanQAngle(), vertex_mean))
print("label image: q_area %.4f; segmentation relaxed to the iso-surface: mean vertex distance %.5f mm" % (
    label_quality.GetMeanQArea(), segmented_mean))
