#!/usr/bin/env bash
# The fuzz campaign: every libFuzzer target (clang-16, ASan + UBSan, `fuzz` preset) for
# SECONDS each (default 600), starting from the committed corpus fuzz/corpus/<target>/;
# afterwards the inputs that add coverage are merged (libFuzzer -merge=1) into fuzz/corpus/<target>/,
# and one line per target is appended to build/fuzz/report.tsv: target, seconds, runs,
# executions per second, coverage (edges), features, corpus size, crashes. A crash leaves
# its input in build/fuzz/artifacts/<target>/ (fix it and add the input to the corpus, so
# that CTest's replay keeps it fixed).
#   bash scripts/fuzz.sh [SECONDS] [TARGET...]     e.g. bash scripts/fuzz.sh 60 mesh_ply
# JOBS=2 runs two targets at a time (each takes one core).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-600}
shift || true
scripts/deps.sh clang-16 libclang-rt-16-dev
cmake --preset fuzz >/dev/null
cmake --build --preset fuzz
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  for f in build/fuzz/fuzz/fuzz_*; do targets+=("$(basename "$f" | sed 's/^fuzz_//')"); done
fi
report=build/fuzz/report.tsv
[ -f "$report" ] || printf 'target\tseconds\truns\texec_per_s\tcov_edges\tfeatures\tcorpus\tcrashes\n' >"$report"

one() {
  local t=$1 work=build/fuzz/work/$1 art=build/fuzz/artifacts/$1/ log=build/fuzz/logs/$1.log
  rm -rf "$work" && mkdir -p "$work" "$art" build/fuzz/logs
  cp fuzz/corpus/"$t"/* "$work"/ 2>/dev/null || true
  # -rss_limit_mb/-malloc_limit_mb: an input that makes iris allocate gigabytes is a finding
  build/fuzz/fuzz/fuzz_"$t" -max_total_time="$seconds" -rss_limit_mb=3072 -malloc_limit_mb=2048 \
    -timeout=60 -print_final_stats=1 -artifact_prefix="$art" "$work" >"$log" 2>&1 || true
  local runs eps cov ft crashes
  runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo 0)
  eps=$(grep -o 'stat::average_exec_per_sec: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo 0)
  cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1 | grep -o '[0-9]*' || echo 0)
  ft=$(grep -o 'ft: [0-9]*' "$log" | tail -1 | grep -o '[0-9]*' || echo 0)
  crashes=$(ls "$art" | wc -l)
  # keep what is new: inputs of the run that add coverage to the committed corpus are
  # merged into it (libFuzzer -merge=1 keeps the smallest such inputs; named seeds stay)
  build/fuzz/fuzz/fuzz_"$t" -merge=1 -rss_limit_mb=3072 -malloc_limit_mb=2048 fuzz/corpus/"$t" "$work" >>"$log" 2>&1 || true
  printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$t" "$seconds" "$runs" "$eps" "$cov" "$ft" "$(ls fuzz/corpus/"$t" | wc -l)" "$crashes" >>"$report"
  echo "$t: $runs runs, cov $cov, ft $ft, $crashes crashes"
}

jobs=${JOBS:-1}
for t in "${targets[@]}"; do
  one "$t" &
  while [ "$(jobs -rp | wc -l)" -ge "$jobs" ]; do wait -n; done
done
wait
column -t -s $'\t' "$report"
