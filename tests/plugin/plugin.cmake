# SPDX-License-Identifier: Apache-2.0
# The OpenFX plugin: an in-process test host (dlopen) compared with the C API, and the check that
# the binary exports only the two OFX entry points.
find_package(Threads REQUIRED)
afn_add_gtest(test_plugin_host
  SOURCES plugin/test_plugin_host.cpp plugin/ofx_test_host.cpp plugin/host_property_suite.cpp
          plugin/host_effect_suite.cpp plugin/host_other_suites.cpp plugin/synthetic_sequence.cpp
  LIBS afn ${CMAKE_DL_LIBS} Threads::Threads)
target_include_directories(test_plugin_host PRIVATE ${PROJECT_SOURCE_DIR}/plugin)
target_compile_definitions(test_plugin_host PRIVATE AFN_OFX_BINARY="$<TARGET_FILE:afn_ofx>")
add_dependencies(test_plugin_host afn_ofx)

add_test(NAME plugin_exports
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/plugin/check_exports.sh $<TARGET_FILE:afn_ofx>)
