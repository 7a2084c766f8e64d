"""MultiLabelSurfaceNetsImageToMeshFilter from Python: every label of a label map in one
pass, each label's surface valid, the shared faces and their labels."""
import itk
import numpy as np
import pytest

from conftest import Mesh, assert_valid_closed


@pytest.fixture(scope="module")
def boxes():
    """Labels 1 and 2: two 4 x 6 x 6 boxes side by side (x < 6 and x >= 6)."""
    array = np.zeros((10, 10, 12), dtype=np.uint8)  # z, y, x
    array[2:8, 2:8, 2:6] = 1
    array[2:8, 2:8, 6:10] = 2
    image = itk.image_from_array(array)
    image.SetSpacing([0.5, 0.5, 0.5])
    return image


def test_shared_faces_once_and_each_label_closed(boxes):
    f = itk.MultiLabelSurfaceNetsImageToMeshFilter[type(boxes), Mesh].New()
    f.SetInput(boxes)
    f.Update()
    mesh = f.GetOutput()
    assert list(f.GetExtractedLabels()) == [1, 2]
    pairs = [(f.GetFaceLabel(i, 0), f.GetFaceLabel(i, 1)) for i in range(mesh.GetNumberOfCells())]
    assert set(pairs) == {(0, 1), (0, 2), (1, 2)}
    shared = pairs.count((1, 2))
    assert shared == 2 * 6 * 6  # the 6 x 6 voxel faces between the boxes, two triangles each
    for label in (1, 2):
        surface = f.GetLabelSurface(label)
        assert_valid_closed(surface)
        # Each box's surface holds the faces it shares with the other.
        assert surface.GetNumberOfCells() == pairs.count((0, label)) + shared


def test_functional_api_and_a_label_list(boxes):
    mesh = itk.multi_label_surface_nets_image_to_mesh_filter(boxes, ttype=(type(boxes), Mesh))
    assert mesh.GetNumberOfCells() > 0
    f = itk.MultiLabelSurfaceNetsImageToMeshFilter[type(boxes), Mesh].New(boxes)
    f.SetLabels([2])
    f.Update()
    assert list(f.GetExtractedLabels()) == [2]
    assert_valid_closed(f.GetLabelSurface(2))


def test_unsigned_short_labels():
    array = np.zeros((8, 8, 8), dtype=np.uint16)
    array[2:6, 2:6, 2:6] = 1000
    image = itk.image_from_array(array)
    f = itk.MultiLabelSurfaceNetsImageToMeshFilter[type(image), Mesh].New(image)
    f.Update()
    assert list(f.GetExtractedLabels()) == [1000]
    assert_valid_closed(f.GetLabelSurface(1000))


def test_a_label_without_voxels_is_an_error(boxes):
    f = itk.MultiLabelSurfaceNetsImageToMeshFilter[type(boxes), Mesh].New(boxes)
    f.SetLabels([7])
    with pytest.raises(RuntimeError, match="7"):
        f.Update()
