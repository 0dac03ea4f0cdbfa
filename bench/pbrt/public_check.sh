#!/usr/bin/env bash
# Public pbrt-v4 scenes (github.com/mmp/pbrt-v4-scenes), imported by iris and rendered by both
# renderers, compared region by region (issue 33; docs/results.md "Public pbrt-v4 scenes"). For
# each scene: a copy of its main file with the film made smaller (WIDTH, default 350 pixels across,
# the aspect kept) and the sample count given on the command line, written beside the original
# (Include paths are relative to the main file) and removed afterwards; pbrt-v4 (its volpath, the
# scene's sampler) and iris (`hwss`, Sobol'; its path tracer, or bdpt where the scene asks for
# pbrt-v4's bdpt) render it with seeds 1 and 2 at SPP
# (default 256); `iris-image regions` compares 20x20-pixel regions: iris s1 against pbrt-v4 s1,
# and each renderer's s1 against its s2 (the noise of the statistic). Speed: each renderer's own
# render time (set-up excluded) as samples per second, and iris's load time and peak memory
# (`iris-scene info` under /usr/bin/time).
#
# pbrt-v4 is not part of iris and never built by it: build it yourself (github.com/mmp/pbrt-v4,
# CMake Release, CPU only) and pass the binary; SCENES is a checkout of pbrt-v4-scenes (or the
# folders of it you have). Needs a release build of iris (README command 2). 2 threads each;
# give the machine to it alone for the times.
# Usage: PBRT=/path/to/pbrt SCENES=/path/to/pbrt-v4-scenes bench/pbrt/public_check.sh [OUT] [SPP] [SCENE.pbrt ...]
set -euo pipefail
trap 'echo "public_check.sh: line $LINENO failed (exit $?): $BASH_COMMAND" >&2' ERR
cd "$(dirname "$0")/../.."
: "${PBRT:?set PBRT to the pbrt-v4 binary}"
: "${SCENES:?set SCENES to a pbrt-v4-scenes checkout}"
apps=$PWD/build/release/apps
out=$(realpath -m "${1:-build/results-pbrt-public}")
spp=${2:-256}
width=${WIDTH:-350}
shift 2 2>/dev/null || shift $# || true
list=("$@")
[ ${#list[@]} -gt 0 ] || list=(killeroos/killeroo-simple.pbrt killeroos/killeroo-gold.pbrt killeroos/killeroo-coated-gold.pbrt)
mkdir -p "$out"
regions() { "$apps/iris-image/iris-image" regions "$1" "$2" --size 20 --floor 0.05; }

printf "%-22s %-9s %-7s %-20s %-26s %-44s %-44s %s\n" scene size spp "samples/s pbrt/iris" "iris load s, peak MiB" \
  "iris vs pbrt" "noise: pbrt s1 vs s2" "noise: iris s1 vs s2"
for rel in "${list[@]}"; do
  src="$SCENES/$rel"
  name=$(basename "$rel" .pbrt)
  copy="$(dirname "$src")/.$name.iris-compare.pbrt"
  trap 'rm -f "$copy"' EXIT
  # the film's resolution, scaled to WIDTH pixels across
  read -r w h < <(/usr/bin/python3 - "$src" <<'PY'
import re, sys
t = open(sys.argv[1]).read()
x = int(re.search(r'"integer xresolution"\s*\[?\s*(\d+)', t).group(1))
y = int(re.search(r'"integer yresolution"\s*\[?\s*(\d+)', t).group(1))
print(x, y)
PY
)
  nw=$width
  nh=$(( (h * width + w / 2) / w ))
  sed -E -e "s/(\"integer xresolution\"[[:space:]]*\[?[[:space:]]*)[0-9]+/\1$nw/" \
         -e "s/(\"integer yresolution\"[[:space:]]*\[?[[:space:]]*)[0-9]+/\1$nh/" "$src" > "$copy"
  # the same family of estimator: bdpt where the scene asks for pbrt-v4's bdpt, else path tracing
  est=nee-mis
  grep -q '^[[:space:]]*Integrator[[:space:]]*"bdpt"' "$src" && est=bdpt
  t=()
  for seed in 1 2; do
    log=$("$PBRT" --nthreads 2 --spp "$spp" --seed "$seed" --outfile "$out/$name-pbrt-s$seed.exr" "$copy" 2>&1 | tr '\r' '\n')
    t+=("$(echo "$log" | grep -o '([0-9.]*s)' | tail -1 | tr -d '(s)')")
    r=$("$apps/iris-render/iris-render" "$copy" --preset hwss --estimator "$est" --spp "$spp" --seed "$seed" --threads 2 \
      -o "$out/$name-iris-s$seed.exr" 2>"$out/$name-iris-s$seed.log")
    t+=("$(echo "$r" | grep -o 'spp in [0-9.]* s' | awk '{print $3}')")
  done
  /usr/bin/time -o "$out/$name-load.txt" -f '%e %M' "$apps/iris-scene/iris-scene" info "$copy" > /dev/null 2>&1
  load=$(tail -1 "$out/$name-load.txt")
  rm -f "$copy"
  "$apps/iris-image/iris-image" convert "$out/$name-pbrt-s1.exr" -o "$out/$name-pbrt.png" > /dev/null
  "$apps/iris-image/iris-image" convert "$out/$name-iris-s1.exr" -o "$out/$name-iris.png" > /dev/null
  px=$((nw * nh * spp))
  rate=$(/usr/bin/python3 -c "import sys; a,b=float(sys.argv[1]),float(sys.argv[2]); p=int(sys.argv[3]); print(f'{p/a/1e6:.2f}M / {p/b/1e6:.2f}M')" "${t[0]}" "${t[1]}" "$px")
  mem=$(echo "$load" | awk '{printf "%s, %.0f", $1, $2/1024}')
  printf "%-22s %-9s %-7s %-20s %-26s %-44s %-44s %s\n" "$name" "${nw}x${nh}" "$spp" "$rate" "$mem" \
    "$(regions "$out/$name-iris-s1.exr" "$out/$name-pbrt-s1.exr")" \
    "$(regions "$out/$name-pbrt-s2.exr" "$out/$name-pbrt-s1.exr")" \
    "$(regions "$out/$name-iris-s2.exr" "$out/$name-iris-s1.exr")"
done
