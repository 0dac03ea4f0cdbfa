#!/usr/bin/env bash
# Open MPI:  mpi_test.sh MPIEXEC IRIS_RENDER WORK_DIR
#
# 1. The prism (dispersive) with `paper`, rendered by one process without mpirun and by
#    mpirun -np 1, 2 and 3: the four images must be the same bytes (the ranks' passes are
#    interleaved, their films summed exactly on rank 0); `paper-fade` with 2 ranks, whose
#    films' fade layers are summed too, the same bytes as in one process.
# 2. A rank killed (SIGKILL) during a 2-rank render: mpirun must end with a non-zero status
#    and say which rank died; the last image and checkpoint must be intact, and resuming
#    them with 3 ranks must give the uninterrupted render's bytes.
# 3. SIGTERM to mpirun (what a batch system sends at its time limit): the ranks stop after
#    the current round, rank 0 writes image and checkpoint; resuming them in one process
#    gives the same bytes again.
# Would catch: a rank rendering another's passes or none, a reduction that is not exact
# (float sums differ with N), rank 0 writing before the reduction, a dead rank hanging the
# job, a checkpoint that a different N cannot resume.
set -u
mpiexec=$1 render=$2 dir=$3
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
mpi=("$mpiexec" --oversubscribe)
pid=""
fail() {
  echo "FAIL: $*" >&2
  for f in out.txt err.txt; do [ -f "$dir/$f" ] && { echo "--- $f" >&2; cat "$dir/$f" >&2; }; done
  [ -n "$pid" ] && kill -KILL "$pid" 2>/dev/null
  exit 1
}
rm -rf "$dir" && mkdir -p "$dir" || fail "cannot create $dir"
cd "$dir" || fail "cannot enter $dir"
args=(prism --preset paper --width 48 --height 32 --nthold 16)

# ---- 1. 1, 2 and 3 ranks = one process
"$render" "${args[@]}" --spp 40 --every 7 -o single.exr >out.txt 2>err.txt || fail "single-process render failed"
for n in 1 2 3; do
  "${mpi[@]}" -np $n "$render" "${args[@]}" --threads 1 --spp 40 --every 7 -o ranks$n.exr --stats ranks$n.json >out.txt 2>err.txt ||
    fail "mpirun -np $n failed"
  grep -q "\"ranks\": $n," ranks$n.json || fail "-np $n: the stats do not say $n ranks: $(cat ranks$n.json)"
  cmp -s ranks$n.exr single.exr || fail "the $n-rank image differs from the single-process image"
done
# the fading preset: the ranks' fade layers are summed too (or the blend would differ)
"$render" "${args[@]/paper/paper-fade}" --spp 40 -o fade-single.exr >out.txt 2>err.txt || fail "single-process paper-fade failed"
"${mpi[@]}" -np 2 "$render" "${args[@]/paper/paper-fade}" --threads 1 --spp 40 -o fade-ranks2.exr >out.txt 2>err.txt ||
  fail "mpirun -np 2 paper-fade failed"
cmp -s fade-ranks2.exr fade-single.exr || fail "the 2-rank paper-fade image differs from the single-process image"
# spectral output: the ranks' spectral layers are summed too (or the S0.<λ>nm channels would differ)
"$render" "${args[@]}" --spp 12 --spectral 8 -o spectral-single.exr >out.txt 2>err.txt || fail "single-process --spectral failed"
"${mpi[@]}" -np 2 "$render" "${args[@]}" --threads 1 --spp 12 --spectral 8 -o spectral-ranks2.exr >out.txt 2>err.txt ||
  fail "mpirun -np 2 --spectral failed"
cmp -s spectral-ranks2.exr spectral-single.exr || fail "the 2-rank spectral image differs from the single-process image"

# ---- 2. a dead rank
"$render" "${args[@]}" --spp 1500 --threads 2 -o full.exr >out.txt 2>err.txt || fail "the uninterrupted render failed"
start() {  # start OUT: a 2-rank render writing image + checkpoint every 4 spp
  "${mpi[@]}" -np 2 "$render" "${args[@]}" --threads 1 --spp 1500 --every 4 -o "$1" >out.txt 2>err.txt &
  pid=$!
  for ((i = 0; i < 600; ++i)); do
    [ -e "$1.ckpt" ] && { sleep 0.3; return; }
    kill -0 "$pid" 2>/dev/null || fail "mpirun for $1 ended before the first checkpoint"
    sleep 0.05
  done
  fail "no checkpoint $1.ckpt within 30 s"
}
finish() {  # finish: mpirun must end within 30 s with a non-zero status
  for ((i = 0; i < 300; ++i)); do
    kill -0 "$pid" 2>/dev/null || break
    sleep 0.1
  done
  kill -0 "$pid" 2>/dev/null && fail "mpirun still running 30 s later"
  wait "$pid"
  local status=$?
  pid=""
  [ "$status" -ne 0 ] || fail "mpirun exited 0"
}
start dead.exr
ranks=$(pgrep -P "$pid" | tr '\n' ' ')
[ "$(wc -w <<<"$ranks")" -eq 2 ] || fail "expected 2 rank processes under mpirun, found '$ranks'"
kill -KILL "$(awk '{print $2}' <<<"$ranks")" || fail "cannot kill a rank"
finish
grep -q "exited on signal 9" err.txt || fail "mpirun did not report the dead rank"
"${mpi[@]}" -np 3 "$render" "${args[@]}" --threads 1 --spp 1500 -o dead.exr --resume --stats dead.json >out.txt 2>err.txt ||
  fail "3-rank resume after the dead rank failed"
grep -q '"resumed_from_spp": [1-9]' dead.json || fail "did not resume from the checkpoint: $(cat dead.json)"
cmp -s dead.exr full.exr || fail "the resumed image differs from the uninterrupted render"

# ---- 3. SIGTERM to mpirun
start term.exr
kill -TERM "$pid" || fail "cannot signal mpirun"
finish
grep -q "(interrupted)" out.txt || fail "rank 0 did not finish its interrupted render: $(cat out.txt)"
"$render" "${args[@]}" --spp 1500 --threads 2 -o term.exr --resume >out.txt 2>err.txt || fail "1-process resume failed"
cmp -s term.exr full.exr || fail "the resumed image differs from the uninterrupted render"
echo "ok: 1, 2, 3 ranks identical (paper-fade with 2 too); dead rank and SIGTERM resumed with 3 ranks and 1 process to the same bytes"
