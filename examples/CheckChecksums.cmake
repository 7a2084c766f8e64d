# Runs scripts/behaviour-checksums.sh with TOOL in WORK and fails unless its lines equal
# those of EXPECTED (comment lines starting with # are ignored). Used by the test
# cli.behaviour_checksums.
file(REMOVE_RECURSE ${WORK})
execute_process(COMMAND bash ${SCRIPT} ${TOOL} ${WORK}
  RESULT_VARIABLE status
  OUTPUT_VARIABLE actual
  ERROR_VARIABLE err)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "behaviour-checksums.sh failed (${status}):\n${err}")
endif()
file(STRINGS ${EXPECTED} expected_lines REGEX "^[^#]")
string(REGEX REPLACE "\n$" "" actual "${actual}")
string(REPLACE "\n" ";" actual_lines "${actual}")
if(NOT "${actual_lines}" STREQUAL "${expected_lines}")
  set(diff "")
  foreach(line IN LISTS actual_lines)
    list(FIND expected_lines "${line}" found)
    if(found EQUAL -1)
      string(APPEND diff "  changed: ${line}\n")
    endif()
  endforeach()
  message(FATAL_ERROR "The meshes differ from the recorded ones (${EXPECTED}):\n${diff}"
                      "If the change is meant to change them, regenerate the file and say why.")
endif()
message(STATUS "ok: every mesh is byte-identical to the recorded one")
