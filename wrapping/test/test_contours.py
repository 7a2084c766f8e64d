"""Connected orthogonal contours (thesis chapter 5) from Python: the template, the
edge-assisted moves (EDEMS) and the model's closed surface."""
import json

import itk
import pytest

from conftest import ImageF, QEMesh, assert_valid_closed, distance_report, make_sphere_surface, phantom_image


@pytest.fixture()
def scene():
    """A 48^3 blurred step edge at a sphere of radius 13 mm, and the three-contour
    template of radius 10 voxels at its centre."""
    sphere = make_sphere_surface([24.0] * 3, 13.0)
    image = phantom_image(sphere, 48, mode=itk.MeshExtractionEnums.PhantomImage_BlurredStep,
                          InsideValue=100.0, OutsideValue=0.0, EdgeWidth=1.0)
    model = itk.OrthogonalContourModel.New()
    model.SetGrid(image)
    model.InitializeTemplate([24, 24, 24], [10.0, 10.0, 10.0])
    return sphere, image, model


def test_template_and_its_closed_surface(scene):
    sphere, image, model = scene
    assert model.GetNumberOfContours() == 3
    assert model.GetNumberOfControlPoints() == 6
    assert model.CheckInvariants() == ""
    mesh = itk.OrthogonalContourModelToMeshFilter[QEMesh].New(model)
    mesh.Update()
    report = assert_valid_closed(mesh.GetOutput())
    assert report["enclosed_volume"] == pytest.approx(model.GetVolume(), rel=0.03)
    # The first points of the mesh are the control points, in order.
    first = mesh.GetOutput().GetPoint(0)
    assert [first[i] for i in range(3)] == pytest.approx([model.GetControlPoint(0)[i] for i in range(3)])


def test_edge_detection_moves_the_control_points_onto_the_edge(scene):
    sphere, image, model = scene
    detector = itk.OrthogonalContourModelEdgeDetector[ImageF].New()
    detector.SetImage(image)
    detector.SetModel(model)
    detector.SetCaptureRange(5.0)
    assert detector.MoveAllControlPoints() == 6
    assert detector.GetNumberOfRefusedMoves() == 0
    assert detector.GetDistanceTravelled() == pytest.approx(18.0, abs=1.5)
    for p in range(model.GetNumberOfControlPoints()):
        assert abs(sphere.Evaluate(model.GetControlPoint(p))) < 0.25
    assert model.CheckInvariants() == ""
    mesh = itk.orthogonal_contour_model_to_mesh_filter(model, ttype=QEMesh)
    assert_valid_closed(mesh)


def test_edits_keep_the_rules_and_survive_json(scene):
    sphere, image, model = scene
    assert model.AddContour(2, 28)
    assert model.GetNumberOfContours() == 4
    assert not model.MoveControlPoint(0, 1000.0)  # out of the grid: refused, unchanged
    assert model.GetRefusalReason() != ""
    text = model.ToJSON()
    json.loads(text)
    copy = itk.OrthogonalContourModel.New()
    copy.FromJSON(text)
    assert copy.GetNumberOfContours() == 4
    assert copy.GetVolume() == pytest.approx(model.GetVolume())
