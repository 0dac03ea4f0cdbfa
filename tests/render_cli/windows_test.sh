#!/usr/bin/env bash
# Automatic window placement through the tools:  windows_test.sh IRIS_RENDER IRIS_SPECTRUM IRIS_IMAGE WORK_DIR
#
# 1. iris-render --preset paper-auto records in the EXR (iris:windows) exactly the windows
#    `iris-spectrum windows SCENE` prints for the scene, on three scenes with different emitters
#    (LED-B1, LED-RGB1, a tabulated laser), and they differ from the hand-placed ones.
# 2. paper records the hand-placed windows; hwss (no windows) records none.
# 3. A scene with one D65 emitter gets the windows of the D65 illuminant itself.
# Would catch: the renderer and iris-spectrum placing differently (other inputs, other
# weights), the placement not reaching the render (the hand windows recorded), windows
# recorded for kernels without any.
set -u
render=$1 spectrum=$2 image=$3 dir=$4
fail() { echo "FAIL: $*" >&2; exit 1; }
rm -rf "$dir" && mkdir -p "$dir" && cd "$dir" || fail "cannot create $dir"
auto_row() { "$spectrum" windows "$@" | awk '$1 == "auto" { print $3 }'; }
windows_of() { "$image" info "$1" | sed -n 's/^iris:windows=//p'; }
hand=464:20,549:20,611:20

for scene in falling-cubes-led falling-cubes-rgb falling-cubes-laser; do
  expected=$(auto_row "$scene") || fail "iris-spectrum windows $scene failed"
  [ -n "$expected" ] || fail "iris-spectrum printed no automatic windows for $scene"
  [ "$expected" != "$hand" ] || fail "$scene: the automatic windows are the hand-placed ones"
  "$render" "$scene" --preset paper-auto --width 16 --height 12 --spp 1 -o "$scene.exr" >/dev/null 2>&1 ||
    fail "iris-render $scene paper-auto failed"
  got=$(windows_of "$scene.exr")
  [ "$got" = "$expected" ] || fail "$scene: the EXR records '$got', iris-spectrum prints '$expected'"
done
"$render" cornell --preset paper --width 16 --height 12 --spp 1 -o paper.exr >/dev/null 2>&1 || fail "paper failed"
[ "$(windows_of paper.exr)" = "$hand" ] || fail "paper records '$(windows_of paper.exr)', expected $hand"
"$render" cornell --preset hwss --width 16 --height 12 --spp 1 -o hwss.exr >/dev/null 2>&1 || fail "hwss failed"
[ -z "$(windows_of hwss.exr)" ] || fail "hwss records windows"
[ "$(auto_row falling-cubes)" = "$(auto_row --spd D65)" ] || fail "falling-cubes (one D65 lamp) and D65 differ"
echo "ok: led $(windows_of falling-cubes-led.exr), rgb $(windows_of falling-cubes-rgb.exr), laser $(windows_of falling-cubes-laser.exr)"
