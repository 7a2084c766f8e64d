# Prints the ITK modules MeshExtraction needs, one list per line, for scripts that
# configure an ITK tree (scripts/build-itk.sh): `cmake -P` this file.
#   DEPENDS ...    the module's library (and its Python wrapping)
#   TEST ...       its tests
#   EXAMPLES ...   the command-line tool
# The lists come from itk-module.cmake and examples/ITKComponents.cmake, the one place
# each is declared.
get_filename_component(_source_dir "${CMAKE_CURRENT_LIST_DIR}/.." ABSOLUTE)
macro(itk_module _name)
  cmake_parse_arguments(_itk_module "EXCLUDE_FROM_DEFAULT;ENABLE_SHARED" "DESCRIPTION"
    "DEPENDS;PRIVATE_DEPENDS;COMPILE_DEPENDS;TEST_DEPENDS;FACTORY_NAMES" ${ARGN})
endmacro()
include(${_source_dir}/itk-module.cmake)
include(${_source_dir}/examples/ITKComponents.cmake)
string(REPLACE ";" " " _depends "${_itk_module_DEPENDS};${_itk_module_PRIVATE_DEPENDS};${_itk_module_COMPILE_DEPENDS}")
string(REPLACE ";" " " _test "${_itk_module_TEST_DEPENDS}")
string(REPLACE ";" " " _examples "${MeshExtractionExamples_ITK_COMPONENTS}")
execute_process(COMMAND ${CMAKE_COMMAND} -E echo "DEPENDS ${_depends}")
execute_process(COMMAND ${CMAKE_COMMAND} -E echo "TEST ${_test}")
execute_process(COMMAND ${CMAKE_COMMAND} -E echo "EXAMPLES ${_examples}")
