"""Bad input from Python raises a Python exception that names the problem; the
interpreter never crashes."""
import itk
import numpy as np
import pytest
from itk import meshextraction

from conftest import ImageF, Mesh, QEMesh


def extract(image, mesh_type=Mesh, **settings):
    f = itk.SurfaceNetsImageToMeshFilter[type(image), mesh_type].New(image, **settings)
    f.Update()
    return f.GetOutput()


def test_a_pixel_type_that_is_not_wrapped():
    rgb = itk.Image[itk.RGBPixel[itk.UC], 3].New()
    with pytest.raises((KeyError, TypeError, itk.TemplateTypeError), match="SurfaceNetsImageToMeshFilter|RGB"):
        itk.SurfaceNetsImageToMeshFilter[type(rgb), Mesh]
    with pytest.raises(Exception, match="SurfaceNetsImageToMeshFilter|not wrapped|RGB"):
        itk.surface_nets_image_to_mesh_filter(rgb, iso_value=0)


def test_a_2d_image_is_refused():
    image = itk.image_from_array(np.zeros((8, 8), dtype=np.float32))
    with pytest.raises(Exception, match="SurfaceNetsImageToMeshFilter|not wrapped|2"):
        itk.surface_nets_image_to_mesh_filter(image, iso_value=0)


def test_an_empty_image():
    image = ImageF.New()
    with pytest.raises(RuntimeError, match="empty|region|size"):
        extract(image, IsoValue=0.0)


def test_a_constant_image_and_a_nan():
    constant = itk.image_from_array(np.ones((8, 8, 8), dtype=np.float32))
    with pytest.raises(RuntimeError, match="no voxel|iso|constant|surface"):
        extract(constant, IsoValue=0.0)
    array = np.random.default_rng(1).normal(size=(8, 8, 8)).astype(np.float32)
    array[3, 4, 5] = np.nan
    with pytest.raises(RuntimeError, match="NaN|not finite"):
        extract(itk.image_from_array(array), IsoValue=0.0)


def test_a_setting_out_of_range(small_sphere):
    from conftest import phantom_image
    image = phantom_image(small_sphere, 20)
    with pytest.raises(RuntimeError, match="GradientSigma|sigma"):
        extract(image, IsoValue=0.0, GradientMethod=itk.SurfaceNetsImageToMeshFilterEnums.Gradient_GaussianDerivative,
                GradientSigma=-1.0)
    with pytest.raises(RuntimeError, match="HighQualityTargetEdgeLength|target edge length"):
        extract(image, IsoValue=0.0, HighQuality=True, HighQualityRemeshing=True, HighQualityTargetEdgeLength=-2.0)


def test_an_open_mesh_where_a_closed_one_is_needed():
    points = np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]], dtype=float)
    triangles = np.array([[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4], [2, 0, 5], [1, 2, 5], [3, 1, 5]])
    opened = meshextraction.mesh_from_arrays(points, triangles)
    closed = meshextraction.mesh_from_arrays(points, np.vstack([triangles, [[0, 3, 5]]]))
    estimator = itk.LandmarkFreeShapeModelEstimator[Mesh].New()
    estimator.AddInputMesh(closed)
    estimator.AddInputMesh(opened)
    with pytest.raises(RuntimeError, match="open|closed|boundary"):
        estimator.Update()


def test_filters_without_input():
    for f in (itk.LaplacianSmoothingQuadEdgeMeshFilter[QEMesh].New(),
              itk.EdgeSwapQuadEdgeMeshFilter[QEMesh].New(),
              itk.SurfaceMeshConvertFilter[Mesh, QEMesh].New(),
              itk.SurfaceMeshFileReader[QEMesh].New()):
        with pytest.raises(RuntimeError):
            f.Update()
    calculator = itk.TriangleMeshQualityCalculator[Mesh].New()
    with pytest.raises(RuntimeError):
        calculator.Compute()
