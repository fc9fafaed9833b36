# SPDX-License-Identifier: Apache-2.0
# The CUDA device (lib/core/cuda). AFN_DEVICE_CUDA selects it:
#   AUTO  build it when a working CUDA compiler is found: CMAKE_CUDA_COMPILER, $CUDACXX, nvcc on the
#         PATH, or /usr/local/cuda/bin/nvcc (the default; without one everything else builds as is)
#   ON    build it; configuring fails when no CUDA compiler works
#   OFF   never build it
# Sets AFN_HAS_CUDA (ON/OFF). The kernels are compiled for Hopper only (sm_90 machine code plus
# compute_90 PTX that newer GPUs compile at load time), with the CUDA runtime linked statically, so
# that binaries need the NVIDIA driver and nothing else from CUDA.
set(AFN_DEVICE_CUDA AUTO CACHE STRING "Build the CUDA device: AUTO (when a CUDA compiler is found), ON or OFF")
set_property(CACHE AFN_DEVICE_CUDA PROPERTY STRINGS AUTO ON OFF)
string(TOUPPER "${AFN_DEVICE_CUDA}" _afn_cuda_mode)
if(NOT _afn_cuda_mode MATCHES "^(AUTO|ON|OFF)$")
  message(FATAL_ERROR "AFN_DEVICE_CUDA must be AUTO, ON or OFF (got '${AFN_DEVICE_CUDA}')")
endif()

set(AFN_HAS_CUDA OFF)
if(NOT _afn_cuda_mode STREQUAL "OFF")
  # check_language() finds compilers through $CUDACXX and the PATH; point it at the usual
  # toolkit location when neither names one.
  if(NOT DEFINED CMAKE_CUDA_COMPILER AND NOT DEFINED ENV{CUDACXX})
    find_program(AFN_NVCC nvcc HINTS /usr/local/cuda/bin ENV CUDA_PATH PATH_SUFFIXES bin)
    if(AFN_NVCC)
      set(ENV{CUDACXX} "${AFN_NVCC}")
    endif()
  endif()
  include(CheckLanguage)
  check_language(CUDA)
  if(CMAKE_CUDA_COMPILER)
    if(NOT DEFINED CMAKE_CUDA_ARCHITECTURES)
      set(CMAKE_CUDA_ARCHITECTURES "90-real;90-virtual")
    endif()
    enable_language(CUDA)
    set(CMAKE_CUDA_STANDARD 17)
    set(CMAKE_CUDA_STANDARD_REQUIRED ON)
    set(CMAKE_CUDA_RUNTIME_LIBRARY Static)
    find_package(CUDAToolkit REQUIRED)
    set(AFN_HAS_CUDA ON)
    message(STATUS "afn: CUDA device ON (${CMAKE_CUDA_COMPILER}, architectures ${CMAKE_CUDA_ARCHITECTURES})")
  elseif(_afn_cuda_mode STREQUAL "ON")
    message(FATAL_ERROR "AFN_DEVICE_CUDA=ON but no working CUDA compiler was found "
      "(set CMAKE_CUDA_COMPILER or CUDACXX)")
  else()
    message(STATUS "afn: CUDA device OFF (no CUDA compiler found)")
  endif()
else()
  message(STATUS "afn: CUDA device OFF (AFN_DEVICE_CUDA=OFF)")
endif()

# Print the kernels' register, shared-memory and spill counts while compiling (ptxas -v).
option(AFN_CUDA_PTXAS_VERBOSE "Report registers and spills of every CUDA kernel" OFF)
