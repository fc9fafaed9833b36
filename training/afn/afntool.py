# SPDX-License-Identifier: Apache-2.0
"""Running the C++ command-line tool from the toolkit.

The toolkit never re-implements what the C++ library does: reading renderers' files (AOV role
mapping), input preparation (demodulation, temporal accumulation, feature scaling), denoising and
metrics all go through ``afntool``.
"""

import glob
import os
import subprocess

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


class AfntoolError(RuntimeError):
    """afntool is missing or exited with an error (the message holds its error line)."""


def find_afntool():
    """$AFNTOOL, else the newest ``build*/cli/afntool`` of this repository, else None."""
    env = os.environ.get("AFNTOOL")
    if env:
        return env
    found = [p for p in glob.glob(os.path.join(REPO, "build*", "cli", "afntool"))
             if os.path.isfile(p) and os.access(p, os.X_OK)]
    return max(found, key=os.path.getmtime) if found else None


def require_afntool():
    """The afntool path; raises :class:`AfntoolError` with what to do when there is none."""
    path = find_afntool()
    if not path or not os.path.isfile(path):
        raise AfntoolError("afntool not found: build it (bash scripts/build.sh) or set $AFNTOOL")
    return path


def error_text(stderr):
    """afntool's own error line(s), else the last line of its stderr."""
    lines = [ln for ln in (stderr or "").splitlines() if ln.strip()]
    errors = [ln for ln in lines if ln.startswith("afntool ERROR")]
    return "; ".join(errors) if errors else (lines[-1] if lines else "no message")


def run(args, afntool=None):
    """Run ``afntool ARGS`` and return its stdout; raises :class:`AfntoolError` on failure."""
    cmd = [afntool or require_afntool()] + [str(a) for a in args]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        raise AfntoolError(f"afntool exited with {p.returncode}: {error_text(p.stderr)}")
    return p.stdout


def frame_list(numbers):
    """afntool --frames syntax for frame numbers: A-B when contiguous, else a comma list."""
    n = [int(x) for x in numbers]
    if n == list(range(n[0], n[0] + len(n))):
        return f"{n[0]}-{n[-1]}"
    return ",".join(str(x) for x in n)
