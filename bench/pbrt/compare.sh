#!/usr/bin/env bash
# iris's bdpt against pbrt-v4's own bdpt on the same scenes at about equal render time
# (issue 32; docs/results.md). Each scene is written for pbrt-v4 by `iris-scene export --pbrt`
# (docs/pbrt-export.md: iris's own spectra inline, lights scaled to iris's radiance), so both
# renderers render the same function and one reference serves both:
#  1. per scene, a 4096-spp reference by iris's bdpt (seed 99), common to both renderers;
#  2. each renderer's speed from a 16-spp run, then renders of about 0.5, 1, 2 and 4 s of its
#     render time (its own report: parsing and set-up excluded for both), 3 seeds;
#  3. relMSE and SSIM of every image against the common reference; efficiency =
#     1 / (relMSE x seconds); and the 4-s seeds' error split into variance and squared bias
#     (iris-image bias): pbrt-v4's bias against iris's reference says whether the export is
#     faithful and the renderers agree, iris's shows the reference's own noise floor.
# iris runs `hwss` (unbiased) with its Sobol' sampler; pbrt-v4 its zsobol sampler, box filter;
# the same max depth (MAXDEPTH, default 32: pbrt-v4's bdpt has no Russian roulette and traces
# every subpath to it, iris's stops paths by roulette — both are unbiased).
# Everything runs on 2 threads and must have the machine to itself. About 20 min on 2 cores.
#
# pbrt-v4 is not part of iris and never built by it: build it yourself beside iris
# (github.com/mmp/pbrt-v4, `git clone --recursive`, CMake Release, CPU only) and pass the
# binary. Needs a release build of iris (README command 2).
# Usage: PBRT=/path/to/pbrt bench/pbrt/compare.sh [OUT=build/results-pbrt-compare] [SCENE ...]
set -euo pipefail
trap 'echo "compare.sh: line $LINENO failed (exit $?): $BASH_COMMAND" >&2' ERR
cd "$(dirname "$0")/../.."
: "${PBRT:?set PBRT to the pbrt-v4 binary}"
apps=$PWD/build/release/apps
render=$apps/iris-render/iris-render
img=$apps/iris-image/iris-image
out=${1:-build/results-pbrt-compare}
depth=${MAXDEPTH:-32}
shift || true
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(falling-cubes falling-cubes-led rubik prism cornell)
mkdir -p "$out"

size() { if [ "$1" = rubik ]; then echo "128 128"; else echo "160 120"; fi; }
# pbrt's render time: the last "(N.Ns)" of its progress bar
pbrt_run() {  # scene spp seed out.exr -> seconds
  "$PBRT" --nthreads 2 --spp "$2" --seed "$3" --outfile "$4" "$out/$1.pbrt" 2>&1 | tr '\r' '\n' |
    grep -o '([0-9.]*s)' | tail -1 | tr -d '(s)'
}
iris_run() {  # scene spp seed out.exr -> seconds
  read -r w h < <(size "$1")
  "$render" "$1" --preset hwss --estimator bdpt --width "$w" --height "$h" --spp "$2" --seed "$3" --threads 2 \
    --max-depth "$depth" \
    -o "$4" 2>&1 | grep -o 'spp in [0-9.]* s' | tail -1 | awk '{print $3}'
}
field() { /usr/bin/python3 -c "import json,sys; print(json.loads(sys.argv[1])[sys.argv[2]])" "$1" "$2"; }

echo "scene,renderer,spp,seed,seconds,relmse,ssim"
for scene in "${scenes[@]}"; do
  read -r w h < <(size "$scene")
  "$apps/iris-scene/iris-scene" export "$scene" -o "$out/$scene.pbrt" --integrator bdpt --spp 64 \
    --max-depth "$depth" --width "$w" --height "$h" > /dev/null
  ref="$out/$scene-d$depth-ref.exr"
  [ -f "$ref" ] || iris_run "$scene" 4096 99 "$ref" > /dev/null
  for r in pbrt iris; do
    t16=$(${r}_run "$scene" 16 7 "$out/$scene-$r-speed.exr")
    for budget in 0.5 1 2 4; do
      spp=$(/usr/bin/python3 -c "print(max(1, round(16 * $budget / $t16)))")
      # pbrt-v4's zsobol renders 2^floor(log2 spp) samples (its SamplesPerPixel): report those
      shown=$spp
      [ "$r" = pbrt ] && shown=$(/usr/bin/python3 -c "print(1 << ($spp.bit_length() - 1))")
      for seed in 1 2 3; do
        f="$out/$scene-$r-$budget-s$seed.exr"
        secs=$(${r}_run "$scene" "$spp" "$seed" "$f")
        d=$("$img" diff --json "$f" "$ref")
        echo "$scene,$r,$shown,$seed,$secs,$(field "$d" relmse),$(field "$d" ssim)"
      done
    done
    echo "# $scene $r 4 s, bias split against the reference: $("$img" bias --json "$out/$scene-$r-4-s"{1,2,3}.exr -r "$ref" | tr -d '\n ')"
  done
done
