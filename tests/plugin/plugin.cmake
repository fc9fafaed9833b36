# SPDX-License-Identifier: Apache-2.0
# The OpenFX plugin: an in-process test host (dlopen) compared with the C API and with afntool,
# and the check that the binary exports only the two OFX entry points.
find_package(Threads REQUIRED)
add_library(afn_ofx_test_host STATIC
  plugin/ofx_test_host.cpp plugin/host_property_suite.cpp plugin/host_effect_suite.cpp
  plugin/host_other_suites.cpp)
target_include_directories(afn_ofx_test_host PUBLIC ${PROJECT_SOURCE_DIR}/plugin)
target_link_libraries(afn_ofx_test_host PUBLIC ${CMAKE_DL_LIBS} Threads::Threads)

afn_add_gtest(test_plugin_host
  SOURCES plugin/test_plugin_host.cpp plugin/synthetic_sequence.cpp
  LIBS afn afn_ofx_test_host)
target_compile_definitions(test_plugin_host PRIVATE AFN_OFX_BINARY="$<TARGET_FILE:afn_ofx>")
add_dependencies(test_plugin_host afn_ofx)

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
