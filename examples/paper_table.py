#!/usr/bin/env python3
"""The paper's table from Python: hwss against paper at 1…16 spp on one loaded scene,
SSIM and MSE against a converged reference, printed and plotted (docs/python.md)."""
import argparse

import matplotlib.pyplot as plt
import iris

ap = argparse.ArgumentParser(description=__doc__)
ap.add_argument("--scene", default="falling-cubes")
ap.add_argument("--size", type=int, nargs=2, default=(160, 120), metavar=("W", "H"))
ap.add_argument("--reference-spp", type=int, default=1024)
ap.add_argument("-o", "--output", default="paper_table.png")
a = ap.parse_args()

scene = iris.load(a.scene)                      # meshes, BVH and lights: built once
size = dict(width=a.size[0], height=a.size[1])
ref = iris.Renderer(scene, preset="hwss", seed=1000, **size)
ref.step(a.reference_spp)
reference = ref.image()

spps, rows = [1, 2, 4, 8, 16], {}
for preset in ("hwss", "paper"):
    r = iris.Renderer(scene, preset=preset, **size)
    for spp in spps:
        r.step(spp - r.spp)                         # progressive: add the missing passes
        rows.setdefault(preset, []).append((iris.ssim(r.image(), reference), iris.mse(r.image(), reference)))
print(f"{'spp':>4} " + " ".join(f"{p + ' SSIM':>11} {p + ' MSE':>11}" for p in rows))
for i, spp in enumerate(spps):
    print(f"{spp:>4} " + " ".join(f"{s:>11.4f} {m:>11.3e}" for s, m in (rows[p][i] for p in rows)))

for preset, values in rows.items():
    plt.plot(spps, [s for s, _ in values], "o-", label=preset)
plt.xscale("log", base=2), plt.xlabel("samples per pixel"), plt.ylabel("SSIM"), plt.legend()
plt.title(f"{a.scene}: SSIM against a {a.reference_spp}-spp reference")
plt.savefig(a.output, dpi=120)
print(f"wrote {a.output}")
