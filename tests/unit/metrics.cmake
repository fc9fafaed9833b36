# SPDX-License-Identifier: Apache-2.0
# Image-quality metrics: the core (internals, vs a naive SSIM and scikit-image) and the C API.
afn_add_gtest(test_metrics SOURCES unit/test_metrics.cpp LIBS afn_core)
afn_add_gtest(test_metrics_api SOURCES unit/test_metrics_api.cpp LIBS afn)
# afntool's report helpers (cli/report_*.cpp), compiled into the test directly.
if(AFN_BUILD_CLI)
  afn_add_gtest(test_report SOURCES unit/test_report.cpp ${PROJECT_SOURCE_DIR}/cli/report_data.cpp
    ${PROJECT_SOURCE_DIR}/cli/report_svg.cpp LIBS afn)
  target_include_directories(test_report PRIVATE ${PROJECT_SOURCE_DIR}/cli)
endif()
# afntool --compare / --benchmark end to end (uses the CLI test runner of tests/integration).
if(AFN_BUILD_CLI)
  afn_add_gtest(test_afntool_compare SOURCES integration/test_afntool_compare.cpp
    integration/cli_runner.cpp LIBS afn)
  target_compile_definitions(test_afntool_compare PRIVATE AFNTOOL_PATH="$<TARGET_FILE:afntool>")
  add_dependencies(test_afntool_compare afntool)
endif()
