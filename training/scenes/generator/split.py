# SPDX-License-Identifier: Apache-2.0
"""Which generated scenes train and which evaluate: a fixed, deterministic split (no ``bpy``).

* The family ``atrium`` (:data:`HELD_OUT_FAMILIES`) never appears in training.
* Seeds from :data:`EVAL_SEED_START` up are reserved for evaluation in every family; training
  seeds are 0 .. EVAL_SEED_START - 1.

The evaluation set is the first scenes of the held-out family plus reserved seeds of training
families (:func:`evaluation_sequences`); training takes families round-robin
(:func:`training_sequences`), so any prefix of the training list is balanced across families.
"""

from .families import FAMILIES

HELD_OUT_FAMILIES = ("atrium",)
TRAIN_FAMILIES = tuple(f for f in FAMILIES if f not in HELD_OUT_FAMILIES)
EVAL_SEED_START = 1000000

# Training families whose reserved seeds join the evaluation set, in order of use.
EVAL_RESERVED_FAMILIES = ("room", "outdoor", "night", "kinetic", "showroom", "tabletop", "clutter")


def sequence_name(family, seed):
    """Directory name of a generated sequence, e.g. ``room-0000017``."""
    return "%s-%07d" % (family, seed)


def is_training(family, seed):
    """True when (family, seed) may be used for training."""
    return family in TRAIN_FAMILIES and 0 <= seed < EVAL_SEED_START


def is_evaluation(family, seed):
    """True when (family, seed) is held out (unseen family or reserved seed)."""
    return family in FAMILIES and not is_training(family, seed) and seed >= 0


def training_sequences(count):
    """The first ``count`` training scenes: (family, seed) pairs, families round-robin."""
    n = len(TRAIN_FAMILIES)
    return [(TRAIN_FAMILIES[i % n], i // n) for i in range(count)]


def evaluation_sequences(held_out=4, reserved=4):
    """``held_out`` scenes of the held-out families and ``reserved`` reserved-seed scenes."""
    pairs = [(HELD_OUT_FAMILIES[k % len(HELD_OUT_FAMILIES)], EVAL_SEED_START + k)
             for k in range(held_out)]
    pairs += [(EVAL_RESERVED_FAMILIES[k % len(EVAL_RESERVED_FAMILIES)], EVAL_SEED_START + k)
              for k in range(reserved)]
    return pairs
