# A check of wrapping/*.wrap for builds without ITK's Python wrapping (Debian's ITK has
# none, so CI cannot build the real wrappers).
#
# It reads every .wrap file with stand-ins for the ITK wrapping macros they use
# (itk_wrap_class, itk_wrap_template, itk_wrap_simple_class, itk_wrap_image_filter,
# itk_wrap_include, UNIQUE) under ITK's default wrapping options plus unsigned short
# (pixel types UC, US, SS, F; double not wrapped; dimensions 2 and 3), or with
# -DPROFILE=wheel under the settings of ITK's Python wheels (UC, US, SS, F, D;
# dimensions 2, 3 and 4), and
#  - checks that nothing is wrapped that ITK's own wrapping has already (Python would
#    warn "already defined"), the superclasses of POINTER_WITH_SUPERCLASS classes too;
#  - checks that every public class of include/ (each class with
#    itkOverrideGetNameOfClassMacro, and each *Enums class) is wrapped;
#  - checks that no class gets the same mangled name twice, that no wrapped class is
#    left without a template, and that every included header exists;
#  - writes, for each .wrap file, a C++ file that explicitly instantiates every wrapped
#    template (all its member functions, as SWIG's wrappers would use them) and the
#    smart pointer of each POINTER class, for the build to compile.
#
# Usage:
#  - from a CMakeLists.txt: include() it, then
#      meshextraction_check_wrapping(<wrapping dir> <include dir> <output dir> <problems var> <sources var>)
#  - as a test: cmake -DWRAPPING_DIR=... -DINCLUDE_DIR=... -DOUTPUT_DIR=... -P MeshExtractionWrappingCheck.cmake
#    fails with the list of problems.


cmake_policy(SET CMP0057 NEW) # if(... IN_LIST ...), also in script mode

# --- ITK's type names (ITK's WrapITKTypes.cmake) and wrapping options ----------------
# PROFILE "default": ITK's default options plus unsigned short (UC, US, SS, F;
# dimensions 2 and 3); "wheel": the settings ITK's Python wheels are built with (UC, US,
# SS, F, D; dimensions 2, 3 and 4).
if(NOT DEFINED PROFILE)
  set(PROFILE default)
endif()
set(ITKT_UC "unsigned char")
set(ITKT_US "unsigned short")
set(ITKT_SS "signed short")
set(ITKT_F "float")
set(ITKT_D "double")
foreach(_meshextraction_t UC US SS F D)
  set(ITKM_${_meshextraction_t} "${_meshextraction_t}")
  foreach(_meshextraction_d 2 3 4)
    set(ITKM_I${_meshextraction_t}${_meshextraction_d} "I${_meshextraction_t}${_meshextraction_d}")
    set(ITKT_I${_meshextraction_t}${_meshextraction_d} "itk::Image< ${ITKT_${_meshextraction_t}},${_meshextraction_d} >")
  endforeach()
endforeach()
foreach(_meshextraction_d 2 3 4)
  set(ITKM_PD${_meshextraction_d} "PD${_meshextraction_d}")
  set(ITKT_PD${_meshextraction_d} "itk::Point< double,${_meshextraction_d} >")
endforeach()
set(WRAP_ITK_INT UC US SS)
if(PROFILE STREQUAL "wheel")
  set(ITK_WRAP_IMAGE_DIMS 2 3 4)
  set(WRAP_ITK_REAL F D)
  set(ITK_WRAP_double ON)
elseif(PROFILE STREQUAL "default")
  set(ITK_WRAP_IMAGE_DIMS 2 3)
  set(WRAP_ITK_REAL F)
  set(ITK_WRAP_double OFF)
else()
  message(FATAL_ERROR "MeshExtractionWrappingCheck: PROFILE must be default or wheel, got '${PROFILE}'")
endif()
set(ITK_WRAP_DIMS ${ITK_WRAP_IMAGE_DIMS})
set(WRAP_ITK_SCALAR ${WRAP_ITK_INT} ${WRAP_ITK_REAL})

# --- what ITK's own wrapping already has, for the classes the module's types meet -----
# (ITK's Modules/Core/{Common,Mesh,QuadEdgeMesh}/wrapping): a .wrap file that wraps one
# of these again, or a class wrapped with its superclass that is one of these, makes
# Python warn "already defined" on import. Entries are "class|template arguments"
# without spaces.
function(_meshextraction_itk_wrapped _class _arguments)
  string(REPLACE " " "" _arguments "${_arguments}")
  set_property(GLOBAL APPEND PROPERTY MESHEXTRACTION_ITK_WRAPPED "${_class}|${_arguments}")
endfunction()
set_property(GLOBAL PROPERTY MESHEXTRACTION_ITK_WRAPPED "")
foreach(_meshextraction_d ${ITK_WRAP_IMAGE_DIMS})
  foreach(_meshextraction_t ${WRAP_ITK_REAL})
    set(_t "${ITKT_${_meshextraction_t}}")
    set(_d ${_meshextraction_d})
    _meshextraction_itk_wrapped("itk::SpatialFunction" "${_t},${_d},${ITKT_PD${_d}}")
    _meshextraction_itk_wrapped("itk::ImageToMeshFilter"
      "${ITKT_I${_meshextraction_t}${_d}}, itk::Mesh< double,${_d},itk::DefaultStaticMeshTraits< double,${_d},${_d},double > >")
    _meshextraction_itk_wrapped("itk::MeshSource" "itk::Mesh< ${_t},${_d},itk::DefaultStaticMeshTraits< ${_t},${_d},${_d},${_t} > >")
    _meshextraction_itk_wrapped("itk::MeshSource" "itk::Mesh< ${_t},${_d},itk::DefaultDynamicMeshTraits< ${_t},${_d},${_d},${_t} > >")
  endforeach()
  foreach(_meshextraction_t ${WRAP_ITK_SCALAR} D)
    _meshextraction_itk_wrapped("itk::Mesh" "${ITKT_${_meshextraction_t}},${_meshextraction_d}")
  endforeach()
  _meshextraction_itk_wrapped("itk::QuadEdgeMeshToQuadEdgeMeshFilter"
    "itk::QuadEdgeMesh< double,${_meshextraction_d} >, itk::QuadEdgeMesh< double,${_meshextraction_d} >")
endforeach()
# The superclass ITK's wrapping makes of a class wrapped POINTER_WITH_SUPERCLASS: its
# name and how many of the class's template arguments it takes.
set(_meshextraction_superclass_itk::SurfaceNetsImageToMeshFilter "itk::ImageToMeshFilter;2")
set(_meshextraction_superclass_itk::MultiLabelSurfaceNetsImageToMeshFilter "itk::ImageToMeshFilter;2")

# The first `count` top-level template arguments of `arguments` (commas inside < > kept).
function(_meshextraction_first_arguments _arguments _count _var)
  set(_depth 0)
  set(_taken 0)
  set(_result "")
  string(LENGTH "${_arguments}" _length)
  math(EXPR _last "${_length} - 1")
  foreach(_i RANGE 0 ${_last})
    string(SUBSTRING "${_arguments}" ${_i} 1 _c)
    if(_c STREQUAL "<")
      math(EXPR _depth "${_depth} + 1")
    elseif(_c STREQUAL ">")
      math(EXPR _depth "${_depth} - 1")
    elseif(_c STREQUAL "," AND _depth EQUAL 0)
      math(EXPR _taken "${_taken} + 1")
      if(_taken EQUAL _count)
        break()
      endif()
    endif()
    string(APPEND _result "${_c}")
  endforeach()
  set(${_var} "${_result}" PARENT_SCOPE)
endfunction()

# A problem if ITK's own wrapping has `class<arguments>` already.
function(_meshextraction_check_not_itk_wrapped _class _arguments _what)
  string(REPLACE " " "" _key "${_class}|${_arguments}")
  get_property(_itk GLOBAL PROPERTY MESHEXTRACTION_ITK_WRAPPED)
  if("${_key}" IN_LIST _itk)
    _meshextraction_wrap_problem(
      "${_meshextraction_wrap_file}: ${_what} ${_class}< ${_arguments} >, which ITK's own wrapping has (${PROFILE} settings)")
  endif()
endfunction()

# --- stand-ins for the wrapping macros -----------------------------------------------
# State lives in global properties: the .wrap files call these from their own scope.
function(_meshextraction_wrap_problem _text)
  set_property(GLOBAL APPEND PROPERTY MESHEXTRACTION_WRAP_PROBLEMS "${_text}")
endfunction()

function(_meshextraction_wrap_auto_include _class)
  if(WRAPPER_AUTO_INCLUDE_HEADERS) # the calling .wrap file's setting
    string(REGEX REPLACE "^itk::" "itk" _header "${_class}")
    itk_wrap_include("${_header}.h")
  endif()
endfunction()

function(itk_wrap_include _header)
  set_property(GLOBAL APPEND PROPERTY MESHEXTRACTION_WRAP_INCLUDES "${_header}")
endfunction()

function(itk_wrap_class _class)
  get_property(_open GLOBAL PROPERTY MESHEXTRACTION_WRAP_CLASS)
  if(_open)
    _meshextraction_wrap_problem("${_meshextraction_wrap_file}: itk_wrap_class(${_class}) inside ${_open}")
  endif()
  set_property(GLOBAL PROPERTY MESHEXTRACTION_WRAP_CLASS "${_class}")
  set_property(GLOBAL PROPERTY MESHEXTRACTION_WRAP_POINTER "${ARGN}")
  set_property(GLOBAL PROPERTY MESHEXTRACTION_WRAP_MANGLED "")
  set_property(GLOBAL APPEND PROPERTY MESHEXTRACTION_WRAP_CLASSES "${_class}")
  _meshextraction_wrap_auto_include("${_class}")
endfunction()

function(itk_wrap_template _mangled _arguments)
  get_property(_class GLOBAL PROPERTY MESHEXTRACTION_WRAP_CLASS)
  if(NOT _class)
    _meshextraction_wrap_problem("${_meshextraction_wrap_file}: itk_wrap_template(${_mangled}) outside a class")
    return()
  endif()
  get_property(_mangledNames GLOBAL PROPERTY MESHEXTRACTION_WRAP_MANGLED)
  if("${_mangled}" IN_LIST _mangledNames)
    _meshextraction_wrap_problem("${_meshextraction_wrap_file}: ${_class} gets the mangled name ${_mangled} twice")
  endif()
  set_property(GLOBAL APPEND PROPERTY MESHEXTRACTION_WRAP_MANGLED "${_mangled}")
  _meshextraction_check_not_itk_wrapped("${_class}" "${_arguments}" "wraps")
  get_property(_pointerKind GLOBAL PROPERTY MESHEXTRACTION_WRAP_POINTER)
  if(_pointerKind MATCHES "WITH_SUPERCLASS" AND DEFINED _meshextraction_superclass_${_class})
    list(GET _meshextraction_superclass_${_class} 0 _superclass)
    list(GET _meshextraction_superclass_${_class} 1 _count)
    _meshextraction_first_arguments("${_arguments}" ${_count} _superArguments)
    _meshextraction_check_not_itk_wrapped("${_superclass}" "${_superArguments}" "wraps, as the superclass of ${_class},")
  endif()
  # One line per instantiation (the arguments contain commas, not semicolons).
  set_property(GLOBAL APPEND_STRING PROPERTY MESHEXTRACTION_WRAP_CODE
    "template class ${_class}< ${_arguments} >; // ${_mangled}\n")
  get_property(_pointer GLOBAL PROPERTY MESHEXTRACTION_WRAP_POINTER)
  if(_pointer MATCHES "POINTER")
    set_property(GLOBAL APPEND_STRING PROPERTY MESHEXTRACTION_WRAP_CODE
      "template class itk::SmartPointer< ${_class}< ${_arguments} > >;\n")
  endif()
endfunction()

function(itk_end_wrap_class)
  get_property(_class GLOBAL PROPERTY MESHEXTRACTION_WRAP_CLASS)
  get_property(_mangledNames GLOBAL PROPERTY MESHEXTRACTION_WRAP_MANGLED)
  if(NOT _mangledNames)
    _meshextraction_wrap_problem("${_meshextraction_wrap_file}: ${_class} is wrapped without a template")
  endif()
  set_property(GLOBAL PROPERTY MESHEXTRACTION_WRAP_CLASS "")
endfunction()

function(itk_wrap_simple_class _class)
  set_property(GLOBAL APPEND PROPERTY MESHEXTRACTION_WRAP_CLASSES "${_class}")
  _meshextraction_wrap_auto_include("${_class}")
  if("${ARGN}" MATCHES "POINTER")
    set_property(GLOBAL APPEND_STRING PROPERTY MESHEXTRACTION_WRAP_CODE "template class itk::SmartPointer< ${_class} >;\n")
  else()
    set_property(GLOBAL APPEND_STRING PROPERTY MESHEXTRACTION_WRAP_CODE "static_assert(sizeof(${_class}) > 0, \"\");\n")
  endif()
endfunction()

# itk_wrap_image_filter(types count [dimensions]): `count` images of the same pixel
# type and dimension, for each wrapped dimension (of `dimensions`, when given).
function(itk_wrap_image_filter _types _count)
  set(_dimensions ${ITK_WRAP_IMAGE_DIMS})
  if(ARGC GREATER 2)
    set(_dimensions)
    foreach(_d ${ARGN})
      if("${_d}" IN_LIST ITK_WRAP_IMAGE_DIMS)
        list(APPEND _dimensions ${_d})
      endif()
    endforeach()
  endif()
  foreach(_d ${_dimensions})
    foreach(_t ${_types})
      set(_mangled "")
      set(_arguments "")
      foreach(_i RANGE 1 ${_count})
        string(APPEND _mangled "${ITKM_I${_t}${_d}}")
        if(_arguments)
          string(APPEND _arguments ", ")
        endif()
        string(APPEND _arguments "${ITKT_I${_t}${_d}}")
      endforeach()
      itk_wrap_template("${_mangled}" "${_arguments}")
    endforeach()
  endforeach()
endfunction()

macro(UNIQUE _var _list)
  set(${_var} ${_list})
  list(REMOVE_DUPLICATES ${_var})
endmacro()

# --- the check -----------------------------------------------------------------------
# Reads every .wrap file of `wrapping_dir`; sets `problems_var` to the list of problems
# and `sources_var` to the C++ files written to `output_dir` (one per .wrap file).
function(meshextraction_check_wrapping wrapping_dir include_dir output_dir problems_var sources_var)
  set_property(GLOBAL PROPERTY MESHEXTRACTION_WRAP_PROBLEMS "")
  set_property(GLOBAL PROPERTY MESHEXTRACTION_WRAP_CLASSES "")
  file(GLOB _wraps "${wrapping_dir}/*.wrap")
  list(SORT _wraps)
  if(NOT _wraps)
    _meshextraction_wrap_problem("no .wrap files in ${wrapping_dir}")
  endif()
  set(_sources)
  foreach(_meshextraction_wrap_file ${_wraps})
    set_property(GLOBAL PROPERTY MESHEXTRACTION_WRAP_INCLUDES "")
    set_property(GLOBAL PROPERTY MESHEXTRACTION_WRAP_CODE "")
    set_property(GLOBAL PROPERTY MESHEXTRACTION_WRAP_CLASS "")
    _meshextraction_read_wrap_file("${_meshextraction_wrap_file}")
    get_property(_open GLOBAL PROPERTY MESHEXTRACTION_WRAP_CLASS)
    if(_open)
      _meshextraction_wrap_problem("${_meshextraction_wrap_file}: ${_open} has no itk_end_wrap_class()")
    endif()
    get_property(_includes GLOBAL PROPERTY MESHEXTRACTION_WRAP_INCLUDES)
    get_property(_code GLOBAL PROPERTY MESHEXTRACTION_WRAP_CODE)
    get_filename_component(_name "${_meshextraction_wrap_file}" NAME_WE)
    set(_text "// Generated by CMake/MeshExtractionWrappingCheck.cmake from wrapping/${_name}.wrap:\n")
    string(APPEND _text "// the C++ instantiations that ITK's Python wrapping of this file would compile.\n")
    list(REMOVE_DUPLICATES _includes)
    foreach(_header ${_includes})
      # The module's own headers must exist; ITK's are found by the compiler.
      if(_header MATCHES "^itk(MeshExtraction|SurfaceNets|[A-Za-z]*ImplicitSurface|TriangleMesh|MeshSurface|ScaleSpace|EdgeSwap|LaplacianSmoothingQuad|TaubinSmoothingQuad|ThreeLandmark|Symmetric)"
         AND NOT EXISTS "${include_dir}/${_header}")
        _meshextraction_wrap_problem("${_meshextraction_wrap_file}: includes ${_header}, which is not in include/")
      endif()
      string(APPEND _text "#include \"${_header}\"\n")
    endforeach()
    string(APPEND _text "\n${_code}")
    set(_source "${output_dir}/${_name}WrappingCheck.cxx")
    # Written only when it changes, so that a configure does not rebuild it.
    if(EXISTS "${_source}")
      file(READ "${_source}" _old)
    else()
      set(_old "")
    endif()
    if(NOT _old STREQUAL _text)
      file(WRITE "${_source}" "${_text}")
    endif()
    list(APPEND _sources "${_source}")
  endforeach()

  # Every public class of include/ is wrapped.
  get_property(_wrapped GLOBAL PROPERTY MESHEXTRACTION_WRAP_CLASSES)
  file(GLOB _headers "${include_dir}/itk*.h")
  list(SORT _headers)
  foreach(_header ${_headers})
    file(STRINGS "${_header}" _lines REGEX "^ *(itkOverrideGetNameOfClassMacro\\([A-Za-z0-9_]+\\);|class [A-Za-z0-9_]+Enums$)")
    foreach(_line ${_lines})
      string(REGEX REPLACE "^ *(itkOverrideGetNameOfClassMacro\\(|class )([A-Za-z0-9_]+).*$" "\\2" _class "${_line}")
      if(NOT "itk::${_class}" IN_LIST _wrapped)
        get_filename_component(_headerName "${_header}" NAME)
        _meshextraction_wrap_problem("itk::${_class} (include/${_headerName}) is not wrapped in any .wrap file")
      endif()
    endforeach()
  endforeach()

  get_property(_problems GLOBAL PROPERTY MESHEXTRACTION_WRAP_PROBLEMS)
  set(${problems_var} "${_problems}" PARENT_SCOPE)
  set(${sources_var} "${_sources}" PARENT_SCOPE)
endfunction()

# A scope of its own for each file (as ITK's wrapping gives each submodule), so that
# e.g. WRAPPER_AUTO_INCLUDE_HEADERS OFF in one file does not reach the next.
function(_meshextraction_read_wrap_file _meshextraction_wrap_file)
  set(WRAPPER_AUTO_INCLUDE_HEADERS ON)
  include("${_meshextraction_wrap_file}")
endfunction()

if(CMAKE_SCRIPT_MODE_FILE AND CMAKE_SCRIPT_MODE_FILE STREQUAL CMAKE_CURRENT_LIST_FILE)
  foreach(_required WRAPPING_DIR INCLUDE_DIR OUTPUT_DIR)
    if(NOT DEFINED ${_required})
      message(FATAL_ERROR "MeshExtractionWrappingCheck: -D${_required}=... is required")
    endif()
  endforeach()
  file(MAKE_DIRECTORY "${OUTPUT_DIR}")
  meshextraction_check_wrapping("${WRAPPING_DIR}" "${INCLUDE_DIR}" "${OUTPUT_DIR}" _problems _sources)
  list(LENGTH _sources _count)
  if(_problems)
    string(REPLACE ";" "\n  " _list "${_problems}")
    message(FATAL_ERROR "The wrapping in ${WRAPPING_DIR} has problems:\n  ${_list}")
  endif()
  message(STATUS "The wrapping in ${WRAPPING_DIR}: ${_count} .wrap files, every public class wrapped, no problem found")
endif()
