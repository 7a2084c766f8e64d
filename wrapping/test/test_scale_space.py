"""Scale-space edge detection and the ED/ES/S refinement protocol (thesis chapter 4)
from Python, with the step table."""
import csv
import io

import itk
import pytest

from conftest import ImageF, QEMesh, assert_valid_closed, distance_report, make_sphere_surface, phantom_image


@pytest.fixture(scope="module")
def blurred_sphere():
    """A blurred step edge (inside 100, outside 0) at a sphere of radius 8 mm."""
    sphere = make_sphere_surface([15.5] * 3, 8.0)
    image = phantom_image(sphere, 32, mode=itk.MeshExtractionEnums.PhantomImage_BlurredStep,
                          InsideValue=100.0, OutsideValue=0.0, EdgeWidth=1.0)
    return sphere, image


@pytest.fixture(scope="module")
def shrunk_mesh():
    """The surface of a smaller sphere (radius 6.5 mm): the edges are 1.5 mm away."""
    small = make_sphere_surface([15.5] * 3, 6.5)
    return itk.surface_nets_image_to_mesh_filter(
        phantom_image(small, 32), iso_value=0.0, inside_is_above_iso_value=False, high_quality=True,
        ttype=(ImageF, QEMesh))


def test_edge_detection_moves_vertices_to_the_edge(blurred_sphere, shrunk_mesh):
    sphere, image = blurred_sphere
    before = distance_report(shrunk_mesh, sphere)["vertices"]["mean"]
    f = itk.ScaleSpaceEdgeDetectionMeshFilter[QEMesh, ImageF].New()
    f.SetInput(shrunk_mesh)
    f.SetInputImage(image)
    f.SetMaximumDeviation(3.0)
    f.Update()
    assert f.GetNumberOfMovedVertices() > 0.9 * shrunk_mesh.GetNumberOfPoints()
    assert f.GetMeanDisplacement() == pytest.approx(1.5, abs=0.4)
    assert_valid_closed(f.GetOutput())
    after = distance_report(f.GetOutput(), sphere)["vertices"]["mean"]
    assert before == pytest.approx(1.5, abs=0.1)
    assert after < 0.3


def test_refinement_protocol_and_its_step_table(blurred_sphere, shrunk_mesh):
    sphere, image = blurred_sphere
    f = itk.ScaleSpaceEdgeMeshRefinementFilter[QEMesh, ImageF].New()
    f.SetInput(shrunk_mesh)
    f.SetInputImage(image)
    f.SetMaximumDeviation(3.0)
    f.SetMaximumNumberOfCycles(2)
    f.Update()
    assert_valid_closed(f.GetOutput())
    assert distance_report(f.GetOutput(), sphere)["vertices"]["mean"] < 0.3
    steps = list(csv.DictReader(io.StringIO(f.GetStepsAsCSV())))
    operations = [s["operation"] for s in steps]
    assert operations[:3] == ["Org", "ED", "ES"]
    assert operations[-2:] == ["ED", "ES"]
    assert set(operations) <= {"Org", "ED", "ES", "S"}
    assert f.GetNumberOfCycles() <= 2
    for step in steps:
        assert int(step["degenerate"]) == 0 and int(step["non_manifold"]) == 0, step
    # The table's quality is the mesh's.
    assert float(steps[-1]["mean_q_area"]) == pytest.approx(
        assert_valid_closed(f.GetOutput())["q_area"]["mean"], abs=1e-4)


def test_refinement_of_a_signed_short_image(blurred_sphere, shrunk_mesh):
    sphere, image = blurred_sphere
    short = itk.cast_image_filter(image, ttype=(ImageF, itk.Image[itk.SS, 3]))
    out = itk.scale_space_edge_mesh_refinement_filter(
        shrunk_mesh, input_image=short, maximum_deviation=3.0, maximum_number_of_cycles=1,
        ttype=(QEMesh, itk.Image[itk.SS, 3]))
    assert_valid_closed(out)
    assert distance_report(out, sphere)["vertices"]["mean"] < 0.4
