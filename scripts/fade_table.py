#!/usr/bin/env python3
"""The bias-fade tables of docs/results.md from docs/results/fade/<scene>/summary.md (written
by scripts/results_fade.sh): per scene and spp, SSIM gain and MSE change against `hwss` of
each preset at equal spp; then at equal time: each preset's SSIM and MSE interpolated (linear
in log seconds between its snapshots) at the seconds `hwss` took for that spp.
    python3 scripts/fade_table.py [SPP,...]   (default 16,512,1024,2048,4096)"""
import math
import os
import re
import sys

SCENES = ["falling-cubes", "falling-cubes-led", "rubik", "falling-cubes-rgb", "falling-cubes-laser", "prism", "cornell"]
PRESETS = ["paper", "paper-fade", "paper-auto-fade"]
root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "docs", "results", "fade")
spps = [int(s) for s in (sys.argv[1] if len(sys.argv) > 1 else "16,512,1024,2048,4096").split(",")]
num = r"([\d.e+-]+)"
row = re.compile(r"^\| (\d+) \| ([\w-]+) \| " + num + r" ± [^|]+ \| ([+-][\d.]+ % ± [\d.]+) \| " + num +
                 r" ± [^|]+ \| ([+-][\d.]+ %) \| [^|]+ \| " + num + r" \|$")


def load(scene):
    path = os.path.join(root, scene, "summary.md")
    data = {}
    if os.path.exists(path):
        for line in open(path, encoding="utf-8"):
            m = row.match(line.strip())
            if m:
                data[(int(m.group(1)), m.group(2))] = {"ssim": float(m.group(3)), "gain": m.group(4),
                                                        "mse": float(m.group(5)), "dmse": m.group(6),
                                                        "seconds": float(m.group(7))}
    return data


def at_time(data, preset, t):
    """(ssim, mse) of `preset` at `t` seconds, linear in log t between snapshots; None outside."""
    pts = sorted((v["seconds"], v["ssim"], v["mse"]) for (s, p), v in data.items() if p == preset)
    for (t0, s0, m0), (t1, s1, m1) in zip(pts, pts[1:]):
        if t0 <= t <= t1 and t1 > t0:
            f = (math.log(t) - math.log(t0)) / (math.log(t1) - math.log(t0))
            return s0 + f * (s1 - s0), math.exp(math.log(m0) + f * (math.log(m1) - math.log(m0)))
    return None


print("Equal spp: SSIM gain (± std over seeds) / MSE change, against `hwss` at the same spp.\n")
print("| scene | spp | " + " | ".join(f"`{p}`" for p in PRESETS) + " | seconds `hwss` / `paper-fade` |")
print("|---|---|" + "---|" * len(PRESETS) + "---|")
for scene in SCENES:
    data = load(scene)
    for spp in spps:
        if (spp, "hwss") not in data:
            continue
        cells = [f"{data[(spp, p)]['gain']} / {data[(spp, p)]['dmse']}" if (spp, p) in data else "—" for p in PRESETS]
        secs = f"{data[(spp, 'hwss')]['seconds']:.2f} / {data[(spp, 'paper-fade')]['seconds']:.2f}"
        print(f"| {scene} | {spp} | " + " | ".join(cells) + f" | {secs} |")

print("\nEqual time: at the seconds `hwss` took for SPP, each preset's SSIM gain / MSE change"
      " (interpolated between its own snapshots).\n")
print("| scene | `hwss` spp (seconds) | " + " | ".join(f"`{p}`" for p in PRESETS) + " |")
print("|---|---|" + "---|" * len(PRESETS))
for scene in SCENES:
    data = load(scene)
    for spp in spps:
        h = data.get((spp, "hwss"))
        if not h:
            continue
        cells = []
        for p in PRESETS:
            v = at_time(data, p, h["seconds"])
            cells.append(f"{100 * (v[0] / h['ssim'] - 1):+.1f} % / {100 * (v[1] / h['mse'] - 1):+.1f} %" if v else "—")
        if any(c != "—" for c in cells):  # not before every preset's first snapshot
            print(f"| {scene} | {spp} ({h['seconds']:.2f} s) | " + " | ".join(cells) + " |")
