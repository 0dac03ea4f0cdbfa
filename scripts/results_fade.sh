#!/usr/bin/env bash
# Issue 16, part 2 (docs/results.md, "Bias fade"): the running mean (`paper`) against the
# MSE-optimal blend (`paper-fade`), with `hwss` as the baseline, at the paper's N_thold = 512,
# 16…4096 spp (2·N_thold = 1024 and 8·N_thold inside the run), 3 seeds, against one
# 16384-spp `hwss` reference per scene (sobol). Scenes: the dispersive built-ins under D65 and
# LED-B1 (falling-cubes, falling-cubes-led, rubik) and the two spiky ones (falling-cubes-rgb,
# falling-cubes-laser), where `paper-auto-fade` is measured too. Equal time: the seconds
# columns and the *_vs_seconds plots, so run it on an otherwise idle machine.
#   bash scripts/results_fade.sh [DIR=build/results-fade]   (REF_SPP=16384 THREADS=0 SPP=...)
# Wall-clock on the 2-core VM with both threads (AVX-512): about 50 min (12 of it references).
set -euo pipefail
cd "$(dirname "$0")/.."
ablate=build/release/apps/iris-ablate/iris-ablate
out=${1:-build/results-fade}
ref_spp=${REF_SPP:-16384}
threads=${THREADS:-0}
spp=${SPP:-16,32,64,128,256,512,1024,2048,4096}
mkdir -p "$out"
# SCENES="prism cornell" for the other two built-ins with glass (the second run in results.md)
for scene in ${SCENES:-falling-cubes falling-cubes-led rubik falling-cubes-rgb falling-cubes-laser}; do
  presets=hwss,paper,paper-fade
  case "$scene" in falling-cubes-rgb|falling-cubes-laser) presets+=,paper-auto-fade ;; esac
  "$ablate" "$scene" --presets "$presets" --nthold 512 --spp "$spp" --reference-spp "$ref_spp" \
    --seeds 3 --width 160 --height 120 --threads "$threads" --cache "$out/cache" -o "$out/$scene"
  mkdir -p "docs/results/fade/$scene"
  cp "$out/$scene"/{results.csv,summary.md,ssim_vs_spp.png,mse_vs_spp.png,ssim_vs_seconds.png,mse_vs_seconds.png} \
    "docs/results/fade/$scene/"
done
echo "copied to docs/results/fade/"
