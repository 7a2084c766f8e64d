"""Shared inputs and checks of the Python tests of itk-meshextraction.

The tests run as a user runs them: in a venv with PyPI's itk and the itk-meshextraction
wheel (scripts/run-python-tests.sh), or in a wrapped ITK build tree. Every input is made
here, by the module's own phantoms."""
import json

import itk
import pytest

ImageF = itk.Image[itk.F, 3]
ImageUC = itk.Image[itk.UC, 3]
Mesh = itk.Mesh[itk.D, 3]
QEMesh = itk.QuadEdgeMesh[itk.D, 3]

# The sphere of the command-line tool's `phantom sphere --size 64`: a 64^3 grid of 1 mm
# voxels at the origin, centre at the grid's centre, radius 0.3 x 64 = 19.2 mm.
SPHERE_SIZE = 64
SPHERE_RADIUS = 0.3 * SPHERE_SIZE
SPHERE_CENTRE = [(SPHERE_SIZE - 1) / 2.0] * 3


def make_sphere_surface(centre=SPHERE_CENTRE, radius=SPHERE_RADIUS):
    sphere = itk.SphereImplicitSurface.New()
    sphere.SetCenter(centre)
    sphere.SetRadius(radius)
    return sphere


def phantom_image(surface, size, spacing=1.0, image_type=ImageF, mode=None, **settings):
    """The image of an implicit surface: its signed distance (mm, negative inside) by
    default, or another mode of ImplicitSurfaceImageSource."""
    source = itk.ImplicitSurfaceImageSource[image_type].New()
    source.SetSurface(surface)
    source.SetSize([size] * 3 if isinstance(size, int) else list(size))
    source.SetSpacing([spacing] * 3 if isinstance(spacing, (int, float)) else list(spacing))
    if mode is not None:
        source.SetImageMode(mode)
    for name, value in settings.items():
        getattr(source, "Set" + name)(value)
    source.Update()
    return source.GetOutput()


def quality_report(mesh):
    """The quality calculator's report, as a dict."""
    calculator = itk.TriangleMeshQualityCalculator[type(mesh)].New()
    calculator.SetMesh(mesh)
    calculator.Compute()
    return json.loads(calculator.GetReportAsJSON())


def distance_report(mesh, reference):
    """Distances (mm) from a mesh to an implicit surface or another mesh, as a dict."""
    calculator = itk.MeshSurfaceDistanceCalculator[type(mesh), type(mesh)].New()
    calculator.SetMesh(mesh)
    if isinstance(reference, itk.ImplicitSurfaceFunction):
        calculator.SetReferenceSurface(reference)
    else:
        calculator.SetReferenceMesh(reference)
    calculator.Compute()
    return json.loads(calculator.GetReportAsJSON())


def assert_valid_closed(mesh, euler=2):
    """Closed, 2-manifold, consistently oriented outward, no degenerate, inverted or
    crossing triangles: what every mesh of the module must be."""
    report = quality_report(mesh)
    assert report["valid_closed_surface"], report
    assert report["euler_characteristic"] == euler, report
    faces = mesh.GetNumberOfFaces() if isinstance(mesh, QEMesh) else mesh.GetNumberOfCells()
    assert report["triangles"] == faces, report
    return report


@pytest.fixture(scope="session")
def sphere():
    return make_sphere_surface()


@pytest.fixture(scope="session")
def sphere_image(sphere):
    return phantom_image(sphere, SPHERE_SIZE)


@pytest.fixture(scope="session")
def small_sphere():
    """A sphere of radius 6 mm on a 20^3 grid of 1 mm voxels."""
    return make_sphere_surface([9.5] * 3, 6.0)


@pytest.fixture(scope="session")
def small_sphere_mesh(small_sphere):
    """Its high-quality SurfaceNets surface, as a QuadEdgeMesh."""
    image = phantom_image(small_sphere, 20)
    return itk.surface_nets_image_to_mesh_filter(
        image, iso_value=0.0, inside_is_above_iso_value=False, high_quality=True, ttype=(ImageF, QEMesh))
