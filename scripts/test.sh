#!/usr/bin/env bash
# README command 2 (and .ci/run): install what is missing, build the release preset and
# run the default test suite (every label except `long`).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/deps.sh
cmake --preset release >/dev/null
cmake --build --preset release
ctest --preset release
