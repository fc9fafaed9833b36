#!/usr/bin/env bash
# Install the Debian packages afn needs (only what is missing).
# Usage: scripts/setup.sh [--blender] [--torch] [--sanitizers]
set -euo pipefail
pkgs=(cmake g++ make pkg-config libopenimageio-dev openimageio-tools libopencolorio-dev
      opencolorio-tools libopenexr-dev libimath-dev libtbb-dev libdnnl-dev libgtest-dev libgmock-dev
      libbenchmark-dev clang-format python3-numpy python3-openimageio python3-pytest python3-skimage
      slurmctld slurmd slurm-client) # Slurm: the farm job template's test (tests/farm, docs/farm.md)
for arg in "$@"; do
  case "$arg" in
    --blender) pkgs+=(blender) ;;
    --torch) pkgs+=(python3-torch libjemalloc2) ;; # jemalloc: training steps, afn/fast_alloc.py
    --sanitizers) pkgs+=(clang libclang-rt-14-dev) ;; # ASan/UBSan build and libFuzzer targets
  esac
done
missing=()
for p in "${pkgs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "afn setup: installing ${missing[*]}"
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO=sudo
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
