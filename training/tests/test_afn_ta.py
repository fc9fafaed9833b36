# SPDX-License-Identifier: Apache-2.0
"""Python BMFR temporal accumulation (afn/ta.py) on hand cases."""

import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from afn.ta import TemporalAccumulator, _footprint  # noqa: E402


def _const(v, h=3, w=4):
    return np.full((h, w, 3), v, np.float32)


def test_static_sequence_running_mean_then_alpha_min():
    ta = TemporalAccumulator(alpha_min=0.2)
    acc, spp = ta.accumulate(_const(1))
    assert np.all(acc == 1) and np.all(spp == 1)
    acc, spp = ta.accumulate(_const(3))          # alpha = 1/2: 1 + 0.5 * 2 = 2
    assert np.all(acc == 2) and np.all(spp == 2)
    acc, spp = ta.accumulate(_const(5))          # alpha = 1/3: 2 + 3/3 = 3
    assert np.allclose(acc, 3) and np.all(spp == 3)
    for _ in range(10):
        acc, spp = ta.accumulate(_const(5))
    # spp 3 -> 13 with alphas 1/4, then max(1/5.., 0.2) = 0.2: the gap 2 shrinks by 3/4 * 0.8^9
    acc, spp = ta.accumulate(_const(0))          # alpha = max(1/14, 0.2) = 0.2
    assert np.allclose(acc, 0.8 * (5 - 2 * 0.75 * 0.8 ** 9), rtol=1e-5) and np.all(spp == 14)


def test_motion_shifts_history_and_rejects_outside_taps():
    ta = TemporalAccumulator()
    first = np.zeros((1, 4, 3), np.float32)
    first[0, :, 0] = [10, 20, 30, 40]
    ta.accumulate(first)
    motion = np.zeros((1, 4, 2), np.float32)
    motion[..., 0] = -1.0                         # the surface was one pixel to the left
    acc, spp = ta.accumulate(np.zeros((1, 4, 3), np.float32), motion=motion)
    # x = 0 reads x = -1: outside, reset (acc = current = 0); others blend with x - 1 at alpha 1/2
    assert acc[0, 0, 0] == 0 and spp[0, 0] == 1
    assert np.allclose(acc[0, 1:, 0], [5, 10, 15]) and np.all(spp[0, 1:] == 2)
    # half-pixel motion: bilinear between two accepted taps
    ta.reset()
    ta.accumulate(first)
    motion[..., 0] = 0.5
    acc, _ = ta.accumulate(np.zeros((1, 4, 3), np.float32), motion=motion)
    assert np.allclose(acc[0, :3, 0], [7.5, 12.5, 17.5])   # 0.5 * mean(neighbours)
    assert acc[0, 3, 0] == 20                                 # only tap x=3 inside: 0.5 * 40


def test_normal_and_position_rejection():
    h, w = 2, 3
    n = np.zeros((h, w, 3), np.float32)
    n[..., 2] = 1
    pos = np.zeros((h, w, 3), np.float32)
    pos[..., 0] = np.arange(w)
    pos[..., 1] = np.arange(h)[:, None]
    ta = TemporalAccumulator()
    ta.accumulate(_const(1, h, w), position=pos, normal=n)
    n2 = n.copy()
    n2[0, 0] = [1, 0, 0]                        # turned 90 degrees: |dn|^2 = 2 > 0.25
    acc, spp = ta.accumulate(_const(3, h, w), position=pos, normal=n2)
    assert spp[0, 0] == 1 and np.all(acc[0, 0] == 3)
    assert np.all(spp.ravel()[1:] == 2) and np.all(acc.reshape(-1, 3)[1:] == 2)
    pos2 = pos.copy()
    pos2[..., 2] = 100.0                        # everything moved 100 units; footprint stays 1
    acc, spp = ta.accumulate(_const(5, h, w), position=pos2, normal=n2)
    assert np.all(spp == 1) and np.all(acc == 5)


def test_footprint_is_nearest_neighbour_distance():
    pos = np.zeros((2, 3, 3), np.float32)
    pos[..., 0] = [[0, 1, 3], [0, 1, 3]]
    pos[..., 1] = [[0, 0, 0], [5, 5, 5]]
    fp = _footprint(pos)
    # x: min over left/right neighbours; y: the only neighbour is 5 away -> max(x, 5) = 5
    assert np.all(fp == 5)
