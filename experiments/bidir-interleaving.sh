#!/usr/bin/env bash
# Mode bidir's spatio-temporal interleaved sampling ([TO12s] A) measured against the reference path
# tracer (report: experiments/bidir-interleaving.md). The measurements are the disabled drivers in
# tests/modes/bidir/InterleavingExperiment.cpp (they need the Vulkan device and the reference in
# one process); this script runs them and plots the temporal one.
#   Spatial: cornell-point, 64^2, MIS one-bounce, 16 pairs per frame, 16 frames, 6 seeds: interleave
#     1 / 2 / 4 with the blur off and on -> spatial.csv
#   Temporal: cornell-animated (block moves, camera dollies) and the same with the camera held still,
#     48^2, 12 frames at 6 fps (the 2 s of animation), one iterate() per frame, 3 runs per config:
#     temporal off with the same sample set every frame ("fixed set", what `render --frames` does
#     with one seed), temporal off with a fresh set per frame ("fresh set", non-periodic), temporal on
#     -> temporal.csv, temporal.png
#   experiments/bidir-interleaving.sh [BUILD_DIR] [OUT_DIR]
# Environment overrides of the drivers: BL_SIDE, BL_FRAMES, BL_SEEDS, BL_FPS, BL_REFERENCE_SPP.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
out=${2:-$root/results/bidir-interleaving}
mkdir -p "$out"
cut -d' ' -f1-3 /proc/loadavg >"$out/load-before.txt"
BL_EXPERIMENT_OUT="$out" nice -n 10 "$build/tests/test_bidir_interleaving" --gtest_also_run_disabled_tests \
    --gtest_filter='InterleavingExperiment.DISABLED_Spatial' | tee "$out/spatial.log"
BL_EXPERIMENT_OUT="$out" BL_REFERENCE_SPP=${BL_REFERENCE_SPP:-256} nice -n 10 \
    "$build/tests/test_bidir_interleaving" --gtest_also_run_disabled_tests \
    --gtest_filter='InterleavingExperiment.DISABLED_Temporal' | tee "$out/temporal.log"
cut -d' ' -f1-3 /proc/loadavg >"$out/load-after.txt"
/usr/bin/python3 - "$out" <<'PY'
import csv, sys, collections
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
out = sys.argv[1]
rows = list(csv.DictReader(open(f"{out}/temporal.csv")))
scenes = sorted({r["scene"] for r in rows})
fig, axes = plt.subplots(2, len(scenes), figsize=(5 * len(scenes), 7), squeeze=False)
for c, scene in enumerate(scenes):
    for config in ["fixed set", "fresh set", "temporal", "temporal 2s2=1e-2"]:
        per = collections.defaultdict(list)
        fl = collections.defaultdict(list)
        for r in rows:
            if r["scene"] == scene and r["config"] == config:
                per[int(r["frame"])].append(float(r["nrmse"]))
                if float(r["flicker_percent"]) >= 0:
                    fl[int(r["frame"])].append(float(r["flicker_percent"]))
        f = sorted(per)
        axes[0][c].plot(f, [sum(per[i]) / len(per[i]) for i in f], marker="o", label=config)
        g = sorted(fl)
        axes[1][c].plot(g, [sum(fl[i]) / len(fl[i]) for i in g], marker="o", label=config)
    ref = {}
    for r in rows:
        if r["scene"] == scene and float(r["reference_flicker_percent"]) >= 0:
            ref[int(r["frame"])] = float(r["reference_flicker_percent"])
    g = sorted(ref)
    axes[1][c].plot(g, [ref[i] for i in g], "k--", label="reference (own noise)")
    axes[0][c].set_title(f"{scene}: per-frame NRMSE of indirect1")
    axes[1][c].set_title(f"{scene}: flicker in static pixels (%)")
    axes[1][c].set_xlabel("frame (6 fps)")
    axes[0][c].legend(); axes[1][c].legend()
fig.tight_layout()
fig.savefig(f"{out}/temporal.png", dpi=100)
print(f"wrote {out}/temporal.png")
PY
