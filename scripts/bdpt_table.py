#!/usr/bin/env python3
"""Path tracing against bdpt at equal time: one markdown table from the results_time.csv of
scripts/results_bdpt.sh's ablations (DIR/SCENE-time-{nee-mis,bdpt}/). Means over seeds.

    python3 scripts/bdpt_table.py build/results-bdpt falling-cubes falling-cubes-led rubik prism cornell
"""
import csv
import pathlib
import sys
from collections import defaultdict


def load(path):
    rows = defaultdict(list)
    with open(path) as f:
        for r in csv.DictReader(f):
            rows[(r["preset"], float(r["budget"]))].append(r)
    return rows


def mean(rows, key):
    return sum(float(r[key]) for r in rows) / len(rows)


def main():
    root = pathlib.Path(sys.argv[1])
    print("| scene | budget | preset | spp path / bdpt | MSE path | MSE bdpt | bdpt / path | SSIM path | SSIM bdpt |")
    print("|---|---|---|---|---|---|---|---|---|")
    for scene in sys.argv[2:]:
        pt = load(root / f"{scene}-time-nee-mis" / "results_time.csv")
        bd = load(root / f"{scene}-time-bdpt" / "results_time.csv")
        for key in sorted(pt, key=lambda k: (k[1], k[0])):
            if key not in bd:
                continue
            a, b = pt[key], bd[key]
            ma, mb = mean(a, "mse"), mean(b, "mse")
            print(f"| {scene} | {key[1]:g} s | `{key[0]}` | {mean(a, 'spp'):.0f} / {mean(b, 'spp'):.0f} | {ma:.4g} | {mb:.4g} | "
                  f"**{mb / ma:.2f}** | {mean(a, 'ssim'):.3f} | {mean(b, 'ssim'):.3f} |")


if __name__ == "__main__":
    main()
