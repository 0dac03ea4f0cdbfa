#!/usr/bin/env bash
# Issue 16, part 1 (docs/results.md, "Window placement"): hand-placed (`paper`) against
# automatic windows (`paper-auto`), with `hwss` as the baseline, on the four falling-cubes
# variants — D65, LED-B1, LED-RGB1 and the tabulated RGB laser — at 16…512 spp, 3 seeds,
# against one hwss reference of REF_SPP spp per scene (sobol). Writes DIR/<scene>/
# (iris-ablate's outputs) and copies the small ones to docs/results/placement/<scene>/.
#   bash scripts/results_placement.sh [DIR=build/results-placement]   (REF_SPP=4096)
# One thread (THREADS=1 by default), so the machine's other core stays free: the seconds
# columns are then not a speed measurement. Wall-clock on the 2-core VM: about 35 min.
set -euo pipefail
cd "$(dirname "$0")/.."
ablate=build/release/apps/iris-ablate/iris-ablate
out=${1:-build/results-placement}
ref_spp=${REF_SPP:-4096}
threads=${THREADS:-1}
mkdir -p "$out"
for scene in falling-cubes falling-cubes-led falling-cubes-rgb falling-cubes-laser; do
  "$ablate" "$scene" --presets hwss,paper,paper-auto --spp 16,32,64,128,256,512 --reference-spp "$ref_spp" \
    --seeds 3 --width 160 --height 120 --threads "$threads" --cache "$out/cache" -o "$out/$scene"
  mkdir -p "docs/results/placement/$scene"
  cp "$out/$scene"/{results.csv,summary.md,ssim_vs_spp.png,mse_vs_spp.png,crops_16spp.png} "docs/results/placement/$scene/"
done
echo "copied to docs/results/placement/"
