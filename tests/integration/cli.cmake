# SPDX-License-Identifier: Apache-2.0
# End-to-end tests of afntool: run the real binary, check exit codes, messages and written files.

# afn_add_afntool_test(NAME SOURCES... [LIBS...] [LABEL L]): a test program that runs the built
# afntool (AFNTOOL_PATH, built first) through integration/cli_runner.cpp.
function(afn_add_afntool_test name)
  cmake_parse_arguments(ARG "" "LABEL" "SOURCES;LIBS" ${ARGN})
  afn_add_gtest(${name} SOURCES ${ARG_SOURCES} integration/cli_runner.cpp LIBS ${ARG_LIBS}
    LABEL ${ARG_LABEL})
  target_compile_definitions(${name} PRIVATE AFNTOOL_PATH="$<TARGET_FILE:afntool>")
  add_dependencies(${name} afntool)
endfunction()

afn_add_afntool_test(test_afntool SOURCES integration/test_afntool.cpp LIBS afn afn_io)

# afntool --compare / --benchmark end to end.
afn_add_afntool_test(test_afntool_compare SOURCES integration/test_afntool_compare.cpp LIBS afn)

# afntool --contact-sheet end to end, measured on the written pixels.
afn_add_afntool_test(test_afntool_sheet SOURCES integration/test_afntool_sheet.cpp
  LIBS afn_io afn_color)

# The --benchmark report's plot and page end to end.
afn_add_afntool_test(test_afntool_report SOURCES integration/test_afntool_report.cpp)

# afntool's diagnostics: role fallback, missing-AOV warnings, strict checks, help, progress.
afn_add_afntool_test(test_afntool_diagnostics SOURCES integration/test_afntool_diagnostics.cpp
  LIBS afn_io PkgConfig::OIIO)

# Faithful outputs (windows, metadata, bit depths, colour encodings) and safe files / frame
# ranges, end to end; test images are made and read with OpenImageIO directly.
afn_add_afntool_test(test_afntool_outputs SOURCES integration/test_afntool_outputs.cpp
  LIBS PkgConfig::OIIO)
afn_add_afntool_test(test_afntool_safety SOURCES integration/test_afntool_safety.cpp LIBS afn_io)

if(AFN_HAS_DNNL) # the engine report then includes the dnnl_sgemm yardstick
  target_compile_definitions(test_afntool_compare PRIVATE AFN_HAS_DNNL)
endif()

# afntool --preroll: farm chunks match a sequential run (docs/farm.md).
afn_add_afntool_test(test_afntool_preroll SOURCES integration/test_afntool_preroll.cpp
  LIBS afn afn_io)

# The Slurm job template against a real single-node Slurm the test starts itself (docs/farm.md);
# skipped (exit 77, reason printed) where Slurm is not installed or cannot start. The script
# bounds itself at AFN_SLURM_TEST_LIMIT (180 s); ctest's timeout is a backstop above that.
add_test(NAME slurm_farm_job_array
  COMMAND bash ${PROJECT_SOURCE_DIR}/tests/farm/slurm_farm_test.sh $<TARGET_FILE:afntool>
    ${PROJECT_SOURCE_DIR})
set_tests_properties(slurm_farm_job_array PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 240
  LABELS farm ENVIRONMENT "OCIO=")

# Input-aware afn: one EXR sequence per input combination, the model chosen and
# reported (--info, per-frame log), and the missing-weights error.
afn_add_afntool_test(test_afntool_input_sets SOURCES integration/test_afntool_input_sets.cpp
  LIBS PkgConfig::OIIO)

# --denoise:quality=fast|balanced|high end to end (the tiers' pixels, errors, help).
afn_add_afntool_test(test_afntool_quality SOURCES integration/test_afntool_quality.cpp
  LIBS PkgConfig::OIIO)
# Work skipping end to end: :mask=, sky depth, skip=off comparison, the sky benchmark.
afn_add_afntool_test(test_afntool_skip SOURCES integration/test_afntool_skip.cpp
  LIBS PkgConfig::OIIO)
# Light-path passes denoised with the beauty on examples/passes: they rebuild the denoised beauty.
afn_add_afntool_test(test_afntool_passes SOURCES integration/test_afntool_passes.cpp
  LIBS afn_io PkgConfig::OIIO)
