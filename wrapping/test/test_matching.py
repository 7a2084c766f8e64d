"""The three-landmark incremental match (thesis chapter 6) from Python: a known
transform recovered from landmarks, usable by itk.resample_image_filter."""
import math

import itk
import numpy as np
import pytest

from conftest import ImageF, phantom_image

Initializer = itk.ThreeLandmarkIncrementalTransformInitializer[itk.Transform[itk.D, 3, 3]]


def rigid(angle=0.7, axis=(0.3, -0.5, 0.8), translation=(6.0, -4.0, 3.0), centre=(20.0, 18.0, 16.0)):
    t = itk.VersorRigid3DTransform[itk.D].New()
    t.SetCenter(centre)
    versor = itk.Versor[itk.D]()
    versor.Set(itk.Vector[itk.D, 3](axis), angle)
    t.SetRotation(versor)
    t.SetTranslation(translation)
    return t


def points(xs):
    return [itk.Point[itk.D, 3](p) for p in xs]


FIXED = points([[10.0, 12.0, 14.0], [30.0, 14.0, 16.0], [18.0, 28.0, 22.0]])


def test_a_rigid_transform_is_recovered_exactly():
    truth = rigid()
    found = itk.VersorRigid3DTransform[itk.D].New()
    initializer = Initializer.New()
    initializer.SetTransform(found)
    initializer.SetFixedLandmarks(FIXED)
    initializer.SetMovingLandmarks([truth.TransformPoint(p) for p in FIXED])
    initializer.InitializeTransform()
    for x in (-50.0, 0.0, 50.0):
        for y in (-50.0, 0.0, 50.0):
            p = itk.Point[itk.D, 3]([x, y, 10.0])
            assert math.dist(found.TransformPoint(p), truth.TransformPoint(p)) < 1e-9
    assert list(initializer.GetLandmarkResiduals()) == pytest.approx([0.0] * 3, abs=1e-9)


def test_distension_recovers_a_scale():
    truth = itk.Similarity3DTransform[itk.D].New()
    truth.SetScale(1.2)
    truth.SetTranslation([2.0, 1.0, -3.0])
    found = itk.Similarity3DTransform[itk.D].New()
    initializer = Initializer.New(Transform=found, Distension=itk.MeshExtractionEnums.LandmarkDistension_Isotropic)
    initializer.SetFixedLandmarks(FIXED)
    initializer.SetMovingLandmarks([truth.TransformPoint(p) for p in FIXED])
    initializer.InitializeTransform()
    assert found.GetScale() == pytest.approx(1.2, rel=1e-9)


def test_the_transform_resamples_an_image_onto_the_other():
    sphere = itk.EllipsoidImplicitSurface.New()
    sphere.SetCenter([18.0, 20.0, 16.0])
    sphere.SetSemiAxes([9.0, 6.0, 4.5])
    fixed = phantom_image(sphere, 40, mode=itk.MeshExtractionEnums.PhantomImage_BlurredStep,
                          InsideValue=100.0, OutsideValue=0.0, EdgeWidth=1.0)
    truth = rigid(angle=0.4)
    # The moving image holds at truth(x) what the fixed image holds at x.
    moving = itk.resample_image_filter(fixed, transform=truth.GetInverseTransform(), use_reference_image=True,
                                       reference_image=fixed)
    found = itk.VersorRigid3DTransform[itk.D].New()
    initializer = Initializer.New(Transform=found)
    initializer.SetFixedLandmarks(FIXED)
    initializer.SetMovingLandmarks([truth.TransformPoint(p) for p in FIXED])
    initializer.InitializeTransform()
    back = itk.resample_image_filter(moving, transform=found, use_reference_image=True, reference_image=fixed)
    f, m, b = (itk.array_from_image(i) for i in (fixed, moving, back))
    inside = np.zeros_like(f, dtype=bool)
    inside[8:32, 8:32, 8:32] = True  # away from the border, where resampling had no data
    before = np.abs(m - f)[inside].mean()
    after = np.abs(b - f)[inside].mean()
    assert before > 5.0
    assert after < 0.1 * before
