#!/usr/bin/env bash
# pbrt-v4's own bdpt on iris's falling-cubes at about equal render time (issue 32): the scene
# written in pbrt-v4's format by make_falling_cubes.py (160x120, maxdepth 32, zsobol), a
# 4096-spp pbrt reference, then 13, 27, 53 and 107 spp (about 0.6, 1.2, 2.3 and 4.7 s of
# pbrt's render time on 2 threads here), 3 seeds each, relMSE against pbrt's own reference
# with iris-image (docs/metrics.md). Efficiency = 1 / (relMSE x render seconds), compared
# with iris's from scripts/results_bdpt.sh (each renderer against its own reference:
# relMSE does not depend on the two renderers' different exposure).
#
# pbrt-v4 is not part of iris and never built by it: build it yourself beside iris
# (github.com/mmp/pbrt-v4, `git clone --recursive`, CMake Release, CPU only) and pass the
# binary. About 7 min on 2 cores (the reference is 5 of them).
# Usage: PBRT=/path/to/pbrt bench/pbrt/equal_time.sh [OUT=build/results-pbrt]
set -euo pipefail
cd "$(dirname "$0")/../.."
: "${PBRT:?set PBRT to the pbrt-v4 binary}"
img=$PWD/build/release/apps/iris-image/iris-image
out=${1:-build/results-pbrt}
mkdir -p "$out"
python3 bench/pbrt/make_falling_cubes.py --spp 64 > "$out/falling-cubes.pbrt"
[ -f "$out/ref-4096.exr" ] || "$PBRT" --nthreads 2 --spp 4096 --seed 99 --outfile "$out/ref-4096.exr" "$out/falling-cubes.pbrt" > /dev/null 2>&1
echo "spp,seed,seconds,mse,relmse,ssim"
for spp in 13 27 53 107; do
  for seed in 1 2 3; do
    f="$out/fc-$spp-s$seed.exr"
    log=$("$PBRT" --nthreads 2 --spp $spp --seed $seed --outfile "$f" "$out/falling-cubes.pbrt" 2>&1 | tr '\r' '\n')
    secs=$(echo "$log" | grep -o '([0-9.]*s)' | tail -1 | tr -d '(s)')  # pbrt's render time (its progress bar)
    d=$("$img" diff --json "$f" "$out/ref-4096.exr")
    /usr/bin/python3 -c "import json,sys; d=json.loads(sys.argv[1]); print(f\"$spp,$seed,$secs,{d['mse']},{d['relmse']},{d['ssim']}\")" "$d"
  done
done
