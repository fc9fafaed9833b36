# SPDX-License-Identifier: Apache-2.0
# AFN engine: weights archive reader, layers, fused filtering/fusion, PyTorch parity.
afn_add_gtest(test_afn
  SOURCES
    unit/test_afn_weights.cpp
    unit/test_afn_layers.cpp
    unit/test_afn_parity.cpp
  LIBS afn_core)
