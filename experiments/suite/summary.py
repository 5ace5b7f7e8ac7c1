#!/usr/bin/python3
"""The benchmark suite's one table (experiments/suite.toml): per scene and method, over seeds, the
relMSE after the equal wall time, the time to relMSE 1e-1 / 1e-2 / 1e-3 (first checkpoint at or
below it, median over the seeds that reach it), the image mean against the reference (the bias
bar: mean over seeds of the luminance-weighted mean ratio, +- the seeds' standard error) and, for
methods judged against the same full-GI reference as the path tracer, its relMSE over the path
tracer's at equal time.

usage: summary.py RESULTS_DIR > experiments/suite/report.md
"""
import csv
import math
import os
import statistics
import sys

LUMA = (0.2126, 0.7152, 0.0722)
THRESHOLDS = (1e-1, 1e-2, 1e-3)
FULL_GI = {"path-tracer", "multibounce", "atlas"}  # judged against the same reference


def time_to(metrics, threshold):
    for row in metrics:
        if row["relmse"] and float(row["relmse"]) <= threshold:
            return float(row["wall_seconds"])
    return None


def main():
    root = sys.argv[1]
    rows = list(csv.DictReader(open(os.path.join(root, "results.csv"))))
    groups = {}
    for r in rows:
        groups.setdefault((r["scene"], r["label"]), []).append(r)
    pt = {scene: statistics.median(float(r["relmse"]) for r in rs)
          for (scene, label), rs in groups.items() if label == "path-tracer"}
    seconds = statistics.median(float(r["wall_seconds"]) for r in rows)
    print("# Benchmark suite: every strategy and the path tracer at equal time\n")
    print(f"`experiments/suite.toml`, {len(rows)} tasks: 64x64, about {seconds:.0f} s of `iterate()` per task, "
          f"{len({r['seed'] for r in rows})} seeds, lavapipe and the path tracer sharing 2 CPU cores. "
          "Made by `experiments/suite/summary.py RESULTS_DIR`; plots of relMSE against time per scene in `plots/`.\n")
    print("| scene | method | iterations | relMSE at equal time | time to 1e-1 (s) | time to 1e-2 (s) | "
          "time to 1e-3 (s) | image mean / reference (seeds) | relMSE / path tracer's |")
    print("|---|---|---|---|---|---|---|---|---|")
    for (scene, label), rs in sorted(groups.items(), key=lambda kv: (kv[0][0], kv[0][1] != "path-tracer", kv[0][1])):
        relmse = statistics.median(float(r["relmse"]) for r in rs)
        iterations = statistics.median(int(r["iterations"]) for r in rs)
        times = []
        for t in THRESHOLDS:
            reached = [x for x in (time_to(list(csv.DictReader(open(os.path.join(root, r["dir"], "metrics.csv")))), t)
                                   for r in rs) if x is not None]
            times.append(f"{statistics.median(reached):.3g}" + ("" if len(reached) == len(rs) else
                                                                 f" ({len(reached)}/{len(rs)})") if reached else "—")
        ratios = [sum(w * float(r[f"mean_ratio_{c}"]) for w, c in zip(LUMA, "rgb")) for r in rs]
        mean = statistics.mean(ratios)
        spread = statistics.stdev(ratios) / math.sqrt(len(ratios)) if len(ratios) > 1 else 0.0
        vs = f"{relmse / pt[scene]:.3g}x" if label in FULL_GI and label != "path-tracer" and scene in pt else "—"
        print(f"| {scene} | {label} | {iterations:g} | {relmse:.3g} | {times[0]} | {times[1]} | {times[2]} | "
              f"{mean:.4f} +- {spread:.4f} | {vs} |")
    print("\nReferences (1024 spp of the path tracer, its own seed): full GI for the path tracer, multibounce and "
          "atlas; at most 4 segments for bidir (two bounces); direct light (2 segments) for raster and skylight, so "
          "their relMSE is against another target and not comparable with the path tracer's. At 64x64 the path "
          "tracer reaches the 1024-spp reference's own noise (`reference_noise_relmse` in results.csv, 1e-4 to 2e-3) "
          "within the 10 s, so its relMSE there is mostly the reference's; the bundle modes stay one to three orders "
          "above it.")


if __name__ == "__main__":
    main()
