"""Convergence and timing plots of a results directory (PNG and SVG beside the data)."""

import os
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from results import load  # noqa: E402


def _save(fig, out_dir, name):
    paths = []
    for ext in ("png", "svg"):
        path = os.path.join(out_dir, f"{name}.{ext}")
        fig.savefig(path, dpi=110, bbox_inches="tight")
        paths.append(path)
    plt.close(fig)
    return paths[0]


def _group_curves(tasks, metric, x):
    """Per group (label + params): the seed-averaged curve over common checkpoints."""
    groups = defaultdict(list)
    for t in tasks:
        xs, ys = t.series(metric, x)
        if len(xs):
            groups[t.group].append((xs, ys))
    curves = {}
    for name, runs in groups.items():
        n = min(len(r[0]) for r in runs)
        xs = np.mean([r[0][:n] for r in runs], axis=0)
        ys = np.mean([r[1][:n] for r in runs], axis=0)
        curves[name] = (xs, ys, len(runs))
    return curves


def convergence_plots(root, metric="relmse"):
    """Error vs time and error vs iterations (log-log), one figure per scene."""
    tasks, _ = load(root)
    out_dir = os.path.join(root, "plots")
    os.makedirs(out_dir, exist_ok=True)
    made = []
    for scene in sorted({t.scene for t in tasks}):
        scene_tasks = [t for t in tasks if t.scene == scene]
        for x, xlabel, suffix in (("wall_seconds", "wall time (s)", "time"), ("iteration", "iterations", "iterations")):
            curves = _group_curves(scene_tasks, metric, x)
            if not curves:
                continue
            fig, ax = plt.subplots(figsize=(6.4, 4.4))
            for name, (xs, ys, seeds) in sorted(curves.items()):
                ax.loglog(xs, ys, marker="o", markersize=3, label=name + (f" ({seeds} seeds)" if seeds > 1 else ""))
            noises = sorted({t.reference_noise for t in scene_tasks if t.reference_noise})
            for i, noise in enumerate(noises):
                ax.axhline(noise, color="gray", linestyle="--", linewidth=1,
                           label="reference's own noise" if i == 0 else None)
            ax.set_xlabel(xlabel)
            ax.set_ylabel(metric + " against the reference")
            ax.set_title(f"{scene}: {metric} vs {xlabel}")
            ax.grid(True, which="both", alpha=0.3)
            ax.legend(fontsize=8)
            made.append(_save(fig, out_dir, f"{scene}-{metric}-vs-{suffix}"))
    return made


def timing_plot(root):
    """Mean GPU/CPU milliseconds per iteration, stacked by pass ([TO12] Table 1's shape)."""
    tasks, _ = load(root)
    out_dir = os.path.join(root, "plots")
    os.makedirs(out_dir, exist_ok=True)
    rows = []
    for t in tasks:
        per_pass = {}
        for p in t.passes:
            try:
                per_pass[p["pass"]] = float(p["total_ms"]) / max(t.iterations, 1)
            except (KeyError, ValueError):
                pass
        if per_pass:
            rows.append((f"{t.scene}\n{t.group}", per_pass))
    if not rows:
        return None
    names = sorted({k for _, p in rows for k in p})
    fig, ax = plt.subplots(figsize=(max(6.0, 1.1 * len(rows)), 4.4))
    bottom = np.zeros(len(rows))
    for name in names:
        values = np.array([p.get(name, 0.0) for _, p in rows])
        ax.bar(range(len(rows)), values, bottom=bottom, label=name)
        bottom += values
    ax.set_xticks(range(len(rows)))
    ax.set_xticklabels([r[0] for r in rows], fontsize=7, rotation=30, ha="right")
    ax.set_ylabel("ms per iteration")
    ax.set_title("time per pass (mean per iteration)")
    ax.legend(fontsize=8)
    return _save(fig, out_dir, "passes")


def bench_scaling_plot(json_paths, out_dir):
    """Bundle benchmark scaling: build, traversal and floor ms against resolution, per scene."""
    import json

    os.makedirs(out_dir, exist_ok=True)
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for path in json_paths:
        data = json.load(open(path))
        res = [r["resolution"] for r in data["results"]]
        name = os.path.splitext(os.path.basename(path))[0] + f" ({data['triangles']} tris)"
        line, = ax.loglog(res, [r["build_ms_median"] + r["traverse_ms_median"] for r in data["results"]],
                          marker="o", label=name + ": build + walk")
        ax.loglog(res, [r["floor_ms_median"] for r in data["results"]], marker="x", linestyle="--",
                  color=line.get_color(), label=name + ": floor")
    ax.set_xlabel("bundle resolution (pixels per side)")
    ax.set_ylabel("ms per bundle (median)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    return _save(fig, out_dir, "bundles-scaling")


if __name__ == "__main__":
    import sys

    if len(sys.argv) > 2 and sys.argv[1] == "--bench":
        print(bench_scaling_plot(sys.argv[3:], sys.argv[2]))
    else:
        for p in convergence_plots(sys.argv[1]) + [timing_plot(sys.argv[1])]:
            print(p)
