#!/usr/bin/env bash
# How much of bdpt's remaining error the camera-only paths carry (issue 32): the paths no
# strategy but a camera path that hits the light can make, through a non-delta vertex
# (specular–diffuse–specular: a caustic seen through glass). Each scene is rendered by bdpt
# (`hwss`, Sobol', 160x120, 256 spp, 4 seeds) three times per seed — all paths, the
# camera-only ones, the rest (`iris-render --paths`; with the same seed the two parts sum to
# the whole) — and each image's per-pixel variance is estimated from the seeds' spread
# (`iris-image bias`, docs/metrics.md). Prints one markdown table. About 6 min on 2 cores.
# Needs a release build (README command 2). Usage: scripts/results_sds.sh [OUT=build/results-sds]
set -euo pipefail
cd "$(dirname "$0")/.."
apps=build/release/apps
out=${1:-build/results-sds}
mkdir -p "$out"
spp=256
seeds=(1 2 3 4)
echo "| scene | variance, all paths | camera-only paths | the rest | camera-only / all |"
echo "|---|---|---|---|---|"
for scene in falling-cubes falling-cubes-led rubik prism cornell; do
  size=(--width 160 --height 120)
  [ "$scene" = rubik ] && size=(--width 128 --height 128)
  declare -A var=()
  for paths in all camera-only rest; do
    files=()
    for seed in "${seeds[@]}"; do
      f="$out/$scene-$paths-seed$seed.exr"
      "$apps/iris-render/iris-render" "$scene" --preset hwss --estimator bdpt --paths "$paths" --spp $spp \
        --seed "$seed" --sampler sobol "${size[@]}" --threads 2 -o "$f" > /dev/null 2>&1
      files+=("$f")
    done
    # the variance part does not depend on the reference: the first seed of all paths stands in
    j=$("$apps/iris-image/iris-image" bias --json -r "$out/$scene-all-seed1.exr" "${files[@]}")
    var[$paths]=$(/usr/bin/python3 -c "import json,sys; print(json.loads(sys.argv[1])['variance'])" "$j")
  done
  /usr/bin/python3 - "$scene" "${var[all]}" "${var[camera-only]}" "${var[rest]}" <<'PY'
import sys
scene, va, vc, vr = sys.argv[1], float(sys.argv[2]), float(sys.argv[3]), float(sys.argv[4])
print(f"| {scene} | {va:.4g} | {vc:.4g} | {vr:.4g} | **{vc / va:.0%}** |")
PY
  unset var
done
