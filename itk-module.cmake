# The one list of MeshExtraction's ITK dependencies. Read by ITK's module macros and,
# against an installed ITK without them, by CMake/MeshExtractionInstalledITK.cmake.
get_filename_component(MY_CURRENT_DIR "${CMAKE_CURRENT_LIST_FILE}" PATH)
file(READ "${MY_CURRENT_DIR}/README.md" DOCUMENTATION)

itk_module(MeshExtraction
  ENABLE_SHARED
  DEPENDS
    ITKCommon
    ITKMesh
    ITKQuadEdgeMesh
    ITKQuadEdgeMeshFiltering
    ITKImageFunction
    ITKImageIntensity
    ITKImageSources
    ITKImageNoise
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
