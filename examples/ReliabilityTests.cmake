# The cases of the second reliability probe (issue 48), each an exit status and the key
# words of its message. Included by CMakeLists.txt inside its test block, where
# meshextraction_cli_test, _out (the working folder) and _input (test/Input) are set.
set(_r ${_out}/reliability)
file(MAKE_DIRECTORY ${_r})
set(_octahedron_faces "f 1 3 5\nf 3 2 5\nf 2 4 5\nf 4 1 5\nf 3 1 6\nf 2 3 6\nf 4 2 6\nf 1 4 6\n")
set(_octahedron_points "v 1 0 0\nv -1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nv 0 0 -1\n")

# 1. A coordinate beyond float range: refused by the readers, no crash in the rendering.
file(WRITE ${_r}/far.obj "v 1e40 0 0\nv -1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nv 0 0 -1\n${_octahedron_faces}")
meshextraction_cli_test(far_coordinate_quality 1 "point 0 has the coordinate 1e+40, beyond the range of float"
  quality ${_r}/far.obj)
meshextraction_cli_test(far_coordinate_report 1 "beyond the range of float coordinates"
  report ${_r}/far-report ${_r}/far.obj)

# 5. Faces of fewer than three vertices are errors naming the face, not dropped.
file(WRITE ${_r}/short-face.obj "${_octahedron_points}${_octahedron_faces}f 1 2\n")
meshextraction_cli_test(short_face 1 "face 8 has 2 vertices; a face needs at least 3"
  quality ${_r}/short-face.obj --require-valid)

# 6. A state that is no similarity: refused when read, before anything is written.
foreach(_case rotation scale)
  if(_case STREQUAL rotation)
    set(_similarity "\"rotation\": [1e308, 0, 0, 0, 1, 0, 0, 0, 1], \"scale\": 1")
    set(_words "the rotation is not a proper rotation")
  else()
    set(_similarity "\"rotation\": [1, 0, 0, 0, 1, 0, 0, 0, 1], \"scale\": 0")
    set(_words "the scale is 0; it must be positive")
  endif()
  file(WRITE ${_r}/state-${_case}.json "{\"e2\": 1, \"corresponded\": \"${_input}/octahedron.obj\", "
    "\"template_to_mesh\": {${_similarity}, \"translation\": [0, 0, 0]}}\n")
  meshextraction_cli_test(renew_bad_${_case} 1 "${_words}" shape-model renew ${_input}/octahedron.obj
    ${_r}/state-${_case}.json --output ${_r}/renewed.ply --json ${_r}/renewal.json)
endforeach()

# 7. Nothing to improve in a mesh whose points all coincide.
string(REGEX REPLACE "v [-0-9 ]+\n" "v 0 0 0\n" _coincident "${_octahedron_points}")
file(WRITE ${_r}/coincident.obj "${_coincident}${_octahedron_faces}")
meshextraction_cli_test(improve_coincident 1 "all 8 triangles are degenerate" improve ${_r}/coincident.obj
  ${_r}/improved.obj)

# 8. Numeric options out of their documented ranges: usage errors naming the range.
meshextraction_cli_test(variance_fraction_negative 2 "--variance-fraction must be in (0, 1], got -1"
  shape-model build ${_input}/octahedron.obj ${_input}/octahedron.obj --output ${_r}/m.h5 --variance-fraction -1)
meshextraction_cli_test(variance_fraction_two 2 "--variance-fraction must be in (0, 1], got 2"
  shape-model build ${_input}/octahedron.obj ${_input}/octahedron.obj --output ${_r}/m.h5 --variance-fraction 2)
meshextraction_cli_test(passes_zero 2 "--passes must be in [1, 100], got 0"
  shape-model build ${_input}/octahedron.obj ${_input}/octahedron.obj --output ${_r}/m.h5 --passes 0)
meshextraction_cli_test(coefficients_huge 2 "--coefficients must be in [-10, 10], got 1e308"
  shape-model sample ${_r}/m.h5 --output ${_r}/s.ply --coefficients=1e308)
meshextraction_cli_test(range_in_help 0 "--variance-fraction F" shape-model --help)
meshextraction_cli_test(range_in_help_text 0 "keep the modes that explain this fraction of the variance ((0, 1]" shape-model --help)

# 9. Settings that would ask for unbounded work.
meshextraction_cli_test(target_edge_length_tiny 1 "is below 0.25 of the smallest voxel spacing"
  extract --phantom sphere ${_r}/x.vtk --size 16 --quality high --remeshing on --target-edge-length 1e-9)
meshextraction_cli_test(remeshing_iterations_huge 2 "--remeshing-iterations must be in [0, 1000], got 100000"
  extract --phantom sphere ${_r}/x.vtk --size 16 --quality high --remeshing on --remeshing-iterations 100000)
meshextraction_cli_test(remeshing_stops_early 0 "rounds (at most 40)"
  extract --phantom sphere ${_r}/x.vtk --size 16 --quality high --remeshing on --remeshing-iterations 20)
meshextraction_cli_test(scales_per_octave_huge 2 "--scales-per-octave must be in [1, 16], got 100000"
  refine ${_r}/sphere.nrrd ${_r}/x.vtk --initial sphere --max-deviation 4 --scales-per-octave 100000)
meshextraction_cli_test(minimum_scale_tiny 1 "blurred images; at most 128"
  refine ${_out}/torus.nrrd ${_r}/x.vtk --initial sphere --radius 10 --max-deviation 4 --minimum-scale 1e-300)
meshextraction_cli_test(improve_iterations_huge 2 "--iterations must be in [0, 1000], got 100000"
  improve ${_input}/octahedron.obj ${_r}/improved.obj --iterations 100000)

# 10. Numbers of the input too large to compute with: named before anything is computed.
set(_nrrd_head "NRRD0004\ntype: float\ndimension: 3\nspace: left-posterior-superior\nsizes: 4 4 4\n")
set(_directions "space directions: (1,0,0) (0,1,0) (0,0,1)\nencoding: ascii\n\n")
string(REPEAT "0 " 63 _zeros)
file(WRITE ${_r}/huge-voxel.nrrd "${_nrrd_head}space origin: (0,0,0)\n${_directions}3e38 ${_zeros}\n")
meshextraction_cli_test(huge_voxel 1 "voxel 0 of the buffer holds 3e+38, beyond +-1e30"
  extract ${_r}/huge-voxel.nrrd ${_r}/x.vtk --iso 1)
file(WRITE ${_r}/far-origin.nrrd "${_nrrd_head}space origin: (1e300,0,0)\n${_directions}1 ${_zeros}\n")
meshextraction_cli_test(far_origin 1 "is beyond +-1e9 mm" extract ${_r}/far-origin.nrrd ${_r}/x.vtk --iso 0.5)
string(REPLACE "sizes: 4 4 4" "sizes: 4 16 1" _flat_head "${_nrrd_head}")
file(WRITE ${_r}/flat.nrrd "${_flat_head}space origin: (0,0,0)\n${_directions}1 ${_zeros}\n")
meshextraction_cli_test(one_voxel_thick 1 "is one voxel thick" extract ${_r}/flat.nrrd ${_r}/x.vtk --iso 0.5)
file(WRITE ${_r}/far-landmarks.json
  "[{\"id\": \"A\", \"coordinates\": [1e300, 0, -10]}, {\"id\": \"B\", \"coordinates\": [0, 0, 10]},\n"
  " {\"id\": \"C\", \"coordinates\": [5, 6, 2]}]\n")
meshextraction_cli_test(far_landmark 1 "landmark \"A\" has the coordinate 1e+300, beyond +-1e9 mm" match ${_match}
  --moving-landmarks ${_r}/far-landmarks.json --transform ${_r}/x.tfm)

# 2-4. Failed writes leave existing models and reports as they were, and no crash.
add_test(NAME cli.failed_runs_keep_outputs
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/CheckOutputsKept.sh $<TARGET_FILE:meshextraction>
          ${_input}/octahedron.obj ${_r}/kept)
# HDF5 crashes on a write that fails part-way: ITK's HDF5 writers (transforms, images)
# get a file only where it can be written whole.
add_test(NAME cli.transform_h5_under_size_limit
  COMMAND ${CMAKE_COMMAND} -DEXPECTED_STATUS=1 "-DPATTERN=HDF5 cannot fail a write safely"
          "-DCOMMAND=sh;-c;ulimit -f 8 && exec $0 match torus.nrrd torus.nrrd --fixed-landmarks match-fixed.json --moving-landmarks match-moving.json --transform limited.h5;$<TARGET_FILE:meshextraction>"
          -P ${CMAKE_CURRENT_SOURCE_DIR}/CheckCommand.cmake
  WORKING_DIRECTORY ${_out})
set_tests_properties(cli.far_landmark cli.minimum_scale_tiny cli.transform_h5_under_size_limit
  PROPERTIES DEPENDS cli.phantom_writes)
