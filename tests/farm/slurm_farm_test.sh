#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# The farm job template against a real single-node Slurm started here: slurmctld + slurmd in a
# temporary directory with their own slurm.conf (127.0.0.1, free ports, auth/none so no munge
# daemon is needed), the job array of scripts/farm/afn-slurm.sbatch over examples/sequence (two
# chunks of 4 frames, preroll 4), its outputs compared pixel for pixel with one sequential afntool
# run. Exit 77 (ctest SKIP_RETURN_CODE) with the reason where Slurm cannot start; the daemons are
# stopped on every exit path and the whole test is bounded by a watchdog.
# Usage: slurm_farm_test.sh AFNTOOL SOURCE_DIR [METHOD]
set -uo pipefail
limit=${AFN_SLURM_TEST_LIMIT:-180} # seconds for the whole test (ctest's TIMEOUT is above it)
if [ -z "${AFN_SLURM_TEST_BOUNDED:-}" ]; then
  # The watchdog: TERM after the limit runs the cleanup trap below; KILL 20 s later at worst.
  AFN_SLURM_TEST_BOUNDED=1 exec timeout -k 20 "$limit" bash "$0" "$@"
fi
afntool=$1 src=$2 method=${3:-ta}
seq_dir=$src/examples/sequence

skip() { echo "SKIPPED: $*"; exit 77; }
fail() { echo "FAILED: $*"; exit 1; }

for tool in slurmctld slurmd sbatch squeue scontrol sinfo; do
  command -v "$tool" >/dev/null || skip "$tool not installed (scripts/setup.sh installs Slurm)"
done
py=/usr/bin/python3 # Debian's, with python3-openimageio and python3-numpy (scripts/setup.sh)
$py -c "import OpenImageIO, numpy" 2>/dev/null || skip "$py cannot import OpenImageIO and numpy"
[ "$(id -u)" -eq 0 ] || skip "slurmd launches jobs only when run as root"
[ -f "$seq_dir/frame.0007.exr" ] || skip "examples/sequence not rendered"

tmp=$(mktemp -d /tmp/afn-slurm.XXXXXX)
ctld_pid="" slurmd_pid="" job=""
# Processes holding a file of the temporary directory: the job steps' slurmstepd (its own
# session, parent init) and what it runs; listed by id, so nothing else on the machine is touched.
pids_in_tmp() {
  find /proc/[0-9]*/fd -maxdepth 1 -lname "$tmp/*" 2>/dev/null | cut -d/ -f3 | sort -u \
    | grep -vx $$
}
cleanup() {
  trap - EXIT INT TERM
  if [ -n "$job" ]; then
    timeout 5 scancel "$job" 2>/dev/null
    for _ in $(seq 10); do
      [ -z "$(timeout 2 squeue -h -j "$job" -o %i 2>/dev/null)" ] && break
      sleep 0.2
    done
  fi
  for pid in $slurmd_pid $ctld_pid; do kill -TERM "$pid" 2>/dev/null; done
  for _ in $(seq 30); do
    alive=0
    for pid in $slurmd_pid $ctld_pid; do kill -0 "$pid" 2>/dev/null && alive=1; done
    [ $alive -eq 0 ] && break
    sleep 0.1
  done
  for pid in $slurmd_pid $ctld_pid $(pids_in_tmp); do kill -KILL "$pid" 2>/dev/null; done
  rm -rf "$tmp"
}
trap cleanup EXIT
trap 'echo "FAILED: interrupted or over the ${limit} s limit"; exit 1' INT TERM
start_time=$SECONDS

logs() {
  for f in "$tmp"/slurmctld.log "$tmp"/slurmd.log "$tmp"/out/afn-denoise-*.log; do
    [ -f "$f" ] && { echo "--- tail of $f"; tail -n 15 "$f"; }
  done
}

# Free ports, one for each daemon (bound once by the kernel's choice, then released).
read -r ctld_port slurmd_port < <($py -c '
import socket
s = [socket.socket() for _ in range(2)]
for x in s: x.bind(("127.0.0.1", 0))
print(*[x.getsockname()[1] for x in s])')
mkdir -p "$tmp/state" "$tmp/spool" "$tmp/out"
export SLURM_CONF=$tmp/slurm.conf
cat >"$SLURM_CONF" <<EOF
ClusterName=afnfarm
SlurmctldHost=$(hostname -s)(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
AuthType=auth/none
CredType=cred/none
SlurmUser=root
SlurmdUser=root
StateSaveLocation=$tmp/state
SlurmdSpoolDir=$tmp/spool
SlurmctldPidFile=$tmp/slurmctld.pid
SlurmdPidFile=$tmp/slurmd.pid
SlurmctldLogFile=$tmp/slurmctld.log
SlurmdLogFile=$tmp/slurmd.log
ProctrackType=proctrack/pgid
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
MpiDefault=none
ReturnToService=2
MinJobAge=600
NodeName=afnfarm NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=afn Nodes=afnfarm Default=YES MaxTime=INFINITE State=UP
EOF

# Own sessions: timeout's TERM reaches this script's process group only, and the cleanup stops
# the daemons after cancelling the job (a controller gone first leaves scancel retrying).
setsid slurmctld -D -c -f "$SLURM_CONF" >"$tmp/slurmctld.out" 2>&1 &
ctld_pid=$!
setsid slurmd -D -N afnfarm -f "$SLURM_CONF" >"$tmp/slurmd.out" 2>&1 &
slurmd_pid=$!

# The sequential reference, run while the daemons start.
"$afntool" -q --frames 0-7 "$seq_dir/frame.####.exr" --denoise:method="$method" -d float \
  -o "$tmp/seq.####.exr" || fail "sequential afntool run"
echo "sequential run done after $((SECONDS - start_time)) s"

for _ in $(seq 300); do
  state=$(sinfo -h -n afnfarm -o %T 2>/dev/null)
  [ "$state" = idle ] && break
  if ! kill -0 "$ctld_pid" 2>/dev/null || ! kill -0 "$slurmd_pid" 2>/dev/null; then
    logs; cat "$tmp"/slurm*.out; skip "a Slurm daemon exited during start-up (logs above)"
  fi
  sleep 0.1
done
[ "$state" = idle ] || { logs; skip "the Slurm node did not become idle (state '$state')"; }
echo "slurm up after $((SECONDS - start_time)) s (ports $ctld_port, $slurmd_port)"

job=$("$src/scripts/farm/afn-farm-submit.sh" --frames 0-7 --chunk 4 --preroll 4 \
  --method "$method" --afntool "$afntool" --args "-d float" \
  "$seq_dir/frame.####.exr" "$tmp/out/chunk.####.exr" -- --chdir="$tmp/out") \
  || { logs; fail "sbatch refused the job array"; }
echo "job array $job submitted"
while [ -n "$(squeue -h -j "$job" -o %i 2>/dev/null)" ]; do
  sleep 0.2
done
states=$(scontrol show job "$job" 2>/dev/null | grep -o 'JobState=[A-Z_]*' | sort | uniq -c)
echo "array tasks after $((SECONDS - start_time)) s: $states"
task_count=$(scontrol show job "$job" | grep -c 'JobState=COMPLETED')
[ "$task_count" -eq 2 ] || { logs; fail "expected 2 COMPLETED array tasks"; }
cat "$tmp"/out/afn-denoise-*.log

for f in 0 1 2 3 4 5 6 7; do
  [ -f "$tmp/out/chunk.000$f.exr" ] || { logs; fail "frame $f not written by the job array"; }
done
# Pixel data compared bit for bit, in one process (one idiff per frame is slow on a loaded
# machine); frames 4 and 5 must differ, so the comparison can fail.
$py - "$tmp/seq.####.exr" "$tmp/out/chunk.####.exr" <<'PY' || fail "chunked and sequential outputs differ"
import sys
import numpy as np
import OpenImageIO as oiio

def bits(pattern, frame):
    buf = oiio.ImageBuf(pattern.replace("####", f"{frame:04d}"))
    if buf.has_error:
        sys.exit(f"cannot read frame {frame}: {buf.geterror()}")
    return np.ascontiguousarray(buf.get_pixels(oiio.FLOAT)).view(np.uint32)

seq, chunk = sys.argv[1], sys.argv[2]
bad = [f for f in range(8) if not np.array_equal(bits(seq, f), bits(chunk, f))]
if bad:
    sys.exit(f"frames {bad} of the chunked run differ from the sequential run")
if np.array_equal(bits(seq, 4), bits(chunk, 5)):
    sys.exit("frames 4 and 5 compare equal: the comparison cannot fail")
PY
echo "PASSED: 8 frames bit-identical to the sequential $method run in $((SECONDS - start_time)) s"
