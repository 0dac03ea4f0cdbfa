#!/usr/bin/env bash
# iris-ablate end to end on a tiny case:  ablate_test.sh IRIS_ABLATE WORK_DIR
#
# Runs `iris-ablate furnace --presets hwss,paper --spp 2,8,32 --reference-spp 256
# --seeds 2 --width 24 --height 16` twice with a fresh reference cache in WORK_DIR: the
# first run renders and caches the reference, the second must load it and reproduce the
# metrics exactly (renders are deterministic for a seed). Checks after the first run:
# exit 0; results.csv has the documented header and exactly one row per preset x seed x
# spp, all with finite metrics; the mean MSE of every preset falls strictly with spp and
# by more than 4x from 2 to 32 spp (the furnace is unbiased and noise-only, so MSE ~ 1/spp
# predicts 16x; snapshots taken at the wrong pass, or a broken reference, would not);
# summary.md has a table row per spp x preset; the plots and the crops are PNGs; the 12
# snapshots exist; no temporary file is left. (SSIM is not checked for a trend: the
# furnace's radiance 5 saturates the display range SSIM is computed on.)
# A third run gives the cached reference back with --reference (a reference rendered
# elsewhere): the same metrics, no reference rendered, and summary.md names the file and its
# header. Then --reference with the wrong size, of another scene (iris:scene), unreadable,
# or together with --reference-spp: exit 2, a message naming the problem, nothing written.
set -u
ablate=$1 work=$2
out=$work/out cache=$work/cache
fail() {
  echo "FAIL: $*" >&2
  for f in "$work/stdout.txt" "$work/stderr.txt"; do [ -f "$f" ] && { echo "--- $f" >&2; head -c 3000 "$f" >&2; }; done
  exit 1
}
run() {
  "$ablate" furnace --presets hwss,paper --spp 2,8,32 --reference-spp 256 --seeds 2 --width 24 --height 16 \
    --cache "$cache" -o "$out" >"$work/stdout.txt" 2>"$work/stderr.txt"
}
is_png() { [ "$(head -c 8 "$1" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ]; }

rm -rf "$work" && mkdir -p "$work" || fail "cannot create $work"

# ---- first run: the reference is rendered and cached
run
status=$?
[ "$status" -eq 0 ] || fail "exit status $status"
grep -q "^reference: 256 spp in .*, cached as " "$work/stderr.txt" || fail "the reference was not rendered and cached"

csv=$out/results.csv
[ -f "$csv" ] || fail "results.csv not written"
header=$(head -n 1 "$csv")
[ "$header" = "scene,preset,sampler,seed,spp,seconds,mse,relmse,ssim,flip" ] || fail "results.csv header is '$header'"
rows=$(($(wc -l <"$csv") - 1))
[ "$rows" -eq 12 ] || fail "results.csv has $rows rows, expected 2 presets x 2 seeds x 3 spp = 12"

awk -F, '
  function bad(msg) { print "results.csv: " msg > "/dev/stderr"; failed = 1 }
  NR == 1 { next }
  {
    if (NF != 10) bad("line " NR " has " NF " fields")
    if ($1 != "furnace") bad("line " NR ": scene " $1)
    if ($3 != "sobol") bad("line " NR ": sampler " $3 " (the default is sobol)")
    if (seen[$2 "," $4 "," $5]++) bad("duplicate row " $2 " seed " $4 " spp " $5)
    for (f = 6; f <= 10; ++f)
      if ($f !~ /^[0-9]+(\.[0-9]+)?(e[-+]?[0-9]+)?$/) bad("line " NR ": field " f " is not a finite number: " $f)
    if (!($7 > 0)) bad("line " NR ": mse " $7 " is not > 0")
    if (!($9 <= 1)) bad("line " NR ": ssim " $9 " > 1")
    if (!($10 > 0 && $10 <= 1)) bad("line " NR ": flip " $10 " is not in (0, 1]")
    sum[$2 "," $5] += $7
    n[$2 "," $5]++
  }
  END {
    np = split("hwss paper", preset, " ")
    ns = split("2 8 32", spp, " ")
    for (p = 1; p <= np; ++p) {
      for (s = 1; s <= ns; ++s)
        for (seed = 1; seed <= 2; ++seed)
          if (!((preset[p] "," seed "," spp[s]) in seen)) bad("no row for " preset[p] " seed " seed " spp " spp[s])
      line = preset[p] " mean mse:"
      for (s = 1; s <= ns; ++s) {
        k = preset[p] "," spp[s]
        mean[s] = n[k] ? sum[k] / n[k] : 0
        line = line " " spp[s] " spp " mean[s]
      }
      print line
      for (s = 2; s <= ns; ++s)
        if (!(mean[s] < mean[s - 1])) bad(preset[p] ": mean mse does not fall from " spp[s - 1] " to " spp[s] " spp")
      if (!(mean[1] > 4 * mean[ns])) bad(preset[p] ": mean mse falls less than 4x from " spp[1] " to " spp[ns] " spp")
    }
    exit failed
  }' "$csv" || fail "results.csv checks failed"

[ -f "$out/summary.md" ] || fail "summary.md not written"
head -n 1 "$out/summary.md" | grep -qx "# Ablation: furnace" || fail "summary.md does not start with '# Ablation: furnace'"
table_rows=$(grep -cE '^\| (2|8|32) \| (hwss|paper) \| ' "$out/summary.md")
[ "$table_rows" -eq 6 ] || fail "summary.md has $table_rows table rows, expected 3 spp x 2 presets = 6"

for png in ssim_vs_spp.png mse_vs_spp.png flip_vs_spp.png ssim_vs_seconds.png mse_vs_seconds.png flip_vs_seconds.png crops_2spp.png; do
  [ -f "$out/$png" ] || fail "$png not written"
  is_png "$out/$png" || fail "$png does not start with the PNG signature"
done
for preset in hwss paper; do
  for seed in 1 2; do
    for spp in 2 8 32; do
      [ -f "$out/snapshots/$preset-seed$seed-${spp}spp.exr" ] || fail "snapshot $preset-seed$seed-${spp}spp.exr missing"
    done
  done
done
leftovers=$(find "$work" -name '*.tmp-*')
[ -z "$leftovers" ] || fail "temporary files left: $leftovers"

# ---- second run: the cached reference gives the same metrics (all but the seconds column)
cut -d, -f1-5,7-9 "$csv" >"$work/metrics_first.csv"
run
status=$?
[ "$status" -eq 0 ] || fail "second run: exit status $status"
grep -q "^reference: .* (cached)$" "$work/stderr.txt" || fail "second run: the cached reference was not used"
cut -d, -f1-5,7-9 "$csv" | cmp -s - "$work/metrics_first.csv" ||
  fail "second run (cached reference) gives other metrics: $(cut -d, -f1-5,7-9 "$csv" | diff "$work/metrics_first.csv" -)"

# ---- third run: the cached reference given with --reference (as one rendered elsewhere
# would be) gives the same metrics, and summary.md says where it came from
ref=$(ls "$cache"/furnace-*-24x16-ref256-*.exr | head -1)
[ -f "$ref" ] || fail "no cached reference in $cache"
cp "$ref" "$work/cluster-reference.exr"
"$ablate" furnace --presets hwss,paper --spp 2,8,32 --seeds 2 --width 24 --height 16 --cache "$work/empty-cache" \
  --reference "$work/cluster-reference.exr" -o "$out" >"$work/stdout.txt" 2>"$work/stderr.txt"
status=$?
[ "$status" -eq 0 ] || fail "--reference run: exit status $status"
[ ! -e "$work/empty-cache" ] || fail "--reference run rendered a reference into the cache"
cut -d, -f1-5,7-9 "$csv" | cmp -s - "$work/metrics_first.csv" || fail "--reference gives other metrics"
grep -q "^Reference: \`$work/cluster-reference.exr\` (given with --reference; its header: preset hwss, 256 spp, sampler sobol, seed " \
  "$out/summary.md" || fail "summary.md does not record the given reference: $(grep '^Reference' "$out/summary.md")"

# ---- a reference of another size or scene, an unreadable one, or --reference with
# --reference-spp: exit 2, one line naming the problem, nothing written
bad() {  # bad WHAT PATTERN SCENE ARGS...
  local what=$1 pattern=$2
  shift 2
  rm -rf "$work/bad-out"
  "$ablate" "$@" --presets hwss --spp 2 --cache "$work/empty-cache" -o "$work/bad-out" \
    >"$work/stdout.txt" 2>"$work/stderr.txt"
  status=$?
  [ "$status" -eq 2 ] || fail "$what: exit status $status, expected 2"
  grep -q -- "$pattern" "$work/stderr.txt" || fail "$what: stderr does not say '$pattern'"
  [ ! -e "$work/bad-out" ] || fail "$what: the output directory was created"
}
bad "other size" "the image is 24x16, the run is 32x16" furnace --width 32 --height 16 --reference "$work/cluster-reference.exr"
bad "other scene" "rendered from scene 'furnace', the run is of 'cornell'" cornell --width 24 --height 16 \
  --reference "$work/cluster-reference.exr"
printf 'not an exr' >"$work/garbage.exr"
bad "unreadable" "garbage.exr" furnace --width 24 --height 16 --reference "$work/garbage.exr"
bad "with --reference-spp" "excludes" furnace --width 24 --height 16 --reference "$work/cluster-reference.exr" --reference-spp 64
echo "ok"
