#!/usr/bin/env bash
# The byte-identity check of a refactoring: render every built-in scene with every preset
# and with the bsdf-only estimator (small: 96x96, 16 spp, N_thold 6, so that the passes
# before and after the relaxation both run; scenes with and without dispersive glass),
# then compare two such sets pixel by pixel.
#   bash scripts/same_images.sh render DIR        # with build/release (must be built)
#   bash scripts/same_images.sh compare DIR_A DIR_B
# `compare` prints every image whose pixels differ (max |a - b| > 0) and exits 1 if any do.
set -euo pipefail
cd "$(dirname "$0")/.."
bin=build/release/apps
render=$bin/iris-render/iris-render
image=$bin/iris-image/iris-image
case "${1:-}" in
render)
  dir=${2:?usage: same_images.sh render DIR}
  mkdir -p "$dir"
  scenes=$("$render" --list-scenes | awk '{print $1}')
  presets=$("$render" --list-presets | awk '{print $1}')
  n=0
  for s in $scenes; do
    common=(--spp 16 --nthold 6 --width 96 --height 96 --threads 2 --seed 7)
    "$render" "$s" "${common[@]}" --estimator bsdf-only -o "$dir/$s-bsdf-only.exr" >/dev/null
    n=$((n + 1))
    for p in $presets; do
      "$render" "$s" "${common[@]}" --preset "$p" -o "$dir/$s-$p.exr" >/dev/null
      n=$((n + 1))
    done
  done
  echo "$n images in $dir"
  ;;
compare)
  a=${2:?usage: same_images.sh compare DIR_A DIR_B} b=${3:?usage: same_images.sh compare DIR_A DIR_B}
  bad=0 n=0
  for f in "$a"/*.exr; do
    g="$b/$(basename "$f")"
    n=$((n + 1))
    if [ ! -f "$g" ]; then
      echo "missing: $g"
      bad=1
      continue
    fi
    m=$("$image" diff "$f" "$g" --json | /usr/bin/python3 -c 'import json,sys; print(json.load(sys.stdin)["max_abs"])')
    if [ "$m" != "0" ] && [ "$m" != "0.0" ]; then
      echo "differs: $(basename "$f") (max |a - b| = $m)"
      bad=1
    fi
  done
  [ $bad -eq 0 ] && echo "all $n images identical"
  exit $bad
  ;;
*)
  echo "usage: same_images.sh render DIR | compare DIR_A DIR_B" >&2
  exit 2
  ;;
esac
