"""Two touching boxes of a label map in one pass from Python: one copy of the faces they
share, and each box's closed surface."""
import json

import itk

ImageType = itk.Image[itk.UC, 3]
MeshType = itk.Mesh[itk.D, 3]
image = ImageType.New()
region = itk.ImageRegion[3]()
region.SetSize([12, 10, 10])
image.SetRegions(region)
image.Allocate()
image.FillBuffer(0)
for z in range(2, 8):
    for y in range(2, 8):
        for x in range(2, 10):
            image.SetPixel([x, y, z], 1 if x < 6 else 2)

f = itk.MultiLabelSurfaceNetsImageToMeshFilter[ImageType, MeshType].New()
f.SetInput(image)
f.Update()
mesh = f.GetOutput()
pairs = [(f.GetFaceLabel(i, 0), f.GetFaceLabel(i, 1)) for i in range(mesh.GetNumberOfCells())]
assert set(pairs) == {(0, 1), (0, 2), (1, 2)}, set(pairs)
shared = pairs.count((1, 2))
assert shared == 2 * 6 * 6, shared  # the 6 x 6 voxel faces between the boxes, two triangles each

for label in (1, 2):
    surface = f.GetLabelSurface(label)
    calculator = itk.TriangleMeshQualityCalculator[MeshType].New()
    calculator.SetMesh(surface)
    calculator.Compute()
    report = json.loads(calculator.GetReportAsJSON())
    assert report["valid_closed_surface"], report
    assert report["euler_characteristic"] == 2, report
    # The faces each box shares with the other are in its own surface too.
    assert surface.GetNumberOfCells() == pairs.count((0, label)) + shared
print("multi-label from Python: ok")
