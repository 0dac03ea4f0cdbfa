#!/usr/bin/env bash
# Cost of bdpt against the path tracer, every preset (issue 32): samples/s and rays/s as
# iris-render reports them (render time only; falling-cubes 160x120, 32 spp, 2 threads, one
# run each), and peak memory (maximum resident set, /usr/bin/time) with 1 and 2 threads —
# the difference is one thread's workspaces. The machine to itself; about 2 min on 2 cores.
# Prints two markdown tables. Needs a release build (README command 2).
# Usage: scripts/results_cost.sh [OUT=build/results-cost]
set -euo pipefail
cd "$(dirname "$0")/.."
render=build/release/apps/iris-render/iris-render
out=${1:-build/results-cost}
mkdir -p "$out"
stat() { /usr/bin/python3 -c "import json,sys; d=json.load(open(sys.argv[1])); print(f\"{d['samples_per_second']/1e6:.2f} | {d['rays_per_second']/1e6:.2f}\")" "$1"; }
echo "| preset | path: M samples/s | path: M rays/s | bdpt: M samples/s | bdpt: M rays/s |"
echo "|---|---|---|---|---|"
for p in $("$render" --list-presets | awk '{print $1}'); do
  row="| \`$p\`"
  for est in nee-mis bdpt; do
    "$render" falling-cubes --preset "$p" --estimator "$est" --spp 32 --width 160 --height 120 --threads 2 \
      --sampler sobol -o "$out/$p-$est.exr" --stats "$out/$p-$est.json" > /dev/null 2>&1
    row="$row | $(stat "$out/$p-$est.json")"
  done
  echo "$row |"
done
echo
echo "| estimator | peak memory, 1 thread | 2 threads | per thread |"
echo "|---|---|---|---|"
for est in nee-mis bdpt; do
  kb=()
  for t in 1 2; do
    /usr/bin/time -f "%M" -o "$out/mem-$est-$t.txt" "$render" falling-cubes --preset paper --estimator "$est" --spp 16 \
      --width 160 --height 120 --threads $t -o "$out/mem-$est-$t.exr" > /dev/null 2>&1
    kb+=("$(tail -1 "$out/mem-$est-$t.txt")")
  done
  /usr/bin/python3 -c "import sys; a,b=map(int,sys.argv[2:]); print(f'| {sys.argv[1]} | {a/1024:.1f} MiB | {b/1024:.1f} MiB | {(b-a)/1024:.2f} MiB |')" "$est" "${kb[@]}"
done
