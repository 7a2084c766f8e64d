"""The symmetric similarity ICP and the landmark-free shape model (thesis chapter 7)
from Python."""
import itk
import pytest

from conftest import ImageF, Mesh, QEMesh, assert_valid_closed, distance_report, phantom_image


def ellipsoid_mesh(semi_axes, centre=(16.0, 16.0, 16.0), mesh_type=Mesh, size=32):
    surface = itk.EllipsoidImplicitSurface.New()
    surface.SetCenter(list(centre))
    surface.SetSemiAxes(list(semi_axes))
    return itk.surface_nets_image_to_mesh_filter(
        phantom_image(surface, size), iso_value=0.0, inside_is_above_iso_value=False, high_quality=True,
        ttype=(ImageF, mesh_type))


@pytest.fixture(scope="module")
def training():
    """Three ellipsoids that differ in one axis, in different positions."""
    return [ellipsoid_mesh((10.0, 7.0, 5.0 + 1.0 * k), centre=(16.0 + k, 16.0 - k, 16.0)) for k in range(3)]


@pytest.mark.parametrize("mesh_type", [Mesh, QEMesh])
def test_icp_recovers_a_similarity(mesh_type):
    fixed = ellipsoid_mesh((10.0, 7.0, 5.0), mesh_type=mesh_type)
    moving = ellipsoid_mesh((10.0, 7.0, 5.0), centre=(17.5, 15.0, 16.5), mesh_type=mesh_type)
    icp = itk.SymmetricSimilarityICPRegistration[mesh_type].New()
    icp.SetFixedMesh(fixed)
    icp.SetMovingMesh(moving)
    icp.Update()
    assert icp.GetMeanDistance() < 0.1
    transform = icp.GetTransform()
    # The transform maps the fixed mesh onto the moving one: the centre moves by the offset.
    centre = transform.TransformPoint(itk.Point[itk.D, 3]([16.0, 16.0, 16.0]))
    assert [centre[i] for i in range(3)] == pytest.approx([17.5, 15.0, 16.5], abs=0.1)
    assert transform.GetScale() == pytest.approx(1.0, abs=0.01)


def test_shape_model_of_three_meshes(training, tmp_path):
    estimator = itk.LandmarkFreeShapeModelEstimator[Mesh].New()
    for mesh in training:
        estimator.AddInputMesh(mesh)
    assert estimator.GetNumberOfInputMeshes() == 3
    estimator.SetVarianceFraction(0.999)
    estimator.Update()
    variances = list(estimator.GetVariances())
    assert 1 <= estimator.GetNumberOfModes() == len(variances) <= 2
    assert variances == sorted(variances, reverse=True) and variances[0] > 0
    assert sum(variances) <= estimator.GetTotalVariance() * (1 + 1e-9)
    mean = estimator.GetMeanMesh()
    assert_valid_closed(mean)
    # The mean shape: the middle ellipsoid's third axis (6 mm), up to the alignment.
    volume = assert_valid_closed(mean)["enclosed_volume"]
    assert volume == pytest.approx(4.0 / 3.0 * 3.141592653589793 * 10 * 7 * 6, rel=0.05)
    plus = estimator.Synthesize([2.0] + [0.0] * (estimator.GetNumberOfModes() - 1))
    minus = estimator.Synthesize([-2.0] + [0.0] * (estimator.GetNumberOfModes() - 1))
    assert_valid_closed(plus)
    assert_valid_closed(minus)
    assert abs(assert_valid_closed(plus)["enclosed_volume"] - assert_valid_closed(minus)["enclosed_volume"]) > \
        0.05 * volume
    coefficients = estimator.Project(training[2])
    assert len(coefficients) == estimator.GetNumberOfModes()
    model_file = tmp_path / "model.h5"
    estimator.WriteModel(str(model_file))
    assert model_file.stat().st_size > 1000


def test_an_open_mesh_is_refused(training):
    from itk import meshextraction
    points, triangles = meshextraction.arrays_from_mesh(training[0])
    opened = meshextraction.mesh_from_arrays(points, triangles[1:])
    estimator = itk.LandmarkFreeShapeModelEstimator[Mesh].New()
    estimator.AddInputMesh(training[1])
    estimator.AddInputMesh(opened)
    with pytest.raises(RuntimeError, match="open"):
        estimator.Update()


def test_symmetric_metric_is_zero_at_half_the_transform():
    """Thesis eq. 7.3 for paired points: Q moves the fixed points forward and the moving
    points back, so the residuals vanish when Q is half the fixed-to-moving transform."""
    PointSet = itk.PointSet[itk.D, 3]
    fixed, moving = PointSet.New(), PointSet.New()
    corners = [[0, 0, 0], [10, 0, 0], [0, 10, 0], [0, 0, 10]]
    for i, p in enumerate(corners):
        fixed.SetPoint(i, itk.Point[itk.D, 3](p))
        moving.SetPoint(i, itk.Point[itk.D, 3]([p[0] + 2, p[1] + 4, p[2] - 6]))
    metric = itk.SymmetricPairedPointSetMetric[PointSet].New()
    metric.SetFixedPointSet(fixed)
    metric.SetMovingPointSet(moving)
    transform = itk.TranslationTransform[itk.D, 3].New()
    metric.SetTransform(transform)
    metric.Initialize()
    assert metric.GetNumberOfValues() == 12
    at_identity = metric.GetValue(transform.GetParameters())
    assert [at_identity[i] for i in range(12)] == pytest.approx([-2.0, -4.0, 6.0] * 4)
    half = transform.GetParameters()
    half[0], half[1], half[2] = 1.0, 2.0, -3.0
    at_half = metric.GetValue(half)
    assert [at_half[i] for i in range(12)] == pytest.approx([0.0] * 12, abs=1e-12)
    metric.SetWeights([1.0, 2.0])  # one weight per pair, or none
    with pytest.raises(RuntimeError, match="Weights: one per pair, 4, got 2"):
        metric.Initialize()
