#!/usr/bin/env bash
# The 65 536-spp falling-cubes reference's noise ceiling (issue 32): how long bdpt takes to
# reach the per-pixel variance of the path tracer's 65 536-spp `hwss` reference. Each
# estimator renders falling-cubes (`hwss`, Sobol', 160x120, 1024 spp) with 4 seeds; the
# seeds' spread gives each one's per-pixel variance at 1024 spp (`iris-image bias`,
# docs/metrics.md), and with variance ∝ 1/N the path tracer's reference has
# var_path(1024)·1024/65536, which bdpt reaches at N = 65536·var_bdpt(1024)/var_path(1024)
# spp. Seconds per spp from the renders' own statistics (render time, 2 threads). About
# 3 min on 2 cores, the machine to itself. Needs a release build (README command 2).
# Usage: scripts/results_ceiling.sh [OUT=build/results-ceiling]
set -euo pipefail
cd "$(dirname "$0")/.."
apps=build/release/apps
out=${1:-build/results-ceiling}
mkdir -p "$out"
spp=1024
declare -A var=() secs=()
for est in nee-mis bdpt; do
  files=()
  total=0
  for seed in 1 2 3 4; do
    f="$out/$est-seed$seed.exr"
    "$apps/iris-render/iris-render" falling-cubes --preset hwss --estimator "$est" --spp $spp --seed "$seed" \
      --sampler sobol --width 160 --height 120 --threads 2 -o "$f" --stats "$out/$est-seed$seed.json" > /dev/null 2>&1
    files+=("$f")
  done
  j=$("$apps/iris-image/iris-image" bias --json -r "${files[0]}" "${files[@]}")
  var[$est]=$(/usr/bin/python3 -c "import json,sys; print(json.loads(sys.argv[1])['variance'])" "$j")
  secs[$est]=$(/usr/bin/python3 -c "
import json,sys
t=[json.load(open(f))['seconds'] for f in sys.argv[1:]]
print(sum(t)/len(t))" "$out"/$est-seed*.json)
done
/usr/bin/python3 - "${var[nee-mis]}" "${var[bdpt]}" "${secs[nee-mis]}" "${secs[bdpt]}" $spp <<'PY'
import sys
vp, vb, sp, sb, n = map(float, sys.argv[1:])
ref = 65536
t_path = sp / n * ref
n_bdpt = ref * vb / vp
t_bdpt = sb / n * n_bdpt
print("| | path tracing | bdpt |")
print("|---|---|---|")
print(f"| per-pixel variance at {n:.0f} spp | {vp:.4g} | {vb:.4g} |")
print(f"| seconds for {n:.0f} spp | {sp:.2f} | {sb:.2f} |")
print(f"| spp to the 65 536-spp path-traced reference's variance | 65 536 | {n_bdpt:.0f} |")
print(f"| seconds to get there | {t_path:.0f} | {t_bdpt:.0f} (**{t_path / t_bdpt:.1f}× less**) |")
PY
