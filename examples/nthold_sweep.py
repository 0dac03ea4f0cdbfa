#!/usr/bin/env python3
"""A parameter sweep on one loaded scene: paper's relaxation length N_thold against SSIM at
16 spp (docs/python.md). The scene is loaded once; each renderer reuses its BVH and lights."""
import argparse
import time

import matplotlib.pyplot as plt
import iris

ap = argparse.ArgumentParser(description=__doc__)
ap.add_argument("--scene", default="falling-cubes")
ap.add_argument("--size", type=int, nargs=2, default=(160, 120), metavar=("W", "H"))
ap.add_argument("--spp", type=int, default=16)
ap.add_argument("--reference-spp", type=int, default=1024)
ap.add_argument("-o", "--output", default="nthold_sweep.png")
a = ap.parse_args()

start = time.perf_counter()
scene = iris.load(a.scene)
print(f"loaded {scene} in {time.perf_counter() - start:.2f} s (BVH and lights: {scene.build_seconds:.3f} s)")
size = dict(width=a.size[0], height=a.size[1])
ref = iris.Renderer(scene, preset="hwss", seed=1000, **size)
ref.step(a.reference_spp)

nthold = [1, 4, 16, 64, 256, 1024]
ssim = []
for n in nthold:
    r = iris.Renderer(scene, preset="paper", nthold=n, **size)
    r.step(a.spp)
    ssim.append(iris.ssim(r.image(), ref.image()))
    print(f"N_thold {n:>5}: SSIM {ssim[-1]:.4f}  ({r.seconds:.2f} s)")

plt.semilogx(nthold, ssim, "o-", base=2)
plt.xlabel("N_thold (samples per pixel)"), plt.ylabel(f"SSIM at {a.spp} spp")
plt.title(f"{a.scene}: paper's relaxation length")
plt.savefig(a.output, dpi=120)
print(f"wrote {a.output}")
