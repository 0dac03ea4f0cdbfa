#!/usr/bin/env bash
# The paper's headline numbers as a regression test (label `long`, ~1–2 min on 2 cores):
#   paper_targets_test.sh IRIS_ABLATE WORK_DIR
# falling-cubes at 160×120, hwss and paper at 16 spp, 3 seeds, against a 4096-spp hwss
# reference (docs/results.md uses 16384; at 16 spp the reference's own noise is 1/256 of
# the estimates'). Targets of the evaluation issue: the SSIM gain of paper over hwss at
# 16 spp ≥ +10 %, and paper's MSE not above hwss's by more than 10 %. Measured: +44 %
# and −87 %; the per-seed spread of SSIM is ≈ 0.002 (under 1 % of the gain), so a failure
# means a regression, not noise. A broken B term (restrict-only's behaviour) gives ≈ +18 %
# and a wrong MIS weight or bias policy moves the MSE by far more than 10 %.
set -u
ablate=$1 work=$2
fail() { echo "FAIL: $*" >&2; [ -f "$work/stderr.txt" ] && head -c 3000 "$work/stderr.txt" >&2; exit 1; }
rm -rf "$work/out" && mkdir -p "$work" || fail "cannot create $work"
"$ablate" falling-cubes --presets hwss,paper --spp 16 --reference-spp 4096 --seeds 3 --width 160 --height 120 \
  --cache "$work/cache" -o "$work/out" >"$work/stdout.txt" 2>"$work/stderr.txt" || fail "iris-ablate exited $?"
csv=$work/out/results.csv
[ -f "$csv" ] || fail "no results.csv"
awk -F, 'NR > 1 && $5 == 16 { ssim[$2] += $9; mse[$2] += $7; n[$2]++ }
  END {
    if (n["hwss"] != 3 || n["paper"] != 3) { print "expected 3 rows per preset" > "/dev/stderr"; exit 1 }
    gain = ssim["paper"] / ssim["hwss"] - 1; ratio = mse["paper"] / mse["hwss"]
    printf "SSIM gain of paper at 16 spp: %+.1f %%; MSE paper / hwss: %.3f\n", 100 * gain, ratio
    if (gain < 0.10) { print "SSIM gain below +10 %" > "/dev/stderr"; exit 1 }
    if (ratio > 1.10) { print "MSE more than 10 % above hwss" > "/dev/stderr"; exit 1 }
  }' "$csv" || fail "targets not met"
