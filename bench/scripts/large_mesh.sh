#!/usr/bin/env bash
# Memory of a 10-million-triangle mesh, from the file to a rendered image:
#   bash bench/scripts/large_mesh.sh [BUILD=build/release] [N=2238]
# Writes an N × N vertex grid (2 (N − 1)² triangles: 10 008 338 for N = 2238) as a binary
# little-endian PLY into build/large-mesh/, a scene with it as a diffuse floor under a
# lamp, then reports wall time and peak resident memory (GNU time's "Maximum resident set
# size") of `iris-scene info` (parse + load + checks) and of a 64×48, 1-spp `iris-render`
# (+ the Embree BVH and the light sampler). docs/performance.md quotes a run.
set -euo pipefail
cd "$(dirname "$0")/../.."
build=${1:-build/release}
n=${2:-2238}
dir=build/large-mesh
mkdir -p "$dir"
/usr/bin/python3 - "$dir/grid.ply" "$n" <<'PY'
import struct, sys
path, n = sys.argv[1], int(sys.argv[2])
tris = 2 * (n - 1) ** 2
with open(path, "wb") as f:
    f.write(f"ply\nformat binary_little_endian 1.0\nelement vertex {n*n}\nproperty float x\nproperty float y\n"
            f"property float z\nelement face {tris}\nproperty list uchar uint vertex_indices\nend_header\n".encode())
    row = struct.Struct("<3f")
    for j in range(n):
        z = -1.0 + 2.0 * j / (n - 1)
        f.write(b"".join(row.pack(-1.0 + 2.0 * i / (n - 1), 0.0, z) for i in range(n)))
    tri = struct.Struct("<B3I")
    for j in range(n - 1):
        out = []
        for i in range(n - 1):
            a = j * n + i
            out.append(tri.pack(3, a, a + n, a + n + 1))  # (v_n − v_a) × (v_n+1 − v_a) = +y
            out.append(tri.pack(3, a, a + n + 1, a + 1))
        f.write(b"".join(out))
print(f"{path}: {n*n} vertices, {tris} triangles")
PY
cat >"$dir/scene.json" <<'JSON'
{"camera": {"position": [0, 1.5, 2.5], "look_at": [0, 0, 0], "fov": 50, "resolution": [64, 48]},
 "materials": {"white": {"type": "diffuse", "reflectance": 0.6}},
 "emitters": {"lamp": {"spd": "D65", "luminance": 20}},
 "shapes": [{"type": "mesh", "file": "grid.ply", "material": "white"},
            {"type": "quad", "size": [0.5, 0.5], "material": "white", "emitter": "lamp",
             "transform": [{"rotate": {"axis": [1, 0, 0], "degrees": 180}}, {"translate": [0, 1.2, 0]}]}]}
JSON
ls -l "$dir/grid.ply"
measure() {
  local what=$1
  shift
  /usr/bin/time -f "%e %M" -o "$dir/time.txt" "$@" >/dev/null
  read -r secs kb <"$dir/time.txt"
  printf '%-28s %8.1f s  %8.0f MiB peak RSS\n' "$what" "$secs" "$((kb / 1024))"
}
measure "iris-scene info" "$build/apps/iris-scene/iris-scene" info "$dir/scene.json"
measure "iris-render (1 spp, 64x48)" "$build/apps/iris-render/iris-render" "$dir/scene.json" --spp 1 -o "$dir/out.exr"
