# SPDX-License-Identifier: Apache-2.0
# Stress suites on the public API: adversarial inputs for every method, fragile numerics, long
# runs, determinism (C API, afntool, plugin) and corrupt files.
add_library(afn_stress_util STATIC stress/stress_util.cpp stress/adversarial_cases.cpp)
target_include_directories(afn_stress_util PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/stress)
target_link_libraries(afn_stress_util PUBLIC afn)
target_compile_definitions(afn_stress_util PUBLIC AFN_TEST_DATA="${AFN_TEST_DATA}")

afn_add_gtest(test_stress_inputs
  SOURCES stress/test_adversarial_values.cpp stress/test_adversarial_frames.cpp
    stress/test_fragile_numerics.cpp
  LIBS afn_stress_util)
# Thousands of frames per method: the soak cases, run by the normal build's ctest only.
afn_add_gtest(test_stress_long SOURCES stress/test_long_runs.cpp LIBS afn_stress_util LABEL soak)
afn_add_gtest(test_stress_determinism SOURCES stress/test_determinism_api.cpp LIBS afn_stress_util)

# afntool on files: determinism, corrupt frames, half output.
if(AFN_BUILD_CLI)
  afn_add_afntool_test(test_stress_cli SOURCES stress/test_cli_files.cpp stress/exr_sequence.cpp
    LIBS afn_stress_util afn_io)
  target_include_directories(test_stress_cli PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/integration)
endif()

# The OpenFX plugin through the test host of tests/plugin.
if(AFN_BUILD_PLUGIN)
  afn_add_gtest(test_stress_plugin
    SOURCES stress/test_determinism_plugin.cpp plugin/synthetic_sequence.cpp
    LIBS afn_stress_util afn_ofx_test_host TBB::tbb)
  target_include_directories(test_stress_plugin PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/plugin)
  target_compile_definitions(test_stress_plugin PRIVATE AFN_OFX_BINARY="$<TARGET_FILE:afn_ofx>")
  add_dependencies(test_stress_plugin afn_ofx)
endif()
