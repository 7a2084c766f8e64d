"""The analytic phantoms from Python: exact signed distances (negative inside), closest
surface points, and their images, from which SurfaceNets recovers the surface."""
import math

import itk
import pytest

from conftest import ImageF, Mesh, assert_valid_closed, distance_report, phantom_image


def P(*xyz):
    return itk.Point[itk.D, 3](list(xyz))


def shapes():
    plane = itk.PlaneImplicitSurface.New()
    plane.SetPoint(P(0, 0, 1))
    plane.SetNormal([0.0, 0.0, 1.0])
    sphere = itk.SphereImplicitSurface.New(Center=P(1, 2, 3), Radius=4.0)
    ellipsoid = itk.EllipsoidImplicitSurface.New()
    ellipsoid.SetSemiAxes([6.0, 4.0, 3.0])
    torus = itk.TorusImplicitSurface.New()
    torus.SetRadii(8.0, 2.0)
    box = itk.BoxImplicitSurface.New()
    box.SetHalfSizes([3.0, 4.0, 5.0])
    union = itk.SphereUnionImplicitSurface.New()
    union.AddSphere(P(-2, 0, 0), 3.0)
    union.AddSphere(P(2, 0, 0), 3.0)
    difference = itk.SphereDifferenceImplicitSurface.New()
    difference.SetCenterA(P(0, 0, 0))
    difference.SetRadiusA(5.0)
    difference.SetCenterB(P(0, 0, 5))
    difference.SetRadiusB(3.0)
    cleft = itk.NarrowCleftImplicitSurface.New()
    # (shape, a point, its exact signed distance)
    return [
        (plane, P(3, -2, 4), 3.0),
        (sphere, P(1, 2, 3), -4.0),
        (sphere, P(1, 2, 10), 3.0),
        (ellipsoid, P(0, 0, 0), -3.0),
        (ellipsoid, P(9, 0, 0), 3.0),
        (torus, P(8, 0, 0), -2.0),
        (torus, P(0, 0, 0), 6.0),
        (box, P(0, 0, 0), -3.0),
        (box, P(0, 0, 8), 3.0),
        (union, P(0, 0, 0), -math.sqrt(5.0)),
        (union, P(8, 0, 0), 3.0),
        (difference, P(0, 0, -2), -3.0),
        (cleft, P(5, 0, 20), 10.0),
    ]


@pytest.mark.parametrize("case", range(len(shapes())))
def test_signed_distance_and_closest_point(case):
    shape, point, distance = shapes()[case]
    assert shape.Evaluate(point) == pytest.approx(distance, abs=1e-9)
    assert shape.IsInside(point) == (distance < 0)
    closest = shape.ClosestSurfacePoint(point)
    assert shape.Evaluate(closest) == pytest.approx(0.0, abs=1e-9)
    assert math.dist(closest, point) == pytest.approx(abs(distance), abs=1e-9)


def test_image_modes_and_the_surface_from_them():
    torus = itk.TorusImplicitSurface.New()
    torus.SetCenter(P(16, 16, 16))
    torus.SetRadii(9.0, 3.5)
    distance = phantom_image(torus, 33)
    value = distance.GetPixel([16 + 9, 16, 16])  # on the tube's centre line
    assert value == pytest.approx(-3.5, abs=1e-5)
    mesh = itk.surface_nets_image_to_mesh_filter(distance, iso_value=0.0, inside_is_above_iso_value=False,
                                                 high_quality=True, ttype=(ImageF, Mesh))
    assert_valid_closed(mesh, euler=0)  # a torus: genus 1
    assert distance_report(mesh, torus)["vertices"]["mean"] < 0.03
    mask = phantom_image(torus, 33, image_type=itk.Image[itk.UC, 3],
                         mode=itk.MeshExtractionEnums.PhantomImage_BinaryMask, InsideValue=7, OutsideValue=0)
    assert mask.GetPixel([16 + 9, 16, 16]) == 7 and mask.GetPixel([16, 16, 16]) == 0
    noisy = phantom_image(torus, 33, mode=itk.MeshExtractionEnums.PhantomImage_BlurredStep, InsideValue=100.0,
                          OutsideValue=0.0, EdgeWidth=1.0, NoiseStandardDeviation=5.0, NoiseSeed=3)
    again = phantom_image(torus, 33, mode=itk.MeshExtractionEnums.PhantomImage_BlurredStep, InsideValue=100.0,
                          OutsideValue=0.0, EdgeWidth=1.0, NoiseStandardDeviation=5.0, NoiseSeed=3)
    a, b = itk.array_from_image(noisy), itk.array_from_image(again)
    assert (a == b).all()  # the noise is a function of the seed and the voxel
    assert 3.0 < (a - itk.array_from_image(phantom_image(
        torus, 33, mode=itk.MeshExtractionEnums.PhantomImage_BlurredStep, InsideValue=100.0, OutsideValue=0.0,
        EdgeWidth=1.0))).std() < 7.0
