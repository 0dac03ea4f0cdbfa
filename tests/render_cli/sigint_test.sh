#!/usr/bin/env bash
# Ctrl-C during a progressive render:  sigint_test.sh IRIS_RENDER IRIS_IMAGE WORK_DIR
#
# Starts a render far too long to finish (100000 spp) that rewrites its image after every
# pass, waits until the image exists, sends SIGINT, and checks that iris-render stopped
# after the current pass: exit status 130, "(interrupted)" in its summary line, the image
# still a valid EXR whose iris:spp is the number of complete passes (< 100000, and the
# same in the summary line and in the --stats JSON, which is only written at the end),
# nothing on stderr, the checkpoint X.exr.ckpt beside it and no temporary file left in the
# directory.
# Would catch: no SIGINT handler (killed by the signal: no summary, no stats), a handler
# that does not stop the render (timeout), the final image not written or written with
# the requested rather than the done spp, a torn or half-renamed EXR.
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
# job control: the render gets SIGINT's default disposition, as when started from a
# terminal (without it, bash starts background jobs with SIGINT ignored)
set -m
"$render" cornell --spp 100000 --every 1 --width 64 --height 48 -o "$dir/X.exr" --stats "$dir/X.json" \
  >"$dir/out.txt" 2>"$dir/err.txt" &
pid=$!

# wait (at most 60 s) for the first image
for ((i = 0; i < 600; ++i)); do
  [ -e "$dir/X.exr" ] && break
  if ! kill -0 "$pid" 2>/dev/null; then
    wait "$pid"
    status=$?
    pid=""
    fail "iris-render exited (status $status) before writing X.exr"
  fi
  sleep 0.1
done
[ -e "$dir/X.exr" ] || fail "X.exr not written within 60 s"

kill -INT "$pid" || fail "cannot send SIGINT"
# it must stop after the current pass (a few ms); allow 30 s on a loaded machine
for ((i = 0; i < 300; ++i)); do
  kill -0 "$pid" 2>/dev/null || break
  sleep 0.1
done
kill -0 "$pid" 2>/dev/null && fail "iris-render still running 30 s after SIGINT"
wait "$pid"
status=$?
pid=""

[ "$status" -eq 130 ] || fail "exit status $status, expected 130"
[ -s "$dir/err.txt" ] && fail "stderr is not empty"
summary=$(cat "$dir/out.txt")
[[ $summary =~ X\.exr:\ cornell\ with\ hwss\ .*,\ 64x48,\ ([0-9]+)\ spp\ in\ .*\(interrupted\)$ ]] ||
  fail "summary line is not an interrupted render's: '$summary'"
summary_spp=${BASH_REMATCH[1]}

info=$("$image" info "$dir/X.exr" 2>&1) || fail "X.exr is not a valid EXR: $info"
[[ $info =~ (^|$'\n')width=64\ height=48($'\n'|$) ]] || fail "X.exr has the wrong size: $info"
[[ $info =~ (^|$'\n')iris:spp=([0-9]+)($'\n'|$) ]] || fail "X.exr has no iris:spp: $info"
exr_spp=${BASH_REMATCH[2]}
((exr_spp >= 1 && exr_spp < 100000)) || fail "X.exr has iris:spp=$exr_spp, expected 1..99999"
((exr_spp == summary_spp)) || fail "X.exr has iris:spp=$exr_spp but the summary says $summary_spp spp"

json=$(tr -d ' \n' <"$dir/X.json") || fail "X.json (--stats) not written"
[[ $json == *'"interrupted":true'* ]] || fail "X.json does not say interrupted: $json"
[[ $json == *"\"spp\":$exr_spp,"* ]] || fail "X.json's spp is not $exr_spp: $json"

[ -s "$dir/X.exr.ckpt" ] || fail "no checkpoint X.exr.ckpt to resume from"
leftover=$(cd "$dir" && ls -A | grep -v -x -e X.exr -e X.exr.ckpt -e X.json -e out.txt -e err.txt)
[ -z "$leftover" ] || fail "files left in $dir: $leftover"
echo "ok: interrupted after $exr_spp spp, exit status 130"
