# SPDX-License-Identifier: Apache-2.0
# afn_io unit tests: role mapping, reading, sequences, BMFR layout, atomic writes.
afn_add_gtest(test_io
  SOURCES
    unit/io/test_io_roles.cpp
    unit/io/test_io_role_fallback.cpp
    unit/io/test_io_diagnostics.cpp
    unit/io/test_io_read.cpp
    unit/io/test_io_sequence.cpp
    unit/io/test_io_write.cpp
    unit/io/test_io_write_header.cpp
    unit/io/test_io_bmfr.cpp
    unit/io/test_io_exr_header.cpp
    unit/io/test_io_passes.cpp
  LIBS afn_io PkgConfig::OIIO)

# The shared library exports only what include/afn/io.hpp declares.
add_test(NAME io_library_exports COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/unit/check_library_exports.sh
  $<TARGET_FILE:afn_io> ${PROJECT_SOURCE_DIR}/include/afn/io.hpp afn::io)
