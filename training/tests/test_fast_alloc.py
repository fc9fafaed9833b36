# SPDX-License-Identifier: Apache-2.0
"""afn.fast_alloc: training entry points re-run themselves on jemalloc when it is installed."""

import os
import subprocess
import sys

import pytest

from afn import fast_alloc

HERE = os.path.dirname(os.path.abspath(__file__))
TRAINING = os.path.dirname(HERE)


def test_env_preloads_the_library_and_keeps_other_preloads():
    env = fast_alloc.jemalloc_env({"LD_PRELOAD": "/x/libother.so", "PATH": "/bin"}, "/l/libjemalloc.so.2")
    assert env["LD_PRELOAD"] == "/l/libjemalloc.so.2 /x/libother.so"
    assert env["MALLOC_CONF"] == fast_alloc.CONF
    assert env["PATH"] == "/bin"


def test_a_user_malloc_conf_is_kept():
    env = fast_alloc.jemalloc_env({"MALLOC_CONF": "narenas:1"}, "/l/libjemalloc.so.2")
    assert env["MALLOC_CONF"] == "narenas:1"


@pytest.mark.parametrize("environ, library", [
    ({}, None),                                                  # not installed
    ({"LD_PRELOAD": "/l/libjemalloc.so.2"}, "/l/libjemalloc.so.2"),  # already running on it
    ({"AFN_NO_JEMALLOC": "1"}, "/l/libjemalloc.so.2"),            # switched off
])
def test_no_rerun(environ, library):
    assert fast_alloc.jemalloc_env(environ, library) is None


def test_find_returns_the_first_existing_candidate(tmp_path):
    lib = tmp_path / "libjemalloc.so.2"
    lib.write_bytes(b"")
    assert fast_alloc.find_jemalloc([str(tmp_path / "missing.so"), str(lib)]) == str(lib)
    assert fast_alloc.find_jemalloc([str(tmp_path / "missing.so")]) is None


@pytest.mark.skipif(fast_alloc.find_jemalloc() is None, reason="libjemalloc2 is not installed")
def test_the_rerun_process_has_jemalloc_mapped_and_the_same_arguments(tmp_path):
    # A module that re-runs itself, then reports what the new process has mapped and received.
    env = {k: v for k, v in os.environ.items() if k not in ("LD_PRELOAD", "AFN_NO_JEMALLOC")}
    env["PYTHONPATH"] = TRAINING
    code = ("import sys\nfrom afn import fast_alloc\nfast_alloc.reexec('afn_probe_main', sys.argv[1:])\n"
            "maps = open('/proc/self/maps').read()\n"
            "print('jemalloc' in maps, sys.argv[1:])\n")
    (tmp_path / "afn_probe_main.py").write_text(code)
    out = subprocess.run([sys.executable, "-m", "afn_probe_main", "a b", "--c"], cwd=tmp_path, env=env,
                         capture_output=True, text=True, timeout=60)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "True ['a b', '--c']"
