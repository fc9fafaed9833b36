# SPDX-License-Identifier: Apache-2.0
"""The paper's learned baselines, trained with the AFN toolkit's data and protocol:
``wskpn`` (Fan et al. 2021), ``nbgd`` (Meng et al. 2020), :mod:`.onnd` (Chaitanya et al. 2017)
and :mod:`.mrkp` (multi-resolution kernel prediction, NBGD supplement). Each model reads the same
features as afn (``afntool --features``, :mod:`afn.dataset`): the TA-1spp demodulated colour,
albedo, normal01 and depth01; the C++ methods are lib/core/methods/{wskpn,nbgd,onnd,mrkp}.
:mod:`.train` trains wskpn or nbgd (``--method``), :mod:`.onnd_mrkp_train` trains onnd or mrkp
(``--model``); :mod:`.make_parity_vectors` and :mod:`.onnd_mrkp_parity_vectors` write their
PyTorch <-> C++ parity vectors; :mod:`.inputs` and :mod:`.common` hold their input code.
"""
