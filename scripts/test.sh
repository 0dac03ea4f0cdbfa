#!/usr/bin/env bash
# README command 2 (and .ci/run): install what is missing, build the release preset and
# run the default test suite (every label except `long`), then build the `asan` preset
# (ASan + UBSan, -fno-sanitize-recover, leaks reported) and run the unit, statistical,
# integration, extreme and fuzz-replay labels under it. Any sanitizer report fails the run.
# IRIS_SKIP_ASAN=1 skips the second half (for a quick local check; CI never sets it).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/deps.sh
cmake --preset release >/dev/null
cmake --build --preset release
ctest --preset release
if [ "${IRIS_SKIP_ASAN:-0}" != 1 ]; then
  echo "== the same suite under AddressSanitizer + UndefinedBehaviorSanitizer (build/asan)"
  cmake --preset asan >/dev/null
  cmake --build --preset asan
  ctest --preset asan
fi
