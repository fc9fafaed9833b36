# SPDX-License-Identifier: Apache-2.0
# The compute core's internals, folder by folder as lib/core (stages, methods, nn, metrics,
# cuda); the shared helpers of these tests sit in unit/core/.
set(AFN_CORE_TESTS ${CMAKE_CURRENT_LIST_DIR})

# Stages and classical methods (demodulation, reprojection, temporal accumulation, SVGF, BMFR) and
# the filters through createFilter; test_methods_blender reads examples/sequence with OIIO.
afn_add_gtest(test_methods
  SOURCES
    unit/core/stages/test_methods_reproject.cpp
    unit/core/stages/test_aux_prefilter.cpp
    unit/core/stages/test_aux_dense_speckle.cpp
    unit/core/stages/test_reproject_identity.cpp
    unit/core/stages/test_taa.cpp
    unit/core/stages/test_highlight_bypass.cpp
    unit/core/stages/test_detail_restore.cpp
    unit/core/stages/test_stage_kernels_isa.cpp
    unit/core/stages/test_gather_accumulate_isa.cpp
    unit/core/methods/test_methods_ta.cpp
    unit/core/methods/test_history_trust.cpp
    unit/core/methods/test_bmfr_detail.cpp
    unit/core/methods/test_methods_filters.cpp
    unit/core/methods/test_svgf_sparse_samples.cpp
    unit/core/methods/test_methods_blender.cpp
    unit/core/methods/svgf/test_svgf_kernels.cpp
    unit/core/methods/svgf/test_svgf_variance_kernel.cpp
    unit/core/methods/svgf/test_svgf_integrate.cpp
    unit/core/methods/svgf/test_svgf_guide.cpp
    unit/core/methods/test_work_skipping.cpp
  LIBS afn_core PkgConfig::OIIO)
target_include_directories(test_methods PRIVATE ${AFN_CORE_TESTS})

# The learned methods' engine: weights archive, layers, fused filtering/fusion, PyTorch parity,
# the afn filter, and the temporal accumulation's golden vectors.
afn_add_gtest(test_afn
  SOURCES
    unit/core/nn/test_afn_weights.cpp
    unit/core/nn/test_afn_layers.cpp
    unit/core/nn/test_conv5.cpp
    unit/core/nn/test_conv_bf16.cpp
    unit/core/methods/afn/test_afn_parity.cpp
    unit/core/methods/afn/test_afn_large.cpp
    unit/core/methods/afn/test_afn_filter.cpp
    unit/core/methods/afn/test_afn_taa.cpp
    unit/core/methods/afn/test_afn_highlights.cpp
    unit/core/methods/afn/test_afn_single_frame.cpp
    unit/core/methods/afn/test_afn_post_filter.cpp
    unit/core/methods/afn/test_afn_post_filter_noise.cpp
    unit/core/methods/afn/test_afn_input_set.cpp
    unit/core/methods/afn/test_afn_engine.cpp
    unit/core/methods/afn/test_afn_stripes.cpp
    unit/core/methods/afn/test_afn_albedo_trust.cpp
    unit/core/methods/afn/test_afn_quality.cpp
    unit/core/methods/afn/test_afn_tone_map.cpp
    unit/core/stages/test_afn_ta_parity.cpp
    unit/core/methods/baselines/test_baselines_parity.cpp
    unit/core/methods/baselines/test_baselines_filters.cpp
    unit/core/methods/baselines/test_onnd_mrkp_parity.cpp
    unit/core/methods/baselines/test_onnd_mrkp_filter.cpp
    unit/core/methods/baselines/test_onnd_contrast_gate.cpp
  LIBS afn_core)
target_include_directories(test_afn PRIVATE ${AFN_CORE_TESTS})
# The embedding mechanism of the shipped weights, exercised on a committed parity file.
include(AfnEmbed)
afn_embed_file(test_afn ${AFN_TEST_DATA}/afn_parity/weights_fusion.afnw afnTestEmbedded)

# Image-quality metrics (internals, vs a naive SSIM and scikit-image).
afn_add_gtest(test_metrics SOURCES unit/core/metrics/test_metrics.cpp LIBS afn_core)

# The CUDA engine's layouts and kernel code on the CPU (host emulation of the kernels' per-pixel
# and per-lane code against the CPU engine); built with or without CUDA. The GPU itself is tested
# by tests/gpu/.
afn_add_gtest(test_cuda_engine
  SOURCES
    unit/core/cuda/test_cuda_layout.cpp
    unit/core/cuda/test_cuda_emulated.cpp
    unit/core/cuda/test_cuda_emulated_stages.cpp
    unit/core/cuda/test_cuda_emulated_blender.cpp
    unit/core/cuda/cuda_emulator.cpp
    unit/core/cuda/cuda_emulator_scales.cpp
    unit/core/cuda/emulated_tensors.cpp
    unit/core/cuda/emulated_large.cpp
    unit/core/cuda/emulated_pipeline.cpp
  LIBS afn_core PkgConfig::OIIO)
target_include_directories(test_cuda_engine PRIVATE ${AFN_CORE_TESTS})
