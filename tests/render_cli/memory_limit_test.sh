#!/usr/bin/env bash
# The largest image iris-render accepts (16384 x 16384: a 14 GiB film at 56 bytes a pixel)
# under a 2 GiB address-space limit:  memory_limit_test.sh IRIS_RENDER WORK_DIR
# Must fail cleanly: exit 1, one line on stderr naming the size and the memory it needs,
# nothing written. Would catch a std::bad_alloc escaping (abort, exit 134), a message
# that does not say what ran out, or a partial output file.
# Not for sanitizer builds (ASan reserves terabytes of address space): label
# sanitizer-incompatible.
set -u
render=$1 dir=$2
rm -rf "$dir" && mkdir -p "$dir"
(
  ulimit -v 2097152
  "$render" furnace --width 16384 --height 16384 --spp 1 --threads 1 -o "$dir/big.exr" >"$dir/out.txt" 2>"$dir/err.txt"
)
status=$?
fail() { echo "FAIL: $*" >&2; cat "$dir/err.txt" >&2; exit 1; }
[ "$status" -eq 1 ] || fail "exit status $status, expected 1"
grep -q "^iris-render: error: not enough memory for a 16384x16384 film (14.00 GiB at 56 bytes per pixel)$" "$dir/err.txt" ||
  fail "no clear out-of-memory message"
[ "$(wc -l <"$dir/err.txt")" -eq 1 ] || fail "more than one line on stderr"
[ ! -s "$dir/out.txt" ] || fail "something on stdout"
[ -z "$(ls -A "$dir" | grep -v -e out.txt -e err.txt)" ] || fail "files written: $(ls "$dir")"
echo "ok: $(cat "$dir/err.txt")"
