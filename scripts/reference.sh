#!/usr/bin/env bash
# The converged reference of issue 14: falling-cubes, 160x120, 65 536 spp, `hwss` with the
# zsobol sampler, rendered with Open MPI (RANKS processes of THREADS threads; default 2 x 1
# on this 2-core VM), one image per seed. Interrupt it at will (Ctrl-C, SIGTERM, a node
# lost): run it again and it resumes each image from its checkpoint. Writes
# DIR/falling-cubes-hwss-zsobol-65536-seed<S>.exr (+ .json stats) and DIR/noise-ceiling.txt
# (iris-image diff of the first two seeds). Needs a release build with MPI.
#   bash scripts/reference.sh [DIR=build/reference] [SEED...=101 102]
set -euo pipefail
cd "$(dirname "$0")/.."
apps=build/release/apps
out=${1:-build/reference}
shift || true
seeds=("$@")
[ ${#seeds[@]} -gt 0 ] || seeds=(101 102)
ranks=${RANKS:-2} threads=${THREADS:-1}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
mkdir -p "$out"
for seed in "${seeds[@]}"; do
  exr="$out/falling-cubes-hwss-zsobol-65536-seed$seed.exr"
  if [ -e "$exr" ] && [ ! -e "$exr.ckpt" ]; then echo "$exr: done"; continue; fi
  resume=()
  [ -e "$exr.ckpt" ] && resume=(--resume)
  mpirun --oversubscribe -np "$ranks" "$apps/iris-render/iris-render" falling-cubes --preset hwss --sampler zsobol \
    --spp 65536 --seed "$seed" --width 160 --height 120 --threads "$threads" --every-seconds 120 \
    -o "$exr" --stats "${exr%.exr}.json" "${resume[@]}"
done
if [ ${#seeds[@]} -ge 2 ]; then
  "$apps/iris-image/iris-image" diff "$out/falling-cubes-hwss-zsobol-65536-seed${seeds[1]}.exr" \
    "$out/falling-cubes-hwss-zsobol-65536-seed${seeds[0]}.exr" | tee "$out/noise-ceiling.txt"
fi
