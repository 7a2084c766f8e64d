# Build MeshExtraction against an installed ITK that lacks ITK's module macros
# (ITKModuleExternal.cmake, ITKModuleMacros.cmake), e.g. Debian's libinsighttoolkit5-dev.
#
# It reads the same itk-module.cmake as ITK's module system and builds the same
# library, tests and examples with plain CMake, GoogleTest and CTest. The shims below
# stand in for the few ITK macros that src/, test/ and examples/ use, so those
# CMakeLists.txt files are shared by every build path.

include(CTest)
include(GenerateExportHeader)

# --- itk-module.cmake, parsed by a stand-in for itk_module() ----------------------
macro(itk_module _name)
  cmake_parse_arguments(_itk_module
    "EXCLUDE_FROM_DEFAULT;ENABLE_SHARED"
    "DESCRIPTION"
    "DEPENDS;PRIVATE_DEPENDS;COMPILE_DEPENDS;TEST_DEPENDS;FACTORY_NAMES"
    ${ARGN})
  set(${_name}_DEPENDS ${_itk_module_DEPENDS} ${_itk_module_PRIVATE_DEPENDS} ${_itk_module_COMPILE_DEPENDS})
  set(${_name}_TEST_DEPENDS ${_itk_module_TEST_DEPENDS})
endmacro()
include(${PROJECT_SOURCE_DIR}/itk-module.cmake)

set(_MeshExtraction_components ${MeshExtraction_DEPENDS})
if(BUILD_TESTING)
  list(APPEND _MeshExtraction_components ${MeshExtraction_TEST_DEPENDS})
endif()
list(REMOVE_DUPLICATES _MeshExtraction_components)
list(REMOVE_ITEM _MeshExtraction_components ITKGoogleTest) # header-only in an install tree

find_package(ITK REQUIRED COMPONENTS ${_MeshExtraction_components})
include(${ITK_USE_FILE})
message(STATUS "MeshExtraction: building against installed ITK ${ITK_VERSION} (${ITK_DIR}) without ITK's module macros")

find_program(MeshExtraction_CCACHE ccache)
if(MeshExtraction_CCACHE AND NOT CMAKE_CXX_COMPILER_LAUNCHER)
  set(CMAKE_CXX_COMPILER_LAUNCHER ${MeshExtraction_CCACHE})
endif()
if(NOT CMAKE_BUILD_TYPE AND NOT CMAKE_CONFIGURATION_TYPES)
  set(CMAKE_BUILD_TYPE Release CACHE STRING "Build type" FORCE)
endif()

set(MeshExtraction_SOURCE_DIR ${PROJECT_SOURCE_DIR})
set(MeshExtraction_BINARY_DIR ${PROJECT_BINARY_DIR})
set(ITK_TEST_OUTPUT_DIR ${PROJECT_BINARY_DIR}/Testing/Temporary)
file(MAKE_DIRECTORY ${ITK_TEST_OUTPUT_DIR})

# --- shims for the ITK macros used in src/, test/ and examples/ --------------------
function(itk_module_add_library _name)
  add_library(${_name} ${ARGN})
  target_include_directories(${_name} PUBLIC
    $<BUILD_INTERFACE:${MeshExtraction_SOURCE_DIR}/include>
    $<BUILD_INTERFACE:${MeshExtraction_BINARY_DIR}/include>)
  target_link_libraries(${_name} PUBLIC ${ITK_LIBRARIES})
  generate_export_header(${_name}
    EXPORT_FILE_NAME ${MeshExtraction_BINARY_DIR}/include/${_name}Export.h
    EXPORT_MACRO_NAME ${_name}_EXPORT
    NO_EXPORT_MACRO_NAME ${_name}_HIDDEN
    STATIC_DEFINE ITK_STATIC)
  if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    target_compile_options(${_name} PRIVATE -Wall -Wextra -Wshadow)
  endif()
endfunction()

macro(itk_module_test)
endmacro()

function(itk_add_test)
  add_test(${ARGN})
endfunction()

function(CreateGoogleTestDriver _kit _libs _tests)
  find_package(GTest REQUIRED)
  include(GoogleTest)
  set(_exe ${_kit}GTestDriver)
  add_executable(${_exe} ${_tests})
  target_link_libraries(${_exe} PRIVATE ${_libs} GTest::gtest GTest::gtest_main)
  if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    target_compile_options(${_exe} PRIVATE -Wall -Wextra -Wshadow)
  endif()
  gtest_discover_tests(${_exe}
    WORKING_DIRECTORY ${ITK_TEST_OUTPUT_DIR}
    DISCOVERY_TIMEOUT 120)
endfunction()
# (CMake command names are case-insensitive: creategoogletestdriver() calls this too.)

# --- the module ------------------------------------------------------------------
set(MeshExtraction-Test_LIBRARIES MeshExtraction ${ITK_LIBRARIES})
add_subdirectory(src)
if(BUILD_TESTING)
  add_subdirectory(test)
endif()
add_subdirectory(examples)
