#!/usr/bin/python3
"""Plots splat-coverage.txt (splat-coverage.sh): holes against redundant nodes per pixel, one curve
per scene, each point labelled with its splat_scale, and exp(-s^2) for independent points."""
import math
import os
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

here = os.path.dirname(os.path.abspath(__file__))
src = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "splat-coverage.txt")
curves, name = {}, None
for line in open(src):
    if line.startswith("=="):
        name = os.path.basename(line.split()[1])
        curves[name] = []
    m = re.match(r"splat_scale ([\d.]+)\s+holes ([\d.]+).*redundant nodes/pixel ([-\d.]+)\s+node ratio ([\d.]+)", line)
    if m and name:
        curves[name].append(tuple(float(g) for g in m.groups()))
fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.2))
for name, pts in curves.items():
    s = [p[0] for p in pts]
    a.semilogy(s, [max(p[1], 1e-6) for p in pts], "o-", label=name)
    b.semilogy([p[3] for p in pts], [max(p[1], 1e-6) for p in pts], "o-", label=name)
xs = [0.5 + 0.05 * i for i in range(51)]
a.semilogy(xs, [math.exp(-x * x) for x in xs], "k--", label="exp(-s^2): independent points")
b.semilogy([x * x for x in xs], [math.exp(-x * x) for x in xs], "k--", label="exp(-s^2)")
a.set_xlabel("splat_scale s")
a.set_ylabel("holes: perfect first hits missed")
b.set_xlabel("nodes, imperfect / perfect (redundancy)")
b.set_ylabel("holes")
for ax in (a, b):
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
fig.suptitle("Imperfect bundles: 16384 points per direction, 16 directions of 128^2")
fig.tight_layout()
fig.savefig(os.path.join(here, "splat-coverage.png"), dpi=110)
