#!/usr/bin/env python3
"""The three-landmark incremental match from Python: a known rigid transform is
recovered from exact landmarks, and A stays on A when C is uncertain."""
import math
import sys

import itk

Initializer = itk.ThreeLandmarkIncrementalTransformInitializer[itk.Transform[itk.D, 3, 3]]
PointType = itk.Point[itk.D, 3]


def point(x, y, z):
    p = PointType()
    p[0], p[1], p[2] = x, y, z
    return p


truth = itk.VersorRigid3DTransform[itk.D].New()
truth.SetCenter(point(5.0, -3.0, 2.0))
versor = itk.Versor[itk.D]()
axis = itk.Vector[itk.D, 3]()
axis[0], axis[1], axis[2] = 0.3, -0.5, 0.8
versor.Set(axis, 0.7)
truth.SetRotation(versor)
translation = itk.Vector[itk.D, 3]()
translation[0], translation[1], translation[2] = 12.0, -4.0, 30.0
truth.SetTranslation(translation)

fixed = [point(0, 0, 0), point(60, 10, 0), point(20, 35, 15)]
moving = [truth.TransformPoint(p) for p in fixed]

found = itk.VersorRigid3DTransform[itk.D].New()
initializer = Initializer.New()
initializer.SetTransform(found)
initializer.SetFixedLandmarks(fixed)
initializer.SetMovingLandmarks(moving)
initializer.InitializeTransform()

largest = 0.0
for x in (-50.0, 0.0, 50.0):
    for y in (-50.0, 0.0, 50.0):
        p = point(x, y, 10.0)
        a, b = found.TransformPoint(p), truth.TransformPoint(p)
        largest = max(largest, math.dist([a[i] for i in range(3)], [b[i] for i in range(3)]))
print("largest difference to the true transform:", largest)
if largest > 1e-9:
    sys.exit(1)
print("residuals at A, B, C:", list(initializer.GetLandmarkResiduals()))
