#!/usr/bin/env bash
# iris-render --tev against the test tev server:  tev_test.sh IRIS_RENDER IRIS_IMAGE TEV_LISTEN WORK_DIR
#
# 1. A render streamed to a listening server: exit 0, nothing on stderr, more than one
#    update received, and the last image received equal, pixel for pixel, to the EXR
#    written at the same spp; the EXR the same bytes as without --tev.
# 2. A server killed after 5 packets: the render goes on to the end (exit 0, the same EXR
#    bytes) with one warning that the connection was lost.
# 3. No server at all: exit 0 and one warning that tev is not reachable.
# Would catch: packets tev cannot decode (the server checks every field), an image that is
# not the written one (wrong channel order, tiles misplaced, a stale last frame), a render
# stopped, failed or slowed to a halt by a viewer that is gone, streaming that changes the image.
set -u
render=$1 image=$2 listen=$3 dir=$4
fail() {
  echo "FAIL: $*" >&2
  for f in out.txt err.txt listen.txt; do [ -f "$dir/$f" ] && { echo "--- $f" >&2; cat "$dir/$f" >&2; }; done
  exit 1
}
rm -rf "$dir" && mkdir -p "$dir" && cd "$dir" || fail "cannot create $dir"
args=(cornell --preset paper --width 64 --height 48 --threads 2)
"$render" "${args[@]}" --spp 60 -o plain.exr >out.txt 2>err.txt || fail "render without --tev failed"

serve() {  # serve NAME [DIE_AFTER]: start the server, set $lpid and $port
  rm -f "$1.port"
  "$listen" "$1.port" "$1-received.exr" ${2:-} >listen.txt 2>&1 &
  lpid=$!
  for ((i = 0; i < 200; ++i)); do [ -s "$1.port" ] && break; sleep 0.05; done
  [ -s "$1.port" ] || fail "tev_listen did not start"
  port=$(cat "$1.port")
}

# ---- 1. a listening viewer
serve live
"$render" "${args[@]}" --spp 60 --tev "127.0.0.1:$port" --tev-seconds 0 -o live.exr >out.txt 2>err.txt ||
  fail "render with --tev failed"
[ -s err.txt ] && fail "stderr not empty with a listening viewer"
wait "$lpid" || fail "tev_listen exit status $? (malformed packets or no image)"
cmp -s live.exr plain.exr || fail "--tev changed the image"
diff=$("$image" diff live-received.exr live.exr) || fail "cannot compare the received image"
[[ $diff == "mse=0 relmse=0 ssim=1.000000 max_abs=0 "* ]] || fail "received image differs from the EXR: $diff"
updates=$("$image" info live-received.exr | sed -n 's/^tev:updates=//p')
((updates >= 2)) || fail "only $updates update(s) received: not progressive"

# ---- 2. a viewer killed mid-render
serve dead 5
"$render" "${args[@]}" --spp 300 --tev "127.0.0.1:$port" --tev-seconds 0 -o dead.exr >out.txt 2>err.txt ||
  fail "the render failed when the viewer died"
wait "$lpid"
[ $? -eq 3 ] || fail "tev_listen was not killed after 5 packets"
grep -q "warning: lost the connection to tev" err.txt || fail "no warning about the lost viewer"
"$render" "${args[@]}" --spp 300 -o dead-plain.exr >/dev/null 2>&1 || fail "render without --tev failed"
cmp -s dead.exr dead-plain.exr || fail "the image differs after the viewer died"

# ---- 3. no viewer
"$render" "${args[@]}" --spp 8 --tev 127.0.0.1:1 -o none.exr >out.txt 2>err.txt || fail "render without a viewer failed"
[ "$(grep -c "warning: tev is not reachable at 127.0.0.1:1" err.txt)" -eq 1 ] || fail "expected one 'not reachable' warning"
echo "ok: $updates updates, the last one equal to the EXR; a dead or missing viewer does not stop the render"
