# ITK modules the examples (the meshextraction command-line tool) need beyond the
# module's own dependencies: readers and writers for images and meshes.
set(MeshExtractionExamples_ITK_COMPONENTS
  ITKIOImageBase
  ITKIONRRD
  ITKIOMeta
  ITKIONIFTI
  ITKIOPNG
  ITKIOGDCM
  ITKIOMeshBase
  ITKIOMeshVTK
  ITKIOMeshOBJ
  ITKIOMeshOFF
  ITKIOMeshGifti
  ITKIOMeshBYU
  ITKIOMeshFreeSurfer
  ITKIOTransformBase
  ITKIOTransformInsightLegacy
  ITKIOTransformHDF5
  ITKRegistrationCommon
  ITKConnectedComponents
  ITKThresholding
  ITKDistanceMap
)
