#!/usr/bin/env bash
# MSE at equal spp and at equal time of two builds of iris-render (e.g. before and after a
# change to the integrator), against one reference rendered by the first build:
#   bash bench/scripts/compare_builds.sh BIN_A BIN_B OUT [SCENES] [PRESETS]
# BIN_* are iris-render executables; defaults: SCENES="falling-cubes cornell",
# PRESETS="hwss paper". Each scene: a 4096-spp hwss reference at 192x192 (seed 1000), then
# every build x preset at 64 spp with seeds 1..16, interleaved (A, B, A, B, ...) so that
# both see the same machine state. Prints, per scene and preset, for each build the mean
# MSE ± its standard error over the seeds, the mean seconds, and the equal-time MSE ratio
# B/A = (MSE_B t_B)/(MSE_A t_A) (Monte Carlo error ∝ 1/time, so this is the MSE B would
# reach in A's time, relative to A's). Uses iris-image from the directory of BIN_A.
set -euo pipefail
a=${1:?BIN_A} b=${2:?BIN_B} out=${3:?OUT}
scenes=${4:-falling-cubes cornell}
presets=${5:-hwss paper}
image=$(dirname "$(dirname "$a")")/iris-image/iris-image
size=(--width 192 --height 192)
mkdir -p "$out"
rm -f "$out/results.txt"
for s in $scenes; do
  ref=$out/$s-reference.exr
  [ -f "$ref" ] || "$a" "$s" "${size[@]}" --preset hwss --spp 4096 --seed 1000 -o "$ref" >/dev/null
  for p in $presets; do
    for seed in $(seq 1 16); do
      for side in A B; do
        bin=$a
        [ $side = B ] && bin=$b
        f=$out/$s-$p-$side-$seed
        "$bin" "$s" "${size[@]}" --preset "$p" --spp 64 --seed "$seed" -o "$f.exr" --stats "$f.json" >/dev/null
        mse=$("$image" diff "$f.exr" "$ref" --json | /usr/bin/python3 -c 'import json,sys; print(json.load(sys.stdin)["mse"])')
        secs=$(/usr/bin/python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["seconds"])' "$f.json")
        echo "$s $p $side $seed $mse $secs" >>"$out/results.txt"
      done
    done
  done
done
/usr/bin/python3 - "$out/results.txt" <<'PY'
import sys, statistics as st, collections
rows = collections.defaultdict(list)
for line in open(sys.argv[1]):
    s, p, side, seed, mse, secs = line.split()
    rows[(s, p, side)].append((float(mse), float(secs)))
print(f"{'scene':14} {'preset':7} {'MSE A':>22} {'MSE B':>22} {'B/A spp':>8} {'t A':>7} {'t B':>7} {'B/A time':>9}")
for (s, p) in sorted({(k[0], k[1]) for k in rows}):
    A, B = rows[(s, p, 'A')], rows[(s, p, 'B')]
    def m(v): return st.mean(x for x, _ in v), st.stdev(x for x, _ in v) / len(v) ** 0.5, st.mean(t for _, t in v)
    ma, ea, ta = m(A); mb, eb, tb = m(B)
    print(f"{s:14} {p:7} {ma:12.5g} ± {ea:<8.2g} {mb:12.5g} ± {eb:<8.2g} {mb/ma:8.3f} {ta:7.3f} {tb:7.3f} {mb*tb/(ma*ta):9.3f}")
PY
