# SPDX-License-Identifier: Apache-2.0
"""The paper's learned baselines, trained with the afn toolkit's data and protocol:
:mod:`.onnd` (Chaitanya et al. 2017) and :mod:`.mrkp` (multi-resolution kernel prediction, NBGD
supplement); :mod:`.train` trains either; :mod:`.common` holds their shared input and sampling code.
"""
