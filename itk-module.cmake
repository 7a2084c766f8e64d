# The one list of MeshExtraction's ITK dependencies. Read by ITK's module macros and,
# against an installed ITK without them, by CMake/MeshExtractionInstalledITK.cmake.
# The description is a line of its own, not README.md: the README's semicolons would
# split it into arguments that ITK's itk_module() rejects ("Unknown argument").
set(DOCUMENTATION "Accurate, well-formed surface meshes from CT and MRI volumes: SurfaceNets with \
greyscale relaxation (SNA, SNERT) and a high-quality mode that alternates it with regularity \
edge swaps, with guarded Laplacian and Taubin smoothing, edge swapping, scale-space edge \
refinement and the mesh quality measures of P.W. de Bruin's thesis (TU Delft, 2004).")

itk_module(MeshExtraction
  ENABLE_SHARED
  DEPENDS
    ITKCommon
    ITKMesh
    ITKQuadEdgeMesh
    ITKQuadEdgeMeshFiltering
    ITKImageFunction
    ITKImageGrid
    ITKImageSources
    ITKTransform
    ITKOptimizers
    ITKRegistrationCommon
    ITKStatistics
    ITKZLIB
    ITKEigen3
    ITKHDF5
  TEST_DEPENDS
    ITKTestKernel
    ITKGoogleTest
    ITKIOImageBase
    ITKIONRRD
    ITKIOMeta
    ITKIOMeshBase
    ITKIOMeshVTK
    ITKIOMeshOBJ
    ITKIOMeshOFF
  DESCRIPTION
    "${DOCUMENTATION}"
  EXCLUDE_FROM_DEFAULT
)
