# SPDX-License-Identifier: Apache-2.0
"""Run a training command on jemalloc instead of glibc's malloc, when jemalloc is installed.

PyTorch on the CPU allocates each step's large activations (the 7x7-kernel unfold of a 16-crop
batch is ~150 MB) afresh. glibc serves blocks that large with mmap and unmaps them on free, so
every step page-faults its whole working set in again. On the 2-core development machine an AFN
step (16 crops of 128x128, 2 threads) took 0.5-16 s with glibc (median ~3 s) and a steady 0.50 s
with jemalloc configured never to return freed memory (`dirty_decay_ms:-1`):

    /usr/bin/python3 /tmp/time_afn.py         # forward + backward + Adam on random data
    LD_PRELOAD=/usr/lib/x86_64-linux-gnu/libjemalloc.so.2 \\
        MALLOC_CONF=dirty_decay_ms:-1,muzzy_decay_ms:-1 /usr/bin/python3 /tmp/time_afn.py

An allocator can only be preloaded before the process starts, so the training entry points call
:func:`reexec` first: it re-runs the same ``python3 -m MODULE ARGS`` with jemalloc preloaded and
returns (does nothing) when that is already so, when jemalloc is not installed (Debian package
``libjemalloc2``; ``scripts/setup.sh --torch`` installs it) or when ``AFN_NO_JEMALLOC=1``. Results
do not depend on the allocator; only the speed does.
"""

import os
import sys

CANDIDATES = ("/usr/lib/x86_64-linux-gnu/libjemalloc.so.2", "/usr/lib/aarch64-linux-gnu/libjemalloc.so.2",
              "/usr/lib/libjemalloc.so.2")
# The price of never returning memory: a long run's resident size grows at each epoch's validation
# and checkpoint (80-220 MB per epoch on 2026-12-03; 14 GB after 49 epochs, when the kernel killed
# one of two runs sharing 24 GB). A 30 s decay kept it at 1.2 GB but made epochs 2x slower (page
# faults: system time above user time), so long runs are split instead: `--minutes M` and a rerun
# resume exactly (training/README.md), and each new process starts small. `narenas:1` does not
# change the growth (two 16-spp runs side by side, 7 epochs: the same 150 MB per epoch, all of it
# right after an epoch's last step, i.e. in validation and checkpointing); the cause is not found.
CONF = "dirty_decay_ms:-1,muzzy_decay_ms:-1"


def find_jemalloc(candidates=CANDIDATES):
    """Path of an installed libjemalloc, or None."""
    return next((p for p in candidates if os.path.exists(p)), None)


def jemalloc_env(environ, library):
    """The environment to re-run with, or None when no re-run is wanted: ``library`` missing,
    already preloaded, or ``AFN_NO_JEMALLOC`` set to anything but 0/empty."""
    if not library or environ.get("AFN_NO_JEMALLOC", "0") not in ("", "0"):
        return None
    preload = environ.get("LD_PRELOAD", "")
    if "jemalloc" in preload:
        return None
    env = dict(environ)
    env["LD_PRELOAD"] = f"{library} {preload}".strip()
    env.setdefault("MALLOC_CONF", CONF)
    return env


def reexec(module, argv=None):
    """Replace this process by ``sys.executable -m module argv`` on jemalloc (see the module
    docstring); returns only when no re-run is wanted."""
    env = jemalloc_env(os.environ, find_jemalloc())
    if env is None:
        return
    args = sys.argv[1:] if argv is None else list(argv)
    sys.stdout.flush()
    sys.stderr.flush()
    os.execve(sys.executable, [sys.executable, "-m", module, *args], env)
