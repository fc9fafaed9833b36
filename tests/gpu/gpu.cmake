# SPDX-License-Identifier: Apache-2.0
# The CUDA filter against the CPU filter (ctest label "gpu"; every test skips, saying why, where no
# usable GPU is present). Self-contained for scripts/make-gpu-bundle.sh: the test archives are
# embedded, the sequences generated, the C API compiled in, and nothing but afn_core, GoogleTest
# and oneTBB linked.
add_executable(test_afn_cuda gpu/test_afn_cuda.cpp
  ${PROJECT_SOURCE_DIR}/lib/api/api.cpp ${PROJECT_SOURCE_DIR}/lib/api/api_metrics.cpp)
target_compile_definitions(test_afn_cuda PRIVATE AFN_BUILDING_LIBRARY)
target_link_libraries(test_afn_cuda PRIVATE afn_core GTest::gtest GTest::gtest_main)
target_include_directories(test_afn_cuda PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/unit/core)
include(AfnEmbed)
afn_embed_file(test_afn_cuda ${AFN_TEST_DATA}/afn_parity/weights_full.afnw afnTestWeightsFull)
afn_embed_file(test_afn_cuda ${AFN_TEST_DATA}/afn_parity/weights_fusion.afnw afnTestWeightsFusion)
afn_embed_file(test_afn_cuda ${AFN_TEST_DATA}/afn_parity/weights_trust.afnw afnTestWeightsTrust)
afn_embed_file(test_afn_cuda ${AFN_TEST_DATA}/afn_parity/weights_quarter.afnw afnTestWeightsQuarter)
afn_embed_file(test_afn_cuda ${AFN_TEST_DATA}/afn_parity/weights_large.afnw afnTestWeightsLarge)
gtest_discover_tests(test_afn_cuda DISCOVERY_TIMEOUT 60 PROPERTIES LABELS gpu TIMEOUT 600)
