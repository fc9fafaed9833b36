# SPDX-License-Identifier: Apache-2.0
"""Tests of the randomized scene generator's pure-Python half (no Blender needed)."""

import json
import os
import subprocess
import sys

import pytest

TRAINING = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENES = os.path.join(TRAINING, "scenes")
sys.path.insert(0, SCENES)
sys.path.insert(0, TRAINING)
from generator import camera, lighting_change, materials, split  # noqa: E402
from generator.describe import describe  # noqa: E402
from generator.families import FAMILIES  # noqa: E402

import generate_dataset as gd  # noqa: E402


def test_same_family_and_seed_give_the_same_description():
    for family in FAMILIES:
        a, b = describe(family, 3, 8), describe(family, 3, 8)
        assert a == b
        assert json.loads(json.dumps(a)) == a  # plain JSON, nothing lost on disk


def test_description_does_not_depend_on_the_interpreter_hash_seed():
    code = ("import sys, json; sys.path.insert(0, %r); from generator.describe import describe; "
            "print(json.dumps(describe('night', 11, 4), sort_keys=True))" % SCENES)
    runs = [subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                           env=dict(os.environ, PYTHONHASHSEED=str(h)), check=True).stdout
            for h in (1, 2)]
    assert runs[0] == runs[1] == json.dumps(describe("night", 11, 4), sort_keys=True) + "\n"


def test_different_seeds_and_families_give_different_scenes():
    seen = set()
    for family in FAMILIES:
        for seed in range(6):
            d = describe(family, seed, 8)
            key = json.dumps({k: d[k] for k in ("objects", "lights", "camera", "world")},
                             sort_keys=True)
            assert key not in seen, (family, seed)
            seen.add(key)


def test_camera_has_one_key_per_frame_and_frames_do_not_change_the_layout():
    for family in FAMILIES:
        d8, d3 = describe(family, 5, 8), describe(family, 5, 3)
        assert len(d8["camera"]["keys"]) == 8 and len(d3["camera"]["keys"]) == 3
        # The lighting event (drawn last) may animate a material at frames that depend on the
        # length; where things are and how they move does not.
        place = lambda d: [(o["shape"], o["location"], o["dims"], o["rotation"], o["velocity"],  # noqa: E731
                            o["spin"]) for o in d["objects"]]
        assert place(d8) == place(d3)


def test_lighting_events_are_common_and_every_kind_is_built():
    """Far more lighting change than the families' own lights: events in about 2 of 3 scenes."""
    sums = [describe(f, s, 8)["summary"] for f, s in split.training_sequences(140)]
    kinds = [s["lighting_event"] for s in sums]
    assert set(kinds) - {None} == set(lighting_change.EVENTS)
    assert 0.5 < sum(k is not None for k in kinds) / len(kinds) < 0.8
    assert sum(s["fading_lights"] > 0 for s in sums) > 0
    assert sum(s["animated_emission"] > 0 for s in sums) > 0
    evals = [describe(f, s, 8)["summary"]["lighting_event"]
             for f, s in split.evaluation_sequences(3, 3)]
    assert sum(k is not None for k in evals) >= 3, evals


def test_a_light_event_keys_frames_inside_the_sequence():
    for f, seed in split.training_sequences(140):
        d = describe(f, seed, 6)
        for lt in d["lights"]:
            for step in (lt["switch"] or []) + (lt["fade"] or []):
                assert 0 <= step[0] < 6
        for o in d["objects"]:
            for frame, strength in o["material"].get("emission_keys", []):
                assert 0 <= frame < 6 and strength >= 0


def test_training_set_covers_the_generator_library():
    """The first 70 training scenes (10 per family) hold every kind of content listed."""
    sums = [describe(f, s, 8)["summary"] for f, s in split.training_sequences(70)]
    union = lambda key: set().union(*(set(s[key]) for s in sums))  # noqa: E731
    assert union("materials") == set(materials.KINDS)
    assert {"AREA", "POINT", "SPOT", "SUN"} <= union("lights")
    assert {"rod", "wire_grid", "helix", "hair_ball", "grass", "text", "rock"} <= union("shapes")
    assert {s["world"] for s in sums} == {"sky", "hdri", "flat"}
    assert {s["camera_motion"] for s in sums} == set(camera.MOTIONS)
    for flag in ("depth_of_field", "motion_blur"):
        assert 0 < sum(s[flag] for s in sums) < len(sums)
    for count in ("moving_objects", "moving_lights", "switching_lights", "small_bright_lights"):
        assert sum(s[count] > 0 for s in sums) > 0, count


def test_held_out_split_never_overlaps_training():
    train = split.training_sequences(5000)
    evals = split.evaluation_sequences(held_out=20, reserved=20)
    assert len(set(train)) == len(train) and len(set(evals)) == len(evals)
    assert not set(train) & set(evals)
    assert all(split.is_training(*p) and not split.is_evaluation(*p) for p in train)
    assert all(split.is_evaluation(*p) and not split.is_training(*p) for p in evals)
    assert not {f for f, _ in train} & set(split.HELD_OUT_FAMILIES)
    assert {f for f, _ in evals} & set(split.HELD_OUT_FAMILIES)
    assert {f for f, _ in evals} - set(split.HELD_OUT_FAMILIES)  # reserved seeds of seen families
    assert split.training_sequences(7) == split.training_sequences(70)[:7]  # prefixes balanced
    assert {f for f, _ in split.training_sequences(len(split.TRAIN_FAMILIES))} == \
        set(split.TRAIN_FAMILIES)


def test_driver_plan_puts_training_first_and_uses_its_settings():
    args = gd.parse_args(["--out", "/nonexistent", "--train", "9"])
    todo = gd.plan(args)
    assert [p[0] for p in todo] == ["train"] * 9 + ["eval"] * 6
    assert todo[-1][3:] == (gd.DEFAULTS["eval_frames"], gd.DEFAULTS["eval_levels"],
                            gd.DEFAULTS["eval_ref_spp"], gd.DEFAULTS["eval_ref_parts"], "reference")
    assert todo[0][3:] == (gd.DEFAULTS["frames"], gd.DEFAULTS["levels"], gd.DEFAULTS["extra_spp"],
                           1, "extra")
    first = gd.plan(gd.parse_args(["--out", "/x", "--train", "9", "--order", "eval-first"]))
    assert [p[0] for p in first] == ["eval"] * 6 + ["train"] * 9
    assert sorted(first) == sorted(todo)
    chosen = gd.plan(gd.parse_args(["--out", "/x", "--sequences", "room:4,atrium:2"]))
    assert [(p[0], p[1], p[2]) for p in chosen] == [("train", "room", 4), ("eval", "atrium", 2)]
    with pytest.raises(gd.DatasetError, match="FAMILY:SEED"):
        gd.plan(gd.parse_args(["--out", "/x", "--sequences", "castle:1"]))


def test_training_targets_leave_their_own_level_out():
    assert gd.level_targets([1, 4, 16, 64], 16) == {1: 100, 4: 97, 16: 85, 64: 37}


def test_rerun_refuses_a_description_the_generator_no_longer_makes(tmp_path):
    desc = describe("room", 1, 2)
    gd.write_description(str(tmp_path), desc)
    gd.write_description(str(tmp_path), desc)  # same: accepted
    desc["seed"] = 99
    with pytest.raises(gd.DatasetError, match="differs"):
        gd.write_description(str(tmp_path), desc)


def test_hard_surfaces_depth_of_field_and_blur_are_common():
    """Metal, glass and glossy props in most scenes; depth of field and motion blur in about 1 in 3."""
    from generator import surfaces
    sums = [describe(f, s, 6)["summary"] for f, s in split.training_sequences(70)]
    hard = set(surfaces.HARD_KINDS)
    assert sum(bool(hard & set(s["materials"])) for s in sums) / len(sums) > 0.9
    assert sum(s["hard_surfaces"] > 0 for s in sums) / len(sums) > 0.8
    assert 0.25 < sum(s["depth_of_field"] for s in sums) / len(sums) < 0.5
    assert 0.25 < sum(s["motion_blur"] for s in sums) / len(sums) < 0.5
    evals = [describe(f, s, 8)["summary"] for f, s in split.evaluation_sequences(4, 3)]
    assert sum(bool({"glass", "metal_mirror", "metal_rough"} & set(s["materials"]))
               for s in evals) >= 5


def test_hard_surfaces_leave_emitters_big_surfaces_and_layout_alone(monkeypatch):
    """Only the materials of props change: emitters, walls, floors and every position stay."""
    from generator import surfaces
    seqs = list(split.training_sequences(35))
    with_step = [describe(f, s, 6) for f, s in seqs]
    monkeypatch.setattr(surfaces, "add_hard_surfaces", lambda rng, desc: 0)
    without = [describe(f, s, 6) for f, s in seqs]
    changed = 0
    for a, b in zip(with_step, without):
        assert a["lights"] == b["lights"] and a["camera"]["keys"] == b["camera"]["keys"]
        for oa, ob in zip(a["objects"], b["objects"]):
            assert (oa["shape"], oa["location"], oa["dims"]) == (ob["shape"], ob["location"], ob["dims"])
            if oa["material"] != ob["material"]:
                changed += 1
                assert ob["material"]["kind"] != "emissive" and not ob["material"].get("emission_keys")
                assert max(ob["dims"]) < surfaces.PROP_SIZE
                assert oa["material"]["kind"] in surfaces.HARD_KINDS
    assert changed > 35
