# SPDX-License-Identifier: Apache-2.0
# AFN_SANITIZE: build every target with AddressSanitizer and UndefinedBehaviorSanitizer (any error
# aborts the program). AFN_BUILD_FUZZERS: additionally instrument every target for libFuzzer's
# coverage and build the fuzz targets of tests/fuzz; needs clang with libFuzzer (otherwise the
# targets are skipped with a warning). Both belong in their own build folder (scripts/build-asan.sh).
option(AFN_SANITIZE "Build everything with AddressSanitizer and UndefinedBehaviorSanitizer" OFF)
option(AFN_BUILD_FUZZERS "Build the libFuzzer targets in tests/fuzz (clang only; implies AFN_SANITIZE)" OFF)
set(AFN_SANITIZERS "address,undefined" CACHE STRING
  "Sanitizers of AFN_SANITIZE builds (\"undefined\" alone runs fuzz targets faster)")

set(AFN_FUZZERS_ENABLED OFF)
if(AFN_BUILD_FUZZERS)
  include(CheckCXXSourceCompiles)
  set(CMAKE_REQUIRED_FLAGS "-fsanitize=fuzzer")
  set(CMAKE_REQUIRED_LINK_OPTIONS "-fsanitize=fuzzer")
  check_cxx_source_compiles([=[
    #include <cstddef>
    #include <cstdint>
    extern "C" int LLVMFuzzerTestOneInput(const uint8_t*, size_t) { return 0; }
  ]=] AFN_HAVE_LIBFUZZER)
  unset(CMAKE_REQUIRED_FLAGS)
  unset(CMAKE_REQUIRED_LINK_OPTIONS)
  if(CMAKE_CXX_COMPILER_ID STREQUAL "Clang" AND AFN_HAVE_LIBFUZZER)
    set(AFN_FUZZERS_ENABLED ON)
    set(AFN_SANITIZE ON)
  else()
    message(WARNING "AFN_BUILD_FUZZERS needs clang with libFuzzer (-fsanitize=fuzzer); "
      "configure with CC=clang CXX=clang++. The fuzz targets are not built.")
  endif()
endif()

if(AFN_SANITIZE)
  add_compile_options(-fsanitize=${AFN_SANITIZERS} -fno-sanitize-recover=all
    -fno-omit-frame-pointer -gline-tables-only)
  add_link_options(-fsanitize=${AFN_SANITIZERS})
  # C programs (examples/minimal.c) link libafn, whose C++ code needs UBSan's C++ runtime.
  add_link_options("$<$<LINK_LANGUAGE:C>:-fsanitize-link-c++-runtime;-lstdc++>")
  if(AFN_FUZZERS_ENABLED)
    # Coverage feedback for libFuzzer in every library the targets reach; the sanitizer runtime
    # provides the hooks for programs that are not fuzz targets (the tests).
    add_compile_options(-fsanitize=fuzzer-no-link)
  endif()
endif()
