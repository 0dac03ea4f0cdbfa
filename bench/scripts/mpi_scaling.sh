#!/usr/bin/env bash
# Open MPI on one machine (docs/performance.md, "Distributed rendering"): the speed of
# 1 process x 1 thread, 1 process x 2 threads, mpirun -np 1 x 2 threads and mpirun -np 2 x
# 1 thread on falling-cubes (160x120, hwss, zsobol, SPP=1024), with the ranks' balance
# (busy seconds, max and mean), then the cost of one gather + write of a 1920x1080 film
# (2 ranks, an image and a checkpoint every pass). Needs a release build with MPI and the
# machine to itself.   bash bench/scripts/mpi_scaling.sh [DIR=build/mpi-scaling]
set -euo pipefail
cd "$(dirname "$0")/../.."
render=build/release/apps/iris-render/iris-render
out=${1:-build/mpi-scaling}
spp=${SPP:-1024}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
mkdir -p "$out"
scene=(falling-cubes --preset hwss --sampler zsobol --width 160 --height 120 --spp "$spp")
field() { /usr/bin/python3 -c "import json,sys; d=json.load(open(sys.argv[1])); print(d.get(sys.argv[2], '-'))" "$1" "$2"; }
row() {  # row NAME JSON
  printf '| %s | %.3f | %.2f | %s | %s |\n' "$1" "$(field "$2" samples_per_second)" "$(field "$2" seconds)" \
    "$(field "$2" rank_busy_seconds_max)" "$(field "$2" rank_busy_seconds_mean)"
}
echo "| run | samples/s | wall s | busy max s | busy mean s |"
echo "|---|---|---|---|---|"
"$render" "${scene[@]}" --threads 1 -o "$out/p1t1.exr" --stats "$out/p1t1.json" >/dev/null
row "1 process, 1 thread" "$out/p1t1.json"
"$render" "${scene[@]}" --threads 2 -o "$out/p1t2.exr" --stats "$out/p1t2.json" >/dev/null
row "1 process, 2 threads" "$out/p1t2.json"
# Open MPI binds each rank to one core by default (np <= 2): its 2 threads then share it
mpirun -np 1 "$render" "${scene[@]}" --threads 2 -o "$out/n1t2.exr" --stats "$out/n1t2.json" >/dev/null 2>&1
row "mpirun -np 1, 2 threads (bound to one core)" "$out/n1t2.json"
mpirun --bind-to none -np 1 "$render" "${scene[@]}" --threads 2 -o "$out/n1t2u.exr" --stats "$out/n1t2u.json" >/dev/null
row "mpirun --bind-to none -np 1, 2 threads" "$out/n1t2u.json"
mpirun -np 2 "$render" "${scene[@]}" --threads 1 -o "$out/n2t1.exr" --stats "$out/n2t1.json" >/dev/null
row "mpirun -np 2, 1 thread each" "$out/n2t1.json"
for f in p1t2 n1t2 n1t2u n2t1; do cmp -s "$out/$f.exr" "$out/p1t1.exr" || { echo "$f.exr differs from p1t1.exr" >&2; exit 1; }; done
echo
echo "1920x1080, 2 ranks, image + checkpoint every pass:"
mpirun -np 2 "$render" falling-cubes --preset hwss --width 1920 --height 1080 --spp 6 --every 1 --threads 1 \
  -o "$out/hd.exr" --stats "$out/hd.json" >/dev/null
for k in gathers gather_seconds gather_bytes write_seconds seconds; do echo "  $k = $(field "$out/hd.json" $k)"; done
ls -l "$out/hd.exr" | awk '{print "  image bytes = " $5}'
