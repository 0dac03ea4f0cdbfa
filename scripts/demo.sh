#!/usr/bin/env bash
# README command 1: install what is missing, build Release and run the demo:
#   1. the XYZ / sRGB of the illuminants compiled into iris, and a plot of their SPDs;
#   2. falling-cubes at 16 spp with the baseline `hwss` and the method `paper`, by path tracing
#      and by bidirectional path tracing (the caustics under the cubes without fireflies);
#   3. a quick ablation (falling-cubes, small, 16-64 spp, short reference): SSIM table + plots.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/deps.sh
cmake --preset release >/dev/null
cmake --build --preset release
bin=build/release/apps
out=build/demo
mkdir -p "$out"

echo
echo "== XYZ (Y = 1) and linear sRGB of the illuminants compiled into iris =="
names=(D65 A LED-B1 LED-B2 LED-B3 LED-B4 LED-B5 LED-BH1 LED-RGB1 LED-V1 LED-V2)
for n in "${names[@]}"; do
  printf '%-9s %s\n' "$n" "$("$bin/iris-spectrum/iris-spectrum" xyz "$n")"
done
"$bin/iris-spectrum/iris-spectrum" plot "${names[@]}" -o "$out/illuminants.png"

if [ -x "$bin/iris-render/iris-render" ]; then
  echo
  echo "== falling-cubes at 16 spp: hwss (baseline) and paper (restrict + relax + propagate) =="
  for p in hwss paper; do
    "$bin/iris-render/iris-render" falling-cubes --preset "$p" --spp 16 -o "$out/falling-cubes-$p-16spp.exr" \
      --png "$out/falling-cubes-$p-16spp.png"
  done
  echo "== the same by bidirectional path tracing (--estimator bdpt) =="
  for p in hwss paper; do
    "$bin/iris-render/iris-render" falling-cubes --preset "$p" --spp 16 --estimator bdpt \
      -o "$out/falling-cubes-$p-bdpt-16spp.exr" --png "$out/falling-cubes-$p-bdpt-16spp.png"
  done
fi
if [ -x "$bin/iris-ablate/iris-ablate" ]; then
  echo
  echo "== quick ablation: falling-cubes 160x120, 16-64 spp, 1024 spp reference =="
  "$bin/iris-ablate/iris-ablate" falling-cubes --presets hwss,paper,paper-fast --spp 16,32,64 --reference-spp 1024 \
    --width 160 --height 120 --seeds 2 -o "$out/ablation"
fi
echo
echo "demo outputs in $out/"
