#!/usr/bin/env bash
# Set up, build and run every test: ctest (C++ unit, API, integration) and the training toolkit's tests.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh --torch
bash scripts/build.sh
(cd build && ctest --output-on-failure -j"${AFN_JOBS:-2}")
if [ -d training/tests ]; then
  /usr/bin/python3 -m pytest -q training/tests
fi
