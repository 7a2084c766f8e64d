# MeshExtractionVTKPeers: the surface-extraction methods SurfaceNets is compared with
# (VTK's marching cubes and flying edges, 3D Slicer's windowed-sinc pipelines, ITK's
# BinaryMask3DMeshSource, the module's own modes), the conversions between ITK and VTK
# they need, and the runner that times them. A small static library, shared by
# meshextraction-compare (examples/), the VTK comparison test (test/) and the benchmarks
# (benchmark/). It is not part of the module, which does not depend on VTK, and not an
# example: the test and the benchmark use it whether or not the examples are built.
#
# include() this file where the library is needed. It looks for VTK, which sets
# VTK_FOUND and VTK_LIBRARIES in the includer's scope (for vtk_module_autoinit), and
# defines the target MeshExtractionVTKPeers once, in the first directory that includes
# it, if VTK is found. The includer provides the module's headers and ITK
# (ITK_LIBRARIES, and the MeshExtraction target where the module is built alongside).
find_package(VTK COMPONENTS FiltersCore FiltersGeneral CommonCore CommonDataModel QUIET)
if(VTK_FOUND AND NOT TARGET MeshExtractionVTKPeers)
  set(_MeshExtractionVTKPeers_dir ${CMAKE_CURRENT_LIST_DIR})
  add_library(MeshExtractionVTKPeers STATIC
    ${_MeshExtractionVTKPeers_dir}/MeshExtractionVTKPeersConversion.cxx
    ${_MeshExtractionVTKPeers_dir}/MeshExtractionVTKPeersMethods.cxx
    ${_MeshExtractionVTKPeers_dir}/MeshExtractionVTKPeersRunner.cxx
  )
  target_include_directories(MeshExtractionVTKPeers PUBLIC ${_MeshExtractionVTKPeers_dir})
  target_compile_features(MeshExtractionVTKPeers PUBLIC cxx_std_17)
  target_link_libraries(MeshExtractionVTKPeers PUBLIC ${ITK_LIBRARIES} ${VTK_LIBRARIES})
  if(TARGET MeshExtraction)
    target_link_libraries(MeshExtractionVTKPeers PUBLIC MeshExtraction)
  endif()
  vtk_module_autoinit(TARGETS MeshExtractionVTKPeers MODULES ${VTK_LIBRARIES})
  if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    # The methods are timed (meshextraction-compare, the benchmarks): built with -O2
    # whatever the build type, as the benchmarks are, so their times do not depend on
    # it. -O2 comes after the build type's flags, so it is the one in effect.
    target_compile_options(MeshExtractionVTKPeers PRIVATE -O2 -Wall -Wextra -Wshadow)
  endif()
endif()
