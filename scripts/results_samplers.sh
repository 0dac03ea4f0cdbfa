#!/usr/bin/env bash
# Issue 12's evaluation (docs/results.md, "Samplers"): the paper's table — hwss and paper on
# falling-cubes, falling-cubes-led and rubik at 16…512 spp, 3 seeds — once per sampler
# (independent, sobol, zsobol), every run of a scene against one reference (hwss, zsobol,
# REF_SPP spp), plus the noise ceiling of each reference (SSIM/MSE between it and a second
# reference with another seed) and a time-equal run on falling-cubes. Writes DIR/<scene>-<sampler>/
# (iris-ablate's outputs), DIR/<scene>-noise-ceiling.txt and DIR/samplers.md (the tables),
# and copies samplers.md to docs/results/samplers.md. Needs a release build.
#   bash scripts/results_samplers.sh [DIR=build/results-samplers]   (REF_SPP=8192 by default)
# Wall-clock on the 2-core VM of 2026-12-03: about 35 min; it must have the machine to itself
# (the seconds columns are quoted).
set -euo pipefail
cd "$(dirname "$0")/.."
apps=build/release/apps
ablate=$apps/iris-ablate/iris-ablate
render=$apps/iris-render/iris-render
image=$apps/iris-image/iris-image
out=${1:-build/results-samplers}
ref_spp=${REF_SPP:-8192}
mkdir -p "$out"

for entry in "falling-cubes 160 120" "falling-cubes-led 160 120" "rubik 128 128"; do
  read -r scene w h <<<"$entry"
  for sampler in independent sobol zsobol; do
    "$ablate" "$scene" --presets hwss,paper --sampler "$sampler" --reference-sampler zsobol \
      --reference-spp "$ref_spp" --spp 16,32,64,128,256,512 --seeds 3 --width "$w" --height "$h" --threads 2 \
      --cache "$out/cache" -o "$out/$scene-$sampler"
  done
  # the noise ceiling: the same reference with another seed
  "$render" "$scene" --preset hwss --sampler zsobol --spp "$ref_spp" --seed 2 --width "$w" --height "$h" \
    -o "$out/$scene-reference-seed2.exr" >/dev/null
  ref=$(ls "$out/cache/$scene"-????????????????-"${w}x${h}-ref${ref_spp}-zsobol-"*.exr | head -1)
  "$image" diff "$out/$scene-reference-seed2.exr" "$ref" >"$out/$scene-noise-ceiling.txt"
done

# time-equal on falling-cubes: both cores, nothing else running
for sampler in independent sobol zsobol; do
  "$ablate" falling-cubes --presets hwss,paper --sampler "$sampler" --reference-sampler zsobol \
    --reference-spp "$ref_spp" --spp 16 --time-budgets 0.5,1,2,4 --seeds 3 --width 160 --height 120 --threads 2 \
    --cache "$out/cache" -o "$out/falling-cubes-time-$sampler"
done

/usr/bin/python3 scripts/samplers_table.py "$out" >"$out/samplers.md"
mkdir -p docs/results
cp "$out/samplers.md" docs/results/samplers.md
echo "wrote $out/samplers.md and docs/results/samplers.md"
