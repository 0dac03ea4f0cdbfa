#!/usr/bin/env python3
"""The spectral film (docs/python.md, docs/method.md "Spectral output"): render a scene with
spectral=B and plot the spectral radiance of three patches of it — the bluest, the median
and the reddest lit one — beside the image. Each band is the mean radiance over its width,
exact and deterministic like the RGB. (A caustic such as the prism's rainbow is found by
light tracing and bdpt, which have no spectral film yet: under nee-mis its spectrum is
fireflies.)"""
import argparse

import matplotlib.pyplot as plt
import numpy as np
import iris

ap = argparse.ArgumentParser(description=__doc__)
ap.add_argument("--scene", default="cornell")
ap.add_argument("--preset", default="hwss")
ap.add_argument("--size", type=int, nargs=2, default=(160, 120), metavar=("W", "H"))
ap.add_argument("--spp", type=int, default=256)
ap.add_argument("--bands", type=int, default=40)
ap.add_argument("-o", "--output", default="spectrum_patches.png")
a = ap.parse_args()

scene = iris.load(a.scene)
r = iris.Renderer(scene, preset=a.preset, width=a.size[0], height=a.size[1], spectral=a.bands)
r.step(a.spp)
nm, s = r.wavelengths, r.image("spectral")        # (B,), (H, W, B)
print(f"{a.scene}: {a.spp} spp with {a.preset} in {r.seconds:.2f} s, {a.bands} bands of {nm[1] - nm[0]:g} nm")

# patches of 8 x 8 pixels (their mean: the noise averages out), three of the lit ones: the
# bluest, the median and the reddest by the centroid of their spectrum
k = 8
h, w = (s.shape[0] // k) * k, (s.shape[1] // k) * k
patches = s[:h, :w].reshape(h // k, k, w // k, k, -1).mean(axis=(1, 3))   # (H/k, W/k, B)
energy = patches.sum(axis=2)
top = np.percentile(energy, 90)  # lit surfaces, not the lamp itself
py, px = np.nonzero((energy > 0.05 * top) & (energy <= top))
centroid = (patches[py, px] * nm).sum(axis=1) / energy[py, px]
order = np.argsort(centroid)
picks = [order[0], order[len(order) // 2], order[-1]]

fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4))
left.imshow(r.image("srgb"))
for i, colour in zip(picks, ["tab:blue", "tab:green", "tab:red"]):
    y, x = py[i], px[i]
    left.add_patch(plt.Rectangle((x * k - 0.5, y * k - 0.5), k, k, fill=False, ec=colour, lw=2))
    right.plot(nm, patches[y, x], "-", color=colour, label=f"pixels ({x * k}, {y * k}) +{k}: centroid {centroid[i]:.0f} nm")
    print(f"patch at ({x * k}, {y * k}): spectral centroid {centroid[i]:.1f} nm, peak at {nm[np.argmax(patches[y, x])]:.1f} nm")
left.set_title(f"{a.scene}, {a.spp} spp ({a.preset})"), left.axis("off")
right.set_xlabel("wavelength (nm)"), right.set_ylabel("spectral radiance (band mean)")
right.set_title(f"{a.bands} bands, {k}x{k}-pixel patches"), right.legend(fontsize=8)
fig.tight_layout()
fig.savefig(a.output, dpi=110)
print(f"wrote {a.output}")
