# SPDX-License-Identifier: Apache-2.0
"""afn.evaluate on a tiny fake dataset: two scenes of three 320x180 frames symlinked from
examples/sequence (frames 0-2 and 3-5, renumbered 0-2). Checks the tables and columns, the noisy
numbers against a direct afntool --compare, the in-memory scores against denoised files written and
compared, baselines beating the noisy input, the bolding of two rows recomputed from the JSON, and a
failing ablation variant shown as "—" with a footnote. Skipped when afntool is not built."""

import json
import os
import subprocess
import sys

import pytest

TRAINING = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SEQUENCE = os.path.join(TRAINING, "..", "examples", "sequence")
PARITY = os.path.join(TRAINING, "..", "tests", "data", "afn_parity")
sys.path.insert(0, TRAINING)
from afn import afntool, evaluate  # noqa: E402

AFNTOOL = afntool.find_afntool()
SCENES = {"alpha": 0, "beta": 3}          # scene -> first example frame it shows
HEADLINE = ["psnr", "ssim", "rmse", "smape"]


def afntool_json(*args):
    p = subprocess.run([AFNTOOL, "--threads", "1", *args, "--json"], check=True,
                       capture_output=True, text=True)
    return json.loads(p.stdout)


def make_dataset(root):
    for scene, first in SCENES.items():
        d = root / scene
        d.mkdir(parents=True)
        for n in range(3):
            for kind in ("frame", "reference"):
                src = os.path.abspath(os.path.join(SEQUENCE, f"{kind}.{first + n:04d}.exr"))
                os.symlink(src, d / f"{kind}.{n:04d}.exr")
    manifest = {"width": 320, "height": 180, "frames": 3, "spp": 1, "ref_spp": 64}
    (root / "manifest.json").write_text(json.dumps(manifest))
    return root


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    if AFNTOOL is None:
        pytest.skip("afntool is not built (../build*/cli/afntool)")
    if not os.path.exists(os.path.join(SEQUENCE, "reference.0005.exr")):
        pytest.skip("examples/sequence not present")
    tmp = tmp_path_factory.mktemp("evaluate")
    data = make_dataset(tmp / "data")
    bad = tmp / "broken.afnw"
    bad.write_bytes(b"AFNX" + bytes(60))
    full = os.path.join(PARITY, "weights_full.afnw")
    fusion = os.path.join(PARITY, "weights_fusion.afnw")
    md, js = tmp / "eval.md", tmp / "eval.json"
    evaluate.main(["--data", str(data), "--scenes", ",".join(SCENES), "--afntool", AFNTOOL,
                   "--weights", full, "--ablation", f"full={full},fusion={fusion},1spp={bad}",
                   "--frames", "0-2", "--threads", "1", "--out", str(md), "--json", str(js)])
    return {"data": data, "md": md.read_text(), "doc": json.loads(js.read_text()), "tmp": tmp}


def section(md, title):
    """Lines of the table under '### title'."""
    lines = md.split("### " + title + "\n", 1)[1].split("\n### ", 1)[0].splitlines()
    return [ln for ln in lines if ln.startswith("|")]


def row(md, title, first_cell):
    for ln in section(md, title):
        cells = [c.strip() for c in ln.strip("|").split("|")]
        if cells[0] == first_cell:
            return cells[1:]
    raise AssertionError(f"no row {first_cell} in {title}")


def test_markdown_has_every_table_and_column(run):
    md = run["md"]
    for title in ["PSNR (dB)", "SSIM", "RMSE", "SMAPE", "Temporal-gradient error"]:
        rows = section(md, title)
        assert rows[0] == "| Scene | " + " | ".join(label for _, label in evaluate.METHODS) + " |"
        assert rows[0].startswith("| Scene | Noisy (1 spp) | TA | SVGF | BMFR |"), title
        assert [r.split("|")[1].strip() for r in rows[2:]] == ["`alpha`", "`beta`", "Average"]
    abl = section(md, "Ablation (paper Table 11): fusion and refinement")
    assert abl[0] == ("| Variant | PSNR (dB) (avg) | SSIM (avg) | RMSE (avg) | SMAPE (avg) | "
                      "PSNR `alpha` | PSNR `beta` |")
    assert [r.split("|")[1].split(" (")[0].strip() for r in abl[2:]] == \
        ["1-spp only", "Fusion only", "Fusion + refinement"]
    full = os.path.join(PARITY, "weights_full.afnw")
    assert evaluate.sha256(full)[:12] in md and "-m afn.evaluate" in md and "--frames 0-2" in md
    assert "320x180, frames 3, spp 1, ref_spp 64" in md


def test_noisy_numbers_match_a_direct_compare(run):
    doc, data = run["doc"], run["data"]
    for scene in SCENES:
        d = os.path.join(data, scene)
        direct = afntool_json("--frames", "0-2", os.path.join(d, "frame.####.exr"),
                              "--compare", os.path.join(d, "reference.####.exr"))
        got = doc["results"][scene]["noisy"]
        assert [f["frame"] for f in got["frames"]] == [0, 1, 2]
        for k in HEADLINE + ["tge"]:
            assert got["mean"][k] == pytest.approx(direct["mean"][k], rel=1e-9), (scene, k)
            for a, b in zip(got["frames"], direct["frames"]):
                assert a.get(k) == pytest.approx(b.get(k), rel=1e-9), (scene, k)
    for k in HEADLINE:
        scenes = [doc["results"][s]["noisy"]["mean"][k] for s in SCENES]
        assert doc["average"]["noisy"][k] == pytest.approx(sum(scenes) / len(scenes), rel=1e-12)
    assert scenes[0] != scenes[1]          # the two scenes really differ


def test_in_memory_scores_equal_written_files(run):
    d = os.path.join(run["data"], "alpha")
    out = os.path.join(run["tmp"], "ta.####.exr")
    subprocess.run([AFNTOOL, "-q", "--threads", "1", "--frames", "0-2",
                    os.path.join(d, "frame.####.exr"), "--denoise:method=ta", "-d", "float",
                    "-o", out], check=True, capture_output=True)
    direct = afntool_json("--frames", "0-2", out, "--compare",
                          os.path.join(d, "reference.####.exr"))
    got = run["doc"]["results"]["alpha"]["ta"]["mean"]
    for k in HEADLINE:
        assert got[k] == pytest.approx(direct["mean"][k], rel=1e-5), k


def test_baselines_beat_the_noisy_input(run):
    res = run["doc"]["results"]
    for scene in SCENES:
        noisy = res[scene]["noisy"]["mean"]
        for m in ("ta", "svgf", "bmfr"):
            assert res[scene][m]["mean"]["psnr"] > noisy["psnr"], (scene, m)
            assert res[scene][m]["mean"]["rmse"] < noisy["rmse"], (scene, m)
    assert "error" not in res["alpha"]["afn"], res["alpha"]["afn"]


def bold_by_hand(values, fmt, higher):
    shown = [float(fmt.format(v)) for v in values]
    best = max(shown) if higher else min(shown)
    return [f"**{fmt.format(v)}**" if s == best else fmt.format(v) for v, s in zip(values, shown)]


def test_best_value_per_row_is_bold(run):
    doc, md = run["doc"], run["md"]
    methods = [m for m, _ in evaluate.METHODS]
    psnr = [doc["average"][m]["psnr"] for m in methods]
    assert row(md, "PSNR (dB)", "Average") == bold_by_hand(psnr, "{:.3f}", True)
    smape = [doc["results"]["beta"][m]["mean"]["smape"] for m in methods]
    expect = bold_by_hand(smape, "{:.4f}", False)
    assert row(md, "SMAPE", "`beta`") == expect and sum("**" in c for c in expect) >= 1


def test_failed_variant_is_a_footnote_not_a_crash(run):
    doc, md = run["doc"], run["md"]
    assert "invalid or corrupted weights" in doc["results"]["alpha"]["ablation:1spp"]["error"]
    assert "error" in doc["average"]["ablation:1spp"]
    abl = section(md, "Ablation (paper Table 11): fusion and refinement")
    cells = [c.strip() for c in abl[2].strip("|").split("|")]
    assert cells[0].startswith("1-spp only") and all(c.startswith("—[^") for c in cells[1:])
    note = cells[-1][1:]                # a per-scene PSNR cell: the afntool error
    assert any(ln.startswith(note + ": 1-spp only: afntool exited with 1")
               for ln in md.splitlines())
    assert "**warning**: the archive could not be read" in md
    fusion = doc["results"]["alpha"]["ablation:fusion"]["mean"]["psnr"]
    assert fusion != doc["results"]["alpha"]["afn"]["mean"]["psnr"]   # really another model


def test_helpers():
    assert afntool.frame_list([0, 1, 2, 3]) == "0-3"
    assert afntool.frame_list([2, 4, 5]) == "2,4,5"
    assert evaluate.best_flags([30.0004, 30.0001, None], "{:.3f}", True) == [True, True, False]
    assert evaluate.best_flags([0.2, 0.1, 0.3], "{:.4f}", False) == [False, True, False]
    assert evaluate.parse_ablation("full=a.afnw,ta=b.afnw") == {"full": "a.afnw", "ta": "b.afnw"}
    with pytest.raises(SystemExit):
        evaluate.parse_ablation("refine=a.afnw")
