#!/usr/bin/env bash
# README command 1: install what is missing, build Release and run the demo.
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
