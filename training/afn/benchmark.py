# SPDX-License-Identifier: Apache-2.0
"""Time the PyTorch AFN forward pass per stage (the reference for the C++ engine's choice of
convolutions: PyTorch's CPU convolutions are oneDNN).

    cd training && /usr/bin/python3 -m afn.benchmark [--size 1280x720] [--threads 1] [--repeat 5]

Reports the median CPU time of the process (robust on a shared machine; with --threads 1 it is the
whole cost) and the median wall time, per stage: encoder-decoder convolutions (oneDNN,
channels-last), heads + softmax + filtering + fusion (shifted slices), refinement convolutions.
"""

import argparse
import time

import numpy as np
import torch
import torch.nn.functional as F

from .color import tonemap
from .model import AFN, AFNConfig, apply_kernels, down2, fuse, up2


def _time(fn, repeat):
    cpu, wall = [], []
    for _ in range(repeat):
        c0, w0 = time.process_time(), time.perf_counter()
        fn()
        cpu.append(time.process_time() - c0)
        wall.append(time.perf_counter() - w0)
    return 1e3 * float(np.median(cpu)), 1e3 * float(np.median(wall))


@torch.no_grad()
def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--size", default="1280x720")
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--repeat", type=int, default=5)
    args = ap.parse_args(argv)
    w, h = (int(v) for v in args.size.split("x"))
    torch.set_num_threads(args.threads)
    net = AFN(AFNConfig()).eval().to(memory_format=torch.channels_last)
    g = torch.Generator().manual_seed(0)
    c1, cta, alb, nrm = (torch.rand(1, 3, h, w, generator=g) for _ in range(4))
    dep = torch.rand(1, 1, h, w, generator=g)
    cl = dict(memory_format=torch.channels_last)
    x = torch.cat([tonemap(c1), tonemap(cta), alb, nrm, dep], 1).contiguous(**cl)
    state = {}

    def predict():
        e1 = F.relu(net.enc1(down2(x)))
        e2 = F.relu(net.enc2(down2(e1)))
        e3 = F.relu(net.enc3(down2(e2)))
        d2 = F.relu(net.dec2(torch.cat([up2(e3), e2], 1)))
        state["d1"] = F.relu(net.dec1(torch.cat([up2(d2), e1], 1)))

    def filter_fuse():
        d1 = state["d1"]
        k1 = torch.softmax(net.head1(d1), 1)
        full = net.headTA(torch.cat([up2(d1), x], 1))
        kta = torch.softmax(full[:, :49], 1)
        alpha = torch.sigmoid(full[:, 49:])
        state["i"] = fuse(apply_kernels(cta, kta), apply_kernels(down2(c1), k1), alpha)

    def refine():
        i = state["i"]
        r = torch.cat([tonemap(i), alb, nrm, dep], 1).contiguous(**cl)
        state["o"] = i + net.ref3(F.relu(net.ref2(F.relu(net.ref1(r)))))

    predict(), filter_fuse(), refine()     # warm up (oneDNN primitive creation)
    print(f"PyTorch {torch.__version__}, {args.threads} thread(s), {w}x{h}, median of "
          f"{args.repeat}: CPU ms / wall ms")
    for name, fn in (("encoder-decoder", predict), ("heads+filtering+fusion", filter_fuse),
                     ("refinement", refine)):
        c, wl = _time(fn, args.repeat)
        print(f"  {name:24s} {c:9.1f} {wl:9.1f}")


if __name__ == "__main__":
    main()
