#!/usr/bin/env bash
# iris-compare, end to end:  compare_test.sh IRIS_COMPARE IRIS_RENDER IRIS_IMAGE TEV_LISTEN WORK_DIR
#
# 1. Equal spp, streamed to the test tev server: exit 0, nothing on stderr; tev received one
#    image per preset and the side-by-side one, each more than once; the last of each equal,
#    pixel for pixel, to the EXR written (and the side-by-side one to the presets' images
#    side by side: its width is 2 x 64 + 4); each preset's image equal to iris-render's at the
#    same seed, sampler and spp (the lockstep changes no pixel); compare.csv: 12 spp each.
# 2. Equal render time: both presets reach the budget, and their render times differ by at
#    most one pass (the longer of the two presets' longest passes), at the end and after every
#    pass of the run. hwss is cheaper per sample
#    than paper, so taking turns pass by pass would leave them ~20 % apart.
#    And the presets did not render at the same time: their render times add up to no more
#    than the run's wall-clock time.
# 3. Ctrl-C: exit 130 within seconds, the images of what was complete written.
# Would catch: a scheduler that alternates instead of balancing time, presets rendering
# concurrently, frames of the wrong preset or stale ones, a side-by-side image misassembled, lanes
# that deadlock at the end (the test's timeout), a signal ignored.
set -u
compare=$1 render=$2 image=$3 listen=$4 dir=$5
fail() {
  echo "FAIL: $*" >&2
  for f in out.txt err.txt listen.txt; do [ -f "$dir/$f" ] && { echo "--- $f" >&2; cat "$dir/$f" >&2; }; done
  exit 1
}
rm -rf "$dir" && mkdir -p "$dir/received" && cd "$dir" || fail "cannot create $dir"
size=(--width 64 --height 48 --threads 2)

# ---- 1. equal spp, live in tev
rm -f port
"$listen" port received/ >listen.txt 2>&1 &
lpid=$!
for ((i = 0; i < 200; ++i)); do [ -s port ] && break; sleep 0.05; done
[ -s port ] || fail "tev_listen did not start"
"$compare" cornell --presets hwss,paper --spp 12 "${size[@]}" --tev "127.0.0.1:$(cat port)" --tev-seconds 0 -o spp \
  >out.txt 2>err.txt || fail "iris-compare --spp failed"
[ -s err.txt ] && fail "stderr not empty"
wait "$lpid" || fail "tev_listen exit status $? (malformed packets or no image)"
for p in hwss paper; do
  [ -f "received/cornell-$p.exr" ] || fail "tev received no image cornell-$p"
  d=$("$image" diff "received/cornell-$p.exr" "spp/$p.exr") || fail "cannot compare $p"
  [[ $d == "mse=0 relmse=0 ssim=1.000000 max_abs=0 "* ]] || fail "$p: received image differs from the EXR: $d"
  u=$("$image" info "received/cornell-$p.exr" | sed -n 's/^tev:updates=//p')
  ((u >= 2)) || fail "$p: only $u update(s) received"
  "$render" cornell --preset "$p" --spp 12 "${size[@]}" -o "alone-$p.exr" >/dev/null 2>&1 || fail "iris-render $p failed"
  d=$("$image" diff "spp/$p.exr" "alone-$p.exr") || fail "cannot compare $p with iris-render"
  [[ $d == "mse=0 relmse=0 ssim=1.000000 max_abs=0 "* ]] || fail "$p: differs from iris-render's image: $d"
  grep -q "^cornell,$p,sobol,1,12," spp/compare.csv || fail "compare.csv has no 12-spp row for $p"
done
[ -f received/cornell-side-by-side.exr ] || fail "tev received no side-by-side image"
"$image" info received/cornell-side-by-side.exr | grep -qx "width=132 height=48" || fail "side-by-side image is not 132x48"
[ -f spp/side-by-side.png ] || fail "no side-by-side.png"

# ---- 2. equal render time
"$compare" cornell --presets hwss,paper --seconds 1.5 "${size[@]}" -o time >out.txt 2>err.txt ||
  fail "iris-compare --seconds failed"
gap=$(sed -n 's/^largest render-time gap between presets after any pass: \([0-9.]*\) s (longest pass: \([0-9.]*\) s)/\1 \2/p' out.txt)
[ -n "$gap" ] || fail "no render-time gap line on stdout"
awk -v g="$gap" 'BEGIN { split(g, v, " "); exit !(v[1] <= v[2] + 1e-3) }' ||
  fail "the presets' render times drifted apart by more than one pass during the run: $gap"
wall=$(sed -n 's/^wall-clock: \([0-9.]*\) s.*/\1/p' out.txt)
[ -n "$wall" ] || fail "no wall-clock line on stdout"
awk -F, -v wall="$wall" 'NR > 1 { s[$2] = $6; m[$2] = $7; n[$2] = $5 }
  END {
    if (s["hwss"] + s["paper"] > wall) { printf "render times %s + %s exceed the wall-clock time %s: not in lockstep\n", s["hwss"], s["paper"], wall; exit 1 }
    if (s["hwss"] < 1.5 || s["paper"] < 1.5) { print "a preset stopped before the budget"; exit 1 }
    d = s["hwss"] - s["paper"]; if (d < 0) d = -d
    mp = m["hwss"] > m["paper"] ? m["hwss"] : m["paper"]
    if (d > mp + 1e-3) { printf "render times %s and %s differ by more than one pass (%s s)\n", s["hwss"], s["paper"], mp; exit 1 }
    printf "hwss %d spp in %s s, paper %d spp in %s s (longest pass %s s)\n", n["hwss"], s["hwss"], n["paper"], s["paper"], mp
  }' time/compare.csv >balance.txt || fail "$(cat balance.txt)"

# ---- 3. Ctrl-C
"$compare" cornell --presets hwss,paper --seconds 600 "${size[@]}" -o int >out.txt 2>err.txt &
cpid=$!
sleep 2
kill -INT "$cpid"
wait "$cpid"
rc=$?
[ $rc -eq 130 ] || fail "exit status $rc after SIGINT, expected 130"
[ -f int/hwss.exr ] && [ -f int/paper.exr ] && [ -f int/compare.csv ] || fail "nothing written after SIGINT"
echo "ok: $(cat balance.txt); tev images equal to the EXRs; Ctrl-C exit 130"
