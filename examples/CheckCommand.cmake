# Runs COMMAND (a ;-list) and fails unless its exit status is EXPECTED_STATUS and its
# combined output matches PATTERN. Used by the command-line tests.
execute_process(COMMAND ${COMMAND}
  RESULT_VARIABLE status
  OUTPUT_VARIABLE out
  ERROR_VARIABLE err)
set(all "${out}${err}")
if(NOT "${status}" STREQUAL "${EXPECTED_STATUS}")
  message(FATAL_ERROR "exit status ${status}, expected ${EXPECTED_STATUS}\n--- output ---\n${all}")
endif()
string(FIND "${all}" "${PATTERN}" found)
if(found EQUAL -1)
  message(FATAL_ERROR "output does not contain '${PATTERN}'\n--- output ---\n${all}")
endif()
message(STATUS "ok: status ${status}, found '${PATTERN}'")
