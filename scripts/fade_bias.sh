#!/usr/bin/env bash
# Issue 16: how much of each preset's error is bias, after scripts/results_fade.sh. For every
# scene, preset and spp from 512 on, `iris-image bias` splits the MSE of the 3 seeds'
# snapshots against the scene's 16384-spp reference into variance and squared bias
# (docs/metrics.md). The reference's own noise is in every bias_sq; `hwss` is unbiased, so
# its bias_sq measures that noise and a preset's own squared bias is the difference.
# Writes a markdown table per scene to docs/results/fade/bias.md.
#   bash scripts/fade_bias.sh [DIR=build/results-fade]
set -euo pipefail
cd "$(dirname "$0")/.."
image=build/release/apps/iris-image/iris-image
dir=${1:-build/results-fade}
out=docs/results/fade/bias.md
{
  echo "# Bias and variance of the fade measurement"
  echo
  echo "Written by \`scripts/fade_bias.sh\` from the snapshots of \`scripts/results_fade.sh\` (3 seeds,"
  echo "160×120, N_thold = 512, 16384-spp \`hwss\` reference). Per scene, preset and spp: the mean MSE of"
  echo "the seeds, one run's variance and the squared bias (with the reference's noise), ± its standard"
  echo "error; *excess* is bias_sq minus \`hwss\`'s at the same spp — the preset's own squared bias — and"
  echo "how many standard errors of the difference it is."
  for scene_dir in "$dir"/*/; do
    scene=$(basename "$scene_dir")
    [ -d "$scene_dir/snapshots" ] || continue
    ref=$(ls "$dir"/cache/"$scene"-????????????????-160x120-ref16384-*.exr 2>/dev/null | head -1 || true)
    [ -n "$ref" ] || { echo "no reference for $scene" >&2; continue; }
    echo
    echo "## $scene"
    echo
    echo "| spp | preset | MSE | variance | bias² (± se) | excess over hwss |"
    echo "|---|---|---|---|---|---|"
    for spp in 512 1024 2048 4096; do
      hwss_bias=""
      for preset in hwss paper paper-fade paper-auto-fade; do
        runs=("$scene_dir"/snapshots/"$preset"-seed{1,2,3}-"$spp"spp.exr)
        [ -e "${runs[0]}" ] && [ -e "${runs[1]}" ] && [ -e "${runs[2]}" ] || continue
        line=$("$image" bias "${runs[@]}" --reference "$ref")
        mse=$(sed 's/.*mse=\([^ ]*\).*/\1/' <<<"$line")
        var=$(sed 's/.*variance=\([^ ]*\).*/\1/' <<<"$line")
        b=$(sed 's/.*bias_sq=\([^ ]*\).*/\1/' <<<"$line")
        se=$(sed 's/.*bias_sq_se=\([^ ]*\).*/\1/' <<<"$line")
        [ "$preset" = hwss ] && { hwss_bias=$b; hwss_se=$se; }
        # the difference's standard error as if the two were independent (they share the
        # reference, whose noise cancels in the difference: this overstates it)
        excess=$(awk -v b="$b" -v h="$hwss_bias" -v se="$se" -v hse="$hwss_se" \
          'BEGIN { s = sqrt(se * se + hse * hse); printf "%.3g (%.1f se)", b - h, (s > 0 ? (b - h) / s : 0) }')
        [ "$preset" = hwss ] && excess="—"
        echo "| $spp | $preset | $mse | $var | $b ± $se | $excess |"
      done
    done
  done
} >"$out"
echo "wrote $out"
