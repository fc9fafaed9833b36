# SPDX-License-Identifier: Apache-2.0
# End-to-end tests of afntool: run the real binary, check exit codes, messages and written files.
afn_add_gtest(test_afntool SOURCES integration/test_afntool.cpp integration/cli_runner.cpp LIBS afn afn_io)
target_compile_definitions(test_afntool PRIVATE AFNTOOL_PATH="$<TARGET_FILE:afntool>")
add_dependencies(test_afntool afntool)

# afntool --compare / --benchmark end to end.
afn_add_gtest(test_afntool_compare SOURCES integration/test_afntool_compare.cpp
  integration/cli_runner.cpp LIBS afn)
target_compile_definitions(test_afntool_compare PRIVATE AFNTOOL_PATH="$<TARGET_FILE:afntool>")
add_dependencies(test_afntool_compare afntool)
if(AFN_HAS_DNNL) # the engine report then includes the dnnl_sgemm yardstick
  target_compile_definitions(test_afntool_compare PRIVATE AFN_HAS_DNNL)
endif()
