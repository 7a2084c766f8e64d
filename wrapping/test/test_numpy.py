"""NumPy and the module's meshes: points and triangles of a mesh as arrays, a mesh made
from arrays (itk.meshextraction), ITK's own NumPy helpers on the filters' itk.Mesh, and
the conversion between itk.Mesh and QuadEdgeMesh."""
import itk
import numpy as np
import pytest
from itk import meshextraction

from conftest import ImageF, Mesh, QEMesh, assert_valid_closed, distance_report, phantom_image


def octahedron():
    points = np.array([[2, 0, 0], [-2, 0, 0], [0, 2, 0], [0, -2, 0], [0, 0, 2], [0, 0, -2]], dtype=float)
    triangles = np.array([[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4], [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]])
    return points, triangles


@pytest.mark.parametrize("mesh_type", [Mesh, QEMesh])
def test_arrays_round_trip(mesh_type):
    points, triangles = octahedron()
    mesh = meshextraction.mesh_from_arrays(points, triangles, mesh_type)
    assert isinstance(mesh, mesh_type)
    assert_valid_closed(mesh)
    back_points, back_triangles = meshextraction.arrays_from_mesh(mesh)
    assert back_points.shape == (6, 3) and back_points.dtype == np.float64
    assert back_triangles.shape == (8, 3) and np.issubdtype(back_triangles.dtype, np.integer)
    np.testing.assert_array_equal(back_points, points)
    # The same triangles, each with its orientation (a QuadEdgeMesh may start a face at
    # another corner).
    def canonical(t):
        return sorted(tuple(np.roll(row, -int(np.argmin(row)))) for row in t)
    assert canonical(back_triangles) == canonical(triangles)


def test_arrays_of_a_filters_output(small_sphere_mesh, small_sphere):
    points, triangles = meshextraction.arrays_from_mesh(small_sphere_mesh)
    assert len(points) == small_sphere_mesh.GetNumberOfPoints()
    assert len(triangles) == small_sphere_mesh.GetNumberOfFaces()
    # The points' distances to the sphere, from the arrays, are the calculator's.
    radii = np.linalg.norm(points - 9.5, axis=1)
    assert np.abs(radii - 6.0).mean() == pytest.approx(
        distance_report(small_sphere_mesh, small_sphere)["vertices"]["mean"], rel=1e-6)
    # Euler characteristic of a sphere from the arrays: V - E + F = 2.
    edges = {tuple(sorted(e)) for t in triangles for e in ((t[0], t[1]), (t[1], t[2]), (t[2], t[0]))}
    assert len(points) - len(edges) + len(triangles) == 2


def test_itk_numpy_helpers_on_the_itk_mesh_output(small_sphere):
    mesh = itk.surface_nets_image_to_mesh_filter(phantom_image(small_sphere, 20), iso_value=0.0,
                                                 inside_is_above_iso_value=False, ttype=(ImageF, Mesh))
    points = itk.array_from_vector_container(mesh.GetPoints())
    assert points.shape == (mesh.GetNumberOfPoints(), 3)
    as_dict = itk.dict_from_mesh(mesh)
    assert as_dict["numberOfCells"] == mesh.GetNumberOfCells()
    again = itk.mesh_from_dict(as_dict)
    assert_valid_closed(again)


def test_conversion_between_mesh_types(small_sphere_mesh):
    plain = itk.surface_mesh_convert_filter(small_sphere_mesh, ttype=(QEMesh, Mesh))
    assert plain.GetNumberOfCells() == small_sphere_mesh.GetNumberOfFaces()  # no edge cells
    qe = itk.SurfaceMeshConvertFilter[Mesh, QEMesh].New(plain)
    qe.Update()
    assert qe.GetOutput().GetNumberOfFaces() == small_sphere_mesh.GetNumberOfFaces()
    assert qe.GetOutput().GetNumberOfEdges() == small_sphere_mesh.GetNumberOfEdges()
    assert_valid_closed(qe.GetOutput())


def test_bad_arrays_are_named():
    points, triangles = octahedron()
    with pytest.raises(ValueError, match="points must be an"):
        meshextraction.mesh_from_arrays(points[:, :2], triangles)
    with pytest.raises(ValueError, match="triangle 7 names point"):
        meshextraction.mesh_from_arrays(points, np.vstack([triangles[:7], [[0, 1, 6]]]))
    bad = points.copy()
    bad[3, 1] = np.nan
    with pytest.raises(ValueError, match="point 3"):
        meshextraction.mesh_from_arrays(bad, triangles)
    with pytest.raises(ValueError, match="integer"):
        meshextraction.mesh_from_arrays(points, triangles.astype(float))
    # Three triangles on one edge: not a surface a QuadEdgeMesh can hold.
    fin = np.vstack([triangles, [[0, 2, 1]]])
    with pytest.raises(RuntimeError, match="manifold|orient"):
        meshextraction.mesh_from_arrays(points, fin, QEMesh)
