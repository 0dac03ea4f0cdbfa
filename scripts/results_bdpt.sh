#!/usr/bin/env bash
# Reproduce docs/results.md's "Bidirectional path tracing" section (issue 32): path tracing
# against bdpt, `hwss` and `paper`, against references rendered with bdpt.
#  1. falling-cubes 160x120, time-equal (0.5-8 s, 3 seeds) and equal-spp (16-512, the
#     paper's table, 3 seeds), each estimator against one bdpt reference (8192 spp);
#  2. falling-cubes-led, rubik, prism and cornell, time-equal (1, 2, 4 s, 2 seeds) against
#     bdpt references of 4096 spp;
#  3. the 16-spp images side by side.
# Every ablation uses both cores and must have the machine to itself (its seconds are the
# measurement). About 35 min on 2 cores. Needs a release build (README command 2).
# Usage: scripts/results_bdpt.sh [OUT=build/results-bdpt] [--quick: falling-cubes only]
set -euo pipefail
cd "$(dirname "$0")/.."
apps=build/release/apps
ablate=$apps/iris-ablate/iris-ablate
render=$apps/iris-render/iris-render
out=${1:-build/results-bdpt}
quick=${2:-}
mkdir -p "$out" docs/results/bdpt

cubes=(--width 160 --height 120)
for est in nee-mis bdpt; do
  "$ablate" falling-cubes --presets hwss,paper --spp 16 --time-budgets 0.5,1,2,4,8 "${cubes[@]}" \
    --estimator "$est" --reference-estimator bdpt --reference-spp 8192 --seeds 3 --threads 2 \
    -o "$out/falling-cubes-time-$est"
  "$ablate" falling-cubes --presets hwss,paper --spp 16,32,64,128,256,512 "${cubes[@]}" \
    --estimator "$est" --reference-estimator bdpt --reference-spp 8192 --seeds 3 --threads 2 \
    -o "$out/falling-cubes-spp-$est"
done

if [ "$quick" != "--quick" ]; then
  for scene in falling-cubes-led rubik prism cornell; do
    size=(--width 160 --height 120)
    [ "$scene" = rubik ] && size=(--width 128 --height 128)
    for est in nee-mis bdpt; do
      "$ablate" "$scene" --presets hwss,paper --spp 16 --time-budgets 1,2,4 "${size[@]}" \
        --estimator "$est" --reference-estimator bdpt --reference-spp 4096 --seeds 2 --threads 2 \
        -o "$out/$scene-time-$est"
    done
  done
fi

# the 16-spp images of seed 1, both estimators, hwss and paper
for est in nee-mis bdpt; do
  for p in hwss paper; do
    "$apps/iris-image/iris-image" convert "$out/falling-cubes-spp-$est/snapshots/$p-seed1-16spp.exr" \
      -o "docs/results/bdpt/falling-cubes-$p-$est-16spp.png"
  done
  cp "$out/falling-cubes-time-$est/summary.md" "docs/results/bdpt/falling-cubes-time-$est.md"
  cp "$out/falling-cubes-spp-$est/summary.md" "docs/results/bdpt/falling-cubes-spp-$est.md"
  cp "$out/falling-cubes-spp-$est/ssim_vs_spp.png" "docs/results/bdpt/falling-cubes-ssim-vs-spp-$est.png"
done
echo "copied to docs/results/bdpt/"
