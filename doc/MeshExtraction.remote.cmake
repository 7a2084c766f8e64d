# The file ITK's Modules/Remote/ would hold for this module (copy it there as
# MeshExtraction.remote.cmake, with the repository's address and the commit to build).
# Configure ITK with -DModule_MeshExtraction:BOOL=ON to fetch and build it.

# Contact: the MeshExtraction maintainers (see README.md)
itk_fetch_module(MeshExtraction
  "Accurate, well-formed surface meshes from CT and MRI volumes: SurfaceNets with greyscale
  relaxation (SNA, SNERT) and a high-quality mode, guarded smoothing and edge swapping,
  scale-space edge refinement, connected orthogonal contours, three-landmark matching and
  the symmetric ICP of a landmark-free shape model (P.W. de Bruin's thesis, TU Delft, 2004)."
  MODULE_COMPLIANCE_LEVEL 2
  GIT_REPOSITORY ${git_protocol}://github.com/REPLACE-WITH-OWNER/ITKMeshExtraction.git
  GIT_TAG REPLACE-WITH-COMMIT
  )
