# SPDX-License-Identifier: Apache-2.0
"""The paper's learned baselines, trained with the AFN toolkit's data and protocol (issue 15):
``wskpn`` (Fan et al. 2021) and ``nbgd`` (Meng et al. 2020). Each model reads the same features as
afn (``afntool --features``, :mod:`afn.dataset`): the TA-1spp demodulated colour, albedo,
normal01 and depth01; the C++ methods are lib/core/methods/wskpn and lib/core/methods/nbgd.
"""
