#!/usr/bin/env bash
# Checkpoint and resume:  resume_test.sh IRIS_RENDER IRIS_IMAGE WORK_DIR
#
# A render of the prism (dispersive) with `paper` is stopped by SIGINT, SIGTERM and
# SIGKILL (between checkpoints), and resumed with --resume; every resumed image must be
# the uninterrupted render's, byte for byte. SIGINT's render is stopped and resumed twice.
# A paper-fade render (its film's fade layer in the checkpoint) is stopped and resumed too.
# Then checkpoints of another render (seed, spp, preset, sampler, size), damaged ones
# (a flipped byte, a truncated file) and missing ones must give exit 2, a message naming
# the problem, and leave the image and the checkpoint untouched; so must a new render
# that would replace an unfinished render's checkpoint.
# Would catch: a resume that restarts at pass 0 or skips passes (other bytes), a signal
# that kills the render before it writes its checkpoint (none to resume), a checkpoint
# written in place (torn by SIGKILL), a mismatch or damage not noticed (a wrong image), or
# noticed after the files were overwritten.
set -u
render=$1 image=$2 dir=$3
pid=""
fail() {
  echo "FAIL: $*" >&2
  for f in out.txt err.txt; do [ -f "$dir/$f" ] && { echo "--- $f" >&2; cat "$dir/$f" >&2; }; done
  [ -n "$pid" ] && kill -KILL "$pid" 2>/dev/null
  exit 1
}
rm -rf "$dir" && mkdir -p "$dir" || fail "cannot create $dir"
cd "$dir" || fail "cannot enter $dir"
args=(prism --preset paper --width 48 --height 32 --spp 600 --nthold 64 --threads 2)

full=full.exr
"$render" "${args[@]}" -o full.exr >out.txt 2>err.txt || fail "the uninterrupted render failed"
[ -e full.exr.ckpt ] && fail "a complete render left its checkpoint"

# start a render that writes image + checkpoint every 5 spp; wait for its first checkpoint
start() {  # start OUT
  set -m  # job control: the render gets SIGINT's default disposition
  "$render" "${args[@]}" -o "$1" --every 5 "${@:2}" >out.txt 2>err.txt &
  pid=$!
  set +m
  for ((i = 0; i < 600; ++i)); do
    [ -e "$1.ckpt" ] && return
    kill -0 "$pid" 2>/dev/null || fail "the render of $1 ended before its first checkpoint"
    sleep 0.05
  done
  fail "no checkpoint $1.ckpt within 30 s"
}
stop() {  # stop SIGNAL EXPECTED_STATUS
  sleep 0.2
  kill -"$1" "$pid" || fail "cannot send SIG$1"
  wait "$pid"
  local status=$?
  pid=""
  [ "$status" -eq "$2" ] || fail "exit status $status after SIG$1, expected $2 (did it finish first?)"
}
resume() {  # resume OUT: must end with the uninterrupted image and no checkpoint
  "$render" "${args[@]}" -o "$1" --resume --stats "$1.json" >out.txt 2>err.txt || fail "resume of $1 failed"
  grep -q '"resumed_from_spp": [1-9]' "$1.json" || fail "$1 did not resume from a checkpoint: $(cat "$1.json")"
  cmp -s "$1" "$full" || fail "resumed $1 differs from the uninterrupted render $full"
  [ -e "$1.ckpt" ] && fail "$1.ckpt left after the render completed"
}

start int.exr
stop INT 130
[[ $(cat out.txt) == *"(interrupted)" ]] || fail "SIGINT: not reported as interrupted"
"$image" info int.exr >/dev/null 2>&1 || fail "SIGINT: int.exr is not a valid EXR"
# stop the resumed render too, then resume again
set -m
"$render" "${args[@]}" -o int.exr --every 5 --resume >out.txt 2>err.txt &
pid=$!
set +m
stop INT 130
resume int.exr

start term.exr
stop TERM 143
resume term.exr

start kill.exr
stop KILL 137
resume kill.exr

# ---- refused: exit 2, the reason on stderr, the files untouched
start keep.exr
stop INT 130
sums=$(md5sum keep.exr keep.exr.ckpt)
refused() {  # refused 'stderr regex' ARGS...: exit 2 and the files untouched
  local expect=$1
  shift
  "$render" "$@" >out.txt 2>err.txt
  local status=$?
  [ "$status" -eq 2 ] || fail "exit status $status for '$*', expected 2"
  grep -Eq "$expect" err.txt || fail "stderr for '$*' does not match '$expect': $(cat err.txt)"
  [ "$(md5sum keep.exr keep.exr.ckpt)" = "$sums" ] || fail "'$*' changed keep.exr or its checkpoint"
  [ -z "$(ls -A | grep -e '^keep\.exr.*\.tmp-')" ] || fail "'$*' left a temporary file"
}
refused "belongs to another render: its seed is 1, this render's is 2" "${args[@]}" -o keep.exr --resume --seed 2
refused "its spp is 600, this render's is 700" "${args[@]/600/700}" -o keep.exr --resume
refused "its preset is paper, this render's is hwss" "${args[@]/paper/hwss}" -o keep.exr --resume
refused "its sampler is sobol, this render's is zsobol" "${args[@]}" -o keep.exr --resume --sampler zsobol
refused "its width is 48, this render's is 40" "${args[@]/48/40}" -o keep.exr --resume
refused "its scene is prism, this render's is cornell" "${args[@]/prism/cornell}" -o keep.exr --resume
refused "unfinished render exists: --resume continues it" "${args[@]}" -o keep.exr
cp keep.exr.ckpt good.ckpt
size=$(stat -c %s keep.exr.ckpt)
printf '\x55' | dd of=keep.exr.ckpt bs=1 seek=$((size / 2)) conv=notrunc status=none
sums=$(md5sum keep.exr keep.exr.ckpt)
refused "checkpoint 'keep.exr.ckpt' is corrupt or not a checkpoint: checksum mismatch" "${args[@]}" -o keep.exr --resume
head -c $((size - 100)) good.ckpt >keep.exr.ckpt
sums=$(md5sum keep.exr keep.exr.ckpt)
refused "is corrupt or not a checkpoint: .* bytes, a 48x32 checkpoint has" "${args[@]}" -o keep.exr --resume
rm keep.exr.ckpt
"$render" "${args[@]}" -o keep.exr --resume >out.txt 2>err.txt
[ $? -eq 2 ] || fail "--resume without a checkpoint: exit status not 2"
grep -q "cannot read checkpoint 'keep.exr.ckpt': no such file" err.txt || fail "--resume without a checkpoint: $(cat err.txt)"

# ---- a fading preset: its checkpoint carries the film's fade layer, so SIGTERM and resume
# give the uninterrupted blend (without the layer the renderer refuses to go on)
args=(prism --preset paper-fade --width 48 --height 32 --spp 600 --nthold 64 --threads 2)
full=fade-full.exr
"$render" "${args[@]}" -o fade-full.exr >out.txt 2>err.txt || fail "the uninterrupted paper-fade render failed"
start fade.exr
stop TERM 143
resume fade.exr
echo "ok: SIGINT (twice), SIGTERM and SIGKILL resumed to the same bytes (paper-fade too); mismatches and damage refused"
