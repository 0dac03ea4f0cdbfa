#!/usr/bin/env bash
# Reproduce docs/results.md: the paper's table (paper vs hwss) on falling-cubes,
# falling-cubes-led and rubik, the ablation over all presets on falling-cubes, the
# N_thold = 128 run, the bias maps, a time-equal run and the samplers' evaluation
# (scripts/results_samplers.sh). Each ablation writes
# DIR/{results.csv,summary.md,*.png,snapshots/}; the small outputs are copied to
# docs/results/<name>/. Needs a release build (README command 2).
# Wall-clock on the 2-core CI machine: about 45 min (two single-threaded ablations at a
# time), then ~3 min for the time-equal run, which must have the machine to itself.
set -euo pipefail
cd "$(dirname "$0")/.."
apps=build/release/apps
ablate=$apps/iris-ablate/iris-ablate
out=${1:-build/results}
common=(--spp 16,32,64,128,256,512 --reference-spp 16384 --seeds 3 --threads 1)
cubes=(--width 160 --height 120)
mkdir -p "$out"

"$ablate" falling-cubes --presets hwss,paper,paper-quadratic,box,gaussian,scaled-pdf,restrict-only \
  "${cubes[@]}" "${common[@]}" -o "$out/falling-cubes" &
{
  "$ablate" falling-cubes-led --presets hwss,paper "${cubes[@]}" "${common[@]}" -o "$out/falling-cubes-led"
  "$ablate" rubik --presets hwss,paper --width 128 --height 128 "${common[@]}" -o "$out/rubik"
  "$ablate" falling-cubes --presets hwss,paper --nthold 128 "${cubes[@]}" "${common[@]}" -o "$out/falling-cubes-nthold128"
} &
wait

# paper-fast against hwss, alone on 2 threads (its seconds column is quoted as a speed)
"$ablate" falling-cubes --presets hwss,paper-fast "${cubes[@]}" --spp 16,32,64,128,256,512 --reference-spp 16384 \
  --seeds 3 --threads 2 -o "$out/falling-cubes-fast"

# time-equal: both cores, nothing else running (its plots are SSIM/MSE against seconds)
"$ablate" falling-cubes --presets hwss,paper,paper-fast --spp 16 --time-budgets 0.5,1,2,4,8 "${cubes[@]}" \
  --reference-spp 16384 --seeds 3 --threads 2 -o "$out/falling-cubes-time"

# where the bias is: paper with α ≈ 0 on every sample against the cached reference
"$apps/iris-render/iris-render" falling-cubes --preset paper --nthold 1000000000 --spp 2048 "${cubes[@]}" \
  -o "$out/paper-alpha0.exr"
ref=$(ls -t "${XDG_CACHE_HOME:-$HOME/.cache}"/iris/falling-cubes-????????????????-160x120-ref16384-*.exr | head -1)  # the newest: this build's
mkdir -p docs/results/bias
"$apps/iris-image/iris-image" convert "$ref" -o docs/results/bias/reference.png
"$apps/iris-image/iris-image" convert "$out/paper-alpha0.exr" -o docs/results/bias/paper-alpha0.png
"$apps/iris-image/iris-image" error-map "$out/paper-alpha0.exr" "$ref" -o docs/results/bias/bias-alpha0.png

# the spp-equal runs shared the machine, so only the time-equal run's seconds plots are kept
for d in falling-cubes falling-cubes-led rubik falling-cubes-nthold128 falling-cubes-fast; do
  mkdir -p "docs/results/$d"
  cp "$out/$d"/{results.csv,summary.md,ssim_vs_spp.png,mse_vs_spp.png,crops_16spp.png} "docs/results/$d/"
done
mkdir -p docs/results/falling-cubes-time
cp "$out/falling-cubes-time"/{results.csv,results_time.csv,summary.md,ssim_vs_seconds.png,mse_vs_seconds.png} \
  docs/results/falling-cubes-time/
echo "copied to docs/results/"

# issue 12: the same evaluation with each sampler, one zsobol reference per scene, its noise
# ceiling, time-equal on falling-cubes (about 35 min more; docs/results/samplers.md)
bash scripts/results_samplers.sh "$out/samplers"
