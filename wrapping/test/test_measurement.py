"""The quality and distance calculators from Python: reports as dicts, per-triangle
measures, distances to an implicit surface and to another mesh."""
import json
import math

import itk
import pytest

from conftest import Mesh, QEMesh, make_sphere_surface


def regular_octahedron(mesh_type=Mesh, scale=1.0):
    """The octahedron with corners at +-scale on the axes: eight equilateral triangles,
    oriented outward."""
    from itk import meshextraction
    points = [[scale, 0, 0], [-scale, 0, 0], [0, scale, 0], [0, -scale, 0], [0, 0, scale], [0, 0, -scale]]
    triangles = [[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4], [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]]
    return meshextraction.mesh_from_arrays(points, triangles, mesh_type)


@pytest.mark.parametrize("mesh_type", [Mesh, QEMesh])
def test_quality_of_a_regular_octahedron(mesh_type):
    mesh = regular_octahedron(mesh_type, 2.0)
    calculator = itk.TriangleMeshQualityCalculator[mesh_type].New()
    calculator.SetMesh(mesh)
    calculator.Compute()
    report = json.loads(calculator.GetReportAsJSON())
    assert report["valid_closed_surface"]
    assert report["triangles"] == 8 and report["points"] == 6 and report["edges"] == 12
    assert report["euler_characteristic"] == 2 and report["genus"] == 0
    for measure in ("q_area", "q_angle", "q_length"):
        assert report[measure]["mean"] == pytest.approx(1.0, abs=1e-9)
    assert calculator.GetMeanQArea() == pytest.approx(1.0, abs=1e-9)
    assert report["min_angle_deg"]["mean"] == pytest.approx(60.0, abs=1e-6)
    # Each face: an equilateral triangle of side 2 sqrt 2; the solid's volume 4/3 * 8.
    assert report["total_area"] == pytest.approx(8 * math.sqrt(3) / 4 * 8, rel=1e-9)
    assert report["enclosed_volume"] == pytest.approx(4.0 / 3.0 * 8, rel=1e-9)
    assert list(calculator.GetTriangleQAngles()) == pytest.approx([1.0] * 8)
    assert len(calculator.GetTriangleQAreas()) == 8


def test_an_open_or_inverted_mesh_is_reported():
    from itk import meshextraction
    points, triangles = meshextraction.arrays_from_mesh(regular_octahedron())
    opened = meshextraction.mesh_from_arrays(points, triangles[:-1])
    report = json.loads(_report(opened))
    assert not report["valid_closed_surface"]
    assert report["boundary_edges"] == 3 and report["boundary_loops"] == 1
    inward = meshextraction.mesh_from_arrays(points, triangles[:, ::-1])
    report = json.loads(_report(inward))
    assert not report["valid_closed_surface"]
    assert report["inverted_triangles_vs_outward"] == 8


def _report(mesh):
    calculator = itk.TriangleMeshQualityCalculator[type(mesh)].New(Mesh=mesh)
    calculator.Compute()
    return calculator.GetReportAsJSON()


def test_distances_to_an_implicit_surface_and_to_a_mesh(small_sphere_mesh, small_sphere):
    calculator = itk.MeshSurfaceDistanceCalculator[QEMesh, QEMesh].New()
    calculator.SetMesh(small_sphere_mesh)
    calculator.SetReferenceSurface(small_sphere)
    calculator.Compute()
    report = json.loads(calculator.GetReportAsJSON())
    assert report["vertices"]["mean"] < 0.04  # radius 6 voxels
    assert report["vertices"]["max"] >= report["vertices"]["mean"]
    # A sphere 0.5 mm larger: every vertex 0.5 mm inside it.
    larger = make_sphere_surface([9.5] * 3, 6.5)
    calculator.SetReferenceSurface(larger)
    calculator.Compute()
    shifted = json.loads(calculator.GetReportAsJSON())["vertices"]
    assert shifted["mean"] == pytest.approx(0.5, abs=0.03)
    assert shifted["signed_mean"] == pytest.approx(-0.5, abs=0.03)
    # Against itself as a mesh: zero, and symmetric Hausdorff zero.
    to_mesh = itk.MeshSurfaceDistanceCalculator[QEMesh, QEMesh].New(
        Mesh=small_sphere_mesh, ReferenceMesh=small_sphere_mesh, Symmetric=True)
    to_mesh.Compute()
    assert to_mesh.GetHausdorffDistance() == pytest.approx(0.0, abs=1e-9)
