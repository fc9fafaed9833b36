# SPDX-License-Identifier: Apache-2.0
# ms per frame of the classical methods (ta, svgf, bmfr) at 1280x720.
afn_add_benchmark(bench_methods SOURCES bench_methods.cpp LIBS afn_core)
