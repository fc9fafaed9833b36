# SPDX-License-Identifier: Apache-2.0
# AFN engine: weights archive reader, layers, fused filtering/fusion, PyTorch parity.
afn_add_gtest(test_afn
  SOURCES
    unit/test_afn_weights.cpp
    unit/test_afn_layers.cpp
    unit/test_afn_parity.cpp
    unit/test_afn_filter.cpp
    unit/test_afn_ta_parity.cpp
  LIBS afn_core)
# The embedding mechanism of the shipped weights, exercised on a committed parity file.
include(AfnEmbed)
afn_embed_file(test_afn ${AFN_TEST_DATA}/afn_parity/weights_fusion.afnw afnTestEmbedded)
