# SPDX-License-Identifier: Apache-2.0
# The CUDA afn filter's speed (docs/gpu.md): a plain program timing graph replays with CUDA events,
# self-contained for scripts/make-gpu-bundle.sh (afn_core and oneTBB only).
add_executable(bench_afn_cuda bench_afn_cuda.cpp)
target_link_libraries(bench_afn_cuda PRIVATE afn_core)
target_include_directories(bench_afn_cuda PRIVATE ${PROJECT_SOURCE_DIR}/tests/unit/core)
