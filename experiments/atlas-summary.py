#!/usr/bin/env python3
"""Summary of experiments/atlas-convergence.toml's results (mode atlas against the reference path
tracer): per contender, the wall time (iterate() only) and iterations at which relMSE first falls to
0.1 / 0.01 / 0.001 (mean over seeds; "-" where a seed never got there), the final relMSE and image
mean ratio, and the relMSE at every checkpoint for the convergence curves ([HHGM10] Fig. 9/10).

    experiments/atlas-summary.py RESULTS_DIR > summary.md
"""
import csv
import json
import statistics
import sys
from pathlib import Path

root = Path(sys.argv[1])
thresholds = (0.1, 0.01, 0.001)
runs = {}
for task in sorted((root / "tasks").iterdir()):
    if not (task / "done.json").exists():
        continue
    info = json.load(open(task / "task.json"))
    label = info.get("label", info.get("mode"))
    settings = info.get("settings", {})
    extra = ",".join(f"{k}={settings[k]}" for k in ("atlas_resolution", "bundle_resolution") if k in settings)
    name = f"{label} ({extra})" if extra and label.startswith("atlas") else label
    rows = list(csv.DictReader(open(task / "metrics.csv")))
    runs.setdefault(name, []).append(rows)


def fmt(values):
    return "-" if any(v is None for v in values) else f"{statistics.mean(values):.3g}"


print("| contender | seeds | " + " | ".join(f"time to relMSE {t} s (iterations)" for t in thresholds) +
      " | final relMSE | final mean ratio (g) |")
print("|---|---|" + "---|" * len(thresholds) + "---|---|")
for name, seeds in runs.items():
    cells = []
    for t in thresholds:
        times, its = [], []
        for rows in seeds:
            hit = next((r for r in rows if float(r["relmse"]) <= t), None)
            times.append(float(hit["wall_seconds"]) if hit else None)
            its.append(int(hit["iteration"]) if hit else None)
        cells.append(f"{fmt(times)} ({fmt(its)})")
    final = [float(rows[-1]["relmse"]) for rows in seeds]
    ratio = [float(rows[-1]["mean_ratio_g"]) for rows in seeds]
    print(f"| {name} | {len(seeds)} | " + " | ".join(cells) +
          f" | {statistics.mean(final):.4g} ({min(final):.3g}-{max(final):.3g}) | "
          f"{min(ratio):.4f}-{max(ratio):.4f} |")

print("\nrelMSE at each checkpoint (mean over seeds; wall seconds in brackets):\n")
for name, seeds in runs.items():
    its = [r["iteration"] for r in seeds[0]]
    cells = []
    for i, it in enumerate(its):
        rel = [float(rows[i]["relmse"]) for rows in seeds if i < len(rows)]
        wall = [float(rows[i]["wall_seconds"]) for rows in seeds if i < len(rows)]
        cells.append(f"{it}: {statistics.mean(rel):.3g} ({statistics.mean(wall):.1f} s)")
    print(f"- {name}: " + ", ".join(cells))
