# SPDX-License-Identifier: Apache-2.0
# AFN engine: msec and GFLOP/s per 1280x720 frame for the three stages and the whole (random
# weights), beside dnnl_sgemm:  afnBenchmarkAfn --benchmark_filter=threads:1 (or threads:0)
afn_add_benchmark(afnBenchmarkAfn SOURCES bench_afn.cpp LIBS afn_core)
if(AFN_HAS_DNNL) # the dnnl_sgemm yardstick in the same program
  target_link_libraries(afnBenchmarkAfn PRIVATE afn_dnnl)
  target_compile_definitions(afnBenchmarkAfn PRIVATE AFN_HAS_DNNL)
  target_include_directories(afnBenchmarkAfn PRIVATE ${PROJECT_SOURCE_DIR}/cli)
endif()

# AFN's stages next to ta, svgf, bmfr and the whole afn filter, in one run (paper Table 10):
#   bench_afn_vs_methods --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
afn_add_benchmark(bench_afn_vs_methods SOURCES bench_afn.cpp bench_methods.cpp LIBS afn_core)
target_compile_definitions(bench_afn_vs_methods PRIVATE AFN_BENCH_NO_MAIN)
