# SPDX-License-Identifier: Apache-2.0
# AFN engine: msec per 1280x720 frame for the three stages and the whole (random weights).
afn_add_benchmark(afnBenchmarkAfn SOURCES bench_afn.cpp LIBS afn_core)
