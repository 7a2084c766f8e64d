"""Mesh files from Python: itk.meshread / itk.meshwrite for itk.Mesh where ITK's mesh IO
has the format, and the module's own reader and writer (VTK legacy 4.2 and 5.1, VTP,
PLY, STL, OBJ, OFF) for itk.Mesh and QuadEdgeMesh; round trips keep points and cells."""
import itk
import numpy as np
import pytest
from itk import meshextraction

from conftest import Mesh, QEMesh, assert_valid_closed

Enums = itk.MeshExtractionEnums
FORMATS = [(".vtk", Enums.VTKLegacyVersion_V4_2, Enums.MeshFileEncoding_ASCII),
           (".vtk", Enums.VTKLegacyVersion_V5_1, Enums.MeshFileEncoding_ASCII),
           (".vtk", Enums.VTKLegacyVersion_V4_2, Enums.MeshFileEncoding_Binary),
           (".vtk", Enums.VTKLegacyVersion_V5_1, Enums.MeshFileEncoding_Binary),
           (".vtp", None, Enums.MeshFileEncoding_Default),
           (".vtp", None, Enums.MeshFileEncoding_ASCII),
           (".ply", None, Enums.MeshFileEncoding_Binary),
           (".ply", None, Enums.MeshFileEncoding_ASCII),
           (".stl", None, Enums.MeshFileEncoding_Binary),
           (".stl", None, Enums.MeshFileEncoding_ASCII),
           (".obj", None, Enums.MeshFileEncoding_Default),
           (".off", None, Enums.MeshFileEncoding_Default)]


def write(mesh, path, version=None, encoding=None):
    writer = itk.SurfaceMeshFileWriter[type(mesh)].New()
    writer.SetInput(mesh)
    writer.SetFileName(str(path))
    if version is not None:
        writer.SetVTKLegacyVersion(version)
    if encoding is not None:
        writer.SetEncoding(encoding)
    writer.Update()


def read(path, mesh_type):
    reader = itk.SurfaceMeshFileReader[mesh_type].New()
    reader.SetFileName(str(path))
    reader.Update()
    return reader.GetOutput()


@pytest.mark.parametrize("case", range(len(FORMATS)))
@pytest.mark.parametrize("mesh_type", [Mesh, QEMesh])
def test_round_trip_keeps_points_and_triangles(case, mesh_type, small_sphere_mesh, tmp_path):
    extension, version, encoding = FORMATS[case]
    mesh = small_sphere_mesh if mesh_type is QEMesh else itk.surface_mesh_convert_filter(
        small_sphere_mesh, ttype=(QEMesh, Mesh))
    path = tmp_path / ("sphere" + extension)
    write(mesh, path, version, encoding)
    back = read(path, mesh_type)
    points, triangles = meshextraction.arrays_from_mesh(mesh)
    back_points, back_triangles = meshextraction.arrays_from_mesh(back)
    assert len(back_triangles) == len(triangles)
    assert_valid_closed(back)
    if extension == ".stl":
        # STL stores corners, joined again by their coordinates: the same point set.
        assert len(back_points) == len(points)
        np.testing.assert_allclose(np.sort(back_points, axis=0), np.sort(points, axis=0), atol=1e-6)
    else:
        np.testing.assert_array_equal(back_points, points)
        np.testing.assert_array_equal(np.sort(np.sort(back_triangles, axis=1), axis=0),
                                      np.sort(np.sort(triangles, axis=1), axis=0))


def test_snake_case_reader_and_writer(small_sphere_mesh, tmp_path):
    path = tmp_path / "sphere.ply"
    itk.surface_mesh_file_writer(small_sphere_mesh, file_name=str(path))
    back = itk.surface_mesh_file_reader(file_name=str(path), ttype=QEMesh)
    assert back.GetNumberOfFaces() == small_sphere_mesh.GetNumberOfFaces()


def test_itk_meshread_and_meshwrite_of_the_itk_mesh(small_sphere_mesh, tmp_path):
    """ITK's own mesh IO, for the itk.Mesh the module converts to."""
    mesh = itk.surface_mesh_convert_filter(small_sphere_mesh, ttype=(QEMesh, Mesh))
    for name in ("sphere.vtk", "sphere.obj", "sphere.off"):
        itk.meshwrite(mesh, str(tmp_path / name))
        back = itk.meshread(str(tmp_path / name), itk.D)
        assert back.GetNumberOfPoints() == mesh.GetNumberOfPoints()
        assert back.GetNumberOfCells() == mesh.GetNumberOfCells()
        # What ITK writes, the module reads, into a QuadEdgeMesh too.
        qe = read(tmp_path / name, QEMesh)
        assert qe.GetNumberOfFaces() == small_sphere_mesh.GetNumberOfFaces()
        assert_valid_closed(qe)
    # And what the module writes, ITK reads.
    write(mesh, tmp_path / "module.vtk")
    assert itk.meshread(str(tmp_path / "module.vtk"), itk.D).GetNumberOfCells() == mesh.GetNumberOfCells()


def test_a_failed_write_keeps_the_old_file(small_sphere_mesh, tmp_path):
    path = tmp_path / "sphere.obj"
    write(small_sphere_mesh, path)
    before = path.read_bytes()
    with pytest.raises(RuntimeError, match="binary|OBJ"):
        write(small_sphere_mesh, path, encoding=Enums.MeshFileEncoding_Binary)  # OBJ is text only
    assert path.read_bytes() == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["sphere.obj"]  # no partial file left


def test_bad_files_are_named(tmp_path):
    truncated = tmp_path / "truncated.ply"
    truncated.write_text("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                         "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                         "0 0 0\n1 0 0\n")
    with pytest.raises(RuntimeError, match="truncated.ply"):
        read(truncated, Mesh)
    with pytest.raises(RuntimeError, match="names no format"):
        read(tmp_path / "mesh.xyz", Mesh)
    with pytest.raises(RuntimeError, match="missing.vtk"):
        read(tmp_path / "missing.vtk", Mesh)
    open_octahedron = tmp_path / "open.obj"
    open_octahedron.write_text("v 1 0 0\nv -1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nv 0 0 -1\n"
                               "f 1 3 5\nf 3 2 5\nf 2 4 5\nf 4 1 5\nf 3 1 6\nf 2 3 6\nf 4 2 6\n")
    assert read(open_octahedron, Mesh).GetNumberOfCells() == 7  # an itk.Mesh holds any faces
    fin = tmp_path / "fin.obj"
    fin.write_text(open_octahedron.read_text() + "f 1 4 6\nf 1 2 3\nf 1 3 4\n")
    with pytest.raises(RuntimeError, match="fin.obj"):
        read(fin, QEMesh)
