#!/usr/bin/env bash
# The pbrt-v4 importer checked image for image against pbrt-v4 itself (issue 33;
# docs/pbrt-import.md, docs/results.md): each feature scene of bench/pbrt/scenes/ (one
# material or light each, written in pbrt-v4's format with pbrt-v4's conventions: a plain
# LookAt, rgb colours, named glasses and metals, blackbody and named illuminants) is rendered
# by pbrt-v4 and, imported, by iris — the same integrator family (pbrt-v4's volpath and
# iris's path tracer, or both bdpt where the file says bdpt), 2 seeds each at SPP (default
# 1024) — and compared in 12x12-pixel regions (iris-image regions): the relative difference of
# each region's mean, per channel, iris's seed 1 against pbrt-v4's seed 1, and, for the noise,
# each renderer's seed 1 against its seed 2 (the same statistic between two renders that differ
# only by noise). Regions darker than 5 % of the image's mean are not compared.
#
# pbrt-v4 is not part of iris and never built by it: build it yourself beside iris
# (github.com/mmp/pbrt-v4, CMake Release, CPU only) and pass the binary. Needs a release
# build of iris (README command 2). About 10 min on 2 cores.
# Usage: PBRT=/path/to/pbrt bench/pbrt/import_check.sh [OUT=build/results-pbrt-import] [SPP=1024] [SCENE.pbrt ...]
# (every scene of bench/pbrt/scenes/ without SCENE arguments)
set -euo pipefail
trap 'echo "import_check.sh: line $LINENO failed (exit $?): $BASH_COMMAND" >&2' ERR
cd "$(dirname "$0")/../.."
: "${PBRT:?set PBRT to the pbrt-v4 binary}"
apps=$PWD/build/release/apps
out=${1:-build/results-pbrt-import}
spp=${2:-1024}
shift 2 2>/dev/null || shift $# || true
files=("$@")
[ ${#files[@]} -gt 0 ] || files=(bench/pbrt/scenes/*.pbrt)
mkdir -p "$out"
regions() { "$apps/iris-image/iris-image" regions "$1" "$2" --size 12 --floor 0.05; }

printf "%-16s %-8s %-22s %-52s %-52s %s\n" scene pbrt "pbrt / iris s" "iris vs pbrt" "noise: pbrt s1 vs s2" "noise: iris s1 vs s2"
for f in "${files[@]}"; do
  name=$(basename "$f" .pbrt)
  integ=$(grep -o 'Integrator "[a-z]*"' "$f" | cut -d'"' -f2)
  est=nee-mis
  [ "$integ" = bdpt ] && est=bdpt
  t=()
  for seed in 1 2; do
    log=$("$PBRT" --nthreads 2 --spp "$spp" --seed "$seed" --outfile "$out/$name-pbrt-s$seed.exr" "$f" 2>&1 | tr '\r' '\n')
    t+=("$(echo "$log" | grep -o '([0-9.]*s)' | tail -1 | tr -d '(s)')")
    r=$("$apps/iris-render/iris-render" "$f" --preset hwss --estimator "$est" --spp "$spp" --seed "$seed" --threads 2 \
      -o "$out/$name-iris-s$seed.exr" 2>/dev/null)
    t+=("$(echo "$r" | grep -o 'spp in [0-9.]* s' | awk '{print $3}')")
  done
  "$apps/iris-image/iris-image" convert "$out/$name-pbrt-s1.exr" -o "$out/$name-pbrt.png" > /dev/null
  "$apps/iris-image/iris-image" convert "$out/$name-iris-s1.exr" -o "$out/$name-iris.png" > /dev/null
  printf "%-16s %-8s %-22s %-52s %-52s %s\n" "$name" "$integ" "${t[0]} / ${t[1]}" \
    "$(regions "$out/$name-iris-s1.exr" "$out/$name-pbrt-s1.exr")" \
    "$(regions "$out/$name-pbrt-s2.exr" "$out/$name-pbrt-s1.exr")" \
    "$(regions "$out/$name-iris-s2.exr" "$out/$name-iris-s1.exr")"
done
