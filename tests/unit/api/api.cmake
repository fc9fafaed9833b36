# SPDX-License-Identifier: Apache-2.0
# The C API's contract (every call's error state), the metrics through the C API, and the
# frame-size heap per pixel of the main methods (test_api_memory: docs/performance.md).
afn_add_gtest(test_api SOURCES unit/api/test_api.cpp LIBS afn)
afn_add_gtest(test_metrics_api SOURCES unit/api/test_metrics_api.cpp LIBS afn)
afn_add_gtest(test_api_missing_inputs SOURCES unit/api/test_api_missing_inputs.cpp LIBS afn)
afn_add_gtest(test_api_quality SOURCES unit/api/test_api_quality.cpp LIBS afn)
afn_add_gtest(test_api_memory SOURCES unit/api/test_api_memory.cpp
    ${PROJECT_SOURCE_DIR}/cli/heap_counter.cpp LIBS afn)
target_include_directories(test_api_memory PRIVATE ${PROJECT_SOURCE_DIR}/cli)
afn_add_gtest(test_api_passes SOURCES unit/api/test_api_passes.cpp LIBS afn)
afn_add_gtest(test_api_aux_stats SOURCES unit/api/test_api_aux_stats.cpp LIBS afn)
afn_add_gtest(test_api_highlights SOURCES unit/api/test_api_highlights.cpp LIBS afn)
