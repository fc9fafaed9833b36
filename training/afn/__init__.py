# SPDX-License-Identifier: Apache-2.0
"""afn training toolkit: the Adaptive Fusion Network (Lee et al., IEEE Access) in PyTorch.

Modules are nouns (color, model, loss, weights, ta, dataset); scripts are verbs (train, export,
make_parity_vectors). Heavy imports (OpenImageIO) happen lazily inside dataset.py.
"""
