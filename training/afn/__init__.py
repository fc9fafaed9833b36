# SPDX-License-Identifier: Apache-2.0
"""afn training toolkit: the Adaptive Fusion Network (Lee et al., IEEE Access) in PyTorch.

Modules are nouns (afntool, color, dataset, loss, model, weights); scripts are verbs (train,
export, evaluate, make_parity_vectors). Input preparation runs in the C++ library through afntool
(dataset.py); heavy imports (OpenImageIO) happen lazily.
"""
