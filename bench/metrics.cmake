# SPDX-License-Identifier: Apache-2.0
# Image-quality metrics through the C API (msec per frame at 720p and 1080p).
afn_add_benchmark(afnBenchmarkMetrics SOURCES bench_metrics.cpp LIBS afn)
