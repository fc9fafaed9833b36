# SPDX-License-Identifier: Apache-2.0
# The OpenFX plugin: an in-process test host (dlopen) compared with the C API and with afntool,
# and the check that the binary exports only the two OFX entry points.
find_package(Threads REQUIRED)
add_library(afn_ofx_test_host STATIC
  plugin/ofx_test_host.cpp plugin/host_property_suite.cpp plugin/host_effect_suite.cpp
  plugin/host_other_suites.cpp)
target_include_directories(afn_ofx_test_host PUBLIC ${PROJECT_SOURCE_DIR}/plugin)
target_link_libraries(afn_ofx_test_host PUBLIC ${CMAKE_DL_LIBS} Threads::Threads)

# Tests that drive the plugin over the synthetic sequence, one executable per subject.
foreach(name test_plugin_host test_plugin_history test_plugin_presentation test_plugin_quality
    test_plugin_skip test_plugin_input_sets test_plugin_passes)
  afn_add_gtest(${name}
    SOURCES plugin/${name}.cpp plugin/plugin_session.cpp plugin/synthetic_sequence.cpp
    LIBS afn afn_ofx_test_host)
  target_compile_definitions(${name} PRIVATE AFN_OFX_BINARY="$<TARGET_FILE:afn_ofx>")
  add_dependencies(${name} afn_ofx)
endforeach()

# The bundle around the binary: Info.plist and icon, in the build tree and installed.
afn_add_gtest(test_plugin_bundle SOURCES plugin/test_plugin_bundle.cpp LIBS afn_ofx_test_host)
target_compile_definitions(test_plugin_bundle PRIVATE AFN_OFX_BINARY="$<TARGET_FILE:afn_ofx>")
add_dependencies(test_plugin_bundle afn_ofx)
find_program(AFN_PYTHON3 NAMES python3)
if(AFN_PYTHON3)
  add_test(NAME plugin_bundle
    COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/plugin/check_bundle.sh ${CMAKE_COMMAND}
      ${PROJECT_BINARY_DIR} $<TARGET_FILE_DIR:afn_ofx>/../.. ${AFN_PYTHON3})
endif()

afn_add_gtest(test_plugin_param_names SOURCES plugin/test_plugin_param_names.cpp
  LIBS afn_ofx_test_host)
target_compile_definitions(test_plugin_param_names PRIVATE AFN_OFX_BINARY="$<TARGET_FILE:afn_ofx>"
  AFN_OFX_PARAMS_GOLDEN="${CMAKE_CURRENT_SOURCE_DIR}/plugin/ofx_params.golden")
add_dependencies(test_plugin_param_names afn_ofx)

# The example sequence through the plugin against afntool (reads EXRs with afn_io; the plugin
# itself never links it).
if(AFN_BUILD_CLI)
  afn_add_gtest(test_plugin_example SOURCES plugin/test_plugin_example.cpp
    LIBS afn afn_io afn_ofx_test_host)
  target_compile_definitions(test_plugin_example PRIVATE
    AFN_OFX_BINARY="$<TARGET_FILE:afn_ofx>" AFNTOOL_PATH="$<TARGET_FILE:afntool>")
  add_dependencies(test_plugin_example afn_ofx afntool)
endif()

add_test(NAME plugin_exports
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/plugin/check_exports.sh $<TARGET_FILE:afn_ofx>)
