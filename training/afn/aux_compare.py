# SPDX-License-Identifier: Apache-2.0
"""Before/after table of the noisy-AOV handling: two afntool builds, every method.

    cd training && /usr/bin/python3 -m afn.aux_compare \\
        --before $BASELINE_AFNTOOL --after ../build/cli/afntool \\
        --seq example=../examples/sequence:0-7 --seq glass=$AFN_DATA/afn-aux/glass:0-9 \\
        [--weights-after FILE] [--crops NAME=X,Y,W,H --crop-dir DIR] [--only before|after] \\
        --out table.md --json table.json

For every sequence and method (ta, svgf, bmfr, afn; plus the 1-spp input) each build denoises the
frames (``afntool -q --frames F DIR/frame.####.exr --denoise:method=M -d float -o ...``, default
parameters, so the "after" build runs with aux=auto) and the reference frames are read through
afntool too (same working colour space). Metrics on the tone-mapped ``T(x) = clip(max(x,0)^(1/2.2),
0, 1)`` (docs/metrics.md), each a mean over frames:

    psnr      10 log10(1 / mean (T(o) - T(r))^2)                               (dB, higher better)
    bad       share of pixels whose max over channels |T(o) - T(r)| > 0.25     (lower better)
    tge       mean |(T(o_t) - T(o_t-1)) - (T(r_t) - T(r_t-1))|, frames 1..N-1  (lower better)
"""

import argparse
import json
import os
import subprocess
import sys
import tempfile

import numpy as np

BAD_THRESHOLD = 0.25
METHODS = ["noisy", "ta", "svgf", "bmfr", "afn"]


def log(msg):
    print(f"afn.aux_compare: {msg}", file=sys.stderr, flush=True)


def read_rgb(path):
    import OpenImageIO as oiio
    buf = oiio.ImageBuf(path)
    if buf.has_error:
        raise OSError(f"cannot read {path}: {buf.geterror()}")
    spec = buf.spec()
    px = np.asarray(buf.get_pixels(oiio.FLOAT), np.float32).reshape(
        spec.height, spec.width, spec.nchannels)
    names = list(spec.channelnames)
    return np.ascontiguousarray(px[..., [names.index(c) for c in "RGB"]])


def tonemap(x):
    return np.clip(np.maximum(x, 0.0) ** (1.0 / 2.2), 0.0, 1.0)


def frames_of(spec):
    a, b = spec.split("-")
    return list(range(int(a), int(b) + 1))


def run_tool(tool, args):
    r = subprocess.run([tool] + args, capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(f"{tool} {' '.join(args)} failed: {r.stderr.strip()}")
    return r.stderr


def render(tool, seq_dir, frames, method, tmp, tag, weights=None):
    """Denoised (or input) frames of one sequence as a list of T-mapped arrays, and the log."""
    out = os.path.join(tmp, f"{tag}.####.exr")
    args = ["--frames", frames, os.path.join(seq_dir, "frame.####.exr")]
    if method != "noisy":
        mods = f"method={method}" + (f":weights={weights}" if weights else "")
        args += [f"--denoise:{mods}"]
    err = run_tool(tool, args + ["-d", "float", "-o", out])
    a, b = frames.split("-")
    return [tonemap(read_rgb(out.replace("####", f"{n:04d}")))
            for n in range(int(a), int(b) + 1)], err


def metrics(outs, refs):
    psnr, bad, tge = [], [], []
    for t, (o, r) in enumerate(zip(outs, refs)):
        d = o - r
        psnr.append(10.0 * np.log10(1.0 / max(float(np.mean(d * d)), 1e-12)))
        bad.append(float(np.mean(np.max(np.abs(d), axis=2) > BAD_THRESHOLD)))
        if t > 0:
            e = (o - outs[t - 1]) - (r - refs[t - 1])
            tge.append(float(np.mean(np.abs(e))))
    return {"psnr": float(np.mean(psnr)), "bad": float(np.mean(bad)),
            "tge": float(np.mean(tge)) if tge else float("nan")}, outs


def save_crop(img, box, path):
    import OpenImageIO as oiio
    x, y, w, h = box
    crop = np.ascontiguousarray(img[y:y + h, x:x + w])
    # 3x nearest upscale so single-pixel speckle is visible
    crop = np.repeat(np.repeat(crop, 3, axis=0), 3, axis=1)
    spec = oiio.ImageSpec(crop.shape[1], crop.shape[0], 3, "uint8")
    out = oiio.ImageOutput.create(path)
    out.open(path, spec)
    out.write_image((crop * 255.0 + 0.5).astype(np.uint8))
    out.close()


def parse_args(argv):
    ap = argparse.ArgumentParser(prog="afn.aux_compare", description=__doc__.split("\n")[0])
    ap.add_argument("--before", required=True, help="afntool of the build before")
    ap.add_argument("--after", required=True, help="afntool of the build after")
    ap.add_argument("--weights-after", default=None, help="afn weights for the after build")
    ap.add_argument("--seq", action="append", required=True, help="NAME=DIR:FIRST-LAST")
    ap.add_argument("--methods", default=",".join(METHODS))
    ap.add_argument("--crops", action="append", default=[],
                    help="NAME=X,Y,W,H: write tone-mapped crops (3x) of the last frame")
    ap.add_argument("--crop-dir", default=None, help="folder for the crops")
    ap.add_argument("--out", required=True, help="markdown table")
    ap.add_argument("--json", required=True,
                    help="results, kept between runs: finished entries are not recomputed")
    ap.add_argument("--only", choices=("before", "after", "both"), default="both",
                    help="run one build only (the table is written once both are in --json)")
    return ap.parse_args(argv)


def main(argv=None):
    args = parse_args(sys.argv[1:] if argv is None else argv)
    crops = {c.split("=")[0]: tuple(int(v) for v in c.split("=")[1].split(",")) for c in args.crops}
    results = {}
    if os.path.exists(args.json):
        with open(args.json) as fh:
            results = {tuple(k.split("/")): v for k, v in json.load(fh).items()}
    whens = [w for w in ("before", "after") if args.only in (w, "both")]
    for spec in args.seq:
        name, rest = spec.split("=", 1)
        seq_dir, frames = rest.rsplit(":", 1)
        with tempfile.TemporaryDirectory(prefix="afn-aux-") as tmp:
            ref_out = os.path.join(tmp, "ref.####.exr")
            ref_tool = args.after if os.path.exists(args.after) else args.before
            run_tool(ref_tool, ["-q", "--frames", frames,
                                  os.path.join(seq_dir, "reference.####.exr"), "-d", "float",
                                  "-o", ref_out])
            refs = [tonemap(read_rgb(ref_out.replace("####", f"{n:04d}")))
                    for n in frames_of(frames)]
            if name in crops and args.crop_dir:
                os.makedirs(args.crop_dir, exist_ok=True)
                save_crop(refs[-1], crops[name], os.path.join(args.crop_dir, f"{name}_reference.png"))
            for method in args.methods.split(","):
                for when, tool in (("before", args.before), ("after", args.after)):
                    if when not in whens or (name, method, when) in results:
                        continue
                    if method == "noisy" and when == "after":
                        results[(name, method, when)] = results[(name, method, "before")]
                        continue
                    weights = args.weights_after if (when == "after" and method == "afn") else None
                    log(f"{name} {method} {when}")
                    outs, err = render(tool, seq_dir, frames, method, tmp, f"{method}_{when}",
                                       weights)
                    m, _ = metrics(outs, refs)
                    m["log"] = [line for line in err.splitlines() if "aux" in line][:1]
                    results[(name, method, when)] = m
                    log(f"  psnr {m['psnr']:.3f}  bad {100 * m['bad']:.3f} %  tge {m['tge']:.5f}")
                    if name in crops and args.crop_dir:
                        save_crop(outs[-1], crops[name],
                                  os.path.join(args.crop_dir, f"{name}_{method}_{when}.png"))
                    save_json(args.json, results)
    write_table(args, results)
    return 0


def save_json(path, results):
    tmp = path + ".tmp"
    with open(tmp, "w") as fh:
        json.dump({"/".join(k): v for k, v in results.items()}, fh, indent=1)
    os.replace(tmp, path)


def write_table(args, results):
    lines = ["| Sequence | Method | bad % before | bad % after | after / before | PSNR before | "
             "PSNR after | TGE before | TGE after |", "|---|---|---|---|---|---|---|---|---|"]
    order = {m: i for i, m in enumerate(METHODS)}
    seqs = list(dict.fromkeys(n for n, _, _ in results))
    keys = sorted((k for k in results if k[2] == "before" and k[:2] + ("after",) in results),
                  key=lambda k: (seqs.index(k[0]), order.get(k[1], 99)))
    for name, method, _ in keys:
        m, a = results[(name, method, "before")], results[(name, method, "after")]
        ratio = a["bad"] / m["bad"] if m["bad"] > 0 else float("nan")
        lines.append(f"| `{name}` | {method} | {100 * m['bad']:.3f} | {100 * a['bad']:.3f} | "
                     f"{ratio:.2f} | {m['psnr']:.2f} | {a['psnr']:.2f} | {m['tge']:.5f} | "
                     f"{a['tge']:.5f} |")
    with open(args.out, "w") as fh:
        fh.write("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    sys.exit(main())
