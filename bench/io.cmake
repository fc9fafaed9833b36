# SPDX-License-Identifier: Apache-2.0
# afn_io benchmark: read/write of a 1280x720, 22-channel Blender-like multilayer EXR.
afn_add_benchmark(bench_io SOURCES bench_io.cpp LIBS afn_io)
