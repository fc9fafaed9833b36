# SPDX-License-Identifier: Apache-2.0
# afn_target_defaults(target): warnings and hidden visibility for the project's own targets.
function(afn_target_defaults target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wno-unused-parameter)
  if(AFN_WARN_AS_ERRORS)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
  set_target_properties(${target} PROPERTIES CXX_VISIBILITY_PRESET hidden VISIBILITY_INLINES_HIDDEN ON)
endfunction()

# afn_add_shared_library(NAME SOURCES ... DEPS ... [DEFINITIONS ...]): a shared library that
# exports only what its public header marks (the build defines AFN_BUILDING_<NAME without afn_>),
# built from an object library NAME_objects that the unit tests of internals can link.
function(afn_add_shared_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS;DEFINITIONS" ${ARGN})
  string(REGEX REPLACE "^afn_" "" short ${name})
  string(TOUPPER ${short} short)
  add_library(${name}_objects OBJECT ${ARG_SOURCES})
  target_include_directories(${name}_objects PUBLIC
    $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include> $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_link_libraries(${name}_objects PUBLIC ${ARG_DEPS})
  target_compile_definitions(${name}_objects PRIVATE AFN_BUILDING_${short} ${ARG_DEFINITIONS})
  set_target_properties(${name}_objects PROPERTIES POSITION_INDEPENDENT_CODE ON)
  afn_target_defaults(${name}_objects)

  add_library(${name} SHARED $<TARGET_OBJECTS:${name}_objects>)
  target_include_directories(${name} PUBLIC
    $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include> $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_link_libraries(${name} PRIVATE ${ARG_DEPS})
  set_target_properties(${name} PROPERTIES VERSION ${PROJECT_VERSION} SOVERSION ${PROJECT_VERSION_MAJOR})
  add_library(afn::${name} ALIAS ${name})
endfunction()
