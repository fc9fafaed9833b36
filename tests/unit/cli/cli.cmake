# SPDX-License-Identifier: Apache-2.0
# afntool's report helpers (cli/report_*.cpp), compiled into the test directly.
if(AFN_BUILD_CLI)
  afn_add_gtest(test_report SOURCES unit/cli/test_report.cpp ${PROJECT_SOURCE_DIR}/cli/report_data.cpp
    ${PROJECT_SOURCE_DIR}/cli/report_svg.cpp LIBS afn)
  target_include_directories(test_report PRIVATE ${PROJECT_SOURCE_DIR}/cli)
  afn_add_gtest(test_sample_count SOURCES unit/cli/test_sample_count.cpp LIBS afn)
  target_include_directories(test_sample_count PRIVATE ${PROJECT_SOURCE_DIR}/cli)
endif()
