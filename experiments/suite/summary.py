#!/usr/bin/python3
"""The benchmark suite's one table (experiments/suite.toml): per scene and method, over seeds, the
relMSE after the equal wall time, the time to relMSE 1e-1 / 1e-2 / 1e-3 (first checkpoint at or
below it, median over the seeds that reach it), the image mean against the reference (the bias
bar: mean over seeds of the luminance-weighted mean ratio, +- the seeds' standard error) and, for
methods judged against the same full-GI reference as the path tracer, its relMSE over the path
tracer's at equal time, measured and noise-corrected.

The reference is itself a Monte Carlo image: against an independent reference R of relative noise
n_R (`reference_noise_relmse`, its pixel means' variance over (mean^2 + 0.01)), a method's measured
relMSE is in expectation its own relMSE plus n_R. At 64x64 the path tracer takes about as many
samples in 10 s as the reference has, so its measured relMSE is mostly n_R and the measured ratios
understate the gap. The corrected ratio divides the method's excess (relMSE - n_R) by the path
tracer's own relMSE, predicted as n_R * spp_R / spp (the same estimator, its variance falling as
1/spp); the report prints that prediction beside the path tracer's measured excess as a check.

usage: summary.py RESULTS_DIR > experiments/suite/report.md
"""
import csv
import math
import os
import statistics
import sys
import tomllib

LUMA = (0.2126, 0.7152, 0.0722)
THRESHOLDS = (1e-1, 1e-2, 1e-3)
FULL_GI = {"path-tracer", "multibounce", "atlas"}  # judged against the same reference


def ratio(value):
    return f"{value:.0f}x" if value >= 1000 else f"{value:.3g}x"


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
    with open(os.path.join(root, "experiment.toml"), "rb") as f:
        reference_spp = tomllib.load(f)["reference"]["spp"]

    def excess(r):  # a task's relMSE less its reference's noise
        return float(r["relmse"]) - float(r["reference_noise_relmse"])

    # The path tracer's own relMSE, predicted from its reference's noise and measured as an excess.
    pt_predicted = {scene: statistics.median(float(r["reference_noise_relmse"]) * reference_spp / int(r["iterations"])
                                             for r in rs)
                    for (scene, label), rs in groups.items() if label == "path-tracer"}
    pt_excess = {scene: statistics.median(excess(r) for r in rs)
                 for (scene, label), rs in groups.items() if label == "path-tracer"}
    seconds = statistics.median(float(r["wall_seconds"]) for r in rows)
    print("# Benchmark suite: every strategy and the path tracer at equal time\n")
    print(f"`experiments/suite.toml`, {len(rows)} tasks: 64x64, about {seconds:.0f} s of `iterate()` per task, "
          f"{len({r['seed'] for r in rows})} seeds, lavapipe and the path tracer sharing 2 CPU cores. "
          "Made by `experiments/suite/summary.py RESULTS_DIR`; plots of relMSE against time per scene in `plots/`.\n")
    print("| scene | method | iterations | relMSE at equal time | time to 1e-1 (s) | time to 1e-2 (s) | "
          "time to 1e-3 (s) | image mean / reference (seeds) | relMSE / path tracer's | noise-corrected |")
    print("|---|---|---|---|---|---|---|---|---|---|")
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
        judged = label in FULL_GI and label != "path-tracer" and scene in pt
        vs = ratio(relmse / pt[scene]) if judged else "—"
        corrected = ratio(statistics.median(excess(r) for r in rs) / pt_predicted[scene]) if judged else "—"
        print(f"| {scene} | {label} | {iterations:g} | {relmse:.3g} | {times[0]} | {times[1]} | {times[2]} | "
              f"{mean:.4f} +- {spread:.4f} | {vs} | {corrected} |")
    print(f"\nReferences ({reference_spp} spp of the path tracer, its own seed): full GI for the path tracer, multibounce and "
          "atlas; at most 4 segments for bidir (two bounces); direct light (2 segments) for raster and skylight, so "
          "their relMSE is against another target and not comparable with the path tracer's. At 64x64 the path "
          f"tracer reaches the {reference_spp}-spp reference's own noise (`reference_noise_relmse` in results.csv, 1e-4 to 2e-3) "
          "within the 10 s, so its relMSE there is mostly the reference's; the bundle modes stay one to three orders "
          "above it. The last column removes the reference's noise: the method's relMSE less the noise over the "
          "path tracer's own relMSE predicted from the noise (noise * reference spp / path tracer's spp). "
          "The prediction against the path tracer's measured relMSE less the noise (medians over seeds):\n")
    print("| scene | reference noise | path tracer: predicted | measured excess |")
    print("|---|---|---|---|")
    for scene in sorted(pt):
        noise = statistics.median(float(r["reference_noise_relmse"]) for r in groups[(scene, "path-tracer")])
        print(f"| {scene} | {noise:.3g} | {pt_predicted[scene]:.3g} | {pt_excess[scene]:.3g} |")


if __name__ == "__main__":
    main()
