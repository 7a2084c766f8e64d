# meshextraction shape-model build, sample and project on four ellipsoid phantoms (the
# ellipsoid phantom on grids of different spacings): the model's samples are closed,
# valid surfaces; a training mesh projects with a small residual; bad coefficients are
# refused; --report writes its page and renderings. Arguments: -DMESHEXTRACTION=path -DWORK=dir.
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})

function(run expected pattern)
  execute_process(COMMAND ${MESHEXTRACTION} ${ARGN} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT "${status}" STREQUAL "${expected}")
    message(FATAL_ERROR "meshextraction ${ARGN}: exit status ${status}, expected ${expected}\n${out}${err}")
  endif()
  string(FIND "${out}${err}" "${pattern}" found)
  if(found EQUAL -1)
    message(FATAL_ERROR "meshextraction ${ARGN}: output lacks '${pattern}'\n${out}${err}")
  endif()
  set(output "${out}${err}" PARENT_SCOPE)
endfunction()

set(meshes)
foreach(spacing 1x1x1 1.25x1x1 1x1x1.3 1.15x1.1x1)
  run(0 "wrote" extract --phantom ellipsoid ${WORK}/e-${spacing}.ply --size 24 --spacing ${spacing})
  list(APPEND meshes ${WORK}/e-${spacing}.ply)
endforeach()
run(0 "model written" shape-model build ${meshes} --output ${WORK}/model.h5 --json ${WORK}/model.json
  --report ${WORK}/report)
foreach(file index.html compactness.svg mean.png mode1-minus2.png mode1-plus2.png)
  if(NOT EXISTS ${WORK}/report/${file})
    message(FATAL_ERROR "build --report wrote no ${file}")
  endif()
endforeach()
run(0 "(the mean)" shape-model sample ${WORK}/model.h5 --output ${WORK}/mean.vtk)
run(0 "valid closed surface: yes" quality ${WORK}/mean.vtk)
run(0 "at (standard deviations): 2 -1" shape-model sample ${WORK}/model.h5 --output ${WORK}/s.vtk --coefficients=2,-1)
run(0 "valid closed surface: yes" quality ${WORK}/s.vtk)
run(0 "written" shape-model sample ${WORK}/model.h5 --output ${WORK}/r.ply --random-seed 3)
run(1 "4 coefficients for a model of" shape-model sample ${WORK}/model.h5 --output ${WORK}/x.ply --coefficients 1,1,1,1)
run(2 "not both" shape-model sample ${WORK}/model.h5 --output ${WORK}/x.ply --coefficients 1 --random-seed 3)
run(0 "coefficients (standard deviations)" shape-model project ${WORK}/model.h5 ${WORK}/e-1.25x1x1.ply
  --json ${WORK}/projection.json)
# A training mesh: what the modes leave is a small fraction of a voxel (1 mm).
file(READ ${WORK}/projection.json projection)
string(JSON residual GET "${projection}" residual)
if(residual GREATER 0.2)
  message(FATAL_ERROR "a training mesh projects with a residual of ${residual} mm")
endif()
message(STATUS "ok: sample and project; a training mesh's residual ${residual} mm")
