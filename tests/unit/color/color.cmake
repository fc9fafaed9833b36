# SPDX-License-Identifier: Apache-2.0
# Colour: conversions against hand-derived values, config resolution, AOV tiles and contact sheets.
find_package(Threads REQUIRED)
afn_add_gtest(test_color_convert SOURCES unit/color/test_color_convert.cpp LIBS afn_color)
# These two also check internal helpers (bitmap font, install-relative config lookup), which the
# shared library hides: they link the object library.
afn_add_gtest(test_color_config SOURCES unit/color/test_color_config.cpp LIBS afn_color_objects)
afn_add_gtest(test_color_tiles SOURCES unit/color/test_color_tiles.cpp LIBS afn_color_objects)
target_include_directories(test_color_tiles PRIVATE ${PROJECT_SOURCE_DIR}/lib/color)
target_include_directories(test_color_config PRIVATE ${PROJECT_SOURCE_DIR}/lib/color)
target_link_libraries(test_color_convert PRIVATE Threads::Threads)

# The shipped config must pass OpenColorIO's own checker; skipped (code 77) without ociocheck.
find_program(AFN_OCIOCHECK ociocheck)
if(AFN_OCIOCHECK)
  add_test(NAME color_ociocheck
    COMMAND ${AFN_OCIOCHECK} --iconfig ${PROJECT_SOURCE_DIR}/ocio/config.ocio)
  set_tests_properties(color_ociocheck PROPERTIES
    ENVIRONMENT "OCIO=" FAIL_REGULAR_EXPRESSION "ERROR|WARNING")
else()
  add_test(NAME color_ociocheck COMMAND sh -c "echo 'ociocheck not found: skipped'; exit 77")
  set_tests_properties(color_ociocheck PROPERTIES SKIP_RETURN_CODE 77)
endif()

# The shared library exports only what include/afn/color.hpp declares.
add_test(NAME color_library_exports
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/unit/check_library_exports.sh
  $<TARGET_FILE:afn_color> ${PROJECT_SOURCE_DIR}/include/afn/color.hpp afn::color)
