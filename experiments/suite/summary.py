#!/usr/bin/python3
"""The benchmark suite's one table (experiments/suite.toml): per scene and method, over seeds, the
relMSE after the equal wall time, the time to relMSE 1e-1 / 1e-2 / 1e-3 (first checkpoint at or
below it, median over the seeds that reach it), the image mean against the reference (the bias
bar: mean over seeds of the luminance-weighted mean ratio, +- the seeds' standard error) and its
relMSE over that of the path tracer judged against the same reference (full GI, or cut to 2 or 4
segments as raster, skylight and bidir compute), measured and noise-corrected
(scripts/reference_noise.py: the reference's own noise is most of the path tracer's measured
relMSE where it takes several times the reference's samples, so the measured ratios understate
the gap). The report prints the path tracer's predicted own relMSE beside its measured excess over
the noise as a check.

usage: summary.py RESULTS_DIR > experiments/suite/report.md
"""
import csv
import math
import os
import statistics
import sys
import tomllib

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
from reference_noise import noise_corrected, predicted_own_relmse, reference_spp  # noqa: E402

LUMA = (0.2126, 0.7152, 0.0722)
THRESHOLDS = (1e-1, 1e-2, 1e-3)


def ratio(value):
    if value is None:
        return "—"
    return f"{value:.0f}x" if value >= 1000 else f"{value:.3g}x"


def number(text):
    return float(text) if text else None


def median(values):
    values = [v for v in values if v is not None]
    return statistics.median(values) if values else None


def time_to(metrics, threshold):
    for row in metrics:
        if row["relmse"] and float(row["relmse"]) <= threshold:
            return float(row["wall_seconds"])
    return None


def main():
    root = sys.argv[1]
    rows = list(csv.DictReader(open(os.path.join(root, "results.csv"))))
    with open(os.path.join(root, "experiment.toml"), "rb") as f:
        configured_spp = tomllib.load(f).get("reference", {}).get("spp", 256)  # the runner's default

    def reference_of(r):  # the reference image a task was judged against (the runner's reference.txt)
        with open(os.path.join(root, r["dir"], "reference.txt")) as f:
            return os.path.basename(f.read().strip())

    groups = {}
    for r in rows:
        groups.setdefault((r["scene"], r["label"]), []).append(r)
    # Per (scene, reference): the path tracer judged by it, its measured relMSE, its own relMSE
    # predicted from the reference's noise and its measured excess over that noise.
    tracers = {}
    for (scene, label), rs in groups.items():
        if rs[0]["mode"] != "reference":
            continue
        spp = reference_spp(os.path.join(root, rs[0]["dir"])) or configured_spp
        noise = [number(r["reference_noise_relmse"]) for r in rs]
        tracers[(scene, reference_of(rs[0]))] = {
            "label": label, "spp": spp, "noise": median(noise),
            "relmse": median(number(r["relmse"]) for r in rs),
            "predicted": median(predicted_own_relmse(n, spp, int(r["iterations"])) for n, r in zip(noise, rs)),
            "excess": median(number(r["relmse"]) - n for n, r in zip(noise, rs) if n is not None and r["relmse"]),
            "iterations": median(int(r["iterations"]) for r in rs)}
    seconds = statistics.median(float(r["wall_seconds"]) for r in rows)
    spps = sorted({t["spp"] for t in tracers.values()}) or [configured_spp]
    print("# Benchmark suite: every strategy and the path tracer at equal time\n")
    print(f"`experiments/suite.toml`, {len(rows)} tasks: 64x64, about {seconds:.0f} s of `iterate()` per task, "
          f"{len({r['seed'] for r in rows})} seeds, lavapipe and the path tracer sharing 2 CPU cores. "
          "Made by `experiments/suite/summary.py RESULTS_DIR`; plots of relMSE against time per scene in `plots/`.\n")
    print("| scene | method | iterations | relMSE at equal time | time to 1e-1 (s) | time to 1e-2 (s) | "
          "time to 1e-3 (s) | image mean / reference (seeds) | against | relMSE / path tracer's | noise-corrected |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for (scene, label), rs in sorted(groups.items(), key=lambda kv: (kv[0][0], kv[1][0]["mode"] != "reference", kv[0][1])):
        relmse = median(number(r["relmse"]) for r in rs)
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
        tracer = tracers.get((scene, reference_of(rs[0])))
        judged = tracer is not None and rs[0]["mode"] != "reference"
        vs = ratio(relmse / tracer["relmse"] if relmse is not None and tracer["relmse"] else None) if judged else "—"
        corrected = ratio(median(noise_corrected(number(r["relmse"]), number(r["reference_noise_relmse"]),
                                                 tracer["noise"], tracer["spp"], tracer["iterations"])
                                 for r in rs)) if judged else "—"
        shown = "—" if relmse is None else f"{relmse:.3g}"
        print(f"| {scene} | {label} | {iterations:g} | {shown} | {times[0]} | {times[1]} | {times[2]} | "
              f"{mean:.4f} +- {spread:.4f} | {tracer['label'] if judged else '—'} | {vs} | {corrected} |")
    print(f"\nReferences ({' / '.join(map(str, spps))} spp of the path tracer, its own seed): full GI for the path "
          "tracer, multibounce and atlas; at most 4 segments for bidir (two bounces) and `path-tracer-4`; direct "
          "light (2 segments) for raster, skylight and `path-tracer-2`. Each method is rated against the path "
          "tracer judged by the same reference (`against`). At 64x64 the path tracer takes one to seven times the "
          "reference's samples in the same time, so its measured relMSE is mostly the reference's own noise "
          "(`reference_noise_relmse` in results.csv) and the measured ratio understates the gap. The last column "
          "removes that noise: the method's relMSE less the noise, over the path tracer's own relMSE predicted from "
          "the noise (noise * reference spp / the path tracer's samples; negative: within the reference's noise). "
          "The prediction against the path tracer's measured relMSE less the noise (medians over seeds):\n")
    print("| scene | path tracer | reference noise | predicted | measured excess |")
    print("|---|---|---|---|---|")

    def fmt(v):
        return "—" if v is None else f"{v:.3g}"
    for (scene, _), t in sorted(tracers.items(), key=lambda kv: (kv[0][0], kv[1]["label"])):
        print(f"| {scene} | {t['label']} | {fmt(t['noise'])} | {fmt(t['predicted'])} | {fmt(t['excess'])} |")


if __name__ == "__main__":
    main()
