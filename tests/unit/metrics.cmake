# SPDX-License-Identifier: Apache-2.0
# Image-quality metrics: the core (internals, vs a naive SSIM and scikit-image) and the C API.
afn_add_gtest(test_metrics SOURCES unit/test_metrics.cpp LIBS afn_core)
afn_add_gtest(test_metrics_api SOURCES unit/test_metrics_api.cpp LIBS afn)
