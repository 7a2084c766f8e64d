"""The guarded mesh filters on a QuadEdgeMesh from Python: Laplacian and Taubin
smoothing, edge swaps; each keeps the surface valid and does what it is for."""
import itk
import pytest

from conftest import ImageF, QEMesh, assert_valid_closed, distance_report, phantom_image

Enums = itk.MeshExtractionEnums


@pytest.fixture(scope="module")
def rough(small_sphere):
    """SurfaceNets without relaxation: nodes at their cell centres, a staircase."""
    image = phantom_image(small_sphere, 20)
    f = itk.SurfaceNetsImageToMeshFilter[ImageF, QEMesh].New(
        image, IsoValue=0.0, InsideIsAboveIsoValue=False,
        Relaxation=itk.SurfaceNetsImageToMeshFilterEnums.Relaxation__None)
    f.Update()
    return f.GetOutput()


def test_laplacian_smooths_and_keeps_the_surface_valid(rough):
    before = assert_valid_closed(rough)
    f = itk.LaplacianSmoothingQuadEdgeMeshFilter[QEMesh].New(rough)
    f.SetNumberOfIterations(10)
    f.SetWeights(Enums.SmoothingWeights_InverseEdgeLength)
    f.Update()
    after = assert_valid_closed(f.GetOutput())
    assert f.GetNumberOfMoves() > 0
    assert after["mean_smoothness"] < 0.5 * before["mean_smoothness"]
    assert after["points"] == before["points"]


def test_laplacian_volume_preservation_and_every_weight(rough):
    plain_volume = None
    for weights in (Enums.SmoothingWeights_Uniform, Enums.SmoothingWeights_InverseEdgeLength,
                    Enums.SmoothingWeights_Area, Enums.SmoothingWeights_Cotangent,
                    Enums.SmoothingWeights_AngleBisector):
        out = itk.laplacian_smoothing_quad_edge_mesh_filter(rough, weights=weights, number_of_iterations=5)
        assert_valid_closed(out)
    start = assert_valid_closed(rough)["enclosed_volume"]
    plain = itk.laplacian_smoothing_quad_edge_mesh_filter(rough, number_of_iterations=20)
    kept = itk.laplacian_smoothing_quad_edge_mesh_filter(rough, number_of_iterations=20, volume_preservation=True)
    plain_volume = assert_valid_closed(plain)["enclosed_volume"]
    kept_volume = assert_valid_closed(kept)["enclosed_volume"]
    assert plain_volume < start  # Laplacian smoothing shrinks
    assert abs(kept_volume - start) < 0.2 * abs(plain_volume - start)


def test_taubin_smooths_without_shrinking(rough, small_sphere):
    start = assert_valid_closed(rough)["enclosed_volume"]
    f = itk.TaubinSmoothingQuadEdgeMeshFilter[QEMesh].New(rough, NumberOfIterations=20)
    f.Update()
    taubin = assert_valid_closed(f.GetOutput())
    laplacian = assert_valid_closed(itk.laplacian_smoothing_quad_edge_mesh_filter(rough, number_of_iterations=20))
    assert abs(taubin["enclosed_volume"] - start) < abs(laplacian["enclosed_volume"] - start)
    assert f.GetLambda() > 0 > f.GetMu()
    assert distance_report(f.GetOutput(), small_sphere)["vertices"]["mean"] < distance_report(
        rough, small_sphere)["vertices"]["mean"]


def regularity_index(report):
    """E_b summed over the mesh: sum over vertices of (valence - 6)^2 (thesis eq. 2.16)."""
    return sum(count * (valence - 6) ** 2 for valence, count in enumerate(report["valence_histogram"]))


def swap(mesh, criterion):
    f = itk.EdgeSwapQuadEdgeMeshFilter[QEMesh].New(mesh, Criterion=getattr(Enums, "EdgeSwapCriterion_" + criterion))
    f.Update()
    return f


def test_edge_swaps_keep_the_surface_valid_and_do_what_they_are_for(rough):
    before = assert_valid_closed(rough)
    regular = swap(rough, "Regularity")
    after = assert_valid_closed(regular.GetOutput())
    assert regular.GetNumberOfSwaps() > 0
    assert after["points"] == before["points"] and after["triangles"] == before["triangles"]
    assert regularity_index(after) < 0.5 * regularity_index(before)
    # SurfaceNets' shortest diagonals are Delaunay already; the regular mesh is not.
    delaunay = swap(regular.GetOutput(), "Delaunay")
    assert delaunay.GetNumberOfSwaps() > 0
    assert assert_valid_closed(delaunay.GetOutput())["min_angle_deg"]["mean"] > after["min_angle_deg"]["mean"]
    shortest = swap(regular.GetOutput(), "ShortestEdge")
    assert shortest.GetNumberOfSwaps() > 0
    assert assert_valid_closed(shortest.GetOutput())["edge_length"]["mean"] < after["edge_length"]["mean"]
